"""Balanced constant torques on an inertia that varies (ΔE ≡ 0): the energy–mass search starts at E_0 = 0,
where the top speed is 0 and dω/dE_0 infinite; it must say so without a division by zero (a RuntimeWarning
on stderr is a defect of its own: the hostile corpus counts it)."""

import warnings

import flyopt
from flyopt.io.scene import from_dict

SCENE = {
    "machine": {"speed": "60 rpm", "delta": 0.05, "cycle": "720 deg"},
    "mechanism": {"kind": "guide_bar", "crank": "150 mm", "frame": "300 mm", "lever": "550 mm", "speed_ratio": 0.5},
    "member": [{"name": "part", "part": "lever", "mass": "3 kg"}],
    "torque": {"driving": {"constant": "100 N*m"}, "resisting": {"constant": "unknown"}},
}


def test_no_division_by_zero_and_the_models_table_is_filled():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solution = flyopt.solve(from_dict(SCENE), design_flywheel=False, extras=("models",))
    analysis = solution.analysis
    assert analysis.a_max == 0.0 and analysis.j_required > 0  # the inertia alone makes the speed vary
    energy = next(row for row in analysis.models if row["model"] == "energy")
    # no flywheel while the lever's inertia falls to (almost) nothing: the speed all but unbounded, δ at its limit 2
    assert energy["j_required"] < 0 and 1.9 < energy["achieved_delta"] <= 2.0
