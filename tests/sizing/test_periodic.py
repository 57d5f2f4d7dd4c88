"""Speed fluctuation beyond the constant-inertia method, against independent references.

References used here:
- the domain page's worked example 2 (published J_F) and flyopt.cycle.indicator's
  constant-inertia method, which every model must reproduce to 1e-8 on a
  scene of constant inertia and angle-only torques;
- a brute-force forward simulation written here with scipy (DOP853 at
  rtol 1e-13, in time, state (φ, E), no ΔE closed form, no CasADi), with the
  slider-crank inertia from the textbook closed form rather than
  flyopt.machine.mechanism;
- for speed-dependent torques, a scipy shooting solution (Brent's method on
  the periodicity condition) written here;
- the closed-form run-up of a DC motor against a constant load.
"""

import math

import casadi as ca
import numpy as np
import pytest
from conftest import assert_published
from numpy.testing import assert_allclose
from scipy import integrate, optimize

from flyopt.cycle.expression import Expression
from flyopt.cycle.indicator import ExcessWork, energy_indicator, required_inertia
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.errors import NonPeriodicCycle, SolverFailed
from flyopt.machine.kinematics import SliderCrank
from flyopt.machine.mechanism import Member, equivalent_inertia, equivalent_torque
from flyopt.machine.motor import DCMotor, InductionMotor
from flyopt.sizing import periodic
from flyopt.sizing.energy_mass import achieved_speed, energy_mass_requirement
from flyopt.sizing.periodic import angle_torque, dynamic_requirement, periodic_solution, verify
from flyopt.sizing.startup import startup_time

TWO_PI = 2 * math.pi
RPM = TWO_PI / 60


# -- scenes ---------------------------------------------------------------------


def shear_press():
    """Domain page example 2: resisting 1600 → 200 N m, constant driving torque balancing it."""
    resisting = PiecewiseLinear(
        np.array([0, math.pi / 4, math.pi / 2, TWO_PI]), np.array([1600.0, 1600.0, 200.0, 200.0])
    )
    return ExcessWork(Constant(None), resisting, TWO_PI)


# A compressor-like slider-crank (zero offset): crank, piston with a stepped
# resisting force on the compression stroke, constant driving torque.
CRANK, ROD, PISTON, J_CRANK = 0.1, 0.35, 12.0, 0.05
FORCE_ANGLES = np.array([0.0, 1.5, 1.5, 2.6, 2.6, TWO_PI])
FORCE_VALUES = np.array([0.0, 0.0, 8000.0, 8000.0, 0.0, 0.0])
N_COMPRESSOR = 300 * RPM


def compressor():
    sc = SliderCrank(CRANK, ROD)
    piston = Member(
        "piston",
        PISTON,
        0.0,
        sc.slider_velocity_ratio,
        0.0,
        force=(FORCE_ANGLES, FORCE_VALUES),
        force_sense="resisting",
    )
    j_e = equivalent_inertia([piston], J_CRANK)
    excess = ExcessWork(Constant(None), equivalent_torque([piston]).resisting(), TWO_PI)
    return excess, j_e


def textbook_slider_ratio(phi):
    """|v_B/ω| of a zero-offset slider-crank: r sin φ (1 + λ cos φ/sqrt(1 − λ² sin² φ)) (textbook, exact)."""
    lam = CRANK / ROD
    return np.abs(CRANK * np.sin(phi) * (1 + lam * np.cos(phi) / np.sqrt(1 - lam**2 * np.sin(phi) ** 2)))


def textbook_compressor_inertia(phi):
    return J_CRANK + PISTON * textbook_slider_ratio(phi) ** 2


def compressor_force(phi, a):
    """The piston force on the piece that starts at angle a (steps seen from the right side)."""
    return 8000.0 if 1.5 <= a < 2.6 else 0.0


def reference_driving_torque():
    """Mean of F |v_B/ω| over the turn, by scipy quad: the balancing driving torque."""
    work = integrate.quad(lambda p: 8000.0 * textbook_slider_ratio(p), 1.5, 2.6, epsabs=0, epsrel=2e-14)[0]
    return work / TWO_PI


def press(rpm, slip, stroke=0.02, peak=50.0, torque=100.0):
    """A press: a rectangular torque spike `peak` × the mean over `stroke` of the turn, zero elsewhere.

    Driven by an induction motor on the reference shaft whose rated point is
    (rpm, mean torque) and whose line has the rated slip `slip`.
    """
    omega_n = rpm * RPM
    a, b = 1.0, 1.0 + stroke * TWO_PI
    load = PiecewiseLinear(np.array([0, a, a, b, b, TWO_PI]), np.array([0, 0, peak * torque, peak * torque, 0, 0.0]))
    motor = InductionMotor(torque * omega_n, omega_n, omega_n / (1 - slip))

    def net(phi, omega):
        return motor.torque(omega) - load.casadi(phi)

    return net, load, motor, omega_n


def energy_estimate(load, omega, delta):
    """Constant-inertia flywheel for the press with the motor replaced by its mean torque."""
    ind = energy_indicator(Constant(None), load, TWO_PI)
    return required_inertia(ind.a_max, omega, delta)


# -- independent references ------------------------------------------------------


def simulate_time_domain(inertia, torque_on_piece, knots, e0, cycle=TWO_PI):
    """One cycle of J(φ) in time with scipy: dφ/dt = sqrt(2E/J(φ)), dE/dt = M(φ) dφ/dt.

    Integrates piece by piece between the knots (events at each knot), then
    finds ω_max and ω_min from the dense output (400 samples per piece,
    refined by a bounded scalar search). Returns (ω_max, ω_min, E(Φ)).
    """
    edges = np.union1d([0.0, cycle], [k for k in knots if 0 < k < cycle])
    t, y = 0.0, np.array([0.0, e0])
    best_max, best_min = -math.inf, math.inf
    for a, b in zip(edges[:-1], edges[1:]):

        def rhs(_, s, a=a):
            omega = math.sqrt(2 * s[1] / inertia(s[0]))
            return [omega, torque_on_piece(s[0], a) * omega]

        def reach(_, s, b=b):
            return s[0] - b

        reach.terminal, reach.direction = True, 1
        span = 10 * (b - a) / math.sqrt(2 * e0 / inertia(a)) + 1.0
        sol = integrate.solve_ivp(
            rhs,
            (t, t + 100 * span),
            y,
            method="DOP853",
            rtol=1e-13,
            atol=[1e-14, 1e-14 * e0],
            events=reach,
            dense_output=True,
        )
        assert sol.status == 1, sol.message
        t_end = sol.t_events[0][0]
        ts = np.linspace(t, t_end, 401)

        def omega_at(tt):
            s = sol.sol(tt)
            return np.sqrt(2 * s[1] / inertia(s[0]))

        w = omega_at(ts)
        for sign in (1, -1):
            i = int(np.argmax(sign * w))
            lo_t, hi_t = ts[max(i - 1, 0)], ts[min(i + 1, len(ts) - 1)]
            res = optimize.minimize_scalar(
                lambda tt: -sign * float(omega_at(tt)),
                bounds=(lo_t, hi_t),
                method="bounded",
                options={"xatol": 1e-14 * max(t_end, 1)},
            )
            value = max(sign * w[i], -res.fun) * sign
            if sign > 0:
                best_max = max(best_max, value)
            else:
                best_min = min(best_min, value)
        t, y = t_end, sol.y_events[0][0]
    return best_max, best_min, y[1]


def scipy_periodic_press(net_numeric, load, j_total, e_guess, method="DOP853"):
    """Periodic solution of dE/dφ = M(φ, ω) for constant J by scipy: Brent on E(Φ) − E(0).

    Returns (ω_max, ω_min) of the periodic orbit from the dense output.
    """
    edges = np.unique(load.angles)

    def cycle(e0, dense=False):
        e, out = e0, []
        for a, b in zip(edges[:-1], edges[1:]):
            level = load.limits(np.array([a]))[1][0]  # the spike's value on this piece

            def rhs(p, s, level=level):
                return [net_numeric(math.sqrt(2 * s[0] / j_total)) - level]

            sol = integrate.solve_ivp(rhs, (a, b), [e], method=method, rtol=1e-13, atol=1e-14 * e0, dense_output=dense)
            assert sol.success, sol.message
            e = sol.y[0, -1]
            out.append(sol)
        return e, out

    e_star = optimize.brentq(
        lambda e0: cycle(e0)[0] - e0, 0.999 * e_guess, 1.001 * e_guess, xtol=1e-15 * e_guess, rtol=1e-15
    )
    _, sols = cycle(e_star, dense=True)
    e_max, e_min = -math.inf, math.inf
    for sol in sols:
        ts = np.linspace(sol.t[0], sol.t[-1], 2001)
        values = sol.sol(ts)[0]
        for sign in (1, -1):
            i = int(np.argmax(sign * values))
            res = optimize.minimize_scalar(
                lambda p: -sign * float(sol.sol(p)[0]),
                bounds=(ts[max(i - 1, 0)], ts[min(i + 1, 2000)]),
                method="bounded",
                options={"xatol": 1e-13},
            )
            v = sign * max(sign * values[i], -res.fun)
            e_max, e_min = max(e_max, v), min(e_min, v)
    return math.sqrt(2 * e_max / j_total), math.sqrt(2 * e_min / j_total)


# -- constant inertia, angle-only torques: every model is exact and agrees -------------


@pytest.mark.parametrize("j_constant", [0.0, 0.3])
def test_constant_inertia_all_models_agree_shear_press(j_constant):
    """Domain example 2 (J_F = 1.0183 kg m^2 with J_c = 0): cycle method, energy–mass and the
    periodic dynamic model give the same J_F to 1e-8 (the issue's agreement requirement)."""
    excess = shear_press()
    omega, delta = 1500 * RPM, 0.05
    ind = energy_indicator(excess.driving, excess.resisting, TWO_PI)
    classic = required_inertia(ind.a_max, omega, delta, j_constant)
    exact = energy_mass_requirement(excess, j_constant, omega, delta)
    dynamic = dynamic_requirement(angle_torque(excess), j_constant, TWO_PI, omega, delta, excess.knots)
    assert_allclose(exact.j_required, classic, rtol=1e-8)
    assert_allclose(dynamic.j_required, classic, rtol=1e-8)
    assert_allclose(exact.a_max, ind.a_max, rtol=1e-12)
    if j_constant == 0.0:
        assert_published(exact.j_required, "1.0183")
    # with constant J the constant-inertia comparison is not off at all
    assert_allclose(exact.j_constant_inertia, exact.j_required, rtol=1e-8)
    assert_allclose(exact.delta_constant_inertia, delta, rtol=1e-8)
    # ω_max at the cycle start, ω_min where the falling resisting torque crosses 462.5 N m
    assert_allclose(exact.phi_omega_min, math.pi / 4 * (1 + 0.8125), rtol=1e-12)
    assert_allclose(dynamic.solution.phi_omega_min, math.pi / 4 * (1 + 0.8125), rtol=1e-6)
    assert "prescribed" in dynamic.held


def test_constant_inertia_expression_torque_all_models_agree():
    """A smooth expression torque (quadrature path): energy–mass, dynamic and cycle method to 1e-8."""
    driving = ExpressionTorque(Expression("1000 + 400*sin(phi) + 150*cos(2*phi)**3 + 30*sin(5*phi)"), 1.0, "test")
    excess = ExcessWork(driving, Constant(None), TWO_PI)
    ind = energy_indicator(driving, Constant(None), TWO_PI)
    omega, delta, j_c = 100.0, 0.02, 0.5
    classic = required_inertia(ind.a_max, omega, delta, j_c)
    assert_allclose(energy_mass_requirement(excess, j_c, omega, delta).j_required, classic, rtol=1e-8)
    dynamic = dynamic_requirement(angle_torque(excess), j_c, TWO_PI, omega, delta, excess.knots)
    assert_allclose(dynamic.j_required, classic, rtol=1e-8)


# -- variable inertia, angle-only torques ---------------------------------------


def test_compressor_driving_torque_matches_quadrature():
    """The reduced piston force balances with M_d = (1/2π)∫ F |v_B/ω| dφ (textbook |v_B/ω|, quad 1e-12)."""
    excess, _ = compressor()
    assert_allclose(excess.driving.value, reference_driving_torque(), rtol=1e-12)


@pytest.mark.parametrize("delta", [0.3, 0.05, 0.01])
def test_energy_mass_against_brute_force_time_simulation(delta):
    """Energy–mass J_F and E_0 give, in an independent time-domain scipy simulation, exactly δ.

    Tolerance 1e-8 in δ: the reference integrates to rtol 1e-13 in E, so
    (ω_max − ω_min) is good to ~1e-12 ω_m, i.e. 1e-10 relative at δ = 0.01.
    """
    excess, j_e = compressor()
    exact = energy_mass_requirement(excess, j_e, N_COMPRESSOR, delta)
    speed = achieved_speed(excess, j_e, N_COMPRESSOR, exact.j_required)
    assert_allclose(speed.delta, delta, rtol=1e-12)  # the forward method inverts the closed form
    assert_allclose(speed.e0, exact.e0, rtol=1e-12)
    m_d = reference_driving_torque()

    def torque(phi, a):
        return m_d - compressor_force(phi, a) * textbook_slider_ratio(phi)

    j_total = lambda p: exact.j_required + textbook_compressor_inertia(p)  # noqa: E731
    w_max, w_min, e_end = simulate_time_domain(j_total, torque, [1.5, 2.6, math.pi], speed.e0)
    assert_allclose(e_end, speed.e0, rtol=1e-11)  # the cycle balances: the speed is periodic
    assert_allclose([w_max, w_min], [speed.omega_max, speed.omega_min], rtol=1e-10)
    assert_allclose((w_max - w_min) / (0.5 * (w_max + w_min)), delta, rtol=1e-8)


def test_constant_inertia_method_is_off_with_variable_inertia():
    """With the piston's J_v the constant-inertia method (J_e → its mean) misses: its flywheel
    is 11 % off the exact one, and the δ it really achieves (checked in the time-domain
    reference to 1e-8) is 10 % off the allowed δ (asserted: more than 5 %)."""
    excess, j_e = compressor()
    delta = 0.05
    exact = energy_mass_requirement(excess, j_e, N_COMPRESSOR, delta)
    assert abs(exact.j_error) > 0.05
    assert abs(exact.delta_constant_inertia / delta - 1) > 0.05
    speed = achieved_speed(excess, j_e, N_COMPRESSOR, exact.j_constant_inertia)
    m_d = reference_driving_torque()

    def torque(phi, a):
        return m_d - compressor_force(phi, a) * textbook_slider_ratio(phi)

    j_total = lambda p: exact.j_constant_inertia + textbook_compressor_inertia(p)  # noqa: E731
    w_max, w_min, _ = simulate_time_domain(j_total, torque, [1.5, 2.6, math.pi], speed.e0)
    assert_allclose((w_max - w_min) / (0.5 * (w_max + w_min)), exact.delta_constant_inertia, rtol=1e-8)
    # and the mean inertia really is the cycle mean of J_e (quad of the textbook J_e, 1e-12)
    mean = integrate.quad(textbook_compressor_inertia, 0, TWO_PI, epsabs=0, epsrel=2e-14, limit=200)[0] / TWO_PI
    assert_allclose(exact.j_machine_mean, mean, rtol=1e-12)


@pytest.mark.parametrize("delta", [0.3, 0.01])
def test_variable_inertia_simulation_agrees_with_energy_mass(delta):
    """The CasADi periodic simulation reproduces the exact δ to 1e-6 (the issue's requirement;
    it reaches ~1e-9), and the dynamic requirement the exact J_F to 1e-8."""
    excess, j_e = compressor()
    exact = energy_mass_requirement(excess, j_e, N_COMPRESSOR, delta)
    sim = periodic_solution(angle_torque(excess), j_e, TWO_PI, N_COMPRESSOR, exact.j_required, excess.knots)
    assert_allclose(sim.delta, delta, rtol=1e-6)
    assert_allclose([sim.omega_max, sim.omega_min], [exact.omega_max, exact.omega_min], rtol=1e-8)
    assert_allclose([sim.phi_omega_max, sim.phi_omega_min], [exact.phi_omega_max, exact.phi_omega_min], rtol=1e-5)
    dynamic = dynamic_requirement(angle_torque(excess), j_e, TWO_PI, N_COMPRESSOR, delta, excess.knots)
    assert_allclose(dynamic.j_required, exact.j_required, rtol=1e-8)


# -- speed-dependent torques: the periodic solution ------------------------------


def test_press_periodic_solution_against_scipy_shooting():
    """Induction-motor press (2 % stroke, 50× spike): δ and ω_m against a scipy shooting solution.

    Tolerances: δ 1e-6 relative (the issue's simulation requirement), ω_m 1e-9.
    """
    net, load, motor, omega_n = press(1500, 0.04)
    j_f = 0.9 * energy_estimate(load, omega_n, 0.05)
    sol = periodic_solution(net, 0.0, TWO_PI, omega_n, j_f, load.breakpoints())
    w_max, w_min = scipy_periodic_press(motor.torque, load, j_f, sol.e0)
    assert_allclose(sol.delta, (w_max - w_min) / (0.5 * (w_max + w_min)), rtol=1e-6)
    assert_allclose(sol.omega_mean, 0.5 * (w_max + w_min), rtol=1e-9)
    assert sol.speed_dependent and sol.multiplier < 1
    assert sol.periodicity_residual <= sol.periodicity_tolerance


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
def test_stiff_motor_periodic_solution_against_scipy_radau():
    """Slip 0.5 % and δ ≈ 0.3: stiff (the orbit forgets its start within the cycle); scipy Radau reference."""
    net, load, motor, omega_n = press(1500, 0.005)
    j_f = energy_estimate(load, omega_n, 0.3)
    sol = periodic_solution(net, 0.0, TWO_PI, omega_n, j_f, load.breakpoints())
    w_max, w_min = scipy_periodic_press(motor.torque, load, j_f, sol.e0, method="Radau")
    assert_allclose(sol.delta, (w_max - w_min) / (0.5 * (w_max + w_min)), rtol=1e-6)
    assert sol.multiplier < 1e-3


HARD_CASES = [
    # (label, reference speed [rpm], rated slip, delta)
    ("press 2% stroke 50x spike", 1500, 0.04, 0.05),
    ("delta 1e-4", 1500, 0.04, 1e-4),
    ("delta 0.3", 1500, 0.04, 0.3),
    ("stiff motor slip 0.5%", 1500, 0.005, 0.05),
    ("1 rpm", 1, 0.04, 0.05),
    ("20,000 rpm", 20000, 0.04, 0.05),
]


@pytest.mark.parametrize("label, rpm, slip, delta", HARD_CASES, ids=[c[0] for c in HARD_CASES])
def test_hard_cases_converge_to_a_periodic_solution(label, rpm, slip, delta):
    """The dynamic requirement converges on every hard case: δ met to 1e-9, the orbit periodic
    to its tolerance and stable (Floquet multiplier < 1)."""
    net, load, _, omega_n = press(rpm, slip)
    result = dynamic_requirement(net, 0.0, TWO_PI, omega_n, delta, load.breakpoints())
    sol = result.solution
    assert result.limit == "delta"
    assert_allclose(sol.delta, delta, rtol=1e-9)
    assert sol.converged and sol.periodicity_residual <= sol.periodicity_tolerance
    assert 0 <= sol.multiplier < 1
    assert result.j_required > 0
    assert "outcome" in result.held


@pytest.mark.slow  # a stiff motor's periodic search over its whole delta range: about 8 s
def test_stiff_motor_never_swings_to_delta_03():
    """Slip 0.5 % and a 50× spike: the speed cannot fall further than the motor's line lets it at the spike,
    ω_min = ω_0 (1 − 50 s_n) = 0.75 ω_0, with ω_max = ω_0 at no load, so δ < (0.25)/(0.875) = 2/7 for every
    flywheel, reaching 2/7 as the inertia vanishes (quasi-static). δ = 0.3 is never reached: no flywheel is
    needed. The requirement once reported J_F = 6e-4 kg·m² with δ = 0.3 there, which was the cubic's
    overshoot between grid nodes (the curve itself and scipy Radau give 2/7 at that flywheel)."""
    net, load, motor, omega_n = press(1500, 0.005)
    result = dynamic_requirement(net, 0.0, TWO_PI, omega_n, 0.3, load.breakpoints())
    # "none": δ = 0.3 is reached at no inertia (it said "delta", which the report read as "δ reaches the
    # allowed value" beside a δ of 2/7); with no inertia of its own the solution is the vanishing inertia's limit
    assert result.limit == "none" and result.j_required <= 0
    assert_allclose(result.solution.delta, 2 / 7, rtol=1e-6)
    omega = np.asarray(result.solution.omega)
    assert_allclose([result.solution.omega_max, result.solution.omega_min], [omega.max(), omega.min()], rtol=1e-9)
    for j_f in (6e-4, 3e-3):  # δ below 2/7 at any flywheel: the requirement's answer, by scipy Radau
        sol = periodic_solution(net, 0.0, TWO_PI, omega_n, j_f, load.breakpoints())
        w_max, w_min = scipy_periodic_press(motor.torque, load, j_f, sol.e0, method="Radau")
        reference = (w_max - w_min) / (0.5 * (w_max + w_min))
        assert_allclose(sol.delta, reference, rtol=1e-6)
        assert reference <= 2 / 7 * (1 + 1e-9)


def test_reference_speed_scaling_is_exact():
    """1 rpm, 1500 rpm and 20,000 rpm with J ∝ 1/ω² and the same slip are the same machine in
    scaled variables: the same δ and ω_m/ω_n to 1e-8."""
    results = []
    for rpm in (1, 1500, 20000):
        net, load, _, omega_n = press(rpm, 0.04)
        j_f = energy_estimate(load, omega_n, 0.05)
        sol = periodic_solution(net, 0.0, TWO_PI, omega_n, j_f, load.breakpoints())
        results.append((sol.delta, sol.omega_mean / omega_n))
    assert_allclose(results[1:], [results[0]] * 2, rtol=1e-8)


def test_cheaper_models_are_off_with_a_speed_dependent_motor():
    """With a soft motor (4 % slip) and δ = 0.3 the constant-inertia flywheel (motor → its mean
    torque) really achieves a δ more than 10 % larger: the verification flags it, and the
    dynamic requirement is more than 10 % larger."""
    net, load, _, omega_n = press(1500, 0.04)
    delta = 0.3
    j_classic = energy_estimate(load, omega_n, delta)
    check = verify(net, 0.0, TWO_PI, omega_n, delta, j_classic, load.breakpoints())
    assert check.flagged and check.achieved_delta > 1.1 * delta
    dynamic = dynamic_requirement(net, 0.0, TWO_PI, omega_n, delta, load.breakpoints())
    assert dynamic.j_required > 1.1 * j_classic


# -- verification -----------------------------------------------------------------


def test_verification_flags_only_a_flywheel_that_misses_delta():
    """The required flywheel passes (δ within the tolerance); 20 % less is flagged."""
    excess, j_e = compressor()
    delta = 0.05
    exact = energy_mass_requirement(excess, j_e, N_COMPRESSOR, delta)
    net = angle_torque(excess)
    ok = verify(net, j_e, TWO_PI, N_COMPRESSOR, delta, exact.j_required, excess.knots)
    assert not ok.flagged and abs(ok.achieved_delta - delta) <= ok.tolerance
    small = verify(net, j_e, TWO_PI, N_COMPRESSOR, delta, 0.8 * exact.j_required, excess.knots)
    assert small.flagged
    report = small.to_dict()
    assert set(report) >= {"method", "achieved_delta", "omega_max", "omega_min", "omega_mean", "tolerance"}
    assert_allclose(report["omega_mean"], N_COMPRESSOR, rtol=1e-12)  # prescribed: angle-only torques


# -- failures are reported, never a non-periodic "steady state" ---------------------


def test_unbalanced_angle_only_torque_is_not_periodic():
    """A net torque of 1 N m over the turn: no periodic solution, NonPeriodicCycle with the imbalance."""
    with pytest.raises(NonPeriodicCycle, match=r"\+6\.28319 J"):
        periodic_solution(lambda phi, omega: 1.0 + 0 * phi, 1.0, TWO_PI, 10.0)


def test_too_weak_motor_reports_a_stall():
    """A DC motor whose stall torque (50 N m) is below the mean load (100 N m): no steady state."""
    _, load, _, omega_n = press(1500, 0.04)
    motor = DCMotor(omega_n * 1.05, 50.0)

    def net(phi, omega):
        return motor.torque(omega) - load.casadi(phi)

    with pytest.raises(SolverFailed, match="stall"):
        periodic_solution(net, 0.0, TWO_PI, omega_n, 1.0, load.breakpoints())


def test_runaway_is_reported():
    """A driving torque that grows with speed (positive feedback) has no steady state."""
    with pytest.raises(SolverFailed, match="runs away"):
        periodic_solution(lambda phi, omega: 0.5 * omega + 5 * ca.cos(phi), 1.0, TWO_PI, 10.0)


@pytest.mark.slow
def test_kloss_motor_beyond_breakdown_is_limited_by_stall():
    """A stiff motor on its Kloss curve cannot let the speed fall 30 %: past its breakdown slip
    the torque collapses and below a flywheel of about 1.5× the classical one no periodic steady
    state exists. The requirement reports that limit ("stall"), where the orbit is close to losing
    stability (Floquet multiplier near 1), with δ below the allowed 0.3. (~60 s)"""
    _, load, motor, omega_n = press(1500, 0.005)

    def net(phi, omega):
        return motor.torque(omega, "kloss") - load.casadi(phi)

    result = dynamic_requirement(net, 0.0, TWO_PI, omega_n, 0.3, load.breakpoints())
    assert result.limit == "stall"
    assert result.solution.delta < 0.3
    assert 0.5 < result.solution.multiplier < 1
    assert result.j_required > energy_estimate(load, omega_n, 0.3)


def test_newton_limit_raises_instead_of_returning(monkeypatch):
    """When the iteration limit stops Newton early, SolverFailed says so; no solution is returned."""
    net, load, _, omega_n = press(1500, 0.04)
    monkeypatch.setattr(periodic, "MAX_NEWTON", 1)
    with pytest.raises(SolverFailed, match="did not converge"):
        periodic_solution(net, 0.0, TWO_PI, 0.5 * omega_n, 0.05, load.breakpoints())


# -- start-up ----------------------------------------------------------------------


@pytest.mark.parametrize("fraction, rtol", [(0.5, 1e-8), (0.9, 1e-8), (0.999, 1e-6)])
def test_startup_dc_motor_constant_load_closed_form(fraction, rtol):
    """J ω' = M_s (1 − ω/ω_0) − M_L: t = −τ ln(1 − ω/ω_∞), τ = J ω_0/M_s, ω_∞ = ω_0 (1 − M_L/M_s).

    Tolerance: 1e-8, and 1e-6 at 99.9 % where t is 150× as sensitive to the speed.
    """
    motor, load, j = DCMotor(100.0, 50.0), 20.0, 2.0

    def net(phi, omega):
        return motor.torque(omega) - load

    w_inf, tau = 100.0 * (1 - load / 50.0), j * 100.0 / 50.0
    result = startup_time(net, j, TWO_PI, fraction * w_inf)
    assert_allclose(result.time, -tau * math.log(1 - fraction), rtol=rtol)
    # a flywheel slows the start in proportion to the inertia
    slower = startup_time(net, j, TWO_PI, fraction * w_inf, j_flywheel=3 * j)
    assert_allclose(slower.time / result.time, 4.0, rtol=rtol)


def test_startup_kloss_motor_fluctuating_load_against_scipy():
    """Kloss induction motor against M_L = 0.5 M_n (1 + 0.5 sin φ), J constant: the time to reach
    97 % of synchronous speed against scipy DOP853 in time with an event (1e-7)."""
    motor = InductionMotor(7500.0, 1440 * RPM, 1500 * RPM)
    m_n, j = motor.rated_torque, 0.8

    def net(phi, omega):
        return motor.torque(omega, "kloss") - 0.5 * m_n * (1 + 0.5 * ca.sin(phi))

    target = 0.97 * 1500 * RPM
    result = startup_time(net, j, TWO_PI, target)

    def rhs(_, s):
        return [s[1], (motor.torque(s[1], "kloss") - 0.5 * m_n * (1 + 0.5 * math.sin(s[0]))) / j]

    def reach(_, s):
        return s[1] - target

    reach.terminal, reach.direction = True, 1
    ref = integrate.solve_ivp(rhs, (0, 100), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-12, events=reach)
    assert_allclose(result.time, ref.t_events[0][0], rtol=1e-7)
    assert_allclose(result.angle, ref.y_events[0][0][0], rtol=1e-7)


def test_startup_failures():
    """A load above the starting torque cannot start; a target above the no-load balance is never reached."""
    motor = DCMotor(100.0, 50.0)
    with pytest.raises(SolverFailed, match="cannot start"):
        startup_time(lambda phi, omega: motor.torque(omega) - 60.0, 1.0, TWO_PI, 10.0)
    with pytest.raises(SolverFailed, match="settles below the target"):
        startup_time(lambda phi, omega: motor.torque(omega) - 20.0, 0.05, TWO_PI, 61.0)


# -- inputs --------------------------------------------------------------------------


def _math_sin_torque(phi, omega):
    return math.sin(phi)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: energy_mass_requirement(shear_press(), 0.0, -1.0, 0.05), "omega_mean must be a positive"),
        (lambda: energy_mass_requirement(shear_press(), 0.0, 100.0, 2.5), r"delta must lie in \(0, 2\)"),
        (lambda: energy_mass_requirement(shear_press(), -1.0, 100.0, 0.05), "j_machine must be a finite number >= 0"),
        (lambda: achieved_speed(shear_press(), 0.0, 157.0, 1e-6), "cannot keep the mean speed"),
        (lambda: achieved_speed(shear_press(), 0.5, 157.0, -0.6), "total inertia"),
        (lambda: periodic_solution(_math_sin_torque, 1.0, TWO_PI, 10.0), "must accept CasADi symbols"),
        (lambda: periodic_solution(lambda p, w: 0 * p, 1.0, -1.0, 10.0), "cycle_angle must be a positive"),
        (lambda: periodic_solution(lambda p, w: 0 * p, 1.0, TWO_PI, 10.0, -2.0), "total inertia"),
        (lambda: startup_time(lambda p, w: 1 + 0 * p, 1.0, TWO_PI, 10.0, phi_start=7.0), "phi_start must lie"),
    ],
)
def test_bad_input_raises_value_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
