"""Command line: ``flyopt solve SCENE.toml [--json]`` and ``flyopt check SCENE.toml``.

Exit status: 0 a design (or none needed), 1 a solver did not converge or a
design failed its verification against the constraints (no design is
reported), 2 bad input (one line on stderr naming the file, the
field and what is allowed), 3 no material and shaft can give the inertia,
4 the verification simulation finds the design misses the allowed δ.
Nothing is printed on stdout before the whole result is ready.
"""

import argparse
import json
import sys

from flyopt import __version__
from flyopt.analysis import analyse
from flyopt.errors import NonPeriodicCycle, SceneError, SolverFailed
from flyopt.pipeline import solve
from flyopt.io.scene import load

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_INFEASIBLE, EXIT_FLAGGED = 0, 1, 2, 3, 4


def main(argv=None):
    """Entry point of the ``flyopt`` command; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["bench"]:  # its own option parser (flyopt.bench)
        from flyopt.bench import main as bench_main

        return bench_main(argv[1:])
    if argv[:1] and argv[0] in ("sweep", "pareto", "tradeoff"):  # their own parsers (flyopt.studies.fronts)
        from flyopt.studies import fronts as studies

        return getattr(studies, f"{argv[0]}_main")(argv[1:])
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except SceneError as err:
        return _fail(str(err), EXIT_INPUT)
    except NonPeriodicCycle as err:
        return _fail(str(err), EXIT_INPUT)
    except SolverFailed as err:
        return _fail(f"{args.scene}: {err}", EXIT_FAILED)
    except ArithmeticError as err:
        return _fail(f"{args.scene}: {err}", EXIT_FAILED)


def _parser():
    parser = argparse.ArgumentParser(prog="flyopt", description="Flywheel design for speed regulation.")
    parser.add_argument("--version", action="version", version=f"flyopt {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    solve = commands.add_parser("solve", help="analyse a scene's cycle and size its flywheel")
    solve.add_argument("scene", help="scene file (TOML)")
    solve.add_argument("--json", action="store_true", help="print one JSON object, all numbers in SI")
    solve.add_argument("--no-design", dest="design", action="store_false",
                       help="stop after the cycle analysis (no optimization)")
    solve.add_argument("--model", choices=("energy", "energy_mass", "dynamic"),
                       help="force the model that sizes the flywheel (default: the cheapest exact one)")
    solve.add_argument("--design-method", choices=("auto", "ipopt", "closed_form"), default="auto",
                       help="auto (default): the exact closed form where it covers the structure, IPOPT "
                            "elsewhere; ipopt: IPOPT on every combination; closed_form: refuse what the "
                            "closed form does not cover")
    solve.add_argument("--verify", action="store_true",
                       help="simulate the machine with the chosen flywheel and report the δ it achieves")
    solve.set_defaults(run=_solve)

    plot = commands.add_parser("plot", help="draw a diagram of a scene, or of sweep/Pareto results (png, svg, pdf)")
    plot.add_argument("scene", help="scene file (TOML), or results (.csv/.parquet) of flyopt sweep or pareto")
    plot.add_argument("--what", required=True, metavar="DIAGRAM",
                      help="turning_moment | energy | inertia_delta | cross_section | speed | energy_mass; "
                           "for results: sweep | pareto")
    plot.add_argument("--x", help="results: the column on the x axis (sweep: a varied field)")
    plot.add_argument("--y", default="mass", help="results: the column on the y axis (default mass)")
    plot.add_argument("--by", help="sweep results: one line per value of this column (e.g. material)")
    plot.add_argument("--verify", action="store_true", help="speed: draw the periodic simulation over the model")
    plot.add_argument("-o", "--output", required=True, help="file to write; the suffix picks the format")
    plot.set_defaults(run=_plot)

    commands.add_parser("bench", help="speed against error of each way to an answer (see flyopt bench --help)",
                        add_help=False)
    commands.add_parser("sweep", help="a parameter sweep (grid or Latin hypercube) to CSV/Parquet", add_help=False)
    commands.add_parser("pareto", help="a Pareto front of two objectives", add_help=False)
    commands.add_parser("tradeoff", help="the lightest design of each material", add_help=False)

    check = commands.add_parser("check", help="check a scene file and say what is wrong")
    check.add_argument("scene", help="scene file (TOML)")
    check.set_defaults(run=_check)
    return parser


def _solve(args):
    scene = load(args.scene)
    solution = solve(scene, design_flywheel=args.design, model=args.model, verify_design=args.verify,
                     design_method=args.design_method)
    if args.json:
        text = json.dumps({"scene": args.scene, **_json_safe(solution.to_dict())}, indent=2, allow_nan=False)
    else:
        from flyopt.report.text import analysis_report, design_report, verification_report

        lines = [analysis_report(solution.analysis, args.scene)]
        if solution.design is not None:
            lines += design_report(solution.design)
        if solution.verification is not None:
            lines += verification_report(solution.verification)
        text = "\n".join(lines)
    print(text)
    if solution.status == "infeasible":
        return EXIT_INFEASIBLE
    if solution.verification is not None and solution.verification["flagged"]:
        return EXIT_FLAGGED
    return EXIT_OK


def _json_safe(value):
    """Infinite or NaN numbers (e.g. δ with no inertia at all) become null."""
    import math

    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


def _plot(args):
    from flyopt.report import plots

    if args.scene.lower().endswith((".csv", ".parquet")):
        return _plot_results(args)
    if args.what not in plots.PLOTS:
        import difflib

        close = difflib.get_close_matches(args.what, list(plots.PLOTS), n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        return _fail(f"--what: unknown diagram {args.what!r}{hint} (known: {', '.join(plots.PLOTS)})", EXIT_INPUT)
    if not _image_suffix(args.output):
        return _fail(f"--output: {args.output!r} must end in .png, .svg or .pdf", EXIT_INPUT)
    scene = load(args.scene)
    solution = solve(scene, design_flywheel=args.what == "cross_section")
    try:
        if args.what == "cross_section":
            if solution.design.best is None:
                return _fail(f"{args.scene}: no flywheel to draw ({solution.design.message})", EXIT_INFEASIBLE)
            ax = plots.plot_cross_section(solution.design.best)
        elif args.what == "speed":
            ax = plots.plot_speed(scene, solution.analysis, simulate=args.verify)
        else:
            ax = getattr(plots, f"plot_{args.what}")(scene, solution.analysis)
    except ValueError as err:
        return _fail(f"{args.scene}: {args.what}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


def _plot_results(args):
    from flyopt.report import plots
    from flyopt.studies.sweep import read_results

    if args.what not in plots.RESULT_PLOTS:
        return _fail(f"--what: {args.what!r} is not a diagram of results (known: {', '.join(plots.RESULT_PLOTS)})",
                     EXIT_INPUT)
    if not _image_suffix(args.output):
        return _fail(f"--output: {args.output!r} must end in .png, .svg or .pdf", EXIT_INPUT)
    if not args.x:
        return _fail(f"--x: the results diagram {args.what!r} needs the column for the x axis", EXIT_INPUT)
    try:
        frame = read_results(args.scene)
    except (OSError, ValueError) as err:
        return _fail(f"{args.scene}: cannot read the results: {err}", EXIT_INPUT)
    try:
        ax = plots.plot_sweep(frame, args.x, args.y, args.by) if args.what == "sweep" else \
            plots.plot_pareto(frame, args.x, args.y)
    except ValueError as err:
        return _fail(f"{args.scene}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


def _image_suffix(path):
    return path.lower().endswith((".png", ".svg", ".pdf"))


def _check(args):
    scene = load(args.scene)
    analyse(scene)  # a cycle that does not close is an input error too
    print(f"{args.scene}: ok ({scene.title})")
    return EXIT_OK


def _fail(message, status):
    print(f"flyopt: error: {message}", file=sys.stderr)
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
