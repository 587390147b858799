# Sourced by the cli tests that set a one-record, one-model study of two shear buildings beside pounding simulate and
# compare them bit for bit (cli.study_steppers, cli.study_modal, cli.rayleigh_modes, cli.study_isolators), after they
# set $bin and $tmp:
#   sine_record FILE A1 F1 A2 F2 [STEPS]  a record (time s, acceleration g) at dt 0.01 s, STEPS + 1 rows (default
#                                         1200: 12 s): A1 sin(2 pi F1 t) + A2 sin(2 pi F2 t + 0.4), g and Hz
#   shear_pair_study FILE [KEY=VALUE ...] writes the study FILE: a 3-storey building (0.78 s, 9.6 m, 9e5 kg) beside
#                                         a 5-storey one (1.22 s, 16 m, 1.5e6 kg), storey stiffness 9.80665e7 N/m,
#                                         elastic, zeta 0.05 (Rayleigh), one sample, record rec.txt (beside FILE) as
#                                         recorded, gap ratios 0.1, 0.2, 0.5, 1 (d = 0.128 m: 0.5 d = 0.064 m), max_dt
#                                         1 ms, Hertzdamp with e 0.5. Each KEY=VALUE sets one key, KEY being the
#                                         table's dotted name and the key (title=..., structures.building2.storeys=4,
#                                         analysis.stepper=...), VALUE in TOML (strings quoted): replaced where the
#                                         study has the key, else added at the end of its table; an empty VALUE
#                                         removes the key. Line 23 is building 1's first added key (the isolation
#                                         table's errors name it).
#   shear_pair_simulate [options]         pounding simulate --json of the same pair on $tmp/rec.txt: uniform storeys
#                                         of 3e5 kg and 9.80665e7 N/m, --storeys2 $pair_storeys2 (default 5), --gap
#                                         $pair_gap (default 0.064), elastic, --zeta 0.05, --dt 0.001, then options.
sine_record() {
  awk -v a1="$2" -v f1="$3" -v a2="$4" -v f2="$5" -v n="${6:-1200}" 'BEGIN { dt = 0.01; for (i = 0; i <= n; i++) {
       t = i * dt; a = a1 * sin(2 * 3.14159265 * f1 * t) + a2 * sin(2 * 3.14159265 * f2 * t + 0.4);
       printf "%.2f %.8f\n", t, a } }' > "$1"
}

shear_pair_base() {
  cat <<'EOF'
title = "two shear buildings"
seed = 7
scene = "impacts"
output = "out.h5"

[records]
files = ["rec.txt"]
polarity = "recorded"

[structures]
model = "shear"
storey_height = 3.2
zeta = 0.05
hysteresis = "elastic"
samples_per_pair = 1

[structures.building1]
period = 0.78
height = 9.6
storeys = 3
mass = 9.0e5
storey_stiffness = 9.80665e7

[structures.building2]
period = 1.22
height = 16.0
storeys = 5
mass = 1.5e6
storey_stiffness = 9.80665e7

[gaps]
ratios = [0.1, 0.2, 0.5, 1.0]

[analysis]
max_dt = 0.001

[contact]
law = "hertzdamp"
e = 0.5
EOF
}

shear_pair_study() {
  local out=$1 kv name; shift
  local keys
  keys=$(for kv in "$@"; do
    name=${kv%%=*}
    [[ $name == *.* ]] || name=".$name"  # a top-level key: the table ""
    printf '%s\t%s\t%s\n' "${name%.*}" "${name##*.}" "${kv#*=}"
  done)
  shear_pair_base | KEYS=$keys awk '
    BEGIN { FS = "\t"; n = split(ENVIRON["KEYS"], rows, "\n")
            for (r = 1; r <= n; r++) { if (split(rows[r], f, "\t") != 3) continue
              value[f[1], f[2]] = f[3]; order[f[1], ++count[f[1]]] = f[2]; tables[f[1]] = 1 }
            FS = " = " }
    function added(t,   i, k) {  # the keys of table t the study does not have yet, at its end
      for (i = 1; i <= count[t]; i++) { k = order[t, i]; if (!done[t, k] && value[t, k] != "") print k " = " value[t, k] }
      seen[t] = 1 }
    /^$/ { blank++; next }
    /^\[.*\]$/ { added(table); for (; blank > 0; blank--) print ""; table = substr($0, 2, length($0) - 2); print; next }
    { for (; blank > 0; blank--) print ""
      if ((table, $1) in value) { done[table, $1] = 1; if (value[table, $1] != "") print $1 " = " value[table, $1]; next }
      print }
    END { added(table)
          for (t in tables) if (!(t in seen)) { print "shear_pair_study: no table [" t "]" > "/dev/stderr"; exit 1 } }
  ' > "$out"
}

shear_pair_simulate() {
  "$bin" simulate --record "$tmp/rec.txt" --storeys1 3 --storey-mass1 3e5 --storey-stiffness1 9.80665e7 \
    --storeys2 "${pair_storeys2:-5}" --storey-mass2 3e5 --storey-stiffness2 9.80665e7 --gap "${pair_gap:-0.064}" \
    --elastic --zeta 0.05 --dt 0.001 --json "$@"
}
