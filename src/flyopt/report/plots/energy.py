"""The energy indicator diagram: ΔE over the cycle, the chain points and A_max."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.errors import BrokenInvariant
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.plots import readout, standard
from flyopt.report.plots.cycle import (
    CycleDiagram,
    DeadCentres,
    Torques,
    angle_axis,
    dead_centres,
    excess_work,
    mark_dead_centres,
)
from flyopt.report.plots.digest import Plot

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


@dataclass(frozen=True, eq=False)
class EnergyDiagram(CycleDiagram):
    """What the energy indicator diagram draws, read off a scene and its analysis (:meth:`of`): all it depends on
    besides its units and digits (:func:`draw_energy` draws it from this alone, so that equal data,
    :func:`flyopt.report.plots.digest.digest`, draw the same diagram)."""

    constant: bool  # a constant inertia
    chain: npt.NDArray[np.float64]  # ΔE at the chain's points [J]
    chain_angle: npt.NDArray[np.float64] | None  # their angles [rad] (None: net areas)
    index_max: int  # the chain's points of ΔE's extremes
    index_min: int
    a_max: float  # the diagram's A_max [J]
    phi: npt.NDArray[np.float64] | None  # where ΔE(φ) is drawn [rad]
    curve: npt.NDArray[np.float64] | None  # ΔE(φ) [J]
    along_phi: npt.NDArray[np.float64] | None  # the dynamic model's: ΔE along its periodic solution
    along: npt.NDArray[np.float64] | None
    omega_at: tuple[tuple[float, float] | None, ...]  # (angle, ΔE there) of the model's ω_max and ω_min
    dead_centres: DeadCentres

    @classmethod
    def of(cls, scene: Scene, analysis: Analysis) -> EnergyDiagram:
        ind = analysis.indicator
        if ind is None:
            raise BrokenInvariant("every analysis carries its energy indicator diagram (flyopt.analysis)")
        constant = analysis.machine is None or not analysis.machine.variable_inertia
        dynamic = analysis.model == Model.DYNAMIC
        phi = curve = along_phi = along = None
        omega_at: tuple[tuple[float, float] | None, ...] = (None, None)
        chain_angle = None
        if ind.chain_angle is not None:
            chain_angle = np.array(ind.chain_angle, dtype=float)
            ew = excess_work(scene, analysis)
            phi = np.union1d(np.linspace(0, scene.cycle_angle, 1501), chain_angle)
            curve = np.asarray(ew(phi), dtype=float)
            if dynamic:
                torques = Torques.of(scene, analysis)
                along_phi, along = torques.phi, torques.excess_work()
            if not constant or dynamic:
                omega_at = tuple(
                    None if angle is None else (float(angle), float(ew(np.array([angle]))[0]))
                    for angle in (analysis.angle_omega_max, analysis.angle_omega_min)
                )
        return cls(
            **CycleDiagram.common(scene, analysis),
            constant=bool(constant),
            chain=np.array(ind.chain_delta_e, dtype=float),
            chain_angle=chain_angle,
            index_max=int(ind.index_max),
            index_min=int(ind.index_min),
            a_max=float(ind.a_max),
            phi=phi,
            curve=curve,
            along_phi=along_phi,
            along=along,
            omega_at=omega_at,
            dead_centres=None if chain_angle is None else dead_centres(scene),
        )


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
    display.check_system(units)  # first, as before the split: a wrong system is said before the data
    return draw_energy(EnergyDiagram.of(scene, analysis), ax, units, digits)


def draw_energy(
    data: EnergyDiagram,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """:func:`plot_energy` of what it draws (:class:`EnergyDiagram`)."""
    display.check_system(units)
    ax, own = standard.axes(ax)
    chain, chain_angle, constant, dynamic = data.chain, data.chain_angle, data.constant, data.model == Model.DYNAMIC
    drawn: list[npt.ArrayLike] = [chain, data.a_max]
    drawn.extend(values for values in (data.curve, data.along) if values is not None)
    energy = standard.scale("energy", units, drawn, digits)
    if chain_angle is None:
        x_chain = np.arange(len(chain), dtype=float)
        ax.plot(x_chain, energy.show(chain), "-", color="tab:blue", lw=1.5, label="ΔE, chained areas")
        ax.set_xlim(0, len(chain) - 1)
        ax.set_xticks(x_chain)
        ax.set_xlabel("end of area k (0: the cycle start)")
    else:
        if data.phi is None or data.curve is None:
            raise BrokenInvariant("a scene of torque curves has its ΔE(φ)")
        x_chain = standard.show(chain_angle, "angle", units)
        frozen = " (torques frozen at ω_m, the motor at its mean)" if dynamic else ""
        (line,) = ax.plot(
            standard.show(data.phi, "angle", units),
            energy.show(data.curve),
            color="tab:blue",
            lw=1.5,
            label=f"ΔE(φ) = ∫(M_d − M_r) dφ{frozen}",
        )
        readout.curve(line, "ΔE", energy)
        if data.along is not None and data.along_phi is not None:
            (line,) = ax.plot(
                standard.show(data.along_phi, "angle", units),
                energy.show(data.along),
                color="tab:purple",
                lw=1.2,
                ls="--",
                label="ΔE along the periodic solution (the motor on its characteristic)",
                gid="along",
            )
            readout.curve(line, "ΔE along ω(φ)", energy)
        angle_axis(ax, data.cycle_angle, units, digits)
        mark_dead_centres(ax, data.dead_centres, units)
    y_chain = energy.show(chain)
    ax.plot(
        x_chain,
        y_chain,
        "o",
        color="black",
        ms=3.5,
        zorder=4,
        label="ends of the areas" if chain_angle is None else "ends of the areas: crossings of the torques",
    )
    hi, lo = float(y_chain[data.index_max]), float(y_chain[data.index_min])
    names = ("ω_max", "ω_min") if constant and not dynamic else ("ΔE largest", "ΔE smallest")
    steady = not hi > lo and constant
    extremes = (
        ()
        if steady
        else ((data.index_max, names[0], standard.SURPLUS, 1), (data.index_min, names[1], standard.DEFICIT, -1))
    )
    for k, name, colour, where in extremes:
        ax.axhline(y_chain[k], color=colour, ls=":", lw=1)
        at = (
            f" at φ = {standard.q(chain_angle[k], 'angle', units, digits)}"
            if chain_angle is not None
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
    if chain_angle is not None and (not constant or dynamic) and not steady:
        for at_omega, name, colour, marker in (
            (data.omega_at[0], "ω_max", standard.SURPLUS, "^"),
            (data.omega_at[1], "ω_min", standard.DEFICIT, "v"),
        ):
            if at_omega is None:
                continue
            angle, excess = at_omega
            ax.plot(
                [float(standard.show(angle, "angle", units))],
                [float(energy.show(excess))],
                marker,
                color=colour,
                ms=7,
                zorder=6,
                gid=f"omega_{name[-3:]}",
                label=f"{name} ({data.model} model) at φ = {standard.q(angle, 'angle', units, digits)}",
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
            f"A_max = {energy.q(data.a_max)}",
            transform=dimension_at,
            rotation=90,
            ha="left",
            va="center",
            fontsize=standard.FONT,
            clip_on=False,
        )
    ax.set_ylabel(energy.axis_label("excess work ΔE"))
    ax.grid(True, alpha=0.25)
    standard.title(ax, own, data.title, f"energy indicator diagram (A_max = {energy.q(data.a_max)})")
    standard.legend(
        ax, own, title="steady running: ΔE = 0 at every angle, the speed does not fluctuate" if steady else None
    )
    return ax


#: The energy indicator diagram as what it draws and how (the app keeps it where an edit leaves its data as they
#: were).
ENERGY = Plot("energy", EnergyDiagram.of, draw_energy)
