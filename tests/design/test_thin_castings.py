"""A textbook wheel thinner than its process makes is said to be so (flyopt.design.castability.thinner_than_process,
flyopt.design.wheel_design.thin_walled; docs/flywheel-design.md, section 23).

The textbook's bare rims and discs are not designed to the castability rules (the books' problems do not
change), so nothing holds their section to what a foundry can pour: a slow machine with a light load and no
envelope gets a rim 19 m across with a section under a millimetre. Such a wheel is checked against the
process of its material and the answer, the report's summary and the design's notes say it cannot be cast
as sized. The reference is the data file's own table, interpolated by numpy (``np.interp``), against the
walls the design reports.
"""

from __future__ import annotations

import json
import re
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from conftest import run_flyopt
from numpy.testing import assert_allclose

import flyopt
from flyopt._toml import tomllib
from flyopt.design import DesignSpec, castability
from flyopt.design.wheel import Dims
from flyopt.design.wheel_design import thin_walled
from flyopt.report.card import solution_card

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "tests" / "data" / "castability" / "thin-textbook-rim.toml"
DATA = tomllib.loads(resources.files("flyopt").joinpath("data", "castability.toml").read_text(encoding="utf-8"))


def _table_wall(process: str, size: float) -> float:
    """The process's minimum wall at ``size`` by numpy's interpolation of the data file's rows (flat beyond them)."""
    sizes, walls = np.array(DATA["process"][process]["min_wall"]).T
    return float(np.interp(size, sizes, walls))


@pytest.mark.parametrize("process", sorted(DATA["process"]))
@pytest.mark.parametrize("size", [0.1, 0.6, 1.4, 3.0, 19.1])
def test_a_wall_is_thin_exactly_below_the_processs_table(process, size):
    rules = castability.processes()[process].rules
    wall = _table_wall(process, size)
    if wall == 0.0:
        pytest.fail(f"{process} has no minimum wall at {size} m")
    for factor, thin in ((1.0 + 1e-9, False), (1.0, False), (1.0 - 1e-9, True), (0.5, True)):
        dims = Dims(d_outer=size, h=3.0 * wall, b=factor * wall)
        found = castability.thinner_than_process(rules, "rim", dims)
        assert (found is not None) == thin, (factor, found)
        if thin:
            assert found is not None
            assert (found.process, found.part) == (process, "rim")
            assert_allclose([found.wall, found.process_min_wall, found.casting_size], [factor * wall, wall, size])


def test_a_discs_wall_is_its_width():
    rules = castability.processes()["cast_steel"].rules
    wall = _table_wall("cast_steel", 0.3)
    found = castability.thinner_than_process(rules, "disc", Dims(d_outer=0.3, h=0.15, b=0.5 * wall))
    assert found is not None and found.part == "disc"
    assert castability.thinner_than_process(rules, "disc", Dims(d_outer=0.3, h=0.15, b=2.0 * wall)) is None


def test_only_a_wheel_not_designed_to_the_rules_is_asked_and_none_means_none():
    thin = Dims(d_outer=19.1, h=1e-3, b=1e-3)
    assert thin_walled(DesignSpec(geometry="rim"), "cast_steel", "rim", thin) is not None
    assert thin_walled(DesignSpec(geometry="thin_rim"), "cast_iron", "thin_rim", thin) is not None
    # a whole wheel is designed to the rules (rows of its NLP): it is not checked again here
    assert thin_walled(DesignSpec(geometry="rim_web"), "cast_steel", "rim_web", thin) is None
    # the scene's "no rules", and a material of no known process
    none = DesignSpec(geometry="rim", castability=castability.Overrides(castability.NONE))
    assert thin_walled(none, "cast_steel", "rim", thin) is None
    assert thin_walled(DesignSpec(geometry="rim"), "unobtainium", "rim", thin) is None
    # the scene's own minimum wall replaces the process's
    own = DesignSpec(geometry="rim", castability=castability.Overrides(min_wall=((0.0, 0.5e-3),)))
    assert thin_walled(own, "cast_steel", "rim", thin) is None


def _walls(candidate):
    return min(candidate["h"], candidate["b"])


def test_the_thin_textbook_rim_says_so_in_the_answer_the_notes_and_the_summary():
    result = run_flyopt("solve", SCENE, "--json")
    assert result.returncode == 0, result.stderr
    best = json.loads(result.stdout)["design"]["candidates"][0]
    assert best["geometry"] == "rim" and best["material"] == "cast_steel"
    wall, needed = _walls(best), _table_wall("cast_steel", best["d_outer"])
    assert best["d_outer"] > 10.0 and wall < 1e-3 < needed  # the premise: 19 m across, under a millimetre
    note = [n for n in best["notes"] if "thinnest wall" in n]
    assert len(note) == 1
    assert f"{wall * 1e3:.4g} mm" in note[0] and f"({needed * 1e3:.4g} mm)" in note[0]

    text = run_flyopt("solve", SCENE)
    assert text.returncode == 0, text.stderr
    answer = text.stdout.splitlines()[:10]
    line = [x for x in answer if x.strip().startswith("casting")]
    assert line, answer
    shown = [float(v) for v in re.findall(r"([\d.]+) mm", line[0])]
    assert_allclose(shown, [wall * 1e3, needed * 1e3], rtol=5e-4)  # four figures
    assert "cast steel process" in line[0] and "not castable as sized" in line[0]
    assert "thinnest wall" in text.stdout  # the note, with the design's others

    imperial = run_flyopt("solve", SCENE, "--units", "imperial").stdout.splitlines()[:10]
    inches = [float(v) for v in re.findall(r"([\d.]+) in\b", next(x for x in imperial if "casting" in x))]
    assert_allclose(inches, [wall / 0.0254, needed / 0.0254], rtol=5e-4)

    card = solution_card(flyopt.solve(flyopt.load(SCENE)))
    rows = {row.label: row for row in card.rows}
    assert rows["casting"].name == "thinnest_wall"
    assert_allclose(rows["casting"].si, wall, rtol=1e-12)
    assert "too thin to cast" in card.verdict


def test_with_an_envelope_the_rim_is_thick_enough_and_nothing_is_said(tmp_path):
    scene = tmp_path / "enveloped.toml"
    scene.write_text(SCENE.read_text(encoding="utf-8") + 'max_outer_diameter = "1.0 m"\n', encoding="utf-8")
    result = run_flyopt("solve", scene, "--json")
    assert result.returncode == 0, result.stderr
    best = json.loads(result.stdout)["design"]["candidates"][0]
    assert _walls(best) > _table_wall("cast_steel", best["d_outer"])
    assert not [n for n in best["notes"] if "thinnest wall" in n]
    text = run_flyopt("solve", scene).stdout
    assert "casting" not in text.split("\n\n")[1] and "not castable" not in text


def _shipped_textbook_wheels():
    scenes = sorted((ROOT / "problems").glob("*.toml")) + sorted((ROOT / "problems" / "textbook").glob("*.toml"))
    return [
        pytest.param(p, id=p.stem, marks=[] if p.stem == "slider-crank-press" else [pytest.mark.slow]) for p in scenes
    ]


@pytest.mark.parametrize("scene", _shipped_textbook_wheels())
def test_no_shipped_textbook_wheel_is_thinner_than_its_process(scene):
    """slider-crank-press's rim is the thinnest shipped (8.0 mm against cast steel's 7.0 mm at 0.62 m)."""
    result = run_flyopt("solve", scene, "--json")
    assert result.returncode == 0, result.stderr
    design = json.loads(result.stdout).get("design") or {}
    for c in design.get("candidates", []):
        if c["geometry"] in ("rim", "thin_rim", "disc") and c.get("feasible"):
            process = castability.process_of(c["material"])
            if process is not None:
                wall = c["b"] if c["geometry"] == "disc" else _walls(c)
                assert wall >= _table_wall(process, c["d_outer"]), c["material"]
            assert not [n for n in c["notes"] if "thinnest wall" in n]
