"""The app without a browser: templates, checking the editor's text, and the answer of one solve.

Everything the page shows comes from flyopt's own paths, so that it cannot
disagree with the command line: a scene is read by :func:`flyopt.io.scene.load`
(its text written into a private temporary folder, so a file the scene names
resolves inside that folder only), solved and gathered as ``flyopt report``
gathers it (:func:`flyopt.cli.report.collect`), and built into the report's
Document (:func:`flyopt.report.builder.build`). The answer card is the
report's summary facts (:func:`flyopt.report.card.card_of`, the card a notebook shows too), the diagrams its figures (drawn by
:mod:`flyopt.report.plots`), the JSON that of ``flyopt solve --json``
(:func:`flyopt.outputs.documents.solution_json`), the provenance the report's.
"""

from __future__ import annotations

import atexit
import functools
import hashlib
import json
import os
import shutil
import tempfile
from collections.abc import Callable, Collection, Iterator
from contextlib import AbstractContextManager, contextmanager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, cast

from flyopt.app import address
from flyopt.report.card import Row, card_of
from flyopt.report.card import card_html as answer_card_html

if TYPE_CHECKING:
    from flyopt.io.scene import Scene
    from flyopt.pipeline import Solution
    from flyopt.report.document import Document

#: The largest editor text or upload the app reads, in bytes (1 MB).
MAX_BYTES = 1_000_000

#: Whether the page is served on this machine's loopback only (``flyopt app`` without ``--host``): set by
#: :func:`serving`. Served beyond it, a visitor is not offered what would make the server reach out (a Dask
#: scheduler: its messages are pickles, code on the server).
served_locally = True


def serving(host: str) -> None:
    """Note the address the page is served on (:data:`served_locally`)."""
    global served_locally
    served_locally = address.local(host)


#: The name the editor's text is written under, in its private folder.
SCENE_NAME = "scene.toml"


def templates() -> dict[str, Path]:
    """The scenes shipped with flyopt, by name ("shear-press", "textbook/NAME"), to start from.

    Read from the repository's ``problems/`` beside the installed package
    (an editable or source install), else from the package's own
    ``flyopt/data/templates/`` where it ships one; read-only, and only these
    files: the page never opens a path it is given.
    """
    import flyopt

    package = Path(flyopt.__file__).resolve().parent
    found: dict[str, Path] = {}
    for root in (package.parents[1] / "problems", package / "data" / "templates"):
        if not root.is_dir():
            continue
        for path in sorted(root.rglob("*.toml")):
            name = path.relative_to(root).with_suffix("").as_posix()
            found.setdefault(name, path)
        if found:
            break
    return found


def template_text(name: str) -> str:
    """The text of the template ``name`` (a key of :func:`templates`); KeyError for any other name."""
    return templates()[name].read_text(encoding="utf-8")


@functools.cache
def template_files(name: str) -> tuple[tuple[str, Path], ...]:
    """The data files the template ``name`` reads (a ``points_file``, a member's ``force_file``, ...), each as
    (its name relative to the template's folder, its path): what flyopt's loader records reading it, so that
    the shipped scenes that keep a table beside them (four-stroke-engine-csv) solve in a session's folder too.
    Empty for a template that reads none, or that does not load (its text then says what is wrong)."""
    from flyopt.errors import FlyoptError
    from flyopt.io.scene import load

    path = templates()[name]
    try:
        read = load(path).inputs
    except FlyoptError:
        return ()
    folder = path.parent.resolve()
    files = [Path(file) for _field, file in read]
    # the loader reads nothing outside the template's folder: a guard, not a case
    return tuple(
        (file.resolve().relative_to(folder).as_posix(), file) for file in files if file.resolve().is_relative_to(folder)
    )


def load_template(name: str, workspace: Workspace) -> str:
    """The text of the template ``name``, its data files copied into ``workspace`` under the names it gives
    them; KeyError for a name not a template."""
    text = template_text(name)
    for relative, source in template_files(name):
        workspace.add(relative, source.read_bytes())
    return text


def field_line(text: str, field_path: str) -> int | None:
    """The 1-based line of ``text`` where the field ``field_path`` ("machine.delta") is written, or None.

    ``flyopt check``'s locator (:mod:`flyopt.cli.toml_lines`): the key's line, else the nearest enclosing
    field's (a missing key: its table's header); None where not even the first part is written or the text
    is not TOML.
    """
    return lines_of_fields(text)(field_path)


def lines_of_fields(text: str) -> Callable[[str], int | None]:
    """:func:`field_line` of ``text`` for many fields: the text's keys scanned once (a text of 4,000 bad keys,
    scanned once per problem, took 61 s)."""
    from flyopt.cli.toml_lines import key_lines, line_of

    try:
        keys = key_lines(text)
    except (IndexError, ValueError):  # not TOML where the scanner stops: nothing to place
        keys = None

    def line(field_path: str) -> int | None:
        if keys is None or not field_path:
            return None
        try:
            return line_of(keys, field_path)
        except (IndexError, ValueError):
            return None

    return line


@dataclass(frozen=True)
class Problem:
    """One thing wrong with the editor's text: the field path, the message, the line (or None)."""

    field: str
    message: str
    line: int | None


@dataclass
class Checked:
    """The editor's text read by flyopt: the scene, or what is wrong with it."""

    text: str
    scene: Scene | None = None
    problems: list[Problem] = field(default_factory=list)


def refuse_oversize(text: str) -> None:
    """Refuse a scene text over :data:`MAX_BYTES` (SceneError), before it is written anywhere."""
    from flyopt.errors import SceneError

    if len(text.encode("utf-8")) > MAX_BYTES:
        raise SceneError("", f"the scene text is over {MAX_BYTES // 1_000_000} MB: the app reads no more")


class Workspace:
    """A private temporary folder (mode 0700) holding the editor's text as ``scene.toml`` and the session's own
    files (a sweep's copy of the scene and its results, a drawing being downloaded), nothing from elsewhere.

    A scene's ``points_file`` and the like resolve relative to the scene's
    folder and must stay inside it (:mod:`flyopt.io.input_files`), so here
    they find nothing: no path the user typed is opened outside this folder.
    """

    def __init__(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="flyopt-app-"))
        self.path = self.folder / SCENE_NAME
        _LIVE.add(self.folder)

    def write(self, text: str) -> Path:
        """Write ``text`` as the scene (refused over :data:`MAX_BYTES`); the scene's path."""
        refuse_oversize(text)
        self.path.write_text(text, encoding="utf-8")
        return self.path

    def hide(self, message: str) -> str:
        """``message`` without the server's folder, no business of the page's: the scene is :data:`SCENE_NAME`
        and a file beside it its own name."""
        message = message.replace(str(self.path), SCENE_NAME)
        for folder in sorted({str(self.folder), str(self.folder.resolve())}, key=len, reverse=True):
            message = message.replace(folder + os.sep, "").replace(folder, ".")  # the folder itself: "."
        return message

    def add(self, relative: str, data: bytes) -> Path:
        """Write ``data`` as the file ``relative`` inside the folder (a template's table); ValueError for a name
        that would leave it."""
        path = (self.folder / relative).resolve()
        if not path.is_relative_to(self.folder.resolve()) or path == self.path.resolve():
            raise ValueError(f"{relative!r} is not a name inside the session's folder")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
        return path

    def close(self) -> None:
        """Remove the folder."""
        shutil.rmtree(self.folder, ignore_errors=True)
        _LIVE.discard(self.folder)


#: The folders of the workspaces not closed yet: a session's is closed when the session ends, and those of the
#: sessions still open when the server stops by :func:`close_workspaces` (``flyopt app`` stopped by Ctrl-C or
#: SIGTERM left each open session's folder, its scene text and files, in the temporary directory).
_LIVE: set[Path] = set()


def close_workspaces() -> None:
    """Remove the folder of every workspace not closed yet (the server's last act; at exit too)."""
    for folder in list(_LIVE):
        shutil.rmtree(folder, ignore_errors=True)
        _LIVE.discard(folder)


atexit.register(close_workspaces)


def check(text: str, workspace: Workspace) -> Checked:
    """Read ``text`` as a scene by flyopt's loader; the scene, or the problem with its field and line."""
    from flyopt.errors import FlyoptError, SceneError
    from flyopt.io.scene import load

    checked = Checked(text)
    path = None
    try:
        path = workspace.write(text)
        checked.scene = load(path)
    except SceneError as err:  # every error flyopt check says, each with its line
        from flyopt.cli.scene import every_error
        from flyopt.io.toml_file import read_toml

        try:
            errors = [(err.field, err.message)] if path is None else every_error(read_toml(path), err)
        except SceneError:  # not TOML: the loader's one error says where
            errors = [(err.field, err.message)]
        from flyopt.cli.scene import MAX_LISTED

        place = lines_of_fields(text)
        found = [Problem(field, workspace.hide(message), place(field)) for field, message in errors]
        found.sort(key=lambda p: p.line or 0)
        if len(found) > MAX_LISTED:  # as flyopt check: the rest counted, not listed
            rest = len(found) - MAX_LISTED
            found = [*found[:MAX_LISTED], Problem("", f"{rest} more errors after these", found[MAX_LISTED].line)]
        checked.problems += found
    except (FlyoptError, ValueError) as err:  # a cycle that does not close, a number out of range
        checked.problems.append(Problem("", workspace.hide(str(err)), None))
    return checked


def live(scene: Scene) -> bool:
    """Whether the scene is solved on every edit: no drive to design and no motor in the cycle.

    The energy and energy–mass models are closed forms and their designs the
    exact closed forms (mass, cost) or a few small NLPs; a drive or a motor's
    characteristic (the dynamic model: a periodic simulation) takes seconds
    and waits for the Solve button.
    """
    from flyopt.cycle.torque import MotorTorque

    if scene.drive is not None or scene.calculation is not None:
        return False
    return not any(isinstance(curve, MotorTorque) for curve in (scene.driving, scene.resisting))


class Shown(NamedTuple):
    """One diagram as the page shows it: its key, caption, SVG ("" where it is not drawn: the note is in the
    caption) and its read-outs, the JSON of :func:`flyopt.report.plots.readout.record` ("" for none); ``digest``:
    that of the data it draws (:attr:`flyopt.report.document.Figure.digest`, "" for none): an edit whose
    diagram has the same digest keeps this one (:class:`flyopt.app.diagrams.Diagrams`)."""

    key: str
    caption: str
    svg: str
    readout: str = ""
    digest: str = ""


@dataclass
class Answer:
    """What one solve shows: the status, the card, the diagrams (SVG), the JSON, the provenance.

    An answer of the numbers only (:func:`numbers`) has ``drawn`` False: its document holds no diagram
    and ``figures`` is empty until :func:`draw` builds the report's document again with its figures.
    """

    status: str
    verdict: str
    card: list[Row]
    figures: list[Shown]
    json: str
    provenance: tuple[tuple[str, str], ...]
    document: Document
    sha256: str
    inputs: Any = None  # the report's inputs (ReportInputs or CalculationInputs): the one solve, kept
    units: str = "engineering"
    drawn: bool = True
    solution: Solution | None = None  # the solve's Solution (None for a scene that is one calculation)


def scene_digest(text: str) -> str:
    """The SHA-256 of the scene's text as written (UTF-8), as the report's provenance gives it."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def numbers(text: str, workspace: Workspace, units: str = "engineering") -> Answer:
    """Solve the editor's text once, as ``flyopt report`` does, and read the card out of its report's numbers.

    The report's document is built without its diagrams (drawing them takes most of a report's time:
    :func:`draw` does it after the card is shown); a calculation's report draws its few either way.
    Raises what ``flyopt report`` raises: SceneError (bad input), SolverFailed (no converged answer).
    """
    from flyopt.cli.report import collect
    from flyopt.outputs.documents import calculation_document, json_text, solution_json
    from flyopt.report.builder import CalculationInputs, build

    path = workspace.write(text)
    inputs = collect(path, f"flyopt app ({SCENE_NAME})", pdf=False, shown_as=SCENE_NAME)
    calculation = isinstance(inputs, CalculationInputs)
    # a calculation's report draws its figures; a document of numbers only draws nothing, and does not wait for
    # a diagram being drawn in the page's drawing worker
    with drawing() if calculation else nullcontext():
        document = build(inputs, units, figures=calculation)
    if isinstance(inputs, CalculationInputs):
        json = json_text(calculation_document(inputs.what, inputs.scene.title, SCENE_NAME, inputs.result.to_dict()))
    else:  # the one solve: the same JSON as flyopt solve --json, its scene named as the page names it
        json = solution_json(cast("Solution", inputs.solution), SCENE_NAME)
    card = card_of(document)
    return Answer(
        status=document.status,
        verdict=card.verdict,
        card=list(card.rows),
        figures=_figures(document) if calculation else [],
        json=json,
        provenance=tuple(inputs.provenance),
        document=document,
        sha256=scene_digest(text),
        inputs=inputs,
        units=units,
        drawn=calculation,
        solution=None if isinstance(inputs, CalculationInputs) else cast("Solution", inputs.solution),
    )


def draw(answer: Answer, keys: Collection[str] | None = None, read: dict[str, Any] | None = None) -> Document:
    """The report's document of ``answer``'s solve with its diagrams (the same inputs: nothing is solved again);
    with ``keys``, those diagrams alone (:class:`flyopt.app.diagrams.Diagrams`: the ones in view first).

    Its figures are open matplotlib Figures: :func:`drawn` takes the document into the answer (and the answer
    closes it with the next), else the caller closes it.
    """
    from flyopt.report.builder import build

    if answer.drawn:
        return answer.document
    with drawing():
        return build(answer.inputs, answer.units, figures=True if keys is None else keys, read=read)


def digests(answer: Answer, read: dict[str, Any] | None = None, keys: Collection[str] | None = None) -> Document:
    """The report's document of ``answer``'s solve without its diagrams, each split diagram's block (of ``keys``:
    those the page shows with a digest; None: all) with the digest of what it draws
    (:class:`flyopt.app.diagrams.Diagrams` compares them with those the page shows); their data kept in
    ``read`` for the documents that draw them. Nothing is drawn or solved again."""
    from flyopt.report.builder import build

    return build(answer.inputs, answer.units, figures=False, digests=True if keys is None else keys, read=read)


def drawing() -> AbstractContextManager[Any]:
    """Held around every draw of the app (making figures, rendering them, closing them): the report's one
    drawing lock (:data:`flyopt.report.plots.standard.LOCK`), since the app draws from worker threads and
    matplotlib is not thread-safe."""
    from flyopt.report.plots import standard

    return standard.LOCK


#: The most objects the collector is left to find while edits hold it (:func:`edit_held`): some five edits'
#: figures (an edit of shear-press leaves some 40,000 in cycles, which only the collector frees).
HELD_MOST = 200_000


@contextmanager
def edit_held() -> Iterator[None]:
    """Python's cyclic garbage collector held from an edit's numbers to its last diagram, then let run.

    An edit makes some 10^5 objects (the report's documents, seven figures' artists and transforms), and the
    collector, run by their count, scans them again and again while they are made and drawn: its young
    collections took some 40 ms of an edit's 430 ms to the last diagram in the app's process (issue 29). Held
    (:func:`flyopt.report.plots.standard.collector_paused`, whose pauses are counted over the process: the
    report's own pauses in the drawing worker nest in it), it runs once the edit is done and finds the last
    edit's figures, closed, in one scan: some 10 ms. The hold is the whole process': while edits overlap (an
    engineer typing on), it lasts until none is in flight, and an edit that finds more than :data:`HELD_MOST`
    objects waiting collects them first.
    """
    import gc

    from flyopt.report.plots import standard

    if gc.get_count()[0] > HELD_MOST:
        gc.collect(1)
    with standard.collector_paused():
        yield


def close(document: Document) -> None:
    """Close ``document``'s figures (:meth:`~flyopt.report.document.Document.close`) under the
    drawing lock."""
    with drawing():
        document.close()


def figure_blocks(document: Document) -> list[Any]:
    """The document's Figure blocks, in its order."""
    from flyopt.report.document import Figure

    return [block for section in document.sections for block in section.blocks if isinstance(block, Figure)]


def page_svg(figure: Any, prefix: str) -> str:
    """A figure as the page shows it: an inline SVG whose texts are text in the figure's font, which the page
    serves (:func:`page_font`; :func:`flyopt.report.html.svg_of`)."""
    from flyopt.report.html import svg_of

    return svg_of(figure, prefix, text_as_text=True)


@functools.cache
def page_font() -> tuple[str, Path]:
    """(family, file) of the font the diagrams' texts are measured in (matplotlib's default, DejaVu Sans), which
    the page serves to the browser (:data:`FONT_ROUTE`): their texts are set in it wherever the page is opened."""
    from matplotlib import ft2font

    from flyopt.report.plots import standard

    file = Path(standard.font_file())
    return str(ft2font.FT2Font(str(file)).family_name), file


#: Where the page serves :func:`page_font`'s file (its name after it).
FONT_ROUTE = "flyopt-font"


def font_face_css() -> str:
    """The page's ``@font-face`` rule of :func:`page_font`, served at :data:`FONT_ROUTE` (in the page's head: a
    rule in a component's own styles names no font for the page)."""
    family, file = page_font()
    return (
        f'@font-face {{ font-family: "{family}"; src: url("/{FONT_ROUTE}/{file.name}") format("truetype"); '
        "font-display: block; }"
    )


def figure_svg(block: Any) -> Shown:
    """One Figure block as the page shows it: the SVG "" and the note in the caption where it is not drawn, the
    read-outs of its curves (:mod:`flyopt.report.plots.readout`, read off the figure as that SVG drew it)."""
    from flyopt.report.document import plain

    svg = found = ""
    if block.figure is not None:
        with drawing():
            svg = page_svg(block.figure, block.key)
            found = readout_json(block.figure)
    caption = plain(block.caption) + (f" — {block.note}" if block.note else "")
    return Shown(block.key, caption, svg, found, block.digest if svg else "")


def readout_json(figure: Any) -> str:
    """The read-outs of a figure just drawn (:func:`flyopt.report.plots.readout.record`) as compact JSON, ""
    where it has none; call it under :func:`drawing`, right after the figure's SVG was drawn."""
    from flyopt.report.plots import readout

    recorded = readout.record(figure)
    return json.dumps(recorded, ensure_ascii=False, separators=(",", ":")) if recorded["axes"] else ""


def drawn(answer: Answer, document: Document, figures: list[Shown]) -> Answer:
    """``answer`` with the document :func:`draw` built and its figures' SVG (what downloads render)."""
    from dataclasses import replace

    return replace(answer, document=document, figures=figures, drawn=True)


def solve(text: str, workspace: Workspace, units: str = "engineering") -> Answer:
    """:func:`numbers`, then the diagrams (:func:`draw`): the whole answer at once, as the downloads need it.

    Raises what ``flyopt report`` raises: SceneError (bad input), SolverFailed (no converged answer).
    """
    answer = numbers(text, workspace, units)
    if answer.drawn:
        return answer
    document = draw(answer)
    return drawn(answer, document, [figure_svg(block) for block in figure_blocks(document)])


def _figures(document: Document) -> list[Shown]:
    return [figure_svg(block) for block in figure_blocks(document)]


def report_bytes(answer: Answer, kind: str) -> bytes:
    """The report of ``answer`` as ``kind`` ("html" or "pdf"), by the report's own renderers, from its one solve
    (nothing is solved again): its figures made and drawn here, once, as ``flyopt report`` draws them (the
    page's were drawn for the page: a figure drawn again is laid out again from where the first draw left it,
    and the page keeps diagrams of earlier edits undrawn, :class:`flyopt.app.diagrams.Diagrams`); a
    calculation's report, drawn with its numbers, as it is."""
    from flyopt.report.builder import CalculationInputs, build

    with drawing():  # called on the server's event loop while a worker may draw
        calculation = isinstance(answer.inputs, CalculationInputs) and answer.drawn
        document = answer.document if calculation else build(answer.inputs, answer.units)
        try:
            if kind == "html":
                from flyopt.report.html import render

                return render(document).encode("utf-8")
            from flyopt.report.pdf import render as render_pdf

            return render_pdf(document)
        finally:
            if document is not answer.document:
                document.close()


#: The wheel's manufacturing files the page offers, as ``flyopt export`` writes them: (kind, label, file name).
MADE = (
    ("pdf", "Drawing (PDF)", "drawing.pdf"),
    ("dxf", "Drawing (DXF)", "drawing.dxf"),
    ("step", "Solid (STEP)", "wheel.step"),
)


def made_available(kind: str) -> bool:
    """Whether this installation can write ``kind`` (a DXF needs ezdxf, a STEP OpenCASCADE: the ``cad`` extra)."""
    if kind == "dxf":
        from flyopt.outputs.drawing import require_ezdxf as require
    elif kind == "step":
        from flyopt.outputs.solid import require_ocp as require
    else:
        return True
    try:
        require()
    except ImportError:
        return False
    return True


def wheel_of(answer: Answer | None) -> Any:
    """The wheel ``answer`` designed (its :class:`flyopt.design.result.Design`), or None: none needed, none
    feasible, a calculation, no answer. What the drawing and solid downloads are made of."""
    solution = answer.solution if answer is not None else None
    design = solution.design if solution is not None else None
    return None if design is None else design.best


def made_bytes(answer: Answer, kind: str, workspace: Workspace) -> bytes | None:
    """The answer's wheel as ``flyopt export`` writes it: its drawing ("pdf", "dxf", "svg") or its solid ("step").

    Of the design the answer holds (nothing is solved again), written into the session's private folder and
    read back (the file then removed); None where there is no wheel (none needed, none feasible, a
    calculation).
    """
    from flyopt.report.drawing import drawing_of_design, write_drawing, write_solid

    best = wheel_of(answer)
    if best is None:
        return None
    scene = cast("Solution", answer.solution).scene
    target = workspace.folder / f"made.{kind}"
    # under the drawing lock: a drawing's rc_context sets matplotlib's settings for the whole process, which the
    # drawing worker's SVG of a diagram must not see change under it
    with drawing():
        try:
            if kind == "step":
                write_solid(best, scene, target)
            else:
                write_drawing(drawing_of_design(best, scene), target, kind)
            return target.read_bytes()
        finally:
            target.unlink(missing_ok=True)


def card_html(answer: Answer | None, problems: list[Problem], busy: str = "", stale: str = "") -> str:
    """The answer card as HTML, every string escaped; ``stale``: what of the page is still the last scene solved's,
    said under the problems (the diagrams beside them may be scrolled to, their own note out of view)."""
    from html import escape

    if problems:
        items = "".join(
            f'<li class="problem"><code>{escape(p.field or "scene")}</code>'
            + (f" (line {p.line})" if p.line else "")
            + f": {escape(p.message)}</li>"
            for p in problems
        )
        note = f'<p class="stale-note">{escape(stale)}</p>' if stale else ""
        return f'<div class="card bad"><b>The scene is not valid</b><ul>{items}</ul>{note}</div>'
    if answer is None:
        return f'<div class="card">{escape(busy) or "No answer yet."}</div>'
    return answer_card_html(card_of(answer.document), busy)


def provenance_html(answer: Answer | None) -> str:
    """The footer: flyopt's version, the scene's SHA-256, the solvers' versions (the report's provenance)."""
    from html import escape

    if answer is None:
        import flyopt

        return f"flyopt {escape(flyopt.__version__)}"
    keep = ("flyopt", "numpy", "scipy", "casadi", "matplotlib", "IPOPT")
    parts = [f"{escape(k)} {escape(v)}" for k, v in answer.provenance if k in keep]
    parts.insert(1, f"scene SHA-256 {answer.sha256}")
    return " · ".join(parts)


def escape_text(value: Any) -> str:
    """Any user string as HTML text."""
    from html import escape

    return escape(str(value))
