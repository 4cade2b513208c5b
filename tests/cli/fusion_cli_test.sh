#!/usr/bin/env bash
# Multi-view fusion as a user meets it (issue 34): train keeps pose references, classify --fuse
# over a dataset's object and over loose views with their sidecars (table and --json), a view
# without a pose refused in one line, and evaluate --protocol fusion with its plot and control;
# on a small simulated set of four objects at two elevations, a view every 45°.
set -u
source "$(dirname "$0")/lib.sh"
data="$(dirname "$0")/../data"

"$KT" simulate --objects "$data/objects-four-categories.csv" --elevations 30,60 --step 45 -q --out "$work/ds" 2> "$work/sim.err"
check "simulate exits 0" test $? -eq 0
fast="--rounds 10"

"$KT" train "$work/ds" --features kpd2+kpa3 $fast --out "$work/model" 2> "$work/train.err"
check "train exits 0" test $? -eq 0
check "train says it kept pose references" grep -q "; pose references for fusion → " "$work/train.err"
check "the sidecar holds one reference per view, 72 bins" \
  test "$(jq -r '.pose_references | "\(.references | length) \(.bins)"' "$work/model/model.json")" = "64 72"

# A dataset's object: the views at 0, 90 and 180° of one elevation, in capture order.
"$KT" classify "$work/model" "$work/ds" --fuse --object box/ycb_004_sugar_box/e30 --azimuths 0,90,180 -q --json \
  > "$work/fused.json" 2> "$work/fused.err"
check "classify --fuse --object exits 0" test $? -eq 0
check "three views, their azimuths from the manifest" \
  test "$(jq -c '[.views[].azimuth_deg]' "$work/fused.json")" = "[0,90,180]"
check "pose fusion is the default" test "$(jq -r .method "$work/fused.json")" = pose
check "each belief sums to 1" \
  test "$(jq '[.views[] | ([.beliefs[]] | add) | (. > 0.999999 and . < 1.000001)] | all' "$work/fused.json")" = true
check "the fused answer is the object's instance" test "$(jq -r '.views[-1].class' "$work/fused.json")" = ycb_004_sugar_box
check "the belief is the answer's share" \
  test "$(jq '[.views[] | .belief == .beliefs[.class]] | all' "$work/fused.json")" = true
"$KT" classify "$work/model" "$work/ds" --fuse --object box/ycb_004_sugar_box/e30 --azimuths 0,90,180 -q \
  --fusion-method independent --stop-belief 0.5 > "$work/fused.txt"
check "the table: a header and one line per view" test "$(wc -l < "$work/fused.txt")" -eq 4
check "  names the method" grep -q "^# view	azimuth	this view	p	fused (independent)	belief" "$work/fused.txt"
check "  and where it became certain" grep -q "^box/ycb_004_sugar_box/e30/a0.0	0.0	.*	certain (>= 0.500)" "$work/fused.txt"

# Loose views: the poses from their sidecars; one without a sidecar is named.
views=("$work"/ds/mug/ycb_025_mug/e60/a{0.0,45.0,90.0}.pcd)
"$KT" classify "$work/model" "${views[@]}" --fuse -q --json > "$work/loose.json"
check "loose views: azimuths read from their sidecars" \
  test "$(jq -c '[.views[].azimuth_deg]' "$work/loose.json")" = "[0,45,90]"
cp "${views[0]}" "$work/no_pose.pcd"
"$KT" classify "$work/model" "${views[1]}" "$work/no_pose.pcd" --fuse -q > /dev/null 2> "$work/no_pose.err"
check "a view without a pose fails pose fusion" test $? -ne 0
check "  in one line naming its sidecar" \
  test "$(cat "$work/no_pose.err")" = "keyturn: $work/no_pose.json: no sidecar, so the view has no turntable pose"
"$KT" classify "$work/model" "${views[1]}" "$work/no_pose.pcd" --fuse --fusion-method independent -q --json > "$work/nopose_ind.json"
check "independent fusion needs no pose" test "$(jq -c '[.views[].azimuth_deg]' "$work/nopose_ind.json")" = "[null,null]"
"$KT" classify "$work/model" "$work/ds" --fuse --object box -q 2> "$work/object.err"
check "a malformed --object is named" grep -q "^keyturn: --object: 'box' is not CLASS/INSTANCE or CLASS/INSTANCE/ELEVATION" "$work/object.err"
"$KT" classify "$work/model" "$work/ds" --object box/ycb_004_sugar_box -q 2> "$work/nofuse.err"
check "--object without --fuse is refused" grep -q "give --fuse" "$work/nofuse.err"
# Every turn of a dataset (--turns): 3 views over 90° from every view of each object and elevation,
# each fused alone; a turn's answer is the one --object gives for the same three views.
"$KT" classify "$work/model" "$work/ds" --fuse --turns -q --json > "$work/turns.json"
check "--turns: one turn from every view (4 objects × 2 elevations × 8 views)" \
  test "$(jq '.turns | length' "$work/turns.json")" -eq 64
check "  each of 3 views of one object, 45° apart" \
  test "$(jq '[.turns[] | (.views | length == 3) and (.views | map(split("/a")[0]) | unique | length == 1)] | all' "$work/turns.json")" = true
"$KT" classify "$work/model" "$work/ds" --fuse --object mug/ycb_025_mug/e60 --azimuths 90,135,180 -q --json > "$work/one_turn.json"
turn_class=$(jq -r '.turns[] | select(.object == "mug/ycb_025_mug/e60" and .start_deg == 90) | .class' "$work/turns.json")
check "  the turn from 90° of the mug at 60° answers as --object does for its views" \
  test -n "$turn_class" -a "$turn_class" = "$(jq -r '.views[-1].class' "$work/one_turn.json")"
check "  and the turn from 315° takes 315, 0 and 45°" \
  test "$(jq -c '[.turns[] | select(.object == "mug/ycb_025_mug/e60" and .start_deg == 315) | .views[] | split("/a")[1]]' "$work/turns.json")" = '["315.0","0.0","45.0"]'
"$KT" classify "$work/model" "$work/ds" --turns -q 2> "$work/turns_nofuse.err"
check "--turns without --fuse is refused" grep -q "give --fuse" "$work/turns_nofuse.err"
"$KT" classify "$work/model" "$work/ds" --fuse --turns --object mug/ycb_025_mug -q 2> "$work/turns_object.err"
check "--turns with --object is refused in one line" \
  test "$(cat "$work/turns_object.err")" = "keyturn: --turns takes every object's turns: leave out --object and --azimuths"
mkdir -p "$work/old"  # the shipped model as it was before pose references
jq 'del(.pose_references)' "$(dirname "$0")/../../data/models/sim-objects/model.json" > "$work/old/model.json"
cp "$(dirname "$0")/../../data/models/sim-objects/model.xgb.json" "$work/old/"
"$KT" classify "$work/old" "${views[@]}" --fuse --json > "$work/old.json" 2> "$work/old.err"
check "a model without pose references fuses independently, saying so" \
  test "$(jq -r .method "$work/old.json")" = independent -a -n "$(grep 'holds no pose references' "$work/old.err")"

# evaluate's fusion protocol: leave-elevation only here (no category has two instances).
"$KT" evaluate "$work/ds" --protocol fusion --features kpd2+kpa3 --classifier xgboost $fast --fusion-views 3 \
  --fusion-schedule 90,step45 -q --out "$work/report" --json > "$work/report.json"
check "evaluate --protocol fusion exits 0" test $? -eq 0
check "one protocol: leave-elevation" test "$(jq -c '[.protocols[].protocol]' "$work/report.json")" = '["leave-elevation"]'
check "every view of the test elevation starts a sequence" \
  test "$(jq '.protocols[0].curves[0].views[0].sequences' "$work/report.json")" -eq 64
check "two schedules × two methods × true and shuffled poses" test "$(jq '.protocols[0].curves | length' "$work/report.json")" -eq 8
check "one view fused is the single view (independent)" \
  test "$(jq '.protocols[0] | (.curves[0].views[0].accuracy == .single_view_accuracy)' "$work/report.json")" = true
check "shuffling poses changes nothing for independent fusion" \
  test "$(jq '.protocols[0].curves | (.[0].views == .[1].views)' "$work/report.json")" = true
check "the plot" test -s "$work/report/accuracy_leave-elevation.png"
check "the Markdown table" grep -q "^| over 90° | pose | shuffled |" "$work/report/report.md"
"$KT" evaluate "$work/ds" --protocol fusion,kfold5 --features kpd2 -q --out "$work/r2" 2> "$work/r2.err"
check "fusion mixed with other protocols is refused" grep -q "give it alone" "$work/r2.err"
"$KT" evaluate "$work/ds" --protocol fusion -q --out "$work/r3" 2> "$work/r3.err"
check "fusion over the default list of feature sets is refused" grep -q "measures one feature set" "$work/r3.err"

# evaluate's next-best-view protocol: next best view against 45° steps, sequences of 3 views.
"$KT" evaluate "$work/ds" --protocol nbv --features kpd2+kpa3 --classifier xgboost $fast --fusion-views 3 \
  -q --out "$work/nbv" --json > "$work/nbv.json"
check "evaluate --protocol nbv exits 0" test $? -eq 0
check "next best view beside the 45° steps" \
  test "$(jq -c '[.protocols[0].curves[].policy]' "$work/nbv.json")" = '["next best view","step 45°"]'
check "every view of the test elevation starts a sequence of each" \
  test "$(jq -c '[.protocols[0].curves[].views[2].sequences]' "$work/nbv.json")" = '[64,64]'
check "both start from the same view" \
  test "$(jq '.protocols[0].curves | (.[0].views[0].accuracy == .[1].views[0].accuracy)' "$work/nbv.json")" = true
check "the target is the 45° steps' accuracy after 3 views" \
  test "$(jq '.protocols[0] | (.target_accuracy == .curves[1].views[2].accuracy)' "$work/nbv.json")" = true
check "every sequence's first turn counted" test "$(jq '[.protocols[0].first_turns[]] | add' "$work/nbv.json")" -eq 64
check "the plot" test -s "$work/nbv/nbv_leave-elevation.png"
"$KT" evaluate "$work/ds" --protocol nbv --features kpd2+kpa3 --classifier xgboost --fusion-schedule 90 -q --out "$work/r4" 2> "$work/r4.err"
check "a spread schedule is refused for nbv" \
  test "$(cat "$work/r4.err")" = "keyturn: --fusion-schedule 90: protocol nbv compares fixed steps, stepDEG (step45: 3 views over 90°)"
finish
