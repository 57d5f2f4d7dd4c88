"""The alternating torque at the wheel's seat from the drive train's forced response (docs/flywheel-design.md,
section 26: "The torque at the seat").

Where the train is modelled, the fatigue check's T_m and T_a are those of the forced response's torque in the
shaft from the seat toward the crank, every order of the cycle's net torque synthesised in time with its phase
(design.shaft.train.seat_torque), not the rigid body's. References: the damped two-inertia closed form under a
harmonic torque, |T| = |F| J_1/(J_1 + J_2) / |1 - β² + 2iζβ| (β = Ω/ω_n, ω_n² = k (J_1 + J_2)/(J_1 J_2)); two
orders summed directly with their phases on a fine grid; the rigid-body share J_1/(J_1 + J_2) of a stiff train;
the per-order solver of flyopt.machine.torsion (forced_response) for the batched one; and, marked slow, a
time-domain integration of the shipped punch press's two-inertia train over the cycle.
"""

import math

import numpy as np
import pytest
from test_shaft_train import GOOD, J_WHEEL, check

import flyopt
from flyopt.design.shaft.train import TrainModel, seat_torque
from flyopt.machine.torsion import (
    Inertia,
    Spring,
    TorqueOrders,
    TorsionalModel,
    forced_response,
    modal_damping,
    modal_spring_torque_orders,
)

J2 = 1.5  # the shaft's other inertia in test_shaft_train's scene (the "crank" node takes it)
SPEED = 50.0  # rad/s of the shaft in test_shaft_train.check
#: The synthesised curve's extremes: sampled, then refined on the series summed directly (their value to some 3e-9
#: of the highest order's amplitude, design.shaft.train._extreme).
RTOL = 1e-9


def _train(k):
    return f'train = [{{ flywheel = true }}, {{ stiffness = "{k!r} N*m/rad" }}, {{ name = "crank" }}]'


def _closed_form(amplitude, q, k, zeta):
    w = math.sqrt(k * (J_WHEEL + J2) / (J_WHEEL * J2))
    beta = q * SPEED / w
    return amplitude * J_WHEEL / (J_WHEEL + J2) / (1 - beta * beta + 2j * zeta * beta)


@pytest.mark.parametrize("beta", [0.3, 0.95, 1.0, 3.0])
def test_the_seats_alternating_torque_is_the_damped_two_inertia_closed_form(write_scene, beta):
    zeta, mean, amplitude = 0.02, 40.0, 300.0
    w = SPEED / beta
    k = w * w * J_WHEEL * J2 / (J_WHEEL + J2)
    excitation = TorqueOrders(mean, np.array([1.0]), np.array([amplitude * np.exp(0.7j)]))
    _, found = check(write_scene, "damping_ratio = 0.02\n" + _train(k), excitation=excitation)
    expected = abs(_closed_form(amplitude, 1.0, k, zeta))
    assert found.torque_source == "forced response"
    assert found.torque_alternating == pytest.approx(expected, rel=RTOL)
    assert found.torque_mean == pytest.approx(mean * J_WHEEL / (J_WHEEL + J2), abs=RTOL * expected)
    assert found.torque_alternating_rigid == 100.0  # the rigid curve the check was given, kept beside it
    # every section the torque passes through is checked with it
    assert any(s.ta == found.torque_alternating for s in found.sections)
    if beta == 1.0:  # at resonance the amplification is 1/(2ζ) = 25
        assert found.torque_alternating == pytest.approx(amplitude * J_WHEEL / (J_WHEEL + J2) / 0.04, rel=RTOL)


def test_orders_are_superposed_with_their_phases_not_added(write_scene):
    """Two orders: the half range of their sum in time (a direct sum of cosines on a fine grid), below the sum of
    their amplitudes (the bound whatever the phases) and above the larger alone."""
    k, zeta = 2.0e4, 0.02
    c1, c3 = 300.0 * np.exp(0.4j), 120.0 * np.exp(-1.9j)
    excitation = TorqueOrders(0.0, np.array([1.0, 2.0, 3.0]), np.array([c1, 0.0, c3]))
    _, found = check(write_scene, "damping_ratio = 0.02\n" + _train(k), excitation=excitation)
    t1, t3 = _closed_form(c1, 1.0, k, zeta), _closed_form(c3, 3.0, k, zeta)
    theta = np.linspace(0.0, 2 * math.pi, 2000001)  # its extremes to (3π/2e6)²/2 = 1e-11
    curve = np.real(t1 * np.exp(1j * theta) + t3 * np.exp(3j * theta))
    half_range = 0.5 * (curve.max() - curve.min())
    assert found.torque_alternating == pytest.approx(half_range, rel=1e-9)
    assert max(abs(t1), abs(t3)) < found.torque_alternating < abs(t1) + abs(t3)


def test_a_stiff_train_gives_the_rigid_bodys_share():
    """As the shaft stiffens (ω_n → ∞) each order's torque tends to J_1/(J_1 + J_2) of the net torque's."""
    from flyopt.design.shaft.train import TrainModel, seat_torque
    from flyopt.machine.torsion import Inertia, Spring, TorsionalModel

    model = TorsionalModel([Inertia(0, J_WHEEL), Inertia(1, J2)], [Spring(0, 1, 1e13)])
    built = TrainModel(model, ("wheel", "crank"), (("shaft", "stiffness", 1e13),), 0, 1)
    excitation = TorqueOrders(0.0, np.array([1.0, 2.0]), np.array([300.0, 100.0j]))
    seat = seat_torque(built, excitation, SPEED * 30 / math.pi, 0.02)
    theta = np.arange(4096) * 2 * math.pi / 4096
    rigid = J_WHEEL / (J_WHEEL + J2) * (excitation.torque(theta) - excitation.mean)
    assert np.max(np.abs(seat.curve - rigid)) <= 1e-6 * np.max(np.abs(rigid))


def test_the_modal_superposition_is_the_per_order_forced_response(write_scene):
    """Every order at once by modal superposition (modal_spring_torque_orders) against
    flyopt.machine.torsion.forced_response, which solves (K - Ω² M + iΩ C) x = T order by order with C the modal
    damping matrix."""
    scene = flyopt.load(write_scene(GOOD))
    from flyopt.design.materials import get_material, material_library
    from flyopt.design.shaft.train import train_model

    shaft = scene.shafts[0]
    library = material_library(scene.materials)
    built = train_model(
        shaft.layout.train,
        shaft.layout,
        get_material(shaft.layout.material, library),
        wheel_inertia=J_WHEEL,
        speed_ratio=shaft.speed_ratio,
        materials=library,
    )
    rng = np.random.default_rng(30)
    orders = np.arange(1, 400) / 3.0
    excitation = TorqueOrders(0.0, orders, rng.normal(size=orders.size) + 1j * rng.normal(size=orders.size))
    c = modal_damping(built.model, 0.02)
    loop = forced_response(built.model, excitation, built.load_node, 700.0, damping=c).shaft_torques
    for e in range(len(built.model.springs)):
        batched = modal_spring_torque_orders(built.model, excitation, built.load_node, 700.0, e, 0.02)
        np.testing.assert_allclose(batched, loop[e], rtol=1e-9, atol=1e-12 * np.max(np.abs(loop[e])))


@pytest.fixture(scope="module")
def punch_press():
    from conftest import PROBLEMS

    from flyopt.pipeline import solve

    return solve(flyopt.load(PROBLEMS / "punch-press-shaft.toml"))


def test_near_resonance_the_seat_sees_more_alternating_stress_than_the_rigid_body(punch_press):
    """punch-press-shaft: the two-inertia mode sits at the 84th harmonic of the punching cycle at the mean speed
    (84 Hz on a 1 Hz cycle), and the punch's break-through is a step: the shaft's torque swings twice the rigid
    body's (the dynamic load factor of a step is 2), and the fatigue factor falls accordingly."""
    from flyopt.design.shaft.check import check_shaft
    from flyopt.design.shaft.cycle import layout_of, torque_curve
    from flyopt.pipeline import shaft_context_of

    (report,) = punch_press.shaft_checks
    c = report.check
    assert c.torque_source == "forced response" and c.holds
    assert 1.9 < c.torque_alternating / c.torque_alternating_rigid < 2.1
    ctx = shaft_context_of(punch_press.scene, punch_press.analysis)
    best = punch_press.design.best
    rigid = check_shaft(
        layout_of(ctx, "intermediate"),
        ctx.materials["intermediate"],
        wheel_mass=best.mass,
        wheel_inertia=best.j_flywheel,
        wheel_width=max(best.dims.b, best.dims.l_hub or 0.0),
        omega_mean=ctx.omega_mean * 6.0,
        delta=ctx.delta,
        torque_curve=torque_curve(ctx, "intermediate", best.j_flywheel),
    )
    assert rigid.torque_source == "rigid body" and rigid.torque_alternating == c.torque_alternating_rigid
    by_name = {s.name: s for s in rigid.sections}
    for section in c.sections:
        if section.ta > 0:  # between the seat and the pinion: a larger alternating torque, a smaller factor
            assert section.ta > 1.9 * by_name[section.name].ta
            assert section.fatigue < by_name[section.name].fatigue


@pytest.mark.slow  # a time-domain integration over three cycles: about a minute and a half
def test_the_seat_torque_is_the_time_domain_steady_state(punch_press):
    """A second method: the two-inertia train integrated in time (scipy, DOP853) under the net torque's series
    until periodic; its spring torque's half range against the synthesised one."""
    from scipy.integrate import solve_ivp

    check = punch_press.shaft_checks[0].check
    built, excitation, rpm, zeta = check.response_inputs
    model = built.model
    j = np.diag(model.mass_matrix)
    k = model.springs[0].stiffness * model.springs[0].ratio ** 2
    mu = j[0] * j[1] / (j[0] + j[1])
    damping = 2 * zeta * math.sqrt(k / mu) * mu  # the modal damping of the one elastic mode
    speed = rpm * math.pi / 30
    theta = np.linspace(0, 2 * math.pi / excitation.orders[0], 200001)
    load = excitation.torque(theta)
    period = theta[-1] / speed

    def rhs(t, y):
        f = np.interp((speed * t) % theta[-1], theta, load)
        return [y[1], (f * j[0] / (j[0] + j[1]) - damping * y[1] - k * y[0]) / mu]

    y = [0.0, 0.0]
    for n in range(3):  # the ringing decays by exp(-ζ ω_n T) = exp(-10.6) a cycle
        run = solve_ivp(rhs, (n * period, (n + 1) * period), y, max_step=period / 20000, rtol=1e-9, atol=1e-12)
        y = run.y[:, -1]
    torque = k * run.y[0]
    assert 0.5 * (torque.max() - torque.min()) == pytest.approx(check.torque_alternating, rel=1e-4)
    assert 0.5 * (torque.max() + torque.min()) == pytest.approx(check.torque_mean, abs=1e-4 * check.torque_alternating)


def _chain(inertias, stiffnesses, wheel):
    """A free chain of ``inertias`` joined by ``stiffnesses``, the wheel at node ``wheel``, the torque entering at the
    last node."""
    model = TorsionalModel(
        [Inertia(i, j) for i, j in enumerate(inertias)], [Spring(i, i + 1, k) for i, k in enumerate(stiffnesses)]
    )
    springs = tuple((f"k{i}", "stiffness", k) for i, k in enumerate(stiffnesses))
    names = tuple(f"n{i}" for i in range(len(inertias)))
    return TrainModel(model, names, springs, wheel, len(inertias) - 1, Inertia(wheel, inertias[wheel]))


def _pulse(level, width, orders):
    """The orders of a rectangular pulse: ``level`` on 0 <= theta < ``width``, 0 elsewhere (mean level width/2pi)."""
    k = np.arange(1, orders + 1)
    c = level / (math.pi * k) * (np.sin(k * width) - 1j * (1.0 - np.cos(k * width)))
    return TorqueOrders(0.0, k.astype(float), c)


def test_a_stiff_train_with_a_smooth_load_gives_the_rigid_share_of_the_section_not_the_wheels():
    """Upstream inertia (a motor J0) turns with the wheel J1 on the section's side: the section between the wheel and
    the crank J2 carries (J0 + J1)/J of a smooth load as the train stiffens, not the wheel's J1/J."""
    j0, j1, j2 = 0.5, 4.0, 1.5
    excitation = TorqueOrders(0.0, np.array([1.0, 2.0]), np.array([300.0, 120.0 * np.exp(1.1j)]))
    theta = np.linspace(0.0, 2 * math.pi, 2000001)
    load = np.real(300.0 * np.exp(1j * theta) + 120.0 * np.exp(1.1j) * np.exp(2j * theta))
    half_range = 0.5 * (load.max() - load.min())
    found = seat_torque(_chain([j0, j1, j2], [1e14, 1e14], 1), excitation, 60.0, 0.02)
    assert found is not None
    assert found.alternating == pytest.approx((j0 + j1) / (j0 + j1 + j2) * half_range, rel=1e-9)
    assert abs(found.alternating / (j1 / (j0 + j1 + j2) * half_range) - 1.0) > 0.1  # not the wheel's share


def test_a_step_rings_the_resolved_mode_to_the_damped_steps_overshoot():
    """A long pulse (half the cycle) through a two-inertia train whose mode (order 60) lies well below the highest
    order (2047): each step rings the section to 1 + exp(-pi zeta / sqrt(1 - zeta^2)) of its jump (the damped
    single-degree step response; 2 undamped, the step's dynamic load factor), the ringing gone before the next step."""
    j1, j2, zeta, level = 4.0, 1.5, 0.1, 1000.0
    mu = j1 * j2 / (j1 + j2)
    k = (60.0 * 2 * math.pi) ** 2 * mu  # at 60 rpm order 1 is 2 pi rad/s
    found = seat_torque(_chain([j1, j2], [k], 0), _pulse(level, math.pi, 2047), 60.0, zeta)
    assert found is not None
    share, overshoot = j1 / (j1 + j2), math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))
    # levels 0 and F, mean F/2: each extreme beyond its level by the overshoot of the jump F
    assert found.alternating == pytest.approx(share * level * (0.5 + overshoot), rel=1e-4)
    assert share * level / 2 < found.alternating < 3 * share * level / 2  # above the rigid, below DLF 2 each side


def test_a_stiff_train_resolves_a_step_only_up_to_the_highest_order():
    """The same pulse through a stiff train: the response is quasi-static up to the truncation, and the truncated
    series overshoots each jump by Gibbs' 8.95 % (Si(pi)/pi - 1/2): T_a is the rigid share's T_a x 1.179, on the
    safe side; flyopt keeps it (docs/flywheel-design.md, section 26)."""
    j1, j2, level = 4.0, 1.5, 1000.0
    found = seat_torque(_chain([j1, j2], [1e14], 0), _pulse(level, math.pi, 2047), 60.0, 0.02)
    assert found is not None
    gibbs = 0.5894898722360836 - 0.5  # Si(pi)/pi - 1/2 (Si(pi) = 1.851937051982466)
    rigid = j1 / (j1 + j2) * level / 2
    assert found.alternating == pytest.approx(rigid * (1 + 2 * gibbs), rel=1e-4)


def test_an_extreme_whose_search_did_not_converge_keeps_its_sample(monkeypatch):
    """_extreme checks BoundedMinimum.converged: a search that did not converge gives no value, the sample stands."""
    from flyopt.cycle import minimize
    from flyopt.design.shaft import train

    amplitudes, harmonics = np.array([100.0 + 0j]), np.array([1])
    curve = np.real(np.exp(1j * np.linspace(0.0, 2 * math.pi, 4096, endpoint=False)) * 100.0)
    assert train._extreme(amplitudes, harmonics, curve, 1.0) == pytest.approx(100.0, rel=1e-15)
    monkeypatch.setattr(minimize, "bounded_minimum", lambda *a, **k: minimize.BoundedMinimum(0.0, -1e9, 500, False))
    assert train._extreme(amplitudes, harmonics, curve, 1.0) == 100.0  # the sample at t = 0, not -(-1e9)
