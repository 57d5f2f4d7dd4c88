"""Tests of flyopt.design.materials: the built-in data file and user materials."""

import math
import sys
from importlib import resources

import pytest
from numpy.testing import assert_allclose

from flyopt.design.materials import (Material, builtin_materials, get_material, make_material,
                              material_library, rim_speed_from_stress)

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
        assert "max_rim_speed" in table or "allowable_stress" in table


def test_builtin_materials_is_cached_but_returns_a_copy():
    first = builtin_materials()
    first.pop("cast_iron")
    assert "cast_iron" in builtin_materials()


def test_rim_speed_from_stress_satisfies_hoop_stress_relation():
    """sigma = rho v^2 of a thin ring (domain notes section 10)."""
    material = make_material("steel S355", 7850.0, allowable_stress=120e6, cost=1.5)
    assert_allclose(material.density * material.max_rim_speed ** 2, 120e6, rtol=1e-14)
    assert material.allowable_stress == 120e6
    assert material.cost == 1.5
    assert_allclose(rim_speed_from_stress(120e6, 7850.0), math.sqrt(120e6 / 7850.0),
                    rtol=1e-15)


def test_make_material_keeps_a_given_rim_speed_with_its_stress():
    material = make_material("x", 7000.0, max_rim_speed=40.0, allowable_stress=20e6)
    assert material.max_rim_speed == 40.0
    assert material.allowable_stress == 20e6


@pytest.mark.parametrize("kwargs, match", [
    (dict(name="x", density=7000.0), "max_rim_speed.*allowable_stress"),
    (dict(name="x", density=-1.0, max_rim_speed=30.0), "density"),
    (dict(name="x", density=float("nan"), max_rim_speed=30.0), "density"),
    (dict(name="x", density=7000.0, max_rim_speed=0.0), "max_rim_speed"),
    (dict(name="x", density=7000.0, allowable_stress=-5.0), "allowable_stress"),
    (dict(name="x", density=7000.0, max_rim_speed=30.0, cost=-1.0), "cost"),
    (dict(name="x", density="heavy", max_rim_speed=30.0), "density"),
    (dict(name="", density=7000.0, max_rim_speed=30.0), "name"),
])
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
    with pytest.raises(ValueError, match="best matches.*cast_iron"):
        get_material("cast irn")
