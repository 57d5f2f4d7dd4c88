"""Design sweeps: one scene varied over a grid or a Latin hypercube of its fields.

``sweep(scene, {"delta": "0.01:0.1:log20", "speed": "300,600,1200rpm",
"material": "cast_iron,cast_steel"})`` returns a pandas DataFrame with one
row per point: every input and every result (the best design, its binding
constraints, feasibility, how it was computed). The same runs from the
command line (``flyopt sweep``) and from a ``[sweep]`` table in a scene file.

The stages, each in its own module, joined here:

- the fields, their values and the other options (:mod:`flyopt.io.sweep_spec`),
- the points, a grid or a Latin hypercube (:mod:`flyopt.studies.plan`),
- the design of every point (:mod:`flyopt.studies.evaluate`),
- the chunks, run serially, in processes or on Dask, with resume
  (:mod:`flyopt.studies.runner`),
- the result table and its files (:mod:`flyopt.io.results`).
"""

from __future__ import annotations

import functools
import time

import numpy as np
import pandas as pd

from flyopt.design import closed_form as batch
from flyopt.errors import Interrupted, SceneError
from flyopt.io.results import write_results
from flyopt.io.sweep_spec import check_options, option_label
from flyopt.studies.evaluate import _context, _evaluate, _Inputs, evaluate_points
from flyopt.studies.plan import plan_sweep
from flyopt.studies.runner import (CHUNK_CLOSED_FORM, CHUNK_IPOPT, SERIAL_SECONDS, Parts,
                                   chunks_of, connect, cpu_count, estimated_seconds,
                                   fingerprint, picklable, run_chunks, stopped)

__all__ = ["sweep"]


def check_sweep(scene, options, where="sweep"):
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
        return plan_sweep(scene, options.get("vary") or {}, samples=options.get("samples"),
                          seed=options.get("seed"), where=option_label(where, "vary"))
    except SceneError as err:
        if where.startswith("--") or scene.source is None:
            raise
        raise err.with_source(scene.source) from None


def sweep(scene, vary=None, *, samples=None, seed=None, output=None, workers="auto",
          chunk_size=None, scheduler=None, resume=False, max_chunks=None, progress=False,
          method="auto", solver_options=None, keep_parts=False):
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
        File to write, ``.parquet`` or ``.csv``. Chunks are streamed to
        ``OUTPUT.parts/`` as they finish.
    workers : int or "auto"
        Worker processes on this machine (1: serial, in this process).
        ``auto``: one per available CPU, or serial when the sweep is
        estimated to take under :data:`~flyopt.studies.runner.SERIAL_SECONDS`
        in one process.
    chunk_size : int, optional
        Points per chunk (default 2500 closed form, 50 when IPOPT runs).
    scheduler : str or dask.distributed Client or cluster, optional
        Run the chunks on a Dask cluster (``"tcp://host:8786"``).
    resume : bool
        Continue an interrupted sweep: chunks whose part file exists (and
        holds its chunk) are read, not rerun. The parts must come from the
        same sweep.
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
        One row per point (see :func:`flyopt.studies.evaluate.evaluate_points`),
        in point order; a Latin hypercube's table has a ``seed`` column after
        ``point``. ``frame.attrs["sweep"]`` tells how it ran: chunks run and
        reused, workers, seconds, seed, whether it is complete.

    Raises
    ------
    SceneError
        Bad fields, values or options (named as on the command line), parts
        of another sweep, or a Dask scheduler that does not answer (checked
        before anything is written).
    NonPeriodicCycle
        The scene's cycle does not balance.
    Interrupted
        Ctrl-C, or a Dask cluster that lost its workers: the finished chunks
        stay in ``OUTPUT.parts/`` and ``resume=True`` continues.
    """
    check_options(dict(samples=samples, seed=seed, output=output, chunk_size=chunk_size,
                       max_chunks=max_chunks, method=method, workers=workers, resume=resume),
                  "--")
    parts = None if output is None else Parts(output)
    if resume and samples is not None and seed is None and parts is not None:
        seed = parts.manifest().get("seed")   # the samples of the sweep being continued
    plan = plan_sweep(scene, vary or {}, samples=samples, seed=seed)
    points = plan.points
    axes = tuple(a.field for a in plan.axes)
    ctx = _context(scene, method, solver_options, axes)
    closed_form, ipopt = _design_counts(_Inputs(ctx.scene, points), method)
    if chunk_size is None:
        chunk_size = CHUNK_IPOPT if ipopt else CHUNK_CLOSED_FORM
    chunks = chunks_of(points, chunk_size)
    task = functools.partial(_evaluate, ctx)
    with connect(scheduler) as client:   # before anything is written
        done = {}
        if parts is not None:
            identity = repr((repr(scene.replace(source=None)), method,
                             sorted((solver_options or {}).items()), axes))
            done = parts.open({"fingerprint": fingerprint(identity, points, chunk_size),
                               "points": len(points), "chunk_size": int(chunk_size),
                               "chunks": len(chunks), "seed": plan.seed}, chunks, resume)
        reused = sorted(done)
        pending = [(i, chunk) for i, chunk in chunks if i not in done]
        if max_chunks is not None:
            pending = pending[:max_chunks]
        if client is not None:
            mode, n_workers = "dask", None
        else:
            if workers == "auto":
                small = estimated_seconds(closed_form, ipopt) < SERIAL_SECONDS
                n_workers = 1 if small else min(cpu_count(), len(pending))
            else:
                n_workers = min(int(workers), max(len(pending), 1))
            mode = "processes" if n_workers > 1 and picklable(task) else "serial"
        start = time.perf_counter()
        results, ran = run_chunks(task, chunks, pending, parts=parts, done=done,
                                  workers=n_workers if mode == "processes" else 1,
                                  client=client, progress=progress)
        seconds = time.perf_counter() - start
    complete = len(results) == len(chunks)
    frames = [results[i] for i in sorted(results)]
    frame = (pd.concat(frames, ignore_index=True) if frames
             else evaluate_points(ctx, points.iloc[:0]))
    if plan.samples is not None:
        frame.insert(1, "seed", np.full(len(frame), plan.seed, dtype=np.int64))
    if complete and parts is not None:
        try:
            write_results(frame, output, temporary_folder=parts.folder)
        except KeyboardInterrupt:
            raise Interrupted(stopped("interrupted while writing the output", parts,
                                      len(results), len(chunks))) from None
        if not keep_parts:
            parts.remove()
    frame.attrs["sweep"] = {
        "points": len(points), "chunks": len(chunks), "chunk_size": int(chunk_size),
        "chunks_run": sorted(ran), "chunks_reused": reused, "complete": complete,
        "mode": mode, "workers": n_workers, "seconds": seconds, "seed": plan.seed,
        "designs": int(sum(results[i]["n_combinations"].sum() for i in ran)),
        "output": None if output is None else str(output),
    }
    return frame


def _design_counts(inputs, method):
    """Designs (point × material × shaft) by the closed form and by IPOPT."""
    per_point = len(inputs.material_names) * len(inputs.shaft_names)
    if inputs.material is not None:
        per_point //= max(len(inputs.material_names), 1)
    if inputs.shaft is not None:
        per_point //= max(len(inputs.shaft_names), 1)
    if method == "ipopt":
        return 0, per_point * inputs.n
    pairs = pd.DataFrame({"g": inputs.geometry, "o": inputs.objective}).value_counts()
    closed = sum(int(count) for (g, o), count in pairs.items() if batch.covers(g, o))
    return per_point * closed, per_point * (inputs.n - closed)
