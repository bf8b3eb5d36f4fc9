#!/usr/bin/env bash
# criticality-bench as a user runs it: the paper's pose-combination counts in the JSON line,
# and a one-line error with a non-zero exit for bad input.
set -u
bench=$1
fail=0
check() {  # check DESCRIPTION CONDITION...
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; fail=1; fi
}

for spec in "S1 6 25930800" "S1 5 18007500" "S2 6 86436000" "S2 5 60025000"; do
  set -- $spec
  json=$("$bench" --scene "$1" --profiles "$2" --repeat 1 --warmup 0 --json | tail -n 1)
  check "$1 with $2 profiles: pose_combinations $3" grep -q "\"pose_combinations\":$3," <<<"$json"
  for key in scene backend profiles ego_trajectories co_trajectories p_collision median_ms min_ms; do
    check "$1/$2 JSON has $key" grep -q "\"$key\":" <<<"$json"
  done
done
json=$("$bench" --scene S1 --backend reference --repeat 1 --warmup 0 --json | tail -n 1)
check "reference backend named in JSON" grep -q '"backend":"reference"' <<<"$json"

# Presets and the discrimination benchmark.
json=$("$bench" --scene S1 --preset paper-literal --repeat 1 --warmup 0 --json | tail -n 1)
check "paper-literal S1 reproduces the first implementation's p_cra" \
  grep -q '"p_collision":0.10743262889816914,' <<<"$json"
out=$("$bench" --discrimination --json)
json=$(tail -n 1 <<<"$out")
check "--discrimination JSON names its preset" grep -q '"preset":"default"' <<<"$json"
for key in name critical ttc_s p_collision p_reference unavoidability best_escape; do
  check "--discrimination JSON has $key" grep -q "\"$key\":" <<<"$json"
done
check "--discrimination has a stopped-car family" grep -q '"name":"stopped-car-ttc-1.50"' <<<"$json"
check "--discrimination prints the margin" grep -q "margin" <<<"$out"
dir=$(mktemp -d)
"$bench" --discrimination --save-scenes "$dir" > /dev/null
check "--save-scenes writes replayable scene files" \
  "$bench" --scene-file "$dir/stopped-car-ttc-1.50.scene" --repeat 1 --warmup 0
rm -rf "$dir"
# --paths-json: every listed hypothesis has as many headings as positions (a picture draws the
# boxes, a trace reads how the body turns against its way).
dir=$(mktemp -d)
"$bench" --scene S1 --paths-json "$dir/p.json" --paths 2 > /dev/null
check "--paths-json gives x, y and yaw of each step" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
hs = d["most_probable"] + d["colliding"]
assert hs and all(len(h["x"]) == len(h["y"]) == len(h["yaw"]) == 100 for h in hs)
' "$dir/p.json"
rm -rf "$dir"
# --fleet: every scene file of a folder in one batch; its mean p_cra is the mean of the scenes
# estimated one by one.
data=$(cd "$(dirname "$0")/../data" && pwd)
json=$("$bench" --fleet "$data" --repeat 1 --warmup 0 --json | tail -n 1)
check "--fleet counts the folder's scene files" grep -q '"egos":4,' <<<"$json"
check "--fleet has the cpu row" grep -q '"backend":"cpu"' <<<"$json"
check "--fleet's cpu-unshared row agrees with cpu exactly" \
  grep -q '"backend":"cpu-unshared"[^}]*"max_dp_vs_cpu":0,' <<<"$json"
fleet_mean=$(sed 's/.*"backend":"cpu"[^}]*"mean_p_collision":\([^,}]*\).*/\1/' <<<"$json")
one_by_one=$(for f in "$data"/*.scene; do
  "$bench" --scene-file "$f" --repeat 1 --warmup 0 --json | tail -n 1 |
    sed 's/.*"p_collision":\([^,]*\),.*/\1/'
done | awk '{s += $1} END {printf "%.12e", s / NR}')
check "--fleet mean p_cra ($fleet_mean) is the scenes' one by one ($one_by_one)" \
  awk -v a="$fleet_mean" -v b="$one_by_one" 'BEGIN {d = a - b; exit !(d < 1e-12 && d > -1e-12 && b > 0)}'
# --experiment: a scene recorded with an ego on its way (a violator turning left across the
# car it hit 1.3 s later; generated violations network gv8, 0.1 s steps) replays under the
# driver's experiment of that name; without it the ego is steered, and p differs.
way_scene="$data/ego_way/violator_turning_left.scene"
p_of() { "$bench" --scene-file "$way_scene" --repeat 1 --warmup 0 --json "$@" | tail -n 1 |
  sed 's/.*"p_collision":\([^,]*\),.*/\1/'; }
steered=$(p_of); on_way=$(p_of --experiment ego-on-way)
tree=$(p_of --experiment ego-on-way --experiment way-lateral-paths)
check "--experiment ego-on-way changes p ($steered -> $on_way)" \
  awk -v a="$steered" -v b="$on_way" 'BEGIN {exit !(a > 0.9 && b > 0 && b < a - 0.05)}'
check "--experiment is repeatable ($on_way, with way-lateral-paths $tree)" \
  awk -v a="$on_way" -v b="$tree" 'BEGIN {exit !(b > 0 && a != b)}'
report=$("$bench" --scene S1 --repeat 1 --warmup 0 --report)
check "--report shows p_reference and unavoidability" grep -q "unavoidability" <<<"$report"
check "--report shows escape routes with their manoeuvre" grep -q "max lateral accel" <<<"$report"

expect_error() {  # expect_error CODE PATTERN ARGS...
  local code=$1 pattern=$2; shift 2
  local err rc
  err=$("$bench" "$@" 2>&1 >/dev/null); rc=$?
  check "'$*' exits $code" test "$rc" -eq "$code"
  check "'$*' error is one line" test "$(printf '%s\n' "$err" | wc -l)" -eq 1
  check "'$*' error names '$pattern'" grep -q -- "$pattern" <<<"$err"
}
expect_error 2 "params.profiles = 2" --profiles 2
expect_error 2 "scene = 'S9'" --scene S9
expect_error 2 "backend = 'gpu'" --backend gpu
expect_error 2 "experiment nope: unknown (known: way-lateral-paths, ego-on-way, euler-stops)" \
  --experiment nope
expect_error 2 "repeat" --repeat 0
expect_error 2 "preset = 'fast'" --preset fast
expect_error 2 "--fleet '/nonexistent': not a folder" --fleet /nonexistent
empty=$(mktemp -d)
expect_error 2 "holds no .scene file" --fleet "$empty"
rmdir "$empty"
expect_error 2 "unrecognised option\|unrecognized option" --bogus
check "--help explains the options" bash -c "'$bench' --help | grep -q -- '--backend'"
exit $fail
