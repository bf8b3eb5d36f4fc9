#!/usr/bin/env bash
# The campaign demo: builds (through tools/setup.sh), runs scenarios/campaigns/demo.yaml (four
# scenarios x warn/brake x two seeds, 16 runs) with a process pool, then merges and reports.
# Resumes a campaign left half done; remove out/campaigns/demo to start afresh.
# Usage: tools/campaign_demo.sh [-j N]
set -euo pipefail
cd "$(dirname "$0")/.."
echo "campaign demo: building (the first run installs packages and compiles for a few minutes)" >&2
./tools/setup.sh >&2
tool=build/tools/campaign/criticality-campaign
"$tool" plan scenarios/campaigns/demo.yaml --show 2
"$tool" run scenarios/campaigns/demo.yaml "${@:--j2}" || [ $? = 3 ]  # 3: some runs failed (recorded)
"$tool" report out/campaigns/demo
echo
sed -n '/^## Per scenario and parameters/,/^## Per parameter value/p' out/campaigns/demo/report/summary.md | head -n -1
echo "Report: out/campaigns/demo/report/index.html (tables: summary.md, database: out/campaigns/demo/campaign.sqlite)"
