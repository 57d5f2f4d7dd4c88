"""The torsional check on the cycle's torque (flyopt.design.shaft.torsional) against closed forms and openTorsion.

The model under it (flyopt.machine.torsion) has its own tests (tests/machine/test_torsion.py); these check what
this module adds - the orders of flyopt's net torque curves, the running range, the orders present, the critical
speeds and Campbell crossings, the forced response over speed - against references that do not come from it:
Fourier coefficients known analytically, closed-form natural frequencies and steady-state amplitudes, and
openTorsion's engine example (examples/ICE_example.py at openTorsion commit 88ab7893d24ce9bf6a03725e246d043c6fd9e657,
transcribed with openTorsion 0.3.2's own output in tests/data/opentorsion_ice_example.json).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import assert_published
from numpy.testing import assert_allclose

from flyopt.cycle.expression import Expression
from flyopt.cycle.indicator import energy_indicator
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.design.shaft.torsional import (
    campbell,
    function_orders,
    net_torque_orders,
    present_orders,
    response_over_speed,
    running_range_rpm,
    torsional_check,
)
from flyopt.io.scene import load
from flyopt.machine.reduce import reduce
from flyopt.machine.torsion import Inertia, Spring, TorsionalModel, chain

ICE = json.loads((Path(__file__).resolve().parents[1] / "data" / "opentorsion_ice_example.json").read_text())
OT_HZ = ICE["opentorsion_0_3_2"]["undamped_hz"]["values"]


def _ice_model():
    return chain(ICE["inertias_kgm2"], ICE["stiffnesses_Nm_per_rad"])


# --- the orders of flyopt's torque curves ----------------------------------------------------------------------------


def test_net_torque_orders_of_a_four_stroke_expression():
    """M_d - M_r = 120 cos(phi/2) + 80 sin(3 phi) + 30 cos(6 phi + 0.4) over 4 pi: the series is exact (trig
    polynomials far below N/2), so c_0.5 = 120, c_3 = -80 i, c_6 = 30 e^{0.4 i} and nothing else, to round-off."""
    driving = ExpressionTorque(Expression("500 + 120*cos(phi/2) + 80*sin(3*phi) + 30*cos(6*phi + 0.4)"), 1.0, "test")
    found = net_torque_orders(driving, Constant(500.0), 4 * math.pi, max_order=10)
    assert_allclose(found.orders[:4], [0.5, 1.0, 1.5, 2.0], rtol=0, atol=0)
    expected = np.zeros(found.orders.size, dtype=complex)
    expected[found.orders == 0.5] = 120.0
    expected[found.orders == 3.0] = -80j
    expected[found.orders == 6.0] = 30.0 * np.exp(0.4j)
    assert_allclose(found.amplitudes, expected, rtol=0, atol=1e-10)
    assert abs(found.mean) < 1e-10
    assert_allclose(present_orders(found), [0.5, 3.0, 6.0], rtol=0, atol=0)


def test_net_torque_orders_of_a_table_with_steps():
    """A square wave of a table: M_d = T on (pi/2, 3 pi/2), -T elsewhere, against M_r = 0. Its series is
    c_k = -(4T/(pi k)) (-1)^((k-1)/2) for odd k, 0 for even k. Sampled at N = 4096 with the mean of the limits at
    the steps (grid points), the sampled sum is the trapezoidal rule: its error in c_k is (pi k / N)^2 / 3 relative
    for the first orders, 5e-6 at k = 5. Taking one limit only would err by 2T/N (5e-4 of T): the test tells them apart.
    """
    t = 1000.0
    half = math.pi / 2
    table = PiecewiseLinear(
        np.array([0.0, half, half, 3 * half, 3 * half, 2 * math.pi]), np.array([-t, -t, t, t, -t, -t])
    )
    found = net_torque_orders(table, Constant(0.0), 2 * math.pi, max_order=5)
    k = np.arange(1, 6)
    expected = np.where(k % 2 == 1, -(4 * t / (math.pi * k)) * (-1.0) ** ((k - 1) // 2), 0.0)
    assert_allclose(found.orders, k, rtol=0, atol=0)
    assert_allclose(found.amplitudes.real, expected, rtol=6e-6, atol=1e-9 * t)
    assert_allclose(found.amplitudes.imag, 0.0, atol=1e-9 * t)
    assert abs(found.mean) < 1e-9 * t


def test_net_torque_orders_of_a_four_stroke_scene_give_its_energy_fluctuation():
    """problems/four-stroke-engine.toml (a 5-deg gas-torque table over 720 deg against the unknown constant load the
    work balance solves): half orders; the mean is the balance's zero (to the trapezoidal rule's O(h^2) at the table's
    kinks, 1e-4 N*m against orders of up to 160 N*m); and the energy the series integrates to,
    dE(phi) = sum_q Re(c_q e^{iq phi} / (iq)), fluctuates by the exact energy indicator's A_max (950.97 J), to the
    series cut at order 200 and the 20001-point search of its extremes (2e-6 found)."""
    machine = reduce(load("problems/four-stroke-engine.toml"))
    found = net_torque_orders(machine.driving, machine.resisting, machine.cycle_angle, max_order=200)
    assert_allclose(found.orders[:3], [0.5, 1.0, 1.5], rtol=0, atol=0)
    assert abs(found.mean) < 1e-3
    phi = np.linspace(0.0, machine.cycle_angle, 20001)
    energy = np.real(np.exp(1j * np.multiply.outer(phi, found.orders)) @ (found.amplitudes / (1j * found.orders)))
    a_max = energy_indicator(machine.driving, machine.resisting, machine.cycle_angle).a_max
    assert_allclose(energy.max() - energy.min(), a_max, rtol=1e-5)


def test_function_orders_of_a_callable_over_two_revolutions():
    """A callable torque over a 4 pi cycle: orders are k/2 per revolution."""
    found = function_orders(lambda phi: 40.0 + 7.0 * np.sin(1.5 * phi - 0.3), 4 * math.pi, samples=64)
    assert_allclose(found.orders, np.arange(1, 32) / 2, rtol=0, atol=0)
    assert_allclose(found.amplitudes[found.orders == 1.5], [7.0 * np.exp(-1j * (0.3 + math.pi / 2))], atol=1e-12)
    assert_allclose(found.mean, 40.0, rtol=1e-14)


def test_running_range_is_the_cycles_speed_range():
    """omega_m (1 -/+ delta/2) of a shaft turning 3 times the reference, in rpm: 60 omega / (2 pi)."""
    low, high = running_range_rpm(50.0, 0.04, ratio=3.0)
    assert_allclose([low, high], [150.0 * 0.98 * 30 / math.pi, 150.0 * 1.02 * 30 / math.pi], rtol=1e-15)


# --- natural frequencies: closed forms -------------------------------------------------------------------------------


def test_two_and_three_inertias_closed_forms_through_the_check():
    j1, j2, j3, k1, k2 = 2.0, 0.5, 1.3, 3.0e4, 1.1e4
    two = torsional_check(chain([j1, j2], [k1]), function_orders(np.cos, 2 * math.pi, samples=16), (100.0, 200.0))
    assert_allclose(two.modes.omega, [math.sqrt(k1 * (j1 + j2) / (j1 * j2))], rtol=1e-13)
    # J1 J2 J3 w^4 - [k1 J3 (J1 + J2) + k2 J1 (J2 + J3)] w^2 + k1 k2 (J1 + J2 + J3) = 0
    b = k1 * j3 * (j1 + j2) + k2 * j1 * (j2 + j3)
    roots = np.roots([j1 * j2 * j3, -b, k1 * k2 * (j1 + j2 + j3)])
    three = torsional_check(chain([j1, j2, j3], [k1, k2]), function_orders(np.cos, 2 * math.pi, samples=16), (1, 2))
    assert_allclose(three.modes.omega, np.sqrt(np.sort(roots.real)), rtol=1e-13)


def test_geared_two_inertias_against_the_reflected_closed_form():
    """A motor J_m turning i = 4 times the flywheel's shaft drives, through a rigid gear pair, a shaft of stiffness k
    to the flywheel J_f. In the flywheel shaft's angle u = theta_m / i the motor has J_m i^2, so
    omega^2 = k (J_m i^2 + J_f) / (J_m i^2 J_f), in whichever shaft the model is reflected to."""
    i, j_m, j_f, k = 4.0, 0.05, 9.0, 2.0e5
    expected = math.sqrt(k * (j_m * i**2 + j_f) / (j_m * i**2 * j_f))
    orders = function_orders(np.cos, 2 * math.pi, samples=16)
    for ref_ratio_motor, ref_ratio_fly in ((i, 1.0), (1.0, 1.0 / i)):
        model = TorsionalModel(
            [Inertia(0, j_m, ref_ratio_motor), Inertia(1, j_f, ref_ratio_fly)], [Spring(0, 1, k, ref_ratio_fly)]
        )
        assert_allclose(torsional_check(model, orders, (1.0, 2.0)).modes.omega, [expected], rtol=1e-13)


# --- openTorsion's engine example --------------------------------------------------------------------------------------


def test_opentorsion_engine_critical_speeds_of_the_orders_present():
    """openTorsion's ICE example (216.58, 592.74, 984.92 Hz; order 6 meets mode 1 at 2166 rpm, as printed), to 1e-6
    of openTorsion 0.3.2's own frequencies. A four-stroke torque of orders 3, 4.5 and 6 with a 0.5 % order 1.5: the
    order 1.5 is not present at 1 %; order 6 meets mode 1 at 60 f_1 / 6, 3.1 % above a 2000-2100 rpm range."""

    def torque(phi):
        return 900.0 * np.cos(3 * phi) + 400.0 * np.cos(4.5 * phi) + 250.0 * np.sin(6 * phi) + 4.5 * np.cos(1.5 * phi)

    check = torsional_check(_ice_model(), function_orders(torque, 4 * math.pi, samples=256), (2000.0, 2100.0))
    assert_allclose(check.modes.frequencies_hz, OT_HZ, rtol=1e-6)
    for value, printed in zip(check.modes.frequencies_hz, ICE["printed"]["frequencies_hz"], strict=False):
        assert_published(value, f"{printed:.2f}")
    assert_allclose(check.orders, [3.0, 4.5, 6.0], rtol=0, atol=0)
    assert len(check.critical) == 8 * 3
    mode1_order6 = next(c for c in check.critical if c.mode == 1 and c.order == 6.0)
    assert_published(mode1_order6.speed_rpm, str(ICE["printed"]["critical_speed_rpm_mode1_order6"]))
    assert_allclose(mode1_order6.speed_rpm, 60 * OT_HZ[0] / 6, rtol=1e-6)
    assert_allclose(mode1_order6.margin, (60 * OT_HZ[0] / 6 - 2100.0) / 2100.0, rtol=1e-6)
    assert check.nearest == mode1_order6 and not check.in_range


def test_opentorsion_engine_campbell_data():
    """Between 0 and 3000 rpm order 6 crosses mode 1 only (mode 2 needs 5927 rpm), at 2166 rpm as printed."""
    diagram = campbell(_ice_model(), [6.0, 3.0], np.linspace(0.0, 3000.0, 31), (2000.0, 2100.0))
    assert_allclose(diagram.frequencies_hz, OT_HZ, rtol=1e-6)
    assert_allclose(diagram.order_lines_hz[:, -1], [300.0, 150.0], rtol=1e-15)
    assert [(c.mode, c.order) for c in diagram.crossings] == [(1, 6.0)]
    assert_published(diagram.crossings[0].speed_rpm, "2166")


# --- forced response ---------------------------------------------------------------------------------------------------


def test_forced_response_of_one_inertia_on_a_damped_shaft():
    """J on a shaft k to the frame with a damper c at J, T0 cos(2 phi): |x| = T0 / sqrt((k - J W^2)^2 + (c W)^2),
    W = 2 (2 pi n / 60); the shaft carries k |x|. Below, near and above resonance (omega_n = 100 rad/s: 477 rpm)."""
    j, k, c, t0 = 2.0, 2.0e4, 30.0, 150.0
    model = TorsionalModel([Inertia(0, j, damping=c)], [Spring(0, None, k)])
    speeds = np.array([200.0, 470.0, 477.46, 900.0])
    found = response_over_speed(
        model, function_orders(lambda p: t0 * np.cos(2 * p), 2 * math.pi, samples=16), 0, speeds
    )
    w = 2 * 2 * math.pi * speeds / 60
    amplitude = t0 / np.sqrt((k - j * w**2) ** 2 + (c * w) ** 2)
    assert_allclose(found.angles[0, found.orders == 2.0, :][0], amplitude, rtol=1e-12)
    assert_allclose(found.shaft_torque_bound[0], k * amplitude, rtol=1e-10)


def test_forced_response_of_two_inertias_to_two_orders():
    """Two free inertias, a torque at J1 of orders 1.5 and 3 of a four-stroke cycle. Undamped, the shaft carries
    T_q J2/(J1+J2) / |1 - W_q^2 / omega^2| of each order (the rigid-body motion takes the rest)."""
    j1, j2, k = 0.4, 1.6, 5.0e4
    omega = math.sqrt(k * (j1 + j2) / (j1 * j2))
    orders = function_orders(lambda p: 60.0 * np.cos(1.5 * p) + 25.0 * np.sin(3 * p + 1.0), 4 * math.pi, samples=32)
    speeds = np.array([600.0, 1500.0, 3000.0])
    found = response_over_speed(chain([j1, j2], [k]), orders, 0, speeds)
    for q, t in ((1.5, 60.0), (3.0, 25.0)):
        w = q * 2 * math.pi * speeds / 60
        expected = t * j2 / (j1 + j2) / np.abs(1 - w**2 / omega**2)
        assert_allclose(found.shaft_torques[0, found.orders == q, :][0], expected, rtol=1e-10)
    assert_allclose(found.shaft_torque_bound[0], found.shaft_torques[0].sum(axis=0), rtol=1e-15)


# --- bad input ------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: function_orders(np.cos, 0.0), "cycle_angle"),
        (lambda: function_orders(np.cos, math.nan), "cycle_angle"),
        (lambda: function_orders(np.cos, 2 * math.pi, samples=3), "samples"),
        (lambda: running_range_rpm(-1.0, 0.1), "omega_mean"),
        (lambda: running_range_rpm(10.0, 2.5), "delta"),
        (lambda: running_range_rpm(10.0, 0.1, ratio=0.0), "ratio"),
        (lambda: present_orders(function_orders(np.cos, 2 * math.pi, samples=8), 1.5), "significant"),
        (lambda: campbell(_ice_model(), [6.0], [100.0, 50.0], (1.0, 2.0)), "speeds_rpm"),
        (lambda: response_over_speed(_ice_model(), function_orders(np.cos, 6.3, samples=8), 0, []), "speeds_rpm"),
    ],
)
def test_bad_input_is_refused_with_its_name(call, message):
    with pytest.raises(ValueError, match=message):
        call()
