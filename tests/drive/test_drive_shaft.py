"""The drive's flywheel shaft described as a part (docs/flywheel-design.md, sections 14 and 26).

The drive puts its wheel on the [[shaft]] named "flywheel" at the ratio it designs; every wheel its
search would choose passes the design's own shaft post-check at that ratio's running range. The
references are closed forms: the running range r n_m (1 -+ δ/2) of the ratio chosen, and the torque
the wheel exchanges with the shaft, T = (I r² / (J_c + I r²)) (M_d - M_r) / r, from the scene's
piecewise-constant punching torque (its extremes at 150 and 9000 N*m) and the motor's mean torque.
"""

import math
import re

import pytest
from conftest import PROBLEMS

from flyopt.drive import codesign
from flyopt.io.scene import load
from flyopt.pipeline import solve

SCENE = PROBLEMS / "punch-press-drive-shaft.toml"
RPM = math.pi / 30


@pytest.fixture(scope="module")
def solved():
    return solve(load(SCENE))


def test_the_described_flywheel_shaft_is_checked_at_the_ratio_the_drive_chose(solved):
    drive, best = solved.drive, solved.drive.best
    assert drive.status == "designed" and best.wheel is not None
    (report,) = solved.shaft_checks
    assert report.shaft == "flywheel" and report.check.holds
    r = best.flywheel_ratio
    # the running range of that ratio: the crank's mean speed held by the motor ratio (60 rpm), δ allowed 0.05
    low, high = report.check.speed_range_rpm
    assert low == pytest.approx(r * 60.0 * (1 - 0.025), rel=1e-6)
    assert high == pytest.approx(r * 60.0 * (1 + 0.025), rel=1e-6)
    # the torque through the shaft at that ratio: the net torque's extremes, the motor's mean torque M̄ at the
    # crank against the resisting 150 and 9000 N*m, shared by the wheel's J_F = I r² of J_c + J_F (J_c: the
    # motor's rotor J_rot i_m², the scene's machine giving none)
    scene = load(SCENE)
    load_torque = solved.analysis.driving_torque
    j_f = best.wheel.j_flywheel * r * r
    j_c = scene.j_constant + best.motor.rotor_inertia * best.motor_ratio**2
    share = j_f / (j_c + j_f) / r
    t_max, t_min = share * (load_torque - 150.0), share * (load_torque - 9000.0)
    assert report.check.torque_mean == pytest.approx((t_max + t_min) / 2, rel=1e-9)
    assert report.check.torque_alternating == pytest.approx((t_max - t_min) / 2, rel=1e-9)
    # the chosen scene carries the described shaft at the ratio chosen, for every output
    (shaft,) = [s for s in solved.scene.shafts if s.name == "flywheel"]
    assert shaft.speed_ratio == r and shaft.layout is not None
    assert solved.to_dict()["shaft_checks"][0]["shaft"] == "flywheel"


def _thin(d_body, d_journal):
    text = SCENE.read_text(encoding="utf-8")
    text = text.replace('diameter = "55 mm"', f'diameter = "{d_body} mm"')
    return text.replace('diameter = "50 mm"', f'diameter = "{d_journal} mm"')


@pytest.mark.slow  # 5 s: a second drive search; the drive's shaft post-check is tested by default above
def test_a_shaft_too_thin_for_the_chosen_wheel_moves_the_choice(tmp_path, solved):
    path = tmp_path / "thin.toml"
    path.write_text(_thin(34, 34), encoding="utf-8")
    scene = load(path)
    thin = codesign.design_drive(scene)
    assert thin.status == "designed"
    before = {r.motor.name: r for r in solved.drive.runs}
    after = {r.motor.name: r for r in thin.runs}
    chosen = solved.drive.best.motor.name
    # the wheel the described 55 mm shaft carried is refused on 34 mm, with the failed limits in numbers
    refused = after[chosen]
    assert before[chosen].feasible and not refused.feasible
    assert refused.reason.startswith("shaft: at ratio 8: ")
    assert (
        "the shaft cannot carry this" in refused.reason and "fatigue factor of safety at the keyseat" in refused.reason
    )
    assert refused.flywheel_ratio == 8.0 and refused.wheel is None
    # no ratio of 2-8 helps: the wheel and its torque only grow as r falls (J ∝ 1/r², T ∝ 1/r)
    assert thin.best.motor.name != chosen
    for run in thin.runs:  # every wheel chosen holds on its shaft; a drive without a wheel needs no check
        if run.feasible and run.wheel is not None:
            assert run.shaft_checks and run.shaft_checks[0].check.holds
    assert thin.best.objective > solved.drive.best.objective


@pytest.mark.parametrize("described", [True, False])
@pytest.mark.parametrize(
    ("extra", "field"),
    [
        ("speed_ratio = 6.0\n", "shaft[1].speed_ratio"),
        ('inertia = "1.5 kg*m^2"\n', "shaft[1].inertia"),
        ("efficiency = 0.95\n", "shaft[1].efficiency"),
    ],
)
def test_the_drive_designs_its_flywheel_shafts_ratio(main_cli, tmp_path, extra, field, described):
    """The drive's flywheel shaft gives no ratio (the drive designs it), nor what would move with it: one line,
    exit 2."""
    text = SCENE.read_text(encoding="utf-8").replace('name = "flywheel"', 'name = "flywheel"\n' + extra.rstrip())
    if not described:  # a plain [[shaft]] of that name is the drive's shaft all the same (not a second one)
        text = re.sub(r"(?m)^segments = .*$", "", text)
    path = tmp_path / "given.toml"
    path.write_text(text, encoding="utf-8")
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and field in err and "[drive] designs" in err and "Traceback" not in err


def test_a_flywheel_shaft_beside_a_drive_is_described(main_cli, tmp_path):
    """Without segments, the drive's flywheel shaft says what it lacks, not "speed_ratio is missing"."""
    text = re.sub(r"(?m)^segments = .*$", "", SCENE.read_text(encoding="utf-8"))
    path = tmp_path / "plain.toml"
    path.write_text(text, encoding="utf-8")
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "shaft[1].segments: is missing" in err and "speed_ratio" not in err


def _flywheel_problem():
    """shear-press's flywheel problem (a bare rim by the closed form: quick) for the drive's wheel search."""
    from flyopt.analysis import analyse
    from flyopt.design import design_inputs

    scene = load(PROBLEMS / "shear-press.toml")
    analysis, inputs = analyse(scene), design_inputs(scene)
    return analysis.j_required, analysis.omega_max, inputs.materials, inputs.spec


@pytest.mark.parametrize("refused_from", [1.25, 1.5, 0.1])
def test_a_refused_winner_sends_the_search_to_the_best_checked_ratio(refused_from):
    """The wheel search checks only its winner; where the shaft refuses it, the search runs again with every
    design checked. Against a brute force over the same ratios, each design checked: the same ratio and mass,
    and where every ratio is refused, no wheel (the refusal's reasons in its candidates)."""
    from flyopt.design.designer import design_flywheel
    from flyopt.design.spec import MountShaft
    from flyopt.names import Objective

    j_need, omega_max, materials, spec = _flywheel_problem()
    ratios = (0.5, 1.0, 1.25, 1.5, 2.0)  # unchecked, 1.25 wins (12.4 kg; 12.8 kg at 1.0, 13.2 kg at 1.5)

    def accept_at(r):
        return lambda candidate: f"refused by the test at ratio {r:g}" if r >= refused_from else None

    found, r_found = codesign._best_wheel(
        j_need, omega_max, ("fixed", *ratios), materials, spec, None, Objective.MASS, None, accept_at=accept_at
    )
    brute = []
    for r in ratios:
        best = design_flywheel(
            j_need, omega_max, [MountShaft(codesign.FLYWHEEL_SHAFT, r, None)], materials, spec, accept=accept_at(r)
        ).best
        if best is not None:
            brute.append((best.mass, r))
    unchecked = [
        design_flywheel(j_need, omega_max, [MountShaft(codesign.FLYWHEEL_SHAFT, r, None)], materials, spec).best
        for r in ratios
    ]
    assert min(zip(ratios, unchecked), key=lambda pair: pair[1].mass)[0] == 1.25  # so 1.25 refuses the winner
    if not brute:
        assert found is not None and found.best is None
        assert all("refused by the test" in c.reason for c in found.candidates if not c.feasible)
        return
    mass, r_best = min(brute)
    assert r_found == r_best and found.best.mass == pytest.approx(mass, rel=1e-12)
