#!/usr/bin/env bash
# The main job on simulated devices: set up, build, render simulated SR4000
# views of shipped objects on the turntable, describe them, and time the chain.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure-build.sh
KT=build/app/keyturn
OUT=${OUT:-out/demo}
mkdir -p "$OUT/views"
# The simulated SR4000 through the real driver (libmesasr-sim), median of 5 frames.
"$KT" grab --camera sim --frames 5 --out "$OUT/grab/mug.pcd"
for obj in mug__ycb_025_mug can__ycb_005_tomato_soup_can bottle__ycb_006_mustard_bottle box__ycb_004_sugar_box; do
  "$KT" render "data/objects/$obj.ply" --angles 0,45,90,135 --out "$OUT/views/${obj}_{angle}.pcd"
done
"$KT" describe "$OUT/views" --out "$OUT/features.csv"
echo
echo "Keypoint count K per view (column 3 of $OUT/features.csv):"
cut -d, -f1-4 "$OUT/features.csv" | tr , "\t"
"$KT" bench "$OUT/views/mug__ycb_025_mug_000.pcd"
