"""Failure paths of the sizing models: no hang, no flood of diagnostics, no silently wrong answer
(issue 11, item 6).

Each scene runs through the command line in a subprocess with a timeout, because each of them
once hung or ran for minutes. References are independent of flyopt: the physics of a torque that
does not vary with the angle (nothing fluctuates), a straight motor line solved by hand, and a
scipy integration of the equation of motion.
"""

import json
import math
import subprocess
import sys
import time

import casadi as ca
import numpy as np
import pytest
from conftest import PROBLEMS, ROOT
from numpy.testing import assert_allclose
from scipy import integrate, optimize

from flyopt.errors import SceneError
from flyopt.sizing import periodic

RPM = 2 * math.pi / 60


def flyopt_cli(*args, timeout=60):
    """Run ``python -m flyopt ARGS``; a hang fails the test (subprocess.TimeoutExpired)."""
    return subprocess.run(
        [sys.executable, "-m", "flyopt", *map(str, args)], capture_output=True, text=True, cwd=ROOT, timeout=timeout
    )


def speed_load(expression, driving='constant = "unknown"', inertia=None):
    """A scene at 1500 rpm, δ = 0.02: a resisting expression against ``driving``; J_c = 0 unless given."""
    return f"""
title = "a load that depends on speed"
[machine]
speed = "1500 rpm"
delta = 0.02
{f'inertia = "{inertia}"' if inertia else ""}
[torque.resisting]
expression = "{expression}"
unit = "N*m"
[torque.driving]
{driving}
"""


# -- a steady machine: the torques do not vary with the angle -----------------------------------


def test_conveyor_by_the_dynamic_model_is_steady_not_non_periodic():
    """Worked example 4 has steady torques (1375 N*m against the unknown constant that balances
    it): nothing fluctuates, so the dynamic model needs no flywheel either. It used to call the
    machine non-periodic against a "cycle work" of 1.4e-12 J, the work of the torques' round-off
    difference; the work of the torques is 1375 N*m x 2 pi = 8639 J."""
    run = flyopt_cli("solve", PROBLEMS / "conveyor.toml", "--model", "dynamic", "--json")
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    assert out["model"] == "dynamic" and out["flywheel_needed"] is False
    assert out["j_required"] == 0.0
    assert out["omega_max"] == out["omega_min"] == out["omega_mean"] == 4.8


def test_conveyor_verifies_with_no_inertia_at_all():
    """The conveyor needs no flywheel and its scene gives J_c = 0: with no fluctuation the speed
    is constant whatever the inertia, so the achieved delta is 0 (it used to end in a traceback)."""
    run = flyopt_cli("solve", PROBLEMS / "conveyor.toml", "--verify", "--json")
    assert run.returncode == 0, run.stderr
    check = json.loads(run.stdout)["verification"]
    assert check["achieved_delta"] == 0.0 and check["flagged"] is False
    assert "no fluctuation" in check["method"]
    assert check["omega_mean"] == 4.8


def test_a_fluctuating_torque_with_no_inertia_is_refused_with_the_field():
    """With J = 0 a torque that varies with the angle would make the speed jump: δ is undefined."""
    with pytest.raises(SceneError, match="machine.inertia: .*no inertia"):
        periodic.verify(lambda phi, omega: 100 * ca.sin(phi), 0.0, 2 * math.pi, 10.0, 0.05, 0.0)


@pytest.mark.parametrize("expression", ["100 + 0.1*omega", "1000/omega"])
def test_a_load_of_speed_alone_against_an_unknown_constant_needs_no_flywheel(write_scene, expression):
    """Neither torque varies with the angle, so nothing fluctuates: A_max = 0, no flywheel (the
    machine's J_c = 0 suffices), the speed is the scene's. It used to hang, or fail after 68,968
    lines of CasADi output."""
    run = flyopt_cli("solve", write_scene(speed_load(expression)), "--json", "--verify")
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    out = json.loads(run.stdout)
    assert out["flywheel_needed"] is False
    assert abs(out["a_max"]) <= 1e-12 * out["work_per_cycle"]  # the indicator's A_max: zero up to round-off
    assert out["omega_max"] == out["omega_min"] == out["omega_mean"] == pytest.approx(1500 * RPM, rel=1e-15)
    assert out["verification"]["achieved_delta"] == 0.0


@pytest.mark.parametrize("command", ["check", "tradeoff"])
def test_check_and_tradeoff_of_a_load_of_speed_alone_answer_at_once(write_scene, command):
    run = flyopt_cli(command, write_scene(speed_load("1000/omega")))
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""


# -- a load whose speed term averages to zero: the mean speed is the scene's ---------------------


def test_a_balancing_constant_holds_the_scene_speed(write_scene):
    """200 + 50 sin(φ) ω/157 against an unknown constant: the ω-term averages to zero, so the
    torque-speed balance cannot set the mean speed (it was silently replaced by 7e-5 rad/s);
    the unknown constant is what holds the scene's 1500 rpm."""
    scene = write_scene(speed_load("200 + 50*sin(phi)*omega/157", inertia="1 kg*m^2"))
    run = flyopt_cli("solve", scene, "--json", "--verify")
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    out = json.loads(run.stdout)
    assert out["model"] == "dynamic"
    assert_allclose(out["omega_mean"], 1500 * RPM, rtol=1e-12)
    assert_allclose(out["verification"]["omega_mean"], 1500 * RPM, rtol=1e-12)
    assert out["omega_min"] < out["omega_mean"] < out["omega_max"]


DC_MOTOR = 'motor = { kind = "dc", rated_power = "40 kW", rated_speed = "1500 rpm", no_load_speed = "1600 rpm" }'
INDUCTION_MOTOR = (
    'motor = { kind = "induction", rated_power = "40 kW", rated_speed = "1440 rpm", synchronous_speed = "1500 rpm" }'
)


@pytest.mark.parametrize(
    "motor, rated, no_load", [(DC_MOTOR, 1500, 1600), (INDUCTION_MOTOR, 1440, 1500)], ids=["dc", "induction"]
)
def test_a_motor_sets_the_mean_speed_by_its_line(write_scene, motor, rated, no_load):
    """The same load driven by a motor: the motor's straight line, M_n (ω_0 − ω)/(ω_0 − ω_n),
    sets the mean speed where it meets the mean load, 200 N*m (the sin φ ω term adds only a
    correlation of order δ² to the mean load). The induction motor is stiff enough to keep δ
    with the machine's own inertia: no flywheel (it used to fail on a total inertia of 0)."""
    run = flyopt_cli("solve", write_scene(speed_load("200 + 50*sin(phi)*omega/157", motor, "1 kg*m^2")), "--json")
    assert run.returncode == 0, run.stderr
    w_rated, w_0 = rated * RPM, no_load * RPM
    omega = w_0 - 200 * (w_0 - w_rated) / (40e3 / w_rated)
    out = json.loads(run.stdout)
    assert_allclose(out["omega_mean"], omega, rtol=1e-4)
    assert out["omega_min"] < out["omega_mean"] < out["omega_max"]


# -- a motor far too weak: refused at once -----------------------------------------------------


def test_a_motor_far_too_weak_is_refused_at_once(write_scene):
    """0.1 kW against the punch press's load (mean 741.7 N*m on the crankshaft): the largest
    torque the motor has, its breakdown torque 2.5 M_n times i = 24, is 39.79 N*m. No steady
    running exists; the scene is refused before any periodic solution (it ran past 10 s)."""
    text = (PROBLEMS / "motor-press.toml").read_text().replace('rated_power = "5.5 kW"', 'rated_power = "0.1 kW"')
    start = time.perf_counter()
    run = flyopt_cli("solve", write_scene(text), timeout=60)
    assert time.perf_counter() - start < 20
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1, run.stderr
    breakdown = 2.5 * 100.0 / (1440 * RPM) * 24 * 0.9215
    assert "torque.driving: the motor's largest torque on the reference shaft" in lines[0]
    assert f"{breakdown:.6g} N*m (breakdown)" in lines[0]
    assert "mean load 741.667 N*m: no steady running" in lines[0]


# -- members whose inertia varies, a load of speed, an unknown constant ----------------------------


SLIDER_CRANK = """
title = "a ram on a slider-crank, a load of speed"
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
[torque.driving]
constant = "unknown"
[torque.resisting]
expression = "100 + 0.1*omega"
unit = "N*m"
"""


def _scipy_delta(j_total, omega_mean):
    """δ of the periodic steady state at mean speed ω_m, by scipy alone.

    J(φ) = j_total + m (dx/dφ)², x = r cos φ + sqrt(l² − r² sin² φ) (textbook slider-crank);
    dE/dφ = c − (100 + 0.1 ω), ω = sqrt(2E/J). For E(0) the constant c making the cycle periodic
    (Brent), and E(0) such that (ω_max + ω_min)/2 = ω_m (Brent); extremes on a fine grid.
    """
    r, length, mass = 0.08, 0.45, 400.0
    grid = np.linspace(0.0, 2 * math.pi, 20001)

    def inertia(phi):
        s = np.sin(phi)
        dx = -r * s - r * r * s * np.cos(phi) / np.sqrt(length**2 - (r * s) ** 2)
        return j_total + mass * dx**2

    def run(e0, c):
        def rhs(phi, e):
            return [c - (100 + 0.1 * np.sqrt(2 * e[0] / inertia(phi)))]

        sol = integrate.solve_ivp(
            rhs, (0.0, 2 * math.pi), [e0], method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True
        )
        return sol

    def periodic_c(e0):
        c0 = 100 + 0.1 * math.sqrt(2 * e0 / inertia(0.0))
        return optimize.brentq(lambda c: run(e0, c).y[0, -1] - e0, c0 - 5, c0 + 5, xtol=1e-13)

    def speeds(e0):
        e = run(e0, periodic_c(e0)).sol(grid)[0]
        return np.sqrt(2 * e / inertia(grid))

    e_guess = 0.5 * inertia(0.0) * omega_mean**2
    e0 = optimize.brentq(
        lambda e: 0.5 * (speeds(e).max() + speeds(e).min()) - omega_mean, 0.8 * e_guess, 1.25 * e_guess, xtol=1e-12
    )
    w = speeds(e0)
    return (w.max() - w.min()) / omega_mean


@pytest.mark.slow  # 6 s; the periodic model of a speed-dependent load runs by default on motor-press and press-drive
def test_members_with_a_load_of_speed_are_sized_by_the_periodic_model(write_scene):
    """It used to fail with "bracket J_F in [2.8e+49, inf]": the energy scale of the shooting was
    Φ max|M|, the round-off of a balanced net torque, while the varying inertia trades
    ½ ΔJ ω² of energy. The flywheel found keeps δ = 0.15 by an independent scipy solution. (~5 s)"""
    run = flyopt_cli("solve", write_scene(SLIDER_CRANK), "--json", timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    out = json.loads(run.stdout)
    assert out["model"] == "dynamic" and out["flywheel_needed"] is True
    assert_allclose(out["omega_mean"], 120 * RPM, rtol=1e-12)
    assert_allclose(_scipy_delta(2.0 + out["j_required"], 120 * RPM), 0.15, rtol=1e-6)


def test_a_singular_balance_is_a_named_solver_failure(write_scene, monkeypatch):
    """An outside audit's speed-stiff load (1000 + 500 sin φ + 1e3 (ω − 62.83)) ended in numpy's own words,
    "Singular matrix", exit 1: the balance's Broyden step could not be solved. It is a SolverFailed that says
    what was being solved. The Jacobian is made singular here for any load (the audit's case is not singular on
    every host, and no longer reaches the balance: its machine has no inertia and its torques' balance holds δ),
    so that the path is taken each time; the balance is asked for the flywheel the requirement starts from.
    It was the whole requirement, whose search now ends at a flywheel large enough for the balance to hold at
    its first trial, with no step to take."""
    import flyopt
    from flyopt.errors import SolverFailed
    from flyopt.machine.reduce import reduce

    machine = reduce(flyopt.load(write_scene(speed_load("1000 + 500*sin(phi) + 10*(omega - 157.08)"))))

    def singular(a, b):
        raise np.linalg.LinAlgError("Singular matrix")

    monkeypatch.setattr(periodic.np.linalg, "solve", singular)
    with pytest.raises(SolverFailed, match=r"balance's Jacobian became singular after \d+ iterations"):
        periodic.periodic_solution(
            machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.omega_mean, 1.0, machine.knots()
        )
