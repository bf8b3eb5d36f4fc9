#!/usr/bin/env python3
"""Plain SUMO runs the city-like traffic scenario (scenarios/city_free) as stated: every car and
person inserted, no collision (SUMO's own detection, junctions included), no teleport.

Usage: city_free_check.py SCENARIO_DIR WORK_DIR
"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

# What scenarios/city_free/scenario.cfg states: 400 cars and 200 pedestrians.
CARS, PERSONS = 400, 200


def main():
    scenario, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    stats, collisions = os.path.join(work, "city_stats.xml"), os.path.join(work, "city_collisions.xml")
    env = dict(os.environ, SUMO_HOME=os.environ.get("SUMO_HOME", "/usr/share/sumo"))
    proc = subprocess.run(["sumo", "-c", "city.sumocfg", "--no-step-log", "--xml-validation", "never",
                           "--statistic-output", stats, "--collision-output", collisions],
                          cwd=scenario, env=env, capture_output=True, text=True)
    fails = []
    if proc.returncode != 0:
        fails.append(f"sumo exited {proc.returncode}: {proc.stderr.strip()}")
    else:
        root = ET.parse(stats).getroot()
        vehicles, persons = root.find("vehicles"), root.find("persons")
        teleports, safety = root.find("teleports"), root.find("safety")
        hits = [(c.get("time"), c.get("collider"), c.get("victim"))
                for c in ET.parse(collisions).getroot().iter("collision")]
        print(f"cars inserted {vehicles.get('inserted')}/{vehicles.get('loaded')}, persons loaded "
              f"{persons.get('loaded')}, teleports {teleports.get('total')}, collisions "
              f"{safety.get('collisions')} ({len(hits)} records)")
        if int(vehicles.get("inserted")) != CARS or int(vehicles.get("loaded")) != CARS:
            fails.append(f"expected {CARS} cars inserted, got {vehicles.get('inserted')}")
        if int(persons.get("loaded")) != PERSONS:
            fails.append(f"expected {PERSONS} persons, got {persons.get('loaded')}")
        if int(teleports.get("total")) != 0:
            fails.append(f"{teleports.get('total')} teleports")
        if int(safety.get("collisions")) != 0 or hits:
            fails.append(f"collisions: {hits[:3]}")
    for f in fails:
        print("FAILED: city_free: " + f)
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
