#!/usr/bin/env bash
# keyturn repeatability as a user runs it: on a simulated (exactly calibrated)
# dataset, and on a pose list.
set -u
source "$(dirname "$0")/lib.sh"

"$KT" capture --class mug --instance sim --step 15 --range 60 --settle 0.005 -q --out "$work/ds" 2> /dev/null
"$KT" repeatability "$work/ds" --eps 0.5:3:0.5 --out "$work/rep" --json > "$work/rep.json" 2> /dev/null
check "repeatability exits 0" test $? -eq 0
for f in repeatability.csv summary.md summary.json absolute_vs_eps.png relative_vs_eps.png relative_vs_rotation.png; do
  check "report has $f" test -s "$work/rep/$f"
done
check "plots are PNG" test "$(head -c 4 "$work/rep/relative_vs_eps.png" | tail -c 3)" = "PNG"
# 4 detectors × 3 consecutive pairs × 6 values of ε, plus the header.
check "one CSV row per detector, pair and ε" test "$(wc -l < "$work/rep/repeatability.csv")" -eq 73
check "JSON names every detector" test "$(grep -cE '"(iss|harris3d|sift3d|uniform)": \{' "$work/rep.json")" -eq 4
bad=$(tail -n +2 "$work/rep/repeatability.csv" | awk -F, '$12 < 0 || $12 > 1 || $11 > $10 || $10 > $8' | wc -l)
check "0 ≤ relative ≤ 1 and absolute ≤ visible ≤ model keypoints" test "$bad" -eq 0
rel_low=$(awk -F, '$1=="iss" && $6==0.5 {s+=$12; n++} END {print s/n}' "$work/rep/repeatability.csv")
rel_high=$(awk -F, '$1=="iss" && $6==3 {s+=$12; n++} END {print s/n}' "$work/rep/repeatability.csv")
check "relative repeatability grows with ε" awk -v a="$rel_low" -v b="$rel_high" 'BEGIN {exit !(b > a)}'

# A pose list of one view twice, at the same pose: everything repeats.
view=$(ls "$work"/ds/mug/sim/e30/a0.0.pcd)
printf '# same view twice\n%s 0 0 0 0 0 0 1\nagain %s 0 0 0 0 0 0 1\n' "$view" "$view" > "$work/poses.txt"
"$KT" repeatability "$work/poses.txt" --detectors iss --eps 1 --out "$work/rep2" --json > "$work/rep2.json" 2> /dev/null
check "pose list exits 0" test $? -eq 0
check "identical views repeat fully" grep -A1 '"relative"' "$work/rep2.json" | grep -qE '^ +1\.0$'
printf 'a.pcd 0 0 0 0 0 0 1\nb.pcd 0 0 zero 0 0 0 1\n' > "$work/bad.txt"
"$KT" repeatability "$work/bad.txt" --out "$work/rep3" 2> "$work/bad.err"
check "a bad pose list names the line" grep -q "bad.txt: line 2: 'zero' is not a number" "$work/bad.err"
"$KT" repeatability "$work/ds" --pairs sideways --out "$work/rep4" 2> "$work/pairs.err"
check "a bad pair rule is named" grep -q "expected consecutive, from-first or all-within:DEG" "$work/pairs.err"
finish
