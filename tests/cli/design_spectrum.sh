#!/usr/bin/env bash
# `pounding spectrum` (issue 23 item 6) prints a code design spectrum at given periods. Against the research
# note's worked numbers (/work/shared/research/fragility-and-codes.md 3.1-3.3, computed there with SciPy):
#   ASCE 7-16 from the maps, site C, Ss 1.5, S1 0.6, TL 8 (Fa 1.2, Fv 1.4: SDS 1.2, SD1 0.56):
#     Sa(0, 0.05, 0.3, 1, 2, 10 s) = 0.48, 0.86571, 1.2, 0.56, 0.28, 0.0448 g; the same from --sds 1.2 --sd1 0.56
#   EC8 ag 0.3 g, ground C, 5 %: type 1 Se(0, 0.1, 0.4, 1, 3) = 0.345, 0.60375, 0.8625, 0.5175, 0.115 g;
#     type 2 Se(0, 0.05, 0.2, 1, 3) = 0.45, 0.7875, 1.125, 0.28125, 0.0375 g
#   Standard 2800 A 0.35, soil III: B(0, 0.1, 0.5, 1, 2, 4.5) = 1.1, 2.2, 2.75, 2.0475, 1.22792, 0.72722 (Sa = A B)
#   csv: linear between the points; Sd = Sa g T^2/4pi^2 (g = 9.80665)
# --range with --count (even and log spacing); the table form; and the errors: site class F, the 11.4.8 cases,
# an option of another code, both design and mapped values, no periods, a period outside a csv table -- each
# one " ERROR:" line naming the option, exit 2, nothing on stdout. A study's [target_spectrum] with ss, s1 and
# site_class gives the same spectrum as with sds and sd1 (the run log's target line).
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

check() {  # <name> <expected Sa, comma-separated> <spectrum args...>: the CSV's sa_g column against the values
  local name=$1 want=$2; shift 2
  "$bin" spectrum "$@" --csv > "$tmp/$name.csv" 2> "$tmp/$name.err" || fail "$name: $(cat "$tmp/$name.err")"
  awk -F, -v want="$want" -v name="$name" '
    BEGIN { n = split(want, w, ","); pi = atan2(0, -1) }
    /^#/ { next }
    $1 == "period_s" { next }
    { k++; d = $2 - w[k]; if (d < 0) d = -d; if (d > 5e-6) { printf "%s: T %s Sa %s, want %s\n", name, $1, $2, w[k]; bad = 1 }
      sd = $2 * 9.80665 * $1 * $1 / (4 * pi * pi); e = $3 - sd; if (e < 0) e = -e
      if (e > 1e-8 * (1 + sd)) { printf "%s: T %s Sd %s, want %s\n", name, $1, $3, sd; bad = 1 } }
    END { if (k != n) { printf "%s: %d rows, want %d\n", name, k, n; bad = 1 }; exit bad }' "$tmp/$name.csv" ||
    fail "$name differs: $(cat "$tmp/$name.csv")"
}

check asce_maps 0.48,0.86571,1.2,0.56,0.28,0.0448 --code "ASCE 7-16" --ss 1.5 --s1 0.6 --site-class C \
  --periods 0,0.05,0.3,1,2,10
check asce_design 0.48,0.86571,1.2,0.56,0.28,0.0448 --code "ASCE 7-16" --sds 1.2 --sd1 0.56 --tl 8 \
  --periods 0,0.05,0.3,1,2,10
check asce_mcer 0.72,1.2985714,1.8,0.84,0.42,0.0672 --code "ASCE 7-16" --ss 1.5 --s1 0.6 --site-class C --mcer \
  --periods 0,0.05,0.3,1,2,10
grep -q "Fa = 1.2, Fv = 1.4" "$tmp/asce_maps.csv" || fail "the maps' coefficients are not stated: $(head -1 "$tmp/asce_maps.csv")"
check ec8_1 0.345,0.60375,0.8625,0.5175,0.115 --code EC8 --type 1 --ground C --agr 0.3 --periods 0,0.1,0.4,1,3
check ec8_2 0.45,0.7875,1.125,0.28125,0.0375 --code EC8 --type 2 --ground C --agr 0.3 --periods 0,0.05,0.2,1,3
check iran 0.385,0.77,0.9625,0.716625,0.429772,0.254527 --code "Standard 2800" --a 0.35 --soil III \
  --periods 0,0.1,0.5,1,2,4.5
printf 'period_s,sa_g\n0.0,0.4\n0.5,1.0\n2.0,0.4\n' > "$tmp/t.csv"
check csv 0.4,0.7,1.0,0.6,0.4 --code csv --file "$tmp/t.csv" --periods 0,0.25,0.5,1.5,2
check range 0.48,0.56,0.28,0.186667,0.14 --code "ASCE 7-16" --sds 1.2 --sd1 0.56 --range 0,4 --count 5
"$bin" spectrum --code "ASCE 7-16" --sds 1.2 --sd1 0.56 --range 0.1,10 --count 3 --log --csv > "$tmp/log.csv"
[ "$(grep -v '^#' "$tmp/log.csv" | sed -n 2,4p | cut -d, -f1 | tr '\n' ' ')" = "0.1 1 10 " ] ||
  fail "--log: $(cat "$tmp/log.csv")"
"$bin" spectrum --code EC8 --type 1 --ground C --agr 0.3 --periods 0.4,1 > "$tmp/table.txt"
grep -q "^EN 1998-1" "$tmp/table.txt" && grep -q "0.86250" "$tmp/table.txt" || fail "table: $(cat "$tmp/table.txt")"

refuse() {  # <name> <pattern the error must hold> <spectrum args...>
  local name=$1 pattern=$2; shift 2
  if "$bin" spectrum "$@" > "$tmp/$name.out" 2> "$tmp/$name.err"; then fail "$name: accepted"; fi
  local rc=0; "$bin" spectrum "$@" > /dev/null 2>&1 || rc=$?
  [ "$rc" = 2 ] || fail "$name: exit $rc, not 2"
  [ "$(grep -c ' ERROR: ' "$tmp/$name.err")" = 1 ] && grep -q -- "$pattern" "$tmp/$name.err" ||
    fail "$name: the error does not say '$pattern': $(cat "$tmp/$name.err")"
  [ ! -s "$tmp/$name.out" ] || fail "$name: wrote output: $(cat "$tmp/$name.out")"
}
refuse site_f "site response analysis.*--site-class" --code "ASCE 7-16" --ss 1 --s1 0.3 --site-class F --periods 1
refuse site_d_s1 "11.4.8.*--s1" --code "ASCE 7-16" --ss 1 --s1 0.3 --site-class D --periods 1
refuse site_e_ss "exception 1.*--ss" --code "ASCE 7-16" --ss 1.2 --s1 0.1 --site-class E --periods 1
refuse site_class "not an ASCE 7-16 site class" --code "ASCE 7-16" --ss 1 --s1 0.1 --site-class G --periods 1
refuse foreign "--agr is not a parameter of --code" --code "ASCE 7-16" --sds 1 --sd1 0.5 --agr 0.3 --periods 1
refuse both "both --sds/--sd1 and --ss" --code "ASCE 7-16" --sds 1 --sd1 0.5 --ss 1 --periods 1
refuse missing "needs --sd1" --code "ASCE 7-16" --sds 1 --periods 1
refuse sds_range "SDS.*--sds" --code "ASCE 7-16" --sds 7 --sd1 0.5 --periods 1
refuse no_periods "no periods" --code EC8 --ground C --agr 0.3
refuse code "unknown design code" --code "NZS 1170" --periods 1
refuse a_zone "zone value.*--a" --code "Standard 2800" --a 0.4 --soil II --periods 1
refuse outside "outside the table.*--periods" --code csv --file "$tmp/t.csv" --periods 3
refuse negative "is not a period" --code EC8 --ground C --agr 0.3 --periods 0.5,-1

# a study's [target_spectrum] from the maps: the same spectrum as from SDS and SD1
"$bin" records suite --synthetic-only --write "$tmp/lib" > /dev/null
for form in maps design; do
  { cat "$src/tests/data/study-select-pair.toml"; printf '[records]\ndirectory = "lib"\nselect = 3\n[target_spectrum]\ncode = "ASCE 7-16"\n'
    if [ $form = maps ]; then printf 'ss = 1.5\ns1 = 0.6\nsite_class = "C"\n'; else printf 'sds = 1.2\nsd1 = 0.56\n'; fi
  } > "$tmp/$form.toml"
  "$bin" run "$tmp/$form.toml" --out "$tmp/$form.h5" > "$tmp/$form.log" 2>&1 || fail "study $form: $(cat "$tmp/$form.log")"
done
grep -q "^target: ASCE 7-16 11.4.6: SDS = 1.2 g, SD1 = 0.56 g, TL = 8 s (from Ss = 1.5 g, S1 = 0.6 g, site class C" \
  "$tmp/maps.log" || fail "the study's target from the maps: $(grep target: "$tmp/maps.log")"
diff <(sed -n '/^rule: /,/^condition/p' "$tmp/maps.log") <(sed -n '/^rule: /,/^condition/p' "$tmp/design.log") ||
  fail "the maps' study selects differently from the SDS/SD1 one"
sed 's/site_class = "C"/site_class = "F"/' "$tmp/maps.toml" > "$tmp/f.toml"
if "$bin" run "$tmp/f.toml" --out "$tmp/f.h5" > /dev/null 2> "$tmp/f.err"; then fail "site class F accepted in a study"; fi
grep -q "f.toml:[0-9]*.*site_class" "$tmp/f.err" || fail "the study's site class F error: $(cat "$tmp/f.err")"
[ ! -e "$tmp/f.h5" ] || fail "a refused study left a results file"
echo "pounding spectrum: ASCE 7-16 (maps and design values), EC8 types 1 and 2, Standard 2800, csv match the worked numbers; errors refused"
