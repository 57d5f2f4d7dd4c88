"""``flyopt sweep``, ``flyopt pareto`` and ``flyopt tradeoff``: their options and handlers.

The studies themselves live in :mod:`flyopt.studies`; this module only reads
the command line, calls them and prints or writes what they return. Errors
are raised and said by :func:`flyopt.cli.exits.status_of` (one line, one
exit code from the table there).

Every file a study writes describes itself (:mod:`flyopt.outputs.results`): the
units of its columns, the flyopt version, the scene and its digest, and for
a Pareto front its objectives (``flyopt plot`` reads them), as Parquet
metadata, as the sidecar ``FILE.csv.json`` of a CSV file, or in the JSON
document itself; missing values are nulls. ``-o`` and ``--quiet`` follow the
conventions of :mod:`flyopt.cli.main`.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, cast

from flyopt.cli.exits import EXIT_INFEASIBLE, EXIT_OK, run
from flyopt.errors import SceneError

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.io.scene import Scene


def _workers(text: str) -> int | Literal["auto"]:
    """``--workers``: "auto" or a whole number, whose range the sweep's options check (``check_options``: one rule
    for the command line and a scene's [sweep] table)."""
    if text == "auto":
        return "auto"
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be 'auto' or a whole number, got {text!r}") from None


def _positive_int(text: str, expected: str = "a whole number") -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: {expected}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: at least 1")
    return value


def add_quiet_argument(parser: argparse.ArgumentParser) -> None:
    """``-q``/``--quiet``, in the words of every flyopt command (see :mod:`flyopt.cli.main`)."""
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        help="print nothing but errors; the result still goes to the -o file, or to stdout without one",
    )


# --------------------------------------------------------------------------
# flyopt sweep
# --------------------------------------------------------------------------

SWEEP_HELP: dict[str, Any] = {  # keyword options of an argparse (sub)parser
    "help": "a parameter sweep (grid or Latin hypercube) to CSV/Parquet",
    "description": "Sweep a scene over a grid (or Latin hypercube) of its fields: one row "
    "per point with every input and result, to Parquet or CSV.",
    "epilog": "FIELD: delta, speed, inertia, torque.scale, design.max_outer_diameter "
    "(envelope), design.max_width, design.d_mean, design.hb_ratio, design.hb_min, "
    "design.hb_max, design.geometry, design.objective, material, shaft, "
    "shaft.NAME.speed_ratio, material.NAME.density|max_rim_speed|cost. "
    "VALUES: a,b,c | a:b:n | a:b:logn, a unit after the last value applies to "
    "all (300,600,1200rpm; 0.4:1.2:5 m); 'none' for no limit.",
}


def add_sweep_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt sweep``; the handler is :func:`run_sweep`."""
    parser.add_argument("scene", help="scene file (TOML); a [sweep] table in it is read too")
    parser.add_argument(
        "--vary", action="append", default=[], metavar="FIELD=VALUES", help="a field and its values (repeat for a grid)"
    )
    parser.add_argument("-o", "--output", help="result file, .parquet or .csv (default: CSV on stdout)")
    from flyopt.report import display

    parser.add_argument(
        "--units",
        choices=(*display.SYSTEMS, display.INPUT_UNITS),
        help="the CSV printed on stdout (without -o) in this unit system, each quantity's unit in its column's "
        "name ('speed [rpm]'); 'input': the varied fields in the units they were given in. Default: SI. A file "
        "written with -o is always SI with its units in its metadata (flyopt.read_results gives it back in any "
        "of these)",
    )
    parser.add_argument(
        "--samples", type=_positive_int, metavar="N", help="N Latin hypercube samples instead of the full grid"
    )
    parser.add_argument("--seed", type=int, help="seed of the Latin hypercube")
    parser.add_argument(
        "--workers",
        type=_workers,
        metavar="N|auto",
        help="worker processes on this machine (default auto: one per CPU, serial when the sweep is too small to gain)",
    )
    parser.add_argument(
        "--chunk-size",
        type=_positive_int,
        metavar="N",
        help="points per chunk (default: sized by the estimated cost of the points, 1 s at most each)",
    )
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        type=_scheduler,
        help="run on a Dask cluster, e.g. tcp://host:8786 (one you trust: Dask sends it pickles)",
    )
    parser.add_argument("--resume", action="store_true", help="continue an interrupted sweep from OUTPUT.parts/")
    parser.add_argument(
        "--max-chunks", type=_positive_int, metavar="K", help="stop after K chunks (continue later with --resume)"
    )
    parser.add_argument(
        "--method",
        choices=("auto", "closed_form", "ipopt"),
        help="design method: closed form where exact, else IPOPT (auto)",
    )
    parser.add_argument("--keep-parts", action="store_true", help="keep OUTPUT.parts/ after writing the output")
    parser.add_argument("--no-progress", dest="progress", action="store_false", help="no progress line on stderr")
    add_quiet_argument(parser)
    parser.set_defaults(run=run_sweep)


def run_sweep(args: argparse.Namespace) -> int:
    """``flyopt sweep``: returns the exit status (0 done, or stopped by --max-chunks)."""
    from flyopt.io.sweep_spec import check_options, load_sweep, resolve_field, vary_from_texts
    from flyopt.said import counted
    from flyopt.studies.sweep import check_sweep, sweep

    scene, options = load_sweep(args.scene)
    if options["vary"] or len(options) > 1:  # the file's own [sweep] table: errors name the file
        check_sweep(scene, options, "sweep")
    cli = {
        "samples": args.samples,
        "seed": args.seed,
        "output": args.output,
        "chunk_size": args.chunk_size,
        "method": args.method,
        "workers": args.workers,
        "max_chunks": args.max_chunks,
    }
    cli = {key: value for key, value in cli.items() if value is not None}
    output = cli.get("output", options.get("output"))
    check_options({**cli, "resume": args.resume, "keep_parts": args.keep_parts, "output": output}, "--")
    if args.max_chunks is not None and output is None:  # the chunks run would be printed nowhere, nor continued
        raise SceneError("--max-chunks", "needs an output file (-o): the chunks it leaves are continued with --resume")
    vary = options.pop("vary")
    for path, values in vary_from_texts(scene, args.vary, "--vary").items():
        canonical = resolve_field(scene, path, "--vary")[0]
        for key in list(vary):  # the command line overrides the file
            if resolve_field(scene, key, "sweep.vary")[0] == canonical:
                del vary[key]
        vary[path] = values
    max_chunks = cli.pop("max_chunks", None)
    options.update(cli)
    output = options.pop("output", None)  # [sweep] output came joined to the file's folder (load_sweep)
    frame = sweep(
        scene,
        vary,
        output=output,
        scheduler=args.scheduler,
        resume=args.resume,
        max_chunks=max_chunks,
        progress=args.progress and not args.quiet,
        keep_parts=args.keep_parts,
        **options,
    )
    info = frame.attrs["sweep"]
    counts = frame["status"].value_counts().to_dict()
    summary = ", ".join(
        f"{counts.get(s, 0)} {s.replace('_', ' ')}" for s in ("designed", "infeasible", "not_needed", "failed")
    )
    methods = ", ".join(f"{v} {k}" for k, v in frame["method"].value_counts().items())
    rate = info["designs"] / info["seconds"] if info["seconds"] > 0 else math.inf
    if not info["complete"]:
        left = info["chunks"] - len(info["chunks_run"]) - len(info["chunks_reused"])
        if not args.quiet:
            print(
                f"flyopt sweep: stopped after {counted(len(info['chunks_run']), 'chunk')}, {left} left: "
                f"continue with --resume ({_parts_name(output)})",
                file=sys.stderr,
            )
        return EXIT_OK
    if output is None:  # missing values as empty cells, as in a CSV file
        from flyopt.outputs.results import csv_rows

        if args.units is not None:  # the user's units, named in the header (the files stay SI, with metadata)
            from flyopt.report.notebook import to_units

            csv_rows(to_units(frame, args.units, labels=True), sys.stdout, header=True)
        else:
            csv_rows(frame, sys.stdout, header=True)
    if args.quiet:
        return EXIT_OK
    where = f"wrote {output}" if output is not None else "done"
    print(
        f"flyopt sweep: {where}: {counted(len(frame), 'point')} ({summary}); methods: {methods}; "
        f"{counted(info['designs'], 'design')} in {info['seconds']:.2f} s ({rate:,.0f} designs/s, "
        f"{info['mode']})",
        file=sys.stderr,
    )
    return EXIT_OK


def _parts_name(output: str | None) -> str:
    return f"{output}.parts" if output is not None else "no output file"


# --------------------------------------------------------------------------
# flyopt pareto
# --------------------------------------------------------------------------

PARETO_HELP: dict[str, Any] = {
    "help": "a Pareto front of two objectives",
    "description": "Pareto front of mass against outer diameter, cost or delta, by an "
    "epsilon-constraint swept through the design model.",
}


def add_pareto_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt pareto``; the handler is :func:`run_pareto`."""
    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument(
        "--objectives",
        default="mass,outer_diameter",
        help="mass,outer_diameter | mass,cost | mass,delta | mass,motor_power (a [drive]) "
        "(default mass,outer_diameter)",
    )
    parser.add_argument("--points", type=int, default=25, help="number of epsilon values, 2 to 1000 (default 25)")
    parser.add_argument("--range", dest="span", metavar="LOW:HIGH", help="range of epsilon, e.g. 0.3:1.2 m or 0.01:0.1")
    _method_and_output(parser, "front")
    parser.set_defaults(run=run_pareto)


def _method_and_output(parser: argparse.ArgumentParser, what: str) -> None:
    """The options ``flyopt pareto`` and ``flyopt tradeoff`` share: the design method and the output."""
    parser.add_argument(
        "--method",
        choices=("auto", "closed_form", "ipopt"),
        default="auto",
        help="design method: closed form where exact, else IPOPT (auto); ipopt: every "
        "combination through the CasADi/IPOPT model",
    )
    parser.add_argument(
        "-o",
        "--output",
        help=f"write the {what} to .csv, .parquet or .json "
        f"(with its units and provenance: Parquet metadata, FILE.csv.json beside a "
        f"CSV file, or in the JSON)",
    )
    parser.add_argument(
        "--json", action="store_true", help=f"print the {what} as one JSON document: its units, provenance and rows"
    )
    from flyopt.cli.scene import units_help
    from flyopt.report import display

    parser.add_argument(
        "--units",
        choices=display.SYSTEMS,
        default=display.DEFAULT,
        help=units_help(f"the printed {what} (files and --json stay in SI, with their units)"),
    )
    from flyopt.cli.scene import add_digits_argument

    add_digits_argument(parser, f"the printed {what}")
    add_quiet_argument(parser)


def _span(text: str | None, other: str) -> tuple[float, float] | None:
    """``--range LOW:HIGH [unit]`` in SI, in the dimension of the front's second objective."""
    from flyopt.io.sweep_spec import split_unit
    from flyopt.studies.pareto import PARETO_OBJECTIVES
    from flyopt.units import quantity

    if text is None:
        return None
    dimension = PARETO_OBJECTIVES[other]
    if dimension is None:
        raise SceneError("--range", f"the {other} front has no range: it is the set of material x shaft designs")
    parts = text.split(":")
    if len(parts) != 2:
        raise SceneError("--range", f"{text!r}: expected LOW:HIGH with an optional unit, e.g. 0.3:1.2 m")
    trailing = split_unit(parts[1])[1]
    ends = []
    for part in parts:
        number, unit = split_unit(part)
        if not number.strip():  # pint's own words for "" were "cannot be an empty string"
            raise SceneError("--range", f"{text!r}: each end needs its number, e.g. 0.3:1.2 m")
        raw = f"{number} {unit or trailing}".strip()
        ends.append(quantity(raw, dimension, "--range"))
    low, high = ends  # two parts, checked above; their order is pareto's to check
    return low, high


_SHOW = {
    "outer_diameter": ["mass", "outer_diameter", "best_material", "best_shaft", "b", "h", "binding", "method"],
    "cost": ["mass", "cost", "best_material", "best_shaft", "d_outer", "binding", "method"],
    "delta": ["mass", "delta", "best_material", "best_shaft", "d_outer", "binding", "method"],
    "motor_power": [
        "mass",
        "motor_power",
        "motor",
        "motor_ratio",
        "flywheel_ratio",
        "j_at_reference",
        "j_required",
        "limit",
        "total_mass",
        "best_material",
        "d_outer",
    ],
}


def run_pareto(args: argparse.Namespace) -> int:
    """``flyopt pareto``: returns the exit status (0 a front or none needed, 3 no design)."""
    from flyopt.io.scene import load
    from flyopt.said import counted
    from flyopt.studies.pareto import check_points, objective_pair, pareto

    check_points(args.points, "--points")
    scene = load(args.scene)
    objectives, other = objective_pair(args.objectives)
    _check_output(args.output, scene, "the front")
    front = pareto(scene, objectives, points=args.points, span=_span(args.span, other), method=args.method)
    if front.empty:  # the front's table without rows, and why: on stdout under --json, in the file asked for
        import pandas as pd

        from flyopt.outputs import documents

        message = front.attrs.get("message", "empty front")
        empty = pd.DataFrame({name: pd.Series(dtype=float) for name in ("mass", other)})
        metadata = _metadata(empty, "pareto", scene, objectives=("mass", other), message=message)
        if args.output is not None:  # written as a front with rows is: no earlier file left in its place
            _write(empty, args.output, metadata)
        if args.json and not (args.quiet and args.output is not None):
            print(documents.json_text(documents.table_document(empty, metadata)))
        elif not args.quiet:
            print(f"{args.scene}: {message}")
            if args.output is not None:
                print(f"wrote {args.output} (no rows)")
        return EXIT_OK if message.startswith("no flywheel needed") else EXIT_INFEASIBLE
    # the objectives first, mass then the other, in every format; the file's metadata names
    # them too, which flyopt plot --what pareto reads
    front = front[["mass", other, *(c for c in front.columns if c not in ("mass", other))]]
    _emit(
        front,
        args,
        "pareto",
        scene,
        _SHOW[other],
        f"{args.scene}: Pareto front, {' vs '.join(objectives)} "
        f"({len(front)} non-dominated of {counted(front.attrs['evaluated'], 'design')})",
        objectives=("mass", other),
    )
    return EXIT_OK


# --------------------------------------------------------------------------
# flyopt tradeoff
# --------------------------------------------------------------------------

TRADEOFF_HELP: dict[str, Any] = {
    "help": "the lightest design of each material",
    "description": "For each material the lightest design: size, rim speed, mass, cost and which limit binds.",
}


def add_tradeoff_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt tradeoff``; the handler is :func:`run_tradeoff`."""
    parser.add_argument("scene", help="scene file (TOML)")
    _method_and_output(parser, "table")
    parser.set_defaults(run=run_tradeoff)


def run_tradeoff(args: argparse.Namespace) -> int:
    """``flyopt tradeoff``: returns the exit status (0 a design, 3 none feasible)."""
    from flyopt.io.scene import load
    from flyopt.studies.tradeoff import material_tradeoff

    scene = load(args.scene)
    _check_output(args.output, scene, "the table")
    table = material_tradeoff(scene, method=args.method)
    _emit(
        table,
        args,
        "tradeoff",
        scene,
        ["material", "status", "shaft", "d_outer", "b", "rim_speed", "rim_speed_limit", "mass", "cost", "limit"],
        f"{args.scene}: lightest design per material",
    )
    if (table["status"] == "infeasible").all():
        if not (args.quiet or args.json):  # --json: one document, whose rows carry each reason
            from flyopt.report import display

            for reason in table["reason"]:  # in the units and figures of the table above, as solve says it
                print(f"  {display.said_text(reason, args.units, args.digits)}")
        return EXIT_INFEASIBLE
    return EXIT_OK


# --------------------------------------------------------------------------
# Output of the tables
# --------------------------------------------------------------------------

_SUFFIXES = (".csv", ".parquet", ".pq", ".json")


def _check_output(output: str | None, scene: Scene, what: str) -> None:
    """The output file of a front or table (``what``: "the front"), checked before anything is computed: its
    suffix, its folder, and that it is none of the files the scene read (the scene file, a ``points_file``)."""
    from flyopt.outputs.files import check_folder
    from flyopt.outputs.results import check_table_output

    if output is None:
        return
    if Path(output).suffix.lower() not in _SUFFIXES:
        raise SceneError("-o/--output", f"{output!r} must end in .csv, .parquet or .json (the suffix picks the format)")
    check_folder(output, "-o/--output")
    check_table_output(output, scene, what)


def _metadata(
    frame: pd.DataFrame,
    kind: str,
    scene: Scene,
    objectives: Sequence[str] | None = None,
    message: str | None = None,
) -> dict[str, Any]:
    """A study's table's metadata (:func:`flyopt.outputs.documents.table_metadata`): its columns' units, the
    scene's provenance, a front's objectives, and why it has no rows (``message``)."""
    from flyopt.outputs import documents
    from flyopt.studies.payload import digest

    return documents.table_metadata(
        kind,
        list(frame.columns),
        scene=documents.scene_record(scene, digest(scene)),
        objectives=objectives,
        objective=documents.objective_of(frame),
        message=message,
    )


def _write(frame: pd.DataFrame, output: str, metadata: dict[str, Any]) -> None:
    """A study's table and its metadata written to ``output`` (atomically): a JSON document, else Parquet or
    CSV by the suffix (:func:`flyopt.outputs.results.write_results`)."""
    from flyopt.outputs import documents, files, results

    if Path(output).suffix.lower() == ".json":
        files.write_text(output, documents.json_text(documents.table_document(frame, metadata)))
    else:
        results.write_results(frame, output, metadata=metadata)


def _emit(
    frame: pd.DataFrame,
    args: argparse.Namespace,
    kind: str,
    scene: Scene,
    columns: Sequence[str],
    title: str,
    objectives: Sequence[str] | None = None,
) -> None:
    """Write a study's table to ``args.output`` (by its suffix) and print it, or its JSON.

    The table goes out with its metadata (units, provenance, a front's
    objectives) and nulls for missing values, whatever the format; a JSON
    file is written atomically like the others. With ``--quiet`` and a file,
    nothing is printed.
    """
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    from flyopt.outputs import documents, quantities, results
    from flyopt.report import display

    frame = results.normalize(frame.copy())
    output = args.output
    metadata = _metadata(frame, kind, scene, objectives)
    if output is not None:
        _write(frame, output, metadata)
    if args.quiet and output is not None:
        return
    if args.json:
        print(documents.json_text(documents.table_document(frame, metadata)))
        return
    front = objectives[1] if objectives else None
    shown = _for_people(frame[[c for c in columns if c in frame]].copy(), scene)
    labels = []
    for c in shown.columns:
        dimension = quantities.dimension_of(c)
        if is_numeric_dtype(shown[c]) and not is_bool_dtype(shown[c]):  # written as solve writes its tables
            values = [None if v != v else float(v) for v in shown[c]]  # NaN: missing, "-"
            unit: str | None
            if dimension is not None:  # in the user's units, one per column, chosen from its values
                unit, texts = display.column(values, c, args.units, args.digits)
            else:
                unit = quantities.unit_of(c, documents.objective_of(frame), front)
                scale = display.largest(values)
                texts = [display.number(v, args.digits, scale) for v in values]
            shown[c] = texts
            labels.append(_label(c, unit))
        else:
            labels.append(_label(c, quantities.unit_of(c, documents.objective_of(frame), front)))
    shown.columns = labels
    print(title)
    print(shown.to_string(index=False, na_rep="-"))
    if output is not None:
        print(f"wrote {output}")


def _for_people(shown: pd.DataFrame, scene: Scene) -> pd.DataFrame:
    """The printed table's materials by their names for people and its binding limits in words
    (:func:`flyopt.report.display.for_people`, the app's too); the files and the JSON keep the keys."""
    from flyopt.report import display

    names = {key: material.display_name for key, material in scene.material_library().items()}
    return cast("pd.DataFrame", display.for_people(shown, names))


def _label(column: str, unit: str | None) -> str:
    """A printed column's heading: its name and unit, ``[-]`` for a plain number."""
    if unit is None:
        return column
    return f"{column} [{'-' if unit == '1' else unit}]"


# --------------------------------------------------------------------------
# Entry points of one command each (the same as ``flyopt COMMAND ...``)
# --------------------------------------------------------------------------


def _one_command(
    name: str, add: Callable[[argparse.ArgumentParser], None], texts: dict[str, Any]
) -> argparse.ArgumentParser:
    """The parser of one study command alone, as ``flyopt NAME`` has it."""
    texts = {k: v for k, v in texts.items() if k != "help"}
    parser = argparse.ArgumentParser(prog=f"flyopt {name}", **texts)
    add(parser)
    return parser


def sweep_main(argv: Sequence[str] | None = None) -> int:
    """``flyopt sweep ARGV``; returns the exit status."""
    return run(_one_command("sweep", add_sweep_arguments, SWEEP_HELP), argv)


def pareto_main(argv: Sequence[str] | None = None) -> int:
    """``flyopt pareto ARGV``; returns the exit status."""
    return run(_one_command("pareto", add_pareto_arguments, PARETO_HELP), argv)


def tradeoff_main(argv: Sequence[str] | None = None) -> int:
    """``flyopt tradeoff ARGV``; returns the exit status."""
    return run(_one_command("tradeoff", add_tradeoff_arguments, TRADEOFF_HELP), argv)


def _scheduler(text: str) -> str:
    """``--scheduler``: the address checked as the option is read (:func:`flyopt.studies.cluster.scheduler_address`)."""
    from flyopt.errors import SceneError
    from flyopt.studies.cluster import scheduler_address

    try:
        return scheduler_address(text)
    except SceneError as err:
        raise argparse.ArgumentTypeError(err.message) from None
