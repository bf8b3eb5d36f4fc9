"""SUMO's SSM device output (--device.ssm.file with --device.ssm.trajectories true), as warning
episodes comparable with ours.

Each <conflict ego foe begin end> holds time series (timeSpan, TTCSpan, DRACSpan; "NA" where a
measure is undefined) and one PET value with the time it was measured. A sample is critical when
TTC < ttc_max or DRAC > drac_min; the critical samples of an ego, over all its foes, make its
episodes (a warning system on the ego built on SSM would warn while any foe is critical), so that
they count like ours, one per ego. PET is only known once the second vehicle has entered the
conflict area, i.e. after the encounter: it can count as a false alarm but never anticipates.
SSM considers vehicles only (no persons): pedestrian scenarios have no SSM episodes.
Times are SUMO's, the same as the driver's (plugin/README.md, "Time stamps").
"""

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from warning_episodes import Episode


@dataclass
class Conflict:
    ego: str
    foe: str
    times: list = field(default_factory=list)
    ttc: list = field(default_factory=list)  # None for NA
    drac: list = field(default_factory=list)
    pet_s: float = None
    pet_time_s: float = None


def _values(element):
    if element is None or element.get("values") is None:
        return []
    return [None if v == "NA" else float(v) for v in element.get("values").split()]


def read_ssm(path):
    """The conflicts of an SSM file; None when the file does not exist (SSM was not run)."""
    if not os.path.exists(path):
        return None
    out = []
    for _, e in ET.iterparse(path):
        if e.tag != "conflict":
            continue
        c = Conflict(e.get("ego"), e.get("foe"))
        c.times = _values(e.find("timeSpan"))
        c.ttc = _values(e.find("TTCSpan")) or [None] * len(c.times)
        c.drac = _values(e.find("DRACSpan")) or [None] * len(c.times)
        pet = e.find("PET")
        if pet is not None and pet.get("value") not in (None, "NA"):
            c.pet_s = float(pet.get("value"))
            c.pet_time_s = float(pet.get("time"))
        out.append(c)
        e.clear()
    return out


def critical_times(conflict, ttc_max=3.0, drac_min=None):
    """The sample times at which the conflict is critical."""
    out = []
    for t, ttc, drac in zip(conflict.times, conflict.ttc, conflict.drac):
        if (ttc is not None and ttc < ttc_max) or (drac_min is not None and drac is not None
                                                   and drac > drac_min):
            out.append(t)
    return out


def merge_times(times, step_s):
    """Episodes from critical sample times: consecutive samples (at most 1.5 steps apart) form
    one episode; it ends one step after its last critical sample."""
    eps = []
    for t in sorted(set(round(x, 6) for x in times)):
        if eps and t - eps[-1].end_s <= 0.5 * step_s + 1e-9:
            eps[-1].end_s = t + step_s
        else:
            eps.append(Episode(t, t + step_s, 1.0))
    return eps


def ego_episodes(conflicts, ego, step_s, ttc_max=3.0, drac_min=3.0, pet_max=2.0, foe=None):
    """The SSM episodes of one ego (all foes, or only `foe`): critical TTC/DRAC samples merged
    over foes, plus a PET below pet_max as a one-step episode at the time it is measured (when it
    falls outside the others)."""
    times = []
    for c in conflicts:
        if c.ego == ego and (foe is None or c.foe == foe):
            times += critical_times(c, ttc_max, drac_min)
            if pet_max is not None and c.pet_s is not None and c.pet_s < pet_max:
                times.append(c.pet_time_s)
    return merge_times(times, step_s)


def all_ego_episodes(conflicts, step_s, ttc_max=3.0, drac_min=None, pet_max=None):
    """{ego: episodes} over every equipped vehicle (the city run: TTC only by default)."""
    egos = sorted({c.ego for c in conflicts})
    return {e: ego_episodes(conflicts, e, step_s, ttc_max, drac_min, pet_max) for e in egos}
