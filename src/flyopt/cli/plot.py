"""``flyopt plot``: a diagram of a scene, or of the results of a sweep or a Pareto front.

The handler computes what a diagram needs (the analysis, the design, the
speed over the cycle, the simulation) and hands it to :mod:`flyopt.report.plots`,
which only draws. The output file is checked before anything is computed.
A diagram that would be empty because no flywheel is needed is said in one
line on stdout with exit status 0 and no file: the scene is valid and the
answer (no flywheel) is the one ``flyopt solve`` gives with status 0. A
diagram that does not apply to the scene (the energy–mass diagram of a
constant inertia, ω(φ) of net areas) is refused in one line, exit status 2,
nothing written. ``--units`` picks the unit system every axis and label is
drawn in (flyopt.report.display); files of results stay SI.
"""

from flyopt.cli.exits import EXIT_INFEASIBLE, EXIT_INPUT, EXIT_OK, fail
from flyopt.errors import FlyoptError
from flyopt.names import Model, hint


def add_plot_arguments(parser):
    """The options of ``flyopt plot``; the handler is :func:`run_plot`."""
    parser.add_argument("scene", help="scene file (TOML), or results (.csv/.parquet) of flyopt sweep or pareto")
    parser.add_argument(
        "--what",
        required=True,
        metavar="DIAGRAM",
        help="turning_moment | energy | inertia_delta | cross_section | stress | speed | "
        "energy_mass; for results: sweep | pareto",
    )
    parser.add_argument(
        "--x",
        help="results: the column on the x axis (sweep: a varied field; pareto: default the front's second objective)",
    )
    parser.add_argument("--y", default="mass", help="results: the column on the y axis (default mass)")
    parser.add_argument("--by", help="sweep results: one line per value of this column (e.g. material)")
    parser.add_argument("--verify", action="store_true", help="speed: draw the periodic simulation over the model")
    parser.add_argument(
        "--units",
        default="engineering",
        metavar="SYSTEM",
        help="units of the axes and labels: engineering (mm, rpm, kN·m, kJ, MPa; the default), "
        "si (m, rad/s, N·m, J, Pa) or imperial (in, rpm, lbf·ft, ft·lbf, psi)",
    )
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        help="file to write (its folder must exist); the suffix picks the format: png, svg, pdf",
    )
    parser.set_defaults(run=run_plot)


def run_plot(args):
    """``flyopt plot``: 0 written (or nothing to draw), 2 a bad request, 3 no feasible flywheel to draw."""
    from flyopt.report import display, plots

    if args.units not in display.SYSTEMS:
        return fail(f"--units: unknown unit system {args.units!r} (allowed: {', '.join(display.SYSTEMS)})", EXIT_INPUT)
    if args.scene.lower().endswith((".csv", ".parquet")):
        return _plot_results(args)
    if args.what not in plots.PLOTS:
        return fail(
            f"--what: unknown diagram {args.what!r}{hint(args.what, plots.PLOTS)} (known: {', '.join(plots.PLOTS)})",
            EXIT_INPUT,
        )
    plots.check_output(args.output)
    try:
        ax = _draw(args, plots)
    except plots.NothingToDraw as said:
        print(f"{args.scene}: {args.what}: {said} (no file written)")
        return EXIT_OK
    except _Infeasible as said:
        return fail(f"{args.scene}: no flywheel to draw ({said})", EXIT_INFEASIBLE)
    except ValueError as err:
        if isinstance(err, FlyoptError):  # an input error names its file and field itself
            raise
        return fail(f"{args.scene}: {args.what}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK


class _Infeasible(Exception):
    """A flywheel is needed and no material and shaft can give it (exit 3)."""


def _draw(args, plots):
    """Compute what the diagram needs, then draw it; returns the Axes."""
    from flyopt.analysis import analyse
    from flyopt.io.scene import load

    units = args.units
    scene = load(args.scene)
    analysis = analyse(scene)
    if args.what in ("cross_section", "stress"):
        from flyopt.pipeline import design_scene

        design = design_scene(scene, analysis)
        if design.status == "not_needed":
            raise plots.NothingToDraw("no flywheel is needed: nothing to draw")
        if design.best is None:
            raise _Infeasible(design.message)
        if args.what == "cross_section":
            return plots.plot_cross_section(design.best, units=units)
        return _draw_stress(scene, analysis, design, plots, units)
    if args.what == "speed":
        if scene.net is not None:  # said by the plot, before any model runs
            return plots.plot_speed(scene, analysis, units=units)
        from flyopt.pipeline import verify

        # the simulation --verify checks, with the required flywheel: pipeline.verify, the one path
        simulation = verify(scene, analysis).solution if args.verify else None
        speed = analysis.speed_curve()
        if speed is None:
            raise plots.NothingToDraw(
                "no flywheel is needed and the speed does not fluctuate (A_max = 0 J, "
                "no inertia at all): nothing to draw"
            )
        return plots.plot_speed(scene, analysis, speed, simulation, units=units)
    if args.what == "energy_mass":
        plots.check_energy_mass(analysis)
        if analysis.model != Model.ENERGY_MASS:  # the diagram draws that model's tangents
            analysis = analyse(scene, model="energy_mass")
    if args.what == "inertia_delta":
        plots.check_inertia_delta(analysis)
        curve = None if analysis.model == Model.ENERGY else inertia_curve(scene, analysis)
        return plots.plot_inertia_delta(scene, analysis, units=units, curve=curve)
    return getattr(plots, f"plot_{args.what}")(scene, analysis, units=units)


def inertia_curve(scene, analysis, deltas=None):
    """J_F at each δ by the analysis' own model: the scene analysed again at that δ.

    With a variable inertia or a speed-dependent torque, J_F is not
    A_max/(ω_m² δ) − J_c (docs/flywheel-design.md, sections 6 and 7): each
    δ is a new sizing by the exact model. The reduced machine and its
    compiled models are reused (``analyse(..., like=analysis)``).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    deltas : sequence of float, optional
        δ [-], each in (0, 2). By default those of
        :func:`flyopt.report.plots.delta_range` (41; 25 for the dynamic model,
        whose every point is a periodic solution), and where J_F falls to zero
        between two of them (δ*, where the machine's own inertia starts to
        suffice, and the curve is steep) eight more between those two.

    Returns
    -------
    (ndarray, ndarray)
        δ and J_F there (``j_margin``: negative where none is needed)
        [kg*m^2]; NaN where the model has no answer at that δ (the periodic
        solution stalls, say).
    """
    import dataclasses

    import numpy as np

    from flyopt.analysis import analyse
    from flyopt.errors import SolverFailed

    if deltas is None:
        from flyopt.report.plots import delta_range

        delta, j = inertia_curve(scene, analysis, delta_range(analysis, 25 if analysis.model == Model.DYNAMIC else 41))
        falls = np.flatnonzero((j[:-1] > 0) & (j[1:] <= 0))
        if len(falls):
            k = falls[0]
            more = inertia_curve(scene, analysis, np.geomspace(delta[k], delta[k + 1], 10)[1:-1])
            order = np.argsort(np.concatenate([delta, more[0]]))
            return np.concatenate([delta, more[0]])[order], np.concatenate([j, more[1]])[order]
        return delta, j
    deltas = np.asarray(deltas, dtype=float)
    j = np.full(deltas.shape, np.nan)
    for k, delta in enumerate(deltas):
        try:
            j[k] = analyse(dataclasses.replace(scene, delta=float(delta)), analysis.model, like=analysis).j_margin
        except SolverFailed:
            continue
    return deltas, j


def wheel_dims(candidate):
    """The :class:`flyopt.design.wheel.Dims` of a designed candidate [m] (0 where it has no such part)."""
    from flyopt.design.wheel import Dims

    c = candidate
    return Dims(
        d_outer=c.d_outer,
        h=c.h,
        b=c.b,
        bore=c.bore or 0.0,
        t_web=c.t_web or 0.0,
        d_hub=c.d_hub or 0.0,
        l_hub=c.l_hub or 0.0,
        arm_major=c.arm_major or 0.0,
        n_arms=c.n_arms or 0,
    )


def stress_profile(scene, analysis, design):
    """The stresses of the design's best wheel over its radius, at omega_max on its own shaft.

    Returns
    -------
    profile, beams : see :func:`flyopt.design.strength.profile`
    omega : float
        omega_max on the wheel's shaft [rad/s].
    material : flyopt.design.materials.Material
    """
    from flyopt.design import strength

    best = design.best
    material = scene.material_library()[best.material]
    if getattr(material, "poisson_ratio", None) is None:
        raise ValueError(f"material {best.material!r} gives no poisson_ratio: its stresses cannot be computed")
    omega = design.omega * best.speed_ratio
    torque = analysis.flywheel_torque()
    torque = torque / best.speed_ratio if torque else 0.0
    profile, beams = strength.profile(material, best.geometry, wheel_dims(best), omega, torque)
    return profile, beams, omega, material


def _draw_stress(scene, analysis, design, plots, units="engineering"):
    profile, beams, omega, material = stress_profile(scene, analysis, design)
    return plots.plot_stress(
        design.best, profile, beams, omega, ductile=bool(getattr(material, "ductile", False)), units=units
    )


def _plot_results(args):
    from flyopt.outputs.results import read_results
    from flyopt.report import plots

    if args.what not in plots.RESULT_PLOTS:
        return fail(
            f"--what: {args.what!r} is not a diagram of results (known: {', '.join(plots.RESULT_PLOTS)})", EXIT_INPUT
        )
    plots.check_output(args.output)
    try:
        frame = read_results(args.scene)
    except (OSError, ValueError) as err:
        return fail(f"{args.scene}: cannot read the results: {err}", EXIT_INPUT)
    x = args.x
    if x is None and args.what == "pareto":
        # the objectives the front's file records (flyopt pareto writes them in its metadata);
        # a file written before they were recorded: its first two columns
        objectives = frame.attrs.get("flyopt", {}).get("objectives") or plots.pareto_objectives(frame)
        x = objectives[1] if objectives else None
    if x is None:
        return fail(f"--x: the results diagram {args.what!r} needs the column for the x axis", EXIT_INPUT)
    units = args.units
    try:
        ax = (
            plots.plot_sweep(frame, x, args.y, args.by, units=units)
            if args.what == "sweep"
            else plots.plot_pareto(frame, x, args.y, units=units)
        )
    except ValueError as err:
        return fail(f"{args.scene}: {err}", EXIT_INPUT)
    plots.save(ax, args.output)
    print(f"wrote {args.output}")
    return EXIT_OK
