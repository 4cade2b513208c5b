#!/usr/bin/env bash
# Live recognition rates of keyturn-studio on the simulated rig, under Xvfb:
# one run per object (and per model), each 20 s after a 3 s warm-up; prints
# one JSON line per run (docs/benchmarks.md). Usage: scripts/measure-studio.sh [BUILD] [MODEL…]
# OBJECTS=all measures every shipped object (data/objects/objects.csv), not only the five below.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
shift || true
models=("$@")
[ ${#models[@]} -eq 0 ] && models=(data/models/sim-objects)
settings=$(mktemp --suffix=.ini)
trap 'rm -f "$settings"' EXIT
for model in "${models[@]}"; do
  objects=(ycb_025_mug ycb_035_power_drill ycb_003_cracker_box utah_teapot ycb_019_pitcher_base)
  [ "${OBJECTS:-}" = all ] && mapfile -t objects < <(tail -n +2 data/objects/objects.csv | cut -d, -f2)
  for object in "${objects[@]}"; do
    for paths in "" --geodesic-paths; do
      rm -f "$settings"
      line=$(xvfb-run -a -s "-screen 0 1920x1080x24" "$B/app/keyturn-studio" --simulated --object "$object" \
               --model "$model" --settings "$settings" $paths --measure "${SECONDS_PER_RUN:-20}" 2>/dev/null | tail -1)
      echo "{\"model\": \"$(basename "$model")\", \"object\": \"$object\", \"paths\": $([ -n "$paths" ] && echo true || echo false), ${line#\{}"
    done
  done
done
