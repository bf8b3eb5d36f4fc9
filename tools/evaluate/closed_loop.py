"""Closed loop against open loop, per designed scenario: the same scenario with --act brake
(variant closed-loop) beside --act warn (ours). Computed from the runs alone, whatever the act
stage does: the ego's first collision (yes/no, with whom), the collider's speed in it (the
impact speed), and the travel-time cost of braking.

Travel-time cost: when the ego arrives at the end of its route in both runs, the difference of
its travel times (depart to arrive). Most designed scenarios end before the ego arrives; then
the travel times run to the end of the run, and the cost adds the distance the closed-loop ego
is behind (each run's distance: its recorded speeds integrated over the steps) divided by the
open-loop ego's mean speed: the time it would need to catch up at that speed. In a collision scenario the open-loop
ego drives through what it hit (collision.action warn), so there the cost says little; it
matters in the collision-free scenarios, where any braking is a false alarm."""

from dataclasses import dataclass


@dataclass
class LoopOutcome:
    collided: bool = False
    partner: str = ""
    impact_speed_mps: float = None  # the collider's speed in the ego's first collision
    travel_time_s: float = None  # depart to arrive, or to the end of the run
    arrived: bool = False
    distance_m: float = None  # recorded speeds integrated over the run
    brakings: int = 0  # brake actions (closed loop)


@dataclass
class ClosedLoopRow:
    scenario: str
    category: str
    status: str = ""
    open: LoopOutcome = None
    closed: LoopOutcome = None
    avoided: bool = False
    impact_speed_reduction_mps: float = None
    travel_time_cost_s: float = None
    note: str = ""


def outcome(run, ego):
    o = LoopOutcome()
    hit = run.first_ego_collision(ego)
    if hit is not None:
        o.collided, o.partner = True, hit.partner_of(ego)
        o.impact_speed_mps = hit.collider_speed_mps
    depart = [t for t, e, ev in run.ego_events if e == ego and ev == "depart"]
    arrive = [t for t, e, ev in run.ego_events if e == ego and ev == "arrive"]
    start = depart[0] if depart else 0.0
    if arrive:
        o.arrived, o.travel_time_s = True, arrive[0] - start
    elif run.end_s is not None:
        o.travel_time_s = run.end_s - start
    o.brakings = int(run.summary.get("actions", 0) or 0)
    times, speeds = run.series(ego, "speed_mps")
    if times:
        o.distance_m = sum(v for v in speeds if v is not None) * run.step_length_s
    return o


def compare(scenario, open_run, closed_run):
    row = ClosedLoopRow(scenario.name, scenario.category)
    if open_run is None or closed_run is None:
        row.status = "not run"
        return row
    if not (open_run.ok and closed_run.ok):
        row.status = f"open {open_run.status}, closed {closed_run.status}"
        return row
    row.status = "ok"
    row.open, row.closed = outcome(open_run, scenario.ego), outcome(closed_run, scenario.ego)
    row.avoided = row.open.collided and not row.closed.collided
    if row.open.collided:
        closed_speed = row.closed.impact_speed_mps if row.closed.collided else 0.0
        row.impact_speed_reduction_mps = row.open.impact_speed_mps - closed_speed
    o, c = row.open, row.closed
    if o.travel_time_s is not None and c.travel_time_s is not None:
        row.travel_time_cost_s = c.travel_time_s - o.travel_time_s
        if not (o.arrived and c.arrived) and o.distance_m and c.distance_m is not None:
            row.travel_time_cost_s += (o.distance_m - c.distance_m) / (o.distance_m /
                                                                       o.travel_time_s)
    notes = []
    if row.closed.collided and row.open.collided and row.closed.partner != row.open.partner:
        notes.append(f"closed loop hits {row.closed.partner} instead")
    if row.closed.collided and not row.open.collided:
        notes.append(f"closed loop causes a collision with {row.closed.partner}")
    if not (row.open.arrived and row.closed.arrived):
        notes.append("cost from the distance behind at the end of the run")
    row.note = "; ".join(notes)
    return row
