#!/usr/bin/env bash
# Re-records, in one command, everything that holds the estimator's outcome (after a change that
# is meant to change it, e.g. the closed loop or the false-alarm work):
#   1. tests/scenarios/recorded_warnings.txt, the regression tests' values, from every scenario
#      of scenarios/ (the city-like run over its first 120 s included), default driver options;
#   2. the evaluation, tools/evaluate.sh with the arguments given here (default: everything),
#      into eval/ (or --out DIR);
#   3. OUT/RESULTS_section.md: a bench/RESULTS.md section (machine, date, commit, command, the
#      summary and the targets) to paste, with the analysis of the misses written by hand.
# Usage: tools/record_evaluation.sh [tools/evaluate.sh arguments]   e.g. --no-city -j 2
# Time (2 shared cores): about 1 minute for the designed scenarios of step 1, 20-40 minutes for
# its city run, then the evaluation (tools/evaluate/README.md gives the time of each mode).
# Review `git diff tests/scenarios/recorded_warnings.txt` before committing it.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${CRIT_PYTHON:-python3}
[ -z "${CRIT_PYTHON:-}" ] && [ -x /usr/bin/python3 ] && python=/usr/bin/python3
if [ -z "${EVALUATE_NO_BUILD:-}" ]; then
  ./tools/setup.sh >&2
fi
out=eval
args=("$@")
for ((k = 0; k < ${#args[@]}; k++)); do
  [ "${args[$k]}" = "--out" ] && out=${args[$((k + 1))]}
done
record_dirs=(scenarios/*/)
case " $* " in
  *" --no-city "*) record_dirs=($(ls -d scenarios/*/ | grep -v '/city_free/')) ;;
esac
echo "record_evaluation: 1/3 recording tests/scenarios/recorded_warnings.txt" >&2
"$python" tests/scenarios/warning_outcome.py --driver build/plugin/sumo-criticality \
  --work build/sumo_work/record_warnings --record "${record_dirs[@]}"
echo "record_evaluation: 2/3 tools/evaluate.sh $*" >&2
EVALUATE_NO_BUILD=1 ./tools/evaluate.sh "$@"
echo "record_evaluation: 3/3 $out/RESULTS_section.md" >&2
{
  echo "## $(date +%Y-%m-%d) — evaluation (issue 10): designed scenarios, SSM side by side, city false alarms"
  echo
  echo "- Machine: $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))," \
       "$(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo), $(uname -sr)," \
       "SUMO $(sumo --version 2>/dev/null | head -1 | awk '{print $NF}')"
  echo "- Commit: $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- . ':!tests/scenarios/recorded_warnings.txt' || echo ' (with uncommitted changes)')"
  echo "- Command: \`tools/record_evaluation.sh $*\` (the evaluation: \`tools/evaluate.sh $*\`)"
  echo
  # The summary, the targets and the variants' tables of the evaluation's Markdown.
  awk '/^## (Summary|Targets)/ {on = 1} /^## / && !/^## (Summary|Targets)/ {on = 0} on' \
    "$out/results.md"
} > "$out/RESULTS_section.md"
cat "$out/RESULTS_section.md"
