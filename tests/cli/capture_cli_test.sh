#!/usr/bin/env bash
# keyturn capture as a user runs it on the simulated rig: killed with SIGKILL
# twice mid-sequence, stopped with Ctrl-C once, resumed each time; at the end
# the dataset verifies and holds every view exactly once. A second writer into a
# dataset being written is refused.
set -u
source "$(dirname "$0")/lib.sh"
ds="$work/ds"
cmd=("$KT" capture --class mug --instance builtin --step 5 --range 180 --settle 0.02 -q --out "$ds")
rows() { [ -f "$ds/manifest.csv" ] && echo $(( $(wc -l < "$ds/manifest.csv") - 1 )) || echo 0; }

for round in 1 2; do
  "${cmd[@]}" 2> "$work/kill$round.err" &
  pid=$!
  target=$((round * 8))
  for _ in $(seq 1500); do [ "$(rows)" -ge "$target" ] && break; sleep 0.02; done
  kill -9 "$pid"; wait "$pid" 2>/dev/null
  check "round $round: killed mid-capture" test "$(rows)" -lt 36
  # Its lock file stays behind, but not its lock (the kernel drops that): the next capture proceeds.
  check "round $round: the killed capture's lock file is left" test -s "$ds/.keyturn-lock"
done
"${cmd[@]}" 2> "$work/int.err" &
pid=$!
for _ in $(seq 1500); do [ "$(rows)" -ge 24 ] && break; sleep 0.02; done
kill -INT "$pid"; wait "$pid"; rc=$?
check "Ctrl-C exits 130" test "$rc" -eq 130
check "Ctrl-C says how to resume" grep -q "run the same command again to resume" "$work/int.err"

"${cmd[@]}" 2> "$work/resume.err"
check "resume exits 0" test $? -eq 0
check "resume skipped what was there" grep -qE "already there" "$work/resume.err"
check "36 views in the manifest" test "$(rows)" -eq 36
check "every angle exactly once" test "$(tail -n +2 "$ds/manifest.csv" | cut -d, -f5 | sort -u | wc -l)" -eq 36
"$KT" verify "$ds" > "$work/verify.txt"
check "verify passes" test $? -eq 0
check "verify counts 36 views" grep -q "36 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/verify.txt"
# The studio's snapshots (Ctrl+S) go into DATASET/snapshots/: the dataset's own files, not orphans.
mkdir -p "$ds/snapshots"
cp "$ds/mug/builtin/e30/a0.0_distance.png" "$ds/snapshots/20260101-120000-000_distance.png"
"$KT" verify "$ds" > "$work/verify-snap.txt"
check "a studio snapshot leaves the dataset verified" grep -q "36 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/verify-snap.txt"

# One writer per dataset: a second capture (or simulate) into a dataset a capture is writing is
# refused at once, in one line naming the dataset and the holder; the first runs to its end.
two="$work/two"
two_cmd=("$KT" capture --class mug --instance builtin --step 5 --range 180 --settle 0.02 -q --out "$two")
"${two_cmd[@]}" 2> "$work/first.err" &
first=$!
for _ in $(seq 1500); do [ "$(ds=$two rows)" -ge 1 ] && break; sleep 0.02; done
"${two_cmd[@]}" 2> "$work/second.err"
check "a second capture into the same dataset exits non-zero" test $? -ne 0
check "it names the dataset and the holder in one line" \
  grep -qx "keyturn: $two: already being written by pid $first (.*keyturn capture .*--out $two) on .* since 20.*; one writer at a time" \
  "$work/second.err"
check "it says nothing else" test "$(wc -l < "$work/second.err")" -eq 1
"$KT" simulate --objects "$(dirname "$0")/../../data/objects/objects.csv" --elevations 30 --step 90 --out "$two" -q \
  2> "$work/second-sim.err"
check "simulate into it is refused the same way" grep -q "^keyturn: $two: already being written by pid $first " "$work/second-sim.err"
wait "$first"
check "the first capture runs to its end" test $? -eq 0
check "the first capture wrote its 36 views" grep -q "36 views written, 0 already there" "$work/first.err"
"$KT" verify "$two" > "$work/verify-two.txt"
check "its dataset verifies, the lock file no orphan" \
  grep -q "36 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/verify-two.txt"

# Measured angles match the commanded ones (the table settled before each view).
bad=$(tail -n +2 "$ds/manifest.csv" | awk -F, '{d=$5-$6; if (d<0) d=-d; if (d>0.11 && d<359.89) print}' | wc -l)
check "measured within tolerance of commanded" test "$bad" -eq 0

# What a SIGKILL in the middle of a view's writes leaves (its files renamed into place but no row,
# a temporary half written), made deterministically: the resume removes the leftover, says so,
# retakes the view, and the dataset verifies (it failed under load with an orphan json.tmp.XXXXXX).
left="$work/leftover"
"$KT" capture --class mug --instance builtin --step 5 --range 20 --settle 0.01 -q --out "$left" 2> /dev/null
head -n 4 "$left/manifest.csv" > "$left/m" && mv "$left/m" "$left/manifest.csv"   # 15°'s row never appended
printf '{\n  "class": "mu' > "$left/mug/builtin/e30/a15.0.json.tmp.Ab12Cd.json"
"$KT" verify "$left" > "$work/left1.txt"
check "verify names the leftover apart" grep -q "^1 leftover temporary file from an interrupted write" "$work/left1.txt"
check "verify lists the row-less view's files as orphans" grep -q "^orphan: mug/builtin/e30/a15.0.pcd" "$work/left1.txt"
"$KT" capture --class mug --instance builtin --step 5 --range 20 --settle 0.01 -q --out "$left" 2> "$work/left.err"
check "the resume removes it and says so" grep -q "removed 1 leftover temporary file of an interrupted write" "$work/left.err"
check "the resume retakes the row-less view" grep -q "1 views written, 3 already there" "$work/left.err"
"$KT" verify "$left" > "$work/left2.txt"
check "the resumed dataset verifies" grep -q "4 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/left2.txt"

# A corrupted file is found.
pcd=$(ls "$ds"/mug/builtin/e30/a45.0.pcd)
printf 'x' >> "$pcd"
"$KT" verify "$ds" > "$work/verify2.txt"
check "verify fails on a corrupt file" test $? -ne 0
check "verify names it" grep -q "^corrupt: mug/builtin/e30/a45.0.pcd" "$work/verify2.txt"
"$KT" describe "$ds" -q > "$work/features.csv"
check "describe reads the dataset" test "$(wc -l < "$work/features.csv")" -eq 37

# Axis calibration from a sphere-target sequence, then a capture that uses it.
"$KT" capture --mesh builtin:sphere-target --class calib --instance sphere --elevation 45 --step 30 --settle 0.01 -q \
    --out "$work/cal" 2> /dev/null
"$KT" calibrate-axis "$work/cal" --out "$work/axis.json" > "$work/cal.txt" 2> /dev/null
check "calibrate-axis exits 0" test $? -eq 0
check "calibrate-axis reports 12 views and a 70 mm circle" grep -qE "target circle r = (69\.[5-9]|70\.[0-4]) mm.*over 12 views" "$work/cal.txt"
check "calibration angles agree (rms < 0.5°)" grep -qE "angle rms 0\.[0-4][0-9]°" "$work/cal.txt"
"$KT" capture --class mug --instance calibrated --step 90 --settle 0.01 -q --calibration "$work/axis.json" --out "$work/calds" 2> /dev/null
check "capture with --calibration exits 0" test $? -eq 0
check "the calibration is kept with the dataset" cmp -s "$work/axis.json" "$work/calds/calibration.json"
check "sidecars carry the calibrated transform" grep -q '"camera_from_turntable": \[' "$work/calds/mug/calibrated/e30/a90.0.json"
"$KT" verify "$work/calds" > /dev/null
check "a calibrated dataset verifies" test $? -eq 0
echo '{"format": "something-else"}' > "$work/notcal.json"
"$KT" capture --class mug --instance x --calibration "$work/notcal.json" --out "$work/bad2" 2> "$work/notcal.err"
check "a wrong calibration file is named" grep -q "notcal.json: not a keyturn axis calibration" "$work/notcal.err"

# simulate over an object list (quoted CSV fields, mesh paths relative to the CSV).
objs="$work/objects"
mkdir -p "$objs"
data=$(cd "$(dirname "$0")/../../data/objects" && pwd)
cp "$data/can__ycb_005_tomato_soup_can.ply" "$data/teapot__utah_teapot.ply" "$objs/"
cat > "$objs/objects.csv" <<CSV
class,instance,mesh,source
can,ycb_005,can__ycb_005_tomato_soup_can.ply,"YCB, via a mirror"
teapot,utah,teapot__utah_teapot.ply,"Newell, 1975"
CSV
"$KT" simulate --objects "$objs/objects.csv" --elevations 30,60 --step 45 --out "$work/sim" -q 2> "$work/sim.err"
check "simulate exits 0" test $? -eq 0
check "simulate: 2 objects x 2 elevations x 8 views" test "$(( $(wc -l < "$work/sim/manifest.csv") - 1 ))" -eq 32
check "simulate reports its rate" grep -q "views/s" "$work/sim.err"
"$KT" verify "$work/sim" > /dev/null
check "simulated dataset verifies" test $? -eq 0
check "teapot at elevation 60 exists" test -s "$work/sim/teapot/utah/e60/a315.0.pcd"
"$KT" simulate --objects "$objs/objects.csv" --elevations 30,60 --step 45 --out "$work/sim" -q 2> "$work/sim2.err"
check "simulate resumes: nothing new" grep -q "0 views written, 32 already there" "$work/sim2.err"
echo 'class,instance' > "$work/bad.csv"
"$KT" simulate --objects "$work/bad.csv" --out "$work/bad" 2> "$work/bad.err"
check "a list without a mesh column is named" grep -q "bad.csv: needs class, instance and mesh columns" "$work/bad.err"

finish
