#!/usr/bin/env bash
# The keyturn command line as a user runs it: render views, describe a folder
# holding a bad file, bench as JSON. Prints "N passed, N failed".
set -u
source "$(dirname "$0")/lib.sh"

"$KT" render builtin:mug --angles 0,90,180 --out "$work/views/mug_{angle}.pcd" 2>"$work/render.err"
check "render exits 0" test $? -eq 0
check "render writes three views" test "$(ls "$work"/views/*.pcd | wc -l)" -eq 3

# A truncated copy and an empty file among good views.
head -c 2000 "$work/views/mug_090.pcd" > "$work/views/broken.pcd"
: > "$work/views/empty.pcd"
"$KT" describe "$work/views" --out "$work/features.csv" -q 2>"$work/describe.err"
rc=$?
check "describe with bad files exits non-zero" test $rc -ne 0
check "good rows still written" test "$(wc -l < "$work/features.csv")" -eq 4
check "truncated file named in one line" grep -q "broken.pcd: truncated PCD" "$work/describe.err"
check "empty file named" grep -q "empty.pcd: empty file" "$work/describe.err"
header=$(head -1 "$work/features.csv")
check "header has keypoint count, 10 filter columns and 6x32 bins" test "$(echo "$header" | tr ',' '\n' | wc -l)" -eq $((7 + 10 + 6 * 32))
check "header names the filter steps" grep -q "input_kind,input_points,crop_removed,jump_edges_removed,support_plane_removed,cluster_removed,outliers_removed,working_spacing_mm,working_removed,filter_flag" "$work/features.csv"
k=$(sed -n 2p "$work/features.csv" | cut -d, -f3)
check "keypoint count is a positive number" test "${k:-0}" -gt 5

rm "$work/views/broken.pcd" "$work/views/empty.pcd"
"$KT" describe "$work/views/mug_000.pcd" --features kpd2+gkpd2,d2 --bins 16 -q > "$work/one.csv"
check "describe one file to stdout exits 0" test $? -eq 0
check "hybrid + baseline columns" test "$(head -1 "$work/one.csv" | tr ',' '\n' | grep -c '^d2_')" -eq 16

"$KT" describe /nonexistent/view.pcd -q > /dev/null 2>"$work/missing.err"
check "missing path exits non-zero" test $? -ne 0
check "missing path named" grep -q "/nonexistent/view.pcd: no such file" "$work/missing.err"

"$KT" describe "$work/views" --features kpd9 2>"$work/badfeat.err"
check "unknown feature is an error" test $? -ne 0
check "unknown feature named" grep -q "unknown feature 'kpd9'" "$work/badfeat.err"

"$KT" bench -n 2 --pcl-repetitions 1 --json > "$work/bench.json" 2>/dev/null
check "bench --json exits 0" test $? -eq 0
for key in total_ms iss_ms keypoints pcl_iss_ms pcl_esf_ms pcl_vfh_ms; do
  check "bench json has $key" grep -q "\"$key\": [0-9]" "$work/bench.json"
done

# grab from the simulated SR4000 through the real driver.
"$KT" grab --camera sim --frames 3 --out "$work/grab/view.pcd" > "$work/grab.out" 2> "$work/grab.err"
check "grab sim exits 0" test $? -eq 0
for f in view.pcd view_distance.png view_amplitude.png view_confidence.png; do
  check "grab wrote $f" test -s "$work/grab/$f"
done
# PNG IHDR: 176 x 144, bit depth 16, grey.
check "distance PNG is 176x144 16-bit grey" \
  test "$(od -An -tx1 -j16 -N10 "$work/grab/view_distance.png" | tr -d ' \n')" = "000000b0000000901000"
check "grab reports the simulated serial" grep -q "serial 4000123: 3 frames (per-pixel median)" "$work/grab.err"
"$KT" describe "$work/grab/view.pcd" -q > "$work/grab.csv"
check "a grabbed view describes" test $? -eq 0

echo '{"faults": {"open_fail": true}}' > "$work/fail.json"
"$KT" grab --camera sim --sim-config "$work/fail.json" --out "$work/grab/x.pcd" 2> "$work/openfail.err"
check "camera that cannot open exits non-zero" test $? -ne 0
check "open failure is one clear line" test "$(wc -l < "$work/openfail.err")" -eq 1
check "open failure names the camera" grep -q "simulated SR4000" "$work/openfail.err"
check "no partial files after a failed grab" test ! -e "$work/grab/x.pcd"

# The simulator's configuration three ways: in the camera's spec, by --sim-config, by $MESASR_SIM_CONFIG
# (the flag's default); the same camera and the same frame each time.
echo '{"serial": 4000777, "elevation": 45}' > "$work/c777.json"
"$KT" grab --camera "sim:$work/c777.json" --out "$work/grab/spec.pcd" > /dev/null 2> "$work/spec.err"
check "grab --camera sim:CONFIG opens the configured camera" grep -q "serial 4000777: 1 frame" "$work/spec.err"
"$KT" grab --camera sim --sim-config "$work/c777.json" --out "$work/grab/flag.pcd" > /dev/null 2> "$work/flag.err"
check "  as --sim-config does" grep -q "serial 4000777: 1 frame" "$work/flag.err"
MESASR_SIM_CONFIG="$work/c777.json" "$KT" grab --camera sim --out "$work/grab/env.pcd" > /dev/null 2> "$work/env.err"
check "  and \$MESASR_SIM_CONFIG" grep -q "serial 4000777: 1 frame" "$work/env.err"
check "  the same frame" cmp -s "$work/grab/spec_distance.png" "$work/grab/flag_distance.png"
check "  the same frame (environment)" cmp -s "$work/grab/spec_distance.png" "$work/grab/env_distance.png"

KEYTURN_MESASR_LIB=/nonexistent/libmesasr.so "$KT" grab --camera usb --out "$work/grab/y.pcd" 2> "$work/nolib.err"
check "missing libMesaSR exits non-zero" test $? -ne 0
check "missing libMesaSR is one line" grep -q "^keyturn: libMesaSR not found (tried /nonexistent/libmesasr.so" "$work/nolib.err"

"$KT" grab --camera eth:10.1.2.3 --mesasr-lib libm.so.6 --out "$work/grab/z.pcd" 2> "$work/wronglib.err"
check "a library that is not libMesaSR exits non-zero" test $? -ne 0
check "wrong library named in one line" grep -q "^keyturn: libm.so.6: not a usable libMesaSR (missing SR_OpenUSB" "$work/wronglib.err"
check "wrong library error is one line" test "$(wc -l < "$work/wronglib.err")" -eq 1
"$KT" grab --camera "eth:10.1.2.3,lib=libm.so.6" --out "$work/grab/z.pcd" 2> "$work/speclib.err"
check "the library in the camera's spec is the one loaded" cmp -s "$work/wronglib.err" "$work/speclib.err"

# USB discovery on umockdev-emulated devices (umockdev-run is Debian's and scripts/install-deps.sh
# installs it: CI has it, so there a skip fails).
if command -v umockdev-run > /dev/null; then
  dev=$(dirname "$0")/../drivers/umockdev
  umockdev-run -d "$dev/sr4000.umockdev" -d "$dev/foreign_mouse.umockdev" -- "$KT" devices --json > "$work/devices.json"
  check "devices --json exits 0" test $? -eq 0
  check "devices lists the SR4000" grep -q '"id": "1ad2:0075"' "$work/devices.json"
  check "devices shows its serial" grep -q '"serial": "4000123"' "$work/devices.json"
  check "devices ignores the mouse" test "$(grep -c '"model"' "$work/devices.json")" -eq 1
else
  skip yes "keyturn devices under umockdev: umockdev-run not installed"
fi

# Real Kinect data (mOSD cuts): every input kind described by default, each step explained.
real="$(dirname "$0")/../data/real/mosd"
"$KT" describe "$real/full/learn0.pcd" "$real/masked/learn0_o1.pcd" "$real/crop/learn0_o1.pcd" --explain -j 1 \
    --features kpd2,kpa3 -q --out "$work/real.csv" 2>"$work/real.err"
check "real full, masked and crop views described" test $? -eq 0 -a "$(wc -l < "$work/real.csv")" -eq 4
check "explain names the three input kinds" grep -q "learn0.pcd: frame" "$work/real.err"
check "explain: masked frame" grep -q "learn0_o1.pcd: masked-frame" "$work/real.err"
check "explain: segmented cloud" grep -q "learn0_o1.pcd: segmented-cloud" "$work/real.err"
check "explain: the table is a support, the box's face is not" \
    sh -c "grep -q 'a support, removed' '$work/real.err' && grep -q 'a face of the object), kept' '$work/real.err'"
check "CSV rows carry the input kind" sh -c "cut -d, -f8 '$work/real.csv' | sort | tr '\n' ' ' | grep -q 'frame input_kind masked-frame segmented-cloud'"
# A step that removes most of the view is flagged in one stderr line and in the row.
"$KT" describe "$real/masked/learn0_o1.pcd" --max-range 0.62 --features kpd2 -q --out "$work/flag.csv" 2>"$work/flag.err"
check "a step removing most of the view is flagged on stderr" grep -q "warning: .*learn0_o1.pcd: crop removed" "$work/flag.err"

finish
