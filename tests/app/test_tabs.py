"""The app's "Compare materials" and "Sweeps" tabs without a browser, against the command line's own outputs.

The library against ``flyopt materials --json``, the trade-off of ticked materials against ``flyopt tradeoff
--json`` of the scene with those materials written into it, the Pareto front against ``flyopt pareto --json``,
the sweep form's ``--vary`` text against ``flyopt sweep``'s parser and output (and the grid's closed form).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from flyopt.app import materials, model, sweeps
from flyopt.errors import SceneError
from flyopt.io.scene import load
from flyopt.report import display
from flyopt.report.plots import readout

pytestmark = pytest.mark.usefixtures("close_figures")  # the app keeps figures open: none outlives a test

ROOT = Path(__file__).resolve().parents[2]
SHEAR = ROOT / "problems" / "shear-press.toml"
BOOK = ROOT / "problems" / "textbook" / "khurmi-16-18.toml"


def with_materials_text(path: Path, names: list[str]) -> str:
    """The scene's text with ``[design] materials = NAMES`` written in (what ticking them means)."""
    text = path.read_text(encoding="utf-8")
    listed = ", ".join(f'"{n}"' for n in names)
    return text.replace("[design]\n", f"[design]\nmaterials = [{listed}]\n", 1)


def test_the_library_is_flyopt_materials_and_the_scene_s_own(main_cli):
    status, out, _ = main_cli("materials", "--json")
    assert status == 0
    cli = json.loads(out)["materials"]
    table = materials.library(None)
    rows = table.drop(columns="origin").astype(object)
    assert rows.where(rows.notna(), None).to_dict("records") == cli
    assert set(table["origin"]) == {"built-in"}

    scene = load(BOOK)  # a scene with its own [[material]] book_cast_iron
    own = materials.library(scene)
    assert own.loc[own["name"] == "book_cast_iron", "origin"].tolist() == ["scene"]
    assert own.loc[own["name"] == "book_cast_iron", "density"].tolist() == [7200.0]
    assert set(own["name"]) == {row["name"] for row in cli} | {"book_cast_iron"}
    assert materials.design_materials(scene) == ["book_cast_iron"]

    shown = materials.library_shown(table, "engineering")
    row = shown[shown["name"] == "en_gjs_400_18"].iloc[0]
    assert row["material"] == "EN-GJS-400-18"
    assert row["R_m [MPa]"] == 400 and row["R_p0.2 [MPa]"] == 250  # EN 1563: 400 and 250 MPa


def test_the_trade_off_of_ticked_materials_is_flyopt_tradeoff_of_the_scene_with_them(main_cli, write_scene):
    ticked = ["cast_steel"]
    status, out, _ = main_cli("tradeoff", write_scene(with_materials_text(SHEAR, ticked)), "--json")
    assert status == 0
    cli = pd.DataFrame(json.loads(out)["rows"])
    table = materials.tradeoff(load(SHEAR), ticked)
    assert table["material"].tolist() == cli["material"].tolist() == ticked
    for column in ("d_outer", "b", "h", "mass", "rim_speed"):
        np.testing.assert_allclose(table[column].to_numpy(float), cli[column].to_numpy(float), rtol=1e-12)
    assert table["status"].tolist() == cli["status"].tolist()

    shown = materials.shown(table, materials.TRADEOFF_SHOWN, "engineering", materials.display_names(load(SHEAR)))
    assert shown["material"].tolist() == ["cast steel"]
    assert shown["d_outer [mm]"].iloc[0] == pytest.approx(cli["d_outer"].iloc[0] * 1000, rel=5e-4)  # 4 figures
    # the limits that bind in words, as the printed flyopt tradeoff names them (the tab showed 'rim_speed,hb_min')
    status, printed, _ = main_cli("tradeoff", write_scene(with_materials_text(SHEAR, ticked)))
    limit = shown["limit"].iloc[0]
    assert "_" not in limit and "," in cli["limit"].iloc[0] and limit in printed, (limit, printed)

    with pytest.raises(SceneError, match="unknown material 'unobtainium'"):
        materials.tradeoff(load(SHEAR), ["unobtainium"])


def test_the_pareto_front_is_flyopt_pareto_and_each_point_is_a_link(main_cli):
    ticked = ["cast_iron", "cast_steel"]  # the scene's own default materials: the CLI runs the scene as is
    status, out, _ = main_cli("pareto", SHEAR, "--json", "--points", "8")
    assert status == 0
    cli = pd.DataFrame(json.loads(out)["rows"])
    front = materials.pareto_front(load(SHEAR), ticked, "mass,outer_diameter", points=8)
    assert list(front.columns[:2]) == ["mass", "outer_diameter"] == list(cli.columns[:2])
    np.testing.assert_allclose(front["mass"].to_numpy(float), cli["mass"].to_numpy(float), rtol=1e-12)
    names = materials.display_names(load(SHEAR))
    svg, found = materials.pareto_svg(front, "engineering", names)
    links = re.findall(r'href="#pareto-?pick-(\d+)"', svg)
    assert sorted(int(n) for n in links) == list(range(len(front)))
    # under the pointer, each link's point reads what its click loads: the card's material, D and mass
    (entry,) = json.loads(found)["axes"]
    for n, x, y in re.findall(r'href="#pareto-?pick-(\d+)".*?<use [^>]*x="([-\d.]+)" y="([-\d.]+)"', svg, re.S):
        drawn = [readout.to_svg(entry, *xy) for xy in entry["marks"]["xy"]]
        k = int(np.argmin([math.hypot(u - float(x), v - float(y)) for u, v in drawn]))
        assert math.hypot(drawn[k][0] - float(x), drawn[k][1] - float(y)) < 0.01  # the same place, to 1/1000 pt
        card = dict(materials.point_rows(front, int(n), "engineering", names))
        material, d, mass = entry["marks"]["rows"][k]
        assert material == f"material = {card['material']}" and mass == f"mass = {card['mass']}"
        assert d == f"outer diameter D = {card['outer diameter D']}"  # the card's words, the axis' words
    lines = dict(materials.point_rows(front, 2, "engineering", materials.display_names(load(SHEAR))))
    d = cli["d_outer"].iloc[2] * 1000
    assert lines["outer diameter D"] == f"{float(f'{d:.4g}'):g} mm"  # four figures, in mm
    binding = cli["binding"].iloc[2]  # the front's names, in words on the card
    assert binding and len(lines["limits that bind"].split(", ")) == len(binding.split(","))
    assert "_" not in lines["limits that bind"]
    with pytest.raises(IndexError):
        materials.point_rows(front, len(front) + 3, "engineering")


def test_a_user_s_strings_are_escaped_on_the_point_card():
    html = materials.rows_html("<b>t</b>", [("material", '<img src=x onerror="alert(1)">')])
    assert "<img" not in html and "&lt;img" in html and "<b>t</b>" not in html


def test_the_form_s_vary_text_is_read_by_flyopt_sweep_and_its_points_are_the_grid(main_cli, tmp_path, workspace):
    axis = sweeps.Axis("speed", "1000", "2000", 5, unit="rpm")
    assert sweeps.vary_text(axis) == "speed=1000:2000:5 rpm"
    assert sweeps.vary_text(sweeps.Axis("delta", "0.01", "0.1", 3, log=True)) == "delta=0.01:0.1:log3"
    assert sweeps.vary_text(sweeps.Axis("material", names="cast_iron, cast_steel")) == "material=cast_iron,cast_steel"

    scene = sweeps.scene_copy(SHEAR.read_text(encoding="utf-8"), workspace)
    names = sweeps.Axis("material", names="cast_iron,cast_steel")
    plan = sweeps.plan(scene, [axis, names])
    assert plan.points == 10
    seen: list[tuple[int, int]] = []
    result = sweeps.run(scene, plan.vary, workspace, progress=lambda done, total: seen.append((done, total)))
    assert result.complete and seen[-1] == (10, 10)
    rpm = np.linspace(1000, 2000, 5) * math.pi / 30  # the grid's closed form, rad/s
    np.testing.assert_allclose(np.unique(result.frame["speed"].to_numpy(float)), rpm, rtol=1e-12)

    output = tmp_path / "cli.parquet"
    args = [a for t in plan.texts for a in ("--vary", t)]
    status, _, _ = main_cli("sweep", SHEAR, *args, "-o", output, "--quiet")
    assert status == 0
    from flyopt import read_results

    cli = read_results(output)
    assert len(cli) == len(result.frame)
    for column in ("material", "status"):
        assert cli[column].tolist() == result.frame[column].tolist()
    for column in ("speed", "mass", "d_outer"):
        np.testing.assert_allclose(result.frame[column].to_numpy(float), cli[column].to_numpy(float), rtol=1e-12)

    # the file names the page's scene, not the server's private folder it was written to
    import pyarrow.parquet as pq

    metadata = json.loads(pq.read_schema(result.parquet).metadata[b"flyopt"])
    assert metadata["scene"] == model.SCENE_NAME and str(workspace.folder) not in json.dumps(metadata)
    from flyopt.studies.payload import digest

    assert metadata["scene_digest"] == digest(load(SHEAR))  # the name changes nothing: the same scene as the CLI's
    csv = sweeps.csv_file(result, workspace)
    assert csv.parent == workspace.folder  # the session's folder, nothing elsewhere
    assert {p.name for p in workspace.folder.iterdir()} <= {
        model.SCENE_NAME,
        sweeps.SCENE,
        sweeps.PARQUET,
        sweeps.CSV,
        sweeps.CSV + ".json",
    }
    assert read_results(csv)["mass"].tolist() == pytest.approx(cli["mass"].tolist())
    assert sweeps.plot_fields(result.frame) == ["speed", "material"]
    assert sweeps.plot_axes(result.frame) == ["speed"]  # the material is a line per value: no axis of text
    with pytest.raises(ValueError, match="column 'material' holds text, and an axis draws numbers"):
        sweeps.plot_shown(result.frame, "material", "mass")
    svg, found = sweeps.plot_shown(result.frame, "speed", "mass", "material")
    assert svg.startswith("<svg")
    (entry,) = json.loads(found)["axes"]  # the read-outs at the first speed: the command line's masses there
    first = cli[np.isclose(cli["speed"], cli["speed"].min())]
    assert entry["rows"][0][0] == "speed = 1,000 rpm"
    assert sorted(entry["rows"][0][1:]) == sorted(
        f"mass (material = {m}) = {display.quantity_text(v, 'mass', 'engineering')}"
        for m, v in zip(first["material"], first["mass"])
    )
    table = sweeps.table(result.frame, "engineering", materials.display_names(scene))
    assert table["speed [rpm]"].tolist() == [1000, 1000, 1250, 1250, 1500, 1500, 1750, 1750, 2000, 2000]


def test_a_sweep_over_the_limit_or_of_an_unknown_field_is_refused_in_the_command_s_words(workspace):
    scene = load(SHEAR)
    big = [sweeps.Axis("speed", "1000", "2000", 200, unit="rpm"), sweeps.Axis("delta", "0.01", "0.1", 100)]
    with pytest.raises(SceneError, match=r"20,000 points: the app runs at most 10,000"):
        sweeps.plan(scene, big)
    with pytest.raises(SceneError, match="did you mean 'speed'"):
        sweeps.plan(scene, [sweeps.Axis("sped", "1", "2", 3)])
    with pytest.raises(SceneError, match="from and to"):
        sweeps.plan(scene, [sweeps.Axis("speed", "", "2", 3)])
    first, total = sweeps.estimate(scene, [sweeps.Axis("speed", "1000", "2000", 5, unit="rpm")], 5)
    assert 0 < first and total == pytest.approx(5 * first)


@pytest.mark.parametrize("objectives", ["mass,outer_diameter", "mass,delta"])
def test_a_point_of_the_front_loaded_into_the_text_solves_to_that_point(workspace, objectives):
    """The text a click on the front loads is solved by flyopt's own solve (not the sweep that made the front) to
    the point's design: its material, mass and D; the scene's comments and layout kept."""
    import flyopt

    text = SHEAR.read_text(encoding="utf-8")
    scene = load(SHEAR)
    front = materials.pareto_front(scene, ["cast_iron", "cast_steel"], objectives, points=4)
    assert len(front) >= 3
    for index in range(len(front)):
        loaded = materials.point_text(text, scene, front, index)
        assert all(line in loaded.splitlines() for line in text.splitlines() if line.startswith("#"))
        design = flyopt.solve(flyopt.load(workspace.write(loaded))).design
        assert design.status == "designed"
        best, row = design.best, front.iloc[index]
        assert best.material == row["best_material"]
        assert best.mass == pytest.approx(row["mass"], rel=1e-6)
        assert best.dims.d_outer == pytest.approx(row["d_outer"], rel=1e-6)
    changed = dict(materials.point_changes(scene, front, 1))
    if objectives == "mass,delta":
        assert float(changed["machine.delta"]) == pytest.approx(front["delta"].iloc[1], rel=1e-9)
    else:
        assert changed["design.max_outer_diameter"].endswith(' mm"')
    assert changed["design.materials"] == f'["{front["best_material"].iloc[1]}"]'


def test_a_point_without_a_design_is_not_loaded():
    scene = load(SHEAR)
    front = pd.DataFrame({"status": ["infeasible"], "best_material": [None], "mass": [math.nan]})
    with pytest.raises(ValueError, match="no design"):
        materials.point_changes(scene, front, 0)
    with pytest.raises(IndexError):
        materials.point_changes(scene, front, 3)


def test_the_material_chart_draws_a_name_with_dollars_as_written():
    """An outside audit: a material named `a$\\frac$b` ended the Compare-materials chart in mathtext's
    ParseSyntaxException, since the chart's layout measured its labels before they were made drawable (the
    design tab, the sweep and Pareto plots drew the name). The chart is drawn, and the name is in it."""
    name = "a$\\frac$b"
    table = pd.DataFrame(
        {"material": ["cast_iron", name], "status": "designed", "mass": [1.0, 2.0], "d_outer": [0.3, 0.4]}
        | {"cost": [1.0, 2.0]}
    )
    plain = materials.chart_svg(table.replace({name: "ab"}), "engineering")
    svg = materials.chart_svg(table, "engineering")
    assert svg.startswith("<svg") and svg != plain  # drawn, with the name's own glyphs (text is drawn as paths)


def test_a_grid_over_the_apps_limit_is_refused_before_it_is_made(monkeypatch, workspace):
    """An outside audit: the form's plan made the whole grid (4000 x 4000 points: 3.4 s and 1 GB at each
    keystroke) and only then refused its count. The axes' counts are now refused before any grid is made."""
    from flyopt.studies import plan as plan_module

    scene = sweeps.scene_copy(SHEAR.read_text(encoding="utf-8"), workspace)
    big = [sweeps.Axis("speed", "1000", "2000", 4000, unit="rpm"), sweeps.Axis("delta", "0.01", "0.1", 4000)]

    def no_grid(*args, **kwargs):
        raise AssertionError("the grid was made")

    monkeypatch.setattr(plan_module.np, "meshgrid", no_grid)  # the grid's indices: made only under the cap
    with pytest.raises(SceneError, match=f"16,000,000 points: the app runs at most {sweeps.MAX_POINTS:,}"):
        sweeps.plan(scene, big)


@pytest.mark.parametrize(
    ("first", "total", "words"),
    [
        (0.006, 0.03, "the first point took 6 ms: at most about 30 ms in one process"),  # was "about 0.0 s"
        (0.0001, 0.0005, "the first point took under 1 ms: at most about 1 ms in one process"),
        (0.42, 4.2, "the first point took 420 ms: at most about 4.2 s in one process"),
        (0.21, 2100.0, "the first point took 210 ms: at most about 35 min in one process"),
    ],
)
def test_the_sweep_s_estimate_is_said_in_the_unit_that_reads(first, total, words):
    assert sweeps.estimate_text(first, total) == words
