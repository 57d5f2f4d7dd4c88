"""A [[shaft]] described as a part (issue 30, item 1): what the reader makes of it, and bad input refused.

Each bad value is refused by ``flyopt check`` in one line naming the file and the field, exit 2 (the
readers' pattern of tests/io/test_scene_wheel_fields.py).
"""

import math

import pytest
from test_input_failures import BASE, assert_refused, cli  # noqa: F401 (cli is a fixture)

import flyopt

SHAFT = """
[[shaft]]
name = "main"
speed_ratio = 1
inertia = "2 kg*m^2"
material = "42crmo4_qt"
segments = [{ to = "100 mm", diameter = "60 mm" }, { to = "500 mm", diameter = "80 mm" }, { to = "700 mm", diameter = "60 mm" }]
bearings = ["50 mm", "650 mm"]
wheel_at = "300 mm"
torque_at = "680 mm"
loads = [{ at = "690 mm", force = "2 kN", angle = "90 deg" }]
"""
GOOD = BASE + SHAFT


def test_a_described_shaft_is_read_in_si(write_scene):
    shaft = flyopt.load(write_scene(GOOD)).shafts[0]
    layout = shaft.layout
    assert layout.steps == pytest.approx((0.1, 0.5, 0.7)) and layout.diameters == pytest.approx((0.06, 0.08, 0.06))
    assert layout.bearings == pytest.approx((0.05, 0.65)) and layout.wheel_at == pytest.approx(0.3)
    assert layout.loads[0].force == 2000.0 and layout.loads[0].angle == pytest.approx(math.pi / 2)
    # the seat follows from the step under the wheel; the defaults are the documented ones
    assert shaft.diameter == pytest.approx(0.08)
    assert layout.balance_grade is None and layout.safety_factor == 1.5  # None: the flywheel's G 6.3
    assert layout.max_slope == 1e-3 and layout.critical_margin == 0.2 and layout.finish == "machined"
    assert not layout.overhung


def test_a_shaft_without_its_geometry_stays_a_speed_ratio(write_scene):
    assert flyopt.load(write_scene(BASE)).shafts[0].layout is None


CASES = [
    ('wheel_at = "300 mm"', 'wheel_at = "900 mm"', "shaft[0].wheel_at", "0 to 700 mm"),
    ('bearings = ["50 mm", "650 mm"]', 'bearings = ["50 mm"]', "shaft[0].bearings", "list of 2"),
    ('bearings = ["50 mm", "650 mm"]', 'bearings = ["50 mm", "50 mm"]', "shaft[0].bearings", "0.001 mm apart"),
    # places a round-off apart are the same place (torque 1e-13 m from the wheel: "Omega = 6.28319 rad/s is a
    # natural frequency of the undamped system", exit 1); a micron apart are two
    (
        'bearings = ["50 mm", "650 mm"]',
        'bearings = ["650 mm", "650.0000000001 mm"]',
        "shaft[0].bearings",
        "at least 0.001 mm apart",
    ),
    (
        '{ to = "500 mm", diameter',
        '{ to = "100.0000000001 mm", diameter',
        r"shaft[0].segments[1].to",
        r"at least 0.001 mm beyond the previous step's end \(100 mm\)",
    ),
    ('torque_at = "680 mm"', 'torque_at = "300.0000000001 mm"', "shaft[0].torque_at", "0.001 mm from wheel_at"),
    ('{ to = "500 mm", diameter', '{ to = "50 mm", diameter', r"shaft[0].segments[1].to", "beyond the previous"),
    ('diameter = "80 mm" }', 'diameter = "-80 mm" }', r"shaft[0].segments[1].diameter", "positive"),
    ('material = "42crmo4_qt"', 'material = "42crmo"', "shaft[0].material", "42crmo4_qt"),
    ('material = "42crmo4_qt"', 'material = "cast_iron"', "shaft[0].material", "elastic_modulus|strength"),
    ('torque_at = "680 mm"\n', 'torque_at = "680 mm"\nfinish = "polished"\n', "shaft[0].finish", "machined"),
    ('torque_at = "680 mm"\n', 'torque_at = "680 mm"\nsafety_factor = 0.8\n', "shaft[0].safety_factor", ">= 1"),
    (
        'torque_at = "680 mm"\n',
        'torque_at = "680 mm"\ncritical_margin = 1.5\n',
        "shaft[0].critical_margin",
        r"\[0, 1\)",
    ),
    ('torque_at = "680 mm"\n', 'torque_at = "680 mm"\nbalance_grade = "0 mm/s"\n', "shaft[0].balance_grade", "G"),
    ('torque_at = "680 mm"\n', 'torque_at = "680 mm"\ndiameter = "70 mm"\n', "shaft[0].diameter", "80 mm"),
    ('force = "2 kN"', 'force = "-2 kN"', "shaft[0].loads[0].force", ">= 0"),
    (
        '{ to = "100 mm", diameter = "60 mm" }',
        '{ to = "100 mm", diameter = "2 mm" }',
        "shaft[0].segments[0].diameter",
        "0.00279 to 0.254 m",
    ),
    ('torque_at = "680 mm"', 'torque_at = "300 mm"', "shaft[0].torque_at", "at least 0.001 mm from wheel_at"),
    (
        '{ to = "700 mm", diameter = "60 mm" }',
        '{ to = "700 mm", diameter = "300 mm" }',
        "shaft[0].segments[2].diameter",
        "ends at 160 mm",
    ),
    ('force = "2 kN"', 'force = "2 kN", pull = "2 kN"', "shaft[0].loads[0].pull", "unknown key"),
    ('segments = [{ to = "100', 'sections = [{ to = "100', "shaft[0].sections", "unknown key"),
    ('segments = [{ to = "100 mm", diameter = "60 mm" }, ', "#", "shaft[0].segments", "is missing"),
]


def test_places_a_micron_apart_are_two(write_scene):
    """The least gap (a micron, the least length a scene gives) holds to the round-off of the millimetres."""
    text = GOOD.replace('torque_at = "680 mm"', 'torque_at = "300.001 mm"').replace(
        'bearings = ["50 mm", "650 mm"]', 'bearings = ["50 mm", "50.001 mm"]'
    )
    text = text.replace('{ to = "500 mm", diameter', '{ to = "100.001 mm", diameter')
    layout = flyopt.load(write_scene(text)).shafts[0].layout
    assert layout.torque_at - layout.wheel_at == pytest.approx(1e-6, rel=1e-6)
    assert layout.bearings[1] - layout.bearings[0] == pytest.approx(1e-6, rel=1e-6)
    assert layout.steps[1] - layout.steps[0] == pytest.approx(1e-6, rel=1e-6)


@pytest.mark.parametrize("old, new, field, match", CASES)
def test_bad_shaft_field_is_refused_in_one_line(tmp_path, cli, old, new, field, match):
    assert old in GOOD, "test bug: the snippet is not in the scene"
    path = tmp_path / "scene.toml"
    path.write_text(GOOD.replace(old, new, 1))
    assert_refused(cli("check", path), path, field, match)


def test_a_micron_is_a_micron_along_any_shaft():
    """Positions written a micron apart in millimetres are apart at every length to a kilometre (the
    tolerance was below the doubles' spacing beyond 16 m: 16004 and 16004.001 mm were one place), and
    0.999 µm apart are not."""
    from flyopt.io.train_section import apart
    from flyopt.units import quantity

    for n in (0, 300, 16_004, 123_457, 999_999):
        here = quantity(f"{n} mm", "length")
        assert apart(here, quantity(f"{n}.001 mm", "length")), n
        assert not apart(here, quantity(f"{n}.000999 mm", "length")), n
