#!/usr/bin/env bash
# The report's counts and warnings agree with each other and with the results file:
#  1. An impacts-scene study of shear buildings whose coupled runs are partly coarse (max_dt 5 ms): the report's
#     "excluded analyses" line gives the header's (and the banner's) total -- uncoupled and coupled together, each part
#     counted here from /uncoupled/status and /impacts/status -- not the uncoupled part alone; the coupled-runs table
#     sets the coupled count beside the uncoupled count on the same analyses (equal in every row) and says how many
#     coupled runs each gap excluded.
#  2. A fragility study of records selected to a spectrum: a record's scale against its recording is its selection
#     factor times the stripe's; the run names every record whose product is outside [0.25, 4] with both factors, and
#     the report's stripes table counts the products (here from /selection/scale x /intensity/scale).
#  3. ASCE 7-16 selection to the design-level spectrum is not called an MCER target (the run says it is design level).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null || { echo "SKIPPED: needs $py with h5py and numpy"; [ "${CI:-}" = true ] && exit 1; exit 77; }

# ---- 1 -----------------------------------------------------------------------------------------------------------------
sed -e "s#^output = .*#output = \"$tmp/c.h5\"#" "$src/studies/quick-storeys.toml" > "$tmp/c.toml"
printf '\n[analysis]\nmax_dt = 0.005\nmax_excluded_fraction = 1.0\n' >> "$tmp/c.toml"
"$bin" run "$tmp/c.toml" > "$tmp/c.out" 2>&1 || fail "the coarse study: exit $?: $(tail -3 "$tmp/c.out")"
"$bin" report "$tmp/c.h5" > "$tmp/c.md" || fail "pounding report: exit $?"
"$py" - "$tmp/c.h5" "$tmp/c.out" "$tmp/c.md" <<'PY' || fail "counts"
import re, sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
us, cs = f["uncoupled/status"][...], f["impacts/status"][...]
unc_bad, cpl_bad = int((us != 0).sum()), int((cs != 0).sum())
total = us.size + cs.size
assert f.attrs["excluded_analyses"] == unc_bad + cpl_bad and f.attrs["total_analyses"] == total, (
    f.attrs["excluded_analyses"], unc_bad, cpl_bad, f.attrs["total_analyses"], total)
assert cpl_bad > 0, "the test needs coarse coupled runs"
ratios = list(f["gaps/ratios"][...]) if "gaps/ratios" in f else None
for path in sys.argv[2:]:
    text = open(path).read()
    m = re.search(r"- excluded analyses: \*\*(\d+)\*\* of (\d+) \([0-9.]+ %\): uncoupled \(diverged or non-finite\) (\d+) of (\d+); "
                  r"coupled \(coarse, diverged or non-finite\) (\d+) of (\d+)", text)
    assert m, f"{path}: no excluded-analyses line with both parts"
    assert [int(x) for x in m.groups()] == [unc_bad + cpl_bad, total, unc_bad, us.size, cpl_bad, cs.size], (path, m.groups())
    rows = re.findall(r"^\| ([0-9.]+) \| (\d+) / (\d+) \| (\d+) / (\d+) \| (\d+) / (\d+) \| (\d+) \|$", text, re.M)
    assert len(rows) == cs.shape[2], (path, rows)
    for g, row in enumerate(rows):
        c_hits, c_n, s_hits, s_n, a_hits, a_n, excl = (int(x) for x in row[1:])
        assert (c_hits, c_n) == (s_hits, s_n), (path, row)
        want = int(((cs[:, :, g] != 0) & (us == 0)).sum())
        assert excl == want and c_n == int((us == 0).sum()) - want, (path, row, want)
print(f"ok   excluded {unc_bad + cpl_bad} of {total} (uncoupled {unc_bad} of {us.size}, coupled {cpl_bad} of {cs.size}); "
      f"coupled = uncoupled on the same analyses at {cs.shape[2]} gaps")
PY

# ---- 2, 3 --------------------------------------------------------------------------------------------------------------
sed -e 's/^samples_per_pair = 200 .*/samples_per_pair = 10/' -e "s#^output = .*#output = \"$tmp/fs.h5\"#" \
    "$src/studies/fragility-select.toml" > "$tmp/fs.toml"
"$bin" run "$tmp/fs.toml" > "$tmp/fs.out" 2>&1 || fail "the selected fragility study: exit $?: $(tail -3 "$tmp/fs.out")"
grep -q "this target is the design-level spectrum" "$tmp/fs.out" || fail "no design-level note on the ASCE 7-16 selection"
! grep -q "to the MCER target; these are single-component" "$tmp/fs.out" || fail "a design-level target called MCER"
"$bin" report "$tmp/fs.h5" > "$tmp/fs.md" || fail "pounding report (fragility): exit $?"
"$py" - "$tmp/fs.h5" "$tmp/fs.out" "$tmp/fs.md" <<'PY' || fail "scale factors"
import re, sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
sel = f["selection/scale"][...]
stripe, dropped = f["intensity/scale"][...], f["intensity/dropped"][...]
levels = f["intensity/levels"][...] if "intensity/levels" in f else None
S, R = stripe.shape
P = R // sel.size
ids = [x.decode() if isinstance(x, bytes) else str(x) for x in f["selection/records"][...]]
out, md = open(sys.argv[2]).read(), open(sys.argv[3]).read()
named = set(re.findall(r"^record (\S+): scale factor outside \[0\.25, 4\]", out, re.M))
want_named, counts = set(), []
for s in range(S):
    n = 0
    for r in range(0, R, P):
        if dropped[s, r]: continue
        x = stripe[s, r] * sel[r // P]
        if x < 0.25 or x > 4:
            n += 1
            want_named.add(r // P)
    counts.append(n)
assert len(named) == len(want_named), (sorted(named), sorted(want_named))
assert any(stripe[s, r] <= 4 < stripe[s, r] * sel[r // P] for s in range(S) for r in range(0, R, P) if not dropped[s, r]), \
    "the test needs a record inside [0.25, 4] at its stripe factor and outside with its selection factor"
assert re.search(r"x[0-9.]+ \(selection [0-9.]+ x stripe [0-9.]+\) at", out), "the factors are not both named"
table = md.split("## Stripes and scale factors")[1].split("\n## ")[0]
rows = [l for l in table.splitlines() if re.match(r"^\| [0-9.]", l)]
got = [int(l.split("|")[7]) for l in rows]
assert got == counts, (got, counts)
print(f"ok   {len(named)} records scaled outside [0.25, 4] (selection x stripe); per stripe {counts}")
PY
echo "report_counts: ok"
