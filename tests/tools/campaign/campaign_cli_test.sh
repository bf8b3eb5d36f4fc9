#!/usr/bin/env bash
# criticality-campaign from the command line, as a user runs it, with the stand-in driver (no
# SUMO): one-line errors and exit codes, plan, run -j 2, kill -9 and Ctrl-C in the middle of a
# campaign then resume, failures, merge, report, and the Slurm script.
# Usage: campaign_cli_test.sh CRITICALITY_CAMPAIGN STAND_IN_DRIVER WORK_DIR
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tool=$1 driver=$2 work=$3
rm -rf "$work" && mkdir -p "$work/a" "$work/b" "$work/sumo_home/bin" && cd "$work" || exit 1
for s in a b; do
  echo "sumo-config = x.sumocfg" >$s/scenario.cfg
  echo '<configuration><input><net-file value="x.net.xml"/></input></configuration>' >$s/x.sumocfg
  echo '<net/>' >$s/x.net.xml
done
. "$here/test_helpers.sh"  # failures, fail, check, running_in
json_field() { sed -n "s/.*\"$1\":\([^,}]*\).*/\1/p" <<<"$2" | tail -n 1; }
export SUMO_CRITICALITY_DRIVER=$driver
# plan asks SUMO ($SUMO_HOME/bin/sumo) about the SUMO options: a stand-in that knows a few.
ln -s "$here/fake_sumo.sh" sumo_home/bin/sumo
export SUMO_HOME=$work/sumo_home

# --- errors: one line, exit 2 ------------------------------------------------------------
"$tool" >/dev/null 2>&1; check [ $? = 2 ]
"$tool" frobnicate >/dev/null 2>err; rc=$?
check [ $rc = 2 ]; check grep -q "unknown command 'frobnicate'" err
printf 'output: o\nscenarios: [a/scenario.cfg]\ngrid:\n  driver:\n    profiles: []\n' >bad.yaml
"$tool" plan bad.yaml >/dev/null 2>err; rc=$?
check [ $rc = 2 ]
check [ "$(wc -l <err)" = 1 ]
check grep -q "bad.yaml:5: grid.driver.profiles: empty grid axis" err
printf 'output: o\nscenarios: [a/scenario.cfg]\ndriver:\n  profils: 3\n' >bad2.yaml
out=$("$tool" run bad2.yaml 2>err); rc=$?
check [ $rc = 2 ]; check grep -q "bad2.yaml:4: driver.profils: sumo-criticality has no option --profils" err
check [ "$(json_field status "$(tail -n 1 <<<"$out")")" = \"failed\" ]  # the last stdout line, failed too
out=$("$tool" plan missing.yaml 2>err); check [ $? = 2 ]; check grep -q "cannot read" err
check [ "$(json_field exit_code "$(tail -n 1 <<<"$out")")" = 2 ]
"$tool" merge "$work" >/dev/null 2>err; check [ $? = 2 ]; check grep -q "not a campaign folder" err

# --- plan proves every run can start ---------------------------------------------------------
# A value the driver refuses and an option SUMO does not know: plan says so (file, line, key),
# exit 2, before anything runs; run refuses too.
cat >typo.yaml <<EOF
output: out-typo
scenarios: [a/scenario.cfg, b/scenario.cfg]
driver:
  act: brak
sumo:
  step-lenght: 0.1
grid:
  driver:
    warn-threshold: [0.5, 0.9]
EOF
"$tool" plan typo.yaml >plan.out 2>err; rc=$?
check [ $rc = 2 ]
check grep -q '"can_start":false' plan.out
check grep -q "typo.yaml:4: driver.act: sumo-criticality says: --act 'brak': use none, warn or brake (run 0: a, warn-threshold=0.5 and 3 more option sets)" err
check grep -q "typo.yaml:6: sumo.step-lenght: sumo says: On processing option '--step-lenght': No option with the name 'step-lenght' exists." err
check [ "$(grep -c "error:" err)" = 2 ]
"$tool" run typo.yaml >/dev/null 2>err; check [ $? = 2 ]
check [ ! -d out-typo/runs ]  # nothing ran
sed -i 's/act: brak/act: warn/; s/\[0.5, 0.9\]/[-0.5, 0.9]/; s/step-lenght/step-length/' typo.yaml
"$tool" plan typo.yaml >/dev/null 2>err; rc=$?
check [ $rc = 2 ]
check grep -q "typo.yaml:9: grid.driver.warn-threshold: '-0.5': sumo-criticality says: --warn-threshold -0.5: must be in (0, 1]" err
sed -i 's/-0.5, 0.9/0.5, 0.9/' typo.yaml
out=$("$tool" plan typo.yaml 2>err); rc=$?
check [ $rc = 0 ]
check grep -q "checked: 4 of 4 driver option sets through sumo-criticality --check-options" <<<"$out"
check grep -q "checked: 2 of 2 SUMO option sets through sumo" <<<"$out"

# --- a changed campaign file over a started folder ------------------------------------------
printf 'output: out-re\nscenarios: [a/scenario.cfg]\ndriver:\n  stand-in-exit: 3\ngrid:\n  sumo:\n    seed: [1, 2]\n' >re.yaml
"$tool" run re.yaml -j 2 >/dev/null 2>&1; check [ $? = 3 ]  # both runs fail
# Run again unchanged: nothing redone, yet the folder's failed runs are said and exit 3.
out=$("$tool" run re.yaml -j 2 2>err); rc=$?
check [ $rc = 3 ]
check [ "$(json_field failed_before "$out")" = 2 ]
check grep -q "2 run(s) of the folder failed before and were not run again; \`run --retry-failed\` redoes them" err
out=$("$tool" plan re.yaml 2>/dev/null)
check grep -q "folder: 2 of 2 runs complete (2 failed: \`run --retry-failed\` redoes them), 0 half done" <<<"$out"
# Fixed: the failed runs are redone, no flag needed.
printf 'output: out-re\nscenarios: [a/scenario.cfg]\ngrid:\n  sumo:\n    seed: [1, 2]\n' >re.yaml
out=$("$tool" run re.yaml -j 2 2>err); rc=$?
check [ $rc = 0 ]
check [ "$(json_field ok "$out")" = 2 ]
check grep -q "to be redone (not successful or half done, and changed) (2):" err
# A new seed: the two runs stay, one runs.
printf 'output: out-re\nscenarios: [a/scenario.cfg]\ngrid:\n  sumo:\n    seed: [1, 2, 3]\n' >re.yaml
out=$("$tool" plan re.yaml 2>/dev/null)
check grep -q "kept: 2 complete runs the new plan has unchanged" <<<"$out"
out=$("$tool" run re.yaml -j 2 2>err); rc=$?
check [ $rc = 0 ]
check [ "$(json_field complete_before "$out")" = 2 ]
check [ "$(json_field ok "$out")" = 1 ]
# A changed value: every successful run would change; only with --replan, and kept aside.
printf 'output: out-re\nscenarios: [a/scenario.cfg]\ndriver:\n  profiles: 3\ngrid:\n  sumo:\n    seed: [1, 2, 3]\n' >re.yaml
"$tool" run re.yaml -j 2 >/dev/null 2>err; rc=$?
check [ $rc = 2 ]
check grep -q "superseded (successful, but the new plan no longer has them) (3):" err
check grep -q "run again with --replan" err
out=$("$tool" run re.yaml -j 2 --replan 2>err); rc=$?
check [ $rc = 0 ]
check [ "$(json_field ok "$out")" = 3 ]
check [ "$(ls out-re/superseded/*/ | grep -c '^0')" = 3 ]

# --- plan, run, resume ---------------------------------------------------------------------
log=$work/executions.log
cat >c.yaml <<EOF
name: cli
output: out
scenarios: [a/scenario.cfg, b/scenario.cfg]
driver:
  stand-in-log: $log
  stand-in-sleep: 0.4
  stand-in-collide: 1.0
  stand-in-warn: 0.6
grid:
  driver:
    act: [warn, brake]
  sumo:
    seed: [1, 2, 3]
slurm:
  time: "00:05:00"
  mem: 1G
  throttle: 3
  runs_per_task: 2
EOF
out=$("$tool" plan c.yaml); rc=$?
check [ $rc = 0 ]
check [ "$(json_field runs "$out")" = 12 ]
check grep -q "run 0: a, act=warn seed=1" <<<"$out"
"$tool" plan c.yaml --list | grep -c $'^[0-9]' | grep -qx 12 || fail "plan --list lists 12 runs"

# kill -9 the campaign half way: runs in flight die with it (PR_SET_PDEATHSIG) and stay .partial
"$tool" run c.yaml -j 2 --no-progress >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do
  [ "$(ls -d out/runs/*[0-9] 2>/dev/null | wc -l)" -ge 2 ] && break
  sleep 0.05
done
kill -9 $pid; wait $pid 2>/dev/null
sleep 0.3
partial=$(ls -d out/runs/*.partial 2>/dev/null | wc -l)
check [ "$partial" -ge 1 ]
running_in "$work/out/runs/" && fail "runs of a killed campaign keep running"
done_before_kill=$(ls -d out/runs/*[0-9] | sed 's|.*/||')
"$tool" merge out >/dev/null 2>&1
merged=$(sqlite3 out/campaign.sqlite "select count(*) from campaign_runs")
complete=$(ls -d out/runs/*[0-9] | wc -l)
check [ "$merged" = "$complete" ]  # never the .partial ones
check [ "$(sqlite3 out/campaign.sqlite "select count(*) from steps where run_index not in (select run_index from campaign_runs)")" = 0 ]

# Ctrl-C (SIGINT) half way: exit 130, running runs left to redo. The signal goes once the
# campaign has started a run (the stand-in logs each start): a background job of this shell
# starts with SIGINT ignored until the tool sets its handler, and a fixed wait lost that race
# on a loaded machine (the campaign then ran to its end).
started=$(wc -l <"$log")
"$tool" run c.yaml -j 2 >run.out 2>run.err &
pid=$!
for _ in $(seq 400); do
  [ "$(wc -l <"$log")" -gt "$started" ] && break
  sleep 0.05
done
sleep 0.1
kill -INT $pid; wait $pid; rc=$?
check [ $rc = 130 ]
check [ "$(json_field interrupted "$(tail -n 1 run.out)")" -ge 1 ]
check grep -q "interrupted; [0-9]* run(s) stopped and left to redo: the same \`run\` command resumes" run.err

# resume: everything completes; each run that completed before ran exactly once
out=$("$tool" run c.yaml -j 2 2>run.err); rc=$?
check [ $rc = 0 ]
check [ "$(json_field remaining "$out")" = 0 ]
check [ "$(ls -d out/runs/*[0-9] | wc -l)" = 12 ]
check [ "$(ls -d out/runs/*.partial 2>/dev/null | wc -l)" = 0 ]
check [ "$(sed 's|.*/||' "$log" | sort -u | wc -l)" = 12 ]
for r in $done_before_kill; do
  check [ "$(grep -c "/$r.partial\$" "$log")" = 1 ]  # complete runs are never redone
done
out=$("$tool" run c.yaml -j 2 2>/dev/null)
check [ "$(json_field complete_before "$out")" = 12 ]
check [ "$(json_field ok "$out")" = 0 ]

# merge: idempotent; report: tables always, figures when matplotlib is there
out=$("$tool" merge out 2>/dev/null)
check [ "$(json_field complete "$out")" = 12 ]
out=$("$tool" merge out 2>/dev/null)
check [ "$(json_field unchanged "$out")" = 12 ]
check [ "$(json_field merged "$out")" = 0 ]
check [ "$(sqlite3 out/campaign.sqlite "select count(*) from steps")" = 120 ]
check [ "$(sqlite3 out/campaign.sqlite "select count(distinct run_index) from collisions")" = 6 ]
out=$("$tool" report out 2>report.err); rc=$?
check [ $rc = 0 ]
check [ -s out/report/summary.md ]
check [ -s out/report/summary.csv ]
check grep -q "| a | warn | 3 | 3 | 0 | 3 | 3 | 3 | 0.4 |" out/report/summary.md
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  check [ "$(json_field figures "$out")" = true ]
  check [ -s out/report/index.html ]
  check [ -s out/report/overview.png ]
  check [ -s out/report/parameter_act.png ]
  check grep -q 'src="overview.png"' out/report/index.html
else
  check grep -q "no figures: " report.err
fi
# Without matplotlib (an interpreter that lacks it): tables, and one line saying what is missing.
printf '#!/bin/sh\nexec /bin/false\n' >nopython && chmod +x nopython
CRIT_PYTHON=$work/nopython PATH=/nonexistent "$tool" report out --python "$work/nopython" >out.json 2>report.err
check [ $? = 0 ]
check grep -q "no figures: " report.err
check [ -s out/report/summary.md ]

# failures: recorded, the others go on, exit 3
cat >f.yaml <<EOF
output: out-fail
scenarios: [a/scenario.cfg]
grid:
  driver:
    stand-in-exit: [0, 2, 5]
EOF
out=$("$tool" run f.yaml -j 2 2>run.err); rc=$?
check [ $rc = 3 ]
check [ "$(json_field ok "$out")" = 1 ]
check [ "$(json_field failed "$out")" = 2 ]
check grep -q "run 1 (a, stand-in-exit=2) failed: bad input (stand-in)" run.err
check grep -q "run 2 (a, stand-in-exit=5) failed: exit code 5" run.err
"$tool" merge out-fail >/dev/null 2>&1
check [ "$(sqlite3 out-fail/campaign.sqlite "select group_concat(exit_code) from campaign_runs")" = "0,2,5" ]

# slurm: the job-array script (submitted in the slurm test)
out=$("$tool" slurm c.yaml 2>/dev/null); rc=$?
check [ $rc = 0 ]
script=out/slurm/campaign.sbatch
check grep -q "^#SBATCH --array=0-5%3$" $script
check grep -q "^#SBATCH --time=00:05:00$" $script
check grep -q "^#SBATCH --mem=1G$" $script
check grep -q -- "--runs \"\$first-\$last\" -j 1 --no-check" $script  # slurm checked already
check bash -n $script

if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed (work folder $work)" >&2
  exit 1
fi
echo "campaign_cli: all checks passed"
