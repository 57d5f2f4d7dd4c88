"""``flyopt plot``: a diagram of a scene, or of the results of a sweep or a Pareto front."""

from flyopt.cli.exits import EXIT_INFEASIBLE, EXIT_INPUT, EXIT_OK, fail


def add_plot_arguments(parser):
    """The options of ``flyopt plot``; the handler is :func:`run_plot`."""
    parser.add_argument("scene", help="scene file (TOML), or results (.csv/.parquet) of flyopt sweep or pareto")
    parser.add_argument("--what", required=True, metavar="DIAGRAM",
                        help="turning_moment | energy | inertia_delta | cross_section | speed | energy_mass; "
                             "for results: sweep | pareto")
    parser.add_argument("--x", help="results: the column on the x axis (sweep: a varied field)")
    parser.add_argument("--y", default="mass", help="results: the column on the y axis (default mass)")
    parser.add_argument("--by", help="sweep results: one line per value of this column (e.g. material)")
    parser.add_argument("--verify", action="store_true", help="speed: draw the periodic simulation over the model")
    parser.add_argument("-o", "--output", required=True, help="file to write; the suffix picks the format")
    parser.set_defaults(run=run_plot)


def run_plot(args):
    """``flyopt plot``: 0 written, 2 a diagram that cannot be drawn or a bad request."""
    from flyopt.io.scene import load
    from flyopt.pipeline import solve
    from flyopt.report import plots

    if args.scene.lower().endswith((".csv", ".parquet")):
        return _plot_results(args)
    if args.what not in plots.PLOTS:
        import difflib

        close = difflib.get_close_matches(args.what, list(plots.PLOTS), n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        return fail(f"--what: unknown diagram {args.what!r}{hint} (known: {', '.join(plots.PLOTS)})", EXIT_INPUT)
    if not _image_suffix(args.output):
        return fail(f"--output: {args.output!r} must end in .png, .svg or .pdf", EXIT_INPUT)
    scene = load(args.scene)
    solution = solve(scene, design_flywheel=args.what == "cross_section")
    try:
        if args.what == "cross_section":
            if solution.design.best is None:
                return fail(f"{args.scene}: no flywheel to draw ({solution.design.message})", EXIT_INFEASIBLE)
            ax = plots.plot_cross_section(solution.design.best)
        elif args.what == "speed":
            ax = plots.plot_speed(scene, solution.analysis, simulate=args.verify)
        else:
            ax = getattr(plots, f"plot_{args.what}")(scene, solution.analysis)
    except ValueError as err:
        return fail(f"{args.scene}: {args.what}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


def _plot_results(args):
    from flyopt.io.results import read_results
    from flyopt.report import plots

    if args.what not in plots.RESULT_PLOTS:
        return fail(f"--what: {args.what!r} is not a diagram of results (known: {', '.join(plots.RESULT_PLOTS)})",
                    EXIT_INPUT)
    if not _image_suffix(args.output):
        return fail(f"--output: {args.output!r} must end in .png, .svg or .pdf", EXIT_INPUT)
    if not args.x:
        return fail(f"--x: the results diagram {args.what!r} needs the column for the x axis", EXIT_INPUT)
    try:
        frame = read_results(args.scene)
    except (OSError, ValueError) as err:
        return fail(f"{args.scene}: cannot read the results: {err}", EXIT_INPUT)
    try:
        ax = plots.plot_sweep(frame, args.x, args.y, args.by) if args.what == "sweep" else \
            plots.plot_pareto(frame, args.x, args.y)
    except ValueError as err:
        return fail(f"{args.scene}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


def _image_suffix(path):
    return path.lower().endswith((".png", ".svg", ".pdf"))
