#!/usr/bin/env python3
"""SUMO's own outcome of a designed scenario, without the estimator's judgement.

Runs one scenario folder through sumo-criticality with --act none (the driver applies the
scenario's scripted events; the estimate is recorded but never acts), with SUMO's FCD output on,
and reports from SUMO's collision detection and the trajectories:
  - every collision (first time, collider, victim), from the results database;
  - the closest approach of the ego to every other vehicle or person (the distance between
    their footprints, m) and when;
  - optionally (--ssm) SUMO's SSM device on the ego: minimum TTC, maximum DRAC, minimum PET.
With --check it compares that with the scenario's expectation (scenario.cfg: expect,
expect-partner, quiet-until) and the recorded outcome (recorded_outcomes.txt beside this file)
and exits 1 on any difference. With --record it checks the expectation only (scenario.cfg) and
writes the outcome of each scenario that meets it into recorded_outcomes.txt (its line replaced
or added; the other lines stay); re-record only after checking that a changed outcome is still
the scenario's intent.

Usage: sumo_outcome.py --driver build/plugin/sumo-criticality [--work DIR] [--ssm]
                       [--check | --record] scenarios/NAME [scenarios/NAME ...]
"""
import argparse
import json
import math
import os
import sqlite3
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
# SUMO's defaults (vehicle type DEFAULT_VEHTYPE, pedestrian type DEFAULT_PEDTYPE).
DEFAULT_VEHICLE = (5.0, 1.8)
DEFAULT_PERSON = (0.215, 0.478)
# Tolerances of --check against recorded_outcomes.txt.
COLLISION_TIME_TOLERANCE_S = 0.3
CLOSEST_TOLERANCE_M = 0.5


def ReadScenarioCfg(path):
    cfg = {"event": []}
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition("=")
            key, value = key.strip(), value.strip()
            if key == "event":
                cfg["event"].append(value)
            else:
                cfg[key] = value
    return cfg


def ReadRecorded(path):
    """recorded_outcomes.txt, one line per scenario:
    NAME collision PARTNER TIME_S   (the ego's first collision: with whom, when)
    NAME free OBJECT CLOSEST_M      (no collision; the object that comes closest, how close)"""
    recorded = {}
    with open(path) as f:
        for line in f:
            w = line.split("#")[0].split()
            if not w:
                continue
            if len(w) != 4 or w[1] not in ("collision", "free"):
                raise ValueError(f"{path}: bad line '{line.strip()}'")
            recorded[w[0]] = (w[1], w[2], float(w[3]))
    return recorded


def Outcome(report):
    """The line recorded_outcomes.txt holds for a run: (kind, object, value)."""
    got = report.get("ego_collision")
    if got:
        return "collision", got["partner"], round(got["time_s"], 1)
    if not report["closest"]:
        return None
    oid, c = min(report["closest"].items(), key=lambda kv: kv[1]["distance_m"])
    return "free", oid, round(c["distance_m"], 2)


def WriteRecorded(path, outcomes):
    """Replaces or adds the lines of the scenarios in outcomes (name -> (kind, object, value));
    comments and the other scenarios' lines stay; collisions first, then free ones, by name."""
    header, entries = [], {}
    with open(path) as f:
        for line in f:
            w = line.split("#")[0].split()
            if not w:
                header.append(line)
            else:
                entries[w[0]] = (w[1], w[2], float(w[3]))
    entries.update(outcomes)
    with open(path, "w") as f:
        f.writelines(header)
        for kind in ("collision", "free"):
            for name in sorted(n for n, e in entries.items() if e[0] == kind):
                _, obj, value = entries[name]
                text = f"{value:.1f}" if kind == "collision" else f"{value:g}"
                f.write(f"{name:<31} {kind:<9} {obj:<15} {text}\n")


def Dimensions(sumocfg):
    """Type id -> (length, width) and object id -> type id, from the run's route files."""
    root = ET.parse(sumocfg).getroot()
    base = os.path.dirname(sumocfg)
    files = []
    for tag in ("route-files", "additional-files"):
        for e in root.iter(tag):
            files += [os.path.join(base, p.strip()) for p in e.get("value").split(",")]
    types = {"DEFAULT_VEHTYPE": DEFAULT_VEHICLE, "DEFAULT_PEDTYPE": DEFAULT_PERSON}
    owner = {}
    for path in files:
        for e in ET.parse(path).getroot().iter():
            if e.tag == "vType":
                ped = e.get("vClass") == "pedestrian"
                d = DEFAULT_PERSON if ped else DEFAULT_VEHICLE
                types[e.get("id")] = (float(e.get("length", d[0])), float(e.get("width", d[1])))
            elif e.tag in ("vehicle", "person", "trip", "flow", "personFlow"):
                default = "DEFAULT_PEDTYPE" if e.tag in ("person", "personFlow") else "DEFAULT_VEHTYPE"
                owner[e.get("id")] = e.get("type", default)
    return types, owner


def Corners(x, y, angle_deg, length, width, is_person):
    """Footprint corners. FCD gives a vehicle's front bumper centre and its navigation angle
    (0 = north, clockwise); a person's position is taken as its centre."""
    a = math.radians(angle_deg)
    fx, fy = math.sin(a), math.cos(a)  # forward
    lx, ly = -fy, fx  # left
    if not is_person:
        x, y = x - 0.5 * length * fx, y - 0.5 * length * fy
    hl, hw = 0.5 * length, 0.5 * width
    return [(x + sl * hl * fx + sw * hw * lx, y + sl * hl * fy + sw * hw * ly)
            for sl, sw in ((1, 1), (1, -1), (-1, -1), (-1, 1))]


def _Separated(p, q):
    for poly in (p, q):
        for i in range(4):
            (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % 4]
            nx, ny = y2 - y1, x1 - x2
            a = [nx * x + ny * y for x, y in p]
            b = [nx * x + ny * y for x, y in q]
            if max(a) < min(b) or max(b) < min(a):
                return True
    return False


def _PointSegment(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / max(dx * dx + dy * dy, 1e-12)
    t = min(1.0, max(0.0, t))
    return math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy)


def BoxDistance(p, q):
    """Distance between two convex quadrilaterals; 0 when they overlap."""
    if not _Separated(p, q):
        return 0.0
    best = math.inf
    for s, t in ((p, q), (q, p)):
        for pt in s:
            for i in range(4):
                best = min(best, _PointSegment(pt, t[i], t[(i + 1) % 4]))
    return best


def ClosestApproach(fcd, ego, types, owner):
    """Other object id -> (closest distance m, time s), over the steps where both exist.
    Times are FCD's, the same convention as the driver's database and SUMO's collision and SSM
    output (plugin/README.md, "Time stamps")."""
    closest = {}
    for _, step in ET.iterparse(fcd):
        if step.tag != "timestep":
            continue
        t = float(step.get("time"))
        boxes = {}
        for e in step:
            person = e.tag == "person"
            oid = e.get("id")
            tid = e.get("type") or owner.get(oid, "DEFAULT_PEDTYPE" if person else "DEFAULT_VEHTYPE")
            length, width = types.get(tid, DEFAULT_PERSON if person else DEFAULT_VEHICLE)
            boxes[oid] = Corners(float(e.get("x")), float(e.get("y")), float(e.get("angle")),
                                 length, width, person)
        step.clear()
        if ego not in boxes:
            continue
        for oid, box in boxes.items():
            if oid == ego:
                continue
            d = BoxDistance(boxes[ego], box)
            if oid not in closest or d < closest[oid][0]:
                closest[oid] = (d, t)
    return closest


def ReadSsm(path):
    out = {"min_ttc_s": None, "max_drac_mps2": None, "min_pet_s": None}
    if not os.path.exists(path):
        return out
    for c in ET.parse(path).getroot().iter("conflict"):
        for tag, key, better in (("minTTC", "min_ttc_s", min), ("maxDRAC", "max_drac_mps2", max),
                                 ("PET", "min_pet_s", min)):
            for e in c.iter(tag):
                v = e.get("value")
                if v in (None, "NA"):
                    continue
                v = float(v)
                out[key] = v if out[key] is None else better(out[key], v)
    return out


def Run(driver, scenario, work, ssm):
    name = os.path.basename(os.path.normpath(scenario))
    cfg_path = os.path.join(scenario, "scenario.cfg")
    cfg = ReadScenarioCfg(cfg_path)
    db = os.path.join(work, name + ".sqlite")
    fcd = os.path.join(work, name + ".fcd.xml")
    ssm_file = os.path.join(work, name + ".ssm.xml")
    for f in (db, fcd, ssm_file):
        if os.path.exists(f):
            os.remove(f)
    # The estimate never acts under --act none; the smallest path set keeps the run cheap.
    cmd = [driver, "--config", cfg_path, "--output", db, "--act", "none", "--no-progress",
           "--own-lane-samples", "1", "--neighbour-lane-samples", "1", "--",
           "--fcd-output", fcd]
    if ssm:
        cmd += ["--device.ssm.explicit", cfg["ego"], "--device.ssm.file", ssm_file,
                "--device.ssm.measures", "TTC DRAC PET", "--device.ssm.thresholds", "3.0 3.0 2.0",
                "--device.ssm.range", "100", "--device.ssm.extratime", "5"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    report = {"scenario": name, "exit": proc.returncode}
    if proc.returncode != 0:
        report["error"] = proc.stderr.strip()
        return cfg, report
    con = sqlite3.connect(db)
    report["status"] = con.execute("select status from runs").fetchone()[0]
    first = {}
    for t, collider, victim, v_collider, v_victim in con.execute(
            "select time_s, collider, victim, collider_speed_mps, victim_speed_mps from collisions "
            "order by time_s"):
        first.setdefault((collider, victim), (t, v_collider, v_victim))
    con.close()
    report["collisions"] = [
        {"time_s": round(t, 2), "collider": c, "victim": v,
         "collider_speed_mps": round(vc or 0.0, 2), "victim_speed_mps": round(vv or 0.0, 2)}
        for (c, v), (t, vc, vv) in sorted(first.items(), key=lambda kv: kv[1][0])]
    ego = cfg["ego"]
    mine = [c for c in report["collisions"] if ego in (c["collider"], c["victim"])]
    if mine:
        c = mine[0]
        ego_is_collider = c["collider"] == ego
        report["ego_collision"] = {
            "time_s": c["time_s"], "partner": c["victim"] if ego_is_collider else c["collider"],
            "ego_speed_mps": c["collider_speed_mps"] if ego_is_collider else c["victim_speed_mps"],
            "partner_speed_mps": c["victim_speed_mps"] if ego_is_collider else c["collider_speed_mps"]}
    sumocfg = os.path.join(scenario, cfg["sumo-config"])
    types, owner = Dimensions(sumocfg)
    closest = ClosestApproach(fcd, ego, types, owner)
    report["closest"] = {oid: {"distance_m": round(d, 2), "time_s": round(t, 2)}
                         for oid, (d, t) in sorted(closest.items(), key=lambda kv: kv[1][0])}
    if ssm:
        report["ssm"] = ReadSsm(ssm_file)
    return cfg, report


def Check(cfg, report, recorded):
    """Human-readable failures (empty when SUMO's outcome matches the expectation)."""
    name = report["scenario"]
    if report["exit"] != 0:
        return [f"driver exited {report['exit']}: {report.get('error', '')}"]
    fails = []
    if report["status"] != "completed":
        fails.append(f"run status '{report['status']}'")
    rec = recorded.get(name)
    if rec is None:
        fails.append(f"no recorded outcome for {name} in recorded_outcomes.txt")
    expect = cfg.get("expect")
    category = cfg.get("category")
    if (expect == "collision") != (category in ("static-object", "moving-object", "pedestrian")) or \
            (expect == "no-collision") != (category == "free"):
        fails.append(f"scenario.cfg: category '{category}' does not fit expect '{expect}'")
    if expect == "collision":
        partner = cfg.get("expect-partner")
        if rec and rec[0] == "collision" and partner and rec[1] != partner:
            fails.append(f"scenario.cfg expects partner {partner}, recorded_outcomes.txt {rec[1]}")
        partner = partner or (rec[1] if rec else None)
        got = report.get("ego_collision")
        if got is None:
            fails.append(f"expected the ego to collide with {partner}: no collision of the ego")
        else:
            if partner and got["partner"] != partner:
                fails.append(f"the ego's first collision is with {got['partner']}, expected {partner}")
            quiet = float(cfg.get("quiet-until", 0))
            if got["time_s"] <= quiet:
                fails.append(f"collision at {got['time_s']} s, inside the quiet phase (until {quiet} s)")
            if rec and rec[0] == "collision" and abs(got["time_s"] - rec[2]) > COLLISION_TIME_TOLERANCE_S:
                fails.append(f"collision at {got['time_s']} s, recorded {rec[2]} s "
                             f"(tolerance {COLLISION_TIME_TOLERANCE_S} s)")
        if rec and rec[0] != "collision":
            fails.append("scenario.cfg expects a collision, recorded_outcomes.txt says free")
    elif expect == "no-collision":
        if report["collisions"]:
            c = report["collisions"][0]
            fails.append(f"expected no collision: {c['collider']} hit {c['victim']} at {c['time_s']} s")
        if rec and rec[0] == "free":
            near = report["closest"].get(rec[1], {}).get("distance_m", math.inf)
            if abs(near - rec[2]) > CLOSEST_TOLERANCE_M:
                fails.append(f"closest approach of {rec[1]} is {near} m, recorded {rec[2]} m "
                             f"(tolerance {CLOSEST_TOLERANCE_M} m)")
        if rec and rec[0] != "free":
            fails.append("scenario.cfg expects no collision, recorded_outcomes.txt says collision")
    else:
        fails.append(f"scenario.cfg: expect is '{expect}', not collision or no-collision")
    return fails


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--driver", required=True, help="path of sumo-criticality")
    ap.add_argument("--work", default="/tmp/sumo_outcome", help="folder for databases and FCD")
    ap.add_argument("--ssm", action="store_true", help="also run SUMO's SSM device on the ego")
    ap.add_argument("--check", action="store_true", help="compare with the expectation; exit 1 on a difference")
    ap.add_argument("--record", action="store_true",
                    help="write each scenario's outcome into recorded_outcomes.txt (only where it "
                    "meets scenario.cfg's expectation; exit 1 where not)")
    ap.add_argument("scenarios", nargs="+")
    a = ap.parse_args()
    if a.check and a.record:
        ap.error("--check and --record exclude each other")
    os.makedirs(a.work, exist_ok=True)
    path = os.path.join(HERE, "recorded_outcomes.txt")
    recorded = ReadRecorded(path) if a.check else {}
    failed = 0
    outcomes = {}
    for scenario in a.scenarios:
        cfg, report = Run(a.driver, scenario, a.work, a.ssm)
        print(json.dumps(report))
        if a.check or a.record:
            if a.record:  # the expectation alone: what this run gives is to be recorded
                outcome = Outcome(report) if report["exit"] == 0 else None
                fails = [f for f in Check(cfg, report, {}) if not f.startswith("no recorded outcome")]
                if outcome is None and not fails:
                    fails = ["nothing to record (no other object near the ego)"]
            else:
                fails = Check(cfg, report, recorded)
            for f in fails:
                print(f"FAILED: {report['scenario']}: {f}")
            if not fails:
                if a.record:
                    outcomes[report["scenario"]] = outcome
                    print(f"recorded: {report['scenario']} {' '.join(map(str, outcome))}")
                else:
                    print(f"ok: {report['scenario']}")
            failed += bool(fails)
    if outcomes:
        WriteRecorded(path, outcomes)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
