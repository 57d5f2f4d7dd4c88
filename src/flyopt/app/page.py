"""The page of ``flyopt app``, laid out with Panel (imported here only: the ``app`` extra).

Left, the scene: a template picker and the TOML in a code editor; every edit
is checked as Panel hands it over (:func:`flyopt.app.model.check`) and its
problem shown inline with its field and line. Right, always in view, the
answer card; below it the report's diagrams. A scene of the fast models is
solved on every valid edit; a drive or a motor's dynamics waits for the Solve
button. The card is shown from the report's numbers first
(:func:`flyopt.app.model.numbers`), then the diagrams of the same solve are
drawn and shown one by one (:func:`flyopt.app.model.draw`); an edit meanwhile
drops the rest. Every solve runs in a worker thread, the diagrams in another, off the server's event
loop (docs/app.md "Latency"), with a busy line and a Cancel (which drops the answer of the running solve:
a thread cannot be stopped, it finishes in the background and is ignored).
Downloads: the report (HTML or PDF, in the units picked), the scene, the JSON.
Beside the Design tab, "Compare materials" and "Sweeps" (:mod:`flyopt.app.tabs`).
"""

from __future__ import annotations

import asyncio
import contextlib
import io
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from flyopt.app import address, model

#: The page's own pause after an edit before the text is checked and its numbers solved, in seconds. Panel
#: already holds the editor's changes for 50 ms before the page sees them (its widgets' ``_debounce``): a pause
#: of the page's on top of it added 50 ms to every answer, so the page waits only for the events of the same
#: tick; the check and the card's numbers of a fast scene take some 35 ms, and an edit that comes while they
#: run drops their answer.
DEBOUNCE = 0.0

#: What the page says when its connection to the server is lost (the server stopped, or a message over the
#: websocket's limit of 4 x :data:`flyopt.app.model.MAX_BYTES` closed it): its answer is no longer kept current.
DISCONNECTED = (
    "The connection to flyopt was lost (the server stopped, or the page sent more than it takes: a scene text "
    f"or a file over {model.MAX_BYTES // 1_000_000} MB is refused). Reload the page; what is shown is not current."
)

#: The template shown first.
FIRST = "shear-press"

#: What of the page is the last scene solved's while the editor's text is not valid (or not yet solved): the
#: diagrams and downloads, or the downloads alone where no diagram of it is shown (an edit came while its first
#: were drawn). Said above them, and on the card under the problems (:func:`flyopt.app.model.card_html`).
STALE_WORDS = "The diagrams and downloads {where} are those of the last scene solved, not of the text in the editor."
STALE_DOWNLOADS_WORDS = "The downloads {where} are those of the last scene solved, not of the text in the editor."


def _stale_html(words: str) -> str:
    """The note above the downloads and diagrams (``words`` said "below" them); "" for no words."""
    return f'<div style="color:#c33;font-weight:bold">{words}</div>' if words else ""


STALE = _stale_html(STALE_WORDS.format(where="below"))
STALE_DOWNLOADS = _stale_html(STALE_DOWNLOADS_WORDS.format(where="below"))

CSS = """
.card {font-family: sans-serif; font-size: 14px; padding: 6px 10px; border-left: 4px solid #2a7;}
.card.bad {border-left-color: #c33;}
.card table {border-collapse: collapse;} .card th {text-align: left; font-weight: normal; color: #555;
 padding: 1px 12px 1px 0; vertical-align: top;} .card td {padding: 1px 0;}
.card .status {font-size: 15px;} .card ul {margin: 4px 0; padding-left: 18px;}
.card .stale-note {color: #c33; margin: 4px 0 0 0;}
.footer {font-family: monospace; font-size: 11px; color: #555;}
.figure svg {max-width: 100%; height: auto;}
"""


#: What a request for the page may name in its ``Host`` besides an address and localhost
#: (:func:`flyopt.app.address.served_names`), set by :func:`serve`; a request naming anything else, or made by
#: another site's page, builds no session (:func:`flyopt.app.address.refused_request`).
SERVED_NAMES: set[str] = set()


def session() -> Any:
    """One browser session's page (Panel calls this once per visitor); a line saying why for a request that
    builds none (one another site's page made)."""
    import html

    import panel as pn

    refused = address.refused_request(pn.state.headers, SERVED_NAMES) if SERVED_NAMES else None
    if refused is not None:
        return pn.pane.HTML(f"<p>flyopt: {html.escape(refused)}</p>")
    return Session(pn).layout


class Session:
    """The widgets of one visitor and what they do; the scene's private folder lives as long as the session."""

    def __init__(self, pn: Any) -> None:
        self.pn = pn
        self.workspace = model.Workspace()
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flyopt-solve")
        #: The diagrams' worker: a diagram being drawn does not hold up the next edit's check and numbers.
        self.drawer = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flyopt-draw")
        self.answer: model.Answer | None = None
        self.checked: model.Checked | None = None
        self.generation = 0
        names = list(model.templates())
        first = FIRST if FIRST in names else (names[0] if names else "")
        self.template = pn.widgets.Select(label="Template (problems/)", options=names, value=first or None, width=320)
        self.units = pn.widgets.Select(label="Units", options=["engineering", "si", "imperial"], value="engineering")
        self.editor = pn.widgets.CodeEditor(
            value=model.load_template(first, self.workspace) if first else "",
            language="toml",
            # the text is read from value_input alone, which the browser sends on every change. With on_keyup the
            # browser sends value too, and Panel copies each value it receives into value_input: on a loaded host
            # (four busy loops on 2 cores) a value of an earlier keystroke reached the server after value_input
            # of the last, and the page solved 'delta = 0.02' under an editor showing 'delta = 0.025', with no
            # change left to come (traced; test_browser's edit test failed 1 run in 2-4, then 0 in 10)
            on_keyup=False,
            sizing_mode="stretch_width",
            height=340,  # the answer card below it stays in view beside the diagrams
        )
        #: The editor's text as last typed, loaded or written by the form: what is checked, solved and downloaded
        #: (the editor's own value and value_input each lag behind one of those).
        self.text: str = str(self.editor.value)
        self.solve_button = pn.widgets.Button(label="Solve", color="primary", width=90)
        self.cancel_button = pn.widgets.Button(label="Cancel", color="warning", width=90, disabled=True)
        self.busy = pn.indicators.LoadingSpinner(value=False, width=24, height=24)
        self.mode = pn.pane.HTML("", css_classes=["mode"])
        from flyopt.app.markup import markup

        self.card = markup(model.card_html(None, []), stylesheets=[CSS], sizing_mode="stretch_width")
        self.figures = pn.Column(sizing_mode="stretch_width")
        #: Each diagram's place: (its column, the caption's pane, the SVG's pane), kept from answer to answer.
        self.figure_slots: list[tuple[Any, Any, Any]] = []
        self.showing: list[model.Shown] = []  # what each of figure_slots shows (flyopt.app.diagrams.kept)
        self.stale = pn.pane.HTML("", sizing_mode="stretch_width")
        self.footer = markup(
            f'<div class="footer">{model.provenance_html(None)}</div>', stylesheets=[CSS], sizing_mode="stretch_width"
        )
        #: The downloads of an answer, and those of its wheel: offered (enabled) only when there is one, so that
        #: a click always gives a file (a download with nothing to give failed silently in the browser).
        self.answer_downloads = [
            pn.widgets.FileDownload(
                callback=self._report("html"), filename="report.html", label="Report (HTML)", disabled=True
            ),
            pn.widgets.FileDownload(
                callback=self._report("pdf"), filename="report.pdf", label="Report (PDF)", disabled=True
            ),
            pn.widgets.FileDownload(callback=self._json, filename="solution.json", label="JSON", disabled=True),
        ]
        self.wheel_downloads = [
            pn.widgets.FileDownload(callback=self._made(kind), filename=name, label=label, disabled=True)
            for kind, label, name in model.MADE
            if model.made_available(kind)
        ]
        downloads = [
            *self.answer_downloads[:2],
            pn.widgets.FileDownload(callback=self._scene, filename="scene.toml", label="Scene (TOML)"),
            *self.answer_downloads[2:],
            *self.wheel_downloads,
        ]
        self.template.param.watch(self._load_template, "value")
        text_parameter = "value_input" if "value_input" in self.editor.param else "value"
        self.editor.param.watch(self._edited, text_parameter)
        self.units.param.watch(self._edited, "value")
        self.solve_button.on_click(self._solve_clicked)
        self.cancel_button.on_click(self._cancel)
        from flyopt.app.form_view import FormView

        self.form = FormView(pn, self._text, self._set_text, self._materials)
        # The two columns scroll apart, each within the page's height: the scene and its answer card on the left
        # stay in view (the "always visible") while the diagrams on the right are scrolled through.
        within_page = {"overflow-y": "auto", "max-height": "calc(100vh - 90px)"}
        left = pn.Column(
            pn.Row(self.template, self.units),
            pn.Tabs(
                ("Scene (TOML)", self.editor), ("Form", self.form.layout), dynamic=False, sizing_mode="stretch_width"
            ),
            pn.Row(self.solve_button, self.cancel_button, self.busy, self.mode),
            self.card,
            sizing_mode="stretch_width",
            min_width=480,
            styles=within_page,
        )
        right = pn.Column(
            pn.FlexBox(*downloads, flex_wrap="wrap"),
            self.stale,
            self.figures,
            sizing_mode="stretch_width",
            min_width=520,
            styles=within_page,
        )
        right.append(self.footer)
        from flyopt.app.tabs import MaterialsTab, SweepsTab, style

        style(CSS, _fluid)
        self.materials_tab = MaterialsTab(pn, self)
        self.sweeps_tab = SweepsTab(pn, self)
        self.tabs = pn.Tabs(
            ("Design", pn.Row(left, right, sizing_mode="stretch_width")),
            ("Compare materials", self.materials_tab.view),
            ("Sweeps", self.sweeps_tab.view),
            sizing_mode="stretch_width",
        )
        self.tabs.param.watch(self._tab_opened, "active")
        # no busy indicator of the template's: it sent the browser two changes (two layouts of the page) around
        # every edit; the page's own spinner says when it works
        self.layout = pn.template.BootstrapTemplate(
            title="flyopt — flywheel design", main=[self.tabs], busy_indicator=None
        )
        pn.state.on_session_destroyed(lambda _context: self.close())
        pn.state.onload(lambda: asyncio.ensure_future(self._refresh(self.text, solve=None)))

    def close(self) -> None:
        """Drop the session's work, folder and figures: whatever is in flight is stale (its answer, arriving, is
        closed, not shown), the answer shown is closed in the drawing worker after the diagram it may be drawing,
        and that worker stops once its queue is done (a diagram at most, and closings, which must run: a server
        serves one visitor after another, and a figure left open stays in matplotlib's registry for good)."""
        self.generation += 1
        answer, self.answer = self.answer, None
        self.executor.shutdown(wait=False, cancel_futures=True)
        if answer is not None:
            self._drop(model.close, answer.document)
        self.drawer.shutdown(wait=False)
        self.materials_tab.close()
        self.sweeps_tab.close()
        self.workspace.close()

    # -- the text ------------------------------------------------------------------------------

    def _text(self) -> str:
        return self.text

    def _set_text(self, text: str) -> None:
        """The form's change, put into the editor (and so checked and solved as a typed edit)."""
        self.text = self.editor.value = text
        asyncio.ensure_future(self._debounced(text))

    def load(self, text: str) -> None:
        """Put ``text`` in the editor as a design loaded from another tab (a point of the Pareto front), shown on
        the Design tab: checked and solved as a typed edit."""
        self._set_text(text)
        self.tabs.active = 0

    def _materials(self) -> dict[str, str]:
        """The scene's material library by key, with the names people read (the last valid text's)."""
        scene = self.checked.scene if self.checked is not None else None
        if scene is None:
            return {}
        return {key: material.display_name for key, material in scene.material_library().items()}

    # -- events --------------------------------------------------------------------------------

    def _tab_opened(self, event: Any) -> None:
        """A tab is shown: the materials and sweeps tabs take the scene the Design tab last checked."""
        if event.new == 1:
            self.materials_tab.opened()
        elif event.new == 2:
            self.sweeps_tab.opened()

    def _load_template(self, event: Any) -> None:
        if event.new:
            self.text = self.editor.value = model.load_template(event.new, self.workspace)
            asyncio.ensure_future(self._refresh(self.text, solve=None))

    def _edited(self, event: Any) -> None:
        if event.obj is self.editor:  # else the units' Select: the text as it is
            self.text = str(event.new)
        asyncio.ensure_future(self._debounced(self.text))

    async def _debounced(self, text: str) -> None:
        self.generation += 1
        mine = self.generation
        await asyncio.sleep(DEBOUNCE)
        if mine == self.generation:
            await self._refresh(text, solve=None)

    def _solve_clicked(self, _event: Any) -> None:
        asyncio.ensure_future(self._refresh(self.text, solve=True))

    def _cancel(self, _event: Any) -> None:
        self.generation += 1  # the running solve's answer is dropped when it arrives
        self._busy(False)
        self.card.html = model.card_html(self.answer, [], busy="cancelled: showing the last answer")

    # -- work ----------------------------------------------------------------------------------

    async def _refresh(self, text: str, solve: bool | None) -> None:
        """Check ``text``; solve it when it is valid and (``solve`` None) fast, or when asked.

        Each change the browser is sent costs it some of a layout of the page, so a fast scene sends nothing
        between its edit and its card: the last answer stays in view until the new card replaces it, the card
        first, then the footer, the form, the mode and the busy line. (Not in one message by Panel's
        ``pn.io.hold``: traced, a hold released while the editor's newer text was on its way sent the server's
        older text back to the browser, over the keys typed since.) The diagrams are drawn after the card has
        left (:meth:`_draw`, in their own worker), so a newer edit's check and numbers never wait behind one.
        """
        self.generation += 1
        mine = self.generation
        loop = asyncio.get_running_loop()
        units = self.units.value
        checked = await loop.run_in_executor(self.executor, model.check, text, self.workspace)
        if mine != self.generation:
            return
        self.checked = checked
        if checked.problems or checked.scene is None:
            self.card.html = model.card_html(None, checked.problems, stale=self._stale_words())
            self.stale.object = self._stale()
            self._busy(False)  # an older edit's work still running is dropped: nothing is being done for this one
            return
        fast = model.live(checked.scene)
        mode = "<small>solved on every edit</small>" if fast else "<small>a slow model: press Solve</small>"
        if solve is None and not fast:  # the last answer is not this scene's: not shown on the card
            self.card.html = model.card_html(None, [], busy="The scene is valid; press Solve for its answer.")
            self.form.show(text)
            self.mode.object = mode
            self.stale.object = self._stale()
            self._busy(False)  # as above: Solve is this scene's next step, so it is offered
            return
        if not fast:
            self.card.html = model.card_html(None, [], busy="Solving (a slow model)…")
            self.form.show(text)
            self.mode.object = mode
            self._busy(True)
            self.stale.object = self._stale()
        # a fast scene's edit holds the collector from its numbers to its last diagram (a slow one's, while it draws)
        with model.edit_held() if fast else contextlib.nullcontext():
            try:
                answer = await loop.run_in_executor(self.executor, model.numbers, text, self.workspace, units)
            except Exception as err:  # noqa: BLE001 -- said on the card, as the CLI says it in one line
                if mine == self.generation:
                    field = getattr(err, "field", "")
                    message = getattr(err, "message", None) or f"{type(err).__name__}: {err}"
                    line = model.field_line(text, field) if field else None
                    problem = model.Problem(field, message, line)
                    self.card.html = model.card_html(None, [problem], stale=self._stale_words())
                    self.stale.object = self._stale()
                    self._busy(False)
                    self.form.show(text)
                    self.mode.object = mode
                return
            if mine != self.generation:
                return
            self.card.html = model.card_html(answer, [], busy="" if answer.drawn else "drawing the diagrams…")
            self._take(answer)
            self.footer.html = f'<div class="footer">{model.provenance_html(answer)}</div>'
            self.form.show(text)
            self.mode.object = mode
            self._busy(not answer.drawn)
            if answer.drawn:  # a calculation's few figures come with its numbers
                self._show_figures(answer.figures)
            if not answer.drawn:
                await asyncio.sleep(0)  # the card's message leaves before a diagram takes the interpreter
                if await self._draw(answer, mine, loop) and mine == self.generation:
                    self.card.html = model.card_html(self.answer, [])
                    self._busy(False)

    async def _draw(self, answer: model.Answer, mine: int, loop: asyncio.AbstractEventLoop) -> bool:
        """Draw ``answer``'s diagrams in the drawing worker, those in view first (:class:`flyopt.app.diagrams.Diagrams`),
        each shown as soon as it is drawn (over the last answer's, in its place); dropped as soon as a newer
        edit comes (checked between diagrams: a diagram being drawn cannot be stopped, but the newer edit's check
        and numbers run beside it in the solving worker, and nothing more of the stale answer is drawn). Whether
        every diagram was drawn: a diagram that fails is said on the card, and its drawing's figures closed."""
        from flyopt.app.diagrams import Diagrams

        diagrams = Diagrams(answer, self._in_view(), list(self.showing))
        with model.edit_held():  # nested in a fast scene's: the collector held while the diagrams are drawn
            while True:
                try:
                    step = await loop.run_in_executor(self.drawer, diagrams.step)
                except Exception as err:  # noqa: BLE001 -- said on the card, as a failed solve is
                    self._drop(diagrams.close)
                    if mine == self.generation:
                        self._busy(False)
                        self.card.html = model.card_html(
                            answer, [], busy=f"The diagrams could not be drawn: {type(err).__name__}: {err}"
                        )
                    return False
                if mine != self.generation:
                    self._drop(diagrams.close)
                    return False
                if step is None:
                    break
                index, figure = step
                if index <= len(self.figure_slots):  # a place further down is added in order, below
                    self._show_figure(index, figure)
            shown = diagrams.figures()
            self._show_figures(shown)
            self._take(model.drawn(answer, diagrams.document(), shown))
            return True

    def _stale(self) -> str:
        """The note above the downloads and diagrams while they are not the editor's text's."""
        return _stale_html(self._stale_words("below"))

    def _stale_words(self, where: str = "on the right") -> str:
        """What of the page is the last scene solved's, said from ``where`` it stands ("on the right" on the card):
        the diagrams only where some are shown; "" before any scene is solved."""
        if self.answer is None:
            return ""
        shown = any(svg_pane.visible for _column, _title, svg_pane in self.figure_slots)
        return (STALE_WORDS if shown else STALE_DOWNLOADS_WORDS).format(where=where)

    def _in_view(self) -> dict[str, float]:
        """The diagrams on the page by key, each with the fraction of it the visitor has in view (the page's order)."""
        return {svg_pane.key: float(svg_pane.seen) for _column, _title, svg_pane in self.figure_slots if svg_pane.key}

    def _take(self, answer: model.Answer) -> None:
        """Make ``answer`` the one shown and downloaded, closing the figures of the one it replaces."""
        old, self.answer = self.answer, answer
        self.stale.object = ""
        for button in self.answer_downloads:
            button.disabled = False
        wheel = model.wheel_of(answer) is not None
        for button in self.wheel_downloads:
            button.disabled = not wheel
        if old is not None and old.document is not answer.document:
            self._drop(model.close, old.document)

    def _drop(self, close: Callable[..., None], *args: Any) -> None:
        """``close(*args)``, which closes figures under the drawing lock (:func:`flyopt.app.model.close` of a
        document, :meth:`flyopt.app.diagrams.Diagrams.close`), in the drawing worker: closing waits for the lock,
        which a diagram may be holding. Here once the session has closed (its worker takes no more work)."""
        try:
            self.drawer.submit(close, *args)
        except RuntimeError:
            close(*args)

    def _show_figures(self, figures: list[model.Shown]) -> None:
        """Show exactly ``figures``, in order."""
        for index, figure in enumerate(figures):
            self._show_figure(index, figure)
        del self.figure_slots[len(figures) :]
        del self.showing[len(figures) :]
        if len(self.figures.objects) != len(figures):
            self.figures.objects = [slot[0] for slot in self.figure_slots]

    def _show_figure(self, index: int, shown: model.Shown) -> None:
        """Show one diagram in the ``index``-th place, with its read-outs under the pointer
        (:mod:`flyopt.app.hover`): its panes kept and only their contents changed (the browser redraws that
        diagram alone), a place added where there was none."""
        from flyopt.app.hover import hover_figure

        pn = self.pn
        key, caption, svg, readout = shown.key, shown.caption, shown.svg, shown.readout
        title = f"<b>{model.escape_text(caption)}</b>"
        body = _fluid(svg) if svg else ""
        classes = ["figure", f"figure-{key}"]
        if index < len(self.figure_slots):
            _column, title_pane, svg_pane = self.figure_slots[index]
            title_pane.object = title
            if svg_pane.css_classes != classes:
                svg_pane.css_classes = classes
            svg_pane.param.update(svg=body, readout=readout, key=key, visible=bool(svg))
            self.showing[index] = shown
            return
        title_pane = pn.pane.HTML(title, sizing_mode="stretch_width")
        svg_pane = hover_figure(
            body, readout, key, css_classes=classes, stylesheets=[CSS], sizing_mode="stretch_width", visible=bool(svg)
        )
        column = pn.Column(title_pane, svg_pane, sizing_mode="stretch_width")
        self.figure_slots.append((column, title_pane, svg_pane))
        self.showing.append(shown)
        self.figures.append(column)

    def _busy(self, on: bool) -> None:
        self.busy.value = on
        self.cancel_button.disabled = not on
        self.solve_button.disabled = on

    # -- downloads -----------------------------------------------------------------------------

    def _report(self, kind: str) -> Any:
        def callback() -> io.BytesIO | None:
            if self.answer is None:
                return None
            return io.BytesIO(model.report_bytes(self.answer, kind))

        return callback

    def _made(self, kind: str) -> Any:
        def callback() -> io.BytesIO | None:
            if self.answer is None:
                return None
            made = model.made_bytes(self.answer, kind, self.workspace)
            return None if made is None else io.BytesIO(made)

        return callback

    def _scene(self) -> io.BytesIO:
        return io.BytesIO(self.text.encode("utf-8"))

    def _json(self) -> io.BytesIO | None:
        return io.BytesIO(self.answer.json.encode("utf-8")) if self.answer is not None else None


def _fluid(svg: str) -> str:
    """The SVG scaled to the pane's width: its fixed width and height dropped (the viewBox keeps the shape)."""
    import re

    return re.sub(
        r'(<svg\b[^>]*?)\s(?:width|height)="[^"]*"([^>]*?)\s(?:width|height)="[^"]*"',
        r'\1\2 width="100%"',
        svg,
        count=1,
    )


def closed_connection_handler(loop: Any, context: dict[str, Any]) -> None:
    """The server's asyncio exception handler: a message Bokeh was still sending when the browser's tab closed
    (an edit's diagrams, drawn after the card) fails with Tornado's ``WebSocketClosedError`` (or
    ``StreamClosedError``) in a task nobody awaits, which asyncio printed as "Task exception was never
    retrieved" and a traceback in the terminal. The connection is gone and the session is closed as usual:
    nothing is wrong, so nothing is printed. Every other exception goes to asyncio's own handler."""
    from tornado.iostream import StreamClosedError
    from tornado.websocket import WebSocketClosedError

    if isinstance(context.get("exception"), (WebSocketClosedError, StreamClosedError)):
        return
    loop.default_exception_handler(context)


def font_route() -> tuple[str, Any, dict[str, str]]:
    """The server's route of the diagrams' font (:func:`flyopt.app.model.page_font`): that one file, read-only,
    at ``/flyopt-font/<its name>`` (Tornado's static file handler, which also answers a browser's cache)."""
    import re

    from tornado.web import StaticFileHandler

    _family, file = model.page_font()
    return rf"/{model.FONT_ROUTE}/({re.escape(file.name)})", StaticFileHandler, {"path": str(file.parent)}


def serve(port: int, host: str, browser: bool) -> None:
    """Serve the app on ``host``:``port`` until interrupted; open the browser when asked."""
    import secrets
    import signal

    import panel as pn

    from flyopt.cli.exits import sigterm_as_ctrl_c

    model.serving(host)
    SERVED_NAMES.clear()
    SERVED_NAMES.update(address.served_names(host))
    # the loop the server runs on (Tornado's IOLoop.current() wraps this thread's asyncio loop)
    loop = asyncio.new_event_loop()
    asyncio.set_event_loop(loop)
    loop.set_exception_handler(closed_connection_handler)
    pn.extension(
        "codeeditor",
        raw_css=[CSS],
        global_css=[model.font_face_css()],  # the diagrams' texts are text in their font: the page serves it
        # a message over the websocket's limit (an editor's text or a file of some 3 MB and more) closes the
        # connection; the page then said nothing and went on showing its last answer as if current
        notifications=True,
        disconnect_notification=DISCONNECTED,
    )
    # SIGTERM stops the server as Ctrl-C does (Panel's own SIGINT handler), so that it returns here
    signal.signal(signal.SIGTERM, sigterm_as_ctrl_c)
    try:
        pn.serve(
            {"/": session},
            port=port,
            address=host,
            websocket_origin=address.origins(host, port),
            # the session's token carries the page request's headers, which session() reads: signed, so that a
            # script cannot forge one (a rebound name's websocket with a token naming 127.0.0.1 built a session)
            sign_sessions=True,
            secret_key=secrets.token_urlsafe(32),
            show=browser,
            title="flyopt",
            websocket_max_message_size=4 * model.MAX_BYTES,
            extra_patterns=[font_route()],
            threaded=False,
        )
    finally:
        # the loop is left open: closing it would destroy the sessions' pending tasks (an edit's debounce) with
        # "Task was destroyed but it is pending!" in the terminal; the process ends here
        model.close_workspaces()  # the sessions still open: nothing of theirs stays behind
