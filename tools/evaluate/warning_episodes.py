"""Warning episodes and what they mean for one scenario.

The driver's rule (plugin/README.md, "Acting"): an episode opens at the first step with
p >= threshold and closes at the first step at which p has stayed below release for
release_after_s (release = 0.8 x threshold unless --warn-release says otherwise; release_after_s
= --warn-release-after, 0.3 s by default; 0: the first step below); an ego that leaves ends it. `episodes` replays that rule on a
recorded series, so that any threshold can be judged without a rerun (threshold_sweep.py); at the
run's own threshold it gives the driver's `warnings` table (checked by the tests and at every
evaluation).

Anticipation: collision time minus the start of the episode that is open at the collision (or
closed at most one step before it), as the driver's collisions.anticipation_s, but only when that
episode starts after the scenario's quiet phase. Where the steps name each step's main object,
the episode must have warned of the collision partner and counts from the first step at which
the partner was its main object (`partner_credit`; the view collision_warnings). One difference: an episode that starts at the
collision's step counts here (0 s), not in the driver's rule (the view collision_anticipation of
plugin/record/result_views.sql), which records a step's collisions before its warnings. A false
positive: an episode that starts at or before the end of the quiet phase, or any episode in a
collision-free scenario.
"""

from dataclasses import dataclass


@dataclass
class Episode:
    start_s: float
    end_s: float  # None: still open when the series ends
    peak: float


def episodes(times, values, threshold, release, step_s, release_after_s=0.0):
    """The episodes of one ego's series (times ascending). A gap of more than 1.5 steps (the ego
    absent, e.g. teleported) closes an open episode one step after its last value."""
    out = []
    open_ep = None
    last_t = None
    below_since = None
    for t, v in zip(times, values):
        if v is None:
            continue
        if open_ep is not None and last_t is not None and t - last_t > 1.5 * step_s:
            open_ep.end_s = last_t + step_s
            out.append(open_ep)
            open_ep = None
        if open_ep is None:
            if v >= threshold:
                open_ep = Episode(t, None, v)
                below_since = None
        elif v < release:
            if below_since is None:
                below_since = t
            if t - below_since >= release_after_s - 1e-9:
                open_ep.end_s = t
                out.append(open_ep)
                open_ep = None
        else:
            below_since = None
            open_ep.peak = max(open_ep.peak, v)
        last_t = t
    if open_ep is not None:
        out.append(open_ep)
    return out


def covering(eps, t_collision, step_s, credit=None):
    """The latest episode open at the collision (started at or before it and not closed more
    than one step before it) that warned of it (credit(e) not None; every episode without
    credit); None when there is none."""
    best = None
    for e in eps:
        if e.start_s <= t_collision + 1e-9 and (e.end_s is None or
                                                 e.end_s >= t_collision - step_s - 1e-9):
            if credit is not None and credit(e) is None:
                continue
            if best is None or e.start_s > best.start_s:
                best = e
    return best


def partner_credit(times, main_objects, partner, t_collision):
    """credit(e) for covering and judge: the first step of episode e before the collision at
    which `partner` was the main object of the estimate (steps.main_object), None when it never
    was; None (no attribution) when the steps name no main object (an older driver)."""
    if not times or not main_objects or partner is None:
        return None

    def credit(e):
        for t, m in zip(times, main_objects):
            if t < e.start_s - 1e-9 or t >= t_collision - 1e-9:
                continue
            if e.end_s is not None and t > e.end_s + 1e-9:
                break
            if m == partner:
                return t
        return None
    return credit


@dataclass
class Judgement:
    anticipation_s: float = None  # None: the collision was not warned (see reason)
    reason: str = ""  # why not warned (empty when warned)
    false_positives: int = 0
    false_positive_starts: tuple = ()


def judge(eps, t_collision, quiet_until_s, step_s, collision_free, credit=None):
    """Anticipation of the ego's collision at t_collision (None: it did not collide) and the
    false positive episodes of a scenario designed collision-free (every episode) or not (those
    starting in the quiet phase). credit (partner_credit): the episode must have warned of the
    partner, and counts from then."""
    if collision_free:
        fp = list(eps)
    else:
        fp = [e for e in eps if e.start_s <= quiet_until_s + 1e-9]
    j = Judgement(false_positives=len(fp), false_positive_starts=tuple(e.start_s for e in fp))
    if t_collision is None:
        return j
    e = covering(eps, t_collision, step_s, credit)
    if e is None and credit is not None and covering(eps, t_collision, step_s) is not None:
        other = covering(eps, t_collision, step_s)
        j.reason = (f"the warning of {other.start_s:.1f} s never named the collision partner as "
                    f"its main object")
    elif e is None:
        before = [x for x in eps if quiet_until_s < x.start_s <= t_collision]
        if before:
            last = before[-1]
            j.reason = (f"the warning of {last.start_s:.1f} s ended at {last.end_s:.1f} s, "
                        f"{t_collision - last.end_s:.1f} s before the collision")
        else:
            j.reason = "no warning before the collision"
    elif e.start_s <= quiet_until_s + 1e-9:
        j.reason = f"warning on since {e.start_s:.1f} s, inside the quiet phase (a false positive)"
    else:
        start = credit(e) if credit is not None else e.start_s
        j.anticipation_s = round(t_collision - start, 6)
    return j
