"""Plot and HTML helpers for sumo-criticality reports.

Generic pieces shared by the campaign report (tools/campaign/campaign_report.py) and the
evaluation (tools/evaluate/): reading the CSV tables the C++ tools write, line and bar charts over
categorical parameter values, a reliability diagram, an ego's criticality over time with its
warnings and collision, trade-off curves (anticipation against false alarms), a map of a SUMO
network with values per edge and junction and event points, and a self-contained HTML page
around the figures and tables.
Needs Python 3 and matplotlib (Debian: python3-matplotlib); no sumolib: the .net.xml is read
with the standard library.
"""

import csv
import gzip
import html
import math
import os
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")  # headless: files only
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import cm, colors  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

# --- tables -------------------------------------------------------------------------------


def read_csv(path):
    """Rows of a CSV file with a header, as dicts; [] when the file is missing."""
    if not os.path.exists(path):
        return []
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def number(text):
    """A table cell as a float; None for an empty or non-numeric cell."""
    if text is None or text == "":
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


# --- figures ------------------------------------------------------------------------------


def new_figure(width=7.0, height=4.0, rows=1, cols=1):
    """A figure and its axes (a list when rows * cols > 1)."""
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False)
    flat = [a for row in axes for a in row]
    return fig, (flat if len(flat) > 1 else flat[0])


def save(fig, path, dpi=110):
    """Writes the figure (format from the extension) and closes it."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def line_by_category(ax, categories, series, ylabel, title=None, xlabel=None):
    """One line per series over categorical x values; None values leave gaps.

    series: {label: [y per category]}."""
    x = list(range(len(categories)))
    for label, ys in series.items():
        ys = [float("nan") if y is None else y for y in ys]
        ax.plot(x, ys, marker="o", label=label)
    ax.set_xticks(x)
    ax.set_xticklabels([str(c) for c in categories])
    ax.set_ylabel(ylabel)
    if xlabel:
        ax.set_xlabel(xlabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if len(series) > 1:
        ax.legend(fontsize=7)


def grouped_bars(ax, categories, series, ylabel, title=None, stacked=False, labels=False,
                 label_format=None):
    """Bars per category, one colour per series ({label: [value per category]}; None draws no
    bar); with labels, each bar carries its value, written by label_format(value) when given
    (it also gets the None values, e.g. to write "missed")."""
    n = max(1, len(series))
    width = 0.8 if stacked else 0.8 / n
    bottom = [0.0] * len(categories)
    for k, (label, raw) in enumerate(series.items()):
        values = [0.0 if v is None else v for v in raw]
        if stacked:
            xs = list(range(len(categories)))
            ax.bar(xs, values, width, bottom=bottom, label=label)
            bottom = [b + v for b, v in zip(bottom, values)]
        else:
            xs = [i - 0.4 + width * (k + 0.5) for i in range(len(categories))]
            bars = ax.bar(xs, values, width, label=label)
            if labels:
                texts = ([label_format(v) for v in raw] if label_format
                         else [f"{v:g}" for v in values])
                ax.bar_label(bars, labels=texts, fontsize=7, padding=1,
                             rotation=90 if label_format else 0)
    ax.set_xticks(list(range(len(categories))))
    ax.set_xticklabels([str(c) for c in categories], rotation=20, ha="right", fontsize=8)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, axis="y", alpha=0.3)
    if len(series) > 1:
        ax.legend(fontsize=7)


def reliability_diagram(ax, bins, title="Reliability"):
    """Predicted p (mean per bin) against the observed frequency, with the diagonal of perfect
    calibration and the number of estimates per bin on a second axis.

    bins: rows with p_low, p_high, steps, mean_p, observed_frequency."""
    ax.plot([0, 1], [0, 1], color="grey", linestyle="--", linewidth=1, label="calibrated")
    pts = [(number(b["mean_p"]), number(b["observed_frequency"])) for b in bins
           if number(b["steps"]) and number(b["mean_p"]) is not None]
    if pts:
        ax.plot([p for p, _ in pts], [o for _, o in pts], marker="o", label="estimator")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("predicted collision probability p")
    ax.set_ylabel("observed collision frequency")
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    counts = ax.twinx()
    lows = [number(b["p_low"]) for b in bins]
    highs = [number(b["p_high"]) for b in bins]
    steps = [number(b["steps"]) or 0 for b in bins]
    counts.bar([(lo + hi) / 2 for lo, hi in zip(lows, highs)], steps,
               width=[(hi - lo) * 0.9 for lo, hi in zip(lows, highs)], alpha=0.15, color="C1")
    counts.set_yscale("log" if max(steps, default=0) > 100 else "linear")
    counts.set_ylabel("estimates per bin", fontsize=8)
    ax.set_zorder(counts.get_zorder() + 1)  # the curve above the count bars
    ax.patch.set_visible(False)


def criticality_timeline(ax, series, threshold=None, collision_s=None, quiet_until_s=None,
                         episodes=(), bands=(), title=None, ylabel="collision probability p"):
    """An ego's criticality over time (the paper's Fig. "results"): one line per series, the
    warning threshold, the end of the quiet phase, the collision, shaded warning episodes and
    thin bands under the curves (e.g. another detector's critical intervals).

    series: {label: (times, values)} or {label: (times, values, style dict)};
    episodes: [(start, end)] (end None: until the last time shown);
    bands: [(label, [(start, end)], colour)], drawn one above the other below p = 0."""
    t_max = 0.0
    for k, (label, data) in enumerate(series.items()):
        times, values = data[0], data[1]
        style = dict(data[2]) if len(data) > 2 else {}
        style.setdefault("linewidth", 1.4 if k == 0 else 1.1)
        if times:
            ax.plot(times, [float("nan") if v is None else v for v in values], label=label,
                    **style)
            t_max = max(t_max, times[-1])
    for start, end in episodes:
        ax.axvspan(start, t_max if end is None else end, color="red", alpha=0.12, linewidth=0)
    if episodes:
        ax.plot([], [], color="red", alpha=0.3, linewidth=6, label="warning")
    if threshold is not None:
        ax.axhline(threshold, color="grey", linestyle=":", linewidth=1,
                   label=f"threshold {threshold:g}")
    if quiet_until_s is not None and quiet_until_s > 0:
        ax.axvline(quiet_until_s, color="grey", linestyle="--", linewidth=1, label="quiet phase end")
    if collision_s is not None:
        ax.axvline(collision_s, color="black", linewidth=1.5, label="collision (SUMO)")
    for k, (label, intervals, colour) in enumerate(bands):
        y0 = -0.06 - 0.05 * k
        for start, end in intervals:
            ax.plot([start, t_max if end is None else end], [y0, y0], color=colour, linewidth=4,
                    solid_capstyle="butt")
        ax.plot([], [], color=colour, linewidth=4, label=label)
    ax.set_ylim(-0.08 - 0.05 * len(bands), 1.05)
    ax.set_xlabel("time (s)")
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)


def tradeoff_curve(ax, curves, xlabel, ylabel, title=None, log_x=False, highlight=None):
    """Curves of (x, y) points, each point labelled with its setting (e.g. anticipation against
    false alarms, one point per threshold).

    curves: {label: [(x, y, point label)]}; highlight: {label: point label} marked larger."""
    highlight = highlight or {}
    drawn = 0
    for label, pts in curves.items():
        pts = [(x, y, t) for x, y, t in pts if x is not None and y is not None]
        if not pts:
            continue
        drawn += 1
        xs = [max(x, 1e-3) if log_x else x for x, _, _ in pts]
        line = ax.plot(xs, [y for _, y, _ in pts], marker="o", markersize=3, label=label)[0]
        for x, (_, y, text) in zip(xs, pts):
            ax.annotate(str(text), (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
            if highlight.get(label) == text:
                ax.plot([x], [y], marker="o", markersize=9, markerfacecolor="none",
                        color=line.get_color())
    if log_x:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if drawn > 1:
        ax.legend(fontsize=7)


# --- SUMO networks ------------------------------------------------------------------------


def _shape(text):
    pts = []
    for pair in (text or "").split():
        xy = pair.split(",")
        if len(xy) >= 2:
            pts.append((float(xy[0]), float(xy[1])))
    return pts


class SumoNet:
    """Lanes and junctions of a SUMO .net.xml (or .net.xml.gz)."""

    def __init__(self, path):
        self.path = path
        self.lanes = {}  # lane id -> (edge id, internal?, shape)
        self.junctions = {}  # junction id -> (x, y, shape)
        opener = gzip.open if path.endswith(".gz") else open
        with opener(path, "rb") as f:
            edge, internal = None, False
            for event, el in ET.iterparse(f, events=("start", "end")):
                if event == "start" and el.tag == "edge":
                    edge = el.get("id")
                    internal = el.get("function") in ("internal", "crossing", "walkingarea")
                elif event == "start" and el.tag == "lane" and edge is not None:
                    self.lanes[el.get("id")] = (edge, internal, _shape(el.get("shape")))
                elif event == "end" and el.tag == "edge":
                    edge = None
                    el.clear()
                elif event == "end" and el.tag == "junction":
                    if el.get("type") != "internal":
                        self.junctions[el.get("id")] = (float(el.get("x", 0)),
                                                        float(el.get("y", 0)),
                                                        _shape(el.get("shape")))
                    el.clear()

    def lane_point(self, lane, pos):
        """The point `pos` metres along a lane's shape (clamped to its ends); None if unknown."""
        entry = self.lanes.get(lane)
        if not entry or not entry[2]:
            return None
        shape = entry[2]
        left = max(0.0, pos)
        for (x0, y0), (x1, y1) in zip(shape, shape[1:]):
            seg = math.hypot(x1 - x0, y1 - y0)
            if left <= seg and seg > 0:
                t = left / seg
                return (x0 + t * (x1 - x0), y0 + t * (y1 - y0))
            left -= seg
        return shape[-1]

    def edge_lines(self, internal=False):
        """{edge id: [lane shapes]} of normal (or internal) edges."""
        out = {}
        for edge, is_internal, shape in self.lanes.values():
            if is_internal == internal and len(shape) >= 2:
                out.setdefault(edge, []).append(shape)
        return out


def network_map(ax, net, edge_values=None, junction_values=None, points=None, title=None,
                value_label="events"):
    """The network in grey; edges coloured (and thickened) by edge_values, junctions circled by
    junction_values, and event points on top.

    edge_values / junction_values: {id: number}; points: [(x, y, label)] drawn per label."""
    edge_values = edge_values or {}
    junction_values = junction_values or {}
    for _, (x, y, shape) in net.junctions.items():
        if len(shape) >= 3:
            ax.fill([p[0] for p in shape], [p[1] for p in shape], color="#e4e4e4", zorder=1)
    base = [s for shapes in net.edge_lines().values() for s in shapes]
    ax.add_collection(LineCollection(base, colors="#b0b0b0", linewidths=0.8, zorder=2))
    vmax = max(list(edge_values.values()) + list(junction_values.values()) + [1])
    norm = colors.Normalize(vmin=0, vmax=vmax)
    cmap = matplotlib.colormaps["inferno_r"]
    lines, cols, widths = [], [], []
    shapes_of = net.edge_lines()
    shapes_of.update(net.edge_lines(internal=True))
    for edge, v in edge_values.items():
        for s in shapes_of.get(edge, []):
            lines.append(s)
            cols.append(cmap(norm(v)))
            widths.append(1.5 + 4.0 * v / vmax)
    if lines:
        ax.add_collection(LineCollection(lines, colors=cols, linewidths=widths, zorder=3))
    jx, jy, jv = [], [], []
    for j, v in junction_values.items():
        if j in net.junctions:
            jx.append(net.junctions[j][0])
            jy.append(net.junctions[j][1])
            jv.append(v)
    if jv:
        ax.scatter(jx, jy, s=[40 + 260 * v / vmax for v in jv], c=[cmap(norm(v)) for v in jv],
                   edgecolors="black", linewidths=0.5, zorder=4, alpha=0.85)
    markers = {"collision": ("x", "red"), "warning": (".", "darkorange")}
    by_label = {}
    for x, y, label in points or []:
        by_label.setdefault(label, []).append((x, y))
    for label, pts in by_label.items():
        m, c = markers.get(label, ("o", "blue"))
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], marker=m, color=c, s=22, zorder=5,
                   label=f"{label}s ({len(pts)})", linewidths=1.2)
    if edge_values or junction_values:
        sm = cm.ScalarMappable(norm=norm, cmap=cmap)
        sm.set_array([])
        plt.colorbar(sm, ax=ax, fraction=0.04, pad=0.02).set_label(value_label, fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if by_label:
        ax.legend(fontsize=7, loc="best")
    if title:
        ax.set_title(title, fontsize=10)


# --- HTML ---------------------------------------------------------------------------------

_STYLE = """
body { font-family: sans-serif; margin: 2em; max-width: 1200px; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; font-size: 0.8em; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
th { background: #f0f0f0; } td:first-child, th:first-child { text-align: left; }
figure { display: inline-block; margin: 0.5em; vertical-align: top; }
figcaption { font-size: 0.85em; color: #555; max-width: 640px; }
img { max-width: 640px; border: 1px solid #ddd; }
.note { color: #8a4b00; }
"""


def html_table(rows, columns=None, max_rows=None):
    """An HTML table of dict rows (columns: the first row's keys unless given)."""
    if not rows:
        return "<p>(none)</p>"
    columns = columns or list(rows[0].keys())
    out = ["<table><tr>" + "".join(f"<th>{html.escape(c)}</th>" for c in columns) + "</tr>"]
    shown = rows if max_rows is None else rows[:max_rows]
    for r in shown:
        out.append("<tr>" + "".join(f"<td>{html.escape(str(r.get(c, '')))}</td>"
                                    for c in columns) + "</tr>")
    out.append("</table>")
    if max_rows is not None and len(rows) > max_rows:
        out.append(f"<p>({len(rows) - max_rows} more rows in the CSV file)</p>")
    return "\n".join(out)


def html_figure(src, caption):
    return (f'<figure><a href="{html.escape(src)}"><img src="{html.escape(src)}" '
            f'alt="{html.escape(caption)}"></a><figcaption>{html.escape(caption)}'
            "</figcaption></figure>")


def html_page(title, blocks):
    """A self-contained page: the title, then the blocks (HTML strings) in order."""
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head><body>\n"
            f"<h1>{html.escape(title)}</h1>\n" + "\n".join(blocks) + "\n</body></html>\n")


def write_text(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path
