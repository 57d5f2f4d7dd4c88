"""``flyopt plot``: a diagram of a scene, or of the results of a sweep or a Pareto front.

The handler solves the scene once (:func:`flyopt.pipeline.solve`, asked for
what the diagrams draw: the design, the speed over the cycle, the simulation,
J_F at other δ, the stresses) and hands the solution to
:mod:`flyopt.report.plots`, which only draws; nothing is computed after the
solve. ``--what all -o DIR/`` draws every diagram of the scene from that one
solve. The output file is checked before anything is computed.
A diagram that would be empty because no flywheel is needed is said in one
line on stdout with exit status 0 and no file: the scene is valid and the
answer (no flywheel) is the one ``flyopt solve`` gives with status 0. A
diagram that does not apply to the scene (the energy–mass diagram of a
constant inertia, ω(φ) of net areas) is refused in one line, exit status 2,
nothing written. ``--units`` picks the unit system every axis and label is
drawn in (flyopt.report.display), each axis of a torque, an energy, a power
or a force with the prefix its largest value needs (as ``solve`` writes it);
``--digits`` the significant figures of the numbers written on the diagram
(its labels, legend and title), as ``solve``'s. Files of results stay SI.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterable

from flyopt.cli.exits import EXIT_INFEASIBLE, EXIT_INPUT, EXIT_OK, fail
from flyopt.errors import FlyoptError
from flyopt.names import Model, hint


def add_plot_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt plot``; the handler is :func:`run_plot`."""
    parser.add_argument("scene", help="scene file (TOML), or results (.csv/.parquet) of flyopt sweep or pareto")
    parser.add_argument(
        "--what",
        required=True,
        metavar="DIAGRAM",
        help="turning_moment | energy | inertia_delta | cross_section | stress | speed | "
        "energy_mass, or all (every diagram of the scene, from one solve, as DIR/<diagram>.png); "
        "for results: sweep | pareto",
    )
    parser.add_argument(
        "--x",
        help="results: the column on the x axis (sweep: a varied field; pareto: default the front's second objective)",
    )
    parser.add_argument("--y", help="results: the column on the y axis (default mass)")
    parser.add_argument("--by", help="sweep results: one line per value of this column (e.g. material)")
    parser.add_argument("--verify", action="store_true", help="speed: draw the periodic simulation over the model")
    parser.add_argument(
        "--units",
        default="engineering",
        metavar="SYSTEM",
        help="units of the axes and labels: engineering (mm, rpm, MPa; N·m, J, W, N with the prefix each "
        "axis needs; the default), "
        "si (m, rad/s, N·m, J, Pa) or imperial (in, rpm, lbf·ft, ft·lbf, psi)",
    )
    from flyopt.cli.scene import add_digits_argument

    add_digits_argument(parser, "the diagram's labels, legend and title")
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        help="file to write (its folder must exist); the suffix picks the format: png, svg, pdf; "
        "with --what all, the existing folder to write every diagram into",
    )
    parser.set_defaults(run=run_plot)


#: ``--what all``: every diagram of the scene, each written as DIR/<diagram>.png.
ALL = "all"


def needs(whats: Iterable[str], verify: bool = False) -> tuple[bool, tuple[str, ...]]:
    """(whether to design, the extras of :func:`flyopt.pipeline.solve`) the diagrams ``whats`` draw."""
    extras = set()
    for what in whats:
        extras |= {
            "inertia_delta": {"inertia_curve"},
            "stress": {"stress"},
            "speed": {"speed", "speed_simulation"} if verify else {"speed"},
            "energy_mass": {"energy_mass"},
        }.get(what, set())
    return any(what in ("cross_section", "stress") for what in whats), tuple(sorted(extras))


def run_plot(args: argparse.Namespace) -> int:
    """``flyopt plot``: 0 written (or nothing to draw), 2 a bad request, 3 no feasible flywheel to draw."""
    from flyopt.report import display, plots

    if args.units not in display.SYSTEMS:
        return fail(f"--units: unknown unit system {args.units!r} (allowed: {', '.join(display.SYSTEMS)})", EXIT_INPUT)
    if args.scene.lower().endswith((".csv", ".parquet")):
        return _plot_results(args)
    if args.verify and args.what not in ("speed", ALL):  # it would be ignored: only ω(φ) draws the simulation
        return fail(
            f"--verify: draws the periodic simulation on the speed diagram (--what speed or all), not on {args.what}",
            EXIT_INPUT,
        )
    given = [f"--{name}" for name in ("x", "y", "by") if getattr(args, name) is not None]
    if given:  # a scene's diagram has its own axes: the options were ignored
        return fail(
            f"{' and '.join(given)}: choose the columns of a results table (flyopt sweep or pareto -o FILE.csv or "
            f".parquet); a scene's diagram ({args.what}) has its own axes",
            EXIT_INPUT,
        )
    if args.what == ALL:
        return _plot_all(args, plots)
    if args.what in plots.RESULT_PLOTS:  # a scene given where results are read
        json_table = " (a JSON table is not read: write them with -o FILE.csv or FILE.parquet)"
        return fail(
            f"{args.scene}: --what {args.what} draws the results of flyopt sweep or pareto, a .csv or .parquet "
            f"file{json_table if args.scene.lower().endswith('.json') else ''}",
            EXIT_INPUT,
        )
    if args.what not in plots.PLOTS:
        return fail(
            f"--what: unknown diagram {args.what!r}{hint(args.what, [*plots.PLOTS, ALL])} (known: {', '.join(plots.PLOTS)}, {ALL})",
            EXIT_INPUT,
        )
    plots.check_output(args.output)
    solution = _solve(args, [args.what], [args.output])
    return _plot_one(args, plots, solution, args.what, args.output)


def _solve(args, whats, outputs):
    """The scene solved once, with what the diagrams ``whats`` draw (:func:`flyopt.pipeline.solve`), once no
    file of ``outputs`` is found to be one the scene read (before the solve)."""
    from flyopt.io.scene import load
    from flyopt.outputs.files import check_not_scene
    from flyopt.pipeline import solve

    design, extras = needs(whats, args.verify)
    scene = load(args.scene)
    for output in outputs:
        check_not_scene(output, scene, "the diagram")
    # a [drive] chooses the machine (its motor and ratio) that every diagram draws: without the drive's
    # design the diagrams would draw the scene's energy model, a machine the answer does not have
    return solve(scene, design_flywheel=design or scene.drive is not None, extras=extras)


def _plot_one(args, plots, solution, what, output, every=False):
    """Draw ``what`` from ``solution`` into ``output``; the exit status.

    ``every`` (``--what all``): a diagram that does not apply to the scene is
    said on stdout and left out (status 0) instead of refused (status 2).
    """
    try:
        ax = _draw(solution, what, plots, args.units, args.verify, args.digits)
    except plots.NothingToDraw as said:
        print(f"{args.scene}: {what}: {said} (no file written)")
        return EXIT_OK
    except _NoDrive as said:
        from flyopt.report.text import NO_MACHINE

        return fail(f"{args.scene}: {what}: {NO_MACHINE} ({said})", EXIT_INFEASIBLE)
    except _Infeasible as said:
        return fail(f"{args.scene}: {what}: no flywheel to draw ({said})", EXIT_INFEASIBLE)
    except ValueError as err:
        if isinstance(err, FlyoptError):  # an input error names its file and field itself
            raise
        if every:
            print(f"{args.scene}: {what}: does not apply: {err} (no file written)")
            return EXIT_OK
        return fail(f"{args.scene}: {what}: {err}", EXIT_INPUT)
    plots.save(ax, output, own_name=every)  # --what all names its files in the folder: never through a link
    print(f"wrote {output}")
    return EXIT_OK


def _plot_all(args, plots):
    """``--what all -o DIR/``: every diagram of the scene from one solve, each as DIR/<diagram>.png.

    A diagram that does not apply to the scene is said in one line and left
    out; the exit status is 3 when a flywheel is needed and none is feasible
    (its diagrams are left out, the others written), else 0.
    """
    from pathlib import Path

    from flyopt.errors import SceneError
    from flyopt.outputs.files import check_not_a_link

    folder = Path(args.output)
    if not folder.is_dir():
        raise SceneError("-o/--output", f"{args.output!r}: with --what all, -o names an existing folder")
    whats = list(plots.PLOTS)
    files = [folder / f"{what}.png" for what in whats]
    for file in files:  # before the solve (and, once the scene is read, none may be a file it reads)
        check_not_a_link(file)  # names flyopt makes in the folder given: a link there leads elsewhere
        plots.check_output(file)
    solution = _solve(args, whats, files)
    statuses = [_plot_one(args, plots, solution, what, file, every=True) for what, file in zip(whats, files)]
    return EXIT_INFEASIBLE if EXIT_INFEASIBLE in statuses else EXIT_OK


class _Infeasible(Exception):
    """A flywheel is needed and no material and shaft can give it (exit 3)."""


class _NoDrive(Exception):
    """A [drive] found no motor size that drives the machine within its limits (exit 3): every diagram would draw
    a machine without the motor the scene asks for."""


def _draw(solution, what, plots, units, verify=False, digits=None):
    """Draw ``what`` from the solved scene (read only: every model ran in the solve); returns the Axes."""
    from flyopt.report import display

    digits = display.DEFAULT_DIGITS if digits is None else digits
    scene, analysis = solution.scene, solution.analysis
    if solution.drive_failed:
        from flyopt.drive.codesign import refused_in_short

        raise _NoDrive(display.said_text(refused_in_short(solution.drive), units, digits))
    if what in ("cross_section", "stress"):
        design = solution.design
        if solution.status == "not_needed":
            raise plots.NothingToDraw("no flywheel is needed: nothing to draw")
        if solution.flywheel is not None:
            from flyopt.report.drawing import GIVEN_WHEEL

            raise plots.NothingToDraw(GIVEN_WHEEL)
        if design is None or design.best is None:
            raise _Infeasible(
                display.said_text(design.message, units, digits)
                if design is not None
                else "no drive and wheel meet the limits"
            )
        if what == "cross_section":
            return plots.plot_cross_section(
                design.best, units=units, material=design.material_name(design.best.material), digits=digits
            )
        if solution.stress is None:
            raise ValueError(solution.stress_note)
        profile, beams, omega, material = solution.stress
        return plots.plot_stress(
            design.best,
            profile,
            beams,
            omega,
            ductile=bool(getattr(material, "ductile", False)),
            units=units,
            material=design.material_name(design.best.material),
            digits=digits,
        )
    if what == "speed":
        if scene.net is not None:  # said by the plot
            return plots.plot_speed(scene, analysis, units=units, digits=digits)
        speed = analysis.speed_curve()
        if speed is None:
            raise plots.NothingToDraw(
                "no flywheel is needed and the speed does not fluctuate (A_max = 0 J, "
                "no inertia at all): nothing to draw"
            )
        simulation = solution.speed_simulation if verify else None
        return plots.plot_speed(scene, analysis, speed, simulation, units=units, digits=digits)
    if what == "energy_mass":
        plots.check_energy_mass(analysis)
        analysis = solution.energy_mass  # the diagram draws that model's tangents
    if what == "inertia_delta":
        plots.check_inertia_delta(analysis)
        curve = None
        if analysis.model != Model.ENERGY:
            if solution.inertia_error is not None:
                raise solution.inertia_error
            curve = solution.inertia_curve
        return plots.plot_inertia_delta(scene, analysis, units=units, curve=curve, digits=digits)
    return getattr(plots, f"plot_{what}")(scene, analysis, units=units, digits=digits)


def _plot_results(args):
    from flyopt.outputs.results import read_results, results_columns
    from flyopt.report import plots
    from flyopt.report.plots.results import plotted_columns

    if args.what not in plots.RESULT_PLOTS:
        return fail(
            f"--what: {args.what!r} is not a diagram of results (known: {', '.join(plots.RESULT_PLOTS)})", EXIT_INPUT
        )
    if args.verify:  # it would be ignored: a table of results has no simulation
        return fail(
            "--verify: draws the periodic simulation on a scene's speed diagram; a table of results has none",
            EXIT_INPUT,
        )
    plots.check_output(args.output)  # drawn from a table of results, whose suffix no diagram has
    try:
        columns, metadata = results_columns(args.scene)
    except (OSError, ValueError) as err:
        return fail(f"{args.scene}: cannot read the results: {err}", EXIT_INPUT)
    x, y = args.x, args.y or "mass"
    if x is None and args.what == "pareto":
        # the objectives the front's file records (flyopt pareto writes them in its metadata);
        # a file written before they were recorded: its first two columns
        objectives = (metadata or {}).get("objectives") or plots.pareto_objectives(columns)
        x = objectives[1] if objectives else None
    try:  # only the columns the diagram reads: a large table's others are not read
        wanted = plotted_columns(columns, metadata, args.what, x, y, args.by) if x is not None else None
    except ValueError:  # a column it does not have: read whole, the diagram names it (after an empty table's why)
        wanted = None
    try:
        frame = read_results(args.scene, columns=wanted)
    except (OSError, ValueError) as err:
        return fail(f"{args.scene}: cannot read the results: {err}", EXIT_INPUT)
    if frame.empty:  # an empty Pareto front's file says why it has no rows
        why = frame.attrs.get("flyopt", {}).get("message")
        return fail(f"{args.scene}: no rows to plot{f': {why}' if why else ''}", EXIT_INPUT)
    if x is None:
        return fail(f"--x: the results diagram {args.what!r} needs the column for the x axis", EXIT_INPUT)
    units = args.units
    try:
        ax = (
            plots.plot_sweep(frame, x, y, args.by, units=units, digits=args.digits)
            if args.what == "sweep"
            else plots.plot_pareto(frame, x, y, units=units, digits=args.digits)
        )
    except ValueError as err:
        return fail(f"{args.scene}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK
