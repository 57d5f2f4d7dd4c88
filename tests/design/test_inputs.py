"""flyopt.design.inputs: the design problem of a scene, and its refusals of the scene's own materials."""

import pytest
from conftest import PROBLEMS, run_flyopt


def _without_poisson(tmp_path, keep_others):
    text = (PROBLEMS / "punch-press-wheel.toml").read_text()
    assert "poisson_ratio = 0.28\n" in text
    text = text.replace("poisson_ratio = 0.28\n", "")
    if not keep_others:
        text = text.replace('materials = ["en_gjl_250", "en_gjs_400_18", "gjs_keyed"]', 'materials = ["gjs_keyed"]')
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("keep_others", [False, True])
@pytest.mark.parametrize("command", ["check", "solve"])
def test_a_scene_material_without_poisson_ratio_under_the_stress_criterion_is_bad_input(tmp_path, command, keep_others):
    """Issue 25, item 6: a [[material]] without poisson_ratio designed by stress ended 'infeasible' (exit 3)
    while check said ok; it is a field the scene left out: one line naming it, exit 2, from both."""
    path = _without_poisson(tmp_path, keep_others)
    run = run_flyopt(command, str(path))
    assert run.returncode == 2, run.stderr
    assert run.stdout == "" and len(run.stderr.splitlines()) == 1
    assert "material.gjs_keyed.poisson_ratio: missing: the stress criterion" in run.stderr
