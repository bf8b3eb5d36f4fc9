#!/usr/bin/env python3
"""Figures and the HTML page of a campaign report.

Called by `criticality-campaign report DIR` after it has written the tables into DIR/report/
(summary.csv, by_parameter.csv, rates.csv, by_vehicle_class.csv, exposure.csv, warnings.csv,
failures.csv, hotspots.csv, events.csv, reliability.csv and the manifest report.json). Writes
PNG figures, one picture per warning scene (scenes/), and index.html next to them. Usage:
    campaign_report.py DIR/report
Every figure is sized for a screen (at most 1150 px wide) and for print (200 dpi), labelled with
units, and says in words what it cannot show ("no ego collisions in any run") instead of
drawing empty axes. Maps use one colour scale for warnings across the whole report.
Generic plotting and HTML helpers: tools/plots/criticality_plots.py and scene_picture.py.
"""

import json
import os
import sqlite3
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plots"))
import criticality_plots as cp  # noqa: E402
import scene_picture as sp  # noqa: E402
from matplotlib import colors as mcolors  # noqa: E402

MAX_WIDTH_IN = 11.5  # 1150 px on the page

SUMMARY_HEADERS = {
    "runs": "runs", "ok": "ok", "failed": "failed runs", "collisions": "collisions (all SUMO saw)",
    "ego_collisions": "ego collisions", "warned_collisions": "warned ego collisions",
    "anticipation_mean_s": "anticipation mean (s)",
    "anticipation_median_s": "anticipation median (s)",
    "anticipation_min_s": "anticipation min (s)", "warnings": "warnings",
    "false_alarms": "false alarms", "collisions_avoided": "collisions avoided by braking",
    "estimator_ms_mean": "estimator per estimate (ms)", "estimator_ms_max": "estimator max (ms)",
    "steps": "ego estimates", "vehicle_hours": "vehicle-hours", "vehicle_km": "vehicle-km",
    "wall_s_mean": "wall time per run (s)", "scenario": "scenario",
    "parameter": "parameter", "value": "value", "vehicle_class": "vehicle class", "egos": "egos",
    "run_index": "run", "parameters": "setting", "status": "status", "exit_code": "exit code",
    "error": "error", "kind": "kind", "id": "ID", "ego": "ego", "start_s": "start (s)",
    "end_s": "end (s)", "peak_p": "peak p", "edge": "edge", "object": "main object",
    "outcome": "what followed", "scene": "scene", "p_low": "p from", "p_high": "p to",
    "steps_in_bin": "estimates", "mean_p": "mean p", "observed_frequency": "observed frequency",
}

MEASURE_COLOURS = {"warnings": "#4c72b0", "false alarms": "#dd8452", "ego collisions": "#c44e52"}
OUTCOME_COLOURS = {"false alarm": "#dd8452", "collision": "#c44e52", "overlap": "#8172b3",
                   "pass-through": "#64b5cd", "hard-braking": "#937860", "avoided": "#55a868"}


def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def safe_name(text):
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)


def num(row, key):
    return cp.number(row.get(key)) if row else None


def grouped(text):
    """A table number with thousands separators (12,345,678; 0.0123 stays as it is)."""
    v = cp.number(text)
    if v is None or abs(v) < 10000:
        return text
    return f"{v:,.0f}"


def ci_text(row, key):
    """"12.3 [9.1 - 15.6]" from a rates row's value and interval columns."""
    v = row.get(key, "")
    if v == "":
        return ""
    low, high = row.get(key + "_low", ""), row.get(key + "_high", "")
    v, low, high = grouped(v), grouped(low), grouped(high)
    return f"{v} [{low} \u2013 {high}]" if low != "" or high != "" else v


class Report:
    """The report folder's tables and the figures made from them."""

    def __init__(self, report_dir):
        self.dir = report_dir
        with open(os.path.join(report_dir, "report.json"), encoding="utf-8") as f:
            self.manifest = json.load(f)
        read = lambda name: cp.read_csv(os.path.join(report_dir, name))  # noqa: E731
        self.summary = read("summary.csv")
        self.by_param = read("by_parameter.csv")
        self.failures = read("failures.csv")
        self.hotspots = read("hotspots.csv")
        self.events = read("events.csv")
        self.reliability = read("reliability.csv")
        self.rates = read("rates.csv")
        self.by_class = read("by_vehicle_class.csv")
        self.exposure = read("exposure.csv")
        self.warnings = read("warnings.csv")
        self.scenarios = [s["name"] for s in self.manifest.get("scenarios", [])]
        self.axes = [a for a in self.manifest.get("axes", []) if a.get("grouping")]
        self.available = self.manifest.get("available", {})
        self.figures = {}  # section -> [(file, caption)]
        self.scene_files = {}  # (run_index, warning_id) -> picture file
        self.notes = list(self.manifest.get("notes", []))
        self._nets = {}

    def add(self, section, path, caption):
        if path:
            self.figures.setdefault(section, []).append((os.path.basename(path), caption))

    def path(self, name):
        return os.path.join(self.dir, name)

    def net(self, scenario):
        if scenario not in self._nets:
            files = {s["name"]: s.get("net_file") for s in self.manifest.get("scenarios", [])}
            f = files.get(scenario)
            self._nets[scenario] = cp.SumoNet(f) if f and os.path.exists(f) else None
        return self._nets[scenario]

    def rate(self, breakdown, measure, scenario="(all)", parameters="-", vehicle_class="(all)"):
        for r in self.rates:
            if (r["breakdown"], r["measure"], r["scenario"], r["parameters"],
                    r["vehicle_class"]) == (breakdown, measure, scenario, parameters,
                                            vehicle_class):
                return r
        return None


# --- figures -------------------------------------------------------------------------------


def overview_figure(rep):
    """Per scenario: ego collisions, warned ones, false alarms and failed runs (all settings)."""
    keys = [("ego_collisions", "ego collisions"), ("warned_collisions", "warned ego collisions"),
            ("false_alarms", "false alarms"), ("failed", "failed runs")]
    totals = {s: {k: 0.0 for k, _ in keys} for s in rep.scenarios}
    for r in rep.summary:
        t = totals.setdefault(r["scenario"], {k: 0.0 for k, _ in keys})
        for k, _ in keys:
            t[k] += cp.number(r.get(k)) or 0
    names = [s for s in totals]
    fig, ax = cp.new_figure(MAX_WIDTH_IN, 1.6 + 0.3 * len(names) * len(keys) / 2)
    if not any(totals[s][k] for s in names for k, _ in keys):
        cp.empty_note(ax, "No ego collisions, no false alarms and no failed runs in any scenario.",
                      "Outcomes per scenario")
        return cp.save(fig, rep.path("overview.png"))
    none = [label for k, label in keys if not any(totals[s][k] for s in names)]
    keys = [(k, label) for k, label in keys if label not in none]
    height = 0.8 / len(keys)
    for j, (k, label) in enumerate(keys):
        ys = [i - 0.4 + height * (j + 0.5) for i in range(len(names))]
        values = [totals[s][k] for s in names]
        bars = ax.barh(ys, values, height, label=label)
        ax.bar_label(bars, labels=[f"{v:g}" if v else "" for v in values], padding=2, fontsize=9)
    ax.set_yticks(range(len(names)))
    ax.set_yticklabels(names)
    ax.invert_yaxis()
    ax.set_xlabel("count, summed over settings and seeds")
    ax.set_title("Outcomes per scenario" + (f" (none: {', '.join(none)})" if none else ""))
    ax.xaxis.get_major_locator().set_params(integer=True)
    ax.grid(True, axis="x", alpha=0.3)
    ax.legend(loc="lower right")
    return cp.save(fig, rep.path("overview.png"))


def errorbar_lines(ax, values, curves, ylabel, title, empty_text):
    """Lines over categorical values with 95 % interval bars; curves: {label: [(y, low, high)]}.
    Says `empty_text` when nothing was measured or every value is 0."""
    ys = [p[0] for pts in curves.values() for p in pts if p and p[0] is not None]
    if not ys or all(y == 0 for y in ys):
        cp.empty_note(ax, empty_text, title)
        return
    n = max(1, len(curves))
    for k, (label, pts) in enumerate(curves.items()):
        dodge = (k - (n - 1) / 2) * 0.06
        xs, y, lo, hi = [], [], [], []
        for i, p in enumerate(pts):
            if p and p[0] is not None:
                xs.append(i + dodge)
                y.append(p[0])
                lo.append(p[0] - (p[1] if p[1] is not None else p[0]))
                hi.append((p[2] if p[2] is not None else p[0]) - p[0])
        ax.errorbar(xs, y, yerr=[lo, hi], marker="o", capsize=3, label=label,
                    linewidth=2.2 if label == "(all)" else 1.3)
    ax.set_xticks(range(len(values)))
    ax.set_xticklabels([str(v) for v in values])
    ax.set_xlim(-0.5, len(values) - 0.5)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    # Intervals of small exposures can be far wider than every value: the axis follows the
    # values (and the interval over all scenarios); a bar that goes on above ends in a caret.
    overall = [p[2] for p in curves.get("(all)", []) if p and p[2] is not None]
    top = 1.3 * max(ys + overall)
    ax.set_ylim(0, top)
    for k, (label, pts) in enumerate(curves.items()):
        dodge = (k - (n - 1) / 2) * 0.06
        for i, p in enumerate(pts):
            if p and p[2] is not None and p[2] > top:
                ax.plot([i + dodge], [top], marker="^", color="black", markersize=5,
                        clip_on=False)
    cp.readable_numbers(ax)
    ax.grid(True, alpha=0.3)


def parameter_figure(rep, axis):
    """Per value of one parameter: anticipation, rates with their intervals, estimator time,
    exposure; a line per scenario and one over all scenarios."""
    name, values = axis["name"], axis["values"]
    rows = [r for r in rep.by_param if r["parameter"] == name]
    present = [s for s in rep.scenarios if any(r["scenario"] == s for r in rows)]
    curves = (["(all)"] if len(present) > 1 else []) + present

    def column(col):
        out = {}
        for s in curves:
            pts = []
            for v in values:
                hit = [r for r in rows if r["value"] == v and r["scenario"] == s]
                pts.append((num(hit[0], col), None, None) if hit else None)
            out[s] = pts
        return out

    def rates(measure, per):
        out = {}
        for s in curves:
            pts = []
            for v in values:
                r = rep.rate("parameter", measure, s, f"{name}={v}")
                pts.append((num(r, per), num(r, per + "_low"), num(r, per + "_high"))
                           if r else None)
            out[s] = pts
        return out

    fig, axes = cp.new_figure(MAX_WIDTH_IN, 7.4, rows=2, cols=3)
    errorbar_lines(axes[0], values, column("anticipation_mean_s"), "mean anticipation (s)",
                   "Anticipation of ego collisions", "No warned ego collision: no anticipation.")
    have_rates = rep.available.get("vehicle_hours")
    no_exposure = "Not computable: the run files have no exposure (older driver)."
    errorbar_lines(axes[1], values, rates("warnings", "per_vehicle_hour") if have_rates else {},
                   "warnings per vehicle-hour", "Warnings",
                   "No warnings." if have_rates else no_exposure)
    errorbar_lines(axes[2], values, rates("false alarms", "per_vehicle_hour") if have_rates else {},
                   "false alarms per vehicle-hour", "False alarms",
                   "No false alarms in any run." if have_rates else no_exposure)
    km = rep.available.get("vehicle_km")
    errorbar_lines(axes[3], values, rates("ego collisions", "per_million_vehicle_km") if km else {},
                   "ego collisions per 10\u2076 vehicle-km", "Ego collisions",
                   "No ego collisions in any run." if km else no_exposure)
    errorbar_lines(axes[4], values, column("estimator_ms_mean"), "time per estimate (ms)",
                   "Estimator time", "No estimator times recorded.")
    errorbar_lines(axes[5], values, column("vehicle_hours"), "vehicle-hours estimated",
                   "Exposure", "No exposure recorded (older run files).")
    for ax in axes:
        if ax.get_xticks().size:  # not on a panel that only says why it is empty
            ax.set_xlabel(name)
    handles, labels = [], []
    for ax in axes:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(6, len(labels)), frameon=False)
    fig.suptitle(f"Effect of {name} (bars: 95 % interval across seeds and repetitions)")
    fig.tight_layout(rect=(0, 0.07 if handles else 0, 1, 0.95))
    return cp.save(fig, rep.path(f"parameter_{safe_name(name)}.png"), tight=False)


def hbar_rates(ax, groups, rows, per, xlabel, title, empty_text):
    """Horizontal bars of one rate per group with its interval; rows: {group: rates row}."""
    vals = [num(rows.get(g), per) for g in groups]
    if not any(v for v in vals if v is not None):
        cp.empty_note(ax, empty_text, title)
        return
    ys = list(range(len(groups)))
    lo, hi = [], []
    for g, v in zip(groups, vals):
        lo.append(v - (num(rows.get(g), per + "_low") or v) if v is not None else 0)
        hi.append((num(rows.get(g), per + "_high") or v) - v if v is not None else 0)
    ax.barh(ys, [v or 0 for v in vals], xerr=[lo, hi], capsize=3, color="#4c72b0", alpha=0.85)
    ax.set_yticks(ys)
    ax.set_yticklabels(groups)
    ax.invert_yaxis()
    ax.set_xlabel(xlabel)
    ax.set_title(title)
    cp.readable_numbers(ax, "x")
    ax.grid(True, axis="x", alpha=0.3)


def class_figure(rep):
    """Rates per vehicle class of the egos, with their intervals."""
    classes = [r["vehicle_class"] for r in rep.by_class]
    if not classes:
        return None
    fig, axes = cp.new_figure(MAX_WIDTH_IN, 1.8 + 0.45 * len(classes), rows=1, cols=3)
    specs = [("warnings", "per_vehicle_hour", "per vehicle-hour", "Warnings", "No warnings."),
             ("false alarms", "per_vehicle_hour", "per vehicle-hour", "False alarms",
              "No false alarms."),
             ("ego collisions", "per_million_vehicle_km", "per 10\u2076 vehicle-km",
              "Ego collisions", "No ego collisions.")]
    for ax, (measure, per, xlabel, title, empty) in zip(axes, specs):
        rows = {c: rep.rate("vehicle class", measure, "(all)", "-", c) for c in classes}
        hbar_rates(ax, classes, rows, per, xlabel, title, empty)
    fig.suptitle("Per vehicle class of the egos (bars: 95 % interval across runs)")
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    return cp.save(fig, rep.path("by_vehicle_class.png"), tight=False)


def time_figure(rep):
    """Warnings (by what followed them) and collisions over simulated time."""
    starts = {}
    for w in rep.warnings:
        t = cp.number(w.get("start_s"))
        if t is not None:
            starts.setdefault(w["outcome"], []).append(t)
    collisions = [cp.number(e["time_s"]) for e in rep.events
                  if e["event"] == "collision" and cp.number(e.get("time_s")) is not None]
    times = [t for ts in starts.values() for t in ts] + collisions
    fig, ax = cp.new_figure(MAX_WIDTH_IN, 3.8)
    if not times:
        cp.empty_note(ax, "No warnings and no located collisions in any successful run.",
                      "Over simulated time")
        return cp.save(fig, rep.path("over_time.png"))
    # Bins of a round width, at most 60 of them.
    lo, hi = min(times), max(times)
    width = next(w for w in (0.5, 1, 2, 5, 10, 20, 30, 60, 120, 300, 600, 1800, 3600, 1e9)
                 if (hi - lo) / w <= 60)
    start = width * (lo // width)
    edges = [start + width * k for k in range(int((hi - start) // width) + 2)]
    labels = [k for k in OUTCOME_COLOURS if k in starts] + \
        [k for k in starts if k not in OUTCOME_COLOURS]
    if labels:
        ax.hist([starts[k] for k in labels], bins=edges, stacked=True,
                color=[OUTCOME_COLOURS.get(k, "#999999") for k in labels],
                label=[f"warnings followed by {k} ({len(starts[k])})" if k != "false alarm" else
                       f"false alarms ({len(starts[k])})" for k in labels])
    if collisions:
        ax.hist(collisions, bins=edges, histtype="step", color="black", linewidth=1.8,
                label=f"collisions ({len(collisions)})")
    ax.set_xlabel(f"simulated time (s), bins of {width:g} s")
    ax.set_ylabel("count (all runs)")
    ax.set_title("Over simulated time: when warnings began, and what followed them")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(loc="upper right")
    return cp.save(fig, rep.path("over_time.png"))


def located_points(rep, net, scenario, setting):
    pts = []
    for e in rep.events:
        if e["scenario"] != scenario or e.get("parameters", "-") != setting:
            continue
        x, y = cp.number(e["x_m"]), cp.number(e["y_m"])
        if (x is None or y is None) and e["lane"] and cp.number(e["pos_m"]) is not None:
            xy = net.lane_point(e["lane"], cp.number(e["pos_m"]))
            x, y = xy if xy else (None, None)
        if x is not None and y is not None:
            pts.append((x, y, e["event"]))
    return pts


def element_xy(net, kind, ident):
    if kind == "junction":
        j = net.junctions.get(ident)
        return (j[0], j[1]) if j else None
    return net.edge_middle(ident)


def focus_of(net, pts, label_xy):
    """The part of the network the events are in (with a margin), or None for all of it."""
    xs = [p[0] for p in pts] + [p[0] for p in label_xy]
    ys = [p[1] for p in pts] + [p[1] for p in label_xy]
    allx = [p[0] for shapes in net.edge_lines().values() for s in shapes for p in s]
    ally = [p[1] for shapes in net.edge_lines().values() for s in shapes for p in s]
    if not xs or not allx:
        return None
    w, h = max(xs) - min(xs), max(ys) - min(ys)
    margin = max(60.0, 0.25 * max(w, h))
    box = (min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin)
    whole = (max(allx) - min(allx)) * (max(ally) - min(ally))
    if (box[2] - box[0]) * (box[3] - box[1]) > 0.5 * whole:
        return None
    return box


def map_figures(rep):
    """Per scenario: one map per setting (grid parameter values), edges and junctions coloured
    by warnings on one scale for the whole report, collisions as crosses, the busiest elements
    labelled with their IDs (those of the hotspot table)."""
    vmax = max([cp.number(h["warnings"]) or 0 for h in rep.hotspots] + [1])
    norm = mcolors.Normalize(vmin=0, vmax=vmax)
    for s in rep.manifest.get("scenarios", []):
        scenario = s["name"]
        net = rep.net(scenario)
        rows = [h for h in rep.hotspots if h["scenario"] == scenario]
        settings = []
        for h in rows + [e for e in rep.events if e["scenario"] == scenario]:
            if h.get("parameters", "-") not in settings:
                settings.append(h.get("parameters", "-"))
        if net is None or not settings:
            continue
        cols = min(3, len(settings))
        nrows = (len(settings) + cols - 1) // cols
        # Every panel shows the same part of the network (the union of where things happened),
        # and the figure takes that part's shape: a long road gets flat panels, not white space.
        views = []
        for setting in settings:
            pts = located_points(rep, net, scenario, setting)
            views.append(focus_of(net, pts, [xy for xy in (
                element_xy(net, h["kind"], h["id"]) for h in rows
                if h.get("parameters", "-") == setting) if xy]) or net.bounds())
        views = [v for v in views if v]
        view = (min(v[0] for v in views), min(v[1] for v in views), max(v[2] for v in views),
                max(v[3] for v in views)) if views else None
        if view:  # a margin, and no flatter than 1 : 3 (a long road keeps some room around it)
            w, h = view[2] - view[0], view[3] - view[1]
            pad = 0.04 * max(w, h, 20.0)
            grow = max(0.0, (w + 2 * pad) / 3.0 - (h + 2 * pad)) / 2.0
            view = (view[0] - pad, view[1] - pad - grow, view[2] + pad, view[3] + pad + grow)
        panel_w = min(6.5, (MAX_WIDTH_IN - 1.2) / cols)
        ratio = (view[3] - view[1]) / max(view[2] - view[0], 1.0) if view else 0.8
        panel_h = min(6.0, panel_w * ratio) + 1.1
        fig, axes = cp.new_figure(panel_w * cols + 1.4, panel_h * nrows + 0.9, rows=nrows,
                                  cols=cols)
        axes = axes if isinstance(axes, list) else [axes]
        mappable = None
        for ax, setting in zip(axes, settings):
            mine = [h for h in rows if h.get("parameters", "-") == setting]
            edges = {h["id"]: cp.number(h["warnings"]) or 0 for h in mine if h["kind"] == "edge"}
            junctions = {h["id"]: cp.number(h["warnings"]) or 0 for h in mine
                         if h["kind"] == "junction"}
            busiest = sorted(mine, key=lambda h: (-(cp.number(h["collisions"]) or 0),
                                                  -(cp.number(h["warnings"]) or 0)))[:6]
            labels = []
            for h in busiest:
                xy = element_xy(net, h["kind"], h["id"])
                if xy:
                    labels.append((xy[0], xy[1], h["id"]))
            pts = located_points(rep, net, scenario, setting)
            m = cp.network_map(ax, net, edges, junctions, pts,
                               setting if setting != "-" else scenario, "warnings starting on it",
                               norm=norm, labels=labels, focus=view, colorbar=False,
                               adjustable="box", legend=False)
            mappable = mappable or m
        for ax in axes[len(settings):]:
            ax.set_visible(False)
        legend = {}
        for ax in axes[:len(settings)]:
            for h, label in zip(*ax.get_legend_handles_labels()):
                legend.setdefault(label.split(" (")[0], h)
        if legend:  # one legend below the maps, none on them
            fig.legend(legend.values(), legend.keys(), loc="lower center", ncol=len(legend),
                       frameon=False)
        if mappable is not None:
            bar = fig.colorbar(mappable, ax=axes, fraction=0.025, pad=0.02, shrink=0.9)
            bar.set_label("warnings begun there")
            cp.integer_ticks(bar)
        fig.suptitle(f"Where warnings and collisions happened: {scenario} "
                     f"({os.path.basename(s['net_file'])})")
        path = rep.path(f"map_{safe_name(scenario)}.png")
        cp.save(fig, path, tight=False, crop=True)
        rep.add("maps", path, f"{scenario}: one map per setting; edges and junctions coloured by "
                "warnings that began on them (the same scale on every map), dots: warning "
                "positions, crosses: collisions; labels: the busiest edges and junctions (IDs as "
                "in the hotspot table).")


def reliability_figure(rep):
    rel = rep.manifest.get("reliability", {})
    if not rel.get("available") or not rep.reliability:
        return None
    fig, ax = cp.new_figure(7.0, 5.5)
    cp.reliability_diagram(ax, rep.reliability,
                           f"Reliability: is p calibrated? (Brier score {rel.get('brier', 0):.3f})")
    return cp.save(fig, rep.path("reliability.png"))


# --- warning scenes --------------------------------------------------------------------------


def chosen_warnings(rep, limit):
    """At most `limit` warnings that have a scene, taken in turn from each outcome (false
    alarms, collisions, ...) and within one from each run, so that every kind and every
    setting is shown."""
    by_outcome = {}
    for w in rep.warnings:
        if w.get("scene") == "yes":
            by_outcome.setdefault(w["outcome"], []).append(w)
    for k, ws in by_outcome.items():  # within an outcome, one run after the other in turn
        per_run = {}
        for w in ws:
            per_run.setdefault(w["run_index"], []).append(w)
        queues = list(per_run.values())
        by_outcome[k] = [q[i] for i in range(max(len(q) for q in queues)) for q in queues
                         if i < len(q)]
    order = [k for k in OUTCOME_COLOURS if k in by_outcome] + \
        [k for k in by_outcome if k not in OUTCOME_COLOURS]
    out = []
    while len(out) < limit and any(by_outcome.get(k) for k in order):
        for k in order:
            if by_outcome.get(k) and len(out) < limit:
                out.append(by_outcome[k].pop(0))
    return out


def run_option(command, name, default=None):
    words = (command or "").split()
    for i, w in enumerate(words[:-1]):
        if w == "--" + name:
            return words[i + 1]
    return default


def replay(bench, scene_text, command):
    """The ego's hypotheses from criticality-bench --paths-json, or (None, why not)."""
    if not bench:
        return None, "no criticality-bench found: the picture shows no hypotheses"
    with tempfile.TemporaryDirectory() as tmp:
        scene_file, out = os.path.join(tmp, "w.scene"), os.path.join(tmp, "w.json")
        with open(scene_file, "w", encoding="utf-8") as f:
            f.write(scene_text)
        argv = [bench, "--scene-file", scene_file, "--paths-json", out, "--threads", "1"]
        for opt in ("profiles", "preset"):
            v = run_option(command, opt)
            if v:
                argv += ["--" + opt, v]
        try:
            p = subprocess.run(argv, capture_output=True, text=True, timeout=120)
        except (OSError, subprocess.TimeoutExpired) as e:
            return None, f"criticality-bench failed: {e}"
        if p.returncode != 0 or not os.path.exists(out):
            return None, "criticality-bench failed: " + (p.stderr.strip().splitlines() or ["?"])[-1]
        with open(out, encoding="utf-8") as f:
            return json.load(f), None


def scene_picture(rep, db, w):
    run, wid, ego = int(w["run_index"]), int(w["warning_id"]), w["ego"]
    row = db.execute("SELECT scene FROM warning_scenes WHERE run_index = ? AND warning_id = ?",
                     (run, wid)).fetchone()
    if not row:
        return None
    start = cp.number(w["start_s"])
    end = cp.number(w["end_s"])
    cols = {r[1] for r in db.execute("PRAGMA table_info(steps)")}
    wanted = [c for c in ("p_collision", "p_reference", "unavoidability") if c in cols]
    steps = db.execute(f"SELECT time_s, {', '.join(wanted)} FROM steps WHERE run_index = ? AND "
                       "ego = ? AND time_s >= ? AND time_s <= ? ORDER BY time_s",
                       (run, ego, start - 3.0, (end if end is not None else start) + 2.0)
                       ).fetchall()
    hit = db.execute("SELECT min(time_s) FROM collisions WHERE run_index = ? AND ? IN "
                     "(collider, victim) AND time_s >= ?", (run, ego, start)).fetchone()
    command = (db.execute("SELECT options FROM runs WHERE run_index = ?", (run,)).fetchone()
               or [""])[0]
    threshold = cp.number(run_option(command, "warn-threshold", "0.9"))
    paths, why = replay(rep.manifest.get("bench"), row[0], command)
    scene = sp.read_scene(row[0])
    fig = cp.plt.figure(figsize=(MAX_WIDTH_IN, 5.4))
    grid = fig.add_gridspec(1, 2, width_ratios=[1.55, 1])
    ax_map, ax_p = fig.add_subplot(grid[0]), fig.add_subplot(grid[1])
    sp.draw_scene(ax_map, scene, rep.net(w["scenario"]), paths,
                  title=f"the scene at {start:g} s: {plural(len(scene['vehicles']), 'vehicle')}, "
                        f"{plural(len(scene['pedestrians']), 'person')} around the ego")
    sp.p_over_episode(ax_p, [r[0] for r in steps],
                      {c: [r[k + 1] for r in steps] for k, c in enumerate(wanted)}, start, end,
                      threshold, hit[0] if hit and hit[0] is not None else None)
    ax_p.set_title("p over the episode (recorded)")
    fig.suptitle(f"run {run} \u00b7 {w['scenario']} \u00b7 {w['parameters']} \u00b7 ego {ego} "
                 f"({w.get('vehicle_class') or 'class unknown'}): warning {start:g}\u2013"
                 f"{w['end_s'] or '?'} s, {w['outcome']}")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    os.makedirs(rep.path("scenes"), exist_ok=True)
    path = rep.path(os.path.join("scenes", f"warning_{run}_{wid}.png"))
    cp.save(fig, path, tight=False, crop=True)
    if why:
        rep.notes.append(f"warning scenes: {why}")
    return path


def scene_pictures(rep):
    scenes = rep.path("scenes")
    if os.path.isdir(scenes):  # pictures of an earlier report may show other warnings
        for name in os.listdir(scenes):
            if name.startswith("warning_") and name.endswith(".png"):
                os.remove(os.path.join(scenes, name))
    limit = int(rep.manifest.get("scene_pictures", 0))
    db_path = rep.manifest.get("database")
    if limit <= 0 or not db_path or not os.path.exists(db_path):
        return 0
    db = sqlite3.connect(f"file:{db_path}?mode=ro", uri=True)
    made = 0
    for w in chosen_warnings(rep, limit):
        try:
            path = scene_picture(rep, db, w)
        except (sqlite3.Error, ValueError, KeyError, IndexError) as e:
            rep.notes.append(f"warning scene of run {w['run_index']}, warning "
                             f"{w['warning_id']}: {e}")
            continue
        if path:
            rep.scene_files[(w["run_index"], w["warning_id"])] = "scenes/" + os.path.basename(path)
            made += 1
    db.close()
    return made


# --- the page ---------------------------------------------------------------------------------


def key_figures(rep):
    m = rep.manifest
    boxes = [("runs", f"{m['complete']} of {m['runs']} complete, {m['failed']} failed")]
    hours = sum(cp.number(r.get("vehicle_hours")) or 0 for r in rep.summary)
    km = sum(cp.number(r.get("vehicle_km")) or 0 for r in rep.summary)
    if rep.available.get("vehicle_hours"):
        boxes.append(("exposure", f"{hours:.4g} vehicle-hours, {km:.4g} vehicle-km"))
        for measure, per, unit in (
                ("warnings", "per_vehicle_hour", "per veh-h"),
                ("false alarms", "per_vehicle_hour", "per veh-h"),
                ("ego collisions", "per_million_vehicle_km", "per 10\u2076 veh-km")):
            r = rep.rate("all runs", measure)
            if r:
                boxes.append((measure, f"{r['events']} \u00b7 {ci_text(r, per)} {unit}"))
    return '<div class="key">' + "".join(
        f"<div>{cp.html.escape(k)}<b>{cp.html.escape(v)}</b></div>" for k, v in boxes) + "</div>"


def rates_table(rep, breakdowns):
    rows = []
    for r in rep.rates:
        if r["breakdown"] not in breakdowns:
            continue
        parts = (r["scenario"] if r["scenario"] != "(all)" else "",
                 r["parameters"] if r["parameters"] != "-" else "",
                 r["vehicle_class"] if r["vehicle_class"] != "(all)" else "")
        group = " \u00b7 ".join(x for x in parts if x) or "all runs"
        rows.append({"group": group, "measure": r["measure"], "events": r["events"],
                     "runs": r["runs"], "vehicle_hours": r["vehicle_hours"],
                     "vehicle_km": r["vehicle_km"],
                     "per_h": ci_text(r, "per_vehicle_hour"),
                     "per_km": ci_text(r, "per_million_vehicle_km")})
    return cp.html_table(rows, headers={
        "group": "scenario \u00b7 setting \u00b7 vehicle class", "vehicle_hours": "vehicle-hours",
        "vehicle_km": "vehicle-km", "per_h": "per vehicle-hour [95 % interval]",
        "per_km": "per 10\u2076 vehicle-km [95 % interval]"}, text_columns=("group",), max_rows=400)


def summary_columns(rep, rows):
    keep = ["scenario"] + [a["name"] for a in rep.axes] + [
        "runs", "failed", "ego_collisions", "warned_collisions", "anticipation_mean_s",
        "anticipation_min_s", "warnings", "false_alarms", "collisions_avoided", "vehicle_hours",
        "vehicle_km", "estimator_ms_mean"]
    have = set(rows[0].keys()) if rows else set()
    return [c for c in keep if c in have
            and (c != "collisions_avoided" or any(r.get(c) for r in rows))]


def warnings_section(rep, made):
    if not rep.warnings:
        return "<p>No warnings in any successful run.</p>"
    link = lambda r: rep.scene_files.get((r["run_index"], r["warning_id"]))  # noqa: E731
    rows = [dict(r, scene="picture" if link(r) else
                 ("not drawn" if r["scene"] == "yes" else "not kept")) for r in rep.warnings]
    cols = ["run_index", "scenario", "parameters", "ego", "vehicle_class", "start_s", "end_s",
            "peak_p", "edge", "object", "outcome", "scene"]
    limit = int(rep.manifest.get("scene_pictures", 0))
    text = (f"<p>{len(rep.warnings)} warnings; {made} drawn (at most {limit}, every kind of "
            "outcome in turn; <code>--scene-pictures N</code>). A picture shows the ego's scene "
            "when the warning began, as the estimator saw it: every object's box with its speed "
            "as a 1 s arrow and its share of p, the ego's lanes as sampled, the ego's most "
            "probable and most probable colliding hypotheses replayed by "
            "<code>criticality-bench</code> (the objects' own hypotheses are not drawn), and p "
            "over the episode. All warnings: <a href=\"warnings.csv\">warnings.csv</a>.</p>")
    return text + cp.html_table(rows, cols, headers=SUMMARY_HEADERS, max_rows=300,
                                links={"scene": link}, text_columns=("scenario", "parameters"))


def hotspot_rows(rep, per_group=10):
    out, count = [], {}
    for h in rep.hotspots:
        key = (h["scenario"], h.get("parameters", "-"))
        count[key] = count.get(key, 0) + 1
        if count[key] <= per_group:
            out.append(h)
    return out


def page(rep, made):
    m = rep.manifest
    blocks = [f"<p>Campaign of {m['runs']} runs: {m['complete']} complete ({m['ok']} ok, "
              f"{m['failed']} failed). Metrics count successful runs; seeds are aggregated over "
              "(intervals: 95 % across the seeds and repetitions of a setting). Tables: <a "
              "href=\"summary.md\">summary.md</a> and the CSV files next to this page; every row "
              "of every run: <code>campaign.sqlite</code> (exposure per run and vehicle class: "
              "table "
              "<code>report_exposure</code>).</p>", key_figures(rep)]
    nav = [("outcomes", "Outcomes"), ("rates", "Rates"), ("parameters", "Parameters"),
           ("classes", "Vehicle classes"), ("time", "Over time"), ("maps", "Hotspot maps"),
           ("warnings", "Warnings"), ("tables", "Tables"), ("failures", "Failed runs")]
    blocks.append("<nav>" + "".join(f'<a href="#{a}">{t}</a>' for a, t in nav) + "</nav>")
    if rep.notes:
        blocks.append("<h2>Not computed</h2><ul>" + "".join(
            f'<li class="note">{cp.html.escape(n)}</li>' for n in dict.fromkeys(rep.notes))
            + "</ul>")

    def figs(section):
        return "".join(cp.html_figure(p, c) for p, c in rep.figures.get(section, []))

    blocks.append('<h2 id="outcomes">Outcomes</h2>' + figs("outcomes"))
    blocks.append('<h2 id="rates">Rates per exposure</h2>' + (
        rates_table(rep, ("all runs", "scenario")) if rep.rates else
        "<p>Not computable: the run files have no exposure (see Not computed).</p>"))
    blocks.append('<h2 id="parameters">Parameters</h2>' + (figs("parameters") or
                  "<p>No grid parameter with more than one value.</p>"))
    blocks.append('<h2 id="classes">Vehicle classes of the egos</h2>' + figs("classes") +
                  (cp.html_table(rep.by_class, headers=SUMMARY_HEADERS) if rep.by_class else
                   "<p>Not computable: the run files have no egos table.</p>") +
                  (rates_table(rep, ("vehicle class",)) if rep.by_class else ""))
    blocks.append('<h2 id="time">Over simulated time</h2>' + figs("time"))
    blocks.append('<h2 id="maps">Hotspot maps</h2>' + (figs("maps") or
                  "<p>No located warnings or collisions (or no network file).</p>") +
                  "<h3>Hotspots (the busiest 10 edges and junctions per scenario and setting)"
                  "</h3>" + cp.html_table(hotspot_rows(rep), headers=SUMMARY_HEADERS,
                                          text_columns=("scenario",)))
    blocks.append('<h2 id="warnings">Warnings</h2>' + warnings_section(rep, made))
    blocks.append('<h2 id="tables">Per scenario and setting</h2>' + cp.html_table(
        rep.summary, summary_columns(rep, rep.summary), headers=SUMMARY_HEADERS,
        text_columns=("scenario",)) + '<p>All columns: <a href="summary.csv">summary.csv</a>.</p>')
    if rep.by_param:
        cols = ["parameter", "value"] + [c for c in summary_columns(rep, rep.by_param) if c not in
                                          [a["name"] for a in rep.axes]]
        blocks.append("<h2>Per parameter value</h2>" + cp.html_table(
            rep.by_param, cols, headers=SUMMARY_HEADERS, text_columns=("scenario",)))
    blocks.append('<h2 id="failures">Failed runs</h2>' + (cp.html_table(
        rep.failures, headers=SUMMARY_HEADERS, max_rows=100, text_columns=("error", "parameters"))
        if rep.failures else "<p>None.</p>"))
    if rep.reliability:
        blocks.append("<h2>Reliability</h2>" + figs("reliability") + cp.html_table(rep.reliability))
    cp.write_text(rep.path("index.html"), cp.html_page(f"Campaign {m['name']}", blocks))


def attempt(rep, what, make, *args):
    """One figure; a figure that fails is a note on the page, not a report without figures."""
    try:
        return make(rep, *args)
    except Exception as e:  # noqa: BLE001 (any failure of one figure)
        cp.plt.close("all")
        rep.notes.append(f"figure {what} not drawn: {type(e).__name__}: {e}")
        return None


def main(report_dir):
    rep = Report(report_dir)
    if rep.summary:
        rep.add("outcomes", attempt(rep, "overview", overview_figure),
                "Ego collisions, those warned before, false alarms and failed runs per scenario, "
                "summed over settings and seeds.")
    for axis in rep.axes:
        if len(axis["values"]) > 1:
            rep.add("parameters", attempt(rep, f"parameter {axis['name']}", parameter_figure, axis),
                    f"Per value of {axis['name']}: one line per scenario and one over all "
                    "scenarios ((all)); rates with 95 % intervals across seeds and repetitions.")
    rep.add("classes", attempt(rep, "vehicle classes", class_figure),
            "Rates per vehicle class (SUMO's vClass) of the egos.")
    rep.add("time", attempt(rep, "over time", time_figure), "When warnings began (stacked by what "
            "followed them) and when located collisions happened, over all successful runs.")
    attempt(rep, "maps", map_figures)
    rep.add("reliability", attempt(rep, "reliability", reliability_figure),
            "Predicted p against observed collisions; consecutive steps are correlated.")
    made = attempt(rep, "warning scenes", scene_pictures) or 0
    page(rep, made)
    count = sum(len(v) for v in rep.figures.values())
    print(f"campaign_report: {count} figures, {made} warning scenes, index.html in {report_dir}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: campaign_report.py REPORT_DIR")
    main(sys.argv[1])
