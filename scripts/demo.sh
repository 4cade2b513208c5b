#!/usr/bin/env bash
# The main job on simulated devices: set up, build, then `keyturn demo` —
# simulate a small dataset of shipped objects on the simulated rig (SR4000 via
# libmesasr-sim, turntable over Modbus, both through the real drivers), verify
# it, describe every view — and time the descriptor chain against PCL.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure-build.sh
KT=build/app/keyturn
OUT=${OUT:-out/demo}
"$KT" demo --out "$OUT"
"$KT" bench
