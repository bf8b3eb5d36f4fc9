#!/usr/bin/env python3
"""Figures and the HTML page of a campaign report.

Called by `criticality-campaign report DIR` after it has written the tables into DIR/report/
(summary.csv, by_parameter.csv, failures.csv, hotspots.csv, events.csv, reliability.csv and the
manifest report.json). Writes PNG figures and index.html next to them. Usage:
    campaign_report.py DIR/report
Generic plotting and HTML helpers live in tools/plots/criticality_plots.py.
"""

import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plots"))
import criticality_plots as cp  # noqa: E402


def safe_name(text):
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)


def overview_figure(out, summary, scenarios):
    """Per scenario: ego collisions, warned ones, false alarms and failed runs (all parameters)."""
    totals = {s: {"ego collisions": 0.0, "warned collisions": 0.0, "false alarms": 0.0,
                  "failed runs": 0.0} for s in scenarios}
    for r in summary:
        t = totals.setdefault(r["scenario"], {k: 0.0 for k in next(iter(totals.values()))})
        t["ego collisions"] += cp.number(r["ego_collisions"]) or 0
        t["warned collisions"] += cp.number(r["warned_collisions"]) or 0
        t["false alarms"] += cp.number(r["false_alarms"]) or 0
        t["failed runs"] += cp.number(r["failed"]) or 0
    names = list(totals)
    series = {k: [totals[s][k] for s in names] for k in next(iter(totals.values()))}
    fig, ax = cp.new_figure(max(6.0, 1.1 * len(names) + 3), 4.0)
    cp.grouped_bars(ax, names, series, "count (all runs)",
                    "Outcomes per scenario (summed over parameters and seeds)", labels=True)
    return cp.save(fig, os.path.join(out, "overview.png"))


def parameter_figure(out, axis, by_param, scenarios):
    """Anticipation, collisions, false alarms and estimator time against one parameter."""
    rows = [r for r in by_param if r["parameter"] == axis["name"]]
    values = axis["values"]
    present = [s for s in scenarios if any(r["scenario"] == s for r in rows)]
    curves = (["(all)"] if len(present) > 1 else []) + present

    def series(column):
        out_series = {}
        for s in curves:
            ys = []
            for v in values:
                hit = [r for r in rows if r["value"] == v and r["scenario"] == s]
                ys.append(cp.number(hit[0][column]) if hit else None)
            out_series[s] = ys
        return out_series

    fig, axes = cp.new_figure(11.0, 7.0, rows=2, cols=2)
    name = axis["name"]
    cp.line_by_category(axes[0], values, series("anticipation_mean_s"),
                        "anticipation time, mean (s)", f"Anticipation vs {name}", name)
    cp.line_by_category(axes[1], values, series("ego_collisions"), "ego collisions",
                        f"Ego collisions vs {name}", name)
    cp.line_by_category(axes[2], values, series("false_alarms"), "false alarms",
                        f"False alarms vs {name}", name)
    cp.line_by_category(axes[3], values, series("estimator_ms_mean"), "estimator time (ms)",
                        f"Estimator time per estimate vs {name}", name)
    return cp.save(fig, os.path.join(out, f"parameter_{safe_name(name)}.png"))


def map_figure(out, scenario, net_file, hotspots, events):
    net = cp.SumoNet(net_file)
    edge_values, junction_values = {}, {}
    for h in hotspots:
        if h["scenario"] != scenario:
            continue
        v = (cp.number(h["collisions"]) or 0) + (cp.number(h["warnings"]) or 0)
        (edge_values if h["kind"] == "edge" else junction_values)[h["id"]] = v
    points = []
    for e in events:
        if e["scenario"] != scenario:
            continue
        x, y = cp.number(e["x_m"]), cp.number(e["y_m"])
        if (x is None or y is None) and e["lane"] and cp.number(e["pos_m"]) is not None:
            xy = net.lane_point(e["lane"], cp.number(e["pos_m"]))
            x, y = xy if xy else (None, None)
        if x is not None and y is not None:
            points.append((x, y, e["event"]))
    if not edge_values and not junction_values and not points:
        return None
    fig, ax = cp.new_figure(8.0, 6.5)
    cp.network_map(ax, net, edge_values, junction_values, points,
                   f"Hotspots: {scenario} ({os.path.basename(net_file)})",
                   "collisions + warnings")
    return cp.save(fig, os.path.join(out, f"map_{safe_name(scenario)}.png"))


def main(report_dir):
    with open(os.path.join(report_dir, "report.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    summary = cp.read_csv(os.path.join(report_dir, "summary.csv"))
    by_param = cp.read_csv(os.path.join(report_dir, "by_parameter.csv"))
    failures = cp.read_csv(os.path.join(report_dir, "failures.csv"))
    hotspots = cp.read_csv(os.path.join(report_dir, "hotspots.csv"))
    events = cp.read_csv(os.path.join(report_dir, "events.csv"))
    reliability = cp.read_csv(os.path.join(report_dir, "reliability.csv"))
    scenarios = [s["name"] for s in manifest.get("scenarios", [])]

    figures = []  # (file, caption)
    if summary:
        figures.append((overview_figure(report_dir, summary, scenarios),
                        "Ego collisions, collisions with a warning before them, false alarms and "
                        "failed runs per scenario."))
    for axis in manifest.get("axes", []):
        if axis.get("grouping") and len(axis["values"]) > 1:
            figures.append((parameter_figure(report_dir, axis, by_param, scenarios),
                            f"Per value of {axis['name']}: one line per scenario and one over "
                            "all scenarios ((all)); seeds aggregated."))
    for s in manifest.get("scenarios", []):
        if s.get("net_file"):
            path = map_figure(report_dir, s["name"], s["net_file"], hotspots, events)
            if path:
                figures.append((path, f"Where collisions (x) and warnings happened on "
                                      f"{s['name']}; edges and junctions coloured by count."))
    rel = manifest.get("reliability", {})
    if rel.get("available") and reliability:
        fig, ax = cp.new_figure(6.0, 5.0)
        cp.reliability_diagram(ax, reliability, "Reliability: is p calibrated? "
                               f"(Brier {rel.get('brier', 0):.3f})")
        figures.append((cp.save(fig, os.path.join(report_dir, "reliability.png")),
                        f"{rel['steps']} estimates of egos, {rel['ego_collisions']} of which collided, "
                        "binned by p; consecutive steps are correlated."))

    blocks = [
        f"<p>{manifest['runs']} runs planned, {manifest['complete']} complete "
        f"({manifest['ok']} ok, {manifest['failed']} failed). Metrics count successful runs; "
        "seeds are aggregated over. Tables: <a href=\"summary.md\">summary.md</a> and the CSV "
        "files next to this page; every row of every run: <code>campaign.sqlite</code>.</p>"]
    notes = manifest.get("notes", [])
    if notes:
        blocks.append("<h2>Not computed</h2><ul>" + "".join(
            f"<li class=\"note\">{cp.html.escape(n)}</li>" for n in notes) + "</ul>")
    blocks.append("<h2>Figures</h2>" + "".join(
        cp.html_figure(os.path.basename(p), c) for p, c in figures))
    blocks.append("<h2>Per scenario and parameters</h2>" + cp.html_table(summary))
    if by_param:
        blocks.append("<h2>Per parameter value</h2>" + cp.html_table(by_param))
    blocks.append("<h2>Failed runs</h2>" + cp.html_table(failures, max_rows=100))
    blocks.append("<h2>Hotspots</h2>" + cp.html_table(hotspots, max_rows=30))
    if reliability:
        blocks.append("<h2>Reliability</h2>" + cp.html_table(reliability))
    cp.write_text(os.path.join(report_dir, "index.html"),
                  cp.html_page(f"Campaign {manifest['name']}", blocks))
    print(f"campaign_report: {len(figures)} figures, index.html in {report_dir}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: campaign_report.py REPORT_DIR")
    main(sys.argv[1])
