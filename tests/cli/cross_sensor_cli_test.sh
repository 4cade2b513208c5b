#!/usr/bin/env bash
# Beyond the training conditions, reduced for CI (docs/results.md): the built-in model names its own
# objects through the camera its training did not see most of — the 15 objects through the simulated
# Kinect-class camera at 40° (an elevation it never trained on), 4 views each, other noise than its
# training's; a model trained on the SR4000 alone named 62.5 % of such views (docs/results.md), so
# this fails on a single-sensor model. Then evaluate --protocol cross-sensor on two cameras' views of
# 4 objects: every cell tested on each camera's views once, its report and plot written, and its
# errors one line each. keyturn finds the simulated OpenNI2 camera with no environment (docs/camera.md).
set -u
source "$(dirname "$0")/lib.sh"
data=$(cd "$(dirname "$0")/../../data" && pwd)
sim() { env -u LD_LIBRARY_PATH "$@"; }

# 1. The built-in model through the OpenNI2 camera at a new elevation.
sim "$KT" simulate --camera openni2 --objects "$data/objects/objects.csv" --elevations 40 --step 90 --seed 3 -q \
  --out "$work/openni2-40" 2> "$work/simulate.err"
check "simulate --camera openni2 exits 0" test $? -eq 0
"$KT" classify "$data/models/sim-objects" "$work/openni2-40" --json -q > "$work/openni2-40.json"
check "classify exits 0" test $? -eq 0
named=$(python3 -c '
import json, sys
views = json.load(open(sys.argv[1]))
assert len(views) == 60, len(views)
print(sum(v["class"] == v["view"].split("/")[-3] for v in views))' "$work/openni2-40.json")
echo "built-in model, OpenNI2 camera at 40°: $named of 60 views named right"
check "the built-in model names >= 51 of 60 OpenNI2 views at 40° (85 %)" test "${named:-0}" -ge 51

# 2. evaluate --protocol cross-sensor on both cameras' views of 4 objects at 30° and 60°.
grep -E '^(class|mug|bowl|drill|teapot),' "$data/objects/objects.csv" |
  sed "s#,\([a-z_]*__[a-z0-9_]*\.ply\),#,$data/objects/\1,#" > "$work/four.csv"
"$KT" simulate --objects "$work/four.csv" --elevations 30,60 --step 90 -q --out "$work/tof" 2>> "$work/simulate.err"
sim "$KT" simulate --camera openni2 --objects "$work/four.csv" --elevations 30,60 --step 90 -q --out "$work/kinect" \
  2>> "$work/simulate.err"
check "both cameras simulated: 32 views each" \
  test "$(($(wc -l < "$work/tof/manifest.csv") + $(wc -l < "$work/kinect/manifest.csv")))" -eq 66
"$KT" evaluate "$work/tof" --protocol cross-sensor --other-camera "$work/kinect" --features kpd2+kpa3 \
  --classifier xgboost --out "$work/report" -q 2> "$work/evaluate.err"
check "evaluate --protocol cross-sensor exits 0" test $? -eq 0
check "its report, table and plot written" \
  test -s "$work/report/report.md" -a -s "$work/report/report.csv" -a -s "$work/report/cross_sensor.png"
check "six cells (trained on tof, kinect, both × tested on each), every one on all 32 of its camera's views" python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
cells = [(c["trained_on"], c["tested_on"], c["views"], len(c["fold_accuracy"])) for c in r["cells"]]
assert r["elevations_left_out"] == ["30", "60"], r["elevations_left_out"]
assert cells == [(t, s, 32, 2) for t in ("tof", "kinect", "both") for s in ("tof", "kinect")], cells' \
  "$work/report/report.json"
# train on both cameras' datasets together (one per camera, the same view ids).
"$KT" train "$work/tof" "$work/kinect" --features kpd2+kpa3 --out "$work/both-model" 2> "$work/train.err"
check "train on two datasets exits 0" test $? -eq 0
check "train says it trained on the 64 views of the 2 datasets" grep -q "^keyturn train: xgboost on kpd2+kpa3, 64 views of 2 datasets, 4 classes" "$work/train.err"
check "the Markdown table has a row per training" test "$(grep -c '^| kpd2+kpa3 | xgboost |' "$work/report/report.md")" -eq 3

"$KT" evaluate "$work/tof" --protocol cross-sensor --out "$work/none" -q 2> "$work/no-other.err"
check "without --other-camera: exit non-zero" test $? -ne 0
check "without --other-camera: one line saying what it needs" \
  grep -qx "keyturn: --protocol cross-sensor needs --other-camera DATASET: the same views through another camera (keyturn simulate --camera openni2 with the same objects, elevations and step)" \
  "$work/no-other.err"
"$KT" evaluate "$work/tof" --protocol cross-sensor,kfold10 --other-camera "$work/kinect" --out "$work/none" -q 2> "$work/mixed.err"
check "cross-sensor with another protocol: one line" \
  grep -qx "keyturn: --protocol cross-sensor is a run of its own: give it alone, not 'cross-sensor,kfold10'" "$work/mixed.err"
sim "$KT" simulate --camera openni2 --objects "$work/four.csv" --elevations 45 --step 90 -q --out "$work/kinect45" \
  2>> "$work/simulate.err"
"$KT" evaluate "$work/tof" --protocol cross-sensor --other-camera "$work/kinect45" --features kpd2+kpa3 \
  --classifier xgboost --out "$work/none" -q 2> "$work/other-views.err"
check "a second camera's dataset of other views: one line naming it and a view" \
  grep -qE "^keyturn: kinect45: view [a-z]+/ycb_[0-9a-z_]+/e45/a[0-9.]+ is not a view of the dataset$" "$work/other-views.err"
"$KT" simulate --camera kinect --objects "$work/four.csv" --out "$work/none" -q 2> "$work/bad-camera.err"
check "simulate --camera with another name: one line naming the choices" \
  grep -qx "keyturn: simulated camera 'kinect': expected sr4000 (time of flight) or openni2 (Kinect-class structured light)" \
  "$work/bad-camera.err"
"$KT" simulate --camera openni2 --jitter-integration 10:20 --objects "$work/four.csv" --out "$work/none" -q 2> "$work/jitter.err"
check "integration-time jitter through the OpenNI2 camera: refused in one line" \
  grep -qx "keyturn: jitter: integration time is the SR4000's; the openni2 camera has none" "$work/jitter.err"
finish
