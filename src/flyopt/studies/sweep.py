"""Design sweeps: one scene varied over a grid or a Latin hypercube of its fields.

``sweep(scene, {"delta": "0.01:0.1:log20", "speed": "300,600,1200rpm",
"material": "cast_iron,cast_steel"})`` returns a pandas DataFrame with one
row per point: every input and every result (the best design, its binding
constraints, feasibility, how it was computed). The same runs from the
command line (``flyopt sweep``) and from a ``[sweep]`` table in a scene file.
With an output file the rows are streamed to it as chunks finish and the
frame returned is a summary (:data:`SUMMARY_COLUMNS`).

The stages, each in its own module, joined here:

- the fields, their values and the other options (:mod:`flyopt.io.sweep_spec`),
- the points, a grid or a Latin hypercube (:mod:`flyopt.studies.plan`),
- the design of every point (:mod:`flyopt.studies.evaluate`), its scene sent
  to workers as data (:mod:`flyopt.studies.payload`),
- the chunks, sized by their estimated cost (:mod:`flyopt.studies.chunks`) and
  run serially, in processes or on Dask (:mod:`flyopt.studies.runner`), with
  resume (:mod:`flyopt.studies.parts`),
- the result table and its files, written piece by piece (:mod:`flyopt.outputs.results`),
  with their metadata: units, flyopt's version, the scene (its file, the file's
  SHA-256 and flyopt's digest of it) and the sweep (fields, values, samples,
  seed, method), also in ``frame.attrs["flyopt"]``. Missing values are nulls.
"""

from __future__ import annotations

import functools
import os
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import numpy.typing as npt
import pandas as pd

import flyopt
from flyopt.design import design_inputs
from flyopt.errors import BrokenInvariant, Interrupted, SceneError
from flyopt.io.sweep_spec import OPTION_MAXIMUMS, OPTION_MINIMUMS, check_options, option_label, whole_number
from flyopt.outputs.documents import scene_record, table_metadata
from flyopt.outputs.files import check_folder
from flyopt.outputs.results import SWEEP_BESIDE, ResultWriter, check_table_output, normalize
from flyopt.studies.chunks import SERIAL_SECONDS, chunk_bounds
from flyopt.studies.cluster import connect, threads
from flyopt.studies.context import chunk_context
from flyopt.studies.evaluate import evaluate_chunk, evaluate_points
from flyopt.studies.parts import Parts, fingerprint
from flyopt.studies.payload import digest
from flyopt.studies.physics import physics_analysis
from flyopt.studies.plan import plan_sweep
from flyopt.studies.points import PHYSICS_FIELDS, design_seconds, physics_codes
from flyopt.studies.processes import cpu_count
from flyopt.studies.runner import run_chunks, stopped
from flyopt.studies.task import task_of

if TYPE_CHECKING:  # the annotations only
    from flyopt.io.scene import Scene
    from flyopt.studies.context import ChunkContext
    from flyopt.studies.plan import SweepPlan

__all__ = ["SUMMARY_COLUMNS", "sweep"]

#: The columns of the table a sweep returns when its rows go to an output file.
SUMMARY_COLUMNS = ("point", "status", "method", "n_combinations")
#: Points whose rows are put back in point order together, when the points of one physics
#: are gathered into chunks (see :func:`_layout`): bounds the memory of that reordering.
BLOCK_POINTS = 10_000
#: Chunks that finished out of turn kept in memory until their turn to be written (others
#: are read back from their parts then).
HELD_CHUNKS = 4
#: A first analysis quicker than this [s] is timed again on a second physics (see
#: :func:`_time_first_analysis`).
RETIME_SECONDS = 0.5


def check_sweep(scene: Scene, options: Mapping[str, Any], where: str = "sweep") -> SweepPlan:
    """Check a sweep as :func:`sweep` would, without running it.

    ``flyopt check`` and ``flyopt sweep`` call it on a scene's ``[sweep]``
    table, so that a table one accepts the other runs.

    Parameters
    ----------
    scene : Scene
    options : mapping
        ``vary`` and the other keywords of :func:`sweep`, e.g. the options
        :func:`flyopt.io.sweep_spec.load_sweep` returns.
    where : str
        ``"sweep"`` for a ``[sweep]`` table (errors then name the scene's
        file), ``"--"`` for the command line.

    Returns
    -------
    SweepPlan
        The points (for a Latin hypercube without a seed, with the seed drawn).

    Raises
    ------
    SceneError
        The first bad field, value or option, named as the user wrote it.
    """
    try:
        check_options(options, where)
        if options.get("output") is not None:  # where it can go (its folder), and not over a file the scene reads
            check_folder(options["output"], option_label(where, "output"), beside=SWEEP_BESIDE)
            check_table_output(options["output"], scene, "the sweep's table", option_label(where, "output"))
        return plan_sweep(
            scene,
            options.get("vary") or {},
            samples=options.get("samples"),
            seed=options.get("seed"),
            where=option_label(where, "vary"),
        )
    except SceneError as err:
        if where.startswith("--") or scene.source is None:
            raise
        raise err.with_source(scene.source) from None


def sweep(
    scene: Scene,
    vary: Mapping[str, Any] | Iterable[str] | None = None,
    *,
    samples: int | None = None,
    seed: int | None = None,
    output: str | os.PathLike[str] | None = None,
    workers: int | Literal["auto"] = "auto",
    chunk_size: int | None = None,
    scheduler: Any = None,
    resume: bool = False,
    max_chunks: int | None = None,
    progress: bool = False,
    method: Literal["auto", "closed_form", "ipopt"] = "auto",
    solver_options: Mapping[str, Any] | None = None,
    keep_parts: bool = False,
) -> pd.DataFrame:
    """Sweep a scene over a grid (or Latin hypercube) of its fields.

    Parameters
    ----------
    scene : Scene
    vary : mapping or iterable of str
        Fields and their values, ``{"delta": "0.01:0.1:log20"}`` or
        ``["delta=0.01:0.1:log20"]``; see :mod:`flyopt.io.sweep_spec` for the grammar.
    samples : int, optional
        Latin hypercube samples instead of the full grid.
    seed : int, optional
        Seed of the Latin hypercube (>= 0). Without it one is drawn, and
        recorded in the ``seed`` column and ``frame.attrs["sweep"]["seed"]``
        so that the samples can be made again; ``resume`` reuses the seed of
        the sweep it continues.
    output : str or Path, optional
        File to write, ``.parquet`` or ``.csv``. Each finished chunk is
        saved to ``OUTPUT.parts/`` at once and appended to the output (in
        point order) as soon as the chunks before it are; the full table is
        never held in memory, and the file appears under its name only
        when complete.
    workers : int or "auto"
        Worker processes on this machine (1: serial, in this process).
        ``auto``: one per available CPU, or serial when the sweep is
        estimated to take under :data:`~flyopt.studies.chunks.SERIAL_SECONDS`
        in one process (the estimate counts the designs and, for a scene
        whose every physics needs its own analysis, that analysis, timed on
        the first point).
    chunk_size : int, optional
        Points per chunk. By default chunks are sized by their estimated
        cost (see :func:`flyopt.studies.chunks.chunk_bounds`).
    scheduler : str or dask.distributed Client or cluster, optional
        Run the chunks on a Dask cluster (``"tcp://host:8786"``).
    resume : bool
        Continue an interrupted sweep: chunks whose part file exists (and
        holds its chunk) are read, not rerun. The parts must come from the
        same sweep (its chunks are those recorded with the parts).
    max_chunks : int, optional
        Run at most this many chunks in this call and stop (the rest is left
        for ``resume``); the returned table then holds the finished chunks.
    progress : bool
        Progress line with rate and ETA on stderr.
    method : {"auto", "closed_form", "ipopt"}
        See :func:`flyopt.studies.evaluate.evaluate_points`.
    solver_options : mapping, optional
        CasADi/IPOPT options for points solved by IPOPT.
    keep_parts : bool
        Keep ``OUTPUT.parts/`` after the final file is written.

    Returns
    -------
    pandas.DataFrame
        Without ``output``: one row per point (see
        :func:`flyopt.studies.evaluate.evaluate_points`), in point order; a
        Latin hypercube's table has a ``seed`` column after ``point``.
        With ``output``: the rows are in the file (read it with
        :func:`flyopt.read_results`, in SI or in the units the fields were given in) and the frame holds only
        :data:`SUMMARY_COLUMNS` of each finished point, in point order
        (``status`` and ``method`` as categoricals).
        ``frame.attrs["sweep"]`` tells how it ran: chunks run and reused,
        mode, workers, seconds, the estimate, seed, whether it is complete,
        and ``summary`` (whether the frame is the summary).

    Raises
    ------
    SceneError
        Bad fields, values or options (named as on the command line), parts
        of another sweep, a Dask scheduler that does not answer, or a scene
        that cannot be sent to a Dask cluster as data (checked before
        anything is written).
    NonPeriodicCycle
        The scene's cycle does not balance.
    Interrupted
        Ctrl-C, or a Dask cluster that lost its workers: the finished chunks
        stay in ``OUTPUT.parts/`` and ``resume=True`` continues.

    Notes
    -----
    Points are sent to worker processes and Dask workers as data: the scene
    as the text of its file (plus the fields that differ from it, see
    :mod:`flyopt.studies.payload`), the points as a table of values. Each
    worker rebuilds the scene once and keeps its analyses for the chunks it
    runs. For a scene whose every physics is analysed anew (varying inertia,
    a real motor), the points that share a physics (δ, speed, J_c, torque
    scale) are run in one chunk where they can: within each run of
    :data:`BLOCK_POINTS` consecutive points they are gathered by physics,
    and put back in point order when written.
    """
    check_options(
        dict(
            samples=samples,
            seed=seed,
            output=output,
            chunk_size=chunk_size,
            max_chunks=max_chunks,
            method=method,
            workers=workers,
            resume=resume,
            keep_parts=keep_parts,
        ),
        "--",
    )
    if output is not None:  # before anything is computed or made: a FIFO or a folder at the output is refused
        check_folder(output, "--output", beside=SWEEP_BESIDE)
        check_table_output(output, scene, "the sweep's table", "--output")  # nor a file the scene read
    parts = None if output is None else Parts(output)
    recorded = _recorded(parts) if resume and parts is not None else {}
    if resume and samples is not None and seed is None:
        seed = recorded.get("seed")  # the samples of the sweep being continued
    plan = plan_sweep(scene, vary or {}, samples=samples, seed=seed)
    points = plan.points
    axes = tuple(a.field for a in plan.axes)
    ctx = chunk_context(scene, method, solver_options, axes)
    with connect(scheduler) as client:  # before anything is written
        start = time.perf_counter()  # the analyses timed for the layout count too
        layout = _layout(scene, ctx, points, method, workers, chunk_size, client, recorded)
        mode, n_workers = layout["mode"], layout["workers"]
        task: Callable[[pd.DataFrame], pd.DataFrame] | None = None
        if mode != "serial":
            task, reason = task_of(ctx, scene)
            if task is None:
                if mode == "dask":
                    raise SceneError("--scheduler", f"cannot run on a Dask cluster: {reason}")
                mode, n_workers, layout["serial_because"] = "serial", 1, reason
        order, bounds = layout["order"], layout["bounds"]
        chunks = [(i, _chunk(points, order, bounds[i], bounds[i + 1])) for i in range(len(bounds) - 1)]
        done = []
        if parts is not None:
            # flyopt's version too: parts another version computed are not mixed with this one's results
            identity = (flyopt.__version__, digest(scene), method, sorted((solver_options or {}).items()), axes)
            record = {
                "fingerprint": fingerprint(identity, points, (layout["grouped"], bounds.tolist())),
                "points": len(points),
                "chunk_size": layout["chunk_size"],
                "chunks": len(chunks),
                "seed": plan.seed,
            }
            if layout["chunk_size"] == "auto":
                record["bounds"] = bounds.tolist()
                record["grouped"] = layout["grouped"]
            done = parts.open(record, chunks, resume)
        reused = sorted(done)
        finished_before = set(reused)
        pending = [(i, chunk) for i, chunk in chunks if i not in finished_before]
        if max_chunks is not None:
            pending = pending[:max_chunks]
        if mode == "processes":
            n_workers = min(n_workers, len(pending))
            if n_workers <= 1:
                mode, n_workers = "serial", 1
        elif mode == "dask":
            n_workers = None
        if mode == "serial":
            task = functools.partial(evaluate_chunk, ctx)
        if task is None:
            raise BrokenInvariant("a sweep mode other than serial has its task (or fell back to serial)")
        prepare = _seed_column(plan)
        describe = _describe(scene, plan, method)
        assembly = _Assembly(layout["units"], len(points), parts, output, prepare, describe)
        complete = written = False  # written: the whole output is in place (the parts folder goes next)
        try:
            for i in reused:
                assembly.add(i)
            _, ran = run_chunks(
                task,
                chunks,
                pending,
                parts=parts,
                done=done,
                sink=assembly.add,
                workers=n_workers if mode == "processes" else 1,
                client=client if mode == "dask" else None,
                progress=progress,
            )
            seconds = time.perf_counter() - start
            complete = len(reused) + len(ran) == len(chunks)
            assembly.finish(complete)
            written = complete
        except KeyboardInterrupt:
            assembly.abort()
            raise Interrupted(
                stopped("interrupted while writing the output", parts, len(assembly.finished), len(chunks))
            ) from None
        except BaseException:
            assembly.abort()
            raise
        finally:
            if parts is not None and not (written and not keep_parts):
                parts.release()  # the folder stays for --resume; another sweep may now take it
    if complete and parts is not None and not keep_parts:
        parts.remove()
    frame = assembly.frame()
    if frame is None:  # no chunk finished, no output: the columns alone
        frame = prepare(evaluate_points(ctx, points.iloc[:0]))
    info = {
        "points": len(points),
        "chunks": len(chunks),
        "chunk_size": layout["chunk_size"],
        "chunks_run": sorted(ran),
        "chunks_reused": reused,
        "complete": complete,
        "mode": mode,
        "workers": n_workers,
        "seconds": seconds,
        "seed": plan.seed,
        "designs": assembly.designs_run(ran),
        "estimated_seconds": layout["estimate"],
        "analysis_seconds": layout["analysis_seconds"],
        "physics": layout["physics"],
        "output": None if output is None else str(output),
        "summary": output is not None,
    }
    if "serial_because" in layout:
        info["serial_because"] = layout["serial_because"]
    frame.attrs["sweep"] = info
    if output is None:
        frame.attrs["flyopt"] = describe(list(frame.columns))
    return frame


def _chunk(points: pd.DataFrame, order: npt.NDArray[np.intp] | None, start: int, end: int) -> pd.DataFrame:
    """The points of one chunk, in point order."""
    if order is None:
        return points.iloc[start:end]
    return points.iloc[np.sort(order[start:end])]


def _seed_column(plan: SweepPlan) -> Callable[[pd.DataFrame], pd.DataFrame]:
    """A function making rows the sweep's table: a Latin hypercube's ``seed`` column after
    ``point`` (grids: none), and nulls for missing values (:func:`flyopt.outputs.results.normalize`)."""

    def prepare(frame: pd.DataFrame) -> pd.DataFrame:
        if plan.samples is not None and "seed" not in frame:
            frame.insert(1, "seed", np.full(len(frame), plan.seed, dtype=np.int64))
        return normalize(frame)

    return prepare


def _describe(scene: Scene, plan: SweepPlan, method: str) -> Callable[[Sequence[str]], dict[str, Any]]:
    """A function giving a sweep table's metadata (:func:`flyopt.outputs.results.table_metadata`)
    from its columns: units, flyopt's version, the scene, and the sweep that made it."""
    varied = {a.field for a in plan.axes}
    objective = None if "design.objective" in varied else design_inputs(scene).spec.objective
    spec = {
        "vary": {
            a.field: {
                "kind": a.kind,
                "values": list(a.values),
                "low": a.low,
                "high": a.high,
                "log": bool(a.log),
                "unit": a.unit,  # as written (rpm): flyopt.read_results(path, units="input") gives it back
            }
            for a in plan.axes
        },
        "samples": plan.samples,
        "seed": plan.seed,
        "method": method,
        "points": len(plan.points),
    }
    record = scene_record(scene, digest(scene))

    def describe(columns: Sequence[str]) -> dict[str, Any]:
        return table_metadata("sweep", columns, scene=record, sweep=spec, objective=objective)

    return describe


def _layout(
    scene: Scene,
    ctx: ChunkContext,
    points: pd.DataFrame,
    method: str,
    workers: int | Literal["auto"],
    chunk_size: int | None,
    client: Any,
    recorded: Mapping[str, Any],
) -> dict[str, Any]:
    """How a sweep runs: mode, workers, the order of its points and its chunks.

    Returns
    -------
    dict
        ``mode`` ("serial", "processes", "dask"), ``workers``, ``order``
        (positions of the points in run order, None for point order),
        ``grouped``, ``bounds`` (see :func:`~flyopt.studies.chunks.chunk_bounds`), ``units``
        (lists of chunks whose rows form the next points, in order),
        ``chunk_size`` (int or "auto"), ``estimate`` (seconds in one
        process), ``analysis_seconds``, ``physics`` (distinct physics).
    """
    n = len(points)
    if chunk_size is None and isinstance(recorded.get("chunk_size"), int):
        chunk_size = recorded["chunk_size"]  # resuming a sweep cut by the user's size
    costs, start_costs = design_seconds(ctx.scene, points, method)
    if ctx.reusable:
        codes, n_physics, analysis_seconds = None, 1, 0.0
    else:
        codes, n_physics = physics_codes(points)
        analysis_seconds = _time_first_analysis(scene, points, codes) if n else 0.0
    estimate = float(costs.sum()) + n_physics * analysis_seconds
    if client is not None:
        mode, n_workers = "dask", max(threads(client), 1)
    elif workers == "auto":
        n_workers = 1 if estimate < SERIAL_SECONDS else cpu_count()
        mode = "processes" if n_workers > 1 else "serial"
    else:
        n_workers = int(workers)
        mode = "processes" if n_workers > 1 else "serial"
    # the points of one physics together: within blocks, grouped by first appearance
    order, grouped, starts, breaks = None, False, None, None
    if codes is not None and n_physics < n:
        if np.any(np.diff(codes) < 0):  # some physics come back later: gather them
            grouped = True
            order = np.concatenate(
                [b + np.argsort(codes[b : b + BLOCK_POINTS], kind="stable") for b in range(0, n, BLOCK_POINTS)]
            )
            breaks = np.arange(BLOCK_POINTS, n, BLOCK_POINTS)
        run_codes = codes if order is None else codes[order]
        starts = np.concatenate([[True], run_codes[1:] != run_codes[:-1]])
        costs = (costs if order is None else costs[order]) + starts * analysis_seconds
        start_costs = start_costs if order is None else start_costs[order]
    elif codes is not None:  # every point a physics of its own
        costs = costs + analysis_seconds
    bounds = None
    if chunk_size is None and recorded.get("bounds") is not None and recorded.get("grouped") == grouped:
        bounds = _recorded_bounds(recorded["bounds"], n)
    if bounds is None:
        bounds = chunk_bounds(
            costs, workers=n_workers, starts=starts, breaks=breaks, chunk_size=chunk_size, start_costs=start_costs
        )
    if grouped:  # a block's chunks are written together, once all are done
        block_of = (bounds[:-1] // BLOCK_POINTS).tolist()
        units: list[list[int]] = [[] for _ in range(max(block_of) + 1)]
        for i, b in enumerate(block_of):
            units[b].append(i)
    else:
        units = [[i] for i in range(len(bounds) - 1)]
    return {
        "mode": mode,
        "workers": n_workers,
        "order": order,
        "grouped": grouped,
        "bounds": bounds,
        "units": units,
        "estimate": estimate,
        "chunk_size": "auto" if chunk_size is None else int(chunk_size),
        "analysis_seconds": analysis_seconds,
        "physics": n_physics,
    }


def _time_first_analysis(scene: Scene, points: pd.DataFrame, codes: npt.NDArray[np.int64]) -> float:
    """Seconds one analysis of a point's physics takes here [s] (the analyses are remembered).

    The first physics is timed; when it took under :data:`RETIME_SECONDS`, the
    second is timed too and counts instead: the first pays costs paid once
    per process (caches, CasADi functions), which made a sweep of 10 ms
    analyses look like one of 60 ms ones.
    """
    fields = [name for name in PHYSICS_FIELDS if name in points]
    positions = [0] if codes.max(initial=0) < 1 else [0, int(np.argmax(codes == 1))]
    seconds = 0.0
    for k in positions:
        physics = {name: float(points[name].iloc[k]) for name in fields}
        start = time.perf_counter()
        physics_analysis(scene, physics)
        seconds = time.perf_counter() - start
        if seconds >= RETIME_SECONDS:
            break
    return seconds


def _recorded(parts: Parts) -> dict[str, Any]:
    """The manifest of the sweep ``--resume`` continues, its seed and chunk size held to what ``--seed`` and
    ``--chunk-size`` allow before either is used: a damaged manifest is refused, naming it, not read as options
    the user gave."""
    recorded = parts.manifest()
    for key in ("seed", "chunk_size"):
        value = recorded.get(key)
        if value is None or (key == "chunk_size" and value == "auto"):
            continue
        try:
            whole_number(value, key, OPTION_MINIMUMS[key], OPTION_MAXIMUMS.get(key))
        except SceneError as err:
            manifest = str(parts.folder / parts.MANIFEST)
            raise SceneError(
                "--resume",
                f"the sweep's manifest {manifest!r} is damaged: its {key} {err.message}; "
                f"delete the folder {str(parts.folder)!r} to start over",
            ) from None
    return recorded


def _recorded_bounds(values: object, n: int) -> npt.NDArray[np.int64] | None:
    """The chunk bounds a parts folder recorded, if they fit ``n`` points (else None)."""
    try:
        bounds = np.asarray(values, dtype=np.int64)
    except (TypeError, ValueError):
        return None
    if bounds.ndim != 1 or len(bounds) < 2 or bounds[0] != 0 or bounds[-1] != n or np.any(np.diff(bounds) <= 0):
        return None
    return bounds


class _Assembly:
    """A sweep's finished chunks, put back in point order: streamed to the output, or kept.

    With an output file, a chunk's rows are appended to it as soon as every
    chunk before it is done (kept meanwhile when it finished out of turn, up
    to :data:`HELD_CHUNKS` of them, else read back from its part), so memory
    holds a few chunks (a block of gathered chunks) at a time,
    plus :data:`SUMMARY_COLUMNS` of every point (~11 bytes a point). Without
    one, the chunks are kept and joined at the end.

    Parameters
    ----------
    units : list of list of int
        Chunks whose rows, sorted by point, are the next points, in order.
    n_points : int
        Points of the sweep (numbered 0 .. n_points - 1).
    parts : Parts or None
    output : str or Path or None
    prepare : callable
        Applied to each unit's rows before they are written or kept.
    describe : callable
        The metadata of the output file, from its columns.
    """

    def __init__(
        self,
        units: list[list[int]],
        n_points: int,
        parts: Parts | None,
        output: str | os.PathLike[str] | None,
        prepare: Callable[[pd.DataFrame], pd.DataFrame],
        describe: Callable[[Sequence[str]], dict[str, Any]],
    ) -> None:
        self.units, self.parts, self.prepare = units, parts, prepare
        self.unit_of = {c: u for u, unit in enumerate(units) for c in unit}
        self.next = 0
        self.finished: set[int] = set()
        self.held: dict[int, pd.DataFrame] = {}
        self.kept: list[pd.DataFrame] = []
        self.designs: dict[int, int] = {}
        self.writer = (
            None if output is None else ResultWriter(output, temporary_folder=self._disk().folder, metadata=describe)
        )
        if self.writer is not None:  # the summary, by point
            self.have = np.zeros(n_points, dtype=bool)
            self.status = np.zeros(n_points, dtype=np.int8)
            self.method = np.zeros(n_points, dtype=np.int8)
            self.combinations = np.zeros(n_points, dtype=np.int64)
            self.names: dict[str, dict[str, int]] = {"status": {}, "method": {}}

    def _disk(self) -> Parts:
        """The parts on disk, which only a sweep that writes an output file keeps."""
        if self.parts is None:
            raise RuntimeError("this sweep keeps no parts on disk: it writes no output file")
        return self.parts

    def add(self, index: int, frame: pd.DataFrame | None = None) -> None:
        """Chunk ``index`` is done: its results ``frame``, or (None) its part on disk."""
        self.finished.add(index)
        if frame is None:
            self._note(self._disk().read(index, columns=list(SUMMARY_COLUMNS)))
        else:
            self.designs[index] = int(frame["n_combinations"].sum())
            if self.writer is None or self.unit_of[index] == self.next or len(self.held) < HELD_CHUNKS:
                self.held[index] = frame
            if self.writer is not None:
                self._note(frame)
        self._flush()

    def _note(self, frame: pd.DataFrame) -> None:
        point = frame["point"].to_numpy(dtype=np.int64)
        self.have[point] = True
        self.combinations[point] = frame["n_combinations"].to_numpy(dtype=np.int64)
        for name, target in (("status", self.status), ("method", self.method)):
            local, uniques = pd.factorize(frame[name].to_numpy(dtype=object))
            names = self.names[name]
            codes = np.array([names.setdefault(u, len(names)) for u in uniques], dtype=np.int8)
            target[point] = codes[local] if len(codes) else 0

    def _flush(self) -> None:
        while self.next < len(self.units) and all(c in self.finished for c in self.units[self.next]):
            if self.writer is None and len(self.units[self.next]) == 1:
                self.kept.append(self.held.pop(self.units[self.next][0]))
            else:
                frames = [self.held.pop(c) if c in self.held else self._disk().read(c) for c in self.units[self.next]]
                rows = frames[0] if len(frames) == 1 else _in_point_order(frames)
                if self.writer is None:
                    self.kept.append(rows)
                else:
                    self.writer.append(self.prepare(rows))
            self.next += 1

    def finish(self, complete: bool) -> None:
        """Put the output file in place (complete) or drop it (stopped early)."""
        if self.writer is None:
            return
        if complete:
            self.writer.close()
        else:
            self.writer.abort()

    def abort(self) -> None:
        if self.writer is not None:
            self.writer.abort()

    def designs_run(self, ran: Iterable[int]) -> int:
        return int(sum(self.designs.get(i, 0) for i in ran))

    def frame(self) -> pd.DataFrame | None:
        """The table to return: every kept row, or the summary (None when nothing finished)."""
        if self.writer is not None:
            point = np.flatnonzero(self.have)
            summary = {"point": point.astype(np.int64)}
            for name, codes in (("status", self.status), ("method", self.method)):
                summary[name] = pd.Categorical.from_codes(codes[point], categories=list(self.names[name]))
            summary["n_combinations"] = self.combinations[point]
            return pd.DataFrame(summary)
        # chunks that finished, in point order (after max_chunks some may be missing)
        rest = [self.held[c] for c in sorted(self.held)]
        frames = self.kept + rest
        if not frames:
            return None
        whole = frames[0] if len(frames) == 1 else pd.concat(frames, ignore_index=True)
        if rest or any(len(u) > 1 for u in self.units):
            whole = whole.sort_values("point", kind="stable", ignore_index=True)
        return self.prepare(whole.reset_index(drop=True))


def _in_point_order(frames: Sequence[pd.DataFrame]) -> pd.DataFrame:
    whole = pd.concat(frames, ignore_index=True)
    return whole.sort_values("point", kind="stable", ignore_index=True)
