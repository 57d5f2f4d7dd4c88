"""flyopt.io.torque_section: the [torque] curves (points, constant, expression), [torque.net], and
the curve a [[member]]'s load stands in for."""

import pytest
from numpy.testing import assert_allclose
from scene_cases import scene_text

import flyopt
from flyopt.cycle.torque import Constant, ExpressionTorque
from flyopt.errors import SceneError


def test_expression_with_unit(write_scene):
    text = scene_text('constant = "unknown"', 'expression = "2.5 + 0.36*sin(phi)"\nunit = "kN*m"')
    text = text.replace(
        'points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]',
        'constant = "2500 N*m"',
    )
    scene = flyopt.load(write_scene(text))
    assert isinstance(scene.driving, ExpressionTorque)
    assert_allclose(flyopt.analyse(scene).a_max, 720, rtol=1e-12)


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
