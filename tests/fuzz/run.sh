#!/usr/bin/env bash
# Fuzz runs of every loader of outside data, and of the chain and the models that meet what the
# loaders let through, from the committed seed corpus. By default short and reproducible (fixed
# seed and run count, as CI runs them);
# FUZZ_SECONDS gives each harness a time budget instead. A crash leaves its input
# in the work folder (crash-*) and fails the run: turn it into a regression test.
# usage: tests/fuzz/run.sh BUILD_DIR [RUNS]
#   RUNS          runs per harness (default 4000; unlimited when FUZZ_SECONDS is set); fuzz_chain
#                 and fuzz_model run a quarter of it (each run describes or classifies a view:
#                 10–20 ms under ASan, against well under 1 ms for a loader), fuzz_oni a tenth
#                 (a recording the check passes is played by OpenNI2: ~30 runs/s)
#   FUZZ_SECONDS  time budget per harness, s (libFuzzer stops at RUNS or this, first)
#   FUZZ_SEED     libFuzzer seed (default 1)
#   FUZZ_MAX_LEN  longest input, bytes (default 16384)
#   FUZZ_TARGETS  harnesses to run (default: all eight)
#   FUZZ_WORK     keep the work folder here (the corpus each run grew, logs, crashes)
set -u
build=$(cd "${1:?hardening build folder}" && pwd)
# The fuzzers sit a folder deeper than the programs: show them the build's plugins.
export KEYTURN_PLUGIN_PATH="$build/lib/keyturn"
if [ -n "${FUZZ_SECONDS:-}" ]; then runs=${2:--1}; else runs=${2:-4000}; fi
here=$(cd "$(dirname "$0")" && pwd)
# System libraries' memory kept to exit (fuzz_oni: OpenNI2's libOniFile) is suppressed by name, as in
# scripts/test-hardening.sh, when this runs on its own.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/../sanitizers/lsan.supp}
if [ -n "${FUZZ_WORK:-}" ]; then out=$FUZZ_WORK; mkdir -p "$out"; else out=$(mktemp -d); fi
out=$(cd "$out" && pwd)
# The harnesses' own scratch (fuzz_file.h) goes to the work folder too: after a crash it stays with the input.
mkdir -p "$out/tmp"
export TMPDIR=$out/tmp
# A work folder of our own (no FUZZ_WORK) goes when the run passes: kept with its logs and crash inputs when not.
keep_work() { [ -n "${FUZZ_WORK:-}" ] || [ "${fail:-0}" -ne 0 ]; }
trap 'keep_work || rm -rf "$out"' EXIT
budget=()
if [ -n "${FUZZ_SECONDS:-}" ]; then budget=(-max_total_time="$FUZZ_SECONDS"); fi
pass=0; fail=0
for target in ${FUZZ_TARGETS:-point_cloud mesh dataset configs learning chain model oni}; do
  bin="$build/tests/fuzz/fuzz_$target"
  corpus="$out/$target"
  mkdir -p "$corpus"
  cp "$here/corpus/$target"/* "$corpus/"
  target_runs=$runs
  case $target in
    chain|model) [ "$runs" -gt 0 ] && target_runs=$(( (runs + 3) / 4 )) ;;
    oni) [ "$runs" -gt 0 ] && target_runs=$(( (runs + 9) / 10 )) ;;
  esac
  if (cd "$out" && "$bin" -seed="${FUZZ_SEED:-1}" -runs="$target_runs" "${budget[@]}" -max_len="${FUZZ_MAX_LEN:-16384}" \
        -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 -artifact_prefix="$out/$target-" "$corpus" \
        > "$out/$target.log" 2>&1); then
    pass=$((pass + 1))
    done_line=$(grep -oE 'Done [0-9]+ runs in [0-9]+ second' "$out/$target.log" | tail -1)
    echo "fuzz_$target: $(grep -oE 'cov: [0-9]+' "$out/$target.log" | tail -1)," \
      "${done_line:+$(echo "$done_line" | awk '{print $2 " runs in " $5 " s"}')}, no crash"
  else
    fail=$((fail + 1))
    echo "FAILED: fuzz_$target (log and crash input in $out):"
    grep -E 'ERROR|SUMMARY|runtime error|crash-|Test unit written' "$out/$target.log" | head -8
  fi
done
echo "$pass passed, $fail failed"
test "$fail" -eq 0
