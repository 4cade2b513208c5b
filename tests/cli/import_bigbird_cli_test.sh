#!/usr/bin/env bash
# BigBIRD in, as a user brings it: a small fixture in its layout (HDF5 depth images, calibration.h5,
# poses/, PBM masks; written by tests/support/write_bigbird_fixture from the real Kinect cuts in
# tests/data/real/mosd) imported, verified and evaluated by category; --categories; and a folder of
# bad files, each reported in one line while the rest is imported.
set -u
source "$(dirname "$0")/lib.sh"
writer=${2:?usage: import_bigbird_cli_test.sh WORK WRITE_BIGBIRD_FIXTURE}
here=$(cd "$(dirname "$0")" && pwd)
"$writer" "$here/../data/real/mosd" "$work/src" > "$work/fixtures.txt"
check "fixtures written" test $? -eq 0
fast="--features kpd2,d2 --classifier xgboost --rounds 10 -q"

# 2 objects × cameras NP1, NP3 × angles 0, 3, 6; colour .jpg files skipped.
"$KT" import bigbird "$work/src/bigbird" --out "$work/bb" -q > "$work/bb.out"
check "the fixture imports cleanly" test $? -eq 0
check "12 views" grep -q "bigbird → $work/bb: 12 views imported, 0 problems" "$work/bb.out"
"$KT" verify "$work/bb" > "$work/bb.verify"
check "the import verifies" grep -q "12 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/bb.verify"
side="$work/bb/cylinder_1/cylinder_1/eNP3/a6.0.json"
check "class and instance are the object, the camera the elevation label, ANGLE the angle" test -s "${side%.json}.pcd"
check "the pose is recorded" jq -e '.camera_from_turntable | length == 4 and (.[3] == [0, 0, 0, 1])' "$side" > /dev/null
check "its origin is named" grep -q '"pose_source": "BigBIRD poses/NP5_6_pose.h5 (the turntable.s calibration board seen by NP5) and calibration.h5 H_NP3_ir_from_NP5; mask masks/NP3_6_mask.pbm"' "$side"
check "the elevation comes from the pose (NP3 above NP1)" \
  jq -e --slurpfile low "$work/bb/cylinder_1/cylinder_1/eNP1/a6.0.json" '.elevation.degrees > $low[0].elevation.degrees + 20' "$side" > /dev/null
check "the sidecar names the source" grep -q '"source": ".*bigbird/cylinder_1/NP3_6.h5"' "$side"
"$KT" evaluate "$work/bb" $fast --protocol kfold3 --label category --out "$work/bb_r"
check "evaluate runs on the import" test $? -eq 0
check "every row is judged by category" test "$(awk -F, 'NR > 1 && $3 != "category"' "$work/bb_r/report.csv" | wc -l)" -eq 0
acc=$(awk -F, '$2 == "kfold3" && $4 == "kpd2" {print $8}' "$work/bb_r/report.csv")
check "the masked box and cylinder told apart by KPD2 ($acc)" awk -v a="$acc" 'BEGIN {exit !(a >= 0.8)}'

# --categories: a class,instance list gives each object's class.
"$KT" import bigbird "$work/src/bigbird" --categories "$work/src/categories.csv" --out "$work/bbc" -q > /dev/null
check "--categories imports" test $? -eq 0
check "the class is the listed category" test -s "$work/bbc/box/box_1/eNP1/a0.0.pcd" -a -s "$work/bbc/cylinder/cylinder_1/eNP3/a3.0.pcd"
"$KT" import folders "$work/src/bigbird" --categories "$work/src/categories.csv" --out "$work/nope" -q 2> "$work/cat.err"
check "--categories with another format is refused in one line" test "$(cat "$work/cat.err")" = \
  "keyturn: --categories is for bigbird (folders names each view's class by its folder)"

# Bad files: one line each, the rest imported.
bad="$work/src/bigbird_bad"
"$KT" import bigbird "$bad" --out "$work/bad" -q > "$work/bad.out"
check "an import with problems exits 1" test $? -eq 1
check "the usable views are imported" grep -q "bigbird_bad → $work/bad: 4 views imported, 6 problems" "$work/bad.out"
check "a malformed name" grep -qx "$bad/box_1/NP7_0.h5: malformed name (expected NPi_ANGLE.h5, i 1 to 5, ANGLE 0 to 357, or calibration.h5)" "$work/bad.out"
check "a missing pose" grep -qx "missing $bad/box_1/poses/NP5_6_pose.h5 (the turntable's pose at 6°: the views at that angle not imported)" "$work/bad.out"
check "a missing calibration" grep -qx "missing $bad/uncalibrated/calibration.h5 (6 views of uncalibrated not imported)" "$work/bad.out"
check "a corrupt HDF5 file" grep -qx "$bad/box_1/NP5_0.h5: corrupt HDF5 file (cannot be opened)" "$work/bad.out"
check "an HDF5 file without depth" grep -qx "$bad/box_1/NP2_0.h5: dataset \"depth\" is missing (not a BigBIRD depth image?)" "$work/bad.out"
check "float depth" grep -qx "$bad/box_1/NP4_0.h5: dataset \"depth\" is not 16-bit unsigned (uint16 depth expected)" "$work/bad.out"
"$KT" verify "$work/bad" > /dev/null
check "what was imported verifies" test $? -eq 0
finish
