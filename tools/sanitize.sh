#!/usr/bin/env bash
# Builds the `sanitizers` preset (AddressSanitizer + UndefinedBehaviorSanitizer, no CUDA) into
# build-asan/ and runs every test there. Leaks inside SUMO's third-party libraries are
# suppressed (tests/lsan.supp); any finding in our code fails the run.
# Usage: tools/sanitize.sh [ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
./tools/setup.sh >/dev/null   # the packages
cmake --preset sanitizers >/dev/null
cmake --build build-asan -j "${JOBS:-$(nproc)}"
cd build-asan
LSAN_OPTIONS=suppressions=$PWD/../tests/lsan.supp:print_suppressions=0 \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "${JOBS:-$(nproc)}" -LE cuda "$@"
