#!/usr/bin/env bash
# Scale figures of criticality-campaign (bench/RESULTS.md), with the stand-in driver from the
# tests (no SUMO, no estimator), so that only the campaign's own costs are measured (--no-check:
# the stand-in scenarios have no SUMO files for plan to check):
#   1. plan of a 100,000-run grid: the summary, and every run listed (--list);
#   2. pool overhead per run: N runs of a stand-in that writes nothing, against the same stand-in
#      started N times by a plain shell loop (the cost of the process itself);
#   3. merge of 1,000 run files (1,000 steps each), then the no-op second merge;
#   4. peak memory of `run` for few and for many runs (repetitions of one run: a grid of N
#      values keeps N strings, about 100 bytes each, in the plan and campaign.json).
# Usage: tools/campaign/bench_campaign.sh [BUILD_DIR] [WORK_DIR]
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-build}" && pwd)
work=${2:-$(mktemp -d /tmp/campaign-bench.XXXXXX)}
tool=$build/tools/campaign/criticality-campaign
stand_in=$build/tests/campaign-stand-in-driver
[ -x "$tool" ] && [ -x "$stand_in" ] || { echo "build $tool and $stand_in first" >&2; exit 1; }
mkdir -p "$work/a" "$work/b" && cd "$work"
echo "sumo-config = x.sumocfg" >a/scenario.cfg
echo "sumo-config = x.sumocfg" >b/scenario.cfg
export SUMO_CRITICALITY_DRIVER=$stand_in
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }
field() { sed -n "s/.*\"$1\":\([^,}]*\).*/\1/p" <<<"$2"; }

echo "machine: $(nproc) CPUs, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo), $(uname -r)"
echo "commit:  $(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo '?')"
echo

# 1. plan
cat >plan.yaml <<'YAML'
output: out-plan
scenarios: [a/scenario.cfg, b/scenario.cfg]
grid:
  driver:
    profiles: {range: [1, 50]}
  sumo:
    seed: {range: [1, 1000]}
YAML
for k in 1 2 3; do
  t0=$(now); "$tool" plan plan.yaml --no-check >/dev/null; t1=$(now)
  "$tool" plan plan.yaml --no-check --list >list.tsv; t2=$(now)
  echo "plan, 100,000 runs: summary $(secs "$t0" "$t1") s, --list (every run) $(secs "$t1" "$t2") s ($(($(wc -l <list.tsv) - 4)) runs listed)"
done
echo

# 2. pool overhead per run
runs=${POOL_RUNS:-1000}
cat >pool.yaml <<YAML
output: out-pool
scenarios: [a/scenario.cfg]
driver:
  stand-in-no-db: true
grid:
  sumo:
    seed: {range: [1, $runs]}
YAML
for k in 1 2 3; do
  rm -rf out-pool
  t0=$(now)
  for i in $(seq "$runs"); do "$stand_in" --output x --stand-in-no-db >/dev/null; done
  t1=$(now)
  out=$("$tool" run pool.yaml -j 1 --no-check --no-progress 2>/dev/null); t2=$(now)
  rm -rf out-pool
  out2=$("$tool" run pool.yaml -j 2 --no-check --no-progress 2>/dev/null); t3=$(now)
  awk -v n="$runs" -v a="$t0" -v b="$t1" -v c="$t2" -v d="$t3" -v ok1="$(field ok "$out")" \
      -v ok2="$(field ok "$out2")" -v cpu="$(field cpu_s "$out")" 'BEGIN {
    direct = (b - a) / n * 1000; pool1 = (c - b) / n * 1000; pool2 = (d - c) / n * 1000;
    printf "pool, %d runs: stand-in alone %.2f ms/run; run -j 1 %.2f ms/run (overhead %.2f ms wall, %.2f ms CPU of the pool); run -j 2 %.2f ms/run wall; ok %d/%d\n",
      n, direct, pool1, pool1 - direct, cpu / n * 1000, pool2, ok1, ok2 }'
done
echo

# 3. merge of 1,000 run files
cat >merge.yaml <<'YAML'
output: out-merge
scenarios: [a/scenario.cfg]
driver:
  stand-in-steps: 1000
  stand-in-collide: 50.0
  stand-in-warn: 49.0
grid:
  sumo:
    seed: {range: [1, 1000]}
YAML
rm -rf out-merge
"$tool" run merge.yaml -j 2 --no-check --no-progress >/dev/null 2>&1
size=$(du -sh out-merge/runs | cut -f1)
for k in 1 2 3; do
  rm -f out-merge/campaign.sqlite
  t0=$(now); out=$("$tool" merge out-merge 2>/dev/null); t1=$(now)
  out2=$("$tool" merge out-merge 2>/dev/null); t2=$(now)
  echo "merge, 1,000 run files ($size, 1,000 steps each): $(secs "$t0" "$t1") s (merged $(field merged "$out")), again (no-op) $(secs "$t1" "$t2") s (unchanged $(field unchanged "$out2")), database $(du -h out-merge/campaign.sqlite | cut -f1)"
done
echo

# 4. memory of run: few and many runs of one plan shape (repetitions, so that the grid's value
#    lists, which the plan keeps, stay the same size)
for n in 100 ${MEMORY_RUNS:-5000}; do
  cat >mem.yaml <<YAML
output: out-mem-$n
scenarios: [a/scenario.cfg]
driver:
  stand-in-no-db: true
repetitions: $n
YAML
  out=$("$tool" run mem.yaml -j 2 --no-check --no-progress 2>/dev/null)
  echo "run memory, $n runs: peak RSS of criticality-campaign $(field max_rss_kb "$out") kB"
done
echo "work folder: $work"
