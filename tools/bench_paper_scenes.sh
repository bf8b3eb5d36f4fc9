#!/usr/bin/env bash
# Runs criticality-bench on the paper's scenes (S1, S2) with 6 and 5 profiles for each backend
# and prints a markdown table (median and min over --repeat runs). All variants run in one
# invocation, one after the other, so that their figures are comparable.
# Usage: tools/bench_paper_scenes.sh [repeat (default 5)] [backends (default "reference cpu")]
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
backends=${2:-reference cpu}
bench=${BUILD_DIR:-build}/estimator/bench/criticality-bench
[ -x "$bench" ] || { echo "bench_paper_scenes: $bench not built; run tools/setup.sh" >&2; exit 1; }
echo "| scene | profiles | backend | threads | pose combinations | p_collision | median ms | min ms | trajectories ms | collisions ms | risk ms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for scene in S1 S2; do
  for profiles in 6 5; do
    for backend in $backends; do
      json=$("$bench" --scene "$scene" --profiles "$profiles" --backend "$backend" \
               --repeat "$repeat" --warmup 1 --json | tail -n 1)
      python3 - "$json" <<'PY'
import json, sys
j = json.loads(sys.argv[1])
print(f"| {j['scene']} | {j['profiles']} | {j['backend']} | {j['threads']} | {j['pose_combinations']:,} "
      f"| {j['p_collision']:.4f} | {j['median_ms']:.1f} | {j['min_ms']:.1f} | {j['median_trajectory_ms']:.1f} "
      f"| {j['median_collision_ms']:.1f} | {j['median_risk_ms']:.1f} |")
PY
    done
  done
done
