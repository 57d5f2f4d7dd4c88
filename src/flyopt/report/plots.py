"""Diagrams of a scene, its analysis and its design (matplotlib).

Each ``plot_*`` function draws on a given Axes (or a new figure) and returns
the Axes; :func:`save` writes a figure atomically (to a temporary file in the
same folder, then renamed), so a failed render leaves nothing half-written.
The backend is Agg unless the caller chose another one.

The plots draw computed results and never run a model: what a diagram needs
beyond the :class:`~flyopt.analysis.Analysis` (the speed over the cycle, a
simulation, a design, J_F at other δ) is computed by the caller and passed
in. A diagram that does not apply to the scene raises :class:`ValueError`;
one that would be empty because the machine needs no flywheel raises
:class:`NothingToDraw`.

One visual standard for every diagram: each axis carries its unit in the
system the caller chose (``units``: :data:`flyopt.report.display.SYSTEMS`,
engineering by default: mm, rpm, kN·m, kJ, MPa), the legend sits outside
the data (below a figure the function made, right of an Axes it was
given), labels are placed where no curve and no other label is, and
titles are wrapped to the figure's width. The diagrams of one cycle share
their x axis: the cycle from 0 to Φ.
"""

import math
import os
import tempfile
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from flyopt.cycle.indicator import ExcessWork, required_inertia
from flyopt.delta_curve import delta_range, flywheel_at_some_delta
from flyopt.errors import SceneError
from flyopt.names import Geometry, Model
from flyopt.report import display

SURPLUS, DEFICIT = "#2e8b57", "#c0392b"
PLOTS = {
    "turning_moment": "driving and resisting torque over the cycle, areas shaded and labelled",
    "energy": "energy indicator diagram: the chain of ΔE with A_max marked",
    "inertia_delta": "required flywheel J_F against δ by the model that ran, the scene's δ marked",
    "cross_section": "dimensioned axial section of the chosen flywheel (hub, web or arms, rim)",
    "stress": "σ_r, σ_t and von Mises over the radius at ω_max, each part's allowable, the governing point",
    "speed": "ω(φ) over the cycle with the required flywheel, from the model that ran",
    "energy_mass": "energy–mass (Wittenbauer) diagram: ΔE against J_e with the two tangents "
    "(an inertia that varies with the angle)",
}
#: Image formats :func:`save` writes, by the suffix of the file.
FORMATS = ("png", "svg", "pdf")
#: Font size of legends and labels on the data [pt].
_FONT = 8.5
#: Significant digits of the numbers written on a diagram.
_DIGITS = 4


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
        raise SceneError("-o/--output", f"{str(path)!r} must end in .png, .svg or .pdf (the suffix picks the format)")
    folder = path.parent
    if not folder.is_dir():
        raise SceneError("-o/--output", f"the folder {str(folder)!r} does not exist")


def _pyplot():
    import matplotlib

    if "MPLBACKEND" not in os.environ and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --------------------------------------------------------------------------
# The visual standard: figures, units, titles, legends
# --------------------------------------------------------------------------


def _axes(ax, figsize=(9, 5.2)):
    """(Axes, own): the caller's Axes, or one on a new figure of constrained layout (own True)."""
    if ax is not None:
        return ax, False
    plt = _pyplot()
    return plt.figure(figsize=figsize, layout="constrained").add_subplot(), True


def _unit(dimension, units):
    """(label, factor) of a dimension in the unit system: shown = SI / factor."""
    return display.unit(dimension, units)


def _show(value, dimension, units):
    """An SI value or array in the system's unit of its dimension."""
    return display.show(np.asarray(value, dtype=float) if np.ndim(value) else float(value), dimension, units)


def _q(value, dimension, units, digits=_DIGITS):
    """A quantity as people read it, "0.4625 kN·m"."""
    return display.quantity_text(value, dimension, units, digits)


def _axis_label(words, dimension, units):
    """ "words [unit]" ("[-]" for a ratio: every axis says its unit)."""
    return f"{words} [{display.label(dimension, units)}]"


def _title(ax, own, *lines, size=11):
    """A title of several lines, each wrapped to the width it has (the figure's, or the Axes')."""
    fig = ax.figure
    width = fig.get_size_inches()[0] * (1.0 if own else ax.get_position().width)
    chars = max(int(width * 72 / (0.6 * size)) - 4, 20)
    text = "\n".join(textwrap.fill(line, chars) for line in lines if line)
    ax.set_title(text, fontsize=size)


def _legend(ax, own, title=None, ncol=2, handles=None):
    """The legend outside the data: below the figure the function made, right of a given Axes.

    Entries and title are wrapped to the width there is (the figure's, shared by ``ncol`` columns;
    about 40 characters beside a given Axes). Returns the Legend (``ax.figure.legends[-1]`` for an
    own figure, else ``ax.get_legend()``).
    """
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    else:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    ncol = min(ncol, len(handles))
    if own:
        chars = int((ax.figure.get_size_inches()[0] - 0.4) * 72 / (0.6 * _FONT))
        wrap, title_wrap = chars // ncol - 8, chars - 4
    else:
        ncol, wrap, title_wrap = 1, 40, 40
    labels = [_fill(label, wrap) for label in labels]
    if title:
        title = _fill(title, title_wrap)
    if own:
        return ax.figure.legend(
            handles,
            labels,
            loc="outside lower center",
            ncol=ncol,
            fontsize=_FONT,
            title=title,
            title_fontsize=_FONT,
            frameon=False,
        )
    return ax.legend(
        handles,
        labels,
        loc="upper left",
        bbox_to_anchor=(1.02, 1.0),
        borderaxespad=0.0,
        fontsize=_FONT,
        title=title,
        title_fontsize=_FONT,
        frameon=False,
    )


def _fill(text, width):
    """Wrap a line to ``width`` characters, never between a number and its unit ("0 mm", "1,512 rpm"),
    nor inside "name = value"."""
    import re

    kept = re.sub(r"(\d) (?=[^\s(=+−-])", "\\1\u00a0", text).replace(" = ", "\u00a0=\u00a0")
    return textwrap.fill(kept, width).replace("\u00a0", " ")


def _angle_axis(ax, cycle_angle, units):
    """The x axis of every diagram of the cycle: the crank angle from 0 to Φ, ticks at whole fractions."""
    from matplotlib.ticker import MultipleLocator

    end = float(_show(cycle_angle, "angle", units))
    ax.set_xlim(0.0, end)
    ax.set_xlabel(_axis_label("crank angle φ", "angle", units))
    if display.label("angle", units) == "deg":
        ax.xaxis.set_major_locator(MultipleLocator(90 if end > 400 else 45))
    return end


def _dead_centres(scene):
    """Marks of the crank's dead centres over the cycle, or None.

    Returns
    -------
    (major, minor, words) or None
        ``major``: [(angle [rad], "TDC"/"BDC" or "ODC"/"IDC")]; ``minor``:
        [(angle, stroke name)] between them (an engine's strokes); ``words``:
        what the marks are. An [engine]'s cylinder 1 (its TDC at its firing
        angle, the start of its cycle: docs/flywheel-design.md, section 14);
        a [mechanism] slider-crank's outer and inner dead centres, where the
        crank and the rod are in line: (l + r) sin ψ = e and (l − r) sin ψ = −e.
    """
    from flyopt.machine.kinematics import SliderCrank

    cycle = scene.cycle_angle
    turns = int(round(cycle / math.pi)) + 2
    if scene.engine is not None:
        engine = scene.engine
        start = float(engine.firing_angles[0])
        names = (
            ("intake", "compression", "power", "exhaust") if engine.cycle == "4-stroke" else ("power", "compression")
        )
        major, minor = [], []
        for k in range(-turns, turns + 1):
            angle = start + k * math.pi
            if -1e-9 <= angle <= cycle + 1e-9:
                major.append((min(max(angle, 0.0), cycle), "TDC" if k % 2 == 0 else "BDC"))
            middle = angle + 0.5 * math.pi
            if 0.0 < middle < cycle:
                minor.append((middle, names[k % len(names)]))
        cylinders = engine.cylinder_count
        words = (
            f"cylinder 1 of {cylinders}: dead centres and strokes"
            if cylinders > 1
            else f"the cylinder's dead centres and strokes ({engine.cycle})"
        )
        return major, minor, words
    mechanism = scene.mechanism
    if isinstance(mechanism, SliderCrank):
        r, l, e = mechanism.crank, mechanism.rod, mechanism.offset
        outer = mechanism.phase + math.asin(e / (l + r))
        inner = mechanism.phase + math.pi + math.asin(e / (l - r))
        major = []
        for k in range(-turns, turns + 1):
            for base, name in ((outer, "ODC"), (inner, "IDC")):
                angle = base + 2 * k * math.pi
                if -1e-9 <= angle <= cycle + 1e-9:
                    major.append((min(max(angle, 0.0), cycle), name))
        return sorted(major), [], "slider-crank dead centres: ODC outer (slider farthest from the crank), IDC inner"
    return None


def _mark_dead_centres(ax, scene, units):
    """The dead centres (and an engine's strokes) on a top axis, faint lines through the data."""
    marks = _dead_centres(scene)
    if marks is None:
        return None
    major, minor, words = marks
    top = ax.secondary_xaxis("top")
    top.set_gid("dead_centres")
    top.set_xticks([float(_show(a, "angle", units)) for a, _n in major], labels=[n for _a, n in major])
    top.set_xticks([float(_show(a, "angle", units)) for a, _n in minor], labels=[n for _a, n in minor], minor=True)
    top.tick_params(axis="x", which="major", labelsize=7.5)
    top.tick_params(axis="x", which="minor", length=0, labelsize=7, labelcolor="dimgray")
    top.set_xlabel(words, fontsize=_FONT)
    for angle, _name in major:
        ax.axvline(float(_show(angle, "angle", units)), color="0.8", lw=0.6, zorder=0)
    return top


# --------------------------------------------------------------------------
# The torques over the cycle, as the model that ran saw them
# --------------------------------------------------------------------------


def _excess_work(scene, analysis):
    """ΔE of the torques as the analysis saw them (members' loads joined, a motor at its mean)."""
    if analysis.machine is not None:
        return analysis.machine.angle_only()
    return ExcessWork(scene.driving, scene.resisting, scene.cycle_angle)


def _unknown(curve):
    from flyopt.cycle.torque import Constant

    return isinstance(curve, Constant) and curve.unknown


def _sides(phi, curve):
    """A curve's values on an increasing grid with repeated angles at its steps: left limit first."""
    left, right = curve.limits(phi)
    left = np.broadcast_to(np.asarray(left, dtype=float), phi.shape)
    value = np.array(np.broadcast_to(np.asarray(right, dtype=float), phi.shape))
    repeated = np.flatnonzero(np.diff(phi) == 0.0)
    value[repeated] = left[repeated]
    return value


def _along(curve, phi, omega):
    """A torque along a speed ω(φ) [N*m]: speed-dependent parts at each point's own speed.

    A motor is its characteristic M(i ω) i η (:meth:`MotorTorque.motor.reference_torque`,
    docs/flywheel-design.md, sections 3 and 7); an expression in ``omega`` is
    evaluated with ω(φ); angle-only curves as they are.
    """
    from flyopt.cycle.torque import ExpressionTorque, MotorTorque, TorqueSum

    if isinstance(curve, TorqueSum):
        return sum(_along(part, phi, omega) for part in curve.parts)
    if isinstance(curve, MotorTorque):
        return (
            np.asarray(
                curve.motor.reference_torque(omega, curve.speed_ratio, curve.efficiency, curve.model), dtype=float
            )
            + 0.0 * phi
        )
    if isinstance(curve, ExpressionTorque) and curve.speed_dependent:
        with np.errstate(all="ignore"):
            return curve.scale * np.asarray(curve.expression.numpy(phi=phi, omega=omega), dtype=float) + 0.0 * phi
    return _sides(phi, curve)


class _Torques:
    """The driving and resisting torques over the cycle [N*m] as the model that ran saw them.

    The energy models see torques of the angle only (an unknown constant
    solved from the work balance); the dynamic model sees every torque along
    its periodic solution ω(φ), a motor on its characteristic, not at its
    mean (docs/flywheel-design.md, section 7). ``phi`` repeats an angle where a
    torque steps (left limit first), so lines and shading draw the steps.
    """

    def __init__(self, scene, analysis):
        machine = analysis.machine
        balanced = machine.angle_only()
        self.along = analysis.model == Model.DYNAMIC
        self.driving_solved = _unknown(machine.driving)
        self.resisting_solved = _unknown(machine.resisting)
        self.motor = _is_motor(machine.driving)
        self.resisting_speed = bool(getattr(machine.resisting, "speed_dependent", False))
        if self.along:
            speed = analysis.requirement.detail.solution  # the periodic solution the dynamic model found
            phi, omega = np.asarray(speed.phi, dtype=float), np.asarray(speed.omega, dtype=float)
            offset = float(getattr(speed, "torque_offset", 0.0) or 0.0)
            # the periodic model's net torque: an unknown constant is the balancing one plus the offset
            self.driving = (
                np.full(phi.shape, balanced.driving.value + offset)
                if self.driving_solved
                else _along(machine.driving, phi, omega)
            )
            self.resisting = (
                np.full(phi.shape, balanced.resisting.value - offset)
                if self.resisting_solved
                else _along(machine.resisting, phi, omega)
            )
        else:
            ind = analysis.indicator
            phi = np.union1d(np.linspace(0.0, scene.cycle_angle, 3001), np.asarray(balanced.knots, dtype=float))
            phi = np.union1d(phi, ind.chain_angle)
            steps = np.zeros(phi.shape, bool)
            for curve in (balanced.driving, balanced.resisting):
                left, right = curve.limits(phi)
                steps |= np.asarray(left != right)
            phi = np.sort(np.concatenate([phi, phi[steps]]))
            self.driving = _sides(phi, balanced.driving)
            self.resisting = _sides(phi, balanced.resisting)
        self.phi = phi

    @property
    def net(self):
        return self.driving - self.resisting

    def excess_work(self):
        """ΔE(φ) = ∫_0^φ (M_d − M_r) dφ of the drawn torques, by the trapezoidal rule [J]."""
        from scipy.integrate import cumulative_trapezoid

        return cumulative_trapezoid(self.net, self.phi, initial=0.0)

    def areas(self):
        """(left, right, area) between the drawn curves from crossing to crossing [rad, rad, J]."""
        net, phi = self.net, self.phi
        scale = max(float(np.max(np.abs(net))), 1e-300)
        sign = np.where(np.abs(net) <= 1e-12 * scale, 0, np.sign(net))
        cuts = [float(phi[0])]
        last = 0
        for k in range(1, len(phi)):
            if sign[k] == 0:
                continue
            if last and sign[k] != last:
                j = k - 1
                while j > 0 and sign[j] == 0:
                    j -= 1
                a, b = net[j], net[k]
                cut = phi[j] if a == b else phi[j] + (phi[k] - phi[j]) * a / (a - b)
                cuts.append(float(cut))
            last = sign[k]
        cuts.append(float(phi[-1]))
        energy = self.excess_work()
        at = np.interp(cuts, phi, energy)
        return [(cuts[k], cuts[k + 1], float(at[k + 1] - at[k])) for k in range(len(cuts) - 1)]


def _is_motor(curve):
    from flyopt.cycle.torque import MotorTorque, TorqueSum

    if isinstance(curve, TorqueSum):
        return any(_is_motor(p) for p in curve.parts)
    return isinstance(curve, MotorTorque)


# --------------------------------------------------------------------------
# Labels placed where nothing else is
# --------------------------------------------------------------------------


def _to_pixels(ax, x, y):
    return ax.transData.transform(np.column_stack([x, y]))


def _boxes_overlap(a, b, pad=0.0):
    return not (a.x1 + pad <= b.x0 or b.x1 + pad <= a.x0 or a.y1 + pad <= b.y0 or b.y1 + pad <= a.y0)


def _place_area_labels(ax, x, lower, upper, spans, obstacles_x=(), obstacles_y=()):
    """Write each area's text inside its shading where it clears both curves, else just above (or below) them.

    The marks of the cycle (vertical lines) and horizontal levels are avoided
    too; where an area is too narrow between its marks, its text is written
    across a mark, on a white ground that interrupts the mark.

    Parameters
    ----------
    x, lower, upper : ndarray
        The drawn angle and the two envelopes (min and max of the curves), in data units.
    spans : list of (x_left, x_right, text, colour)
    obstacles_x, obstacles_y : sequence of float
        Vertical and horizontal lines (data x, data y) a label should not cover.

    Returns
    -------
    list of Text
        The labels placed (gid ``area``); a label that finds no free place is left out.
    """
    from matplotlib.transforms import Bbox

    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    lo_px, hi_px = _to_pixels(ax, x, lower), _to_pixels(ax, x, upper)
    px = lo_px[:, 0]
    axes_box = ax.get_window_extent(renderer)
    lines_px = [ax.transData.transform((v, 0.0))[0] for v in obstacles_x]
    levels_px = [ax.transData.transform((0.0, v))[1] for v in obstacles_y]
    placed: list[Any] = []
    texts: list[Any] = []
    pad = 2.0
    for left, right, text, colour in spans:
        label = ax.text(0, 0, text, ha="center", va="center", fontsize=_FONT, color=colour, gid="area")
        box = label.get_window_extent(renderer)
        w, h = box.width + 2 * pad, box.height + 2 * pad
        a, b = ax.transData.transform((left, 0))[0], ax.transData.transform((right, 0))[0]
        middle = 0.5 * (a + b)
        centres = np.linspace(a + w / 2, b - w / 2, 61) if b - a > w else np.array([middle])
        best = None
        for mode in ("inside", "above", "below", "across"):
            for cx in centres:
                window = (px >= cx - w / 2) & (px <= cx + w / 2)
                if not window.any() or (
                    mode != "across" and any(cx - w / 2 - 3 <= v <= cx + w / 2 + 3 for v in lines_px)
                ):
                    continue
                top, bottom = hi_px[window, 1], lo_px[window, 1]
                if mode in ("inside", "across"):
                    slack = float(top.min() - bottom.max()) - h
                    cy, score = 0.5 * float(top.min() + bottom.max()), slack
                    if slack < 0:
                        continue
                elif mode == "above":
                    cy, score = float(top.max()) + 1.0 + h / 2, -abs(cx - middle)
                else:
                    cy, score = float(bottom.min()) - 1.0 - h / 2, -abs(cx - middle)
                candidate = Bbox.from_bounds(cx - w / 2, cy - h / 2, w, h)
                if (
                    candidate.y0 < axes_box.y0
                    or candidate.y1 > axes_box.y1
                    or any(candidate.y0 <= v <= candidate.y1 for v in levels_px)
                    or any(_boxes_overlap(candidate, other) for other in placed)
                ):
                    continue
                if best is None or score > best[0]:
                    best = (score, cx, cy, candidate)
            if best is not None:
                break
        if best is None:
            label.remove()
            continue
        if mode == "across":
            label.set_bbox({"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 0.5})
            label.set_zorder(5)
        placed.append(best[3])
        label.set_position(ax.transData.inverted().transform((best[1], best[2])))
        texts.append(label)
    return texts


# --------------------------------------------------------------------------
# The turning-moment diagram
# --------------------------------------------------------------------------


def _omega_marks(analysis, units):
    """The vertical marks of the speed extremes and of the ends of A_max: (angle, label, colour, style, gid).

    With a constant inertia and torques of the angle only the speed is extreme
    where ΔE is (docs/flywheel-design.md, section 4): one mark each. With a
    variable J_e(φ) the speed is extreme where the energy–mass tangents touch
    (section 6), with a speed-dependent torque where the periodic solution
    says (section 7): both pairs are marked, and the legend says why.
    """
    marks: list[Any] = []
    note = None
    if analysis.a_max <= 0 and not (analysis.machine is not None and analysis.machine.variable_inertia):
        return marks, "steady running: M_d = M_r at every angle, A_max = 0, the speed does not fluctuate"
    model = {"energy": "energy method", "energy_mass": "energy–mass model", "dynamic": "periodic solution"}[
        analysis.model
    ]
    pairs = (
        ("max", analysis.angle_omega_max, analysis.angle_delta_e_max, "largest", SURPLUS),
        ("min", analysis.angle_omega_min, analysis.angle_delta_e_min, "smallest", DEFICIT),
    )
    differ = False
    for name, omega_at, delta_e_at, word, colour in pairs:
        if omega_at is None:
            continue
        apart = delta_e_at is not None and abs(omega_at - delta_e_at) > 1e-3
        differ |= apart
        if analysis.model == Model.DYNAMIC:
            marks.append(
                (omega_at, f"ω_{name} ({model}): φ = {_q(omega_at, 'angle', units)}", colour, "--", f"omega_{name}")
            )
        elif not apart:
            marks.append(
                (
                    omega_at,
                    f"ω_{name} where ΔE is {word}: φ = {_q(omega_at, 'angle', units)}",
                    colour,
                    "--",
                    f"omega_{name}",
                )
            )
        else:
            marks.append(
                (omega_at, f"ω_{name} ({model}): φ = {_q(omega_at, 'angle', units)}", colour, "--", f"omega_{name}")
            )
            marks.append(
                (
                    delta_e_at,
                    f"ΔE {word} (an end of A_max): φ = {_q(delta_e_at, 'angle', units)}",
                    colour,
                    ":",
                    f"delta_e_{name}",
                )
            )
    if differ and analysis.model == Model.ENERGY_MASS:
        note = (
            "J_e varies with φ: the speed is extreme where the energy–mass tangents touch (section 6 of "
            "the notes), not where ΔE is, at the ends of A_max"
        )
    elif analysis.model == Model.DYNAMIC:
        note = "a torque depends on speed: the torques and the speed extremes along the periodic solution (section 7)"
    return marks, note


def plot_turning_moment(scene, analysis, ax=None, units=display.DEFAULT):
    """Turning-moment diagram: M_d and M_r over the cycle, surplus and deficit shaded.

    Each area between crossings is labelled with its energy where it has room
    (areas under 1 % of A_max and 2 % of the cycle are left unlabelled); the
    angles of ω_max and ω_min by the model that ran are marked, and where they
    are not the ends of A_max (a variable inertia, a speed-dependent torque)
    those are marked too and the legend says why. A torque solved from the
    work balance is given with its value. With the dynamic model the torques
    are drawn along its periodic solution ω(φ): a motor on its characteristic,
    its mean dashed. An [engine]'s dead centres and strokes, a slider-crank's
    dead centres, are marked on a top axis. Net-area scenes have no curves:
    their areas are drawn as bars, area k over [k − 1, k] like the chain of
    :func:`plot_energy`.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    ax : matplotlib Axes, optional
    units : {"engineering", "si", "imperial"}
        The unit system of the axes and labels (:mod:`flyopt.report.display`).

    Returns
    -------
    matplotlib Axes
        Lines labelled by their meaning; the marks of the extremes carry gids
        ``omega_max``, ``omega_min`` (and ``delta_e_max``, ``delta_e_min``),
        the area texts gid ``area``.
    """
    display.check_system(units)
    ax, own = _axes(ax)
    energy = _unit("energy", units)[0]
    ind = analysis.indicator
    if scene.net is not None:
        areas = ind.areas
        k = np.arange(1, len(areas) + 1)
        ax.bar(k - 0.5, _show(areas, "energy", units), width=0.8, color=[SURPLUS if a > 0 else DEFICIT for a in areas])
        ax.axhline(0, color="black", lw=0.8)
        for x, a in zip(k - 0.5, areas):
            ax.annotate(
                _q(a, "energy", units),
                (x, float(_show(a, "energy", units))),
                xytext=(0, 3 if a > 0 else -3),
                textcoords="offset points",
                ha="center",
                va="bottom" if a > 0 else "top",
                fontsize=_FONT,
                gid="area",
            )
        ax.set_xlim(0, len(areas))
        ax.set_xticks(k - 0.5, labels=[str(i) for i in k])
        ax.margins(y=0.15)
        ax.set(
            xlabel="area between the torque curves, in order over the cycle",
            ylabel=_axis_label("energy of the area", "energy", units),
        )
        _title(ax, own, scene.title, f"net areas between the torque curves (A_max = {_q(ind.a_max, 'energy', units)})")
        return ax
    torques = _Torques(scene, analysis)
    x = _show(torques.phi, "angle", units)
    md, mr = _show(torques.driving, "torque", units), _show(torques.resisting, "torque", units)
    ax.fill_between(x, md, mr, where=md >= mr, color=SURPLUS, alpha=0.25, interpolate=True, lw=0)
    ax.fill_between(x, md, mr, where=md < mr, color=DEFICIT, alpha=0.25, interpolate=True, lw=0)
    ax.plot(
        x,
        md,
        color="tab:blue",
        lw=1.8,
        label=_torque_words("driving M_d", torques.driving_solved, torques.driving, torques, units),
    )
    ax.plot(
        x,
        mr,
        color="black",
        lw=1.8,
        label=_torque_words("resisting M_r", torques.resisting_solved, torques.resisting, torques, units),
    )
    levels = []
    if torques.along and not torques.driving_solved and np.ptp(torques.driving) > 0:
        mean = analysis.driving_torque
        levels.append(float(_show(mean, "torque", units)))
        ax.axhline(
            float(_show(mean, "torque", units)),
            color="tab:blue",
            ls="--",
            lw=1.0,
            label=f"mean M_d = W/Φ = {_q(mean, 'torque', units)}",
            gid="mean_driving",
        )
    marks, note = _omega_marks(analysis, units)
    for angle, words, colour, style, gid in marks:
        ax.axvline(float(_show(angle, "angle", units)), color=colour, ls=style, lw=1.1, label=words, gid=gid)
    end = _angle_axis(ax, scene.cycle_angle, units)
    top = _mark_dead_centres(ax, scene, units)
    ax.set_ylabel(_axis_label("torque at the reference shaft", "torque", units))
    if torques.along:
        areas = torques.areas()
        what = "along the periodic solution"
    else:
        areas = list(zip(ind.chain_angle[:-1], ind.chain_angle[1:], ind.areas))
        what = f"A_max = {_q(analysis.a_max, 'energy', units)}"
    _title(ax, own, scene.title, f"turning-moment diagram, {what} ({analysis.model} model)")
    span = max(float(np.ptp(np.concatenate([md, mr]))), 1e-12 * max(1.0, float(np.max(np.abs(md)))))
    low, high = float(min(md.min(), mr.min())), float(max(md.max(), mr.max()))
    if span <= 1e-9 * max(abs(high), 1.0):
        ax.set_ylim(low - 0.5 * max(abs(low), 1.0), high + 0.5 * max(abs(high), 1.0))
    else:
        ax.set_ylim(low - 0.12 * span, high + 0.22 * span)
    _legend(ax, own, title=note)
    largest = max([abs(a) for _l, _r, a in areas] + [0.0])
    spans = [
        (
            float(_show(left, "angle", units)),
            float(_show(right, "angle", units)),
            f"{'+' if area > 0 else '−'}{_q(abs(area), 'energy', units)}",
            SURPLUS if area > 0 else DEFICIT,
        )
        for left, right, area in areas
        if largest > 0
        and (abs(area) >= 0.01 * largest or right - left >= 0.02 * scene.cycle_angle)
        and abs(area) > 1e-9 * largest
    ]
    _place_area_labels(
        ax,
        x,
        np.minimum(md, mr),
        np.maximum(md, mr),
        spans,
        [float(_show(a, "angle", units)) for a, *_r in marks],
        levels,
    )
    ax.set_xlim(0.0, end)
    del top, energy
    return ax


def _torque_words(words, solved, values, torques, units):
    """A torque's legend entry: its value when it is a constant solved from the work balance."""
    if solved:
        how = "with the periodic solution" if torques.along else "from the work balance"
        return f"{words} = {_q(float(values[0]), 'torque', units)} (constant, solved {how})"
    if torques.along and words.startswith("driving") and torques.motor:
        return f"{words}: the motor on its characteristic along ω(φ)"
    if torques.along and torques.resisting_speed and words.startswith("resisting"):
        return f"{words} along ω(φ)"
    if np.ptp(values) == 0:
        return f"{words} = {_q(float(values[0]), 'torque', units)}"
    return words


# --------------------------------------------------------------------------
# The energy indicator diagram
# --------------------------------------------------------------------------


def plot_energy(scene, analysis, ax=None, units=display.DEFAULT):
    """Energy indicator diagram: ΔE from the cycle start, the chain points, ΔE's extremes and A_max.

    The x axis is the turning-moment diagram's (0 to Φ). A_max is dimensioned
    right of the plot, between the levels of the largest and smallest ΔE
    (docs/flywheel-design.md, section 4). ΔE's extremes are where ω is extreme
    for a constant inertia; with a variable inertia or a speed-dependent
    torque the speed extremes of the model that ran are marked on the curve
    as well. With the dynamic model the diagram is that of the torques frozen
    at the mean speed, a motor at its mean (section 7, the A_max the analysis
    reports), and ΔE along the periodic solution is drawn over it.

    Returns
    -------
    matplotlib Axes
        The A_max dimension is the annotation of gid ``a_max``.
    """
    display.check_system(units)
    ax, own = _axes(ax)
    ind = analysis.indicator
    chain = np.asarray(ind.chain_delta_e, dtype=float)
    constant = analysis.machine is None or not analysis.machine.variable_inertia
    if ind.chain_angle is None:
        x_chain = np.arange(len(chain), dtype=float)
        ax.plot(x_chain, _show(chain, "energy", units), "-", color="tab:blue", lw=1.5, label="ΔE, chained areas")
        ax.set_xlim(0, len(chain) - 1)
        ax.set_xticks(x_chain)
        ax.set_xlabel("end of area k (0: the cycle start)")
    else:
        x_chain = _show(ind.chain_angle, "angle", units)
        ew = _excess_work(scene, analysis)
        phi = np.union1d(np.linspace(0, scene.cycle_angle, 1501), ind.chain_angle)
        frozen = " (torques frozen at ω_m, the motor at its mean)" if analysis.model == Model.DYNAMIC else ""
        ax.plot(
            _show(phi, "angle", units),
            _show(ew(phi), "energy", units),
            color="tab:blue",
            lw=1.5,
            label=f"ΔE(φ) = ∫(M_d − M_r) dφ{frozen}",
        )
        if analysis.model == Model.DYNAMIC:
            torques = _Torques(scene, analysis)
            ax.plot(
                _show(torques.phi, "angle", units),
                _show(torques.excess_work(), "energy", units),
                color="tab:purple",
                lw=1.2,
                ls="--",
                label="ΔE along the periodic solution (the motor on its characteristic)",
                gid="along",
            )
        _angle_axis(ax, scene.cycle_angle, units)
        _mark_dead_centres(ax, scene, units)
    y_chain = _show(chain, "energy", units)
    ax.plot(
        x_chain,
        y_chain,
        "o",
        color="black",
        ms=3.5,
        zorder=4,
        label="ends of the areas" if ind.chain_angle is None else "ends of the areas: crossings of the torques",
    )
    hi, lo = float(y_chain[ind.index_max]), float(y_chain[ind.index_min])
    names = ("ω_max", "ω_min") if constant and analysis.model != Model.DYNAMIC else ("ΔE largest", "ΔE smallest")
    steady = not hi > lo and constant
    extremes = () if steady else ((ind.index_max, names[0], SURPLUS, 1), (ind.index_min, names[1], DEFICIT, -1))
    for k, name, colour, where in extremes:
        ax.axhline(y_chain[k], color=colour, ls=":", lw=1)
        angle = (
            f" at φ = {_q(ind.chain_angle[k], 'angle', units)}"
            if ind.chain_angle is not None
            else f" at the end of area {k}"
        )
        ax.plot(
            [x_chain[k]],
            [y_chain[k]],
            "o",
            ms=7,
            mfc="none",
            mec=colour,
            mew=1.6,
            zorder=5,
            label=f"{name}: ΔE = {_q(chain[k], 'energy', units)}{angle}",
            gid="chain_max" if where > 0 else "chain_min",
        )
        ax.annotate(
            name,
            (x_chain[k], y_chain[k]),
            xytext=(0, 7 * where),
            textcoords="offset points",
            ha="center",
            va="bottom" if where > 0 else "top",
            fontsize=_FONT,
            color=colour,
            gid="extreme_label",
        )
    if ind.chain_angle is not None and (not constant or analysis.model == Model.DYNAMIC) and not steady:
        ew = _excess_work(scene, analysis)
        for angle, name, colour, marker in (
            (analysis.angle_omega_max, "ω_max", SURPLUS, "^"),
            (analysis.angle_omega_min, "ω_min", DEFICIT, "v"),
        ):
            if angle is None:
                continue
            ax.plot(
                [float(_show(angle, "angle", units))],
                [float(_show(ew(np.array([angle]))[0], "energy", units))],
                marker,
                color=colour,
                ms=7,
                zorder=6,
                gid=f"omega_{name[-3:]}",
                label=f"{name} ({analysis.model} model) at φ = {_q(angle, 'angle', units)}",
            )
    top, bottom = hi, lo
    for line in ax.get_lines():  # every curve drawn (ΔE along the periodic solution too) within the plot
        values = np.asarray(line.get_ydata(), dtype=float)
        if values.size > 2:
            top, bottom = max(top, float(np.nanmax(values))), min(bottom, float(np.nanmin(values)))
    span = top - bottom
    ax.set_ylim(bottom - 0.2 * span if span > 0 else bottom - 1.0, top + 0.2 * span if span > 0 else top + 1.0)
    if hi > lo:  # A_max as a dimension right of the plot, clear of the curve
        from matplotlib.transforms import blended_transform_factory

        dimension_at = blended_transform_factory(ax.transAxes, ax.transData)
        ax.annotate(
            "",
            (1.025, hi),
            (1.025, lo),
            xycoords=dimension_at,
            textcoords=dimension_at,
            annotation_clip=False,
            arrowprops={
                "arrowstyle": "<|-|>",
                "color": "black",
                "lw": 0.9,
                "shrinkA": 0,
                "shrinkB": 0,
                "mutation_scale": 8,
            },
            gid="a_max",
        )
        for level in (hi, lo):
            ax.plot([1.0, 1.045], [level, level], transform=dimension_at, clip_on=False, color="gray", lw=0.6)
        ax.text(
            1.04,
            0.5 * (hi + lo),
            f"A_max = {_q(ind.a_max, 'energy', units)}",
            transform=dimension_at,
            rotation=90,
            ha="left",
            va="center",
            fontsize=_FONT,
            clip_on=False,
        )
    ax.set_ylabel(_axis_label("excess work ΔE", "energy", units))
    ax.grid(True, alpha=0.25)
    _title(ax, own, scene.title, f"energy indicator diagram (A_max = {_q(ind.a_max, 'energy', units)})")
    _legend(ax, own, title="steady running: ΔE = 0 at every angle, the speed does not fluctuate" if steady else None)
    return ax


# --------------------------------------------------------------------------
# J_F against δ
# --------------------------------------------------------------------------


def check_inertia_delta(analysis):
    """Raise NothingToDraw when no flywheel is needed at any δ: a steady machine of constant inertia."""
    if not flywheel_at_some_delta(analysis):
        raise NothingToDraw("no flywheel is needed for any δ (A_max = 0 J, so J_F(δ) = 0): nothing to draw")


def plot_inertia_delta(scene, analysis, ax=None, units=display.DEFAULT, curve=None):
    """J_F against δ by the model that ran, the scene's δ marked on the curve.

    With a constant inertia and torques of the angle only J_F = A_max/(ω_m² δ)
    − J_c (docs/flywheel-design.md, section 5), drawn from the closed form;
    with a variable inertia or a speed-dependent torque A_max no longer
    decides alone, and J_F(δ) is the exact model's answer at each δ, which
    the caller computes (``curve``; :func:`flyopt.delta_curve.inertia_curve`
    analyses the scene again at each δ of :func:`delta_range`). The
    constant-inertia method is drawn beside it for comparison. J_F is
    positive only below δ*, where the machine's own inertia starts to suffice;
    δ* is marked when it lies in range.

    Parameters
    ----------
    curve : (ndarray, ndarray), optional
        δ [-] and J_F there (``j_margin``, negative where none is needed)
        [kg*m^2], by the analysis' model; required unless that is the
        energy method.

    Raises
    ------
    NothingToDraw
        A steady machine of constant inertia: no flywheel for any δ.
    ValueError
        An exact model other than the energy method without ``curve``.
    """
    display.check_system(units)
    check_inertia_delta(analysis)
    j_mean = analysis.machine.j_mean() if analysis.machine is not None else analysis.j_constant
    if curve is None:
        if analysis.model != Model.ENERGY:
            raise ValueError(
                f"J_F(δ) of the {analysis.model} model comes from analysing the scene again at each "
                f"δ: pass curve (flyopt.delta_curve.inertia_curve)"
            )
        low, high = delta_range(analysis)[[0, -1]]
        delta = np.geomspace(float(low), float(high), 200)
        delta = np.union1d(delta, [analysis.delta])
        j = np.array([required_inertia(analysis.a_max, analysis.omega_mean, d, analysis.j_constant) for d in delta])
    else:
        delta, j = (np.asarray(v, dtype=float) for v in curve)
        order = np.argsort(delta)
        delta, j = delta[order], j[order]
    ax, own = _axes(ax)
    inertia = _unit("inertia", units)[0]
    shown = _show(np.where(j > 0, j, np.nan), "inertia", units)
    exact = analysis.model != Model.ENERGY
    ax.plot(
        delta,
        shown,
        "-" if not exact else ".-",
        ms=3,
        color="tab:blue",
        lw=1.6,
        gid="j_delta",
        label=f"J_F(δ), {analysis.model} model"
        + (" (the scene analysed at each δ)" if exact else " = A_max/(ω_m² δ) − J_c (section 5)"),
    )
    if exact and analysis.a_max > 0:
        # the constant-inertia method of section 5, J_e replaced by its cycle mean, for comparison
        d = np.geomspace(delta[0], delta[-1], 200)
        approx = np.array([required_inertia(analysis.a_max, scene.omega_mean, v, j_mean) for v in d])
        ax.plot(
            d,
            _show(np.where(approx > 0, approx, np.nan), "inertia", units),
            color="gray",
            ls="--",
            lw=1,
            label="constant-inertia method, A_max/(ω_m² δ) − mean J_e (section 5), for comparison",
            gid="constant_inertia",
        )
    free, about = _zero_crossing(delta, j), "≈ "
    if analysis.model == Model.ENERGY and analysis.j_constant > 0 and analysis.a_max > 0:
        free, about = analysis.a_max / (analysis.omega_mean**2 * analysis.j_constant), "= "  # section 5, exact
    if free is not None and delta[0] <= free <= delta[-1]:
        ax.axvline(
            free,
            color="gray",
            ls=":",
            lw=1,
            gid="delta_free",
            label=f"δ* {about}{display.number(free, _DIGITS if about == '= ' else 2)}: above it J_F = 0 "
            f"(the machine's own inertia suffices)",
        )
    if analysis.flywheel_needed:
        ax.plot(
            [analysis.delta],
            [float(_show(analysis.j_required, "inertia", units))],
            "o",
            color=DEFICIT,
            ms=7,
            zorder=5,
            gid="design_point",
            label=f"the scene: δ = {display.number(analysis.delta, _DIGITS)}, "
            f"J_F = {_q(analysis.j_required, 'inertia', units)}",
        )
    else:
        ax.axvline(
            analysis.delta,
            color=DEFICIT,
            lw=1,
            gid="design_point",
            label=f"the scene's δ = {display.number(analysis.delta, _DIGITS)}: no flywheel needed",
        )
    ax.set(
        xscale="log",
        yscale="log",
        xlabel="coefficient of speed fluctuation δ [-]",
        ylabel=f"required flywheel J_F at the reference shaft [{inertia}]",
    )
    ax.set_xlim(delta[0], delta[-1])
    _plain_log_ticks(ax)
    ax.grid(True, which="both", alpha=0.25)
    _title(ax, own, scene.title, f"required flywheel J_F against δ ({analysis.model} model)")
    _legend(ax, own, ncol=1)
    return ax


def _plain_log_ticks(ax):
    """Numbers as numbers on log axes (0.05, 200), not powers of ten, at 1, 2 and 5 of each decade."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: display.number(v, 3)))
        axis.set_minor_formatter(NullFormatter())


def _zero_crossing(delta, j):
    """The δ where a sampled J_F(δ) falls through zero (log-linear interpolation), or None."""
    k = np.flatnonzero((j[:-1] > 0) & (j[1:] <= 0))
    if not len(k):
        return None
    k = k[0]
    t = j[k] / (j[k] - j[k + 1])
    return float(math.exp(math.log(delta[k]) + t * (math.log(delta[k + 1]) - math.log(delta[k]))))


# --------------------------------------------------------------------------
# The wheel: its section and its stresses
# --------------------------------------------------------------------------

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
    return max(0, math.ceil(-math.log10(1e-4 / _unit("length", units)[1]) - 1e-9))


def _length_text(value, decimals):
    """A length in the drawing's unit as a drawing gives it: to its decimals, no trailing zeros."""
    return f"{value:.{decimals}f}".rstrip("0").rstrip(".") if decimals else f"{value:.0f}"


class _InUnits:
    """A candidate's lengths in the drawing's unit (its other fields as they are)."""

    LENGTHS = ("d_outer", "d_inner", "d_mean", "h", "b", "bore", "t_web", "d_hub", "l_hub", "arm_major", "arm_minor")

    def __init__(self, candidate, factor):
        self._c, self._factor = candidate, factor

    def __getattr__(self, name):
        value = getattr(self._c, name)
        if name in self.LENGTHS and value is not None:
            return value / self._factor
        if name == "key" and value:
            return {k: (v / self._factor if k in ("b", "t2", "h", "t1", "length") else v) for k, v in value.items()}
        return value


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


def _section_parts(c):
    """The hatched blocks of the axial half-section: (name, r_inner, r_outer, axial width), inner first,
    and the arms (r_inner, r_outer, major, minor) or None."""
    r_o = c.d_outer / 2.0
    r_bore = (c.bore or 0.0) / 2.0
    if c.geometry == Geometry.DISC:
        return [("disc", r_bore, r_o, c.b)], None
    r_i = c.d_inner / 2.0
    rim = ("rim", r_i, r_o, c.b)
    if c.geometry == Geometry.RIM_WEB:
        if not c.bore:
            return [("web", 0.0, r_i, c.t_web), rim], None
        return [("hub", r_bore, c.d_hub / 2.0, c.l_hub), ("web", c.d_hub / 2.0, r_i, c.t_web), rim], None
    if c.geometry == Geometry.RIM_ARMS:
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


def plot_cross_section(candidate, ax=None, units=display.DEFAULT):
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
    if not candidate.feasible or candidate.d_outer is None:
        raise ValueError(f"{candidate.material} on {candidate.shaft} is not a design: nothing to draw")
    length, factor = _unit("length", units)
    decimals = _length_decimals(units)

    def _mm_text(value):
        return _length_text(value, decimals)

    c = _InUnits(candidate, factor)
    notes = _section_notes(c, length, _mm_text)
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
    texts = [f"Ø{_mm_text(2 * r)}" for r, _x, _n in diameters]
    left_in = (_DIM_FIRST + 0.45) if has_rim else 0.3  # H (and the arm's a) on the left
    lines_in, right_in = _diameter_lines(diameters, texts, None)
    top_in = _DIM_FIRST + 0.25
    note_lines = sum(len(textwrap.wrap(n, 95)) for n in notes)
    bottom_in = 0.25
    own = ax is None
    if own:
        plt = _pyplot()
        scale = min(_SECTION_HEIGHT / (2 * r_o), 5.0 / w_max)  # [in per drawing unit]
        lines_in, right_in = _diameter_lines(diameters, texts, scale)
        width_in = w_max * scale + left_in + right_in
        height_in = 2 * r_o * scale + top_in + bottom_in
        front_in = 0.62 * 2 * r_o * scale + 0.6 if arms else 0.0  # the front view, smaller
        title_in, margin = 0.75, 0.3
        notes_in = 0.17 * note_lines + (0.15 if notes else 0.0)
        fig_w = max(width_in + front_in + 2 * margin, 7.0)
        fig_h = height_in + title_in + notes_in + 2 * margin
        fig = plt.figure(figsize=(fig_w, fig_h))
        x0 = (fig_w - width_in - front_in) / 2.0
        ax = fig.add_axes([x0 / fig_w, (margin + notes_in) / fig_h, width_in / fig_w, height_in / fig_h])
        if arms:
            size = 0.62 * 2 * r_o * scale + 0.3
            front = fig.add_axes(
                [
                    (x0 + width_in + 0.3) / fig_w,
                    (margin + notes_in + (height_in - size) / 2) / fig_h,
                    size / fig_w,
                    size / fig_h,
                ]
            )
            _front_view(front, c, arms, _mm_text)
    else:
        box = ax.get_position()
        fig_w, fig_h = ax.figure.get_size_inches()
        for _pass in range(2):  # the room the diameters need depends on the scale, and the scale on it
            scale = min(
                (box.height * fig_h - top_in - bottom_in) / (2 * r_o), (box.width * fig_w - left_in - right_in) / w_max
            )
            scale = max(scale, 1e-9)
            lines_in, right_in = _diameter_lines(diameters, texts, scale)
    sheet = _Sheet(ax, scale)
    d = sheet.d
    for group in _groups(blocks):
        for sign in (1, -1):
            for name, r0, r1, w in group:
                y = r0 if sign > 0 else -r1
                ax.add_patch(
                    Rectangle((-w / 2.0, y), w, r1 - r0, gid=f"{name}{'+' if sign > 0 else '-'}", **_SECTION_HATCH)
                )
        upper = _outline(group)
        if group[0][1] > 0:  # a bore: the halves are two sections
            outlines = [upper, [(x, -y) for x, y in upper]]
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
            f"l_hub {_mm_text(hub[3])}",
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
        sheet.linear(-w / 2.0, w / 2.0, -0.5 * (r0 + r1), f"t_web {_mm_text(w)}", vertical=False)
    if arms:
        r0, r1, major, minor = arms
        middle = 0.5 * (r0 + r1)
        sheet.linear(-minor / 2.0, minor / 2.0, -middle, f"a/2 {_mm_text(minor)}", vertical=False)
        sheet.linear(
            middle - major / 2.0,
            middle + major / 2.0,
            -w_max / 2.0 - d(_DIM_FIRST),
            f"a {_mm_text(major)}",
            vertical=True,
            feature=(0.0, 0.0),
        )
    ax.set_aspect("equal")
    ax.set_xlim(-w_max / 2.0 - d(left_in), w_max / 2.0 + d(right_in))
    ax.set_ylim(-r_o - d(bottom_in), r_o + d(top_in))
    ax.set_axis_off()
    what = {"rim_arms": f"rim on {c.n_arms} arms", "rim_web": "rim and web", "thin_rim": "thin rim"}.get(
        c.geometry, c.geometry
    )
    title = (
        f"Flywheel, {what}: {c.material}, {_q(c.mass, 'mass', units)}, "
        f"J = {_q(c.j_flywheel, 'inertia', units)} on {c.shaft}\n"
        f"axial section{', arm section revolved' if arms else ''}, dimensions in {length}"
    )
    if own:  # the figure is this drawing's: its title over both views, the notes under them
        ax.figure.suptitle(title, fontsize=10)
        if notes:
            ax.figure.text(
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
            "of this design, and their inertia is left out, on the safe side (docs/flywheel-design.md, "
            "section 9)."
        )
    disc = c.geometry == Geometry.DISC
    ratio = c.d_outer / (c.b if disc else min(c.b, c.h))
    if ratio >= _SLENDER:
        binding = ", ".join(c.binding) if c.binding else "none"
        sides = f"{text(c.b)} {length} thick" if disc else f"B {text(c.b)} × H {text(c.h)} {length}"
        notes.append(
            f"A slender {'disc' if disc else 'rim'}: {sides} at Ø{text(c.d_outer)} {length}, the diameter "
            f"{ratio:.0f} times its thinnest side. It is the lightest the design's limits allow (binding: "
            f"{binding}); its stiffness, casting and mounting are not checked."
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


#: Colours of the stress curves.
_STRESS_COLOURS = {"sr": "tab:blue", "st": "tab:red", "vm": "black"}
#: Shades of the parts' spans, inner to outer.
_PART_SHADES = ("#eef1f6", "#f8f4ea")


def plot_stress(candidate, profile, beams=(), omega=None, ductile=True, ax=None, units=display.DEFAULT):
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
    units : {"engineering", "si", "imperial"}
        Stress and radius in the system's units (MPa over mm by default).

    Returns
    -------
    matplotlib Axes
        Lines labelled "σ_r", "σ_t" and "von Mises" (the first part's; the
        others' carry a leading underscore), stress over radius in ``units``.
    """
    display.check_system(units)
    c = candidate
    if not c.feasible or not c.parts:
        raise ValueError(f"{c.material} on {c.shaft} is not a design: no stresses to draw")
    if not c.stress:
        raise ValueError(f"the design of {c.material} carries no stresses (its notes: {'; '.join(c.notes) or 'none'})")
    ax, own = _axes(ax, figsize=(9, 5.6))
    mm, mpa = 1.0 / _unit("length", units)[1], 1.0 / _unit("stress", units)[1]
    r_unit, s_unit = _unit("length", units)[0], _unit("stress", units)[0]
    checked = {p["part"]: p for p in c.stress.get("parts", [])}
    spans = {p["name"]: (p["r_inner"], p["r_outer"]) for p in c.parts}
    # the parts' spans, shaded and named at the top
    for k, p in enumerate(c.parts):
        r0, r1 = p["r_inner"] * mm, p["r_outer"] * mm
        ax.axvspan(r0, r1, color=_PART_SHADES[k % 2], lw=0, zorder=0)
        ax.axvline(r0, color="gray", lw=0.5, zorder=1)
        narrow = (r1 - r0) < 0.06 * c.d_outer / 2 * mm
        ax.text(
            0.5 * (r0 + r1),
            0.985,
            p["name"],
            transform=ax.get_xaxis_transform(),
            ha="center",
            va="top",
            fontsize=8,
            color="dimgray",
            rotation=90 if narrow else 0,
        )
    # the curves of the disc parts
    names = {"sr": "σ_r", "st": "σ_t", "vm": "von Mises"}
    for k, (_part, r, sr, st, vm) in enumerate(profile):
        for key, values, style in (("sr", sr, "-"), ("st", st, "-"), ("vm", vm, "--")):
            ax.plot(
                np.asarray(r) * mm,
                np.asarray(values) * mpa,
                style,
                color=_STRESS_COLOURS[key],
                lw=1.5,
                label=names[key] if k == 0 else f"_{names[key]}",
            )
    # each part's allowable over its span
    allowables = [
        (name, checked[name]["allowable"])
        for name in spans
        if name in checked and _finite_positive(checked[name].get("allowable"))
    ]
    same = len({a for _n, a in allowables}) == 1
    for k, (name, allowable) in enumerate(allowables):
        label = (
            (f"allowable {_q(allowable, 'stress', units)}" if same else "allowable of each part")
            if k == 0
            else "_allowable"
        )
        ax.hlines(
            allowable * mpa,
            spans[name][0] * mm,
            spans[name][1] * mm,
            colors=DEFICIT,
            linestyles=":",
            lw=1.8,
            label=label,
        )
        if not same:
            ax.annotate(
                display.number(allowable * mpa, _DIGITS),
                (0.5 * (spans[name][0] + spans[name][1]) * mm, allowable * mpa),
                xytext=(0, 2),
                textcoords="offset points",
                ha="center",
                va="bottom",
                fontsize=7,
                color=DEFICIT,
            )
    # the beams of an arms wheel
    beam_words = {"arms": ("arm root (pull + bending)", "^"), "rim": ("rim (hoop + bending)", "s")}
    for part, r, sr, st in beams:
        value = sr if part == "arms" else st
        words, marker = beam_words.get(part, (part, "o"))
        ax.plot(
            [r * mm],
            [value * mpa],
            marker,
            color="tab:purple",
            ms=8,
            zorder=4,
            label=f"{words}: {_q(value, 'stress', units)}",
        )
        at = r / (c.d_outer / 2)  # near an end of the axis the label turns inwards
        ha, dx = ("left", -4) if at < 0.15 else ("right", 4) if at > 0.85 else ("center", 0)
        ax.annotate(
            f"{words}\n{_q(value, 'stress', units)}",
            (r * mm, value * mpa),
            xytext=(dx, -12),
            textcoords="offset points",
            ha=ha,
            va="top",
            fontsize=8,
            color="tab:purple",
        )
    # the governing point
    where = c.stress.get("where") or {}
    governing = checked.get(where.get("part"))
    if governing is not None:
        measure = "von Mises" if ductile else "largest principal"
        utilisation = governing["stress"] / governing["allowable"] if governing.get("allowable") else math.nan
        x, y = governing["radius"] * mm, governing["stress"] * mpa
        ax.plot(
            [x],
            [y],
            "o",
            ms=11,
            mfc="none",
            mec="black",
            mew=1.5,
            zorder=5,
            label=f"governing: {governing['part']}, {measure} {_q(governing['stress'], 'stress', units)} at "
            f"r = {_q(governing['radius'], 'length', units)} ({100 * utilisation:.0f} % of allowable)",
        )
    ax.axhline(0, color="black", lw=0.6)
    top = max([a for _n, a in allowables] + [governing["stress"] if governing else 0.0]) * mpa
    r_in, r_out = min(spans.values())[0] * mm, c.d_outer / 2 * mm
    # from the axis, unless the wheel is a ring far from it (a bare rim): then its own span
    left = 0.0 if r_in < 0.4 * r_out else r_in - 0.08 * (r_out - r_in)
    ax.set_xlim(left, r_out + 0.03 * (r_out - left))
    low = min([0.0] + [float(np.min(np.minimum(sr, st))) * mpa for _p, _r, sr, st, _v in profile])
    ax.set_ylim(low - 0.05 * top, 1.25 * top if top > 0 else 1.0)
    speed = f" = {_q(omega, 'angular_speed', units, 5)}" if omega else ""
    ax.set(xlabel=f"radius r [{r_unit}]", ylabel=f"stress [{s_unit}]")
    _title(ax, own, f"{c.material} {c.geometry} on {c.shaft}", f"stresses over the radius at ω_max{speed}")
    ax.grid(True, alpha=0.3)
    _legend(ax, own)
    return ax


def _finite_positive(value):
    return value is not None and math.isfinite(value) and value > 0


# --------------------------------------------------------------------------
# The speed over the cycle
# --------------------------------------------------------------------------


def plot_speed(scene, analysis, speed=None, simulation=None, ax=None, units=display.DEFAULT):
    """ω(φ) over the cycle with the required flywheel, from the model that ran.

    The mean speed ω_m and the extremes ω_max and ω_min are drawn as levels,
    the angles of the extremes marked; the title gives the δ the curve
    achieves beside the δ allowed.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    speed : SpeedFluctuation or PeriodicSolution, optional
        The model's speed over the cycle: ``phi`` [rad], ``omega`` [rad/s]
        and ``delta``. Energy models: ω² = 2 (E_0 + ΔE)/J_e with E_0 such
        that (ω_max + ω_min)/2 = ω_m (docs/flywheel-design.md, section 6,
        forward use: :meth:`Analysis.speed_curve`); the dynamic model: its
        periodic solution, which the analysis carries (the default).
    simulation : PeriodicSolution, optional
        The periodic simulation of the machine with that flywheel (the
        verification's), drawn over it: ``phi``, ``omega`` and ``delta``.
    ax : matplotlib Axes, optional
    units : {"engineering", "si", "imperial"}

    Returns
    -------
    matplotlib Axes
        The model's line has gid ``model``, the simulation's ``simulation``,
        the levels ``omega_mean``, ``omega_max``, ``omega_min``.

    Raises
    ------
    ValueError
        A net-area scene: it has no angles; or no ``speed`` for an analysis
        whose result does not carry one (the energy models).
    """
    display.check_system(units)
    if scene.net is not None:
        raise ValueError("a net-area scene has no angles: ω(φ) cannot be drawn")
    if speed is None:
        if analysis.requirement is None or analysis.requirement.model != Model.DYNAMIC:
            raise ValueError(
                f"the {analysis.model} model's result carries no ω(φ): pass speed (Analysis.speed_curve())"
            )
        speed = analysis.speed_curve()
    ax, own = _axes(ax)
    omega = np.asarray(speed.omega, dtype=float)
    x = _show(speed.phi, "angle", units)
    ax.plot(
        x,
        _show(omega, "angular_speed", units),
        color="tab:blue",
        lw=1.6,
        gid="model",
        label=f"ω(φ), {analysis.model} model, J_F = {_q(analysis.j_required, 'inertia', units)}",
    )
    if simulation is not None:
        ax.plot(
            _show(simulation.phi, "angle", units),
            _show(simulation.omega, "angular_speed", units),
            color=DEFICIT,
            ls="--",
            lw=1,
            gid="simulation",
            label=f"periodic simulation (δ = {display.number(simulation.delta, 6)})",
        )
    w_max, w_min = float(np.max(omega)), float(np.min(omega))
    w_max = float(getattr(speed, "omega_max", w_max))
    w_min = float(getattr(speed, "omega_min", w_min))
    w_mean = 0.5 * (w_max + w_min)
    where = {"max": getattr(speed, "phi_omega_max", None), "min": getattr(speed, "phi_omega_min", None)}
    for value, name, colour, style in (
        (w_max, "max", SURPLUS, ":"),
        (w_mean, "mean", "gray", "-."),
        (w_min, "min", DEFICIT, ":"),
    ):
        at = where.get(name)
        angle = f" at φ = {_q(at, 'angle', units)}" if at is not None and w_max > w_min else ""
        symbol = "ω_m = (ω_max + ω_min)/2" if name == "mean" else f"ω_{name}"
        ax.axhline(
            float(_show(value, "angular_speed", units)),
            color=colour,
            ls=style,
            lw=1,
            gid=f"omega_{name}",
            label=f"{symbol} = {_q(value, 'angular_speed', units, 6)}{angle}",
        )
        if at is not None and name != "mean" and w_max > w_min:
            ax.plot(
                [float(_show(at, "angle", units))],
                [float(_show(value, "angular_speed", units))],
                "o",
                color=colour,
                ms=5,
                zorder=5,
            )
    _angle_axis(ax, scene.cycle_angle, units)
    _mark_dead_centres(ax, scene, units)
    span = max(w_max - w_min, 1e-9 * w_mean)
    ax.set_ylim(*(float(_show(v, "angular_speed", units)) for v in (w_min - 0.12 * span, w_max + 0.12 * span)))
    ax.set_ylabel(_axis_label("speed of the reference shaft ω", "angular_speed", units))
    ax.grid(True, alpha=0.25)
    achieved = float(getattr(speed, "delta", (w_max - w_min) / w_mean))
    _title(
        ax,
        own,
        scene.title,
        f"speed over the cycle: δ = {display.number(achieved, 4)} achieved, "
        f"{display.number(analysis.delta, 4)} allowed",
    )
    _legend(ax, own)
    return ax


# --------------------------------------------------------------------------
# The energy–mass diagram
# --------------------------------------------------------------------------


def check_energy_mass(analysis):
    """Raise ValueError unless the energy–mass diagram applies: curves of the angle only, J_e varying.

    With a constant inertia the diagram is a vertical line (every point at
    J_e = J_c) and its tangents say nothing the energy diagram does not
    (docs/flywheel-design.md, section 6 reduces to section 5).
    """
    if analysis.machine is None:
        raise ValueError(
            "a net-area scene has no curves, and the energy–mass diagram needs torques of the angle "
            "only given as curves"
        )
    if analysis.machine.speed_dependent:
        raise ValueError(
            "a torque depends on speed, and the energy–mass diagram needs torques of the angle only "
            "given as curves: see turning_moment and speed (the periodic solution)"
        )
    if not analysis.machine.variable_inertia:
        raise ValueError(
            "the energy–mass diagram is drawn for an inertia that varies with the angle; this "
            "machine's J_e is constant, so it would be a vertical line: see the energy diagram"
        )


def plot_energy_mass(scene, analysis, ax=None, units=display.DEFAULT):
    """Wittenbauer's energy–mass diagram: ΔE against J_e over the cycle, with the two tangents.

    From the true origin (−J_F, −E_0) the lines of slope ω_max²/2 and ω_min²/2
    touch the curve where the speed is highest and lowest
    (docs/flywheel-design.md, section 6); the tangent points are marked with
    their angles, and the curve is coloured by the crank angle φ. On a figure
    the function makes, a second panel left of the diagram shows the whole
    picture: the origin where the tangents meet, and the curve beside it.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        Sized by the energy–mass model (``analyse(scene, model="energy_mass")``):
        ``analysis.requirement.detail`` is its EnergyMassRequirement
        (``j_required``, ``e0``, ``omega_max``, ``omega_min``, ``phi_omega_max``,
        ``phi_omega_min``).
    ax : matplotlib Axes, optional
        The diagram near the curve only (the origin then given in the legend).
    units : {"engineering", "si", "imperial"}

    Returns
    -------
    matplotlib Axes
        The diagram near the curve; the tangent points have gids ``tangent_max``
        and ``tangent_min``, the origin (on the overview panel) ``origin``.

    Raises
    ------
    ValueError
        Torques that depend on speed, net areas or a constant inertia; or an
        analysis by another model.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.ticker import MaxNLocator

    display.check_system(units)
    check_energy_mass(analysis)
    if analysis.requirement is None or analysis.requirement.model != Model.ENERGY_MASS:
        raise ValueError(
            f"the energy–mass diagram draws the energy–mass model's result, and this "
            f"analysis ran the {analysis.model} model: analyse with model='energy_mass'"
        )
    machine = analysis.machine
    em = analysis.requirement.detail
    ew = machine.angle_only()
    phi = np.union1d(np.linspace(0, scene.cycle_angle, 1441), ew.knots)
    j = np.asarray(machine.j_machine(phi), dtype=float)
    de = np.asarray(ew(phi), dtype=float)
    j_f = max(em.j_required, 0.0)
    x0, y0 = -j_f, -em.e0
    own = ax is None
    if own:
        plt = _pyplot()
        fig, (overview, ax) = plt.subplots(
            1, 2, figsize=(11, 5.6), layout="constrained", gridspec_kw={"width_ratios": [1, 1.5]}
        )
    else:
        overview = None
    inertia, energy = _unit("inertia", units)[0], _unit("energy", units)[0]
    sj, se = (lambda v: _show(v, "inertia", units)), (lambda v: _show(v, "energy", units))
    tangents = ((em.omega_max, em.phi_omega_max, SURPLUS, "max"), (em.omega_min, em.phi_omega_min, DEFICIT, "min"))
    points = np.column_stack([sj(j), se(de)])
    segments = np.stack([points[:-1], points[1:]], axis=1)
    coloured = LineCollection(list(segments), cmap="twilight", lw=2.2, gid="curve")  # cyclic: φ = Φ meets φ = 0
    coloured.set_array(_show(0.5 * (phi[:-1] + phi[1:]), "angle", units))
    ax.add_collection(coloured)
    coloured.set_clim(0.0, float(_show(scene.cycle_angle, "angle", units)))
    bar = ax.figure.colorbar(coloured, ax=ax, pad=0.01)
    bar.set_label(_axis_label("crank angle φ", "angle", units))
    if display.label("angle", units) == "deg":
        bar.set_ticks(np.arange(0.0, float(_show(scene.cycle_angle, "angle", units)) + 1.0, 90.0))
    ax.plot([sj(j[0])], [se(de[0])], "s", color="black", ms=5, label="φ = 0, the cycle's start", zorder=5)
    span_x, span_y = float(np.ptp(j)), float(np.ptp(de))
    xs = np.array([j.min() - 0.3 * span_x, j.max() + 0.3 * span_x])
    for w, at, colour, name in tangents:
        slope = 0.5 * w**2
        ax.plot(
            sj(xs),
            se(y0 + slope * (xs - x0)),
            color=colour,
            lw=1,
            ls="--",
            label=f"tangent of slope ω_{name}²/2, ω_{name} = {_q(w, 'angular_speed', units, 5)}",
        )
        touch = np.array([at])
        ax.plot(
            [sj(machine.j_machine(touch)[0])],
            [se(ew(touch)[0])],
            "o",
            ms=8,
            mfc="white",
            mec=colour,
            mew=2,
            zorder=6,
            gid=f"tangent_{name}",
            label=f"touches where the speed is ω_{name}: φ = {_q(at, 'angle', units)}",
        )
    ax.set_xlim(sj(j.min() - 0.15 * max(span_x, 1e-12)), sj(j.max() + 0.15 * max(span_x, 1e-12)))
    ax.set_ylim(se(de.min() - 0.15 * max(span_y, 1e-12)), se(de.max() + 0.15 * max(span_y, 1e-12)))
    ax.set(xlabel=f"equivalent inertia of the machine J_e [{inertia}]", ylabel=f"excess work ΔE [{energy}]")
    ax.grid(True, alpha=0.25)
    origin = (
        f"the tangents meet at the true origin (−J_F, −E_0) = ({_q(x0, 'inertia', units)}, "
        f"{_q(y0, 'energy', units)}): J_F = {_q(j_f, 'inertia', units)}"
    )
    if overview is not None:
        overview.plot(sj(j), se(de), color="tab:blue", lw=1.5)
        ends = np.array([x0, j.max() + 0.1 * (j.max() - x0)])
        for w, _at, colour, _name in tangents:
            overview.plot(sj(ends), se(y0 + 0.5 * w**2 * (ends - x0)), color=colour, lw=1, ls="--")
        overview.plot([sj(x0)], [se(y0)], "ko", ms=6, gid="origin", label=origin)
        overview.axhline(0, color="gray", lw=0.5)
        overview.axvline(0, color="gray", lw=0.5)
        overview.set(xlabel=f"J_e [{inertia}]", ylabel=f"ΔE [{energy}]")
        overview.xaxis.set_major_locator(MaxNLocator(4))  # a narrow panel: few ticks, none overlapping
        overview.set_title("the whole: from the true origin", fontsize=_FONT + 1)
        overview.grid(True, alpha=0.25)
        ax.set_title("near the curve: the tangent points", fontsize=_FONT + 1)
        fig.suptitle(f"{scene.title}\nenergy–mass diagram (Wittenbauer), {analysis.model} model", fontsize=11)
        handles = overview.get_legend_handles_labels()[0] + ax.get_legend_handles_labels()[0]
        _legend(ax, True, handles=handles)
    else:
        ax.plot([], [], " ", label=origin)
        _title(ax, False, scene.title, "energy–mass diagram (Wittenbauer)")
        _legend(ax, False)
    return ax


# --------------------------------------------------------------------------
# Results of sweeps and Pareto fronts
# --------------------------------------------------------------------------

RESULT_PLOTS = {
    "sweep": "a result of a sweep against a varied field, one line per group (--by) and per other varied field",
    "pareto": "a Pareto front: the non-dominated designs of two objectives",
}

#: Most lines a sweep diagram draws (one per group of the other varied fields).
MAX_LINES = 12


def _dimension(column, frame=None):
    """The dimension of a results column (flyopt.outputs.results' table), or None (text, counts, unknown)."""
    metadata = (frame.attrs.get("flyopt", {}) if frame is not None else {}) or {}
    if column == "objective":
        column = metadata.get("objective") or _objective_of(frame)
        if column is None:
            return None
    if column == "epsilon":
        objectives = metadata.get("objectives") or (pareto_objectives(frame) if frame is not None else None)
        if not objectives:
            return None
        column = objectives[1]
    try:
        return display.dimension_of(column)
    except ValueError:
        return None


def _objective_of(frame):
    if frame is None or "design.objective" not in frame.columns:
        return None
    names = frame["design.objective"].dropna().unique()
    return str(names[0]) if len(names) == 1 else None


def _label(column, units=display.DEFAULT, frame=None):
    """A column's axis label with its unit in the system (flyopt.outputs.results: the one table of units)."""
    dimension = _dimension(column, frame)
    if column == "cost":
        return "cost [currency of the prices]"
    if dimension is None:
        return column
    return _axis_label(column, dimension, units)


def _column(frame, name):
    """The column a user names: itself, or the result of that name (``material`` is ``best_material``)."""
    for column in (name, f"best_{name}"):
        if column in frame.columns:
            return column
    raise ValueError(f"the results have no column {name!r} (columns: {', '.join(frame.columns)})")


def _values(frame, column, units):
    """A column's numbers in the system's unit of its dimension."""
    values = frame[column].to_numpy(dtype=float)
    dimension = _dimension(column, frame)
    return values if dimension is None else _show(values, dimension, units)


def _value_text(value, column, units, frame=None):
    """A varied field's value as a legend writes it: "speed = 600 rpm", "material = cast_iron"."""
    if isinstance(value, (float, int, np.floating, np.integer)) and not isinstance(value, bool):
        dimension = _dimension(column, frame)
        if dimension is None:
            return f"{column} = {display.number(float(value), _DIGITS)}"
        return f"{column} = {_q(float(value), dimension, units)}"
    return f"{column} = {value}"


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


def varied_fields(frame):
    """The inputs a sweep varied: its recorded sweep specification, else the input columns that take
    more than one value (flyopt.outputs.results.INPUTS and the material and shaft fields)."""
    from flyopt.outputs.quantities import INPUTS

    recorded = ((frame.attrs.get("flyopt") or {}).get("sweep") or {}).get("vary")
    if recorded:
        return [name for name in recorded if name in frame.columns]
    names = [c for c in frame.columns if c in INPUTS or c.startswith(("material.", "shaft."))]
    return [c for c in names if frame[c].nunique(dropna=True) > 1]


_NOT_DESIGNED = {
    "infeasible": ("x", "infeasible: no material and shaft can give J_F"),
    "failed": ("X", "failed: the solver did not converge"),
    "not_needed": ("o", "no flywheel needed"),
}


def plot_sweep(frame, x, y="mass", by=None, ax=None, units=display.DEFAULT):
    """A sweep's result ``y`` against a varied field ``x``: one line per value of ``by`` and of every
    other varied field, so that a line never joins points that differ in anything but ``x``.

    Points that are not designed (infeasible, failed, not needed) have no
    ``y``: each is marked at its ``x`` along the bottom of the plot, by kind,
    and counted in the legend. Values are shown in the system's units, the
    legends' too (``speed = 600 rpm``). A field spanning more than a decade is
    drawn on a log axis. A name that is not a column may name a result:
    ``material`` and ``shaft`` are the winner's, ``best_material`` and
    ``best_shaft``, when the sweep did not vary them.

    Raises
    ------
    ValueError
        A column that does not exist, or more than :data:`MAX_LINES` lines.
    """
    from matplotlib.transforms import blended_transform_factory

    display.check_system(units)
    x, y = _column(frame, x), _column(frame, y)
    by = _column(frame, by) if by else None
    others = [f for f in varied_fields(frame) if f not in (x, by)]
    keys = ([by] if by else []) + others
    groups = list(frame.groupby(keys, sort=True, dropna=False)) if keys else [((), frame)]
    if len(groups) > MAX_LINES:
        raise ValueError(
            f"the sweep varies {', '.join(keys)} besides {x}: {len(groups)} lines would be drawn "
            f"(at most {MAX_LINES}); sweep fewer fields at once, or plot one of them along x"
        )
    ax, own = _axes(ax)
    status = frame["status"] if "status" in frame.columns else None
    bottom = blended_transform_factory(ax.transData, ax.transAxes)
    counts: dict[Any, int] = {}
    for key, part in groups:
        part = part.sort_values(x)
        key = key if isinstance(key, tuple) else (key,)
        words = ", ".join(_value_text(v, k, units, frame) for k, v in zip(keys, key)) or y
        ok = (part["status"] == "designed").to_numpy() if status is not None else np.ones(len(part), bool)
        xs, ys = _values(part, x, units), _values(part, y, units)
        (line,) = ax.plot(xs[ok], ys[ok], "o-", ms=3.5, lw=1.3, label=words)
        for kind, (marker, _w) in _NOT_DESIGNED.items():
            miss = (part["status"] == kind).to_numpy() if status is not None else np.zeros(len(part), bool)
            if miss.any():
                ax.plot(
                    xs[miss],
                    np.full(miss.sum(), 0.03),
                    marker,
                    transform=bottom,
                    color=line.get_color(),
                    ms=6,
                    mfc="none" if marker == "o" else line.get_color(),
                    clip_on=False,
                    gid=kind,
                )
                counts[kind] = counts.get(kind, 0) + int(miss.sum())
    for kind, n in counts.items():
        marker, words = _NOT_DESIGNED[kind]
        ax.plot(
            [],
            [],
            marker,
            color="gray",
            mfc="none" if marker == "o" else "gray",
            label=f"{words} ({n} point{'s' if n > 1 else ''}), marked at the bottom",
        )
    values = _values(frame, x, units) if np.issubdtype(frame[x].dtype, np.number) else np.array([])
    positive = values[np.isfinite(values) & (values > 0)]
    if positive.size and positive.max() / positive.min() > 10:
        ax.set_xscale("log")
    ax.set(xlabel=_label(x, units, frame), ylabel=_label(y, units, frame))
    ax.grid(True, alpha=0.3)
    _title(ax, own, f"sweep: {y} against {x}" + (f", one line per {', '.join(keys)}" if keys else ""))
    _legend(ax, own, ncol=3)
    return ax


def plot_pareto(frame, x, y, ax=None, units=display.DEFAULT):
    """The Pareto front of two objectives (both minimized), non-dominated points joined.

    A front compares designs of one machine: the points must share the
    fields that set the machine's physics (``delta``, ``speed``, ``inertia``,
    ``torque.scale``: flyopt.studies.evaluate.PHYSICS_FIELDS), unless the
    field is an objective itself (``flyopt pareto --objectives mass,delta``).
    Points without a design are left out and counted in the legend.

    Raises
    ------
    ValueError
        A column that does not exist, or points of different physics.
    """
    from flyopt.studies.evaluate import PHYSICS_FIELDS

    display.check_system(units)
    x, y = _column(frame, x), _column(frame, y)
    mixed = [f for f in PHYSICS_FIELDS if f in frame.columns and f not in (x, y) and frame[f].nunique(dropna=True) > 1]
    if mixed:
        spans = "; ".join(
            f"{f} from {_value_text(frame[f].min(), f, units, frame).split(' = ')[1]} to "
            f"{_value_text(frame[f].max(), f, units, frame).split(' = ')[1]}"
            for f in mixed
        )
        hint = ", or make δ an objective (flyopt pareto --objectives mass,delta)" if mixed == ["delta"] else ""
        raise ValueError(
            f"the points differ in {' and '.join(mixed)} ({spans}), and a Pareto front compares "
            f"designs of one machine: plot the points of one {' and '.join(mixed)} at a time{hint}"
        )
    ax, own = _axes(ax)
    usable = frame[[x, y]].notna().all(axis=1).to_numpy()
    if "status" in frame.columns:
        usable = usable & frame["status"].isin(["designed", "not_needed"]).to_numpy()
    data = np.column_stack([_values(frame, x, units), _values(frame, y, units)])[usable]
    order = np.lexsort((data[:, 1], data[:, 0]))
    data = data[order]
    front = data[np.concatenate(([True], data[1:, 1] < np.minimum.accumulate(data[:, 1])[:-1]))]
    dropped = int((~usable).sum())
    ax.plot(
        data[:, 0],
        data[:, 1],
        "o",
        color="lightgray",
        ms=4,
        label=f"designs ({len(data)})" + (f"; {dropped} without a design left out" if dropped else ""),
    )
    ax.step(front[:, 0], front[:, 1], where="post", color=DEFICIT, lw=1.2)
    ax.plot(
        front[:, 0], front[:, 1], "o", color=DEFICIT, ms=5, label=f"Pareto front ({len(front)} points)", gid="front"
    )
    ax.set(xlabel=_label(x, units, frame), ylabel=_label(y, units, frame))
    ax.grid(True, alpha=0.3)
    _title(ax, own, f"Pareto front: {y} against {x}, both minimized")
    _legend(ax, own)
    return ax


def save(ax, path, dpi=150):
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
        fig.savefig(tmp, format=suffix, dpi=dpi)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
        _pyplot().close(fig)
    return path
