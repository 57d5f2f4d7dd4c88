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


def test_the_text_and_the_report_say_the_step_of_delta_is_a_first_order_estimate(tmp_path, main_cli):
    """The δ line ("delta: +0.01 ... changes the mass by ...") is the slope times the step, a first-order
    estimate: for this disc the exact m(δ + 0.01) − m(δ) is 9 % smaller. The text's block said "Sensitivities
    of the mass:" and nothing of first order (the report's table did); both now head it with the words that
    say so, one wording."""
    import re

    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Table

    delta, a_max, v_max = 0.1, 1600.0, 50.0
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.format(delta=delta))

    def mass(d):  # the disc at its rim speed limit, in closed form (the module's docstring)
        return 2 * a_max * (1 + d / 2) ** 2 / (v_max**2 * d)

    first_order = 2 * a_max / v_max**2 * ((1 + delta / 2) / delta - (1 + delta / 2) ** 2 / delta**2) * 0.01
    again = mass(delta + 0.01) - mass(delta)
    assert abs(again - first_order) > 0.05 * abs(again)  # the two differ where the text shows them
    status, out, _ = main_cli("solve", path)
    assert status == 0
    lines = out.splitlines()
    at = next(k for k, line in enumerate(lines) if line.startswith("  - delta: +0.01"))
    shown = float(re.search(r"changes the mass by ([-+][\d.]+) kg", lines[at]).group(1))
    assert shown == pytest.approx(first_order, rel=5e-4) and shown != pytest.approx(again, rel=0.05)
    start = at
    while lines[start - 1].startswith("  - "):
        start -= 1
    heading = lines[start - 1]
    assert "first order" in heading, heading
    document = build(collect(str(path)), figures=False)
    try:
        captions = [
            block.caption
            for section in document.sections
            for block in section.blocks
            if isinstance(block, Table) and block.name == "sensitivities"
        ]
    finally:
        document.close()
    assert captions == [heading.rstrip(":")]


@pytest.mark.parametrize(("delta", "step"), [(0.01, 0.001), (0.05, 0.005), (0.1, 0.01)])
def test_the_step_of_delta_is_a_tenth_of_delta_so_the_estimate_holds(tmp_path, main_cli, delta, step):
    """The δ line's step was +0.01 whatever δ: all of a δ of 0.01, where the engine template's 74 kg wheel was
    said to change by -99.3 kg (a negative mass; 30.5 kg at 0.02). The step is a tenth of δ to one figure, and
    the estimate stays within an eighth of the exact change of this disc's closed-form mass (a mass as 1/δ moves
    by 1/1.1 − 1 = −9.1 % for a tenth, the first order by −10 %)."""
    import re

    a_max, v_max = 1600.0, 50.0
    path = tmp_path / "scene.toml"
    path.write_text(SCENE.format(delta=delta))

    def mass(d):  # the disc at its rim speed limit, in closed form (the module's docstring)
        return 2 * a_max * (1 + d / 2) ** 2 / (v_max**2 * d)

    status, out, _ = main_cli("solve", path)
    assert status == 0
    line = next(line for line in out.splitlines() if line.startswith("  - delta: "))
    assert line.startswith(f"  - delta: +{step:g} (e.g. {delta:g} to {delta + step:.3g})"), line
    shown = float(re.search(r"changes the mass by ([-+][\d.]+) kg", line).group(1))
    exact = mass(delta + step) - mass(delta)
    assert shown == pytest.approx(exact, rel=0.125) and mass(delta) + shown > 0
