#!/usr/bin/env bash
# keyturn enroll as a user meets it (issue 50): a small open-set model of four categories (SR4000
# views) takes a fifth object from its mesh, given as a file or as a reconstruction folder holding
# mesh.ply; the new model names the object on views it was not trained on (another elevation and
# noise seed) and still names the old objects; bad input gets one line each.
set -u
source "$(dirname "$0")/lib.sh"
data="$(dirname "$0")/../data"
drill_mesh="$(dirname "$0")/../../data/objects/drill__ycb_035_power_drill.ply"
one_line() { test "$(wc -l < "$1")" -eq 1 && grep -q "$2" "$1"; }

# A rate of 20 % false accepts: with 24 views an object, 5 % leaves a quarter of known views unknown.
"$KT" simulate --objects "$data/objects-four-categories.csv" --elevations 30,60 --step 30 -q --out "$work/ds"
"$KT" train "$work/ds" --features kpd2+kpa3 --open-set knn-relative --false-accept 0.2 --rounds 10 -q --out "$work/model"
check "train keeps one training view per open-set reference" \
  test "$(jq -r '"\(.training_views.label) \(.training_views.views | length) \(.open_set.references | length) \(.training_views.captures | length)"' "$work/model/model.json")" = "instance 96 96 8"

mkdir -p "$work/reconstruction"
cp "$drill_mesh" "$work/reconstruction/mesh.ply"
"$KT" enroll "$work/reconstruction" --class drill --instance ycb_035_power_drill --model "$work/model" \
  --cameras sr4000 --elevations 30,60 --step 30 --out "$work/model2" 2> "$work/enroll.err"
check "enroll from a reconstruction folder exits 0" test $? -eq 0
check "  says each stage" grep -q "rendering 24 views of ycb_035_power_drill" "$work/enroll.err"
check "  and what it made" grep -q "ycb_035_power_drill added: 5 classes, 24 new views; threshold .* → " "$work/enroll.err"
check "  the rendered views are gone" test ! -e "$work/model2.views"
check "the new model has the object as a fifth class, trained on 120 views" \
  test "$(jq -r '"\(.classes | length) \(.classes | index("ycb_035_power_drill") != null) \(.training_views.views | length) \(.open_set.references | length)"' "$work/model2/model.json")" = "5 true 120 120"
check "  with the old model's classifier parameters and open-set rate" \
  test "$(jq -r '"\(.xgboost.rounds) \(.open_set.method) \(.open_set.false_accept)"' "$work/model2/model.json")" = "10 knn-relative 0.2"

# New views: another elevation (45°) and noise seed than either model was trained on.
"$KT" simulate --objects "$data/objects-unknown-drill.csv" --elevations 45 --step 45 --seed 3 -q --out "$work/drill45"
"$KT" simulate --objects "$data/objects-four-categories.csv" --elevations 45 --step 45 --seed 3 -q --out "$work/old45"
"$KT" classify "$work/model" "$work/drill45" --json -q > "$work/before.json"
"$KT" classify "$work/model2" "$work/drill45" --json -q > "$work/after.json"
named() { jq "[.[] | select(.class == \"$2\")] | length" "$1"; }
best() { jq "[.[] | select(.best == \"$2\")] | length" "$1"; }
# The classifier's choice (best) and the open-set answer (class): a model of 4 then 5 categories
# calibrates its threshold on 4 or 5 left-out categories, which moves it by a few hundredths.
check "before: the drill is unknown on most of its 8 views" test "$(jq '[.[] | select(.answer == "unknown")] | length' "$work/before.json")" -ge 6
check "after: the drill is the classifier's choice on at least 7 of its 8 new views" test "$(best "$work/after.json" ycb_035_power_drill)" -ge 7
check "  and named on at least 5" test "$(named "$work/after.json" ycb_035_power_drill)" -ge 5
"$KT" classify "$work/model" "$work/old45" --json -q > "$work/old_before.json"
"$KT" classify "$work/model2" "$work/old45" --json -q > "$work/old_after.json"
right() { jq "[.[] | select(.$2 == (.view | split(\"/\") | .[-3]))] | length" "$1"; }
check "the old objects are the classifier's choice on as many of their 32 new views, less one at most" \
  test "$(right "$work/old_after.json" best)" -ge $(( $(right "$work/old_before.json" best) - 1 ))
check "  and named on at least 20" test "$(right "$work/old_after.json" class)" -ge 20

# The same object again, from its mesh file: refused before anything is rendered.
"$KT" enroll "$drill_mesh" --class drill --instance ycb_035_power_drill --model "$work/model2" --out "$work/model3" \
  --cameras sr4000 --elevations 30 --step 90 -q 2> "$work/again.err"
check "an object already in the model: exit 1" test $? -eq 1
check "  with one line naming the class" one_line "$work/again.err" "'ycb_035_power_drill' is already a class of the model"
check "  nothing written" test ! -e "$work/model3"

"$KT" enroll "$work/nothing.ply" --class drill --instance d2 --model "$work/model" --out "$work/m" -q 2> "$work/e1.err"
check "no mesh: one line" one_line "$work/e1.err" "nothing.ply: no such mesh file or reconstruction folder"
mkdir -p "$work/empty_reconstruction"
"$KT" enroll "$work/empty_reconstruction" --class drill --instance d2 --model "$work/model" --out "$work/m" -q 2> "$work/e2.err"
check "a folder without mesh.ply: one line" one_line "$work/e2.err" "empty_reconstruction: a folder without mesh.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n' > "$work/broken.ply"
"$KT" enroll "$work/broken.ply" --class drill --instance d2 --model "$work/model" --out "$work/m" -q 2> "$work/e3.err"
check "a broken mesh: one line naming it" one_line "$work/e3.err" "broken.ply"
mkdir -p "$work/old_model"
jq 'del(.training_views)' "$work/model/model.json" > "$work/old_model/model.json"
cp "$work/model/model.xgb.json" "$work/old_model/"
"$KT" enroll "$drill_mesh" --class drill --instance d2 --model "$work/old_model" --out "$work/m" -q 2> "$work/e4.err"
check "a model without training views: one line saying to retrain" one_line "$work/e4.err" "keeps no training views .*retrain it with keyturn train"
"$KT" train "$work/ds" --features kpd2+kpa3 --rounds 10 -q --out "$work/closed"
"$KT" enroll "$drill_mesh" --class drill --instance d2 --model "$work/closed" --out "$work/m" -q 2> "$work/e5.err"
check "a closed-set model: the same line" one_line "$work/e5.err" "keeps no training views"
check "  no model written by any of them" test ! -e "$work/m"
finish
