#!/usr/bin/env bash
# keyturn repeatability as a user runs it: on a simulated (exactly calibrated)
# dataset, on the same views with their poses in every pose format, and on
# inverted poses that the overlap check must catch.
set -u
source "$(dirname "$0")/lib.sh"
here=$(dirname "$0")

"$KT" capture --class mug --instance sim --step 15 --range 60 --settle 0.005 -q --out "$work/ds" 2> /dev/null
"$KT" repeatability "$work/ds" --eps 0.5:3:0.5 --out "$work/rep" --json > "$work/rep.json" 2> /dev/null
check "repeatability exits 0" test $? -eq 0
for f in repeatability.csv pairs.csv summary.md summary.json absolute_vs_eps.png relative_vs_eps.png relative_vs_rotation.png; do
  check "report has $f" test -s "$work/rep/$f"
done
check "plots are PNG" test "$(head -c 4 "$work/rep/relative_vs_eps.png" | tail -c 3)" = "PNG"
# 4 detectors × 2 budgets (native, equal) × 3 consecutive pairs × 6 values of ε, plus the header.
check "one CSV row per detector, budget, pair and ε" test "$(wc -l < "$work/rep/repeatability.csv")" -eq 145
check "pairs.csv lists each pair with its rotation and overlap" \
  awk -F, 'NR > 1 {n++; if ($4 != 15 || $5 < 0.5 || $5 > 1) bad++} END {exit !(n == 3 && bad == 0)}' "$work/rep/pairs.csv"
check "JSON names every detector" test "$(grep -cE '"(iss|harris3d|sift3d|uniform)": \{' "$work/rep.json")" -eq 4
bad=$(tail -n +2 "$work/rep/repeatability.csv" | awk -F, '$14 < 0 || $14 > 1 || $13 > $12 || $12 > $10' | wc -l)
check "0 ≤ relative ≤ 1 and absolute ≤ visible ≤ model keypoints" test "$bad" -eq 0
# Equal budget: every detector has exactly ISS's count in each view.
uneq=$(tail -n +2 "$work/rep/repeatability.csv" | awk -F, '$2 == "equal" {k[$4","$8] = k[$4","$8] " " $10}
  $1 == "iss" && $2 == "native" {iss[$4","$8] = $10}
  END {for (p in k) {n = split(k[p], v, " "); for (i = 1; i <= n; i++) if (v[i] != iss[p]) bad++}; print bad + 0}')
check "equal budget gives each detector ISS's K" test "$uneq" -eq 0
"$KT" repeatability "$work/ds" --eps 1 --keypoints 25 --out "$work/rep25" 2> /dev/null > /dev/null
check "--keypoints K gives each detector exactly K" \
  awk -F, 'NR > 1 && $2 == "equal" {n++; if ($10 != 25 || $11 != 25) bad++} END {exit !(n == 12 && bad == 0)}' "$work/rep25/repeatability.csv"
rel_low=$(awk -F, '$1=="iss" && $2=="native" && $8==0.5 {s+=$14; n++} END {print s/n}' "$work/rep/repeatability.csv")
rel_high=$(awk -F, '$1=="iss" && $2=="native" && $8==3 {s+=$14; n++} END {print s/n}' "$work/rep/repeatability.csv")
check "relative repeatability grows with ε" awk -v a="$rel_low" -v b="$rel_high" 'BEGIN {exit !(b > a)}'

# The same views with their poses in each format: the same scores as the dataset's sidecars.
python3 "$here/write_pose_files.py" "$work/ds" "$work/poses"
scores() { python3 -c 'import json, sys; print(json.dumps({d: {k: v for k, v in s.items() if k != "detection_ms"}
  for d, s in json.load(open(sys.argv[1]))["detectors"].items()}, sort_keys=True))' "$1"; }
want=$(scores "$work/rep.json")
for f in poses.txt scans.conf matrices.txt "trajectory.txt --views $work/poses/depth.txt"; do
  # shellcheck disable=SC2086
  "$KT" repeatability "$work/poses/"$f --eps 0.5:3:0.5 --out "$work/rep_fmt" --json > "$work/fmt.json" 2> /dev/null
  check "poses as ${f%% *} give the dataset's scores" test "$(scores "$work/fmt.json")" = "$want"
done

# Views of an object from an orbiting camera: inverted poses give no overlap at all.
python3 "$here/write_orbit_views.py" "$work/orbit"
"$KT" repeatability "$work/orbit/poses.txt" --no-filter --detectors iss --out "$work/orbit_ok" > /dev/null 2>&1
check "right poses pass the overlap check" test $? -eq 0
"$KT" repeatability "$work/orbit/inverted.txt" --no-filter --detectors iss --out "$work/orbit_inv" > /dev/null 2> "$work/inv.err"
check "inverted poses exit non-zero" test $? -ne 0
check "inverted poses: one line naming the inverse's overlap" \
  test "$(grep -v '\[' "$work/inv.err")" = "keyturn: poses give no overlap between views (3 of 3 pairs under 5 %) — inverted? the inverse gives 100 % (--invert-poses); --force scores anyway"
"$KT" repeatability "$work/orbit/inverted.txt" --no-filter --detectors iss --force --out "$work/orbit_force" > /dev/null 2>&1
check "--force scores inverted poses anyway" test -s "$work/orbit_force/summary.json"
"$KT" repeatability "$work/orbit/inverted.txt" --invert-poses --no-filter --detectors iss --out "$work/orbit_fixed" > /dev/null 2>&1
check "--invert-poses repairs them" test $? -eq 0

view=$(ls "$work"/ds/mug/sim/e30/a0.0.pcd)
printf '# same view twice\n%s 0 0 0 0 0 0 1\nagain %s 0 0 0 0 0 0 1\n' "$view" "$view" > "$work/same.txt"
"$KT" repeatability "$work/same.txt" --detectors iss --eps 1 --out "$work/rep2" --json > "$work/rep2.json" 2> /dev/null
check "pose list exits 0" test $? -eq 0
check "identical views repeat fully" grep -A1 '"relative"' "$work/rep2.json" | grep -qE '^ +1\.0$'
printf 'a.pcd 0 0 0 0 0 0 1\nb.pcd 0 0 zero 0 0 0 1\n' > "$work/bad.txt"
"$KT" repeatability "$work/bad.txt" --out "$work/rep3" 2> "$work/bad.err"
check "a bad pose list names the line" test "$(cat "$work/bad.err")" = "keyturn: $work/bad.txt: line 2: 'zero' is not a number"
printf 'camera 0 0 0 0 0 0 1\nbmesh a.ply 0 0 0 0 0 1\n' > "$work/bad.conf"
"$KT" repeatability "$work/bad.conf" --out "$work/rep5" 2> "$work/conf.err"
check "a bad .conf names the line" test "$(cat "$work/conf.err")" = "keyturn: $work/bad.conf: line 2: expected bmesh FILE tx ty tz qx qy qz qw, found 8 fields"
"$KT" repeatability "$work/ds" --pairs sideways --out "$work/rep4" 2> "$work/pairs.err"
check "a bad pair rule is named" grep -q "expected consecutive, from-first or all-within:DEG" "$work/pairs.err"
finish
