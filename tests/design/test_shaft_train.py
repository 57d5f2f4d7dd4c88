"""The drive train of a described shaft as a torsional chain (issue 30, item 4, in the scene and the check).

The trains are written as a scene would write them and read by the loader, then checked by
:func:`flyopt.design.shaft.check.check_shaft`. References, independent of the code under test:

- three inertias on two springs, free at both ends (W. T. Thomson, *Theory of Vibration with
  Applications*, torsional systems; docs/flywheel-design.md, section 22):
  J_1 J_2 J_3 w^4 - [k_1 J_3 (J_1 + J_2) + k_2 J_1 (J_2 + J_3)] w^2 + k_1 k_2 (J_1 + J_2 + J_3) = 0;
- a belt of two spans of stretch stiffness k_b on a pulley of radius r: k = 2 k_b r^2 on that pulley's
  shaft; an inertia J and a stiffness k on a shaft turning i times the shaft they are seen from count as
  J i^2 and k i^2 there (worked by hand below, not through flyopt's reflection);
- a solid round shaft: k = G pi d^4 / (32 l), G = E / (2 (1 + nu));
- two free inertias with modal damping zeta on their one elastic mode, driven by T e^{i W t} on J_2: the
  twist obeys mu theta'' + 2 zeta w mu theta' + k theta = T J_1 / (J_1 + J_2) (mu = J_1 J_2 / (J_1 + J_2)),
  so the shaft carries |k theta| = T J_1 / (J_1 + J_2) / |1 - s^2 + 2 i zeta s|, s = W / w.
"""

import math

import numpy as np
import pytest
from test_input_failures import BASE, assert_refused, cli  # noqa: F401 (cli is a fixture)

import flyopt
from flyopt.design.materials import get_material, material_library
from flyopt.design.shaft.check import check_shaft
from flyopt.machine.torsion import TorqueOrders

SHAFT = """
[[shaft]]
name = "main"
speed_ratio = 2
inertia = "{other}"
material = "42crmo4_qt"
segments = [{{ to = "100 mm", diameter = "60 mm" }}, {{ to = "500 mm", diameter = "80 mm" }}, {{ to = "700 mm", diameter = "60 mm" }}]
bearings = ["50 mm", "650 mm"]
wheel_at = "300 mm"
torque_at = "680 mm"
{train}

[[shaft]]
name = "motor"
speed_ratio = 8
inertia = "0.05 kg*m^2"
"""
J_WHEEL = 4.0
EXCITATION = TorqueOrders(0.0, np.array([0.5, 1.0, 2.0]), np.array([300.0, 200.0 + 50.0j, 100.0]))


def scene_text(train, other="1.5 kg*m^2"):
    return BASE + SHAFT.format(train=train, other=other)


def check(write_scene, train, other="1.5 kg*m^2", excitation=EXCITATION, wheel=J_WHEEL, key=None, inertia=None):
    """check_shaft of the scene's shaft with ``train`` and a wheel of ``wheel`` kg*m^2 (80 kg); ``key``: a designed
    key (:class:`flyopt.design.shaft.check.KeySeat`); ``inertia``: the other inertia in place of the shaft's."""
    scene = flyopt.load(write_scene(scene_text(train, other)))
    shaft = scene.shafts[0]
    library = material_library(scene.materials)
    return shaft, check_shaft(
        shaft.layout,
        get_material(shaft.layout.material, library),
        wheel_mass=80.0,
        wheel_inertia=wheel,
        omega_mean=50.0,
        delta=0.05,
        torque_curve=np.array([-100.0, 100.0]),
        excitation=excitation,
        other_inertia=shaft.inertia if inertia is None else inertia,
        speed_ratio=shaft.speed_ratio,
        materials=library,
        key=key,
    )


def check_with_key(write_scene, key, other_inertia=None):
    """:func:`check` of the two-inertia train ("" train: the shaft's ``inertia`` at ``torque_at``) with a
    designed ``key`` (:class:`flyopt.design.shaft.check.KeySeat`); ``other_inertia`` 0: no train at all."""
    return check(write_scene, "", key=key, inertia=other_inertia)


def three_inertias(j1, j2, j3, k1, k2):
    """The two elastic omega of a free-free chain, from the quadratic in omega^2."""
    a, b, c = j1 * j2 * j3, -(k1 * j3 * (j1 + j2) + k2 * j1 * (j2 + j3)), k1 * k2 * (j1 + j2 + j3)
    root = math.sqrt(b * b - 4 * a * c)
    return sorted(math.sqrt(x) for x in ((-b - root) / (2 * a), (-b + root) / (2 * a)))


def test_a_train_of_three_inertias_and_two_springs_is_the_closed_form(write_scene):
    train = (
        'train = [{ name = "pulley", inertia = "0.5 kg*m^2" }, { stiffness = "2e5 N*m/rad" }, '
        '{ flywheel = true }, { stiffness = "8e4 N*m/rad" }, { name = "pinion" }]'
    )
    shaft, found = check(write_scene, train)
    omega = found.train.modes.omega
    assert omega == pytest.approx(three_inertias(0.5, J_WHEEL, 1.0, 2e5, 8e4), rel=1e-12)
    # the pinion took the rest of the shaft's 1.5 kg*m^2; the torque enters at it, the last node
    assert found.train.built.nodes == ("pulley", "flywheel", "pinion") and found.train.built.load_node == 2
    assert float(found.train.built.model.mass_matrix[2, 2]) == pytest.approx(1.0, rel=1e-15)


def test_a_belt_reflects_the_motor_by_the_ratio_squared(write_scene):
    # motor rotor (8 x the reference, 4 x this shaft) - belt - driven pulley - shaft piece - flywheel
    train = (
        'train = [{ name = "rotor", shaft = "motor" }, { belt = "300 kN/m", radius = "50 mm" }, '
        '{ name = "driven pulley" }, { length = "200 mm", diameter = "50 mm" }, { flywheel = true }]'
    )
    shaft, found = check(write_scene, train)
    i = 8.0 / 2.0
    k_belt = 2 * 300e3 * 0.05**2 * i**2  # on the motor shaft, then seen from this one
    steel = get_material("42crmo4_qt")
    e, nu = steel.elastic_modulus, steel.poisson_ratio
    k_piece = e / (2 * (1 + nu)) * math.pi * 0.05**4 / 32 / 0.2
    expected = three_inertias(0.05 * i**2, 1.5, J_WHEEL, k_belt, k_piece)
    assert found.train.modes.omega == pytest.approx(expected, rel=1e-12)
    # the belt's torque is reported on its own (the motor's) shaft: k theta_motor = (k_belt / i^2) (i theta)
    (belt, kind, k) = found.train.built.springs[0]
    assert kind == "belt" and k == pytest.approx(2 * 300e3 * 0.05**2, rel=1e-15)


def test_the_two_inertia_train_is_exactly_the_shafts_default(write_scene):
    default = check(write_scene, "")[1]
    written = check(
        write_scene,
        'train = [{ flywheel = true }, { name = "shaft, seat to torque_at", span = ["wheel_at", "torque_at"] }, '
        '{ name = "inertia at torque_at" }]',
    )[1]
    assert written.to_dict() == default.to_dict()
    # and the default is the two-inertia closed form with the shaft's steps in series from 300 to 680 mm
    steel = get_material("42crmo4_qt")
    g = steel.elastic_modulus / (2 * (1 + steel.poisson_ratio))
    k = 1 / (0.2 / (g * math.pi * 0.08**4 / 32) + 0.18 / (g * math.pi * 0.06**4 / 32))
    assert default.train.modes.omega[0] == pytest.approx(math.sqrt(k * (J_WHEEL + 1.5) / (J_WHEEL * 1.5)), rel=1e-12)


def test_the_forced_response_of_two_damped_inertias_is_the_closed_form(write_scene):
    shaft, found = check(
        write_scene,
        "damping_ratio = 0.05\n" + 'train = [{ flywheel = true }, { stiffness = "5e4 N*m/rad" }, { name = "crank" }]',
    )
    j1, j2, k, zeta = J_WHEEL, 1.5, 5e4, 0.05
    w = math.sqrt(k * (j1 + j2) / (j1 * j2))
    speed = 50.0  # rad/s of this shaft: order q turns at q x 50 rad/s
    got = found.train.shaft_torques[0]
    assert list(found.train.orders) == [0.5, 1.0, 2.0]
    for q, c, t in zip(EXCITATION.orders, EXCITATION.amplitudes, got):
        s = q * speed / w
        assert t == pytest.approx(abs(c) * j1 / (j1 + j2) / abs(1 - s * s + 2j * zeta * s), rel=1e-10)


GOOD = scene_text(
    'train = [{ name = "rotor", shaft = "motor" }, { belt = "300 kN/m", radius = "50 mm" }, '
    '{ name = "driven pulley", inertia = "1 kg*m^2" }, { length = "200 mm", diameter = "50 mm" }, '
    '{ flywheel = true }, { span = ["wheel_at", "torque_at"] }, { name = "pinion" }]\ndamping_ratio = 0.02'
)

CASES = [
    (
        "{ flywheel = true }, { span",
        "{ flywheel = true }, { flywheel = true }, { span",
        "shaft[0].train[5].flywheel",
        "once",
    ),
    ("{ flywheel = true }", '{ name = "hub", inertia = "0.1 kg*m^2" }', "shaft[0].train", "once"),
    ('shaft = "motor" }', 'shaft = "motr" }', "shaft[0].train[0].shaft", "motor"),
    ('{ belt = "300 kN/m", radius = "50 mm" }', '{ stiffness = "1e4 N*m/rad" }', "shaft[0].train[1]", "only a belt"),
    (
        '{ length = "200 mm", diameter = "50 mm" }, ',
        '{ length = "200 mm", diameter = "50 mm" }, { stiffness = 1 }, ',
        "shaft[0].train[4]",
        "in a row",
    ),
    ('{ name = "pinion" }]', '{ name = "pinion" }, { stiffness = 1 }]', "shaft[0].train[7]", "end with an inertia"),
    ('inertia = "1 kg*m^2" }', 'inertia = "2 kg*m^2" }', "shaft[0].train[6].inertia", "nothing is left"),
    ('{ name = "pinion" }', '{ name = "pinion", inertia = "0.1 kg*m^2" }', "shaft[0].train[6].inertia", "add up to"),
    ('belt = "300 kN/m", radius', 'belt = "300 kN/m", stiffness = 1, radius', "shaft[0].train[1].belt", "one thing"),
    ('radius = "50 mm"', 'radius = "-50 mm"', "shaft[0].train[1].radius", "positive"),
    ('belt = "300 kN/m"', 'belt = "300 kN"', "shaft[0].train[1].belt", "stiffness"),
    (
        'span = ["wheel_at", "torque_at"]',
        'span = ["wheel_at", "900 mm"]',
        "shaft[0].train[5].span[1]",
        "lie on the shaft",
    ),
    (  # a round-off apart: one place (as torque_at from wheel_at, a micron at least)
        'span = ["wheel_at", "torque_at"]',
        'span = ["wheel_at", "300.0000000001 mm"]',
        "shaft[0].train[5].span",
        "at least 0.001 mm apart",
    ),
    (
        'diameter = "50 mm" }',
        'diameter = "50 mm", material = "unobtainium" }',
        "shaft[0].train[3].material",
        "unobtainium",
    ),
    (
        '{ name = "driven pulley"',
        '{ name = "driven pulley", radius = "1 m"',
        "shaft[0].train[2].radius",
        "unknown|not belong",
    ),
    ("damping_ratio = 0.02", "damping_ratio = 1.5", "shaft[0].damping_ratio", r"\(0, 1\)"),
    (
        'train = [{ name = "rotor"',
        'train = [{ stiffness = 1 }, { name = "rotor"',
        "shaft[0].train[0]",
        "between two inertias",
    ),
]


@pytest.mark.parametrize("old, new, field, match", CASES)
def test_a_bad_train_is_refused_in_one_line(tmp_path, cli, old, new, field, match):
    assert old in GOOD, "test bug: the snippet is not in the scene"
    path = tmp_path / "scene.toml"
    path.write_text(GOOD.replace(old, new, 1))
    assert_refused(cli("check", path), path, field, match)


def test_the_good_train_is_accepted(tmp_path, cli):
    path = tmp_path / "scene.toml"
    path.write_text(GOOD)
    result = cli("check", path)
    assert result.returncode == 0, result.stderr


def test_the_shipped_drive_train_is_the_hand_assembled_chain():
    """problems/motor-press-drive-train.toml's modes, as its committed JSON gives them (tests/test_golden.py
    holds the live output to that copy), against the chain assembled by hand from the scene's numbers: each
    inertia and stiffness reflected to the intermediate shaft (x6) by (r / 6)^2, the motor's by 4^2, the
    crankshaft's by (1/6)^2, and the eigenvalues of K phi = w^2 M phi by numpy's own symmetric solver."""
    import json

    from conftest import ROOT

    document = json.loads((ROOT / "tests" / "data" / "golden" / "motor-press-drive-train.json").read_text())
    train = document["shaft_checks"][0]["drive_train"]
    j_wheel = document["design"]["j_flywheel"]
    steel = get_material("42crmo4_qt")
    g = steel.elastic_modulus / (2 * (1 + steel.poisson_ratio))

    def piece(length, d):
        return g * math.pi * d**4 / (32 * length)

    motor, crank = 4.0**2, (1 / 6) ** 2
    inertias = [
        0.0214 * motor,  # rotor: the rest of the motor shaft's 0.0294
        0.008 * motor,  # motor pulley
        1.2,  # driven pulley
        j_wheel,
        0.3 + 18 * crank,  # pinion and crank gear, meshed: one node
        6 * crank,  # crank: the rest of the crankshaft's 24
    ]
    springs = [
        piece(0.15, 0.038) * motor,
        2 * 1e6 * 0.07**2 * motor,  # the belt: 2 k_b r^2 on the motor shaft
        1 / (1 / piece(0.1, 0.06) + 1 / piece(0.18, 0.07)),  # 20-120 mm at 60, 120-300 mm at 70
        1 / (1 / piece(0.22, 0.07) + 1 / piece(0.14, 0.06)),  # 300-520 mm at 70, 520-660 mm at 60
        piece(0.5, 0.14) * crank,
    ]
    n = len(inertias)
    k = np.zeros((n, n))
    for e, s in enumerate(springs):
        k[e : e + 2, e : e + 2] += s * np.array([[1, -1], [-1, 1]])
    m_half = np.diag(1 / np.sqrt(inertias))
    omega2 = np.sort(np.linalg.eigvalsh(m_half @ k @ m_half))[1:]  # the rigid-body 0 left out
    found = [mode["natural_frequency"] for mode in train["modes"]]
    assert found == pytest.approx(np.sqrt(omega2), rel=1e-9)
    assert train["node_names"] == [
        "motor rotor",
        "motor pulley",
        "driven pulley",
        "flywheel",
        "pinion + crank gear",
        "crank",
    ]
    assert [s["torsional_stiffness"] for s in train["springs"]] == pytest.approx(
        [springs[0] / motor, springs[1] / motor, springs[2], springs[3], springs[4] / crank], rel=1e-12
    )


def test_the_report_and_the_text_show_the_trains_rows_in_the_units_asked():
    """The report's table of modes and the text's are read from the same rows (report.shaft.train_rows): in SI
    both give a mode's nearest critical speed in rad/s, the same number (the report wrote rpm whatever --units
    said)."""
    from conftest import PROBLEMS

    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Table
    from flyopt.report.shaft import train_lines

    path = PROBLEMS / "motor-press-drive-train.toml"
    inputs = collect(path, "test", pdf=False)
    document = build(inputs, "si", figures=False)
    table = next(b for s in document.sections for b in s.blocks if isinstance(b, Table) and b.name == "train_modes")
    nearest = [row[3] for row in table.rows]
    assert all(cell.endswith("rad/s") for cell in nearest if cell != "-")
    check = inputs.solution.shaft_checks[0].check
    text = "\n".join(train_lines(check, "si"))
    for cell in nearest:
        order, speed = cell.split(" at ")
        assert f"{order}: {speed}" in text
