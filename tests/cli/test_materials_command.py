"""flyopt materials: the built-in library as a table in the user's units, or as JSON in SI."""

import json

import pytest
from conftest import ROOT
from numpy.testing import assert_allclose

from flyopt._toml import tomllib

DATA = tomllib.loads((ROOT / "src" / "flyopt" / "data" / "materials.toml").read_text(encoding="utf-8"))


def test_json_lists_every_material_of_the_data_file_with_its_numbers(main_cli):
    status, out, err = main_cli("materials", "--json")
    assert status == 0 and err == ""
    document = json.loads(out)
    rows = {row["name"]: row for row in document["materials"]}
    assert sorted(rows) == sorted(DATA)  # the data file, read independently
    assert document["units"] == {
        "density": "kg/m³",
        "tensile_strength": "Pa",
        "yield_strength": "Pa",
        "rim_speed_limit": "m/s",
    }
    for name, entry in DATA.items():
        row = rows[name]
        assert row["density"] == entry["density"]
        assert row["default"] == entry.get("default", False)
        assert row["ductile"] == entry.get("ductile")
        assert row["source"] == " ".join(entry["source"].split())
        table = entry.get("strength_by_thickness")
        if table:  # strengths by thickness: the weakest row
            assert row["tensile_strength"] == min(r[1] for r in table)
        else:
            assert row["tensile_strength"] == entry.get("tensile_strength")
    assert rows["cast_iron"]["rim_speed_limit"] == 36.0 and rows["cast_steel"]["rim_speed_limit"] == 50.0
    assert rows["en_gjs_400_18"]["display_name"] == "EN-GJS-400-18"
    assert rows["42crmo4_qt"]["display_name"] == "42CrMo4+QT"
    assert rows["cast_iron"]["display_name"] == "cast iron"


@pytest.mark.parametrize(
    "units, heading, density",
    [
        ("engineering", "density [kg/m³]", "7,200"),
        ("si", "density [kg/m³]", "7,200"),
        # 7200 kg/m^3 / 27679.9047 (kg/m^3 per lb/in^3) = 0.26012 lb/in^3; Shigley's Table A-5 prints 0.260
        ("imperial", "density [lb/in³]", "0.2601"),
    ],
)
def test_the_table_follows_units(main_cli, units, heading, density):
    status, out, err = main_cli("materials", "--units", units)
    assert status == 0 and err == ""
    lines = out.splitlines()
    assert heading in lines[0]
    cast_iron = next(line for line in lines if line.startswith("cast_iron "))
    assert f" {density} " in cast_iron


def test_the_table_shows_strengths_in_the_users_units(main_cli):
    _, out, _ = main_cli("materials", "--units", "imperial")
    row = next(line for line in out.splitlines() if line.startswith("en_gjs_400_18 "))
    # 400 MPa / 6894.757 Pa/psi = 58,015 psi, 250 MPa = 36,259 psi (4 significant figures)
    assert " 58,020 " in row and " 36,260 " in row
    assert_allclose(400e6 / 6894.7572931683635, 58015.1, rtol=1e-5)
    _, out, _ = main_cli("materials")
    row = next(line for line in out.splitlines() if line.startswith("en_gjs_400_18 "))
    assert " 400 " in row and " 250 " in row and "EN-GJS-400-18" in row
