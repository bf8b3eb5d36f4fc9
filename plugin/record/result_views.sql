-- What a warning episode was followed by, and how long before a collision it began: the one
-- definition of both, as views over the results tables (plugin/README.md, "Results database").
-- The same text serves the driver's run files, a merged campaign.sqlite and the evaluation's
-- own episodes (tools/evaluate), so the campaign report and the evaluation judge alike.
--
-- Placeholders (plugin/record/result_views.h fills them in; tools/evaluate/result_views.py too):
--   {{schema}}           main (views stored in the file) or temp (views of one connection)
--   {{run_key}}          the run column of the tables below: run_id in a run file, run_index in
--                        a merged campaign.sqlite (where every run's run_id is 1)
--   {{runs_key}}         the column of {{runs}} that {{run_key}} refers to: id, or run_index
--   {{warnings}}         the episodes judged: columns {{run_key}}, ego, start_s, end_s (NULL:
--                        still open); the driver's warnings table, or a table of other episodes
--   {{collisions}}       SUMO's collisions: {{run_key}}, time_s, collider, victim
--   {{critical_events}}  the egos' critical events: {{run_key}}, time_s, ego, kind
--   {{runs}}             the runs: {{runs_key}}, step_length_s
--   {{steps}}            the egos' steps: {{run_key}}, ego, time_s (and main_object)
--   {{attributed}}       1: the steps name each step's main object, s.main_object; 0: they do
--                        not (run files of older drivers)
--   {{step_main_object}} s.main_object, or NULL where {{attributed}} is 0
--   {{grace_s}}          seconds after an episode's end within which what follows still counts
--                        (a number; default 2.0, the evaluation's)
-- Inside the views other views are named without a schema: a view stored in a file may name
-- only objects of its own file, and it resolves them there even when the file is attached to
-- another database under another name (as criticality-campaign merge does); a TEMP view finds
-- the TEMP views first.
-- The comparisons are written as the evaluation's Python wrote them (t <= end_s + grace, not
-- t - end_s <= grace) so that a time on the boundary is judged as it was.

-- Each episode with the end of the window in which what follows it counts: its end plus the
-- grace. An episode still open (end_s NULL) is judged as if it had ended at its start: only what
-- follows within the grace of its start counts. The driver closes every open episode when a run
-- ends, so in its files only killed runs (never counted by the report) leave end_s NULL; the
-- evaluation's replayed episodes are open when the recorded series ends during them.
CREATE VIEW {{schema}}.warning_windows AS
SELECT w.{{run_key}} AS {{run_key}}, w.ego AS ego, w.start_s AS start_s, w.end_s AS end_s,
       COALESCE(w.end_s, w.start_s) + {{grace_s}} AS window_end_s
FROM {{warnings}} w;

-- Each episode with what followed it from its start to the end of its window, the first that
-- applies: 'collision' (SUMO reported one of its ego, as collider or victim), 'overlap' (its
-- ego's body overlapped another's), 'pass-through' (its ego's body and another's passed
-- through each other between two steps), 'hard-braking' (its ego braked harder than its normal
-- maximum); NULL: nothing did, a false alarm. Critical events of other kinds do not count.
CREATE VIEW {{schema}}.warning_outcomes AS
SELECT w.{{run_key}} AS {{run_key}}, w.ego AS ego, w.start_s AS start_s, w.end_s AS end_s,
       w.window_end_s AS window_end_s,
       CASE
         WHEN EXISTS (SELECT 1 FROM {{collisions}} c
                      WHERE c.{{run_key}} = w.{{run_key}} AND w.ego IN (c.collider, c.victim)
                        AND c.time_s >= w.start_s AND c.time_s <= w.window_end_s)
           THEN 'collision'
         WHEN EXISTS (SELECT 1 FROM {{critical_events}} e
                      WHERE e.{{run_key}} = w.{{run_key}} AND e.ego = w.ego AND e.kind = 'overlap'
                        AND e.time_s >= w.start_s AND e.time_s <= w.window_end_s)
           THEN 'overlap'
         WHEN EXISTS (SELECT 1 FROM {{critical_events}} e
                      WHERE e.{{run_key}} = w.{{run_key}} AND e.ego = w.ego
                        AND e.kind = 'pass-through'
                        AND e.time_s >= w.start_s AND e.time_s <= w.window_end_s)
           THEN 'pass-through'
         WHEN EXISTS (SELECT 1 FROM {{critical_events}} e
                      WHERE e.{{run_key}} = w.{{run_key}} AND e.ego = w.ego
                        AND e.kind = 'hard-braking'
                        AND e.time_s >= w.start_s AND e.time_s <= w.window_end_s)
           THEN 'hard-braking'
       END AS outcome
FROM warning_windows w;

-- Each critical event with warned = 1 when an episode of its ego began at or before it and the
-- episode's window reaches it (the same window as above, seen from the event).
CREATE VIEW {{schema}}.critical_event_warnings AS
SELECT e.{{run_key}} AS {{run_key}}, e.time_s AS time_s, e.ego AS ego, e.kind AS kind,
       EXISTS (SELECT 1 FROM warning_windows w
               WHERE w.{{run_key}} = e.{{run_key}} AND w.ego = e.ego
                 AND e.time_s >= w.start_s AND e.time_s <= w.window_end_s) AS warned
FROM {{critical_events}} e;

-- Each collision with the episodes that may have anticipated it: the episodes of its collider
-- or victim that began before it and were still open at it (end_s NULL, or at or after it) or
-- ended at most one step (the run's step_length_s, plus 1e-6 s for the rounding of the times)
-- before it. "Began before": the driver writes a step's collisions before that step's warnings,
-- so an episode that opens at the impact does not anticipate it. credited_s is when the episode
-- warned of this collision: the first of its steps before the impact at which the collision
-- partner (the other of collider and victim) was the object with the largest share of p
-- ({{steps}}.main_object); NULL when it never was (the episode warned of something else). Where
-- the steps name no main object ({{attributed}} 0: run files of older drivers) every episode is
-- credited from its start.
CREATE VIEW {{schema}}.collision_warnings AS
SELECT c.rowid AS collision_rowid, c.{{run_key}} AS {{run_key}}, w.ego AS ego,
       w.start_s AS start_s,
       CASE WHEN {{attributed}} THEN
         (SELECT min(s.time_s) FROM {{steps}} s
          WHERE s.{{run_key}} = w.{{run_key}} AND s.ego = w.ego
            AND s.time_s >= w.start_s AND s.time_s < c.time_s
            AND (w.end_s IS NULL OR s.time_s <= w.end_s)
            AND {{step_main_object}} = CASE WHEN w.ego = c.collider THEN c.victim
                                       ELSE c.collider END)
       ELSE w.start_s END AS credited_s
FROM {{collisions}} c JOIN {{warnings}} w
  ON w.{{run_key}} = c.{{run_key}} AND w.ego IN (c.collider, c.victim) AND w.start_s < c.time_s
 AND (w.end_s IS NULL OR
      w.end_s >= c.time_s - ((SELECT r.step_length_s FROM {{runs}} r
                              WHERE r.{{runs_key}} = c.{{run_key}}) + 1e-6));

-- Each collision with its anticipation: the collision time minus the credited time of the latest
-- of those episodes that warned of it (collision_warnings, credited_s not NULL); NULL when none
-- did. This is the rule by which the driver fills collisions.anticipation_s when it records a
-- collision (the same arithmetic, so the same value).
CREATE VIEW {{schema}}.collision_anticipation AS
SELECT k.collision_rowid AS collision_rowid, k.{{run_key}} AS {{run_key}}, k.time_s AS time_s,
       k.collider AS collider, k.victim AS victim, k.warning_start_s AS warning_start_s,
       ROUND(k.time_s - k.warning_start_s, 6) AS anticipation_s  -- no 0.8999999999 from the subtraction
FROM (SELECT c.rowid AS collision_rowid, c.{{run_key}} AS {{run_key}}, c.time_s AS time_s,
             c.collider AS collider, c.victim AS victim,
             (SELECT cw.credited_s FROM collision_warnings cw
              WHERE cw.collision_rowid = c.rowid AND cw.credited_s IS NOT NULL
              ORDER BY cw.start_s DESC LIMIT 1) AS warning_start_s
      FROM {{collisions}} c) k;
