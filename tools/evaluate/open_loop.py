"""Per designed scenario, open loop: SUMO's outcome, our warning (anticipation at the warning
threshold and at "unavoidable"), our false positives, and SSM's anticipation and false positives
on the same run.

"Unavoidable": the steps column `unavoidability` (the smallest collision probability over all ego
hypotheses, estimator Result::unavoidability; 1 = every ego hypothesis collides, the paper's
unavoidable collision) at or above UNAVOIDABLE_LEVEL; its anticipation is the collision time
minus the start of the run of steps at or above that level that lasts until the collision. A
driver that does not record the column gives None ("not recorded").
"""

from dataclasses import dataclass, field

import ssm_log
import warning_episodes as we

UNAVOIDABLE_LEVEL = 0.95


@dataclass
class OpenLoopRow:
    scenario: str
    category: str
    variant: str
    status: str = ""  # the run's status (ok, failed, ...) or "not run"
    expected: str = ""  # "collision with X" / "no collision"
    collision: bool = False
    partner: str = ""
    collision_s: float = None
    outcome_as_expected: bool = False
    threshold: float = None
    anticipation_s: float = None
    not_warned_reason: str = ""
    false_positives: int = 0
    false_positive_starts: tuple = ()
    peak_p_quiet: float = None  # highest p in the quiet phase (free: the whole run)
    unavoidable_s: float = None
    unavoidable_note: str = ""
    replay_matches_driver: bool = True
    ssm_anticipation_s: float = None
    ssm_note: str = ""
    ssm_false_positives: int = None
    ssm_min_ttc_s: float = None
    ssm_max_drac_mps2: float = None
    ssm_min_pet_s: float = None
    warnings: list = field(default_factory=list)  # the ego's episodes (Episode)


def warn_settings(run, driver_help):
    """(threshold, release) of a run: its command line, else the driver's defaults."""
    thr = run.option_value("warn-threshold")
    thr = float(thr) if thr is not None else driver_help.default_float("warn-threshold", 0.5)
    rel = run.option_value("warn-release")
    rel = float(rel) if rel is not None else 0.8 * thr
    return thr, rel


def warn_release_after(run, driver_help):
    """--warn-release-after of a run (s): its command line, else the driver's default (0 for a
    driver without the option: it ended episodes at the first step below the release)."""
    v = run.option_value("warn-release-after")
    if v is not None:
        return float(v)
    return driver_help.default_float("warn-release-after", 0.0)


def warn_column(run, driver_help):
    """The steps column the run's warning reads (--warn-on: p_collision, p_reference or
    unavoidability; the driver's default when the run does not say)."""
    return (run.option_value("warn-on") or driver_help.options.get("warn-on") or
            "p_collision")


def _driver_episodes(run, ego):
    return [we.Episode(w.start_s, w.end_s, w.peak_p) for w in run.ego_warnings(ego)]


def replay_matches(run, ego, threshold, release, column="p_collision", release_after_s=0.0):
    """Whether replaying the driver's rule on the recorded series of the column the warning
    reads gives the driver's episode starts (a check of the replay the threshold sweep relies
    on)."""
    times, p = run.series(ego, column)
    mine = we.episodes(times, p, threshold, release, run.step_length_s, release_after_s)
    theirs = _driver_episodes(run, ego)
    return [round(e.start_s, 3) for e in mine] == [round(e.start_s, 3) for e in theirs]


def _partner_credit(run, ego, partner, t_collision):
    """warning_episodes.partner_credit over the ego's recorded main objects (None without)."""
    if t_collision is None:
        return None
    times, mains = run.series(ego, "main_object")
    return we.partner_credit(times, mains, partner, t_collision)


def judge_run(scenario, variant, run, driver_help, ssm_conflicts=None):
    """The OpenLoopRow of one run of a designed scenario."""
    row = OpenLoopRow(scenario.name, scenario.category, variant)
    row.expected = (f"collision with {scenario.partner}" if scenario.collides else "no collision")
    if run is None:
        row.status = "not run"
        return row
    row.status = run.status
    if not run.ok:
        row.not_warned_reason = f"run {run.status}: {run.error}"
        return row
    ego, step = scenario.ego, run.step_length_s
    hit = run.first_ego_collision(ego)
    if hit is not None:
        row.collision, row.partner, row.collision_s = True, hit.partner_of(ego), hit.time_s
    row.outcome_as_expected = (row.collision == scenario.collides and
                               (not scenario.collides or not scenario.partner or
                                row.partner == scenario.partner))
    row.threshold, release = warn_settings(run, driver_help)
    eps = _driver_episodes(run, ego)
    row.warnings = eps
    j = we.judge(eps, row.collision_s, scenario.quiet_until_s, step,
                 collision_free=not scenario.collides,
                 credit=_partner_credit(run, ego, row.partner, row.collision_s))
    row.anticipation_s, row.not_warned_reason = j.anticipation_s, j.reason
    row.false_positives, row.false_positive_starts = j.false_positives, j.false_positive_starts
    column = warn_column(run, driver_help)
    times, p = run.series(ego, column)
    quiet = [v for t, v in zip(times, p) if v is not None and
             (not scenario.collides or t <= scenario.quiet_until_s + 1e-9)]
    row.peak_p_quiet = max(quiet) if quiet else None
    row.replay_matches_driver = replay_matches(run, ego, row.threshold, release, column,
                                               warn_release_after(run, driver_help))
    # Unavoidable: a run of steps at or above the level that lasts until the collision.
    times, u = run.series(ego, "unavoidability")
    if not times:
        row.unavoidable_note = "not recorded by this driver"
    elif row.collision_s is not None:
        ue = we.episodes(times, u, UNAVOIDABLE_LEVEL, UNAVOIDABLE_LEVEL, step)
        uj = we.judge(ue, row.collision_s, scenario.quiet_until_s, step, collision_free=False)
        row.unavoidable_s, row.unavoidable_note = uj.anticipation_s, uj.reason
    if ssm_conflicts is not None:
        judge_ssm(row, scenario, ssm_conflicts, step)
    return row


def judge_ssm(row, scenario, conflicts, step_s):
    """SSM's side of the row: anticipation from the conflict with the collision partner (TTC < 3 s
    or DRAC > 3 m/s^2), false positives as ours (over all foes), and the extreme values."""
    mine = [c for c in conflicts if c.ego == scenario.ego]
    ttc = [v for c in mine for v in c.ttc if v is not None]
    drac = [v for c in mine for v in c.drac if v is not None]
    pet = [c.pet_s for c in mine if c.pet_s is not None]
    row.ssm_min_ttc_s = min(ttc) if ttc else None
    row.ssm_max_drac_mps2 = max(drac) if drac else None
    row.ssm_min_pet_s = min(pet) if pet else None
    everyone = ssm_log.ego_episodes(conflicts, scenario.ego, step_s)
    j = we.judge(everyone, row.collision_s, scenario.quiet_until_s, step_s,
                 collision_free=not scenario.collides)
    row.ssm_false_positives = j.false_positives
    if scenario.category == "pedestrian":
        row.ssm_note = "SSM ignores pedestrians"
    if row.collision_s is not None:
        partner = ssm_log.ego_episodes(conflicts, scenario.ego, step_s, pet_max=None,
                                       foe=row.partner)
        pj = we.judge(partner, row.collision_s, scenario.quiet_until_s, step_s,
                      collision_free=False)
        row.ssm_anticipation_s = pj.anticipation_s
        if pj.anticipation_s is None and not row.ssm_note:
            row.ssm_note = pj.reason
