#!/usr/bin/env bash
# Issue 44 items 8, 10 (command line) and 11: the command line refuses what a study refuses, before any work, as
# errors naming the option (exit 2, one " ERROR: " line, nothing on stdout, no output file or folder):
#   item 8  sizes: simulate --duration 1e12 (std::bad_alloc), --dt 1e-9 (std::bad_alloc), --bridge with
#           --wave-delay 1e300 (vector::_M_fill_insert) or 1e6 (3.1 GB), and runs whose time loop would not fit
#           in the memory available (POUNDING_TEST_MEMORY_AVAILABLE stands in for MemAvailable); collide --steps
#           2e9 (std::bad_alloc); motions --realisations and a study's [records.motions] that would not fit;
#   item 10 empty and wrapped values: simulate --modal-zeta '' (every mode's damping 0), --gap '' (a gap of 0),
#           modes --modal-zeta '' (Rayleigh instead), motions --seed -1 and 2^64 (2^64 - 1), a list with an empty
#           field (accuracy's lists dropped it: --laws linear,,kelvin ran two laws); bench --duration 1e9;
#   item 11 the study keys' ranges: storey masses 1e-30 and 1e300, --T1 1e9, --kh 1e30, --m1, --h1, --zeta,
#           --gap-offsets longer than the contact levels, a bridge's joints given --kh beyond a joint's range, and
#           motions from a target spectrum whose records a study refuses (PGA above 5 g).
# Every case runs under `timeout` with a virtual-memory limit, so a regression ends as a failure, not as a machine
# out of memory. Args: <pounding binary> <source dir>
set -uo pipefail
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }

# A 12 s two-column record (time s, acceleration g) at dt 0.01.
awk 'BEGIN { for (i = 0; i <= 1200; i++) { t = i * 0.01;
             printf "%.2f %.8f\n", t, 0.15 * sin(6.2831853 * 0.9 * t) + 0.1 * sin(6.2831853 * 3.1 * t) } }' \
  > "$tmp/rec.txt"
# The four-frame bridge with frame K on support K (four ground-motion channels).
awk '/^\[\[frame\]\]/ { print; print "support = " ++k; next } { print }' "$src/tests/data/bridge/four-frame.toml" \
  > "$tmp/ff4.toml"

# refuse <label> <patterns (|-separated, each must appear)> <command and arguments...>: exit 2, one ERROR line, every
# pattern, nothing on stdout, no $tmp/out* left. The command runs under a 20 s timeout and a 3 GiB address space.
refuse() {
  local label=$1 patterns=$2 rc=0
  shift 2
  rm -rf "$tmp"/out*
  (ulimit -v 3145728; exec timeout 20 "$bin" "$@") > "$tmp/stdout" 2> "$tmp/stderr" || rc=$?
  local bad="" p
  [ "$rc" = 2 ] || bad+=" exit $rc (want 2);"
  [ "$(grep -c '^ ERROR: ' "$tmp/stderr")" = 1 ] || bad+=" not one ' ERROR: ' line;"
  IFS='|' read -r -a list <<< "$patterns"
  for p in "${list[@]}"; do grep -qF -- "$p" "$tmp/stderr" || bad+=" no '$p';"; done
  [ ! -s "$tmp/stdout" ] || bad+=" wrote to stdout;"
  ! ls -d "$tmp"/out* > /dev/null 2>&1 || bad+=" output left: $(ls -d "$tmp"/out*);"
  if [ -n "$bad" ]; then fail "$label:$bad stderr: $(head -c 400 "$tmp/stderr")"; else ok "$label: $(head -c 240 "$tmp/stderr")"; fi
}
# accept <label> <command and arguments...>: exit 0 (the limits do not refuse what is valid)
accept() {
  local label=$1 rc=0
  shift
  rm -rf "$tmp"/out*
  (ulimit -v 3145728; exec timeout 60 "$bin" "$@") > "$tmp/stdout" 2> "$tmp/stderr" || rc=$?
  if [ "$rc" = 0 ]; then ok "$label: accepted"; else fail "$label: exit $rc: $(head -c 300 "$tmp/stderr")"; fi
  rm -rf "$tmp"/out*
}
sim=(simulate --record "$tmp/rec.txt" --series "$tmp/out.csv")
storeys=(simulate --record "$tmp/rec.txt" --storeys1 3 --storeys2 3)
motions=(motions --loss high --soil D --realisations 1 --duration 10 --rise 1 --strong 4 --match-points 5 --iterations 1 --quiet
         --out "$tmp/out_motions")

# ---- item 10: empty and silently wrapped values ----------------------------------------------------------------
refuse "simulate --modal-zeta ''" "--modal-zeta|empty" "${storeys[@]}" --modal-zeta ''
refuse "simulate --modal-zeta 0.02,,0.05" "--modal-zeta|empty field" "${storeys[@]}" --modal-zeta 0.02,,0.05
refuse "simulate --gap ''" "--gap|empty" "${sim[@]}" --gap ''
refuse "simulate --record ''" "--record|empty" simulate --record '' --series "$tmp/out.csv"
refuse "modes --modal-zeta ''" "--modal-zeta|empty" modes --storeys 3 --mass 1e5 --stiffness 1e8 --modal-zeta ''
refuse "motions --seed -1" "--seed|-1 is negative|[0, 2^64 - 1]" "${motions[@]}" --seed -1
refuse "motions --seed 2^64" "--seed|18446744073709551616|[0, 2^64 - 1]" "${motions[@]}" --seed 18446744073709551616
refuse "motions --seed 010" "--seed|leading zero" "${motions[@]}" --seed 010
refuse "motions --positions 0,,100" "--positions|empty field" "${motions[@]}" --positions 0,,100
refuse "accuracy restitution --laws linear,,kelvin" "--laws|empty field" accuracy restitution --laws linear,,kelvin
refuse "accuracy restitution --targets 0.5,,0.6" "--targets|empty field" accuracy restitution --targets 0.5,,0.6
refuse "accuracy chart --rows with an empty field" "--rows|empty field" accuracy chart --rows ,central-difference:hertzdamp:2
refuse "accuracy validate-muthukumar --ratios 0.3,,0.5" "--ratios|empty field" accuracy validate-muthukumar --ratios 0.3,,0.5
accept "motions --seed 18446744073709551615" "${motions[@]}" --seed 18446744073709551615

# ---- item 8: sizes with no upper bound ----------------------------------------------------------------------------
refuse "simulate --duration 1e12" "--duration|free vibration|give --duration <= 1012 s" "${sim[@]}" --duration 1e12
refuse "simulate --dt 1e-9" "--dt|1e+07 integration steps per record step|10000" "${sim[@]}" --dt 1e-9
refuse "simulate --bridge --wave-delay 1e300" "--wave-delay|[0, 200] s" \
  simulate --record "$tmp/rec.txt" --bridge "$tmp/ff4.toml" --wave-delay 1e300
refuse "simulate --bridge --wave-delay 1e6" "--wave-delay|[0, 200] s" \
  simulate --record "$tmp/rec.txt" --bridge "$tmp/ff4.toml" --wave-delay 1e6
# within the ranges, beyond the memory: POUNDING_TEST_MEMORY_AVAILABLE stands in for MemAvailable
export POUNDING_TEST_MEMORY_AVAILABLE=1073741824
refuse "simulate --duration 1000 --dt 1e-6 on a 1 GiB machine" "--duration|the run needs 89.4 GiB|every step kept for --series|1 GiB of memory available" \
  "${sim[@]}" --duration 1000 --dt 1e-6
export POUNDING_TEST_MEMORY_AVAILABLE=67108864
refuse "simulate --bridge --wave-delay 200 --dt 0.0005 on a 64 MiB machine" \
  "--wave-delay|4 supports of 61201 samples|64 MiB of memory available" \
  simulate --record "$tmp/rec.txt" --bridge "$tmp/ff4.toml" --wave-delay 200 --dt 0.0005
accept "simulate --duration 60 on a 64 MiB machine" "${sim[@]}" --duration 60 --gap 0.5
export POUNDING_TEST_MEMORY_AVAILABLE=1073741824
refuse "collide --steps 2e9 on a 1 GiB machine" "--steps|needs 44.7 GiB|give --steps <=" collide --steps 2000000000
refuse "bench --duration 1e9 on a 1 GiB machine" "--duration|of memory available|give --duration <=" bench --duration 1e9
unset POUNDING_TEST_MEMORY_AVAILABLE

# ---- item 11: the ranges of the study keys that mean the same quantity ----------------------------------------------
refuse "simulate --storey-mass1 1e-30" "--storey-mass1|[1e-3, 1e9] kg|floor_mass" "${storeys[@]}" --storey-mass1 1e-30
refuse "simulate --storey-mass1 1e300" "--storey-mass1|[1e-3, 1e9] kg|floor_mass" "${storeys[@]}" --storey-mass1 1e300
refuse "simulate --storey-stiffness2 1e15" "--storey-stiffness2|[1, 1e12]" "${storeys[@]}" --storey-stiffness2 1e15
refuse "simulate --storey-height1 0.001" "--storey-height1|[0.01, 10]" "${storeys[@]}" --storey-height1 0.001
refuse "simulate --T1 1e9" "--T1|[0.02, 20]|period" "${sim[@]}" --T1 1e9
refuse "simulate --T3 1e9 (a row)" "--T3|[0.02, 20]" simulate --record "$tmp/rec.txt" --buildings 3 --T3 1e9
refuse "simulate --kh 1e30" "--kh|(0, 1e20]|stiffness" "${sim[@]}" --kh 1e30
refuse "simulate --m1 1e-30" "--m1|[1e3, 1e10]|mass" "${sim[@]}" --m1 1e-30
refuse "simulate --h1 5000" "--h1|[2, 1000]" "${sim[@]}" --h1 5000
refuse "simulate --zeta 0.9" "--zeta|[0, 0.5]" "${sim[@]}" --zeta 0.9
refuse "simulate --k1 1e15" "--k1|[1, 1e12]" "${sim[@]}" --k1 1e15
refuse "simulate --fy1 1" "--fy1|times the weight|yield_coefficient" "${sim[@]}" --fy1 1
refuse "simulate --density 1e9" "--density|contact_density" "${sim[@]}" --density 1e9
refuse "simulate --gap-offsets longer than the levels" "--gap-offsets|5 values|levels 1 to 3" \
  "${storeys[@]}" --gap-offsets 0,0,0,0,0
refuse "simulate --gap-offsets -0.05" "--gap-offsets|[0, 10]" "${storeys[@]}" --gap 0.1 --gap-offsets -0.05,0,0
grep -v contact_stiffness "$src/tests/data/bridge/four-frame.toml" > "$tmp/nokc.toml"
refuse "simulate --bridge (joints without a stiffness) --kh 1e18" "--kh|[1, 1e16]|contact_stiffness" \
  simulate --record "$tmp/rec.txt" --bridge "$tmp/nokc.toml" --kh 1e18
accept "simulate --storeys1 3 --storeys2 3 (defaults)" "${storeys[@]}" --duration 2 --gap 0.5
accept "simulate --m1 1e3 --T1 0.5 --kh 1e20" simulate --record "$tmp/rec.txt" --duration 2 --m1 1e3 --T1 0.5 --kh 1e20 \
  --gap 0.5

# ---- motions: what a study refuses ---------------------------------------------------------------------------------
printf 'period_s,sa_g\n0,1e29\n0.5,1e29\n20,1e29\n' > "$tmp/huge_sa.csv"
refuse "motions from a csv target of Sa 1e29 g" "--spectrum-file|PGA|above the 5 g|a study refuses these records" \
  motions --loss high --realisations 1 --duration 10 --rise 1 --strong 4 --match-points 5 --iterations 1 --quiet \
  --spectrum csv --spectrum-file "$tmp/huge_sa.csv" --out "$tmp/out_motions"
export POUNDING_TEST_MEMORY_AVAILABLE=1073741824
refuse "motions --realisations 10000 (600 s, 4 supports) on a 1 GiB machine" \
  "--realisations|10000 realisations x 4 supports x 120001 samples need 35.8 GiB|--realisations <= 279" \
  motions --loss high --soil D --supports 4 --realisations 10000 --duration 600 --dt 0.005 --quiet --out "$tmp/out_motions"
# the same check for a study's [records.motions] (spatial::settings_from: one check for both)
cat > "$tmp/out_study.toml" <<'TOML'
seed = 26
[records.motions]
supports = 4
loss = "high"
soil = "D"
duration = 600.0
dt = 0.005
realisations = 10000
[bridge]
[[bridge.frame]]
mass = 1895413.0
period = 1.0
[[bridge.frame]]
mass = 1895413.0
period = 0.8
support = 2
[[bridge.joint]]
gap = 0.01
[contact]
stiffness = 2.0e9
TOML
mv "$tmp/out_study.toml" "$tmp/motions_study.toml"
refuse "a study's [records.motions] realisations = 10000 on a 1 GiB machine" \
  "motions_study.toml|realisations|35.8 GiB|realisations <= 279" run "$tmp/motions_study.toml" --out "$tmp/out.h5" --quiet
unset POUNDING_TEST_MEMORY_AVAILABLE

if [ "$fails" -gt 0 ]; then
  echo "FAIL: $fails check(s) failed"
  exit 1
fi
echo "input_simulate_limits: ok"
