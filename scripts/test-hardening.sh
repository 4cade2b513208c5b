#!/usr/bin/env bash
# The hardening run: a clang build with AddressSanitizer + UndefinedBehaviorSanitizer
# (leak checking on), the core, driver, rig, simulator, learning and studio tests in it, then short
# reproducible libFuzzer runs of every loader of outside data, the chain and the models. Part of
# scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/toolchain.sh
B=${HARDENING_BUILD_DIR:-build-hardening}
# LeakSanitizer matches tests/sanitizers/lsan.supp by function name: without a symbolizer nothing
# matches and system libraries' leaks fail tests that are sound. Said once, before the long build.
if [ ! -x "$KEYTURN_SYMBOLIZER" ]; then
  echo "test-hardening: no $KEYTURN_SYMBOLIZER (package llvm-$KEYTURN_CLANG_VERSION; scripts/install-deps.sh installs it): the leak suppressions cannot match" >&2
  exit 1
fi
if [ ! -f "$B/build.ninja" ]; then
  CC=$KEYTURN_CC CXX=$KEYTURN_CXX cmake -S . -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKEYTURN_HARDENING=ON
fi
cmake --build "$B" --parallel "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp
export ASAN_SYMBOLIZER_PATH=$KEYTURN_SYMBOLIZER
# umockdev's preload library cannot come before ASan's runtime, and the CLI, soak, Slurm and docs
# scripts exercise the same code through the tool (the docs examples, ~27 min under the sanitizers,
# time out there): those run in the normal build. So does studio.chain, the CLI's chain (train,
# capture, Poisson, enroll) behind the studio's buttons: its first sanitizer run passed 600 s unfinished.
ctest --test-dir "$B" --output-on-failure --parallel "$(nproc)" -E '^(cli\.|soak\.|slurm\.|docs\.examples|drivers\.usb|studio\.chain)'
bash tests/fuzz/run.sh "$B" "${FUZZ_RUNS:-4000}"
