"""Motor characteristics against nameplate arithmetic and the Kloss formula's defining properties."""

import math

import casadi as ca
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import optimize

from flyopt.machine.motor import DEFAULT_BREAKDOWN_RATIO, DCMotor, InductionMotor

RPM = 2 * math.pi / 60


def issue_motor(**kwargs):
    """The issue's example: 7.5 kW, 1440 rpm, synchronous 1500 rpm."""
    return InductionMotor(7500.0, 1440 * RPM, 1500 * RPM, **kwargs)


def test_induction_nameplate_rated_torque_and_slip():
    """M_n = P/ω_n = 7500/(1440·2π/60) = 49.736 N m (9550 P[kW]/n rule: 49.74); s_n = 4 %."""
    m = issue_motor()
    assert_allclose(m.rated_torque, 7500 / (1440 * RPM), rtol=1e-15)
    assert_allclose(m.rated_torque, 9549.296585513721 * 7.5 / 1440, rtol=1e-15)  # 30000/π · P[kW]/n
    assert_allclose(m.rated_slip, 0.04, rtol=1e-14)


def test_induction_linear_line_through_rated_point_and_synchronous_speed():
    """Linear model: M_n at ω_n, 0 at ω_0, and M_n/s_n = 25 M_n at rest (the issue's warning)."""
    m = issue_motor()
    assert_allclose(m.torque(1440 * RPM), m.rated_torque, rtol=1e-14)
    assert_allclose(m.torque(1500 * RPM), 0.0, atol=1e-12)
    assert_allclose(m.torque(0.0) / m.rated_torque, 25.0, rtol=1e-13)
    assert_allclose(m.slope, -m.rated_torque / (60 * RPM), rtol=1e-14)  # a few ulps of round-off


def test_kloss_curve_properties():
    """Kloss: through the rated point, its maximum (found numerically) is M_b at s_b, on the stable side.

    s_b = s_n (k + sqrt(k² − 1)); starting torque 2 M_b/(1/s_b + s_b). Tolerances: 1e-14 for
    closed forms, 1e-9 for the numerically located maximum (flat there: value to ~xatol²).
    """
    k = 2.5
    m = issue_motor(breakdown_ratio=k)
    w0 = 1500 * RPM
    assert_allclose(m.torque(1440 * RPM, "kloss"), m.rated_torque, rtol=1e-14)
    assert_allclose(m.breakdown_slip, 0.04 * (k + math.sqrt(k * k - 1)), rtol=1e-14)
    peak = optimize.minimize_scalar(
        lambda w: -m.torque(w, "kloss"), bounds=(0, w0), method="bounded", options={"xatol": 1e-10}
    )
    assert_allclose(-peak.fun, k * m.rated_torque, rtol=1e-12)
    assert_allclose(1 - peak.x / w0, m.breakdown_slip, rtol=1e-7)
    sb = m.breakdown_slip
    assert_allclose(m.starting_torque(), 2 * k * m.rated_torque / (1 / sb + sb), rtol=1e-14)
    # the rated point lies on the stable branch: torque falls with speed there
    assert m.torque(1441 * RPM, "kloss") < m.rated_torque < m.torque(1439 * RPM, "kloss")


def test_linear_model_validity_limit():
    """The linear line reaches M_b = k M_n at ω_0 − k (ω_0 − ω_n); Kloss peaks at ω_0 (1 − s_b)."""
    m = issue_motor(breakdown_ratio=2.5)
    assert_allclose(m.torque(m.linear_limit_speed), 2.5 * m.rated_torque, rtol=1e-13)
    assert_allclose(m.torque(m.breakdown_speed, "kloss"), 2.5 * m.rated_torque, rtol=1e-14)


def test_kloss_default_breakdown_ratio():
    """Default M_b/M_n = 2.5, inside NEMA design B's 175–300 %."""
    assert DEFAULT_BREAKDOWN_RATIO == 2.5
    assert issue_motor().breakdown_ratio == 2.5


def test_dc_motor_line_from_rated_point():
    """DC line through (ω_n, P/ω_n) and (ω_0, 0): stall torque M_n ω_0/(ω_0 − ω_n)."""
    m = DCMotor.from_rated(3000.0, 100.0, 120.0)
    assert_allclose(m.torque(100.0), 30.0, rtol=1e-15)
    assert_allclose(m.torque(120.0), 0.0, atol=1e-13)
    assert_allclose(m.stall_torque, 30.0 * 120 / 20, rtol=1e-15)
    assert_allclose(m.slope, -30.0 / 20, rtol=1e-15)


def test_reference_torque_keeps_power_through_the_transmission():
    """M' ω = η M(i ω) i ω: the reduced torque carries the motor's power times η."""
    m = issue_motor()
    omega_ref = 1440 * RPM / 12
    reduced = m.reference_torque(omega_ref, speed_ratio=12.0, efficiency=0.9)
    assert_allclose(reduced * omega_ref, 0.9 * m.rated_torque * 1440 * RPM, rtol=1e-14)
    assert_allclose(m.reference_torque(0.0, 12.0, 1.0, model="kloss"), 12 * m.starting_torque(), rtol=1e-14)


@pytest.mark.parametrize(
    "motor, model", [(issue_motor(), "linear"), (issue_motor(), "kloss"), (DCMotor(100.0, 50.0), None)]
)
def test_casadi_and_numpy_agree(motor, model):
    """The torque laws are the same expression in CasADi and numpy (1e-14)."""
    w = ca.SX.sym("w")
    expr = motor.torque(w) if model is None else motor.torque(w, model)
    f = ca.Function("f", [w], [expr])
    speeds = np.array([0.0, 30.0, 100.0, 150.0])
    numeric = motor.torque(speeds) if model is None else motor.torque(speeds, model)
    assert_allclose(np.asarray(f(speeds.reshape(1, -1))).ravel(), numeric, rtol=1e-14, atol=1e-12)


@pytest.mark.parametrize(
    "build, match",
    [
        (lambda: InductionMotor(7500.0, 160.0, 150.0), "must be below its synchronous speed"),
        (lambda: InductionMotor(-1.0, 150.0, 157.0), "rated_power"),
        (lambda: InductionMotor(7500.0, 150.0, 157.0, breakdown_ratio=0.9), "must exceed 1"),
        (lambda: InductionMotor(7500.0, 150.0, math.inf), "synchronous_speed"),
        (lambda: issue_motor().torque(100.0, "steinmetz"), "model 'steinmetz' is not known"),
        (lambda: issue_motor().reference_torque(1.0, efficiency=1.2), r"efficiency must lie in \(0, 1\]"),
        (lambda: DCMotor(0.0, 1.0), "no_load_speed"),
        (lambda: DCMotor.from_rated(1000.0, 120.0, 100.0), "must be below the no-load speed"),
    ],
)
def test_bad_input_raises_value_error(build, match):
    with pytest.raises(ValueError, match=match):
        build()


@pytest.mark.parametrize(
    ("motor", "field", "words"),
    [
        # the plate's speeds, said in rpm as written (they were rad/s to sixteen figures: 167.5516081914556)
        (
            'kind = "induction", rated_power = "5.5 kW", rated_speed = "1600 rpm", synchronous_speed = "1500 rpm"',
            "torque.driving.motor",
            "rated speed (1600 rpm) must be below its synchronous speed (1500 rpm)",
        ),
        (
            'kind = "dc", rated_power = "5.5 kW", rated_speed = "1600 rpm", no_load_speed = "1500 rpm"',
            "torque.driving.motor",
            "rated speed (1600 rpm) must be below the no-load speed (1500 rpm)",
        ),
        # a negative rating: its own field, as written (it said "rated_power [W] must be ... got -5500.0")
        (
            'kind = "induction", rated_power = "-5.5 kW", rated_speed = "1450 rpm", synchronous_speed = "1500 rpm"',
            "torque.driving.motor.rated_power",
            "must be positive, got '-5.5 kW'",
        ),
        (
            'kind = "dc", no_load_speed = "1500 rpm", stall_torque = "-30 N*m"',
            "torque.driving.motor.stall_torque",
            "must be positive, got '-30 N*m'",
        ),
    ],
)
def test_a_motors_bad_plate_is_said_in_the_units_written(write_scene, motor, field, words):
    import flyopt
    from flyopt.errors import SceneError

    text = (
        '[machine]\nspeed = "1450 rpm"\ndelta = 0.05\n'
        f"[torque.driving]\nmotor = {{ {motor} }}\n"
        '[torque.resisting]\npoints = [["0 deg", "20 N*m"], ["360 deg", "20 N*m"]]\n'
    )
    with pytest.raises(SceneError) as info:
        flyopt.load(write_scene(text))
    message = str(info.value)
    assert f": {field}: " in message and words in message, message
    assert "rad/s" not in message
