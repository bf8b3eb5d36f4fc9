"""A picture of one estimated scene: what the estimator saw when a warning began.

Left: the road (SUMO's lanes around the ego, from the .net.xml), the ego and every object as
its box (length x width about its centre, at its heading), its speed as an arrow (the distance
covered in 1 s), the ego's lanes as the estimator got them (three samples per divider), the
ego's most probable hypotheses (blue, line width by probability; the reference dashed) and its
most probable colliding ones (red), each object's share of p. Right: p over the episode (the
run's recorded steps): p_collision, p_reference, unavoidability, the threshold, the warning, and
the ego's collision.

Scene files are the estimator's text format (estimator/src/scene_io.cc): positions in SUMO's
network frame (m), yaw in radians from +x, counter-clockwise; lane dividers in the observer's
own frame (x forward, y left). The hypotheses come from `criticality-bench --scene-file F
--paths-json OUT` (their poses in the same frame).
"""

import math

import matplotlib.patches as patches
from matplotlib.collections import LineCollection


def read_scene(text):
    """The objects of a scene file: {"ego": obj, "vehicles": [obj], "pedestrians": [obj]}; obj
    has id, x, y, yaw, speed, length, width and, for the ego and vehicles with lanes, "lanes":
    {name: (left points, right points)} in the object's own frame."""
    scene = {"ego": None, "vehicles": [], "pedestrians": []}
    last = None
    for line in text.splitlines():
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        kind = words[0]
        if kind in ("ego", "vehicle", "pedestrian"):
            nums = [float(w) if w != "-" else None for w in words[2:]]
            obj = {"id": words[1], "x": nums[0], "y": nums[1], "yaw": nums[2], "speed": nums[3],
                   "length": nums[7], "width": nums[8], "lanes": {}, "kind": kind}
            if kind == "ego":
                scene["ego"] = obj
            else:
                scene[kind + "s"].append(obj)
            last = obj
        elif kind == "lane" and last is not None:
            pts = [float(w) for w in words[3:15]]
            left = [(pts[0], pts[1]), (pts[2], pts[3]), (pts[4], pts[5])]
            right = [(pts[6], pts[7]), (pts[8], pts[9]), (pts[10], pts[11])]
            last["lanes"][words[1]] = (left, right)
    return scene


def to_world(obj, points):
    """Points of an object's own frame in the scene frame."""
    c, s = math.cos(obj["yaw"]), math.sin(obj["yaw"])
    return [(obj["x"] + c * px - s * py, obj["y"] + s * px + c * py) for px, py in points]


def box(obj):
    """The corners of an object's box (length x width about its centre)."""
    hl, hw = obj["length"] / 2, obj["width"] / 2
    return to_world(obj, [(hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw)])


def draw_scene(ax, scene, net=None, paths=None, radius=None, title=None):
    """The scene around the ego (see the module doc); returns the axes' extent."""
    ego = scene["ego"]
    objects = scene["vehicles"] + scene["pedestrians"]
    shares = {o["id"]: o["contribution"] for o in (paths or {}).get("objects", [])}
    if radius is None:
        # What matters: the objects with a share of p, the hypotheses, 15 m around them.
        far = [math.hypot(o["x"] - ego["x"], o["y"] - ego["y"]) for o in objects
               if shares.get(o["id"], 0.0) > 0]
        for h in (paths or {}).get("most_probable", []) + (paths or {}).get("colliding", []):
            far += [math.hypot(x - ego["x"], y - ego["y"]) for x, y in zip(h["x"], h["y"])]
        far.append(ego["speed"] * 2.0)
        radius = max(25.0, min(150.0, max(far) + 15.0))
    if net is not None:
        # Every lane with a segment in the view (a long straight lane has points only far away).
        x0, x1 = ego["x"] - 1.5 * radius, ego["x"] + 1.5 * radius
        y0, y1 = ego["y"] - 1.5 * radius, ego["y"] + 1.5 * radius
        near = [shape for _, _, shape in net.lanes.values()
                if any(min(a[0], b[0]) <= x1 and max(a[0], b[0]) >= x0 and
                       min(a[1], b[1]) <= y1 and max(a[1], b[1]) >= y0
                       for a, b in zip(shape, shape[1:]))]
        ax.add_collection(LineCollection(near, colors="#bdbdbd", linewidths=1.0, zorder=1))
    for name, (left, right) in ego["lanes"].items():
        for divider in (left, right):
            pts = to_world(ego, divider)
            ax.plot([p[0] for p in pts], [p[1] for p in pts], ":", color="#4a7ab8",
                    linewidth=1.0, zorder=2)
    if paths:
        # The colliding ones below, the most probable on top (they often share a stretch).
        for h in paths.get("colliding", []):
            ax.plot(h["x"], h["y"], color="#d62728", alpha=0.6, linewidth=2.2, zorder=3)
        for h in paths.get("most_probable", []):
            ax.plot(h["x"], h["y"], color="#1f5fbf", alpha=0.9,
                    linewidth=0.6 + 8.0 * h["probability"],
                    linestyle="--" if h["reference"] else "-", zorder=3.5)
    for obj in [ego] + objects:
        is_ego = obj is ego
        share = shares.get(obj["id"], 0.0)
        share = share if share >= 0.005 else 0.0  # what rounds to 0.00 has no share to show
        colour = "#1f5fbf" if is_ego else ("#d62728" if share > 0 else "#7f7f7f")
        ax.add_patch(patches.Polygon(box(obj), closed=True, facecolor=colour, alpha=0.85,
                                     edgecolor="black", linewidth=0.6, zorder=4))
        if obj["speed"] > 0.1:
            dx, dy = math.cos(obj["yaw"]) * obj["speed"], math.sin(obj["yaw"]) * obj["speed"]
            ax.annotate("", (obj["x"] + dx, obj["y"] + dy), (obj["x"], obj["y"]), zorder=5,
                        arrowprops={"arrowstyle": "->", "color": colour, "linewidth": 1.2})
        if is_ego or share > 0 or math.hypot(obj["x"] - ego["x"], obj["y"] - ego["y"]) < radius:
            label = f"{obj['id']}" + (f"  share {share:.2f}" if share > 0 else "")
            ax.annotate(label, (obj["x"], obj["y"]), xytext=(6, -12), textcoords="offset points",
                        fontsize=9, zorder=6)
    ax.set_xlim(ego["x"] - radius, ego["x"] + radius)
    ax.set_ylim(ego["y"] - 0.75 * radius, ego["y"] + 0.75 * radius)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    handles = [patches.Patch(color="#1f5fbf", label="ego"),
               patches.Patch(color="#d62728", label="object with a share of p"),
               patches.Patch(color="#7f7f7f", label="other object")]
    if paths:
        from matplotlib.lines import Line2D
        handles += [Line2D([], [], color="#1f5fbf", label="most probable ego paths"),
                    Line2D([], [], color="#d62728", label="colliding ego paths")]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3,
              fontsize=8, frameon=False)
    if title:
        ax.set_title(title)


def p_over_episode(ax, times, series, start_s, end_s, threshold=None, collision_s=None):
    """p over the episode: {label: values} at `times`, the warning shaded, the threshold, the
    ego's collision."""
    styles = {"p_collision": ("p_collision (p_cra)", "#1f5fbf", "-"),
              "p_reference": ("p_reference", "#ff7f0e", "--"),
              "unavoidability": ("unavoidability", "#555555", ":")}
    for key, values in series.items():
        label, colour, style = styles.get(key, (key, None, "-"))
        if any(v is not None for v in values):
            ax.plot(times, [float("nan") if v is None else v for v in values], style,
                    color=colour, label=label, linewidth=1.5)
    ax.axvspan(start_s, end_s if end_s is not None else start_s, color="red", alpha=0.12,
               label="warning")
    if threshold is not None:
        ax.axhline(threshold, color="grey", linestyle=":", linewidth=1,
                   label=f"threshold {threshold:g}")
    if collision_s is not None:
        ax.axvline(collision_s, color="black", linewidth=1.5, label="collision (SUMO)")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("probability")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=3, fontsize=8, frameon=False)
