"""The form's widgets (Panel, the ``app`` extra): the common fields, a table's grid, its paste and its CSV upload.

What the widgets do is :mod:`flyopt.app.form`'s: they show the text's values after each valid edit
(:meth:`FormView.show`) and hand every change to ``write`` as the new text, which the page puts into
the editor (checked and solved there like a typed edit).
"""

from __future__ import annotations

import asyncio
import html
from collections.abc import Callable
from typing import Any

from flyopt.app import form
from flyopt.app.model import MAX_BYTES

#: How a limit of :data:`MAX_BYTES` reads in a message.
LIMIT = f"{MAX_BYTES / 1e6:g} MB"

#: Where a table too long for the app goes instead.
ELSEWHERE = "solve so long a table by flyopt solve, from a CSV file beside the scene (points_file)"

#: The units offered for a pasted or uploaded table's columns (the loader knows many more; type them in the editor).
ANGLE_UNITS = ("deg", "rad")
VALUE_UNITS = {
    "torque": ("N*m", "kN*m", "lbf*ft"),
    "force": ("N", "kN", "lbf"),
    "pressure": ("Pa", "kPa", "MPa", "bar", "psi"),
}


def _rows_written(text: str, pasted: str, path: str, units: tuple[str, str], source: str) -> str:
    """``text`` with the table at ``path`` holding the rows ``pasted`` (:func:`flyopt.app.form.pasted_rows`,
    :func:`flyopt.app.form.set_table_numbers`)."""
    numbers = form.pasted_rows(pasted, path, units, source)
    return form.set_table_numbers(text, path, numbers, units)


class FormView:
    """The form of one session; ``read()`` gives the editor's text, ``write(text)`` replaces it."""

    def __init__(
        self, pn: Any, read: Callable[[], str], write: Callable[[str], None], materials: Callable[[], dict[str, str]]
    ) -> None:
        self.pn = pn
        self.read, self.write, self.materials = read, write, materials
        self._showing = False  # True while the widgets are set from the text (their watchers write nothing)
        self.widgets: dict[str, Any] = {}
        for field in form.FIELDS:
            if field.kind == "choice":
                widget = pn.widgets.Select(label=field.label, options=["", *field.choices], value="")
            elif field.kind == "materials":
                widget = pn.widgets.MultiChoice(label=field.label, options={}, value=[])
            else:
                widget = pn.widgets.TextInput(label=field.label, value="")
            widget.param.watch(self._field_changed(field), "value")
            self.widgets[field.path] = widget
        self.shafts = pn.widgets.Tabulator(
            value=None, show_index=False, sizing_mode="stretch_width", height=130, editors={}, layout="fit_columns"
        )
        self.shafts.on_edit(self._shaft_edited)
        self.table = pn.widgets.Select(label="Table", options=[], value=None)
        self.table.param.watch(lambda _event: self._show_table(), "value")
        self.grid = pn.widgets.Tabulator(
            value=None, show_index=False, sizing_mode="stretch_width", height=260, editors={}, layout="fit_columns"
        )
        self.grid.on_edit(self._cell_edited)
        self.angle_unit = pn.widgets.Select(label="angle unit", options=list(ANGLE_UNITS), value="deg", width=110)
        self.value_unit = pn.widgets.Select(label="value unit", options=list(VALUE_UNITS["torque"]), width=110)
        self.paste = pn.widgets.TextAreaInput(
            label="Rows pasted from a spreadsheet (two columns: angle, value; tabs, commas or semicolons)",
            placeholder="0\t1600\n45\t1600\n90\t200\n360\t200",
            height=110,
            sizing_mode="stretch_width",
            # the browser's box keeps this many characters of a paste and drops the rest without a word (Panel's
            # default, 5,000, cut a spreadsheet's 300th row mid-number): one more than the app reads, so that a
            # paste it cut is always over the limit and refused, never read short
            max_length=MAX_BYTES + 1,
        )
        self.use_paste = pn.widgets.Button(label="Use the pasted rows", color="default")
        self.use_paste.on_click(self._paste_used)
        self.upload = pn.widgets.FileInput(accept=".csv,.txt", multiple=False)
        # Panel gives an empty file's value as None: its name's change says it came
        self.upload.param.watch(self._uploaded, ["value", "filename"])
        self.message = pn.pane.HTML("", sizing_mode="stretch_width")
        self.layout = pn.Column(
            pn.pane.HTML("<b>Common fields</b> (written into the TOML as if typed)"),
            *self.widgets.values(),
            pn.pane.HTML("<b>Shafts</b> (each [[shaft]] the scene writes: its name and speed ratio)"),
            self.shafts,
            pn.pane.HTML("<b>Tables</b>"),
            self.table,
            self.grid,
            pn.Row(self.angle_unit, self.value_unit),
            self.paste,
            pn.Row(self.use_paste, pn.pane.HTML("or a CSV file:"), self.upload),
            self.message,
            sizing_mode="stretch_width",
            height=340,  # the editor's: the page's answer card, below the two, stays in view (it scrolls within)
            styles={"overflow-y": "auto"},
        )

    # -- text -> form --------------------------------------------------------------------------

    def show(self, text: str) -> None:
        """Set the widgets from a valid text (nothing is written back)."""
        data = form.parse(text)
        if data is None:
            return
        self._showing = True
        try:
            library = self.materials()
            shown = form.shown_values(data)
            for field in form.FIELDS:
                widget = self.widgets[field.path]
                if field.kind == "materials":
                    names = {label: key for key, label in library.items()}
                    for key in shown[field.path]:
                        names.setdefault(key, key)
                    # the picker (Choices.js) shows its labels as HTML: a material named with markup would run
                    names = {html.escape(label): key for label, key in names.items()}
                    if widget.options != names:
                        widget.options = names
                    chosen = [k for k in shown[field.path] if k in names.values()]
                    if widget.value != chosen:
                        widget.value = chosen
                elif field.kind == "choice":
                    value = shown[field.path]
                    value = value if value in widget.options else ""
                    if widget.value != value:
                        widget.value = value
                elif widget.value != shown[field.path]:
                    widget.value = shown[field.path]
            self._show_shafts(data)
            found = form.tables(data)
            keep = self.table.value if self.table.value in found else (found[0] if found else None)
            if list(self.table.options) != found:
                self.table.options = found
            if self.table.value != keep:
                self.table.value = keep
            self._show_table(data)
        finally:
            self._showing = False

    def _show_shafts(self, data: dict[str, Any]) -> None:
        import pandas as pd

        rows = form.shaft_rows(data)
        shown = self.shafts.value
        if shown is not None and shown.astype(str).values.tolist() == rows:
            return  # the same shafts: nothing sent to the browser again
        self.shafts.value = pd.DataFrame(rows, columns=list(form.SHAFT_COLUMNS))
        self.shafts.editors = {c: {"type": "input"} for c in form.SHAFT_COLUMNS}

    def _show_table(self, data: dict[str, Any] | None = None) -> None:
        import pandas as pd

        path = self.table.value
        if data is None:
            data = form.parse(self.read()) or {}
        if not path:
            self.grid.value = pd.DataFrame({"angle": [], "value": []})
            return
        columns = form.columns_of(path)
        rows = form.rows_of(data, path)
        shown = self.grid.value
        if shown is not None and list(shown.columns) == list(columns) and shown.astype(str).values.tolist() == rows:
            return  # the same table: nothing sent to the browser again
        self.grid.value = pd.DataFrame(rows, columns=list(columns))
        self.grid.editors = {c: {"type": "input"} for c in columns}
        units = VALUE_UNITS.get(columns[1], ("N*m",))
        if list(self.value_unit.options) != list(units):
            self.value_unit.options = list(units)
            self.value_unit.value = units[0]

    # -- form -> text --------------------------------------------------------------------------

    def _field_changed(self, field: form.Field) -> Callable[[Any], None]:
        def changed(event: Any) -> None:
            if self._showing:
                return
            self._write(lambda text: form.set_field(text, field, event.new))

        return changed

    def _cell_edited(self, _event: Any) -> None:
        path = self.table.value
        if self._showing or not path:
            return
        rows = self.grid.value.astype(str).values.tolist()
        self._write(lambda text: form.set_rows(text, path, rows))

    def _shaft_edited(self, _event: Any) -> None:
        if self._showing:
            return
        rows = self.shafts.value.astype(str).values.tolist()
        self._write(lambda text: form.set_shafts(text, rows))

    async def _paste_used(self, _event: Any) -> None:
        pasted = self.paste.value or ""
        if len(pasted.encode("utf-8")) > MAX_BYTES:
            self._say(f"the pasted rows are over {LIMIT}, more than the app reads: {ELSEWHERE}")
            return
        await self._take_rows(pasted, "the pasted rows")

    async def _uploaded(self, *_events: Any) -> None:
        value, name = self.upload.value, self.upload.filename or "the file"
        if value is None and not self.upload.filename:
            return
        data = bytes(value) if value is not None else b""
        if not data:
            self._say(f"{name} is empty: a CSV of two columns of numbers is expected")
            return
        if len(data) > MAX_BYTES:
            self._say(f"{name} is {len(data) / 1e6:.1f} MB, more than the {LIMIT} the app reads: {ELSEWHERE}")
            return
        try:
            pasted = data.decode("utf-8-sig")
        except UnicodeDecodeError:
            self._say(f"{name} is not UTF-8 text: a CSV of two columns of numbers is expected")
            return
        await self._take_rows(pasted, name)

    async def _take_rows(self, pasted: str, source: str) -> None:
        """Read the rows and write them into the table the grid shows, in a worker thread (a megabyte of rows
        takes seconds to read and write into the text; the server's event loop serves every session); dropped
        with a word if the text changed meanwhile (another template, an edit), so that they never land in a
        text they were not read for."""
        from flyopt.errors import SceneError

        path = self.table.value
        if not path:
            self._say("the scene writes no table inline to fill (a points = [...] of a torque, force or pressure)")
            return
        units = (self.angle_unit.value, self.value_unit.value)
        before = self.read()
        try:
            text = await asyncio.get_running_loop().run_in_executor(
                None, _rows_written, before, pasted, path, units, source
            )
        except SceneError as err:
            self._say(f"{err.field}: {err.message}")
            return
        except KeyError as err:
            self._say(str(err.args[0]) if err.args else "that table cannot be set from the form")
            return
        if self.read() != before:
            what = source if source == "the pasted rows" else f"the rows of {source}"
            self._say(f"the scene changed while {what} were read: use them again")
            return
        self._write(lambda _text: text)

    def _write(self, change: Callable[[str], str]) -> None:
        try:
            text = change(self.read())
        except KeyError as err:
            self._say(str(err.args[0]) if err.args else "that field cannot be set from the form")
            self.show(self.read())  # the widgets back to what the text says: the refused change is not shown
            return
        size = len(text.encode("utf-8"))
        if size > MAX_BYTES:  # refused here, before the editor (and the browser) is sent a text it cannot send back
            self._say(
                f"with this the scene's text would be {size / 1e6:.1f} MB, more than the {LIMIT} the app reads: "
                f"{ELSEWHERE}"
            )
            self.show(self.read())
            return
        self._say("")
        self.write(text)

    def _say(self, message: str) -> None:
        from html import escape

        self.message.object = f'<div style="color:#c33">{escape(message)}</div>' if message else ""
