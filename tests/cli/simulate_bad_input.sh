#!/usr/bin/env bash
# `pounding simulate` with non-physical input (issue 2, "Bad input"): exit code 2, one " ERROR: ..." line on
# stderr that names the option, and no output file (neither --series FILE nor its temporary) left behind.
# Usage: simulate_bad_input.sh <pounding binary> <source dir>
set -uo pipefail
bin=${1:?pounding binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0

# A good run first: the harness itself must be able to see success and an output file.
if ! "$bin" simulate --duration 2 --series "$work/good.csv" >"$work/out" 2>"$work/err"; then
  echo "FAIL: a valid simulate run failed: $(cat "$work/err")"
  fails=$((fails + 1))
elif [[ ! -s $work/good.csv ]]; then
  echo "FAIL: a valid simulate run wrote no series file"
  fails=$((fails + 1))
fi

# check <option named in the message> <arguments...>
check() {
  local option=$1
  shift
  local out="$work/series.csv"
  rm -f "$out" "$out.tmp"
  "$bin" simulate --duration 2 "$@" --series "$out" >"$work/out" 2>"$work/err"
  local rc=$?
  local msg
  msg=$(cat "$work/err")
  local bad=""
  [[ $rc -eq 2 ]] || bad+=" exit code $rc (want 2);"
  grep -q '^ ERROR: ' "$work/err" || bad+=" no ' ERROR: ' line;"
  grep -qF -- "$option" "$work/err" || bad+=" message does not name $option;"
  [[ ! -e $out && ! -e $out.tmp ]] || bad+=" output file left behind;"
  if [[ -n $bad ]]; then
    echo "FAIL: simulate $*:$bad stderr: ${msg:0:200}"
    fails=$((fails + 1))
  else
    echo "ok:   simulate $* -> ${msg:0:120}"
  fi
}

# masses and periods: > 0 and finite
check --m1 --m1 0
check --m1 --m1 -1e6
check --m2 --m2 0
check --m1 --m1 nan
check --m2 --m2 inf
check --T1 --T1 0
check --T2 --T2 -1.5
check --T1 --T1 nan
check --T2 --T2 inf
# stiffness and yield given directly: > 0 (a negative value must not silently fall back to --T / --h)
check --k1 --k1 -5e7
check --k2 --k2 nan
check --fy1 --fy1 -1e5
check --h1 --h1 0
# restitution (0, 1]
check --e --e 0
check --e --e 1.5
check --e --e -0.2
check --e --e nan
# post-yield ratio [0, 1)
check --alpha --alpha 1
check --alpha --alpha -0.1
check --alpha --alpha inf
# damping ratio [0, 1)
check --zeta --zeta -0.05
check --zeta --zeta nan
# gap >= 0 and finite
check --gap --gap -0.01
check --gap --gap nan
check --gap --gap inf
# integration step > 0 (0 is not "default": it is a non-physical step)
check --dt --dt 0
check --dt --dt -0.001
check --dt --dt nan
# unknown names: the message names the option
check --contact --contact springy
check --damping-law --contact hertzdamp --damping-law bogus
check --stepper --stepper euler

if [[ $fails -gt 0 ]]; then
  echo "$fails bad-input case(s) failed"
  exit 1
fi
echo "all bad-input cases rejected"
