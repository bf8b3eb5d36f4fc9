#!/usr/bin/env python3
"""Checks of the mixed_fleet cases of scenario_cases.sh (issue 21: every run completes on
networks with trains at level crossings, trams in streets, trucks with trailers, buses at stops,
parking areas, bike lanes and pedestrians), from SUMO's FCD and stop output and the driver's
results database (and scenes).

  mixed_fleet_check.py named SUMOCFG FCD DB SCENES EGO NEAR_M SPECIAL[,...] [--in-scene ID,...]
      For every SPECIAL (a vehicle or person): the steps where its footprint comes within NEAR_M
      of the ego's (at least 10 of them: the traffic does what it is meant to); at every one of
      them a step of EGO is recorded; with --in-scene, those IDs are objects of the ego's scene
      (SCENES, --record-scenes) at every one of them.
  mixed_fleet_check.py all STOPS DB [--egos ID,...] [--no-egos ID,...]
      --all-vehicles: no vehicle is an ego while it is parked (SUMO's stop output, parking="1");
      the --egos IDs are estimated as egos at some step, the --no-egos IDs (rail vehicles under
      the default --ego-classes) never.
Prints what it found; exits 1 on a failed check.
"""
import argparse
import os
import sqlite3
import sys
import xml.etree.ElementTree as ET

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios"))
import sumo_outcome  # noqa: E402  (footprints from FCD: the same geometry as the scenario checks)


def Footprints(sumocfg, fcd):
    """time (rounded to ms) -> {id: corners}"""
    types, owner = sumo_outcome.Dimensions(sumocfg)
    steps = {}
    for _, step in ET.iterparse(fcd):
        if step.tag != "timestep":
            continue
        boxes = {}
        for e in step:
            person = e.tag == "person"
            oid = e.get("id")
            tid = e.get("type") or owner.get(oid, "DEFAULT_PEDTYPE" if person else "DEFAULT_VEHTYPE")
            default = sumo_outcome.DEFAULT_PERSON if person else sumo_outcome.DEFAULT_VEHICLE
            length, width = types.get(tid, default)
            boxes[oid] = sumo_outcome.Corners(float(e.get("x")), float(e.get("y")),
                                              float(e.get("angle")), length, width, person)
        steps[round(float(step.get("time")), 3)] = boxes
        step.clear()
    return steps


def StepTimes(db, ego):
    con = sqlite3.connect(db)
    times = {round(t, 3) for (t,) in con.execute("select time_s from steps where ego = ?", (ego,))}
    con.close()
    return times


def SceneObjects(scenes, t, ego):
    path = os.path.join(scenes, "t%010.3f_%s.scene" % (t, ego))
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return {w[1] for w in (line.split() for line in f) if w and w[0] in ("vehicle", "pedestrian")}


def Named(a):
    fails = []
    steps = Footprints(a.sumocfg, a.fcd)
    recorded = StepTimes(a.db, a.ego)
    in_scene = set(a.in_scene.split(",")) if a.in_scene else set()
    for special in a.specials.split(","):
        near = sorted(t for t, boxes in steps.items() if a.ego in boxes and special in boxes and
                      sumo_outcome.BoxDistance(boxes[a.ego], boxes[special]) <= a.near_m)
        missing = [t for t in near if t not in recorded]
        line = (f"{special}: within {a.near_m:g} m of {a.ego} at {len(near)} steps"
                + (f" ({near[0]:g}-{near[-1]:g} s)" if near else "")
                + f", {len(near) - len(missing)} of them with a step of {a.ego} recorded")
        if special in in_scene:
            absent = [t for t in near if t not in missing
                      and special not in (SceneObjects(a.scenes, t, a.ego) or ())]
            line += f", {special} in the scene at {len(near) - len(missing) - len(absent)}"
            if absent:
                fails.append(f"{special} missing from {a.ego}'s scene at {len(absent)} steps where it is "
                             f"within {a.near_m:g} m: {absent[0]:g}-{absent[-1]:g} s")
        print(line)
        if len(near) < 10:
            fails.append(f"{special} is within {a.near_m:g} m of {a.ego} at only {len(near)} steps (the "
                         "traffic is not what the case needs)")
        if missing:
            fails.append(f"no step of {a.ego} recorded at {len(missing)} steps with {special} within "
                         f"{a.near_m:g} m: {missing[0]:g}-{missing[-1]:g} s")
    return fails


def All(a):
    fails = []
    con = sqlite3.connect(a.db)
    steps = {}
    for ego, t in con.execute("select ego, time_s from steps"):
        steps.setdefault(ego, []).append(round(t, 3))
    con.close()
    parked = 0
    for e in ET.parse(a.stops).getroot().iter("stopinfo"):
        if e.get("parking") != "1":
            continue
        parked += 1
        v, start = e.get("id"), float(e.get("started"))
        end = float(e.get("ended")) if e.get("ended") not in (None, "-1", "-1.00") else float("inf")
        while_parked = [t for t in steps.get(v, []) if start + 0.05 < t < end - 0.05]
        print(f"{v}: parked {start:g}-{end:g} s, estimated as an ego at {len(while_parked)} steps "
              f"while parked, {len(steps.get(v, []))} in all")
        if while_parked:
            fails.append(f"{v} estimated as an ego while parked at {len(while_parked)} steps "
                         f"({while_parked[0]:g}-{while_parked[-1]:g} s)")
    for v in filter(None, (a.egos or "").split(",")):
        print(f"{v}: an ego at {len(steps.get(v, []))} steps")
        if not steps.get(v):
            fails.append(f"{v} never estimated as an ego")
    for v in filter(None, (a.no_egos or "").split(",")):
        print(f"{v}: an ego at {len(steps.get(v, []))} steps (rail: none under the default "
              "--ego-classes)")
        if steps.get(v):
            fails.append(f"{v} estimated as an ego at {len(steps[v])} steps")
    return fails


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="mode", required=True)
    n = sub.add_parser("named")
    for arg in ("sumocfg", "fcd", "db", "scenes", "ego"):
        n.add_argument(arg)
    n.add_argument("near_m", type=float)
    n.add_argument("specials")
    n.add_argument("--in-scene", default="")
    al = sub.add_parser("all")
    for arg in ("stops", "db"):
        al.add_argument(arg)
    al.add_argument("--egos", default="")
    al.add_argument("--no-egos", default="")
    a = ap.parse_args()
    fails = Named(a) if a.mode == "named" else All(a)
    for f in fails:
        print("FAILED:", f)
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
