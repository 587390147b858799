#!/usr/bin/env bash
# Base isolation and moat walls in studies ([structures.buildingK] isolation / moat, issue 25 §2, §6): the study's
# numbers equal `pounding simulate`'s for the same pair (the link-element paper's BIF20: isolated 3-storey against
# fixed 5-storey, Hertzdamp three-spring, e = 0.5, 20 cm) -- two independent paths into the system stepper
# (study/system_block.cpp and cli/commands/simulate.cpp) -- per record and sign, uncoupled and coupled; and with a
# moat the walls stay active in the uncoupled run (and the run's description names the bearing and the moat) (its base peak stays below the moat's gap plus the wall's
# penetration), while the pounding's D still decides every gap. Needs ../shared/records/real.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
. "$src/tests/lib/needs_real_records.sh"
needs_real_records
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sed "s|\.\./\.\./shared/records/real|$real|" "$src/studies/link-element-pairs.toml" > "$tmp/le.toml"
"$bin" run "$tmp/le.toml" --out "$tmp/le.h5" --quiet > /dev/null 2>&1
for rec in Kobe_1995_NishiAkashi_000 LomaPrieta_1989_GilroyArray3_000; do
  "$bin" simulate --record "$real/$rec.txt" --storeys1 3 --storey-mass1 3e5 --storey-stiffness1 9.80665e7 \
    --isolation1 linear --base-mass1 3e5 --bearing-keff1 1e6 --bearing-zeta1 0 --storeys2 5 --storey-mass2 3e5 \
    --storey-stiffness2 9.80665e7 --gap 0.2 --elastic --zeta 0.05 --contact hertzdamp --damping-law three-spring \
    --e 0.5 --dt 0.001 --json > "$tmp/$rec.json"
done
/usr/bin/python3 - "$tmp" <<'PY'
import json, sys, h5py, numpy as np
tmp = sys.argv[1]
f = h5py.File(f"{tmp}/le.h5", "r")
ids = [x.decode() for x in f["records/id"][()]]
G = list(f["impacts/gap_ratios"][()])
g = G.index(1.5625)
d = f["models/code_gap"][()][0]
assert abs(1.5625 * d - 0.2) < 1e-12, d
close = lambda a, b: abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-12)
touched = 0
for rec in ["Kobe_1995_NishiAkashi_000", "LomaPrieta_1989_GilroyArray3_000"]:
    r = ids.index(rec)  # row 2r: as recorded (polarity both: 2r + 1 reversed)
    s = json.load(open(f"{tmp}/{rec}.json"))
    u1 = max(max(s["peak_u1"]), s["peak_bearing_u1"])  # the study's peak_u1 includes the base
    u2 = max(s["peak_u2"])
    st, cnt = f["impacts/status"][()].reshape(-1, len(G))[r, g], f["impacts/impact_count"][()].reshape(-1, len(G))[r, g]
    pu1 = f["impacts/peak_u1"][()].reshape(-1, len(G))[r, g]
    pu2 = f["impacts/peak_u2"][()].reshape(-1, len(G))[r, g]
    pf = f["impacts/peak_force"][()].reshape(-1, len(G))[r, g]
    t1 = f["impacts/t_first_impact"][()].reshape(-1, len(G))[r, g]
    assert st == 0 and s["status"] == "ok"
    assert cnt == s["impact_count"], (rec, cnt, s["impact_count"])
    assert close(pu1, u1) and close(pu2, u2), (rec, pu1, u1, pu2, u2)
    if cnt:
        touched += 1
        assert close(pf, s["peak_force"]) and close(t1, s["t_first_impact"]), (rec, pf, s["peak_force"], t1, s["t_first_impact"])
    # touch <=> D > gap (the uncoupled peak closing)
    assert (f["uncoupled/peak_closing"][()][r, 0] > 0.2) == (cnt > 0)
    print(f"{rec}: {cnt} impacts, peak force {pf:.6g} N, peak u1 {pu1:.6g} m -- study and simulate agree")
assert touched >= 1
PY
# a moat 5 cm around the isolated base: the walls act in the uncoupled run too (every record's largest displacement
# of the isolated building drops, 0.29-0.87 times the free one), and the study's pounding decision is still D > gap
sed 's/^isolation = {bearing = "linear", base_mass = 3.0e5, k_eff = 1.0e6, zeta_eff = 0.0}/&\nmoat = {gap = 0.05, law = "hertzdamp", e = 0.5}/' \
  "$tmp/le.toml" > "$tmp/moat.toml"
grep -q '^moat = ' "$tmp/moat.toml"
"$bin" run "$tmp/moat.toml" --out "$tmp/moat.h5" > "$tmp/moat.log" 2>&1
# the run says what it models: the bearing and the moat in building1's line, nothing of either in building2's
grep -q '^building1: shear building, .*; isolated: linear bearing k_eff 1e+06 N/m, zeta_eff 0; base 300000 kg; moat: walls 0.05 m either side of the base; law hertzdamp' "$tmp/moat.log" \
  || { echo "FAIL: the run does not describe building1's isolation and moat:"; grep '^building' "$tmp/moat.log"; exit 1; }
! grep '^building2: ' "$tmp/moat.log" | grep -q 'isolated\|moat' || { echo "FAIL: building2 described as isolated"; exit 1; }
/usr/bin/python3 - "$tmp" <<'PY'
import sys, h5py, numpy as np
tmp = sys.argv[1]
a, b = h5py.File(f"{tmp}/le.h5", "r"), h5py.File(f"{tmp}/moat.h5", "r")
free, walled = a["uncoupled/peak_u1"][()].ravel(), b["uncoupled/peak_u1"][()].ravel()
print("uncoupled peak u1 without / with a 5 cm moat:", np.round(free, 4), np.round(walled, 4))
assert (free > 0.1).all() and (walled < free).all() and (walled / free).mean() < 0.7, walled / free
G = len(b["impacts/gap_ratios"])
cnt = b["impacts/impact_count"][()].reshape(-1, G)
touch = b["uncoupled/peak_closing"][()].reshape(-1, 1) > b["impacts/gap_ratios"][()][None, :] * b["models/code_gap"][()][0]
assert np.array_equal(touch, cnt > 0)
PY
echo "1 passed, 0 failed"
