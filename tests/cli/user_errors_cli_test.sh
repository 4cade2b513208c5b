#!/usr/bin/env bash
# What a new user running the docs' examples slightly wrong gets back: one line naming the file or
# option and what was wrong, exit 1 — and nothing half-made left on disk (issue 22's findings).
set -u
source "$(dirname "$0")/lib.sh"
STUDIO=${KEYTURN_STUDIO:-}
data=$(cd "$(dirname "$0")/../../data" && pwd)
one_line() { test "$(wc -l < "$1")" -eq 1; }

# The simulator's configuration: paths relative to the file's folder; a bad file or mesh is named.
mkdir -p "$work/cfg/objects"
cp "$data/objects/mug__ycb_025_mug.ply" "$work/cfg/objects/"
echo '{"mesh": "objects/mug__ycb_025_mug.ply", "elevation": 45}' > "$work/cfg/c.json"
(cd "$work" && "$KT" grab --camera sim --sim-config cfg/c.json --out "$work/cfg.pcd" > /dev/null 2> "$work/cfg.err")
check "a config's mesh path is relative to the config's folder" test $? -eq 0
"$KT" grab --camera sim --sim-config "$work/none.json" --out "$work/x.pcd" 2> "$work/none.err"
check "a missing config exits 1" test $? -eq 1
check "a missing config is named in one line" grep -q "none.json: cannot read (No such file or directory)" "$work/none.err"
check "  (one line)" one_line "$work/none.err"
echo '{"mesh": ' > "$work/broken.json"
"$KT" grab --camera sim --sim-config "$work/broken.json" --out "$work/x.pcd" 2> "$work/broken.err"
check "a malformed config is named" grep -q "broken.json: not JSON at byte 10 (unexpected end of input; expected '\\[', '{', or a literal)" "$work/broken.err"
echo '{"mesh": "nowhere.ply"}' > "$work/nomesh.json"
"$KT" grab --camera sim --sim-config "$work/nomesh.json" --out "$work/x.pcd" 2> "$work/nomesh.err"
check "a config's missing mesh is named with the config" grep -q "nomesh.json: mesh: .*nowhere.ply" "$work/nomesh.err"
check "  (one line)" one_line "$work/nomesh.err"
check "no files after a failed grab" test ! -e "$work/x.pcd"

# --camera: every choice is listed, sim included.
"$KT" capture --camera gige --class a --instance b --out "$work/gige" 2> "$work/gige.err"
check "an unknown camera exits 1" test $? -eq 1
check "an unknown camera lists sim and openni2" grep -q "camera 'gige': expected sim, sim:CONFIG, usb, usb:SERIAL, eth:IP, openni2, openni2:URI, playback:DATASET" "$work/gige.err"
check "  and leaves no dataset" test ! -e "$work/gige"

# Out-of-range and missing options: one line, exit 1, like every other error.
"$KT" describe --bins 1 "$work/cfg.pcd" 2> "$work/bins.err"
check "describe --bins 1 exits 1" test $? -eq 1
check "describe --bins 1 is one line naming the option" grep -q "^keyturn describe: --bins: must be within 2..4096" "$work/bins.err"
check "  (one line)" one_line "$work/bins.err"
"$KT" evaluate "$work" --bins 16,0 --out "$work/ev" 2> "$work/evbins.err"
check "evaluate --bins 16,0 exits 1" test $? -eq 1
check "evaluate --bins checks each value as describe does" grep -q "^keyturn: --bins: must be within 2..4096, not '0'" "$work/evbins.err"
check "  (one line)" one_line "$work/evbins.err"
"$KT" describe --max-range nan "$work/cfg.pcd" 2> "$work/nan.err"
check "describe --max-range nan exits 1" test $? -eq 1
check "describe --max-range nan names the option" grep -q "^keyturn describe: --max-range: is not a finite number: 'nan'" "$work/nan.err"
"$KT" grab --frames 0 --out "$work/x.pcd" 2> "$work/frames.err"
check "grab --frames 0 exits 1" test $? -eq 1
check "  (one line)" one_line "$work/frames.err"
"$KT" describe --help > /dev/null
check "--help still exits 0" test $? -eq 0

# Two angles that round to one file name would overwrite each other: refused before anything is written.
"$KT" render builtin:mug --angles 10,10.2 --out "$work/r{angle}.pcd" 2> "$work/render.err"
check "render of two angles with one file name exits 1" test $? -eq 1
check "  and names both angles and the file" grep -q "angles 10 and 10.2 would both write .*r010.pcd" "$work/render.err"
check "  and writes nothing" test ! -e "$work/r010.pcd"

# A mesh is not a view.
"$KT" describe "$data/objects/mug__ycb_025_mug.ply" -q > /dev/null 2> "$work/mesh.err"
check "describe on a mesh exits 1" test $? -eq 1
check "describe on a mesh says so" grep -q "mug__ycb_025_mug.ply: is a mesh (.* faces), not a camera view: render views of it first" "$work/mesh.err"

# A capture that fails before its first view leaves no dataset that verify would call OK.
echo '{"format": "something-else"}' > "$work/notcal.json"
"$KT" capture --class mug --instance x --calibration "$work/notcal.json" --out "$work/badcal" 2> "$work/badcal.err"
check "a bad --calibration exits 1" test $? -eq 1
check "  and leaves no dataset" test ! -e "$work/badcal"
# A real-rig capture whose turntable answers (the simulated one) but whose camera library is missing.
"$KT" sim turntable --modbus-tcp 127.0.0.1:0 --duration 120 > "$work/table.out" 2> /dev/null &
table=$!
trap 'kill $table 2>/dev/null' EXIT
for _ in $(seq 300); do [ -s "$work/table.out" ] && break; sleep 0.1; done
KEYTURN_MESASR_LIB=/nonexistent/libmesasr.so "$KT" capture --camera usb --pose "$(head -1 "$work/table.out")" \
    --class a --instance b --out "$work/nolib" 2> "$work/nolib.err"
check "a capture without libMesaSR exits 1" test $? -eq 1
check "  says libMesaSR is missing" grep -q "libMesaSR not found" "$work/nolib.err"
check "  and leaves no dataset" test ! -e "$work/nolib"
kill $table 2>/dev/null
"$KT" capture --camera usb --pose modbus-tcp:127.0.0.1:1 --profile "$work/missing.json" --class a --instance b \
    --out "$work/noprof" 2> "$work/noprof.err"
check "a missing --profile is named before the camera is looked for" grep -q "missing.json" "$work/noprof.err"
check "  (not libMesaSR)" test "$(grep -c "libMesaSR" "$work/noprof.err")" -eq 0
mkdir -p "$work/empty"
"$KT" capture --class mug --instance x --step 90 --settle 0.01 -q --out "$work/empty/ds" 2> /dev/null
head -1 "$work/empty/ds/manifest.csv" > "$work/empty/m.csv" && mv "$work/empty/m.csv" "$work/empty/ds/manifest.csv"
rm -rf "$work/empty/ds/mug"
"$KT" verify "$work/empty/ds" > "$work/empty.out"
check "verify fails on a dataset without views" test $? -eq 1
check "verify says it is empty" grep -q "0 views.* — EMPTY (no views)" "$work/empty.out"

# calibrate-axis on a sequence without the sphere target refuses instead of writing a wrong axis.
"$KT" capture --class mug --instance x --step 30 --settle 0.01 -q --out "$work/mugseq" 2> /dev/null
"$KT" calibrate-axis "$work/mugseq" --out "$work/axis.json" > "$work/cal.out" 2> "$work/cal.err"
check "calibrate-axis without a sphere target exits 1" test $? -eq 1
check "  says it is not a sphere-target sequence" grep -q "mugseq: .*not a sphere-target sequence" "$work/cal.err"
check "  on one line" test "$(grep -c "^keyturn" "$work/cal.err")" -eq 1
check "  and writes no calibration" test ! -e "$work/axis.json"

# keyturn-studio: an unknown --object is refused before any window opens (no display needed).
if [ -n "$STUDIO" ]; then
  env -u DISPLAY "$STUDIO" --simulated --object nope 2> "$work/studio.err"
  check "studio --object nope exits 1" test $? -eq 1
  check "studio names the object and the list" grep -q "^keyturn-studio: --object nope: not in .*objects-27.csv (.*ycb_035_power_drill.*ycb_037_scissors" "$work/studio.err"
  env -u DISPLAY "$STUDIO" --playback "$work/no-recording" 2> "$work/playback.err"
  check "studio --playback of nothing exits 1" test $? -eq 1
  check "studio names the recording, in one line" test "$(cat "$work/playback.err")" = \
    "keyturn-studio: $work/no-recording: no such dataset to play back"
  env -u DISPLAY "$STUDIO" --playback "$work" --simulated 2> "$work/both.err"
  check "studio --playback with --simulated is refused" test $? -eq 1 -a "$(wc -l < "$work/both.err")" -eq 1
  env -u DISPLAY "$STUDIO" --threads 0 2> "$work/threads.err"
  check "studio --threads 0 is one line, exit 1" test $? -eq 1 -a "$(wc -l < "$work/threads.err")" -eq 1
  # Ctrl-C closes the window as its close button does: exit 0, settings saved, the simulator's folder
  # removed. Sent as soon as the studio catches it (its simulated rig folder is made after the handler,
  # before the window), so during start-up, the moment a fixed sleep used to guess past: a Ctrl-C then
  # is kept and closes the window once it is up (issue 52: under load the sleep ended mid-start-up and
  # the time measured from Ctrl-C was the rest of the start-up). env --default-signal: SIGINT at its
  # default however this script was started (a background job of a script starts with it ignored,
  # and the studio keeps an ignored SIGINT ignored).
  rm -f "$work/studio.ini"
  HOME="$work/home" xvfb-run -a -s "-screen 0 1600x1000x24" bash -c '
    env --default-signal=INT "$1" --simulated --settings "$2/studio.ini" > /dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1200); do [ -d "${TMPDIR:-/tmp}/keyturn-studio-$pid" ] && break; sleep 0.05; done
    kill -INT $pid; wait $pid; rc=$?
    echo "$rc $(date +%s.%N) $pid"' _ "$STUDIO" "$work" > "$work/sigint.txt"
  read -r rc exited pid < "$work/sigint.txt"
  check "studio: Ctrl-C during start-up exits 0 (rc $rc)" test "$rc" -eq 0
  check "studio: settings saved on Ctrl-C" grep -q "geometry" "$work/studio.ini"
  # From the close (the settings written) to the exit: devices closed, workers joined (the recognition
  # workers finish the frame they hold, so the time is the machine's load: about 0.2 s idle, 4.4 s at
  # load 11, 12.7 s at load 29 on 2 cores). Issue 51: a 3 s bound, loosened to 20 s after flakes, only
  # measured that load; a studio waiting on a worker that never returns never exits, and the wait above
  # then ends at ctest's time limit, a failure. The time is shown, not asserted.
  ms=$(python3 -c 'import os, sys; print(int((float(sys.argv[2]) - os.stat(sys.argv[1]).st_mtime) * 1000))' \
    "$work/studio.ini" "$exited" 2> /dev/null)
  check "studio: exited after closing its window (${ms:-?} ms from the close)" test -n "$exited" -a -n "$ms"
  check "studio: its temporary folder is gone" test ! -e "${TMPDIR:-/tmp}/keyturn-studio-$pid"
fi

# keyturn slurm: a folder that is no dataset, and evaluate options the stages set themselves.
"$KT" slurm "$work/cfg" --tasks 2 --out "$work/jobs" 2> "$work/slurm_ds.err"
check "slurm names a folder without a manifest" grep -q "cfg: not a dataset folder (no manifest.csv)" "$work/slurm_ds.err"
check "  and writes no scripts" test ! -e "$work/jobs"
echo "class,instance,elevation,azimuth,file" > "$work/cfg/manifest.csv"
"$KT" slurm "$work/cfg" --tasks 2 --out "$work/jobs" --evaluate "--features kpd2 --out elsewhere" 2> "$work/slurm_out.err"
check "slurm refuses --out among evaluate's options" \
  grep -q "^keyturn: --evaluate: leave out --out (the stages set --out, --shard, --merge and --jobs)$" "$work/slurm_out.err"
check "  and writes no scripts" test ! -e "$work/jobs"
"$KT" slurm "$work/cfg" --tasks 0 --out "$work/jobs" 2> "$work/slurm_tasks.err"
check "slurm --tasks 0 is one line naming the option" grep -q "^keyturn slurm: --tasks" "$work/slurm_tasks.err"
check "  (one line)" one_line "$work/slurm_tasks.err"
finish
