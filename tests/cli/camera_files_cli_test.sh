#!/usr/bin/env bash
# Camera files users have (docs/camera.md), on the command line: a real Kinect depth PNG (cut from
# tests/data/real/mosd) described with keyturn's flat file, a ROS camera_info YAML, a CameraInfo
# message, Open3D's PinholeCameraIntrinsic JSON and an OpenCV calibration YAML gives the same row;
# distortion applied changes it, an unsupported model and a malformed file are one line naming the
# file; a depth scale in units per metre (1000, 10000) says which scale fits (describe and classify),
# a right one says nothing.
set -u
source "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)
python3 "$here/write_depth_views.py" "$here/../data/real/mosd" "$work/src" > /dev/null
check "fixtures written" test $? -eq 0
png="$work/src/pair/view_depth.png"

# The same intrinsics in each format, the numbers written as Python's repr (exact round trip).
python3 - "$work/src/camera.json" "$work" <<'PY'
import json, pathlib, sys
c = json.loads(pathlib.Path(sys.argv[1]).read_text())
fx, fy, cx, cy = (repr(float(c[k])) for k in ("fx", "fy", "cx", "cy"))
w = pathlib.Path(sys.argv[2])
(w / "flat.yaml").write_text(f"fx: {fx}\nfy: {fy}\ncx: {cx}\ncy: {cy}\n")
(w / "ros.yaml").write_text(f"""image_width: 640
image_height: 480
camera_name: kinect_depth
camera_matrix:
  rows: 3
  cols: 3
  data: [{fx}, 0, {cx}, 0, {fy}, {cy}, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0, 0, 0, 0, 0]
""")
(w / "camera_info.yaml").write_text(f"""header:
  frame_id: camera_depth_optical_frame
height: 480
width: 640
distortion_model: plumb_bob
D: [0.0, 0.0, 0.0, 0.0, 0.0]
K: [{fx}, 0.0, {cx}, 0.0, {fy}, {cy}, 0.0, 0.0, 1.0]
---
""")
(w / "open3d.json").write_text(json.dumps({"width": 640, "height": 480,
                                           "intrinsic_matrix": [float(fx), 0, 0, 0, float(fy), 0, float(cx), float(cy), 1]}))
def opencv(d):
    return f"""%YAML:1.0
---
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ {fx}, 0., {cx}, 0., {fy}, {cy}, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: {len(d)}
   dt: d
   data: [ {", ".join(d)} ]
"""
(w / "opencv.yaml").write_text(opencv(["0."] * 5))
(w / "opencv_distorted.yaml").write_text(opencv(["-0.2", "0.05", "0.001", "-0.001", "0."]))
(w / "fisheye.yaml").write_text((w / "ros.yaml").read_text().replace("plumb_bob", "equidistant")
                                .replace("cols: 5\n  data: [0, 0, 0, 0, 0]", "cols: 4\n  data: [0.1, 0.01, 0, 0]"))
(w / "short.yaml").write_text((w / "ros.yaml").read_text().replace(", 0, 0, 1]", ", 0, 0]"))
PY
check "camera files written" test $? -eq 0

"$KT" describe "$png" --camera "$work/flat.yaml" -q > "$work/flat.csv" 2> "$work/flat.err"
check "the flat camera file describes the view" test "$(wc -l < "$work/flat.csv")" -eq 2
for f in ros.yaml camera_info.yaml open3d.json opencv.yaml; do
  "$KT" describe "$png" --camera "$work/$f" -q > "$work/$f.csv" 2> "$work/$f.err"
  check "$f: exit 0" test $? -eq 0
  check "$f: the flat file's row, number for number" cmp -s "$work/flat.csv" "$work/$f.csv"
  check "$f: nothing said" test ! -s "$work/$f.err"
done

"$KT" describe "$png" --camera "$work/opencv_distorted.yaml" -q > "$work/distorted.csv" 2> "$work/distorted.err"
check "a distorted camera file is applied (exit 0)" test $? -eq 0
check "  and changes the row" test "$(tail -1 "$work/distorted.csv")" != "$(tail -1 "$work/flat.csv")"

for f in fisheye.yaml short.yaml; do
  "$KT" describe "$png" --camera "$work/$f" -q > /dev/null 2> "$work/$f.err"
  check "$f: exit 1" test $? -eq 1
  check "$f: one line naming the file" test "$(wc -l < "$work/$f.err")" -eq 1 -a "$(grep -c "$work/$f: " "$work/$f.err")" -eq 1
done
check "an unsupported model is named" grep -q "distortion model 'equidistant' with non-zero coefficients" "$work/fisheye.yaml.err"
check "a short camera matrix is said" grep -q "camera_matrix is 3 × 3 but its data holds 8 values" "$work/short.yaml.err"

# Open3D's depth_scale (units per metre) given as keyturn's (metres per unit).
for scale in 1000 10000; do
  "$KT" describe "$png" --camera "$work/open3d.json" --depth-scale $scale -q > /dev/null 2> "$work/scale$scale.err"
  check "--depth-scale $scale: exit 1" test $? -eq 1
  check "--depth-scale $scale: one line" test "$(wc -l < "$work/scale$scale.err")" -eq 1
  check "--depth-scale $scale: names the file and says which scale fits" \
    grep -q "^keyturn describe: $png: depth scale $scale puts the median distance at .* m (0 of [0-9]* points within the filter's range); --depth-scale 0.001.* would put it at [0-9.]* m: keyturn counts metres per unit" "$work/scale$scale.err"
done
check "1000 is the reciprocal: Open3D's convention is named" \
  grep -q "\-\-depth-scale 0.001 (1/1000) would put it at 0.6 m: keyturn counts metres per unit, Open3D units per metre" "$work/scale1000.err"
# classify words it as core does (no flag), and answers no "no object" for it: the scale is the user's to fix.
"$KT" classify "$here/../../data/models/sim-objects" "$png" --camera "$work/open3d.json" --depth-scale 1000 -q \
  > "$work/classify.out" 2> "$work/classify.err"
check "classify with a wrong scale: exit 1" test $? -eq 1
check "  one line naming the view and the scale that fits" \
  grep -q "^keyturn classify: $png: depth scale 1000 (metres per unit) puts the median distance at .* m, 0 of [0-9]* points within the 0.1–3 m the filter keeps; 0.001 (1/1000) would put it at 0.6 m$" "$work/classify.err"
check "  not answered 'no object'" test "$(grep -c 'no object' "$work/classify.out")" -eq 0
"$KT" describe "$png" --camera "$work/open3d.json" --depth-scale 0.001 -q > "$work/right.csv" 2> "$work/right.err"
check "a right scale: described, no hint" test $? -eq 0 -a ! -s "$work/right.err"
check "  the default scale's row" cmp -s "$work/right.csv" "$work/flat.csv"
finish
