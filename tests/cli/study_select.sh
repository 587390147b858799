#!/usr/bin/env bash
# A study with [records] select = N and [target_spectrum] chooses the same records with the same factors as
# `pounding records select` with the same target and options on the same library (issue 14 part 4): the two
# paths share only select_records and the summary's format -- the study parses TOML, resolves its period range
# from the buildings' median periods and loads the library through load_study_records; the command line parses
# flags and reads the files itself. The library is the builtin synthetic suite written as AT2 (`records suite
# --write`), so no ../shared is needed. Three targets: ASCE 7-16 (rule ASCE 7-16), EC8 type 1 ground C (rule EC8,
# with its PGA condition) and a tabulated csv (rule ASCE 7-10, range 0.2-1.5 T). For each: the printed rows (rank,
# record, f_i, MSE, scale), the suite factor, the smallest mean/target and the verdict are identical; the results'
# /selection (ids, scale, mean) agrees with the command line's CSV to 1e-8; /records holds the chosen records in
# that order with their PGA multiplied by the factor. 1 and 2 ranks: cli.study_select_ranks. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py=${POUNDING_PYTHON:-/usr/bin/python3}
. "$src/tests/lib/needs_real_records.sh"
"$py" -c 'import h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py python3-numpy)"

"$bin" records suite --synthetic-only --write "$tmp/lib" > /dev/null
[ "$(ls "$tmp/lib" | wc -l)" = 25 ] || fail "records suite --write: not 25 AT2 files"
printf 'period_s,sa_g\n0.0,0.4\n0.1,1.0\n0.5,1.0\n1.0,0.55\n2.0,0.3\n4.0,0.12\n' > "$tmp/target.csv"

study() {  # <name> <select> <target section>: tests/data/study-select-pair.toml on the library
  { cat "$src/tests/data/study-select-pair.toml"; printf '[records]\ndirectory = "lib"\nselect = %s\n%s\n' "$2" "$3"; } \
    > "$tmp/$1.toml"
}

rows() {  # the summary from "target:" to "condition", without the file column (the study shows the record's source)
  sed -n '/^target: /,/^condition/p' "$1" | awk '/^ *[0-9]+ /{ print $1, $2, $3, $4, $5; next } { print }' |
    grep -v '^target: '
}

compare() {  # <name> <select> <target section> <records select flags...>
  local name=$1 n=$2 section=$3; shift 3
  study "$name" "$n" "$section"
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" > "$tmp/$name.log" 2>&1 || fail "$name: run: $(cat "$tmp/$name.log")"
  "$bin" records select --directory "$tmp/lib" --period 0.9,1.3 --count "$n" "$@" -o "$tmp/$name.csv" \
    > "$tmp/$name.cli" 2>&1 || fail "$name: records select: $(cat "$tmp/$name.cli")"
  rows "$tmp/$name.log" > "$tmp/$name.study.rows"
  rows "$tmp/$name.cli" > "$tmp/$name.cli.rows"
  [ "$(grep -c '^ *[0-9]* EQ' "$tmp/$name.study.rows")" = "$n" ] || fail "$name: $n rows expected: $(cat "$tmp/$name.log")"
  diff "$tmp/$name.cli.rows" "$tmp/$name.study.rows" > "$tmp/$name.diff" ||
    fail "$name: the study's selection differs from records select:
$(cat "$tmp/$name.diff")"
  "$py" - "$tmp/$name.h5" "$tmp/$name.csv" "$n" "$src/tests/lib" <<'PY'
import sys, h5py, numpy as np
h5, csv, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
sys.path.insert(0, sys.argv[-1])
from selection_csv import read_selection_csv
meta, header, rows = read_selection_csv(csv)
data = np.array(rows)
with h5py.File(h5) as f:
    g = f["selection"]
    ids = [x.decode() for x in g["records"][()]]
    assert ids == header[3:], (ids, header[3:])
    assert len(ids) == n
    rec_ids = [x.decode() for x in f["records/id"][()]]
    if f["settings/records"].attrs["polarity"] in ("both", b"both"):  # a pair study: each record with both signs
        assert list(f["records/polarity"][()]) == [1, -1] * n and rec_ids[0::2] == rec_ids[1::2], rec_ids
        rec_ids = rec_ids[0::2]
    assert rec_ids == ids, ("the analysed records are the chosen ones, in order", rec_ids, ids)
    F = g.attrs["suite_factor"]
    assert abs(F / float(meta["suite_factor"]) - 1) < 1e-8, (F, meta["suite_factor"])
    assert np.allclose(g["periods"][()], data[:, 0], rtol=1e-8, atol=0)
    assert np.allclose(g["target"][()], data[:, 1], rtol=1e-8, atol=0)
    assert np.allclose(g["mean"][()], data[:, 2], rtol=1e-8, atol=0)
    assert np.allclose(g["spectra"][()].T, data[:, 3:], rtol=1e-8, atol=0)
    scale = g["scale"][()]
    assert np.allclose(scale, g["individual_scale"][()] * F, rtol=1e-14)
    assert int(g.attrs["meets"]) == (meta["condition_holds"] == "yes")
    # the analysed records are the library's, multiplied by f_i F (PGA of the AT2 files x scale)
    pga = f["records/pga_g"][()][:: len(f["records/pga_g"][()]) // n]  # the recorded rows (polarity "both": every other)
    lib = {}
    for i, rid in enumerate(ids):
        vals = []
        for line in open(f"{h5.rsplit('/', 1)[0]}/lib/{rid}.AT2").read().splitlines()[4:]:
            vals += [float(x) for x in line.split()]
        lib[rid] = max(abs(v) for v in vals)
        assert abs(pga[i] / (scale[i] * lib[rid]) - 1) < 1e-9, (rid, pga[i], scale[i], lib[rid])
print(f"{h5}: {n} records, F = {F:.6f}, /selection agrees with the CLI CSV to 1e-8, PGAs scaled by f_i F")
PY
  echo "ok   $name: $(grep -m1 '^suite factor' "$tmp/$name.log"), $(grep -m1 '^condition' "$tmp/$name.log")"
}

compare asce 11 '[target_spectrum]
code = "ASCE 7-16"
sds = 1.0
sd1 = 0.6
tl = 8' --asce7 1.0,0.6,8
compare ec8 7 '[target_spectrum]
code = "EC8"
type = 1
ground = "C"
agr = 0.25
max_scale = 10' --ec8 1,C,0.25 --max-scale 10
grep -q "mean PGA / ag S = " "$tmp/ec8.log" || fail "ec8: no PGA ratio in the run log"
compare csv 9 '[target_spectrum]
code = "csv"
file = "target.csv"
rule = "ASCE 7-10"
points = 20
min_scale = 0.2' --target-csv "$tmp/target.csv" --rule "ASCE 7-10" --points 20 --min-scale 0.2
grep -q "0.18-1.95 s" "$tmp/csv.log" || fail "csv: ASCE 7-10 range 0.2 min T - 1.5 max T: $(grep '^rule' "$tmp/csv.log")"
# the report prints the section
"$bin" report "$tmp/asce.h5" | sed -n '/^## Records selected to the design spectrum/,$p' > "$tmp/asce.md"
grep -q "## Records selected to the design spectrum" "$tmp/asce.md" || fail "report: no selection section"
[ "$(grep -c '^| EQ' "$tmp/asce.md")" = 11 ] || fail "report: 11 rows expected"
grep -q "90 % of the target over 0.18-2.60 s: \*\*holds\*\*" "$tmp/asce.md" || fail "report: no condition line"
echo "study_select: ok"
