"""The energy–mass (Wittenbauer) diagram: ΔE against J_e with the two tangents."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from flyopt.errors import BrokenInvariant
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.plots import readout, standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


def check_energy_mass(analysis: Analysis) -> None:
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


#: Colour steps of the energy–mass curve over the cycle (one a degree of a 360° cycle).
COLOURS = 360


def plot_energy_mass(
    scene: Scene,
    analysis: Analysis,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
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
        Each energy axis takes its unit from what it draws (:func:`~flyopt.report.plots.standard.scale`): the
        diagram near the curve from ΔE, the overview from ΔE and the true origin's E_0, which its legend gives.
    digits : int
        Significant figures of the numbers written on the diagram (the speeds of the tangents one more).

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
    if machine is None:
        raise BrokenInvariant("the energy–mass diagram is of a machine given by torque curves (check_energy_mass)")
    em = analysis.requirement.detail
    ew = machine.angle_only()
    phi = np.union1d(np.linspace(0, scene.cycle_angle, 1441), ew.knots)
    j = np.asarray(machine.j_machine(phi), dtype=float)
    de = np.asarray(ew(phi), dtype=float)
    j_f = max(em.j_required, 0.0)
    x0, y0 = -j_f, -em.e0
    overview: Axes | None = None
    if ax is None:
        fig = standard.new_figure(figsize=(11, 5.6), layout="constrained")
        overview, ax = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 1.5]})
    inertia = standard.unit("inertia", units)[0]
    near = standard.scale("energy", units, [de], digits)
    reach = np.array([x0, j.max() + 0.1 * (j.max() - x0)])  # the overview's span of J_e, from the true origin
    whole = standard.scale(
        "energy", units, [de, y0, y0 + 0.5 * max(em.omega_max, em.omega_min) ** 2 * (reach - x0)], digits
    )
    legend_energy = whole if overview is not None else near
    sj, se = (lambda v: standard.show(v, "inertia", units)), near.show
    tangents = (
        (em.omega_max, em.phi_omega_max, standard.SURPLUS, "max"),
        (em.omega_min, em.phi_omega_min, standard.DEFICIT, "min"),
    )
    points = np.column_stack([sj(j), se(de)])
    # the curve coloured by φ in at most COLOURS pieces, each a polyline through every computed point of its
    # span (the shape is all the points; the colour steps by 1/COLOURS of the cycle, finer than the eye or the
    # colour map): one path per piece, not one per pair of points (1441 angles and the knots)
    ends = np.unique(np.linspace(0, len(phi) - 1, min(COLOURS, len(phi) - 1) + 1).round().astype(int))
    pieces = [points[a : b + 1] for a, b in zip(ends[:-1], ends[1:])]
    coloured = LineCollection(pieces, cmap="twilight", lw=2.2, gid="curve")  # cyclic: φ = Φ meets φ = 0
    coloured.set_array(standard.show(0.5 * (phi[ends[:-1]] + phi[ends[1:]]), "angle", units))
    ax.add_collection(coloured)
    angle = standard.scale("angle", units, digits=digits)
    j_scale = standard.scale("inertia", units, [j], digits)

    def rows(at: np.ndarray, energy: standard.Scale, first: str | None = None) -> list[list[str]]:
        """A point's read-out at the angles ``at``: φ, J_e and ΔE (ΔE in the panel's ``energy`` scale)."""
        j_at, e_at = np.asarray(machine.j_machine(at), dtype=float), np.asarray(ew(at), dtype=float)
        return [
            [*([first] if first else []), f"φ = {angle.q(p)}", f"J_e = {j_scale.q(a)}", f"ΔE = {energy.q(b)}"]
            for p, a, b in zip(at.tolist(), j_at.tolist(), e_at.tolist())
        ]

    readout.points(coloured, rows(phi, near))
    coloured.set_clim(0.0, float(standard.show(scene.cycle_angle, "angle", units)))
    bar = ax.figure.colorbar(coloured, ax=ax, pad=0.01)
    bar.set_label(standard.axis_label("crank angle φ", "angle", units))
    if display.label("angle", units) == "deg":
        bar.set_ticks(np.arange(0.0, float(standard.show(scene.cycle_angle, "angle", units)) + 1.0, 90.0).tolist())
    ax.plot([sj(j[0])], [se(de[0])], "s", color="black", ms=5, label="φ = 0, the cycle's start", zorder=5)
    span_x, span_y = float(np.ptp(j)), float(np.ptp(de))
    xs = np.array([j.min() - 0.3 * span_x, j.max() + 0.3 * span_x])
    apart = standard.digits_apart([w for w, *_rest in tangents], "angular_speed", units, digits)
    for w, at, colour, name in tangents:
        slope = 0.5 * w**2
        ax.plot(
            sj(xs),
            se(y0 + slope * (xs - x0)),
            color=colour,
            lw=1,
            ls="--",
            label=f"tangent of slope ω_{name}²/2, ω_{name} = {standard.q(w, 'angular_speed', units, apart)}",
        )
        touch = np.array([at])
        (point,) = ax.plot(
            [sj(machine.j_machine(touch)[0])],
            [se(ew(touch)[0])],
            "o",
            ms=8,
            mfc="white",
            mec=colour,
            mew=2,
            zorder=6,
            gid=f"tangent_{name}",
            label=f"touches where the speed is ω_{name}: φ = {standard.q(at, 'angle', units, digits)}",
        )
        readout.points(point, rows(touch, near, f"the tangent of ω_{name} touches"))
    ax.set_xlim(sj(j.min() - 0.15 * max(span_x, 1e-12)), sj(j.max() + 0.15 * max(span_x, 1e-12)))
    ax.set_ylim(se(de.min() - 0.15 * max(span_y, 1e-12)), se(de.max() + 0.15 * max(span_y, 1e-12)))
    ax.set(xlabel=f"equivalent inertia of the machine J_e [{inertia}]", ylabel=near.axis_label("excess work ΔE"))
    ax.grid(True, alpha=0.25)
    origin = (
        f"the tangents meet at the true origin (−J_F, −E_0) = ({standard.q(x0, 'inertia', units, digits)}, "
        f"{legend_energy.q(y0)}): J_F = {standard.q(j_f, 'inertia', units, digits)}"
    )
    if overview is not None:
        (whole_curve,) = overview.plot(sj(j), whole.show(de), color="tab:blue", lw=1.5)
        readout.points(whole_curve, rows(phi, whole))
        for w, _at, colour, _name in tangents:
            overview.plot(sj(reach), whole.show(y0 + 0.5 * w**2 * (reach - x0)), color=colour, lw=1, ls="--")
        overview.plot([sj(x0)], [whole.show(y0)], "ko", ms=6, gid="origin", label=origin)
        overview.axhline(0, color="gray", lw=0.5)
        overview.axvline(0, color="gray", lw=0.5)
        overview.set(xlabel=f"J_e [{inertia}]", ylabel=whole.axis_label("ΔE"))
        overview.xaxis.set_major_locator(MaxNLocator(4))  # a narrow panel: few ticks, none overlapping
        overview.set_title("the whole: from the true origin", fontsize=standard.FONT + 1)
        overview.grid(True, alpha=0.25)
        ax.set_title("near the curve: the tangent points", fontsize=standard.FONT + 1)
        fig.suptitle(f"{scene.title}\nenergy–mass diagram (Wittenbauer), {analysis.model} model", fontsize=11)
        handles = overview.get_legend_handles_labels()[0] + ax.get_legend_handles_labels()[0]
        standard.legend(ax, True, handles=handles)
    else:
        ax.plot([], [], " ", label=origin)
        standard.title(ax, False, scene.title, "energy–mass diagram (Wittenbauer)")
        standard.legend(ax, False)
    return ax
