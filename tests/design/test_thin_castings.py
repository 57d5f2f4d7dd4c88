"""A bare wheel thinner than can be made is said to be so (flyopt.design.castability.too_thin,
flyopt.design.wheel_design.thin_walled; docs/flywheel-design.md, section 23).

The textbook's bare rims and discs are not designed to the castability rules (the books' problems do not
change), so nothing holds their section to what a foundry can pour: a slow machine with a light load and no
envelope gets a rim 19 m across with a section under a millimetre. Such a wheel is checked against the
process of its material and the answer, the report's summary and the design's notes say it cannot be cast
as sized. The reference is the data file's own table, interpolated by numpy (``np.interp``), against the
walls the design reports.
"""

from __future__ import annotations

import dataclasses
import json
import re
from importlib import resources
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from conftest import run_flyopt
from numpy.testing import assert_allclose

import flyopt
from flyopt._toml import tomllib
from flyopt.design import DesignSpec, castability
from flyopt.design.materials import builtin_materials
from flyopt.design.wheel import Dims
from flyopt.design.wheel_design import thin_walled
from flyopt.outputs.schema import schema
from flyopt.report.card import card_html, solution_card

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "tests" / "data" / "castability" / "thin-textbook-rim.toml"
DATA = tomllib.loads(resources.files("flyopt").joinpath("data", "castability.toml").read_text(encoding="utf-8"))


def _table_wall(process: str, size: float) -> float:
    """The process's minimum wall at ``size`` by numpy's interpolation of the data file's rows (flat beyond them)."""
    sizes, walls = np.array(DATA["process"][process]["min_wall"]).T
    return float(np.interp(size, sizes, walls))


def _steel():
    return builtin_materials()["cast_steel"]


@pytest.mark.parametrize("process", sorted(DATA["process"]))
@pytest.mark.parametrize("size", [0.1, 0.6, 1.4, 3.0, 19.1])
@pytest.mark.parametrize("thinner", ["b", "h"])
def test_a_wall_is_thin_exactly_below_the_processs_table(process, size, thinner):
    rules = castability.processes()[process].rules
    wall = _table_wall(process, size)
    if wall == 0.0:
        pytest.fail(f"{process} has no minimum wall at {size} m")
    for factor, thin in ((1.0 + 1e-9, False), (1.0, False), (1.0 - 1e-9, True), (0.5, True)):
        sides = {"h": 3.0 * wall, "b": 3.0 * wall, thinner: factor * wall}
        found = castability.too_thin(rules, 0.0, "rim", Dims(d_outer=size, **sides))
        assert (found is not None) == thin, (factor, found)
        if found is not None:
            assert (found["process"], found["thinnest_part"], found["set_by"]) == (process, "rim", "process")
            assert found["cast"] == ("draft" in DATA["process"][process])  # a cast piece has a draft
            assert_allclose(
                [found["thinnest_wall"], found["min_wall"], found["process_min_wall"], found["casting_size"]],
                [factor * wall, wall, wall, size],
            )


def test_the_wall_asked_is_the_larger_of_the_processs_and_min_wall():
    rules = castability.processes()["cast_steel"].rules
    table = _table_wall("cast_steel", 1.0)
    dims = Dims(d_outer=1.0, h=0.03, b=0.012)
    assert castability.too_thin(rules, 0.0, "rim", dims) is None
    found = castability.too_thin(rules, 0.015, "rim", dims)  # the scene's 15 mm asks more than the process
    assert found is not None and found["set_by"] == "min_wall"
    assert_allclose([found["min_wall"], found["process_min_wall"]], [0.015, table])
    alone = castability.too_thin(None, 0.015, "rim", dims)  # no process: min_wall alone
    assert alone is not None and alone["process"] is None and alone["process_min_wall"] == 0.0
    assert not alone["cast"]
    assert castability.too_thin(None, 0.0, "rim", Dims(d_outer=1.0, h=1e-6, b=1e-6)) is None  # nothing asked


def test_a_discs_wall_is_its_width():
    rules = castability.processes()["cast_steel"].rules
    wall = _table_wall("cast_steel", 0.3)
    found = castability.too_thin(rules, 0.0, "disc", Dims(d_outer=0.3, h=0.15, b=0.5 * wall))
    assert found is not None and found["thinnest_part"] == "disc"
    assert castability.too_thin(rules, 0.0, "disc", Dims(d_outer=0.3, h=0.15, b=2.0 * wall)) is None


def test_only_a_wheel_not_designed_to_the_rules_is_asked_and_none_means_none():
    thin = Dims(d_outer=19.1, h=1e-3, b=1e-3)
    steel = _steel()
    assert thin_walled(DesignSpec(geometry="rim"), steel, "rim", thin) is not None
    assert thin_walled(DesignSpec(geometry="thin_rim"), steel, "thin_rim", thin) is not None
    # a whole wheel is designed to the rules (rows of its NLP): it is not checked again here
    assert thin_walled(DesignSpec(geometry="rim_web"), steel, "rim_web", thin) is None
    # the scene's "no rules", and a material of no known process
    none = DesignSpec(geometry="rim", castability=castability.Overrides(castability.NONE))
    assert thin_walled(none, steel, "rim", thin) is None
    unknown = dataclasses.replace(steel, name="unobtainium")
    assert castability.process_of("unobtainium") is None
    assert thin_walled(DesignSpec(geometry="rim"), unknown, "rim", thin) is None
    # the scene's own minimum wall replaces the process's
    own = DesignSpec(geometry="rim", castability=castability.Overrides(min_wall=((0.0, 0.5e-3),)))
    assert thin_walled(own, steel, "rim", thin) is None


def _walls(candidate):
    return min(candidate["h"], candidate["b"])


def _solve_json(scene):
    result = run_flyopt("solve", scene, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_the_thin_textbook_rim_says_so_in_the_answer_the_notes_the_json_and_the_summary():
    document = _solve_json(SCENE)
    best = document["design"]["candidates"][0]
    assert best["geometry"] == "rim" and best["material"] == "cast_steel"
    wall, needed = _walls(best), _table_wall("cast_steel", best["d_outer"])
    assert best["d_outer"] > 10.0 and wall < 1e-3 < needed  # the premise: 19 m across, under a millimetre
    thin = best["thin_wall"]
    assert (thin["process"], thin["thinnest_part"], thin["set_by"], thin["cast"]) == (
        "cast_steel",
        "rim",
        "process",
        True,
    )
    assert_allclose([thin["thinnest_wall"], thin["min_wall"], thin["casting_size"]], [wall, needed, best["d_outer"]])
    assert document["design"]["thin_wall"] == thin  # the chosen design's, as every candidate's
    jsonschema.validate(document, schema())
    note = [n for n in best["notes"] if "thinnest wall" in n]
    assert len(note) == 1
    assert f"{wall * 1e3:.4g} mm" in note[0] and f"the {needed * 1e3:.4g} mm the cast steel process" in note[0]

    text = run_flyopt("solve", SCENE)
    assert text.returncode == 0, text.stderr
    answer = text.stdout.splitlines()[:10]
    line = [x for x in answer if x.strip().startswith("wall")]
    assert line, answer
    shown = [float(v) for v in re.findall(r"([\d.]+) mm", line[0])]
    assert_allclose(shown, [wall * 1e3, needed * 1e3], rtol=5e-4)  # four figures
    assert "cast steel process" in line[0] and "not castable as sized" in line[0]
    assert "thinnest wall" in text.stdout  # the note, with the design's others

    imperial = run_flyopt("solve", SCENE, "--units", "imperial").stdout
    inches = [
        float(v) for v in re.findall(r"([\d.]+) in\b", next(x for x in imperial.splitlines()[:10] if "wall" in x))
    ]
    assert_allclose(inches, [wall / 0.0254, needed / 0.0254], rtol=5e-4)
    noted = next(x for x in imperial.splitlines() if "thinnest wall" in x)
    assert " mm" not in noted and " in," in noted  # the note in the reader's units too

    card = solution_card(flyopt.solve(flyopt.load(SCENE)))
    rows = {row.label: row for row in card.rows}
    assert rows["thinnest wall"].name == "thinnest_wall"
    assert_allclose(rows["thinnest wall"].si, wall, rtol=1e-12)
    assert "too thin to cast" in card.verdict
    # the card warns as the report's verdict does (its status is still "designed": the book's problem is answered)
    assert card.status == "designed" and card.warned and not card.good
    assert card_html(card).startswith('<div class="card flyopt-answer bad">')


@pytest.mark.parametrize(
    ("extra", "words", "set_by"),
    [
        ('process = "machined"', "the 0.8 mm the machined process makes at this size: too thin to make", "process"),
        ('process = "none"\nmin_wall = "10 mm"', "the 10 mm asked of it (design.min_wall", "min_wall"),
        ('criterion = "stress"', "the 8 mm the cast steel process makes at this size: not castable", "process"),
    ],
    ids=["machined", "min-wall", "stress-criterion"],
)
def test_who_asks_the_wall_and_how_the_rim_was_sized_are_said_as_they_are(tmp_path, extra, words, set_by):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE.read_text(encoding="utf-8").replace('geometry = "rim"', f'geometry = "rim"\n{extra}'))
    best = _solve_json(scene)["design"]["candidates"][0]
    assert best["thin_wall"]["set_by"] == set_by
    text = run_flyopt("solve", scene).stdout
    assert words in next(x for x in text.splitlines()[:10] if x.strip().startswith("wall"))
    note = next(n for n in best["notes"] if "thinnest wall" in n)
    sized = "its inertia and stresses alone" if "stress" in extra else "its inertia and rim speed alone"
    assert sized in note


def test_a_thin_textbook_disc_is_said_to_be_so_and_one_with_a_bore_is_designed_whole(tmp_path):
    scene = tmp_path / "disc.toml"
    scene.write_text(SCENE.read_text(encoding="utf-8").replace('geometry = "rim"', 'geometry = "disc"'))
    best = _solve_json(scene)["design"]["candidates"][0]
    assert best["geometry"] == "disc" and best["b"] < _table_wall("cast_steel", best["d_outer"])
    assert best["thin_wall"]["thinnest_part"] == "disc"
    assert "the disc's width" in next(n for n in best["notes"] if "castability rules" in n)
    bored = tmp_path / "bored.toml"
    bored.write_text(scene.read_text(encoding="utf-8") + 'bore = "40 mm"\n')
    whole = _solve_json(bored)["design"]["candidates"][0]
    assert whole["thin_wall"] is None and whole["castability"] is not None  # designed to the rules instead
    assert whole["castability"]["thinnest_wall"] >= whole["castability"]["min_wall"] * (1 - 1e-6)


def test_with_an_envelope_the_rim_is_thick_enough_and_nothing_is_said(tmp_path):
    scene = tmp_path / "enveloped.toml"
    scene.write_text(SCENE.read_text(encoding="utf-8") + 'max_outer_diameter = "1.0 m"\n', encoding="utf-8")
    best = _solve_json(scene)["design"]["candidates"][0]
    assert _walls(best) > _table_wall("cast_steel", best["d_outer"])
    assert best["thin_wall"] is None and not [n for n in best["notes"] if "thinnest wall" in n]
    text = run_flyopt("solve", scene).stdout
    assert not [x for x in text.split("\n\n")[0].splitlines() if x.strip().startswith("wall")]
    assert "not castable" not in text and "too thin" not in text
    card = solution_card(flyopt.solve(flyopt.load(scene)))
    assert card.good and not card.warned and "thinnest wall" not in {row.label for row in card.rows}


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
            assert c["thin_wall"] is None and not [n for n in c["notes"] if "thinnest wall" in n]


def test_the_cross_section_of_a_thin_rim_says_it_cannot_be_made():
    """The drawing's note said a bare rim's castability was not checked; it now says what the check found."""
    from flyopt.report import plots

    best = flyopt.solve(flyopt.load(SCENE)).design.best
    ax = plots.plot_cross_section(best)
    (note,) = [t for t in ax.figure.texts if t.get_gid() == "note"]
    words = " ".join(note.get_text().split())
    assert "its walls are thinner than can be made (see the design's notes)" in words
    assert "castability are not checked" not in words


def test_the_rules_of_overrides_given_as_lists_are_those_of_tuples():
    """rules_for is remembered by its arguments; a caller's rows given as lists (as TOML reads them) are made
    tuples first, and read as the same numbers."""
    listed = castability.rules_for("en_gjl_250", castability.Overrides(min_wall=[[0.0, 0.005], [1.0, 0.007]]))
    tupled = castability.rules_for("en_gjl_250", castability.Overrides(min_wall=((0.0, 0.005), (1.0, 0.007))))
    assert listed == tupled and listed is not None and listed.min_wall == ((0.0, 0.005), (1.0, 0.007))
