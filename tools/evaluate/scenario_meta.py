"""A designed scenario's metadata, read from its scenario.cfg (scenarios/README.md).

The keys the evaluation needs: ego, expect (collision | no-collision), expect-partner,
quiet-until (the end of the quiet phase: a warning that starts at or before it is a false
alarm), category (static-object, moving-object, pedestrian, free) and all-vehicles (the
city-like run, not a designed scenario).
"""

import os
from dataclasses import dataclass

CATEGORIES = ("static-object", "moving-object", "pedestrian", "free")


@dataclass
class Scenario:
    name: str
    folder: str
    cfg_path: str
    ego: str = ""
    expect: str = ""
    partner: str = ""
    quiet_until_s: float = 0.0
    category: str = ""
    all_vehicles: bool = False

    @property
    def collides(self):
        return self.expect == "collision"


def read_cfg(path):
    """`name = value` lines of a scenario.cfg as a dict (repeated keys: the last one; events
    are left out)."""
    cfg = {}
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            key, sep, value = line.partition("=")
            if not sep:
                raise ValueError(f"{path}:{number}: expected 'name = value', got '{line}'")
            key = key.strip()
            if key != "event":
                cfg[key] = value.strip()
    return cfg


def read_scenario(folder):
    """The Scenario of a folder holding scenario.cfg; ValueError naming the file when a key the
    evaluation needs is missing or wrong."""
    folder = os.path.abspath(folder)
    path = os.path.join(folder, "scenario.cfg")
    cfg = read_cfg(path)
    s = Scenario(name=os.path.basename(folder), folder=folder, cfg_path=path,
                 ego=cfg.get("ego", ""), expect=cfg.get("expect", ""),
                 partner=cfg.get("expect-partner", ""), category=cfg.get("category", ""),
                 all_vehicles=cfg.get("all-vehicles", "false") == "true")
    try:
        s.quiet_until_s = float(cfg.get("quiet-until", "0"))
    except ValueError:
        raise ValueError(f"{path}: quiet-until '{cfg['quiet-until']}' is not a number") from None
    if s.expect not in ("collision", "no-collision"):
        raise ValueError(f"{path}: expect must be collision or no-collision, got '{s.expect}'")
    if s.category not in CATEGORIES:
        raise ValueError(f"{path}: category must be one of {', '.join(CATEGORIES)}, "
                         f"got '{s.category}'")
    if not s.all_vehicles and not s.ego:
        raise ValueError(f"{path}: a designed scenario names its ego (ego = ID)")
    return s


def suite(root):
    """(designed scenarios, city-like runs) under root: every folder with a scenario.cfg, sorted
    by name; those with all-vehicles = true are the city-like runs."""
    designed, city = [], []
    for name in sorted(os.listdir(root)):
        if os.path.exists(os.path.join(root, name, "scenario.cfg")):
            s = read_scenario(os.path.join(root, name))
            (city if s.all_vehicles else designed).append(s)
    return designed, city
