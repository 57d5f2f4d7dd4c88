"""A name, and the title, is one line of text (found by an outside audit of hostile inputs).

A material named "iron\\n  0\\nEOF" was written raw into the exported DXF's
custom properties, where the lines "0" and "EOF" end the file: `flyopt export`
said "wrote" (exit 0) and no DXF reader could open it; the text report split
its lines at the name. Every name a scene gives (materials, shafts, members,
drive-train elements, motor options) and its title is refused with a control
character in it, naming the field.
"""

import pytest

from flyopt.errors import SceneError
from flyopt.io.scene import from_dict

BASE = {"machine": {"speed": "600 rpm", "delta": 0.05}, "torque": {"net": {"areas": [1000.0, -1000.0]}}}


@pytest.mark.parametrize(
    "extra, field",
    [
        ({"title": "Press\nline two"}, "title"),
        (
            {"material": [{"name": "iron\n  0\nEOF", "density": "7100 kg/m^3", "allowable_stress": "14 MPa"}]},
            "material[0].name",
        ),
        ({"shaft": [{"name": "main\x1b[31m", "speed_ratio": 1.0}]}, "shaft[0].name"),
        ({"shaft": [{"name": "a\tb", "speed_ratio": 1.0}]}, "shaft[0].name"),
        ({"shaft": [{"name": "nul\x00", "speed_ratio": 1.0}]}, "shaft[0].name"),
        ({"title": "Press\u2028line two"}, "title"),  # Unicode's line and paragraph separators end a line too
        ({"shaft": [{"name": "a\u2029b", "speed_ratio": 1.0}]}, "shaft[0].name"),
    ],
)
def test_a_name_with_a_control_character_is_refused_naming_it(extra, field):
    with pytest.raises(SceneError) as refusal:
        from_dict({**BASE, **extra})
    assert refusal.value.field == field and "holds a control character" in refusal.value.message


def test_a_name_in_any_script_is_a_name():
    """Only control characters are refused: accents, Greek, CJK and a right-to-left name read (the reports show a
    bidirectional override as its escape)."""
    for name in ("Gußeisen", "чугун", "鋳鉄", "ω-shaft", "حديد"):
        scene = from_dict({**BASE, "title": name, "shaft": [{"name": name, "speed_ratio": 1.0}]})
        assert scene.title == name and scene.shafts[0].name == name
