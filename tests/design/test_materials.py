"""Tests of flyopt.design.materials: the built-in data file and user materials."""

import dataclasses
import math
import sys
from importlib import resources

import pytest
from numpy.testing import assert_allclose

from flyopt.design.materials import (
    Material,
    StrengthRow,
    ThicknessOutOfRange,
    _material_from_table,
    builtin_materials,
    default_materials,
    get_material,
    make_material,
    material_library,
    rim_speed_from_stress,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def test_domain_notes_section10_textbook_rim_speed_limits():
    """Domain notes section 10: cast iron v_max < 36 m/s, cast steel < 50 m/s."""
    materials = builtin_materials()
    assert materials["cast_iron"].max_rim_speed == 36.0
    assert materials["cast_steel"].max_rim_speed == 50.0


def test_builtin_densities_with_their_sources():
    """Cast steel 7800 kg/m^3 (domain notes, worked example 6); grey cast iron
    7.20 Mg/m^3 (Shigley, Table A-5). Exact: these are the tabulated numbers."""
    materials = builtin_materials()
    assert materials["cast_steel"].density == 7800.0
    assert "worked example 6" in materials["cast_steel"].source
    assert materials["cast_iron"].density == 7200.0
    assert "Table A-5" in materials["cast_iron"].source


def test_data_file_entries_all_cite_a_source():
    text = resources.files("flyopt").joinpath("data", "materials.toml").read_text("utf-8")
    data = tomllib.loads(text)
    assert data, "no built-in materials"
    for name, table in data.items():
        assert table.get("source", "").strip(), f"{name} has no source"
        assert table["density"] > 0
        # the default design's materials give the rim-speed criterion its limit themselves; a
        # standard grade is given by its strengths, to be divided by the design's safety factor
        if table.get("default"):
            assert "max_rim_speed" in table or "allowable_stress" in table
        else:
            assert "strength_by_thickness" in table or "tensile_strength" in table, name


def test_builtin_materials_is_cached_but_returns_a_copy():
    first = builtin_materials()
    first.pop("cast_iron")
    assert "cast_iron" in builtin_materials()


def test_rim_speed_from_stress_satisfies_hoop_stress_relation():
    """sigma = rho v^2 of a thin ring (domain notes section 10)."""
    material = make_material("steel S355", 7850.0, allowable_stress=120e6, cost=1.5)
    assert_allclose(material.density * material.max_rim_speed**2, 120e6, rtol=1e-14)
    assert material.allowable_stress == 120e6
    assert material.cost == 1.5
    assert_allclose(rim_speed_from_stress(120e6, 7850.0), math.sqrt(120e6 / 7850.0), rtol=1e-15)


def test_make_material_keeps_a_given_rim_speed_with_its_stress():
    material = make_material("x", 7000.0, max_rim_speed=40.0, allowable_stress=20e6)
    assert material.max_rim_speed == 40.0
    assert material.allowable_stress == 20e6


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(name="x", density=7000.0), "max_rim_speed.*allowable_stress"),
        (dict(name="x", density=-1.0, max_rim_speed=30.0), "density"),
        (dict(name="x", density=float("nan"), max_rim_speed=30.0), "density"),
        (dict(name="x", density=7000.0, max_rim_speed=0.0), "max_rim_speed"),
        (dict(name="x", density=7000.0, allowable_stress=-5.0), "allowable_stress"),
        (dict(name="x", density=7000.0, max_rim_speed=30.0, cost=-1.0), "cost"),
        (dict(name="x", density="heavy", max_rim_speed=30.0), "density"),
        (dict(name="", density=7000.0, max_rim_speed=30.0), "name"),
    ],
)
def test_make_material_rejects(kwargs, match):
    with pytest.raises(ValueError, match=match):
        make_material(**kwargs)


def test_user_materials_extend_and_override():
    cheap_iron = Material("cast_iron", 7100.0, 30.0, cost=0.8, source="supplier sheet")
    aluminium = make_material("aluminium", 2700.0, allowable_stress=50e6)
    library = material_library([cheap_iron, aluminium])
    assert library["cast_iron"] is cheap_iron
    assert library["aluminium"] is aluminium
    assert library["cast_steel"] == builtin_materials()["cast_steel"]
    with pytest.raises(ValueError, match="twice"):
        material_library([aluminium, aluminium])
    with pytest.raises(ValueError, match="Material"):
        material_library(["aluminium"])


def test_get_material_is_case_insensitive_and_suggests():
    assert get_material("Cast Steel").name == "cast_steel"
    with pytest.raises(ValueError, match=r"material 'cast irn' is not known; did you mean 'cast_iron'\?"):
        get_material("cast irn")


# --- strengths, safety factors and the allowable stress -------------------------------------

#: A user table shaped like EN 1563's (three ranges of relevant wall thickness); the numbers are
#: this test's own, chosen so that every row differs.
TABLE = [(0.030, 400e6, 250e6), (0.060, 390e6, 245e6), (0.200, 370e6, 240e6)]


def _table_material(**extra):
    values = dict(ductile=True, strength_by_thickness=TABLE, thickness_rule="part")
    values.update(extra)
    return make_material("tabled", 7100.0, **values)


def test_textbook_allowable_is_the_hoop_stress_of_the_speed_limit():
    """Domain notes section 10: sigma = rho v^2, so cast iron's 36 m/s allows 7200 * 36^2 Pa."""
    cast_iron = builtin_materials()["cast_iron"]
    assert cast_iron.allowable() == 7200.0 * 36.0**2 == 9_331_200.0
    # a thickness or a design's safety factor does not change a speed limit
    assert cast_iron.allowable(thickness=0.05, safety_factor=3.0) == 9_331_200.0
    assert cast_iron.rim_speed_limit(safety_factor=3.0) == 36.0
    assert cast_iron.strength() == (None, None)
    assert cast_iron.failure_criterion is None


def test_explicit_allowable_stress_wins_over_strengths_and_factors():
    material = make_material(
        "x", 7000.0, allowable_stress=20e6, tensile_strength=200e6, ductile=False, safety_factor=4.0
    )
    assert material.allowable() == 20e6
    assert material.allowable(safety_factor=2.0) == 20e6
    assert_allclose(material.max_rim_speed, math.sqrt(20e6 / 7000.0), rtol=1e-15)


def test_ductile_allowable_is_yield_over_safety_factor():
    """Von Mises against R_p0.2: 300 MPa / 2 = 150 MPa; the design's 3 wins: 100 MPa."""
    material = make_material(
        "steel", 7850.0, tensile_strength=500e6, yield_strength=300e6, ductile=True, safety_factor=2.0
    )
    assert material.failure_criterion == "von_mises"
    assert material.allowable() == 150e6
    assert material.allowable(safety_factor=3.0) == 100e6
    # the rim speed derives from the material's own factor, as from an allowable stress
    assert_allclose(material.max_rim_speed, math.sqrt(150e6 / 7850.0), rtol=1e-15)
    assert_allclose(material.rim_speed_limit(safety_factor=3.0), math.sqrt(100e6 / 7850.0), rtol=1e-15)


def test_brittle_allowable_is_tensile_over_safety_factor():
    """Largest principal stress against R_m: 200 MPa / 4 = 50 MPa."""
    material = make_material("iron", 7200.0, tensile_strength=200e6, ductile=False, safety_factor=4.0)
    assert material.failure_criterion == "max_principal"
    assert material.yield_strength is None
    assert material.allowable() == 50e6
    assert material.allowable(safety_factor=5.0) == 40e6


def test_strengths_without_any_safety_factor():
    """No factor in the material: no derived rim speed, and the design must give one."""
    material = make_material("iron", 7200.0, tensile_strength=200e6, ductile=False)
    assert material.max_rim_speed is None
    assert material.allowable(safety_factor=8.0) == 25e6
    assert_allclose(material.rim_speed_limit(safety_factor=8.0), math.sqrt(25e6 / 7200.0), rtol=1e-15)
    with pytest.raises(ValueError, match="material 'iron'.*safety factor"):
        material.allowable()
    with pytest.raises(ValueError, match="material 'iron'.*safety factor"):
        material.rim_speed_limit()


def test_strength_table_rows_by_thickness():
    """A row holds up to and including its bound; above the last row the table refuses."""
    material = _table_material()
    assert material.strength(0.010) == (400e6, 250e6)
    assert material.strength(0.030) == (400e6, 250e6)
    assert material.strength(0.0301) == (390e6, 245e6)
    assert material.strength(0.200) == (370e6, 240e6)
    # no thickness: the weakest row, which holds for every section of the table
    assert material.strength() == (370e6, 240e6)
    assert (material.tensile_strength, material.yield_strength) == (370e6, 240e6)
    assert material.allowable(0.045, safety_factor=2.0) == 245e6 / 2.0
    assert material.allowable(safety_factor=2.0) == 240e6 / 2.0
    with pytest.raises(ThicknessOutOfRange, match="material 'tabled'.*201 mm.*200 mm"):
        material.strength(0.201)
    with pytest.raises(ValueError, match="material 'tabled'.*thickness"):
        material.allowable(0.201, safety_factor=2.0)
    with pytest.raises(ValueError, match="material 'tabled'.*thickness"):
        material.strength(-0.01)
    rows = material.strength_by_thickness
    assert all(isinstance(row, StrengthRow) for row in rows)


def test_table_fields_may_repeat_the_weakest_row():
    """dataclasses.replace passes the filled-in strengths back; they must be accepted."""
    material = _table_material(safety_factor=2.0)
    again = dataclasses.replace(material, density=7200.0)
    assert again.strength_by_thickness == material.strength_by_thickness
    assert again.tensile_strength == 370e6


def test_elastic_constants_and_limits_are_kept():
    material = make_material(
        "x", 7000.0, max_rim_speed=40.0, elastic_modulus=170e9, poisson_ratio=0.0, min_wall=0.004, bearing_pressure=90e6
    )
    assert (material.elastic_modulus, material.poisson_ratio) == (170e9, 0.0)
    assert (material.min_wall, material.bearing_pressure) == (0.004, 90e6)


def test_scene_values_pass_through_make_material():
    """The scene parser hands every key to make_material as SI floats and a bool."""
    table = [[0.016, 1100e6, 900e6], [0.040, 1000e6, 750e6]]
    material = make_material(
        "forged",
        7840.0,
        source="scene",
        ductile=True,
        safety_factor=2.5,
        strength_by_thickness=table,
        thickness_rule="wheel",
    )
    assert material.strength(0.02) == (1000e6, 750e6)
    assert_allclose(material.max_rim_speed, math.sqrt(750e6 / 2.5 / 7840.0), rtol=1e-15)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(elastic_modulus=-1.0), "elastic_modulus"),
        (dict(elastic_modulus=0.0), "elastic_modulus"),
        (dict(poisson_ratio=0.5), r"poisson_ratio.*< 0.5"),
        (dict(poisson_ratio=0.6), "poisson_ratio"),
        (dict(poisson_ratio=-0.1), r"poisson_ratio.*>= 0"),
        (dict(poisson_ratio=float("nan")), "poisson_ratio"),
        (dict(tensile_strength=0.0, ductile=False), "tensile_strength"),
        (dict(tensile_strength=-5.0, ductile=False), "tensile_strength"),
        (dict(yield_strength=0.0, ductile=True), "yield_strength"),
        (dict(tensile_strength=300e6, yield_strength=400e6, ductile=True), "yield_strength.*<= tensile"),
        (dict(tensile_strength=300e6, ductile=False, safety_factor=1.0), r"safety_factor.*> 1"),
        (dict(tensile_strength=300e6, ductile=False, safety_factor=0.5), "safety_factor"),
        (dict(safety_factor=2.0), "safety_factor applies to"),
        (dict(tensile_strength=300e6), "ductile must be given"),
        (dict(tensile_strength=300e6, ductile="yes"), "ductile must be true or false"),
        (dict(tensile_strength=300e6, ductile=True), "ductile material.*yield_strength"),
        (dict(yield_strength=300e6, ductile=False), "brittle material.*tensile_strength"),
        (dict(min_wall=0.0), "min_wall"),
        (
            dict(min_wall=6.0),
            r"min_wall 6 m is out of range \(allowed: 1e-05 to 0.5 m; a wall from 0.01 mm to 500 mm\)",
        ),
        (dict(bearing_pressure=-1.0), "bearing_pressure"),
        (dict(thickness_rule="part"), "thickness_rule 'part' needs a strength_by_thickness"),
        (dict(ductile=True, strength_by_thickness=TABLE), r"thickness_rule must be one of \['part', 'wheel'\]"),
        (dict(ductile=True, strength_by_thickness=TABLE, thickness_rule="ruling"), "thickness_rule"),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=[(0.03, 400e6, 450e6)]),
            r"strength_by_thickness\[0\].yield_strength.*<= tensile",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=[(0.03, -1.0, 250e6)]),
            r"strength_by_thickness\[0\].tensile_strength",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=[(0.0, 400e6, 250e6)]),
            r"strength_by_thickness\[0\].max_thickness",
        ),
        (
            dict(
                ductile=True, thickness_rule="part", strength_by_thickness=[(0.06, 400e6, 250e6), (0.03, 390e6, 240e6)]
            ),
            r"strength_by_thickness\[1\].max_thickness.*increasing",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=[(0.03, 400e6, 250e6, 1.0)]),
            r"strength_by_thickness\[0\] must have 2 or 3 numbers",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness="0.03 400e6"),
            "strength_by_thickness must be a list of rows",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=[(0.03, 400e6)]),
            "ductile material.*yield_strength",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=TABLE, tensile_strength=400e6),
            "tensile_strength 4e[+]08 Pa differs from the weakest row",
        ),
        (
            dict(ductile=True, thickness_rule="part", strength_by_thickness=TABLE, min_wall=0.3),
            "min_wall.*above the thickest row",
        ),
        (dict(elasticity=200e9), "unknown field 'elasticity'.*allowed are.*'elastic_modulus'"),
    ],
)
def test_make_material_rejects_bad_new_fields(kwargs, match):
    """Each bad value is refused with the material's name, the field and what is allowed."""
    kwargs.setdefault("max_rim_speed", 40.0)
    with pytest.raises(ValueError, match=f"material 'bad'.*{match}"):
        make_material("bad", 7000.0, **kwargs)


def test_make_material_needs_a_speed_an_allowable_stress_or_a_strength():
    with pytest.raises(ValueError, match="material 'x'.*max_rim_speed.*allowable_stress.*tensile_strength"):
        make_material("x", 7000.0, elastic_modulus=200e9)


def test_allowable_rejects_a_bad_design_safety_factor():
    material = make_material("iron", 7200.0, tensile_strength=200e6, ductile=False)
    with pytest.raises(ValueError, match="material 'iron'.*safety_factor.*> 1"):
        material.allowable(safety_factor=1.0)


def test_data_file_rejects_unknown_keys_naming_material_and_key():
    table = {"density": 7000.0, "max_rim_speed": 30.0, "source": "x", "yield": 1e6}
    with pytest.raises(ValueError, match="data.toml: material 'odd' has unknown keys .'yield'."):
        _material_from_table("odd", table, "data.toml")
    table = {"density": 7000.0, "max_rim_speed": 30.0, "source": "x", "poisson_ratio": 0.5}
    with pytest.raises(ValueError, match="data.toml: material 'odd': poisson_ratio"):
        _material_from_table("odd", table, "data.toml")


# --- the default set -------------------------------------------------------------------------


def test_default_materials_are_the_textbook_pair_and_the_users():
    """A scene that names no materials designs with what it did before the grades were added."""
    assert set(builtin_materials(default_only=True)) == {"cast_iron", "cast_steel"}
    # builtin_materials() returns what it did before the grades were added
    assert builtin_materials() == builtin_materials(default_only=True)
    assert default_materials() == builtin_materials(default_only=True)
    assert set(builtin_materials(default_only=False)) >= {"cast_iron", "cast_steel"}
    aluminium = make_material("aluminium", 2700.0, allowable_stress=50e6)
    cheap_iron = Material("cast_iron", 7100.0, 30.0, source="supplier sheet")
    library = material_library([aluminium, cheap_iron])
    chosen = default_materials(library)
    assert chosen["aluminium"] is aluminium
    assert chosen["cast_iron"] is cheap_iron
    assert set(chosen) == {"cast_iron", "cast_steel", "aluminium"}
