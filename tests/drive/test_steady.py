"""A motor's steady running by Newton on the compiled shooting (flyopt.drive.steady).

The references are independent of the compiled path: the CVODES search of the
same motor (flyopt.drive.codesign's fallback, adaptive BDF at rtol 1e-11 with
its own secant on the ratio and roots for the flywheel), CVODES's periodic
solution at the ratio and flywheel found, and central differences of the
residuals for the Newton Jacobian.
"""

import dataclasses
import math

import numpy as np
import pytest
from conftest import ROOT

from flyopt.analysis import analyse
from flyopt.design import design_inputs
from flyopt.drive import codesign, steady
from flyopt.io.scene import load
from flyopt.machine.motor import InductionMotor
from flyopt.sizing.periodic import periodic_solution


@pytest.fixture(scope="module")
def press():
    scene = load("problems/press-drive.toml")
    analysis = analyse(scene)
    motors = {m.name: m for m in scene.drive.motors.motors}
    return scene, analysis, motors, codesign.drive_model(scene, analysis, scene.drive.motors.motors[0])


@pytest.mark.parametrize(
    # the smallest motor's CVODES search is the longest (7 s): the slow run; the two others in the default run
    "name",
    [pytest.param("112M-4 4 kW", marks=pytest.mark.slow), "132S-4 5.5 kW", "132MA-4 7.5 kW"],
)
def test_each_motor_as_the_cvodes_search_finds_it(press, name):
    # the three sizes press-drive solves: one held by the thermal limit (a flywheel), two by none
    scene, analysis, motors, model = press
    inputs = design_inputs(scene)
    args = (scene, motors[name], analysis.driving_torque, scene.drive, scene.drive.ratio_choice())
    fast = codesign.evaluate_motor(*args, inputs.materials, inputs.spec, drive_model=model)
    slow = codesign.evaluate_motor(*args, inputs.materials, inputs.spec)
    assert fast.feasible and slow.feasible and fast.limit == slow.limit
    # the CVODES search holds the mean speed to 1e-7 (SPEED_RTOL) and the flywheel to 1e-6 (SETTLE_RTOL);
    # the compiled solve holds them to 1e-12 and 1e-10, so the two agree to the search's tolerances
    assert fast.omega_mean == pytest.approx(scene.omega_mean, rel=1e-11)
    assert fast.motor_ratio == pytest.approx(slow.motor_ratio, rel=2e-7)
    assert fast.j_flywheel == pytest.approx(slow.j_flywheel, rel=2e-6, abs=1e-9)
    assert fast.rms_torque == pytest.approx(slow.rms_torque, rel=2e-6)
    assert fast.startup_time == pytest.approx(slow.startup_time, rel=1e-5)
    assert fast.total_mass == pytest.approx(slow.total_mass, rel=1e-5)


def test_the_solution_is_cvodes_periodic_solution(press):
    # the thermal-limited size: CVODES at the ratio and flywheel found gives the same speeds and RMS torque
    scene, analysis, motors, model = press
    motor = motors["112M-4 4 kW"]
    ratio = codesign.motor_ratio_estimate(motor, analysis.driving_torque, scene.omega_mean, scene.efficiency)
    found, _ = codesign._settle_compiled(model, motor, ratio, True, {})
    machine = codesign.reduce(codesign.motor_scene(scene, motor, found.ratio))
    sol = periodic_solution(
        machine.net_torque(),
        machine.j_machine,
        machine.cycle_angle,
        scene.omega_mean,
        found.j_flywheel,
        machine.knots(),
    )
    assert sol.omega_mean == pytest.approx(found.omega_mean, rel=1e-9)
    assert sol.delta == pytest.approx(found.delta, rel=1e-8)
    assert codesign.rms_torque(sol, motor.motor(), found.ratio)[0] == pytest.approx(found.rms_torque, rel=1e-8)
    assert found.rms_torque == pytest.approx(motor.rated_torque, rel=1e-9)


@pytest.mark.parametrize("limit", ["delta", "thermal"])
def test_newton_jacobian_against_central_differences(press, limit):
    scene, analysis, motors, model = press
    motor = motors["112M-4 4 kW"]
    newton = steady._Newton(model, motor, limit, None)
    full = np.array([math.log(scene.omega_mean), math.log(newton.j_s + 1e5), math.log(118.0)])
    point = newton.state(full, 2, True)
    assert point is not None
    numeric = np.zeros((3, 3))
    for column in range(3):
        h = 1e-6
        up, down = full.copy(), full.copy()
        up[column] += h
        down[column] -= h
        numeric[:, column] = (newton.state(up, 2, False).residuals() - newton.state(down, 2, False).residuals()) / (
            2 * h
        )
    # the extremes' derivatives are taken at their grid points (the envelope theorem): exact where the
    # extreme is a smooth maximum, off by the grid's spacing otherwise
    np.testing.assert_allclose(point.jacobian(), numeric, rtol=1e-5, atol=1e-8)


def test_a_motor_whose_mean_torque_exceeds_its_rating_is_refused_in_words(press):
    scene, analysis, motors, model = press
    motor = motors["100LA-4 2.2 kW"]
    with pytest.raises(steady.Unreachable, match="mean torque .* exceeds its rated torque"):
        model.steady(motor, "thermal", (math.log(scene.omega_mean), math.log(1e5), math.log(115.0)))


def test_kloss_curve_is_one_formula():
    # the Kloss curve through the rated point at M_b/M_n = k: M(ω_n) = M_n, M(ω_b) = M_b (its maximum)
    motor = InductionMotor(rated_power=5500.0, rated_speed=150.0, synchronous_speed=157.0796, breakdown_ratio=2.5)
    assert motor.torque(150.0, "kloss") == pytest.approx(motor.rated_torque, rel=1e-12)
    assert motor.torque(motor.breakdown_speed, "kloss") == pytest.approx(2.5 * motor.rated_torque, rel=1e-12)


def test_verifying_a_run_against_a_scene_without_a_drive_is_refused_in_words(press):
    scene, analysis, motors, model = press
    run = codesign.MotorRun(motor=motors["132S-4 5.5 kW"], feasible=True, motor_ratio=122.0, j_flywheel=0.0)
    with pytest.raises(ValueError, match=r"no \[drive\]"):
        codesign.verify_drive(dataclasses.replace(scene, drive=None), run)


def test_the_chosen_motor_without_a_flywheel_is_analysed_without_the_one_solve(press, monkeypatch):
    # a motor whose slip alone holds δ: asked first (slip_first, as flyopt.pipeline.solve_drive does for a
    # chosen motor the search found to need no flywheel), the requirement is the one the default path finds
    # after its one Newton solve gives up (CVODES's periodic solution with none), and the one solve never runs
    from flyopt.sizing import periodic

    scene, analysis, motors, model = press
    motor = motors["132S-4 5.5 kW"]
    ratio = codesign.motor_ratio_estimate(motor, analysis.driving_torque, scene.omega_mean, scene.efficiency)
    machine = codesign.reduce(codesign.motor_scene(scene, motor, ratio))
    args = (machine.net_torque(), machine.j_machine, machine.cycle_angle, scene.omega_mean, scene.delta)
    with monkeypatch.context() as patch:

        def refused(*_):
            raise AssertionError("the one solve ran")

        patch.setattr(periodic, "_one_solve", refused)
        first = periodic.dynamic_requirement(*args, machine.knots(), slip_first=True)
    before = periodic.BUILDS["fallback to the CVODES search"]
    default = periodic.dynamic_requirement(*args, machine.knots())
    assert periodic.BUILDS["fallback to the CVODES search"] == before + 1  # the one solve gave up there
    assert first.limit == default.limit == "none"
    assert first.j_required == default.j_required == -float(machine.j_machine)
    assert first.solution.delta == default.solution.delta < scene.delta
    assert first.solution.omega_mean == default.solution.omega_mean


def test_the_delta_of_a_flywheel_on_the_chosen_drive_is_cvodes(press, monkeypatch):
    # the analysis' comparison of the models asks the chosen drive for the δ of the energy model's flywheel:
    # by the compiled model the search solved, it is CVODES's periodic solution of the chosen machine (rtol
    # 1e-11) to the steps' check (1e-9); where the compiled model does not settle, it is CVODES's own
    import json

    from flyopt.sizing.shooting import NotSettled

    scene, analysis, motors, model = press
    golden = json.loads((ROOT / "tests" / "data" / "golden" / "press-drive.json").read_text(encoding="utf-8"))
    motor, ratio = motors["132S-4 5.5 kW"], golden["drive"]["best"]["motor_ratio"]
    run = codesign.MotorRun(motor=motor, feasible=True, motor_ratio=ratio, j_flywheel=0.0)
    drive = codesign.DriveDesign("designed", "mass", run, (run,), model=model)
    machine = codesign.reduce(codesign.chosen_scene(scene, run))
    delta = codesign.flywheel_delta(drive, machine)
    j = 48123.77499097989  # the energy model's flywheel for it
    reference = periodic_solution(
        machine.net_torque(), machine.j_machine, machine.cycle_angle, scene.omega_mean, j, machine.knots()
    ).delta
    assert delta(j) == pytest.approx(reference, rel=1e-9)
    assert delta(j) != reference  # two methods, not one
    with monkeypatch.context() as patch:

        def unsettled(*_):
            raise NotSettled("the steps do not settle")

        patch.setattr(model, "with_flywheel", unsettled)
        assert delta(j) == reference
    assert codesign.flywheel_delta(dataclasses.replace(drive, model=None), machine) is None


def test_an_unreachable_limit_pickles_with_its_sentence_and_limit():
    """A worker process may raise it: its sentence (with its quantities) and its limit come back whole."""
    import pickle

    from flyopt.said import said

    sentence = said("its mean torque {t} exceeds its rated torque", t=(28.2, "torque", "28.2 N·m"))
    back = pickle.loads(pickle.dumps(steady.Unreachable(sentence, "thermal")))
    assert (str(back), back.limit, back.args[0].values) == (sentence, "thermal", sentence.values)
