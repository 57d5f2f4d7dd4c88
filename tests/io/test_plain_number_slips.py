"""A plain number whose unit was left out is refused, saying what to write (units.PLAIN_SLIPS).

Plain numbers are SI. punch-press-wheel's intermediate seat written ``diameter = 70`` (meaning mm) was a
70 m shaft: `flyopt check` said "ok" and `solve` designed the wheel on the motor shaft instead, saying why only
among its infeasible combinations ("no DIN 6885-1 key on the 70,000 mm seat"). A plain material strength of
400 (meaning MPa) was 400 Pa.
"""

import math

import pytest
from conftest import PROBLEMS

from flyopt.errors import SceneError
from flyopt.units import PLAIN_SLIPS, quantity

WHEEL = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")


def _written(tmp_path, old, new):
    assert old in WHEEL, f"test bug: {old!r} is not in punch-press-wheel"
    path = tmp_path / "scene.toml"
    path.write_text(WHEEL.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.mark.parametrize("command", ["check", "solve"])
def test_a_shaft_seat_in_mm_written_plain_is_refused_in_one_line(tmp_path, main_cli, command):
    path = _written(tmp_path, 'diameter = "70 mm"', "diameter = 70")
    status, out, err = main_cli(command, path)
    assert status == 2
    line = err.strip().splitlines()
    assert len(line) == 1, err
    assert str(path) in line[0] and "shaft[1].diameter" in line[0]
    assert "the plain number 70 is 70 m" in line[0] and '"70 mm"' in line[0]
    assert "Traceback" not in err and out.strip() == ""


def test_the_same_value_with_its_unit_is_read_as_written(tmp_path, main_cli):
    """The refusal is of the missing unit only: "70 m" is a 70 m shaft, whose combinations are infeasible
    (the design then says why), and "70 mm" is the scene as shipped."""
    status, out, _ = main_cli("solve", _written(tmp_path, 'diameter = "70 mm"', 'diameter = "70 m"'))
    assert status == 0
    assert "intermediate" in out and "70,000 mm seat" in out
    status, out, _ = main_cli("solve", PROBLEMS / "punch-press-wheel.toml")
    assert status == 0 and "70,000 mm" not in out


def test_a_material_strength_in_mpa_written_plain_is_refused(tmp_path, main_cli):
    status, _, err = main_cli("check", _written(tmp_path, 'tensile_strength = "400 MPa"', "tensile_strength = 400"))
    assert status == 2
    assert "material[0].tensile_strength" in err and "400 Pa" in err and '"400 MPa"' in err


@pytest.mark.parametrize(
    ("value", "dimension", "si"),
    [
        (9.99, "length", 9.99),  # a plain 9.99 m is a length of a large machine, read as SI
        (0.07, "length", 0.07),
        (10, "length", None),
        ("70", "length", None),  # a string without a unit is a plain number too
        (" 70 ", "length", None),
        (9999.0, "length", None),
        (1e4, "length", 1e4),  # beyond the band: the field's magnitude check answers (a kilometre at most)
        (-70, "length", -70.0),  # a sign the field refuses or reads (an offset): not a missing unit
        ("70 mm", "length", 0.07),
        ("70 m", "length", 70.0),
        (0.5, "stress", 0.5),  # below the band: the field's magnitude check answers
        (1, "stress", None),
        (999.9, "stress", None),
        (1000, "stress", 1000.0),  # 1 kPa, a pressure plausible in pascals
        (2.5e8, "stress", 2.5e8),
        ("400 Pa", "stress", 400.0),
        (400, "torque", 400.0),  # no band: torques, speeds, energies are read as written
        (70, "mass", 70.0),
    ],
)
def test_the_bands(value, dimension, si):
    if si is None:
        with pytest.raises(SceneError, match="plain numbers are SI"):
            quantity(value, dimension, "f")
    else:
        assert quantity(value, dimension, "f") == pytest.approx(si, rel=1e-15)


def test_each_band_lies_inside_what_its_dimension_means():
    """The bands are of the two dimensions whose slips were met; each is a range of positive numbers."""
    assert set(PLAIN_SLIPS) == {"length", "stress"}
    for low, high, _, _ in PLAIN_SLIPS.values():
        assert 0 < low < high


def test_a_sweep_axis_written_plain_in_mm_is_refused(main_cli):
    status, _, err = main_cli(
        "sweep", PROBLEMS / "punch-press-wheel.toml", "--vary", "design.max_outer_diameter=800:1200:3"
    )
    assert status == 2
    assert "--vary design.max_outer_diameter" in err and '"800 mm"' in err


TABLE = """
title = "t"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
unit = "kN*m"
angle_unit = "deg"
points = [[0, 1.6], [45, 1.6], [90, 0.2], [360, 0.2]]
[torque.driving]
constant = "unknown"
"""


def test_a_quoted_number_in_a_table_with_its_own_unit_is_in_that_unit(tmp_path):
    """A table's cell written "90" (a string without a unit) was read as SI, 90 rad (and 1.6 N*m), where the
    table's angle_unit is deg and its unit kN*m; it is the same number as unquoted. (A press's force table of
    position_unit = "mm" read "20" as 20 m.)"""
    import flyopt

    quoted = TABLE.replace(
        "[[0, 1.6], [45, 1.6], [90, 0.2], [360, 0.2]]", '[[0, "1.6"], ["45", 1.6], ["90", "0.2"], [360, 0.2]]'
    )
    assert quoted != TABLE
    (tmp_path / "plain.toml").write_text(TABLE, encoding="utf-8")
    (tmp_path / "quoted.toml").write_text(quoted, encoding="utf-8")
    plain, again = flyopt.load(tmp_path / "plain.toml"), flyopt.load(tmp_path / "quoted.toml")
    assert plain.resisting.angles[2] == pytest.approx(math.pi / 2, rel=1e-15)  # 90 deg
    assert plain.resisting.values[0] == pytest.approx(1600.0, rel=1e-15)  # 1.6 kN*m
    assert list(again.resisting.angles) == list(plain.resisting.angles)
    assert list(again.resisting.values) == list(plain.resisting.values)


@pytest.mark.parametrize("written", ['"7*10"', '"(35 + 35)"', '"0.07*1000"', '"1e1 * 7"'])
def test_arithmetic_without_a_unit_is_a_plain_number(tmp_path, main_cli, written):
    """A string of arithmetic names no unit either: the reader evaluates "7*10" to the plain 70, which was a
    70 m shaft seat (the refusal looked at strings of one number only); it is refused as 70 is, and with its unit,
    "7*10 mm", it is read as written."""
    path = _written(tmp_path, 'diameter = "70 mm"', f"diameter = {written}")
    status, out, err = main_cli("check", path)
    assert status == 2 and len(err.strip().splitlines()) == 1, err
    assert "shaft[1].diameter" in err and "(plain numbers are SI): give its unit" in err, err
    assert quantity(written.strip('"') + " mm", "length", "x") == pytest.approx(0.07, rel=1e-15)


def test_arithmetic_in_a_table_with_its_own_unit_is_in_that_unit(tmp_path):
    """A quoted cell of arithmetic ("45*2") in a table of angle_unit = "deg" is degrees, as "90" and 90 are."""
    import flyopt

    sums = TABLE.replace(
        "[[0, 1.6], [45, 1.6], [90, 0.2], [360, 0.2]]", '[[0, "0.8*2"], [45, 1.6], ["45*2", 0.2], [360, 0.2]]'
    )
    (tmp_path / "plain.toml").write_text(TABLE, encoding="utf-8")
    (tmp_path / "sums.toml").write_text(sums, encoding="utf-8")
    plain, again = flyopt.load(tmp_path / "plain.toml"), flyopt.load(tmp_path / "sums.toml")
    assert list(again.resisting.angles) == list(plain.resisting.angles)
    assert again.resisting.values == pytest.approx(plain.resisting.values, rel=1e-15)


@pytest.mark.parametrize(
    ("field", "written", "refused"),
    [
        ("elastic_modulus", "169000", True),  # N/mm^2 written plain: 169 kPa, no solid a wheel is made of
        ("elastic_modulus", '"169000 MPa"', False),
        ("elastic_modulus", '"0.05 GPa"', True),
        ("elastic_modulus", '"2000 GPa"', True),  # beyond diamond's 1,050 GPa
        ("tensile_strength", "40000", True),  # 40 kPa as a plain number: no strength of a solid
        ("tensile_strength", '"400 MPa"', False),
        ("yield_strength", '"250 kPa"', False),  # 0.25 MPa: within the bounds (a weak grade, not a slip)
        ("yield_strength", '"50 kPa"', True),
        ("min_wall", "6", True),  # mm written plain: 6 m, beyond design.castability's walls (0.01-500 mm)
        ("min_wall", '"6 mm"', False),
        ("min_wall", "0.006", False),
        ("bearing_pressure", '"50 kPa"', True),  # a hub's key pressure, bounded as the strengths are
        ("bearing_pressure", "90e6", False),
    ],
)
def test_a_materials_modulus_and_strengths_lie_within_what_solids_have(tmp_path, main_cli, field, written, refused):
    """Outside PLAIN_SLIPS's bands, a [[material]]'s modulus and strengths are held to what a solid has
    (material_section.MATERIAL_MAGNITUDES): a plain modulus of 169000 meaning N/mm² was read as 169 kPa, and the wheel's
    Lamé stresses were computed with it."""
    old = {
        "elastic_modulus": 'elastic_modulus = "169 GPa"',
        "tensile_strength": 'tensile_strength = "400 MPa"',
        "yield_strength": 'yield_strength = "250 MPa"',
        "min_wall": 'min_wall = "6 mm"',
        "bearing_pressure": 'bearing_pressure = "90 MPa"',
    }[field]
    status, _, err = main_cli("check", _written(tmp_path, old, f"{field} = {written}"))
    if refused:
        assert status == 2 and f"material[0].{field}: " in err and "is out of range" in err, err
    else:
        assert status == 0, err
