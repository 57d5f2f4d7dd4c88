"""Torsional vibration of the drive train (issue 30, item 4) against closed forms, textbook and openTorsion figures.

References: closed forms of two and three inertias and of uniform chains (e.g. Ker Wilson,
*Practical Solution of Torsional Vibration Problems*, vol. 1); openTorsion's internal-combustion
engine example (examples/ICE_example.py, data and provenance in tests/data/opentorsion_ice_example.json);
Friswell et al., *Dynamics of Rotating Machines* (2010), examples as openTorsion's own tests
(opentorsion/tests/tests.py) transcribe them.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import assert_published
from numpy.testing import assert_allclose

from flyopt.machine.torsion import (
    Inertia,
    Spring,
    TorsionalModel,
    chain,
    critical_speed,
    critical_speeds,
    damped_eigenvalues,
    forced_response,
    harmonic_response,
    modal_damping,
    modes,
    rayleigh_damping,
    torque_orders,
)

ICE = json.loads((Path(__file__).resolve().parents[1] / "data" / "opentorsion_ice_example.json").read_text())


# --- (1) closed forms ----------------------------------------------------------------------------------------------


def test_two_inertias_closed_form():
    """omega^2 = k (J1 + J2) / (J1 J2), plus the rigid-body mode at 0 Hz kept apart."""
    j1, j2, k = 211.4, 8.3, 9.775e6
    found = modes(chain([j1, j2], [k]))
    assert_allclose(found.omega, [math.sqrt(k * (j1 + j2) / (j1 * j2))], rtol=1e-13)
    assert found.rigid_shapes.shape == (2, 1)
    assert_allclose(found.all_frequencies_hz, [0.0, found.frequencies_hz[0]], rtol=0)
    # the node: the shape's amplitudes are in the inverse ratio of the inertias, opposite in sign
    phi = found.shapes[:, 0]
    assert_allclose(phi[0] / phi[1], -j2 / j1, rtol=1e-12)
    # openTorsion's test_shaft: the same pair gives 176.1 Hz
    assert_published(found.frequencies_hz[0], "176.1")


def test_three_inertias_closed_form():
    """Free J1-k1-J2-k2-J3: J1 J2 J3 w^4 - [k1 J3 (J1+J2) + k2 J1 (J2+J3)] w^2 + k1 k2 (J1+J2+J3) = 0."""
    j1, j2, j3, k1, k2 = 3.0, 0.5, 7.0, 2.0e5, 4.5e5
    a = j1 * j2 * j3
    b = k1 * j3 * (j1 + j2) + k2 * j1 * (j2 + j3)
    c = k1 * k2 * (j1 + j2 + j3)
    root = math.sqrt(b * b - 4 * a * c)
    expected = np.sqrt([(b - root) / (2 * a), (b + root) / (2 * a)])
    found = modes(chain([j1, j2, j3], [k1, k2]))
    assert_allclose(found.omega, expected, rtol=1e-12)
    m = np.diag([j1, j2, j3])
    assert_allclose(found.shapes.T @ m @ found.shapes, np.eye(2), atol=1e-14)
    assert_allclose(found.rigid_shapes.T @ m @ found.shapes, np.zeros((1, 2)), atol=1e-14)


@pytest.mark.parametrize("n", [2, 5, 12])
def test_uniform_free_chain(n):
    """n equal inertias J and shafts k, both ends free: omega_j = 2 sqrt(k/J) sin(j pi / 2n), j = 1..n-1."""
    j, k = 0.25, 4.0e4
    found = modes(chain([j] * n, [k] * (n - 1)))
    expected = 2 * math.sqrt(k / j) * np.sin(np.arange(1, n) * math.pi / (2 * n))
    assert_allclose(found.omega, expected, rtol=1e-12)


@pytest.mark.parametrize("n", [1, 4, 9])
def test_uniform_chain_clamped_at_one_end(n):
    """Clamped through k at one end, free at the other: omega_j = 2 sqrt(k/J) sin((2j-1) pi / (2(2n+1)))."""
    j, k = 1.5, 3.0e3
    model = TorsionalModel(
        [Inertia(i, j) for i in range(n)], [Spring(0, None, k)] + [Spring(i, i + 1, k) for i in range(n - 1)]
    )
    found = modes(model)
    assert found.rigid_shapes.shape == (n, 0)
    expected = 2 * math.sqrt(k / j) * np.sin((2 * np.arange(1, n + 1) - 1) * math.pi / (2 * (2 * n + 1)))
    assert_allclose(found.omega, expected, rtol=1e-12)


def test_friswell_example_971_chain():
    """Five inertias in a free chain; 81.21, 141.21, 378.95, 536.36 Hz (openTorsion's test_friswell_ex971)."""
    found = modes(chain([3.5e-3, 3.5e-3, 3.5e-3, 0.15, 0.05], [12e3, 12e3, 14e3, 10e3]))
    for value, printed in zip(found.frequencies_hz, ["81.21", "141.21", "378.95", "536.36"], strict=True):
        assert_published(value, printed)


def test_friswell_branched_tree_through_a_gear_pair():
    """A motor drives two rotors through a 1:1 gear pair (both wheels one node): 425.4, 634.1, 3247.2 Hz."""
    i_m, i_r, i_g = 400e-6, 700e-6, 25e-6
    model = TorsionalModel(
        [Inertia(0, i_m), Inertia(1, i_g), Inertia(1, i_g, ratio=-1.0), Inertia(2, i_r, ratio=-1.0), Inertia(3, i_r)],
        [Spring(0, 1, 1e4), Spring(1, 2, 5e3, ratio=-1.0), Spring(1, 3, 5e3)],
    )
    for value, printed in zip(modes(model).frequencies_hz, ["425.4", "634.1", "3247.2"], strict=True):
        assert_published(value, printed)


def test_friswell_example_963_geared_shafts():
    """Gears of radii 0.5 m and 0.8 m reflect J r^2 and k r^2 (r = -0.625): 10.304, 20.479, 24.423 Hz."""

    def stiffness(length, diameter):  # solid steel shaft, G = 68 GPa
        return 68e9 * math.pi * diameter**4 / (32 * length)

    r = 0.5 / 0.8
    model = TorsionalModel(
        [
            Inertia(0, 3200.0),
            Inertia(1, 200.0),  # gear 1 on the input shaft
            Inertia(1, 200.0, ratio=-1.0),  # gear 2 meshing with it, same radius
            Inertia(1, 800.0, ratio=-r),  # gear 3 meshing with gear 1
            Inertia(1, 800.0, ratio=r),  # gear 4 meshing with gear 2
            Inertia(2, 450.0, ratio=-r),
            Inertia(3, 450.0, ratio=r),
        ],
        [
            Spring(0, 1, stiffness(2.5, 0.2)),
            Spring(1, 2, stiffness(3.5, 0.25), -r),
            Spring(1, 3, stiffness(3.5, 0.25), r),
        ],
    )
    for value, printed in zip(modes(model).frequencies_hz, ["10.304", "20.479", "24.423"], strict=True):
        assert_published(value, printed)


def test_reflection_is_independent_of_the_reference_shaft():
    """One geared train seen from its motor shaft and from its output shaft: same frequencies, same physical
    shaft torques for the same physical excitation."""
    i = 3.2  # output turns 1/3.2 of the motor speed
    j_motor, j_pinion, j_wheel, j_fly = 0.08, 0.004, 0.9, 12.0
    k_coupling, k_shaft = 4.0e4, 2.5e5

    def train(ratio_motor, ratio_output):
        return TorsionalModel(
            [
                Inertia(0, j_motor, ratio_motor),
                Inertia(1, j_pinion, ratio_motor),
                Inertia(1, j_wheel, ratio_output),
                Inertia(2, j_fly, ratio_output),
            ],
            [Spring(0, 1, k_coupling, ratio_motor), Spring(1, 2, k_shaft, ratio_output)],
        )

    seen_from_output, seen_from_motor = train(i, 1.0), train(1.0, 1.0 / i)
    assert_allclose(modes(seen_from_output).omega, modes(seen_from_motor).omega, rtol=1e-12)
    assert_allclose(seen_from_output.mass_matrix[0, 0], j_motor * i**2, rtol=1e-15)
    assert_allclose(seen_from_output.stiffness_matrix[0, 0], k_coupling * i**2, rtol=1e-15)
    angle = np.arange(64) * 2 * math.pi / 64
    orders = torque_orders(angle, 300.0 + 80.0 * np.cos(angle) + 25.0 * np.sin(2 * angle + 0.4))
    # the torque acts on the flywheel's shaft turning at 500 rpm
    a = forced_response(seen_from_output, orders, 2, 500.0, ratio=1.0)
    b = forced_response(seen_from_motor, orders, 2, 500.0, ratio=1.0 / i)
    assert_allclose(a.shaft_torques, b.shaft_torques, rtol=1e-10)
    # and the twisting angle of the motor coupling, in radians of the motor shaft, is the same
    assert_allclose(i * a.angles[0], b.angles[0], rtol=1e-10)


# --- (2) openTorsion's engine example --------------------------------------------------------------------------------


def _ice_model():
    return chain(
        ICE["inertias_kgm2"], ICE["stiffnesses_Nm_per_rad"], absolute_damping=ICE["absolute_damping_Nms_per_rad"]
    )


def test_opentorsion_ice_example_undamped_frequencies():
    """The undamped modes match openTorsion 0.3.2's to 1e-6 (they agree to round-off) and its printed digits."""
    found = modes(_ice_model())
    reference = ICE["opentorsion_0_3_2"]["undamped_hz"]["values"]
    assert_allclose(found.frequencies_hz, reference, rtol=1e-6)
    assert found.rigid_shapes.shape == (9, 1)
    assert found.all_frequencies_hz[0] == 0.0
    for value, printed in zip(found.frequencies_hz, ICE["printed"]["frequencies_hz"], strict=False):
        assert_published(value, f"{printed:.2f}")


def test_opentorsion_ice_example_order6_critical_speed_of_mode1():
    """60 f_1 / 6 = 2165.836 rpm: openTorsion's value to 1e-6, 2166 rpm as printed."""
    f1 = modes(_ice_model()).frequencies_hz[0]
    speed = critical_speed(f1, 6)
    assert_allclose(speed, 60 * ICE["opentorsion_0_3_2"]["undamped_hz"]["values"][0] / 6, rtol=1e-6)
    assert_published(speed, str(ICE["printed"]["critical_speed_rpm_mode1_order6"]))


def test_opentorsion_ice_example_with_its_dampers():
    """openTorsion's modal_analysis (and its Campbell diagram) take |lambda| of the damped state matrix: with the
    example's 2 N m s/rad at each cylinder, 216.5767 Hz, not the undamped 216.5836 Hz (3e-5 apart, both print
    216.58). damped_eigenvalues reproduces its |lambda| and damping ratios to 1e-6."""
    lam = damped_eigenvalues(_ice_model())
    reference = ICE["opentorsion_0_3_2"]
    assert_allclose(np.abs(lam) / (2 * math.pi), reference["damped_abs_lambda_hz"]["values"], rtol=1e-6)
    assert_allclose(-lam.real / np.abs(lam), reference["damping_ratios"], rtol=1e-6)
    for value, printed in zip(np.abs(lam) / (2 * math.pi), ICE["printed"]["frequencies_hz"], strict=False):
        assert_published(value, f"{printed:.2f}")
    assert_published(critical_speed(abs(lam[0]) / (2 * math.pi), 6), "2166")


# --- damping -------------------------------------------------------------------------------------------------------


def test_rayleigh_damping_ratios():
    """C = alpha M + beta K damps mode m by zeta_m = alpha / (2 omega_m) + beta omega_m / 2."""
    model = chain([2.0, 0.7, 1.1, 5.0], [3e4, 5e4, 2e4])
    alpha, beta = 1.5, 2e-5
    omega = modes(model).omega
    lam = damped_eigenvalues(model, rayleigh_damping(model, alpha, beta))
    assert_allclose(np.abs(lam), omega, rtol=1e-10)
    assert_allclose(-lam.real / np.abs(lam), alpha / (2 * omega) + beta * omega / 2, rtol=1e-9)


def test_modal_damping_ratios():
    """C = M Phi diag(2 zeta omega) Phi^T M keeps the undamped omega_m and gives each mode its zeta_m."""
    model = chain([2.0, 0.7, 1.1, 5.0], [3e4, 5e4, 2e4])
    zeta = [0.02, 0.05, 0.1]
    lam = damped_eigenvalues(model, modal_damping(model, zeta))
    assert_allclose(np.abs(lam), modes(model).omega, rtol=1e-10)
    assert_allclose(-lam.real / np.abs(lam), zeta, rtol=1e-9)
    assert_allclose(modal_damping(model, 0.03), modal_damping(model, [0.03] * 3), rtol=1e-15)


# --- (3) forced response ------------------------------------------------------------------------------------------


def test_forced_response_of_two_inertias_closed_form():
    """Undamped J1-k-J2 driven at J1 by T cos(q Omega t): x2 = T k / D, x1 = T (k - W^2 J2) / D with
    D = W^4 J1 J2 - W^2 k (J1 + J2); the shaft carries T J2 / (J1 + J2) / (1 - (W/omega_n)^2)."""
    j1, j2, k = 0.6, 4.0, 8.0e4
    model = chain([j1, j2], [k])
    omega_n = math.sqrt(k * (j1 + j2) / (j1 * j2))
    speed = 600.0  # rpm
    angle = np.linspace(0.0, 4 * math.pi, 241)  # a two-revolution cycle, its end sample included
    c_half, c_2, c_3 = 40.0 * np.exp(0.3j), 120.0 * np.exp(-1.1j), 15.0
    torque = (
        200.0
        + np.real(c_half * np.exp(0.5j * angle))
        + np.real(c_2 * np.exp(2j * angle))
        + np.real(c_3 * np.exp(3j * angle))
    )
    orders = torque_orders(angle, torque, cycle_revolutions=2.0)
    assert_allclose(orders.mean, 200.0, rtol=1e-13)
    assert_allclose(orders.orders[:6], [0.5, 1.0, 1.5, 2.0, 2.5, 3.0], rtol=0)
    expected = np.zeros(orders.orders.size, dtype=complex)
    expected[[0, 3, 5]] = [c_half, c_2, c_3]
    assert_allclose(orders.amplitudes, expected, atol=1e-12)
    assert_allclose(orders.torque(angle), torque, atol=1e-11)

    response = forced_response(model, orders, 0, speed)
    w = orders.orders * 2 * math.pi * speed / 60.0
    assert_allclose(response.omega, w, rtol=1e-15)
    d = w**4 * j1 * j2 - w**2 * k * (j1 + j2)
    t = orders.amplitudes
    assert_allclose(response.angles[0], t * (k - w**2 * j2) / d, rtol=1e-10, atol=1e-18)
    assert_allclose(response.angles[1], t * k / d, rtol=1e-10, atol=1e-18)
    through = t * j2 / (j1 + j2) / (1 - (w / omega_n) ** 2)
    assert_allclose(response.shaft_torques[0], through, rtol=1e-10, atol=1e-12)
    assert_allclose(response.shaft_torque_bound[0], np.abs(through).sum(), rtol=1e-10)


def test_harmonic_response_refuses_the_undamped_rigid_mode_at_rest():
    with pytest.raises(ValueError, match="natural frequency"):
        harmonic_response(chain([1.0, 2.0], [1e3]), 0.0, np.array([1.0, 0.0]))


def test_torque_orders_phase_follows_the_first_angle():
    """Samples starting at phi_0 != 0 give the same series: T(phi) = 5 cos(phi - 0.2)."""
    angle = 1.0 + np.arange(32) * 2 * math.pi / 32
    orders = torque_orders(angle, 5.0 * np.cos(angle - 0.2), max_order=3)
    assert_allclose(orders.orders, [1.0, 2.0, 3.0], rtol=0)
    assert_allclose(orders.amplitudes, [5.0 * np.exp(-0.2j), 0.0, 0.0], atol=1e-13)


# --- critical speeds and margins ----------------------------------------------------------------------------------


def test_critical_speeds_and_margins():
    """n_c = 60 f / q and the separation from the running range [900, 1100] rpm."""
    found = critical_speeds([20.0, 50.0], [1.0, 2.5], (900.0, 1100.0))
    assert [(c.mode, c.order) for c in found] == [(1, 1.0), (1, 2.5), (2, 1.0), (2, 2.5)]
    assert_allclose([c.speed_rpm for c in found], [1200.0, 480.0, 3000.0, 1200.0], rtol=1e-15)
    assert_allclose([c.margin for c in found], [100 / 1100, 420 / 900, 1900 / 1100, 100 / 1100], rtol=1e-14)
    assert not any(c.in_range for c in found)
    inside = critical_speeds([16.0], [1.0], (900.0, 1100.0))[0]
    assert inside.in_range and inside.margin == 0.0 and inside.speed_rpm == pytest.approx(960.0, rel=1e-15)


def test_critical_speeds_of_many_pairs_are_each_pairs_own():
    """All pairs at once (arrays) give, bit for bit, what n_c = 60 f / q of each pair and its margin give one at a
    time, in Python floats; a bad entry is named as critical_speed names it."""
    rng = np.random.default_rng(7)
    f, q = rng.uniform(5.0, 900.0, 7), np.concatenate([rng.uniform(0.25, 30.0, 40), [60.0 * 16.0 / 1000.0]])
    low, high = 900.0, 1100.0
    found = iter(critical_speeds(f, q, (low, high)))
    for mode, fi in enumerate(f, start=1):
        for qk in q:
            c = next(found)
            speed = 60.0 * float(fi) / float(qk)
            margin = (speed - high) / high if speed > high else (low - speed) / low if speed < low else 0.0
            assert (c.mode, c.order, c.frequency_hz) == (mode, float(qk), float(fi))
            assert c.speed_rpm == speed and c.margin == margin and c.in_range == (low <= speed <= high)
    with pytest.raises(ValueError, match="order = 0.0"):
        critical_speeds([10.0, 20.0], [1.0, 0.0], (low, high))
    with pytest.raises(ValueError, match="frequency_hz = nan"):
        critical_speeds([10.0, float("nan")], [1.0], (low, high))


# --- (4) validation -------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("inertias", "stiffnesses", "message"),
    [
        ([1.0, 0.0], [1e3], r"inertias\[1\] = 0.0 must be a finite number > 0"),
        ([1.0, -2.0], [1e3], r"inertias\[1\] = -2.0"),
        ([1.0, float("nan")], [1e3], r"inertias\[1\] = nan"),
        ([1.0, 2.0], [0.0], r"stiffnesses\[0\] = 0.0 must be a finite number > 0"),
        ([1.0, 2.0], [-5.0], r"stiffnesses\[0\] = -5.0"),
        ([1.0, 2.0, 3.0], [1e3], "a chain of 3 inertias needs 2 stiffnesses, got 1"),
        ([1.0, 2.0], [1e3, 1e3], "a chain of 2 inertias needs 1 stiffnesses, got 2"),
        ([], [], "at least one inertia"),
    ],
)
def test_chain_rejects_bad_input(inertias, stiffnesses, message):
    with pytest.raises(ValueError, match=message):
        chain(inertias, stiffnesses)


def test_chain_rejects_mismatched_options():
    with pytest.raises(ValueError, match="ratios needs 2 values"):
        chain([1.0, 2.0], [1e3], ratios=[1.0])
    with pytest.raises(ValueError, match="shaft_damping needs 1 values"):
        chain([1.0, 2.0], [1e3], shaft_damping=[0.1, 0.1])
    with pytest.raises(ValueError, match="a gear or belt stage is rigid"):
        chain([1.0, 2.0], [1e3], ratios=[1.0, 2.0])


@pytest.mark.parametrize(
    ("inertias", "springs", "message"),
    [
        ([Inertia(0, 1.0), Inertia(2, 1.0)], [Spring(0, 2, 1.0)], r"node\(s\) \[1\] carry no inertia"),
        ([Inertia(0, 1.0), Inertia(1, 1.0)], [Spring(0, 3, 1.0)], "joins node 3, which is not one of 0..1"),
        ([Inertia(0, 1.0), Inertia(1, 1.0)], [Spring(1, 1, 1.0)], "joins node 1 to itself"),
        ([Inertia(0, 1.0), Inertia(1, 1.0), Inertia(2, 1.0)], [Spring(0, 1, 1.0)], "2 separate pieces"),
        ([Inertia(0, 1.0, ratio=0.0)], [], r"inertias\[0\].ratio = 0.0 must be a finite, non-zero speed ratio"),
        ([Inertia(0, 1.0, damping=-1.0)], [], r"inertias\[0\].damping = -1.0 must be a finite number >= 0"),
        ([Inertia(0, 1.0), Inertia(1, 1.0)], [Spring(0, 1, -1.0)], r"springs\[0\].stiffness = -1.0"),
        ([Inertia(-1, 1.0)], [], "inertia nodes must be integers >= 0"),
    ],
)
def test_model_rejects_bad_input(inertias, springs, message):
    with pytest.raises(ValueError, match=message):
        TorsionalModel(inertias, springs)


def test_other_functions_reject_bad_input():
    model = chain([1.0, 2.0], [1e3])
    angle = np.arange(8) * 2 * math.pi / 8
    orders = torque_orders(angle, np.cos(angle))
    with pytest.raises(ValueError, match="node 2 is not one of 0..1"):
        forced_response(model, orders, 2, 100.0)
    with pytest.raises(ValueError, match="speed_rpm = 0.0"):
        forced_response(model, orders, 0, 0.0)
    with pytest.raises(ValueError, match="one length"):
        torque_orders(angle, np.cos(angle)[:-1])
    with pytest.raises(ValueError, match="equally spaced"):
        torque_orders(angle**1.1, np.cos(angle))
    with pytest.raises(ValueError, match="one cycle is"):
        torque_orders(angle[:5], np.cos(angle[:5]))
    with pytest.raises(ValueError, match="n_max >= n_min"):
        critical_speeds([10.0], [1.0], (1000.0, 900.0))
    with pytest.raises(ValueError, match="order = 0"):
        critical_speed(10.0, 0)
    with pytest.raises(ValueError, match="zeta needs one ratio or 1"):
        modal_damping(model, [0.1, 0.2])
    with pytest.raises(ValueError, match="2 x 2"):
        damped_eigenvalues(model, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="one amplitude per node"):
        harmonic_response(model, 10.0, np.zeros(3))
