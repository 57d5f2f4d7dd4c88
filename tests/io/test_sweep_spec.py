"""flyopt.io.sweep_spec: the grammar of --vary and of a scene's [sweep] table."""

import math

import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.errors import SceneError
from flyopt.io.sweep_spec import parse_vary

SCENE = flyopt.load(PROBLEMS / "punch-press.toml")


@pytest.mark.parametrize("count", ["3.2", "log3.5", "3e2", "3,5", "2.0"])
def test_a_range_count_that_is_not_a_whole_number_is_refused(count):
    """Issue 25, item 2: 0.01:0.1:3.2 gave δ = 0.002, 0.011, 0.020 (3 values, '.2' taken for a unit
    factor scaling every one); in --vary and in [sweep.vary] alike (one parser)."""
    with pytest.raises(SceneError, match="the count of a range is a whole number of values"):
        parse_vary(SCENE, {"delta": f"0.01:0.1:{count}"})


@pytest.mark.parametrize(
    "text, values",
    [
        ("0.01:0.1:3", (0.01, 0.055, 0.1)),
        ("0.01:0.1:log3", (0.01, (0.01 * 0.1) ** 0.5, 0.1)),  # the geometric mean in the middle
    ],
)
def test_a_whole_count_still_gives_its_values(text, values):
    axis = parse_vary(SCENE, {"delta": text})[0]
    assert axis.values == pytest.approx(values, rel=1e-12)


def test_a_unit_after_the_count_is_still_a_unit():
    axis = parse_vary(SCENE, {"speed": "300:600:3rpm"})[0]
    assert axis.values == pytest.approx([rpm * 2 * math.pi / 60 for rpm in (300, 450, 600)], rel=1e-12)


@pytest.mark.parametrize(
    "field, values, unit",
    [
        ("speed", "300,600,1200rpm", "rpm"),  # the unit after the last value applies to all
        ("speed", "300rpm,600rpm", "rpm"),
        ("speed", "300:600:3rpm", "rpm"),
        ("speed", "300 rpm:600 rpm:3", "rpm"),
        ("design.max_outer_diameter", "0.4:1.2:5 m", "m"),
        ("design.max_width", "150mm,none", "mm"),
        ("speed", ["300rpm", "600rpm"], "rpm"),  # a TOML list of strings
        ("speed", "30,60", None),  # plain numbers are SI: nothing to give back
        ("speed", "300rpm,60rad/s", None),  # two units: the column stays SI
        ("speed", ["300rpm", 60.0], None),
        ("material", "cast_iron,cast_steel", None),
    ],
)
def test_an_axis_records_the_unit_its_values_were_given_in(field, values, unit):
    """Issue 29: a sweep's file records it, so that flyopt.read_results can give the column back in it."""
    assert parse_vary(SCENE, {field: values})[0].unit == unit
