#!/usr/bin/env python3
"""Plain SUMO runs an evaluation network's traffic (sumo_nets/grid_4x4, sumo_nets/spider_mixed)
as stated: every vehicle and person inserted, every vehicle arrived, no teleport, and no more
collisions (SUMO's own detection, junctions included) than stated.

Usage: traffic_check.py SUMOCFG WORK_DIR --vehicles N [--persons N] [--max-collisions K]
"""
import argparse
import os
import subprocess
import sys
import xml.etree.ElementTree as ET


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sumocfg")
    ap.add_argument("work")
    ap.add_argument("--vehicles", type=int, required=True)
    ap.add_argument("--persons", type=int, default=0)
    ap.add_argument("--max-collisions", type=int, default=0)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    name = os.path.splitext(os.path.basename(a.sumocfg))[0]
    stats = os.path.join(a.work, name + ".stats.xml")
    collisions = os.path.join(a.work, name + ".collisions.xml")
    env = dict(os.environ, SUMO_HOME=os.environ.get("SUMO_HOME", "/usr/share/sumo"))
    proc = subprocess.run(["sumo", "-c", os.path.basename(a.sumocfg), "--no-step-log",
                           "--xml-validation", "never", "--statistic-output", stats,
                           "--collision-output", collisions],
                          cwd=os.path.dirname(os.path.abspath(a.sumocfg)), env=env,
                          capture_output=True, text=True)
    fails = []
    if proc.returncode != 0:
        fails.append(f"sumo exited {proc.returncode}: {proc.stderr.strip()}")
    else:
        root = ET.parse(stats).getroot()
        vehicles, persons = root.find("vehicles"), root.find("persons")
        teleports, safety = root.find("teleports"), root.find("safety")
        first = {}
        for c in ET.parse(collisions).getroot().iter("collision"):
            first.setdefault((c.get("collider"), c.get("victim")), (c.get("time"), c.get("type")))
        print(f"{name}: vehicles inserted {vehicles.get('inserted')}/{vehicles.get('loaded')}, "
              f"running at the end {vehicles.get('running')}, persons {persons.get('loaded')} "
              f"(running {persons.get('running')}), teleports {teleports.get('total')}, "
              f"collisions {safety.get('collisions')}: "
              + ", ".join(f"{c} > {v} at {t} s ({k})" for (c, v), (t, k) in first.items()))
        if int(vehicles.get("loaded")) != a.vehicles or int(vehicles.get("inserted")) != a.vehicles:
            fails.append(f"expected {a.vehicles} vehicles inserted, got {vehicles.get('inserted')}")
        if int(vehicles.get("running")) != 0:
            fails.append(f"{vehicles.get('running')} vehicles still running at the end")
        if int(persons.get("loaded")) != a.persons:
            fails.append(f"expected {a.persons} persons, got {persons.get('loaded')}")
        if int(teleports.get("total")) != 0:
            fails.append(f"{teleports.get('total')} teleports")
        if int(safety.get("collisions")) > a.max_collisions:
            fails.append(f"{safety.get('collisions')} collisions, at most {a.max_collisions} expected")
    for f in fails:
        print(f"FAILED: {name}: {f}")
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
