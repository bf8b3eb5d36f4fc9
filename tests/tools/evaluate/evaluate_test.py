#!/usr/bin/env python3
"""Unit tests of the evaluation's analysis (tools/evaluate/): warning episodes and their
judgement, SSM files, the driver's --help, campaign files, the threshold sweep, the closed loop,
the city's false alarms and the targets, on hand-made inputs with hand-computed answers. No SUMO,
no matplotlib."""

import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools", "evaluate"))

import campaign_runs  # noqa: E402
import city_false_alarms  # noqa: E402
import closed_loop  # noqa: E402
import driver_help  # noqa: E402
import family_eval  # noqa: E402
import network_family  # noqa: E402
import open_loop  # noqa: E402
import run_data  # noqa: E402
import scenario_meta  # noqa: E402
import ssm_log  # noqa: E402
import targets  # noqa: E402
import threshold_sweep  # noqa: E402
import warning_episodes as we  # noqa: E402

STEP = 0.1


def times(n, start=0.0):
    return [round(start + STEP * k, 6) for k in range(n)]


def make_run(name, ego, p, collision_s=None, partner="obstacle", speeds=None, events=(),
             end_s=None, warnings=None, status="ok", options=""):
    t = times(len(p))
    r = run_data.Run(0, name, "/nonexistent", status, "", {"sim_time_s": end_s or t[-1]})
    r.options = options
    r.steps[ego] = {"time_s": t, "p_collision": list(p)}
    if speeds is not None:
        r.steps[ego]["speed_mps"] = list(speeds)
    if collision_s is not None:
        r.collisions.append(run_data.Collision(collision_s, ego, partner, 20.0, 0.0, True))
    r.ego_events = list(events)
    if warnings is None:  # the driver's episodes at 0.5 / 0.4
        warnings = [run_data.Warning(ego, e.start_s, e.end_s, e.peak)
                    for e in we.episodes(t, p, 0.5, 0.4, STEP)]
    r.warnings = warnings
    return r


def scenario(name, expect="collision", category="static-object", quiet=1.0, partner="obstacle"):
    return scenario_meta.Scenario(name, "/x", "/x/scenario.cfg", ego="ego", expect=expect,
                                  partner=partner if expect == "collision" else "",
                                  quiet_until_s=quiet, category=category)


class EpisodesTest(unittest.TestCase):
    def test_hysteresis_opens_at_threshold_and_closes_below_release(self):
        t = times(8)
        p = [0.1, 0.5, 0.45, 0.41, 0.39, 0.6, 0.7, 0.2]
        eps = we.episodes(t, p, 0.5, 0.4, STEP)
        self.assertEqual([(e.start_s, e.end_s) for e in eps], [(0.1, 0.4), (0.5, 0.7)])
        self.assertAlmostEqual(eps[1].peak, 0.7)

    def test_release_after_keeps_an_episode_through_a_short_dip(self):
        t = times(10)
        p = [0.1, 0.6, 0.3, 0.6, 0.3, 0.3, 0.3, 0.3, 0.6, 0.1]
        # 0.3 s: the one-step dip at 0.2 s does not end it; below from 0.4 s, it ends at 0.7 s.
        eps = we.episodes(t, p, 0.5, 0.4, STEP, release_after_s=0.3)
        self.assertEqual([(e.start_s, e.end_s) for e in eps], [(0.1, 0.7), (0.8, None)])
        # 0 (the first step below): three episodes.
        eps = we.episodes(t, p, 0.5, 0.4, STEP, release_after_s=0.0)
        self.assertEqual([(e.start_s, e.end_s) for e in eps],
                         [(0.1, 0.2), (0.3, 0.4), (0.8, 0.9)])

    def test_open_at_the_end_and_closed_by_a_gap(self):
        eps = we.episodes([0.0, 0.1, 0.5, 0.6], [0.9, 0.9, 0.9, 0.9], 0.5, 0.4, STEP)
        self.assertEqual([(e.start_s, e.end_s) for e in eps], [(0.0, 0.2), (0.5, None)])

    def test_judge_warned_after_the_quiet_phase(self):
        eps = [we.Episode(0.5, 0.6, 0.6), we.Episode(2.0, None, 1.0)]
        j = we.judge(eps, 3.0, 1.0, STEP, collision_free=False)
        self.assertAlmostEqual(j.anticipation_s, 1.0)
        self.assertEqual(j.false_positives, 1)  # the one starting at 0.5, in the quiet phase
        self.assertEqual(j.false_positive_starts, (0.5,))

    def test_judge_a_warning_on_since_the_quiet_phase_is_no_anticipation(self):
        j = we.judge([we.Episode(0.8, None, 1.0)], 3.0, 1.0, STEP, collision_free=False)
        self.assertIsNone(j.anticipation_s)
        self.assertIn("quiet phase", j.reason)
        self.assertEqual(j.false_positives, 1)

    def test_judge_an_episode_closed_two_steps_before_the_collision_misses_it(self):
        j = we.judge([we.Episode(2.0, 2.8, 0.6)], 3.0, 1.0, STEP, collision_free=False)
        self.assertIsNone(j.anticipation_s)
        self.assertIn("ended at 2.8 s", j.reason)
        # closed one step before: still the collision's warning (the driver's rule)
        j = we.judge([we.Episode(2.0, 2.9, 0.6)], 3.0, 1.0, STEP, collision_free=False)
        self.assertAlmostEqual(j.anticipation_s, 1.0)

    def test_judge_counts_from_the_first_step_that_named_the_partner(self):
        eps = [we.Episode(2.0, None, 0.9)]
        t = [2.0, 2.1, 2.2, 2.3, 2.4]
        credit = we.partner_credit(t, ["ped", "ped", "car", "ped", "car"], "car", 2.5)
        j = we.judge(eps, 2.5, 1.0, STEP, collision_free=False, credit=credit)
        self.assertAlmostEqual(j.anticipation_s, 0.3)  # 2.5 - 2.2, not 2.5 - 2.0
        # an episode that only warned of someone else: not the collision's warning
        credit = we.partner_credit(t, ["ped"] * 5, "car", 2.5)
        j = we.judge(eps, 2.5, 1.0, STEP, collision_free=False, credit=credit)
        self.assertIsNone(j.anticipation_s)
        self.assertIn("never named the collision partner", j.reason)
        # steps without main objects (an older driver): from the episode's start
        self.assertIsNone(we.partner_credit(t, [], "car", 2.5))
        j = we.judge(eps, 2.5, 1.0, STEP, collision_free=False,
                     credit=we.partner_credit(t, [], "car", 2.5))
        self.assertAlmostEqual(j.anticipation_s, 0.5)

    def test_judge_collision_free_counts_every_episode(self):
        j = we.judge([we.Episode(5.0, 5.5, 0.6), we.Episode(9.0, 9.1, 0.5)], None, 0.0, STEP,
                     collision_free=True)
        self.assertEqual(j.false_positives, 2)
        self.assertIsNone(j.anticipation_s)


SSM_XML = """<?xml version="1.0"?>
<SSMLog>
  <conflict begin="1.0" end="1.5" ego="ego" foe="a">
    <timeSpan values="1.00 1.10 1.20 1.30 1.40 1.50"/>
    <TTCSpan values="NA 3.50 2.90 2.80 NA 2.00"/>
    <DRACSpan values="NA NA NA NA 3.50 NA"/>
    <minTTC time="1.50" position="0,0" type="2" value="2.00"/>
    <PET time="NA" position="NA" type="NA" value="NA"/>
  </conflict>
  <conflict begin="1.6" end="1.8" ego="ego" foe="b">
    <timeSpan values="1.60 1.70 1.80"/>
    <TTCSpan values="2.00 NA NA"/>
    <DRACSpan values="NA NA NA"/>
    <PET time="4.00" position="0,0" type="2" value="1.50"/>
  </conflict>
  <conflict begin="2.0" end="2.1" ego="other" foe="ego">
    <timeSpan values="2.00 2.10"/>
    <TTCSpan values="1.00 1.00"/>
    <DRACSpan values="NA NA"/>
  </conflict>
</SSMLog>
"""


class SsmTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "ssm.xml")
        with open(self.path, "w") as f:
            f.write(SSM_XML)

    def tearDown(self):
        self.dir.cleanup()

    def test_missing_file_is_none(self):
        self.assertIsNone(ssm_log.read_ssm(os.path.join(self.dir.name, "none.xml")))

    def test_conflicts_and_critical_times(self):
        c = ssm_log.read_ssm(self.path)
        self.assertEqual([(x.ego, x.foe) for x in c], [("ego", "a"), ("ego", "b"), ("other", "ego")])
        self.assertEqual(c[0].ttc, [None, 3.5, 2.9, 2.8, None, 2.0])
        self.assertEqual(c[1].pet_s, 1.5)
        self.assertEqual(ssm_log.critical_times(c[0], 3.0, None), [1.2, 1.3, 1.5])
        self.assertEqual(ssm_log.critical_times(c[0], 3.0, 3.0), [1.2, 1.3, 1.4, 1.5])

    def test_episodes_merge_over_foes_and_count_pet(self):
        c = ssm_log.read_ssm(self.path)
        eps = ssm_log.ego_episodes(c, "ego", STEP)  # TTC<3 or DRAC>3, PET<2
        self.assertEqual([(e.start_s, round(e.end_s, 6)) for e in eps],
                         [(1.2, 1.7), (4.0, 4.1)])  # 1.2-1.6 from a, 1.6 from b; PET at 4.0
        eps = ssm_log.ego_episodes(c, "ego", STEP, pet_max=None, foe="a")
        self.assertEqual([(e.start_s, round(e.end_s, 6)) for e in eps], [(1.2, 1.6)])
        eps = ssm_log.ego_episodes(c, "ego", STEP, drac_min=None, pet_max=None, foe="a")
        self.assertEqual([(e.start_s, round(e.end_s, 6)) for e in eps],
                         [(1.2, 1.4), (1.5, 1.6)])  # one uncritical sample (1.4) splits
        eps = ssm_log.ego_episodes(c, "ego", STEP, ttc_max=2.5, drac_min=None, pet_max=None)
        self.assertEqual([e.start_s for e in eps], [1.5])  # 2.0 at 1.5 and 1.6: one episode
        self.assertEqual(set(ssm_log.all_ego_episodes(c, STEP)), {"ego", "other"})

    def test_ssm_side_of_a_row(self):
        c = ssm_log.read_ssm(self.path)
        row = open_loop.OpenLoopRow("s", "moving-object", "ours", collision_s=1.6, partner="a")
        open_loop.judge_ssm(row, scenario("s", quiet=1.0, partner="a"), c, STEP)
        self.assertAlmostEqual(row.ssm_anticipation_s, 0.4)  # 1.6 - 1.2 (TTC 2.9 at 1.2)
        self.assertEqual(row.ssm_min_ttc_s, 2.0)
        self.assertEqual(row.ssm_false_positives, 0)
        ped = open_loop.OpenLoopRow("p", "pedestrian", "ours", collision_s=9.0, partner="walker")
        open_loop.judge_ssm(ped, scenario("p", category="pedestrian", partner="walker"), c, STEP)
        self.assertIsNone(ped.ssm_anticipation_s)
        self.assertEqual(ped.ssm_note, "SSM ignores pedestrians")


# Lines as sumo-criticality --help prints them (boost::program_options).
HELP = """Usage: sumo-criticality ...

General:
  -h [ --help ]                         show this help and exit
  -c [ --sumo-config ] arg              SUMO configuration
  --warn-threshold arg (=0.90000000000000002)
                                        value of the --warn-on estimate that
  --warn-release arg (=0.8 x warn threshold)
                                        value below which
  --record-scenes arg                   write every scene as a scene file that 'criticality-bench
                                        --scene-file' replays without SUMO
  --no-lateral-controller               the ablation
"""


class DriverHelpTest(unittest.TestCase):
    def test_options_and_defaults(self):
        h = driver_help.DriverHelp(HELP)
        self.assertTrue(h.has("sumo-config") and h.has("no-lateral-controller"))
        self.assertFalse(h.has("scene-file"))  # a wrapped description line, not an option
        self.assertFalse(h.has("preset"))
        self.assertAlmostEqual(h.default_float("warn-threshold", None), 0.9)
        self.assertEqual(h.default_float("warn-release", -1.0), -1.0)

    def test_variants_name_their_missing_options(self):
        import variants
        h = driver_help.DriverHelp(HELP + "  --act arg (=warn)   act\n")
        self.assertEqual(variants.by_name("no-lateral-controller").missing_options(h), [])
        self.assertEqual(variants.by_name("paper-literal").missing_options(h), ["preset"])
        self.assertEqual(variants.by_name("no-road-model").missing_options(h), ["no-road-model"])


class CampaignFileTest(unittest.TestCase):
    def test_yaml(self):
        text = campaign_runs.campaign_yaml("ours", "/o/ours", ["/s/a/scenario.cfg"],
                                           {"act": "warn", "no-road-model": "true"},
                                           {"device.ssm.measures": "TTC DRAC PET"}, 600)
        self.assertIn('output: "/o/ours"\n', text)
        self.assertIn('  - "/s/a/scenario.cfg"\n', text)
        self.assertIn('driver:\n  act: "warn"\n  no-road-model: true\n', text)
        self.assertIn('sumo:\n  device.ssm.measures: "TTC DRAC PET"\n', text)
        self.assertIn("limits:\n  time_s: 600\n", text)
        self.assertTrue(campaign_runs.SSM_OPTIONS["device.ssm.file"].startswith("/proc/self/cwd/"))


# A driver whose default threshold is 0.5 (make_run's episodes are at 0.5 / 0.4).
HELP_05 = HELP.replace("(=0.90000000000000002)", "(=0.5)")


class OpenLoopTest(unittest.TestCase):
    def test_row_of_a_warned_collision(self):
        p = [0.0] * 10 + [0.2, 0.6, 0.7, 0.9, 1.0, 1.0]
        run = make_run("s", "ego", p, collision_s=1.5)
        h = driver_help.DriverHelp(HELP_05)
        row = open_loop.judge_run(scenario("s"), "ours", run, h)
        self.assertTrue(row.collision and row.outcome_as_expected)
        self.assertAlmostEqual(row.anticipation_s, 0.4)  # 1.5 - 1.1
        self.assertEqual(row.threshold, 0.5)
        self.assertTrue(row.replay_matches_driver)
        self.assertEqual(row.unavoidable_note, "not recorded by this driver")

    def test_anticipation_counts_from_when_the_partner_was_the_main_object(self):
        p = [0.0] * 10 + [0.2, 0.6, 0.7, 0.9, 1.0, 1.0]
        run = make_run("s", "ego", p, collision_s=1.5)
        run.steps["ego"]["main_object"] = [None] * 10 + ["ped", "ped", "ped", "obstacle",
                                                           "obstacle", "obstacle"]
        row = open_loop.judge_run(scenario("s"), "ours", run, driver_help.DriverHelp(HELP_05))
        self.assertAlmostEqual(row.anticipation_s, 0.2)  # 1.5 - 1.3, the partner's first step

    def test_replay_mismatch_is_reported(self):
        p = [0.0, 0.6, 0.6, 0.0]
        run = make_run("s", "ego", p, warnings=[run_data.Warning("ego", 0.2, 0.3, 0.6)])
        row = open_loop.judge_run(scenario("s", "no-collision", "free"), "ours", run,
                                  driver_help.DriverHelp(HELP_05))
        self.assertFalse(row.replay_matches_driver)
        self.assertEqual(row.false_positives, 1)

    def test_unavoidability_when_recorded(self):
        p = [0.0] * 10 + [0.6] * 6
        run = make_run("s", "ego", p, collision_s=1.5)
        run.steps["ego"]["unavoidability"] = [0.0] * 13 + [0.96, 0.99, 1.0]
        row = open_loop.judge_run(scenario("s"), "ours", run, driver_help.DriverHelp(HELP_05))
        self.assertAlmostEqual(row.unavoidable_s, 0.2)

    def test_a_run_option_overrides_the_default_threshold(self):
        run = make_run("s", "ego", [0.0], options="sumo-criticality --warn-threshold 0.9")
        self.assertEqual(open_loop.warn_settings(run, driver_help.DriverHelp(HELP_05)),
                         (0.9, 0.9 * 0.8))


class SweepTest(unittest.TestCase):
    def test_thresholds_trade_anticipation_for_false_positives(self):
        crit = make_run("c", "ego", [0.0] * 5 + [0.3, 0.3, 0.6, 0.6, 0.95, 1.0], collision_s=1.0)
        free = make_run("f", "ego", [0.0, 0.35, 0.35, 0.0])
        scen = [scenario("c", quiet=0.2), scenario("f", "no-collision", "free")]
        rows = threshold_sweep.sweep_ours(scen, {"c": crit, "f": free}, None,
                                          thresholds=[0.25, 0.5, 0.9])
        self.assertEqual([r.suite_false_positives for r in rows], [1, 0, 0])
        self.assertEqual([r.warned for r in rows], [1, 1, 1])
        for r, want in zip(rows, [0.5, 0.3, 0.1]):
            self.assertAlmostEqual(r.mean_anticipation_s, want)
            self.assertAlmostEqual(r.mean_all_s, want)


class ClosedLoopTest(unittest.TestCase):
    def test_avoided_and_travel_time(self):
        s = scenario("s")
        events = [(0.0, "ego", "depart")]
        opened = make_run("s", "ego", [0.0] * 10, collision_s=0.5, speeds=[20.0] * 10,
                          events=events)
        closed = make_run("s", "ego", [0.0] * 10, speeds=[20.0] * 5 + [10.0] * 5,
                          events=events)
        row = closed_loop.compare(s, opened, closed)
        self.assertTrue(row.avoided)
        self.assertAlmostEqual(row.impact_speed_reduction_mps, 20.0)
        # open: 20 m in 0.9 s; closed: 15 m: 5 m behind at 20/0.9 m/s
        self.assertAlmostEqual(row.travel_time_cost_s, 5.0 / (20.0 / 0.9))

    def test_both_arrive(self):
        s = scenario("s", "no-collision", "free")
        o = make_run("s", "ego", [0.0] * 3, events=[(0.0, "ego", "depart"), (10.0, "ego", "arrive")])
        c = make_run("s", "ego", [0.0] * 3, events=[(0.0, "ego", "depart"), (12.5, "ego", "arrive")])
        row = closed_loop.compare(s, o, c)
        self.assertFalse(row.avoided)
        self.assertAlmostEqual(row.travel_time_cost_s, 2.5)


class CityTest(unittest.TestCase):
    def test_false_alarms_per_vehicle_hour(self):
        run = make_run("city", "a", [0.0] * 36000)  # one hour of one vehicle
        run.steps["b"] = {"time_s": times(18000), "p_collision": [0.0] * 18000}
        run.warnings = [run_data.Warning("a", 10.0, 11.0, 0.6), run_data.Warning("b", 5.0, 6.0, 0.6),
                        run_data.Warning("b", 100.0, 101.0, 0.6)]
        run.collisions = [run_data.Collision(102.5, "b", "x", 5.0, 0.0, True)]  # within 2 s
        row = city_false_alarms.judge_city(run, "test", None)
        self.assertAlmostEqual(row.vehicle_hours, 1.5)
        self.assertEqual(row.false_alarms, 2)
        self.assertAlmostEqual(row.per_vehicle_hour, 2 / 1.5)
        self.assertEqual(row.followed_by_collision, 1)
        self.assertAlmostEqual(row.warnings_per_vehicle_hour, 3 / 1.5)

    def test_an_overlap_or_hard_braking_after_a_warning_is_no_false_alarm(self):
        run = make_run("city", "a", [0.0] * 36000)
        run.warnings = [run_data.Warning("a", 10.0, 11.0, 0.9), run_data.Warning("a", 20.0, 21.0, 0.9),
                        run_data.Warning("a", 40.0, 41.0, 0.9), run_data.Warning("a", 50.0, None, 0.9)]
        ev = run_data.CriticalEvent
        run.critical_events = [
            ev(12.5, "a", "overlap", "p1", 6.0),       # within 2 s of the end
            ev(21.0, "b", "hard-braking", None, 9.0),  # another vehicle's
            ev(39.0, "a", "overlap", "p2", 3.0),       # before the start
            ev(43.5, "a", "hard-braking", None, 9.0),  # 2.5 s after the end: too late
            ev(51.9, "a", "hard-braking", None, 9.0)]  # open episode: 2 s after its start
        row = city_false_alarms.judge_city(run, "test", None)
        self.assertEqual((row.followed_by_overlap, row.followed_by_hard_braking, row.false_alarms),
                         (1, 1, 2))
        # Of the five events, the overlap at 12.5 s and the braking at 51.9 s were warned of.
        self.assertEqual((row.critical_events, row.warned_critical_events), (5, 2))
        # A collision outranks what else followed.
        run.collisions = [run_data.Collision(11.5, "a", "p1", 5.0, 1.0, True)]
        row = city_false_alarms.judge_city(run, "test", None)
        self.assertEqual((row.followed_by_collision, row.followed_by_overlap), (1, 0))


    def test_false_alarms_per_vehicle_class(self):
        run = make_run("city", "a", [0.0] * 36000)  # a car for an hour
        run.steps["t"] = {"time_s": times(18000), "p_collision": [0.0] * 18000}  # a truck, 0.5 h
        run.steps["x"] = {"time_s": times(3600), "p_collision": [0.0] * 3600}  # not in egos
        run.ego_classes = {"a": "passenger", "t": "truck"}
        run.warnings = [run_data.Warning("a", 10.0, 11.0, 0.6), run_data.Warning("t", 5.0, 6.0, 0.6),
                        run_data.Warning("t", 100.0, 101.0, 0.6)]
        run.collisions = [run_data.Collision(102.5, "t", "y", 5.0, 0.0, True)]  # within 2 s
        rows = {r.vehicle_class: r for r in city_false_alarms.judge_city_by_class(run)}
        self.assertEqual(sorted(rows), ["(unknown)", "passenger", "truck"])
        self.assertEqual((rows["passenger"].warnings, rows["passenger"].false_alarms), (1, 1))
        self.assertAlmostEqual(rows["passenger"].per_vehicle_hour, 1.0)
        self.assertEqual((rows["truck"].warnings, rows["truck"].false_alarms), (2, 1))
        self.assertAlmostEqual(rows["truck"].vehicle_hours, 0.5)
        self.assertAlmostEqual(rows["truck"].per_vehicle_hour, 2.0)
        self.assertEqual(rows["(unknown)"].false_alarms, 0)
        self.assertAlmostEqual(rows["(unknown)"].vehicle_hours, 0.1)
        run.status = "failed"
        self.assertEqual(city_false_alarms.judge_city_by_class(run), [])


class TargetsTest(unittest.TestCase):
    def test_misses_say_by_how_much(self):
        def row(name, cat, ant, fp=0):
            r = open_loop.OpenLoopRow(name, cat, "ours", status="ok", anticipation_s=ant,
                                      false_positives=fp, peak_p_quiet=0.6)
            r.not_warned_reason = "" if ant is not None else "no warning before the collision"
            return r
        rows = [row("s1", "static-object", 0.8), row("s2", "static-object", 1.0),
                row("m1", "moving-object", 0.5), row("m2", "moving-object", None),
                row("f1", "free", None, fp=2)]
        city = city_false_alarms.CityRow(vehicle_hours=2.0, false_alarms=10, per_vehicle_hour=5.0)
        got = {t.target: t for t in targets.check(rows, city)}
        self.assertFalse(got["every collision warned"].met)
        self.assertIn("m2: no warning", got["every collision warned"].gap)
        self.assertIn("m1: 500 ms (160 ms short)", got["each warned >= 660 ms ahead"].gap)
        self.assertIn("32 ms short", got["static-object mean >= 932 ms"].gap)  # mean 900 ms
        self.assertFalse(got["zero warnings in the collision-free scenarios"].met)
        city_row = got["<= 1 false alarm per vehicle-hour (city)"]
        self.assertFalse(city_row.met)
        self.assertIn("5x", city_row.gap)

    def test_ssm_comparison_says_why_when_ours_is_later(self):
        def row(name, ours, ssm):
            return open_loop.OpenLoopRow(name, "moving-object", "ours", status="ok",
                                         anticipation_s=ours, false_positives=0,
                                         ssm_anticipation_s=ssm, ssm_false_positives=1)
        later = {t.target: t for t in targets.check([row("a", 1.5, 3.0), row("b", 1.0, 2.0)],
                                                     None)}
        ssm_row = later["earlier than SSM's TTC at fewer false alarms"]
        self.assertFalse(ssm_row.met)
        self.assertIn("why: ours predicts 2 s ahead", ssm_row.gap)
        self.assertIn("a: ours 1500 ms, SSM 3000 ms", ssm_row.gap)
        earlier = {t.target: t for t in targets.check([row("a", 1.5, 1.0)], None)}
        ssm_row = earlier["earlier than SSM's TTC at fewer false alarms"]
        self.assertTrue(ssm_row.met)
        self.assertNotIn("why", ssm_row.gap)


class NetworkFamilyTest(unittest.TestCase):
    def test_the_split_is_disjoint_by_seed_and_covers_every_kind_and_step_in_both_sets(self):
        nets = network_family.family("full")
        self.assertEqual(len(nets), len(set(n.name for n in nets)))
        tuning = [n for n in nets if n.split == "tuning"]
        held = [n for n in nets if n.split == "held-out"]
        self.assertEqual(len(tuning) + len(held), len(nets))
        self.assertFalse({n.seed for n in tuning} & {n.seed for n in held})
        for group in (tuning, held):
            self.assertEqual({(n.kind, n.step_s) for n in group},
                             {(k, dt) for k in network_family.KINDS
                              for dt in network_family.STEPS_S})
        quick = network_family.family("quick")
        self.assertTrue(set(quick) < set(nets))
        self.assertEqual({n.split for n in quick}, {"tuning", "held-out"})
        with self.assertRaises(ValueError):
            network_family.family("huge")
        short = network_family.family("quick", 0.1)  # --family-step 0.1
        self.assertEqual(short, [n for n in quick if n.step_s == 0.1])
        self.assertEqual(len(short), len(quick) // 2)
        with self.assertRaises(ValueError):
            network_family.family("quick", 0.5)

    def test_the_sublane_profile_is_the_earlier_sublane_protocol(self):
        # g1 (tuning), h4, sp and g7 (held-out) of bench/RESULTS.md, at 0.1 s steps only, with
        # SUMO's sublane model and their own traffic. Catches a net in the wrong set, a 1 s
        # run, the family's default traffic or junction checks in their configuration.
        nets = network_family.family("sublane")
        self.assertEqual([(n.name, n.split, n.end_s) for n in nets],
                         [("sgrid1_0.1s", "tuning", 150.0), ("sgrid4_0.1s", "held-out", 150.0),
                          ("sgrid7_0.1s", "held-out", 150.0),
                          ("sspider31_0.1s", "held-out", 130.0)])
        self.assertEqual(network_family.family("sublane", 0.1), nets)
        self.assertEqual(network_family.family("sublane", 1.0), [])
        cfg = network_family.sumocfg_text(nets[1], ["cars.rou.xml"])
        self.assertIn('<lateral-resolution value="0.8"/>', cfg)
        self.assertNotIn("collision.check-junctions", cfg)
        self.assertIn("collision.check-junctions",
                      network_family.sumocfg_text(network_family.Network("grid", 1, 0.1), []))
        self.assertEqual(list(network_family.net_traffic_args(nets[3], 130.0)), ["cars", "bikes"])
        self.assertIn("7", network_family.net_traffic_args(nets[2], 150.0)["cars"])
        self.assertIn("4", network_family.net_traffic_args(nets[1], 150.0)["cars"])
        self.assertFalse(any(n.sublane for n in network_family.family("full")))

    def test_family_nets_picks_networks_by_name_and_names_unknown_ones(self):
        # Catches a filter that keeps every network, drops a step length or the profile's
        # order, or ignores a misspelt name.
        nets = network_family.family("sublane")
        self.assertEqual([n.name for n in network_family.only(nets, "sgrid7, sgrid1")],
                         ["sgrid1_0.1s", "sgrid7_0.1s"])
        quick = network_family.family("quick")
        grid1 = network_family.only(quick, "grid1")
        self.assertEqual(sorted(n.step_s for n in grid1), [0.1, 1.0])
        with self.assertRaisesRegex(ValueError, "sgrid9: not among the networks"):
            network_family.only(nets, "sgrid1,sgrid9")
        with self.assertRaises(ValueError):
            network_family.only(nets, " , ")

    def test_the_seed_draws_the_network_and_the_traffic(self):
        self.assertNotEqual(network_family.netgenerate_args("grid", 1),
                            network_family.netgenerate_args("grid", 3))
        self.assertIn("3", network_family.netgenerate_args("rand", 3))
        for args in network_family.traffic_args(3, 300).values():
            self.assertEqual(args[:2], ["-s", "3"])
        net = network_family.Network("spider", 3, 0.1)
        cfg = network_family.sumocfg_text(net, ["cars.rou.xml", "peds.rou.xml"])
        self.assertIn('<step-length value="0.1"/>', cfg)
        self.assertIn('<end value="60"/>', cfg)
        self.assertIn("spider3.net.xml", cfg)
        self.assertIn("held-out", cfg)


class ViolationFamilyTest(unittest.TestCase):
    def test_violation_networks_have_their_own_split_and_priority_junctions(self):
        nets = network_family.family("violations")
        self.assertEqual({n.kind for n in nets}, set(network_family.VIOLATION_KINDS))
        self.assertEqual({(n.seed, n.split) for n in nets}, {(5, "tuning"), (6, "held-out")})
        self.assertTrue(all(n.violations for n in nets))
        self.assertFalse(any(n.violations for n in network_family.family("full")))
        # Seeds added later join a set and never move one: 5 and 7 tune, 6, 8 and 9 judge.
        full = network_family.family("violations-full")
        self.assertEqual({(n.seed, n.split) for n in full},
                         {(5, "tuning"), (6, "held-out"), (7, "tuning"), (8, "held-out"),
                          (9, "held-out")})
        self.assertTrue(set(nets) < set(full))
        self.assertEqual(len(full), 20)
        for kind in network_family.VIOLATION_KINDS:
            args = network_family.netgenerate_args(kind, 6)
            self.assertIn("priority", args)
            self.assertNotIn("--tls.guess", args)
        dense = network_family.net_traffic_args(nets[0], 200)["cars"]
        plain = network_family.net_traffic_args(network_family.Network("grid", 1, 1.0), 200)
        self.assertLess(float(dense[dense.index("-p") + 1]),
                        float(plain["cars"][plain["cars"].index("-p") + 1]))

    def test_violators_are_a_seeded_share_of_cars_and_trucks_named_in_events(self):
        routes = ["".join(f'<vehicle id="car{k}" depart="{k}"/>' for k in range(400)),
                  "".join(f'<vehicle id="truck{k}" depart="{k}"/>' for k in range(100)) +
                  "".join(f'<vehicle id="bike{k}" depart="{k}"/>' for k in range(50))]
        net = network_family.Network("rv", 6, 1.0)
        ids = network_family.violators(net, routes)
        self.assertEqual(ids, network_family.violators(net, routes))  # deterministic
        self.assertNotEqual(ids, network_family.violators(network_family.Network("rv", 5, 1.0),
                                                          routes))
        self.assertFalse(any(v.startswith("bike") for v in ids))
        self.assertTrue(any(v.startswith("truck") for v in ids))
        share = len(ids) / 500
        self.assertGreater(share, network_family.VIOLATOR_SHARE - 0.06)
        self.assertLess(share, network_family.VIOLATOR_SHARE + 0.06)
        text = network_family.scenario_cfg_text(net, ids)
        self.assertIn("sumo-config = ../rv6_1s.sumocfg", text)
        events = [l for l in text.splitlines() if l.startswith("event = ")]
        self.assertEqual(events, [f"event = 0 {v} speed-mode 23" for v in ids])


class FamilyEvalTest(unittest.TestCase):
    def test_a_rewarning_opens_within_the_gap_after_the_same_egos_last_episode(self):
        w = run_data.Warning
        eps = [w("a", 1.0, 2.0, 0.9), w("a", 3.5, 4.0, 0.9),  # 1.5 s later: a re-warning
               w("a", 7.0, 8.0, 0.9),                          # 3 s later: a new approach
               w("b", 4.5, 5.0, 0.9)]                          # another ego's
        self.assertEqual(family_eval.rewarnings(eps), 1)
        self.assertEqual(family_eval.rewarnings(eps, gap_s=3.0), 2)

    def test_flicker_counts_the_turns_of_p_over_an_approach(self):
        # The approach: 0.81, 0.93, 0.0, 0.72, 0.58, 0.69, 1.0, 0.0 turns five times.
        self.assertEqual(family_eval.dp_sign_changes([0.81, 0.93, 0.0, 0.72, 0.58, 0.69, 1.0,
                                                      0.0]), 5)
        self.assertEqual(family_eval.dp_sign_changes([0.0, 0.3, 0.6, 0.9, 1.0, 0.5, 0.0]), 1)
        # Steps below the minimum change are no turn.
        self.assertEqual(family_eval.dp_sign_changes([0.5, 0.52, 0.5, 0.53, 0.9]), 0)
        p = [0.0] * 10 + [0.3, 0.9, 0.2, 0.95, 0.97, 0.0] + [0.0] * 30
        run = make_run("grid1_0.1s", "a", p)
        run.warnings = [run_data.Warning("a", 1.1, 1.5, 0.97)]
        self.assertEqual(family_eval.episode_flicker(run), [3])

    def test_network_rows_and_set_sums(self):
        run = make_run("grid1_1s", "a", [0.0] * 36000)  # one vehicle-hour
        run.warnings = [run_data.Warning("a", 10.0, 10.5, 0.9),  # ends 2.5 s before the collision
                        run_data.Warning("a", 12.0, 13.0, 0.9),  # a re-warning, open at the collision
                        run_data.Warning("a", 500.0, 501.0, 0.9)]
        run.collisions = [run_data.Collision(13.0, "a", "b", 5.0, 0.0, True),
                          run_data.Collision(900.0, "c", "d", 5.0, 0.0, False)]
        tuning = network_family.Network("grid", 1, 1.0)
        row = family_eval.judge("ours", tuning, run)
        self.assertEqual((row.warnings, row.false_alarms, row.rewarnings), (3, 2, 1))
        self.assertEqual((row.collisions, row.warned_collisions), (2, 1))
        self.assertAlmostEqual(row.median_anticipation_s, 1.0)  # from the episode at 12.0 s
        self.assertAlmostEqual(row.false_alarms_per_vehicle_hour, 2.0)
        held = network_family.Network("grid", 3, 1.0)
        failed = make_run("grid3_1s", "a", [0.0] * 10, status="failed")
        rows = [row, family_eval.judge("ours", held, failed),
                family_eval.judge("ours", network_family.Network("rand", 3, 1.0), None)]
        by = {s.split: s for s in family_eval.sets(rows)}
        self.assertEqual(by["tuning"].status, "ok")
        self.assertEqual(by["tuning"].false_alarms, 2)
        self.assertEqual(by["held-out"].status, "incomplete")
        self.assertEqual(by["held-out"].network, "0 of 2 networks")
        self.assertIsNone(by["held-out"].false_alarms_per_vehicle_hour)
        with tempfile.TemporaryDirectory() as d:
            family_eval.write(d, rows, ["- test"])
            text = open(os.path.join(d, "family.md"), encoding="utf-8").read()
            self.assertIn("| ours | tuning | 1 of 1 networks |", text)
            self.assertTrue(os.path.exists(os.path.join(d, "family.html")))

    def test_false_alarms_in_a_junction_are_those_opened_on_an_internal_lane(self):
        # Three episodes, none followed by anything: two false alarms opened on a junction's
        # internal lane, one on a normal edge; a warned collision on an internal lane is no
        # false alarm. Catches a count of warnings instead of false alarms, an edge matched to
        # another episode, a test for ':' anywhere in the ID, and a set sum that drops it.
        run = make_run("grid1_0.1s", "a", [0.0] * 3000)
        run.warnings = [run_data.Warning("a", 10.0, 10.5, 0.9, ":B1_3_0"),
                        run_data.Warning("a", 40.0, 40.5, 0.9, "A0B0"),
                        run_data.Warning("a", 80.0, 80.5, 0.9, ":C2_1_0"),
                        run_data.Warning("a", 120.0, 121.0, 0.9, ":D0_2_0")]
        run.collisions = [run_data.Collision(121.0, "a", "b", 5.0, 0.0, True)]
        row = family_eval.judge("ours", network_family.Network("grid", 1, 0.1), run)
        self.assertEqual((row.false_alarms, row.junction_false_alarms), (3, 2))
        other = make_run("grid1_1s", "a", [0.0] * 100)
        other.warnings = [run_data.Warning("a", 5.0, 5.5, 0.9, "A:B")]  # not a junction's
        rows = [row, family_eval.judge("ours", network_family.Network("grid", 1, 1.0), other)]
        self.assertEqual(rows[1].junction_false_alarms, 0)
        self.assertEqual(family_eval.sets(rows)[0].junction_false_alarms, 2)

    def test_closed_loop_actions_are_counted_per_network_and_summed_per_set(self):
        # The closed-loop variant's rows carry the driver's summary count of actions; the set
        # row sums them and family.md has the column. Catches a count that is dropped, taken
        # from another variant's run, or not summed.
        braked = make_run("grid1_1s", "a", [0.0] * 100)
        braked.summary["actions"] = 7
        other = make_run("grid2_1s", "a", [0.0] * 100)
        other.summary["actions"] = 5
        warned = make_run("grid1_1s", "a", [0.0] * 100)
        rows = [family_eval.judge("closed-loop", network_family.Network("grid", 1, 1.0), braked),
                family_eval.judge("closed-loop", network_family.Network("grid", 2, 1.0), other),
                family_eval.judge("ours", network_family.Network("grid", 1, 1.0), warned)]
        self.assertEqual([r.actions for r in rows], [7, 5, 0])
        by = {(s.variant, s.split): s for s in family_eval.sets(rows)}
        self.assertEqual(by[("closed-loop", "tuning")].actions, 12)
        self.assertEqual(by[("ours", "tuning")].actions, 0)
        with tempfile.TemporaryDirectory() as d:
            family_eval.write(d, rows, ["- test"])
            text = open(os.path.join(d, "family.md"), encoding="utf-8").read()
            self.assertIn("closed-loop actions |", text)
            self.assertIn("| closed-loop | tuning | 2 of 2 networks |", text)

    def test_an_episode_whose_window_runs_past_the_end_is_unjudged(self):
        # A 0.1 s run whose last step is 59.9 s: ego a from 0 s (600 steps), b from 30 s (300),
        # c from 0 s until it left at 19.9 s (200).
        run = make_run("gv5_0.1s", "a", [0.0] * 600)
        run.steps["b"] = {"time_s": times(300, 30.0), "p_collision": [0.0] * 300}
        run.steps["c"] = {"time_s": times(200), "p_collision": [0.0] * 200}
        w = run_data.Warning
        run.warnings = [w("a", 53.0, 54.9, 0.9),  # ends 5 s before the end: a false alarm
                        w("a", 55.5, 57.9, 0.9),  # its window ends at 59.9 s: still judged
                        w("a", 58.0, 59.4, 0.9),  # ends 0.5 s before the end: unjudged
                        w("b", 58.5, 59.5, 0.9)]  # its window runs past the end, but
        run.collisions = [run_data.Collision(59.8, "b", "x", 5.0, 0.0, True)]  # this followed
        self.assertAlmostEqual(city_false_alarms.last_time_s(run), 59.9)
        # Every step counts 0.1 s: 1100 steps; judged: those at or before 59.9 - 2 = 57.9 s:
        # a 0.0-57.9 (580), b 30.0-57.9 (280), c all 200: 1060 steps.
        vh, judged_vh = 1100 * 0.1 / 3600, 1060 * 0.1 / 3600
        self.assertAlmostEqual(city_false_alarms.judged_vehicle_hours(run), judged_vh)
        row = family_eval.judge("ours", network_family.Network("gv", 5, 0.1), run)
        # false_alarms keeps its meaning (the unjudged episode included); the collision after
        # b's episode counts although its window runs past the end.
        self.assertEqual((row.warnings, row.false_alarms, row.unjudged), (4, 3, 1))
        self.assertEqual(row.collisions, 1)
        self.assertAlmostEqual(row.vehicle_hours, vh)
        self.assertAlmostEqual(row.false_alarms_per_vehicle_hour, 3 / vh)
        self.assertAlmostEqual(row.judged_false_alarms_per_vehicle_hour, 2 / judged_vh)
        eps = {}
        for x in run.warnings:
            eps.setdefault(x.ego, []).append(we.Episode(x.start_s, x.end_s, x.peak_p))
        got, _, unjudged = city_false_alarms.judged(run, eps)
        self.assertEqual((got.get(None), got.get("collision"), unjudged), (3, 1, 1))
        (s,) = family_eval.sets([row])
        self.assertEqual((s.false_alarms, s.unjudged), (3, 1))
        self.assertAlmostEqual(s.judged_false_alarms_per_vehicle_hour, 2 / judged_vh)
        city = city_false_alarms.judge_city(run, "test", None)
        self.assertEqual((city.false_alarms, city.unjudged, city.followed_by_collision),
                         (3, 1, 1))
        self.assertAlmostEqual(city.per_vehicle_hour, 3 / vh)
        self.assertAlmostEqual(city.judged_vehicle_hours, judged_vh)
        self.assertAlmostEqual(city.judged_per_vehicle_hour, 2 / judged_vh)
        with tempfile.TemporaryDirectory() as d:
            family_eval.write(d, [row], ["- test"])
            with open(os.path.join(d, "family.csv"), encoding="utf-8") as f:
                header = f.readline()
            self.assertIn(",false_alarms,false_alarms_per_vehicle_hour,unjudged,"
                          "judged_vehicle_hours,judged_false_alarms_per_vehicle_hour,", header)
            with open(os.path.join(d, "family_sets.csv"), encoding="utf-8") as f:
                header = f.readline()
            self.assertIn(",unjudged,judged_vehicle_hours,judged_false_alarms_per_vehicle_hour,",
                          header)

    def test_an_ego_that_left_before_the_run_ended_is_judged(self):
        # SUMO ran on to 70 s after the only ego's last step (59.9 s): the driver recorded
        # collisions until then, so its episode ending at 59.4 s is a false alarm, not unjudged.
        run = make_run("gv5_0.1s", "a", [0.0] * 600, end_s=70.0,
                       warnings=[run_data.Warning("a", 58.0, 59.4, 0.9)])
        self.assertAlmostEqual(city_false_alarms.last_time_s(run), 70.0)
        row = family_eval.judge("ours", network_family.Network("gv", 5, 0.1), run)
        self.assertEqual((row.false_alarms, row.unjudged), (1, 0))
        self.assertAlmostEqual(row.judged_vehicle_hours, row.vehicle_hours)


    def test_the_sets_are_also_given_per_step_length(self):
        # The targets are per step length: one tuning network at 0.1 s steps with one false
        # alarm, the same network at 1 s steps with two (the rows take their step from the
        # network; both runs are STEP runs of 60 s).
        w = run_data.Warning
        fast = make_run("gv5_0.1s", "a", [0.0] * 600, warnings=[w("a", 10.0, 10.5, 0.9)])
        slow = make_run("gv5_1s", "a", [0.0] * 600,
                        warnings=[w("a", 10.0, 12.0, 0.9), w("a", 30.0, 31.0, 0.9)])
        rows = [family_eval.judge("ours", network_family.Network("gv", 5, 0.1), fast),
                family_eval.judge("ours", network_family.Network("gv", 5, 1.0), slow)]
        (both,) = family_eval.sets(rows)
        self.assertEqual((both.false_alarms, both.step_s), (3, None))
        per = family_eval.sets(rows, by_step=True)
        self.assertEqual([(s.split, s.step_s, s.false_alarms) for s in per],
                         [("tuning", 1.0, 2), ("tuning", 0.1, 1)])
        self.assertEqual([s.network for s in per], ["1 of 1 networks"] * 2)
        self.assertAlmostEqual(per[1].false_alarms_per_vehicle_hour, 1 / (600 * STEP / 3600))
        with tempfile.TemporaryDirectory() as d:
            family_eval.write(d, rows, ["- test"])
            with open(os.path.join(d, "family_set_steps.csv"), encoding="utf-8") as f:
                lines = f.read().splitlines()
            self.assertEqual(len(lines), 3)  # the header and the two step lengths
            self.assertTrue(lines[1].startswith("ours,tuning,1 of 1 networks,1.000,ok,"))
            with open(os.path.join(d, "family.md"), encoding="utf-8") as f:
                self.assertIn("## By set and step length", f.read())

if __name__ == "__main__":
    unittest.main()
