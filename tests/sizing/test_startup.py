"""The run-up from rest (flyopt.sizing.startup): the Kloss run-up in closed form against quadrature and CVODES.

References: scipy's adaptive quadrature of t = J/(i² η) ∫ dω_m/M(ω_m) and of
φ = J/(η i³) ∫ ω_m dω_m/M(ω_m) from rest (the equation of motion J dω/dt = i η M(i ω)
rearranged, not the antiderivatives under test), and flyopt's CVODES run-up
(:func:`startup_time`, the equation of motion integrated in the angle).
"""

import math

import pytest
from scipy import integrate

from flyopt.analysis import analyse, startup_run
from flyopt.cycle.torque import MotorTorque
from flyopt.io.scene import load
from flyopt.machine.motor import InductionMotor
from flyopt.sizing.startup import kloss_runup_angle, kloss_runup_time, startup_time

MOTOR = InductionMotor(
    rated_power=4000.0, rated_speed=1440 * math.pi / 30, synchronous_speed=50 * math.pi, breakdown_ratio=2.8
)


@pytest.mark.parametrize(
    "inertia, ratio, eta, omega", [(300.0, 24.0, 0.92, 6.2), (12.0, 3.0, 1.0, 40.0), (5e3, 120.0, 0.85, 1.2)]
)
def test_kloss_runup_time_and_angle_against_quadrature(inertia, ratio, eta, omega):
    args = (inertia, ratio, eta, MOTOR.breakdown_torque, MOTOR.breakdown_slip, MOTOR.synchronous_speed, omega)

    def quad(f):
        return integrate.quad(f, 0, ratio * omega, epsabs=0, epsrel=1e-13, limit=400)[0]

    time = inertia / (ratio**2 * eta) * quad(lambda wm: 1 / float(MOTOR.torque(wm, "kloss")))
    angle = inertia / (eta * ratio**3) * quad(lambda wm: wm / float(MOTOR.torque(wm, "kloss")))
    assert kloss_runup_time(*args) == pytest.approx(time, rel=1e-11)
    assert kloss_runup_angle(*args) == pytest.approx(angle, rel=1e-11)


def test_a_constant_inertia_on_the_kloss_curve_runs_up_in_closed_form_as_cvodes_integrates_it():
    scene = load("problems/motor-press.toml")
    analysis = analyse(scene)
    machine = analysis.machine
    driving = machine.driving
    curve = MotorTorque(driving.motor, driving.speed_ratio, driving.efficiency, "kloss", driving.where)
    for j_flywheel in (analysis.j_required, 3 * analysis.j_required):
        closed = startup_run(machine, analysis.omega_mean, j_flywheel)
        assert closed.method.endswith("in closed form")
        cvodes = startup_time(
            lambda phi, omega: curve.casadi(phi, omega),
            machine.j_machine,
            machine.cycle_angle,
            analysis.omega_mean,
            j_flywheel,
        )
        # CVODES at rtol 1e-11, its first reach located between output points
        assert closed.time == pytest.approx(cvodes.time, rel=1e-8)
        assert closed.cycles == pytest.approx(cvodes.cycles, rel=1e-8)


def test_a_varying_inertia_is_still_integrated():
    scene = load("problems/motor-press.toml")
    analysis = analyse(scene)
    machine = analysis.machine
    import dataclasses

    varying = dataclasses.replace(
        machine, variable_inertia=True, j_machine=lambda phi: 0 * phi + float(machine.j_machine)
    )
    run = startup_run(varying, analysis.omega_mean, analysis.j_required)
    assert run is not None and not run.method.endswith("in closed form")


@pytest.mark.parametrize("target", [1.2566, 5.0, 20.0])
def test_a_constant_torque_runs_up_as_its_closed_form(target):
    # J dω/dt = M: t = J ω/M, φ = J ω²/(2 M); the first two reach the target within the first piece
    inertia, torque = 320.0, 1000.0
    run = startup_time(lambda phi, omega: torque + 0 * omega, inertia, 2 * math.pi, target, 0.0)
    assert run.time == pytest.approx(inertia * target / torque, rel=1e-8)
    assert run.angle == pytest.approx(inertia * target**2 / (2 * torque), rel=1e-8)


def test_a_run_up_ending_in_the_first_output_interval_is_timed_right():
    # press-drive's 5.5 kW motor at ratio 122 with no flywheel: its rotor alone (320 kg*m^2 at the crank)
    # runs up in 0.075 s, inside the first of the cycle's output intervals, where dt/dphi = 1/omega is
    # singular at rest; the time read from the cubic through that interval's ends was 5.9 s
    from flyopt.drive import codesign

    scene = load("problems/press-drive.toml")
    motor = next(m for m in scene.drive.motors.motors if m.name.startswith("132S"))
    machine = codesign.reduce(codesign.motor_scene(scene, motor, 122.36301477071807))
    driving = machine.driving
    curve = MotorTorque(driving.motor, driving.speed_ratio, driving.efficiency, "kloss", driving.where)
    args = (float(machine.j_machine), driving.speed_ratio, driving.efficiency)
    kloss = (driving.motor.breakdown_torque, driving.motor.breakdown_slip, driving.motor.synchronous_speed)
    run = startup_time(
        lambda phi, omega: curve.casadi(phi, omega), machine.j_machine, machine.cycle_angle, scene.omega_mean
    )
    assert run.time == pytest.approx(kloss_runup_time(*args, *kloss, scene.omega_mean), rel=1e-6)
    assert run.angle == pytest.approx(kloss_runup_angle(*args, *kloss, scene.omega_mean), rel=1e-6)
