"""flyopt.io.design_section: a wrong [design] field is refused, naming the file and the field."""

import pytest
from scene_cases import scene_text

import flyopt
from flyopt.errors import SceneError

DESIGN_BAD = [
    ('geometry = "rimm"', "design.geometry", "'rimm' is not known; did you mean 'rim'"),
    ('materials = ["cast_iorn"]', "design.materials[0]", "unknown material 'cast_iorn'; did you mean 'cast_iron'"),
    ("materials = []", "design.materials", "non-empty list"),
    ('shafts = ["mian"]', "design.shafts[0]", "unknown shaft 'mian'; did you mean 'main'"),
    ("hb_ratio = [2.0, 1.5]", "design.hb_ratio", "0 < min <= max"),
    ("hb_ratio = [1, 2, 3]", "design.hb_ratio", "one number or a range"),
    ('max_outer_diameter = "-1 m"', "design.max_outer_diameter", "must be positive"),
    ('max_width = "25 kg"', "design.max_width", "wrong dimension"),
    ('objective = "cost"', "design.objective", "needs a cost per kg"),
    ('objective = "volume"', "design.objective", "not known"),
    ('colour = "red"', "design.colour", "unknown key"),
]


@pytest.mark.parametrize("line, field, words", DESIGN_BAD)
def test_bad_design_section(write_scene, line, field, words):
    path = write_scene(scene_text() + f"[design]\n{line}\n")
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ")
    assert words in str(info.value)
