#!/usr/bin/env bash
# Fragility studies of rows (issue 25: [intensity] with [structures] buildings = 3; refused before: "a fragility study
# runs a pair"). studies/fragility-storeys.toml small, with a third shear building (6 storeys) right of the pair:
#  1. MSA (stripes) and IDA (bisection) give bit-identical results without mpirun and on 1 and 2 ranks;
#  2. one lane of one stripe (every stripe run on the scaled record: scale_elastic = false) is `pounding simulate
#     --buildings 3` with the same shear buildings on the record times the stripe's factor, bit for bit: every floor's
#     peak |u| and drift of the three buildings, every element's closing, D; the row's building 3 has its own
#     stripe rows (uncoupled/peak_u3);
#  3. the IDA's final brackets hold the first contact at ANY joint: simulate at scale_lo does not reach the gap, at
#     scale_hi it does.
# Synthetic records only (no ../shared needed). Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/study_invariance.sh"  # $tmp, cmp
py=${POUNDING_PYTHON:-/usr/bin/python3}
fail() { echo "FAIL: $*"; exit 1; }
run() { "$bin" run "$tmp/$1.toml" --out "$tmp/$1.h5" --quiet "${@:2}" > "$tmp/$1.log" 2>&1 || { cat "$tmp/$1.log"; fail "$1 did not run"; }; }

awk 'BEGIN { dt = 0.01; for (i = 0; i <= 1200; i++) { t = i * dt;
       a = 0.12 * sin(2 * 3.14159265 * 0.9 * t) * exp(-0.15 * t) + 0.06 * sin(2 * 3.14159265 * 2.3 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$tmp/rec.txt"
row() {  # the shipped study, small, one text record, a third building; $1: extra sed expression
  sed -e 's/^samples_per_pair = 20 /samples_per_pair = 2 /' -e '/^output = /d' -e 's/^bootstrap = 2000/bootstrap = 200/' \
      -e "s|^curve = \"example-hazard.csv\"|curve = \"$src/studies/example-hazard.csv\"|" \
      -e 's/^suite = "builtin"/files = ["rec.txt"]\npolarity = "recorded"/' -e '/^synthetic_only/d' -e '/^limit = /d' \
      -e 's/^model = "shear"/model = "shear"\nbuildings = 3/' \
      -e 's/^mass = 3.1e6/mass = 3.1e6\nfloor_mass = 3.875e5\nstorey_stiffness = 6e8/' \
      -e 's/^mass = 4.7e6/mass = 4.7e6\nfloor_mass = 3.9e5\nstorey_stiffness = 4e8/' \
      -e 's/^\[gaps\]/[structures.building3]\nperiod = 0.7\nheight = 21.0\nmass = 2.3e6\nfloor_mass = 3.8e5\nstorey_stiffness = 5e8\n\n[gaps]/' \
      -e "${1:-b}" "$src/studies/fragility-storeys.toml"
}
row 's/^max_scale = 10/max_scale = 10\n\n[analysis]\nscale_elastic = false/' > "$tmp/one.toml"
row 's/^max_scale = 10/max_scale = 10\nmethod = "ida"\ntolerance = 0.02/' > "$tmp/one_ida.toml"
(cd "$tmp" && run one && run one_ida)
# 1. invariance
for m in one one_ida; do
  (cd "$tmp" && timeout 120 mpirun -np 1 "$bin" run "$tmp/$m.toml" --out "$tmp/${m}_r1.h5" --quiet > /dev/null 2>&1 &&
     timeout 120 mpirun -np 2 "$bin" run "$tmp/$m.toml" --out "$tmp/${m}_r2.h5" --quiet > /dev/null 2>&1) || fail "$m under mpirun"
  for o in r1 r2; do cmp "$tmp/$m.h5" "$tmp/${m}_$o.h5" --ignore=output; done
done
# 2. a lane is simulate
sim() {  # factor out.json
  "$py" -c "
import sys
f = float(sys.argv[1])
for line in open(sys.argv[2]):
    t, a = line.split()
    print(t, repr(f * (float(a) * 9.80665)))" "$1" "$tmp/rec.txt" > "$tmp/scaled.txt"
  "$bin" simulate --record "$tmp/scaled.txt" --units m/s2 --contact none --zeta 0.05 --alpha 0.05 --buildings 3 \
    --storeys1 8 --storey-mass1 3.875e5 --storey-stiffness1 6e8 --storey-height1 3.5 \
    --storeys2 12 --storey-mass2 3.9e5 --storey-stiffness2 4e8 --storey-height2 3.5 \
    --storeys3 6 --storey-mass3 3.8e5 --storey-stiffness3 5e8 --storey-height3 3.5 --json > "$2"
}
stripe_factor=$("$py" -c "import h5py; print(repr(float(h5py.File('$tmp/one.h5', 'r')['intensity/scale'][6, 0])))")
sim "$stripe_factor" "$tmp/lane.json"
"$py" - "$tmp/one.h5" "$tmp/lane.json" <<'PY'
import sys, json, h5py
f, j = h5py.File(sys.argv[1], "r"), json.load(open(sys.argv[2]))
u = f["uncoupled"]
n = 0
for b in (1, 2, 3):
    assert list(u[f"peak_u_floors{b}"][6, 0, 0]) == j[f"peak_u{b}"], (b, u[f"peak_u_floors{b}"][6, 0, 0], j[f"peak_u{b}"])
    assert list(u[f"peak_drift{b}"][6, 0, 0]) == j[f"peak_drift{b}"], b
    n += 2 * len(j[f"peak_u{b}"])
assert u["peak_u3"][6, 0, 0] == max(j["peak_u3"])
labels = [x.decode() if isinstance(x, bytes) else x for x in f["system/element_label"][()]]
assert labels == [l["label"] for l in j["levels"]], (labels, j["levels"])
assert list(u["peak_closing_elements"][6, 0, 0]) == [l["peak_closing"] for l in j["levels"]]
assert u["peak_closing"][6, 0, 0] == max(l["peak_closing"] for l in j["levels"])
assert max(j["peak_drift1"]) > 0.02 / 6 * 3.5, "the lane should yield at this stripe (else test a higher one)"
print(f"ok   stripe 7, record 1, model 1 of the row = simulate --buildings 3 on the record x {f['intensity/scale'][6, 0]:.4g}: "
      f"{n + len(labels) + 1} numbers bit for bit, D {u['peak_closing'][6, 0, 0]:.4f} m")
PY
# 3. the IDA's brackets: up to 3 bisected (model, gap) of record 1, each checked at both ends
check_ida_brackets "$tmp/one_ida.h5"
