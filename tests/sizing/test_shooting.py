"""Tests of flyopt.sizing.shooting: the dynamic model's flywheel in one Newton solve.

References, each independent of the one-solve:
- the CVODES search (BDF at rtol 1e-11 with a Newton iteration per trial flywheel), which
  stays the verifier: J_F, the achieved δ and the speed extremes must agree to 1e-8;
- Wittenbauer's energy–mass closed form (flyopt.sizing.energy_mass) on angle-only
  variable-inertia machines, exact up to quadrature round-off: J_F to 1e-9.
A case the one-solve cannot settle must fall back on the CVODES search, never return.
"""

import math

import numpy as np
import pytest
from conftest import PROBLEMS
from numpy.testing import assert_allclose
from test_periodic import HARD_CASES, N_COMPRESSOR, TWO_PI, compressor, press
from test_sizing_failures import speed_load

import flyopt
from flyopt.errors import NonPeriodicCycle, SolverFailed
from flyopt.machine.motor import DCMotor
from flyopt.machine.reduce import reduce
from flyopt.sizing import energy_mass, periodic, periodic_model, shooting


def requirement_args(machine):
    """The arguments of periodic.dynamic_requirement for a reduced scene."""
    return (
        machine.net_torque(),
        machine.j_machine,
        machine.cycle_angle,
        machine.omega_mean,
        machine.delta,
        machine.knots(),
    )


def by_cvodes(monkeypatch, args):
    """The requirement by the CVODES search alone (the one-solve made to give up)."""
    with monkeypatch.context() as patch:
        patch.setattr(
            shooting,
            "required_flywheel",
            lambda *a, **k: (_ for _ in ()).throw(shooting.NotSettled("test: CVODES only")),
        )
        return periodic.dynamic_requirement(*args)


def one_solve(args):
    periodic.BUILDS.pop("fallback to the CVODES search", None)
    result = periodic.dynamic_requirement(*args)
    fell_back = periodic.BUILDS.pop("fallback to the CVODES search", 0) > 0
    assert fell_back or "one Newton solve" in result.solution.status
    return result, fell_back


def assert_agree(fast, reference, rtol=1e-8):
    a, b = fast.solution, reference.solution
    assert_allclose(fast.j_required, reference.j_required, rtol=rtol)
    for name in ("delta", "omega_max", "omega_min", "omega_mean"):
        assert_allclose(getattr(a, name), getattr(b, name), rtol=rtol, err_msg=name)
    assert a.periodicity_residual <= a.periodicity_tolerance


@pytest.mark.parametrize("label, rpm, slip, delta", HARD_CASES, ids=[c[0] for c in HARD_CASES])
def test_hard_cases_agree_with_cvodes(monkeypatch, label, rpm, slip, delta):
    """2 % working stroke with a 50× spike, δ 1e-4 and 0.3, 0.5 % slip, 1 and 20,000 rpm:
    J_F, δ and the speed extremes as the CVODES search gives them, to 1e-8."""
    net, load, _, omega_n = press(rpm, slip)
    args = (net, 0.0, TWO_PI, omega_n, delta, load.breakpoints())
    fast, fell_back = one_solve(args)
    assert not fell_back
    assert_agree(fast, by_cvodes(monkeypatch, args))
    assert_allclose(fast.solution.delta, delta, rtol=1e-9)
    assert 0 <= fast.solution.multiplier < 1


def test_motor_press_agrees_with_cvodes(monkeypatch):
    machine = reduce(flyopt.load(PROBLEMS / "motor-press.toml"))
    args = requirement_args(machine)
    fast, fell_back = one_solve(args)
    assert not fell_back
    assert_agree(fast, by_cvodes(monkeypatch, args))


@pytest.mark.slow  # 3 s: a CVODES run; the shooting is held to CVODES by default on constant inertia
def test_variable_inertia_with_a_motor_agrees_with_cvodes(monkeypatch, write_scene):
    """The slider-crank press (J_e(φ) from a 400 kg ram) driven by an induction motor: both
    exact models at once."""
    text = (
        (PROBLEMS / "slider-crank-press.toml")
        .read_text()
        .replace(
            'constant = "unknown"',
            'motor = { kind = "induction", rated_power = "4 kW", rated_speed = "1440 rpm", '
            'synchronous_speed = "1500 rpm", shaft = "motor" }',
        )
    )
    machine = reduce(flyopt.load(write_scene(text)))
    assert machine.speed_dependent and machine.variable_inertia
    args = requirement_args(machine)
    fast, fell_back = one_solve(args)
    assert not fell_back
    assert_agree(fast, by_cvodes(monkeypatch, args))


def test_balancing_constant_agrees_with_cvodes(monkeypatch, write_scene):
    """A load that depends on speed against an unknown constant torque: the constant's
    correction and the mean speed are unknowns of the same solve."""
    machine = reduce(flyopt.load(write_scene(speed_load("200 + 50*sin(phi)*omega/157", inertia="1 kg*m^2"))))
    args = requirement_args(machine)
    fast, fell_back = one_solve(args)
    assert not fell_back and periodic_model.periodic_model(*args[:3], args[5]).balanced
    reference = by_cvodes(monkeypatch, args)
    assert_agree(fast, reference)
    assert_allclose(fast.solution.omega_mean, machine.omega_mean, rtol=1e-12)
    assert_allclose(fast.solution.torque_offset, reference.solution.torque_offset, atol=1e-8 * 200)


@pytest.mark.parametrize("delta", [0.01, 0.05, 0.2])
def test_angle_only_variable_inertia_matches_the_energy_mass_closed_form(delta):
    """The compressor (J_e(φ) of a slider-crank, a tabulated indicator torque): the one-solve's
    flywheel is Wittenbauer's closed form's, to 1e-9."""
    excess, j_e = compressor()
    exact = energy_mass.energy_mass_requirement(excess, j_e, N_COMPRESSOR, delta)
    fast, fell_back = one_solve((periodic.angle_torque(excess), j_e, TWO_PI, N_COMPRESSOR, delta, excess.knots))
    assert not fell_back
    assert_allclose(fast.j_required, exact.j_required, rtol=1e-9)
    assert_allclose([fast.solution.omega_max, fast.solution.omega_min], [exact.omega_max, exact.omega_min], rtol=1e-9)


def test_slider_crank_press_matches_the_energy_mass_closed_form():
    machine = reduce(flyopt.load(PROBLEMS / "slider-crank-press.toml"))
    exact = energy_mass.energy_mass_requirement(
        machine.angle_only(), machine.j_machine, machine.omega_mean, machine.delta
    )
    fast, fell_back = one_solve(requirement_args(machine))
    assert not fell_back
    assert_allclose(fast.j_required, exact.j_required, rtol=1e-9)


def test_a_motor_too_weak_is_not_settled_and_the_search_says_why():
    """A DC motor whose stall torque is half the mean load: the one-solve gives up (it never
    returns a speed that is not a steady state), and the CVODES search says the drive falls short.

    Its first trial stalls, and the drive's best work over the cycle (the largest torque of any speed at each
    angle, a bound from above) is then weighed against the load's. The DC line's largest torque is its stall
    torque, at rest: the drive gives at most 2π × 50 J a turn against the spike's 5000 N·m over 0.02 of a turn,
    so it falls 2π (100 − 50) J short, which the bound may understate by its margin between grid speeds but
    never overstate. (It used to end, some 20 s later, in "down to a stall": CVODES was allowed 200,000 steps
    a piece, and ground through trials that stall.)"""
    import re

    _, load, _, omega_n = press(1500, 0.04)
    motor = DCMotor(omega_n * 1.05, 50.0)

    def net(phi, omega):
        return motor.torque(omega) - load.casadi(phi)

    model = periodic_model.periodic_model(net, 0.0, TWO_PI, load.breakpoints())
    with pytest.raises(shooting.NotSettled):
        shooting.required_flywheel(model, 0.05, omega_n, 1.0)
    with pytest.raises(SolverFailed, match="a stronger drive is needed") as info:
        periodic.dynamic_requirement(net, 0.0, TWO_PI, omega_n, 0.05, load.breakpoints())
    short = float(re.search(r"the drive falls ([0-9.]+) J short", str(info.value)).group(1))
    exact = TWO_PI * (5000.0 * 0.02 - 50.0)  # the load's work less the stall torque's over the turn
    assert 0.97 * exact <= short <= exact * (1 + 5e-4)  # printed to 4 figures


def test_unbalanced_angle_only_torques_are_not_periodic():
    """1 N·m net over the turn: the one-solve cannot make it periodic and hands over; the
    search raises NonPeriodicCycle with the imbalance."""
    import casadi as ca

    def net(phi, omega):
        return 1.0 + 5 * ca.sin(phi)

    with pytest.raises(NonPeriodicCycle):
        periodic.dynamic_requirement(net, 1.0, TWO_PI, 10.0, 0.05)


def test_fixed_steps_are_refined_until_halving_them_changes_nothing(monkeypatch):
    """With the grid made coarse (a quarter of the outputs), one step per interval no longer
    holds 1e-11: the solve refines its steps and still agrees with CVODES."""
    net, load, _, omega_n = press(1500, 0.04)
    args = (net, 0.0, TWO_PI, omega_n, 0.05, load.breakpoints())
    monkeypatch.setattr(periodic_model, "OUTPUTS_PER_PIECE", 16)
    periodic_model._MODELS.clear()
    seen = []
    original = shooting._State

    def recording(solve, x, substeps, derivatives):
        seen.append(substeps)
        return original(solve, x, substeps, derivatives)

    monkeypatch.setattr(shooting, "_State", recording)
    fast, fell_back = one_solve(args)
    monkeypatch.setattr(shooting, "_State", original)
    assert not fell_back and max(seen) >= 2
    reference = by_cvodes(monkeypatch, args)
    periodic_model._MODELS.clear()
    assert math.isclose(fast.j_required, reference.j_required, rel_tol=1e-8)


def test_buffered_call_equals_casadis_own_call_for_matrices():
    """_numerics.call (CasADi buffers into numpy) against CasADi's ordinary call, on inputs and
    outputs that are not square, so a row/column mix-up cannot pass."""
    import casadi as ca
    import numpy as np

    from flyopt.sizing._numerics import call, evaluate

    a, b = ca.SX.sym("a", 2, 3), ca.SX.sym("b", 3)
    f = ca.Function("f", [a, b], [ca.mtimes(a, b), ca.sin(a).T, ca.sum1(a) * 2])
    rng = np.random.default_rng(1)
    a0, b0 = rng.normal(size=(2, 3)), rng.normal(size=3)
    got = call(f, a0, b0)
    want = [np.asarray(o, dtype=float) for o in f(a0, b0)]
    assert got[0].shape == (2,) and got[1].shape == (3, 2) and got[2].shape == (1, 3)
    assert_allclose(got[0], want[0].ravel(), rtol=0, atol=0)
    assert_allclose(got[1], want[1], rtol=0, atol=0)
    assert_allclose(got[2], want[2], rtol=0, atol=0)
    with pytest.raises(ValueError, match="input 1 has 2 numbers, 3 expected"):
        call(f, a0, b0[:2])
    # elementwise on a 2-D grid, against numpy directly
    phi, omega = ca.SX.sym("phi"), ca.SX.sym("omega")
    g = ca.Function("g", [phi, omega], [ca.sin(phi) * omega + phi**2])
    grid = rng.uniform(0, 6, size=(4, 7))
    speeds = rng.uniform(1, 9, size=(4, 1))
    (value,) = evaluate(g, {}, grid, speeds)
    assert_allclose(value, np.sin(grid) * speeds + grid**2, rtol=1e-15)


def test_the_carried_tangent_is_the_derivative_of_the_discrete_cycle():
    """shooting.cycle's ∂y/∂(J_F, E_ref) (forward sensitivities carried with the RK4 steps)
    against central differences of the same discrete cycle without them."""
    import numpy as np

    machine = reduce(flyopt.load(PROBLEMS / "motor-press.toml"))
    net = machine.net_torque()
    model = periodic_model.periodic_model(net, machine.j_machine, machine.cycle_angle, machine.knots())
    omega = machine.omega_mean
    w_s = shooting.energy_swing(model, omega)
    j_f = w_s / (omega**2 * 0.05)
    e_ref = 0.5 * (j_f + float(model.inertia(0.0))) * omega**2
    y, jac = shooting.cycle(model, 1, j_f, e_ref, w_s, 0.0, True)
    plain, _ = shooting.cycle(model, 1, j_f, e_ref, w_s, 0.0, False)
    assert_allclose(plain, y, rtol=0, atol=0)
    for k, (value, step) in enumerate(((j_f, 1e-5 * j_f), (e_ref, 1e-5 * e_ref))):
        args = [j_f, e_ref]
        args[k] = value + step
        up, _ = shooting.cycle(model, 1, *args, w_s, 0.0, False)
        args[k] = value - step
        down, _ = shooting.cycle(model, 1, *args, w_s, 0.0, False)
        central = (up - down) / (2 * step)
        scale = np.max(np.abs(central))
        assert scale > 0
        assert np.max(np.abs(jac[..., k] - central)) <= 1e-7 * scale


@pytest.mark.parametrize(
    "torque, guess",
    [
        (lambda w: 10.0 - 0.5 * w, 3.0),  # linear: the balance at 20 rad/s, bracketed outward
        (lambda w: 100.0 * (1.0 - w / 157.08) - 2.0 - 1e-3 * w * w, 50.0),
        (lambda w: math.atan(5.0 - w) + 0.01, 40.0),  # from above
    ],
)
def test_speed_balance_is_scipys_brentq_bit_for_bit(torque, guess):
    """speed_balance refines by flyopt's port of Brent's method: the same zero as scipy.optimize.brentq."""
    from scipy.optimize import brentq

    from flyopt.sizing.shooting import speed_balance

    found = speed_balance(torque, guess)
    # the bracket speed_balance searches, from the guess outward by factors of 2
    lo = hi = guess
    while not (torque(lo) > 0 > torque(hi)):
        if torque(hi) >= 0:
            lo, hi = hi, 2 * hi
        else:
            hi, lo = lo, 0.5 * lo
    assert found == brentq(torque, lo, hi, xtol=1e-15 * hi, rtol=4 * np.finfo(float).eps, maxiter=500)
    assert torque(found) == pytest.approx(0.0, abs=1e-12)
