"""Running the evaluation's variants through criticality-campaign (tools/campaign/README.md):
one campaign file and folder per variant, written here, run with its process pool (`run -j N`:
resume, per-run time limit, a failed run recorded while the others go on), then `merge`d into
one database per variant.

Why the campaign tool and not a loop over the driver: it gives the pool, the time limit, resume
after an interrupted evaluation (--resume) and one database per variant with every run's tables
and status; the evaluation reads only that database and the SSM files in the run folders.
"""

import json
import os
import shutil
import subprocess

# SUMO's SSM device (https://sumo.dlr.de/docs/Simulation/Output/SSM_Device.html): the measures
# and thresholds the issue names (TTC < 3 s, DRAC > 3 m/s^2, PET < 2 s), time series of every
# conflict (trajectories), 100 m range, 5 s of tracking after the encounter. SUMO 1.15 resolves a
# relative device.ssm.file against the .sumocfg's folder (not the working directory, as it does
# for --fcd-output), which would put every run's file into the scenario folder; /proc/self/cwd
# is the driver's working directory, the run's folder in a campaign.
SSM_FILE = "ssm.xml"
SSM_OPTIONS = {
    "device.ssm.measures": "TTC DRAC PET",
    "device.ssm.thresholds": "3 3 2",
    "device.ssm.trajectories": "true",
    "device.ssm.range": "100",
    "device.ssm.extratime": "5",
    "device.ssm.file": "/proc/self/cwd/" + SSM_FILE,
}


def _yaml_value(v):
    if isinstance(v, list):
        return "[" + ", ".join(_yaml_value(x) for x in v) + "]"
    text = str(v)
    if text in ("true", "false"):
        return text
    return json.dumps(text)  # a double-quoted YAML string


def campaign_yaml(name, output, scenario_cfgs, driver_options, sumo_options, time_limit_s):
    """The text of a campaign file (keys: tools/campaign/README.md)."""
    lines = [f"# Written by tools/evaluate (variant {name}); do not edit, it is rewritten.",
             f"name: {_yaml_value(name)}", f"output: {_yaml_value(output)}", "scenarios:"]
    lines += [f"  - {_yaml_value(p)}" for p in scenario_cfgs]
    for section, options in (("driver", driver_options), ("sumo", sumo_options)):
        if options:
            lines.append(f"{section}:")
            lines += [f"  {k}: {_yaml_value(v)}" for k, v in options.items()]
    lines += ["limits:", f"  time_s: {int(time_limit_s)}", "  kill_after_s: 10"]
    return "\n".join(lines) + "\n"


class CampaignRunner:
    def __init__(self, tool, driver, folder, jobs, log):
        self.tool = tool
        self.driver = driver
        self.folder = folder  # eval/runs
        self.jobs = jobs
        self.log = log

    def run(self, name, scenario_cfgs, driver_options, sumo_options, time_limit_s, resume,
            jobs=None):
        """Runs one campaign and merges it; returns its folder (with campaign.sqlite). Without
        resume an earlier folder of the same name is removed first, so that every run comes from
        the driver as it is now."""
        out = os.path.join(self.folder, name)
        if os.path.exists(out) and not resume:
            shutil.rmtree(out)
        os.makedirs(self.folder, exist_ok=True)
        path = os.path.join(self.folder, name + ".yaml")
        with open(path, "w", encoding="utf-8") as f:
            f.write(campaign_yaml(name, out, scenario_cfgs, driver_options, sumo_options,
                                  time_limit_s))
        cmd = [self.tool, "run", path, "-j", str(jobs or self.jobs), "--driver", self.driver]
        self.log(f"evaluate: {name}: {len(scenario_cfgs)} runs: {' '.join(cmd)}")
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, text=True)
        if proc.returncode not in (0, 3):  # 3: some runs failed, recorded in the campaign
            raise RuntimeError(f"criticality-campaign run {path} exited {proc.returncode}: "
                               f"{(proc.stdout.strip().splitlines() or [''])[-1]}")
        proc = subprocess.run([self.tool, "merge", out], stdout=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"criticality-campaign merge {out} exited {proc.returncode}")
        return out
