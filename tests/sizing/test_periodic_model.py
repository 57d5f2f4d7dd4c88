"""The periodic model's numeric helpers (flyopt.sizing.periodic_model)."""

import numpy as np
import pytest

from flyopt.cycle.torque import Constant, MotorTorque
from flyopt.machine.motor import InductionMotor
from flyopt.machine.reduce import NetTorque
from flyopt.sizing.periodic_model import PeriodicModel


def _motor_model():
    motor = InductionMotor(rated_power=5500.0, rated_speed=152.4, synchronous_speed=157.08)
    net = NetTorque(MotorTorque(motor, 120.0, 0.9, "kloss"), Constant(300.0), work=2000.0)
    return motor, PeriodicModel(net, 2.0, 2 * np.pi)


def test_torque_and_its_slope_never_share_a_mapped_function():
    # the torque and ∂M/∂ω were mapped into one dictionary keyed by the array's size: after the
    # torque was evaluated on an array of some size, the slope on an array of that size returned the
    # torque (the one-solve's stiffness then read the torque as a slope)
    motor, model = _motor_model()
    phi = model.grid_angles()[:, :-1]
    omega = np.full(phi.shape, 1.25)
    model.torque(phi, omega)
    slope = model.torque_slope(phi, omega)
    # the Kloss curve's slope by central differences, reduced to the crank: d(i η M(i ω))/dω
    h = 1e-6
    expected = 120.0 * 0.9 * (motor.torque(120.0 * (1.25 + h), "kloss") - motor.torque(120.0 * (1.25 - h), "kloss"))
    expected /= 2 * h
    np.testing.assert_allclose(slope, expected, rtol=1e-7)
    assert not np.allclose(slope, model.torque(phi, omega))


def test_quasi_static_delta_of_a_dc_motor_against_its_closed_form():
    # M_stall (1 − i ω/ω_0) i η = M_r(φ) at every angle: ω(φ) = ω_0/i (1 − M_r/(i η M_stall)), linear in M_r,
    # so δ = 2 (ω(M_min) − ω(M_max)) / (ω(M_min) + ω(M_max)) over the load's extremes
    from flyopt.cycle.torque import PiecewiseLinear
    from flyopt.machine.motor import DCMotor
    from flyopt.sizing.periodic import quasi_static_delta

    w0, stall, i, eta = 150.0, 80.0, 100.0, 0.9
    load = PiecewiseLinear(np.array([0.0, 1.0, 2.5, 4.0, 2 * np.pi]), np.array([1500.0, 4200.0, 900.0, 2600.0, 1500.0]))
    net = NetTorque(MotorTorque(DCMotor(w0, stall), i, eta), load, work=1e4)
    model = PeriodicModel(net, 5.0, 2 * np.pi, load.breakpoints())

    def speed(m):
        return w0 / i * (1 - m / (i * eta * stall))

    # the model takes the torques inside each piece (a step from its own side), so the load's extremes
    # are those at its inner angles: the table interpolated there by numpy, then the closed form
    loads = np.interp(model.inner_angles, load.angles, load.values)
    fast, slow = speed(loads.min()), speed(loads.max())
    assert quasi_static_delta(model, 1.0) == pytest.approx((fast - slow) / (0.5 * (fast + slow)), rel=1e-13)
    assert (fast - slow) / (0.5 * (fast + slow)) == pytest.approx(0.70967741935, rel=1e-9)  # 900 and 4200 N*m


def test_quasi_static_delta_refuses_past_a_motors_breakdown():
    # a load above the Kloss curve's breakdown torque at the crank: no balance on the stable branch
    motor = InductionMotor(rated_power=5500.0, rated_speed=152.4, synchronous_speed=157.08)
    from flyopt.sizing.periodic import quasi_static_delta

    too_much = 1.01 * motor.breakdown_torque * 120.0 * 0.9
    net = NetTorque(MotorTorque(motor, 120.0, 0.9, "kloss"), Constant(too_much), work=2000.0)
    assert quasi_static_delta(PeriodicModel(net, 2.0, 2 * np.pi), 1.25) is None
