"""The evaluation's figures, drawn with the shared helpers of tools/plots/criticality_plots.py:
criticality over time per scenario (the paper's Fig. "results"), anticipation and false
positives per scenario (ours, the variants, SSM), the threshold curve and the summary."""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plots"))
import criticality_plots as cp  # noqa: E402

import ssm_log  # noqa: E402

SSM_LABEL = "SSM (TTC<3 s, DRAC>3, PET<2 s)"


def _ms(v):
    return "missed" if v is None else f"{v * 1000:.0f}"


def _ms_unit(v):
    return "missed" if v is None else f"{v * 1000:.0f} ms"


def timeline(ax, scenario, rows_by_variant, runs, ssm_conflicts, ref, compact=False):
    """One scenario: p of ours and of every open-loop variant, unavoidability when recorded,
    our warnings, SSM's critical intervals as a band."""
    series = {}
    ours = rows_by_variant.get(ref)
    for k, (name, row) in enumerate(rows_by_variant.items()):
        run = runs.get(name, {}).get(scenario.name)
        if run is None or not run.ok:
            continue
        times, p = run.series(scenario.ego, "p_collision")
        style = ({"linewidth": 2.2, "zorder": 5} if name == ref else
                 {"linestyle": "-", "alpha": 0.7, "linewidth": 1.0})
        series[f"p {name}"] = (times, p, style)
        if name == ref:
            times, u = run.series(scenario.ego, "unavoidability")
            if times:
                series[f"unavoidability {name}"] = (times, u, {"linestyle": "--",
                                                              "color": "purple"})
    bands = []
    if ssm_conflicts is not None and ours is not None and ours.status == "ok":
        run = runs[ref][scenario.name]
        eps = ssm_log.ego_episodes(ssm_conflicts, scenario.ego, run.step_length_s)
        bands.append(("SSM critical", [(e.start_s, e.end_s) for e in eps], "darkorange"))
    eps = [(e.start_s, e.end_s) for e in ours.warnings] if ours is not None else []
    title = scenario.name
    if not compact and ours is not None and ours.collision:
        title += (f" (collision with {ours.partner}; ours {_ms_unit(ours.anticipation_s)}, "
                  f"SSM {_ms_unit(ours.ssm_anticipation_s)})")
    cp.criticality_timeline(ax, series, threshold=ours.threshold if ours else None,
                            collision_s=ours.collision_s if ours else None,
                            quiet_until_s=scenario.quiet_until_s, episodes=eps, bands=bands,
                            title=title)
    if compact:
        ax.set_xlabel("")
        ax.set_ylabel("")
        ax.tick_params(labelsize=6)
    else:
        ax.legend(fontsize=7, loc="upper left")


def timelines(out, designed, rows, runs, ssm, ref):
    """timeline_NAME.png per scenario and timelines.png with all of them."""
    files = {}
    by_scenario = {s.name: {v: next(r for r in rs if r.scenario == s.name)
                            for v, rs in rows.items()} for s in designed}
    for s in designed:
        fig, ax = cp.new_figure(8.0, 4.0)
        timeline(ax, s, by_scenario[s.name], runs, ssm.get(s.name), ref)
        files[s.name] = cp.save(fig, os.path.join(out, f"timeline_{s.name}.png"))
    cols = 5
    nrows = (len(designed) + cols - 1) // cols
    fig, axes = cp.new_figure(3.2 * cols, 2.3 * nrows, rows=nrows, cols=cols)
    axes = axes if isinstance(axes, list) else [axes]
    for ax, s in zip(axes, designed):
        timeline(ax, s, by_scenario[s.name], runs, ssm.get(s.name), ref, compact=True)
    for ax in axes[len(designed):]:
        ax.axis("off")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(6, len(labels)), fontsize=8)
    fig.suptitle("Criticality over time (black: SUMO's collision, dashed: end of the quiet phase, "
                 "red: our warnings, orange band: SSM critical)", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(os.path.join(out, "timelines.png"), dpi=90)
    cp.plt.close(fig)
    files["(all)"] = os.path.join(out, "timelines.png")
    return files


def anticipation_bars(out, designed, rows, ref):
    crit = [s for s in designed if s.collides]
    names = [s.name for s in crit]
    series = {}
    for v, rs in rows.items():
        by = {r.scenario: r for r in rs}
        series[v] = [by[n].anticipation_s if by[n].status == "ok" else None for n in names]
    by = {r.scenario: r for r in rows.get(ref, [])}
    series[SSM_LABEL] = [by[n].ssm_anticipation_s if n in by else None for n in names]
    fig, ax = cp.new_figure(min(20.0, max(8.0, 0.75 * len(names) * max(1, len(series)) / 2 + 3)),
                            4.8)
    cp.grouped_bars(ax, names, series, "anticipation (s)",
                    "Anticipation per collision scenario (collision time minus warning start; "
                    "labels in ms)", labels=True, label_format=_ms)
    ax.axhline(0.66, color="red", linestyle=":", linewidth=1)
    ax.annotate("660 ms target", (len(names) - 0.5, 0.66), fontsize=7, color="red",
                ha="right", va="bottom")
    return cp.save(fig, os.path.join(out, "anticipation.png"))


def false_positive_bars(out, designed, rows, ref):
    names = [s.name for s in designed]
    series = {}
    for v, rs in rows.items():
        by = {r.scenario: r for r in rs}
        series[v] = [by[n].false_positives if by[n].status == "ok" else None for n in names]
    by = {r.scenario: r for r in rows.get(ref, [])}
    series[SSM_LABEL] = [by[n].ssm_false_positives if n in by else None for n in names]
    fig, ax = cp.new_figure(min(20.0, max(9.0, 0.45 * len(names) * max(1, len(series)) / 2 + 3)),
                            4.5)
    cp.grouped_bars(ax, names, series, "false-positive episodes",
                    "False positives per scenario (warnings in the quiet phase or in a "
                    "collision-free scenario)", labels=True,
                    label_format=lambda v: "" if not v else f"{v:g}")
    return cp.save(fig, os.path.join(out, "false_positives.png"))


def threshold_curve(out, sweep, default_threshold):
    fig, axes = cp.new_figure(12.0, 4.8, rows=1, cols=2)
    for ax, key, xlabel, log_x in (
            (axes[0], "suite_false_positives", "false-positive episodes in the designed suite",
             False),
            (axes[1], "city_false_alarms_per_vh", "false alarms per vehicle-hour (city run)",
             True)):
        curves = {}
        for detector in ("ours", "SSM TTC"):
            pts = [(getattr(r, key), r.mean_all_s, f"{r.threshold:g}")
                   for r in sweep if r.detector == detector]
            curves[detector if detector == "ours" else "SSM TTC < x s"] = pts
        cp.tradeoff_curve(ax, curves, xlabel, "mean anticipation (s; a missed collision: 0)",
                          log_x=log_x, highlight={"ours": f"{default_threshold:g}",
                                                  "SSM TTC < x s": "3"})
        if key == "city_false_alarms_per_vh":
            ax.axvline(1.0, color="red", linestyle=":", linewidth=1)
    axes[0].set_title("Threshold sweep: anticipation against false positives (labels: "
                      "threshold; circled: default)", fontsize=9)
    axes[1].set_title("... against false alarms in city traffic (red: target 1 per "
                      "vehicle-hour)", fontsize=9)
    return cp.save(fig, os.path.join(out, "threshold_curve.png"))


def summary(out, summary_rows, city_row, closed_rows):
    fig, axes = cp.new_figure(13.0, 3.8, rows=1, cols=4)
    detectors = [r["detector"] for r in summary_rows]
    cp.grouped_bars(axes[0], ["static objects", "moving objects"],
                    {d: [r["static_mean_ms"], r["moving_mean_ms"]]
                     for d, r in zip(detectors, summary_rows)},
                    "mean anticipation (ms)", "Mean anticipation (warned)", labels=True,
                    label_format=lambda v: "-" if v is None else f"{v:.0f}")
    axes[0].axhline(932, color="red", linestyle=":", linewidth=1)
    # Room above the bars for their labels, the legend under the axes (not over the bars).
    top = max([v for r in summary_rows for v in (r["static_mean_ms"], r["moving_mean_ms"])
               if isinstance(v, (int, float))] or [1000])
    axes[0].set_ylim(0, top * 1.25)
    axes[0].legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=2)
    cp.grouped_bars(axes[1], detectors, {"false positives": [r["false_positives"]
                                                             for r in summary_rows]},
                    "episodes", "False positives (designed suite)", labels=True)
    if city_row is not None and city_row.per_vehicle_hour is not None:
        cp.grouped_bars(axes[2], ["ours", "SSM TTC < 3 s"],
                        {"per vehicle-hour": [city_row.per_vehicle_hour,
                                              city_row.ssm_per_vehicle_hour]},
                        "false alarms per vehicle-hour", "City run", labels=True,
                        label_format=lambda v: "-" if v is None else f"{v:.1f}")
        axes[2].axhline(1.0, color="red", linestyle=":", linewidth=1)
    else:
        axes[2].text(0.5, 0.5, "city run not made", ha="center", transform=axes[2].transAxes)
        axes[2].axis("off")
    ok = [r for r in closed_rows if r.status == "ok" and r.open.collided]
    if ok:
        avoided = sum(1 for r in ok if r.avoided)
        cp.grouped_bars(axes[3], ["collisions (open loop)", "avoided by braking"],
                        {"scenarios": [len(ok), avoided]}, "scenarios", "Closed loop", labels=True)
    else:
        axes[3].text(0.5, 0.5, "closed loop not run", ha="center", transform=axes[3].transAxes)
        axes[3].axis("off")
    return cp.save(fig, os.path.join(out, "summary.png"))
