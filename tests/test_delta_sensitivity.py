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


SHAFT = """
[[shaft]]
name = "motor"
speed_ratio = 1.0
material = "42crmo4_qt"
segments = [{ to = "400 mm", diameter = "80 mm" }]
bearings = ["50 mm", "350 mm"]
wheel_at = "200 mm"
torque_at = "380 mm"
"""


def _shear_press_on_a_described_shaft(tmp_path):
    from conftest import PROBLEMS

    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    start = text.index("[[shaft]]")
    end = text.index("[design]")
    path = tmp_path / "scene.toml"
    path.write_text(text[:start] + SHAFT.lstrip() + "\n" + text[end:], encoding="utf-8")
    return load(path)


def _delta_slope(best):
    return [s for s in best.limits.sensitivities if s["limit"] == "delta"]


def test_the_slopes_redesigns_pass_the_shafts_post_check(tmp_path, monkeypatch):
    """d(mass)/d(delta) re-designs the winner at delta (1 +- 1e-4): each must pass the same post-check as the
    design. Here the shaft's check is made to refuse any wheel heavier than the chosen one: the heavier wheel of
    the smaller delta is refused, so no slope is given (it was given from a wheel the shaft refused)."""
    import flyopt.design.shaft.cycle as cycle

    scene = _shear_press_on_a_described_shaft(tmp_path)
    plain = solve(scene)
    assert plain.shaft_checks and _delta_slope(plain.design.best)  # the shaft checked, the slope given
    chosen = plain.design.best.mass
    real = cycle.acceptor

    def heavier_refused(ctx, *names):
        check = real(ctx, *names)

        def accept(candidate):
            if candidate.mass > chosen * (1 + 1e-9):
                return f"a made-up limit: {candidate.mass} kg is over {chosen} kg"
            return check(candidate)

        return accept

    monkeypatch.setattr(cycle, "acceptor", heavier_refused)
    refused = solve(scene)
    assert refused.design.best.mass == chosen
    assert _delta_slope(refused.design.best) == []
