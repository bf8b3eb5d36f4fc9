#!/usr/bin/env bash
# Builds (through tools/setup.sh) and runs the test suites with ctest.
# Usage: tools/test.sh [ctest arguments...]   e.g. tools/test.sh -L unit, tools/test.sh -LE slow
set -euo pipefail
cd "$(dirname "$0")/.."
./tools/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
cd "$BUILD_DIR"
ctest --output-on-failure -j "${JOBS:-$(nproc)}" "$@"
