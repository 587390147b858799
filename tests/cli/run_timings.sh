#!/usr/bin/env bash
# Issue 27.2: honest timing. `pounding run --timings` (under mpirun -np 2 when mpirun exists; skipped without it,
# a failure under CI=true) prints one "timing:" line and the table of phases; the results hold /timing (phase,
# rank0_s, max_s in s; wall_s), and:
#  - wall_s = the root attribute wall_time_s = the report's "wall time" (to its printed digits);
#  - wall_s covers the phases it contains (MPI start + inputs + structures + units + analysis + report <= wall_s)
#    and is no more than the process's own elapsed time; the printed wall adds the results write;
#  - max over ranks >= rank 0 for every phase; under MPI, both ranks computed (max compute > 0) and MPI start > 0.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
/usr/bin/python3 -c 'import h5py' 2>/dev/null || skip_or_fail "needs /usr/bin/python3 with h5py (Debian: python3-h5py)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cat > "$tmp/s.toml" <<'TOML'
title = "timings"
seed = 5
scene = "probability"
[records]
suite = "builtin"
synthetic_only = true
limit = 4
[structures]
samples_per_pair = 8
TOML
launch=()
if command -v mpirun > /dev/null; then launch=(timeout 120 mpirun -np 2); ranks=2
elif [ "${CI:-}" = true ]; then fail "mpirun missing under CI=true"
else echo "note: no mpirun, one rank"; ranks=1; fi
t0=$(date +%s.%N)
"${launch[@]}" "$bin" run "$tmp/s.toml" --out "$tmp/s.h5" --quiet --timings > "$tmp/out" 2> "$tmp/err"
took=$(echo "$(date +%s.%N) - $t0" | bc)
[ "$(grep -c '^timing: wall ' "$tmp/err")" -eq 1 ] || { cat "$tmp/err"; fail "want one 'timing: wall' line"; }
for p in mpi_start inputs structures units compute reduce checkpoint analysis report bootstrap results_write wall; do
  grep -q "^| $p | " "$tmp/err" || fail "--timings table lacks $p"
done
printed=$(sed -n 's/^timing: wall \([0-9.]*\) s .*/\1/p' "$tmp/err")
/usr/bin/python3 - "$tmp/s.h5" "$tmp/out" "$took" "$printed" "$ranks" <<'PY' || fail "the /timing checks"
import re, sys, h5py
f = h5py.File(sys.argv[1], "r")
out, took, printed, ranks = open(sys.argv[2]).read(), float(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])
g = f["timing"]
names = [x.decode() for x in g["phase"][()]]
assert names == ["mpi_start", "inputs", "structures", "units", "compute", "reduce", "checkpoint", "analysis",
                 "report", "bootstrap", "results_write"], names
for d in ("rank0_s", "max_s"):
    assert g[d].attrs["units"] in (b"s", "s"), g[d].attrs["units"]
t = dict(zip(names, g["rank0_s"][()])); m = dict(zip(names, g["max_s"][()]))
wall = g.attrs["wall_s"]
assert wall == f.attrs["wall_time_s"], (wall, f.attrs["wall_time_s"])
shown = re.search(r"wall time ([0-9.]+) s\)", out).group(1)
assert shown == f"{wall:.2f}", (shown, wall)
inside = sum(t[p] for p in ("mpi_start", "inputs", "structures", "units", "analysis", "report"))
assert inside <= wall + 1e-6, (inside, wall)
assert t["bootstrap"] <= t["report"] and t["compute"] <= t["units"] + 1e-6, t
# printed: the timing line's wall to 2 decimals (it adds the results write, which can be under 5 ms)
assert wall <= took and printed + 0.005 >= wall and printed - 0.005 <= took, (wall, printed, took)
assert all(m[p] >= t[p] for p in names), (t, m)
assert t["report"] > 0 and t["units"] > 0 and m["compute"] > 0, t
if ranks > 1:
    assert t["mpi_start"] > 0, t
print(f"ok: wall {wall:.3f} s in the file, {printed} s printed, process {took:.3f} s; units {t['units']:.3f} s, "
      f"compute rank 0 {t['compute']:.3f} s / max {m['compute']:.3f} s, report {t['report']:.3f} s")
PY
echo "ok: timing line, --timings table and /timing consistent ($ranks ranks)"
# On one node the network messaging layer (Open MPI's pml cm and its MTLs) is not loaded, unless the user chose a
# layer or POUNDING_MPI_TRANSPORTS=all (src/parallel/mpi_executor.cpp); Open MPI's own pml_base_verbose says which
# components it loaded. The results are the same either way.
if [ "$ranks" -gt 1 ]; then
  loaded() { grep -c "components_open: found loaded component cm$" "$1" || true; }
  run_v() {  # <out.h5> <log> [env ...]: the run with Open MPI's pml selection verbose
    timeout 120 mpirun -np 2 env OMPI_MCA_pml_base_verbose=10 "${@:3}" "$bin" run "$tmp/s.toml" --out "$1" --quiet \
      > /dev/null 2> "$2" || { cat "$2"; fail "the verbose run ${*:3}"; }
  }
  run_v "$tmp/v0.h5" "$tmp/v0.log"
  run_v "$tmp/v1.h5" "$tmp/v1.log" POUNDING_MPI_TRANSPORTS=all
  run_v "$tmp/v2.h5" "$tmp/v2.log" OMPI_MCA_mtl=^psm
  [ "$(loaded "$tmp/v0.log")" -eq 0 ] || fail "one node: Open MPI still loaded pml cm"
  grep -q "components_open: found loaded component ob1$" "$tmp/v0.log" || fail "no pml ob1 in Open MPI's verbose output"
  [ "$(loaded "$tmp/v1.log")" -eq 2 ] || fail "POUNDING_MPI_TRANSPORTS=all: want cm loaded on both ranks"
  [ "$(loaded "$tmp/v2.log")" -eq 2 ] || fail "OMPI_MCA_mtl set by the user: want Open MPI's own choice (cm loaded)"
  for n in 1 2; do
    /usr/bin/python3 "$src/tests/cli/compare_results.py" "$tmp/v0.h5" "$tmp/v$n.h5" --ignore=output > /dev/null \
      || fail "results differ with POUNDING_MPI_TRANSPORTS / OMPI_MCA_mtl"
  done
  echo "ok: one node, pml cm not loaded; loaded with POUNDING_MPI_TRANSPORTS=all or a user's OMPI_MCA_mtl; results equal"
  # any other value is refused on every rank before MPI starts, said once, nothing written
  rc=0; timeout 120 mpirun -np 2 env POUNDING_MPI_TRANSPORTS=none "$bin" run "$tmp/s.toml" --out "$tmp/v3.h5" --quiet \
    > /dev/null 2> "$tmp/v3.err" || rc=$?
  { [ "$rc" -eq 2 ] && [ "$(grep -c ERROR "$tmp/v3.err")" -eq 1 ] && grep -q "POUNDING_MPI_TRANSPORTS=none is not a choice" "$tmp/v3.err" \
    && [ ! -e "$tmp/v3.h5" ]; } && echo "ok: POUNDING_MPI_TRANSPORTS=none refused: $(cat "$tmp/v3.err")" \
    || fail "POUNDING_MPI_TRANSPORTS=none: exit $rc: $(cat "$tmp/v3.err")"
fi
