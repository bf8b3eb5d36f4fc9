#!/usr/bin/env python3
"""The estimator's outcome on a designed scenario or the city-like run, as a regression test.

Runs the scenario through sumo-criticality with --act warn (default estimator and warning
options) and checks, from its results database, with the evaluation's definitions
(tools/evaluate/warning_episodes.py):
  - collision scenarios: SUMO's collision of the ego with the expected partner; a warning
    episode open at the collision that starts after the scenario's quiet phase; its anticipation
    (collision time minus the episode's start) not worse than the recorded value by more than
    ANTICIPATION_TOLERANCE_S; no more warnings in the quiet phase than recorded (the target: 0);
  - collision-free scenarios: no collision; no more warning episodes than recorded (the target:
    0; a recorded count above 0 is a known miss, printed as such);
  - the city-like run (all-vehicles), over its first CITY_END_S s: no collision; false alarms
    per vehicle-hour not above the recorded rate by more than CITY_TOLERANCE;
  - every run: the driver's warning rule replayed on the recorded p series (what the
    evaluation's threshold sweep does) gives the driver's own warning episodes.
Recorded values: recorded_warnings.txt beside this file. Re-record on purpose only (after a
change that is meant to change the estimator's outcome), for every scenario at once:
    tests/scenarios/warning_outcome.py --driver build/plugin/sumo-criticality --record scenarios/*/
(--record runs the scenarios and rewrites their lines; the file's other lines stay.)

Usage: warning_outcome.py --driver PATH [--work DIR] [--record] [--driver-args '...']
                          [--recorded FILE] SCENARIO_DIR [...]
Exit 1 when a check fails (each failure one line starting with FAILED).
"""

import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools", "evaluate"))
import city_false_alarms  # noqa: E402
import driver_help  # noqa: E402
import open_loop  # noqa: E402
import run_data  # noqa: E402
import scenario_meta  # noqa: E402
import warning_episodes as we  # noqa: E402

RECORDED = os.path.join(HERE, "recorded_warnings.txt")
ANTICIPATION_TOLERANCE_S = 0.2  # two steps of 0.1 s
CITY_END_S = 120  # the city run's window (the evaluation's default window too)
CITY_TOLERANCE = 0.10  # relative, on false alarms per vehicle-hour
CITY_VEHICLE_HOURS_TOLERANCE = 0.02  # relative: the same traffic must be run

HEADER = f"""# The estimator's recorded outcome on the designed scenarios and the city-like run, as
# tests/scenarios/warning_outcome.py checks it (sumo-criticality --act warn, default options):
#   NAME collision ANTICIPATION_S QUIET_WARNINGS   anticipation at the warning threshold (s;
#        tolerance {ANTICIPATION_TOLERANCE_S} s worse) and warnings that start in the quiet phase
#        (target 0; more fail)
#   NAME free EPISODES                             warning episodes in a collision-free scenario
#        (target 0; more fail; above 0 is a known miss)
#   NAME city FALSE_ALARMS VEHICLE_HOURS           the first {CITY_END_S} s of the city-like run
#        (false alarms per vehicle-hour: tolerance {CITY_TOLERANCE:.0%} worse)
# Re-record only on purpose, all at once (see warning_outcome.py):
#   tests/scenarios/warning_outcome.py --driver build/plugin/sumo-criticality --record scenarios/*/
"""


def read_recorded(path=RECORDED):
    recorded = {}
    if not os.path.exists(path):
        return recorded
    with open(path, encoding="utf-8") as f:
        for line in f:
            w = line.split("#")[0].split()
            if not w:
                continue
            kinds = {"collision": 4, "free": 3, "city": 4}
            if len(w) < 2 or kinds.get(w[1]) != len(w):
                raise ValueError(f"{path}: bad line '{line.strip()}'")
            recorded[w[0]] = (w[1], [float(x) for x in w[2:]])
    return recorded


def write_recorded(recorded, path=RECORDED):
    lines = [HEADER.rstrip("\n")]
    for kind in ("collision", "free", "city"):
        for name in sorted(n for n, (k, _) in recorded.items() if k == kind):
            values = recorded[name][1]
            text = " ".join(f"{v:g}" if kind != "city" or k == 0 else f"{v:.3f}"
                            for k, v in enumerate(values))
            lines.append(f"{name:<32}{kind:<10}{text}")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def run(driver, scenario, work, extra=()):
    db = os.path.join(work, scenario.name + ".sqlite")
    for suffix in ("", "-wal", "-shm"):
        if os.path.exists(db + suffix):
            os.remove(db + suffix)
    cmd = [driver, "--config", scenario.cfg_path, "--output", db, "--act", "warn",
           "--no-progress"] + list(extra)
    if scenario.all_vehicles:
        cmd += ["--end", str(CITY_END_S)]
    else:
        cmd += ["--threads", "1"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if not os.path.exists(db):
        return None, f"driver exited {proc.returncode}: {proc.stderr.strip()[-300:]}"
    r = run_data.read_run_file(db, scenario.name, proc.returncode)
    if not r.ok:
        return None, f"driver exited {proc.returncode}: {r.error or proc.stderr.strip()[-300:]}"
    return r, ""


def measure(scenario, r):
    """(kind, values, facts) of a run: what recorded_warnings.txt holds, and what else checks
    need."""
    if scenario.all_vehicles:
        row = city_false_alarms.judge_city(r, f"first {CITY_END_S} s", None)
        return "city", [row.false_alarms, row.vehicle_hours], {"collisions": row.collisions}
    hit = r.first_ego_collision(scenario.ego)
    eps = [we.Episode(w.start_s, w.end_s, w.peak_p) for w in r.ego_warnings(scenario.ego)]
    j = we.judge(eps, hit.time_s if hit else None, scenario.quiet_until_s, r.step_length_s,
                 collision_free=not scenario.collides)
    facts = {"hit": hit, "judgement": j, "collisions": len(r.collisions)}
    if scenario.collides:
        return "collision", [j.anticipation_s, j.false_positives], facts
    return "free", [j.false_positives], facts


def replay_differences(r, helptext):
    """Egos whose replayed warning episodes (the run's threshold and release: its options, else
    the driver's defaults) differ from the driver's warnings table."""
    thr, rel = open_loop.warn_settings(r, helptext)
    column = open_loop.warn_column(r, helptext)
    after = open_loop.warn_release_after(r, helptext)
    return [ego for ego in r.steps
            if not open_loop.replay_matches(r, ego, thr, rel, column, after)]


def check(scenario, kind, values, facts, rec):
    fails, notes = [], []
    if facts.get("replay_differs"):
        fails.append("replaying the warning rule on the p series differs from the driver's "
                     f"warnings for {', '.join(facts['replay_differs'][:5])} (the threshold "
                     "sweep of tools/evaluate relies on it)")
    if rec is None:
        return ["no recorded outcome: record it (--record)"], []
    if rec[0] != kind:
        return [f"recorded as '{rec[0]}', the scenario is '{kind}'"], []
    if kind == "collision":
        hit, j = facts["hit"], facts["judgement"]
        if hit is None:
            return [f"SUMO's collision of {scenario.ego} with {scenario.partner} did not happen"], []
        partner = hit.partner_of(scenario.ego)
        if scenario.partner and partner != scenario.partner:
            fails.append(f"the ego's first collision is with {partner}, expected "
                         f"{scenario.partner}")
        if j.anticipation_s is None:
            fails.append(f"collision at {hit.time_s:.1f} s not warned: {j.reason}")
        elif j.anticipation_s < rec[1][0] - ANTICIPATION_TOLERANCE_S - 1e-9:
            fails.append(f"anticipation {j.anticipation_s:.2f} s, recorded {rec[1][0]:g} s "
                         f"(tolerance {ANTICIPATION_TOLERANCE_S} s)")
        elif j.anticipation_s > rec[1][0] + ANTICIPATION_TOLERANCE_S + 1e-9:
            notes.append(f"anticipation {j.anticipation_s:.2f} s, better than the recorded "
                         f"{rec[1][0]:g} s: re-record")
        if j.false_positives > rec[1][1]:
            fails.append(f"{j.false_positives} warnings start in the quiet phase (until "
                         f"{scenario.quiet_until_s:g} s, at "
                         f"{', '.join(f'{t:.1f}' for t in j.false_positive_starts)} s), "
                         f"recorded {rec[1][1]:g}")
    elif kind == "free":
        if facts["collisions"]:
            fails.append(f"{facts['collisions']} collisions in a collision-free scenario")
        n = values[0]
        if n > rec[1][0]:
            fails.append(f"{n} warning episodes, recorded {rec[1][0]:g} (target 0; at "
                         f"{', '.join(f'{t:.1f}' for t in facts['judgement'].false_positive_starts)} s)")
        elif n < rec[1][0]:
            notes.append(f"{n} warning episodes, fewer than the recorded {rec[1][0]:g}: re-record")
        if rec[1][0] > 0:
            notes.append(f"known miss: {rec[1][0]:g} warning episodes recorded where the target "
                         "is 0")
    else:
        if facts["collisions"]:
            fails.append(f"{facts['collisions']} collisions in the collision-free city run")
        fa, vh = values
        rfa, rvh = rec[1]
        if abs(vh - rvh) > CITY_VEHICLE_HOURS_TOLERANCE * rvh:
            fails.append(f"{vh:.3f} vehicle-hours, recorded {rvh:.3f}: not the same traffic")
        rate, rrate = fa / vh if vh else 0.0, rfa / rvh if rvh else 0.0
        if rate > rrate * (1 + CITY_TOLERANCE) + 1e-9:
            fails.append(f"{rate:.1f} false alarms per vehicle-hour, recorded {rrate:.1f} "
                         f"(tolerance {CITY_TOLERANCE:.0%})")
        elif rate < rrate * (1 - CITY_TOLERANCE):
            notes.append(f"{rate:.1f} false alarms per vehicle-hour, fewer than the recorded "
                         f"{rrate:.1f}: re-record")
        notes.append(f"{rate:.1f} false alarms per vehicle-hour (target 1)")
    return fails, notes


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--driver", required=True, help="path of sumo-criticality")
    ap.add_argument("--work", default="/tmp/warning_outcome", help="folder for the databases")
    ap.add_argument("--record", action="store_true",
                    help="rewrite the scenarios' lines of recorded_warnings.txt from this run")
    ap.add_argument("--driver-args", default="",
                    help="further driver options, e.g. '--warn-threshold 0.3' (to see a check "
                    "fail; the recorded values are for the default options)")
    ap.add_argument("--recorded", default=RECORDED,
                    help="the recorded outcomes (default: recorded_warnings.txt beside this file)")
    ap.add_argument("scenarios", nargs="+", help="scenario folders (others are skipped)")
    a = ap.parse_args()
    if a.record and a.driver_args:
        ap.error("--record takes the driver's default options only (no --driver-args)")
    os.makedirs(a.work, exist_ok=True)
    recorded = read_recorded(a.recorded)
    helptext = driver_help.read_driver_help(a.driver)
    failed = ran = 0
    for folder in a.scenarios:
        if not os.path.exists(os.path.join(folder, "scenario.cfg")):
            print(f"skipped: {folder} (no scenario.cfg)")
            continue
        ran += 1
        scenario = scenario_meta.read_scenario(folder)
        r, error = run(a.driver, scenario, a.work, a.driver_args.split())
        if r is None:
            print(f"FAILED: {scenario.name}: {error}")
            failed += 1
            continue
        kind, values, facts = measure(scenario, r)
        facts["replay_differs"] = replay_differences(r, helptext)
        if a.record:
            if kind == "collision" and values[0] is None:
                print(f"FAILED: {scenario.name}: not recorded: the collision is not warned "
                      f"({facts['judgement'].reason}); every collision must be")
                failed += 1
                continue
            recorded[scenario.name] = (kind, values)
            write_recorded(recorded, a.recorded)
            print(f"recorded: {scenario.name} {kind} {values}")
            continue
        fails, notes = check(scenario, kind, values, facts, recorded.get(scenario.name))
        for f in fails:
            print(f"FAILED: {scenario.name}: {f}")
        for n in notes:
            print(f"note: {scenario.name}: {n}")
        if not fails:
            print(f"ok: {scenario.name} {kind} {values}")
        failed += bool(fails)
    if not ran:
        print("FAILED: no scenario folder among the arguments")
    sys.exit(1 if failed or not ran else 0)


if __name__ == "__main__":
    main()
