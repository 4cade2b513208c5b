#!/usr/bin/env bash
# The ISS sweep of docs/repeatability.md: each setting of ISS's radii, eigenvalue-ratio
# thresholds and suppression radius scored on a simulated SR4000 dataset (the rig's sensor
# model and noise, exact poses), natively and at an equal budget of K keypoints, and its
# keypoint count on the real Kinect cuts (tests/data/real/mosd/crop: views of one scene are
# not posed, so they only show K stays sane). Prints one Markdown row per setting.
# Usage: [FRAMES="4 6 8"] [NMS="2 4 6"] [GAMMAS="0.975 0.8"] scripts/sweep-iss.sh SIMULATED_DATASET OUT_DIR [K]
set -euo pipefail
cd "$(dirname "$0")/.."
data=$1 out=$2 k=${3:-30}
kt=${KEYTURN:-build/app/keyturn}
mkdir -p "$out"
# Each real cut at the identity pose (only its keypoint count is read).
for f in tests/data/real/mosd/crop/*.pcd; do echo "$PWD/$f 0 0 0 0 0 0 1"; done > "$out/real_cuts.txt"
field() { python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))["detectors"]["iss"]
print(" | ".join(f"{v:.3f}" for v in [j["keypoints"]] + j["relative"] + j["equal_k"]["relative"]))' "$1"; }
echo "| r_frame | r_nms | γ21 = γ32 | K native | rel@1 | rel@2 | rel@3 | rel@1 at K=$k | rel@2 at K=$k | rel@3 at K=$k | K on real cuts |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for frame in ${FRAMES:-4 6 8}; do
  for nms in ${NMS:-2 4 6}; do
    for gamma in ${GAMMAS:-0.975 0.8}; do
      flags=(--iss-frame "$frame" --iss-nms "$nms" --iss-gamma "$gamma" --detectors iss)
      "$kt" repeatability "$data" "${flags[@]}" --eps 1,2,3 --keypoints "$k" --out "$out/sim" --json > "$out/sim.json" 2> /dev/null
      "$kt" repeatability "$out/real_cuts.txt" "${flags[@]}" --no-filter --force --eps 1 --out "$out/real" --json \
        > "$out/real.json" 2> /dev/null
      real=$(python3 -c 'import json, sys; print(round(json.load(open(sys.argv[1]))["detectors"]["iss"]["keypoints"], 1))' \
        "$out/real.json")
      echo "| $frame | $nms | $gamma | $(field "$out/sim.json") | $real |"
    done
  done
done
