"""flyopt.io.material_section: the scene's own [[material]]s, checked, extending or overriding the built-in ones."""

import pytest
from numpy.testing import assert_allclose
from scene_cases import scene_text

import flyopt
from flyopt.errors import SceneError

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
