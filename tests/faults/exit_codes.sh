#!/usr/bin/env bash
# Issue 44 item 12: every command keeps to the exit-code table of docs/failure-behaviour.md. Each error is exit 2
# with ONE line on stderr, " ERROR: <what>, <where>, <how to fix>", never CLI11's raw text, exit 1 or a crash.
#  1. every command `pounding --help` lists, and every sub-command of those that have them (records select,
#     records im, accuracy chart, ...), read from the help itself: a bogus option; the command without its required
#     options and arguments where it has one (its help says REQUIRED); a value option given twice; a command that
#     needs a sub-command given none. --help and --version stay exit 0 with nothing on stderr.
#  2. the other parse errors: a value of the wrong type, two options that exclude each other, an option without
#     the option it needs, an option without its value, an unknown command.
#  3. the paths that ended with exit 1: out of memory (bench --width 1e11 under a 2 GiB
#     address-space limit: "out of memory" and how to make the problem smaller), a damaged chunk of a results file
#     (the file named, not just "zlib error -5 inflating chunk 1 of ..."), an HDF5 attribute of another type, output
#     to a full device (> /dev/full: exit 1, or exit 0 with the output lost); and an HDF5 file of another program
#     ("the study has no seed, :1" before): "not a pounding results file", named, with the fix.
# Synthetic records only (no ../shared); /usr/bin/python3 with h5py writes the damaged and foreign files.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); src=$(cd "$2" && pwd)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"  # nothing a command might write lands in the source tree
fails=0 checks=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
at=0
ok() { [ "$fails" != "$at" ] || echo "ok   $*"; at=$fails; }  # a section's line, when none of its checks failed

# expect_error <label> <regex the ERROR line must match> -- <command...>: exit 2, stderr exactly one line, that line
# " ERROR: <what>, <where>, <fix>" matching the regex.
expect_error() {
  local label=$1 want=$2 rc=0
  shift 3
  timeout 60 "$@" > "$tmp/out" 2> "$tmp/err" < /dev/null || rc=$?
  checks=$((checks + 1))
  local line bad=""
  line=$(head -1 "$tmp/err")
  [ "$rc" = 2 ] || bad+=" exit $rc (want 2);"
  [ "$(wc -l < "$tmp/err")" = 1 ] || bad+=" $(wc -l < "$tmp/err") lines on stderr (want 1);"
  [[ "$line" =~ ^\ ERROR:\ [^,].*,\ .+,\ .+$ ]] || bad+=" not ' ERROR: <what>, <where>, <how to fix>';"
  [[ "$line" =~ $want ]] || bad+=" does not match /$want/;"
  if [ -n "$bad" ]; then fail "$label:$bad stderr: $(head -c 400 "$tmp/err")"; fi
}

# --- 1. every command, read from the help --------------------------------------------------------------
# The sub-commands a help text lists (the lines after "Subcommands:").
subcommands() { "$bin" "$@" --help | awk '/^Subcommands:/ { on = 1; next } on && /^  [a-z]/ { print $1 }'; }
commands=()
while read -r c; do
  commands+=("$c")
  while read -r s; do commands+=("$c $s"); done < <(subcommands "$c")
done < <(subcommands)
[ "${#commands[@]}" -ge 20 ] || fail "only ${#commands[@]} commands read from pounding --help"
for want in run report results simulate "records select" "records im" "records show" "accuracy chart" sample; do
  printf '%s\n' "${commands[@]}" | grep -qx "$want" || fail "'$want' is not among the commands read from the help"
done

# The options of a command's help, one per line: "<name> <TYPE or -> <default or -> <vector: 1 or 0> <required: 1 or 0>".
options_of() {
  "$bin" $1 --help | awk '
    /^(Options|Positionals):/ { on = 1; next }
    /^[A-Z][a-z]*:/ { on = 0 }
    on && /^  [-a-z]/ {
      head = substr($0, 3); sub(/  +.*/, "", head)
      n = split(head, w, " "); name = w[1]; sub(/^-[a-z],/, "", name)
      type = "-"; def = "-"; vec = 0; req = 0
      for (i = 2; i <= n; i++) {
        if (w[i] == "...") vec = 1
        else if (w[i] == "REQUIRED") req = 1
        else if (w[i] ~ /^[A-Z]+(=.*)?$/) { type = w[i]; if (type ~ /=/) { def = type; sub(/^[A-Z]+=/, "", def); sub(/=.*/, "", type) } }
      }
      print name, type, def, vec, req
    }'
}

repeats=0 required=0
for cmd in "${commands[@]}"; do
  read -r -a words <<< "$cmd"
  expect_error "pounding $cmd --bogus-44" "unknown option '--bogus-44' in pounding $cmd, command line, " -- \
    "$bin" "${words[@]}" --bogus-44
  if [ -n "$(subcommands "${words[@]}")" ]; then
    expect_error "pounding $cmd (no sub-command)" "pounding $cmd needs a command, command line, give one of: " -- \
      "$bin" "${words[@]}"
    continue
  fi
  opts=$(options_of "$cmd")
  if echo "$opts" | awk '$5 == 1 { found = 1 } END { exit !found }'; then
    expect_error "pounding $cmd (required missing)" "pounding $cmd needs the (option|argument) [^,]+, command line, give " -- \
      "$bin" "${words[@]}"
    required=$((required + 1))
  fi
  # a value option (not a list) given twice: its default as the value where it shows one (it passes the option's
  # checks), else 1; the first option that CLI11 lets through to the count check is the one tested
  repeated=""
  while read -r name type def vec req; do
    [[ "$name" == --* && "$type" != - && "$vec" = 0 ]] || continue
    value=$def; [ "$value" != - ] || value=1
    timeout 60 "$bin" "${words[@]}" "$name" "$value" "$name" "$value" > /dev/null 2> "$tmp/err" < /dev/null || true
    if grep -q "is given 2 times" "$tmp/err"; then
      expect_error "pounding $cmd $name $value $name $value" \
        "the option $name of pounding $cmd is given 2 times, command line, give $name once" -- \
        "$bin" "${words[@]}" "$name" "$value" "$name" "$value"
      repeated=$name repeats=$((repeats + 1))
      break
    fi
  done < <(echo "$opts" | awk '$3 != "-"'; echo "$opts" | awk '$3 == "-"')
  if [ -z "$repeated" ] && echo "$opts" | awk '$1 ~ /^--/ && $2 != "-" && $4 == 0 { found = 1 } END { exit !found }'; then
    fail "pounding $cmd: no value option repeated gave 'is given 2 times' (last stderr: $(head -c 300 "$tmp/err"))"
  fi
done
ok "${#commands[@]} commands: a bogus option each, the required ones missing ($required commands), a value option twice
     ($repeats commands), no sub-command ($checks checks)"

for h in "--help" "run --help" "records select --help" "accuracy --help" "--version"; do
  rc=0; "$bin" $h > "$tmp/out" 2> "$tmp/err" || rc=$?
  { [ "$rc" = 0 ] && [ -s "$tmp/out" ] && [ ! -s "$tmp/err" ]; } || fail "pounding $h: exit $rc, stderr $(cat "$tmp/err")"
done
ok "--help and --version: exit 0, nothing on stderr"

# --- 2. the other parse errors ----------------------------------------------------------------------
expect_error "wrong type" "--T1 = abc, command line, give a value of the option's type" -- "$bin" simulate --T1 abc
expect_error "excluded options" "--(md|csv) and --(md|csv) of pounding report cannot be given together, command line, give one of them" -- \
  "$bin" report x.h5 --csv --md
expect_error "an option without the one it needs" "--no-figures of pounding report needs --html, command line, add --html" -- \
  "$bin" report x.h5 --no-figures
expect_error "an option without its value" "the option --out of pounding run has no value, command line, give --out a value" -- \
  "$bin" run x.toml --out
expect_error "unknown command" "unknown command 'bogus' in pounding, command line, check the spelling" -- "$bin" bogus
expect_error "unknown sub-command" "unknown command 'selec' in pounding records, command line, " -- "$bin" records selec
ok "wrong type, excluded, needs, no value, unknown command"

# --- 3. what ended with exit 1, and another program's HDF5 file --------------------------------------
# out of memory: a 2 GiB address-space limit makes the allocation fail whatever the machine's overcommit setting
if ! (ulimit -v 2097152 && "$bin" --version) > /dev/null 2>&1; then
  echo "note: pounding does not start under a 2 GiB address-space limit (a sanitizer build?): out of memory not checked"
else
  (ulimit -v 2097152; f0=$fails
   expect_error "out of memory (bench)" "^ ERROR: out of memory, pounding bench, give the command a smaller problem" -- \
     "$bin" bench --width 100000000000
   [ "$fails" = "$f0" ]) || fails=$((fails + 1))
  ok "out of memory: exit 2, said so, with how to make the problem smaller"
fi

suite="$src/records/stochastic-pounding-suite.toml"
sed -e 's/^samples_per_pair = 32/samples_per_pair = 8/' -e "s#^suite = .*#suite = \"$suite\"#" \
    "$src/studies/quick.toml" > "$tmp/q.toml"
"$bin" run "$tmp/q.toml" --out "$tmp/q.h5" --quiet > /dev/null 2>&1 || fail "the small study did not run"
/usr/bin/python3 - "$tmp" <<'PY' || fail "could not write the damaged and foreign files"
import shutil, sys
import h5py, numpy as np
d = sys.argv[1]
shutil.copy(f"{d}/q.h5", f"{d}/damaged.h5")
with h5py.File(f"{d}/q.h5", "r") as f:
    ds = f["uncoupled/peak_closing"]
    info = ds.id.get_chunk_info(ds.id.get_num_chunks() - 1)  # a stored, deflated chunk
with open(f"{d}/damaged.h5", "r+b") as g:
    g.seek(info.byte_offset + info.size // 2)
    g.write(b"\xff" * 16)
with h5py.File(f"{d}/foreign.h5", "w") as f:  # another program's file
    f["data"] = np.arange(10.0)
    f.attrs["creator"] = "h5py"
with h5py.File(f"{d}/typed.h5", "w") as f:  # format_version of another type
    f.attrs["format_version"] = "three"
PY
for c in "report" "report --csv"; do
  expect_error "damaged chunk ($c)" \
    "^ ERROR: cannot read $tmp/damaged.h5: chunk [0-9]+ of /uncoupled/peak_closing is damaged \(zlib error -?[0-9]+: [^)]*\), $tmp/damaged.h5, the file is damaged" -- \
    "$bin" $c "$tmp/damaged.h5"
done
expect_error "damaged chunk (report --html)" "cannot read $tmp/damaged.h5: chunk [0-9]+ of /uncoupled/peak_closing is damaged" -- \
  "$bin" report "$tmp/damaged.h5" --html "$tmp/d.html" --no-figures
[ ! -e "$tmp/d.html" ] || fail "report --html of a damaged file left $tmp/d.html"
for f in foreign typed; do
  for c in "report" "results" "report --csv"; do
    expect_error "$f HDF5 file ($c)" \
      "^ ERROR: $tmp/$f.h5 is not a pounding results file \(.*another program\), $tmp/$f.h5, give a results file written by .pounding run" -- \
      "$bin" $c "$tmp/$f.h5"
  done
done
ok "a damaged chunk names the file and the dataset; another program's HDF5 file is not a results file"

expect_error "report > /dev/full" "^ ERROR: .*No space left on device.*, pounding report, free disk space" -- \
  sh -c '"$1" report "$2" > /dev/full' sh "$bin" "$tmp/q.h5"
expect_error "study-reference > /dev/full" "^ ERROR: cannot write the output: .*, standard output of pounding study-reference, " -- \
  sh -c '"$1" study-reference > /dev/full' sh "$bin"
ok "output to a full device: exit 2 and an ERROR line, not exit 1 or 0"

if [ "$fails" -gt 0 ]; then echo "$fails check(s) failed"; exit 1; fi
echo "all exit-code checks passed ($checks ERROR lines checked)"
