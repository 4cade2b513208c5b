#!/usr/bin/env bash
# A recording as a camera: keyturn capture --camera playback:DATASET copies a simulated capture
# view for view (the same PCDs and PNGs, angles and calibration), grab takes its first frame,
# and a missing dataset, a view file gone, or capturing into the recording itself is one line.
set -u
source "$(dirname "$0")/lib.sh"
src="$work/src"
"$KT" capture --class mug --instance builtin --step 30 --settle 0.01 -q --out "$src" 2> "$work/src.err"
check "the source capture exits 0" test $? -eq 0

# The same sequence through the playback camera and its pose source, with more frames per view than
# the source took: the view held is the one recorded, so the median is that view.
copy=("$KT" capture --camera playback:"$src" --class mug --instance builtin --step 30 --settle 0.01 --frames 3 -q)
"${copy[@]}" --out "$work/copy" 2> "$work/copy.err"
check "capture from playback exits 0" test $? -eq 0
check "it writes 12 views" grep -q "12 views written" "$work/copy.err"
"$KT" verify "$work/copy" > "$work/verify.txt"
check "the copy verifies" test $? -eq 0
# Per view: class, instance, elevation, angles, and every file but the sidecar, by checksum.
views() { tail -n +2 "$1/manifest.csv" | awk -F, '{n = split($9, s, ";"); printf "%s,%s,%s,%s,%s,%s", $1, $2, $3, $4, $5, $6; for (i = 1; i < n; i++) printf ",%s", s[i]; print ""}'; }
views "$src" > "$work/src.views"
views "$work/copy" > "$work/copy.views"
check "12 views in the source" test "$(wc -l < "$work/src.views")" -eq 12
check "the copy's views equal the source's (angles, PCDs, PNGs)" cmp -s "$work/src.views" "$work/copy.views"
check "each view has its PCD and three PNGs compared" test "$(head -1 "$work/copy.views" | tr ',' '\n' | wc -l)" -eq 10
python3 - "$src" "$work/copy" <<'PY' > "$work/sidecars.txt"
import json, sys, glob, os
src, copy = sys.argv[1:]
bad = 0
for a in sorted(glob.glob(src + "/mug/builtin/e30/a*.json")):
    s, c = json.load(open(a)), json.load(open(copy + a[len(src):]))
    ms, mc = s["camera_from_turntable"], c["camera_from_turntable"]
    worst = max(abs(ms[r][k] - mc[r][k]) for r in range(4) for k in range(4))
    if worst > 1e-9 or s["measured_deg"] != c["measured_deg"] or s["camera"] != c["camera"]: bad += 1
    print(os.path.basename(a), worst)
print("differ", bad)
PY
check "sidecars: same measured angle, camera and camera-from-turntable" grep -q "^differ 0$" "$work/sidecars.txt"
check "sidecars: 12 compared" test "$(grep -c '^a' "$work/sidecars.txt")" -eq 12
check "the copy's pose source is the playback" grep -q "\"pose_source\": \"playback of $src\"" "$work/copy/mug/builtin/e30/a90.0.json"

"$KT" grab --camera playback:"$src" --out "$work/first.pcd" 2> "$work/grab.err" > /dev/null
check "grab from playback exits 0" test $? -eq 0
check "grab's frame is the first view" cmp -s "$work/first.pcd" "$src/mug/builtin/e30/a0.0.pcd"
check "grab's distance image is the first view's" cmp -s "$work/first_distance.png" "$src/mug/builtin/e30/a0.0_distance.png"
check "grab names the recording" grep -q "recording $src (12 views" "$work/grab.err"

# Errors: one line each, naming the file; a failed capture leaves no dataset.
"$KT" capture --camera playback:"$work/nope" --class mug --instance builtin -q --out "$work/e1" 2> "$work/e1.err"
check "a missing dataset fails" test $? -eq 1
check "a missing dataset is named" test "$(cat "$work/e1.err")" = "keyturn: $work/nope: no such dataset to play back"
check "no dataset is left behind" test ! -e "$work/e1"
"${copy[@]}" --out "$src" 2> "$work/e2.err"
check "capturing into the recording is refused" test "$(cat "$work/e2.err")" = "keyturn: $src: is the recording played back; capture into another folder"
check "the recording is untouched" test "$(tail -n +2 "$src/manifest.csv" | wc -l)" -eq 12
cp -r "$src" "$work/gone"
rm "$work/gone/mug/builtin/e30/a60.0_confidence.png"
"$KT" capture --camera playback:"$work/gone" --class mug --instance builtin --step 30 --settle 0.01 -q \
    --out "$work/e3" 2> "$work/e3.err"
check "a view file gone fails" test $? -eq 1
check "the file gone is named, in one line" test "$(cat "$work/e3.err")" = \
  "keyturn: $work/gone/mug/builtin/e30/a60.0_confidence.png: missing (view mug/builtin/e30/a60.0 of the recording)"
check "the views before it were written" test "$(tail -n +2 "$work/e3/manifest.csv" | wc -l)" -eq 2
"$KT" capture --camera playback:"$src@0" --class mug --instance x --out "$work/e4" 2> "$work/e4.err"
check "a zero rate is refused" grep -q "the playback rate after @ must be a positive number of frames/s" "$work/e4.err"
finish
