"""The dimensioned axial section of a flywheel (hub, web or arms, rim), with a front view of an arms wheel."""

from __future__ import annotations

import math
import textwrap
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.design.check import binding_label
from flyopt.design.result import Design
from flyopt.names import Geometry
from flyopt.outputs.drawing import keyway, section_blocks
from flyopt.report import display
from flyopt.report.plots import readout, standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.design.result import Candidate

#: Font size of dimensions and notes on the drawing [pt].
_DIM_FONT = 8
#: Distance between stacked dimension lines, and of the first from the part [in].
_DIM_STEP, _DIM_FIRST = 0.30, 0.34
#: Extension lines: gap from the part, overshoot past the dimension line [in].
_EXT_GAP, _EXT_OVER = 0.03, 0.06
#: Height the wheel's outer diameter is drawn at when the function makes its own figure [in].
_SECTION_HEIGHT = 6.4
_SECTION_HATCH: dict[str, Any] = dict(facecolor="#e8ebf0", edgecolor="black", linewidth=0, hatch="////")


def _length_decimals(units):
    """Decimals a drawing gives its lengths to in the system's unit: 0.1 mm (mm 1, in 3, m 4)."""
    return max(0, math.ceil(-math.log10(1e-4 / standard.unit("length", units)[1]) - 1e-9))


def _length_text(value, decimals):
    """A length in the drawing's unit as a drawing gives it: to its decimals, no trailing zeros."""
    return f"{value:.{decimals}f}".rstrip("0").rstrip(".") if decimals else f"{value:.0f}"


class _InUnits:
    """What the drawing reads of a design, its lengths in the drawing's unit (divided by ``factor``)."""

    def __init__(self, design: Design, factor: float) -> None:
        def scaled(value: float | None) -> float | None:
            return None if value is None else value / factor

        dims, key = design.dims, design.parts.key
        self.geometry, self.material, self.shaft = design.geometry, design.material, design.shaft
        self.mass, self.j_flywheel, self.n_arms = design.mass, design.j_flywheel, design.n_arms
        self.binding = design.limits.binding
        self.cast_checked = design.limits.castability is not None  # its walls and section ratios (issue 28)
        self.thin_wall = design.parts.thin_wall  # a bare wheel thinner than its process makes (its notes say)
        self.d_outer, self.d_inner, self.h, self.b = (v / factor for v in (dims.d_outer, dims.d_inner, dims.h, dims.b))
        self.bore, self.t_web, self.d_hub = scaled(design.bore), scaled(dims.t_web), scaled(dims.d_hub)
        self.l_hub, self.arm_major, self.arm_minor = scaled(dims.l_hub), scaled(dims.arm_major), scaled(dims.arm_minor)
        self.key = (
            {k: (v / factor if k in ("b", "t2", "h", "t1", "length") else v) for k, v in key.items()} if key else key
        )


def _text_width(text, size=_DIM_FONT):
    """Rough width of a line of text [in] (DejaVu Sans: about 0.6 em per character)."""
    return 0.6 * size * len(text) / 72.0


class _Sheet:
    """Draws dimensions on an Axes of equal aspect whose scale is known: ``scale`` inches per data unit."""

    def __init__(self, ax, scale):
        self.ax, self.scale = ax, scale

    def d(self, inches):
        """A length on the sheet [in] in data units (the drawing's length unit)."""
        return inches / self.scale

    def _arrow(self, tip, tail):
        self.ax.annotate(
            "",
            tip,
            tail,
            arrowprops={
                "arrowstyle": "-|>",
                "lw": 0.7,
                "color": "black",
                "mutation_scale": 7,
                "shrinkA": 0,
                "shrinkB": 0,
            },
        )

    def linear(self, a, b, line, text, vertical, feature=None, room=None, beside=None):
        """A dimension between ``a`` and ``b`` (along y if ``vertical``, else along x).

        Arrows go inside the extension lines where there is room, else outside
        pointing in. The text of a vertical dimension reads from the right,
        left of its line (ISO 129) where it fits between the ends, else on the
        far side of the line; of a horizontal one above the line where it fits
        in ``room``, else beside the outside arrow, away from the middle of the
        drawing.

        Parameters
        ----------
        a, b : float
            The two ends on the measured axis (data units).
        line : float
            Where the dimension line runs, on the other axis.
        text : str
        vertical : bool
        feature : tuple of float or None
            Where on the other axis the extension lines start at ``a`` and
            ``b`` (the part's edges); None: the dimension line spans the part.
        room : float or None
            A horizontal dimension's text may be this wide, centred (it
            must clear the next extension lines out); None: the dimension's length.
        beside : {1, -1} or None
            Put a horizontal dimension's text beside its line, right (1) or
            left (-1); None: above where it fits, else away from the middle.
        """
        ax, d = self.ax, self.d
        lo, hi = min(a, b), max(a, b)

        def point(along, across):
            return (across, along) if vertical else (along, across)

        away = 1.0 if feature is None or line >= feature[0] else -1.0  # from the part towards the line
        if feature is not None:
            for end, start in zip((a, b), feature):
                p0, p1 = point(end, start + away * d(_EXT_GAP)), point(end, line + away * d(_EXT_OVER))
                ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="black", lw=0.5, solid_capstyle="butt")
        length = (hi - lo) * self.scale
        inside = length > 0.32
        arrow = {"lw": 0.7, "color": "black", "mutation_scale": 7, "shrinkA": 0, "shrinkB": 0}
        if inside:
            ax.annotate("", point(lo, line), point(hi, line), arrowprops={"arrowstyle": "<|-|>", **arrow})
        else:  # too short for arrows inside: arrows from outside, pointing in
            ax.plot(*zip(point(lo, line), point(hi, line)), color="black", lw=0.7)
            for tip, tail in ((lo, lo - d(0.16)), (hi, hi + d(0.16))):
                ax.annotate("", point(tip, line), point(tail, line), arrowprops={"arrowstyle": "-|>", **arrow})
        fits = _text_width(text) < length - 0.12
        off = d(_EXT_OVER + 0.03)
        if vertical:
            side = -1.0 if fits or (feature is not None and away < 0) else away
            ax.text(
                line + side * off,
                0.5 * (lo + hi),
                text,
                rotation=90,
                rotation_mode="anchor",
                ha="center",
                va="bottom" if side < 0 else "top",
                fontsize=_DIM_FONT,
            )
        elif (
            beside is None
            and feature is not None
            and _text_width(text) < max(length, (room or 0.0) * self.scale) - 0.08
        ):
            ax.text(0.5 * (lo + hi), line + off, text, ha="center", va="bottom", fontsize=_DIM_FONT)
        else:
            right = beside > 0 if beside is not None else 0.5 * (lo + hi) >= 0
            gap = d(0.2) if not inside else d(0.06)
            ax.text(
                hi + gap if right else lo - gap,
                line,
                text,
                ha="left" if right else "right",
                va="center",
                fontsize=_DIM_FONT,
            )


def _diameter_lines(diameters, texts, scale):
    """Where the diameters' dimension lines run right of the section [in from its side], and the room
    they take: one step apart, one more where a text is too long for its line and goes outside it
    (:meth:`_Sheet.linear`), so that it does not land on the next dimension's text."""
    at, lines = _DIM_FIRST, []
    outside = 0.0
    for (r, _x, _name), text in zip(diameters, texts):
        at += outside
        lines.append(at)
        fits = scale is not None and _text_width(text) < 2 * r * scale - 0.12
        outside = 0.0 if fits or scale is None else _DIM_FONT / 72.0 * 1.4 + 0.05
        at += _DIM_STEP
    return lines, lines[-1] + outside + 0.3


def _section_parts(candidate, factor):
    """The hatched blocks of the axial half-section in the drawing's unit (:func:`flyopt.outputs.drawing.section_blocks`,
    the one description every drawing of the wheel takes): (name, r_inner, r_outer, axial width), inner first,
    and the arms (r_inner, r_outer, major, minor) or None."""
    blocks, arms = section_blocks(candidate)
    scaled = [(name, *(v / factor for v in rest)) for name, *rest in blocks]
    return scaled, (tuple(v / factor for v in arms) if arms else None)


def _outline(blocks, cut=0.0):
    """The outline of contiguous centred blocks (the upper half), as polygon vertices; ``cut``: the first
    block's inner edge that much further out (the keyway's depth in the hub)."""
    right = []
    for index, (_name, r0, r1, w) in enumerate(blocks):
        right += [(w / 2.0, r0 + (cut if index == 0 else 0.0)), (w / 2.0, r1)]
    return right + [(-x, y) for x, y in reversed(right)]


def _groups(blocks):
    """Blocks that touch (one outline each)."""
    out = [[blocks[0]]]
    for block in blocks[1:]:
        if math.isclose(block[1], out[-1][-1][2], rel_tol=1e-9, abs_tol=1e-12):
            out[-1].append(block)
        else:
            out.append([block])
    return out


def plot_cross_section(
    candidate: Candidate,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    material: str | None = None,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """Dimensioned axial section of a designed wheel, mirrored about the axis, in the system's length unit.

    The hub (bore to D_hub, length l_hub), the web (t_web) and the rim (H x B)
    are drawn hatched as one casting; the arms of a ``rim_arms`` wheel are
    drawn unhatched (they are not cut: the drafting rule for spokes) with
    their elliptical section revolved into the view, and a small front view
    beside the section shows their number. A bare rim or disc draws alone,
    and a note under the drawing says what it leaves out: a bare rim is the
    rim of docs/flywheel-design.md, section 9, whose hub and arms are not
    designed; a section far thinner than its diameter (D over its thinnest
    side 40 or more) is named, with the limits that made it so.

    Parameters
    ----------
    candidate : flyopt.design.result.Candidate
        A feasible design.
    ax : matplotlib Axes, optional
        Where to draw the section; by default a new figure sized so that the
        dimensions are legible (and, for arms, with the front view beside it).
    units : {"engineering", "si", "imperial"}
        The drawing's length unit (mm, m, in), its data coordinates and its
        dimensions (to 0.1 mm).
    material : str, optional
        The material's name for people in the title (default: its key with spaces).

    Returns
    -------
    matplotlib Axes
        The section, in the length unit of ``units``. Every hatched block is
        a Rectangle whose ``gid`` is its part and half: ``"rim+"``,
        ``"hub-"``...; the revolved arm section an Ellipse with gid
        ``"arm_section"``; the note under the drawing a Text of gid ``"note"``.
    """
    from matplotlib.patches import Ellipse, Polygon, Rectangle

    display.check_system(units)
    if not isinstance(candidate, Design):
        raise ValueError(f"{candidate.material} on {candidate.shaft} is not a design: nothing to draw")
    length, factor = standard.unit("length", units)
    decimals = _length_decimals(units)

    def _mm_text(value):
        return _length_text(value, decimals)

    c = _InUnits(candidate, factor)
    notes = _section_notes(c, length, _mm_text)
    blocks, arms = _section_parts(candidate, factor)
    b_key, t2 = (v / factor for v in keyway(candidate))
    r_o = c.d_outer / 2.0
    w_max = max([w for *_x, w in blocks] + ([arms[3]] if arms else []))
    has_hub = blocks[0][0] == "hub"
    has_rim = blocks[-1][0] == "rim"
    bored = blocks[0][0] in ("hub", "disc") and blocks[0][1] > 0
    # dimension lines: right of the section the diameters, inner to outer; above it the rim's width
    diameters = []
    if bored:
        diameters.append((blocks[0][1], blocks[0][3] / 2.0, "bore"))
    if has_hub:
        diameters.append((blocks[0][2], blocks[0][3] / 2.0, "D_hub"))
    if has_rim:
        diameters.append((blocks[-1][1], c.b / 2.0, "D_inner"))
    diameters.append((r_o, c.b / 2.0, "D_outer"))
    texts = [f"Ø{_mm_text(2 * r)}" for r, _x, _n in diameters]
    left_in = (_DIM_FIRST + 0.45) if has_rim else 0.3  # H (and the arm's a) on the left
    lines_in, right_in = _diameter_lines(diameters, texts, None)
    top_in = _DIM_FIRST + 0.25
    note_lines = sum(len(textwrap.wrap(n, 95)) for n in notes)
    bottom_in = 0.25
    own = ax is None
    if ax is None:
        scale = min(_SECTION_HEIGHT / (2 * r_o), 5.0 / w_max)  # [in per drawing unit]
        lines_in, right_in = _diameter_lines(diameters, texts, scale)
        width_in = w_max * scale + left_in + right_in
        height_in = 2 * r_o * scale + top_in + bottom_in
        front_in = 0.62 * 2 * r_o * scale + 0.6 if arms else 0.0  # the front view, smaller
        title_in, margin = 0.75, 0.3
        notes_in = 0.17 * note_lines + (0.15 if notes else 0.0)
        fig_w = max(width_in + front_in + 2 * margin, 7.0)
        fig_h = height_in + title_in + notes_in + 2 * margin
        fig = standard.new_figure(figsize=(fig_w, fig_h))
        x0 = (fig_w - width_in - front_in) / 2.0
        ax = fig.add_axes((x0 / fig_w, (margin + notes_in) / fig_h, width_in / fig_w, height_in / fig_h))
        if arms:
            size = 0.62 * 2 * r_o * scale + 0.3
            front = fig.add_axes(
                (
                    (x0 + width_in + 0.3) / fig_w,
                    (margin + notes_in + (height_in - size) / 2) / fig_h,
                    size / fig_w,
                    size / fig_h,
                )
            )
            _front_view(front, c, arms, _mm_text)
    else:
        box = ax.get_position()
        fig_w, fig_h = standard.figure_of(ax).get_size_inches()
        for _pass in range(2):  # the room the diameters need depends on the scale, and the scale on it
            scale = min(
                (box.height * fig_h - top_in - bottom_in) / (2 * r_o), (box.width * fig_w - left_in - right_in) / w_max
            )
            scale = max(scale, 1e-9)
            lines_in, right_in = _diameter_lines(diameters, texts, scale)
    sheet = _Sheet(ax, scale)
    d = sheet.d
    for group in _groups(blocks):
        # the upper half is cut through the hub's keyway (section A-A of the drawing): its face starts at t2 over the bore
        cut = t2 if group[0] is blocks[0] else 0.0  # the keyway is in the bore's block (t2 is 0 without a bore)
        for sign in (1, -1):
            for index, (name, r0, r1, w) in enumerate(group):
                start = r0 + (cut if sign > 0 and index == 0 else 0.0)
                y = start if sign > 0 else -r1
                ax.add_patch(
                    Rectangle((-w / 2.0, y), w, r1 - start, gid=f"{name}{'+' if sign > 0 else '-'}", **_SECTION_HATCH)
                )
        upper = _outline(group, cut)
        if group[0][1] > 0:  # a bore: the halves are two sections
            outlines = [upper, [(x, -y) for x, y in _outline(group)]]
            if cut:  # the bore's edge seen through the keyway
                seen = math.sqrt(max(group[0][1] ** 2 - (b_key / 2.0) ** 2, 0.0))
                ax.plot([-group[0][3] / 2.0, group[0][3] / 2.0], [seen, seen], color="black", lw=0.6, gid="keyway")
        else:  # solid to the centre: one section, no line on the axis
            right = upper[: len(upper) // 2]
            side = [(x, -y) for x, y in reversed(right)] + right[1:]
            outlines = [side + [(-x, y) for x, y in reversed(side)]]
        for outline in outlines:
            ax.add_patch(Polygon(outline, closed=True, fill=False, edgecolor="black", lw=1.2))
    if arms:
        r0, r1, major, minor = arms
        for sign in (1, -1):
            ax.add_patch(
                Rectangle(
                    (-minor / 2.0, r0 if sign > 0 else -r1),
                    minor,
                    r1 - r0,
                    fill=False,
                    edgecolor="black",
                    lw=1.0,
                    gid=f"arms{'+' if sign > 0 else '-'}",
                )
            )
        middle = 0.5 * (r0 + r1)
        ax.add_patch(Ellipse((0.0, middle), minor, major, gid="arm_section", zorder=3, **_SECTION_HATCH))
        ax.add_patch(Ellipse((0.0, middle), minor, major, fill=False, edgecolor="black", lw=1.0, zorder=3))
    # the axis: dash-dot, a little past the outline
    reach = w_max / 2.0 + d(0.06)  # short of the text of the first diameter
    ax.plot([-reach, reach], [0, 0], color="black", lw=0.6, ls=(0, (12, 3, 2, 3)))
    # diameters, right of the section
    for (r, x_edge, _name), text, at in zip(diameters, texts, lines_in):
        sheet.linear(-r, r, w_max / 2.0 + d(at), text, vertical=True, feature=(x_edge, x_edge))
    # the width above (nothing else is there: its text may overhang the extension lines)
    sheet.linear(
        -c.b / 2.0,
        c.b / 2.0,
        r_o + d(_DIM_FIRST),
        f"B {_mm_text(c.b)}",
        vertical=False,
        feature=(r_o, r_o),
        room=c.b + d(1.0),
    )
    if has_hub:  # the hub's length just outside it (not above the rim: its extension lines would
        # run the height of the drawing and read as outlines), its text left, clear of the diameters;
        # under the axis when the arms' dimension a takes the upper left
        hub = blocks[0]
        side = -1.0 if arms else 1.0
        sheet.linear(
            -hub[3] / 2.0,
            hub[3] / 2.0,
            side * (hub[2] + d(0.22)),
            f"hub length {_mm_text(hub[3])}",
            vertical=False,
            feature=(side * hub[2], side * hub[2]),
            beside=-1,
        )
    if has_rim:
        rim = blocks[-1]
        line = -w_max / 2.0 - d(_DIM_FIRST)
        sheet.linear(
            rim[1], rim[2], line, f"H {_mm_text(rim[2] - rim[1])}", vertical=True, feature=(-c.b / 2.0, -c.b / 2.0)
        )
    # web or arm thickness, across it in the lower half
    thin = [b for b in blocks if b[0] == "web"]
    if thin:
        _name, r0, r1, w = thin[0]
        sheet.linear(-w / 2.0, w / 2.0, -0.5 * (r0 + r1), f"web {_mm_text(w)}", vertical=False)
    if arms:
        r0, r1, major, minor = arms
        middle = 0.5 * (r0 + r1)
        sheet.linear(-minor / 2.0, minor / 2.0, -middle, f"arm a/2 {_mm_text(minor)}", vertical=False)
        sheet.linear(
            middle - major / 2.0,
            middle + major / 2.0,
            -w_max / 2.0 - d(_DIM_FIRST),
            f"arm a {_mm_text(major)}",
            vertical=True,
            feature=(0.0, 0.0),
        )
    ax.set_aspect("equal")
    ax.set_xlim(-w_max / 2.0 - d(left_in), w_max / 2.0 + d(right_in))
    ax.set_ylim(-r_o - d(bottom_in), r_o + d(top_in))
    ax.set_axis_off()
    readout.ordinate(ax, "r", standard.scale("length", units, digits=digits), absolute=True)  # the app's read-out
    what = {"rim_arms": f"rim on {c.n_arms} arms", "rim_web": "rim and web", "thin_rim": "thin rim"}.get(
        c.geometry, c.geometry
    )
    title = (
        f"Flywheel, {what}: {material or c.material.replace('_', ' ')}, {standard.q(c.mass, 'mass', units, digits)}, "
        f"J = {standard.q(c.j_flywheel, 'inertia', units, digits)} on {c.shaft}\n"
        f"axial section{', arm section revolved' if arms else ''}, dimensions in {length}"
    )
    if own:  # the figure is this drawing's: its title over both views, the notes under them
        standard.figure_of(ax).suptitle(title, fontsize=10)
        if notes:
            standard.figure_of(ax).text(
                0.5,
                margin / fig_h,
                "\n".join(textwrap.fill(n, 95) for n in notes),
                ha="center",
                va="bottom",
                fontsize=_DIM_FONT,
                color="dimgray",
                gid="note",
            )
    else:
        ax.set_title(title, fontsize=9)
        if notes:
            ax.text(
                0.5,
                -0.01,
                "\n".join(textwrap.fill(n, 70) for n in notes),
                transform=ax.transAxes,
                ha="center",
                va="top",
                fontsize=_DIM_FONT,
                color="dimgray",
                gid="note",
            )
    return ax


#: A section whose diameter is this many times its thinnest side or more is named slender in a note.
_SLENDER = 40.0


def _section_notes(c, length, text):
    """What a drawing of the candidate leaves out, or should make one look twice (sentences).

    ``c`` has its lengths in the drawing's unit ``length``, written by ``text``
    as the dimensions are. The rim of a rim-and-web or arms wheel (or a disc)
    is slender when the outer diameter is :data:`_SLENDER` times its thinnest
    side or more; a web is thin by design and not counted.
    """
    notes = []
    if c.geometry in ("rim", "thin_rim"):
        notes.append(
            f"The rim alone, as designed (geometry '{c.geometry}'): its hub and arms or web are not part "
            "of this design, and their inertia is left out, on the safe side."
        )
    disc = c.geometry == Geometry.DISC
    ratio = c.d_outer / (c.b if disc else min(c.b, c.h))
    if ratio >= _SLENDER:
        binding = ", ".join(binding_label(name) for name in c.binding) if c.binding else "none"
        sides = f"{text(c.b)} {length} thick" if disc else f"B {text(c.b)} × H {text(c.h)} {length}"
        notes.append(
            f"A slender {'disc' if disc else 'rim'}: {sides} at Ø{text(c.d_outer)} {length}, the diameter "
            f"{ratio:.0f} times its thinnest side. It is the lightest the design's limits allow (binding: "
            f"{binding}); "
            + (
                "its castability (walls, section ratios) is checked, its stiffness is not."
                if c.cast_checked
                else "its walls are thinner than can be made (see the design's notes); its stiffness is not checked."
                if c.thin_wall is not None
                else "its thinnest wall is checked against its process where one is known; its section ratios "
                "and stiffness are not."
            )
        )
    return notes


def _front_view(ax, c, arms, _mm_text):
    """A small front view of an arms wheel: rim, hub, bore, key seat and the arms, not dimensioned."""
    from matplotlib.patches import Circle, Polygon, Rectangle, Wedge

    r_o, r_i = c.d_outer / 2.0, c.d_inner / 2.0
    r_hub, r_bore = c.d_hub / 2.0, (c.bore or 0.0) / 2.0
    grey = {"facecolor": "#e8ebf0", "edgecolor": "black", "lw": 0.9}
    ax.add_patch(Wedge((0, 0), r_o, 0, 360, width=r_o - r_i, **grey))
    half = arms[2] / 2.0
    for k in range(c.n_arms):
        angle = math.pi / 2 + 2 * math.pi * k / c.n_arms
        u = np.array([math.cos(angle), math.sin(angle)])
        v = np.array([-u[1], u[0]])
        # the arm's sides run from the hub circle to the rim circle
        corners = []
        for side in (-half, half):
            for r in (r_hub, r_i):
                along = math.sqrt(max(r * r - side * side, 0.0))
                corners.append(tuple(along * u + side * v))
        corners = [corners[0], corners[1], corners[3], corners[2]]
        ax.add_patch(Polygon(corners, closed=True, gid="arm", **grey))
    ax.add_patch(Circle((0, 0), r_hub, **grey))
    ax.add_patch(Circle((0, 0), r_bore, facecolor="white", edgecolor="black", lw=0.9))
    if c.key:
        b_key, t2 = c.key["b"], c.key["t2"]
        ax.add_patch(
            Rectangle(
                (-b_key / 2, r_bore - 0.002 * r_o),
                b_key,
                t2 + 0.002 * r_o,
                facecolor="white",
                edgecolor="black",
                lw=0.9,
            )
        )
    reach = 1.08 * r_o
    for xs, ys in (([-reach, reach], [0, 0]), ([0, 0], [-reach, reach])):
        ax.plot(xs, ys, color="black", lw=0.5, ls=(0, (12, 3, 2, 3)))
    ax.set_aspect("equal")
    ax.set_xlim(-1.1 * r_o, 1.1 * r_o)
    ax.set_ylim(-1.1 * r_o, 1.1 * r_o)
    ax.set_axis_off()
    ax.set_title(
        f"front view: {c.n_arms} arms of elliptical section\n{_mm_text(arms[2])} × {_mm_text(arms[3])} (a × a/2)",
        fontsize=_DIM_FONT,
    )
