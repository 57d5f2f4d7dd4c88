"""The manufacturing drawing as a matplotlib figure (SVG, PDF), and ``export``: a scene's wheel to a file.

:func:`figure` draws a :class:`flyopt.outputs.drawing.Drawing` on an A3 sheet
at the drawing's scale (1 paper mm is 1 mm of the printed sheet): the same
lines, hatched faces, dimensions, names and title block that
:func:`flyopt.outputs.drawing.write_dxf` writes to DXF. :func:`export` solves
a scene, draws its chosen wheel and writes it as DXF, SVG or PDF by the
suffix of the file, or (.step, .stp) writes its solid
(:func:`export_solid`, :mod:`flyopt.outputs.solid`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from flyopt.outputs.drawing import SHEET, Drawing

if TYPE_CHECKING:
    import datetime
    import os

    from matplotlib.figure import Figure

    from flyopt.design.result import Design
    from flyopt.io.scene import Scene
    from flyopt.outputs.solid import Solid

__all__ = [
    "EXPORT_FORMATS",
    "NoWheel",
    "design_of_scene",
    "drawing_of_scene",
    "export",
    "export_solid",
    "export_format",
    "figure",
    "write_drawing",
    "write_solid",
]

#: The formats of ``flyopt export``, by the suffix of the file.
EXPORT_FORMATS = {".dxf": "dxf", ".svg": "svg", ".pdf": "pdf", ".step": "step", ".stp": "step"}

#: Line widths on paper [mm] (ISO 128-20: wide 0.5, narrow 0.25).
_WIDE, _NARROW = 0.5, 0.25
_PT = 72.0 / 25.4  # points per paper mm
#: Behind a dimension's text: the sheet, so that lines break there (DXF: DIMTFILL 1).
_CLEAR = {"facecolor": "white", "edgecolor": "none", "pad": 0.6}


#: Why a scene that gives its [flywheel] has no wheel to draw (its drawing, cross-section and stresses).
GIVEN_WHEEL = "the scene gives its flywheel ([flywheel]) and designs none: nothing to draw (flyopt solve checks it)"


def export_format(path: str | os.PathLike[str]) -> str:
    """ "dxf", "svg", "pdf" or "step" from the suffix of ``path``; SceneError at ``-o/--output`` otherwise."""
    from pathlib import Path

    from flyopt.errors import SceneError

    kind = EXPORT_FORMATS.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError(
            "-o/--output", f"{str(path)!r} must end in .dxf, .svg, .pdf or .step/.stp (the suffix picks the format)"
        )
    return kind


def figure(drawing: Drawing) -> Figure:
    """The drawing on an A3 sheet at its scale: a matplotlib Figure (save it as SVG or PDF)."""
    from matplotlib.patches import Arc as ArcPatch
    from matplotlib.patches import Polygon

    from flyopt.report.plots import standard

    width, height, _border = SHEET
    fig = standard.figure_class()(figsize=(width / 25.4, height / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    x0, y0, x1, y1 = drawing.sheet
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_axis_off()
    paper = drawing.scale  # paper mm per model mm

    def lw(style):
        return (_NARROW if style in ("thin", "chain") else _WIDE) * _PT

    def dashes(style):
        return (0, (24.0 / _NARROW / _PT * 0.3, 3.0, 2.0, 3.0)) if style == "chain" else "solid"

    for hatch in drawing.hatches:
        ax.add_patch(Polygon(hatch.boundary, closed=True, fill=False, lw=0.0, hatch="////", edgecolor="0.35"))
    for line in drawing.lines:
        points = list(line.points) + ([line.points[0]] if line.closed else [])
        xs, ys = zip(*points)
        ax.plot(xs, ys, color="black", lw=lw(line.style), ls=dashes(line.style), solid_capstyle="butt")
    for arc in drawing.arcs:
        ax.add_patch(
            ArcPatch(arc.center, 2 * arc.radius, 2 * arc.radius, theta1=arc.start, theta2=arc.end, lw=lw(arc.style))
        )
    for text in drawing.texts:
        ax.text(
            *text.at,
            text.text,
            fontsize=_font(text.height * paper),
            ha=text.align,
            va="baseline",
            rotation=text.rotation,
            color="black",
        )
    for dim in drawing.dimensions:
        _dimension(ax, dim, paper)
    return fig


def _font(cap_height_mm):
    """matplotlib's font size [pt] whose capitals are ``cap_height_mm`` tall (DejaVu Sans: 0.73 em)."""
    return cap_height_mm * _PT / 0.73


def _arrow(ax, tip, direction, paper):
    """A closed filled arrow at ``tip`` pointing along the unit vector ``direction`` (2.5 mm on paper)."""
    from matplotlib.patches import Polygon

    length, half = 2.5 / paper, 0.45 / paper
    ux, uy = direction
    back = (tip[0] - ux * length, tip[1] - uy * length)
    ax.add_patch(
        Polygon(
            [tip, (back[0] - uy * half, back[1] + ux * half), (back[0] + uy * half, back[1] - ux * half)],
            closed=True,
            facecolor="black",
            edgecolor="black",
            lw=0.2,
        )
    )


def _dimension(ax, dim, paper):
    """Draw one dimension: extension lines, the line with its arrows, the text where the description puts it."""
    thin = {"color": "black", "lw": _NARROW * _PT * 0.7, "solid_capstyle": "butt"}
    size = _font(2.5)
    if dim.kind in ("radius", "chamfer"):
        # a leader: from the text to the arc (a radius: arrow on the arc, its line from the centre's side) or to
        # the chamfer's middle, with a shoulder under the text
        tip = dim.p2
        start = dim.text_at if dim.kind == "radius" else dim.p1
        width = 0.75 * 2.5 * len(dim.text) / paper
        left = dim.text_at[0]
        shoulder_x = left if abs(start[0] - left) < abs(start[0] - (left + width)) else left + width
        ax.plot([tip[0], start[0], shoulder_x], [tip[1], start[1], dim.text_at[1]], **thin)
        ax.plot([left, left + width], [dim.text_at[1], dim.text_at[1]], **thin)
        ux, uy = tip[0] - start[0], tip[1] - start[1]
        norm = math.hypot(ux, uy)
        _arrow(ax, tip, (ux / norm, uy / norm), paper)
        ax.text(left, dim.text_at[1] + 0.4 / paper, dim.text, fontsize=size, ha="left", va="bottom", color="black")
        return
    if dim.kind == "diameter":
        cx, cy = dim.p1
        ux, uy = dim.p2[0] - cx, dim.p2[1] - cy
        r = math.hypot(ux, uy)
        ux, uy = ux / r, uy / r
        far = (cx - ux * r, cy - uy * r)
        near = (cx + ux * r, cy + uy * r)
        ax.plot([far[0], dim.text_at[0]], [far[1], dim.text_at[1]], **thin)
        _arrow(ax, near, (ux, uy), paper)
        _arrow(ax, far, (-ux, -uy), paper)
        ax.text(*dim.text_at, " " + dim.text, fontsize=size, ha="left", va="bottom", color="black", bbox=_CLEAR)
        return
    vertical = dim.vertical
    axis = 1 if vertical else 0
    line = dim.base[0] if vertical else dim.base[1]
    ends = sorted((dim.p1, dim.p2), key=lambda pt: pt[axis])
    gap, over = 1.0 / paper, 1.5 / paper
    for end in ends:
        feature = end[0] if vertical else end[1]
        sign = 1.0 if line >= feature else -1.0
        if abs(line - feature) > gap:
            if vertical:
                ax.plot([feature + sign * gap, line + sign * over], [end[1], end[1]], **thin)
            else:
                ax.plot([end[0], end[0]], [feature + sign * gap, line + sign * over], **thin)
    lo, hi = ends[0][axis], ends[1][axis]

    def point(along):
        return (line, along) if vertical else (along, line)

    inside = (hi - lo) * paper > 8.0
    text_along = dim.text_at[1] if vertical else dim.text_at[0]
    if inside:
        ax.plot(*zip(point(lo), point(hi)), **thin)
        _arrow(ax, point(lo), (0, -1) if vertical else (-1, 0), paper)
        _arrow(ax, point(hi), (0, 1) if vertical else (1, 0), paper)
    else:  # arrows outside pointing in, the line out to the text where it is beyond an end
        start = min(lo - 5.0 / paper, text_along)
        stop = max(hi + 5.0 / paper, text_along)
        ax.plot(*zip(point(start), point(stop)), **thin)
        _arrow(ax, point(lo), (0, 1) if vertical else (1, 0), paper)
        _arrow(ax, point(hi), (0, -1) if vertical else (-1, 0), paper)
    beyond = not (lo <= text_along <= hi)
    ax.text(
        *dim.text_at,
        dim.text,
        fontsize=size,
        ha="center",
        va="center" if not beyond else "bottom",
        rotation=90 if vertical else 0,
        rotation_mode="anchor",
        color="black",
        bbox=_CLEAR,
    )


class NoWheel(ValueError):
    """A scene whose solution has no wheel to draw: none is needed, or (``infeasible``) none meets the limits."""

    def __init__(self, message: str, infeasible: bool) -> None:
        super().__init__(message)
        self.infeasible = infeasible


def design_of_scene(scene: Scene) -> Design:
    """Solve ``scene`` and return its chosen wheel.

    Raises
    ------
    NoWheel
        No flywheel is needed, or none is feasible.
    SolverFailed
        The design did not converge (exit 1).
    """
    from flyopt.pipeline import solve

    if scene.flywheel is not None:  # a wheel that exists, checked by solve: nothing is designed
        raise NoWheel(GIVEN_WHEEL, infeasible=False)
    solution = solve(scene)
    if solution.status == "not_needed":
        raise NoWheel("no flywheel is needed: nothing to draw", infeasible=False)
    design = solution.design
    if design is None or design.best is None:
        said = design.message if design is not None else "no drive and wheel meet the limits"
        raise NoWheel(f"no flywheel to draw ({said})", infeasible=True)
    return design.best


def drawing_of_scene(scene: Scene, date: datetime.date | None = None) -> tuple[Drawing, Design]:
    """Solve ``scene`` and describe the drawing of its chosen wheel.

    Raises
    ------
    NoWheel
        No flywheel is needed, or none is feasible: nothing to draw.
    SolverFailed
        The design did not converge (exit 1).
    """
    best = design_of_scene(scene)
    return drawing_of_design(best, scene, date), best


def drawing_of_design(best: Design, scene: Scene, date: datetime.date | None = None) -> Drawing:
    """The manufacturing drawing of a scene's designed wheel (title block from the scene's file): what
    ``flyopt export`` writes and the report shows."""
    from flyopt.outputs.documents import scene_record
    from flyopt.outputs.drawing import drawing_of

    record = scene_record(scene)
    return drawing_of(
        best,
        scene=record["scene"],
        sha256=record["scene_file_sha256"],
        date=date,
        material=scene.material_library()[best.material].display_name,
    )


def drawing_axes(best: Design, scene: Scene) -> Any:
    """The drawing of :func:`drawing_of_design` on its sheet, as the axes of a matplotlib figure (the report's
    diagram: the same drawing as the exported one)."""
    return figure(drawing_of_design(best, scene)).axes[0]


def export(
    scene: Scene | str | os.PathLike[str], output: str | os.PathLike[str], date: datetime.date | None = None
) -> Drawing | Solid:
    """Write the manufacturing drawing of a scene's wheel to ``output``: .dxf, .svg or .pdf by its suffix;
    .step or .stp: its solid (:func:`export_solid`).

    Parameters
    ----------
    scene : Scene or path
        A loaded scene, or its file.
    output : path
        The file to write, atomically; its folder must exist.
    date : datetime.date, optional
        The date in the title block (default: today; not used for STEP).

    Returns
    -------
    Drawing or Solid
        What was drawn; for STEP, the solid as its file reads back.

    Raises
    ------
    SceneError
        A suffix other than .dxf, .svg, .pdf, .step, .stp or a folder that
        does not exist; nothing is written.
    NoWheel
        No wheel to draw; nothing is written.
    ImportError
        A DXF without ezdxf or a STEP without OCP (the ``cad`` extra), said in one line.
    """
    from flyopt.outputs.files import check_folder

    kind = export_format(output)
    if kind == "step":
        return export_solid(scene, output)
    check_folder(output, "-o/--output")
    if kind == "dxf":
        from flyopt.outputs.drawing import require_ezdxf

        require_ezdxf()  # refused before the solve
    from flyopt.io.scene import Scene, load

    loaded = scene if isinstance(scene, Scene) else load(scene)
    drawn, _design = drawing_of_scene(loaded, date)
    write_drawing(drawn, output, kind)
    return drawn


def export_solid(scene: Scene | str | os.PathLike[str], output: str | os.PathLike[str]) -> Solid:
    """Write the solid of a scene's wheel to ``output`` as STEP (mm), atomically, checked by reading it back.

    :func:`flyopt.outputs.solid.write_step`: the wheel as designed (rim, web
    or arms, hub or disc, the bore and the hub's keyway), sharp-edged.

    Returns
    -------
    Solid
        Volume, mass and J about the axis of the file as read back.

    Raises
    ------
    SceneError
        A suffix other than .step or .stp, or a folder that does not exist; nothing is written.
    ImportError
        OCP missing (the ``cad`` extra), said in one line, before the solve.
    NoWheel
        No wheel; nothing is written.
    BrokenInvariant
        The file did not read back as the wheel; nothing is written.
    """
    from flyopt.errors import SceneError
    from flyopt.io.scene import Scene, load
    from flyopt.outputs.files import check_folder
    from flyopt.outputs.solid import require_ocp

    if export_format(output) != "step":
        raise SceneError("-o/--output", f"{str(output)!r} must end in .step or .stp for a solid")
    check_folder(output, "-o/--output")
    require_ocp()  # refused before the solve
    loaded = scene if isinstance(scene, Scene) else load(scene)
    return write_solid(design_of_scene(loaded), loaded, output)


def write_solid(design: Design, scene: Scene, output: str | os.PathLike[str]) -> Solid:
    """Write the solid of ``design``, a wheel of ``scene``, to ``output`` as STEP (its material's density from the scene)."""
    from flyopt.design.materials import get_material
    from flyopt.outputs.solid import write_step

    density = get_material(design.material, scene.material_library()).density
    return write_step(design, output, density, name=f"flywheel ({design.material})")


def write_drawing(drawing: Drawing, output: str | os.PathLike[str], kind: str) -> None:
    """Write ``drawing`` to ``output`` as ``kind`` ("dxf", "svg", "pdf"), atomically."""
    if kind == "dxf":
        from flyopt.outputs.drawing import write_dxf

        write_dxf(drawing, output)
        return
    import io

    import matplotlib

    from flyopt.outputs.files import write_atomically

    fig = figure(drawing)
    buffer = io.BytesIO()
    metadata = {"Title": drawing.title.get("title", "")}
    if kind == "pdf":
        metadata["Creator"] = drawing.title.get("version", "flyopt")
    # texts stay texts (SVG <text>, PDF TrueType): a reader can search and copy the dimensions and the title block
    with matplotlib.rc_context({"svg.fonttype": "none", "pdf.fonttype": 42}):
        fig.savefig(buffer, format=kind, metadata=metadata)
    data = buffer.getvalue()
    write_atomically(output, lambda handle: handle.write(data))
