"""The required-inertia section: J_F by the constant-inertia, energy–mass and dynamic models.

Each model (:mod:`flyopt.sizing.choose`) on a constant-inertia, a
variable-inertia and a speed-dependent scene, against the model that is exact
for the scene; on the constant-inertia scene (domain worked example 2,
docs/flywheel-design.md) against its closed form, so that the exact model is
itself checked.
"""

from __future__ import annotations

import math

from flyopt._toml import tomllib
from flyopt.bench.timing import Config, Row, measure, once, set_ratios
from flyopt.io.scene import from_dict
from flyopt.machine.reduce import reduce
from flyopt.sizing.choose import ENERGY_MASS, ORDER, achieved_delta, choose, requirement

__all__ = ["INERTIA_SCENES", "section_required_inertia"]


INERTIA_SCENES = {
    # constant inertia, torques of the angle: domain worked example 2 (closed form known)
    "constant J (shear press)": """
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]
[torque.driving]
constant = "unknown"
""",
    # the inertia varies with the angle: a slider-crank press with a heavy ram
    "variable J (slider-crank press)": """
[machine]
speed = "120 rpm"
delta = 0.15
inertia = "2 kg*m^2"
[mechanism]
kind = "slider_crank"
crank = "0.08 m"
rod = "0.45 m"
[[member]]
name = "ram"
part = "slider"
mass = "400 kg"
angle_unit = "deg"
unit = "kN"
force = [[0, 0], [140, 0], [140, 25], [175, 60], [180, 0], [360, 0]]
[[member]]
name = "rod"
part = "rod"
centre = "0.15 m"
mass = "60 kg"
inertia = "1.2 kg*m^2"
[torque.driving]
constant = "unknown"
[torque.resisting]
constant = "150 N*m"
""",
    # a torque depends on speed: the punch press on an induction motor
    "speed-dependent (motor press)": """
[machine]
speed = "60 rpm"
delta = 0.1
efficiency = 0.9215
[torque.driving]
motor = { kind = "induction", rated_power = "5.5 kW", rated_speed = "1440 rpm", synchronous_speed = "1500 rpm", shaft = "motor" }
[torque.resisting]
unit = "N*m"
angle_unit = "deg"
points = [[0, 150], [150, 150], [150, 2000], [165, 9000], [180, 9000], [180, 150], [360, 150]]
[[shaft]]
name = "motor"
speed_ratio = 24.0
""",
}


def section_required_inertia(config: Config) -> list[Row]:
    """J_F by the constant-inertia, energy–mass and dynamic models on scenes that need each.

    Error: relative to the exact model's J_F (for worked example 2, to its closed
    form, so that the exact model is itself checked); the note gives the δ that each
    J_F really achieves, by the exact model. Reference method for time ratios: the
    exact model of each scene.
    """
    rows = []
    for case, text in INERTIA_SCENES.items():
        scene = from_dict(tomllib.loads(text), source=f"bench: {case}")
        machine = reduce(scene)
        exact, _ = choose(machine)
        results, timings = {}, {}
        for model in ORDER:
            if model == ENERGY_MASS and not machine.variable_inertia and exact != ENERGY_MASS:
                continue  # with a constant inertia it is the energy method again
            if model == ENERGY_MASS and machine.speed_dependent:
                continue  # the energy–mass closed form holds only for torques of the angle alone

            def run(model=model):  # a fresh reduction each call: no cached ExcessWork, the whole model timed
                return requirement(reduce(scene), model)

            if config.quick:  # one call: the periodic solution takes seconds
                results[model], timings[model] = once(run)
            else:
                results[model], timings[model] = run(), measure(run, 3, 0.0)
        if case.startswith("constant"):
            omega = 1500 * 2 * math.pi / 60
            j_ref = math.pi / 4 * 1137.5 * (1 + 0.8125 / 2) / (omega**2 * 0.05)
            reference = "closed form of worked example 2"
        else:
            j_ref = results[exact].j_required
            reference = f"the exact model ({exact})"
        for model, res in results.items():
            delta = achieved_delta(machine, res.j_required)
            err = abs(res.j_required - j_ref) / j_ref
            setting = (
                "cheapest exact"
                if model == exact
                else "exact, costlier"
                if ORDER.index(model) > ORDER.index(exact)
                else "approximate"
            )
            rows.append(
                Row.timed(
                    "required_inertia",
                    case,
                    model,
                    setting,
                    timings[model],
                    error=err,
                    error_median=err,
                    reference=reference,
                    note=f"J_F {res.j_required:.6g} kg*m^2; achieves delta {delta:.6g} "
                    f"(allowed {scene.delta:g}){'; the exact model' if model == exact else ''}",
                )
            )
    set_ratios(rows, lambda r: r.setting == "cheapest exact")
    return rows
