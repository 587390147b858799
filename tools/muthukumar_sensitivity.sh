#!/usr/bin/env bash
# The Muthukumar-DesRoches (2006) comparison over the two parameters the stored paper text does not give
# (docs/validation.md, "Sensitivity"): flexible period T2 in {0.5, 1, 2} s x Kelvin/linear stiffness
# {0.5, 1, 2} x 25,000 kip/in, on every banded record ("all") and on the records of the paper's Table I that
# ../shared/records/real holds ("matched"). One `pounding accuracy validate-muthukumar` run per configuration,
# one process at a time (~2 min each for "all" on one core, ~20 s for "matched").
#
#   tools/muthukumar_sensitivity.sh [pounding binary] [output CSV] [work dir]
#       defaults: build/pounding docs/muthukumar_sensitivity.csv build/muthukumar-sensitivity
#   SETS="all matched" T2S="0.5 1 2" SCALES="0.5 1 2"   (environment) restrict the grid
#   REUSE=1   keep per-configuration CSVs already in the work dir (resume an interrupted sweep)
#
# Output: records_set,T2,kelvin_scale followed by the columns of docs/muthukumar.csv.
# Verdicts per finding: tools/muthukumar_verdicts.py docs/muthukumar_sensitivity.csv
set -euo pipefail
bin=${1:-build/pounding}
out=${2:-docs/muthukumar_sensitivity.csv}
work=${3:-build/muthukumar-sensitivity}
sets=${SETS:-all matched}
t2s=${T2S:-0.5 1 2}
scales=${SCALES:-0.5 1 2}
[ -x "$bin" ] || { echo "muthukumar_sensitivity.sh: no pounding binary at $bin (build it, or give its path as argument 1)" >&2; exit 2; }
mkdir -p "$work"
for set in $sets; do
  for t2 in $t2s; do
    for s in $scales; do
      f="$work/${set}_T2-${t2}_k-${s}.csv"
      if [ "${REUSE:-0}" = 1 ] && [ -s "$f" ]; then continue; fi
      sel=()
      [ "$set" = all ] || sel=(--records "$set")
      start=$(date +%s)
      "$bin" accuracy validate-muthukumar --T2 "$t2" --kelvin-scale "$s" "${sel[@]}" --out "$f" > "$f.log"
      echo "$set T2=$t2 kelvin_scale=$s: $(( $(date +%s) - start )) s" >&2
    done
  done
done
tmp="$out.tmp.$$"
first=1
for set in $sets; do
  for t2 in $t2s; do
    for s in $scales; do
      f="$work/${set}_T2-${t2}_k-${s}.csv"
      if [ $first = 1 ]; then echo "records_set,T2,kelvin_scale,$(head -1 "$f")" > "$tmp"; first=0; fi
      tail -n +2 "$f" | sed "s/^/$set,$t2,$s,/" >> "$tmp"
    done
  done
done
mv "$tmp" "$out"
echo "wrote $out" >&2
