#!/usr/bin/env bash
# Builds (through tools/setup.sh) and runs the test suites with ctest.
# Usage: tools/test.sh [ctest arguments...]
#   no arguments: the quick run, ctest -LE slow (what CI runs; well under 20 minutes on 2 cores)
#   TEST_ALL=1 tools/test.sh: every test, the slow ones included (the whole scenario suite, the
#   city-like runs); tools/test.sh -L slow: only the slow ones; tools/test.sh -L unit: the fast
#   suites
set -euo pipefail
cd "$(dirname "$0")/.."
./tools/setup.sh
BUILD_DIR=${BUILD_DIR:-build}
cd "$BUILD_DIR"
if [ $# -eq 0 ] && [ "${TEST_ALL:-0}" != 1 ]; then
  set -- -LE slow
fi
ctest --output-on-failure -j "${JOBS:-$(nproc)}" "$@"
