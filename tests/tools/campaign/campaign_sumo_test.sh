#!/usr/bin/env bash
# A small campaign through the real driver on our scenarios and a plain .sumocfg: run -j 2 with
# a kill -9 in the middle, resume, merge, report; every run's rows are in the merged database
# exactly once and the killed runs' half-written files never are.
# Usage: campaign_sumo_test.sh CRITICALITY_CAMPAIGN SUMO_CRITICALITY SCENARIOS_DIR WORK_DIR
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tool=$1 driver=$2 scenarios=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
. "$here/test_helpers.sh"  # failures, fail, check, running_in
q() { sqlite3 out/campaign.sqlite "$1"; }

cat >c.yaml <<YAML
name: sumo-small
output: out
scenarios:
  - $scenarios/rear_end/scenario.cfg
  - $scenarios/crossing_right_of_way/scenario.cfg
  - path: $scenarios/motorway_dense_free/motorway.sumocfg
    egos: [ego]
driver:
  act: warn
  threads: 1
grid:
  driver:
    profiles: [6, 3]
  sumo:
    seed: [1, 2]
YAML
"$tool" plan c.yaml --driver "$driver" >plan.out || fail "plan"
check grep -q '"runs":12' plan.out

"$tool" run c.yaml -j 2 --driver "$driver" --no-progress >/dev/null 2>&1 &
pid=$!
for _ in $(seq 200); do
  [ "$(ls -d out/runs/*[0-9] 2>/dev/null | wc -l)" -ge 3 ] && break
  sleep 0.1
done
kill -9 $pid
wait $pid 2>/dev/null
sleep 0.5
check [ "$(ls -d out/runs/*.partial 2>/dev/null | wc -l)" -ge 1 ]
running_in "$work/out/runs/" && fail "drivers outlive a killed campaign"

out=$("$tool" run c.yaml -j 2 --driver "$driver" 2>run.err)
rc=$?
check [ $rc = 0 ]
check grep -q '"remaining":0' <<<"$out"
"$tool" report out >report.out 2>report.err
check [ $? = 0 ]
check [ "$(q "select count(*) from campaign_runs where status = 'ok'")" = 12 ]
# Each run's steps are there once: as many rows as its summary counted estimates.
check [ "$(q "select count(*) from campaign_runs r where (select count(*) from steps s where
  s.run_index = r.run_index) != json_extract(r.summary, '$.estimates')")" = 0 ]
check [ "$(q "select count(*) from runs where status != 'completed'")" = 0 ]
check [ "$(q "select count(distinct run_index) from runs")" = 12 ]
# The scenarios' outcomes: a collision in each rear_end and crossing run, none on the motorway.
check [ "$(q "select count(distinct c.run_index) from collisions c join campaign_runs r
  using(run_index) where r.scenario in ('rear_end', 'crossing_right_of_way')")" = 8 ]
check [ "$(q "select count(*) from collisions c join campaign_runs r using(run_index)
  where r.scenario = 'motorway'")" = 0 ]
check [ "$(q "select count(*) from plan_params where name = 'profiles'")" = 12 ]
check [ "$(grep -c '^rear_end,\|^crossing_right_of_way,\|^motorway,' out/report/summary.csv)" = 6 ]
check grep -q "^rear_end,6,2,2,0,2,2,2," out/report/summary.csv

# The driver's own exposure (its summary) is what the report computes from the steps.
check [ "$(q "select count(*) from campaign_runs r where abs(json_extract(r.summary,
  '$.vehicle_hours') - (select count(*) * max(u.step_length_s) / 3600.0 from steps s, runs u
  where s.run_index = r.run_index and u.run_index = r.run_index)) > 1e-9")" = 0 ]
check [ "$(q "select count(*) from campaign_runs r where abs(json_extract(r.summary,
  '$.vehicle_km') - (select sum(s.speed_mps) * max(u.step_length_s) / 1000.0 from steps s, runs u
  where s.run_index = r.run_index and u.run_index = r.run_index)) > 1e-6")" = 0 ]
check [ "$(q "select count(*) from report_exposure where vehicle_class = 'passenger'")" = 12 ]
check grep -q "^all runs,(all),-,(all),ego collisions,8,12," out/report/rates.csv
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  check [ "$(ls out/report/scenes/*.png 2>/dev/null | wc -l)" -ge 1 ]  # warning scenes, replayed
fi

# plan proves the runs can start, through the real driver and SUMO: a value the driver refuses,
# an option SUMO does not know, and a collision action it does not know.
cat >typo.yaml <<YAML
output: out-typo
scenarios: [$scenarios/rear_end/scenario.cfg]
driver:
  act: brak
sumo:
  step-lenght: 0.1
grid:
  sumo:
    collision.action: [warn, explode]
YAML
"$tool" plan typo.yaml --driver "$driver" >plan.out 2>plan.err; rc=$?
check [ $rc = 2 ]
check grep -q "typo.yaml:4: driver.act: sumo-criticality says: --act 'brak': use none, warn or brake" plan.err
check grep -q "typo.yaml:6: sumo.step-lenght: sumo says: On processing option '--step-lenght': No option with the name 'step-lenght' exists." plan.err
sed -i 's/act: brak/act: warn/; s/step-lenght/step-length/' typo.yaml
"$tool" plan typo.yaml --driver "$driver" >plan.out 2>plan.err; rc=$?
check [ $rc = 2 ]
check grep -q "typo.yaml:9: grid.sumo.collision.action: 'explode': sumo says: Invalid collision.action 'explode'." plan.err
sed -i 's/, explode//' typo.yaml
"$tool" plan typo.yaml --driver "$driver" >plan.out 2>plan.err
check [ $? = 0 ]

if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed (work folder $work)" >&2
  exit 1
fi
echo "campaign_sumo: all checks passed"
