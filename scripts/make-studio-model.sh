#!/usr/bin/env bash
# Rebuilds the studio's built-in model (data/models/sim-objects): the simulated
# SR4K-D style dataset of the 15 shipped objects (elevations 30/45/60, every 5°),
# then XGBoost on KPD2+KPA3 with instance labels, open-set answers (knn-relative, calibrated for 5 %
# false accepts) and pose references for fusion. About 8 minutes on 2 cores.
# Usage: scripts/make-studio-model.sh [BUILD] [DATASET]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
D=${2:-datasets/sr4kd-sim}
"$B/app/keyturn" simulate --objects data/objects/objects.csv --elevations 30,45,60 --step 5 --out "$D"
"$B/app/keyturn" train "$D" --features kpd2+kpa3 --classifier xgboost --label instance --open-set knn-relative \
  --false-accept 0.05 --out data/models/sim-objects
