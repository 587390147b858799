#!/usr/bin/env bash
# `pounding simulate --bridge FILE.toml` (issue 26 §1): the Muthukumar-DesRoches four-frame bridge
# (tests/data/bridge/four-frame.toml: Q-Hyst frames, Hertzdamp hinges, restrainers, bearings, Caltrans abutments)
#  - runs with status ok at --dt 0.0005, one line per joint (impacts, peak force) and per link (restrainers, hinge
#    and abutment bearings, backfill: peak force and deformation), per-frame peaks; the energy balance closes;
#  - --json and the text agree on the per-joint impacts and the links;
#  - an abutment's Caltrans numbers (width, height) give K_abut and P_bw (T5.3): the backfill never exceeds P_bw;
#  - multi-support (issue 26 §2): the same bridge with each frame on its own support (4 channels) and --wave-delay 0
#    prints the uniform run's observers exactly; --support-record with the same file 4 times too; --wave-delay 0.05
#    changes them and the energy balance (with the supports' work) still closes;
#  - e(v0) at the joints (--restitution-*; a joint's own restitution beside it refused): a constant curve is e; lindsay2011 counts per joint the impacts outside
#    its valid range;
#  - bad input: one ERROR line naming FILE:line and the key (or the option), exit 2, nothing on stdout.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
. "$src/tests/lib/simulate_cli.sh"  # $py, $tmp, fail, two_tone_record, sim, bad
two_tone_record 0.9
file="$src/tests/data/bridge/four-frame.toml"
sim() { "$bin" simulate --record "$tmp/rec.txt" "$@"; }

sim --bridge "$file" --dt 0.0005 > "$tmp/b.txt"
sim --bridge "$file" --dt 0.0005 --json > "$tmp/b.json"
"$py" - "$tmp/b.txt" "$tmp/b.json" <<'PY'
import json, sys
text = dict(l.split(": ", 1) for l in open(sys.argv[1]).read().splitlines() if ": " in l)
out = json.load(open(sys.argv[2]))
assert text["status"] == "ok", text["status"]
assert out["status"] == "ok"
assert abs(float(text["energy_balance_error_rel"])) < 1e-4, text["energy_balance_error_rel"]
for k in (1, 2, 3):
    line = text[f"joint {k}"]
    imp = int(line.split("impacts ")[1].split(",")[0])
    lev = out["levels"][k - 1]
    assert lev["label"] == f"joint {k}" and lev["impacts"] == imp, (lev, line)
    assert imp > 0, f"joint {k} is never hit: raise the record"
links = {l["label"]: l for l in out["links"]}
want = ["restrainer 1", "hinge bearing 1", "restrainer 2", "hinge bearing 2", "restrainer 3", "hinge bearing 3",
        "abutment left backfill", "abutment left bearing", "abutment right backfill", "abutment right bearing"]
assert list(links) == want, list(links)
for name, l in links.items():
    f = float(text[name].split("peak_force_N ")[1].split(",")[0])
    assert abs(f - l["peak_force"]) <= 1e-5 * max(1.0, f), (name, f, l)
# Caltrans SDC, 15.85 m x 1.6764 m back wall: P_bw = w h 239.401 kPa (h / 1.6764 m)
p_bw = 15.85 * 1.6764 * 5 * 4448.2216152605 / 0.3048**2
for side in ("left", "right"):
    assert links[f"abutment {side} backfill"]["peak_force"] <= p_bw * (1 + 1e-9), links[f"abutment {side} backfill"]
for k in (1, 2, 3, 4):
    assert 0 < out[f"peak_u{k}"][0] < 1, out[f"peak_u{k}"]
print("bridge: joints", [out["levels"][k]["impacts"] for k in range(3)], "restrainer peaks",
      [round(links[f"restrainer {k}"]["peak_force"]) for k in (1, 2, 3)], "frames", [out[f"peak_u{k}"][0] for k in (1, 2, 3, 4)])
PY

# multi-support: frame K on support K, the abutments on supports 1 and 4
"$py" - "$file" "$tmp/ff4.toml" <<'PY'
import sys
t = open(sys.argv[1]).read().split("[[frame]]")
out = t[0] + "".join(f"[[frame]]\nsupport = {k + 1}" + p for k, p in enumerate(t[1:]))
out = out.replace("[abutment.left]\n", "[abutment.left]\nsupport = 1\n").replace("[abutment.right]\n", "[abutment.right]\nsupport = 4\n")
open(sys.argv[2], "w").write(out)
PY
sim --bridge "$file" --dt 0.0005 | sed -n '/^status:/,$p' > "$tmp/u1.txt"
sim --bridge "$tmp/ff4.toml" --dt 0.0005 --wave-delay 0 | sed -n '/^status:/,$p' > "$tmp/u4.txt"
cmp "$tmp/u1.txt" "$tmp/u4.txt" || fail "4 supports with identical records differ from uniform input: $(diff "$tmp/u1.txt" "$tmp/u4.txt" | head -5)"
"$bin" simulate --bridge "$tmp/ff4.toml" --dt 0.0005 --support-record "$tmp/rec.txt" --support-record "$tmp/rec.txt" \
    --support-record "$tmp/rec.txt" --support-record "$tmp/rec.txt" | sed -n '/^status:/,$p' > "$tmp/s4.txt"
cmp "$tmp/u1.txt" "$tmp/s4.txt" || fail "--support-record x4 differs from uniform input"
sim --bridge "$tmp/ff4.toml" --dt 0.0005 --wave-delay 0.05 > "$tmp/wd.txt"
grep -q '^support4_record: .*(delayed 0.15 s)' "$tmp/wd.txt" || fail "support 4 is not delayed 0.15 s: $(grep support4 "$tmp/wd.txt")"
! cmp -s <(sed -n '/^status:/,$p' "$tmp/wd.txt") "$tmp/u1.txt" || fail "a wave delay changed nothing"
"$py" -c 'import sys; t = dict(l.split(": ", 1) for l in open(sys.argv[1]) if ": " in l)
assert t["status"].strip() == "ok" and abs(float(t["energy_balance_error_rel"])) < 1e-4, t["energy_balance_error_rel"]' "$tmp/wd.txt"

# bad input
bad "4 supports and one record" --bridge "$tmp/ff4.toml"
set +e; "$bin" simulate --bridge "$tmp/ff4.toml" --support-record "$tmp/rec.txt" --support-record "$tmp/rec.txt" > "$tmp/o" 2> "$tmp/e"
rc=$?; set -e
[ $rc -eq 2 ] && [ ! -s "$tmp/o" ] && grep -q "ERROR: 2 --support-record files for a bridge of 4 supports" "$tmp/e" ||
  fail "two records for four supports: exit $rc, $(cat "$tmp/e")"
bad "gives every support its record" --bridge "$tmp/ff4.toml" --support-record "$tmp/rec.txt"
bad "not a whole number of record steps" --bridge "$tmp/ff4.toml" --wave-delay 0.015
bad "add --bridge" --wave-delay 0.02
cp "$file" "$tmp/ok.toml"
sed 's/^mass = 1.30635e6$/mass = -1/' "$file" > "$tmp/neg.toml"
bad "mass = -1 is out of range, .*neg.toml:10 \[frame1\].mass" --bridge "$tmp/neg.toml"
sed 's/^zeta = 0.05$/zeta = 0.05\nspan = 40/' "$file" > "$tmp/unknown.toml"
bad "unknown.*span" --bridge "$tmp/unknown.toml"
sed 's/^backfill = "epp"$/backfill = "gravel"/' "$file" > "$tmp/fill.toml"
bad "unknown backfill 'gravel'.*\[abutment.left\].backfill" --bridge "$tmp/fill.toml"
"$py" -c 'import sys; t = open(sys.argv[1]).read(); i = t.rindex("[[joint]]"); j = t.index("[abutment.left]")
open(sys.argv[2], "w").write(t[:i] + t[j:])' "$file" "$tmp/joints.toml"
bad "4 frames need 3 joints" --bridge "$tmp/joints.toml"
sed 's/^contact_stiffness = 2.808e10$//' "$file" > "$tmp/kc.toml"
bad "contact_stiffness" --bridge "$tmp/kc.toml"
sed 's/^hysteresis = "q-hyst"$/hysteresis = "takeda"/' "$file" > "$tmp/hys.toml"
bad "unknown hysteresis 'takeda'" --bridge "$tmp/hys.toml"
bad "building options do not apply" --bridge "$file" --storeys1 3
bad "describes a building of the pair" --bridge "$file" --m1 1e6
bad "bridge file" --bridge "$tmp/missing.toml"

# e(v0) at the joints (issue 26 §3; the system stepper's onset): a constant curve e(v) = 0.6 runs as e = 0.6 (same
# impacts per joint, peaks within 1e-6); the preset lindsay2011 gives every joint its restitution_outside and their
# sum; text and JSON agree; a curve with another contact law is refused
sed '/^restitution = 0.6$/d' "$file" > "$tmp/noe.toml"
sim --bridge "$tmp/noe.toml" --dt 0.0005 --json --e 0.6 > "$tmp/e06.json"
sim --bridge "$tmp/noe.toml" --dt 0.0005 --json --restitution-polynomial 0.6 > "$tmp/c06.json"
sim --bridge "$tmp/noe.toml" --dt 0.0005 --json --restitution-preset lindsay2011 > "$tmp/lin.json"
sim --bridge "$tmp/noe.toml" --dt 0.0005 --restitution-preset lindsay2011 > "$tmp/lin.txt"
"$py" - "$tmp/e06.json" "$tmp/c06.json" "$tmp/lin.json" "$tmp/lin.txt" <<'PY'
import json, sys
e, c, lin = (json.load(open(p)) for p in sys.argv[1:4])
text = dict(l.split(": ", 1) for l in open(sys.argv[4]).read().splitlines() if ": " in l)
for k in range(1, 5):
    a, b = e[f"peak_u{k}"][0], c[f"peak_u{k}"][0]
    assert abs(a - b) <= 1e-6 * a, (k, a, b)
assert [l["impacts"] for l in e["levels"]] == [l["impacts"] for l in c["levels"]], (e["levels"], c["levels"])
assert sum(l["impacts"] for l in c["levels"]) > 0
assert all(l["restitution_outside"] == 0 for l in c["levels"]), c["levels"]  # a polynomial: valid [0, inf)
outside = [l["restitution_outside"] for l in lin["levels"]]
assert sum(outside) == lin["restitution_outside_valid"] and all(0 <= o <= l["impacts"] for o, l in zip(outside, lin["levels"]))
assert sum(outside) > 0, outside  # model-scale m/s: hinge impacts below 0.99 m/s are outside
assert text["restitution_outside_valid"] == f"{sum(outside)} of {sum(l['impacts'] for l in lin['levels'])} impacts", text["restitution_outside_valid"]
assert any(a != b for a, b in zip([lin[f"peak_u{k}"][0] for k in range(1, 5)], [e[f"peak_u{k}"][0] for k in range(1, 5)]))
print("bridge e(v0): constant = e, outside per joint", outside)
PY
bad "hertzdamp" --bridge "$tmp/noe.toml" --restitution-preset lindsay2011 --contact kelvin --kh 1e9
# a joint's own restitution beside a curve for every joint: refused at the joint's line (it was silently replaced)
bad "the joint gives its own restitution and --restitution-preset gives every joint e(v0), .*four-frame.toml:43 \[joint1\].restitution" \
  --bridge "$file" --restitution-preset lindsay2011
echo "simulate_bridge: ok"
