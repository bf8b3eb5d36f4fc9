"""The runs of one merged campaign database (criticality-campaign merge), as the evaluation reads
them: per run its scenario, status, the driver's summary, and its tables (plugin/README.md,
"Results database") grouped by ego. Columns are asked from the database, so a driver that
records more (e.g. p_reference, unavoidability in `steps`) is used when present."""

import json
import os
import sqlite3
from dataclasses import dataclass, field


@dataclass
class Warning:
    ego: str
    start_s: float
    end_s: float  # None while open at the end of the run
    peak_p: float
    edge: str = None  # the ego's SUMO edge where the episode opened (":..." in a junction)


@dataclass
class CriticalEvent:
    """An ego's body overlapping another's, or its braking harder than its normal maximum
    (the driver's critical_events table, plugin/observe/critical_events.h)."""
    time_s: float
    ego: str
    kind: str  # overlap | pass-through | hard-braking
    other: str  # overlap: the object; else None
    value: float


@dataclass
class Collision:
    time_s: float
    collider: str
    victim: str
    collider_speed_mps: float
    victim_speed_mps: float
    involves_ego: bool

    def partner_of(self, ego):
        return self.victim if self.collider == ego else self.collider

    def speed_of(self, who):
        return self.collider_speed_mps if self.collider == who else self.victim_speed_mps


@dataclass
class Run:
    index: int
    scenario: str
    folder: str  # the run's folder (its SSM file, stdout, stderr)
    status: str  # the campaign's: ok, failed, timeout, killed
    error: str
    summary: dict
    step_length_s: float = 0.1
    options: str = ""
    steps: dict = field(default_factory=dict)  # ego -> {column: [values by time]}
    warnings: list = field(default_factory=list)
    collisions: list = field(default_factory=list)
    ego_events: list = field(default_factory=list)  # (time_s, ego, event)
    critical_events: list = field(default_factory=list)  # CriticalEvent, by time
    ego_classes: dict = field(default_factory=dict)  # ego -> SUMO's vClass (table egos)

    @property
    def ok(self):
        return self.status == "ok"

    @property
    def end_s(self):
        return self.summary.get("sim_time_s") if self.summary else None

    def series(self, ego, column):
        """(times, values) of one ego's steps column; ([], []) when absent."""
        s = self.steps.get(ego)
        if not s or column not in s:
            return [], []
        return s["time_s"], s[column]

    def ego_warnings(self, ego):
        return [w for w in self.warnings if w.ego == ego]

    def first_ego_collision(self, ego):
        mine = [c for c in self.collisions if ego in (c.collider, c.victim)]
        return min(mine, key=lambda c: c.time_s) if mine else None

    def option_value(self, name):
        """The value of --name on the run's command line (runs.options), else None."""
        words = self.options.split()
        for k, w in enumerate(words[:-1]):
            if w == "--" + name:
                return words[k + 1]
        return None


def _columns(con, table):
    return [r[1] for r in con.execute(f"pragma table_info({table})")]


STEP_COLUMNS = ("p_collision", "p_reference", "unavoidability", "speed_mps", "acting",
                "main_object")


def _read_tables(con, runs, key):
    """Fills runs ({key value: Run}) from the run tables; key: "run_index" (a merged campaign)
    or "0" (one run's own file). Returns the steps columns present."""
    tables = {r[0] for r in con.execute("select name from sqlite_master where type='table'")}
    present = []
    by = f"{key}, " if key == "run_index" else ""  # ORDER BY 0 would mean a column number
    if "runs" in tables:
        for index, step, options in con.execute(
                f"select {key}, step_length_s, options from runs"):
            if index in runs:
                runs[index].step_length_s = step or 0.1
                runs[index].options = options or ""
    if "steps" in tables:
        have = _columns(con, "steps")
        present = [c for c in STEP_COLUMNS if c in have]
        cols = ", ".join([key, "ego", "time_s"] + present)
        for row in con.execute(f"select {cols} from steps order by {by}ego, time_s"):
            run = runs.get(row[0])
            if run is None:
                continue
            s = run.steps.get(row[1])
            if s is None:
                s = run.steps[row[1]] = {c: [] for c in ["time_s"] + present}
            s["time_s"].append(row[2])
            for c, v in zip(present, row[3:]):
                s[c].append(v)
    if "warnings" in tables:
        edge = "edge" if "edge" in _columns(con, "warnings") else "NULL"
        for index, ego, start, end, peak, where in con.execute(
                f"select {key}, ego, start_s, end_s, peak_p, {edge} from warnings "
                f"order by {by}start_s"):
            if index in runs:
                runs[index].warnings.append(Warning(ego, start, end, peak, where))
    if "collisions" in tables:
        for index, t, collider, victim, vc, vv, ego in con.execute(
                f"select {key}, time_s, collider, victim, collider_speed_mps, "
                f"victim_speed_mps, involves_ego from collisions order by {by}time_s"):
            if index in runs:
                runs[index].collisions.append(Collision(t, collider, victim, vc or 0.0,
                                                        vv or 0.0, bool(ego)))
    if "critical_events" in tables:
        for index, t, ego, kind, other, value in con.execute(
                f"select {key}, time_s, ego, kind, other, value from critical_events "
                f"order by {by}time_s"):
            if index in runs:
                runs[index].critical_events.append(CriticalEvent(t, ego, kind, other, value))
    if "egos" in tables and "vehicle_class" in _columns(con, "egos"):
        # An ego that came back keeps the class of its first entry.
        for index, ego, vclass in con.execute(
                f"select {key}, ego, vehicle_class from egos order by {by}first_s desc"):
            if index in runs:
                runs[index].ego_classes[ego] = vclass
    if "ego_events" in tables:
        for index, t, ego, event in con.execute(
                f"select {key}, time_s, ego, event from ego_events order by {by}time_s"):
            if index in runs:
                runs[index].ego_events.append((t, ego, event))
    return present


def read_campaign(folder):
    """{scenario name: Run} of a merged campaign folder, and the steps columns present."""
    con = sqlite3.connect(os.path.join(folder, "campaign.sqlite"))
    runs = {}
    for index, scenario, status, error, summary in con.execute(
            "select run_index, scenario, status, error, summary from campaign_runs "
            "order by run_index"):
        try:
            summary = json.loads(summary) if summary else {}
        except ValueError:
            summary = {}
        runs[index] = Run(index, scenario, os.path.join(folder, "runs", f"{index:06d}"), status,
                          error or "", summary)
    present = _read_tables(con, runs, "run_index")
    con.close()
    return {r.scenario: r for r in runs.values()}, present


def read_run_file(path, scenario, exit_code):
    """The Run of one driver results file (no campaign): status ok when the driver exited 0 and
    its summary says completed."""
    con = sqlite3.connect(path)
    row = con.execute("select status, error, summary from runs").fetchone()
    summary = json.loads(row[2]) if row and row[2] else {}
    ok = exit_code == 0 and summary.get("status") == "completed"
    runs = {0: Run(0, scenario, os.path.dirname(path), "ok" if ok else "failed",
                   (row[1] if row else "") or "", summary)}
    _read_tables(con, runs, "0")
    con.close()
    return runs[0]
