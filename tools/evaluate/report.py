"""Writes the evaluation folder: results.csv (one wide row per designed scenario), city.csv,
threshold_sweep.csv, targets.csv, summary.csv, results.md (all tables with what was run), the
figures and index.html."""

import html
import os

import figures
import open_loop
import tables
from figures import cp

SSM = "SSM"


def _mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def _ms(v):
    return None if v is None else round(v * 1000.0)


def wide_rows(designed, rows, closed, ref):
    """One dict per designed scenario, every figure of every variant."""
    out = []
    closed_by = {r.scenario: r for r in closed}
    for s in designed:
        d = {"scenario": s.name, "category": s.category, "expected": (
            f"collision with {s.partner}" if s.collides else "no collision"),
            "quiet_until_s": s.quiet_until_s}
        for v, rs in rows.items():
            r = next(x for x in rs if x.scenario == s.name)
            if v == ref:
                d.update({"status": r.status, "sumo_collision": r.collision,
                          "partner": r.partner, "collision_s": r.collision_s,
                          "as_expected": r.outcome_as_expected, "threshold": r.threshold})
            d[f"{v}_anticipation_s"] = r.anticipation_s
            d[f"{v}_not_warned"] = r.not_warned_reason if s.collides else ""
            d[f"{v}_false_positives"] = r.false_positives if r.status == "ok" else None
            d[f"{v}_peak_p_quiet"] = r.peak_p_quiet
            if v == ref:
                d[f"{v}_unavoidable_s"] = r.unavoidable_s
                d[f"{v}_unavoidable_note"] = r.unavoidable_note
                d[f"{v}_replay_matches_driver"] = r.replay_matches_driver
                d.update({"ssm_anticipation_s": r.ssm_anticipation_s,
                          "ssm_false_positives": r.ssm_false_positives,
                          "ssm_min_ttc_s": r.ssm_min_ttc_s,
                          "ssm_max_drac_mps2": r.ssm_max_drac_mps2,
                          "ssm_min_pet_s": r.ssm_min_pet_s, "ssm_note": r.ssm_note})
        c = closed_by.get(s.name)
        if c is not None and c.status == "ok":
            d.update({"closed_collision": c.closed.collided,
                      "closed_partner": c.closed.partner, "avoided": c.avoided,
                      "impact_open_mps": c.open.impact_speed_mps,
                      "impact_closed_mps": c.closed.impact_speed_mps,
                      "impact_reduction_mps": c.impact_speed_reduction_mps,
                      "travel_open_s": c.open.travel_time_s,
                      "travel_closed_s": c.closed.travel_time_s,
                      "travel_time_cost_s": c.travel_time_cost_s, "closed_note": c.note})
        elif c is not None:
            d["closed_note"] = c.status
        out.append(d)
    return out


def summary_rows(rows, ref, city):
    out = []

    def one(name, rs, ant, fp):
        crit = [r for r in rs if r.category != "free" and r.status == "ok"]
        vals = {cat: [ant(r) for r in crit if r.category == cat]
                for cat in ("static-object", "moving-object", "pedestrian")}
        warned = [ant(r) for r in crit if ant(r) is not None]
        row = {"detector": name, "warned": f"{len(warned)} of {len(crit)}",
               "static_mean_ms": _ms(_mean(vals["static-object"])),
               "moving_mean_ms": _ms(_mean(vals["moving-object"])),
               "moving_range_ms": (f"{_ms(min(x for x in vals['moving-object'] if x is not None))}-"
                                   f"{_ms(max(x for x in vals['moving-object'] if x is not None))}"
                                   if any(x is not None for x in vals["moving-object"]) else ""),
               "pedestrian_mean_ms": _ms(_mean(vals["pedestrian"])),
               "min_ms": _ms(min(warned)) if warned else None,
               "false_positives": sum(fp(r) or 0 for r in rs if r.status == "ok"),
               "city_per_vehicle_hour": None}
        out.append(row)
        return row

    for name, rs in rows.items():
        row = one(name, rs, lambda r: r.anticipation_s, lambda r: r.false_positives)
        if name == ref and city is not None:
            row["city_per_vehicle_hour"] = city.per_vehicle_hour
    if ref in rows:
        row = one(SSM + " (TTC<3, DRAC>3, PET<2)", rows[ref], lambda r: r.ssm_anticipation_s,
                  lambda r: r.ssm_false_positives)
        row["pedestrian_mean_ms"] = "n/a (SSM ignores pedestrians)"
        if city is not None:
            row["city_per_vehicle_hour"] = city.ssm_per_vehicle_hour
    return out


def closed_loop_line(closed):
    """One line: the closed loop's collisions avoided, impact speeds and the cost of braking in
    the collision-free scenarios."""
    ok = [c for c in closed if c.status == "ok"]
    if not ok:
        return "Closed loop (--act brake): not run."
    hit = [c for c in ok if c.open.collided]
    avoided = [c for c in hit if c.avoided]
    reduced = [c.impact_speed_reduction_mps for c in hit if not c.avoided]
    caused = [c for c in ok if c.closed.collided and not c.open.collided]
    free_braking = [c for c in ok if not c.open.collided and c.closed.brakings > 0]
    line = (f"Closed loop (--act brake): {len(avoided)} of {len(hit)} open-loop collisions "
            f"avoided ({', '.join(c.scenario for c in hit if not c.avoided) or 'all'} not)")
    if reduced:
        line += (f"; impact speed of the others reduced by {_mean(reduced):.1f} m/s on average "
                 f"({', '.join(f'{v:.1f}' for v in reduced)})")
    line += (f"; {len(caused)} collisions caused; braking in {len(free_braking)} of "
             f"{len(ok) - len(hit)} collision-free scenarios")
    costs = [c.travel_time_cost_s for c in avoided if c.travel_time_cost_s is not None]
    if costs:
        line += f"; travel-time cost where avoided {_mean(costs):.1f} s on average"
    return line + "."


def _info_lines(info):
    lines = [f"- date {info['date']}, commit {info['commit']}, driver {info['driver_version']}",
             f"- command: `{info['command'].strip()}`, {info['jobs']} runs at once",
             f"- variants run: {', '.join(info['variants'])}"]
    lines.append(f"- designed scenarios: {len(info['scenarios'])}; city-like run: "
                 f"{info['city'] or 'not run'}")
    lines.append("- wall time (s): " + ", ".join(f"{k} {v:g}" for k, v in info["wall_s"].items()))
    return lines


def write_all(out, designed, rows, closed, city, sweep, target_rows, info, runs, columns, ssm,
              available, city_classes=()):
    ref = "ours"
    wide = wide_rows(designed, rows, closed, ref)
    wide_cols = list(dict.fromkeys(k for d in wide for k in d))
    tables.write_csv(os.path.join(out, "results.csv"), wide, wide_cols)
    summ = summary_rows(rows, ref, city)
    summ_cols = ["detector", "warned", "static_mean_ms", "moving_mean_ms", "moving_range_ms",
                 "pedestrian_mean_ms", "min_ms", "false_positives", "city_per_vehicle_hour"]
    tables.write_csv(os.path.join(out, "summary.csv"), summ, summ_cols)
    sweep_d = [vars(r) for r in sweep]
    sweep_cols = list(sweep_d[0]) if sweep_d else []
    tables.write_csv(os.path.join(out, "threshold_sweep.csv"), sweep_d, sweep_cols)
    target_d = [{"target": t.target, "value": t.value,
                 "met": "n/a" if t.met is None else ("yes" if t.met else "NO"), "gap": t.gap}
                for t in target_rows]
    tables.write_csv(os.path.join(out, "targets.csv"), target_d, ["target", "value", "met", "gap"])
    city_d = [vars(city)] if city is not None else []
    city_cols = list(city_d[0]) if city_d else []
    if city_d:
        tables.write_csv(os.path.join(out, "city.csv"), city_d, city_cols)
    class_d = [vars(c) for c in city_classes]
    class_cols = list(class_d[0]) if class_d else []
    if class_d:  # per vehicle class of the egos (SUMO's vClass)
        tables.write_csv(os.path.join(out, "city_by_class.csv"), class_d, class_cols)

    # Figures.
    figs = []
    if rows:
        tl = figures.timelines(out, designed, rows, runs, ssm, ref)
        figs.append(("summary.png", None))
        figs.append((figures.anticipation_bars(out, designed, rows, ref),
                     "Anticipation per collision scenario: ours, the variants and SSM (bars "
                     "absent: not warned)."))
        figs.append((figures.false_positive_bars(out, designed, rows, ref),
                     "False-positive episodes per scenario."))
        default_thr = next((r.threshold for r in rows[ref] if r.threshold is not None), 0.5)
        figs.append((figures.threshold_curve(out, sweep, default_thr),
                     "Threshold sweep from the recorded p series: each point a threshold."))
        figs.append((tl["(all)"], "Criticality over time, every designed scenario."))
    figures.summary(out, summ, city, closed)
    figs[0] = (os.path.join(out, "summary.png"),
               "Summary: mean anticipation (red: the paper's 932 ms for static objects), false "
               "positives, false alarms per vehicle-hour in the city run (red: target), "
               "collisions avoided in closed loop.")

    # Markdown.
    md = ["# Evaluation of sumo-criticality", "", *_info_lines(info), "",
          "## Summary", "", tables.markdown(summ, summ_cols, [
              "detector", "collisions warned", "static mean ms", "moving mean ms",
              "moving range ms", "pedestrian mean ms", "min ms", "false positives (suite)",
              "city false alarms / vehicle-hour"], 1), "",
          closed_loop_line(closed), "",
          "## Targets (at the default threshold)", "",
          tables.markdown(target_d, ["target", "value", "met", "gap"]), ""]
    open_cols = ["scenario", "category", "expected", "sumo_collision", "partner", "collision_s",
                 "ours_anticipation_s", "ours_unavoidable_s", "ours_false_positives",
                 "ours_peak_p_quiet", "ssm_anticipation_s", "ssm_false_positives",
                 "ssm_min_ttc_s", "ssm_note", "ours_not_warned"]
    md += ["## Open loop per scenario: ours and SSM", "", tables.markdown(wide, open_cols, [
        "scenario", "category", "expected", "SUMO collision", "with", "at s", "ours s",
        "unavoidable s", "ours FP", "peak p (quiet)", "SSM s", "SSM FP", "SSM min TTC s",
        "SSM note", "ours not warned: why"]), ""]
    others = [v for v in rows if v != ref]
    if others:
        cols = ["scenario", "ours_anticipation_s", "ours_false_positives"]
        heads = ["scenario", "ours s", "ours FP"]
        for v in others:
            cols += [f"{v}_anticipation_s", f"{v}_false_positives"]
            heads += [f"{v} s", f"{v} FP"]
        md += ["## Variants (ablations, presets)", "", tables.markdown(wide, cols, heads), ""]
    if closed:
        cols = ["scenario", "sumo_collision", "closed_collision", "avoided", "impact_open_mps",
                "impact_closed_mps", "impact_reduction_mps", "travel_open_s", "travel_closed_s",
                "travel_time_cost_s", "closed_note"]
        md += ["## Closed loop (--act brake) against open loop (--act warn)", "",
               tables.markdown(wide, cols, ["scenario", "open: collision", "closed: collision",
                                            "avoided", "impact open m/s", "impact closed m/s",
                                            "reduction m/s", "travel open s", "travel closed s",
                                            "cost s", "note"]), ""]
    if city_d:
        md += ["## City-like run", "", tables.markdown(city_d, city_cols), ""]
    if class_d:
        md += ["## City-like run per vehicle class of the egos", "",
               tables.markdown(class_d, class_cols), ""]
    if sweep_d:
        md += ["## Threshold sweep", "", tables.markdown(sweep_d, sweep_cols), ""]
    md += ["## Definitions", "", DEFINITIONS_TEXT, ""]
    tables_md = "\n".join(md) + "\n"
    cp.write_text(os.path.join(out, "results.md"), tables_md)

    # HTML.
    blocks = ["<ul>" + "".join(f"<li>{html.escape(x[2:])}</li>" for x in _info_lines(info)) +
              "</ul>",
              "<h2>Summary</h2>", cp.html_table(summ, summ_cols),
              "<h2>Targets</h2>", cp.html_table(target_d),
              "<h2>Figures</h2>"]
    blocks += [cp.html_figure(os.path.basename(f), c) for f, c in figs]
    if rows:
        blocks.append("<h2>Criticality over time, per scenario</h2>")
        blocks += [cp.html_figure(f"timeline_{s.name}.png", s.name) for s in designed]
    blocks += ["<h2>Open loop per scenario</h2>",
               cp.html_table([{k: tables.cell(d.get(k)) for k in open_cols} for d in wide],
                             open_cols)]
    if closed:
        cols = ["scenario", "sumo_collision", "closed_collision", "avoided", "impact_open_mps",
                "impact_closed_mps", "impact_reduction_mps", "travel_time_cost_s", "closed_note"]
        blocks += ["<h2>Closed loop</h2>",
                   cp.html_table([{k: tables.cell(d.get(k)) for k in cols} for d in wide], cols)]
    if city_d:
        blocks += ["<h2>City-like run</h2>",
                   cp.html_table([{k: tables.cell(v) for k, v in city_d[0].items()}])]
    if class_d:
        blocks += ["<h3>Per vehicle class of the egos</h3>",
                   cp.html_table([{k: tables.cell(v) for k, v in d.items()} for d in class_d])]
    if sweep_d:
        blocks += ["<h2>Threshold sweep</h2>",
                   cp.html_table([{k: tables.cell(v) for k, v in d.items()} for d in sweep_d])]
    blocks += ["<h2>Definitions</h2>", f"<p>{html.escape(DEFINITIONS_TEXT)}</p>",
               "<p>All tables: results.csv (every column), summary.csv, targets.csv, city.csv, "
               "threshold_sweep.csv; the same as Markdown: results.md.</p>"]
    cp.write_text(os.path.join(out, "index.html"),
                  cp.html_page("Evaluation of sumo-criticality", blocks))


DEFINITIONS_TEXT = " ".join(f"""Times are SUMO's (plugin/README.md, "Time stamps").
Anticipation: SUMO's collision time minus the start of the warning episode open at the collision,
counted only when that episode starts after the scenario's quiet phase (quiet-until in its
scenario.cfg). Unavoidable: the same for the steps column unavoidability >=
{open_loop.UNAVOIDABLE_LEVEL} where the driver records it. A false positive (FP): an episode that
starts in the quiet phase, or any episode in a collision-free scenario. SSM: SUMO's SSM device on
the ego in the same runs, critical while TTC < 3 s or DRAC > 3 m/s^2 with any foe (episodes over
all foes, as ours); PET < 2 s counts as a false positive only (it is measured after the
encounter); SSM's anticipation comes from its conflict with the collision partner. SSM ignores
pedestrians. City: every vehicle an ego; vehicle-hours = estimated ego steps x step length; a
false alarm is a warning episode of an ego that did not collide, overlap another's body or brake
harder than its vehicle type's decel (the driver's critical_events) between the episode's start
and 2 s after its end; unjudged: those false alarms whose window runs past the run's last
simulated time (nothing after it was recorded); per_vehicle_hour counts them,
judged_per_vehicle_hour leaves them out and divides by judged_vehicle_hours (the ego steps at or
before that last time minus 2 s); SSM's episodes are runs of steps with TTC < 3 s with any foe.
Closed loop: the same scenario with --act brake; impact speed is the collider's speed in the
ego's first collision; travel time runs from the ego's departure to its arrival (or the end of
the run).
""".split())
