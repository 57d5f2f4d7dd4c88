"""Scene files: what is accepted, and one clear error for everything that is not."""

import math

import pytest
from numpy.testing import assert_allclose

import flyopt
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.errors import SceneError

VALID = """
title = "t"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]
[torque.driving]
constant = "unknown"
[[shaft]]
name = "main"
speed_ratio = 1.0
"""


def scene_text(old=None, new=None, extra=""):
    text = VALID if old is None else VALID.replace(old, new)
    if old is not None and old not in VALID:
        raise ValueError(f"test bug: {old!r} is not in the base scene")
    return text + extra


def test_valid_scene_units_are_converted_to_si(write_scene):
    scene = flyopt.load(write_scene(scene_text()))
    assert_allclose(scene.omega_mean, 50 * math.pi, rtol=1e-15)
    assert isinstance(scene.driving, Constant) and scene.driving.unknown
    assert isinstance(scene.resisting, PiecewiseLinear)
    assert_allclose(scene.resisting.angles, [0, math.pi / 4, math.pi / 2, 2 * math.pi], rtol=1e-15)
    assert scene.shafts[0].name == "main" and scene.cycle_angle == 2 * math.pi


def test_plain_numbers_are_si_and_section_units_apply(write_scene):
    text = scene_text(
        'points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]',
        'angle_unit = "deg"\nunit = "kN*m"\npoints = [[0, 1.6], [45, 1.6], [90, 0.2], [360, 0.2]]',
    )
    scene = flyopt.load(write_scene(text.replace('speed = "1500 rpm"', "speed = 157.07963267948966")))
    assert_allclose(scene.resisting.values, [1600, 1600, 200, 200], rtol=1e-15)
    assert_allclose(scene.resisting.angles[1], math.pi / 4, rtol=1e-15)
    assert_allclose(flyopt.analyse(scene).a_max, math.pi / 4 * 1137.5 * (1 + 0.8125 / 2), rtol=1e-13)


def test_expression_with_unit(write_scene):
    text = scene_text('constant = "unknown"', 'expression = "2.5 + 0.36*sin(phi)"\nunit = "kN*m"')
    text = text.replace(
        'points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]',
        'constant = "2500 N*m"',
    )
    scene = flyopt.load(write_scene(text))
    assert isinstance(scene.driving, ExpressionTorque)
    assert_allclose(flyopt.analyse(scene).a_max, 720, rtol=1e-12)


def test_gd2_and_efficiency_lists(write_scene):
    text = scene_text("delta = 0.05", 'delta = 0.05\ngd2 = "39.24 N*m^2"\nefficiency = [0.95, 0.97]')
    scene = flyopt.load(write_scene(text))
    assert_allclose(scene.j_constant, 1.0, rtol=1e-15)  # 39.24 / (4 * 9.81)
    assert_allclose(scene.efficiency, 0.95 * 0.97, rtol=1e-15)


def test_reference_efficiency_comes_from_the_shaft_at_ratio_one(write_scene):
    text = scene_text("speed_ratio = 1.0", "speed_ratio = 1.0\nefficiency = 0.9")
    assert flyopt.load(write_scene(text)).efficiency == 0.9


SPEED_LINE = 'speed = "1500 rpm"'
POINTS = 'points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]'

BAD = [
    # (old, new, extra, field, words)
    ("title", "titel", "", "titel", "unknown key; did you mean 'title'"),
    ("delta = 0.05", "delta = 0.05\nspeeed = 3", "", "machine.speeed", "unknown key; did you mean 'speed'"),
    ('constant = "unknown"', 'constant = "unknown"\nscale = 2', "", "torque.driving.scale", "unknown key"),
    (SPEED_LINE, "", "", "machine.speed", "is missing"),
    ("delta = 0.05", "", "", "machine.delta", "is missing"),
    ("delta = 0.05", "delta = 0", "", "machine.delta", "between 0 and 2"),
    ("delta = 0.05", "delta = -0.1", "", "machine.delta", "between 0 and 2"),
    ("delta = 0.05", "delta = 2.0", "", "machine.delta", "between 0 and 2"),
    (SPEED_LINE, 'speed = "0 rpm"', "", "machine.speed", "must be positive"),
    (SPEED_LINE, "speed = -10", "", "machine.speed", "must be positive"),
    (SPEED_LINE, 'speed = "1500 m"', "", "machine.speed", "wrong dimension: expected a rotational speed"),
    (SPEED_LINE, 'speed = "1500 rpn"', "", "machine.speed", "cannot read '1500 rpn'"),
    (SPEED_LINE, "speed = true", "", "machine.speed", "expected a rotational speed"),
    ("delta = 0.05", "delta = nan", "", "machine.delta", "must be finite"),
    ("delta = 0.05", "delta = inf", "", "machine.delta", "must be finite"),
    (SPEED_LINE, 'speed = "inf rpm"', "", "machine.speed", "must be finite"),
    ('"1600 N*m"], ["45 deg"', '"nan N*m"], ["45 deg"', "", "torque.resisting.points[0] torque", "finite"),
    (
        '["45 deg", "1600 N*m"], ["90 deg"',
        '["95 deg", "1600 N*m"], ["90 deg"',
        "",
        "torque.resisting.points",
        "angles must not decrease",
    ),
    (
        '["45 deg", "1600 N*m"]',
        '["45 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["45 deg", "1600 N*m"]',
        "",
        "torque.resisting.points",
        "three points at one angle",
    ),
    ('["360 deg", "200 N*m"]', '["300 deg", "200 N*m"]', "", "torque.resisting.points", "does not close"),
    ('[["0 deg"', '[["10 deg"', "", "torque.resisting.points", "does not close"),
    ('["90 deg", "200 N*m"]', '["90 deg", "200 m"]', "", "torque.resisting.points[2] torque", "wrong dimension"),
    ('["90 deg", "200 N*m"]', '["90 deg"]', "", "torque.resisting.points[2]", r"an \[angle, torque\] pair"),
    (
        'constant = "unknown"',
        'expression = "1000 + sinh(phi)"',
        "",
        "torque.driving.expression",
        "unknown function 'sinh'",
    ),
    ('constant = "unknown"', 'expression = "1000 + theta"', "", "torque.driving.expression", "unknown name 'theta'"),
    (
        'constant = "unknown"',
        "expression = \"__import__('os')\"",
        "",
        "torque.driving.expression",
        "unknown function '__import__'",
    ),
    ('constant = "unknown"', 'expression = "phi.real"', "", "torque.driving.expression", "not allowed"),
    ('constant = "unknown"', 'expression = "1000 +"', "", "torque.driving.expression", "cannot parse"),
    ('constant = "unknown"', 'expression = "1/(phi-phi)"', "", "torque.driving.expression", "not finite"),
    (
        'constant = "unknown"',
        'constant = "unknown"\nexpression = "1000"',
        "",
        "torque.driving",
        "the torque is given twice",
    ),
    ('constant = "unknown"', 'constant = "300 N*m"', "", "torque", "non-periodic fluctuation"),
    (POINTS, 'constant = "unknown"', "", "torque.resisting.constant", "both torques are unknown"),
    ("", "", "[torque.net]\nareas = [1, -1]\n", "torque.net", "the torque is given twice"),
    ("", "", "[machine.extra]\n", "machine.extra", "unknown key"),
    ('name = "main"', 'name = ""', "", "shaft[0].name", "non-empty string"),
    ("speed_ratio = 1.0", "speed_ratio = 0", "", "shaft[0].speed_ratio", "must be positive"),
    ("speed_ratio = 1.0", "speed_ratio = 1.0\nefficiency = 1.2", "", "shaft[0].efficiency", r"in \(0, 1\]"),
    ("", "", '[[shaft]]\nname = "main"\nspeed_ratio = 2\n', "shaft[1].name", "given twice"),
    ("delta = 0.05", 'delta = 0.05\ncycle = "-1 deg"', "", "machine.cycle", "must be positive"),
    ("delta = 0.05", 'delta = 0.05\ninertia = "-1 kg*m^2"', "", "machine.inertia", "must not be negative"),
    ("delta = 0.05", 'delta = 0.05\ninertia = "1 kg"', "", "machine.inertia", "wrong dimension"),
]


@pytest.mark.parametrize("old, new, extra, field, words", BAD, ids=[f"{b[3]}-{k}" for k, b in enumerate(BAD)])
def test_bad_scenes_name_the_file_and_the_field(write_scene, old, new, extra, field, words):
    path = write_scene(scene_text(old, new, extra) if old else scene_text() + extra)
    with pytest.raises(ValueError) as info:  # SceneError, or NonPeriodicCycle for "torque"
        flyopt.analyse(flyopt.load(path))
    assert isinstance(info.value, (SceneError, flyopt.NonPeriodicCycle))
    message = str(info.value)
    assert message.startswith(f"{path}: {field}: "), message
    assert "\n" not in message
    import re

    assert re.search(words, message), message


NET_BAD = [
    ("areas = [1500, -1000]", "torque", "non-periodic"),
    ('areas = ["1500 J", "-1500 m"]', "torque.net.areas[1]", "wrong dimension"),
    ('areas = [580, -580]\narea_unit = "mm^2"', "torque.net", "need all of area_unit, torque_scale"),
    ('areas = ["1 J"]', "torque.net.areas", "at least two"),
    (
        'areas = [580, -580]\narea_unit = "mm^2"\ntorque_scale = "100 N*m/mm"\nangle_scale = "0.01 rad"',
        "torque.net.angle_scale",
        "wrong dimension",
    ),
]


@pytest.mark.parametrize("body, field, words", NET_BAD)
def test_bad_net_areas(write_scene, body, field, words):
    path = write_scene(f'[machine]\nspeed = "1500 rpm"\ndelta = 0.02\n[torque.net]\n{body}\n')
    with pytest.raises(Exception) as info:
        flyopt.analyse(flyopt.load(path))
    assert isinstance(info.value, ValueError)
    if field != "torque":
        assert str(info.value).startswith(f"{path}: {field}: ")
    assert words in str(info.value)


def test_toml_syntax_and_duplicate_tables(write_scene):
    with pytest.raises(SceneError, match=r"scene.toml: not valid TOML"):
        flyopt.load(write_scene("[machine\nspeed = 1"))
    dup = scene_text() + '[torque.driving]\nconstant = "10 N*m"\n'
    with pytest.raises(SceneError, match=r"not valid TOML.*torque"):
        flyopt.load(write_scene(dup))


def test_missing_file():
    with pytest.raises(SceneError, match=r"no-such.toml: cannot read the file"):
        flyopt.load("no-such.toml")


DESIGN_BAD = [
    ('geometry = "rimm"', "design.geometry", "'rimm' is not known; did you mean 'rim'"),
    ('materials = ["cast_iorn"]', "design.materials[0]", "unknown material 'cast_iorn'; did you mean 'cast_iron'"),
    ("materials = []", "design.materials", "non-empty list"),
    ('shafts = ["mian"]', "design.shafts[0]", "unknown shaft 'mian'; did you mean 'main'"),
    ("hb_ratio = [2.0, 1.5]", "design.hb_ratio", "0 < min <= max"),
    ("hb_ratio = [1, 2, 3]", "design.hb_ratio", "one number or a range"),
    ('max_outer_diameter = "-1 m"', "design.max_outer_diameter", "must be positive"),
    ('max_width = "25 kg"', "design.max_width", "wrong dimension"),
    ('objective = "cost"', "design.objective", "needs a cost per kg"),
    ('objective = "volume"', "design.objective", "not known"),
    ('colour = "red"', "design.colour", "unknown key"),
]


@pytest.mark.parametrize("line, field, words", DESIGN_BAD)
def test_bad_design_section(write_scene, line, field, words):
    path = write_scene(scene_text() + f"[design]\n{line}\n")
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ")
    assert words in str(info.value)


MATERIAL_BAD = [
    ('name = "x"\ndensity = "7000 kg/m^3"', "material[0]", "give max_rim_speed, allowable_stress"),
    ('name = "x"\nmax_rim_speed = "40 m/s"', "material[0].density", "is missing"),
    ('name = "x"\ndensity = "7000 kg"\nmax_rim_speed = "40 m/s"', "material[0].density", "wrong dimension"),
    ('name = "x"\ndensity = "7000 kg/m^3"\nmax_rim_speed = "-4 m/s"', "material[0].max_rim_speed", "positive"),
    (
        'name = "x"\ndensity = "7000 kg/m^3"\nmax_rim_speed = "40 m/s"\nyield = "1 MPa"',
        "material[0].yield",
        "unknown key",
    ),
]


@pytest.mark.parametrize("body, field, words", MATERIAL_BAD)
def test_bad_user_material(write_scene, body, field, words):
    path = write_scene(scene_text() + f"[[material]]\n{body}\n")
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ")
    assert words in str(info.value)


def test_user_material_overrides_builtin_and_cost_objective(write_scene):
    path = write_scene(
        scene_text() + '[design]\nobjective = "cost"\nmaterials = ["cast_iron"]\n'
        '[[material]]\nname = "cast_iron"\ndensity = "7100 kg/m^3"\nmax_rim_speed = "30 m/s"\n'
        'cost = "1.5 1/kg"\n'
    )
    scene = flyopt.load(path)
    assert scene.material_library()["cast_iron"].max_rim_speed == 30.0
    result = flyopt.solve(scene)
    assert_allclose(result.design.best.cost, 1.5 * result.design.best.mass, rtol=1e-15)


SLIDER_CRANK = """
[machine]
speed = "120 rpm"
delta = 0.15
inertia = "2 kg*m^2"
[mechanism]
kind = "slider_crank"
crank = "0.08 m"
rod = "0.45 m"
[[member]]
name = "ram"
part = "slider"
mass = "400 kg"
angle_unit = "deg"
unit = "kN"
force = [[0, 0], [140, 0], [140, 25], [175, 60], [180, 0], [360, 0]]
[torque.driving]
constant = "unknown"
"""


def test_a_member_force_may_carry_the_whole_load(write_scene):
    # a [torque.resisting] left out means zero when [[member]] forces carry the load
    left_out = flyopt.load(write_scene(SLIDER_CRANK, "left_out.toml"))
    explicit = flyopt.load(write_scene(SLIDER_CRANK + "[torque.resisting]\nconstant = 0\n", "explicit.toml"))
    assert left_out.resisting == Constant(0.0)
    assert_allclose(flyopt.analyse(left_out).a_max, flyopt.analyse(explicit).a_max, rtol=1e-15)
    assert flyopt.analyse(left_out).a_max > 0


def test_member_loads_alone_must_balance_over_the_cycle(write_scene):
    # no [torque] at all: nothing is unknown, and a resisting force alone cannot be periodic
    path = write_scene(SLIDER_CRANK.replace('[torque.driving]\nconstant = "unknown"\n', ""))
    with pytest.raises(flyopt.NonPeriodicCycle, match="does not balance"):
        flyopt.analyse(flyopt.load(path))


def test_a_missing_torque_curve_without_member_loads_is_an_error(write_scene):
    path = write_scene(scene_text('[torque.driving]\nconstant = "unknown"\n', ""))
    with pytest.raises(SceneError, match=r"torque.driving: is missing.*\[\[member\]\] forces or torques"):
        flyopt.load(path)
