"""The app's "Sweeps" tab without a browser: the ``--vary`` spec from a form, its points, the run, the files.

The form's rows (field, from, to, points, log, unit; or a list of names) are
written as the ``--vary FIELD=VALUES`` texts of ``flyopt sweep`` (the grammar
of :mod:`flyopt.io.sweep_spec`) and read by the command's own parser
(:func:`flyopt.io.sweep_spec.vary_from_texts`, :func:`flyopt.studies.plan.plan_sweep`),
so the points are the command's. A sweep over :data:`MAX_POINTS` points is
refused in one line: the app holds its table in the page, the command line
does not.

The sweep runs through flyopt's own runner (:func:`flyopt.studies.sweep.sweep`,
processes on this machine or a Dask address as ``--scheduler`` takes), its
output a Parquet file in the session's private folder (:class:`flyopt.app.model.Workspace`),
a few chunks at a time as ``flyopt sweep --resume --max-chunks K`` runs it:
between calls the page's bar moves (the points finished over the points) and
a Cancel stops it at the next chunk's end, the finished chunks kept in
``sweep.parquet.parts/`` as the command keeps them. The results are read back
by :func:`flyopt.read_results` (the full table, SI), drawn by the report's
:func:`flyopt.report.plots.plot_sweep` (the plot of ``flyopt plot --what sweep``)
and written to CSV by :func:`flyopt.outputs.results.write_results`, beside
the Parquet file and nowhere else. docs/flywheel-design.md §9 (studies).
"""

from __future__ import annotations

import dataclasses
import os
import shutil
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.app.model import Workspace
    from flyopt.io.scene import Scene

#: The most points a sweep of the app may have: its table lives in the page. Larger sweeps: ``flyopt sweep``.
MAX_POINTS = 10_000

#: The files of a sweep in the session's folder.
PARQUET = "sweep.parquet"
CSV = "sweep.csv"
SCENE = "sweep-scene.toml"

#: Chunks run per call of the runner on a Dask cluster (on this machine: one per worker process).
DASK_CHUNKS = 8


@dataclass(frozen=True)
class Axis:
    """One row of the form: a field and its values, as a range (from, to, points, log) or a list of names.

    ``start``/``stop`` are numbers as the user typed them, in ``unit`` (any unit flyopt reads; "" for SI or a
    plain number); ``names`` replaces the range for a field of names (material, shaft, geometry).
    """

    field: str
    start: str = ""
    stop: str = ""
    count: int = 5
    log: bool = False
    unit: str = ""
    names: str = ""


def vary_text(axis: Axis) -> str:
    """The ``--vary`` text of one row: ``FIELD=FROM:TO:N UNIT``, ``FIELD=FROM:TO:logN UNIT`` or ``FIELD=a,b``.

    SceneError (naming ``--vary`` and the field) for a row with neither a range nor names.
    """
    from flyopt.errors import SceneError

    field = axis.field.strip()
    if axis.names.strip():
        return f"{field}={','.join(n.strip() for n in axis.names.split(',') if n.strip())}"
    if not axis.start.strip() or not axis.stop.strip():
        raise SceneError(f"--vary {field}", "give its from and to values (or a list of names)")
    count = f"log{axis.count}" if axis.log else str(axis.count)
    unit = f" {axis.unit.strip()}" if axis.unit.strip() else ""
    return f"{field}={axis.start.strip()}:{axis.stop.strip()}:{count}{unit}"


def first_text(axis: Axis) -> str:
    """The ``--vary`` text of the row's first value alone (the point an estimate is timed on)."""
    field = axis.field.strip()
    if axis.names.strip():
        return f"{field}={axis.names.split(',')[0].strip()}"
    unit = f" {axis.unit.strip()}" if axis.unit.strip() else ""
    return f"{field}={axis.start.strip()}{unit}"


@dataclass(frozen=True)
class Plan:
    """A sweep the form describes: its ``--vary`` texts, the fields to values mapping, the number of points."""

    texts: tuple[str, ...]
    vary: dict[str, str]
    points: int


def plan(scene: Scene, axes: Sequence[Axis]) -> Plan:
    """The sweep of the form's rows, read by ``flyopt sweep``'s own parser; its number of points.

    Raises
    ------
    SceneError
        What ``flyopt sweep --vary`` says of the same texts, or more than :data:`MAX_POINTS` points.
    """
    from flyopt.errors import SceneError
    from flyopt.io.sweep_spec import TooManyPoints, vary_from_texts
    from flyopt.studies.plan import plan_sweep

    texts = tuple(vary_text(a) for a in axes if a.field.strip())
    if not texts:
        raise SceneError("--vary", "choose a field to vary")
    vary = vary_from_texts(scene, texts, "--vary")
    try:  # refused from the axes' counts before any grid is made (a 4000 x 4000 grid was, at each keystroke)
        points = len(plan_sweep(scene, vary, max_points=MAX_POINTS).points)
    except TooManyPoints as err:  # in the app's words, pointing to the command line
        raise SceneError(
            "--vary",
            f"{err.points:,} points: the app runs at most {MAX_POINTS:,} (use flyopt sweep on the command line for more)",
        ) from None
    return Plan(texts, vary, points)


def scene_copy(text: str, workspace: Workspace) -> Scene:
    """The scene of a sweep, read from its own copy of the editor's text in the session's folder (an edit
    while it runs does not change the scene the chunks and ``--resume`` see)."""
    from flyopt.app.model import SCENE_NAME, refuse_oversize
    from flyopt.io.scene import load

    refuse_oversize(text)
    path = workspace.folder / SCENE
    path.write_text(text, encoding="utf-8")
    return dataclasses.replace(load(path), shown_as=SCENE_NAME)  # the page's name, not its server's folder


def estimate(scene: Scene, axes: Sequence[Axis], points: int) -> tuple[float, float]:
    """(seconds of the first point, estimated seconds of all ``points`` in one process): the sweep's first
    point timed through the runner (serially, no file), times the number of points: an upper bound, the
    first point paying for the analyses the others share."""
    from flyopt.studies.sweep import sweep

    texts = [first_text(a) for a in axes if a.field.strip()]
    start = time.perf_counter()
    sweep(scene, texts, workers=1)
    first = time.perf_counter() - start
    return first, first * points


def estimate_text(first: float, total: float) -> str:
    """The sweep form's words for :func:`estimate`'s (first, total) seconds, each in the unit that reads: "the
    first point took 6 ms: at most about 30 ms in one process", "… about 4.2 s …", "… about 35 min …" (a total of
    0.03 s read "0.0 s")."""
    return (
        f"the first point took {duration_text(first)}: at most about {duration_text(max(total, 1e-3))} in one process"
    )


def duration_text(seconds: float) -> str:
    """A time in ms below a second, in s to two minutes, else in minutes, as a person reads it at a glance (the
    sweep tab's one way of saying how long)."""
    if seconds < 1e-3:
        return "under 1 ms"
    if seconds < 1.0:
        return f"{seconds * 1e3:,.0f} ms"
    if seconds < 120.0:
        return f"{seconds:,.1f} s"
    return f"{seconds / 60.0:,.0f} min"


@dataclass
class Run:
    """A finished (or cancelled) sweep: its full table (SI) and its files in the session's folder."""

    frame: pd.DataFrame
    parquet: Path | None
    complete: bool
    info: dict[str, Any]


def clear(workspace: Workspace) -> None:
    """Remove the files of the session's last sweep (its output, its parts, its CSV and sidecar)."""
    folder = workspace.folder
    for name in (PARQUET, CSV, CSV + ".json"):
        (folder / name).unlink(missing_ok=True)
    shutil.rmtree(folder / (PARQUET + ".parts"), ignore_errors=True)


def run(
    scene: Scene,
    vary: dict[str, str],
    workspace: Workspace,
    *,
    scheduler: str | None = None,
    progress: Callable[[int, int], None] | None = None,
    cancelled: Callable[[], bool] | None = None,
    resume: bool = False,
) -> Run:
    """Run the sweep by :func:`flyopt.studies.sweep.sweep` into ``sweep.parquet`` of the session's folder.

    It runs as ``flyopt sweep --resume --max-chunks K`` runs, again until complete: K chunks per call
    (one per CPU on processes, :data:`DASK_CHUNKS` on a Dask cluster); after each call ``progress(done,
    total)`` is told the points finished, and ``cancelled()`` asked whether to stop (the finished chunks
    stay in ``sweep.parquet.parts/``, and ``resume=True`` continues them). Without ``resume`` the last
    sweep's files are removed first.
    """
    from flyopt.outputs.results import read_results
    from flyopt.studies.cluster import scheduler_address
    from flyopt.studies.sweep import sweep

    address = scheduler_address(scheduler) if scheduler else None  # SceneError as --scheduler says it
    if not resume:
        clear(workspace)
    output = workspace.folder / PARQUET
    per_call = DASK_CHUNKS if scheduler else max(1, os.cpu_count() or 1)
    while True:
        frame = sweep(scene, vary, output=output, resume=True, max_chunks=per_call, scheduler=address)
        info = frame.attrs["sweep"]
        if progress is not None:
            progress(len(frame), info["points"])
        if info["complete"]:
            full = read_results(output)
            return Run(full, output, True, info)
        if cancelled is not None and cancelled():
            return Run(frame, None, False, info)


def csv_file(result: Run, workspace: Workspace) -> Path:
    """The sweep's table as CSV (with its ``.csv.json`` sidecar of units), in the session's folder."""
    from flyopt.outputs.results import write_results

    path = workspace.folder / CSV
    write_results(result.frame, path, metadata=result.frame.attrs.get("flyopt"))
    return path


def plot_fields(frame: pd.DataFrame) -> list[str]:
    """The fields the sweep varied: what the plot may draw along x (``flyopt plot --x``)."""
    from flyopt.report.plots.results import varied_fields

    return varied_fields(frame)


def plot_axes(frame: pd.DataFrame) -> list[str]:
    """The varied fields the plot may draw along x (:func:`flyopt.report.plots.results.axis_fields`)."""
    from flyopt.report.plots.results import axis_fields

    return axis_fields(frame)


def plot_svg(frame: pd.DataFrame, x: str, y: str = "mass", by: str | None = None, units: str = "engineering") -> str:
    """The sweep plot of ``flyopt plot --what sweep --x X --y Y --by BY`` as inline SVG.

    ValueError as the plot says it (an unknown column, more lines than it draws).
    """
    return plot_shown(frame, x, y, by, units)[0]


def plot_shown(
    frame: pd.DataFrame, x: str, y: str = "mass", by: str | None = None, units: str = "engineering"
) -> tuple[str, str]:
    """(SVG, read-outs) of the sweep plot (:func:`plot_svg`; the read-outs' JSON of
    :func:`flyopt.app.model.readout_json`, "" where an axis has no unit to read it in)."""
    from flyopt.app.model import page_svg, readout_json
    from flyopt.report.plots import plot_sweep, standard

    with standard.LOCK:  # drawn in the tab's worker thread: one draw at a time (matplotlib is not thread-safe)
        ax = plot_sweep(frame, x, y, by, units=units)
        figure = standard.figure_of(ax)
        try:
            return page_svg(figure, "sweep"), readout_json(figure)
        finally:
            standard.close(figure)


#: The table's columns after the varied fields: the answer of each point.
RESULT_COLUMNS = ("status", "best_material", "best_shaft", "d_outer", "b", "h", "mass", "cost", "rim_speed", "method")


def table(frame: pd.DataFrame, units: str, names: dict[str, str] | None = None) -> pd.DataFrame:
    """The results as the tab's filterable table: the point, the varied fields, the answer, in the unit system."""
    from flyopt.app.materials import shown

    columns = ["point", *plot_fields(frame), *RESULT_COLUMNS]
    return shown(frame, list(dict.fromkeys(columns)), units, names)
