"""The app's form: a field or a table set there reads in the text as if typed, and flyopt's loader judges it."""

from __future__ import annotations

import html
from pathlib import Path

import pytest
import tomllib

import flyopt
from flyopt.app import form
from flyopt.cli.toml_lines import set_value
from flyopt.errors import SceneError

ROOT = Path(__file__).resolve().parents[2]
SHEAR = (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("path", "typed", "expected"),
    [
        ("machine.delta", "0.02", 0.02),
        ("machine.speed", "1450 rpm", "1450 rpm"),
        ("machine.efficiency", "0.9", 0.9),  # not written before: added to its table
        ("design.max_width", "250 mm", "250 mm"),
        ("design.hb_ratio", "1.2, 1.8", [1.2, 1.8]),
        ("design.geometry", "disc", "disc"),
    ],
)
def test_a_field_set_in_the_form_reads_back_by_tomllib_and_only_its_line_changes(path, typed, expected):
    field = next(f for f in form.FIELDS if f.path == path)
    edited = form.set_field(SHEAR, field, typed)
    data = tomllib.loads(edited)
    table, key = path.split(".")
    assert data[table][key] == expected
    before = tomllib.loads(SHEAR)
    data[table].pop(key)
    before[table].pop(key, None)
    assert data == before  # nothing else moved
    kept = [line for line in SHEAR.splitlines() if line.startswith("#")]
    assert kept == [line for line in edited.splitlines() if line.startswith("#")]  # comments kept
    assert form.shown_values(tomllib.loads(edited))[path] == (", ".join(typed.split(", ")) if "," in typed else typed)


def test_the_materials_are_written_as_a_list_of_names():
    field = next(f for f in form.FIELDS if f.kind == "materials")
    edited = form.set_field(SHEAR, field, ["cast_iron", "cast_steel"])
    assert tomllib.loads(edited)["design"]["materials"] == ["cast_iron", "cast_steel"]


def test_set_value_keeps_a_trailing_comment_and_refuses_an_entry_that_is_not_written():
    text = '[machine]\nspeed = "1500 rpm"   # the motor\ndelta = 0.05\n\n[[shaft]]\nname = "motor"\n'
    edited = set_value(text, "machine.speed", '"1450 rpm"')
    assert '"1450 rpm"   # the motor' in edited
    assert tomllib.loads(set_value(text, "shaft[0].speed_ratio", "2.5"))["shaft"][0] == {
        "name": "motor",
        "speed_ratio": 2.5,
    }
    with pytest.raises(KeyError):
        set_value(text, "shaft[1].speed_ratio", "2.5")
    assert tomllib.loads(set_value(text, "title", '"T"'))["title"] == "T"  # a top-level key before the tables


def test_a_typed_delta_solves_as_the_same_scene_written_by_hand(tmp_path):
    field = next(f for f in form.FIELDS if f.path == "machine.delta")
    by_form = tmp_path / "form.toml"
    by_form.write_text(form.set_field(SHEAR, field, "0.025"), encoding="utf-8")
    by_hand = tmp_path / "hand.toml"
    by_hand.write_text(SHEAR.replace("delta = 0.05", "delta = 0.025"), encoding="utf-8")
    assert "delta = 0.05" in SHEAR
    a, b = flyopt.solve(flyopt.load(by_form)), flyopt.solve(flyopt.load(by_hand))
    assert a.analysis.delta == b.analysis.delta == 0.025
    assert a.design.best.mass == b.design.best.mass


def test_the_tables_are_found_and_shown_as_cells():
    data = tomllib.loads(SHEAR)
    assert form.tables(data) == ["torque.resisting.points"]
    rows = form.rows_of(data, "torque.resisting.points")
    assert rows[0] == ["0 deg", "1600 N*m"] and len(rows) == len(data["torque"]["resisting"]["points"])
    press = tomllib.loads((ROOT / "problems" / "motor-press.toml").read_text(encoding="utf-8"))
    assert form.rows_of(press, "torque.resisting.points")[2] == ["150", "2000"]


def test_an_edited_cell_is_written_back_as_typed():
    data = tomllib.loads(SHEAR)
    rows = form.rows_of(data, "torque.resisting.points")
    rows[1][1] = "1500 N*m"
    edited = tomllib.loads(form.set_rows(SHEAR, "torque.resisting.points", rows))
    assert edited["torque"]["resisting"]["points"][1] == ["45 deg", "1500 N*m"]


def test_rows_pasted_from_a_spreadsheet_give_the_books_answer(tmp_path):
    """The shear press's table pasted as tab-separated numbers in degrees and N*m: A_max is the book's 1256.33 J
    (docs/flywheel-design.md, worked example 2), as with the table written with units."""
    pasted = "angle\ttorque\n0\t1600\n45\t1600\n90\t200\n360\t200\n"
    numbers = form.pasted_rows(pasted, "torque.resisting.points", ("deg", "N*m"))
    assert numbers == [[0.0, 1600.0], [45.0, 1600.0], [90.0, 200.0], [360.0, 200.0]]
    edited = form.set_table_numbers(SHEAR, "torque.resisting.points", numbers, ("deg", "N*m"))
    table = tomllib.loads(edited)["torque"]["resisting"]
    assert table["angle_unit"] == "deg" and table["unit"] == "N*m"
    path = tmp_path / "pasted.toml"
    path.write_text(edited, encoding="utf-8")
    analysis = flyopt.analyse(flyopt.load(path))
    assert analysis.a_max == pytest.approx(1256.33, abs=0.005)


def test_pasted_rows_that_are_not_a_table_are_refused_with_the_line():
    with pytest.raises(SceneError) as said:
        form.pasted_rows("0;1600\n45;x\n", "torque.resisting.points", ("deg", "N*m"))
    assert "line 2" in str(said.value)


@pytest.mark.parametrize(
    "typed", ["-.5", "+.5", "007", "1_", "1__0", "a\x7fb", "x\x85y", "inf", "0.05", "1_000", "1500 rpm"]
)
def test_whatever_is_typed_is_written_as_toml_tomllib_reads(typed):
    """A value typed in the form is a TOML number only where TOML reads it as one; anything else is a string
    holding exactly what was typed (DEL and the C1 controls escaped: TOML refuses them raw)."""
    value = tomllib.loads(f"v = {form.literal(typed)}")["v"]
    assert value == typed or (isinstance(value, (int, float)) and value == float(typed.replace("_", "")))


def test_the_shafts_are_shown_and_an_edited_ratio_or_name_is_written_as_typed(tmp_path):
    """The form's shafts (issue 29 names them among the common fields): punch-press's three [[shaft]] entries
    as cells; an edited speed ratio and name land on their own lines, the loader reads them, and a row for a
    shaft the text does not write is refused in words."""
    import difflib

    text = (ROOT / "problems" / "punch-press.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    rows = form.shaft_rows(data)
    assert [row[0] for row in rows] == [entry["name"] for entry in data["shaft"]]
    rows[1][1] = "12"
    rows[2][0] = "motor pulley"
    changed = form.set_shafts(text, rows)
    diff = [d for d in difflib.ndiff(text.splitlines(), changed.splitlines()) if d[:2] in ("- ", "+ ")]
    assert len(diff) == 4, diff  # two lines, each replaced
    back = tomllib.loads(changed)["shaft"]
    assert back[1]["speed_ratio"] == 12 and back[2]["name"] == "motor pulley"
    path = tmp_path / "edited.toml"
    path.write_text(changed, encoding="utf-8")
    scene = flyopt.load(path)
    assert {s.name: s.speed_ratio for s in scene.shafts}[back[1]["name"]] == 12
    with pytest.raises(KeyError, match=r"shaft\[3\]: add a \[\[shaft\]\] in the TOML"):
        form.set_shafts(text, [*form.shaft_rows(data), ["extra", "2"]])


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_the_forms_shafts_grid_shows_the_text_and_writes_an_edit_into_it():
    """The widgets' side: FormView shows punch-press's shafts in its grid, and an edited cell becomes the text."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app.form_view import FormView

    text = (ROOT / "problems" / "punch-press.toml").read_text(encoding="utf-8")
    written: list[str] = []
    view = FormView(pn, lambda: text, written.append, dict)
    view.show(text)
    grid = view.shafts.value
    assert grid.astype(str).values.tolist() == form.shaft_rows(tomllib.loads(text))
    edited = grid.copy()
    edited.loc[2, "speed_ratio"] = "25"
    view.shafts.value = edited
    view._shaft_edited(None)
    assert len(written) == 1 and tomllib.loads(written[0])["shaft"][2]["speed_ratio"] == 25


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_shafts_written_inline_are_refused_in_words_and_the_grid_shows_the_text_again():
    """shaft = [{...}] is a valid scene the form cannot edit line by line: said so, and the grid goes back."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app.form_view import FormView

    title = next(line for line in SHEAR.splitlines() if line.startswith("title = "))
    text = SHEAR.replace('[[shaft]]\nname = "motor"\nspeed_ratio = 1.0\n', "").replace(
        title, title + '\nshaft = [{ name = "motor", speed_ratio = 1.0 }]'
    )
    assert text != SHEAR and tomllib.loads(text)["shaft"] == [{"name": "motor", "speed_ratio": 1.0}]
    with pytest.raises(KeyError, match="written inline"):
        form.set_shafts(text, [["motor", "2"]])
    written: list[str] = []
    view = FormView(pn, lambda: text, written.append, dict)
    view.show(text)
    edited = view.shafts.value.copy()
    edited.loc[0, "speed_ratio"] = "2"
    view.shafts.value = edited
    view._shaft_edited(None)
    assert written == [] and "written inline" in view.message.object
    assert view.shafts.value.astype(str).values.tolist() == [["motor", "1.0"]]


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_the_materials_picker_shows_a_names_markup_as_text():
    """An outside audit: a [[material]] named `<img src=x onerror=alert(document.domain)>` ran as script in the
    page, because the form's materials picker (Choices.js) shows its labels as HTML. Its labels are escaped;
    the values stay the names the scene writes."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app.form_view import FormView

    name = "<img src=x onerror=alert(document.domain)>"
    text = (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")
    assert "materials" not in text and text.count("[design]\n") == 1
    text = text.replace("[design]\n", f'[design]\nmaterials = ["cast_iron", "{name}"]\n')
    assert tomllib.loads(text)["design"]["materials"] == ["cast_iron", name]
    view = FormView(pn, lambda: text, lambda _text: None, lambda: {"cast_iron": "cast iron", name: name})
    view.show(text)
    picker = view.widgets["design.materials"]
    assert name in picker.options.values() and name in picker.value
    assert all("<" not in label and ">" not in label for label in picker.options)
    assert html.escape(name) in picker.options


def _table_view(pn, text, written):
    from flyopt.app.form_view import FormView

    view = FormView(pn, lambda: text, written.append, dict)
    view.show(text)
    assert view.table.value == "torque.resisting.points"
    return view


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_an_uploaded_file_is_named_in_what_is_said_of_it_and_empty_or_oversized_ones_are_refused(monkeypatch):
    """An outside audit: an empty file was ignored without a word; a file of any size was read (and parsed on
    the server's event loop, which serves every session); a message named "the pasted rows", not the file.
    The files come as Panel hands them over from the browser (its FileInput's own processing: an empty file's
    value is None, which the page took for no file at all, as an outside review found)."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio
    import base64

    import param

    from flyopt.app.model import MAX_BYTES

    # the widgets' async watchers run to their end here, each on a loop closed after it (Panel's executor, off a
    # server, leaves a new loop open for each)
    monkeypatch.setattr(param.parameterized, "async_executor", lambda run: asyncio.run(run()))

    written: list[str] = []
    view = _table_view(pn, SHEAR, written)

    def upload(name: str, data: bytes) -> None:
        sent = {"value": base64.b64encode(data).decode(), "filename": name, "mime_type": "text/csv"}
        view.upload.param.update(**view.upload._process_property_change(sent))  # the watchers run here

    upload("empty.csv", b"")
    assert view.upload.value is None  # Panel's own reading of an empty file
    assert "empty.csv is empty" in view.message.object and written == []
    for data, said in [
        (b"0,1\n" * (MAX_BYTES // 4 + 1), "press-torque.csv is 1.0 MB, more than the 1 MB the app reads"),
        (b"0,1\n\xff\xfe,2\n", "press-torque.csv is not UTF-8 text"),
        (b"angle,torque\n0,1600\n45,x\n360,200\n", "press-torque.csv"),
    ]:
        upload("press-torque.csv", data)
        assert said in view.message.object and written == [], (said, view.message.object)
    assert "line 3" in view.message.object  # the loader's reader names the wrong line
    upload("press-torque.csv", b"angle,torque\n0,1600\n45,1600\n90,200\n360,200\n")
    assert view.message.object == "" and len(written) == 1
    assert tomllib.loads(written[0])["torque"]["resisting"]["points"][1] == [45.0, 1600.0]


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_rows_read_for_a_text_that_changed_meanwhile_are_dropped_with_a_word(monkeypatch):
    """An outside review: the rows were read in a worker, then written into whatever text was current when
    they came back: a template picked meanwhile got the shear press's table in its own torque.resisting."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio

    from flyopt.app import form_view

    current = [SHEAR]
    written: list[str] = []
    view = form_view.FormView(pn, lambda: current[0], written.append, dict)
    view.show(SHEAR)
    real = form_view._rows_written

    def slow(*args):  # the other template picked while the rows are read
        current[0] = (ROOT / "problems" / "punch-press.toml").read_text(encoding="utf-8")
        return real(*args)

    monkeypatch.setattr(form_view, "_rows_written", slow)
    view.paste.value = "0\t1\n180\t2\n360\t3\n"
    asyncio.run(view._paste_used(None))
    assert written == [] and "the scene changed while the pasted rows were read" in view.message.object


@pytest.mark.filterwarnings("ignore:The inplace keyword:Warning")  # pandas 3.1's, inside Panel's Tabulator
def test_pasted_rows_are_read_off_the_event_loop_and_a_table_too_long_for_the_app_is_refused_before_the_editor():
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio
    import threading

    from flyopt.app.model import MAX_BYTES

    written: list[str] = []
    view = _table_view(pn, SHEAR, written)
    # the browser's box keeps a paste up to its max_length and drops the rest silently (Panel's default 5,000
    # characters cut a spreadsheet's 300th row): it keeps more than the app reads, so a cut paste is refused
    assert view.paste.max_length > MAX_BYTES
    threads = []
    real = form.pasted_rows

    def reading(*args):
        threads.append(threading.current_thread())
        return real(*args)

    rows = "".join(f"{k * 360 / 44_999:.6f}\t{1600 if k < 5_625 else 200}\n" for k in range(45_000))
    assert 5_000 < len(rows) < MAX_BYTES
    view.paste.value = rows
    try:
        form.pasted_rows = reading
        asyncio.run(view._paste_used(None))
    finally:
        form.pasted_rows = real
    assert threads and threads[0] is not threading.main_thread()
    # 45,000 rows read, but written inline they make the text over the app's limit: refused before the editor
    assert written == [] and "text would be 1.1 MB" in view.message.object and "1 MB" in view.message.object
    view.paste.value = "0\t" + "1" * MAX_BYTES  # a paste the box cut: over the limit, refused unread
    asyncio.run(view._paste_used(None))
    assert written == [] and "the pasted rows are over 1 MB" in view.message.object
    view.paste.value = rows[: rows.index("\n", 6_000) + 1] + "360\t200\n"  # some 430 rows, over 5,000 characters
    assert len(view.paste.value) > 5_000
    asyncio.run(view._paste_used(None))
    assert view.message.object == "" and len(written) == 1
    assert len(tomllib.loads(written[0])["torque"]["resisting"]["points"]) == view.paste.value.count("\n")


def test_a_field_s_label_says_what_the_loader_takes_where_the_text_does_not_write_it():
    """The form shows an empty field where the text does not write it: its label says what flyopt then takes, as
    the loader takes it (a scene that writes neither the efficiency nor the rim's H/B)."""
    scene = flyopt.load(ROOT / "problems" / "shear-press.toml")
    data = form.parse((ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8"))
    shown = form.shown_values(data)
    labels = {f.path: f.label for f in form.FIELDS}
    assert shown["machine.efficiency"] == "" and shown["design.hb_ratio"] == ""
    assert f"; {scene.efficiency:g} if not given" in labels["machine.efficiency"]
    low, high = scene.design.hb_ratio
    assert f"; {low:g} to {high:g} if not given" in labels["design.hb_ratio"]
