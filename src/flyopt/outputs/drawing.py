"""The manufacturing drawing of a designed wheel: one geometric description, and its DXF.

:func:`drawing_of` describes the drawing of a :class:`flyopt.design.result.Design`
once: the axial section A–A (cut through the keyway) and a front view, each
line, circle, hatched region, dimension, part name and the title block, in
model millimetres at true size (the wheel's axis on y = 0, the section
centred on x = 0). :func:`write_dxf` writes it with ezdxf (the ``cad``
extra) and :mod:`flyopt.report.drawing` draws the same description with
matplotlib for SVG and PDF, so the files agree.

The sheet is ISO A3 landscape; the scale is the largest of ISO 5455's
reduction scales (1:1, 1:2, 1:5, 1:10, 1:20, 1:50) at which both views fit.
Text heights, gaps and arrow sizes are given on paper [mm] and converted
with the scale, as a drawing office would plot model space.

What the drawing dimensions is what the pattern maker and the machinist
need and nothing twice: the outer, rim-inner and hub diameters, the rim's
and the hub's width, the web's thickness or the arm's section, the bore with
its ISO 286 H7 limits (:func:`flyopt.design.fits.hole_tolerance`) and the
hub's keyway (DIN 6885-1: width b JS9 and depth d + t2, the standard's way
of giving the hub's keyway depth). The rim's radial thickness H follows from
two diameters and is not dimensioned again.

The finish (:func:`finish_of`, every number by the one rule of
:mod:`flyopt.design.castability`): a fillet at each re-entrant junction of the
section (the FE check's rule and radii), a 45 degree chamfer on each machined
edge, the draft of the cast faces and the machined faces' texture. Section
A-A draws them at its scale; details B (the hub) and C (the rim), enlarged
below the views where the sheet has room, carry their dimensions (radius
dimensions, chamfer leaders) and ISO 1302 texture symbols; the notes say the
rule, the draft and that the STEP solid stays sharp-edged.
"""

from __future__ import annotations

import datetime
import io
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from flyopt.design import wheel
from flyopt.design.balance import BALANCE_GRADE
from flyopt.design.fits import hole_tolerance
from flyopt.names import Geometry

if TYPE_CHECKING:
    import os

    from flyopt.design.result import Candidate, Design

__all__ = [
    "CAD_EXTRA",
    "LAYERS",
    "SCALES",
    "SHEET",
    "Arc",
    "Dimension",
    "Drawing",
    "Hatch",
    "Line",
    "Text",
    "Finish",
    "drawing_of",
    "finish_of",
    "finish_rule",
    "keyway",
    "require_ezdxf",
    "section_blocks",
    "size_text",
    "write_dxf",
]

#: The layers of the DXF, and what each holds.
LAYERS = {
    "OUTLINE": "visible outlines of the wheel",
    "CENTER": "the axis and centre lines",
    "HATCH": "hatching of the cut faces",
    "DIMENSIONS": "dimensions and part names",
    "TITLE": "the sheet's border, the title block and notes",
}
#: The sheet, ISO A3 landscape [paper mm]: width, height, border.
SHEET = (420.0, 297.0, 10.0)
#: ISO 5455 reduction scales tried, largest first (paper mm per model mm).
SCALES = (1.0, 0.5, 0.2, 0.1, 0.05, 0.02)
#: The pip extra that brings ezdxf.
CAD_EXTRA = "flyopt[cad]"

#: Paper sizes [mm]: text height of dimensions and names, of the title, of small print; a dimension
#: line's distance from the part and from the next; the arrow's length.
_TEXT, _TITLE_TEXT, _SMALL = 2.5, 5.0, 1.8
_FIRST, _STEP, _ARROW = 8.0, 8.0, 2.5
#: Width of a character in text heights (a rough mean of ISO 3098 type B's letters).
_CHAR = 0.75
#: Title block [paper mm]: width, row height, rows.
_BLOCK_W, _ROW = 180.0, 7.0
#: The smallest step between two faces the front view shows as a line [mm] (the drawing's 0.1 mm).
_SEEN = 0.05
#: Paper between two lines of the notes [mm].
_NOTE_STEP = 3.4
#: Paper left of the section for the part names, right of the front view, between the views.
_LEFT, _RIGHT, _GAP = 62.0, 14.0, 40.0


@dataclass(frozen=True)
class Line:
    """A polyline [model mm] on a layer; ``style`` "solid", "thin" or "chain" (a centre line)."""

    layer: str
    points: tuple[tuple[float, float], ...]
    closed: bool = False
    style: str = "solid"


@dataclass(frozen=True)
class Arc:
    """A circular arc [model mm], angles in degrees counter-clockwise from +x (0, 360: a circle)."""

    layer: str
    center: tuple[float, float]
    radius: float
    start: float = 0.0
    end: float = 360.0
    style: str = "solid"


@dataclass(frozen=True)
class Hatch:
    """A cut face [model mm]: a closed boundary, hatched at 45 degrees."""

    boundary: tuple[tuple[float, float], ...]
    layer: str = "HATCH"


@dataclass(frozen=True)
class Text:
    """A text [model mm]: its anchor, height, alignment ("left", "center", "right") and rotation [deg]."""

    layer: str
    at: tuple[float, float]
    text: str
    height: float
    align: str = "left"
    rotation: float = 0.0


@dataclass(frozen=True)
class Dimension:
    """A dimension of the drawing [model mm].

    Attributes
    ----------
    name : str
        What it measures, by the Design's name: ``d_outer``, ``d_inner``,
        ``d_hub``, ``bore``, ``b``, ``t_web``, ``l_hub``, ``arm_major``,
        ``arm_minor``, ``key_width``, ``key_depth`` (bore + t2).
    words : str
        The same in words ("outer diameter").
    kind : {"linear", "diameter", "radius", "chamfer"}
        A linear dimension measures ``p1`` to ``p2`` along x (``angle`` 0) or y
        (90); a diameter dimension measures a circle about ``p1`` through
        ``p2`` (both ends of the line are on the circle); a radius dimension
        an arc about ``p1`` through ``p2`` (a fillet); a chamfer is a leader
        from ``p1`` to the chamfer's middle ``p2``, its size in its text.
    p1, p2 : (float, float)
    base : (float, float)
        A point the dimension line runs through (linear).
    angle : float
    value : float
        The measurement [mm].
    prefix : str
        "Ø" for a diameter, "R" for a radius.
    fit : str or None
        ISO 286 class; ``upper``, ``lower`` its limit deviations [mm].
    lfac : float
        The size over the drawn length: 1 on the views, 1 / enlargement in a detail (DXF DIMLFAC).
    text_at : (float, float)
        The middle of the text; for a radius and a chamfer, its left end.
    """

    name: str
    words: str
    kind: str
    p1: tuple[float, float]
    p2: tuple[float, float]
    base: tuple[float, float]
    angle: float
    value: float
    text_at: tuple[float, float]
    prefix: str = ""
    fit: str | None = None
    upper: float = 0.0
    lower: float = 0.0
    lfac: float = 1.0

    @property
    def text(self) -> str:
        """The dimension's text as drawn: prefix, size to 0.1 mm, class and limits; a chamfer's "1.6 × 45°"."""
        if self.kind == "chamfer":
            return f"{size_text(self.value)} × 45°"
        out = f"{self.prefix}{size_text(self.value)}"
        if self.fit and self.upper == -self.lower:
            out += f" {self.fit} (±{_deviation(self.upper)[1:]})"
        elif self.fit:
            out += f" {self.fit} ({_deviation(self.upper)}/{_deviation(self.lower)})"
        return out

    @property
    def vertical(self) -> bool:
        """Measured along y."""
        return self.kind == "linear" and self.angle == 90.0


@dataclass(frozen=True)
class Drawing:
    """The drawing of one wheel: every item in model mm, the scale, the sheet and the title block's fields.

    Attributes
    ----------
    scale : float
        Paper mm per model mm (0.2: 1:5).
    sheet : (float, float, float, float)
        The sheet's border in model mm: x_min, y_min, x_max, y_max (the paper's edge).
    lines, arcs, hatches, texts, dimensions : tuple
    title : dict of str
        The title block's fields by name (``title``, ``material``, ``mass``,
        ``inertia``, ``balance``, ``scale``, ``date``, ``version``, ``scene``,
        ``sha256``, ``units``).
    """

    scale: float
    sheet: tuple[float, float, float, float]
    lines: tuple[Line, ...] = ()
    arcs: tuple[Arc, ...] = ()
    hatches: tuple[Hatch, ...] = ()
    texts: tuple[Text, ...] = ()
    dimensions: tuple[Dimension, ...] = ()
    title: dict[str, str] = field(default_factory=dict)

    @property
    def scale_text(self) -> str:
        """ "1:5" (or "2:1")."""
        return f"1:{1 / self.scale:g}" if self.scale <= 1 else f"{self.scale:g}:1"


def size_text(mm: float) -> str:
    """A size [mm] as the drawing writes it: to 0.1 mm, no trailing zero ("719.8", "55")."""
    return f"{mm:.1f}".rstrip("0").rstrip(".")


def _deviation(mm):
    """A limit deviation [mm] to three decimals at least, as ISO 286 tables give them: "+0.030", "-0.0215", "0"."""
    if mm == 0:
        return "0"
    text = f"{mm:+.4f}"
    return text[:-1] if text.endswith("0") else text


class _Builder:
    """Collects the items of a drawing; ``p(paper mm)`` is the length in model mm."""

    def __init__(self, scale):
        self.scale = scale
        self.lines, self.arcs, self.hatches, self.texts, self.dimensions = [], [], [], [], []

    def p(self, paper):
        return paper / self.scale

    def line(self, layer, points, closed=False, style="solid"):
        self.lines.append(Line(layer, tuple((float(x), float(y)) for x, y in points), closed, style))

    def text(self, layer, at, text, height=_TEXT, align="left", rotation=0.0):
        self.texts.append(Text(layer, (float(at[0]), float(at[1])), text, self.p(height), align, rotation))

    def width(self, text, height=_TEXT):
        """The width of a text on the sheet, in model mm (an estimate, generous)."""
        return self.p(height * _CHAR * len(text))

    def linear(self, name, words, p1, p2, line, vertical, text_side=0.0, **fit):
        """A linear dimension from ``p1`` to ``p2`` whose line runs at ``line`` across the measured axis.

        ``text_side`` 0: the text in the middle of the line, on its outer side
        (a vertical one reads from the right, left of its line); -1 or +1: the
        text beyond the lower or upper end of the line (where it does not fit
        between the extension lines).
        """
        axis = 1 if vertical else 0
        lo, hi = sorted((p1[axis], p2[axis]))
        value = hi - lo
        dim = Dimension(name, words, "linear", p1, p2, (0, 0), 90.0 if vertical else 0.0, value, (0, 0), **fit)
        half = self.width(dim.text) / 2.0
        gap = self.p(1.0 + _TEXT / 2.0)
        if text_side == 0.0:
            along, across = 0.5 * (lo + hi), line - gap if vertical else line + gap
        elif text_side > 0:
            along, across = hi + self.p(_ARROW + 2.0) + half, line
        else:
            along, across = lo - self.p(_ARROW + 2.0) - half, line
        if vertical:
            base, text_at = (line, lo), (across, along)
        else:
            base, text_at = (lo, line), (along, across)
        self.dimensions.append(
            Dimension(
                name,
                words,
                "linear",
                p1,
                p2,
                base,
                dim.angle,
                value,
                (float(text_at[0]), float(text_at[1])),
                **fit,
            )
        )


def section_blocks(design: Candidate) -> tuple[list[tuple[str, float, float, float]], tuple[float, ...] | None]:
    """The axial section of a designed wheel, as every drawing of it takes it [m].

    Returns
    -------
    blocks : list of (part, r_inner, r_outer, axial width)
        The centred blocks of the half-section, inner first: "hub", "web",
        "rim" or "disc" (a bare rim is one "rim"; a web wheel without a bore
        is solid to the axis).
    arms : (r_inner, r_outer, major, minor) or None
        The arms of a ``rim_arms`` wheel: from the hub to the rim, of
        elliptical section (major along the circumference).
    """
    dims = design.dims
    if dims is None:
        raise ValueError(f"{design.material} on {design.shaft} is not a design: nothing to draw")
    # the parts as the design counts them (one decision: flyopt.design.wheel.parts), the arms apart
    parts = wheel.parts(design.geometry, dims.wheel(design.n_arms, design.bore), 1.0)
    blocks = [(p.name, float(p.r_inner), float(p.r_outer), float(p.thickness)) for p in parts if p.name != "arms"]
    if design.geometry == Geometry.RIM_ARMS and dims.d_hub and dims.arm_major and dims.arm_minor:
        return blocks, (dims.d_hub / 2.0, dims.d_inner / 2.0, dims.arm_major, dims.arm_minor)
    return blocks, None


def keyway(design: Candidate) -> tuple[float, float]:
    """The hub's keyway of a designed wheel, (width b, depth t2) [m] of its DIN 6885-1 key; (0, 0): none."""
    key = design.parts.key if design.parts else None
    if not key or not design.bore:
        return 0.0, 0.0
    return float(key["b"]), float(key["t2"])


def _blocks(design):
    """:func:`section_blocks` in mm."""
    blocks, arms = section_blocks(design)
    return [(name, *(v * 1e3 for v in rest)) for name, *rest in blocks], (
        tuple(v * 1e3 for v in arms) if arms else None
    )


def _groups(blocks):
    """Blocks that touch, one outline each."""
    out = [[blocks[0]]]
    for block in blocks[1:]:
        if math.isclose(block[1], out[-1][-1][2], rel_tol=1e-9, abs_tol=1e-9):
            out[-1].append(block)
        else:
            out.append([block])
    return out


def _upper_outline(group, r_start):
    """The closed outline of touching centred blocks in the upper half, its inner edge at ``r_start``."""
    right = []
    for index, (_name, r0, r1, w) in enumerate(group):
        right += [(w / 2.0, r_start if index == 0 else r0), (w / 2.0, r1)]
    return right + [(-x, y) for x, y in reversed(right)]


def _ellipse(center, major, minor, n=72):
    """An ellipse as a closed polygon: ``major`` along y, ``minor`` along x."""
    return tuple(
        (center[0] + minor / 2.0 * math.cos(t), center[1] + major / 2.0 * math.sin(t))
        for t in (2 * math.pi * k / n for k in range(n))
    )


# ---------------------------------------------------------------------------
# The section's outline with its fillets and chamfers
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Finish:
    """The fillets, chamfers, draft and surface texture a drawing gives a wheel [model mm, deg, um].

    Attributes
    ----------
    fillets : dict of str to float
        Fillet radius by junction ("hub-web", "web-rim", "hub-arms", "arms-rim"), each
        :func:`flyopt.design.castability.fillet_radius` of the drawn parts (0: the parts are as thick).
    chamfers : dict of str to float
        45 degree chamfer by edge ("rim": the rim's (or disc's) outer edges, "hub": the hub's end faces at
        their outside, "bore": the bore's entry), :func:`flyopt.design.castability.chamfer_size`.
    process : str or None
        The process the numbers are of (:func:`flyopt.design.castability.process_of_design`).
    ratio, min_fillet : float
        The fillet rule: its ratio to the thinner part [-] and the process's smallest fillet [mm].
    draft : float or None
        Draft of the cast faces parallel to the axis [deg]; None: not cast, or the process is not known.
    machined_ra, bore_ra : float
        Ra of the machined faces and of the bore [um].
    """

    fillets: dict[str, float]
    chamfers: dict[str, float]
    process: str | None
    ratio: float
    min_fillet: float
    draft: float | None
    machined_ra: float
    bore_ra: float


def finish_of(design: Candidate) -> Finish:
    """The fillets, chamfers, draft and texture of a designed wheel's drawing (model mm), by the one rule
    of each (:mod:`flyopt.design.castability`; the FE check's section takes the same fillets)."""
    from flyopt.design import castability

    rules = castability.finishing(castability.process_of_design(design))
    blocks, arms = _blocks(design)
    fillets: dict[str, float] = {}
    for inner, outer in zip(blocks, blocks[1:]):
        if not math.isclose(inner[2], outer[1], rel_tol=1e-9, abs_tol=1e-9):
            continue
        thin = inner if inner[3] < outer[3] else outer
        fillets[f"{inner[0]}-{outer[0]}"] = 1e3 * castability.fillet_radius(
            rules, inner[3] * 1e-3, outer[3] * 1e-3, (thin[2] - thin[1]) * 1e-3
        )
    if arms:  # the arm's section as the section shows it: its minor axis across the wheel
        r0, r1, _major, minor = arms
        for name, part in (("hub-arms", blocks[0]), ("arms-rim", blocks[-1])):
            # an arm as wide as the part or wider makes no re-entrant corner with it
            fillets[name] = (
                1e3 * castability.fillet_radius(rules, minor * 1e-3, part[3] * 1e-3, (r1 - r0) * 1e-3)
                if minor < part[3]
                else 0.0
            )
    chamfers: dict[str, float] = {}
    outer = blocks[-1]
    r_o = outer[2]
    chamfers["rim"] = 1e3 * castability.chamfer_size(2e-3 * r_o, 1e-3 * min(outer[3], r_o - outer[1]))
    if blocks[0][0] == "hub":
        _n, r_b, r_h, l_hub = blocks[0]
        wall = min(r_h - r_b, l_hub)
        chamfers["hub"] = 1e3 * castability.chamfer_size(2e-3 * r_h, 1e-3 * wall)
        chamfers["bore"] = 1e3 * castability.chamfer_size(2e-3 * r_b, 1e-3 * wall)
    elif blocks[0][0] == "disc" and blocks[0][1] > 0:  # a bored disc
        chamfers["bore"] = 1e3 * castability.chamfer_size(
            2e-3 * blocks[0][1], 1e-3 * min(blocks[0][3], r_o - blocks[0][1])
        )
    return Finish(
        fillets,
        chamfers,
        rules.process,
        rules.fillet_ratio,
        rules.min_fillet * 1e3,
        rules.draft,
        round(rules.machined_ra * 1e6, 6),
        round(rules.bore_ra * 1e6, 6),
    )


_EPS = 1e-9


def _clean(points):
    """A closed polygon without repeated points and without vertices on a straight run."""
    pts: list[tuple[float, float]] = []
    for p in points:
        if not pts or math.dist(p, pts[-1]) > _EPS:
            pts.append(p)
    if len(pts) > 1 and math.dist(pts[0], pts[-1]) <= _EPS:
        pts.pop()
    changed = True
    while changed and len(pts) > 3:
        changed = False
        for i in range(len(pts)):
            a, v, b = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            if abs((v[0] - a[0]) * (b[1] - v[1]) - (v[1] - a[1]) * (b[0] - v[0])) <= _EPS * max(1.0, math.dist(a, b)):
                del pts[i]
                changed = True
                break
    return pts


def _unit(a, b):
    d = math.dist(a, b)
    return ((b[0] - a[0]) / d, (b[1] - a[1]) / d)


def _arc_item(center, radius, a, b):
    """("arc", centre, radius, start, end) [deg] of the quarter from ``a`` to ``b`` (either way round),
    counter-clockwise from start to end as DXF draws it."""
    t_a = math.degrees(math.atan2(a[1] - center[1], a[0] - center[0]))
    t_b = math.degrees(math.atan2(b[1] - center[1], b[0] - center[0]))
    if (t_b - t_a) % 360.0 > 180.0:
        t_a, t_b = t_b, t_a
    start = t_a % 360.0
    return ("arc", center, radius, start, start + (t_b - t_a) % 360.0)


def _corner_path(points, treat):
    """The closed outline through ``points`` with its corners treated: a list of ("line", a, b) and
    ("arc", centre, radius, start, end) in path order.

    ``treat(vertex, concave)`` gives ("fillet", r), ("chamfer", c) or None for each corner; a fillet is
    tangent to both edges, a chamfer cuts ``c`` off each (45 degrees at a right angle).
    """
    pts = _clean(points)
    n = len(pts)
    area = sum(pts[i - 1][0] * pts[i][1] - pts[i][0] * pts[i - 1][1] for i in range(n))
    turn = 1.0 if area > 0 else -1.0
    cuts = []
    for i in range(n):
        prev, v, nxt = pts[i - 1], pts[i], pts[(i + 1) % n]
        u, w = _unit(prev, v), _unit(v, nxt)
        concave = (u[0] * w[1] - u[1] * w[0]) * turn < 0
        what = treat(v, concave)
        if not what or what[1] <= 0:
            cuts.append((v, v, None))
            continue
        kind, size = what
        a = (v[0] - u[0] * size, v[1] - u[1] * size)
        b = (v[0] + w[0] * size, v[1] + w[1] * size)
        if kind == "fillet":
            item = _arc_item((a[0] + w[0] * size, a[1] + w[1] * size), size, a, b)
        else:
            item = ("line", a, b)
        cuts.append((a, b, item))
    out = []
    for i in range(n):
        _a, b, item = cuts[i]
        if item:
            out.append(item)
        following = cuts[(i + 1) % n][0]
        if math.dist(b, following) > _EPS:
            out.append(("line", b, following))
    return out


def _arc_points(item, n=8):
    _kind, c, r, start, end = item
    return [
        (c[0] + r * math.cos(math.radians(t)), c[1] + r * math.sin(math.radians(t)))
        for t in (start + (end - start) * j / n for j in range(n + 1))
    ]


def _polygon(path):
    """The outline as a polygon (arcs as chords) for its hatch, in path order."""
    out: list[tuple[float, float]] = []
    for item in path:
        if item[0] == "line":
            pts = [item[1], item[2]]
        else:
            pts = _arc_points(item)
            if out and math.dist(out[-1], pts[-1]) < math.dist(out[-1], pts[0]):
                pts.reverse()
        for p in pts:
            if not out or math.dist(p, out[-1]) > _EPS:
                out.append(p)
    if len(out) > 1 and math.dist(out[0], out[-1]) <= _EPS:
        out.pop()
    return tuple(out)


def _emit(k, path, closed, layer="OUTLINE"):
    """Add a path's items to the drawing: runs of lines as one polyline each, arcs as ARCs."""
    run: list[tuple[float, float]] = []
    lines = []
    for item in path:
        if item[0] == "line":
            if run and math.dist(run[-1], item[1]) <= _EPS:
                run.append(item[2])
            else:
                if run:
                    lines.append(run)
                run = [item[1], item[2]]
        else:
            if run:
                lines.append(run)
            run = []
            _kind, c, r, start, end = item
            k.arcs.append(Arc(layer, (float(c[0]), float(c[1])), float(r), float(start), float(end)))
    if run:
        lines.append(run)
    if closed and not any(item[0] == "arc" for item in path) and len(lines) == 1:
        k.line(layer, lines[0][:-1], closed=True)
        return
    if closed and len(lines) > 1 and path[0][0] == "line" and path[-1][0] == "line":
        lines[0] = lines[-1] + lines[0][1:]  # the run through the path's start is one polyline
        lines.pop()
    for run in lines:
        k.line(layer, run)


def _section_shapes(blocks, arms, t2, finish):
    """The section's outlines [model mm]: (path, closed, hatched) of each cut face's upper and lower half
    (fillets at the re-entrant junctions, chamfers on the machined edges) and the uncut arms' edges."""
    r_o = blocks[-1][2]
    r_bore = blocks[0][1] if blocks[0][0] in ("hub", "disc") else 0.0  # a bare rim's inside is no bore
    hub = blocks[0] if blocks[0][0] == "hub" else None
    b_out = blocks[-1][3]
    fillet_at = {}  # the radius of a junction by the radius it is at
    for inner, outer in zip(blocks, blocks[1:]):
        name = f"{inner[0]}-{outer[0]}"
        if finish.fillets.get(name):
            fillet_at[outer[1]] = finish.fillets[name]

    def near(a, b):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-6)

    def treat(v, concave):
        x, y = abs(v[0]), abs(v[1])
        if concave:
            for r, f in fillet_at.items():
                if near(y, r):
                    return ("fillet", f)
            return None
        if near(y, r_o) and near(x, b_out / 2.0):
            return ("chamfer", finish.chamfers.get("rim", 0.0))
        if hub and near(y, hub[2]) and near(x, hub[3] / 2.0):
            return ("chamfer", finish.chamfers.get("hub", 0.0))
        if r_bore > 0 and near(y, r_bore) and near(x, blocks[0][3] / 2.0):
            return ("chamfer", finish.chamfers.get("bore", 0.0))
        return None

    shapes = []
    for group in _groups(blocks):
        r_start = group[0][1] + (t2 if group[0] is blocks[0] else 0.0)  # the keyway is in the bore's block
        upper = _upper_outline(group, r_start)
        lower = [(x, -y) for x, y in _upper_outline(group, group[0][1])]
        if group[0][1] > 0:
            halves = [upper, lower]
        else:  # solid to the centre: one face, no line on the axis
            right_u = upper[: len(upper) // 2]
            side = [(x, -y) for x, y in reversed(right_u)] + right_u[1:]
            halves = [side + [(-x, y) for x, y in reversed(side)]]
        for outline in halves:
            shapes.append((_corner_path(outline, treat), True, True))
    if arms:  # arms are not cut (drafting rule for spokes): their edges, filleted into the hub and the rim
        r0, r1, _major, minor = arms
        f_hub, f_rim = finish.fillets.get("hub-arms", 0.0), finish.fillets.get("arms-rim", 0.0)
        for sign in (1, -1):
            for side in (1, -1):
                x = side * minor / 2
                path = []
                if f_hub:
                    a, b = (x, sign * (r0 + f_hub)), (x + side * f_hub, sign * r0)
                    path.append(_arc_item((x + side * f_hub, sign * (r0 + f_hub)), f_hub, a, b))
                path.append(("line", (x, sign * (r0 + f_hub)), (x, sign * (r1 - f_rim))))
                if f_rim:
                    a, b = (x, sign * (r1 - f_rim)), (x + side * f_rim, sign * r1)
                    path.append(_arc_item((x + side * f_rim, sign * (r1 - f_rim)), f_rim, a, b))
                shapes.append((path, False, False))
    return shapes


# ---------------------------------------------------------------------------
# Details: a window of the section enlarged, with the fillets' and chamfers' dimensions
# ---------------------------------------------------------------------------

#: Scales of a detail view (paper mm per model mm), largest first (ISO 5455 enlargement and full size).
DETAIL_SCALES = (10.0, 5.0, 2.0, 1.0, 0.5)


def _clip_segment(a, b, box):
    """The part of segment a-b inside box (x0, y0, x1, y1) (Liang-Barsky), or None."""
    x0, y0, x1, y1 = box
    dx, dy = b[0] - a[0], b[1] - a[1]
    t0, t1 = 0.0, 1.0
    for p, q in ((-dx, a[0] - x0), (dx, x1 - a[0]), (-dy, a[1] - y0), (dy, y1 - a[1])):
        if abs(p) < 1e-15:
            if q < 0:
                return None
            continue
        t = q / p
        if p < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return None
    return (a[0] + t0 * dx, a[1] + t0 * dy), (a[0] + t1 * dx, a[1] + t1 * dy)


def _clip_polygon(points, box):
    """A polygon clipped to box (Sutherland-Hodgman against its four edges)."""
    x0, y0, x1, y1 = box
    out = list(points)
    for inside, cut in (
        (lambda p: p[0] >= x0, lambda a, b: (x0, a[1] + (b[1] - a[1]) * (x0 - a[0]) / (b[0] - a[0]))),
        (lambda p: p[0] <= x1, lambda a, b: (x1, a[1] + (b[1] - a[1]) * (x1 - a[0]) / (b[0] - a[0]))),
        (lambda p: p[1] >= y0, lambda a, b: (a[0] + (b[0] - a[0]) * (y0 - a[1]) / (b[1] - a[1]), y0)),
        (lambda p: p[1] <= y1, lambda a, b: (a[0] + (b[0] - a[0]) * (y1 - a[1]) / (b[1] - a[1]), y1)),
    ):
        pts, out = out, []
        for i, p in enumerate(pts):
            prev = pts[i - 1]
            if inside(p):
                if not inside(prev):
                    out.append(cut(prev, p))
                out.append(p)
            elif inside(prev):
                out.append(cut(prev, p))
        if not out:
            return ()
    return tuple(out)


@dataclass(frozen=True)
class _Detail:
    """A detail view: its letter, the window of the section it shows [model mm], where it goes on the
    sheet (the window's centre there), its enlargement over the section (``factor``) and the part of the
    window it is about (``core``, marked on the section)."""

    letter: str
    window: tuple[float, float, float, float]
    at: tuple[float, float]
    factor: float
    core: tuple[float, float, float, float]

    def map(self, p):
        x0, y0, x1, y1 = self.window
        cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        return (self.at[0] + self.factor * (p[0] - cx), self.at[1] + self.factor * (p[1] - cy))


def _draw_detail(k, detail, shapes):
    """The section's items inside the detail's window, enlarged and moved to its place."""
    box = detail.window
    for path, _closed, hatched in shapes:
        if hatched:
            clipped = _clip_polygon(_polygon(path), box)
            if len(clipped) >= 3:
                k.hatches.append(Hatch(tuple(detail.map(p) for p in clipped)))
        for item in path:
            if item[0] == "arc":
                pts = _arc_points(item, 16)
                inside = [box[0] <= x <= box[2] and box[1] <= y <= box[3] for x, y in pts]
                if all(inside):
                    _kind, c, r, start, end = item
                    k.arcs.append(Arc("OUTLINE", detail.map(c), r * detail.factor, start, end))
                    continue
                segments = list(zip(pts, pts[1:]))
            else:
                segments = [(item[1], item[2])]
            for a, b in segments:
                part = _clip_segment(a, b, box)
                if part and math.dist(*part) > _EPS:
                    k.line("OUTLINE", [detail.map(part[0]), detail.map(part[1])])
    # where the window cuts a face: a thin break line
    x0, y0, x1, y1 = box
    for path, _closed, hatched in shapes:
        if not hatched:
            continue
        clipped = _clip_polygon(_polygon(path), box)
        for a, b in zip(clipped, clipped[1:] + clipped[:1]):
            on_edge = (math.isclose(a[0], b[0]) and any(math.isclose(a[0], e) for e in (x0, x1))) or (
                math.isclose(a[1], b[1]) and any(math.isclose(a[1], e) for e in (y0, y1))
            )
            if on_edge and math.dist(a, b) > _EPS:
                k.line("OUTLINE", [detail.map(a), detail.map(b)], style="thin")
    # its name above
    k.text(
        "DIMENSIONS",
        (detail.at[0], detail.map((x0, y1))[1] + k.p(3.0)),
        f"DETAIL {detail.letter}  {_scale_text(detail.factor * k.scale)}",
        height=3.5,
        align="center",
    )
    # its mark on the section: a thin circle about what it shows, the letter outside it, away from the axis
    c0, c1, c2, c3 = detail.core
    cx, cy = 0.5 * (c0 + c2), 0.5 * (c1 + c3)
    radius = 0.5 * math.hypot(c2 - c0, c3 - c1) + k.p(1.5)
    k.arcs.append(Arc("DIMENSIONS", (cx, cy), radius, style="thin"))
    if cy >= 0:  # above the axis: at the circle's upper left
        letter_at = (cx - radius * 0.75 - k.p(1.0), cy + radius * 0.75)
    else:  # below it: at its left, clear of the axis and of the hub's length below
        letter_at = (cx - radius - k.p(1.5), cy - k.p(1.75))
    k.text("DIMENSIONS", letter_at, detail.letter, height=3.5, align="right")


def _scale_text(scale):
    """ "1:5" or "2:1"."""
    return f"1:{1 / scale:g}" if scale < 1 else f"{scale:g}:1"


def _fillet_dim(k, detail, name, words, corner, air, radius):
    """A radius dimension of the fillet at ``corner`` whose air side is the diagonal ``air`` (+-1, +-1),
    drawn in ``detail``: its text beyond the fillet's centre, on the air side."""
    centre = (corner[0] + air[0] * radius, corner[1] + air[1] * radius)
    angle = math.degrees(math.atan2(-air[1], -air[0]))
    c = detail.map(centre)
    on_arc = (
        c[0] - air[0] * radius * detail.factor / math.sqrt(2),
        c[1] - air[1] * radius * detail.factor / math.sqrt(2),
    )
    reach = k.p(7.0)
    text_at = (on_arc[0] + air[0] * reach, on_arc[1] + air[1] * reach)
    if air[0] < 0:  # the text ends at the leader
        text_at = (text_at[0] - k.width(f"R{size_text(radius)}"), text_at[1])
    k.dimensions.append(
        Dimension(
            name,
            words,
            "radius",
            c,
            on_arc,
            c,
            angle,
            radius,
            (float(text_at[0]), float(text_at[1])),
            prefix="R",
            lfac=1.0 / detail.factor,
        )
    )


def _chamfer_dim(k, detail, name, words, corner, air, size):
    """A leader to the chamfer ``size`` x 45 deg at ``corner`` (air side ``air``), in ``detail``."""
    mid = detail.map((corner[0] - air[0] * size / 2.0, corner[1] - air[1] * size / 2.0))
    reach = k.p(6.0)
    elbow = (mid[0] + air[0] * reach, mid[1] + air[1] * reach)
    text_x = elbow[0] + k.p(0.5) if air[0] > 0 else elbow[0] - k.p(0.5) - k.width(f"{size_text(size)} × 45°")
    k.dimensions.append(
        Dimension(
            name,
            words,
            "chamfer",
            elbow,
            mid,
            elbow,
            45.0,
            size,
            (float(text_x), float(elbow[1])),
            lfac=1.0 / detail.factor,
        )
    )


#: ISO 1302 symbol for text height 2.5 [paper mm]: the short and the long leg's heights.
_H1, _H2 = 3.5, 7.5


def _texture_symbol(k, point, normal, ra):
    """ISO 1302's symbol 'material removal required' standing on a face at ``point`` (sheet
    coordinates), its tip on the face, upright along the face's outward ``normal``; its Ra [um] beside it."""
    theta = math.atan2(normal[1], normal[0]) - math.pi / 2.0
    c, s = math.cos(theta), math.sin(theta)

    def to(x, y):  # paper mm about the tip, rotated
        return (point[0] + k.p(x * c - y * s), point[1] + k.p(x * s + y * c))

    tan60 = math.tan(math.radians(60.0))
    short, long_ = (-_H1 / tan60, _H1), (_H2 / tan60, _H2)
    k.line("DIMENSIONS", [to(*short), to(0.0, 0.0), to(*long_), to(long_[0] + 6.5, _H2)], style="thin")
    k.line("DIMENSIONS", [to(*short), to(_H1 / tan60, _H1)], style="thin")  # the bar: material removed
    k.text(
        "DIMENSIONS",
        to(long_[0] - 0.3, _H2 - 2.5 - 0.8),
        f"Ra {ra:g}",
        height=_TEXT * 0.8,
        rotation=math.degrees(theta),
    )


def _detail_items(blocks, arms, finish):
    """The details a drawing office would add: (letter, core window [model mm], fillets, chamfers, textures)
    with each fillet and chamfer as (name, words, corner, air side, size) and each texture as
    (point, outward normal, Ra [um])."""
    out = []
    r_o = blocks[-1][2]
    rim = blocks[-1]
    b_half = rim[3] / 2.0
    hub = blocks[0] if blocks[0][0] == "hub" else None
    thin = arms[3] if arms else next((w for name, _r0, _r1, w in blocks if name == "web"), 0.0)  # 0: none
    if hub:
        _n, r_b, r_h, l_hub = hub
        f_hub = finish.fillets.get("hub-arms" if arms else "hub-web", 0.0)
        stub = 1.6 * f_hub + 0.2 * (r_h - r_b)  # the web or arm below the hub: its fillet and a little more
        fillets = [("fillet_hub", "fillet, hub to " + ("arm" if arms else "web"), (thin / 2.0, -r_h), (1, -1), f_hub)]
        fillets = fillets if thin else []
        chamfers = [
            ("chamfer_hub", "chamfer, hub's ends", (l_hub / 2.0, -r_h), (1, -1), finish.chamfers.get("hub", 0.0)),
            (
                "chamfer_bore",
                "chamfer, the bore's entry",
                (-l_hub / 2.0, -r_b),
                (-1, 1),
                finish.chamfers.get("bore", 0.0),
            ),
        ]
        textures = [
            ((-l_hub / 2.0, -(r_b + 0.65 * (r_h - r_b))), (-1, 0), finish.machined_ra),
            ((l_hub / 4.0, -r_b), (0, 1), finish.bore_ra),
        ]
        out.append(("B", (-l_hub / 2.0, -(r_h + stub), l_hub / 2.0, -r_b), fillets, chamfers, textures))
    elif blocks[0][0] == "disc" and blocks[0][1] > 0:  # a bored disc
        _n, r_b, _r1, w = blocks[0]
        depth = min(2.0 * w, r_o - r_b)
        chamfers = [
            ("chamfer_bore", "chamfer, the bore's entry", (-w / 2.0, -r_b), (-1, 1), finish.chamfers.get("bore", 0.0))
        ]
        textures = [((w / 4.0, -r_b), (0, 1), finish.bore_ra)]
        out.append(("B", (-w / 2.0, -(r_b + depth), w / 2.0, -r_b), [], chamfers, textures))
    f_rim = finish.fillets.get("arms-rim" if arms else "web-rim", 0.0)
    r_in = rim[1]
    depth = (rim[2] - rim[1]) if rim[0] == "rim" else min(2.0 * rim[3], r_o - r_in)
    low = r_o - depth - ((1.6 * f_rim + 0.3 * depth) if thin and rim[0] == "rim" else 0.0)
    fillets = (
        [("fillet_rim", "fillet, rim to " + ("arm" if arms else "web"), (thin / 2.0, r_in), (1, -1), f_rim)]
        if thin
        else []
    )
    chamfers = [("chamfer_rim", "chamfer, rim's outer edges", (-b_half, r_o), (-1, 1), finish.chamfers.get("rim", 0.0))]
    textures = [
        ((-b_half / 2.0, r_o), (0, 1), finish.machined_ra),
        ((-b_half, r_o - 0.65 * depth), (-1, 0), finish.machined_ra),
    ]
    out.append(("C", (-b_half, low, b_half, r_o), fillets, chamfers, textures))
    return out


def _details(k, shapes, blocks, arms, finish, region):
    """Draw the details in ``region`` (x0, y0, x1, y1, sheet coordinates): each enlarged to the largest of
    :data:`DETAIL_SCALES` at which it fits its share, with the fillets' and chamfers' dimensions and the
    machined faces' texture symbols. Returns the letters drawn."""
    items = _detail_items(blocks, arms, finish)
    x0, y0, x1, y1 = region
    share = (x1 - x0) / len(items)
    pad, pad_v = k.p(10.0), k.p(8.0)  # room for the leaders' texts beside and the symbols above and below
    drawn = []
    for index, (letter, core, fillets, chamfers, textures) in enumerate(items):
        width, height = core[2] - core[0], core[3] - core[1]
        room_w, room_h = share - 2 * pad, (y1 - y0) - 2 * pad_v - k.p(6.0)
        factor = next(
            (m / k.scale for m in DETAIL_SCALES if width * m / k.scale <= room_w and height * m / k.scale <= room_h),
            None,
        )
        if factor is None or factor < 1.5:
            continue  # no room, or the section shows it as large already
        mx, my = pad / factor, pad_v / factor
        window = (core[0] - mx, core[1] - my, core[2] + mx, core[3] + my)
        centre = (x0 + share * (index + 0.5), y0 + 0.5 * (y1 - y0 - k.p(6.0)))
        detail = _Detail(letter, window, centre, factor, core)
        _draw_detail(k, detail, shapes)
        for name, words, corner, air, size in fillets:
            if size > 0:
                _fillet_dim(k, detail, name, words, corner, air, size)
        for name, words, corner, air, size in chamfers:
            if size > 0:
                _chamfer_dim(k, detail, name, words, corner, air, size)
        for point, normal, ra in textures:
            _texture_symbol(k, detail.map(point), normal, ra)
        drawn.append(letter)
    return drawn


def _scale_for(width, height):
    """The largest ISO 5455 scale at which a content ``width`` x ``height`` [model mm] and its margins fit."""
    sheet_w, sheet_h, border = SHEET
    for scale in SCALES:
        room_w = sheet_w - 2 * border - _LEFT - _RIGHT - _GAP - 40.0  # the right-hand diameters
        room_h = sheet_h - 2 * border - 6 * _ROW - 2 * (_FIRST + 14.0)  # the block, the dimensions
        if width * scale <= room_w and height * scale <= room_h:
            return scale
    return SCALES[-1]


def drawing_of(
    design: Design,
    *,
    scene: str | None = None,
    sha256: str | None = None,
    version: str | None = None,
    date: datetime.date | None = None,
    material: str | None = None,
) -> Drawing:
    """The manufacturing drawing of a designed wheel (model mm, true size).

    Parameters
    ----------
    design : flyopt.design.result.Design
    scene : str, optional
        The scene file the design came from, named in the title block.
    sha256 : str, optional
        The scene file's SHA-256 (:func:`flyopt.outputs.documents.scene_record`).
    version : str, optional
        flyopt's version (default: :data:`flyopt.__version__`).
    date : datetime.date, optional
        The drawing's date (default: today).
    material : str, optional
        The material's name for people (:attr:`flyopt.design.materials.Material.display_name`); default: the
        design's material key with spaces.

    Returns
    -------
    Drawing

    Raises
    ------
    ValueError
        ``design`` is not a feasible design, or its bore is beyond ISO 286's table.
    """
    from flyopt.design.result import Design

    if not isinstance(design, Design):
        raise ValueError(f"{design.material} on {design.shaft} is not a design: nothing to draw")
    if version is None:
        import flyopt

        version = flyopt.__version__
    date = date or datetime.date.today()
    blocks, arms = _blocks(design)
    r_o = design.dims.d_outer * 500.0
    w_max = max([w for *_x, w in blocks] + ([arms[3]] if arms else []))
    scale = _scale_for(w_max + 2 * r_o, 2 * r_o)
    k = _Builder(scale)
    p = k.p
    key = design.parts.key if design.parts else None
    r_bore = (design.bore or 0.0) * 500.0
    b_key, t2 = (v * 1e3 for v in keyway(design))

    # --- section A-A: the upper half cut through the keyway, the lower half through solid hub
    finish = finish_of(design)
    shapes = _section_shapes(blocks, arms, t2, finish)
    for path, closed, hatched in shapes:
        _emit(k, path, closed)
        if hatched:
            k.hatches.append(Hatch(_polygon(path)))
    if t2:  # the bore's edge behind the keyway, seen through it
        hub = blocks[0]
        seen = math.sqrt(max(r_bore**2 - (b_key / 2.0) ** 2, 0.0))
        k.line("OUTLINE", [(-hub[3] / 2.0, seen), (hub[3] / 2.0, seen)], style="thin")
    if arms:  # one arm's section revolved into the lower half
        r0, r1, major, minor = arms
        middle = -0.5 * (r0 + r1)
        ring = _ellipse((0.0, middle), major, minor)
        k.line("OUTLINE", ring, closed=True)
        k.hatches.append(Hatch(ring))
    reach = w_max / 2.0 + p(4.0)
    k.line("CENTER", [(-reach, 0.0), (reach, 0.0)], style="chain")

    # diameters right of the section, inner to outer
    stack = []
    if blocks[0][0] == "hub":
        stack.append(("d_hub", "hub diameter", blocks[0][2], blocks[0][3] / 2.0))
    if blocks[-1][0] == "rim":
        stack.append(("d_inner", "rim inner diameter", blocks[-1][1], blocks[-1][3] / 2.0))
    stack.append(("d_outer", "outer diameter", r_o, blocks[-1][3] / 2.0))
    for index, (name, words, r, x_edge) in enumerate(stack):
        line = w_max / 2.0 + p(_FIRST + _STEP * index)
        # the hub's diameter at the solid side (the cut keyway is above)
        k.linear(name, words, (x_edge, -r), (x_edge, r), line, vertical=True, prefix="Ø")
    # widths: the rim's above it
    b = blocks[-1][3]
    k.linear(
        "b", "rim width" if blocks[-1][0] == "rim" else "width", (-b / 2, r_o), (b / 2, r_o), r_o + p(_FIRST), False
    )
    left_text = -w_max / 2.0 - p(4.0)  # texts beside a short dimension go left, clear of the diameters
    if blocks[0][0] == "hub":
        hub = blocks[0]
        line = -(hub[2] + p(_FIRST))
        k.linear("l_hub", "hub length", (-hub[3] / 2, -hub[2]), (hub[3] / 2, -hub[2]), line, False, -1.0)
        clear = (hub[3] - _thin_width(blocks, arms)) / 2.0  # the line's free length left of the web or arm
        if k.width(size_text(hub[3])) + p(2.0 + _ARROW) < clear:  # the text above the line, left of the web
            dim = k.dimensions[-1]
            x = -hub[3] / 2.0 + clear / 2.0
            k.dimensions[-1] = Dimension(**{**dim.__dict__, "text_at": (x, line + p(1.0 + _TEXT / 2.0))})
        else:
            _move_text_left(k, left_text)
    webs = [blk for blk in blocks if blk[0] == "web"]
    if webs:
        _name, r0, r1, w = webs[0]
        y = -0.5 * (r0 + r1)
        k.linear("t_web", "web thickness", (-w / 2, y), (w / 2, y), y, False, -1.0)
        _move_text_left(k, left_text)
    if arms:
        r0, r1, major, minor = arms
        middle = -0.5 * (r0 + r1)
        k.linear("arm_minor", "arm section, minor axis", (-minor / 2, middle), (minor / 2, middle), middle, False, -1.0)
        _move_text_left(k, left_text)
        k.linear(  # left of the section, past the minor axis' text
            "arm_major",
            "arm section, major axis",
            (0.0, middle - major / 2),
            (0.0, middle + major / 2),
            left_text - k.width(k.dimensions[-1].text) - p(_FIRST),
            True,
        )

    # the part names, left of the section, each with a leader to its part (upper half)
    names = []
    for name, r0, r1, w in blocks:
        words = {"rim": "Rim", "web": "Web", "hub": "Hub", "disc": "Disc"}[name]
        names.append((0.5 * (r0 + r1 + (t2 if name == "hub" else 0.0)), -w / 4.0 if w > p(3) else 0.0, words))
    if arms:
        r0, r1, major, minor = arms
        names.append((0.5 * (r0 + r1), -minor / 4.0, f"Arm, {design.n_arms} off, elliptical section (revolved below)"))
    if t2 and key:
        names.append((r_bore + t2 / 2.0, 0.0, f"Keyway DIN 6885-1, key {key['size']}"))
    if r_bore:
        names.append((r_bore * 0.5, 0.0, "Bore (shaft seat)"))
    names.sort()
    x_text = -w_max / 2.0 - p(14.0)
    last = -math.inf
    for y, x_part, words in names:
        y_text = max(y, last + p(_TEXT * 2.0))
        last = y_text
        k.line("DIMENSIONS", [(x_text + p(1.0), y_text), (x_part, y)], style="thin")
        k.text("DIMENSIONS", (x_text, y_text), words, align="right")
    # the view's name
    k.text("DIMENSIONS", (0.0, r_o + p(_FIRST + 9.0)), "SECTION A–A", height=3.5, align="center")

    # --- front view, right of the section
    cx = w_max / 2.0 + p(_FIRST + _STEP * len(stack) + _GAP) + r_o
    _front_view(k, design, blocks, arms, cx, r_o, r_bore, t2, b_key, key)

    # --- the sheet: border, title block, notes (paper mm from the sheet's lower left corner)
    sheet_w, sheet_h, border = SHEET
    views_w = cx + r_o + p(_RIGHT) - (-w_max / 2.0 - p(_LEFT))
    x0 = -w_max / 2.0 - p(_LEFT) - (p(sheet_w - 2 * border) - views_w) / 2.0 - p(border)
    y_mid_paper = border + 6 * _ROW + (sheet_h - 2 * border - 6 * _ROW) / 2.0
    y0 = -p(y_mid_paper)

    def at(xp, yp):
        return (x0 + p(xp), y0 + p(yp))

    k.line("TITLE", [at(0, 0), at(sheet_w, 0), at(sheet_w, sheet_h), at(0, sheet_h)], closed=True, style="thin")
    k.line(
        "TITLE",
        [
            at(border, border),
            at(sheet_w - border, border),
            at(sheet_w - border, sheet_h - border),
            at(border, sheet_h - border),
        ],
        closed=True,
    )
    title = _title_fields(design, scene, sha256, version, date, k, material)
    _title_block(k, at, title)
    # the notes above the title block where the views leave room, else at the lower left; the details
    # left of the title block, below the views
    views_bottom = y_mid_paper - r_o * scale - 12.0
    lines = _wrapped(_notes(design, arms, t2, finish, ("B", "C")), _BLOCK_W - 4.0)
    beside = border + 6 * _ROW + 4.0 + len(lines) * _NOTE_STEP <= views_bottom
    if not beside:
        lines = _wrapped(_notes(design, arms, t2, finish, ("B", "C")), sheet_w - 2 * border - _BLOCK_W - 12.0)
    low = border + 4.0 + (0.0 if beside else len(lines) * _NOTE_STEP + 2.0)
    region = (*at(border + 4.0, low), *at(sheet_w - border - _BLOCK_W - 4.0, min(views_bottom, sheet_h - border - 20)))
    details = _details(k, shapes, blocks, arms, finish, region) if region[3] - region[1] > p(25.0) else []
    notes = _notes(design, arms, t2, finish, details)
    lines = _wrapped(notes, _BLOCK_W - 4.0 if beside else sheet_w - 2 * border - _BLOCK_W - 12.0)
    x_notes = sheet_w - border - _BLOCK_W + 2.0 if beside else border + 4.0
    y_notes = border + 6 * _ROW + 4.0 if beside else border + 4.0
    for index, line in enumerate(lines):
        k.text("TITLE", at(x_notes, y_notes + (len(lines) - 1 - index) * _NOTE_STEP), line, height=_SMALL)
    return Drawing(
        scale=scale,
        sheet=(*at(0, 0), *at(sheet_w, sheet_h)),
        lines=tuple(k.lines),
        arcs=tuple(k.arcs),
        hatches=tuple(k.hatches),
        texts=tuple(k.texts),
        dimensions=tuple(k.dimensions),
        title=title,
    )


def _thin_width(blocks, arms):
    """The widest thin part the hub's dimension line crosses (web or arm) [mm]."""
    widths = [w for name, _r0, _r1, w in blocks if name == "web"] + ([arms[3]] if arms else [])
    return max(widths, default=0.0)


def _move_text_left(k, x_right):
    """Put the last dimension's text left of the section, its right end at ``x_right`` (clear of the
    diameters on the right, and of the part it measures)."""
    dim = k.dimensions[-1]
    x = x_right - k.width(dim.text) / 2.0
    k.dimensions[-1] = Dimension(**{**dim.__dict__, "text_at": (x, dim.text_at[1])})


def _front_view(k, design, blocks, arms, cx, r_o, r_bore, t2, b_key, key):
    """The front view about (cx, 0): the circles seen, the arms, the bore and keyway, their dimensions."""
    p = k.p
    k.arcs.append(Arc("OUTLINE", (cx, 0.0), r_o))
    names = [blk[0] for blk in blocks]
    widths = {blk[0]: blk[3] for blk in blocks}
    # a step between two faces is seen where their widths differ by what the drawing shows (0.1 mm)
    if "rim" in names and (arms or "web" not in names or abs(widths["rim"] - widths["web"]) >= _SEEN):
        k.arcs.append(Arc("OUTLINE", (cx, 0.0), blocks[-1][1]))
    if "hub" in names and (arms or abs(widths["hub"] - widths.get("web", -1.0)) >= _SEEN):
        k.arcs.append(Arc("OUTLINE", (cx, 0.0), blocks[0][2]))
    if arms:
        r0, r1, major, _minor = arms
        half = major / 2.0
        for index in range(design.n_arms):
            angle = math.pi / 2 + 2 * math.pi * (index + 0.5) / design.n_arms  # clear of the keyway and its text
            u, v = (math.cos(angle), math.sin(angle)), (-math.sin(angle), math.cos(angle))
            for side in (-half, half):
                a0, a1 = math.sqrt(max(r0 * r0 - side * side, 0.0)), math.sqrt(max(r1 * r1 - side * side, 0.0))
                k.line(
                    "OUTLINE",
                    [
                        (cx + a0 * u[0] + side * v[0], a0 * u[1] + side * v[1]),
                        (cx + a1 * u[0] + side * v[0], a1 * u[1] + side * v[1]),
                    ],
                )
    reach = r_o + p(5.0)
    k.line("CENTER", [(cx - reach, 0.0), (cx + reach, 0.0)], style="chain")
    k.line("CENTER", [(cx, -reach), (cx, reach)], style="chain")
    # the cutting plane A-A: the vertical centre line, named at its ends
    for sign in (1, -1):
        k.text("DIMENSIONS", (cx + p(2.0), sign * (reach + p(1.0)) - (p(3.5) if sign < 0 else 0.0)), "A", height=3.5)
    k.text("DIMENSIONS", (cx, r_o + p(_FIRST + 9.0)), "FRONT VIEW", height=3.5, align="center")
    if not r_bore:
        return
    if t2:
        side = math.degrees(math.asin(min(b_key / 2.0 / r_bore, 1.0)))
        k.arcs.append(Arc("OUTLINE", (cx, 0.0), r_bore, 90.0 + side, 360.0 + 90.0 - side))
        seen = math.sqrt(max(r_bore**2 - (b_key / 2.0) ** 2, 0.0))
        top = r_bore + t2
        k.line(
            "OUTLINE", [(cx - b_key / 2, seen), (cx - b_key / 2, top), (cx + b_key / 2, top), (cx + b_key / 2, seen)]
        )
    else:
        k.arcs.append(Arc("OUTLINE", (cx, 0.0), r_bore))
    # the bore: a diameter dimension at an angle clear of the keyway and the arms, its text outside
    angle = math.radians(_bore_angle(design.n_arms if arms else None))
    bore_fit = hole_tolerance(design.bore, "H7")
    r_text = max(blocks[0][2] if blocks[0][0] == "hub" else r_bore, r_bore) + p(14.0)
    k.dimensions.append(
        Dimension(
            "bore",
            "bore (shaft seat)",
            "diameter",
            (cx, 0.0),
            (cx + r_bore * math.cos(angle), r_bore * math.sin(angle)),
            (cx, 0.0),
            math.degrees(angle),
            2.0 * r_bore,
            (cx + r_text * math.cos(angle), r_text * math.sin(angle)),
            prefix="Ø",
            fit="H7",
            upper=bore_fit.upper * 1e3,
            lower=bore_fit.lower * 1e3,
        )
    )
    # the keyway: width JS9 over it, depth d + t2 to its left (DIN 6885-1)
    if t2:
        width_fit = hole_tolerance(key["b"], "JS9")
        k.linear(
            "key_width",
            "keyway width",
            (cx - b_key / 2, r_bore + t2),
            (cx + b_key / 2, r_bore + t2),
            r_bore + t2 + p(_FIRST),
            False,
            1.0,
            fit="JS9",
            upper=width_fit.upper * 1e3,
            lower=width_fit.lower * 1e3,
        )
        r_side = blocks[0][2] if blocks[0][0] == "hub" else r_bore
        k.linear(
            "key_depth",
            "keyway depth over the bore, d + t2",
            (cx, -r_bore),
            (cx - b_key / 2, r_bore + t2),
            cx - r_side - p(_FIRST),
            True,
        )


def _bore_angle(n_arms):
    """The direction [deg] of the bore's diameter dimension in the front view: down and right, in the gap
    between two arms nearest -45 degrees (the arms stand half a pitch off the vertical), off the centre lines."""
    if not n_arms:
        return -35.0
    pitch = 360.0 / n_arms
    gaps = [90.0 + k * pitch - 360.0 for k in range(n_arms + 1)]
    angle = min(gaps, key=lambda a: (abs(a + 45.0), -a))
    if math.isclose(angle % 90.0, 0.0, abs_tol=1e-9) or math.isclose(angle % 90.0, 90.0, abs_tol=1e-9):
        angle -= pitch / 4.0
    return angle


def _title_fields(design, scene, sha256, version, date, k, material=None):
    """The title block's fields: name to text."""
    from pathlib import Path

    what = {
        Geometry.RIM_WEB: "rim, web and hub",
        Geometry.RIM_ARMS: f"rim, {design.n_arms} arms and hub",
        Geometry.DISC: ("disc on its hub" if design.dims.d_hub else "disc") if design.bore else "solid disc",
    }.get(design.geometry, "rim")
    unbalance = design.stresses.unbalance_permissible if design.stresses else None
    balance = f"G {BALANCE_GRADE:g} (ISO 21940-11)"
    if unbalance is not None:
        balance += f", U_per = {unbalance * 1e6:.0f} g·mm"
    return {
        "title": f"Flywheel, {what}",
        "material": material or design.material.replace("_", " "),
        "mass": f"{design.mass:.2f} kg",
        "inertia": f"{design.j_flywheel:.4g} kg·m²",
        "balance": balance,
        "scale": f"1:{1 / k.scale:g}",
        "date": date.isoformat(),
        "version": f"flyopt {version}",
        "scene": Path(scene).name if scene else "(a scene made in Python)",
        "sha256": sha256 or "-",
        "units": "dimensions in mm",
        "shaft": design.shaft,
    }


def _title_block(k, at, title):
    """The title block in the sheet's lower right corner (ISO 7200 width): six rows of fields."""
    sheet_w, _sheet_h, border = SHEET
    x1 = sheet_w - border
    x0 = x1 - _BLOCK_W
    y0 = border
    rows = 6
    k.line("TITLE", [at(x0, y0), at(x1, y0), at(x1, y0 + rows * _ROW), at(x0, y0 + rows * _ROW)], closed=True)
    for row in range(1, rows):
        k.line("TITLE", [at(x0, y0 + row * _ROW), at(x1, y0 + row * _ROW)], style="thin")
    half = x0 + _BLOCK_W / 2.0
    cells = [  # (row from the top, x start, x end, label, field)
        (0, x0, x1, "", "title"),
        (1, x0, half, "Material", "material"),
        (1, half, x1, "Shaft", "shaft"),
        (2, x0, half, "Mass", "mass"),
        (2, half, x1, "J about the axis", "inertia"),
        (3, x0, x1, "Balance", "balance"),
        (4, x0, x0 + 40, "Scale", "scale"),
        (4, x0 + 40, x0 + 80, "Date", "date"),
        (4, x0 + 80, x0 + 125, "", "version"),
        (4, x0 + 125, x1, "", "units"),
        (5, x0, x1, "Scene", "scene"),
    ]
    for row, xs, _xe, label, name in cells:
        y = y0 + (rows - 1 - row) * _ROW + 2.0
        if xs > x0:
            k.line("TITLE", [at(xs, y0 + (rows - 1 - row) * _ROW), at(xs, y0 + (rows - row) * _ROW)], style="thin")
        text = f"{label}: {title[name]}" if label else title[name]
        if name == "title":
            k.text("TITLE", at(xs + 2.0, y - 0.5), text, height=4.0)
        elif name == "scene":
            k.text("TITLE", at(xs + 2.0, y), f"{text}   SHA-256 {title['sha256']}", height=_SMALL)
        else:
            k.text("TITLE", at(xs + 2.0, y), text, height=_TEXT)


def _wrapped(notes, width):
    """The notes as lines no wider than ``width`` [paper mm] at the notes' text height; a note's further
    lines indented."""
    import textwrap

    chars = max(20, int(width / (_SMALL * _CHAR)))
    out = []
    for note in notes:
        out += textwrap.wrap(note, chars, subsequent_indent="   ")
    return out


def _notes(design, arms, t2, finish, details):
    """What the drawing says in words beside the views."""
    notes = ["Dimensions in mm. Section A–A is cut through the keyway." if t2 else "Dimensions in mm."]
    if arms:
        notes.append("Arms are not hatched in section (drafting rule for spokes); one arm's section is revolved.")
    if not design.bore and design.geometry not in (Geometry.RIM, Geometry.THIN_RIM):
        notes.append("No bore: the design gives no shaft seat; the seat and its key are to be added.")
    elif not t2:
        notes.append("No key: the design gives none for this seat.")
    if design.geometry in (Geometry.RIM, Geometry.THIN_RIM):
        notes.append("The rim alone, as designed: its hub and arms or web are not part of this design.")
    where = f" (detail{'s' if len(details) > 1 else ''} {' and '.join(details)})" if details else ""
    fillets = sorted({f for f in finish.fillets.values() if f > 0})
    if fillets:
        notes.append(
            f"Fillets {', '.join('R' + size_text(f) for f in fillets)}{where}: {finish_rule(finish)} "
            "(the FE check's rule)."
        )
    chamfers = sorted({c for c in finish.chamfers.values() if c > 0})
    if chamfers:
        notes.append(f"Chamfers {', '.join(size_text(c) + ' × 45°' for c in chamfers)}{where}.")
    drafted, machined = _faces(design)
    bore = f"; the bore Ra {finish.bore_ra:g} µm" if design.bore else ""
    if finish.draft is not None and drafted:
        notes.append(
            f"Draft {finish.draft:g}° on the cast faces parallel to the axis ({', '.join(drafted)}), added to the "
            "material (not in the mass and J); none on machined faces."
        )
        notes.append(
            f"Machined ▽ (ISO 1302): {', '.join(machined)} Ra {finish.machined_ra:g} µm{bore}; other faces as cast."
        )
    else:
        if finish.process is None:
            why = "no draft (the process is not known: the foundry's draft is to be added if it is cast)"
        elif finish.process == "machined" or finish.draft is None:
            why = "no draft (not cast)"
        else:  # a cast wheel machined all over: no face is left as cast
            why = f"the casting's draft ({finish.draft:g}°) is turned off"
        notes.append(f"Machined all over ▽ (ISO 1302, material removed) Ra {finish.machined_ra:g} µm{bore}; {why}.")
    notes.append("The STEP solid has sharp edges: no fillets, chamfers or draft.")
    return notes


def _faces(design):
    """The faces of a cast wheel parallel to the axis left as cast (drafted), and the faces machined."""
    hub = design.geometry in (Geometry.RIM_WEB, Geometry.RIM_ARMS) and bool(design.bore)
    if design.geometry == Geometry.DISC:
        return [], ["all"]
    drafted = ["rim inside"] + (["hub outside"] if hub else [])
    machined = ["rim outside and faces"] + (["hub ends"] if hub else [])
    return drafted, machined


def finish_rule(finish: Finish) -> str:
    """The fillet rule in words, as the drawing's note gives it: "r = 0.5 × the thinner part, at least R3"."""
    out = f"{finish.ratio:g} × the thinner part"
    if finish.min_fillet:
        out += f", at least R{size_text(finish.min_fillet)}"
    return out + ", at most half the step"


# ---------------------------------------------------------------------------
# DXF
# ---------------------------------------------------------------------------


def require_ezdxf() -> Any:
    """ezdxf, or a one-line refusal naming the extra that brings it."""
    try:
        import ezdxf
    except ImportError:
        raise ImportError(f"a DXF drawing needs ezdxf: pip install '{CAD_EXTRA}'") from None
    return ezdxf


#: The XDATA application that names what a DXF dimension measures (the Dimension's ``name``).
XDATA_APP = "FLYOPT"


def write_dxf(drawing: Drawing, path: str | os.PathLike[str]) -> None:
    """Write ``drawing`` as a DXF (R2013, mm) to ``path``, atomically.

    Layers :data:`LAYERS`; outlines as LWPOLYLINEs, ARCs (the fillets) and
    CIRCLEs; cut faces as HATCH entities (ANSI31, 3 mm apart on paper); every
    dimension a real DIMENSION entity (linear, diameter, or radius for a
    fillet) whose measurement is the design's size (in a detail, times its
    enlargement, with DIMLFAC its inverse so that the text is true), with its
    ISO 286 limits as the dimension's tolerance and, as XDATA of application
    ``FLYOPT``, the name of what it measures; a chamfer as a LEADER (XDATA: its
    name and size [mm]) with its "1.6 × 45°" as TEXT; texts as TEXT. Model space is true size; text heights and arrows are in model
    units, the inverse of the drawing's scale times their paper size, so they
    plot at their paper size when model space is plotted at the drawing's scale.

    Raises
    ------
    ImportError
        ezdxf is not installed (one line naming the ``cad`` extra).
    """
    from flyopt.outputs.files import write_atomically

    ezdxf = require_ezdxf()
    doc = ezdxf.new("R2013", setup=True, units=4)  # 4: millimetres
    doc.appids.add(XDATA_APP)
    colours = {"OUTLINE": 7, "CENTER": 1, "HATCH": 8, "DIMENSIONS": 3, "TITLE": 5}
    for name in LAYERS:
        doc.layers.add(name, color=colours[name], linetype="CENTER" if name == "CENTER" else "Continuous")
    inverse = 1.0 / drawing.scale
    doc.header["$LTSCALE"] = inverse
    style = doc.dimstyles.new("FLYOPT")
    # sizes in model units (DIMSCALE 1): ezdxf 1.4 scales a tolerance's text by DIMSCALE twice
    for attribute, value in {
        "dimtxt": _TEXT * inverse,
        "dimasz": _ARROW * inverse,
        "dimexe": 1.5 * inverse,
        "dimexo": 1.0 * inverse,
        "dimgap": 1.0 * inverse,
        "dimscale": 1.0,
        "dimdsep": ord("."),
        "dimtfac": 0.7,
        "dimdec": 1,
        "dimtdec": 4,
        "dimzin": 8,  # no trailing zeros
        "dimtzin": 8,
        "dimlfac": 1.0,
        "dimtad": 1,  # text above the line
        "dimtih": 0,
        "dimtoh": 0,
        "dimblk": "",  # closed filled arrows
        "dimtxsty": "Standard",
        "dimclrd": 3,
        "dimclre": 3,
        "dimclrt": 3,
        "dimtfill": 1,  # the text on the drawing's background: lines break behind it
    }.items():
        style.dxf.set(attribute, value)
    msp = doc.modelspace()
    for line in drawing.lines:
        attribs: dict[str, Any] = {"layer": line.layer}
        if line.style == "thin":
            attribs["lineweight"] = 25
        msp.add_lwpolyline(line.points, close=line.closed, dxfattribs=attribs)
    for arc in drawing.arcs:
        if arc.end - arc.start >= 360.0:
            msp.add_circle(arc.center, arc.radius, dxfattribs={"layer": arc.layer})
        else:
            msp.add_arc(arc.center, arc.radius, arc.start, arc.end, dxfattribs={"layer": arc.layer})
    for region in drawing.hatches:
        hatch = msp.add_hatch(color=8, dxfattribs={"layer": region.layer})
        hatch.set_pattern_fill("ANSI31", scale=inverse)
        hatch.paths.add_polyline_path(region.boundary, is_closed=True)
    align = {"left": "LEFT", "center": "CENTER", "right": "RIGHT"}
    for text in drawing.texts:
        entity = msp.add_text(
            text.text, height=text.height, rotation=text.rotation, dxfattribs={"layer": text.layer, "style": "Standard"}
        )
        entity.set_placement(text.at, align=ezdxf.enums.TextEntityAlignment[f"BOTTOM_{align[text.align]}"])
    for dim in drawing.dimensions:
        override: dict[str, Any] = {}
        if dim.fit:
            override.update({"dimtol": 1, "dimtp": dim.upper, "dimtm": -dim.lower})
        # a diameter dimension writes its Ø itself; a linear one of a diameter is told to
        label = (
            ("%%c" if dim.prefix == "Ø" and dim.kind == "linear" else "") + "<>" + (f" {dim.fit}" if dim.fit else "")
        )
        if dim.lfac != 1.0:  # a detail's: drawn enlarged, measured true
            override["dimlfac"] = dim.lfac
        if dim.kind == "chamfer":  # a leader to the chamfer, its size as text
            leader = msp.add_leader([dim.p2, dim.p1], dimstyle="FLYOPT", dxfattribs={"layer": "DIMENSIONS"})
            leader.set_xdata(XDATA_APP, [(1000, dim.name), (1040, dim.value)])
            note = msp.add_text(
                dim.text, height=_TEXT / drawing.scale, dxfattribs={"layer": "DIMENSIONS", "style": "Standard"}
            )
            note.set_placement(dim.text_at, align=ezdxf.enums.TextEntityAlignment.BOTTOM_LEFT)
            continue
        if dim.kind == "radius":
            entity = msp.add_radius_dim(
                center=dim.p1,
                radius=math.dist(dim.p1, dim.p2),
                angle=dim.angle,
                location=dim.text_at,
                dimstyle="FLYOPT",
                override=override,
                dxfattribs={"layer": "DIMENSIONS"},
            )
        elif dim.kind == "diameter":
            radius = dim.value / 2.0
            entity = msp.add_diameter_dim(
                center=dim.p1,
                radius=radius,
                angle=dim.angle,
                location=dim.text_at,
                text=label,
                dimstyle="FLYOPT",
                override=override,
                dxfattribs={"layer": "DIMENSIONS"},
            )
        else:
            entity = msp.add_linear_dim(
                base=dim.base,
                p1=dim.p1,
                p2=dim.p2,
                angle=dim.angle,
                location=dim.text_at,
                text=label,
                dimstyle="FLYOPT",
                override=override,
                dxfattribs={"layer": "DIMENSIONS"},
            )
        entity.render()
        entity.dimension.set_xdata(XDATA_APP, [(1000, dim.name)])
    for name, value in drawing.title.items():  # the title block's fields, for a reader that wants them
        doc.header.custom_vars.append(f"FLYOPT_{name.upper()}", value)
    stream = io.StringIO()
    doc.write(stream)
    data = stream.getvalue().encode("utf-8")
    write_atomically(path, lambda handle: handle.write(data))
