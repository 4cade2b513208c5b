#!/usr/bin/env bash
# Other people's data in, as a user brings it: Washington RGB-D's two layouts and labelled folders
# (fixtures cut from the real Kinect frames in tests/data/real/mosd) imported, verified and
# evaluated by category; a depth PNG described like the PCD of its pixels; manifests from a
# spreadsheet (CRLF, byte order mark) read, another header refused in one line.
set -u
source "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)
python3 "$here/write_depth_views.py" "$here/../data/real/mosd" "$work/src" > "$work/fixtures.txt"
check "fixtures written" test $? -eq 0
cam="$work/src/camera.json"
fast="--features kpd2,d2 --classifier xgboost --rounds 10 -q"

# Washington, cropped form: 5 instances × videos 1, 2, 4 × 2 frames, and three files it cannot use.
"$KT" import washington "$work/src/washington_crop" --out "$work/wcrop" -q > "$work/wcrop.out"
check "an import with problems exits 1" test $? -eq 1
check "the usable views are imported" grep -q "washington_crop → $work/wcrop: 30 views imported, 5 problems" "$work/wcrop.out"
check "a video other than 1, 2, 4 is named, one line per file" \
  test "$(grep -c 'box_1_3_1_.*: video 3 (Washington.s videos are 1, 2, 4' "$work/wcrop.out")" -eq 3
check "a malformed name is named" grep -q "box/box_1/notes.txt: malformed name" "$work/wcrop.out"
check "a missing file is named" grep -q "^missing .*box/box_1/box_1_4_9_loc.txt (a cropped view needs" "$work/wcrop.out"
"$KT" verify "$work/wcrop" > "$work/wcrop.verify"
check "the import verifies" grep -q "30 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/wcrop.verify"
check "videos are elevations, frames angles" test -s "$work/wcrop/cylinder/cylinder_3/e45/a180.0.pcd"
check "the sidecar names the source and the angle's origin" \
  grep -q '"pose_source": "none: Washington RGB-D video 2 frame 2' "$work/wcrop/cylinder/cylinder_3/e45/a180.0.json"
check "the sidecar names the source file" grep -q '"source": ".*washington_crop/cylinder/cylinder_3/cylinder_3_2_2_depthcrop.png"' \
  "$work/wcrop/cylinder/cylinder_3/e45/a180.0.json"
"$KT" import washington "$work/src/washington_crop" --out "$work/wcrop" -q > "$work/wcrop2.out"
check "a second import leaves what is there" grep -q ": 0 views imported, 30 already there, 5 problems" "$work/wcrop2.out"
"$KT" evaluate "$work/wcrop" $fast --protocol kfold3,leave-elevation,leave-instance --label category --out "$work/wcrop_r"
check "evaluate runs on the cropped import" test $? -eq 0
check "every row is judged by category" test "$(awk -F, 'NR > 1 && $3 != "category"' "$work/wcrop_r/report.csv" | wc -l)" -eq 0
check "the report says so" grep -q "Labels: category for kfold3, leave-elevation and leave-instance (as asked: category)" \
  "$work/wcrop_r/report.md"
acc=$(awk -F, '$2 == "kfold3" && $4 == "kpd2" {print $8}' "$work/wcrop_r/report.csv")
check "boxes and cylinders told apart by KPD2 ($acc)" awk -v a="$acc" 'BEGIN {exit !(a >= 0.8)}'

# Washington, point clouds (ascii x y z rgb imX imY).
"$KT" import washington "$work/src/washington_pcd" --out "$work/wpcd" -q > "$work/wpcd.out"
check "the PCD layout imports cleanly" test $? -eq 0
check "30 PCD views" grep -q ": 30 views imported, 0 problems" "$work/wpcd.out"
"$KT" verify "$work/wpcd" > /dev/null
check "the PCD import verifies" test $? -eq 0
"$KT" evaluate "$work/wpcd" $fast --protocol kfold3 --label category --out "$work/wpcd_r"
check "evaluate runs on the PCD import" test $? -eq 0 -a "$(awk -F, 'NR == 2 {print $3}' "$work/wpcd_r/report.csv")" = category
"$KT" evaluate "$work/wpcd" $fast --protocol kfold3,leave-instance --label instance --out "$work/wpcd_i"
check "--label instance keeps leave-instance by category" \
  grep -q "Labels: instance for kfold3, category for leave-instance (as asked: instance; leave-instance is always judged by category)" \
  "$work/wpcd_i/report.md"
"$KT" evaluate "$work/wpcd" $fast --protocol kfold3 --label colour --out "$work/wpcd_x" 2> "$work/label.err"
check "an unknown label is refused" grep -q "label colour: expected instance or category" "$work/label.err"

# Labelled folders: depth PNGs (with mask and crop offset), PLY and PCD views.
"$KT" import folders "$work/src/folders" --out "$work/fold_nocam" -q 2> "$work/nocam.err"
check "depth images without intrinsics are refused" test $? -ne 0 -a "$(wc -l < "$work/nocam.err")" -eq 1
check "the refusal names a PNG and the flags" grep -q "_depth.png: depth images need the camera's intrinsics (--camera FILE" "$work/nocam.err"
check "and nothing was written" test ! -e "$work/fold_nocam"
# Clouds with one 8-bit PNG among them (a thumbnail, no depth image), no --camera: the PNG is one
# line, the clouds imported (the whole import stopped at the PNG before).
cp -r "$work/src/folders" "$work/mixed"
find "$work/mixed" -name '*_depth.png' -delete
m=$(cd "$work/mixed" && find . -name '*_mask.png' | sort | head -1)
cp "$work/mixed/$m" "$work/mixed/$(dirname "$m")/thumb.png"
"$KT" import folders "$work/mixed" --out "$work/mixed_ds" -q > "$work/mixed.out" 2> "$work/mixed.err"
check "an 8-bit PNG among clouds: exit 1 for the one problem" test $? -eq 1
check "  the PNG is one line naming it" \
  grep -q "^$work/mixed/$(dirname "${m#./}")/thumb.png: 8-bit image; a depth image is 16-bit" "$work/mixed.out"
check "  and the 15 clouds are imported" grep -q "mixed → $work/mixed_ds: 15 views imported, 1 problem$" "$work/mixed.out"
check "  nothing on stderr" test ! -s "$work/mixed.err"
"$KT" import folders "$work/src/folders" --camera "$cam" --out "$work/fold" -q > "$work/fold.out"
check "the folders import cleanly" grep -q ": 30 views imported, 0 problems" "$work/fold.out"
"$KT" verify "$work/fold" > /dev/null
check "the folders import verifies" test $? -eq 0
check "eLABEL folders are elevations; views spread over a turn" test -s "$work/fold/box/box_2/e60/a180.0.pcd"
"$KT" evaluate "$work/fold" $fast --protocol kfold3 --label category --out "$work/fold_r"
check "evaluate runs on the folders import" test $? -eq 0 -a "$(tail -n +2 "$work/fold_r/report.csv" | wc -l)" -eq 2
mkdir -p "$work/notds" && touch "$work/notds/x"
"$KT" import folders "$work/src/folders" --camera "$cam" --out "$work/notds" -q 2> "$work/notds.err"
check "an OUT that is not a dataset is refused" grep -q "notds: exists and is neither empty nor a keyturn dataset" "$work/notds.err"

# A depth PNG describes to the same PDFs as the PCD of its pixels (computed by the fixture script).
"$KT" describe "$work/src/pair/view_depth.png" --camera "$cam" -q | cut -d, -f2- > "$work/png.csv"
"$KT" describe "$work/src/pair/view.pcd" -q | cut -d, -f2- > "$work/pcd.csv"
check "depth PNG and PCD describe alike" cmp -s "$work/png.csv" "$work/pcd.csv"
check "with keypoints" test "$(awk -F, 'NR == 2 {print $1}' "$work/png.csv")" -gt 4
"$KT" describe "$work/src/pair" --camera "$cam" -q > "$work/folder.csv"
check "a folder gives its PCD and its depth image, not the mask" test "$(tail -n +2 "$work/folder.csv" | wc -l)" -eq 2
"$KT" describe "$work/src/pair/view_depth.png" -q > /dev/null 2> "$work/nok.err"
check "a depth image without intrinsics: one line" test "$(wc -l < "$work/nok.err")" -eq 1
check "naming the file" grep -q "view_depth.png: a depth image needs the camera's intrinsics" "$work/nok.err"
head -c 100 "$work/src/pair/view_depth.png" > "$work/cut.png"
"$KT" describe "$work/cut.png" --fx 525 --fy 525 --cx 319.5 --cy 239.5 -q > /dev/null 2> "$work/cut.err"
check "a cut PNG: one line naming it" test "$(cat "$work/cut.err")" = "keyturn describe: $work/cut.png: truncated PNG (a chunk runs past the end of the file)"
"$KT" describe "$work/src/pair/view_depth.png" --fx 525 --fy 525 -q > /dev/null 2> "$work/two.err"
check "half the pinhole flags are refused" grep -q "give all four" "$work/two.err"

# Manifests from a spreadsheet: CRLF endings and a byte order mark.
cp -r "$work/wpcd" "$work/crlf"
python3 -c "import sys; p = sys.argv[1]; t = open(p, 'rb').read(); open(p, 'wb').write(b'\xef\xbb\xbf' + t.replace(b'\n', b'\r\n'))" \
  "$work/crlf/manifest.csv"
check "the manifest now has CRLF" grep -q $'\r$' "$work/crlf/manifest.csv"
"$KT" verify "$work/crlf" > "$work/crlf.verify"
check "a CRLF + BOM manifest of an evaluated dataset (its feature cache no orphan) verifies" grep -q "30 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/crlf.verify"
"$KT" evaluate "$work/crlf" $fast --protocol kfold3 --label category --out "$work/crlf_r"
check "and evaluates" test $? -eq 0
sed -i '1s/^.*$/class,instance,elev,elevation_deg,commanded_deg,measured_deg,captured_at,files,sha256/' "$work/crlf/manifest.csv"
"$KT" verify "$work/crlf" > "$work/hdr.out" 2> "$work/hdr.err"
check "another header fails verify" test $? -ne 0
check "in one line naming the manifest and the column" test "$(cat "$work/hdr.err")" = \
  "keyturn: $work/crlf/manifest.csv: line 1: column 3 is 'elev', expected 'elevation' (header: class,instance,elevation,elevation_deg,commanded_deg,measured_deg,captured_at,files,sha256)"
check "and lists no orphans" test ! -s "$work/hdr.out"
finish
