"""d(mass)/d(delta) of the winner, against its derivative written out.

Worked example 1 (net areas, A_max = 1600 J, 1500 rpm) with a disc sized by
the rim speed limit and no envelope: J_F = A_max/(omega^2 delta) (no J_c),
omega_max = omega (1 + delta/2), D = 2 v_max/omega_max and m = 8 J/D^2, so

    m(delta) = 2 A_max (1 + delta/2)^2 / (v_max^2 delta),
    dm/ddelta = 2 A_max / v_max^2 * [(1 + delta/2)/delta - (1 + delta/2)^2/delta^2].

flyopt takes the slope by a central difference of the whole design
(pipeline.DELTA_STEP = 1e-4): truncation ~(1e-4)^2 of the curvature, so 1e-6.
"""

import math

import pytest

from flyopt.io.scene import load
from flyopt.pipeline import solve

SCENE = """
title = "net areas, a disc"
[machine]
speed = "1500 rpm"
delta = {delta}
[torque.net]
areas = ["1500 J", "-1000 J", "400 J", "-1000 J", "100 J"]
[design]
geometry = "disc"
materials = ["cast_steel"]
"""


@pytest.mark.parametrize("delta", [0.02, 0.1, 0.3])
def test_dmass_ddelta_of_a_disc_at_its_rim_speed_limit(tmp_path, delta):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.format(delta=delta))
    best = solve(load(path)).design.best
    a_max, v_max = 1600.0, 50.0
    assert best.mass == pytest.approx(2 * a_max * (1 + delta / 2) ** 2 / (v_max**2 * delta), rel=1e-12)
    slope = {s["limit"]: s["dmass_dlimit"] for s in best.limits.sensitivities}["delta"]
    exact = 2 * a_max / v_max**2 * ((1 + delta / 2) / delta - (1 + delta / 2) ** 2 / delta**2)
    assert slope == pytest.approx(exact, rel=1e-6)
    assert math.copysign(1, slope) == -1
