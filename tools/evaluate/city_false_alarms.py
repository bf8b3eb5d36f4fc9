"""False alarms per vehicle-hour in the city-like run (scenarios/city_free, every vehicle an
ego). Vehicle-hours: every estimated ego step counts one step length (the time the vehicles
were in the network and estimated). Ours: the driver's warning episodes after which, from the
episode's start to GRACE_S after its end, nothing critical happened to the ego: no collision
SUMO reported, no overlap of its body with another's, no braking harder than its normal maximum
(the driver's critical_events table, plugin/observe/critical_events.h). An episode followed by one of
these is counted by what followed it (the first that applies, in that order), not as a false
alarm. SSM: the device on every vehicle; an episode is a run of consecutive steps in which the
vehicle has TTC < 3 s with any foe (ssm_log.all_ego_episodes), judged the same way. The rule is
the views warning_outcomes and critical_event_warnings of plugin/record/result_views.sql (the
campaign report's too), queried through result_views.py.

An episode that nothing followed but whose window runs past the run's last time (last_time_s) is
also counted apart as unjudged: what followed it was not recorded. false_alarms keeps counting
it (so that earlier figures stay comparable); the judged rate leaves it out and divides by the
vehicle-hours in which an episode could be judged (judged_vehicle_hours)."""

from dataclasses import dataclass

import result_views
import ssm_log
import warning_episodes as we

GRACE_S = result_views.DEFAULT_GRACE_S
# Tolerance of the comparisons with the run's last time: the rounding of the recorded times
# (as the view collision_warnings allows).
TIME_EPS_S = 1e-6


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
    # Of the false alarms, those whose window runs past the run's last time (unjudged()); the
    # others per vehicle-hour in which an episode could be judged (judged_vehicle_hours())
    unjudged: int = 0
    judged_vehicle_hours: float = 0.0
    judged_per_vehicle_hour: float = None
    # The egos' overlaps and hard braking (critical_events), and of those the ones a warning
    # of that ego preceded (an episode that started at or before it and ended at most GRACE_S
    # before it)
    critical_events: int = 0
    warned_critical_events: int = 0
    ssm_episodes: int = None
    ssm_false_alarms: int = None
    ssm_per_vehicle_hour: float = None
    ssm_unjudged: int = None
    ssm_judged_per_vehicle_hour: float = None
    ssm_warned_critical_events: int = None
    wall_s: float = None


@dataclass
class ClassRow:
    """The city run's warnings and false alarms of the egos of one vehicle class."""
    vehicle_class: str = ""
    egos: int = 0
    vehicle_hours: float = 0.0
    warnings: int = 0
    false_alarms: int = 0
    warnings_per_vehicle_hour: float = None
    per_vehicle_hour: float = None


def judge_city_by_class(run):
    """One ClassRow per vehicle class of the run's egos (the driver's egos table; "(unknown)"
    for an ego it lacks), judged as judge_city judges the whole run; [] for a run that did not
    succeed."""
    if run is None or not run.ok:
        return []
    class_of = {ego: run.ego_classes.get(ego) or "(unknown)" for ego in run.steps}
    rows = []
    for vclass in sorted(set(class_of.values())):
        egos = [e for e, c in class_of.items() if c == vclass]
        row = ClassRow(vehicle_class=vclass, egos=len(egos))
        row.vehicle_hours = sum(len(run.steps[e]["time_s"]) for e in egos) * \
            run.step_length_s / 3600.0
        ours = {}
        for w in run.warnings:
            if class_of.get(w.ego) == vclass:
                ours.setdefault(w.ego, []).append(we.Episode(w.start_s, w.end_s, w.peak_p))
        row.warnings = sum(len(v) for v in ours.values())
        row.false_alarms = false_alarms(run, ours) if ours else 0
        if row.vehicle_hours > 0:
            row.per_vehicle_hour = row.false_alarms / row.vehicle_hours
            row.warnings_per_vehicle_hour = row.warnings / row.vehicle_hours
        rows.append(row)
    return rows


def vehicle_hours(run):
    return sum(len(s["time_s"]) for s in run.steps.values()) * run.step_length_s / 3600.0


def last_time_s(run):
    """The run's last simulated time: the summary's sim_time_s (the driver records collisions
    and critical events until then, also after the egos it names have left), else the latest
    step time the run recorded for any ego; None when it has neither."""
    if run.end_s is not None:
        return run.end_s
    return max((max(s["time_s"]) for s in run.steps.values() if s["time_s"]), default=None)


def judged_vehicle_hours(run):
    """The vehicle-hours in which an episode could be judged: the ego steps at or before the
    run's last time minus GRACE_S, each one step length (vehicle_hours() counts every step)."""
    last = last_time_s(run)
    if last is None:
        return 0.0
    until = last - GRACE_S + TIME_EPS_S
    steps = sum(1 for s in run.steps.values() for t in s["time_s"] if t <= until)
    return steps * run.step_length_s / 3600.0


def judged(run, eps_by_ego):
    """({outcome: number of episodes} (None: false alarms), critical events warned of, unjudged):
    the episodes {ego: [Episode]} judged by the views warning_outcomes (what followed each
    episode from its start to GRACE_S after its end: "collision", "overlap", "pass-through",
    "hard-braking", else None) and critical_event_warnings (an episode of the event's ego began
    at or before it and ended at most GRACE_S before it). An episode still open (end_s None)
    counts as ending at its start. Unjudged: the false alarms whose window (window_end_s) ends
    after the run's last time (last_time_s), so that what followed was not recorded; they stay
    in the count of None."""
    last = last_time_s(run)
    con = result_views.open_run(run, eps_by_ego, GRACE_S)
    try:
        out = dict(con.execute("SELECT outcome, count(*) FROM warning_outcomes GROUP BY 1"))
        warned = con.execute("SELECT count(*) FROM critical_event_warnings WHERE warned")
        warned = warned.fetchone()[0]
        unjudged = 0 if last is None else con.execute(
            "SELECT count(*) FROM warning_outcomes WHERE outcome IS NULL AND window_end_s > ?",
            (last + TIME_EPS_S,)).fetchone()[0]
        return out, warned, unjudged
    finally:
        con.close()


def false_alarm_starts(run, eps_by_ego):
    """[(ego, start_s)] of the episodes that nothing critical followed (as false_alarms)."""
    con = result_views.open_run(run, eps_by_ego, GRACE_S)
    try:
        return list(con.execute(
            "SELECT ego, start_s FROM warning_outcomes WHERE outcome IS NULL ORDER BY start_s"))
    finally:
        con.close()


def outcomes(run, eps_by_ego):
    """{outcome: number of episodes} (None: false alarms)."""
    return judged(run, eps_by_ego)[0]


def false_alarms(run, eps_by_ego):
    """Episodes that nothing critical followed (the unjudged ones included)."""
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
    got, row.warned_critical_events, row.unjudged = judged(run, ours)
    row.followed_by_collision = got.get("collision", 0)
    row.followed_by_overlap = got.get("overlap", 0)
    row.followed_by_hard_braking = got.get("hard-braking", 0)
    row.false_alarms = got.get(None, 0)
    row.critical_events = len(run.critical_events)
    row.judged_vehicle_hours = judged_vehicle_hours(run)
    if row.vehicle_hours > 0:
        row.per_vehicle_hour = row.false_alarms / row.vehicle_hours
        row.warnings_per_vehicle_hour = row.warnings / row.vehicle_hours
    if row.judged_vehicle_hours > 0:
        row.judged_per_vehicle_hour = (row.false_alarms - row.unjudged) / row.judged_vehicle_hours
    if ssm_conflicts is not None:
        ssm = ssm_log.all_ego_episodes(ssm_conflicts, run.step_length_s)
        row.ssm_episodes = sum(len(v) for v in ssm.values())
        got, row.ssm_warned_critical_events, row.ssm_unjudged = judged(run, ssm)
        row.ssm_false_alarms = got.get(None, 0)
        if row.vehicle_hours > 0:
            row.ssm_per_vehicle_hour = row.ssm_false_alarms / row.vehicle_hours
        if row.judged_vehicle_hours > 0:
            row.ssm_judged_per_vehicle_hour = ((row.ssm_false_alarms - row.ssm_unjudged) /
                                               row.judged_vehicle_hours)
    return row
