"""``flyopt report``: the engineering report of one scene, as one self-contained HTML or PDF file.

::

    flyopt report SCENE.toml -o report.html [--units engineering|si|imperial]
    flyopt report SCENE.toml -o report.pdf

The scene is solved once, as ``flyopt solve --verify`` solves it
(:func:`flyopt.pipeline.solve` with ``verify_design=True``) and with every
extra the report shows (:func:`report_extras`: what ``flyopt solve`` shows,
the model comparison, the start-up, an engine's textbook flywheel, and what
its diagrams draw, the speed over the cycle, J_F at other δ, the energy–mass
analysis, the stress profile; not the simulation with the required flywheel,
which only ``flyopt plot --what speed --verify`` draws: the report's
simulation is the verification of the design); :func:`collect` then only
reads them out of the solution (with the provenance), and
:mod:`flyopt.report.builder` builds the report from them without running a
model. The suffix of ``-o`` picks the format; the file is
written atomically (nothing half-written on an error or Ctrl-C) and its
folder is checked before anything is computed.

A scene that is one calculation rather than a cycle ([operation], [position],
[electric_drive], [power_chain]) is answered once, as ``flyopt solve`` answers
it (:func:`flyopt.pipeline.solve_calculation`), and reported by
:mod:`flyopt.report.builder.calculation`: the given data, the method with the
numbers substituted and the answers, with no diagram (it has no cycle).

Exit status as ``flyopt solve``: 0 written, 2 bad input (one line naming the
file and the field), 3 infeasible (the report is still written and says
so), 4 the verification flagged the design, or an operation's speed falls
beyond machine.delta (written, and says so).
"""

from __future__ import annotations

import argparse
import os
from typing import TYPE_CHECKING, cast

from flyopt.cli.exits import calculation_exit, solution_exit
from flyopt.names import Model

if TYPE_CHECKING:
    from flyopt.io.scene import Scene
    from flyopt.pipeline import Solution
    from flyopt.report.builder import CalculationInputs, ReportInputs
    from flyopt.report.document import Document

#: The report's formats, by the suffix of the output file.
FORMATS = {".html": "html", ".htm": "html", ".pdf": "pdf"}


def add_report_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt report``; the handler is :func:`run_report`."""
    from flyopt.report.display import DEFAULT, SYSTEMS

    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="FILE",
        help="the report to write: .html (one self-contained page) or .pdf; written atomically, its folder must exist",
    )
    parser.add_argument(
        "--units",
        choices=SYSTEMS,
        default=DEFAULT,
        help=f"units of the summary and tables (default {DEFAULT}: mm, rpm, MPa, and N·m, J, W, N with the "
        "prefix each value needs, 36.1 N·m or 1.256 kJ; si: SI base units; imperial: in, rpm, lbf·ft, psi); "
        "the equations stay in SI",
    )
    from flyopt.cli.scene import add_digits_argument

    add_digits_argument(parser, "the report, its tables and equations")
    parser.set_defaults(run=run_report)


def output_kind(path: str | os.PathLike[str]) -> str:
    """ "html" or "pdf" from the suffix of ``path``; SceneError at ``-o/--output`` otherwise."""
    from pathlib import Path

    from flyopt.errors import SceneError

    kind = FORMATS.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError("-o/--output", f"{str(path)!r} must end in .html or .pdf (the suffix picks the format)")
    return kind


def run_report(args: argparse.Namespace) -> int:
    """``flyopt report``: 0 written, 3 infeasible (written), 4 verification flagged (written)."""
    import sys

    from flyopt.outputs.files import check_folder

    kind = output_kind(args.output)
    check_folder(args.output, "-o/--output")
    command = f"flyopt report {args.scene} -o {args.output} --units {args.units} --digits {args.digits}"
    inputs = collect(args.scene, command, pdf=kind == "pdf", output=args.output)
    from flyopt.report.builder import CalculationInputs, build

    document = build(inputs, args.units, title_block=_title_lines(inputs), digits=args.digits)
    try:
        write(document, args.output, kind)
    finally:
        document.close()
    for failure in document.failures:
        print(f"flyopt: warning: {args.scene}: diagram {failure}", file=sys.stderr)
    print(f"wrote {args.output}")
    if isinstance(inputs, CalculationInputs):
        return calculation_exit(inputs.result)
    return solution_exit(cast("Solution", inputs.solution))  # collect solved it


def write(document: Document, path: str | os.PathLike[str], kind: str) -> None:
    """Render ``document`` as ``kind`` ("html" or "pdf") and write it to ``path`` atomically."""
    from flyopt.outputs.files import write_atomically, write_text

    if kind == "html":
        from flyopt.report.html import render

        write_text(path, render(document))
        return
    try:
        from flyopt.report.pdf import render as render_pdf

        data = render_pdf(document)
    except ImportError as err:  # reportlab is a dependency: only a broken installation lacks it
        from flyopt.errors import SceneError

        raise SceneError(
            "-o/--output", f"a PDF report needs reportlab ({err}); install it (pip install reportlab) or write .html"
        ) from None

    write_atomically(path, lambda handle: handle.write(data))  # the handle of the file it made, not a name


def collect(
    path: str | os.PathLike[str],
    command: str = "",
    pdf: bool = False,
    shown_as: str | None = None,
    output: str | os.PathLike[str] | None = None,
) -> ReportInputs | CalculationInputs:
    """Solve a scene and gather what its report shows (:class:`flyopt.report.builder.ReportInputs`), or,
    for a scene that is one calculation (:data:`flyopt.names.CALCULATIONS`), answer it as ``flyopt solve``
    does (:func:`flyopt.pipeline.solve_calculation`) into a :class:`flyopt.report.builder.CalculationInputs`.

    Parameters
    ----------
    path : str
        The scene file.
    command : str
        The command line, for the provenance.
    pdf : bool
        Name reportlab's version in the provenance.
    shown_as : str, optional
        The scene file's name in the report (default ``path``): the app's, whose file is its server's own.
    output : str or Path, optional
        The report's file: refused once the scene is read, before it is solved, if it is the scene file or a
        data file the scene reads (:func:`flyopt.outputs.files.check_not_scene`).

    Raises
    ------
    SceneError, NonPeriodicCycle
        The scene cannot be read, or its cycle does not close (exit 2).
    SolverFailed
        A model or the design did not converge (exit 1).
    """
    import dataclasses
    from pathlib import Path

    from flyopt.io.scene import load
    from flyopt.io.toml_file import read_toml
    from flyopt.pipeline import solve
    from flyopt.report.builder import ReportInputs

    data = read_toml(path)
    scene = load(path, data)
    if output is not None:
        from flyopt.outputs.files import check_not_scene

        check_not_scene(output, scene, "the report")
    name = shown_as or str(path)  # the file as the report names it
    if shown_as is not None:
        scene = dataclasses.replace(scene, shown_as=shown_as)
    what = scene.calculation
    if what is not None:
        from flyopt.pipeline import solve_calculation
        from flyopt.report.builder import CalculationInputs

        result = solve_calculation(scene)  # the one answer, as flyopt solve gives it: the report only reads it
        calculation = CalculationInputs(name, Path(path).read_text(encoding="utf-8"), scene, what, result)
        calculation.provenance = provenance(scene, command, pdf)
        return calculation
    solution = solve(scene, verify_design=True, extras=report_extras())  # the one solve: what follows only reads
    inputs = ReportInputs(
        scene_file=name,
        scene_text=Path(path).read_text(encoding="utf-8"),
        scene_tables=tuple(k for k, v in data.items() if isinstance(v, (dict, list))),
        scene=scene,
        solution=solution,
    )
    _speed(inputs)
    _machine(inputs)
    _inertia_delta(inputs)
    _stress(inputs)
    inputs.provenance = provenance(scene, command, pdf)
    return inputs


def report_extras() -> tuple[str, ...]:
    """The extras of :func:`flyopt.pipeline.solve` the report reads: what ``flyopt solve`` shows
    (:data:`flyopt.pipeline.SHOWN`) and what its diagrams, every one of :data:`flyopt.report.plots.PLOTS`,
    draw without ``--verify`` (:func:`flyopt.cli.plot.needs`). A reader that reads any other extra gets
    :class:`flyopt.analysis.NotComputed`, so that nothing is computed that the report does not show (the
    simulation with the required flywheel cost slider-crank-press half of its solve, motor-press a quarter)."""
    from flyopt.cli.plot import needs
    from flyopt.pipeline import SHOWN
    from flyopt.report.plots import PLOTS

    return tuple(dict.fromkeys((*SHOWN, *needs(PLOTS)[1])))


def _speed(inputs):
    """ω(φ) with the required flywheel, by the model that sized it (as ``flyopt plot --what speed``)."""
    solution = inputs.solution
    if solution.scene.net is not None:
        inputs.speed_note = "a scene given as net areas has no angles"
        return
    try:
        inputs.speed = solution.analysis.speed_curve()
    except ValueError as err:
        inputs.speed_note = str(err)
        return
    if inputs.speed is None:
        inputs.speed_note = "no flywheel is needed and the speed does not fluctuate (A_max = 0 J, no inertia at all)"


def _machine(inputs):
    """J_e(φ)'s range and mean, the energy–mass tangent points and analysis, an engine's textbook flywheel."""
    import numpy as np

    solution = inputs.solution
    analysis = solution.analysis
    machine = analysis.machine
    if machine is None:
        return
    if machine.variable_inertia:
        phi = np.linspace(0.0, machine.cycle_angle, 4097)
        j = np.asarray(machine.j_machine(phi), dtype=float)
        inputs.j_machine = (float(j.min()), machine.j_mean(), float(j.max()))
    else:
        j_c = float(machine.j_machine)
        inputs.j_machine = (j_c, j_c, j_c)
    inputs.textbook = analysis.textbook
    inputs.energy_mass = solution.energy_mass  # None where the diagram does not apply
    if inputs.energy_mass is not None and analysis.model == Model.ENERGY_MASS:
        detail = analysis.requirement.detail
        excess = machine.angle_only()
        inputs.tangents = {
            key: (
                float(phi_k),
                float(np.asarray(machine.j_machine(np.array([phi_k])))[0]),
                float(np.asarray(excess(np.array([phi_k])))[0]),
            )
            for key, phi_k in (("max", detail.phi_omega_max), ("min", detail.phi_omega_min))
        }


def _inertia_delta(inputs):
    """J_F at each δ by the exact model, where it is not the energy method's closed form (as ``flyopt plot``)."""
    solution = inputs.solution
    inputs.inertia_curve = solution.inertia_curve
    if solution.inertia_error is not None:  # the report goes on; the diagram says why it is missing
        model = solution.analysis.model
        inputs.inertia_note = f"J_F could not be found at every δ by the {model} model ({solution.inertia_error})"


def _stress(inputs):
    """The stresses over the radius of the chosen wheel (:func:`flyopt.pipeline.stress_profile`)."""
    solution = inputs.solution
    design = solution.design
    best = design.best if design is not None else None
    if best is None or not best.stresses.stress or not best.parts.items:
        return
    inputs.stress, inputs.stress_note = solution.stress, solution.stress_note


def provenance(scene: Scene, command: str = "", pdf: bool = False) -> tuple[tuple[str, str], ...]:
    """Where the report came from: flyopt's version, the scene file and its SHA-256, the date, the solvers.

    Parameters
    ----------
    scene : Scene
    command : str
        The command line.
    pdf : bool
        Name reportlab's version too.

    The data files the scene read (:attr:`~flyopt.io.scene.Scene.inputs`) are listed, each by its field and its
    path from the scene file's folder, not hashed.

    Returns
    -------
    tuple of (str, str)
    """
    import datetime
    import platform

    import flyopt
    from flyopt.outputs.documents import scene_record

    record = scene_record(scene)
    rows = [
        ("flyopt", flyopt.__version__),
        ("scene file", record["scene"] or "-"),
        ("scene file SHA-256", record["scene_file_sha256"] or "-"),
    ]
    if scene.inputs:
        folder = os.path.dirname(scene.source or "") or os.curdir
        rows.append(
            (
                "data files the scene reads",
                "; ".join(f"{field} = {os.path.relpath(path, folder)}" for field, path in scene.inputs)
                + " (not in the hash above)",
            )
        )
    rows += [
        ("written", datetime.datetime.now().astimezone().isoformat(timespec="seconds")),
        ("command", command or "-"),
        ("Python", f"{platform.python_version()} ({platform.python_implementation()}), {platform.platform()}"),
    ]
    for name in ("numpy", "scipy", "casadi", "matplotlib", "pint") + (("reportlab",) if pdf else ()):
        rows.append((name, _version_of(name)))
    rows.append(("IPOPT", ipopt_version()))
    return tuple(rows)


def _version_of(name: str) -> str:
    from importlib import metadata

    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def ipopt_version() -> str:
    """IPOPT's version as CasADi's build reports it (``CasadiMeta.feature_list``), or why it is not known."""
    import re

    try:
        import casadi as ca

        found = re.search(r"BUILD_IPOPT_VERSION=([^)\s]+)", ca.CasadiMeta.feature_list())
    except (ImportError, AttributeError, RuntimeError):
        return "not reported by CasADi"
    return (
        f"{found.group(1)} (built into CasADi {getattr(ca, '__version__', '?')})" if found else "not reported by CasADi"
    )


def _title_lines(inputs):
    """The title block's lines beside the scene file: date, flyopt version, the file's SHA-256."""
    rows = dict(inputs.provenance)
    return (
        ("date", rows.get("written", "-")),
        ("flyopt version", rows.get("flyopt", "-")),
        ("scene SHA-256", rows.get("scene file SHA-256", "-")),
    )
