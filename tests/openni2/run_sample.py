#!/usr/bin/env python3
"""Runs one of Debian's OpenNI2 samples, unchanged, against the simulated OpenNI2
driver and checks what it prints.

The samples loop until a key is pressed (wasKeyboardHit polls stdin), so the
sample reads a pipe: for the first half of the run the simulated turntable (the
config's world file) stands at one angle, then at another, and a "q" ends it.
Each depth line is "[timestamp_us] middle-pixel-depth-mm"; colour lines are
"[timestamp_us] 0xRRGGBB". The middle pixel sees the mug's body at the first
angle and its handle at the second, so the depths must form two groups.
"""
import argparse
import json
import os
import re
import subprocess
import sys


def write_world(path, degrees):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump({"turntable_deg": degrees}, f)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("program")
    ap.add_argument("--work", required=True)
    ap.add_argument("--frames", type=int, default=40, help="depth frames before the turn, and after it")
    ap.add_argument("--angles", type=float, nargs=2, default=[0.0, 270.0])
    ap.add_argument("--colour", action="store_true", help="expect colour lines too")
    args = ap.parse_args()

    os.makedirs(args.work, exist_ok=True)
    world = os.path.join(args.work, "world.json")
    config = os.path.join(args.work, "sim.json")
    write_world(world, args.angles[0])
    with open(config, "w") as f:
        json.dump({"mesh": "builtin:mug", "distance": 0.7, "world": "world.json", "seed": 5}, f)
    env = dict(os.environ, KEYTURN_OPENNI2_SIM_CONFIG=config)

    # Line-buffered (stdbuf), so the frames are counted as the sample prints them: the world turns
    # after so many depth frames, and the key is pressed after so many more (no sleep guessing how
    # many a loaded machine delivered by then).
    proc = subprocess.Popen(["stdbuf", "-oL", os.path.abspath(args.program)], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, cwd=args.work)
    printed = []
    depth_line = re.compile(rb"^\[(\d+)\]\s+(\d+)\s*$")

    def read_depth_frames(n):
        seen = 0
        while seen < n:
            line = proc.stdout.readline()
            if not line:
                return  # the sample ended: what it printed is judged below
            printed.append(line)
            seen += bool(depth_line.match(line))

    read_depth_frames(args.frames)
    write_world(world, args.angles[1])
    read_depth_frames(args.frames)
    try:
        out, _ = proc.communicate(b"q", timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        sys.exit("FAIL: %s did not stop after a key press" % args.program)
    out = b"".join(printed) + out
    text = out.decode(errors="replace")
    if proc.returncode != 0:
        sys.exit("FAIL: %s exited %d:\n%s" % (args.program, proc.returncode, text[-2000:]))

    depth = [(int(t), int(d)) for t, d in re.findall(r"^\[(\d+)\]\s+(\d+)\s*$", text, re.M)]
    colour = re.findall(r"^\[(\d+)\]\s+0x([0-9a-f]{6})\s*$", text, re.M)
    problems = []
    if "Wait failed" in text or "Read failed" in text or "Couldn't" in text:
        problems.append("the sample reported an error")
    if len(depth) < 20:
        problems.append("only %d depth lines" % len(depth))
    times = [t for t, _ in depth]
    if any(b <= a for a, b in zip(times, times[1:])):
        problems.append("timestamps do not increase")
    if len(depth) >= 2:
        rate = (len(depth) - 1) / ((times[-1] - times[0]) / 1e6)
        print("%d depth frames at %.1f frames/s" % (len(depth), rate))
        if rate > 31:
            problems.append("%.1f frames/s: faster than the 30 the stream announces" % rate)
    values = [d for _, d in depth]
    if any(not 500 <= d <= 4500 for d in values):
        problems.append("middle depths outside 0.5-4.5 m: %s" % sorted(set(values))[:10])
    # First and last quarter: before and well after the turntable turned.
    q = max(1, len(values) // 4)
    before, after = values[:q], values[-q:]
    print("middle depth (mm) before the turn: %s; after: %s" % (sorted(set(before)), sorted(set(after))))
    if before and after and abs(sum(before) / len(before) - sum(after) / len(after)) < 8:
        problems.append("the middle depth did not follow the turntable")
    if args.colour:
        print("%d colour lines, e.g. %s" % (len(colour), colour[:1]))
        if len(colour) < 10:
            problems.append("only %d colour lines" % len(colour))
    if problems:
        print(text[-3000:])
        sys.exit("FAIL: " + "; ".join(problems))
    print("OK")


if __name__ == "__main__":
    main()
