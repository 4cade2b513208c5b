#!/usr/bin/env bash
# OpenNI2 cameras as a user runs keyturn with them, against the simulated OpenNI2 driver that
# Debian's real libOpenNI2 loads from its folder (argument 2: found through keyturn's RUNPATH with
# no environment, and put first on the library path as for any other OpenNI2 program): the folder
# links the system's drivers, grab writes frames, devices lists the device, a capture with
# the simulated turntable writes a dataset verify passes; without a device, with a URI not present
# and with an .oni file missing, one line says so.
set -u
source "$(dirname "$0")/lib.sh"
simdir=${2:?the simulated OpenNI2 driver\'s folder (lib/keyturn/openni2)}
sim() { LD_LIBRARY_PATH="$simdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$@"; }

# No device: Debian's libOpenNI2 beside a drivers folder holding only the .oni driver (as a machine
# with no camera plugged in), and beside an empty one (OpenNI2 cannot start).
nodev="$work/no-device"
mkdir -p "$nodev/OpenNI2/Drivers" "$work/no-drivers/OpenNI2/Drivers"
ln -s "$(readlink -f "$simdir/libOpenNI2.so.0")" "$nodev/libOpenNI2.so.0"
system_drivers=$(dirname "$(readlink -f "$simdir/libOpenNI2.so.0")")/OpenNI2/Drivers
ln -s "$system_drivers/libOniFile.so.0" "$nodev/OpenNI2/Drivers/libOniFile.so.0"
ln -s "$(readlink -f "$simdir/libOpenNI2.so.0")" "$work/no-drivers/libOpenNI2.so.0"
LD_LIBRARY_PATH="$nodev" "$KT" grab --camera openni2 --out "$work/none.pcd" 2> "$work/none.err"
check "no device: grab exits non-zero" test $? -ne 0
check "no device: one line naming the drivers folder and the folder its links lead into" \
  grep -qx "keyturn: no OpenNI2 device found (is it plugged in and readable by this user? OpenNI2's drivers folder: $nodev/OpenNI2/Drivers (links into $system_drivers))" "$work/none.err"
check "no device: nothing else said" test "$(wc -l < "$work/none.err")" -eq 1
LD_LIBRARY_PATH="$nodev" "$KT" devices > "$work/none-devices.txt"
check "no device: devices says so" grep -qx "No OpenNI2 depth camera." "$work/none-devices.txt"
LD_LIBRARY_PATH="$work/no-drivers" "$KT" grab --camera openni2 --out "$work/none.pcd" 2> "$work/nodrivers.err"
check "no drivers: one line saying OpenNI2 could not start" \
  grep -qx "keyturn: OpenNI2 could not start: Found no files matching '$work/no-drivers/OpenNI2/Drivers/lib\*.so.0'" "$work/nodrivers.err"
LD_LIBRARY_PATH="$work/no-drivers" "$KT" devices --json > "$work/nodrivers.json"
check "no drivers: devices still lists the SwissRangers and says why OpenNI2 is absent" \
  python3 -c "import json,sys; j = json.load(open(sys.argv[1])); assert j['cameras'] == [] and j['openni2'] == [] and 'could not start' in j['openni2_error']" "$work/nodrivers.json"

# Without any environment (issue 52): keyturn's RUNPATH finds its own folder, whose libOpenNI2 loads
# the simulated camera's driver, links to every driver of the system's folder (real cameras) and, for
# .oni recordings, keyturn's guard of the system's libOniFile (simulators/openni2_sim/oni_file_guard.cpp).
linked=0
for driver in "$system_drivers"/lib*.so.0; do
  case "$(basename "$driver")" in libKeyturn*|libOniFile.so.0) continue ;; esac
  [ "$(readlink "$simdir/OpenNI2/Drivers/$(basename "$driver")")" = "$driver" ] && linked=$((linked + 1))
done
check "the folder links every driver of $system_drivers ($linked)" \
  test "$linked" -eq "$(ls "$system_drivers"/lib*.so.0 | grep -Evc '/(libKeyturn[^/]*|libOniFile\.so\.0)$')" -a "$linked" -ge 1
check "the folder plays .oni recordings through keyturn's guard of libOniFile, not a link to it" \
  test -f "$simdir/OpenNI2/Drivers/libKeyturnOniFile.so.0" -a ! -e "$simdir/OpenNI2/Drivers/libOniFile.so.0"
env -u LD_LIBRARY_PATH "$KT" grab --camera openni2 --out "$work/noenv.pcd" 2> "$work/noenv.err"
check "no environment: grab --camera openni2 takes the simulated camera" \
  grep -q "^keyturn grab: keyturn Simulated structured-light camera (keyturn-sim://default)" "$work/noenv.err"
env -u LD_LIBRARY_PATH "$KT" devices > "$work/noenv-devices.txt"
check "no environment: devices lists the simulated camera" grep -q "openni2:keyturn-sim://default" "$work/noenv-devices.txt"
env -u LD_LIBRARY_PATH "$KT" capture --camera openni2 --pose sim --class mug --instance builtin --step 180 --settle 0.01 -q \
  --out "$work/noenv-ds" 2> "$work/noenv-capture.err"
check "no environment: capture --camera openni2 --pose sim writes its views" grep -q "2 views written" "$work/noenv-capture.err"

# grab: three frames of the simulated Kinect-class camera, their per-pixel median written.
sim "$KT" grab --camera openni2 --frames 3 --out "$work/grab/frame.pcd" > "$work/grab.out" 2> "$work/grab.err"
check "grab --camera openni2 exits 0" test $? -eq 0
check "grab writes the PCD and the depth PNG" test -s "$work/grab/frame.pcd" -a -s "$work/grab/frame_distance.png"
check "grab lists what it wrote" grep -qx "$work/grab/frame.pcd" "$work/grab.out"
check "the PCD is the organized 640 x 480 frame" grep -aqx "WIDTH 640" "$work/grab/frame.pcd"
check "grab reports the device's pinhole" grep -q "depth in 1 mm units, fx 580 fy 580 cx 319.5 cy 239.5, registered to colour" "$work/grab.err"
valid=$(sed -n 's/.* frames (per-pixel median), \([0-9]*\) of 307200 pixels with a return.*/\1/p' "$work/grab.err")
check "grab: the object is seen (${valid:-0} pixels with a return)" test "${valid:-0}" -gt 5000

# devices --json: URI, name, depth modes, intrinsics.
sim "$KT" devices --json > "$work/devices.json"
check "devices --json exits 0" test $? -eq 0
python3 - "$work/devices.json" <<'PY' > "$work/devices.check"
import json, sys
d = json.load(open(sys.argv[1]))["openni2"]
ok = len(d) == 1 and d[0]["uri"] == "keyturn-sim://default" and d[0]["spec"] == "openni2:keyturn-sim://default"
ok = ok and {"width": 640, "height": 480, "fps": 30, "format": "depth 1 mm"} in d[0]["depth_modes"]
ok = ok and abs(d[0]["intrinsics"]["fx"] - 580) < 0.5 and d[0]["intrinsics"]["cx"] == 319.5
ok = ok and d[0]["colour"] and d[0]["registration"]
print("ok" if ok else d)
PY
check "devices --json lists the simulated device with its modes and intrinsics" grep -qx ok "$work/devices.check"
sim "$KT" devices > "$work/devices.txt"
check "devices lists its spec" grep -q "openni2:keyturn-sim://default" "$work/devices.txt"

sim "$KT" grab --camera openni2:1d27/0601@9/9 --out "$work/x.pcd" 2> "$work/uri.err"
check "a URI not present: exits non-zero" test $? -ne 0
check "a URI not present: named with those present" \
  grep -qx "keyturn: OpenNI2 device '1d27/0601@9/9' not found; present: keyturn-sim://default" "$work/uri.err"
"$KT" grab --camera "playback:$work/gone.oni" --out "$work/x.pcd" 2> "$work/gone.err"
check "an .oni file missing: named" grep -qx "keyturn: $work/gone.oni: no such .oni recording" "$work/gone.err"

# A capture sequence: the simulated turntable turning, the simulated OpenNI2 camera seeing it.
ds="$work/dataset"
sim "$KT" capture --camera openni2 --pose sim --class mug --instance builtin --step 90 --settle 0.01 -q --out "$ds" \
  2> "$work/capture.err"
check "capture --camera openni2 --pose sim exits 0" test $? -eq 0
check "capture writes 4 views" grep -q "4 views written" "$work/capture.err"
"$KT" verify "$ds" > "$work/verify.txt"
check "the dataset verifies" test $? -eq 0
check "verify counts 4 views, OK" grep -q "4 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/verify.txt"
python3 - "$ds" <<'PY' > "$work/sidecar.check"
import json, sys
s = json.load(open(sys.argv[1] + "/mug/builtin/e30/a90.0.json"))
cam = s["camera"]
ok = "modulation_mhz" not in cam and "keyturn-sim://" in cam["device"] and len(s["camera_from_turntable"]) == 4
print("ok" if ok else s)
PY
check "the sidecar records the OpenNI2 device, no SR4000 settings, the exact calibration" grep -qx ok "$work/sidecar.check"
# The object turned: the views differ.
check "views at 0 and 90 degrees differ" bash -c "! cmp -s '$ds/mug/builtin/e30/a0.0.pcd' '$ds/mug/builtin/e30/a90.0.pcd'"
sim "$KT" capture --camera openni2:keyturn-sim://default --pose sim --class mug --instance builtin --out "$work/other" \
  2> "$work/world.err"
check "pose sim with another OpenNI2 device is refused in one line" \
  grep -q "pose sim needs --camera sim or openni2 (the simulated OpenNI2 camera)" "$work/world.err"
# keyturn simulate through the OpenNI2 camera takes each view at its own angle and gives the same
# dataset on every run: the driver's frames run free at 30/s, so the frames that may predate the move
# are discarded and the noise is fixed per pose (before, the 90° view was the 0° frame again, and 3 of
# 4 views differed between two runs).
objects="$(cd "$(dirname "$0")/../../data/objects" && pwd)"
head -1 "$objects/objects.csv" > "$work/mug.csv"
echo "mug,ycb_025_mug,$objects/mug__ycb_025_mug.ply" >> "$work/mug.csv"
for run in 1 2; do
  env -u LD_LIBRARY_PATH "$KT" simulate --camera openni2 --objects "$work/mug.csv" --elevations 30 --step 90 \
    --out "$work/twice-$run" > /dev/null 2>&1
done
check "simulate --camera openni2 twice: 4 views each" test "$(find "$work/twice-1" "$work/twice-2" -name '*.pcd' | wc -l)" -eq 8
check "simulate --camera openni2: each angle its own view (none a frame from before the table moved)" \
  test "$(find "$work/twice-1" -name '*.pcd' | xargs sha256sum | cut -d' ' -f1 | sort -u | wc -l)" -eq 4
check "simulate --camera openni2 twice: the same clouds" \
  diff <(cd "$work/twice-1" && find . -name '*.pcd' | sort | xargs sha256sum) <(cd "$work/twice-2" && find . -name '*.pcd' | sort | xargs sha256sum)

# The studio with the OpenNI2 camera live (headless under Xvfb), no environment needed: frames arrive,
# recognition runs.
studio="$(dirname "$KT")/keyturn-studio"
if [ -x "$studio" ] && command -v xvfb-run > /dev/null; then
  data="$(cd "$(dirname "$0")/../../data" && pwd)"
  env -u LD_LIBRARY_PATH xvfb-run -a -s "-screen 0 1600x1000x24" "$studio" --camera openni2 --model "$data/models/sim-objects" \
    --settings "$work/studio.ini" --measure 3 --screenshot "$work/studio.png" > "$work/studio.json" 2> "$work/studio.err"
  check "studio --camera openni2 exits 0" test $? -eq 0
  # Frames arrived and were recognised during the 3 s measured. How many a second is the machine's
  # load (5 frames/s was loosened to 2 after flakes, issue 51): a rate, measured in the benchmarks
  # (keyturn-studio --measure, docs/benchmarks.md), not asserted here.
  rates=$(python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d['camera_fps'], d['recognition_fps'])" \
    "$work/studio.json" 2>/dev/null)
  check "studio: the OpenNI2 camera live, its frames recognised (${rates:-none} frames/s)" \
    python3 -c "import sys; c, r = map(float, sys.argv[1:3]); sys.exit(not (c > 0 and r > 0))" ${rates:-0 0}
  check "studio: screenshot written" test -s "$work/studio.png"
else
  skip yes "the studio under Xvfb (keyturn-studio or xvfb-run missing)"
fi
finish
