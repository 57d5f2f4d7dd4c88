"""[design] process and [design.castability]: the scene's castability, and every bad value refused in one line."""

import pytest
from scene_cases import scene_text

import flyopt
from flyopt.errors import SceneError

# ------------------------------------------------------------------ the scene


def _with_design(lines):
    return scene_text() + '[design]\ngeometry = "rim_web"\ncriterion = "stress"\n' + lines


def test_scene_names_the_process_and_its_numbers(write_scene):
    path = write_scene(
        _with_design(
            'process = "cast_steel"\n[design.castability]\nmin_wall = [["0.2 m", "6 mm"], ["1 m", "9 mm"]]\n'
            "section_ratio = 1.5\n"
        )
    )
    spec = flyopt.load(path).design
    assert spec.castability.process == "cast_steel" and spec.castability.section_ratio == 1.5
    assert [v for row in spec.castability.min_wall for v in row] == pytest.approx([0.2, 0.006, 1.0, 0.009], rel=1e-15)
    path = write_scene(_with_design('[design.castability]\nmin_wall = "10 mm"\n'))
    assert flyopt.load(path).design.castability.min_wall == ((0.0, 0.01),)


CAST_BAD = [
    ('process = "lost_wax"', "design.process", "not known"),
    ("process = 3", "design.process", "not known"),
    ('[design.castability]\nmin_wall = "0.001 um"', "design.castability.min_wall", "out of range"),
    ('[design.castability]\nmin_wall = "2 m"', "design.castability.min_wall", "out of range"),
    ('[design.castability]\nmin_wall = "5 kg"', "design.castability.min_wall", "wrong dimension"),
    ("[design.castability]\nmin_wall = []", "design.castability.min_wall", "rows [size, wall]"),
    ('[design.castability]\nmin_wall = [["1 m"]]', "design.castability.min_wall[0]", "two lengths"),
    (
        '[design.castability]\nmin_wall = [["1 m", "9 mm"], ["0.5 m", "10 mm"]]',
        "design.castability.min_wall",
        "go up in size",
    ),
    (
        '[design.castability]\nmin_wall = [["0.5 m", "9 mm"], ["1 m", "5 mm"]]',
        "design.castability.min_wall",
        "must not go down",
    ),
    ('[design.castability]\nmin_wall = [["-1 m", "9 mm"]]', "design.castability.min_wall[0]", "out of range"),
    ("[design.castability]\nsection_ratio = 0.5", "design.castability.section_ratio", "allowed: 1 to 10"),
    ("[design.castability]\nsection_ratio = 1e300", "design.castability.section_ratio", "allowed: 1 to 10"),
    ('[design.castability]\ndraft = "1 deg"', "design.castability.draft", "unknown key"),
]


@pytest.mark.parametrize("lines, field, words", CAST_BAD)
def test_bad_castability_is_refused_in_one_line(write_scene, lines, field, words):
    path = write_scene(_with_design(lines + "\n"))
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    message = str(info.value)
    assert message.startswith(f"{path}: {field}: "), message
    assert words in message and "\n" not in message
