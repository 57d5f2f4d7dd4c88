"""The built-in material data against the standards and tables they cite.

Each spot value is the published figure of the table named in the test (see
the entry's ``source`` in flyopt/data/materials.toml); exact comparisons,
since the data file holds the tabulated numbers themselves, in SI units.
"""

import math
import sys
from importlib import resources

import pytest

from flyopt.design.materials import ThicknessOutOfRange, builtin_materials, default_materials, get_material

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MPA = 1e6
MM = 1e-3
MATERIALS = builtin_materials(default_only=False)
NUMERIC = (
    "density",
    "max_rim_speed",
    "allowable_stress",
    "cost",
    "elastic_modulus",
    "tensile_strength",
    "yield_strength",
    "safety_factor",
    "min_wall",
    "bearing_pressure",
)


def _data():
    text = resources.files("flyopt").joinpath("data", "materials.toml").read_text("utf-8")
    return tomllib.loads(text)


@pytest.mark.parametrize("name", sorted(_data()))
def test_entry_cites_a_source_and_gives_positive_numbers(name):
    table = _data()[name]
    assert len(table["source"].strip()) > 40, "the source must say where each number comes from"
    for key in NUMERIC:
        if key in table:
            assert math.isfinite(table[key]) and table[key] > 0, key
    if "poisson_ratio" in table:
        assert 0.0 <= table["poisson_ratio"] < 0.5
    for row in table.get("strength_by_thickness", []):
        assert all(math.isfinite(x) and x > 0 for x in row), row


@pytest.mark.parametrize("name", sorted(n for n, m in MATERIALS.items() if m.strength_by_thickness))
def test_strength_does_not_rise_with_thickness(name):
    """Thicker sections cool (castings) or harden through (quenched steels) less: never stronger."""
    rows = MATERIALS[name].strength_by_thickness
    for thinner, thicker in zip(rows, rows[1:]):
        assert thicker.max_thickness > thinner.max_thickness
        assert thicker.tensile_strength <= thinner.tensile_strength
        if thinner.yield_strength is not None:
            assert thicker.yield_strength <= thinner.yield_strength


def test_the_default_design_set_is_still_the_textbook_pair():
    """New grades must not enter a scene's default design (its results would move)."""
    assert set(default_materials()) == {"cast_iron", "cast_steel"} == set(builtin_materials())
    assert len(MATERIALS) > 2
    assert MATERIALS["cast_iron"].max_rim_speed == 36.0
    assert MATERIALS["cast_steel"].max_rim_speed == 50.0


def test_shigley_table_a5_elastic_constants():
    """Shigley, Table A-5: gray cast iron E = 100.0 GPa, nu = 0.211; carbon steel 207.0 GPa, 0.292."""
    assert (MATERIALS["cast_iron"].elastic_modulus, MATERIALS["cast_iron"].poisson_ratio) == (100.0e9, 0.211)
    assert (MATERIALS["cast_steel"].elastic_modulus, MATERIALS["cast_steel"].poisson_ratio) == (207.0e9, 0.292)


def test_en1561_1997_table1_anticipated_strength_of_en_gjl_250():
    """EN 1561:1997 Table 1, EN-GJL-250 in the casting: 250 / 225 / 195 / 170 / 155 MPa
    over 5-10 / 10-20 / 20-40 / 40-80 / 80-150 mm; no value given over 150 mm."""
    gjl = get_material("EN-GJL-250")
    assert gjl.name == "en_gjl_250" and gjl.ductile is False and gjl.thickness_rule == "part"
    for wall, rm in ((8, 250), (10, 250), (15, 225), (40, 195), (60, 170), (150, 155)):
        assert gjl.strength(wall * MM) == (rm * MPA, None), wall
    assert gjl.min_wall == 5 * MM
    with pytest.raises(ThicknessOutOfRange, match="en_gjl_250"):
        gjl.strength(151 * MM)


def test_en1561_1997_table1_first_rows_of_en_gjl_200_and_300():
    """EN-GJL-200 from 2.5 mm: 230 MPa up to 5 mm; EN-GJL-300 from 10 mm: 270 MPa up to 20 mm."""
    assert MATERIALS["en_gjl_200"].strength(4 * MM) == (230 * MPA, None)
    assert MATERIALS["en_gjl_200"].strength(100 * MM) == (115 * MPA, None)
    assert MATERIALS["en_gjl_300"].strength(15 * MM) == (270 * MPA, None)
    assert MATERIALS["en_gjl_300"].strength(30 * MM) == (240 * MPA, None)
    assert (MATERIALS["en_gjl_200"].min_wall, MATERIALS["en_gjl_300"].min_wall) == (2.5 * MM, 10 * MM)


@pytest.mark.parametrize(
    "name, rm, rp",
    [
        ("EN-GJS-400-18", 400, 250),
        ("EN-GJS-500-7", 500, 320),
        ("EN-GJS-600-3", 600, 370),
        ("EN-GJS-700-2", 700, 420),
    ],
)
def test_en1563_1997_table1_separately_cast_strengths(name, rm, rp):
    """EN 1563:1997 Table 1 (the grade's designation values), used up to 30 mm walls only."""
    gjs = get_material(name)
    assert gjs.ductile is True and gjs.failure_criterion == "von_mises"
    assert gjs.strength(30 * MM) == (rm * MPA, rp * MPA)
    with pytest.raises(ThicknessOutOfRange):
        gjs.strength(31 * MM)


@pytest.mark.parametrize(
    "t_mm, rm, rp",
    [
        (8, 1100, 900),
        (20, 1000, 750),
        (50, 900, 650),
        (100, 800, 550),
        (160, 750, 500),
    ],
)
def test_en10083_3_42crmo4_qt_by_ruling_section(t_mm, rm, rp):
    """EN 10083-3, 42CrMo4+QT by flat ruling section t: R_m (lower end of range), R_p0.2 minimum."""
    steel = MATERIALS["42crmo4_qt"]
    assert steel.thickness_rule == "wheel"
    assert steel.strength(t_mm * MM) == (rm * MPA, rp * MPA)


def test_42crmo4_qt_refuses_sections_beyond_the_standard():
    with pytest.raises(ThicknessOutOfRange, match="160 mm"):
        MATERIALS["42crmo4_qt"].strength(161 * MM)


def test_standard_grades_need_the_designs_safety_factor():
    """No factor of practice is sourced for the grades: no rim speed of their own, and
    allowable() divides by the design's factor (hand values: 225/5, 320/2, 650/2 MPa)."""
    grades = [m for n, m in MATERIALS.items() if n not in ("cast_iron", "cast_steel")]
    assert all(m.safety_factor is None and m.max_rim_speed is None for m in grades)
    assert MATERIALS["en_gjl_250"].allowable(15 * MM, safety_factor=5.0) == 45 * MPA
    assert MATERIALS["en_gjs_500_7"].allowable(20 * MM, safety_factor=2.0) == 160 * MPA
    assert MATERIALS["42crmo4_qt"].allowable(50 * MM, safety_factor=2.0) == 325 * MPA
    with pytest.raises(ValueError, match="en_gjl_250.*safety factor"):
        MATERIALS["en_gjl_250"].allowable(15 * MM)


def test_every_builtin_hub_rule_is_a_rule_of_keys_toml():
    """A material's hub rule names a hub_proportions row that exists (a wrong name would end a design)."""
    from importlib import resources

    import tomllib

    from flyopt.design.materials import builtin_materials

    rows = tomllib.loads(resources.files("flyopt").joinpath("data", "keys.toml").read_text())["hub_proportions"]
    for name, material in builtin_materials(default_only=False).items():
        assert material.hub_kind in rows, name


def test_hub_rule_by_material_not_by_name():
    """Cast irons keep the grey-iron hub (D/d 1.8-2) even when ductile; cast steel the steel row (1.6-1.8)."""
    from flyopt.design.materials import builtin_materials, make_material

    lib = builtin_materials(default_only=False)
    assert {lib[n].hub_kind for n in lib if n.startswith("en_gjs")} == {"cast_iron"}
    assert {lib[n].hub_kind for n in lib if n.startswith("en_gjl")} == {"cast_iron"}
    assert lib["cast_iron"].hub_kind == "cast_iron"
    assert lib["cast_steel"].hub_kind == "steel"
    assert lib["42crmo4_qt"].hub_kind == "steel"
    # a user's material without a rule: by its ductility, the larger hub when it is not known
    assert make_material("x", 7800.0, max_rim_speed=40.0).hub_kind == "cast_iron"
    assert make_material("y", 7800.0, tensile_strength=500e6, yield_strength=300e6, ductile=True).hub_kind == "steel"
    assert make_material("z", 7800.0, max_rim_speed=40.0, hub_rule="steel").hub_kind == "steel"
