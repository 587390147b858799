#!/usr/bin/env bash
# Issue 10.5: an unknown key has ONE wording everywhere -- study file (top level, [records], a files entry,
# [analysis], [structures]), records suite file ([suite], [[record]]) and the command line (unknown option,
# surplus argument, unknown command):
#   " ERROR: unknown <key|option|argument|command> '<name>' in <section>, <where>, check the spelling; <section> takes: <list>"
# exit 2, nothing else on stderr. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }

# check <label> <kind> <name> <section> <where> <one allowed name> -- <command...>
check() {
  local label=$1 kind=$2 name=$3 section=$4 where=$5 allowed=$6 rc=0
  shift 7
  "$@" > "$tmp/out" 2> "$tmp/err" || rc=$?
  local line expect
  line=$(cat "$tmp/err")
  expect=" ERROR: unknown $kind '$name' in $section, $where, check the spelling; $section takes: "
  local bad=""
  [ "$rc" = 2 ] || bad+=" exit $rc (want 2);"
  [ "$(wc -l < "$tmp/err")" = 1 ] || bad+=" $(wc -l < "$tmp/err") lines on stderr (want 1);"
  [ "${line:0:${#expect}}" = "$expect" ] || bad+=" wording differs (want '$expect...');"
  case "${line:${#expect}}" in *"$allowed"*) ;; *) bad+=" allowed list lacks '$allowed';" ;; esac
  ! ls "$tmp"/o.* > /dev/null 2>&1 || bad+=" output left;"
  if [ -n "$bad" ]; then fail "$label:$bad got: $line"; else ok "$label"; fi
}

base='seed = 1
[records]
suite = "builtin"
synthetic_only = true
limit = 1
[structures]
periods = [1.0]
samples_per_pair = 2'
printf 'colour = 1\n%s\n' "$base" > "$tmp/top.toml"
check "study top level" key colour "the study file's top level" "$tmp/top.toml:1 colour" "records" -- \
  "$bin" run "$tmp/top.toml" --out "$tmp/o.h5"
printf '%s\n' "$base" | sed 's/^limit = 1$/limit = 1\nlimmit = 2/' > "$tmp/rec.toml"
check "study [records]" key limmit "[records]" "$tmp/rec.toml:6 [records].limmit" "synthetic_only" -- \
  "$bin" run "$tmp/rec.toml" --out "$tmp/o.h5"
printf '%s\n[analysis]\nbatchsize = 8\n' "$base" > "$tmp/an.toml"
check "study [analysis]" key batchsize "[analysis]" "$tmp/an.toml:10 [analysis].batchsize" "max_excluded_fraction" -- \
  "$bin" run "$tmp/an.toml" --out "$tmp/o.h5"
printf '%s\nrho_meen = 1800\n' "$base" > "$tmp/st.toml"
check "study [structures]" key rho_meen "[structures]" "$tmp/st.toml:9 [structures].rho_meen" "rho_mean" -- \
  "$bin" run "$tmp/st.toml" --out "$tmp/o.h5"
printf 'seed = 1\n[records]\nfiles = [{path = "a.AT2", scael = 2}]\n' > "$tmp/fe.toml"
check "study files entry" key scael "[records.files]" "$tmp/fe.toml:3 [records.files].scael" "scale" -- \
  "$bin" run "$tmp/fe.toml" --out "$tmp/o.h5"
# a key of non-ASCII bytes is shown escaped (TOML itself refuses control characters in keys)
printf 'seed = 1\n[records]\nsuite = "builtin"\n[gaps]\n"\xc3\xa9x" = 2\n' > "$tmp/bin.toml"
check "study key with non-ASCII bytes" key '\xC3\xA9x' "[gaps]" "$tmp/bin.toml:5 [gaps].\xC3\xA9x" "ratios" -- \
  "$bin" run "$tmp/bin.toml" --out "$tmp/o.h5"

# records suite files
printf '[suite]\nnmae = "x"\n[[record]]\nid = "A"\nfile = "a.AT2"\n' > "$tmp/s1.toml"
check "suite [suite]" key nmae "[suite]" "$tmp/s1.toml:2" "name" -- "$bin" records suite "$tmp/s1.toml"
printf '[[record]]\nid = "A"\nfile = "a.AT2"\nspeed = 3\n' > "$tmp/s2.toml"
check "suite [[record]]" key speed "[[record]]" "$tmp/s2.toml:4" "pga_g" -- "$bin" records suite "$tmp/s2.toml"
printf 'record = 1\nextra = 2\n' > "$tmp/s3.toml"
check "suite top level" key extra "the suite file" "$tmp/s3.toml:2" "record" -- "$bin" records suite "$tmp/s3.toml"

# the command line
check "CLI option" option --colour "pounding collide" "command line" "--e" -- "$bin" collide --colour 1
check "CLI option (run)" option --outt "pounding run" "command line" "--out" -- "$bin" run x.toml --outt "$tmp/o.h5"
check "CLI argument" argument extra "pounding collide" "command line" "--law" -- "$bin" collide extra
check "CLI command" command bogus "pounding" "command line" "simulate" -- "$bin" bogus
check "CLI sub-command" command shwo "pounding records" "command line" "show" -- "$bin" records shwo

if [ "$fails" -gt 0 ]; then
  echo "FAIL: $fails check(s) failed"
  exit 1
fi
echo "input_unknown_keys: ok"
