#!/usr/bin/env bash
# A real single-node Slurm cluster (tools/slurm_local.sh, Debian's packages, started here and
# stopped again whatever happens): a small campaign through `slurm --submit`, merged, must equal
# the same campaign through `run -j 2`, row by row, apart from timings, hosts and attempt IDs.
# Needs root (the daemons run as root) and apt-get the first time (slurm_local.sh installs).
# Usage: campaign_slurm_test.sh CRITICALITY_CAMPAIGN SUMO_CRITICALITY SOURCE_DIR WORK_DIR
set -uo pipefail
tool=$1 driver=$2 src=$3 work=$4
slurm=$src/tools/slurm_local.sh
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

# Stop the cluster on every exit, but only if this test started it.
started=0
cleanup() { if [ $started = 1 ]; then "$slurm" stop >/dev/null 2>&1; fi; }
trap cleanup EXIT
trap 'exit 130' INT TERM
if ! "$slurm" status 2>/dev/null | grep -q "^slurmctld running"; then
  started=1
  "$slurm" start || { echo "FAIL: tools/slurm_local.sh start" >&2; exit 1; }
fi

cat >c.yaml <<YAML
name: slurm-check
output: out-slurm
scenarios:
  - $src/scenarios/rear_end/scenario.cfg
  - $src/scenarios/crossing_right_of_way/scenario.cfg
driver:
  act: warn
  threads: 1
  profiles: 3
grid:
  sumo:
    seed: [1, 2]
slurm:
  time: "00:05:00"
  mem: 1G
  throttle: 2
YAML
if ! "$tool" slurm c.yaml --driver "$driver" --submit --wait --poll 0.5 >submit.out 2>submit.err
then
  cat submit.err >&2
  echo "FAIL: slurm --submit --wait" >&2
  exit 1
fi
if ! grep -q '"complete":4' submit.out; then
  echo "FAIL: not every run completed under Slurm: $(cat submit.out)" >&2
  cat out-slurm/slurm/logs/* >&2
  exit 1
fi
ls out-slurm/slurm/logs/task_*_*.out >/dev/null || { echo "FAIL: no task logs" >&2; exit 1; }
"$tool" merge out-slurm >/dev/null 2>&1 || { echo "FAIL: merge (slurm)" >&2; exit 1; }
"$tool" run c.yaml --output out-local -j 2 --driver "$driver" >/dev/null 2>&1 ||
  { echo "FAIL: run -j 2" >&2; exit 1; }
"$tool" merge out-local >/dev/null 2>&1 || { echo "FAIL: merge (local)" >&2; exit 1; }

# Compare every table, leaving out what may differ between two correct executions: timings
# (*_utc, *_ms, *_unix, wall, cpu, heartbeat, memory; in the JSON summaries also per-stage
# times and rates), host and attempt IDs.
python3 - out-slurm/campaign.sqlite out-local/campaign.sqlite <<'PY'
import json, sqlite3, sys

def varying_column(name):
    n = name.lower()
    return (n.endswith(("_utc", "_ms", "_unix")) or "_ms_" in n or "rss" in n
            or n.startswith(("heartbeat", "wall", "cpu")) or n in ("host", "attempt"))

def varying_key(key):
    k = key.lower()
    return varying_column(k) or "per_s" in k or ("time" in k and k != "sim_time_s")

def dump(path):
    db = sqlite3.connect(path)
    out = {}
    for (t,) in db.execute("select name from sqlite_master where type='table' order by name"):
        cols = [c[1] for c in db.execute(f'pragma table_info("{t}")')
                if not varying_column(c[1])]
        rows = []
        sel = ", ".join('"' + c + '"' for c in cols)
        for row in db.execute(f'select {sel} from "{t}"'):
            row = list(row)
            if "summary" in cols and row[cols.index("summary")]:
                s = json.loads(row[cols.index("summary")])
                row[cols.index("summary")] = json.dumps(
                    {k: v for k, v in s.items() if not varying_key(k)}, sort_keys=True)
            rows.append(tuple(row))
        out[t] = (cols, sorted(rows, key=repr))
    return out

a, b = dump(sys.argv[1]), dump(sys.argv[2])
if a.keys() != b.keys():
    sys.exit(f"FAIL: tables differ: {sorted(a)} vs {sorted(b)}")
bad = [t for t in a if a[t] != b[t]]
for t in bad:
    ra, rb = set(a[t][1]), set(b[t][1])
    print(f"FAIL: table {t} differs; only Slurm: {list(ra - rb)[:2]}; only local: "
          f"{list(rb - ra)[:2]}", file=sys.stderr)
if bad:
    sys.exit(1)
n = {t: len(a[t][1]) for t in a}
if n.get("campaign_runs") != 4 or not n.get("steps"):
    sys.exit(f"FAIL: expected 4 runs with steps, got {n}")
print(f"campaign_slurm: Slurm and run -j 2 agree on every table ({n})")
PY
