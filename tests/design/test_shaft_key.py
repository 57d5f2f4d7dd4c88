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


@pytest.fixture(scope="module")
def soft(tmp_path_factory):
    """The soft-train punch press (:func:`_soft_punch_press`), loaded and solved: (scene, solution)."""
    from flyopt.pipeline import solve

    scene = flyopt.load(_soft_punch_press(tmp_path_factory.mktemp("soft")))
    return scene, solve(scene)


def _soft_punch_press(tmp_path):
    """The punch press of problems/punch-press-shaft.toml with one material (gjs keyed, 90 MPa), a softer train and
    an 85 mm seat in place of the scene's 80 mm (the soft train's torque on the key sets the hub there)."""
    text = (PROBLEMS / "punch-press-shaft.toml").read_text(encoding="utf-8")
    text = text.replace('materials = ["en_gjl_250", "en_gjs_400_18", "gjs_keyed"]', 'materials = ["gjs_keyed"]')
    seat = '{ to = "520 mm", diameter = "80 mm" }'
    assert seat in text
    text = text.replace(seat, '{ to = "520 mm", diameter = "85 mm" }')
    soft = 'train = [{ flywheel = true }, { stiffness = "3e5 N*m/rad" }, { name = "pinion" }]\n'
    text = text.replace('fillet = "3 mm"\n', 'fillet = "3 mm"\n' + soft)
    path = tmp_path / "soft.toml"
    path.write_text(text, encoding="utf-8")
    return path


#: DIN 6885-1's standard key lengths [mm] from 70 to 125 (flyopt/data/keys.toml, DIN 6885 Blatt 1), each at most
#: 1.5 d on the seats below (85 and 70 mm: 127.5 and 105 mm).
LENGTHS_MM = (70, 80, 90, 100, 110, 125)


def _by_hand_length(torque, d, flank, b, pressure):
    """The shortest standard key whose pressure 2 T / (d (h - t1) (l - b)) is within ``pressure`` [m]."""
    needed = b + 2.0 * torque / (d * flank * pressure)
    return next(mm for mm in LENGTHS_MM if mm / 1e3 >= needed) / 1e3


def test_the_key_is_designed_at_the_trains_torque_the_post_check_checks_it_at(soft):
    """Issue 30, item 5: one torque for the key. On a soft train (the forced response 16 % above the rigid peak)
    the design sizes the hub's key at the train's J_w theta''_w, from the same call the post-check makes: the
    design's torque is that call at the inertia the design must supply, the check's that call at the wheel's own
    inertia (to 1e-12 both); the key is the DIN 6885-1 length worked by hand at it, and it passes the post-check,
    where the key sized at the rigid peak (90 mm) would not."""
    from flyopt.design.shaft.cycle import check_candidate, key_torque_on
    from flyopt.machine.transmission import inertia_on_shaft
    from flyopt.pipeline import shaft_context_of

    scene, solution = soft
    design = solution.design
    best = design.best
    assert design.status == "designed" and best is not None and best.bore == 0.085
    ctx = shaft_context_of(scene, solution.analysis)
    j_shaft = inertia_on_shaft(solution.analysis.j_margin * design.spec.rim_share, 6.0)
    key = best.parts.key
    assert key["torque"] == pytest.approx(key_torque_on(ctx, "intermediate", j_shaft), rel=1e-12)
    check = check_candidate(ctx, best)
    assert check.key_torque == pytest.approx(key_torque_on(ctx, "intermediate", best.j_flywheel), rel=1e-12)
    # the design's wheel carries a little more inertia than required (rounded): the torques agree to that
    assert check.key_torque == pytest.approx(key["torque"], rel=1e-3)
    (limit,) = [lim for lim in check.limits if lim.kind == "key"]
    assert limit.holds and limit.utilisation <= 1.0
    # 22 x 14 on the 85 mm seat (75 < d <= 85): h - t1 = 14 - 9 mm, b = 22 mm; 90 MPa the material's
    flank, b = 0.014 - 0.009, 0.022
    assert key["size"] == "22 x 14" and key["length"] == _by_hand_length(key["torque"], 0.085, flank, b, 90e6)
    assert key["length"] == 0.11
    pressure = 2 * check.key_torque / (0.085 * flank * (key["length"] - b))
    assert limit.value == pytest.approx(pressure, rel=1e-12) and pressure <= 90e6
    # the rigid peak's key is 90 mm, which the train's torque overloads
    rigid = solution.analysis.flywheel_torque() / 6.0
    assert _by_hand_length(rigid, 0.085, flank, b, 90e6) == 0.09
    assert 2 * check.key_torque / (0.085 * flank * (0.09 - b)) > 90e6


def test_a_two_inertia_train_sets_the_hub_by_din_6885(tmp_path):
    """The two-inertia closed form (:func:`_closed_form`) of one order drives the hub: a wheel designed on a shaft
    carrying that torque (:attr:`flyopt.design.spec.MountShaft.torque`) has the key DIN 6885-1 gives by hand."""
    from flyopt.design.designer import design_flywheel
    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec, MountShaft

    j1, j2, zeta, rpm, c = 4.0, 1.5, 0.03, 300.0, 300.0
    speed = rpm * math.pi / 30.0
    k = (1.3 * speed) ** 2 * j1 * j2 / (j1 + j2)  # the mode 30 % above order 1: amplified, not resonant
    built = _two_inertias(j1, j2, k)
    found = key_torque(built, TorqueOrders(0.0, np.array([1.0]), np.array([c])), rpm, zeta)
    torque = abs(_closed_form(c, speed, j1, j2, k, zeta))
    assert found is not None and found.peak == pytest.approx(torque, rel=1e-9)
    assert torque > 1.5 * c * j1 / (j1 + j2)  # well above the rigid body's share
    iron = Material(  # a steel hub's proportions (l >= 1.2 d = 84 mm): the key, not the rule, sets the hub
        "keyed iron",
        density=7200.0,
        max_rim_speed=36.0,
        elastic_modulus=100e9,
        poisson_ratio=0.211,
        bearing_pressure=50e6,
        hub_rule="steel",
    )
    spec = DesignSpec(geometry="rim_web", max_outer_diameter=1.0)
    result = design_flywheel(j1, speed * 1.02, [MountShaft("s", 1.0, 0.07, torque=found.peak)], [iron], spec)
    assert result.best is not None
    key = result.best.parts.key
    # 20 x 12 on the 70 mm seat (65 < d <= 75): h - t1 = 12 - 7.5 mm, b = 20 mm
    assert key["size"] == "20 x 12" and key["torque"] == found.peak
    # by hand: l >= b + 2 T / (d (h - t1) p) = 20 + 2 * 531.57 / (0.07 * 0.0045 * 50e6) mm = 87.5 mm: the 90 mm key,
    # within 1.5 d = 105 mm; the steel rule's shortest hub (84 mm) is shorter, so the key sets the hub's length
    assert _by_hand_length(found.peak, 0.07, 0.012 - 0.0075, 0.020, 50e6) == 0.09
    assert key["length"] == 0.09
    assert result.best.dims.l_hub == pytest.approx(0.09, abs=1e-9)
    assert result.best.dims.l_hub >= key["length"] - 1e-9


def test_a_wheel_refused_for_its_key_alone_is_designed_again_at_its_torque(soft):
    """The short fixed point (:func:`flyopt.design.shaft.cycle.rekeyed`): the soft punch press's wheel with a
    100 mm key, one standard length short, refused by its post-check for that key alone, sends its shaft back to the
    design at the torque the post-check found on it (the train's, at the wheel's own inertia); a wheel refused for
    another limit, or one whose shaft was designed at a torque that covers its check's, sends nothing back."""
    import dataclasses

    from flyopt.design.result import Parts
    from flyopt.design.shaft.cycle import REFUSED, check_candidate, key_torque_on, reject_reason, rekeyed
    from flyopt.design.spec import MountShaft
    from flyopt.pipeline import shaft_context_of

    scene, solution = soft
    ctx = shaft_context_of(scene, solution.analysis)
    best = solution.design.best
    short = {**best.parts.key, "length": 0.100}  # 2 T / (d (h - t1) (l - b)) = 90.4 > 90 MPa at the train's torque
    wheel = dataclasses.replace(best, parts=Parts(best.parts.items, short))
    check = check_candidate(ctx, wheel)
    assert [lim.kind for lim in check.failed()] == ["key"]
    refused = dataclasses.replace(wheel, feasible=False, reason=reject_reason(wheel, check))
    assert REFUSED in refused.reason
    result = dataclasses.replace(solution.design, best=None, candidates=(refused,))
    designed_at = key_torque_on(ctx, "intermediate", best.j_flywheel * 0.999)  # a little below the wheel's
    shaft = MountShaft("intermediate", 6.0, 0.085, torque=designed_at)
    (again,) = rekeyed(ctx, result, [shaft])
    assert again.torque == check.key_torque > designed_at and again.diameter == 0.085
    covered = dataclasses.replace(shaft, torque=check.key_torque * 1.001)
    assert rekeyed(ctx, result, [covered]) is None
    # the same wheel refused by another limit as well (a stiffer requirement on the slope) is not the key's
    strict = dataclasses.replace(ctx, shafts={**ctx.shafts}, _cache={}, _keyed={})
    layout = dataclasses.replace(strict.shafts["intermediate"].layout, max_slope=1e-6)
    strict.shafts["intermediate"] = dataclasses.replace(strict.shafts["intermediate"], layout=layout)
    assert {lim.kind for lim in check_candidate(strict, wheel).failed()} >= {"key", "slope"}
    assert rekeyed(strict, result, [shaft]) is None
