"""Issue 10's targets, at the default threshold, against the evaluation's figures: met or not,
by how much a missed one is missed, and the reasons the data gives (per scenario)."""

from dataclasses import dataclass

MIN_ANTICIPATION_S = 0.660  # the paper's smallest anticipation for moving objects
STATIC_MEAN_S = 0.932  # the paper's mean for static objects
CITY_MAX_PER_VH = 1.0
HORIZON_S = 2.0  # the estimator's default prediction horizon (Params::horizon_s, the paper's)


@dataclass
class TargetRow:
    target: str
    value: str
    met: bool = None  # None: not measurable here (says why)
    gap: str = ""


def _mean(xs):
    return sum(xs) / len(xs) if xs else None


def check(rows, city, ssm_city_note=""):
    """rows: OpenLoopRows of the reference variant; city: CityRow or None."""
    out = []
    crit = [r for r in rows if r.category != "free" and r.status == "ok"]
    free = [r for r in rows if r.category == "free" and r.status == "ok"]
    warned = [r for r in crit if r.anticipation_s is not None]
    missed = [r for r in crit if r.anticipation_s is None]
    out.append(TargetRow(
        "every collision warned", f"{len(warned)} of {len(crit)}", len(missed) == 0,
        "; ".join(f"{r.scenario}: {r.not_warned_reason or 'no collision in SUMO'}"
                  for r in missed)))
    short = [r for r in warned if r.anticipation_s < MIN_ANTICIPATION_S - 1e-9]
    out.append(TargetRow(
        f"each warned >= {MIN_ANTICIPATION_S * 1000:.0f} ms ahead",
        (f"min {min(r.anticipation_s for r in warned) * 1000:.0f} ms" if warned else "none warned"),
        (len(short) == 0 and len(missed) == 0) if crit else None,
        "; ".join([f"{r.scenario}: {r.anticipation_s * 1000:.0f} ms "
                   f"({(MIN_ANTICIPATION_S - r.anticipation_s) * 1000:.0f} ms short)"
                   for r in short] + [f"{r.scenario}: not warned" for r in missed])))
    static = [r for r in crit if r.category == "static-object"]
    static_ant = [r.anticipation_s for r in static if r.anticipation_s is not None]
    m = _mean(static_ant)
    gap = ""
    if m is not None and m < STATIC_MEAN_S:
        gap = f"{(STATIC_MEAN_S - m) * 1000:.0f} ms short"
    if len(static_ant) < len(static):
        gap += ("; " if gap else "") + (f"{len(static) - len(static_ant)} of {len(static)} "
                                        "static collisions not warned (left out of the mean)")
    out.append(TargetRow(f"static-object mean >= {STATIC_MEAN_S * 1000:.0f} ms",
                         f"{m * 1000:.0f} ms" if m is not None else "none warned",
                         (m is not None and m >= STATIC_MEAN_S and len(static_ant) == len(static))
                         if static else None, gap))
    moving = [r.anticipation_s for r in crit if r.category == "moving-object"
              and r.anticipation_s is not None]
    out.append(TargetRow("moving-object anticipation (paper: 660-1800 ms)",
                         (f"{min(moving) * 1000:.0f}-{max(moving) * 1000:.0f} ms, mean "
                          f"{_mean(moving) * 1000:.0f} ms" if moving else "none warned"),
                         (min(moving) >= MIN_ANTICIPATION_S) if moving else None))
    fp_free = [r for r in free if r.false_positives > 0]
    out.append(TargetRow(
        "zero warnings in the collision-free scenarios",
        f"{sum(r.false_positives for r in free)} episodes in {len(fp_free)} of {len(free)}",
        len(fp_free) == 0 if free else None,
        "; ".join(f"{r.scenario}: {r.false_positives} (peak p {r.peak_p_quiet:.2f})"
                  for r in fp_free)))
    fp_quiet = [r for r in crit if r.false_positives > 0]
    out.append(TargetRow(
        "zero false positives in the quiet phases (paper)",
        f"{sum(r.false_positives for r in crit)} episodes in {len(fp_quiet)} of {len(crit)}",
        len(fp_quiet) == 0 if crit else None,
        "; ".join(f"{r.scenario}: warning at {', '.join(f'{t:.1f}' for t in r.false_positive_starts)} s "
                  f"(quiet phase; peak p {r.peak_p_quiet:.2f})" for r in fp_quiet)))
    if city is None or city.per_vehicle_hour is None:
        out.append(TargetRow(f"<= {CITY_MAX_PER_VH:g} false alarm per vehicle-hour (city)",
                             "not run", None, city.status if city else "the city run was skipped"))
    else:
        per = city.per_vehicle_hour
        out.append(TargetRow(
            f"<= {CITY_MAX_PER_VH:g} false alarm per vehicle-hour (city)",
            (f"{per:.1f} ({city.false_alarms} in {city.vehicle_hours:.2f} vehicle-hours; of "
             f"{city.warnings} warnings, {city.followed_by_collision} were followed by a "
             f"collision, {city.followed_by_overlap} by a body overlap, "
             f"{city.followed_by_hard_braking} by hard braking)"),
            per <= CITY_MAX_PER_VH,
            f"{per / CITY_MAX_PER_VH:.0f}x the target" if per > CITY_MAX_PER_VH else ""))
        ssm_part = ("" if city.ssm_warned_critical_events is None else
                    f"; SSM's TTC < 3 s: {city.ssm_warned_critical_events}")
        out.append(TargetRow("critical events in the city warned of (overlaps, hard braking)",
                             f"ours: {city.warned_critical_events} of {city.critical_events}"
                             f"{ssm_part}", None,
                             "informational: a warning episode of that ego began at or before "
                             "the event and ended at most 2 s before it"))
        if city.ssm_per_vehicle_hour is not None:
            out.append(TargetRow("SSM TTC < 3 s in the city (issue: ~100 per vehicle-hour)",
                                 f"{city.ssm_per_vehicle_hour:.1f} per vehicle-hour "
                                 f"({city.ssm_false_alarms} episodes)", None, ssm_city_note))
    # Earlier than SSM's TTC at fewer false alarms: on the collisions both can see (vehicles).
    both = [r for r in crit if r.ssm_anticipation_s is not None and r.anticipation_s is not None]
    seen = [r for r in crit if r.category != "pedestrian"]
    ours_m = _mean([r.anticipation_s or 0.0 for r in seen])
    ssm_m = _mean([r.ssm_anticipation_s or 0.0 for r in seen])
    if seen and any(r.ssm_false_positives is not None for r in rows):
        later = [r for r in both if r.anticipation_s < r.ssm_anticipation_s]
        ours_fp = sum(r.false_positives for r in rows if r.status == "ok")
        ssm_fp = sum(r.ssm_false_positives or 0 for r in rows if r.status == "ok")
        earlier = ours_m >= ssm_m
        fewer = ours_fp <= ssm_fp
        if city and city.per_vehicle_hour is not None and city.ssm_per_vehicle_hour is not None:
            fewer = fewer and city.per_vehicle_hour <= city.ssm_per_vehicle_hour
        out.append(TargetRow(
            "earlier than SSM's TTC at fewer false alarms",
            (f"vehicle collisions: ours {ours_m * 1000:.0f} ms, SSM {ssm_m * 1000:.0f} ms mean "
             "(not warned = 0); false positives in the suite: ours "
             f"{ours_fp}, SSM {ssm_fp}"), earlier and fewer,
            ("" if earlier else
             f"why: ours predicts {HORIZON_S:.0f} s ahead (the paper's horizon), so no warning "
             "of it comes earlier than that, at any threshold (threshold_sweep.csv); SSM's "
             "TTC < 3 s fires 3 s before a contact at constant speeds, whether or not the "
             "driver still brakes in time. Later: ") +
            "; ".join(f"{r.scenario}: ours {r.anticipation_s * 1000:.0f} ms, SSM "
                      f"{r.ssm_anticipation_s * 1000:.0f} ms" for r in later)))
    return out
