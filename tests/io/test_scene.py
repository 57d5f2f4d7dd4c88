"""flyopt.io.scene: scene files, what is accepted, and one clear error for everything that is not."""

import math

import pytest
from numpy.testing import assert_allclose
from scene_cases import scene_text

import flyopt
from flyopt.cycle.torque import Constant, PiecewiseLinear
from flyopt.errors import SceneError


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


def test_gd2_and_efficiency_lists(write_scene):
    text = scene_text("delta = 0.05", 'delta = 0.05\ngd2 = "39.24 N*m^2"\nefficiency = [0.95, 0.97]')
    scene = flyopt.load(write_scene(text))
    assert_allclose(scene.j_constant, 1.0, rtol=1e-15)  # 39.24 / (4 * 9.81)
    assert_allclose(scene.efficiency, 0.95 * 0.97, rtol=1e-15)


SPEED_LINE = 'speed = "1500 rpm"'
POINTS = 'points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]'

BAD = [
    # (old, new, extra, field, words)
    ("title", "titel", "", "titel", "unknown key; did you mean 'title'"),
    ("delta = 0.05", "delta = 0.05\nspeeed = 3", "", "machine.speeed", "unknown key; did you mean 'speed'"),
    ('constant = "unknown"', 'constant = "unknown"\nscale = 2', "", "torque.driving.scale", "unknown key"),
    (SPEED_LINE, "", "", "machine.speed", "is missing"),
    ("delta = 0.05", "", "", "machine.delta", "is missing"),
    ("delta = 0.05", "delta = 0", "", "machine.delta", "between 1e-06 and 2"),
    ("delta = 0.05", "delta = -0.1", "", "machine.delta", "between 1e-06 and 2"),
    ("delta = 0.05", "delta = 2.0", "", "machine.delta", "between 1e-06 and 2"),
    # one range for every δ (below 1e-6 it said "out of range (allowed: 1e-06 to 2", beside "between 0 and 2")
    ("delta = 0.05", "delta = 1e-7", "", "machine.delta", r"must lie between 1e-06 and 2 \(2 excluded\), got 1e-07"),
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
