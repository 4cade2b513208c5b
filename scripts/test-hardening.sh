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
# intercept_tls_get_addr=0: clang 14's ASan misreads glibc 2.36's dynamic TLS, and at exit LeakSanitizer
# scanned the bogus ranges of every thread that had touched a dlopen'ed plugin's TLS. Open3D's Poisson
# starts 2,298 threads (std::async), so one reconstruction test grew to 24 GB and 115 s after it had
# passed in 10 s (OOM-killed on this 24 GB machine); without the interception: 10.6 s, 0.54 GB.
# docs/reliability.md, "Sanitizer build".
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp
export ASAN_SYMBOLIZER_PATH=$KEYTURN_SYMBOLIZER
# umockdev's preload library cannot come before ASan's runtime, and the CLI, soak, Slurm and docs
# scripts exercise the same code through the tool (the docs examples, ~27 min under the sanitizers,
# time out there): those run in the normal build. studio.chain (train, capture, Poisson, enroll behind
# the studio's buttons) runs here since its OpenMP threads wait passively: 87 s alone (its first
# sanitizer run had passed 600 s unfinished).
ctest --test-dir "$B" --output-on-failure --parallel "$(nproc)" -E '^(cli\.|soak\.|slurm\.|docs\.examples|drivers\.usb)'
bash tests/fuzz/run.sh "$B" "${FUZZ_RUNS:-4000}"
