#!/usr/bin/env bash
# Sim-to-real (docs/results.md "Sim-to-real"): category models (box or cylinder) trained only on
# simulated views of the shipped YCB boxes (cracker, sugar) and cans (master chef, tomato soup),
# through the simulated SR4000 (176 × 144 ToF) and the simulated OpenNI2 camera (640 × 480 structured
# light), classify the 38 real Kinect objects of tests/data/real/mosd/crop (mOSD: scenes learn0–16 boxes,
# 33–44 cylindric objects). Prints the real crops' accuracy per camera, feature set and classifier.
# About 15 minutes on 2 cores.
# usage: scripts/sim-to-real.sh [OUT_DIR] [FEATURE_SET ...]
#        (default out/sim-to-real; kpd2 kpa3 kpd2+kpa3 kpa3+s_kpd2 kpa3+s_kpd2+size kpd2+gkpd2 esf vfh d2)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
KT=$root/build/app/keyturn
out=${1:-out/sim-to-real}
shift || true
sets=("$@")
[ ${#sets[@]} -gt 0 ] || sets=(kpd2 kpa3 kpd2+kpa3 kpa3+s_kpd2 kpa3+s_kpd2+size kpd2+gkpd2 esf vfh d2)
mkdir -p "$out"
export LD_LIBRARY_PATH=$root/build/lib/keyturn/openni2${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
objects=(box:ycb_003_cracker_box box:ycb_004_sugar_box cylinder:ycb_002_master_chef_can cylinder:ycb_005_tomato_soup_can)
for camera in sim openni2; do
  [ -f "$out/$camera/.done" ] && continue
  rm -rf "$out/$camera"
  for o in "${objects[@]}"; do
    category=${o%%:*}; instance=${o#*:}
    mesh=$(ls "$root"/data/objects/*__"$instance".ply)
    for elevation in 30 45 60; do
      "$KT" capture --camera $camera --pose sim --class $category --instance "$instance" --mesh "$mesh" --step 15 \
        --elevation $elevation --settle 0.01 -q --out "$out/$camera" 2>> "$out/capture.log"
    done
    echo "sim-to-real: $camera captured $instance" >&2
  done
  touch "$out/$camera/.done"
done
for features in "${sets[@]}"; do
  for camera in sim openni2; do
    case $features in kpset*) classifiers=(setnet) ;; *) classifiers=(xgboost mlp) ;; esac
    for classifier in "${classifiers[@]}"; do
      model="$out/model-$camera-$classifier-$features"
      "$KT" train "$out/$camera" --label category --features "$features" --classifier $classifier --out "$model" -q
      "$KT" classify "$model" "$root"/tests/data/real/mosd/crop/*.pcd --json -q > "$out/$features-$camera-$classifier.json"
    done
  done
done
python3 - "$out" "${sets[@]}" <<'PY'
import json, os, re, sys
out, sets = sys.argv[1], sys.argv[2:]
def truth(path):  # mOSD's scene ranges: learn0–16 boxes, 33–44 cylindric objects
    return "box" if int(re.match(r"learn(\d+)_", os.path.basename(path)).group(1)) <= 16 else "cylinder"
print("| features | SR4000 · xgboost | SR4000 · network | OpenNI2 · xgboost | OpenNI2 · network |")
print("|---|---:|---:|---:|---:|")
for f in sets:
    cells = []
    for cam in ("sim", "openni2"):
        for cl in (("-", "setnet") if f.startswith("kpset") else ("xgboost", "mlp")):
            if cl == "-":
                cells.append("–")
                continue
            views = json.load(open(f"{out}/{f}-{cam}-{cl}.json"))
            right = sum(truth(v["view"]) == v["best"] for v in views)
            cells.append(f"{100 * right / len(views):.1f}" + (" (setnet)" if cl == "setnet" else ""))
    print(f"| {f} | " + " | ".join(cells) + " |")
PY
