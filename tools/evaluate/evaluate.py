#!/usr/bin/env python3
"""The evaluation of sumo-criticality on the designed scenarios and the city-like run (issue 10):
runs the variants through criticality-campaign, then writes OUT/ (default eval/): results.csv and
results.md (per scenario: SUMO's outcome, our anticipation at the warning threshold and at
"unavoidable", false positives, SSM's side by side, the variants, the closed loop), city.csv,
threshold_sweep.csv, targets.csv, figures (PNG), index.html and run_info.json (what was run).

Usage: tools/evaluate.sh [options]   (or python3 tools/evaluate/evaluate.py [options])
Every option: --help. tools/evaluate/README.md says what each figure means."""

import argparse
import datetime
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

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
import variants as variant_table  # noqa: E402

# The city run by default: the first CITY_END_S simulated seconds (the traffic builds up over the
# first ~130 s; every vehicle an ego costs about 3 s of CPU per simulated second at its peak, so
# 300 s did not finish in 15 minutes on the shared 2-core machine). --full: the whole run (900 s,
# about 14 vehicle-hours).
CITY_END_S = 120


def log(text):
    print(text, file=sys.stderr, flush=True)


def parse_args(argv):
    ap = argparse.ArgumentParser(
        prog="tools/evaluate.sh",
        description="Evaluate sumo-criticality on the designed scenarios (ours, SUMO's SSM "
        "device, ablations, closed loop) and the city-like run; writes tables, figures and "
        "index.html.")
    ap.add_argument("--out", default=os.path.join(ROOT, "eval"),
                    help="output folder (default: eval/ in the repository)")
    ap.add_argument("--driver", default=os.path.join(ROOT, "build", "plugin", "sumo-criticality"))
    ap.add_argument("--campaign-tool",
                    default=os.path.join(ROOT, "build", "tools", "campaign", "criticality-campaign"))
    ap.add_argument("--scenarios", default=os.path.join(ROOT, "scenarios"),
                    help="folder of scenario folders (default: scenarios/)")
    ap.add_argument("--only", default="",
                    help="comma-separated designed scenarios to run (default: all)")
    ap.add_argument("--variants", default="",
                    help="comma-separated variants (default: all; see tools/evaluate/variants.py)")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 2,
                    help="runs at once (default: the cores)")
    city = ap.add_mutually_exclusive_group()
    city.add_argument("--full", action="store_true",
                      help="the whole city-like run (900 s, about an hour on 2 cores) instead of "
                      f"its first {CITY_END_S} s")
    city.add_argument("--city-end", type=float, default=CITY_END_S,
                      help=f"simulated seconds of the city-like run (default {CITY_END_S})")
    city.add_argument("--no-city", action="store_true", help="skip the city-like run")
    ap.add_argument("--resume", action="store_true",
                    help="keep complete runs of an earlier evaluation in OUT/runs (default: run "
                    "everything afresh, so that every figure comes from the driver as it is now)")
    ap.add_argument("--family", choices=sorted(network_family.PROFILES),
                    help="instead of the designed scenarios: the held-out protocol's generated "
                    "networks (tools/evaluate/network_family.py; quick: seeds 1 and 3, 12 runs "
                    "per variant; full: seeds 1-4; violations: priority-junction grid and rand nets "
                    "where a seeded 30 %% of cars and trucks ignore right of way, seeds 5 and 6, "
                    "8 runs; violations-full: seeds 5-9, 5 and 7 tuning, 20 runs; sublane: "
                    "the sublane grids and spider of bench/RESULTS.md, 0.1 s steps, g1 tuning, "
                    "h4, sp and g7 held-out, 4 runs of 10-25 minutes), every vehicle an ego, "
                    "tuning and held-out "
                    "sets side by side; default variants: ours and observable")
    ap.add_argument("--family-step", type=float, choices=network_family.STEPS_S,
                    help="with --family: only the networks at this SUMO step length (s), e.g. "
                    "0.1 for a change that acts at short steps only (default: both, 1 and 0.1)")
    ap.add_argument("--family-nets", default="",
                    help="with --family: only these of its networks, comma-separated by network "
                    "name as in the tables (e.g. sgrid1,sgrid7; default: all of the profile)")
    ap.add_argument("--family-time-limit", type=int, default=3600,
                    help="seconds one family run may take before it is stopped (default 3600)")
    ap.add_argument("--report-only", action="store_true",
                    help="no runs: tables and figures from OUT/runs as they are")
    return ap.parse_args(argv)


def git_describe():
    try:
        rev = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return rev + ("+changes" if dirty else "")
    except OSError:
        return "unknown"


def run_family(a, chosen, info):
    """The held-out protocol (--family): generate the networks, run each variant over them
    with every vehicle an ego (closed-loop variants under --act brake), write family.* into
    OUT."""
    out = os.path.abspath(a.out)
    nets = network_family.family(a.family, a.family_step)
    if a.family_nets:
        try:
            nets = network_family.only(nets, a.family_nets)
        except ValueError as e:
            log(f"evaluate: --family-nets: {e} of --family {a.family}")
            return 2
    if not nets:
        log(f"evaluate: --family {a.family} has no networks at {a.family_step:g} s steps: "
            "leave out --family-step or choose another")
        return 2
    try:
        cfgs = [network_family.generate(n, os.path.join(out, "family_nets"), log) for n in nets]
    except (RuntimeError, OSError) as e:
        log(f"evaluate: {e}")
        return 2
    runs_dir = os.path.join(out, "runs")
    if not a.report_only:
        runner = campaign_runs.CampaignRunner(a.campaign_tool, a.driver, runs_dir, a.jobs, log)
        try:
            for v in chosen:
                t0 = time.time()
                driver = dict(v.options, **{"all-vehicles": "true", "threads": 1})
                runner.run("family-" + v.name, cfgs, driver, {}, a.family_time_limit, a.resume)
                info["wall_s"]["family-" + v.name] = round(time.time() - t0, 1)
        except (RuntimeError, OSError) as e:
            log(f"evaluate: {e}")
            return 1
    rows = []
    for v in chosen:
        by = family_eval.read_runs(os.path.join(runs_dir, "family-" + v.name))
        rows += [family_eval.judge(v.name, n, by.get(n.name)) for n in nets]
    lines = [f"- {info['date']}, commit {info['commit']}, `{info['command']}`",
             f"- profile {a.family}: {len(nets)} networks "
             f"({sum(n.split == 'tuning' for n in nets)} tuning, "
             f"{sum(n.split == 'held-out' for n in nets)} held-out"
             + (f", {a.family_step:g} s steps only" if a.family_step is not None else "")
             + "); variants "
             f"{', '.join(v.name for v in chosen)}"]
    family_eval.write(out, rows, lines)
    info["networks"] = [{"name": n.name, "split": n.split} for n in nets]
    with open(os.path.join(out, "run_info.json"), "w", encoding="utf-8") as f:
        json.dump(info, f, indent=1)
    log(f"evaluate: {out}/family.html")
    return 0


def main(argv):
    a = parse_args(argv)
    started = time.time()
    out = os.path.abspath(a.out)
    runs_dir = os.path.join(out, "runs")
    os.makedirs(out, exist_ok=True)
    for tool in (a.driver, a.campaign_tool):
        if not os.access(tool, os.X_OK):
            log(f"evaluate: {tool} is missing: build first (tools/setup.sh)")
            return 2
    try:
        helptext = driver_help.read_driver_help(a.driver)
        designed, cities = scenario_meta.suite(a.scenarios)
    except (RuntimeError, ValueError, OSError) as e:
        log(f"evaluate: {e}")
        return 2
    if a.only:
        wanted = [w.strip() for w in a.only.split(",") if w.strip()]
        unknown = [w for w in wanted if w not in {s.name for s in designed}]
        if unknown:
            log(f"evaluate: --only: no designed scenario {', '.join(unknown)} in {a.scenarios}")
            return 2
        designed = [s for s in designed if s.name in wanted]
    chosen = variant_table.VARIANTS
    if a.family and not a.variants:
        chosen = [variant_table.by_name("ours"), variant_table.by_name("observable")]
    if a.variants:
        names = [w.strip() for w in a.variants.split(",") if w.strip()]
        try:
            chosen = [variant_table.by_name(n) for n in names]
        except KeyError as e:
            log(f"evaluate: --variants: unknown variant {e} (known: "
                f"{', '.join(v.name for v in variant_table.VARIANTS)})")
            return 2
        if variant_table.REFERENCE not in names and not a.family:  # the family needs none
            chosen = [variant_table.by_name(variant_table.REFERENCE)] + chosen
    missing = {v.name: v.missing_options(helptext) for v in chosen}
    missing = {k: m for k, m in missing.items() if m}
    if missing:
        for name, m in missing.items():
            log(f"evaluate: variant {name} needs {', '.join('--' + o for o in m)}, which "
                f"{a.driver} --help does not list: build the driver of this checkout "
                "(tools/setup.sh) or pass --driver")
        return 2
    available = list(chosen)
    city_setting = None
    if not a.no_city and cities:
        city_setting = ("the whole run (900 s)" if a.full else
                        f"the first {a.city_end:g} s (--end {a.city_end:g})")

    info = {"date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), "commit": git_describe(),
            "driver": a.driver, "command": "tools/evaluate.sh " + " ".join(argv),
            "jobs": a.jobs, "variants": [v.name for v in available],
            "scenarios": [s.name for s in designed], "city": city_setting,
            "unavoidable_level": open_loop.UNAVOIDABLE_LEVEL, "wall_s": {}}
    try:
        info["driver_version"] = subprocess.run([a.driver, "--version"], capture_output=True,
                                                text=True).stdout.strip()
    except OSError:
        info["driver_version"] = ""

    if a.family:
        return run_family(a, available, info)
    if not a.report_only:
        runner = campaign_runs.CampaignRunner(a.campaign_tool, a.driver, runs_dir, a.jobs, log)
        egos = ",".join(sorted({s.ego for s in designed}))
        cfgs = [s.cfg_path for s in designed]
        try:
            for v in available:
                t0 = time.time()
                driver = dict(v.options, threads=1)  # the pool runs one run per core
                sumo = dict(campaign_runs.SSM_OPTIONS, **{"device.ssm.explicit": egos}) \
                    if v.ssm else {}
                runner.run(v.name, cfgs, driver, sumo, 600, a.resume)
                info["wall_s"][v.name] = round(time.time() - t0, 1)
            if city_setting:
                t0 = time.time()
                driver = {"act": "warn", "threads": a.jobs}
                if not a.full:
                    driver["end"] = f"{a.city_end:g}"
                sumo = dict(campaign_runs.SSM_OPTIONS, **{"device.ssm.probability": "1"})
                runner.run("city", [c.cfg_path for c in cities[:1]], driver, sumo, 0, a.resume,
                           jobs=1)
                info["wall_s"]["city"] = round(time.time() - t0, 1)
        except (RuntimeError, OSError) as e:
            log(f"evaluate: {e}")
            return 1
    info["wall_s"]["runs_total"] = round(time.time() - started, 1)

    # --- the figures ---------------------------------------------------------------------------
    import report  # noqa: E402  (matplotlib only from here on)
    runs, columns = {}, {}
    for v in available:
        folder = os.path.join(runs_dir, v.name)
        if os.path.exists(os.path.join(folder, "campaign.sqlite")):
            runs[v.name], columns[v.name] = run_data.read_campaign(folder)
        else:
            log(f"evaluate: no runs of variant {v.name} in {folder}")
    ref = variant_table.REFERENCE
    ssm = {}
    for s in designed:
        run = runs.get(ref, {}).get(s.name)
        if run is not None:
            ssm[s.name] = ssm_log.read_ssm(os.path.join(run.folder, campaign_runs.SSM_FILE))
    rows = {name: [open_loop.judge_run(s, name, by.get(s.name), helptext,
                                       ssm.get(s.name) if name == ref else None)
                   for s in designed]
            for name, by in runs.items() if variant_table.by_name(name).loop == "open"}
    closed = []
    for v in available:
        if v.loop == "closed" and v.name in runs:
            closed = [closed_loop.compare(s, runs.get(ref, {}).get(s.name),
                                          runs[v.name].get(s.name)) for s in designed]
    city_row, city_run, city_ssm, city_classes = None, None, None, []
    city_folder = os.path.join(runs_dir, "city")
    if city_setting and os.path.exists(os.path.join(city_folder, "campaign.sqlite")):
        by, _ = run_data.read_campaign(city_folder)
        city_run = next(iter(by.values()), None)
        if city_run is not None:
            city_ssm = ssm_log.read_ssm(os.path.join(city_run.folder, campaign_runs.SSM_FILE))
        city_row = city_false_alarms.judge_city(city_run, city_setting, city_ssm)
        city_classes = city_false_alarms.judge_city_by_class(city_run)
    ref_runs = runs.get(ref, {})
    release_ratio, release_after = 0.8, 0.0
    first = next((r for r in ref_runs.values() if r.ok), None)
    if first is not None:
        thr, rel = open_loop.warn_settings(first, helptext)
        release_ratio = rel / thr if thr > 0 else 0.8
        release_after = open_loop.warn_release_after(first, helptext)
    sweep = (threshold_sweep.sweep_ours(designed, ref_runs, city_run, release_ratio,
                                        release_after_s=release_after) +
             threshold_sweep.sweep_ssm(designed, ref_runs, ssm, city_run, city_ssm))
    target_rows = targets.check(rows.get(ref, []), city_row)
    info["wall_s"]["total"] = round(time.time() - started, 1)
    report.write_all(out, designed, rows, closed, city_row, sweep, target_rows, info, runs,
                     columns, ssm, available, city_classes)
    info["wall_s"]["total"] = round(time.time() - started, 1)
    with open(os.path.join(out, "run_info.json"), "w", encoding="utf-8") as f:
        json.dump(info, f, indent=1)
    log(f"evaluate: {out}/index.html ({info['wall_s']['total']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
