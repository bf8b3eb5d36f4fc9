#!/usr/bin/env bash
# The main job, for now: estimate the criticality of the paper's scene S1 (ego + 3 other
# vehicles on a straight 3-lane road) and print a readable summary.
set -euo pipefail
cd "$(dirname "$0")/.."
echo "demo: building (the first run installs packages and compiles for a few minutes)" >&2
./tools/setup.sh >&2
exec "${BUILD_DIR:-build}/estimator/bench/criticality-bench" --scene S1 --report --repeat 3 "$@"
