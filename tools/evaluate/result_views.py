"""The result views of plugin/record/result_views.sql (what followed a warning episode, a
collision's anticipation) over one run, so that the evaluation judges episodes by the same SQL
as the campaign report. The run's collisions and critical events and the episodes to judge (the
driver's warnings, SSM's or replayed episodes) are put into an in-memory SQLite database with
the driver's table and column names, and the views are created over it, their placeholders
filled in as plugin/record/result_views.cc fills them."""

import math
import os
import re
import sqlite3
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
SQL_FILE = os.path.join(HERE, "..", "..", "plugin", "record", "result_views.sql")
DEFAULT_GRACE_S = 2.0

_IDENTIFIER = re.compile(r"^[A-Za-z0-9_.]+$")


def sql_real_literal(value):
    """value as an SQL literal that SQLite reads back as exactly the same float: the shortest
    decimal when it has at most 15 significant digits, else an exact quotient (SQLite's
    decimal reader may round a longer one differently from Python's)."""
    if not math.isfinite(value):
        raise ValueError("result views: number not finite")
    text = repr(float(value))
    mantissa = re.split("[eE]", text)[0]
    if len(mantissa.replace("-", "").replace(".", "").lstrip("0")) <= 15:
        return text if re.search("[.eE]", text) else text + ".0"
    q = Fraction(value)
    if q.denominator == 1:
        return f"CAST({q.numerator} AS REAL)"
    return f"(CAST({q.numerator} AS REAL) / {q.denominator})"


def views_sql(grace_s=DEFAULT_GRACE_S, schema="main", run_key="run_id", runs_key="id",
              warnings="warnings", collisions="collisions", critical_events="critical_events",
              runs="runs", steps="steps", attributed=True):
    """The CREATE VIEW statements of result_views.sql with its placeholders filled in."""
    names = {"schema": schema, "run_key": run_key, "runs_key": runs_key, "warnings": warnings,
             "collisions": collisions, "critical_events": critical_events, "runs": runs,
             "steps": steps}
    for what, name in names.items():
        if not _IDENTIFIER.match(name):
            raise ValueError(f"result views: {what} {name!r} is not a plain SQL identifier")
    values = dict(names, grace_s=sql_real_literal(grace_s), attributed="1" if attributed else "0",
                  step_main_object="s.main_object" if attributed else "NULL")
    with open(SQL_FILE, encoding="utf-8") as f:
        text = f.read()

    def fill(m):
        if m.group(1) not in values:
            raise ValueError(f"result views: no value for {{{{{m.group(1)}}}}}")
        return values[m.group(1)]

    return re.sub(r"\{\{(\w+)\}\}", fill, text)


def open_run(run, eps_by_ego, grace_s=DEFAULT_GRACE_S):
    """An in-memory database holding one run (its collisions, critical events, step length, the
    steps' main objects where recorded) and the episodes {ego: [Episode or Warning]} as its
    warnings table, with the views over them."""
    con = sqlite3.connect(":memory:")
    con.executescript(
        "CREATE TABLE runs(id INTEGER PRIMARY KEY, step_length_s REAL);"
        "CREATE TABLE warnings(run_id INTEGER, ego TEXT, start_s REAL, end_s REAL);"
        "CREATE TABLE collisions(run_id INTEGER, time_s REAL, collider TEXT, victim TEXT);"
        "CREATE TABLE critical_events(run_id INTEGER, time_s REAL, ego TEXT, kind TEXT);"
        "CREATE TABLE steps(run_id INTEGER, time_s REAL, ego TEXT, main_object TEXT);"
        "CREATE INDEX warnings_by_ego ON warnings(run_id, ego, start_s);"
        "CREATE INDEX steps_by_ego ON steps(run_id, ego, time_s);"
        "CREATE INDEX critical_events_by_ego ON critical_events(run_id, ego, time_s);")
    con.execute("INSERT INTO runs VALUES(1, ?)", (run.step_length_s,))
    con.executemany("INSERT INTO warnings VALUES(1, ?, ?, ?)",
                    [(ego, e.start_s, e.end_s) for ego, eps in eps_by_ego.items() for e in eps])
    con.executemany("INSERT INTO collisions VALUES(1, ?, ?, ?)",
                    [(c.time_s, c.collider, c.victim) for c in run.collisions])
    con.executemany("INSERT INTO critical_events VALUES(1, ?, ?, ?)",
                    [(e.time_s, e.ego, e.kind) for e in run.critical_events])
    attributed = any("main_object" in s for s in run.steps.values())
    if attributed:  # only the steps that name one: what the view asks of them
        con.executemany("INSERT INTO steps VALUES(1, ?, ?, ?)",
                        [(t, ego, m) for ego, s in run.steps.items()
                         for t, m in zip(s["time_s"], s.get("main_object", [])) if m is not None])
    con.executescript(views_sql(grace_s, attributed=attributed))
    return con
