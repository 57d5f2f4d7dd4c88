"""``flyopt solve`` and ``flyopt check``: one scene, analysed and designed or checked."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from flyopt.cli.exits import EXIT_OK, calculation_exit, one_line, solution_exit
from flyopt.names import Model
from flyopt.report import display

if TYPE_CHECKING:
    from flyopt.errors import SceneError
    from flyopt.io.scene import Scene


def units_help(what: str = "the text report") -> str:
    """The help of ``--units``, its units read from the display table (``flyopt plot`` takes the same choices)."""
    shown = ("length", "angular_speed", "torque", "energy", "stress", "power", "mass")

    def name(dimension: str, system: str) -> str:  # a prefixed one by its SI unit: "(k)J"
        base = display.PREFIXED.get(system, {}).get(dimension)
        return display.label(dimension, system) if base is None else f"(k){base}"

    systems = "; ".join(
        f"{system}: {', '.join(dict.fromkeys(name(d, system) for d in shown))}" for system in display.SYSTEMS
    )
    return f"unit system of {what} (default {display.DEFAULT}; {systems}; (k): the prefix each value needs)"


def digits_count(text: str) -> int:
    """``--digits N``: the significant figures of the printed numbers, checked by
    :func:`flyopt.report.display.check_digits` (the one rule); a bad one is argparse's one-line error, exit 2."""
    try:
        return display.check_digits(int(text))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a count of significant figures (a whole number from 1 to {display.MAX_DIGITS})"
        ) from None


def add_digits_argument(parser: argparse.ArgumentParser, what: str = "the text report") -> None:
    """``--digits N``, in the words of every command that prints numbers for people (never the JSON's)."""
    parser.add_argument(
        "--digits",
        type=digits_count,
        default=display.DEFAULT_DIGITS,
        metavar="N",
        help=f"significant figures of the numbers in {what} (default {display.DEFAULT_DIGITS}, "
        f"1 to {display.MAX_DIGITS}); files and --json keep full precision",
    )


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
    add_digits_argument(parser)
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
    from flyopt.cli.exits import EXIT_INPUT, fail
    from flyopt.io.scene import load
    from flyopt.pipeline import solve

    if args.timings and not args.json:  # each would be dropped without a word
        return fail("--timings: adds each design solve's time to the JSON, which --json prints", EXIT_INPUT)
    if not args.design and args.design_method != "auto":
        return fail("--design-method: chooses how the wheel is designed, which --no-design leaves out", EXIT_INPUT)
    scene = load(args.scene)
    if getattr(args, "output", None) is not None:  # -o (flyopt.cli.main._printed_to_file): no file the scene reads
        from flyopt.outputs.files import check_not_scene

        check_not_scene(args.output, scene, "the result")
    what = scene.calculation
    if what is not None:
        dropped = [
            option
            for option, given in (
                ("--no-design", not args.design),
                ("--model", args.model is not None),
                ("--design-method", args.design_method != "auto"),
                ("--verify", args.verify),
            )
            if given
        ]
        if dropped:  # a calculation has no cycle to model, no wheel to design, nothing to simulate
            return fail(
                f"{dropped[0]}: {args.scene} is one calculation ({what}), with no cycle to model or simulate "
                "and no wheel to design",
                EXIT_INPUT,
            )
        return _run_calculation(what, scene, args)
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
        from flyopt.report.text import (
            analysis_report,
            answer_report,
            design_report,
            flywheel_report,
            verification_report,
        )

        label = "δ reached by the flywheel" if solution.flywheel is not None else "allowed δ"
        shown = {"units": args.units, "digits": args.digits}
        answer = answer_report(solution, **shown)
        lines = [analysis_report(solution.analysis, args.scene, delta_label=label, answer=answer, **shown)]
        if solution.flywheel is not None:
            lines += flywheel_report(solution.flywheel, **shown)
        if solution.design is not None:
            lines += design_report(solution.design, **shown)
        if solution.shaft_checks:
            from flyopt.report.shaft import shaft_report

            lines += shaft_report(solution.shaft_checks, **shown)
        if solution.drive is not None:
            from flyopt.report.drive import drive_report

            lines += drive_report(solution.drive, solution.drive_check, **shown)
        if solution.verification is not None:
            lines += verification_report(solution.verification, **shown)
        text = "\n".join(lines)
    print(text)
    return solution_exit(solution)


def _run_calculation(what: str, scene: Scene, args: argparse.Namespace) -> int:
    """``flyopt solve`` of a scene that is one calculation (:data:`flyopt.names.CALCULATIONS`):
    0, or 4 when an operation's speed falls beyond machine.delta."""
    from flyopt.pipeline import solve_calculation

    result = solve_calculation(scene)
    if args.json:
        from flyopt.outputs.documents import calculation_document, json_text

        print(json_text(calculation_document(what, scene.title, args.scene, result.to_dict())))
    else:
        from flyopt.report.text import CALCULATION_REPORTS

        print(CALCULATION_REPORTS[what](result, scene.title, args.scene, units=args.units, digits=args.digits))
    return calculation_exit(result)


def add_check_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt check``; the handler is :func:`run_check`."""
    parser.add_argument("scene", help="scene file (TOML)")
    parser.set_defaults(run=run_check)


def run_check(args: argparse.Namespace) -> int:
    """``flyopt check``: 0 when the scene reads, its cycle closes and its ``[sweep]`` table would run.

    A scene the loader refuses is said as every structural error of the file
    at once (:func:`flyopt.cli.scene_schema.structural_errors`: unknown keys,
    wrong types, missing keys; the loader's words for the one it met first),
    or, when the structure is sound, the loader's error and the first value
    error of each other part read on its own (:func:`flyopt.io.scene.section_errors`:
    each of the machine's scalars, each material and shaft table, the title, the design); each on its own
    line ``FILE:LINE: field: message`` on stderr, in the order of the file
    (a field the file does not write, derived from another section, as
    ``flyopt: error: FILE: field: message``); exit status 2. A file that is not TOML, and the other commands,
    keep the one-line refusal.
    """
    from flyopt.errors import SceneError
    from flyopt.io.toml_file import read_toml

    data = read_toml(args.scene)
    try:
        return _check(args, data)
    except SceneError as err:
        return _say_errors(args.scene, data, err)


MAX_LISTED = 100
"""The most errors ``flyopt check`` lists; the rest are counted."""


def _say_errors(path: str, data: dict[str, Any], err: SceneError) -> int:
    """Print :func:`every_error` of ``data`` as ``FILE:LINE: field: message``, in the order of the file; return 2."""
    import sys
    from pathlib import Path

    from flyopt.cli.exits import EXIT_INPUT, one_line
    from flyopt.cli.toml_lines import key_lines, line_of
    from flyopt.errors import SceneError

    errors = every_error(data, err)
    lines = key_lines(Path(path).read_text(encoding="utf-8", errors="replace"))
    placed = [(line_of(lines, field), field, message) for field, message in errors]
    placed.sort(key=lambda item: item[0] or 0)  # in the order of the file (stable: the schema's order within a line)
    for line, field, message in placed[:MAX_LISTED]:
        # a field the file does not write (machine.delta that a [press] derives) is said as every command says it
        where = f"{path}:{line}" if line is not None else f"flyopt: error: {path}"
        print(one_line(SceneError(field, message, where)), file=sys.stderr)  # the field clipped as every refusal
    if len(placed) > MAX_LISTED:  # a hostile file of a million bad keys is not a million lines
        line = placed[MAX_LISTED][0]
        print(f"{path}:{line or 1}: {len(placed) - MAX_LISTED} more errors after these", file=sys.stderr)
    return EXIT_INPUT


def every_error(data: dict[str, Any], err: SceneError) -> list[tuple[str, str]]:
    """Every error ``flyopt check`` says of a scene the loader refused with ``err``, as (field, message), in no
    particular order: every structural error of ``data`` (the loader's words for the one it met first), or, the
    structure sound, the loader's error and the first value error of each other part read on its own (each of
    [machine]'s scalars, each [[material]] and [[shaft]] table, the title, [design]:
    :func:`flyopt.io.scene.section_errors`). The app's card says the same."""
    from flyopt.cli.scene_schema import structural_errors

    errors = structural_errors(data)
    fields = [field for field, _ in errors]
    if err.field in fields:  # the loader's own words for the error it met first: they say what is allowed
        errors[fields.index(err.field)] = (err.field, err.message)
    if errors:
        return errors
    from flyopt.io.scene import section_errors

    errors, said = [(err.field, err.message)], {err.field}
    for other in section_errors(data):
        if other.field not in said:  # the loader's first error, met again alone
            said.add(other.field)
            errors.append((other.field, other.message))
    return errors


def _check(args: argparse.Namespace, data: dict[str, Any]) -> int:
    from flyopt.analysis import analyse
    from flyopt.io.scene import load

    scene = load(args.scene, data)
    if scene.calculation is not None or scene.flywheel is not None:
        from flyopt.pipeline import check_flywheel, solve_calculation  # no cycle, or no design

        if scene.calculation is not None:
            solve_calculation(scene)
        else:
            check_flywheel(scene)
        print(one_line(f"{args.scene}: ok ({scene.title})"))  # a title's control and bidi characters escaped
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
    print(one_line(f"{args.scene}: ok ({scene.title})"))  # a title's control and bidi characters escaped
    return EXIT_OK
