#!/usr/bin/env bash
# Soak test of the simulated rig: a long capture with random faults in the
# camera and the turntable, the capture process killed with SIGKILL at random
# moments and resumed, until every view is taken. At the end the dataset must
# verify and hold every view exactly once, at its pose. Prints the counts.
# usage: KEYTURN=path/to/keyturn soak.sh WORKDIR [VIEWS] [FAULT_RATE] [SEED]
set -u
source "$(dirname "$0")/../cli/lib.sh"
views=${2:-3240}
rate=${3:-0.02}
seed=${4:-1}
RANDOM=$seed
step=1
per=$((360 / step))
instances=$(( (views + per - 1) / per ))
expected=$((instances * per))
ds="$work/ds"
kills=0; error_exits=0; runs=0; left=0
start=$(date +%s)
for i in $(seq 1 "$instances"); do
  while :; do
    runs=$((runs + 1))
    "$KT" capture --class soak --instance "i$i" --step "$step" --settle 0.002 --sim-faults "$rate" \
        --seed "$((seed + i))" -q --out "$ds" >> "$work/stdout.log" 2>> "$work/run$runs.err" &
    pid=$!
    # Kill it at a random moment in a third of the runs (0.2–2.2 s in).
    if [ $((RANDOM % 3)) -eq 0 ]; then
      sleep "0.$((RANDOM % 10))"; sleep "$((RANDOM % 2))"
      if kill -0 "$pid" 2> /dev/null; then
        kill -9 "$pid"; wait "$pid" 2> /dev/null; kills=$((kills + 1))
        # Temporaries the kill left mid-write (the next run must remove them: verify checks at the end).
        left=$((left + $(find "$ds" -path "$ds/.sim" -prune -o -type f -name '*.tmp*' -print | wc -l)))
        continue
      fi
    fi
    wait "$pid"; rc=$?
    [ "$rc" -eq 0 ] && break
    error_exits=$((error_exits + 1))   # a documented error (e.g. retries exhausted): resume
  done
done
secs=$(( $(date +%s) - start ))
cam_retries=$(cat "$work"/run*.err | grep -c "^keyturn: camera: " || true)
table_retries=$(cat "$work"/run*.err | grep -c "^keyturn: turntable: " || true)
table_faults=$(cat "$work"/run*.err | sed -nE 's/.* ([0-9]+) faults injected/\1/p' | awk '{s+=$1} END {print s+0}')
rows=$(( $(wc -l < "$ds/manifest.csv") - 1 ))
unique=$(tail -n +2 "$ds/manifest.csv" | cut -d, -f2,5 | sort -u | wc -l)
off_pose=$(tail -n +2 "$ds/manifest.csv" | awk -F, '{d=$5-$6; if (d<0) d=-d; if (d>0.11 && d<359.89) n++} END {print n+0}')
"$KT" verify "$ds" > "$work/verify.txt"; verify_rc=$?

echo "views expected        $expected"
echo "views in the manifest $rows (unique $unique)"
echo "views off their pose  $off_pose"
echo "capture runs          $runs ($kills killed with SIGKILL, $error_exits ended by an error and resumed)"
echo "temporaries left      $left by the kills (removed by the resumes)"
echo "camera retries        $cam_retries (logged reopenings)"
echo "turntable retries     $table_retries (logged); faults injected in completed runs: $table_faults"
echo "verify                $(tail -1 "$work/verify.txt")"
echo "time                  ${secs} s"
check "every view exactly once" test "$rows" -eq "$expected" -a "$unique" -eq "$expected"
check "every view at its pose" test "$off_pose" -eq 0
check "verify passes" test "$verify_rc" -eq 0
check "faults were injected" test "$((cam_retries + table_retries))" -gt 0
finish
