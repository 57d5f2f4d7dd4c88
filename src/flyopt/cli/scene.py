"""``flyopt solve`` and ``flyopt check``: one scene, analysed and designed or checked."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from flyopt.cli.exits import EXIT_FLAGGED, EXIT_OK, solution_exit
from flyopt.names import Model
from flyopt.report import display

if TYPE_CHECKING:
    from flyopt.io.scene import Scene


def units_help(what: str = "the text report") -> str:
    """The help of ``--units``, its units read from the display table (``flyopt plot`` takes the same choices)."""
    shown = ("length", "angular_speed", "torque", "energy", "stress", "power", "mass")
    systems = "; ".join(
        f"{system}: {', '.join(dict.fromkeys(display.label(d, system) for d in shown))}" for system in display.SYSTEMS
    )
    return f"unit system of {what} (default {display.DEFAULT}; {systems})"


def add_solve_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt solve``; the handler is :func:`run_solve`."""
    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument(
        "--json", action="store_true", help="print one JSON object, all numbers in SI whatever --units says"
    )
    parser.add_argument(
        "--units",
        choices=display.SYSTEMS,
        default=display.DEFAULT,
        help=units_help() + "; --json ignores it: the JSON is always SI",
    )
    parser.add_argument(
        "--no-design", dest="design", action="store_false", help="stop after the cycle analysis (no optimization)"
    )
    parser.add_argument(
        "--model",
        choices=Model.values(),
        help="force the model that sizes the flywheel (default: the cheapest exact one)",
    )
    parser.add_argument(
        "--design-method",
        choices=("auto", "ipopt", "closed_form"),
        default="auto",
        help="auto (default): the exact closed form where it covers the structure, IPOPT "
        "elsewhere; ipopt: IPOPT on every combination; closed_form: refuse what the "
        "closed form does not cover",
    )
    parser.add_argument(
        "--verify",
        action="store_true",
        help="simulate the machine with the chosen flywheel and report the δ it achieves",
    )
    parser.add_argument(
        "--timings",
        action="store_true",
        help="--json: also the wall-clock time of each design solve (solve_time [s]); left out "
        "by default, so that the same scene gives the same JSON",
    )
    parser.set_defaults(run=run_solve)


def run_solve(args: argparse.Namespace) -> int:
    """``flyopt solve``: 0 a design or none needed, 3 infeasible, 4 verification flagged."""
    from flyopt.io.scene import load
    from flyopt.pipeline import solve

    scene = load(args.scene)
    if scene.operation is not None:
        return _run_operation(scene, args)
    if scene.position is not None:
        return _run_position(scene, args)
    solution = solve(
        scene,
        design_flywheel=args.design,
        model=args.model,
        verify_design=args.verify,
        design_method=args.design_method,
    )
    if args.json:
        from flyopt.outputs.documents import solution_json

        text = solution_json(solution, args.scene, timings=args.timings)
    else:
        from flyopt.report.text import analysis_report, design_report, flywheel_report, verification_report

        reached = solution.flywheel is not None and solution.flywheel.delta_allowed is None
        label = "δ reached by the flywheel" if reached else "allowed δ"
        lines = [analysis_report(solution.analysis, args.scene, units=args.units, delta_label=label)]
        if solution.flywheel is not None:
            lines += flywheel_report(solution.flywheel, units=args.units)
        if solution.design is not None:
            lines += design_report(solution.design, units=args.units)
        if solution.drive is not None:
            from flyopt.report.drive import drive_report

            lines += drive_report(solution.drive, solution.drive_check, units=args.units)
        if solution.verification is not None:
            lines += verification_report(solution.verification, units=args.units)
        text = "\n".join(lines)
    print(text)
    return solution_exit(solution)


def _run_operation(scene: Scene, args: argparse.Namespace) -> int:
    """``flyopt solve`` of an [operation]: 0, or 4 when the speed falls beyond machine.delta."""
    from flyopt.pipeline import solve_operation

    result = solve_operation(scene)
    if args.json:
        from flyopt.outputs.documents import json_text, operation_document

        print(json_text(operation_document(result, scene.title, args.scene)))
    else:
        from flyopt.report.text import operation_report

        print(operation_report(result, scene.title, args.scene, units=args.units))
    return EXIT_FLAGGED if result.holds is False else EXIT_OK


def _run_position(scene: Scene, args: argparse.Namespace) -> int:
    """``flyopt solve`` of a [position]: the slider-crank's forces at that crank angle; 0."""
    from flyopt.pipeline import solve_position

    forces = solve_position(scene)
    if args.json:
        from flyopt.outputs.documents import json_text, position_document

        print(json_text(position_document(forces, scene.title, args.scene)))
    else:
        from flyopt.report.text import position_report

        print(position_report(forces, scene.title, args.scene, units=args.units))
    return EXIT_OK


def add_check_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt check``; the handler is :func:`run_check`."""
    parser.add_argument("scene", help="scene file (TOML)")
    parser.set_defaults(run=run_check)


def run_check(args: argparse.Namespace) -> int:
    """``flyopt check``: 0 when the scene reads, its cycle closes and its ``[sweep]`` table would run."""
    from flyopt.analysis import analyse
    from flyopt.io.scene import load
    from flyopt.io.toml_file import read_toml

    data = read_toml(args.scene)
    scene = load(args.scene, data)
    if scene.operation is not None or scene.position is not None or scene.flywheel is not None:
        from flyopt.pipeline import check_flywheel, solve_operation, solve_position  # no cycle, or no design

        if scene.operation is not None:
            solve_operation(scene)
        elif scene.position is not None:
            solve_position(scene)
        else:
            check_flywheel(scene)
        print(f"{args.scene}: ok ({scene.title})")
        return EXIT_OK
    analyse(scene)  # a cycle that does not close is an input error too
    from flyopt.design import design_inputs

    design_inputs(scene)  # the design's own refusals of its inputs, as flyopt solve makes them
    if "sweep" in data:  # the sweep's modules (pandas, pyarrow) only for a [sweep] table
        from flyopt.io.sweep_spec import load_sweep
        from flyopt.studies.sweep import check_sweep

        _, options = load_sweep(args.scene)
        if options["vary"] or len(options) > 1:  # the same checks flyopt sweep makes before it runs
            check_sweep(scene, options, "sweep")
    print(f"{args.scene}: ok ({scene.title})")
    return EXIT_OK
