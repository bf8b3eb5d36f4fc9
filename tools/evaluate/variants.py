"""The runs of the evaluation over the designed scenarios: one row per variant, each a set of
extra sumo-criticality options (name: value without dashes, as in a campaign file's `driver`
section; true = a switch). To add a variant, add a row. The evaluation stops before running
anything when the driver's --help does not list an option a chosen variant names (an older
driver; evaluate.py).

`ours` (open loop, --act warn, with SUMO's SSM device on the ego) is the reference every other
row is compared with; `closed-loop` is the same scenarios with --act brake."""

from dataclasses import dataclass, field


@dataclass
class Variant:
    name: str
    what: str  # one line for tables and captions
    options: dict = field(default_factory=dict)
    loop: str = "open"  # open: an ablation or preset beside ours; closed: --act brake
    ssm: bool = False  # SUMO's SSM device on the ego (SSM does not change the traffic)

    def missing_options(self, driver_help):
        return [name for name in self.options if not driver_help.has(name)]


VARIANTS = [
    Variant("ours", "default estimator and options, --act warn", {"act": "warn"}, ssm=True),
    Variant("closed-loop", "--act brake (brake while p >= the brake threshold)",
            {"act": "brake"}, loop="closed"),
    Variant("no-lateral-controller", "the paper's ablation: lateral controller off",
            {"act": "warn", "no-lateral-controller": "true"}),
    Variant("no-road-model", "the paper's ablation: no road model (virtual lanes only)",
            {"act": "warn", "no-road-model": "true"}),
    Variant("no-car-following",
            "ours without the car-following reference (the paper's: keep the current acceleration)",
            {"act": "warn", "no-car-following": "true"}),
    Variant("observable", "ours with only what sensors could know (--observable-only: no routes)",
            {"act": "warn", "observable-only": "true"}),
    Variant("no-yield-stops",
            "ours without yield lines where SUMO has a foe approaching (--no-yield-stops)",
            {"act": "warn", "no-yield-stops": "true"}),
    Variant("release-braking",
            "ours with braking that no known cause asks for released in the reference "
            "(--release-braking)",
            {"act": "warn", "release-braking": "true"}),
    Variant("no-world-step-collisions",
            "ours with collisions counted at every step, not only at SUMO's "
            "(--no-world-step-collisions)",
            {"act": "warn", "no-world-step-collisions": "true"}),
    Variant("ego-stops",
            "ours with the ego's own credible stop line as its reference (--ego-stops)",
            {"act": "warn", "ego-stops": "true"}),
    Variant("no-internal-junction-yield",
            "ours with a yield line at the junction's entry also where SUMO lets the vehicle "
            "wait inside (--no-internal-junction-yield)",
            {"act": "warn", "no-internal-junction-yield": "true"}),
    Variant("no-crossing-stops",
            "ours without a waiting pedestrian's stop where its crossing begins (--no-crossing-stops)",
            {"act": "warn", "no-crossing-stops": "true"}),
    Variant("bodies-on-path",
            "ours with every vehicle SUMO's box, predicted centred on the chord of its path "
            "(--bodies-on-path)",
            {"act": "warn", "bodies-on-path": "true"}),
    Variant("bent-bodies",
            "ours with a body bent by a turn as a chain of boxes along its way (--bent-bodies)",
            {"act": "warn", "bent-bodies": "true"}),
    Variant("no-heading-hold",
            "ours taking SUMO's heading as it is, also where it turns faster than grip allows "
            "(--no-heading-hold)",
            {"act": "warn", "no-heading-hold": "true"}),
    Variant("no-way-heading",
            "ours taking SUMO's angle also just after a lane change past a junction "
            "(--no-way-heading)",
            {"act": "warn", "no-way-heading": "true"}),
    Variant("no-lane-fit-check",
            "ours using a lane's samples over the full reach even where their parabola leaves "
            "the lane (--no-lane-fit-check)",
            {"act": "warn", "no-lane-fit-check": "true"}),
    Variant("no-straight-by-fit",
            "ours taking a short straight's (2-15 m) middle samples at the middle of the reach, "
            "not at the straight's end where that fits the road better (--no-straight-by-fit)",
            {"act": "warn", "no-straight-by-fit": "true"}),
    Variant("no-hold-line",
            "ours with every vehicle heading for its lane's centre, a cyclist at the kerb too, "
            "not holding the line it rides (--no-hold-line)",
            {"act": "warn", "no-hold-line": "true"}),
    Variant("no-sumo-box",
            "ours with every vehicle's box its full length from its front along SUMO's angle, "
            "not SUMO's box from front to back on a bent way (--no-sumo-box)",
            {"act": "warn", "no-sumo-box": "true"}),
    Variant("lane-corners",
            "experiment (ours): lanes that turn are sent as corners: straight, a parabola "
            "tangent to both straights, straight (--lane-corners)",
            {"act": "warn", "lane-corners": "true"}),
    Variant("no-lane-heading-yaw-rate",
            "ours taking every vehicle's yaw rate at short steps from its last step's heading "
            "change (--no-lane-heading-yaw-rate)",
            {"act": "warn", "no-lane-heading-yaw-rate": "true"}),
    Variant("no-lane-change-yaw-rate",
            "ours taking the heading change of a vehicle SUMO moves sideways just past a "
            "junction as its yaw rate, not its lane's (--no-lane-change-yaw-rate)",
            {"act": "warn", "no-lane-change-yaw-rate": "true"}),
    Variant("lane-change-target",
            "experiment (ours): a vehicle seen changing lanes is taken as on the lane it moves "
            "into (--lane-change-target)",
            {"act": "warn", "lane-change-target": "true"}),
    Variant("lane-corner-in-turn",
            "experiment (ours): a vehicle in a junction turn too tight for its lane's samples "
            "gets a corner from where it is instead of no lanes (--lane-corner-in-turn)",
            {"act": "warn", "lane-corner-in-turn": "true"}),
    Variant("no-junction-ways",
            "ours predicting a vehicle whose body is in a junction like any other, steering "
            "after its lanes, not along its way as SUMO moves it (--no-junction-ways)",
            {"act": "warn", "no-junction-ways": "true"}),
    Variant("way-lateral-paths",
            "experiment (ours): a vehicle on its way through a junction gets its lanes' lateral "
            "samples as paths beside its way, not one path on it (--way-lateral-paths)",
            {"act": "warn", "way-lateral-paths": "true"}),
    Variant("ego-on-way",
            "experiment (ours): an ego whose body is in a junction moves along its way on one "
            "path, as other vehicles do, not steered after its lanes (--ego-on-way)",
            {"act": "warn", "ego-on-way": "true"}),
    Variant("euler-stops",
            "experiment (ours): a hypothesis whose speed is 0 at one of SUMO's steps stays "
            "where SUMO's previous step left it, not half a step's speed change back "
            "(--euler-stops)",
            {"act": "warn", "euler-stops": "true"}),
    Variant("no-junction-chord-heading",
            "ours reading a vehicle whose body is in a junction with SUMO's angle or a heading "
            "held over its jumps, not its lanes' chord from back to front "
            "(--no-junction-chord-heading)",
            {"act": "warn", "no-junction-chord-heading": "true"}),
    Variant("ego-way-euler-stops",
            "experiments (ours) together: the ego on its way and hypotheses that stop within "
            "one of SUMO's steps staying there (--ego-on-way --euler-stops)",
            {"act": "warn", "ego-on-way": "true", "euler-stops": "true"}),
    Variant("no-expected-accel-at-once",
            "ours holding a vehicle's current acceleration through the reaction latency also "
            "where its expected one is lower (--no-expected-accel-at-once)",
            {"act": "warn", "no-expected-accel-at-once": "true"}),
    Variant("no-stop-at-once",
            "ours holding a vehicle with a credible stop line at its current acceleration "
            "through the reaction latency, complying only within 3.4 m/s^2 (--no-stop-at-once)",
            {"act": "warn", "no-stop-at-once": "true"}),
    Variant("no-junction-shapes",
            "ours drawing the lanes ahead through a junction as the chord between the lanes, "
            "not along its internal lanes (--no-junction-shapes)",
            {"act": "warn", "no-junction-shapes": "true"}),
    Variant("accel-window-0.3",
            "ours reading each vehicle's acceleration as its speed change over 0.3 s, not the "
            "last step's (--accel-window 0.3)",
            {"act": "warn", "accel-window": "0.3"}),
    Variant("accel-window-0.5",
            "ours reading each vehicle's acceleration as its speed change over 0.5 s, not the "
            "last step's (--accel-window 0.5)",
            {"act": "warn", "accel-window": "0.5"}),
    Variant("horizon-3", "ours predicting 3 s ahead (--horizon 3) instead of the paper's 2 s",
            {"act": "warn", "horizon": "3"}),
    Variant("paper-literal", "the first implementation's scoring (ParamsPreset paper-literal)",
            {"act": "warn", "preset": "paper-literal"}),
]

REFERENCE = "ours"


def by_name(name):
    for v in VARIANTS:
        if v.name == name:
            return v
    raise KeyError(name)
