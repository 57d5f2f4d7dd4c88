"""The periodic model's numeric helpers (flyopt.sizing.periodic_model)."""

import numpy as np

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
