#!/usr/bin/env bash
# Beyond the training conditions (docs/results.md): a model's single-view answers on views it was
# not trained on, through both simulated cameras. The 27 objects of data/objects/objects-27.csv are
# simulated through the SR4000 (libmesasr-sim) and the Kinect-class camera (the simulated OpenNI2
# driver) at elevations 30, 40, 45 and 60 degrees, every 45 degrees (8 views an object and
# elevation), with another noise seed than training's; the model classifies every view. Prints, per
# camera and elevation: the model's own objects named right, and the objects it was never trained on
# answered "unknown"; then per camera the same over turns of the table (3 views over 90° from every
# view, `classify --fuse --turns`). About 6 minutes on 2 cores.
# usage: scripts/beyond-training.sh [MODEL] [OUT_DIR] [ELEVATIONS]
#        (default data/models/sim-objects, out/beyond-training, 30,40,45,60)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
KT=$root/build/app/keyturn
model=${1:-$root/data/models/sim-objects}
out=${2:-out/beyond-training}
elevations=${3:-30,40,45,60}
mkdir -p "$out"
for camera in sr4000 openni2; do
  "$KT" simulate --camera $camera --objects "$root/data/objects/objects-27.csv" --elevations "$elevations" --step 45 \
    --seed 2 -q --out "$out/views-$camera"
  "$KT" classify "$model" "$out/views-$camera" --json -q > "$out/answers-$camera.json"
  "$KT" classify "$model" "$out/views-$camera" --fuse --turns --json -q > "$out/turns-$camera.json"
done
python3 - "$out" "$model" <<'PY'
import json, sys, collections
out, model = sys.argv[1], sys.argv[2]
known = set(json.load(open(f"{model}/model.json"))["classes"])
print(f"model: {model} ({len(known)} classes)")
print("| camera | elevation | own objects named right | own objects unknown | other objects unknown |")
print("|---|---|---:|---:|---:|")
totals = {}
for camera in ("sr4000", "openni2"):
    cells = collections.defaultdict(lambda: [0, 0, 0, 0, 0])  # own views, named right, own unknown, other views, other unknown
    for v in json.load(open(f"{out}/answers-{camera}.json")):
        cls, instance, elevation = v["view"].split("/")[-4:-1]
        c = cells[elevation.lstrip("e")]
        if instance in known:
            c[0] += 1; c[1] += v["class"] == instance; c[2] += v["class"] == "unknown"
        else:
            c[3] += 1; c[4] += v["class"] == "unknown"
    for e in sorted(cells, key=float):
        n, right, unk, m, munk = cells[e]
        pct = lambda a, b: f"{100 * a / b:.1f} % of {b}" if b else "–"
        print(f"| {camera} | {e}° | {pct(right, n)} | {pct(unk, n)} | {pct(munk, m)} |")
# Turns: 3 views over 90° from every view (classify --fuse --turns: TurnFusion's answer, as evaluate reads turns).
print()
print("| camera | turns of its own objects named right | turns of the other objects unknown |")
print("|---|---:|---:|")
for camera in ("sr4000", "openni2"):
    own = right = other = unknown = 0
    for turn in json.load(open(f"{out}/turns-{camera}.json"))["turns"]:
        instance = turn["object"].split("/")[1]
        if instance in known:
            own += 1; right += turn["class"] == instance
        else:
            other += 1; unknown += turn["answer"] == "unknown"
    pct = lambda a, b: f"{100 * a / b:.1f} % of {b}" if b else "–"
    print(f"| {camera} | {pct(right, own)} | {pct(unknown, other)} |")
PY
