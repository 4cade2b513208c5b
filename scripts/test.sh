#!/usr/bin/env bash
# Set up, build and run the whole test suite: unit, command-line and soak tests,
# then the hardening run (sanitizers and fuzzers, scripts/test-hardening.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure-build.sh
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure --parallel "$(nproc)"
bash scripts/test-hardening.sh
