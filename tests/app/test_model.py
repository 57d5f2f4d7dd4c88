"""The app's model layer without a browser: templates, checking, the answer card against ``flyopt solve --json``."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from conftest import run_flyopt

import flyopt
from flyopt.app import model
from flyopt.report import display

pytestmark = pytest.mark.usefixtures("close_figures")  # the app keeps figures open: none outlives a test


ROOT = Path(__file__).resolve().parents[2]


def test_templates_are_the_shipped_problems_and_the_textbook_gallery():
    found = model.templates()
    shipped = {p.stem for p in (ROOT / "problems").glob("*.toml")}
    textbook = {f"textbook/{p.stem}" for p in (ROOT / "problems" / "textbook").glob("*.toml")}
    assert shipped | textbook == set(found)
    assert model.template_text("shear-press") == (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")


def test_a_name_that_is_not_a_template_opens_nothing():
    for name in ("../pyproject", "/etc/passwd", "shear-press.toml"):
        with pytest.raises(KeyError):
            model.template_text(name)


def test_a_broken_delta_is_named_with_its_line(workspace):
    text = model.template_text("shear-press").replace("delta = 0.05", "delta = -1")
    checked = model.check(text, workspace)
    assert checked.scene is None
    [problem] = checked.problems
    assert problem.field == "machine.delta"
    assert "between 1e-06 and 2" in problem.message
    assert text.splitlines()[problem.line - 1].startswith("delta = -1")


def test_errors_in_two_sections_are_both_named_with_their_lines_as_flyopt_check_names_them(workspace, main_cli):
    """The card listed the first error alone; it lists what flyopt check lists (a δ and a design's geometry)."""
    text = (
        model.template_text("shear-press")
        .replace("delta = 0.05", "delta = -1")
        .replace('geometry = "rim"', 'geometry = "blob"')
    )
    checked = model.check(text, workspace)
    assert checked.scene is None
    assert [(p.field, text.splitlines()[p.line - 1].split(" =")[0]) for p in checked.problems] == [
        ("machine.delta", "delta"),
        ("design.geometry", "geometry"),
    ]
    path = workspace.folder / "cli.toml"
    path.write_text(text, encoding="utf-8")
    status, _, err = main_cli("check", path)
    assert status == 2 and [line.split(": ", 2)[2] for line in err.splitlines()] == [
        p.message for p in checked.problems
    ]
    html = model.card_html(None, checked.problems)
    assert "machine.delta" in html and "design.geometry" in html


def test_bad_toml_is_said_not_raised(workspace):
    checked = model.check("[machine\nspeed = 1", workspace)
    assert checked.scene is None and checked.problems


def test_field_line_finds_the_key_in_its_table():
    text = "title = 'x'\n[design]\ndelta = 3\n[machine]\nspeed = 1\ndelta = 2\n"
    assert model.field_line(text, "machine.delta") == 6
    assert model.field_line(text, "machine.speed") == 5
    assert model.field_line(text, "machine") == 4
    assert model.field_line(text, "nowhere.at_all") is None


def test_a_file_named_by_the_scene_is_not_read_outside_the_private_folder(workspace, tmp_path):
    outside = tmp_path / "torque.csv"
    outside.write_text("angle,torque\n0,1\n6.283185307179586,1\n", encoding="utf-8")
    text = model.template_text("four-stroke-engine-csv")
    for name in (str(outside), os.path.relpath(outside, workspace.folder)):
        broken = text.replace("four-stroke-engine-torque.csv", name.replace("\\", "/"))
        assert broken != text
        checked = model.check(broken, workspace)
        assert checked.scene is None and checked.problems, name


def test_a_template_that_keeps_its_table_beside_it_solves_in_the_private_folder(workspace):
    """four-stroke-engine-csv reads four-stroke-engine-torque.csv beside it: loaded in the app, its table comes
    with it into the session's folder and the page's answer is flyopt solve's (it failed with "cannot read")."""
    text = model.load_template("four-stroke-engine-csv", workspace)
    assert text == (ROOT / "problems" / "four-stroke-engine-csv.toml").read_text(encoding="utf-8")
    table = ROOT / "problems" / "four-stroke-engine-torque.csv"
    assert (workspace.folder / table.name).read_bytes() == table.read_bytes()
    checked = model.check(text, workspace)
    assert checked.scene is not None, checked.problems
    solved = run_flyopt("solve", ROOT / "problems" / "four-stroke-engine-csv.toml", "--json")
    assert solved.returncode == 0, solved.stderr
    answer = model.solve(text, workspace)
    assert json.loads(answer.json)["design"]["mass"] == json.loads(solved.stdout)["design"]["mass"]
    # a template that reads no file copies none
    before = sorted(workspace.folder.iterdir())
    model.load_template("shear-press", workspace)
    assert sorted(workspace.folder.iterdir()) == before


def test_a_missing_table_is_named_without_the_server_s_folder(workspace):
    checked = model.check(model.template_text("four-stroke-engine-csv"), workspace)  # the table not copied
    assert checked.scene is None
    (problem,) = checked.problems
    assert problem.field == "torque.driving.points_file" and problem.line == 22
    assert "cannot read four-stroke-engine-torque.csv" in problem.message, problem.message
    assert str(workspace.folder) not in problem.message and "flyopt-app-" not in problem.message
    # a file named "." is the folder itself (an outside review: its path was shown)
    text = model.template_text("four-stroke-engine-csv").replace('"four-stroke-engine-torque.csv"', '"."')
    (problem,) = model.check(text, workspace).problems
    assert "flyopt-app-" not in problem.message and "cannot read ." in problem.message, problem.message


def test_the_private_folder_takes_no_file_from_outside_it(workspace, tmp_path):
    for name in ("../x.csv", str(tmp_path / "x.csv"), model.SCENE_NAME):
        with pytest.raises(ValueError, match="not a name inside"):
            workspace.add(name, b"0")
    assert not (workspace.folder.parent / "x.csv").exists() and not (tmp_path / "x.csv").exists()


def test_the_text_is_refused_over_the_size_limit(workspace):
    checked = model.check("#" * (model.MAX_BYTES + 1), workspace)
    assert checked.scene is None and "over 1 MB" in checked.problems[0].message


def test_live_only_for_the_fast_models(workspace):
    assert model.live(model.check(model.template_text("shear-press"), workspace).scene)
    assert not model.live(model.check(model.template_text("press-drive"), workspace).scene)
    assert not model.live(model.check(model.template_text("motor-press"), workspace).scene)


def test_the_card_equals_flyopt_solve_json_to_the_digits_shown(workspace):
    text = model.template_text("shear-press")
    answer = model.solve(text, workspace)
    solved = run_flyopt("solve", ROOT / "problems" / "shear-press.toml", "--json")  # the command line, in process
    assert solved.returncode == 0, solved.stderr
    document = json.loads(solved.stdout)
    best = document["design"]
    expected = {
        "a_max": ("energy", document["a_max"]),
        "j_required": ("inertia", document["j_required"]),
        "omega_mean": ("angular_speed", document["omega_mean"]),
        "mass": ("mass", best["mass"]),
        "d_outer": ("length", best["d_outer"]),
        "h": ("length", best["h"]),
        "rim_speed": ("speed", best["rim_speed"]),
    }
    rows = {row.name: row for row in answer.card if row.name}
    for name, (dimension, value) in expected.items():
        shown = display.quantity_text(value, dimension, "engineering")
        assert rows[name].value.startswith(shown), (name, rows[name].value, shown)
    width = display.quantity_text(best["b"], "length", "engineering")
    assert width in rows["h"].value
    assert answer.status == "designed"
    assert json.loads(answer.json)["design"]["mass"] == best["mass"]
    # the material by its name for people (the JSON names it by its key)
    named = flyopt.load(ROOT / "problems" / "shear-press.toml").material_library()[best["material"]].display_name
    assert named in next(r.value for r in answer.card if r.label == "chosen wheel")


def test_the_apps_card_is_the_notebooks(workspace):
    """One answer card (issue 29): the app's and a notebook's ``Solution._repr_html_`` come from one builder
    (flyopt.report.card) and show the same title, status, verdict and rows, label for label."""
    import re
    from html import unescape

    def shown(card):
        rows = re.findall(r"<th[^>]*>(.*?)</th><td[^>]*>(.*?)</td>", card)
        head = re.search(r'<div class="status">(.*?)</div><p>(.*?)</p>', card).groups()
        return head, [(unescape(label), unescape(value)) for label, value in rows]

    answer = model.solve(model.template_text("shear-press"), workspace)  # solved and verified, as flyopt report
    app, notebook = model.card_html(answer, []), answer.solution._repr_html_()
    (status, verdict), rows = shown(app)
    assert shown(notebook) == ((status, verdict), rows)
    assert (
        "status <b>designed</b>" in status
        and verdict.startswith("A cast steel rim on the motor shaft, ")
        and "simulated, it gives δ" in verdict
    )
    labels = [label for label, _ in rows]
    assert {"mass", "outer diameter", "rim speed", "chosen wheel"} <= set(labels) and len(labels) >= 10


def test_the_figures_are_the_reports_and_the_downloads_open(workspace):
    from pypdf import PdfReader

    answer = model.solve(model.template_text("shear-press"), workspace)
    keys = [key for key, _, svg, *_ in answer.figures if svg]
    assert {"turning_moment", "energy", "stress", "cross_section", "speed"} <= set(keys)
    assert all(svg.lstrip().startswith("<svg") for _, _, svg, *_ in answer.figures if svg)
    readouts = {f.key: f.readout for f in answer.figures}  # the curves' read-outs; the drawing's radius only
    assert json.loads(readouts["speed"])["axes"][0]["rows"][0][0].startswith("φ = ")
    (section,) = json.loads(readouts["cross_section"])["axes"]
    assert section["rows"] == [] and section["across"]["rows"][0].startswith("r = ")
    html = model.report_bytes(answer, "html").decode("utf-8")
    assert "Shear press (worked example 2)" in html
    import io

    reader = PdfReader(io.BytesIO(model.report_bytes(answer, "pdf")))
    assert "Shear press" in reader.pages[0].extract_text()
    # the downloads name the page's scene, not the file in the server's private folder it was solved from
    pdf = "".join(page.extract_text() for page in reader.pages)
    for text in (html, pdf, answer.json):
        assert str(workspace.folder) not in text and model.SCENE_NAME in text
    assert json.loads(answer.json)["scene"] == model.SCENE_NAME


def test_the_card_comes_first_from_the_same_solve_and_the_diagrams_draw_without_solving_again(workspace, monkeypatch):
    """The card is the report's numbers without its diagrams (drawing is most of a report's time); the
    diagrams, drawn after, come from the same solve: with the solve made impossible they still draw, and they
    and the card are those of the whole answer at once."""
    import flyopt.cli.report as cli_report

    text = model.template_text("shear-press")
    whole = model.solve(text, workspace)
    first = model.numbers(text, workspace)
    assert not first.drawn and first.figures == []
    assert [(r.label, r.value) for r in first.card] == [(r.label, r.value) for r in whole.card]
    assert first.json == whole.json and first.status == whole.status == "designed"
    assert all(b.figure is None for b in model.figure_blocks(first.document))

    def no_second_solve(*_args, **_kwargs):
        raise AssertionError("the diagrams solved the scene again")

    monkeypatch.setattr(cli_report, "collect", no_second_solve)
    document = model.draw(first)
    figures = [model.figure_svg(block) for block in model.figure_blocks(document)]
    done = model.drawn(first, document, figures)
    assert done.drawn and [f.key for f in done.figures] == [f.key for f in whole.figures]
    assert [f.key for f in done.figures if f.svg] == [f.key for f in whole.figures if f.svg]
    # a download of an answer whose diagrams are not drawn yet draws them (the report is whole)
    html = model.report_bytes(first, "html").decode("utf-8")
    assert html.count("<svg") == sum(1 for f in whole.figures if f.svg)


def test_user_strings_are_escaped(workspace):
    problem = model.Problem("machine.<b>", "<script>alert(1)</script>", 3)
    html = model.card_html(None, [problem])
    assert "<script>" not in html and "&lt;script&gt;" in html and "<b>" not in html.split("</b>", 1)[1]
    answer = model.solve(model.template_text("shear-press").replace("Shear press", "<img src=x onerror=1>"), workspace)
    assert "<img" not in model.card_html(answer, [])


def test_the_footer_names_the_versions_and_the_scenes_hash(workspace):
    import hashlib

    import flyopt

    text = model.template_text("shear-press")
    footer = model.provenance_html(model.solve(text, workspace))
    assert hashlib.sha256(text.encode()).hexdigest() in footer
    assert f"flyopt {flyopt.__version__}" in footer and "IPOPT" in footer and "casadi" in footer


def test_flyopt_app_without_panel_refuses_in_one_line(monkeypatch, capsys):
    import importlib.util

    from flyopt.cli.main import main

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "panel" else real(name, *a))
    assert main(["app", "--no-browser"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and 'pip install "flyopt[app]"' in err


def test_the_wheels_drawing_and_solid_are_those_flyopt_export_writes(workspace, tmp_path):
    """The page's manufacturing downloads are the answer's own design as `flyopt export` draws it (the same
    drawing of the same wheel: its sheet's text equal, but the date), and none where there is no wheel."""
    from pypdf import PdfReader

    from flyopt.report.drawing import export

    answer = model.numbers(model.template_text("shear-press"), workspace)
    made = model.made_bytes(answer, "pdf", workspace)
    exported = tmp_path / "drawing.pdf"
    export(ROOT / "problems" / "shear-press.toml", exported)
    import io

    def words(data):
        return PdfReader(io.BytesIO(data)).pages[0].extract_text().split()

    ours, theirs = words(made), words(exported.read_bytes())
    assert ours == theirs or (len(ours) == len(theirs) and sum(a != b for a, b in zip(ours, theirs)) <= 1)
    assert "600" in " ".join(ours)  # D = 600 mm, the design's outer diameter
    if model.made_available("dxf"):
        import ezdxf

        dxf = ezdxf.read(io.StringIO(model.made_bytes(answer, "dxf", workspace).decode("utf-8")))
        assert len(dxf.modelspace()) > 20  # the views, the dimensions, the title block
    assert list(workspace.folder.iterdir()) == [workspace.path]  # nothing left beside the scene
    conveyor = model.numbers((ROOT / "problems" / "conveyor.toml").read_text(encoding="utf-8"), workspace)
    assert model.made_bytes(conveyor, "pdf", workspace) is None  # no flywheel needed: nothing to draw


def test_a_text_of_thousands_of_bad_keys_is_checked_at_once_and_listed_as_flyopt_check_lists_it():
    """An outside audit: `check` placed each problem by scanning the text's keys again, so a text of 4,000
    unknown keys took 61 s (quadratic) and the card listed all of them. The keys are scanned once and the
    problems listed as `flyopt check` lists them: the first 100 in the file's order, then the rest counted."""
    from flyopt.cli.scene import MAX_LISTED

    text = (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")
    text += "\n" + "\n".join(f"k{i} = {i}" for i in range(4000)) + "\n"
    space = model.Workspace()
    try:
        checked = model.check(text, space)
    finally:
        space.close()
    problems = checked.problems
    assert len(problems) == MAX_LISTED + 1
    assert problems[-1].message == f"{4000 - MAX_LISTED} more errors after these"
    first = text.splitlines().index("k0 = 0") + 1
    assert [p.line for p in problems[:MAX_LISTED]] == list(range(first, first + MAX_LISTED))
    assert all(str(space.folder) not in p.message for p in problems)


def test_an_edit_holds_the_collector_and_lets_it_run_after(monkeypatch):
    """edit_held: the collector off while an edit is solved and drawn (the report's own pauses nested in it), on
    again after; an edit that finds more than HELD_MOST objects waiting collects them first."""
    import gc

    from flyopt.report.plots import standard

    assert gc.isenabled()
    with model.edit_held():
        assert not gc.isenabled()
        with standard.collector_paused():  # build's and svg_of's pauses leave it to the hold
            pass
        assert not gc.isenabled()
    assert gc.isenabled()
    collected = []
    monkeypatch.setattr(gc, "collect", lambda generation=2: collected.append(generation) or 0)
    monkeypatch.setattr(gc, "get_count", lambda: (model.HELD_MOST + 1, 0, 0))
    with model.edit_held():
        pass
    assert collected == [1]
    monkeypatch.setattr(gc, "get_count", lambda: (model.HELD_MOST, 0, 0))
    with model.edit_held():
        pass
    assert collected == [1]


def test_the_pages_diagrams_set_their_texts_as_text_in_the_font_the_page_serves(workspace):
    """The page's SVG holds each text as a <text> in the font matplotlib measured it in (some 55 % smaller
    than glyph paths, and drawn faster), and the page serves that font's file under the family the SVG names."""
    import re

    from matplotlib import ft2font

    answer = model.solve(model.template_text("shear-press"), workspace)
    turning = next(f for f in answer.figures if f.key == "turning_moment")
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", turning.svg)
    assert "crank angle φ [deg]" in texts
    assert "DejaVuSans-" not in turning.svg  # no glyphs drawn as paths
    family, file = model.page_font()
    assert family == ft2font.FT2Font(str(file)).family_name and f"'{family}'" in turning.svg
    css = model.font_face_css()
    assert f'font-family: "{family}"' in css and f'url("/{model.FONT_ROUTE}/{file.name}")' in css
    model.close(answer.document)


def test_overlapping_holds_keep_the_collector_held_until_the_last_ends():
    """Two edits' holds (or an edit's and a figure's pause in the drawing worker) that end out of order: the
    collector runs again only when the last one ends (the first to end let it run under the other)."""
    import gc

    from flyopt.report.plots import standard

    assert gc.isenabled()
    first, second = model.edit_held(), standard.collector_paused()
    first.__enter__()
    second.__enter__()
    first.__exit__(None, None, None)
    assert not gc.isenabled()
    second.__exit__(None, None, None)
    assert gc.isenabled()
    gc.disable()  # paused by someone else (a caller's own choice): left so
    try:
        with model.edit_held():
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()
