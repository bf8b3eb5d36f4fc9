#!/usr/bin/env bash
# The main job: run SUMO with the criticality estimator on the default scenario (a rear-end
# collision, scenarios/rear_end) with --act warn, then print what happened: the run's JSON
# summary, its warning episodes and SUMO's collisions with their anticipation times.
# Usage: tools/demo.sh [scenario name] [further sumo-criticality options]
set -euo pipefail
cd "$(dirname "$0")/.."
scenario=${1:-rear_end}
[ $# -gt 0 ] && shift
echo "demo: building (the first run installs packages and compiles for a few minutes)" >&2
./tools/setup.sh >&2
mkdir -p out
db="out/demo-$scenario-$(date +%Y%m%d-%H%M%S).sqlite"
echo "demo: scenario $scenario -> $db" >&2
build/plugin/sumo-criticality --config "scenarios/$scenario/scenario.cfg" --act warn --output "$db" "$@"
echo
echo "Warning episodes:"
sqlite3 -column -header "$db" "select ego, start_s, end_s, round(peak_p, 3) as peak_p from warnings"
echo
echo "SUMO's collisions:"
sqlite3 -column -header "$db" "select time_s, collider, victim, type, round(collider_speed_mps, 1) as collider_mps, anticipation_s from collisions"
echo
echo "Criticality of the ego over the last 2.5 s before its first collision:"
sqlite3 -column -header "$db" "select s.time_s, round(s.p_collision, 3) as p_collision, s.objects from steps s,
  (select min(time_s) as t from collisions) c where s.time_s > c.t - 2.5 and s.time_s <= c.t and
  cast(round(s.time_s * 10) as int) % 2 = 0"
