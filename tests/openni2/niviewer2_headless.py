#!/usr/bin/env python3
"""NiViewer2 (openni2-utils), unchanged, on the simulated OpenNI2 camera under Xvfb.

Runs NiViewer2 with the simulated camera's drivers folder on LD_LIBRARY_PATH inside
xvfb-run, whose screen is kept as an XWD file (-fbdir), watches that screen until NiViewer2
has drawn frames (no fixed wait: a loaded machine draws later), and checks it: NiViewer2
shows depth on the left (a yellow ramp where depth is measured) and colour on the right
(the simulated mug's orange on the grey table).
Writes the screen as a PPM beside it for a person to look at.
usage: niviewer2_headless.py XVFB_RUN NIVIEWER2 OPENNI2_DIR WORK
"""
import json
import os
import shutil
import struct
import subprocess
import sys
import time


def read_xwd(path):
    data = open(path, "rb").read()
    h = struct.unpack(">25I", data[:100])
    header, width, height, bpp, bpl, ncolors = h[0], h[4], h[5], h[11], h[12], h[19]
    if bpp != 32:
        sys.exit("FAIL: %s: %d bits per pixel, expected 32" % (path, bpp))
    pixels = data[header + 12 * ncolors:]
    def rgb(x, y):
        o = y * bpl + 4 * x
        b, g, r = pixels[o], pixels[o + 1], pixels[o + 2]  # little-endian BGRX
        return r, g, b
    return width, height, rgb


def panels(path):
    """What the screen at `path` shows: (yellow depth samples, orange colour samples, samples per panel)."""
    width, height, rgb = read_xwd(path)
    half = width // 2
    yellow = orange = 0
    for y in range(0, 460, 2):
        for x in range(0, width, 2):
            r, g, b = rgb(x, y)
            if x < half and r > 80 and g > 80 and b < 40 and abs(r - g) < 30:
                yellow += 1
            if x >= half and r > 120 and r > b + 60 and g > b + 20:
                orange += 1
    return yellow, orange, (460 // 2) * (half // 2)


def drawn(yellow, orange, samples):
    return yellow >= 0.2 * samples and orange >= 0.005 * samples


def main():
    xvfb, viewer, folder, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    fb = os.path.join(work, "fb")
    os.makedirs(fb, exist_ok=True)
    config = os.path.join(work, "sim.json")
    with open(config, "w") as f:
        json.dump({"distance": 0.8, "turntable_deg": 270, "seed": 3}, f)
    screen = os.path.join(fb, "Xvfb_screen0")
    seen = os.path.join(work, "seen")
    if os.path.exists(seen):
        os.remove(seen)
    # NiViewer2 runs until closed: xvfb-run runs a shell that starts it and ends it once this script,
    # watching the screen, has seen it draw depth and colour (or given up) and made the file `seen`.
    script = ('LD_LIBRARY_PATH="$1" KEYTURN_OPENNI2_SIM_CONFIG="$2" "$3" > "$4/niviewer2.log" 2>&1 & '
              'pid=$!; while [ ! -e "$5" ] && kill -0 $pid 2>/dev/null; do sleep 0.2; done; '
              'kill $pid 2>/dev/null; wait $pid 2>/dev/null; true')
    xvfb_run = subprocess.Popen([xvfb, "-a", "-s", "-screen 0 1400x1000x24 -fbdir " + fb, "bash", "-c", script,
                                 "niviewer2", folder, config, viewer, work, seen])
    kept = os.path.join(work, "screen.xwd")
    started = time.monotonic()
    deadline = started + 90  # the test's own limit is 180 s
    while True:
        if os.path.exists(screen):
            shutil.copyfile(screen, kept)
            try:
                if drawn(*panels(kept)):
                    print("NiViewer2 drew depth and colour %.1f s after its start" % (time.monotonic() - started))
                    break
            except (IndexError, struct.error):  # the server is still laying the file out
                pass
        if xvfb_run.poll() is not None or time.monotonic() > deadline:
            break  # ended or out of time: the screen as it is now is judged below
        time.sleep(0.2)
    open(seen, "w").close()
    if xvfb_run.wait(timeout=60) != 0:
        sys.exit("FAIL: xvfb-run exited %d" % xvfb_run.returncode)
    width, height, rgb = read_xwd(kept)
    yellow, orange, samples = panels(kept)
    with open(os.path.join(work, "screen.ppm"), "wb") as out:
        out.write(b"P6 %d %d 255\n" % (width, height))
        out.write(bytes(v for y in range(height) for x in range(width) for v in rgb(x, y)))
    print("depth panel: %.1f%% measured (yellow); colour panel: %.2f%% the mug's orange" %
          (100.0 * yellow / samples, 100.0 * orange / samples))
    log = open(os.path.join(work, "niviewer2.log")).read()
    if yellow < 0.2 * samples:
        sys.exit("FAIL: NiViewer2 shows little depth\n" + log[-2000:])
    if orange < 0.005 * samples:
        sys.exit("FAIL: NiViewer2 shows no mug in colour\n" + log[-2000:])
    print("OK")


if __name__ == "__main__":
    main()
