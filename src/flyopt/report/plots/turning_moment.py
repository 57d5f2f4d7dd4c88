"""The turning-moment diagram: driving and resisting torque over the cycle, the areas between them shaded and labelled."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from flyopt.errors import BrokenInvariant
from flyopt.report import display
from flyopt.report.plots import readout, standard
from flyopt.report.plots.cycle import (
    CycleDiagram,
    DeadCentres,
    Extremes,
    Torques,
    angle_axis,
    dead_centres,
    mark_dead_centres,
    omega_marks,
)
from flyopt.report.plots.digest import Plot
from flyopt.report.plots.labels import place_area_labels

if TYPE_CHECKING:
    from collections.abc import Sequence

    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


@dataclass(frozen=True, eq=False)
class TurningMoment(CycleDiagram):
    """What the turning-moment diagram draws, read off a scene and its analysis (:meth:`of`): all it depends on
    besides its units and digits (:func:`draw_turning_moment` draws it from this alone, so that equal data,
    :func:`flyopt.report.plots.digest.digest`, draw the same diagram)."""

    a_max: float  # the analysis' A_max [J]
    areas: npt.NDArray[np.float64]  # the energy indicator diagram's areas [J]
    indicator_a_max: float  # its A_max [J]
    net: bool  # a net-area scene: its areas as bars, no curves (the fields below unused)
    torques: Torques | None
    between: tuple[tuple[float, float, float], ...]  # (left, right, energy) of each area between the curves
    driving_torque: float | None  # the mean driving torque W/Φ [N*m]
    extremes: Extremes | None
    dead_centres: DeadCentres

    @classmethod
    def of(cls, scene: Scene, analysis: Analysis) -> TurningMoment:
        ind = analysis.indicator
        if ind is None:
            raise BrokenInvariant("every analysis carries its energy indicator diagram (flyopt.analysis)")

        def made(**rest: Any) -> TurningMoment:
            return cls(
                **CycleDiagram.common(scene, analysis),
                a_max=float(analysis.a_max),
                areas=np.array(ind.areas, dtype=float),
                indicator_a_max=float(ind.a_max),
                **rest,
            )

        if scene.net is not None:
            return made(net=True, torques=None, between=(), driving_torque=None, extremes=None, dead_centres=None)
        torques = Torques.of(scene, analysis)
        if torques.along:
            between = torques.areas()
        else:
            if ind.chain_angle is None:
                raise BrokenInvariant("a scene of torque curves has the angles of its chain")
            between = [
                (float(l), float(r), float(a)) for l, r, a in zip(ind.chain_angle[:-1], ind.chain_angle[1:], ind.areas)
            ]
        mean = analysis.driving_torque
        return made(
            net=False,
            torques=torques,
            between=tuple(between),
            driving_torque=None if mean is None else float(mean),
            extremes=Extremes.of(analysis),
            dead_centres=dead_centres(scene),
        )


def plot_turning_moment(
    scene: Scene,
    analysis: Analysis,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """Turning-moment diagram: M_d and M_r over the cycle, surplus and deficit shaded.

    Each area between crossings is labelled with its energy where it has room
    (areas under 1 % of A_max and 2 % of the cycle are left unlabelled, and of
    more than :data:`MAX_AREA_LABELS` areas the largest alone); the
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
        The unit system of the axes and labels (:mod:`flyopt.report.display`); the torque axis takes its
        prefix from the torques it draws, the areas' energies theirs from the areas and A_max
        (:func:`~flyopt.report.plots.standard.scale`), as the text writes them.
    digits : int
        Significant figures of the numbers written on the diagram.

    Returns
    -------
    matplotlib Axes
        Lines labelled by their meaning; the marks of the extremes carry gids
        ``omega_max``, ``omega_min`` (and ``delta_e_max``, ``delta_e_min``),
        the area texts gid ``area``.
    """
    display.check_system(units)  # first, as before the split: a wrong system is said before the data
    return draw_turning_moment(TurningMoment.of(scene, analysis), ax, units, digits)


def draw_turning_moment(
    data: TurningMoment,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """:func:`plot_turning_moment` of what it draws (:class:`TurningMoment`)."""
    display.check_system(units)
    ax, own = standard.axes(ax)
    energy = standard.scale("energy", units, [data.areas, data.indicator_a_max, data.a_max], digits)
    if data.net:
        areas = data.areas
        k = np.arange(1, len(areas) + 1)
        ax.bar(
            k - 0.5,
            energy.show(areas),
            width=0.8,
            color=[standard.SURPLUS if a > 0 else standard.DEFICIT for a in areas],
        )
        ax.axhline(0, color="black", lw=0.8)
        for x, a in zip(k - 0.5, areas):
            ax.annotate(
                energy.q(a),
                (x, float(energy.show(a))),
                xytext=(0, 3 if a > 0 else -3),
                textcoords="offset points",
                ha="center",
                va="bottom" if a > 0 else "top",
                fontsize=standard.FONT,
                gid="area",
            )
        ax.set_xlim(0, len(areas))
        ax.set_xticks(k - 0.5, labels=[str(i) for i in k])
        ax.margins(y=0.15)
        ax.set(
            xlabel="area between the torque curves, in order over the cycle",
            ylabel=energy.axis_label("energy of the area"),
        )
        standard.title(
            ax,
            own,
            data.title,
            f"net areas between the torque curves (A_max = {energy.q(data.indicator_a_max)})",
        )
        return ax
    torques, between, extremes = data.torques, data.between, data.extremes
    if torques is None or extremes is None:
        raise BrokenInvariant("a scene of torque curves has its torques and extremes")
    energy = standard.scale("energy", units, [[a for *_lr, a in between], data.a_max], digits)
    mean = data.driving_torque if torques.along and not torques.driving_solved else None
    torque = standard.scale("torque", units, [torques.driving, torques.resisting, mean], digits)
    x = standard.show(torques.phi, "angle", units)
    md, mr = torque.show(torques.driving), torque.show(torques.resisting)
    ax.fill_between(x, md, mr, where=md >= mr, color=standard.SURPLUS, alpha=0.25, interpolate=True, lw=0)
    ax.fill_between(x, md, mr, where=md < mr, color=standard.DEFICIT, alpha=0.25, interpolate=True, lw=0)
    (driving,) = ax.plot(
        x,
        md,
        color="tab:blue",
        lw=1.8,
        label=_torque_words("driving M_d", torques.driving_solved, torques.driving, torques, torque),
    )
    (resisting,) = ax.plot(
        x,
        mr,
        color="black",
        lw=1.8,
        label=_torque_words("resisting M_r", torques.resisting_solved, torques.resisting, torques, torque),
    )
    readout.curve(driving, "M_d", torque)
    readout.curve(resisting, "M_r", torque)
    levels = []
    if torques.along and not torques.driving_solved and np.ptp(torques.driving) > 0:
        mean = data.driving_torque
        if mean is None:
            raise BrokenInvariant("a scene of torque curves has its mean driving torque")
        levels.append(float(torque.show(mean)))
        ax.axhline(
            float(torque.show(mean)),
            color="tab:blue",
            ls="--",
            lw=1.0,
            label=f"mean M_d = W/Φ = {torque.q(mean)}",
            gid="mean_driving",
        )
    marks, note = omega_marks(extremes, units, digits)
    for angle, words, colour, style, gid in marks:
        ax.axvline(float(standard.show(angle, "angle", units)), color=colour, ls=style, lw=1.1, label=words, gid=gid)
    end = angle_axis(ax, data.cycle_angle, units, digits)
    top = mark_dead_centres(ax, data.dead_centres, units)
    ax.set_ylabel(torque.axis_label("torque at the reference shaft"))
    what = "along the periodic solution" if torques.along else f"A_max = {energy.q(data.a_max)}"
    standard.title(ax, own, data.title, f"turning-moment diagram, {what} ({data.model} model)")
    span = max(float(np.ptp(np.concatenate([md, mr]))), 1e-12 * max(1.0, float(np.max(np.abs(md)))))
    low, high = float(min(md.min(), mr.min())), float(max(md.max(), mr.max()))
    if span <= 1e-9 * max(abs(high), 1.0):
        ax.set_ylim(low - 0.5 * max(abs(low), 1.0), high + 0.5 * max(abs(high), 1.0))
    else:
        ax.set_ylim(low - 0.12 * span, high + 0.22 * span)
    standard.legend(ax, own, title=note)
    largest = max([abs(a) for _l, _r, a in between] + [0.0])
    spans = [
        (
            float(standard.show(left, "angle", units)),
            float(standard.show(right, "angle", units)),
            f"{'+' if area > 0 else '−'}{energy.q(abs(area))}",
            standard.SURPLUS if area > 0 else standard.DEFICIT,
        )
        for left, right, area in _labelled(between, largest, data.cycle_angle)
    ]
    place_area_labels(
        ax,
        x,
        np.minimum(md, mr),
        np.maximum(md, mr),
        spans,
        [float(standard.show(a, "angle", units)) for a, *_r in marks],
        levels,
        keep_layout=own,  # a caller's figure keeps its engine: it may add panels, legends, a title
    )
    ax.set_xlim(0.0, end)
    del top
    return ax


#: The turning-moment diagram as what it draws and how (the app keeps it where an edit leaves its data as they were).
TURNING_MOMENT = Plot("turning_moment", TurningMoment.of, draw_turning_moment)

#: The most areas the diagram labels: the largest, where a table crosses its mean thousands of times (a label
#: needs some 15 mm of a diagram about 180 mm wide; each costs a search over the drawn points).
MAX_AREA_LABELS = 40


def _labelled(
    between: Sequence[tuple[float, float, float]], largest: float, cycle: float
) -> list[tuple[float, float, float]]:
    """The areas (left, right, energy) worth a label, in their order: not under 1 % of the largest and 2 % of the
    cycle, nor round-off, and of more than :data:`MAX_AREA_LABELS` the largest."""
    if largest <= 0:
        return []
    kept = [
        (left, right, area)
        for left, right, area in between
        if (abs(area) >= 0.01 * largest or right - left >= 0.02 * cycle) and abs(area) > 1e-9 * largest
    ]
    if len(kept) > MAX_AREA_LABELS:
        cut = sorted(abs(area) for *_lr, area in kept)[-MAX_AREA_LABELS]
        kept = [k for k in kept if abs(k[2]) >= cut][:MAX_AREA_LABELS]
    return kept


def _torque_words(
    words: str, solved: bool, values: npt.NDArray[np.float64], torques: Torques, torque: standard.Scale
) -> str:
    """A torque's legend entry: its value when it is a constant solved from the work balance."""
    if solved:
        how = "with the periodic solution" if torques.along else "from the work balance"
        return f"{words} = {torque.q(float(values[0]))} (constant, solved {how})"
    if torques.along and words.startswith("driving") and torques.motor:
        return f"{words}: the motor on its characteristic along ω(φ)"
    if torques.along and torques.resisting_speed and words.startswith("resisting"):
        return f"{words} along ω(φ)"
    if np.ptp(values) == 0:
        return f"{words} = {torque.q(float(values[0]))}"
    return words
