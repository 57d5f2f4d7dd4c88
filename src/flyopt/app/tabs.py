"""The app's "Compare materials" and "Sweeps" tabs, laid out with Panel (passed in: the ``app`` extra).

Each tab reads the scene the Design tab last checked (:attr:`flyopt.app.page.Session.checked`) when it is
opened, and does its work in its own worker thread, off the server's event loop (a sweep does not hold up
the Design tab's solves), with a generation counter that drops the answer of a request a newer one replaced.
The logic is :mod:`flyopt.app.materials` and :mod:`flyopt.app.sweeps`; this module only lays it out.
"""

from __future__ import annotations

import asyncio
import io
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from flyopt.app import materials, model, sweeps
from flyopt.app.hover import hover_figure
from flyopt.said import counted

#: Shown where a tab needs a valid scene and the editor's text is not one.
NO_SCENE = "The scene in the editor is not valid: fix it on the Design tab first."

#: How many rows of a results table a page of the table shows.
PAGE_SIZE = 20


def _message(text: str, bad: bool = True) -> str:
    """One line for the tab's message pane, escaped."""
    colour = "#c33" if bad else "#555"
    return f'<div class="message" style="color:{colour}">{model.escape_text(text)}</div>'


def _error_text(err: BaseException) -> str:
    """An error in the command line's words: "FIELD: message" (SceneError), else its text."""
    field = getattr(err, "field", "")
    message = getattr(err, "message", None) or str(err) or type(err).__name__
    return f"{field}: {message}" if field else message


def show_table(widget: Any, frame: Any) -> None:
    """Put ``frame`` in a Tabulator, its numbers written as :func:`flyopt.report.display.number` wrote them
    (thousands grouped, no trailing zeros: Tabulator's own format adds a ".0" to every whole number)."""
    from bokeh.models.widgets.tables import NumberFormatter
    from pandas.api.types import is_float_dtype

    if frame is not None:
        widget.formatters = {
            c: NumberFormatter(format="0,0.[000000]", text_align="right")
            for c in frame.columns
            if is_float_dtype(frame[c])
        }
    widget.value = frame


class MaterialsTab:
    """The library with a tick per material; the trade-off of the ticked ones, its chart, their Pareto front."""

    def __init__(self, pn: Any, session: Any) -> None:
        self.pn = pn
        self.session = session
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flyopt-materials")
        self.generation = 0
        self.scene: Any = None
        self.text = ""  # the scene's text, as the Design tab checked it: what a point of the front is loaded into
        self.loaded = ""  # the text a click on the front last put in the editor
        self.units = ""
        self.table = None
        self.front = None
        self.names: dict[str, str] = {}
        self.message = pn.pane.HTML("", sizing_mode="stretch_width")
        self.library = pn.widgets.Tabulator(
            None,
            selectable="checkbox",
            disabled=True,
            show_index=False,
            height=330,
            layout="fit_data_stretch",
            sizing_mode="stretch_width",
            widths={"source": 420},
            css_classes=["library"],
        )
        show_table(self.library, materials.library_shown(materials.library(None), "engineering"))
        self.library.param.watch(self._ticked, "selection")
        self.tradeoff = pn.widgets.Tabulator(
            None, disabled=True, show_index=False, layout="fit_data", css_classes=["tradeoff"]
        )
        self.chart = pn.pane.HTML("", width=820, stylesheets=[_card_css()], css_classes=["figure", "tradeoff-chart"])
        self.objectives = pn.widgets.Select(label="Pareto front", options=list(materials.OBJECTIVES), width=220)
        self.pareto_button = pn.widgets.Button(label="Draw the front", color="primary", width=140)
        self.pareto_button.on_click(lambda _e: asyncio.ensure_future(self._pareto()))
        self.pareto_plot = hover_figure("", "", "pareto", sizing_mode="stretch_width", min_height=420)
        self.pareto_plot.param.watch(self._picked, "clicks")
        self.point = pn.pane.HTML("", stylesheets=[_card_css()], width=360, css_classes=["point"])
        self.view = pn.Column(
            pn.pane.HTML(
                "<b>Material library</b>: built-in and the scene's own <code>[[material]]</code>s. Tick the "
                "materials to compare: each one's lightest design (<code>flyopt tradeoff</code>).",
                sizing_mode="stretch_width",
            ),
            self.message,
            self.library,
            self.tradeoff,
            self.chart,
            pn.Row(self.objectives, self.pareto_button),
            pn.Row(self.pareto_plot, self.point, sizing_mode="stretch_width"),
            sizing_mode="stretch_width",
        )

    def close(self) -> None:
        self.executor.shutdown(wait=False, cancel_futures=True)

    def opened(self) -> None:
        """The tab is shown: take the Design tab's scene (its library and design materials ticked)."""
        checked = self.session.checked
        scene = checked.scene if checked is not None and not checked.problems else None
        if scene is None:
            self.message.object = _message(NO_SCENE)
            self.scene = None
            return
        units = self.session.units.value
        if (scene is self.scene or (self.loaded and checked.text == self.loaded)) and units == self.units:
            return  # the same scene, or a point of this front loaded from here: the front and its ticks stay
        ticked = self.ticked_names() if scene is self.scene else materials.design_materials(scene)
        self.scene, self.units, self.text, self.loaded = scene, units, checked.text, ""
        self.names = materials.display_names(scene)
        table = materials.library(scene)
        self.message.object = ""
        self.front = None
        self.pareto_plot.param.update(svg="", readout="")
        self.point.object = ""
        show_table(self.library, materials.library_shown(table, units))
        self.library.selection = [i for i, name in enumerate(table["name"]) if name in ticked]
        asyncio.ensure_future(self._tradeoff())  # the same ticks as before may not fire the selection's watcher

    def ticked_names(self) -> list[str]:
        frame = self.library.value
        return [str(frame["name"].iloc[i]) for i in self.library.selection if i < len(frame)]

    def _ticked(self, _event: Any) -> None:
        asyncio.ensure_future(self._tradeoff())

    async def _tradeoff(self) -> None:
        """The trade-off of the ticked materials, in the worker thread; a newer tick drops it."""
        if self.scene is None:
            return
        self.generation += 1
        mine = self.generation
        names = self.ticked_names()
        if not names:
            self.message.object = _message("Tick at least one material.", bad=False)
            return
        self.message.object = _message(f"designing {len(names)} material(s)…", bad=False)
        loop = asyncio.get_running_loop()
        units = self.session.units.value
        try:
            table = await loop.run_in_executor(self.executor, materials.tradeoff, self.scene, names)
            chart = await loop.run_in_executor(self.executor, materials.chart_svg, table, units, self.names)
        except Exception as err:  # noqa: BLE001 -- said in one line, as flyopt tradeoff says it
            if mine == self.generation:  # no table of other materials left under the message
                self.message.object = _message(_error_text(err))
                self.table = None
                show_table(self.tradeoff, None)
                self.chart.object = ""
            return
        if mine != self.generation:
            return
        self.table = table
        self.message.object = ""
        show_table(self.tradeoff, materials.shown(table, materials.TRADEOFF_SHOWN, units, self.names))
        self.chart.object = _fluid(chart) if chart else ""

    async def _pareto(self) -> None:
        if self.scene is None:
            self.message.object = _message(NO_SCENE)
            return
        names = self.ticked_names()
        loop = asyncio.get_running_loop()
        units = self.session.units.value
        self.pareto_button.disabled = True
        self.point.object = ""
        try:
            front = await loop.run_in_executor(
                self.executor, materials.pareto_front, self.scene, names, self.objectives.value
            )
            if front.empty:
                self.message.object = _message(front.attrs.get("message", "empty front"))
                self.pareto_plot.param.update(svg="", readout="")
                return
            svg, found = await loop.run_in_executor(self.executor, materials.pareto_svg, front, units, self.names)
        except Exception as err:  # noqa: BLE001 -- said in one line, as flyopt pareto says it
            self.message.object = _message(_error_text(err))
            return
        finally:
            self.pareto_button.disabled = False
        self.front = front
        self.message.object = ""
        self.pareto_plot.param.update(svg=svg, readout=found)

    def _picked(self, _event: Any) -> None:
        """A point of the front was clicked: its design beside the plot, and loaded into the editor (the scene
        that yields it: :func:`flyopt.app.materials.point_text`), where the Design tab solves it as an edit."""
        if self.front is None:
            return
        index = self.pareto_plot.picked
        try:
            lines = materials.point_rows(self.front, index, self.session.units.value, self.names)
            text = materials.point_text(self.text, self.scene, self.front, index)
        except IndexError:
            return
        except (ValueError, KeyError) as err:  # no design at that point, a key the text cannot take
            self.point.object = materials.rows_html(f"Design of point {index} of the front", lines)
            self.message.object = _message(_error_text(err))
            return
        self.point.object = materials.rows_html(f"Design of point {index} of the front, loaded into the editor", lines)
        self.loaded = text
        self.session.load(text)  # on the Design tab: the card and the diagrams of that design


def _card_css() -> str:
    """The page's style sheet (:data:`flyopt.app.page.CSS`), which the session hands the tabs."""
    return _STYLE["css"]


def _fluid(svg: str) -> str:
    """The SVG scaled to its pane's width, as the Design tab's diagrams (by the page's own function)."""
    return _STYLE["fluid"](svg)


#: The page's style sheet and SVG scaler, given by the page (:func:`style`): the tabs do not import the page.
_STYLE: dict[str, Any] = {"css": "", "fluid": lambda svg: svg}


def style(css: str, fluid: Any) -> None:
    """Take the page's style sheet and its function scaling an SVG to its pane (called by the page)."""
    _STYLE.update(css=css, fluid=fluid)


class SweepsTab:
    """A form building the ``--vary`` spec, its point count and estimate, the run with a bar and a Cancel,
    the results as a filterable table and the sweep plot, Parquet and CSV downloads."""

    ROWS = 2
    Y_CHOICES = ("mass", "d_outer", "b", "h", "cost", "rim_speed", "hoop_stress")

    def __init__(self, pn: Any, session: Any) -> None:
        from flyopt.io.sweep_spec import FIELDS

        self.pn = pn
        self.session = session
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flyopt-sweep")
        self.estimator = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flyopt-estimate")
        self.generation = 0
        self.estimate_generation = 0
        self.cancel_asked = False
        self.scene: Any = None
        self.plan: sweeps.Plan | None = None
        self.result: sweeps.Run | None = None
        fields = ["", *FIELDS]
        self.rows = []
        for i in range(self.ROWS):
            row = {
                "field": pn.widgets.Select(label="field", options=fields, value="speed" if i == 0 else "", width=200),
                "start": pn.widgets.TextInput(label="from", value="1000" if i == 0 else "", width=90),
                "stop": pn.widgets.TextInput(label="to", value="2000" if i == 0 else "", width=90),
                "count": pn.widgets.IntInput(label="points", value=5, start=1, end=sweeps.MAX_POINTS, width=80),
                "log": pn.widgets.Checkbox(label="log", value=False, width=50),
                "unit": pn.widgets.TextInput(label="unit", value="rpm" if i == 0 else "", width=80),
                "names": pn.widgets.TextInput(label="or names (a,b)", value="", width=200),
            }
            for widget in row.values():
                widget.param.watch(self._form_changed, "value")
            self.rows.append(row)
        self.where = pn.widgets.Select(
            label="run on", options=["this machine (processes)", "a Dask cluster"], value="this machine (processes)"
        )
        self.address = pn.widgets.TextInput(label="Dask address", placeholder="tcp://host:8786", width=220)
        if not model.served_locally:  # served beyond this machine: a visitor must not point the server at a scheduler
            self.where.options = ["this machine (processes)"]
            self.address.disabled = True
        self.spec = pn.pane.HTML("", sizing_mode="stretch_width", css_classes=["sweep-spec"])
        self.run_button = pn.widgets.Button(label="Run the sweep", color="primary", width=140)
        self.cancel_button = pn.widgets.Button(label="Cancel", color="warning", width=90, disabled=True)
        self.run_button.on_click(lambda _e: asyncio.ensure_future(self._run()))
        self.cancel_button.on_click(self._cancel)
        self.bar = pn.indicators.Progress(value=0, max=100, width=420, css_classes=["sweep-bar"])
        self.status = pn.pane.HTML("", css_classes=["sweep-status"])
        self.results = pn.widgets.Tabulator(
            None,
            disabled=True,
            show_index=False,
            header_filters=True,
            pagination="remote",
            page_size=PAGE_SIZE,
            layout="fit_data",
            width=700,
            css_classes=["sweep-table"],
        )
        self.x = pn.widgets.Select(label="x", options=[], width=160)
        self.y = pn.widgets.Select(label="y", options=list(self.Y_CHOICES), value="mass", width=140)
        self.by = pn.widgets.Select(label="one line per", options=[""], width=160)
        for widget in (self.x, self.y, self.by):
            widget.param.watch(lambda _e: self._draw(), "value")
        self.plot = hover_figure(
            "", "", "sweep", width=620, stylesheets=[_card_css()], css_classes=["figure", "sweep-plot"]
        )
        #: Offered once a sweep is done (a click with no file to give failed silently in the browser).
        self.downloads = [
            pn.widgets.FileDownload(
                callback=self._file("parquet"), filename="sweep.parquet", label="Parquet", disabled=True
            ),
            pn.widgets.FileDownload(callback=self._file("csv"), filename="sweep.csv", label="CSV", disabled=True),
        ]
        downloads = pn.Row(*self.downloads)
        form = pn.Column(
            *(pn.Row(*row.values()) for row in self.rows),
            pn.Row(self.where, self.address),
            self.spec,
            pn.Row(self.run_button, self.cancel_button, self.bar, self.status),
        )
        self.view = pn.Column(
            pn.pane.HTML(
                "<b>Sweep</b> the scene over a grid of its fields (<code>flyopt sweep --vary</code>): a range "
                "from, to, points (log: spaced in ratio), in the unit given, or a list of names; at most "
                f"{sweeps.MAX_POINTS:,} points.",
                sizing_mode="stretch_width",
            ),
            form,
            pn.Row(self.x, self.y, self.by, downloads),
            pn.Row(self.results, self.plot),
            sizing_mode="stretch_width",
        )

    def close(self) -> None:
        self.cancel_asked = True
        self.executor.shutdown(wait=False, cancel_futures=True)
        self.estimator.shutdown(wait=False, cancel_futures=True)

    def opened(self) -> None:
        """The tab is shown: take the Design tab's scene and count the form's points."""
        checked = self.session.checked
        text = checked.text if checked is not None and not checked.problems and checked.scene is not None else None
        if text is None:
            self.scene = None
            self.spec.object = _message(NO_SCENE)
            self.run_button.disabled = True
            return
        try:
            self.scene = sweeps.scene_copy(text, self.session.workspace)
        except Exception as err:  # noqa: BLE001 -- said in one line
            self.scene = None
            self.spec.object = _message(_error_text(err))
            return
        self._form_changed(None)

    def axes(self) -> list[sweeps.Axis]:
        return [
            sweeps.Axis(
                field=row["field"].value or "",
                start=row["start"].value,
                stop=row["stop"].value,
                count=int(row["count"].value or 1),
                log=bool(row["log"].value),
                unit=row["unit"].value,
                names=row["names"].value,
            )
            for row in self.rows
        ]

    def _form_changed(self, _event: Any) -> None:
        """Count the points of the form (the command's parser) and time its first point, in the background."""
        if self.scene is None:
            return
        axes = self.axes()
        try:
            self.plan = sweeps.plan(self.scene, axes)
        except Exception as err:  # noqa: BLE001 -- the command line's words
            self.plan = None
            self.spec.object = _message(_error_text(err))
            self.run_button.disabled = True
            return
        self.run_button.disabled = False
        self.spec.object = self._spec_html("timing the first point…")
        asyncio.ensure_future(self._estimate(axes, self.plan))

    def _spec_html(self, estimate: str) -> str:
        from html import escape

        if self.plan is None:
            return ""
        texts = " ".join(f"--vary '{escape(t)}'" for t in self.plan.texts)
        return (
            f'<div><b class="points">{self.plan.points:,} points</b> — {escape(estimate)}<br>'
            f"<small>as <code>flyopt sweep scene.toml {texts}</code></small></div>"
        )

    async def _estimate(self, axes: list[sweeps.Axis], plan: sweeps.Plan) -> None:
        self.estimate_generation += 1
        mine = self.estimate_generation
        loop = asyncio.get_running_loop()
        try:
            first, total = await loop.run_in_executor(self.estimator, sweeps.estimate, self.scene, axes, plan.points)
        except Exception as err:  # noqa: BLE001 -- the first point's own error, in one line
            if mine == self.estimate_generation:
                self.spec.object = self._spec_html(f"the first point fails: {_error_text(err)}")
            return
        if mine == self.estimate_generation and plan is self.plan:
            self.spec.object = self._spec_html(sweeps.estimate_text(first, total))

    def _cancel(self, _event: Any) -> None:
        self.cancel_asked = True
        self.status.object = _message("cancelling at the end of the running chunks…", bad=False)

    async def _run(self) -> None:
        if self.scene is None or self.plan is None:
            return
        self.generation += 1
        mine = self.generation
        self.cancel_asked = False
        self.run_button.disabled = True
        self.cancel_button.disabled = False
        self.result = None  # its files are removed by the new run: no download of them meanwhile
        self._offer(False)
        self.bar.value = 0
        self.status.object = _message(f"0 / {self.plan.points:,} points", bad=False)
        loop = asyncio.get_running_loop()
        scheduler = self.address.value.strip() if self.where.value == "a Dask cluster" else None

        def progress(done: int, total: int) -> None:
            loop.call_soon_threadsafe(self._progress, mine, done, total)

        def run() -> sweeps.Run:
            return sweeps.run(
                self.scene,
                self.plan.vary if self.plan is not None else {},
                self.session.workspace,
                scheduler=scheduler,
                progress=progress,
                cancelled=lambda: self.cancel_asked or mine != self.generation,
            )

        try:
            result = await loop.run_in_executor(self.executor, run)
        except Exception as err:  # noqa: BLE001 -- as flyopt sweep says it
            if mine == self.generation:
                self.status.object = _message(_error_text(err))
            return
        finally:
            if mine == self.generation:
                self.run_button.disabled = False
                self.cancel_button.disabled = True
        if mine != self.generation:
            return
        if not result.complete:
            self.status.object = _message(
                f"cancelled after {len(result.frame):,} of {counted(result.info['points'], 'point')}", bad=False
            )
            return
        self._show(result)

    def _show(self, result: sweeps.Run) -> None:
        """A finished sweep's status, table and plot (each of the last run replaced)."""
        self.result = result
        self._offer(result.parquet is not None)
        info = result.info
        # every point done: the bar full before the status says so (the last progress call, from the sweep's
        # thread, may not have reached the page yet: a loaded host showed "done: 5 points" beside a bar at 0)
        self.bar.value = 100
        self.status.object = _message(
            f"done: {counted(len(result.frame), 'point')} in {sweeps.duration_text(info['seconds'])} ({info['mode']})",
            bad=False,
        )
        units = self.session.units.value
        names = materials.display_names(self.scene)
        show_table(self.results, sweeps.table(result.frame, units, names))
        fields, axes = sweeps.plot_fields(result.frame), sweeps.plot_axes(result.frame)
        self.by.options = ["", *fields]
        self.x.options = axes  # a text field (the material) is a line per value, never an axis
        self.x.value = axes[0] if axes else None
        self.by.value = next((f for f in fields if f != self.x.value), "")
        self._draw()

    def _progress(self, mine: int, done: int, total: int) -> None:
        if mine != self.generation:
            return
        self.bar.value = int(round(100 * done / total)) if total else 100
        self.status.object = _message(f"{done:,} / {counted(total, 'point')}", bad=False)

    def _draw(self) -> None:
        if self.result is None:
            return
        if not self.x.value:  # the last sweep's plot is not left beside this one's table
            self.plot.param.update(
                svg=_message(
                    "the sweep varies no number to draw along x: a field of names (the material) is drawn as one "
                    "line per value along a varied number",
                    bad=False,
                ),
                readout="",
            )
            return
        by = self.by.value or None
        if by == self.x.value:
            by = None
        try:
            svg, found = sweeps.plot_shown(self.result.frame, self.x.value, self.y.value, by, self.session.units.value)
            self.plot.param.update(svg=_fluid(svg), readout=found)
        except ValueError as err:
            self.plot.param.update(svg=_message(str(err)), readout="")

    def _offer(self, on: bool) -> None:
        for button in self.downloads:
            button.disabled = not on

    def _file(self, kind: str) -> Any:
        def callback() -> io.BytesIO | None:
            if self.result is None or self.result.parquet is None:
                return None
            if kind == "parquet":
                return io.BytesIO(self.result.parquet.read_bytes())
            return io.BytesIO(sweeps.csv_file(self.result, self.session.workspace).read_bytes())

        return callback
