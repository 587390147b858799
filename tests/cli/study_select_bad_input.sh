#!/usr/bin/env bash
# Bad [records] select, max_per_event, components and [target_spectrum] inputs fail before any work (issue 14 part
# 4, issue 23 item 7): exit 2, one " ERROR:"
# line naming the file, line and key (and the fix), no results file and no checkpoint left behind.
# Args: <pounding binary> <source dir>
set -uo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
body=$(cat "$src/tests/data/study-select-pair.toml")
fails=0; passes=0
expect_error() {  # name, pattern expected in the message (grep -E), sections appended to the base study
  local name=$1 pattern=$2
  printf '%s\n%s\n' "$body" "$3" > "$tmp/$name.toml"
  "$bin" run "$tmp/$name.toml" --out "$tmp/$name.h5" --quiet > "$tmp/$name.out" 2>&1
  local rc=$?
  if [ $rc -ne 2 ] || [ "$(grep -c "ERROR:" "$tmp/$name.out")" != 1 ] || ! grep -Eq -- "$pattern" "$tmp/$name.out" \
     || [ -e "$tmp/$name.h5" ] || [ -e "$tmp/$name.h5.ckpt" ]; then
    echo "FAIL $name (rc $rc):"; cat "$tmp/$name.out"; fails=$((fails+1))
  else
    echo "ok   $name: $(grep ERROR "$tmp/$name.out")"; passes=$((passes+1))
  fi
}
R='[records]
suite = "builtin"
synthetic_only = true'
T='[target_spectrum]
code = "ASCE 7-16"
sds = 1.0
sd1 = 0.6'
n=$(printf '%s\n' "$body" | wc -l)  # the line numbers below count from the appended sections
expect_error select_without_target "no \[target_spectrum\].*select_without_target.toml:$((n + 4)) \[records\]\.select.*add \[target_spectrum\]" "$R
select = 11"
expect_error target_without_select "\[target_spectrum\] is given but \[records\] has no select.*target_spectrum.*add select = N" "$R
$T"
expect_error select_over_candidates "select = 30 but the library holds 25 records.*:$((n + 4)) \[records\]\.select.*select <= 25" "$R
select = 30
$T"
expect_error select_zero "select = 0 is out of range.*\[records\]\.select" "$R
select = 0
$T"
expect_error select_with_limit "limit and select.*\[records\]\.limit.*delete limit" "$R
limit = 5
select = 3
$T"
expect_error unknown_code "unknown design code 'ASCE 7-22'.*\[target_spectrum\]\.code.*ASCE 7-16" "$R
select = 11
[target_spectrum]
code = \"ASCE 7-22\""
expect_error bad_ground "ground = \"F\" is not one of the EC8 ground types.*:$((n + 8)) \[target_spectrum\]\.ground.*\"E\"" "$R
select = 7
[target_spectrum]
code = \"EC8\"
agr = 0.3
ground = \"F\""
expect_error missing_csv "nowhere\.csv.*\[target_spectrum\]\.file" "$R
select = 7
[target_spectrum]
code = \"csv\"
file = \"nowhere.csv\""
expect_error sds_range "SDS = 9 is out of range.*\[target_spectrum\]\.sds.*\(0, 5\] g" "$R
select = 11
[target_spectrum]
code = \"ASCE 7-16\"
sds = 9
sd1 = 0.6"
expect_error sd1_missing "needs sd1.*\[target_spectrum\]\.sd1" "$R
select = 11
[target_spectrum]
code = \"ASCE 7-16\"
sds = 1.0"
expect_error other_code_key "unknown key 'agr' in \[target_spectrum\].*takes: code, sds, sd1" "$R
select = 11
$T
agr = 0.3"
expect_error iran_a "A = 0.4 is not a zone value.*\[target_spectrum\]\.a" "$R
select = 11
[target_spectrum]
code = \"Standard 2800\"
a = 0.4
soil = \"II\""
expect_error bad_rule "unknown scaling rule 'ASCE 7-05'.*\[target_spectrum\]\.rule" "$R
select = 11
$T
rule = \"ASCE 7-05\""
expect_error empty_range "period range .* is empty.*\[target_spectrum\]\.t_max" "$R
select = 11
$T
t_min = 2.0
t_max = 1.0"
expect_error too_few_eligible "only [0-9]+ of 25 candidate records.*\[records\]\.select and .*\[target_spectrum\] min_scale, max_scale.*relax \[target_spectrum\] max_scale" "$R
select = 20
$T
max_scale = 1.5"
expect_error scale_limits_crossed "min_scale = 5 is above max_scale = 4.*\[target_spectrum\]\.min_scale.*min_scale = 0.25 and max_scale = 4" "$R
select = 11
$T
min_scale = 5"
# issue 23 item 7: the recording rules, only with select; issue 24 item 5: the command line's ranges are these
expect_error rules_without_select "max_per_event and components are rules of a selection.*\[records\]\.max_per_event.*add select = N" "$R
max_per_event = 1"
expect_error bad_components "unknown components rule 'all'.*\[records\]\.components.*\"one\" or \"both\"" "$R
select = 11
components = \"all\"
$T"
expect_error negative_max_per_event "max_per_event = -1 is out of range.*\[records\]\.max_per_event" "$R
select = 11
max_per_event = -1
$T"
expect_error t_max_above_20 "t_max = 25 is out of range.*\[target_spectrum\]\.t_max.*\[0.01, 20\]" "$R
select = 11
$T
t_max = 25"
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
