#!/usr/bin/env bash
# keyturn bench as a user runs it: a folder with one corrupt and one good view (the
# bad one named, the good one timed, exit 1), the ISS comparison's wording against
# the times it compares, and --scaling's JSON and PNG. No timing is asserted.
set -u
source "$(dirname "$0")/lib.sh"
data=$(cd "$(dirname "$0")/../.." && pwd)/data

mkdir -p "$work/views"
"$KT" render builtin:mug --angles 0 --out "$work/views/good.pcd" 2>/dev/null
check "render exits 0" test $? -eq 0
printf 'VERSION 0.7\nFIELDS x y z\nnot a point cloud\n' > "$work/views/bad.pcd"

# Table: the bad view named on stderr in one line, the good one timed on stdout.
"$KT" bench --no-builtin -n 1 --pcl-repetitions 1 "$work/views" > "$work/bench.out" 2> "$work/bench.err"
rc=$?
check "bench with a bad view exits non-zero" test $rc -ne 0
check "the bad view is named on stderr" grep -q "^keyturn bench: $work/views/bad.pcd: " "$work/bench.err"
check "the bad view is one line" test "$(grep -c 'bad.pcd' "$work/bench.err")" -eq 1
check "the good view is timed" grep -q "^$work/views/good.pcd: .*K = [0-9]" "$work/bench.out"
check "the good view's total" grep -qE "^  total +[0-9]" "$work/bench.out"
check "the good view is not reported as a failure" bash -c "! grep -q '^keyturn bench: .*good.pcd' '$work/bench.err'"

# JSON: an "error" entry for the bad view, the good one timed after it was met.
"$KT" bench --no-builtin -n 1 --pcl-repetitions 1 --json "$work/views" > "$work/bench.json" 2> "$work/bench_json.err"
rc=$?
check "bench --json with a bad view exits non-zero" test $rc -ne 0
check "json: two views, one failed" test "$(jq -r '[(.views | length), .failed] | join(",")' "$work/bench.json")" = "2,1"
check "json: the bad view's error" \
  test "$(jq -r --arg f "$work/views/bad.pcd" '.views[] | select(.name == $f) | .error | length > 0' "$work/bench.json")" = true
check "json: the good view timed" \
  test "$(jq -r --arg f "$work/views/good.pcd" '.views[] | select(.name == $f) | (.total_ms > 0 and .keypoints >= 3)' "$work/bench.json")" = true

# The ISS comparison says faster exactly when keyturn's median is the shorter, and by the ratio of the medians.
check "json: ISS wording agrees with the times" test "$(jq -r '
  .iss_ms as $k | .pcl_iss_ms as $p | .iss_vs_pcl as $w |
  if $w == "about as fast" then (($p / $k - 1) | fabs) < 0.05
  else ($w | capture("^(?<n>[0-9.]+)× (?<d>faster|slower)$")) as $m | ($m.n | tonumber) as $n |
    if $m.d == "faster" then $p > $k and (($n - $p / $k) | fabs) <= 0.0501
    else $p < $k and (($n - $k / $p) | fabs) <= 0.0501 end
  end' "$work/bench.json")" = true
check "table: the ISS line uses the same words" grep -qE "keyturn ISS vs PCL ISSKeypoint3D: ([0-9.]+× (faster|slower)|about as fast) \(" "$work/bench.out"

# Nothing usable: a missing file is an error line and exit 1, too.
"$KT" bench --no-builtin -n 1 --pcl-repetitions 1 "$work/nothing.pcd" > /dev/null 2> "$work/missing.err"
check "a missing file exits 1" test $? -eq 1
check "a missing file is named" grep -q "^keyturn bench: $work/nothing.pcd: no such file or folder" "$work/missing.err"

# --scaling on the shipped Kinect frame: one object-subset row and one resampled-frame row.
"$KT" bench --scaling --sizes 1000,30000 -n 1 --pcl-repetitions 1 --json --plot "$work/scaling.png" \
  > "$work/scaling.json" 2> "$work/scaling.err"
rc=$?
failed=$(jq .failed "$work/scaling.json")
check "scaling: exit status follows the failed rows" test "$rc" -eq "$([ "$failed" -eq 0 ] && echo 0 || echo 1)"
check "scaling: the shipped frame" test "$(jq -r '.source' "$work/scaling.json")" = "$data/frames/mosd_learn0.pcd"
check "scaling: 640 x 480 organized" test "$(jq -r '[.width, .height, .organized] | join(",")' "$work/scaling.json")" = "640,480,true"
check "scaling: rows by size and kind" \
  test "$(jq -r '[.rows[] | "\(.size):\(.kind):\(.frame_pixels)"] | join(",")' "$work/scaling.json")" = "1000:object:1000,30000:frame:30000"
check "scaling: the frame row is 200 x 150" test "$(jq -r '.rows[1].input' "$work/scaling.json")" = "frame 200 × 150"
check "scaling: at least one row timed" test "$(jq '[.rows[] | select(has("error") | not)] | length' "$work/scaling.json")" -ge 1
check "scaling: timed rows carry K, keyturn and PCL times" test "$(jq -r '[.rows[] | select(has("error") | not) |
  (.keypoints >= 3 and .total_ms > 0 and .total_cpu_ms > 0 and .iss_ms > 0 and .pcl_iss_ms > 0 and .pcl_esf_ms > 0
   and (.pcl_iss_keypoints | type) == "number" and .points <= .input_points)] | all' "$work/scaling.json")" = true
check "scaling: failed rows say why" test "$(jq -r '[.rows[] | select(has("error")) | .error | length > 0] | all' "$work/scaling.json")" = true
check "scaling: PNG written" test "$(head -c 8 "$work/scaling.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a"

# A size larger than the input is left out with a line, not timed.
"$KT" bench --scaling "$data/frames/mosd_learn0.pcd" --sizes 400000 -n 1 --pcl-repetitions 1 > /dev/null 2> "$work/big.err"
check "scaling: nothing fits exits 1" test $? -eq 1
check "scaling: the left-out size is named" grep -q "no 400000-point input" "$work/big.err"

# Start-up: the heavy libraries stay out of a process that does not use them (the plugins of
# core/plugin.h), and `bench --startup` times the two commands as whole processes.
LD_DEBUG=files "$KT" --help > /dev/null 2> "$work/help.ld"
check "--help opens no plugin" bash -c "! grep -q 'libkeyturn_' '$work/help.ld'"
for heavy in libtorch libQt5 libopencv_imgcodecs libpcl_io libpcl_features libvtk; do
  check "--help does not load $heavy" bash -c "! grep -q 'file=[^ ]*$heavy' '$work/help.ld'"
done
LD_DEBUG=files "$KT" describe "$work/views/good.pcd" > /dev/null 2> "$work/describe.ld"
check "describe of a PCD loads the pcl_io plugin" grep -q 'file=[^ ]*libkeyturn_pcl_io.so' "$work/describe.ld"
for heavy in libtorch libQt5 libopencv_imgcodecs libpcl_features libkeyturn_png libkeyturn_mlp; do
  check "describe of a PCD does not load $heavy" bash -c "! grep -q 'file=[^ ]*$heavy' '$work/describe.ld'"
done
"$KT" bench --startup -n 2 --json > "$work/startup.json" 2> "$work/startup.err"
check "bench --startup exits 0" test $? -eq 0
check "startup: two commands, two runs each, all exit 0" test "$(jq -r '[.timings[] | "\(.runs):\(.exit_codes | map(tostring) | join("+"))"] | join(",")' "$work/startup.json")" = "2:0+0,2:0+0"
check "startup: --help and a describe" test "$(jq -r '[.timings[].command | split(" ")[1]] | join(",")' "$work/startup.json")" = "--help,describe"
check "startup: times and memory measured" test "$(jq -r '[.timings[] | (.wall_s.min > 0 and .wall_s.min <= .wall_s.median and .wall_s.median <= .wall_s.max and .peak_mib.median > 1)] | all' "$work/startup.json")" = true
"$KT" bench --startup -n 1 "$work/views/bad.pcd" > /dev/null 2> "$work/startup_bad.err"
check "startup: a describe that fails exits 1" test $? -eq 1
check "startup: and says which" grep -q "keyturn describe VIEW' exited with 1" "$work/startup_bad.err"

finish
