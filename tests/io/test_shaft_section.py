"""flyopt.io.shaft_section: the [[shaft]]s and the efficiency from the motor to the reference shaft."""

from scene_cases import scene_text

import flyopt


def test_reference_efficiency_comes_from_the_shaft_at_ratio_one(write_scene):
    text = scene_text("speed_ratio = 1.0", "speed_ratio = 1.0\nefficiency = 0.9")
    assert flyopt.load(write_scene(text)).efficiency == 0.9
