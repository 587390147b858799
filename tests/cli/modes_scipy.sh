#!/usr/bin/env bash
# `pounding modes --json` on non-uniform shear buildings against tools/reference_systems.py (scipy.linalg.eigh(K, M),
# none of our code; issue 25 §5, docs/architecture.md §2.8 "non-uniform modes"). 40 random sticks (numpy seed 25):
# 1 to 40 storeys, floor masses 1e4 to 1e6 kg and storey stiffnesses 1e7 to 1e9 N/m (log-uniform, each floor
# and storey drawn alone, so neighbours differ by up to 100x), zeta 0 to 0.2, a random Rayleigh pair. Compared at 1e-9:
# omega, period, frequency and each mode's Rayleigh zeta relative; Gamma (roof = 1) relative; the shape relative
# to the mode's largest |value| (at the Davis-Kahan bound where that is looser, see below); effective mass, its share and the cumulative share relative to the total mass.
# First the reference's own selftest (eigh against the uniform closed form, lsim and modal superposition
# against a damped SDOF's step response, lsim against modal on a 3-storey building).
# Needs /usr/bin/python3 with numpy and scipy: skipped (exit 77) without them, a failure under CI=true.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import numpy, scipy' 2>/dev/null ||
  skip_or_fail "needs $py with numpy and scipy (Debian: python3-numpy python3-scipy; tools/setup.sh installs them)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$py" "$src/tools/reference_systems.py" selftest > "$tmp/selftest.txt" || { cat "$tmp/selftest.txt"; exit 1; }

"$py" - "$tmp/cases.txt" "$tmp/cases.json" <<'PY'
import json, sys, numpy as np
rng = np.random.default_rng(25)
cases = []
with open(sys.argv[1], "w") as f:
    for case in range(40):
        n = 1 + case if case < 30 else int(rng.integers(1, 41))
        m = 1e4 * 10 ** rng.uniform(0, 2, n)
        k = 1e7 * 10 ** rng.uniform(0, 2, n)
        zeta = rng.uniform(0, 0.2)
        pair = sorted(int(x) for x in rng.choice(np.arange(1, n + 1), 2, replace=False)) if n > 1 else [1, 2]
        cases.append({"masses": list(m), "stiffnesses": list(k), "zeta": zeta, "rayleigh_modes": pair})
        f.write(" ".join([",".join(repr(float(x)) for x in m), ",".join(repr(float(x)) for x in k), repr(zeta),
                          f"{pair[0]},{pair[1]}"]) + "\n")
json.dump(cases, open(sys.argv[2], "w"))
PY
"$py" "$src/tools/reference_systems.py" modes --input "$tmp/cases.json" > "$tmp/scipy.json"
case=0
while read -r masses stiffnesses zeta pair; do
  case=$((case + 1))
  extra=()
  [ "$(echo "$masses" | tr ',' '\n' | wc -l)" -gt 1 ] && extra=(--rayleigh-modes "$pair")
  "$bin" modes --masses "$masses" --stiffnesses "$stiffnesses" --zeta "$zeta" "${extra[@]}" --json \
    > "$tmp/engine_$case.json"
done < "$tmp/cases.txt"

"$py" - "$tmp" "$case" <<'PY'
import json, sys
tmp, cases = sys.argv[1], int(sys.argv[2])
tol, worst, bad, confined = 1e-9, {}, [], 0
reference = json.load(open(f"{tmp}/scipy.json"))
def note(key, err, where):
    worst[key] = max(worst.get(key, 0.0), err)
    if not err <= tol:
        bad.append(f"{where} {key}: error {err:.3e}")
for c in range(1, cases + 1):
    e = json.load(open(f"{tmp}/engine_{c}.json"))
    r = reference[c - 1]
    assert len(e["modes"]) == len(r["modes"]) == e["storeys"], f"case {c}: mode counts"
    total = r["total_mass"]
    for key in ("a0", "a1"):
        if key in r["damping"]:
            note(key, abs(e["damping"][key] - r["damping"][key]) / max(abs(r["damping"][key]), 1e-300), f"case {c}")
    for em, rm in zip(e["modes"], r["modes"]):
        where = f"case {c} ({e['storeys']} storeys) mode {rm['mode']}"
        if em["shape_normalisation"] != rm["shape_normalisation"]:
            bad.append(f"{where}: normalised to the {em['shape_normalisation']}, scipy to the {rm['shape_normalisation']}")
        confined += em["shape_normalisation"] == "largest"
        for key in ("omega", "period", "frequency", "zeta"):
            note(key, abs(em[key] - rm[key]) / max(abs(rm[key]), 1e-300), where)
        scale = max(abs(x) for x in rm["shape"])
        # an eigenvector is determined to d = (n eps ||A||) / gap (Davis-Kahan) relative to its largest value;
        # scaled to roof = 1 it carries the roof's own relative error, d (largest / roof) = d max|shape|. The shape
        # is compared at 1e-9 or at that bound with n eps = 1e-13, whichever is looser (a mode with a close
        # neighbour, or one whose roof moves little).
        w2 = [x["omega"] ** 2 for x in r["modes"]]
        gap = min([abs(w2[rm["mode"] - 1] - x) for i, x in enumerate(w2) if i != rm["mode"] - 1] or [w2[-1]])
        shape_tol = max(tol, 1e-13 * w2[-1] / gap * (scale if rm.get("shape_normalisation", "roof") == "roof" else 1))
        note("shape", max(abs(a - b) for a, b in zip(em["shape"], rm["shape"])) / scale * tol / shape_tol, where)
        note("gamma", abs(em["gamma"] - rm["gamma"]) / max(abs(rm["gamma"]), 1.0 / scale), where)
        for key in ("effective_mass",):
            note(key, abs(em[key] - rm[key]) / total, where)
        for key in ("effective_mass_ratio", "cumulative_ratio"):
            note(key, abs(em[key] - rm[key]), where)
print(f"{cases} sticks ({confined} modes confined below the roof, scaled to their largest value), worst "
      f"differences against scipy.linalg.eigh (tolerance {tol:g}):")
for key, err in worst.items():
    print(f"  {key:<22} {err:.2e}")
if bad:
    print("FAIL:\n  " + "\n  ".join(bad[:20]), file=sys.stderr)
    sys.exit(1)
PY
