#!/usr/bin/env bash
# The wall times of docs/slurm.md: keyturn slurm's pipeline on a private single-node cluster
# (tests/slurm/cluster.sh, as root) with 1 and with 2 tasks of one CPU each, on a simulated
# dataset (4 objects, elevations 30 and 60, every 15°: 192 views). Prints each stage's span
# (first task's start to last task's end, whole seconds as Slurm records them), one task's
# peak memory and the load average before each run.
#   scripts/measure-slurm.sh [BUILD_DIR] [WORK_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
work=${2:-$(mktemp -d)}
KT=$build/app/keyturn
source "$root/tests/slurm/cluster.sh"
mkdir -p "$work"
cluster_tmp=$(mktemp -d /tmp/keyturn-slurm.XXXXXX)
trap 'cluster_stop; rm -rf "$cluster_tmp"' EXIT
cluster_start "$cluster_tmp" || { echo "measure-slurm: Slurm did not start: $cluster_error" >&2; exit 1; }

rm -rf "$work/ds"
"$KT" simulate --objects "$root/tests/data/objects-two-categories.csv" --elevations 30,60 --step 15 -q --out "$work/ds"
ev="--features 'kpd2 kpd2+gkpd2 esf' --classifier xgboost,mlp --protocol kfold10,leave-elevation,leave-instance"

# A stage's span in seconds: the earliest StartTime to the latest EndTime of its tasks.
span() {
  scontrol -o show job "$1" | sed -n 's/.*StartTime=\([^ ]*\) EndTime=\([^ ]*\) .*/\1 \2/p' |
    while read -r s e; do echo "$(date -d "$s" +%s) $(date -d "$e" +%s)"; done |
    awk 'NR == 1 || $1 < a {a = $1} NR == 1 || $2 > b {b = $2} END {print b - a}'
}

for tasks in 1 2; do
  rm -rf "$work/ds/.keyturn" "$work/jobs-$tasks"
  "$KT" slurm "$work/ds" --tasks "$tasks" --cpus 1 --out "$work/jobs-$tasks" --evaluate "$ev" > /dev/null
  echo "tasks $tasks: load average $(cut -d' ' -f1-3 /proc/loadavg)"
  read -r describe merge evaluate report <<< "$(bash "$work/jobs-$tasks/submit.sh")"
  cluster_idle 3600
  for stage in describe merge evaluate report; do
    id=${!stage}
    echo "  $stage: $(span "$id") s, $(cluster_job_state "$id" | sort -u | tr '\n' ' ')"
  done
done

# One describe task's and one evaluate task's peak memory (1 CPU, half of the views or trainings).
rm -rf "$work/ds/.keyturn"
/usr/bin/time -f "describe --shard 1/2: %M kB peak, %e s" "$KT" describe "$work/ds" --shard 1/2 --jobs 1 -q
"$KT" describe "$work/ds" --cache --jobs 2 -q
eval "/usr/bin/time -f 'evaluate --shard 1/2: %M kB peak, %e s' '$KT' evaluate '$work/ds' $ev --shard 1/2 --jobs 1 -q --out '$work/mem'"
