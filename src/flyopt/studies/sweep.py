"""Design sweeps: one scene varied over a grid or a Latin hypercube of its fields.

``sweep(scene, {"delta": "0.01:0.1:log20", "speed": "300,600,1200rpm",
"material": "cast_iron,cast_steel"})`` returns a pandas DataFrame with one
row per point: every input and every result (the best design, its binding
constraints, feasibility, how it was computed). The same runs from the
command line (``flyopt sweep``) and from a ``[sweep]`` table in a scene file.

The stages, each in its own module: the fields and their values
(:mod:`flyopt.io.sweep_spec`), the points (:mod:`flyopt.studies.plan`), the
design of every point (:mod:`flyopt.studies.evaluate`), the chunks run in
processes or on Dask with resume (:mod:`flyopt.studies.runner`) and the
result files (:mod:`flyopt.io.results`).
"""

from __future__ import annotations

import json
import math
import shutil
import time

import numpy as np
import pandas as pd

from flyopt.design import closed_form as batch
from flyopt.errors import SceneError
from flyopt.io.results import _check_folder, _format, read_results, write_results
from flyopt.studies.evaluate import _context, _Inputs, evaluate_points
from flyopt.studies.plan import plan_sweep
from flyopt.studies.runner import (CHUNK_CLOSED_FORM, CHUNK_IPOPT, SERIAL_SECONDS, _cpu_count,
                                   _estimated_seconds, _fingerprint, _part_path, _parts_dir,
                                   _Progress, _run_chunk, _run_dask, _run_processes)

__all__ = ["sweep"]


def sweep(scene, vary=None, *, samples=None, seed=None, output=None, workers="auto",
          chunk_size=None, scheduler=None, resume=False, max_chunks=None, progress=False,
          method="auto", solver_options=None, keep_parts=False):
    """Sweep a scene over a grid (or Latin hypercube) of its fields.

    Parameters
    ----------
    scene : Scene
    vary : mapping or iterable of str
        Fields and their values, ``{"delta": "0.01:0.1:log20"}`` or
        ``["delta=0.01:0.1:log20"]``; see the module notes for the grammar.
    samples : int, optional
        Latin hypercube samples instead of the full grid.
    seed : int, optional
        Seed of the Latin hypercube.
    output : str or Path, optional
        File to write, ``.parquet`` or ``.csv``. Chunks are streamed to
        ``OUTPUT.parts/`` as they finish.
    workers : int or "auto"
        Worker processes on this machine (1: serial, in this process).
        ``auto``: one per available CPU, or serial when the sweep is
        estimated to take under :data:`SERIAL_SECONDS` in one process.
    chunk_size : int, optional
        Points per chunk (default 2500 closed form, 50 when IPOPT runs).
    scheduler : str or dask.distributed Client or cluster, optional
        Run the chunks on a Dask cluster (``"tcp://host:8786"``).
    resume : bool
        Continue an interrupted sweep: chunks whose part file exists are
        read, not rerun. The parts must come from the same sweep.
    max_chunks : int, optional
        Run at most this many chunks in this call and stop (the rest is left
        for ``resume``); the returned table then holds the finished chunks.
    progress : bool
        Progress line with rate and ETA on stderr.
    method : {"auto", "closed_form", "ipopt"}
        See :func:`evaluate_points`.
    solver_options : mapping, optional
        CasADi/IPOPT options for points solved by IPOPT.
    keep_parts : bool
        Keep ``OUTPUT.parts/`` after the final file is written.

    Returns
    -------
    pandas.DataFrame
        One row per point (see :func:`evaluate_points`), in point order.
        ``frame.attrs["sweep"]`` tells how it ran: chunks run and reused,
        workers, seconds, whether it is complete.

    Raises
    ------
    SceneError
        Bad fields, values or options (named), or parts of another sweep.
    NonPeriodicCycle
        The scene's cycle does not balance.
    """
    if method not in ("auto", "closed_form", "ipopt"):
        raise SceneError("method", f"{method!r} is not known (allowed: auto, closed_form, ipopt)")
    plan = plan_sweep(scene, vary or {}, samples=samples, seed=seed)
    points = plan.points
    ctx = _context(scene, method, solver_options, tuple(a.field for a in plan.axes))
    n = len(points)
    inputs = _Inputs(ctx.scene, points)
    all_closed = method != "ipopt" and all(
        batch.covers(g, o) for g, o in set(zip(inputs.geometry, inputs.objective)))
    if chunk_size is None:
        chunk_size = CHUNK_CLOSED_FORM if all_closed else CHUNK_IPOPT
    if not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise SceneError("chunk_size", f"must be a positive whole number, got {chunk_size!r}")
    n_chunks = max(1, math.ceil(n / chunk_size))
    chunks = [(i, points.iloc[i * chunk_size:(i + 1) * chunk_size]) for i in range(n_chunks)]
    if output is not None:
        _format(output)
    if resume and output is None:
        raise SceneError("resume", "needs an output file (its parts hold the finished chunks)")
    # -- parts already on disk ---------------------------------------------
    done = {}
    parts = _parts_dir(output) if output is not None else None
    fingerprint = _fingerprint(ctx, points, chunk_size)
    if parts is not None:
        manifest = parts / "sweep.json"
        if parts.exists():
            if not resume:
                raise SceneError("output", f"{str(parts)!r} holds the chunks of an earlier, "
                                 f"unfinished sweep: resume it (--resume) or delete the folder")
            try:
                old = json.loads(manifest.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                old = {}
            if old.get("fingerprint") != fingerprint:
                raise SceneError("resume", f"the parts in {str(parts)!r} come from a different "
                                 f"sweep (scene, fields, values or chunk size differ); delete "
                                 f"the folder to start over")
            for i, _ in chunks:
                part = _part_path(parts, i)
                if part.exists():
                    done[i] = read_results(part)
        else:
            _check_folder(parts)
            parts.mkdir()
            manifest.write_text(json.dumps({"fingerprint": fingerprint, "points": n,
                                            "chunk_size": int(chunk_size),
                                            "chunks": n_chunks}), encoding="utf-8")
    pending = [(i, chunk) for i, chunk in chunks if i not in done]
    if max_chunks is not None:
        if not isinstance(max_chunks, (int, np.integer)) or max_chunks < 0:
            raise SceneError("max_chunks", f"must be a whole number >= 0, got {max_chunks!r}")
        pending = pending[:max_chunks]
    # -- how to run ----------------------------------------------------------
    if scheduler is not None:
        mode, n_workers = "dask", None
    else:
        if workers == "auto":
            small = _estimated_seconds(inputs, method) < SERIAL_SECONDS
            n_workers = 1 if small else min(_cpu_count(), len(pending))
        else:
            if not isinstance(workers, (int, np.integer)) or workers < 1:
                raise SceneError("workers", f"must be a positive whole number or 'auto', "
                                 f"got {workers!r}")
            n_workers = min(int(workers), max(len(pending), 1))
        # a scene whose torques must travel to the workers may not pickle
        mode = "serial" if n_workers <= 1 or not ctx.reusable else "processes"
    meter = _Progress(n, n_chunks, progress, done_points=sum(len(d) for d in done.values()))
    results = dict(done)
    ran = []
    start = time.perf_counter()

    def finished(i, frame):
        if parts is not None:
            write_results(frame, _part_path(parts, i))
        results[i] = frame
        ran.append(i)
        meter.update(len(frame), int(frame["n_combinations"].sum()))

    if pending:
        if mode == "serial":
            for i, chunk in pending:
                finished(*_run_chunk(ctx, i, chunk))
        elif mode == "processes":
            _run_processes(ctx, pending, n_workers, finished)
        else:
            _run_dask(scheduler, ctx, pending, finished)
    meter.close()
    elapsed = time.perf_counter() - start
    complete = len(results) == n_chunks
    frames = [results[i] for i in sorted(results)]
    frame = (pd.concat(frames, ignore_index=True) if frames
             else evaluate_points(ctx, points.iloc[:0]))
    if complete and output is not None:
        write_results(frame, output)
        if not keep_parts:
            shutil.rmtree(parts, ignore_errors=True)
    frame.attrs["sweep"] = {
        "points": n, "chunks": n_chunks, "chunk_size": int(chunk_size),
        "chunks_run": sorted(ran), "chunks_reused": sorted(done), "complete": complete,
        "mode": mode, "workers": n_workers, "seconds": elapsed,
        "designs": int(sum(results[i]["n_combinations"].sum() for i in ran)),
        "output": None if output is None else str(output),
    }
    return frame


