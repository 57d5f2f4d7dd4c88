"""``flyopt export``: the manufacturing drawing of a scene's wheel, as DXF, SVG or PDF, or its solid as STEP.

::

    flyopt export SCENE.toml -o drawing.dxf|drawing.svg|drawing.pdf|wheel.step

The scene is solved (:func:`flyopt.pipeline.solve`) and its chosen wheel
drawn (:mod:`flyopt.outputs.drawing`: section A–A through the keyway, a front
view, every dimension a pattern maker and a machinist need, the title
block). The suffix of ``-o`` picks the format; .step or .stp writes the
wheel's solid in mm (:mod:`flyopt.outputs.solid`), read back and checked
before it takes its name. The output's folder and suffix are checked, and
the ``cad`` extra's presence for a DXF (ezdxf) or a STEP (OCP), before
anything is computed; the file is written atomically.

Exit status: 0 written; 2 bad input (a suffix, a folder, a DXF or STEP
without the ``cad`` extra, a scene that needs no flywheel); 3 infeasible (no
wheel meets the limits); 1 the design did not converge. Nothing is written
unless 0.
"""

from __future__ import annotations

import argparse

from flyopt.cli.exits import EXIT_INFEASIBLE, EXIT_INPUT, EXIT_OK, fail


def add_export_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt export``; the handler is :func:`run_export`."""
    parser.add_argument("scene", help="scene file (TOML)")
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="FILE",
        help="the drawing to write: .dxf (needs the cad extra: pip install 'flyopt[cad]'), .svg or .pdf; "
        "or the wheel's solid: .step/.stp (mm, needs the cad extra); written atomically, its folder must exist",
    )
    parser.set_defaults(run=run_export)


def run_export(args: argparse.Namespace) -> int:
    """``flyopt export``: 0 written, 2 a bad request or no flywheel needed, 3 infeasible."""
    from flyopt.io.scene import load
    from flyopt.outputs.files import check_folder, check_not_scene
    from flyopt.report.drawing import (
        NoWheel,
        design_of_scene,
        drawing_of_scene,
        export_format,
        write_drawing,
        write_solid,
    )

    kind = export_format(args.output)
    check_folder(args.output, "-o/--output")
    if kind in ("dxf", "step"):
        from flyopt.outputs.drawing import require_ezdxf
        from flyopt.outputs.solid import require_ocp

        try:
            require_ezdxf() if kind == "dxf" else require_ocp()
        except ImportError as err:
            return fail(f"-o/--output: {err}", EXIT_INPUT)
    scene = load(args.scene)
    check_not_scene(args.output, scene, "the drawing")
    try:
        if kind == "step":
            design = design_of_scene(scene)
        else:
            drawing, _design = drawing_of_scene(scene)
    except NoWheel as said:
        return fail(f"{args.scene}: {said}", EXIT_INFEASIBLE if said.infeasible else EXIT_INPUT)
    if kind == "step":
        write_solid(design, scene, args.output)
    else:
        write_drawing(drawing, args.output, kind)
    print(f"wrote {args.output}")
    return EXIT_OK
