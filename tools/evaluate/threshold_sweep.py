"""Anticipation against false alarms as the warning threshold moves: the curve a user picks a
threshold from. Computed from the recorded p series (no rerun): the driver's warning rule is
replayed (warning_episodes.episodes) at each threshold, with the release at the run's
release/threshold ratio (0.8 by default). Beside it, SSM's TTC at thresholds up to 3 s (the SSM
device logs only conflicts that cross its configured thresholds, so larger TTC thresholds cannot
be judged from its file)."""

from dataclasses import dataclass

import city_false_alarms
import ssm_log
import warning_episodes as we

THRESHOLDS = [round(0.10 + 0.05 * k, 2) for k in range(18)]  # 0.10 .. 0.95
SSM_TTC_THRESHOLDS = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]


@dataclass
class SweepRow:
    detector: str  # "ours" or "SSM TTC"
    threshold: float
    collisions: int = 0
    warned: int = 0
    mean_anticipation_s: float = None  # over the warned collisions
    mean_all_s: float = None  # over every collision, a missed one counting 0 s
    static_mean_s: float = None
    moving_mean_s: float = None
    min_anticipation_s: float = None
    suite_false_positives: int = 0
    city_false_alarms_per_vh: float = None


def _mean(xs):
    return sum(xs) / len(xs) if xs else None


def _aggregate(row, judged):
    """judged: [(scenario, Judgement)] for the designed scenarios."""
    ants = {"all": [], "static-object": [], "moving-object": []}
    for s, j in judged:
        row.suite_false_positives += j.false_positives
        if s.collides:
            row.collisions += 1
            if j.anticipation_s is not None:
                row.warned += 1
                ants["all"].append(j.anticipation_s)
                if s.category in ants:
                    ants[s.category].append(j.anticipation_s)
    row.mean_anticipation_s = _mean(ants["all"])
    if row.collisions:
        row.mean_all_s = sum(ants["all"]) / row.collisions
    row.static_mean_s = _mean(ants["static-object"])
    row.moving_mean_s = _mean(ants["moving-object"])
    row.min_anticipation_s = min(ants["all"]) if ants["all"] else None


def _collision_time(run, s):
    hit = run.first_ego_collision(s.ego)
    return hit.time_s if hit else None


def sweep_ours(scenarios, runs, city_run, release_ratio=0.8, thresholds=THRESHOLDS,
               release_after_s=0.0):
    """runs: {scenario name: Run} of the open-loop variant; city_run: the city Run or None."""
    rows = []
    for thr in thresholds:
        row = SweepRow("ours", thr)
        judged = []
        for s in scenarios:
            run = runs.get(s.name)
            if run is None or not run.ok:
                continue
            times, p = run.series(s.ego, "p_collision")
            eps = we.episodes(times, p, thr, release_ratio * thr, run.step_length_s,
                              release_after_s)
            t_c = _collision_time(run, s)
            hit = run.first_ego_collision(s.ego) if t_c is not None else None
            credit = None
            if hit is not None:
                mt, mains = run.series(s.ego, "main_object")
                credit = we.partner_credit(mt, mains, hit.partner_of(s.ego), t_c)
            judged.append((s, we.judge(eps, t_c, s.quiet_until_s, run.step_length_s,
                                       collision_free=not s.collides, credit=credit)))
        _aggregate(row, judged)
        if city_run is not None and city_run.ok:
            by_ego = {ego: we.episodes(st["time_s"], st["p_collision"], thr, release_ratio * thr,
                                       city_run.step_length_s, release_after_s)
                      for ego, st in city_run.steps.items()}
            vh = city_false_alarms.vehicle_hours(city_run)
            if vh > 0:
                row.city_false_alarms_per_vh = (
                    city_false_alarms.false_alarms(city_run, by_ego) / vh)
        rows.append(row)
    return rows


def sweep_ssm(scenarios, runs, ssm_by_scenario, city_run, city_ssm,
              thresholds=SSM_TTC_THRESHOLDS):
    """SSM's TTC alone at each threshold (no DRAC, no PET), judged as ours."""
    rows = []
    for ttc in thresholds:
        row = SweepRow("SSM TTC", ttc)
        judged = []
        for s in scenarios:
            run, conflicts = runs.get(s.name), ssm_by_scenario.get(s.name)
            if run is None or not run.ok or conflicts is None:
                continue
            step = run.step_length_s
            t_c = _collision_time(run, s)
            eps = ssm_log.ego_episodes(conflicts, s.ego, step, ttc, None, None)
            j = we.judge(eps, t_c, s.quiet_until_s, step, collision_free=not s.collides)
            if t_c is not None:
                hit = run.first_ego_collision(s.ego)
                partner = ssm_log.ego_episodes(conflicts, s.ego, step, ttc, None, None,
                                               foe=hit.partner_of(s.ego))
                j.anticipation_s = we.judge(partner, t_c, s.quiet_until_s, step,
                                            collision_free=False).anticipation_s
            judged.append((s, j))
        _aggregate(row, judged)
        if city_run is not None and city_run.ok and city_ssm is not None:
            vh = city_false_alarms.vehicle_hours(city_run)
            eps = ssm_log.all_ego_episodes(city_ssm, city_run.step_length_s, ttc)
            if vh > 0:
                row.city_false_alarms_per_vh = city_false_alarms.false_alarms(city_run, eps) / vh
        rows.append(row)
    return rows
