"""The evaluation on the held-out protocol's network family (network_family.py): every variant
chosen (a closed-loop one with `--act brake`) runs every network of the profile with every vehicle an ego (`--all-vehicles
--act warn`), through criticality-campaign; then, per network and per set (tuning, held-out):
vehicle-hours of estimation, warnings and false alarms per vehicle-hour (the views of
plugin/record/result_views.sql, as for the city-like run: city_false_alarms.py), the false
alarms whose window runs past the run's end (unjudged) and the others per vehicle-hour in which
an episode could be judged, SUMO's
collisions and how many of them a warning anticipated (and by how long: the view
collision_anticipation), re-warnings and the turns of p within an approach (flicker).

A re-warning is an episode of an ego that opens within REWARN_GAP_S of the end of the same
ego's previous episode: one approach warned, released and warned again, as in the issue's
"0.81, 0.93, 0.0, 0.72, ..." (the driver's hysteresis already joins dips shorter than
--warn-release-after).

Writes OUT/family.csv (one row per network and variant), OUT/family_sets.csv (one row per set
and variant), OUT/family_set_steps.csv (one per set, step length and variant: the targets are
per step length), OUT/family.md and OUT/family.html."""

import html
import os
import statistics
from dataclasses import dataclass

import city_false_alarms
import result_views
import run_data
import tables
import warning_episodes as we

REWARN_GAP_S = 2.0
# Flicker within an approach: sign changes of dp over an episode and the APPROACH_S before it,
# counting only steps that change p by at least FLICKER_MIN_DP (so that numerical noise on a
# flat p is no flicker).
APPROACH_S = 2.0
FLICKER_MIN_DP = 0.05


@dataclass
class FamilyRow:
    variant: str = ""
    network: str = ""
    split: str = ""
    kind: str = ""
    step_s: float = None
    status: str = ""
    vehicle_hours: float = 0.0
    egos: int = 0
    warnings: int = 0
    false_alarms: int = 0  # the unjudged ones included
    unjudged: int = 0  # false alarms whose window runs past the run's last time
    junction_false_alarms: int = 0  # false alarms opened with the ego in a junction
    judged_vehicle_hours: float = 0.0  # up to the run's last time minus the grace
    rewarnings: int = 0
    dp_sign_changes: int = 0  # summed over the episodes (episode_flicker)
    collisions: int = 0
    warned_collisions: int = 0
    anticipation_s: list = None  # of the warned collisions
    actions: int = 0  # the closed loop's (--act brake; 0 under --act warn)

    @property
    def warnings_per_vehicle_hour(self):
        return self.warnings / self.vehicle_hours if self.vehicle_hours > 0 else None

    @property
    def false_alarms_per_vehicle_hour(self):
        return self.false_alarms / self.vehicle_hours if self.vehicle_hours > 0 else None

    @property
    def judged_false_alarms_per_vehicle_hour(self):
        """The false alarms less the unjudged ones per judged vehicle-hour."""
        if self.judged_vehicle_hours <= 0:
            return None
        return (self.false_alarms - self.unjudged) / self.judged_vehicle_hours

    @property
    def rewarnings_per_vehicle_hour(self):
        return self.rewarnings / self.vehicle_hours if self.vehicle_hours > 0 else None

    @property
    def dp_sign_changes_per_warning(self):
        return self.dp_sign_changes / self.warnings if self.warnings else None

    @property
    def median_anticipation_s(self):
        return statistics.median(self.anticipation_s) if self.anticipation_s else None

    def as_dict(self):
        d = {k: getattr(self, k) for k in ("variant", "network", "split", "kind", "step_s",
                                           "status", "vehicle_hours", "egos", "warnings",
                                           "false_alarms", "unjudged",
                                           "junction_false_alarms", "judged_vehicle_hours",
                                           "rewarnings", "collisions", "warned_collisions",
                                           "actions")}
        d.update(warnings_per_vehicle_hour=self.warnings_per_vehicle_hour,
                 false_alarms_per_vehicle_hour=self.false_alarms_per_vehicle_hour,
                 judged_false_alarms_per_vehicle_hour=self.judged_false_alarms_per_vehicle_hour,
                 rewarnings_per_vehicle_hour=self.rewarnings_per_vehicle_hour,
                 dp_sign_changes_per_warning=self.dp_sign_changes_per_warning,
                 median_anticipation_s=self.median_anticipation_s)
        return d


def rewarnings(warnings, gap_s=REWARN_GAP_S):
    """Episodes (run_data.Warning) that open within gap_s after the end of their ego's previous
    episode."""
    n = 0
    last_end = {}
    for w in sorted(warnings, key=lambda w: (w.ego, w.start_s)):
        end = last_end.get(w.ego)
        if end is not None and w.start_s - end <= gap_s + 1e-9:
            n += 1
        last_end[w.ego] = w.end_s if w.end_s is not None else w.start_s
    return n


def dp_sign_changes(values, min_dp=FLICKER_MIN_DP):
    """Sign changes of the successive differences of values, over the differences of at least
    min_dp (smaller ones are skipped, not counted as a change)."""
    n, last = 0, 0
    for a, b in zip(values, values[1:]):
        d = b - a
        if abs(d) < min_dp:
            continue
        sign = 1 if d > 0 else -1
        if last and sign != last:
            n += 1
        last = sign
    return n


def episode_flicker(run):
    """[sign changes of dp] for each warning episode of the run: its ego's p_collision from
    APPROACH_S before the episode's start to its end."""
    out = []
    for w in run.warnings:
        t, p = run.series(w.ego, "p_collision")
        end = w.end_s if w.end_s is not None else w.start_s
        vals = [v for ti, v in zip(t, p)
                if w.start_s - APPROACH_S - 1e-9 <= ti <= end + 1e-9 and v is not None]
        out.append(dp_sign_changes(vals))
    return out


def junction_false_alarms(run, eps_by_ego):
    """How many false alarms opened while their ego was on a junction's internal lane (its
    SUMO edge, as the warnings table records it, begins with ':'); 0 where the edge is not
    recorded."""
    edges = {(w.ego, round(w.start_s, 6)): w.edge for w in run.warnings}
    return sum(1 for ego, start in city_false_alarms.false_alarm_starts(run, eps_by_ego)
               if (edges.get((ego, round(start, 6))) or "").startswith(":"))


def collision_anticipation(run):
    """[anticipation_s or None] for each of SUMO's collisions in the run (the view
    collision_anticipation over the driver's warnings)."""
    eps = {}
    for w in run.warnings:
        eps.setdefault(w.ego, []).append(we.Episode(w.start_s, w.end_s, w.peak_p))
    con = result_views.open_run(run, eps)
    try:
        return [r[0] for r in con.execute(
            "SELECT anticipation_s FROM collision_anticipation ORDER BY time_s")]
    finally:
        con.close()


def judge(variant, net, run):
    row = FamilyRow(variant=variant, network=net.name, split=net.split, kind=net.kind,
                    step_s=net.step_s)
    if run is None:
        row.status = "not run"
        return row
    row.status = run.status
    if not run.ok:
        return row
    row.vehicle_hours = city_false_alarms.vehicle_hours(run)
    row.egos = len(run.steps)
    row.warnings = len(run.warnings)
    eps = {}
    for w in run.warnings:
        eps.setdefault(w.ego, []).append(we.Episode(w.start_s, w.end_s, w.peak_p))
    row.judged_vehicle_hours = city_false_alarms.judged_vehicle_hours(run)
    if eps:
        got, _, row.unjudged = city_false_alarms.judged(run, eps)
        row.false_alarms = got.get(None, 0)
        row.junction_false_alarms = junction_false_alarms(run, eps)
    row.rewarnings = rewarnings(run.warnings)
    row.dp_sign_changes = sum(episode_flicker(run))
    ant = collision_anticipation(run)
    row.collisions = len(ant)
    row.anticipation_s = [a for a in ant if a is not None]
    row.warned_collisions = len(row.anticipation_s)
    row.actions = int((run.summary or {}).get("actions", 0) or 0)
    return row


def sets(rows, by_step=False):
    """One row per (variant, split), or with by_step per (variant, split, step length): the sums
    over its networks that ran, and the rates of the sums (a set's rate weighs its networks by
    their vehicle-hours)."""
    out = []
    order = list(dict.fromkeys(r.variant for r in rows))  # as the variants were given
    step = (lambda r: r.step_s) if by_step else (lambda r: None)
    keys = sorted({(r.variant, r.split, step(r)) for r in rows},
                  key=lambda k: (order.index(k[0]), k[1] != "tuning", -(k[2] or 0.0)))
    for variant, split, step_s in keys:
        mine = [r for r in rows if r.variant == variant and r.split == split and
                step(r) == step_s]
        ok = [r for r in mine if r.status == "ok"]
        s = FamilyRow(variant=variant, network=f"{len(ok)} of {len(mine)} networks", split=split,
                      step_s=step_s, status="ok" if len(ok) == len(mine) else "incomplete")
        for r in ok:
            s.vehicle_hours += r.vehicle_hours
            s.egos += r.egos
            s.warnings += r.warnings
            s.false_alarms += r.false_alarms
            s.unjudged += r.unjudged
            s.junction_false_alarms += r.junction_false_alarms
            s.judged_vehicle_hours += r.judged_vehicle_hours
            s.rewarnings += r.rewarnings
            s.dp_sign_changes += r.dp_sign_changes
            s.collisions += r.collisions
            s.warned_collisions += r.warned_collisions
            s.actions += r.actions
        s.anticipation_s = [a for r in ok for a in (r.anticipation_s or [])]
        out.append(s)
    return out


COLUMNS = ["variant", "split", "network", "step_s", "status", "vehicle_hours", "egos",
           "warnings", "warnings_per_vehicle_hour", "false_alarms",
           "false_alarms_per_vehicle_hour", "unjudged", "judged_vehicle_hours",
           "judged_false_alarms_per_vehicle_hour", "junction_false_alarms", "rewarnings",
           "rewarnings_per_vehicle_hour", "dp_sign_changes_per_warning", "collisions",
           "warned_collisions", "median_anticipation_s", "actions"]
HEADERS = ["variant", "set", "network", "step (s)", "status", "vehicle-hours", "egos",
           "warnings", "warnings / veh-h", "false alarms", "false alarms / veh-h", "unjudged",
           "judged veh-h", "judged false alarms / veh-h", "false alarms in a junction",
           "re-warnings", "re-warnings / veh-h", "dp sign changes / warning", "collisions",
           "warned collisions", "median anticipation (s)", "closed-loop actions"]
SET_COLUMNS = [c for c in COLUMNS if c != "step_s"]
SET_HEADERS = [h for c, h in zip(COLUMNS, HEADERS) if c != "step_s"]


def write(out, rows, info_lines):
    """family.csv, family_sets.csv, family.md, family.html; returns the set rows."""
    per = [r.as_dict() for r in rows]
    summary = [r.as_dict() for r in sets(rows)]
    by_step = [r.as_dict() for r in sets(rows, by_step=True)]
    tables.write_csv(os.path.join(out, "family.csv"), per, COLUMNS)
    tables.write_csv(os.path.join(out, "family_sets.csv"), summary, SET_COLUMNS)
    tables.write_csv(os.path.join(out, "family_set_steps.csv"), by_step, COLUMNS)
    intro = ["# Held-out networks (tools/evaluate/network_family.py)", ""] + info_lines + [
        "", "Every vehicle an ego, `--act warn` (a closed-loop variant: `--act brake`, every "
        "vehicle braked and steered by the closed loop; its collisions beside ours' are what "
        "the closed loop changed, and 'closed-loop actions' counts its brake, steer and release "
        "rows). A false alarm: a warning episode that no "
        "collision, body overlap or hard braking of its ego followed within "
        f"{city_false_alarms.GRACE_S:g} s of its end. Unjudged: a false alarm whose window (from "
        f"the episode's start to {city_false_alarms.GRACE_S:g} s after its end) runs past the "
        "last simulated time of the run: what would have followed was not recorded. "
        "'false alarms' and 'false alarms / veh-h' count the unjudged ones, as before, so that "
        "earlier figures stay comparable; 'judged false alarms / veh-h' leaves them out and "
        "divides by the judged vehicle-hours, the ego steps at or before that last time minus "
        f"{city_false_alarms.GRACE_S:g} s. An episode followed by a collision, overlap or hard "
        "braking is judged by it even when its window runs past the end. False alarms in a "
        "junction: those that opened with the ego on a junction's internal lane. "
        f"A re-warning: an episode opening within {REWARN_GAP_S:g} s of the end of its ego's "
        "previous one. dp sign changes / warning: how often p turned (by at least "
        f"{FLICKER_MIN_DP:g} a step) over an episode and the {APPROACH_S:g} s before it: 1 for a "
        "p that rises once and falls once. A rule is kept only if it helps the held-out set.", ""]
    md = intro + ["## By set", "", tables.markdown(summary, SET_COLUMNS, SET_HEADERS), "",
                  "## By set and step length", "", tables.markdown(by_step, COLUMNS, HEADERS), "",
                  "## By network", "", tables.markdown(per, COLUMNS, HEADERS), ""]
    with open(os.path.join(out, "family.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md))

    def table(rows_, cols, heads):
        th = "".join(f"<th>{html.escape(h)}</th>" for h in heads)
        trs = "".join("<tr>" + "".join(f"<td>{html.escape(tables.cell(r.get(c)) or '-')}</td>"
                                       for c in cols) + "</tr>" for r in rows_)
        return f"<table><tr>{th}</tr>{trs}</table>"

    page = ["<!doctype html><html><head><meta charset='utf-8'><title>Held-out networks</title>",
            "<style>body{font-family:sans-serif;max-width:1300px;margin:auto}"
            "table{border-collapse:collapse;font-size:14px}td,th{border:1px solid #ccc;"
            "padding:3px 6px;text-align:right}th{background:#eee}</style></head><body>",
            "<h1>Held-out networks</h1>"] + [f"<p>{html.escape(x)}</p>" for x in intro[2:] if x]
    page += ["<h2>By set</h2>", table(summary, SET_COLUMNS, SET_HEADERS),
             "<h2>By set and step length</h2>", table(by_step, COLUMNS, HEADERS),
             "<h2>By network</h2>", table(per, COLUMNS, HEADERS),
             "<p>family.csv, family_sets.csv, family_set_steps.csv: the same tables.</p>"
             "</body></html>"]
    with open(os.path.join(out, "family.html"), "w", encoding="utf-8") as f:
        f.write("\n".join(page))
    return summary


def read_runs(folder):
    """{scenario name: Run} of one variant's merged campaign; {} when it has none."""
    if not os.path.exists(os.path.join(folder, "campaign.sqlite")):
        return {}
    return run_data.read_campaign(folder)[0]
