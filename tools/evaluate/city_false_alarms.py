"""False alarms per vehicle-hour in the city-like run (scenarios/city_free, every vehicle an
ego). Vehicle-hours: every estimated ego step counts one step length (the time the vehicles
were in the network and estimated). Ours: the driver's warning episodes after which, from the
episode's start to GRACE_S after its end, nothing critical happened to the ego: no collision
SUMO reported, no overlap of its body with another's, no braking harder than its normal maximum
(the driver's critical_events table, plugin/critical_events.h). An episode followed by one of
these is counted by what followed it (the first that applies, in that order), not as a false
alarm. SSM: the device on every vehicle; an episode is a run of consecutive steps in which the
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
    warnings_per_vehicle_hour: float = None
    # Episodes of ours followed by a SUMO collision, a body overlap, hard braking (outcome())
    followed_by_collision: int = 0
    followed_by_overlap: int = 0
    followed_by_hard_braking: int = 0
    false_alarms: int = 0
    per_vehicle_hour: float = None
    # The egos' overlaps and hard braking (critical_events), and of those the ones a warning
    # of that ego preceded (an episode that started at or before it and ended at most GRACE_S
    # before it)
    critical_events: int = 0
    warned_critical_events: int = 0
    ssm_episodes: int = None
    ssm_false_alarms: int = None
    ssm_per_vehicle_hour: float = None
    ssm_warned_critical_events: int = None
    wall_s: float = None


def vehicle_hours(run):
    return sum(len(s["time_s"]) for s in run.steps.values()) * run.step_length_s / 3600.0


def outcome(run, ego, start_s, end_s):
    """What followed an episode of `ego` from its start to GRACE_S after its end: "collision"
    (SUMO reported one), "overlap" (its body overlapped another's), "hard-braking" (it braked
    harder than its normal maximum), else None: a false alarm."""
    end = (start_s if end_s is None else end_s) + GRACE_S

    def within(t):
        return start_s <= t <= end

    if any(ego in (c.collider, c.victim) and within(c.time_s) for c in run.collisions):
        return "collision"
    kinds = {e.kind for e in run.critical_events if e.ego == ego and within(e.time_s)}
    for kind in ("overlap", "hard-braking"):
        if kind in kinds:
            return kind
    return None


def outcomes(run, eps_by_ego):
    """{outcome: number of episodes} (None: false alarms)."""
    out = {}
    for ego, eps in eps_by_ego.items():
        for e in eps:
            k = outcome(run, ego, e.start_s, e.end_s)
            out[k] = out.get(k, 0) + 1
    return out


def warned(eps_by_ego, event):
    """Whether an episode of the event's ego started at or before it and ended at most GRACE_S
    before it (or was still open)."""
    return any(e.start_s <= event.time_s and
               (e.end_s is None or event.time_s <= e.end_s + GRACE_S)
               for e in eps_by_ego.get(event.ego, []))


def false_alarms(run, eps_by_ego):
    """Episodes that nothing critical followed."""
    return outcomes(run, eps_by_ego).get(None, 0)


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
    got = outcomes(run, ours)
    row.followed_by_collision = got.get("collision", 0)
    row.followed_by_overlap = got.get("overlap", 0)
    row.followed_by_hard_braking = got.get("hard-braking", 0)
    row.false_alarms = got.get(None, 0)
    row.critical_events = len(run.critical_events)
    row.warned_critical_events = sum(1 for e in run.critical_events if warned(ours, e))
    if row.vehicle_hours > 0:
        row.per_vehicle_hour = row.false_alarms / row.vehicle_hours
        row.warnings_per_vehicle_hour = row.warnings / row.vehicle_hours
    if ssm_conflicts is not None:
        ssm = ssm_log.all_ego_episodes(ssm_conflicts, run.step_length_s)
        row.ssm_episodes = sum(len(v) for v in ssm.values())
        row.ssm_false_alarms = false_alarms(run, ssm)
        row.ssm_warned_critical_events = sum(1 for e in run.critical_events if warned(ssm, e))
        if row.vehicle_hours > 0:
            row.ssm_per_vehicle_hour = row.ssm_false_alarms / row.vehicle_hours
    return row
