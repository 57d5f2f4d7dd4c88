"""The energy indicator diagram: ΔE over the cycle, the chain points and A_max."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.errors import BrokenInvariant
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.plots import readout, standard
from flyopt.report.plots.cycle import Torques, angle_axis, excess_work, mark_dead_centres

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


def plot_energy(
    scene: Scene,
    analysis: Analysis,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """Energy indicator diagram: ΔE from the cycle start, the chain points, ΔE's extremes and A_max.

    The x axis is the turning-moment diagram's (0 to Φ). A_max is dimensioned
    right of the plot, between the levels of the largest and smallest ΔE
    (docs/flywheel-design.md, section 4). ΔE's extremes are where ω is extreme
    for a constant inertia; with a variable inertia or a speed-dependent
    torque the speed extremes of the model that ran are marked on the curve
    as well. With the dynamic model the diagram is that of the torques frozen
    at the mean speed, a motor at its mean (section 7, the A_max the analysis
    reports), and ΔE along the periodic solution is drawn over it.

    The energy axis takes its unit from what it draws and A_max (:func:`~flyopt.report.plots.standard.scale`:
    "536.7 J", as the text says it); ``digits`` are the significant figures of the numbers written on it.

    Returns
    -------
    matplotlib Axes
        The A_max dimension is the annotation of gid ``a_max``.
    """
    display.check_system(units)
    ax, own = standard.axes(ax)
    ind = analysis.indicator
    if ind is None:
        raise BrokenInvariant("every analysis carries its energy indicator diagram (flyopt.analysis)")
    chain = np.asarray(ind.chain_delta_e, dtype=float)
    constant = analysis.machine is None or not analysis.machine.variable_inertia
    drawn: list[npt.ArrayLike] = [chain, ind.a_max]
    if ind.chain_angle is not None:
        ew = excess_work(scene, analysis)
        phi = np.union1d(np.linspace(0, scene.cycle_angle, 1501), ind.chain_angle)
        curve = ew(phi)
        drawn.append(curve)
        if analysis.model == Model.DYNAMIC:
            torques = Torques(scene, analysis)
            along = torques.excess_work()
            drawn.append(along)
    energy = standard.scale("energy", units, drawn, digits)
    if ind.chain_angle is None:
        x_chain = np.arange(len(chain), dtype=float)
        ax.plot(x_chain, energy.show(chain), "-", color="tab:blue", lw=1.5, label="ΔE, chained areas")
        ax.set_xlim(0, len(chain) - 1)
        ax.set_xticks(x_chain)
        ax.set_xlabel("end of area k (0: the cycle start)")
    else:
        x_chain = standard.show(ind.chain_angle, "angle", units)
        frozen = " (torques frozen at ω_m, the motor at its mean)" if analysis.model == Model.DYNAMIC else ""
        (line,) = ax.plot(
            standard.show(phi, "angle", units),
            energy.show(curve),
            color="tab:blue",
            lw=1.5,
            label=f"ΔE(φ) = ∫(M_d − M_r) dφ{frozen}",
        )
        readout.curve(line, "ΔE", energy)
        if analysis.model == Model.DYNAMIC:
            (line,) = ax.plot(
                standard.show(torques.phi, "angle", units),
                energy.show(along),
                color="tab:purple",
                lw=1.2,
                ls="--",
                label="ΔE along the periodic solution (the motor on its characteristic)",
                gid="along",
            )
            readout.curve(line, "ΔE along ω(φ)", energy)
        angle_axis(ax, scene.cycle_angle, units, digits)
        mark_dead_centres(ax, scene, units)
    y_chain = energy.show(chain)
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
    extremes = (
        ()
        if steady
        else ((ind.index_max, names[0], standard.SURPLUS, 1), (ind.index_min, names[1], standard.DEFICIT, -1))
    )
    for k, name, colour, where in extremes:
        ax.axhline(y_chain[k], color=colour, ls=":", lw=1)
        at = (
            f" at φ = {standard.q(ind.chain_angle[k], 'angle', units, digits)}"
            if ind.chain_angle is not None
            else f" ({display.chain_point(k)})"
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
            label=f"{name}: ΔE = {energy.q(chain[k])}{at}",
            gid="chain_max" if where > 0 else "chain_min",
        )
        ax.annotate(
            name,
            (x_chain[k], y_chain[k]),
            xytext=(0, 7 * where),
            textcoords="offset points",
            ha="center",
            va="bottom" if where > 0 else "top",
            fontsize=standard.FONT,
            color=colour,
            gid="extreme_label",
        )
    if ind.chain_angle is not None and (not constant or analysis.model == Model.DYNAMIC) and not steady:
        for angle, name, colour, marker in (
            (analysis.angle_omega_max, "ω_max", standard.SURPLUS, "^"),
            (analysis.angle_omega_min, "ω_min", standard.DEFICIT, "v"),
        ):
            if angle is None:
                continue
            ax.plot(
                [float(standard.show(angle, "angle", units))],
                [float(energy.show(ew(np.array([angle]))[0]))],
                marker,
                color=colour,
                ms=7,
                zorder=6,
                gid=f"omega_{name[-3:]}",
                label=f"{name} ({analysis.model} model) at φ = {standard.q(angle, 'angle', units, digits)}",
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
            f"A_max = {energy.q(ind.a_max)}",
            transform=dimension_at,
            rotation=90,
            ha="left",
            va="center",
            fontsize=standard.FONT,
            clip_on=False,
        )
    ax.set_ylabel(energy.axis_label("excess work ΔE"))
    ax.grid(True, alpha=0.25)
    standard.title(ax, own, scene.title, f"energy indicator diagram (A_max = {energy.q(ind.a_max)})")
    standard.legend(
        ax, own, title="steady running: ΔE = 0 at every angle, the speed does not fluctuate" if steady else None
    )
    return ax
