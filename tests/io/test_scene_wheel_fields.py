"""Bad values of the whole-wheel fields (issue 13): exit 2, one line naming the file and the field.

Every new field of [design], [[shaft]] and [[material]] is tried with what an
engineer might mistype: a negative length, Poisson's ratio of 0.5 or more, a
strength of zero, a bore wider than the envelope, fewer than three arms.
"""

import pytest
from test_input_failures import BASE, assert_refused, cli  # noqa: F401 (cli is a fixture)

MATERIAL = """
[[material]]
name = "gjs"
density = "7100 kg/m^3"
elastic_modulus = "169 GPa"
poisson_ratio = 0.275
tensile_strength = "400 MPa"
yield_strength = "250 MPa"
ductile = true
safety_factor = 4
"""
SHAFT = """
[[shaft]]
name = "main"
speed_ratio = 1
diameter = "80 mm"
"""
DESIGN = """
[design]
geometry = "rim_web"
criterion = "stress"
materials = ["gjs"]
max_outer_diameter = "1.2 m"
"""
GOOD = BASE + SHAFT + DESIGN + MATERIAL

CASES = [
    ("poisson_ratio = 0.275", "poisson_ratio = 0.5", "material[0].poisson_ratio", r"\[0, 0.5\)"),
    ("poisson_ratio = 0.275", "poisson_ratio = -0.1", "material[0].poisson_ratio", r"\[0, 0.5\)"),
    ('tensile_strength = "400 MPa"', 'tensile_strength = "0 MPa"', "material[0].tensile_strength", "positive"),
    ('yield_strength = "250 MPa"', 'yield_strength = "-250 MPa"', "material[0].yield_strength", "positive"),
    ('yield_strength = "250 MPa"', 'yield_strength = "450 MPa"', "material[0]", "yield"),
    ('elastic_modulus = "169 GPa"', 'elastic_modulus = "-1 GPa"', "material[0].elastic_modulus", "positive"),
    ("ductile = true", 'ductile = "yes"', "material[0].ductile", "true or false"),
    ("safety_factor = 4", "safety_factor = 0.5", "material[0].safety_factor", ">= 1"),
    (
        "safety_factor = 4",
        'safety_factor = 4\nhub_rule = "bronze"',
        "material[0].hub_rule",
        r"'bronze' is not a hub rule \(allowed: cast_iron, steel, cast_iron_flywheel\)",
    ),
    ('diameter = "80 mm"', 'diameter = "-80 mm"', "shaft[0].diameter", "positive"),
    ('criterion = "stress"', 'criterion = "strength"', "design.criterion", "not known"),
    ('geometry = "rim_web"', 'geometry = "rim_spokes"', "design.geometry", "not known"),
    ('criterion = "stress"', 'criterion = "stress"\nbore = "1.5 m"', "design.bore", "does not fit"),
    ('criterion = "stress"', 'criterion = "stress"\nbore = "-10 mm"', "design.bore", ">= 0"),
    ('criterion = "stress"', 'criterion = "stress"\narms = [2, 4]', "design.arms", ">= 3"),
    ('criterion = "stress"', 'criterion = "stress"\narms = [4, 4]', "design.arms", "each once"),
    ('criterion = "stress"', 'criterion = "stress"\narms = [4.5]', "design.arms", "whole"),
    ('criterion = "stress"', 'criterion = "stress"\nmin_wall = "0 mm"', "design.min_wall", "positive"),
    ('criterion = "stress"', 'criterion = "stress"\nsafety_factor = 0.9', "design.safety_factor", ">= 1"),
    ('criterion = "stress"', 'criterion = "stress"\nprune = "yes"', "design.prune", "true or false"),
    ('criterion = "stress"', 'criterion = "stress"\nprune = 1', "design.prune", "true or false"),
]


@pytest.mark.parametrize("old, new, field, match", CASES)
@pytest.mark.parametrize("command", ["check", "solve"])
def test_bad_wheel_field_is_refused_in_one_line(tmp_path, cli, command, old, new, field, match):
    assert old in GOOD, "test bug: the snippet is not in the scene"
    path = tmp_path / "scene.toml"
    path.write_text(GOOD.replace(old, new, 1))
    assert_refused(cli(command, path), path, field, match)


def test_the_good_scene_designs_a_whole_wheel(tmp_path, cli):
    path = tmp_path / "scene.toml"
    path.write_text(GOOD)
    result = cli("solve", path)
    assert result.returncode == 0, result.stderr
    assert "rim_web" in result.stdout


def test_a_materials_hub_rule_sets_its_hub(tmp_path):
    """[[material]] hub_rule: the same ductile iron with the grey-iron rule gets a hub of D/d 1.8-2, with the
    steel rule one of D/d 1.6-1.8 (keys.toml), on the 80 mm seat of the good scene."""
    import flyopt

    found = {}
    for rule in ("cast_iron", "steel"):
        path = tmp_path / f"{rule}.toml"
        path.write_text(GOOD.replace("safety_factor = 4", f'safety_factor = 4\nhub_rule = "{rule}"'))
        scene = flyopt.load(path)
        assert scene.materials[0].hub_kind == rule
        found[rule] = flyopt.solve(scene).design.best.dims.d_hub / 0.080
    assert 1.8 - 1e-6 <= found["cast_iron"] <= 2.0 + 1e-6
    assert 1.6 - 1e-6 <= found["steel"] <= 1.8 + 1e-6


def test_a_42crmo4_wheel_is_designed_by_stress(tmp_path):
    """The quenched-and-tempered steel has E and ν (Shigley, Table A-5): the stress criterion can use it."""
    import flyopt

    path = tmp_path / "steel.toml"
    path.write_text(GOOD.replace('materials = ["gjs"]', 'materials = ["42crmo4_qt"]\nsafety_factor = 3'))
    best = flyopt.solve(flyopt.load(path)).design.best
    assert best is not None and best.material == "42crmo4_qt"
    assert best.stresses.strength_safety >= 3 * (1 - 1e-6)
