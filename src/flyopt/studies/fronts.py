"""Design studies built on sweeps: Pareto fronts, the material trade-off table, and
the command-line entry points ``flyopt sweep``, ``flyopt pareto`` and
``flyopt tradeoff``.

Pareto fronts (two objectives, both minimized) come from an ε-constraint
swept through the design model, then the dominated points are removed:

- ``mass`` vs ``outer_diameter``: minimize the mass subject to
  D_outer <= ε, for ε from the smallest wheel that can give the inertia
  (objective ``outer_diameter``, solved by IPOPT) to the outer diameter of the
  lightest wheel (beyond it the constraint no longer binds). The constraint is
  the scene's envelope, so each ε is one sweep point
  ``design.max_outer_diameter = ε``.
- ``mass`` vs ``cost``: for one material and shaft the lightest wheel is also
  the cheapest (cost = mass × cost per kg), so the constraint cost <= ε only
  changes the answer at the cost of some combination's lightest design: the
  front is the non-dominated set of the material × shaft designs (a sweep of
  ``material`` × ``shaft``). Needs a cost on every material.
- ``mass`` vs ``delta``: the lightest wheel for δ <= ε has δ = ε (J_F falls
  as δ grows), so the front is a sweep of δ; where no flywheel is needed the
  mass is 0.

Each front point is a row of the sweep table (the design, how it was
computed) with the two objectives as columns and ``epsilon``, the constraint
value that produced it.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from flyopt.errors import NonPeriodicCycle, SceneError
from flyopt.io.results import write_results
from flyopt.io.sweep_spec import _resolve, _split_unit, load_sweep
from flyopt.studies.evaluate import evaluate_points
from flyopt.studies.plan import plan_sweep
from flyopt.studies.sweep import sweep
from flyopt.units import quantity

__all__ = ["PARETO_OBJECTIVES", "non_dominated", "pareto", "material_tradeoff",
           "sweep_main", "pareto_main", "tradeoff_main"]

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_INFEASIBLE = 0, 1, 2, 3

#: Second objectives a front may trade against mass, with the unit of --range.
PARETO_OBJECTIVES = {
    "outer_diameter": "length",
    "cost": None,
    "delta": "dimensionless",
}


# --------------------------------------------------------------------------
# Pareto fronts
# --------------------------------------------------------------------------

def non_dominated(first, second):
    """Mask of the points no other point dominates (both objectives minimized).

    A point is dominated when another is no worse in both objectives and
    better in one; of several equal points the first is kept.

    Parameters
    ----------
    first, second : array_like
        Objective values (NaN: not a candidate).

    Returns
    -------
    ndarray of bool
    """
    f1, f2 = np.asarray(first, dtype=float), np.asarray(second, dtype=float)
    keep = np.zeros(f1.shape, dtype=bool)
    valid = np.flatnonzero(~(np.isnan(f1) | np.isnan(f2)))
    order = valid[np.lexsort((valid, f2[valid], f1[valid]))]
    best = math.inf
    for k in order:
        if f2[k] < best:
            keep[k] = True
            best = f2[k]
    return keep


def _pair(objectives):
    if isinstance(objectives, str):
        objectives = [o.strip() for o in objectives.split(",")]
    objectives = tuple(objectives)
    other = [o for o in objectives if o != "mass"]
    if len(objectives) != 2 or objectives.count("mass") != 1 or other[0] not in PARETO_OBJECTIVES:
        raise SceneError("objectives", f"{','.join(objectives)!r} is not a known pair: "
                         f"give mass and one of {', '.join(PARETO_OBJECTIVES)} "
                         f"(e.g. mass,outer_diameter)")
    return objectives, other[0]


def pareto(scene, objectives=("mass", "outer_diameter"), *, points=25, span=None,
           method="auto", solver_options=None):
    """Pareto front of mass against a second objective, by an ε-constraint.

    Parameters
    ----------
    scene : Scene
    objectives : pair of str or "mass,OTHER"
        ``mass`` and one of ``outer_diameter``, ``cost``, ``delta``.
    points : int
        Number of ε values (outer diameter, δ).
    span : (float, float), optional
        Range of ε in SI ([m] for the outer diameter, δ for delta); by
        default the whole front for the outer diameter and δ/10 .. 10 δ
        (below 1) for delta.
    method : {"auto", "closed_form", "ipopt"}
        How each ε point is designed (see :func:`flyopt.studies.sweep.evaluate_points`):
        ``ipopt`` sends every point through the CasADi/IPOPT model.
    solver_options : mapping, optional

    Returns
    -------
    pandas.DataFrame
        The non-dominated designs, sorted by the second objective: the sweep
        columns plus ``epsilon`` and one column per objective. Empty (with
        ``attrs["message"]``) when no flywheel is needed or none is feasible.

    Raises
    ------
    SceneError
        Unknown objectives, bad span, materials without a cost for ``cost``.
    """
    objectives, other = _pair(objectives)
    if not isinstance(points, (int, np.integer)) or points < 2:
        raise SceneError("points", f"must be a whole number >= 2, got {points!r}")
    from flyopt.analysis import analyse

    analysis = analyse(scene)
    empty = pd.DataFrame()
    if analysis.j_margin <= 0.0 and other != "delta":
        empty.attrs["message"] = (f"no flywheel needed (J_F = {analysis.j_margin:.4g} kg·m²): "
                                  f"nothing to trade")
        return empty
    if other == "outer_diameter":
        rows = _front_outer_diameter(scene, points, span, method, solver_options)
    elif other == "cost":
        rows = _front_cost(scene, method, solver_options)
    else:
        rows = _front_delta(scene, points, span, method, solver_options)
    if rows.empty:
        rows.attrs["message"] = "no material and shaft can give the inertia anywhere on the range"
        return rows
    rows = rows.copy()
    rows["mass"] = np.where(rows["status"] == "not_needed", 0.0, rows["mass"])
    rows[other] = rows[{"outer_diameter": "d_outer", "cost": "cost", "delta": "delta"}[other]]
    if other == "outer_diameter":
        rows[other] = np.where(rows["status"] == "not_needed", 0.0, rows[other])
    usable = rows["status"].isin(["designed", "not_needed"]).to_numpy()
    keep = non_dominated(np.where(usable, rows[other], np.nan), rows["mass"])
    front = rows[keep].sort_values([other, "mass"], kind="stable").reset_index(drop=True)
    front.attrs["objectives"] = list(objectives)
    front.attrs["evaluated"] = len(rows)
    return front


def _front_outer_diameter(scene, points, span, method, solver_options):
    spec = scene.design
    envelope = spec.max_outer_diameter
    lightest = evaluate_points(scene, pd.DataFrame({"point": [0], "design.objective": ["mass"]}),
                               method=method, solver_options=solver_options)
    if span is None:
        if spec.geometry == "disc" and spec.max_width is None:
            raise SceneError("design.max_width", "a disc with no width limit can be made as "
                             "small as one likes (thinner and wider): give max_width or a "
                             "range for the outer diameter")
        smallest = evaluate_points(
            scene, pd.DataFrame({"point": [1], "design.objective": ["outer_diameter"]}),
            solver_options=solver_options)
        if lightest["status"].iloc[0] != "designed" or smallest["status"].iloc[0] != "designed":
            return pd.DataFrame()
        low, high = float(smallest["d_outer"].iloc[0]), float(lightest["d_outer"].iloc[0])
        smallest = smallest.assign(epsilon=low)
        # the smallest wheel is the end of the front; the ε points start just above it,
        # where the lightest wheel under the cap exists without rounding doubts
        grid = np.geomspace(low, high, points)[1:] if high > low else np.array([])
    else:
        low, high = span
        if envelope is not None:
            high = min(high, envelope)
        if not 0 < low <= high:
            raise SceneError("range", f"the outer diameter range {low:.6g}..{high:.6g} m is "
                             f"empty or not positive")
        grid = np.geomspace(low, high, points)
        smallest = None
    frames = [] if smallest is None else [smallest]
    if grid.size:
        swept = sweep(scene, {"design.max_outer_diameter": list(grid), "design.objective": "mass"},
                      method=method, solver_options=solver_options, workers=1)
        frames.append(swept.assign(epsilon=swept["design.max_outer_diameter"]))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def _front_cost(scene, method, solver_options):
    library = scene.material_library()
    names = list(scene.design_materials or library)
    missing = [n for n in names if library[n].cost is None]
    if missing:
        raise SceneError("material", f"a mass-cost front needs a cost per kg on every "
                         f"material; none is given for {', '.join(missing)} "
                         f"(add cost = \"... 1/kg\" in [[material]])")
    shafts = [s.name for s in scene.shafts
              if scene.design_shafts is None or s.name in scene.design_shafts]
    swept = sweep(scene, {"material": names, "shaft": shafts, "design.objective": "mass"},
                  method=method, solver_options=solver_options, workers=1)
    return swept.assign(epsilon=swept["cost"])


def _front_delta(scene, points, span, method, solver_options):
    if span is None:
        span = (scene.delta / 10.0, min(scene.delta * 10.0, 1.0))
    low, high = span
    if not 0 < low <= high < 2:
        raise SceneError("range", f"the δ range {low:.6g}..{high:.6g} must lie in (0, 2)")
    grid = np.geomspace(low, high, points)
    swept = sweep(scene, {"delta": list(grid), "design.objective": "mass"}, method=method,
                  solver_options=solver_options, workers=1)
    return swept.assign(epsilon=swept["delta"])


# --------------------------------------------------------------------------
# Material trade-off table
# --------------------------------------------------------------------------

TRADEOFF_COLUMNS = ("material", "status", "shaft", "speed_ratio", "d_outer", "d_mean", "h", "b",
                    "hb_ratio", "rim_speed", "rim_speed_limit", "mass", "cost", "binding", "limit",
                    "reason", "method", "solver_status")


def material_tradeoff(scene, solver_options=None, method="auto"):
    """For each material, its lightest design: size, rim speed, mass, cost, binding limit.

    Parameters
    ----------
    scene : Scene
        Its materials (``design.materials`` or every known one) and shafts;
        the objective is mass whatever the scene says.
    solver_options : mapping, optional
    method : {"auto", "ipopt", "closed_form"}
        Design method (see :func:`flyopt.design.optimize.design_flywheel`).

    Returns
    -------
    pandas.DataFrame
        One row per material, lightest first, then the infeasible ones:
        ``material``, ``status`` (designed, infeasible, not_needed), the
        chosen ``shaft``, ``d_outer``, ``d_mean``, ``h``, ``b`` [m],
        ``rim_speed`` and its limit [m/s], ``mass`` [kg], ``cost``,
        ``binding`` (every active constraint), ``limit`` (the active limits
        other than the inertia itself), ``reason`` (for an infeasible
        material: why, for each shaft), ``method`` and ``solver_status``.

    Notes
    -----
    Each material is designed by :func:`flyopt.design.optimize.design_flywheel`
    (the exact closed form, or IPOPT, after the closed-form infeasibility
    proof) on every allowed shaft; the lightest shaft wins.
    """
    from flyopt.analysis import analyse
    from flyopt.design.optimize import MountShaft, design_flywheel

    analysis = analyse(scene)
    library = scene.material_library()
    names = list(scene.design_materials or library)
    shafts = [MountShaft(s.name, s.speed_ratio) for s in scene.shafts
              if scene.design_shafts is None or s.name in scene.design_shafts]
    spec = dataclasses.replace(scene.design, objective="mass")
    rows = []
    for name in names:
        material = library[name]
        row = dict.fromkeys(TRADEOFF_COLUMNS)
        row.update(material=name, rim_speed_limit=material.max_rim_speed, binding="", limit="",
                   reason="", method="", solver_status="", shaft="")
        result = design_flywheel(analysis.j_margin, analysis.omega_max, shafts, [material], spec,
                                 solver_options=solver_options, method=method)
        row["status"] = result.status
        best = result.best
        if best is not None:
            row.update(shaft=best.shaft, speed_ratio=best.speed_ratio, d_outer=best.d_outer,
                       d_mean=best.d_mean, h=best.h, b=best.b, hb_ratio=best.hb_ratio,
                       rim_speed=best.rim_speed, mass=best.mass, cost=best.cost,
                       binding=",".join(best.binding),
                       limit=",".join(b for b in best.binding if b != "inertia"),
                       method="closed_form" if best.solver_status == "closed_form" else "ipopt",
                       solver_status=best.solver_status)
        elif result.status == "infeasible":
            row["reason"] = "; ".join(c.reason for c in result.candidates)
            row["method"] = "closed_form"
        else:
            row["reason"] = result.message
            row["method"] = "none"
        rows.append(row)
    table = pd.DataFrame(rows, columns=list(TRADEOFF_COLUMNS))
    for column in ("speed_ratio", "d_outer", "d_mean", "h", "b", "hb_ratio", "rim_speed",
                   "rim_speed_limit", "mass", "cost"):
        table[column] = pd.to_numeric(table[column]).astype(float)
    order = np.lexsort((np.arange(len(table)), table["mass"].fillna(np.inf).to_numpy()))
    return table.iloc[order].reset_index(drop=True)


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def _fail(message, status):
    print(f"flyopt: error: {message}", file=sys.stderr)
    return status


def _guard(run, args, scene_path):
    try:
        return run(args)
    except (SceneError, NonPeriodicCycle) as err:
        return _fail(str(err), EXIT_INPUT)
    except OSError as err:
        where = f"{err.filename}: " if getattr(err, "filename", None) else ""
        return _fail(f"{scene_path}: cannot write the results: {where}{err.strerror or err}", EXIT_INPUT)
    except ArithmeticError as err:
        return _fail(f"{scene_path}: {err}", EXIT_FAILED)


def _workers(text):
    if text == "auto":
        return "auto"
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: a whole number or 'auto'") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: at least 1")
    return value


def _positive_int(text):
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: at least 1")
    return value


def sweep_parser():
    """The argparse parser of ``flyopt sweep`` (for embedding as a subcommand)."""
    parser = argparse.ArgumentParser(
        prog="flyopt sweep",
        description="Sweep a scene over a grid (or Latin hypercube) of its fields: one row "
                    "per point with every input and result, to Parquet or CSV.",
        epilog="FIELD: delta, speed, inertia, torque.scale, design.max_outer_diameter "
               "(envelope), design.max_width, design.d_mean, design.hb_ratio, design.hb_min, "
               "design.hb_max, design.geometry, design.objective, material, shaft, "
               "shaft.NAME.speed_ratio, material.NAME.density|max_rim_speed|cost. "
               "VALUES: a,b,c | a:b:n | a:b:logn, a unit after the last value applies to "
               "all (300,600,1200rpm; 0.4:1.2:5 m); 'none' for no limit.")
    parser.add_argument("scene", help="scene file (TOML); a [sweep] table in it is read too")
    parser.add_argument("--vary", action="append", default=[], metavar="FIELD=VALUES",
                        help="a field and its values (repeat for a grid)")
    parser.add_argument("-o", "--output", help="result file, .parquet or .csv "
                        "(default: CSV on stdout)")
    parser.add_argument("--samples", type=_positive_int, metavar="N",
                        help="N Latin hypercube samples instead of the full grid")
    parser.add_argument("--seed", type=int, help="seed of the Latin hypercube")
    parser.add_argument("--workers", type=_workers, metavar="N|auto",
                        help="worker processes on this machine (default auto: one per CPU, "
                             "serial when the sweep is too small to gain)")
    parser.add_argument("--chunk-size", type=_positive_int, metavar="N",
                        help="points per chunk (default 2500 closed form, 50 with IPOPT)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run on a Dask cluster, e.g. tcp://host:8786")
    parser.add_argument("--resume", action="store_true",
                        help="continue an interrupted sweep from OUTPUT.parts/")
    parser.add_argument("--max-chunks", type=int, metavar="K",
                        help="stop after K chunks (continue later with --resume)")
    parser.add_argument("--method", choices=("auto", "closed_form", "ipopt"),
                        help="design method: closed form where exact, else IPOPT (auto)")
    parser.add_argument("--keep-parts", action="store_true",
                        help="keep OUTPUT.parts/ after writing the output")
    parser.add_argument("--no-progress", dest="progress", action="store_false",
                        help="no progress line on stderr")
    return parser


def sweep_main(argv=None):
    """``flyopt sweep``: returns the exit status (0 done, 2 bad input)."""
    args = sweep_parser().parse_args(argv)
    return _guard(_sweep_command, args, args.scene)


def _sweep_command(args):
    scene, options = load_sweep(args.scene)
    vary = dict(options.pop("vary", {}))
    if vary:  # the file's own values: errors name the file and its sweep.vary field
        plan_sweep(scene, vary, samples=options.get("samples"), seed=options.get("seed"),
                   where=f"{args.scene}: sweep.vary")
    for text in args.vary:
        if "=" not in text:
            raise SceneError("--vary", f"{text!r}: expected FIELD=VALUES, e.g. "
                             f"delta=0.01:0.1:log20 or speed=300,600,1200rpm")
        path, values = text.split("=", 1)
        canonical = _resolve(scene, path.strip(), "--vary")[0]
        for key in list(vary):   # the command line overrides the file
            if _resolve(scene, key, "sweep.vary")[0] == canonical:
                del vary[key]
        vary[path.strip()] = values
    cli = {"samples": args.samples, "seed": args.seed, "output": args.output,
           "chunk_size": args.chunk_size, "method": args.method, "workers": args.workers}
    for key, value in cli.items():
        if value is not None:
            options[key] = value
    output = options.pop("output", None)
    if output is not None and args.output is None:
        output = Path(args.scene).parent / output   # [sweep] output is relative to the file
    frame = sweep(scene, vary, output=output, scheduler=args.scheduler, resume=args.resume,
                  max_chunks=args.max_chunks, progress=args.progress,
                  keep_parts=args.keep_parts, **options)
    info = frame.attrs["sweep"]
    counts = frame["status"].value_counts().to_dict()
    summary = ", ".join(f"{counts.get(s, 0)} {s.replace('_', ' ')}"
                        for s in ("designed", "infeasible", "not_needed", "failed"))
    methods = ", ".join(f"{v} {k}" for k, v in frame["method"].value_counts().items())
    rate = info["designs"] / info["seconds"] if info["seconds"] > 0 else math.inf
    if not info["complete"]:
        left = info["chunks"] - len(info["chunks_run"]) - len(info["chunks_reused"])
        print(f"flyopt sweep: stopped after {len(info['chunks_run'])} chunks, {left} left: "
              f"continue with --resume ({_parts_name(output)})", file=sys.stderr)
        return EXIT_OK
    if output is None:
        sys.stdout.write(frame.to_csv(index=False))
    where = f"wrote {output}" if output is not None else "done"
    print(f"flyopt sweep: {where}: {len(frame)} points ({summary}); methods: {methods}; "
          f"{info['designs']} designs in {info['seconds']:.2f} s ({rate:,.0f} designs/s, "
          f"{info['mode']})", file=sys.stderr)
    return EXIT_OK


def _parts_name(output):
    return f"{output}.parts" if output is not None else "no output file"


def _span(text, other):
    if text is None:
        return None
    dimension = PARETO_OBJECTIVES[other]
    if dimension is None:
        raise SceneError("--range", f"the {other} front has no range: it is the set of "
                         f"material x shaft designs")
    parts = text.split(":")
    if len(parts) != 2:
        raise SceneError("--range", f"{text!r}: expected LOW:HIGH with an optional unit, "
                         f"e.g. 0.3:1.2 m")
    trailing = _split_unit(parts[1])[1]
    ends = []
    for part in parts:
        number, unit = _split_unit(part)
        raw = f"{number} {unit or trailing}".strip()
        ends.append(quantity(raw, dimension, "--range"))
    return tuple(ends)


_SHOW = {
    "outer_diameter": ["mass", "outer_diameter", "best_material", "best_shaft", "b", "h",
                       "binding", "method"],
    "cost": ["mass", "cost", "best_material", "best_shaft", "d_outer", "binding", "method"],
    "delta": ["mass", "delta", "best_material", "best_shaft", "d_outer", "binding", "method"],
}


def pareto_parser():
    """The argparse parser of ``flyopt pareto``."""
    parser = argparse.ArgumentParser(
        prog="flyopt pareto",
        description="Pareto front of mass against outer diameter, cost or delta, by an "
                    "epsilon-constraint swept through the design model.")
    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument("--objectives", default="mass,outer_diameter",
                        help="mass,outer_diameter | mass,cost | mass,delta "
                             "(default mass,outer_diameter)")
    parser.add_argument("--points", type=_positive_int, default=25,
                        help="number of epsilon values (default 25)")
    parser.add_argument("--range", dest="span", metavar="LOW:HIGH",
                        help="range of epsilon, e.g. 0.3:1.2 m or 0.01:0.1")
    _method_and_output(parser, "front")
    return parser


def _method_and_output(parser, what):
    """The options ``flyopt pareto`` and ``flyopt tradeoff`` share: the design method and the output."""
    parser.add_argument("--method", choices=("auto", "closed_form", "ipopt"), default="auto",
                        help="design method: closed form where exact, else IPOPT (auto); ipopt: every "
                             "combination through the CasADi/IPOPT model")
    parser.add_argument("-o", "--output", help=f"write the {what} to .csv, .parquet or .json")
    parser.add_argument("--json", action="store_true", help=f"print the {what} as JSON records")


def pareto_main(argv=None):
    """``flyopt pareto``: returns the exit status (0 front, 2 bad input, 3 no design)."""
    args = pareto_parser().parse_args(argv)
    return _guard(_pareto_command, args, args.scene)


def _pareto_command(args):
    from flyopt.io.scene import load

    scene = load(args.scene)
    objectives, other = _pair(args.objectives)
    front = pareto(scene, objectives, points=args.points, span=_span(args.span, other),
                   method=args.method)
    if front.empty:
        message = front.attrs.get("message", "empty front")
        print(f"{args.scene}: {message}")
        return EXIT_OK if message.startswith("no flywheel needed") else EXIT_INFEASIBLE
    _emit(front, args.output, args.json, _SHOW[other],
          f"{args.scene}: Pareto front, {' vs '.join(objectives)} "
          f"({len(front)} non-dominated of {front.attrs['evaluated']} designs)")
    return EXIT_OK


def tradeoff_parser():
    """The argparse parser of ``flyopt tradeoff``."""
    parser = argparse.ArgumentParser(
        prog="flyopt tradeoff",
        description="For each material the lightest design: size, rim speed, mass, cost and "
                    "which limit binds.")
    parser.add_argument("scene", help="scene file (TOML)")
    _method_and_output(parser, "table")
    return parser


def tradeoff_main(argv=None):
    """``flyopt tradeoff``: returns the exit status (0 a design, 2 bad input, 3 none feasible)."""
    args = tradeoff_parser().parse_args(argv)
    return _guard(_tradeoff_command, args, args.scene)


def _tradeoff_command(args):
    from flyopt.io.scene import load

    scene = load(args.scene)
    table = material_tradeoff(scene, method=args.method)
    _emit(table, args.output, args.json,
          ["material", "status", "shaft", "d_outer", "b", "rim_speed", "rim_speed_limit",
           "mass", "cost", "limit"],
          f"{args.scene}: lightest design per material")
    if (table["status"] == "infeasible").all():
        for reason in table["reason"]:
            print(f"  {reason}")
        return EXIT_INFEASIBLE
    return EXIT_OK


_UNITS = {"mass": "kg", "outer_diameter": "m", "d_outer": "m", "d_mean": "m", "b": "m", "h": "m",
          "rim_speed": "m/s", "rim_speed_limit": "m/s", "delta": "-", "cost": "",
          "epsilon": ""}


def _emit(frame, output, as_json, columns, title):
    if output is not None:
        suffix = Path(output).suffix.lower()
        if suffix == ".json":
            Path(output).write_text(_json(frame), encoding="utf-8")
        else:
            write_results(frame, output)
    if as_json:
        print(_json(frame))
        return
    shown = frame[[c for c in columns if c in frame]].copy()
    shown.columns = [f"{c} [{_UNITS[c]}]" if _UNITS.get(c) else c for c in shown.columns]
    print(title)
    print(shown.to_string(index=False, float_format=lambda x: f"{x:.5g}", na_rep="-"))
    if output is not None:
        print(f"wrote {output}")


def _json(frame):
    records = json.loads(frame.to_json(orient="records"))
    return json.dumps(records, indent=2, allow_nan=False)
