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

# Sizes for a screen and for print: a figure of W inches is shown W x 100 px wide (a 12 in
# figure fills a 1200 px column), its PNG has twice that resolution (sharp on high-density
# screens, 200 dpi on paper), and text is 10-12 pt at that scale.
SCREEN_PX_PER_INCH = 100
SAVE_DPI = 200
DISPLAY_WIDTH = {}  # file name -> width in px at which the page shows it

plt.rcParams.update({
    "font.size": 11, "axes.titlesize": 12, "axes.labelsize": 11, "legend.fontsize": 10,
    "xtick.labelsize": 10, "ytick.labelsize": 10, "figure.titlesize": 13,
    "legend.framealpha": 0.85, "axes.spines.top": False, "axes.spines.right": False,
})


def new_figure(width=7.0, height=4.0, rows=1, cols=1):
    """A figure and its axes (a list when rows * cols > 1)."""
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False)
    flat = [a for row in axes for a in row]
    return fig, (flat if len(flat) > 1 else flat[0])


def save(fig, path, dpi=SAVE_DPI, tight=True, crop=False):
    """Writes the figure (format from the extension) and closes it; remembers the width at
    which a page shows it (html_figure). crop: cut the file to what is drawn (legends outside
    the axes included)."""
    if tight:
        fig.tight_layout()
    extra = {"bbox_inches": "tight", "pad_inches": 0.12} if crop else {}
    fig.savefig(path, dpi=dpi, **extra)
    width_in = fig.get_figwidth()
    if crop:
        from PIL import Image  # matplotlib depends on Pillow
        with Image.open(path) as im:
            width_in = im.size[0] / dpi
    DISPLAY_WIDTH[os.path.basename(path)] = int(round(width_in * SCREEN_PX_PER_INCH))
    plt.close(fig)
    return path


def readable_numbers(ax, axis="y"):
    """Tick labels without an exponent offset: 1 200, 35k, 2.5M."""
    from matplotlib.ticker import FuncFormatter

    def fmt(v, _pos):
        a = abs(v)
        if a >= 1e6:
            return f"{v / 1e6:g}M"
        if a >= 1e4:
            return f"{v / 1e3:g}k"
        return f"{v:g}"

    (ax.yaxis if axis == "y" else ax.xaxis).set_major_formatter(FuncFormatter(fmt))


def empty_note(ax, text, title=None):
    """An axes that has nothing to plot says so ("no collisions in any run") instead of
    showing empty or flat axes."""
    ax.set_xticks([])
    ax.set_yticks([])
    for side in ax.spines.values():
        side.set_visible(False)
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, wrap=True,
            color="#555555", fontsize=11)
    if title:
        ax.set_title(title)


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
        ax.set_title(title)
    ax.grid(True, alpha=0.3)
    if len(series) > 1:
        ax.legend()


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
                ax.bar_label(bars, labels=texts, fontsize=9, padding=1,
                             rotation=90 if label_format else 0)
    ax.set_xticks(list(range(len(categories))))
    ax.set_xticklabels([str(c) for c in categories], rotation=20, ha="right")
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.grid(True, axis="y", alpha=0.3)
    if len(series) > 1:
        ax.legend()


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
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left")
    counts = ax.twinx()
    lows = [number(b["p_low"]) for b in bins]
    highs = [number(b["p_high"]) for b in bins]
    steps = [number(b["steps"]) or 0 for b in bins]
    counts.bar([(lo + hi) / 2 for lo, hi in zip(lows, highs)], steps,
               width=[(hi - lo) * 0.9 for lo, hi in zip(lows, highs)], alpha=0.15, color="C1")
    counts.set_yscale("log" if max(steps, default=0) > 100 else "linear")
    counts.set_ylabel("estimates per bin")
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
        ax.set_title(title)
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
            ax.annotate(str(text), (x, y), fontsize=8, xytext=(3, 3), textcoords="offset points")
            if highlight.get(label) == text:
                ax.plot([x], [y], marker="o", markersize=9, markerfacecolor="none",
                        color=line.get_color())
    if log_x:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.grid(True, alpha=0.3)
    if drawn > 1:
        ax.legend()


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

    def bounds(self):
        """(xmin, ymin, xmax, ymax) of the normal lanes; None without any."""
        pts = [p for _, internal, shape in self.lanes.values() if not internal for p in shape]
        if not pts:
            return None
        return (min(p[0] for p in pts), min(p[1] for p in pts), max(p[0] for p in pts),
                max(p[1] for p in pts))

    def edge_middle(self, edge):
        """The point halfway along an edge's first lane; None if unknown."""
        lanes = [lane for lane, (e, _, shape) in self.lanes.items() if e == edge and shape]
        if not lanes:
            return None
        shape = self.lanes[sorted(lanes)[0]][2]
        length = sum(math.hypot(x1 - x0, y1 - y0) for (x0, y0), (x1, y1) in zip(shape, shape[1:]))
        return self.lane_point(sorted(lanes)[0], length / 2)

    def edge_lines(self, internal=False):
        """{edge id: [lane shapes]} of normal (or internal) edges."""
        out = {}
        for edge, is_internal, shape in self.lanes.values():
            if is_internal == internal and len(shape) >= 2:
                out.setdefault(edge, []).append(shape)
        return out


def network_map(ax, net, edge_values=None, junction_values=None, points=None, title=None,
                value_label="events", norm=None, cmap="YlOrRd", labels=None, focus=None,
                colorbar=True, adjustable="datalim", legend=True):
    """The network in grey; edges coloured (and thickened) by edge_values, junctions circled by
    junction_values (one quantity, one colour scale: give the same `norm` to every map of a
    report so that colours compare), event points on top, and text labels.

    edge_values / junction_values: {id: number}; points: [(x, y, label)] drawn per label
    (collision: red x, warning: dark dot); labels: [(x, y, text)] with a white outline;
    focus: (xmin, ymin, xmax, ymax) to show, else the whole network. Returns the colour
    scale's mappable (for a shared colour bar), or None when nothing was coloured."""
    import matplotlib.patheffects as pe
    edge_values = edge_values or {}
    junction_values = junction_values or {}
    for _, (x, y, shape) in net.junctions.items():
        if len(shape) >= 3:
            ax.fill([p[0] for p in shape], [p[1] for p in shape], color="#e8e8e8", zorder=1)
    base = [s for shapes in net.edge_lines().values() for s in shapes]
    ax.add_collection(LineCollection(base, colors="#a8a8a8", linewidths=0.8, zorder=2))
    vmax = max(list(edge_values.values()) + list(junction_values.values()) + [1])
    norm = norm or colors.Normalize(vmin=0, vmax=vmax)
    cmap = matplotlib.colormaps[cmap] if isinstance(cmap, str) else cmap
    lines, cols, widths = [], [], []
    shapes_of = net.edge_lines()
    shapes_of.update(net.edge_lines(internal=True))
    for edge, v in edge_values.items():
        if v <= 0:
            continue
        for s in shapes_of.get(edge, []):
            lines.append(s)
            cols.append(cmap(norm(v)))
            widths.append(2.0 + 4.0 * min(1.0, v / norm.vmax))
    if lines:
        ax.add_collection(LineCollection(lines, colors=cols, linewidths=widths, zorder=3))
    jx, jy, jv = [], [], []
    for j, v in junction_values.items():
        if j in net.junctions and v > 0:
            jx.append(net.junctions[j][0])
            jy.append(net.junctions[j][1])
            jv.append(v)
    if jv:
        ax.scatter(jx, jy, s=[60 + 240 * min(1.0, v / norm.vmax) for v in jv],
                   c=[cmap(norm(v)) for v in jv], edgecolors="black", linewidths=0.6, zorder=4)
    markers = {"collision": ("x", "#c00000", 40), "warning": (".", "#303030", 30)}
    by_label = {}
    for x, y, label in points or []:
        by_label.setdefault(label, []).append((x, y))
    for label, pts in sorted(by_label.items(), reverse=True):
        m, c, size = markers.get(label, ("o", "blue", 20))
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], marker=m, color=c, s=size, zorder=5,
                   label=f"{label}s ({len(pts)})", linewidths=1.5)
    xs = [p[0] for s in base for p in s] + [p[0] for p in points or []] or [0.0]
    ys = [p[1] for s in base for p in s] + [p[1] for p in points or []] or [0.0]
    view = focus or (min(xs), min(ys), max(xs), max(ys))
    near = 0.04 * max(view[2] - view[0], view[3] - view[1], 1.0)
    placed = []
    for k, (x, y, text) in enumerate(labels or []):
        # Labels that would overlap an earlier one sit on the other side of their point.
        crowded = any(abs(x - px) < near and abs(y - py) < near for px, py in placed)
        offset = (-6, -12) if crowded else (5, 5)
        ax.annotate(text, (x, y), xytext=offset, textcoords="offset points", fontsize=9,
                    ha="right" if crowded else "left", zorder=6,
                    path_effects=[pe.withStroke(linewidth=3, foreground="white")])
        placed.append((x, y))
    mappable = None
    if edge_values or junction_values:
        mappable = cm.ScalarMappable(norm=norm, cmap=cmap)
        mappable.set_array([])
        if colorbar:
            bar = plt.colorbar(mappable, ax=ax, fraction=0.04, pad=0.02)
            bar.set_label(value_label)
            integer_ticks(bar)
    ax.set_aspect("equal", adjustable=adjustable)
    if focus:
        ax.set_xlim(focus[0], focus[2])
        ax.set_ylim(focus[1], focus[3])
    else:
        ax.autoscale_view()
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if by_label and legend:
        ax.legend(loc="best")
    if title:
        ax.set_title(title)
    return mappable


def integer_ticks(colorbar):
    """Counts on a colour bar: whole numbers only."""
    from matplotlib.ticker import MaxNLocator
    colorbar.locator = MaxNLocator(integer=True)
    colorbar.update_ticks()


# --- HTML ---------------------------------------------------------------------------------

_STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em auto; max-width: 1320px; padding: 0 1em;
       color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { font-size: 1.25em; margin-top: 1.8em; border-bottom: 1px solid #ccc; }
h3 { font-size: 1.05em; margin-top: 1.2em; }
.table-wrap { max-width: 100%; overflow-x: auto; margin: 0.5em 0; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #d0d0d0; padding: 3px 7px; text-align: right; vertical-align: top; }
th { background: #f0f0f0; font-weight: 600; max-width: 9em; white-space: normal; }
td { white-space: nowrap; }
td.text { text-align: left; white-space: normal; max-width: 16em; overflow-wrap: anywhere; }
tr:nth-child(even) td { background: #fafafa; }
td:first-child, th:first-child { text-align: left; }
figure { display: block; margin: 1em 0; }
figcaption { font-size: 0.9em; color: #444; max-width: 1150px; }
img { max-width: 100%; height: auto; border: 1px solid #ddd; }
.note { color: #8a4b00; } .key { display: flex; flex-wrap: wrap; gap: 0.8em; }
.key div { border: 1px solid #ccc; border-radius: 4px; padding: 0.4em 0.8em; background: #f8f8f8; }
.key b { display: block; font-size: 1.2em; }
nav a { margin-right: 1em; }
@media print { body { max-width: none; margin: 0; } nav { display: none; }
  figure, table { page-break-inside: avoid; } img { border: none; } }
"""

_UNITS = [("_per_million_vehicle_km", " per 10\u2076 veh-km"), ("_per_vehicle_hour", " per veh-h"),
          ("_mps", " (m/s)"), ("_ms", " (ms)"), ("_kb", " (kB)"), ("_km", " (km)"),
          ("_s", " (s)"), ("_m", " (m)"), ("_p", " p")]


def header_label(column):
    """A table header from a snake_case column name: words, and the unit its suffix names
    (anticipation_mean_s -> "anticipation mean (s)")."""
    for suffix, unit in _UNITS:
        if column.endswith(suffix) and len(column) > len(suffix):
            return column[: -len(suffix)].replace("_", " ") + unit
    return column.replace("_", " ")


def html_table(rows, columns=None, max_rows=None, headers=None, links=None, text_columns=()):
    """An HTML table of dict rows (columns: the first row's keys unless given), in a box that
    scrolls sideways instead of widening the page; headers: {column: label} (default
    header_label); links: {column: function(row) -> href or None}; text_columns: left-aligned,
    wrapping columns."""
    if not rows:
        return "<p>(none)</p>"
    columns = columns or list(rows[0].keys())
    headers = headers or {}
    links = links or {}
    out = ['<div class="table-wrap"><table><tr>' + "".join(
        f"<th>{html.escape(headers.get(c, header_label(c)))}</th>" for c in columns) + "</tr>"]
    shown = rows if max_rows is None else rows[:max_rows]
    for r in shown:
        cells = []
        for c in columns:
            text = html.escape(str(r.get(c, "")))
            href = links[c](r) if c in links else None
            if href:
                text = f'<a href="{html.escape(href)}">{text}</a>'
            cls = ' class="text"' if c in text_columns else ""
            cells.append(f"<td{cls}>{text}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table></div>")
    if max_rows is not None and len(rows) > max_rows:
        out.append(f"<p>({len(rows) - max_rows} more rows in the CSV file)</p>")
    return "\n".join(out)


def html_figure(src, caption, extra=""):
    """A figure shown at its screen width (save() remembers it), linked to the full-resolution
    file; `extra`: HTML after the caption (e.g. a link to its data)."""
    width = DISPLAY_WIDTH.get(os.path.basename(src))
    size = f' width="{width}"' if width else ""
    return (f'<figure><a href="{html.escape(src)}"><img src="{html.escape(src)}"{size} '
            f'alt="{html.escape(caption)}"></a><figcaption>{html.escape(caption)}{extra}'
            "</figcaption></figure>")


def html_page(title, blocks):
    """A self-contained page: the title, then the blocks (HTML strings) in order."""
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head><body>\n"
            f"<h1>{html.escape(title)}</h1>\n" + "\n".join(blocks) + "\n</body></html>\n")


def write_text(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path
