#!/usr/bin/env bash
# The driver's benchmark on the city-like network (bench/city): plain `sumo` against
# sumo-criticality on the same configuration, back to back, each RUNS times (medians of wall
# time; CPU time, user + system over all threads, beside it: it is less disturbed by other
# processes on a shared machine).
#   A. one ego (car22, in the network from 13.2 s until it arrives at 416.6 s): plain sumo to
#      the same end time vs the driver with the full hypothesis set and cheaper settings, the
#      full set also with --no-pipeline (each step estimated before SUMO makes the next);
#   B. every vehicle an ego (--all-vehicles) over 20 s of the busiest phase (300-320 s, about
#      360 vehicles, from a SUMO state saved at 300 s): ego estimates per second of wall time,
#      the share answered by the exact reach shortcut.
# Usage: bench/driver_bench.sh [RUNS] [BUILD_DIR]    Prints markdown tables.
set -euo pipefail
runs=${1:-3}
build=$(cd "${2:-build}" && pwd)
cd "$(dirname "$0")/city"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
driver=$build/plugin/sumo-criticality
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sumo_opts=(--no-step-log --xml-validation never)  # as the driver runs SUMO

median() { sort -g | awk '{a[NR]=$0} END {print a[int((NR+1)/2)]}'; }
plain() {  # plain ARGS...: "wall cpu" seconds of plain sumo
  /usr/bin/time -f "%e %U %S" sumo -c city.sumocfg "${sumo_opts[@]}" "$@" 2>&1 >/dev/null |
    tail -n 1 | awk '{print $1, $2 + $3}'
}
drive() {  # drive ARGS...: the driver's summary line
  rm -f "$work/run.sqlite"
  "$driver" -c city.sumocfg --output "$work/run.sqlite" --no-progress "$@" | tail -n 1
}
field() { python3 -c "import json,sys; d=json.loads(sys.argv[1]); print(eval(sys.argv[2], dict(d)))" "$1" "$2"; }
ratio() { python3 -c "print(round($1 / $2, 1))"; }
stages="'/'.join('%.1f' % time_s[k] for k in ['sumo','observe','scenes','estimate','act','record','estimate_wait'])"

full="--profiles 6 --own-lane-samples 3 --neighbour-lane-samples 2"
cheap="--profiles 3 --own-lane-samples 1 --neighbour-lane-samples 1"
cheaper="$cheap --step 0.05"

echo "## A. One ego (car22, 13.2-416.6 s), $runs runs, median by wall time"
echo
echo "| run | wall s | CPU s | x plain (wall) | x plain (CPU) | estimates | shortcut share | estimator ms | stages s: sumo/observe/scenes/estimate/act/record/wait | max RSS MB |"
echo "|---|---|---|---|---|---|---|---|---|---|"
read -r pw pc < <(for r in $(seq "$runs"); do plain --end 416.7; done | median)
echo "| plain sumo --end 416.7 | $pw | $pc | 1.0 | 1.0 | | | | | |"
for setting in "full:$full --threads 2" "full, not pipelined:$full --threads 2 --no-pipeline" \
               "full, 1 thread:$full --threads 1" \
               "full, 1 thread, not pipelined:$full --threads 1 --no-pipeline" \
               "cheap:$cheap --threads 1" "cheaper:$cheaper --threads 1"; do
  name=${setting%%:*} args=${setting#*:}
  for r in $(seq "$runs"); do drive --ego car22 $args; done > "$work/one.txt"
  w=$(while read -r l; do field "$l" wall_s; done < "$work/one.txt" | median)
  l=$(grep "\"wall_s\":$w," "$work/one.txt" | head -n 1)  # the median run's summary
  c=$(field "$l" "round(cpu_s, 2)")
  echo "| $name (\`$args\`) | $w | $c | $(ratio "$w" "$pw") | $(ratio "$c" "$pc") |" \
       "$(field "$l" estimates) | $(field "$l" "round(shortcut_estimates / estimates, 3)") |" \
       "$(field "$l" "round(estimator_ms_mean, 2)") | $(field "$l" "$stages") |" \
       "$(field "$l" "round(max_rss_mb)") |"
done

echo
echo "## B. Every vehicle an ego, 300-320 s (state saved at 300 s), $runs runs, median by wall time"
echo
sumo -c city.sumocfg "${sumo_opts[@]}" --end 300.1 --save-state.times 300 \
  --save-state.files "$work/state300.xml" >/dev/null 2>&1
state=(--load-state "$work/state300.xml" --begin 300 --end 320)
echo "| run | wall s | CPU s | x plain (wall) | estimates | estimates/s | shortcut share | objects out of reach / estimate | stages s: sumo/observe/scenes/estimate/act/record/wait | max RSS MB |"
echo "|---|---|---|---|---|---|---|---|---|---|"
read -r pw pc < <(for r in $(seq "$runs"); do plain "${state[@]}"; done | median)
echo "| plain sumo | $pw | $pc | 1.0 | | | | | | |"
for setting in "full:$full" "full, not pipelined:$full --no-pipeline" "cheap:$cheap" \
               "cheaper:$cheaper"; do
  name=${setting%%:*} args=${setting#*:}
  for r in $(seq "$runs"); do drive --all-vehicles $args -- "${state[@]}"; done > "$work/all.txt"
  w=$(while read -r l; do field "$l" wall_s; done < "$work/all.txt" | median)
  l=$(grep "\"wall_s\":$w," "$work/all.txt" | head -n 1)
  echo "| $name (\`$args\`) | $w | $(field "$l" "round(cpu_s, 2)") | $(ratio "$w" "$pw") |" \
       "$(field "$l" estimates) | $(field "$l" "round(estimates_per_s)") |" \
       "$(field "$l" "round(shortcut_estimates / estimates, 3)") |" \
       "$(field "$l" "round(objects_out_of_reach / estimates, 2)") | $(field "$l" "$stages") |" \
       "$(field "$l" "round(max_rss_mb)") |"
done
