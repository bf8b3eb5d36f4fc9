"""False alarms per vehicle-hour in the city-like run (scenarios/city_free, every vehicle an
ego). Vehicle-hours: every estimated ego step counts one step length (the time the vehicles
were in the network and estimated). Ours: the driver's warning episodes of egos that did not
collide from the episode's start to GRACE_S after its end (with no collision at all, every
episode). SSM: the device on every vehicle; an episode is a run of consecutive steps in which the
vehicle has TTC < 3 s with any foe (ssm_log.all_ego_episodes), judged the same way."""

from dataclasses import dataclass

import ssm_log
import warning_episodes as we

GRACE_S = 2.0


@dataclass
class CityRow:
    setting: str = ""  # what was run (window, options)
    status: str = ""
    vehicle_hours: float = 0.0
    egos: int = 0
    collisions: int = 0
    ego_collisions: int = 0
    warnings: int = 0
    false_alarms: int = 0
    per_vehicle_hour: float = None
    ssm_episodes: int = None
    ssm_false_alarms: int = None
    ssm_per_vehicle_hour: float = None
    wall_s: float = None


def vehicle_hours(run):
    return sum(len(s["time_s"]) for s in run.steps.values()) * run.step_length_s / 3600.0


def is_false(ego, start_s, end_s, collisions):
    end = start_s if end_s is None else end_s
    return not any(ego in (c.collider, c.victim) and start_s <= c.time_s <= end + GRACE_S
                   for c in collisions)


def false_alarms(run, eps_by_ego):
    return sum(1 for ego, eps in eps_by_ego.items() for e in eps
               if is_false(ego, e.start_s, e.end_s, run.collisions))


def judge_city(run, setting, ssm_conflicts):
    row = CityRow(setting=setting)
    if run is None:
        row.status = "not run"
        return row
    row.status = run.status
    if not run.ok:
        return row
    row.vehicle_hours = vehicle_hours(run)
    row.egos = len(run.steps)
    row.collisions = len(run.collisions)
    row.ego_collisions = sum(1 for c in run.collisions if c.involves_ego)
    row.wall_s = run.summary.get("wall_s")
    ours = {}
    for w in run.warnings:
        ours.setdefault(w.ego, []).append(we.Episode(w.start_s, w.end_s, w.peak_p))
    row.warnings = len(run.warnings)
    row.false_alarms = false_alarms(run, ours)
    if row.vehicle_hours > 0:
        row.per_vehicle_hour = row.false_alarms / row.vehicle_hours
    if ssm_conflicts is not None:
        ssm = ssm_log.all_ego_episodes(ssm_conflicts, run.step_length_s)
        row.ssm_episodes = sum(len(v) for v in ssm.values())
        row.ssm_false_alarms = false_alarms(run, ssm)
        if row.vehicle_hours > 0:
            row.ssm_per_vehicle_hour = row.ssm_false_alarms / row.vehicle_hours
    return row
