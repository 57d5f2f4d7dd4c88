"""The wheel's key checked at the drive train's torque on the wheel (docs/flywheel-design.md, section 26: "The
key at the train's torque").

The design sizes the DIN 6885-1 key at the rigid body's peak torque (J_F/J)(M_d - M_r); where the train is
modelled, the shaft's post-check checks the same key, by the same rule (flyopt.design.key.check_key), at the peak
of the torque that accelerates the wheel itself, J_w theta''_w. References: the damped two-inertia closed form
per order, written out below from the two equations of motion (not the modal superposition flyopt uses); the
DIN key's bearing pressure p = 2 T / (d (h - t1) (l - b)) worked by hand; and a small scene whose soft train
makes a key the rigid torque accepts fail.
"""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from test_shaft_train import check_with_key

import flyopt
from flyopt.design.shaft.train import TrainModel, key_torque, wheel_torque_orders
from flyopt.machine.torsion import Inertia, Spring, TorqueOrders, TorsionalModel, modes

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


def _two_inertias(j1, j2, k):
    """Wheel J1 at node 0, spring k, J2 at node 1 where the torque enters."""
    model = TorsionalModel([Inertia(0, j1), Inertia(1, j2)], [Spring(0, 1, k)])
    return TrainModel(model, ("wheel", "crank"), (("shaft", "stiffness", k),), 0, 1, Inertia(0, j1))


def _closed_form(c, omega, j1, j2, k, zeta):
    """J1 theta1'' per order of a harmonic torque c at J2, with a dashpot c_d across the spring.

    (K - J1 W^2) X1 - K X2 = 0 and -K X1 + (K - J2 W^2) X2 = c, K = k + i W c_d, give
    X1 = c K / (J1 J2 W^4 - K W^2 (J1 + J2)), so -J1 W^2 X1 = c J1/(J1 + J2) K / (K - mu W^2), mu = J1 J2/(J1 + J2).
    Modal damping zeta of the one elastic mode (omega_n^2 = k/mu) is the dashpot c_d = 2 zeta omega_n mu.
    """
    mu = j1 * j2 / (j1 + j2)
    c_d = 2.0 * zeta * math.sqrt(k / mu) * mu
    stiff = k + 1j * omega * c_d
    return c * j1 / (j1 + j2) * stiff / (stiff - mu * omega * omega)


@pytest.mark.parametrize("beta", [0.2, 0.9, 1.0, 2.5])
def test_the_wheels_inertial_torque_per_order_is_the_two_inertia_closed_form(beta):
    j1, j2, zeta, rpm = 4.0, 1.5, 0.03, 300.0
    speed = rpm * math.pi / 30.0
    orders = np.array([0.5, 1.0, 2.0, 3.0])
    w_n = beta * speed  # the mode at beta x the shaft's speed: order 1 at beta = 1 is resonant
    k = w_n * w_n * j1 * j2 / (j1 + j2)
    c = np.array([300.0, 200.0 + 50.0j, -80.0j, 40.0])
    built = _two_inertias(j1, j2, k)
    found = wheel_torque_orders(built, TorqueOrders(0.0, orders, c), rpm, zeta)
    expected = [_closed_form(cq, q * speed, j1, j2, k, zeta) for cq, q in zip(c, orders)]
    assert found == pytest.approx(expected, rel=1e-10)
    if beta == 1.0:  # order 1 at resonance: |K/(K - mu W^2)| = sqrt(1 + 4 zeta^2) / (2 zeta)
        ratio = abs(found[1]) / (abs(c[1]) * j1 / (j1 + j2))
        assert ratio == pytest.approx(math.sqrt(1 + 4 * zeta**2) / (2 * zeta), rel=1e-10)


def test_one_order_peaks_at_its_amplitude_and_a_stiff_train_gives_the_rigid_share():
    j1, j2, rpm = 4.0, 1.5, 300.0
    c = 250.0 * np.exp(0.9j)
    built = _two_inertias(j1, j2, 2.0e5)
    one = key_torque(built, TorqueOrders(0.0, np.array([1.0]), np.array([c])), rpm, 0.02)
    assert one is not None
    assert one.peak == pytest.approx(abs(_closed_form(c, rpm * math.pi / 30.0, j1, j2, 2.0e5, 0.02)), rel=1e-9)
    stiff = key_torque(_two_inertias(j1, j2, 1e14), TorqueOrders(0.0, np.array([1.0]), np.array([c])), rpm, 0.02)
    assert stiff is not None
    assert stiff.peak == pytest.approx(abs(c) * j1 / (j1 + j2), rel=1e-9)  # the rigid body's J_F/J of it


def test_the_wheel_alone_at_its_node_carries_its_own_share():
    """A pulley turning with the wheel at its node: the key drives the wheel only, J_w theta''_w, not the node's
    J_w + J_p (with a stiff train theta'' = c/J: the key takes J_w/J of c, the node J_w + J_p of it)."""
    j_w, j_p, j2, rpm = 4.0, 1.0, 1.5, 300.0
    model = TorsionalModel([Inertia(0, j_w), Inertia(0, j_p), Inertia(1, j2)], [Spring(0, 1, 1e14)])
    built = TrainModel(model, ("wheel + pulley", "crank"), (("shaft", "stiffness", 1e14),), 0, 1, Inertia(0, j_w))
    found = wheel_torque_orders(built, TorqueOrders(0.0, np.array([1.0]), np.array([100.0])), rpm, 0.02, modes(model))
    assert abs(found[0]) == pytest.approx(100.0 * j_w / (j_w + j_p + j2), rel=1e-9)


def test_without_a_train_the_key_is_not_checked_again(write_scene):
    """No train (no inertia on the shaft besides the wheel): the design's own check at the rigid peak stands."""
    from flyopt.design.shaft.check import KeySeat

    key = KeySeat(0.07, 0.1, 1.0, 1.0)  # allowables of 1 Pa: any torque would fail it
    _, rigid = check_with_key(write_scene, key, other_inertia=0.0)
    assert rigid.torque_source == "rigid body" and not any(lim.kind == "key" for lim in rigid.limits)
    assert math.isnan(rigid.key_torque)
    _, trained = check_with_key(write_scene, key)
    assert [lim.kind for lim in trained.limits if not lim.holds] == ["key"]


def test_a_soft_train_refuses_a_key_the_rigid_torque_accepts(tmp_path):
    """The punch press of problems/punch-press-shaft.toml with one material and a softer train: the design's key
    (20 x 12, 125 mm, on the 70 mm seat) passes at the rigid peak, and the post-check refuses it at the train's."""
    from flyopt.pipeline import solve

    text = (PROBLEMS / "punch-press-shaft.toml").read_text(encoding="utf-8")
    text = text.replace('materials = ["en_gjl_250", "en_gjs_400_18", "gjs_keyed"]', 'materials = ["gjs_keyed"]')
    soft = 'train = [{ flywheel = true }, { stiffness = "3e5 N*m/rad" }, { name = "pinion" }]\n'
    text = text.replace('fillet = "3 mm"\n', 'fillet = "3 mm"\n' + soft)
    path = tmp_path / "soft.toml"
    path.write_text(text, encoding="utf-8")
    design = solve(flyopt.load(path)).design
    assert design.best is None
    (refused,) = design.candidates
    key = refused.parts.key
    assert key["ok"] and key["size"] == "20 x 12" and key["length"] == 0.125 and refused.bore == 0.07
    # the rigid peak's pressure by hand: h - t1 = 12 - 7.5 mm, l - b = 125 - 20 mm
    flank, bearing = 0.012 - 0.0075, 0.125 - 0.020
    assert key["bearing_pressure"] == pytest.approx(2 * key["torque"] / (0.07 * flank * bearing), rel=1e-12)
    assert key["bearing_pressure"] < 90e6
    found = re.search(
        r"key 20 x 12, 125 mm long, at the wheel seat \(bearing pressure\): ([\d.]+) > 90 MPa at "
        r"the train's peak torque on the wheel ([\d.]+) N\*m",
        refused.reason,
    )
    assert found is not None, refused.reason
    # only the key fails (no other limit in the reason); its pressure by hand at the torque the reason gives
    assert refused.reason.count(" > ") == 1 and "inside the running range" not in refused.reason
    torque = float(found.group(2))
    assert float(found.group(1)) == pytest.approx(2 * torque / (0.07 * flank * bearing) / 1e6, rel=1e-3)
    assert torque > 1.1 * key["torque"]
