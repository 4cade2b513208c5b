#!/usr/bin/env bash
# Across sensors (docs/results.md "Across sensors"): the 15 objects of data/models/sim-objects
# captured on the simulated rig through the simulated SR4000 (libmesasr-sim, 176 × 144 ToF) and the
# simulated OpenNI2 camera (640 × 480 structured light), at elevations 30° and 45°, every 45°.
# For each feature set, a model trained on one camera's 30° views classifies both cameras' 45° views;
# prints top-1 accuracy per (trained on, tested on). About 10 minutes on 2 cores.
# usage: scripts/across-sensors.sh [OUT_DIR] [FEATURE_SET ...]   (default out/across-sensors; kpd2+kpa3 esf s_kpd2+kpa3)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
KT=$root/build/app/keyturn
out=${1:-out/across-sensors}
shift || true
sets=("$@")
[ ${#sets[@]} -gt 0 ] || sets=(kpd2+kpa3 esf s_kpd2+kpa3)
mkdir -p "$out"
# The simulated OpenNI2 camera is found through its drivers folder (docs/camera.md).
export LD_LIBRARY_PATH=$root/build/lib/keyturn/openni2${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
classes=$(python3 -c "import json,sys; print(' '.join(json.load(open(sys.argv[1]))['classes']))" \
          "$root/data/models/sim-objects/model.json")
n=0
for c in $classes; do
  n=$((n + 1))
  mesh=$(ls "$root"/data/objects/*__"$c".ply)
  category=$(basename "$mesh" .ply); category=${category%%__*}
  for camera in sim openni2; do
    for elevation in 30 45; do
      "$KT" capture --camera $camera --pose sim --class "$category" --instance "$c" --mesh "$mesh" --step 45 \
        --elevation $elevation --settle 0.01 -q --out "$out/$camera-$elevation" 2>> "$out/capture.log"
    done
  done
  echo "across-sensors: captured $n objects ($c)" >&2
done
for features in "${sets[@]}"; do
  for trained in sim openni2; do
    "$KT" train "$out/$trained-30" --features "$features" --out "$out/model-$trained-$features" -q
    for tested in sim openni2; do
      "$KT" classify "$out/model-$trained-$features" "$out/$tested-45" --json -q > "$out/$features-$trained-on-$tested.json"
    done
  done
done
python3 - "$out" "${sets[@]}" <<'PY'
import json, sys
out, sets = sys.argv[1], sys.argv[2:]
name = {"sim": "SR4000", "openni2": "OpenNI2"}
print("| features | trained on (30°) | tested on SR4000 (45°) | tested on OpenNI2 (45°) |")
print("|---|---|---:|---:|")
for f in sets:
    for t in ("sim", "openni2"):
        row = []
        for d in ("sim", "openni2"):
            views = json.load(open(f"{out}/{f}-{t}-on-{d}.json"))
            right = sum(v["view"].split("/")[-3] == v["best"] for v in views)
            row.append(f"{100 * right / len(views):.1f} % of {len(views)}")
        print(f"| {f} | {name[t]} | {row[0]} | {row[1]} |")
PY
