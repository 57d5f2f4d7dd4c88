"""Diagrams of a scene, its analysis and its design (matplotlib).

Each ``plot_*`` function draws on a given Axes (or a new figure) and returns
the Axes; :func:`save` writes a figure atomically (to a temporary file in the
same folder, then renamed), so a failed render leaves nothing half-written.
The backend is Agg unless the caller chose another one.

The plots draw computed results and never run a model: what a diagram needs
beyond the :class:`~flyopt.analysis.Analysis` (the speed over the cycle, a
simulation, a design) is computed by the caller and passed in. A diagram that
cannot be drawn for this scene raises :class:`ValueError`; one that would be
empty because the machine needs no flywheel raises :class:`NothingToDraw`.
"""

import math
import os
import tempfile
from pathlib import Path

import numpy as np

from flyopt.cycle.indicator import ExcessWork
from flyopt.errors import SceneError
from flyopt.units import rad_s_to_rpm

SURPLUS, DEFICIT = "#2e8b57", "#c0392b"
PLOTS = {
    "turning_moment": "driving and resisting torque over the cycle, areas shaded and labelled",
    "energy": "energy indicator diagram: the chain of ΔE with A_max marked",
    "inertia_delta": "required flywheel J against δ (the hyperbola), the scene's δ marked",
    "cross_section": "dimensioned axial section of the chosen flywheel (hub, web or arms, rim), in mm",
    "stress": "σ_r, σ_t and von Mises over the radius at ω_max, each part's allowable, the governing point",
    "speed": "ω(φ) over the cycle with the required flywheel, from the model that ran",
    "energy_mass": "energy–mass (Wittenbauer) diagram: ΔE against J_e with the two tangents",
}
#: Image formats :func:`save` writes, by the suffix of the file.
FORMATS = ("png", "svg", "pdf")


class NothingToDraw(Exception):
    """The diagram would be empty for this machine (no flywheel is needed): not an error."""


def check_output(path):
    """Check the file a diagram will go to, before anything is computed.

    Parameters
    ----------
    path : str or Path
        The output file; its suffix picks the format (:data:`FORMATS`).

    Raises
    ------
    SceneError
        Field ``-o/--output``: an unsupported suffix, or a folder that does
        not exist (flyopt does not create folders the user did not ask for).
    """
    path = Path(path)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise SceneError("-o/--output", f"{str(path)!r} must end in .png, .svg or .pdf "
                         f"(the suffix picks the format)")
    folder = path.parent
    if not folder.is_dir():
        raise SceneError("-o/--output", f"the folder {str(folder)!r} does not exist")


def _pyplot():
    import matplotlib

    if "MPLBACKEND" not in os.environ and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _axes(ax, figsize=(8, 4.5)):
    if ax is not None:
        return ax
    plt = _pyplot()
    return plt.figure(figsize=figsize, layout="constrained").add_subplot()


def _excess_work(scene, analysis):
    """ΔE of the torques as the analysis saw them (members' loads joined, a motor at its mean)."""
    if analysis.machine is not None:
        return analysis.machine.angle_only()
    return ExcessWork(scene.driving, scene.resisting, scene.cycle_angle)


def _curve_samples(curve, cycle_angle, n=2000):
    """Angles and values that draw a torque curve exactly (tables at their points)."""
    from flyopt.machine.torque import Constant, PiecewiseLinear

    if isinstance(curve, PiecewiseLinear):
        return curve.angles, curve.values
    if isinstance(curve, Constant):
        return np.array([0.0, cycle_angle]), np.array([curve.value, curve.value])
    phi = np.linspace(0.0, cycle_angle, n)
    return phi, curve(phi)


def plot_turning_moment(scene, analysis, ax=None):
    """Turning-moment diagram: M_d and M_r over the cycle, surplus and deficit shaded.

    Each area between crossings is labelled with its energy [J]; the angles of
    ω_max and ω_min are marked. Net-area scenes have no curves: their areas are
    drawn as a bar chart instead.
    """
    ax = _axes(ax)
    ind = analysis.indicator
    if scene.net is not None:
        areas = ind.areas
        ax.bar(np.arange(1, len(areas) + 1), areas, color=[SURPLUS if a > 0 else DEFICIT for a in areas])
        ax.axhline(0, color="black", lw=0.8)
        ax.set(xlabel="area (in order over the cycle)", ylabel="energy [J]",
               title=f"{analysis.title}: net areas between the torque curves")
        return ax
    ew = _excess_work(scene, analysis)
    grid = np.union1d(np.linspace(0, scene.cycle_angle, 3000), ind.chain_angle)
    grid = np.union1d(grid, ew.knots)
    d = _curve_samples(ew.driving, scene.cycle_angle)
    r = _curve_samples(ew.resisting, scene.cycle_angle)
    md = np.interp(grid, *d) if not hasattr(ew.driving, "expression") else ew.driving(grid)
    mr = np.interp(grid, *r) if not hasattr(ew.resisting, "expression") else ew.resisting(grid)
    deg = np.degrees(grid)
    ax.fill_between(deg, md, mr, where=md >= mr, color=SURPLUS, alpha=0.3, interpolate=True, lw=0)
    ax.fill_between(deg, md, mr, where=md < mr, color=DEFICIT, alpha=0.3, interpolate=True, lw=0)
    ax.plot(np.degrees(d[0]), d[1], color="tab:blue", lw=1.8, label="driving M_d")
    ax.plot(np.degrees(r[0]), r[1], color="black", lw=1.8, label="resisting M_r")
    span = max(np.ptp(np.concatenate([md, mr])), 1e-12)
    for left, right, area in zip(ind.chain_angle[:-1], ind.chain_angle[1:], ind.areas):
        if right - left < 0.02 * scene.cycle_angle and abs(area) < 0.05 * max(ind.a_max, 1e-300):
            continue
        mid = 0.5 * (left + right)
        y = 0.5 * (np.interp(mid, grid, md) + np.interp(mid, grid, mr))
        ax.annotate(f"{area:+.4g} J", (math.degrees(mid), y), ha="center", va="center", fontsize=8,
                    color=SURPLUS if area > 0 else DEFICIT)
    for angle, label in ((analysis.angle_omega_max, "ω_max"), (analysis.angle_omega_min, "ω_min")):
        ax.axvline(math.degrees(angle), color="gray", ls="--", lw=0.8)
        ax.text(math.degrees(angle), 0.97, f" {label}", transform=ax.get_xaxis_transform(), ha="left", va="top",
                fontsize=8, color="gray")
    ax.set(xlabel="crank angle φ [deg]", ylabel="torque [N·m]", xlim=(0, math.degrees(scene.cycle_angle)),
           title=f"{analysis.title}: turning-moment diagram (A_max = {analysis.a_max:.5g} J)")
    ax.margins(y=0.08 if span else 0.5)
    ax.legend(loc="best", fontsize=8)
    return ax


def plot_energy(scene, analysis, ax=None):
    """Energy indicator diagram: ΔE from the cycle start, the chain points and A_max."""
    ax = _axes(ax)
    ind = analysis.indicator
    chain = ind.chain_delta_e
    if ind.chain_angle is None:
        x = np.arange(len(chain))
        ax.plot(x, chain, "o-", color="tab:blue")
        ax.set_xlabel("end of area")
        where_max, where_min = x[ind.index_max], x[ind.index_min]
    else:
        ew = _excess_work(scene, analysis)
        phi = np.union1d(np.linspace(0, scene.cycle_angle, 1500), ind.chain_angle)
        ax.plot(np.degrees(phi), ew(phi), color="tab:blue", lw=1.5, label="ΔE(φ)")
        ax.plot(np.degrees(ind.chain_angle), chain, "o", color="black", ms=4, label="crossings")
        ax.set_xlabel("crank angle φ [deg]")
        where_max, where_min = np.degrees(ind.chain_angle[[ind.index_max, ind.index_min]])
    hi, lo = chain[ind.index_max], chain[ind.index_min]
    ax.axhline(hi, color=SURPLUS, ls=":", lw=1)
    ax.axhline(lo, color=DEFICIT, ls=":", lw=1)
    x_arrow = 0.5 * (where_max + where_min)
    ax.annotate("", (x_arrow, hi), (x_arrow, lo), arrowprops={"arrowstyle": "<->", "color": "gray"})
    ax.annotate(f"A_max = {ind.a_max:.5g} J", (x_arrow, 0.5 * (hi + lo)), ha="left", va="center", fontsize=9)
    ax.set(ylabel="excess work ΔE [J]", title=f"{analysis.title}: energy indicator diagram")
    return ax


def plot_inertia_delta(scene, analysis, ax=None):
    """J_F against δ: J_F = A_max/(ω_m² δ) − J_c, an equilateral hyperbola, the scene's δ marked.

    J_F is positive only below δ* = A_max/(ω_m² J_c), where the machine's own
    inertia stops sufficing; the δ axis reaches down to δ*/20 when the scene's
    δ lies above it, and δ* is marked.

    Raises
    ------
    NothingToDraw
        A_max = 0: no flywheel is needed for any δ.
    """
    if analysis.a_max <= 0:
        raise NothingToDraw("no flywheel is needed for any δ (A_max = 0 J, so J_F(δ) = 0): nothing to draw")
    ax = _axes(ax)
    omega2 = analysis.omega_mean**2
    delta_free = analysis.a_max / (omega2 * analysis.j_constant) if analysis.j_constant > 0 else math.inf
    lo, hi = min(analysis.delta, delta_free) / 20, min(1.9, analysis.delta * 20)
    delta = np.geomspace(lo, hi, 200)
    j = analysis.a_max / (omega2 * delta) - analysis.j_constant
    ax.plot(delta, np.where(j > 0, j, np.nan), color="tab:blue", label="J_F(δ)")
    if delta_free < hi:
        ax.axvline(delta_free, color="gray", ls="--", lw=0.8,
                   label=f"δ* = {delta_free:.4g}: J_F = 0 above (J_c suffices)")
    if analysis.flywheel_needed:
        ax.plot([analysis.delta], [analysis.j_required], "o", color=DEFICIT,
                label=f"δ = {analysis.delta:.4g}: J_F = {analysis.j_required:.4g} kg·m²")
    ax.set(xscale="log", yscale="log", xlabel="coefficient of speed fluctuation δ",
           ylabel="required flywheel J_F [kg·m²]", title=f"{analysis.title}: J grows like 1/δ")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax


#: Font size of dimensions and notes on the drawing [pt].
_DIM_FONT = 8
#: Distance between stacked dimension lines, and of the first from the part [in].
_DIM_STEP, _DIM_FIRST = 0.30, 0.34
#: Extension lines: gap from the part, overshoot past the dimension line [in].
_EXT_GAP, _EXT_OVER = 0.03, 0.06
#: Height the wheel's outer diameter is drawn at when the function makes its own figure [in].
_SECTION_HEIGHT = 6.4
_SECTION_HATCH = dict(facecolor="#e8ebf0", edgecolor="black", linewidth=0, hatch="////")


def _mm_text(metres):
    """A length in mm as a drawing gives it: to 0.1 mm, no trailing zeros."""
    return f"{metres * 1e3:.1f}".rstrip("0").rstrip(".")


def _text_width(text, size=_DIM_FONT):
    """Rough width of a line of text [in] (DejaVu Sans: about 0.6 em per character)."""
    return 0.6 * size * len(text) / 72.0


class _Sheet:
    """Draws dimensions on an Axes of equal aspect whose scale is known: ``scale`` inches per metre."""

    def __init__(self, ax, scale):
        self.ax, self.scale = ax, scale

    def d(self, inches):
        """A length on the sheet [in] in data units [m]."""
        return inches / self.scale

    def _arrow(self, tip, tail):
        self.ax.annotate("", tip, tail, arrowprops={"arrowstyle": "-|>", "lw": 0.7, "color": "black",
                                                     "mutation_scale": 7, "shrinkA": 0, "shrinkB": 0})

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
            The two ends [m] on the measured axis.
        line : float
            Where the dimension line runs, on the other axis [m].
        text : str
        vertical : bool
        feature : tuple of float or None
            Where on the other axis the extension lines start at ``a`` and
            ``b`` (the part's edges); None: the dimension line spans the part.
        room : float or None
            A horizontal dimension's text may be this wide, centred [m] (it
            must clear the next extension lines out); None: the dimension's length.
        beside : {1, -1} or None
            Put a horizontal dimension's text beside its line, right (1) or
            left (-1); None: above where it fits, else away from the middle.
        """
        ax, d = self.ax, self.d
        lo, hi = min(a, b), max(a, b)

        def point(along, across):
            return (across, along) if vertical else (along, across)

        away = 1.0 if feature is None or line >= feature[0] else -1.0   # from the part towards the line
        if feature is not None:
            for end, start in zip((a, b), feature):
                p0, p1 = point(end, start + away * d(_EXT_GAP)), point(end, line + away * d(_EXT_OVER))
                ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="black", lw=0.5, solid_capstyle="butt")
        length = (hi - lo) * self.scale
        inside = length > 0.32
        arrow = {"lw": 0.7, "color": "black", "mutation_scale": 7, "shrinkA": 0, "shrinkB": 0}
        if inside:
            ax.annotate("", point(lo, line), point(hi, line), arrowprops={"arrowstyle": "<|-|>", **arrow})
        else:   # too short for arrows inside: arrows from outside, pointing in
            ax.plot(*zip(point(lo, line), point(hi, line)), color="black", lw=0.7)
            for tip, tail in ((lo, lo - d(0.16)), (hi, hi + d(0.16))):
                ax.annotate("", point(tip, line), point(tail, line), arrowprops={"arrowstyle": "-|>", **arrow})
        fits = _text_width(text) < length - 0.12
        off = d(_EXT_OVER + 0.03)
        if vertical:
            side = -1.0 if fits or (feature is not None and away < 0) else away
            ax.text(line + side * off, 0.5 * (lo + hi), text, rotation=90, rotation_mode="anchor",
                    ha="center", va="bottom" if side < 0 else "top", fontsize=_DIM_FONT)
        elif beside is None and feature is not None and \
                _text_width(text) < max(length, (room or 0.0) * self.scale) - 0.08:
            ax.text(0.5 * (lo + hi), line + off, text, ha="center", va="bottom", fontsize=_DIM_FONT)
        else:
            right = beside > 0 if beside is not None else 0.5 * (lo + hi) >= 0
            gap = d(0.2) if not inside else d(0.06)
            ax.text(hi + gap if right else lo - gap, line, text, ha="left" if right else "right",
                    va="center", fontsize=_DIM_FONT)


def _section_parts(c):
    """The hatched blocks of the axial half-section: (name, r_inner, r_outer, axial width) [m], inner first,
    and the arms (r_inner, r_outer, major, minor) or None."""
    r_o = c.d_outer / 2.0
    r_bore = (c.bore or 0.0) / 2.0
    if c.geometry == "disc":
        return [("disc", r_bore, r_o, c.b)], None
    r_i = c.d_inner / 2.0
    rim = ("rim", r_i, r_o, c.b)
    if c.geometry == "rim_web":
        if not c.bore:
            return [("web", 0.0, r_i, c.t_web), rim], None
        return [("hub", r_bore, c.d_hub / 2.0, c.l_hub), ("web", c.d_hub / 2.0, r_i, c.t_web), rim], None
    if c.geometry == "rim_arms":
        return [("hub", r_bore, c.d_hub / 2.0, c.l_hub), rim], (c.d_hub / 2.0, r_i, c.arm_major, c.arm_minor)
    return [rim], None


def _outline(blocks):
    """The outline of contiguous centred blocks (the upper half), as polygon vertices."""
    right = []
    for _name, r0, r1, w in blocks:
        right += [(w / 2.0, r0), (w / 2.0, r1)]
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


def plot_cross_section(candidate, ax=None):
    """Dimensioned axial section of a designed wheel, mirrored about the axis, dimensions in mm.

    The hub (bore to D_hub, length l_hub), the web (t_web) and the rim (H x B)
    are drawn hatched as one casting; the arms of a ``rim_arms`` wheel are
    drawn unhatched (they are not cut: the drafting rule for spokes) with
    their elliptical section revolved into the view, and a small front view
    beside the section shows their number. A bare rim or disc draws alone.

    Parameters
    ----------
    candidate : flyopt.design.result.Candidate
        A feasible design.
    ax : matplotlib Axes, optional
        Where to draw the section; by default a new figure sized so that the
        dimensions are legible (and, for arms, with the front view beside it).

    Returns
    -------
    matplotlib Axes
        The section. Every hatched block is a Rectangle whose ``gid`` is its
        part and half: ``"rim+"``, ``"hub-"``...; the revolved arm section an
        Ellipse with gid ``"arm_section"``.
    """
    from matplotlib.patches import Ellipse, Polygon, Rectangle

    c = candidate
    if not c.feasible or c.d_outer is None:
        raise ValueError(f"{c.material} on {c.shaft} is not a design: nothing to draw")
    blocks, arms = _section_parts(c)
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
    n_right = len(diameters)
    left_in = (_DIM_FIRST + 0.45) if has_rim else 0.3           # H (and the arm's a) on the left
    right_in = _DIM_FIRST + _DIM_STEP * (n_right - 1) + 0.3
    top_in = _DIM_FIRST + 0.25
    bottom_in = 0.25
    own = ax is None
    if own:
        plt = _pyplot()
        scale = min(_SECTION_HEIGHT / (2 * r_o), 5.0 / w_max)      # [in/m]
        width_in = w_max * scale + left_in + right_in
        height_in = 2 * r_o * scale + top_in + bottom_in
        front_in = 0.62 * 2 * r_o * scale + 0.6 if arms else 0.0   # the front view, smaller
        title_in, margin = 0.75, 0.3
        fig_w = max(width_in + front_in + 2 * margin, 7.0)
        fig_h = height_in + title_in + 2 * margin
        fig = plt.figure(figsize=(fig_w, fig_h))
        x0 = (fig_w - width_in - front_in) / 2.0
        ax = fig.add_axes([x0 / fig_w, margin / fig_h, width_in / fig_w, height_in / fig_h])
        if arms:
            size = 0.62 * 2 * r_o * scale + 0.3
            front = fig.add_axes([(x0 + width_in + 0.3) / fig_w, (margin + (height_in - size) / 2) / fig_h,
                                  size / fig_w, size / fig_h])
            _front_view(front, c, arms)
    else:
        box = ax.get_position()
        fig_w, fig_h = ax.figure.get_size_inches()
        scale = min((box.height * fig_h - top_in - bottom_in) / (2 * r_o),
                    (box.width * fig_w - left_in - right_in) / w_max)
        scale = max(scale, 1e-9)
    sheet = _Sheet(ax, scale)
    d = sheet.d
    for group in _groups(blocks):
        for sign in (1, -1):
            for name, r0, r1, w in group:
                y = r0 if sign > 0 else -r1
                ax.add_patch(Rectangle((-w / 2.0, y), w, r1 - r0, gid=f"{name}{'+' if sign > 0 else '-'}",
                                       **_SECTION_HATCH))
        upper = _outline(group)
        if group[0][1] > 0:      # a bore: the halves are two sections
            outlines = [upper, [(x, -y) for x, y in upper]]
        else:                    # solid to the centre: one section, no line on the axis
            right = upper[: len(upper) // 2]
            side = [(x, -y) for x, y in reversed(right)] + right[1:]
            outlines = [side + [(-x, y) for x, y in reversed(side)]]
        for outline in outlines:
            ax.add_patch(Polygon(outline, closed=True, fill=False, edgecolor="black", lw=1.2))
    if arms:
        r0, r1, major, minor = arms
        for sign in (1, -1):
            ax.add_patch(Rectangle((-minor / 2.0, r0 if sign > 0 else -r1), minor, r1 - r0, fill=False,
                                   edgecolor="black", lw=1.0, gid=f"arms{'+' if sign > 0 else '-'}"))
        middle = 0.5 * (r0 + r1)
        ax.add_patch(Ellipse((0.0, middle), minor, major, gid="arm_section", zorder=3, **_SECTION_HATCH))
        ax.add_patch(Ellipse((0.0, middle), minor, major, fill=False, edgecolor="black", lw=1.0, zorder=3))
    # the axis: dash-dot, a little past the outline
    reach = w_max / 2.0 + d(0.06)   # short of the text of the first diameter
    ax.plot([-reach, reach], [0, 0], color="black", lw=0.6, ls=(0, (12, 3, 2, 3)))
    # diameters, right of the section
    for k, (r, x_edge, _name) in enumerate(diameters):
        line = w_max / 2.0 + d(_DIM_FIRST + _DIM_STEP * k)
        sheet.linear(-r, r, line, f"Ø{_mm_text(2 * r)}", vertical=True, feature=(x_edge, x_edge))
    # the width above (nothing else is there: its text may overhang the extension lines)
    sheet.linear(-c.b / 2.0, c.b / 2.0, r_o + d(_DIM_FIRST), f"B {_mm_text(c.b)}", vertical=False,
                 feature=(r_o, r_o), room=c.b + d(1.0))
    if has_hub:   # the hub's length just outside it (not above the rim: its extension lines would
        # run the height of the drawing and read as outlines), its text left, clear of the diameters
        hub = blocks[0]
        sheet.linear(-hub[3] / 2.0, hub[3] / 2.0, hub[2] + d(0.22), f"l_hub {_mm_text(hub[3])}",
                     vertical=False, feature=(hub[2], hub[2]), beside=-1)
    if has_rim:
        rim = blocks[-1]
        line = -w_max / 2.0 - d(_DIM_FIRST)
        sheet.linear(rim[1], rim[2], line, f"H {_mm_text(rim[2] - rim[1])}", vertical=True,
                     feature=(-c.b / 2.0, -c.b / 2.0))
    # web or arm thickness, across it in the lower half
    thin = [b for b in blocks if b[0] == "web"]
    if thin:
        _name, r0, r1, w = thin[0]
        sheet.linear(-w / 2.0, w / 2.0, -0.5 * (r0 + r1), f"t_web {_mm_text(w)}", vertical=False)
    if arms:
        r0, r1, major, minor = arms
        middle = 0.5 * (r0 + r1)
        sheet.linear(-minor / 2.0, minor / 2.0, -middle, f"a/2 {_mm_text(minor)}", vertical=False)
        sheet.linear(middle - major / 2.0, middle + major / 2.0, -w_max / 2.0 - d(_DIM_FIRST),
                     f"a {_mm_text(major)}", vertical=True, feature=(0.0, 0.0))
    ax.set_aspect("equal")
    ax.set_xlim(-w_max / 2.0 - d(left_in), w_max / 2.0 + d(right_in))
    ax.set_ylim(-r_o - d(bottom_in), r_o + d(top_in))
    ax.set_axis_off()
    what = {"rim_arms": f"rim on {c.n_arms} arms", "rim_web": "rim and web", "thin_rim": "thin rim"}.get(
        c.geometry, c.geometry)
    title = (f"Flywheel, {what}: {c.material}, {c.mass:.4g} kg, J = {c.j_flywheel:.4g} kg·m² on {c.shaft}\n"
             f"axial section{', arm section revolved' if arms else ''}, dimensions in mm")
    if own:   # the figure is this drawing's: its title over both views
        ax.figure.suptitle(title, fontsize=10)
    else:
        ax.set_title(title, fontsize=9)
    return ax


def _front_view(ax, c, arms):
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
        ax.add_patch(Rectangle((-b_key / 2, r_bore - 0.002 * r_o), b_key, t2 + 0.002 * r_o, facecolor="white",
                               edgecolor="black", lw=0.9))
    reach = 1.08 * r_o
    for xs, ys in (([-reach, reach], [0, 0]), ([0, 0], [-reach, reach])):
        ax.plot(xs, ys, color="black", lw=0.5, ls=(0, (12, 3, 2, 3)))
    ax.set_aspect("equal")
    ax.set_xlim(-1.1 * r_o, 1.1 * r_o)
    ax.set_ylim(-1.1 * r_o, 1.1 * r_o)
    ax.set_axis_off()
    ax.set_title(f"front view: {c.n_arms} arms of elliptical section\n{_mm_text(arms[2])} × "
                 f"{_mm_text(arms[3])} (a × a/2)", fontsize=_DIM_FONT)


#: Colours of the stress curves.
_STRESS_COLOURS = {"sr": "tab:blue", "st": "tab:red", "vm": "black"}
#: Shades of the parts' spans, inner to outer.
_PART_SHADES = ("#eef1f6", "#f8f4ea")


def plot_stress(candidate, profile, beams=(), omega=None, ductile=True, ax=None):
    """sigma_r, sigma_t and von Mises over the radius at omega_max, each part's span and allowable.

    Parameters
    ----------
    candidate : flyopt.design.result.Candidate
        A feasible design with its ``parts`` and ``stress`` (the check the
        design carries: each part's governing stress and allowable).
    profile : list of (part, r, sr, st, vm)
        The stresses of the disc parts over their radii [m, Pa], from
        :func:`flyopt.design.strength.profile` at the same speed.
    beams : list of (part, r, sr, st)
        The parts of a ``rim_arms`` wheel the texts treat as beams: the arms'
        root stress (a radial stress at the hub) and the rim's combined hoop
        and bending stress (at its mean radius) [m, Pa].
    omega : float or None
        The speed the stresses are at, on the wheel's shaft [rad/s] (for the title).
    ductile : bool
        Whether the governing stress is von Mises (True) or the largest
        principal stress (False).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
        Lines labelled "σ_r", "σ_t" and "von Mises" (the first part's; the
        others' carry a leading underscore), in MPa over mm.
    """
    c = candidate
    if not c.feasible or not c.parts:
        raise ValueError(f"{c.material} on {c.shaft} is not a design: no stresses to draw")
    if not c.stress:
        raise ValueError(f"the design of {c.material} carries no stresses (its notes: "
                         f"{'; '.join(c.notes) or 'none'})")
    ax = _axes(ax, figsize=(9, 5.2))
    mm, mpa = 1e3, 1e-6
    checked = {p["part"]: p for p in c.stress.get("parts", [])}
    spans = {p["name"]: (p["r_inner"], p["r_outer"]) for p in c.parts}
    # the parts' spans, shaded and named at the top
    for k, p in enumerate(c.parts):
        r0, r1 = p["r_inner"] * mm, p["r_outer"] * mm
        ax.axvspan(r0, r1, color=_PART_SHADES[k % 2], lw=0, zorder=0)
        ax.axvline(r0, color="gray", lw=0.5, zorder=1)
        narrow = (r1 - r0) < 0.06 * c.d_outer / 2 * mm
        ax.text(0.5 * (r0 + r1), 0.985, p["name"], transform=ax.get_xaxis_transform(), ha="center", va="top",
                fontsize=8, color="dimgray", rotation=90 if narrow else 0)
    # the curves of the disc parts
    names = {"sr": "σ_r", "st": "σ_t", "vm": "von Mises"}
    for k, (part, r, sr, st, vm) in enumerate(profile):
        for key, values, style in (("sr", sr, "-"), ("st", st, "-"), ("vm", vm, "--")):
            ax.plot(np.asarray(r) * mm, np.asarray(values) * mpa, style, color=_STRESS_COLOURS[key], lw=1.5,
                    label=names[key] if k == 0 else f"_{names[key]}")
    # each part's allowable over its span
    allowables = [(name, checked[name]["allowable"]) for name in spans
                  if name in checked and _finite_positive(checked[name].get("allowable"))]
    same = len({a for _n, a in allowables}) == 1
    for k, (name, allowable) in enumerate(allowables):
        label = (f"allowable {allowable * mpa:.4g} MPa" if same else "allowable of each part") if k == 0 else \
            "_allowable"
        ax.hlines(allowable * mpa, spans[name][0] * mm, spans[name][1] * mm, colors=DEFICIT, linestyles=":",
                  lw=1.8, label=label)
        if not same:
            ax.annotate(f"{allowable * mpa:.4g}", (0.5 * (spans[name][0] + spans[name][1]) * mm, allowable * mpa),
                        xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", fontsize=7,
                        color=DEFICIT)
    # the beams of an arms wheel
    beam_words = {"arms": ("arm root (pull + bending)", "^"), "rim": ("rim (hoop + bending)", "s")}
    for part, r, sr, st in beams:
        value = sr if part == "arms" else st
        words, marker = beam_words.get(part, (part, "o"))
        ax.plot([r * mm], [value * mpa], marker, color="tab:purple", ms=8, zorder=4,
                label=f"{words}: {value * mpa:.4g} MPa")
        at = r / (c.d_outer / 2)       # near an end of the axis the label turns inwards
        ha, dx = ("left", -4) if at < 0.15 else ("right", 4) if at > 0.85 else ("center", 0)
        ax.annotate(f"{words}\n{value * mpa:.4g} MPa", (r * mm, value * mpa), xytext=(dx, -12),
                    textcoords="offset points", ha=ha, va="top", fontsize=8, color="tab:purple")
    # the governing point
    where = c.stress.get("where") or {}
    governing = checked.get(where.get("part"))
    if governing is not None:
        measure = "von Mises" if ductile else "largest principal"
        utilisation = governing["stress"] / governing["allowable"] if governing.get("allowable") else math.nan
        x, y = governing["radius"] * mm, governing["stress"] * mpa
        ax.plot([x], [y], "o", ms=11, mfc="none", mec="black", mew=1.5, zorder=5,
                label=f"governing: {governing['part']}, {measure} {y:.4g} MPa at r = {x:.4g} mm "
                      f"({100 * utilisation:.0f} % of allowable)")
    ax.axhline(0, color="black", lw=0.6)
    top = max([a for _n, a in allowables] + [governing["stress"] if governing else 0.0]) * mpa
    r_in, r_out = min(spans.values())[0] * mm, c.d_outer / 2 * mm
    # from the axis, unless the wheel is a ring far from it (a bare rim): then its own span
    left = 0.0 if r_in < 0.4 * r_out else r_in - 0.08 * (r_out - r_in)
    ax.set_xlim(left, r_out + 0.03 * (r_out - left))
    low = min([0.0] + [float(np.min(np.minimum(sr, st))) * mpa for _p, _r, sr, st, _v in profile])
    ax.set_ylim(low - 0.05 * top, 1.25 * top if top > 0 else 1.0)
    speed = f" = {omega:.5g} rad/s ({rad_s_to_rpm(omega):.5g} rpm)" if omega else ""
    ax.set(xlabel="radius r [mm]", ylabel="stress [MPa]",
           title=f"{c.material} {c.geometry} on {c.shaft}: stresses at ω_max{speed}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    return ax


def _finite_positive(value):
    return value is not None and math.isfinite(value) and value > 0


def plot_speed(scene, analysis, speed=None, simulation=None, ax=None):
    """ω(φ) over the cycle with the required flywheel, from the model that ran.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    speed : SpeedFluctuation or PeriodicSolution, optional
        The model's speed over the cycle: ``phi`` [rad] and ``omega`` [rad/s].
        Energy models: ω² = 2 (E_0 + ΔE)/J_e with E_0 such that
        (ω_max + ω_min)/2 = ω_m (docs/flywheel-design.md, section 6, forward
        use: :func:`flyopt.sizing.energy_mass.achieved_speed`); the dynamic
        model: its periodic solution, which the analysis carries (the default).
    simulation : PeriodicSolution, optional
        The periodic simulation of the machine with that flywheel (the
        verification's), drawn over it: ``phi``, ``omega`` and ``delta``.
    ax : matplotlib Axes, optional

    Raises
    ------
    ValueError
        A net-area scene: it has no angles; or no ``speed`` for an analysis
        whose result does not carry one (the energy models).
    """
    if scene.net is not None:
        raise ValueError("a net-area scene has no angles: ω(φ) cannot be drawn")
    if speed is None:
        if analysis.requirement is None or analysis.requirement.model != "dynamic":
            raise ValueError(f"the {analysis.model} model's result carries no ω(φ): pass speed "
                             f"(flyopt.sizing.energy_mass.achieved_speed with J_F)")
        speed = analysis.requirement.detail.solution
    ax = _axes(ax)
    omega = np.asarray(speed.omega)
    ax.plot(np.degrees(speed.phi), rad_s_to_rpm(omega), color="tab:blue", label=f"model: {analysis.model}")
    if simulation is not None:
        ax.plot(np.degrees(simulation.phi), rad_s_to_rpm(simulation.omega), color=DEFICIT, ls="--", lw=1,
                label=f"simulation (δ = {simulation.delta:.6g})")
    for value, label in ((omega.max(), "ω_max"), (omega.min(), "ω_min")):
        ax.axhline(rad_s_to_rpm(value), color="gray", ls=":", lw=0.8)
        ax.annotate(label, (0, rad_s_to_rpm(value)), fontsize=8, va="bottom")
    ax.set(xlabel="crank angle φ [deg]", ylabel="speed [rpm]", xlim=(0, math.degrees(scene.cycle_angle)),
           title=f"{analysis.title}: speed over the cycle (δ = {analysis.delta:.4g})")
    ax.legend(fontsize=8)
    return ax


def plot_energy_mass(scene, analysis, ax=None):
    """Wittenbauer's energy–mass diagram: ΔE against J_e over the cycle, with the two tangents.

    From the true origin (−J_F, −E_0) the lines of slope ω_max²/2 and ω_min²/2
    touch the curve where the speed is highest and lowest (docs/flywheel-design.md, section 6).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        Sized by the energy–mass model (``analyse(scene, model="energy_mass")``):
        ``analysis.requirement.detail`` is its EnergyMassRequirement
        (``j_required``, ``e0``, ``omega_max``, ``omega_min``).
    ax : matplotlib Axes, optional

    Raises
    ------
    ValueError
        Torques that depend on speed, or net areas; or an analysis by another model.
    NothingToDraw
        A_max = 0 with a constant inertia: the curve is one point.
    """
    check_energy_mass(analysis)
    if analysis.requirement is None or analysis.requirement.model != "energy_mass":
        raise ValueError(f"the energy–mass diagram draws the energy–mass model's result, and this "
                         f"analysis ran the {analysis.model} model: analyse with model='energy_mass'")
    machine = analysis.machine
    if analysis.a_max <= 0 and not machine.variable_inertia:
        raise NothingToDraw("no flywheel is needed and the diagram is one point (A_max = 0 J, constant "
                            "inertia): nothing to draw")
    ax = _axes(ax, figsize=(7, 5.5))
    em = analysis.requirement.detail
    ew = machine.angle_only()
    phi = np.union1d(np.linspace(0, scene.cycle_angle, 1500), ew.knots)
    j = np.broadcast_to(machine.j_machine(phi) if machine.variable_inertia else machine.j_machine, phi.shape)
    de = ew(phi)
    ax.plot(j, de, color="tab:blue", lw=1.5, label="(J_e(φ), ΔE(φ))")
    j_f = max(em.j_required, 0.0)
    x0, y0 = -j_f, -em.e0
    xs = np.array([x0, j.max() + 0.05 * (j.max() - x0)])
    for w, colour, label in ((em.omega_max, SURPLUS, "ω_max²/2"), (em.omega_min, DEFICIT, "ω_min²/2")):
        ax.plot(xs, y0 + 0.5 * w**2 * (xs - x0), color=colour, lw=1, ls="--", label=f"slope {label}")
    ax.plot([x0], [y0], "ko")
    ax.annotate(f"origin (−J_F, −E_0), J_F = {j_f:.4g} kg·m²", (x0, y0), fontsize=8, xytext=(5, 5),
                textcoords="offset points")
    span_x = j.max() - j.min()
    ax.set_xlim(j.min() - 0.5 * max(span_x, 1e-9), j.max() + 0.5 * max(span_x, 1e-9))
    span_y = de.max() - de.min()
    ax.set_ylim(de.min() - 0.3 * max(span_y, 1e-9), de.max() + 0.3 * max(span_y, 1e-9))
    if x0 < j.min() - 0.5 * max(span_x, 1e-9):
        ax.text(0.01, 0.01, f"tangents meet at (−J_F, −E_0) = ({x0:.4g} kg·m², {y0:.4g} J), off the plot",
                transform=ax.transAxes, fontsize=8, color="gray")
    ax.set(xlabel="equivalent inertia J_e [kg·m²]", ylabel="excess work ΔE [J]",
           title=f"{analysis.title}: energy–mass diagram")
    ax.legend(fontsize=8)
    return ax


def check_energy_mass(analysis):
    """Raise ValueError unless the energy–mass diagram can be drawn: torques of the angle only, as curves."""
    if analysis.machine is None or analysis.machine.speed_dependent:
        raise ValueError("the energy–mass diagram needs torques of the angle only given as curves")


RESULT_PLOTS = {
    "sweep": "a result of a sweep against a varied field, one line per group (--by)",
    "pareto": "a Pareto front: the non-dominated designs of two objectives",
}


def _label(column):
    units = {"mass": "kg", "d_outer": "m", "outer_diameter": "m", "d_mean": "m", "b": "m", "h": "m",
             "speed": "rad/s", "j_required": "kg·m²", "rim_speed": "m/s", "delta": "-", "cost": "currency"}
    unit = units.get(column)
    return f"{column} [{unit}]" if unit else column


def _column(frame, name):
    """The column a user names: itself, or the result of that name (``material`` is ``best_material``)."""
    for column in (name, f"best_{name}"):
        if column in frame.columns:
            return column
    raise ValueError(f"the results have no column {name!r} (columns: {', '.join(frame.columns)})")


def pareto_objectives(frame):
    """The two objectives of a front written by ``flyopt pareto``, or None.

    A front has an ``epsilon`` column (the constraint value of each point)
    and its two objectives as its first two columns, mass first.

    Returns
    -------
    tuple of str or None
        ``("mass", "outer_diameter")`` and so on; None for other results (a sweep).
    """
    columns = list(frame.columns)
    if "epsilon" not in columns or len(columns) < 3 or columns[0] != "mass":
        return None
    return tuple(columns[:2])


def plot_sweep(frame, x, y="mass", by=None, ax=None):
    """A sweep's result ``y`` against a varied field ``x``, one line per value of ``by``.

    Points that are not designed (infeasible, failed, not needed) are left out of
    the lines and counted in the legend. A field spanning more than a decade is
    drawn on a log axis. A name that is not a column may name a result:
    ``material`` and ``shaft`` are the winner's, ``best_material`` and
    ``best_shaft``, when the sweep did not vary them.
    """
    x, y = _column(frame, x), _column(frame, y)
    by = _column(frame, by) if by else None
    ax = _axes(ax)
    groups = frame.groupby(by, sort=True) if by else [(None, frame)]
    for key, part in groups:
        part = part.sort_values(x)
        ok = part["status"] == "designed" if "status" in part.columns else np.ones(len(part), bool)
        label = f"{by} = {key}" if by else y
        missing = int((~ok).sum())
        if missing:
            label += f" ({missing} not designed)"
        ax.plot(part[x][ok], part[y][ok], "o-", ms=3, lw=1.2, label=label)
    values = frame[x].to_numpy()
    positive = values[values > 0] if np.issubdtype(values.dtype, np.number) else values[:0]
    if positive.size and positive.max() / positive.min() > 10:
        ax.set_xscale("log")
    ax.set(xlabel=_label(x), ylabel=_label(y), title=f"sweep: {y} against {x}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_pareto(frame, x, y, ax=None):
    """The Pareto front of two objectives (both minimized), non-dominated points joined."""
    x, y = _column(frame, x), _column(frame, y)
    ax = _axes(ax)
    data = frame[[x, y]].dropna().to_numpy(dtype=float)
    order = np.lexsort((data[:, 1], data[:, 0]))
    data = data[order]
    front = data[np.concatenate(([True], data[1:, 1] < np.minimum.accumulate(data[:, 1])[:-1]))]
    ax.plot(data[:, 0], data[:, 1], "o", color="lightgray", ms=4, label="designs")
    ax.step(front[:, 0], front[:, 1], where="post", color=DEFICIT, lw=1.2)
    ax.plot(front[:, 0], front[:, 1], "o", color=DEFICIT, ms=5, label=f"Pareto front ({len(front)})")
    ax.set(xlabel=_label(x), ylabel=_label(y), title=f"Pareto front: {y} against {x}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def save(ax, path):
    """Write the Axes' figure to ``path`` (png, svg or pdf by suffix), atomically.

    Raises
    ------
    SceneError
        See :func:`check_output`.
    OSError
        The folder cannot be written; the error names ``path``.
    """
    check_output(path)
    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    fig = ax.figure
    try:
        handle, tmp = tempfile.mkstemp(suffix=path.suffix, dir=path.parent)
    except OSError as err:
        _pyplot().close(fig)
        raise OSError(err.errno, err.strerror, str(path)) from err
    os.close(handle)
    try:
        fig.savefig(tmp, format=suffix, dpi=150)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
        _pyplot().close(fig)
    return path
