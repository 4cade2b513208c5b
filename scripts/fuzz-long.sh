#!/usr/bin/env bash
# The long fuzz pass: every harness for minutes instead of CI's 4,000 runs, one
# at a time, then what the run reached merged into the committed corpus, minimised
# (libFuzzer -merge=1: a smallest set of inputs with all the coverage).
# Not part of CI; run it before a stop that changes a loader of outside data and
# record the figures in docs/reliability.md. Needs the hardening build
# (scripts/test-hardening.sh makes build-hardening/).
# usage: scripts/fuzz-long.sh [SECONDS_PER_HARNESS]   (default 300)
#   FUZZ_SEED (default: from the clock, printed), FUZZ_TARGETS, FUZZ_MAX_LEN as for tests/fuzz/run.sh;
#   HARDENING_BUILD_DIR (default build-hardening); FUZZ_WORK (default: a new temporary folder)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
build=${HARDENING_BUILD_DIR:-build-hardening}
export KEYTURN_PLUGIN_PATH="$(pwd)/$build/lib/keyturn"  # the fuzzers sit a folder deeper than the programs
seed=${FUZZ_SEED:-$(date +%s)}
work=${FUZZ_WORK:-$(mktemp -d)}
mkdir -p "$work"
corpus=$(pwd)/tests/fuzz/corpus
[ -x "$build/tests/fuzz/fuzz_mesh" ] || { echo "fuzz-long: no fuzzers in $build (run scripts/test-hardening.sh)" >&2; exit 1; }

size() { find "$1" -type f -printf '%s\n' | awk '{ n++; s += $1 } END { printf "%d files, %d bytes", n, s }'; }

echo "fuzz-long: $seconds s per harness, seed $seed, commit $(git rev-parse --short HEAD), work $work"
failed=0
for target in ${FUZZ_TARGETS:-point_cloud mesh dataset configs learning chain model oni}; do
  before=$(size "$corpus/$target")
  rc=0
  FUZZ_SECONDS=$seconds FUZZ_SEED=$seed FUZZ_TARGETS=$target FUZZ_WORK=$work \
    bash tests/fuzz/run.sh "$build" > "$work/$target.summary" || rc=$?
  grep -v 'passed, .* failed$' "$work/$target.summary" || true
  if [ "$rc" -ne 0 ]; then
    failed=$((failed + 1))
    echo "fuzz-long: fuzz_$target found a failure (log and inputs: $work/$target*); nothing merged"
    continue
  fi
  runs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$work/$target.log" | awk '{print $2}')
  # Minimise: the named seeds (formats, regressions) stay; of the rest (SHA-1 names, found
  # by fuzzing) merge keeps a smallest set that reaches every feature the committed corpus
  # and this run reached together. The run's folder holds both.
  min=$work/$target.min
  rm -rf "$min"; mkdir -p "$min"
  find "$corpus/$target" -type f ! -regex '.*/[0-9a-f]\{40\}' -exec cp {} "$min/" \;
  "$build/tests/fuzz/fuzz_$target" -merge=1 -max_len="${FUZZ_MAX_LEN:-16384}" -rss_limit_mb=2048 -timeout=20 \
    "$min" "$work/$target" > "$work/$target.merge.log" 2>&1 ||
    { failed=$((failed + 1)); echo "fuzz-long: merging fuzz_$target failed (log: $work/$target.merge.log)"; continue; }
  find "$corpus/$target" -type f -regex '.*/[0-9a-f]\{40\}' -delete
  cp "$min"/* "$corpus/$target/"
  echo "fuzz-long: fuzz_$target: ${runs:-?} runs, $(grep -oE 'cov: [0-9]+' "$work/$target.log" | tail -1);" \
    "committed corpus $before -> $(size "$corpus/$target")"
done
echo "fuzz-long: $failed harness(es) with findings; corpus now $(size "$corpus")"
test "$failed" -eq 0
