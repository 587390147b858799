#!/usr/bin/env bash
# Result format 2 from a real run (docs/results-format.md): every dataset carries non-empty `units` and
# `description`; status and the impacts fields have the shape of what they qualify; /gaps in every scene. And
# the format change moved no number: tests/data/results-format1.h5 (written by the format-1 writer from
# tests/data/results-format1.toml) holds, value for value, what this build writes for the same study.
# Needs /usr/bin/python3 with h5py and numpy (skipped without, a failure under CI=true).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null ||
  skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py python3-numpy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$bin" run "$src/tests/data/results-format1.toml" --out "$tmp/f2.h5" --quiet > /dev/null
sed 's/^scene = "impacts"/scene = "probability"/' "$src/tests/data/results-format1.toml" > "$tmp/p.toml"
"$bin" run "$tmp/p.toml" --out "$tmp/p.h5" --quiet > /dev/null
# The format-1 file's values are the Release build's bits: another build (POUNDING_BITS_NOT_CLAIMED, set by
# CMakeLists.txt: a sanitizer or -O2 build) or POUNDING_KERNEL_ARCH=OFF does not compare them, and says why.
"$py" - "$tmp/f2.h5" "$tmp/p.h5" "$src/tests/data/results-format1.h5" "${POUNDING_KERNEL_ARCH:-native}" \
  "${POUNDING_BITS_NOT_CLAIMED:-}" <<'PY'
import sys, h5py, numpy as np
new, prob, old, arch = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), h5py.File(sys.argv[3], "r"), sys.argv[4]
not_claimed = sys.argv[5]

def datasets(f):
    out = []
    f.visititems(lambda name, obj: out.append(name) if isinstance(obj, h5py.Dataset) else None)
    return out

for f in (new, prob):
    assert f.attrs["format_version"] == 2, f.attrs["format_version"]
    names = datasets(f)
    bare = [n for n in names if not f[n].attrs.get("units") or not f[n].attrs.get("description")]
    assert not bare, f"datasets without units or description: {bare}"
    R, M = len(f["records/id"]), len(f["models/T1"])
    for n in names:
        if n.startswith("uncoupled/"):
            assert f[n].shape == (R, M), (n, f[n].shape)
    assert f["gaps/ratios"][()].tolist() == [0.1, 0.3, 1.0]
    assert np.array_equal(f["gaps/metres"][()], f["models/code_gap"][()][:, None] * f["gaps/ratios"][()][None, :])
    print(f"ok:   {len(names)} datasets with units and description, status {f['uncoupled/status'].shape}")
G = 3
for n in datasets(new):
    if n.startswith("impacts/") and n != "impacts/gap_ratios":
        assert new[n].shape == (R, M, G), (n, new[n].shape)
assert "impacts" not in prob
print(f"ok:   impacts fields [records, models, gaps] = {new['impacts/status'].shape}; none in the probability scene")
units = {n: new[n].attrs["units"] for n in datasets(new)}
assert units["records/pga_g"] == "g" and units["models/m1"] == "kg" and units["impacts/peak_force"] == "N", units
# same values as the format-1 file (its flat arrays against the shaped ones)
if arch == "OFF":
    print("skip: value comparison with the format-1 file (POUNDING_KERNEL_ARCH=OFF: no FMA contraction)")
elif not_claimed:
    print(f"skip: value comparison with the format-1 file (not applicable: {not_claimed})")
else:
    for n in datasets(old):
        a, b = old[n][()], new[n][()]
        same = np.array_equal(a.ravel(), b.ravel(), equal_nan=a.dtype.kind == "f") if a.dtype.kind != "O" else \
            list(a.ravel()) == list(b.ravel())
        assert same, f"/{n} differs from the format-1 file"
    print(f"ok:   every one of the format-1 file's {len(datasets(old))} datasets has the same values")
PY
# a format-1 file still reads: the report of the fixture runs
"$bin" report "$src/tests/data/results-format1.h5" > "$tmp/old.md"
grep -q "^## Total probability of pounding (Table 3)" "$tmp/old.md"
echo "1 passed, 0 failed"
