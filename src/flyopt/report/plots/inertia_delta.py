"""The required flywheel J_F against δ by the model that ran, the scene's δ marked."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.cycle.indicator import required_inertia
from flyopt.delta_curve import delta_range, flywheel_at_some_delta
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.method import NOTES, cite
from flyopt.report.plots import readout, standard
from flyopt.report.plots.digest import Plot

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


def check_inertia_delta(analysis: Analysis) -> None:
    """Raise NothingToDraw when no flywheel is needed at any δ: a steady machine of constant inertia."""
    if not flywheel_at_some_delta(analysis):
        raise standard.NothingToDraw("no flywheel is needed for any δ (A_max = 0 J, so J_F(δ) = 0): nothing to draw")


@dataclass(frozen=True, eq=False)
class InertiaDelta:
    """What the J_F–δ diagram draws, read off a scene and its analysis (:meth:`of`): all it depends on besides its
    units and digits (:func:`draw_inertia_delta` draws it from this alone, so that equal data,
    :func:`flyopt.report.plots.digest.digest`, draw the same diagram)."""

    title: str
    model: str  # the model that ran
    delta: npt.NDArray[np.float64]  # δ [-], increasing
    j: npt.NDArray[np.float64]  # J_F there [kg*m^2] (negative where none is needed)
    a_max: float  # [J]
    omega_mean: float  # the analysis' ω_m [rad/s]
    scene_omega_mean: float  # the scene's (the constant-inertia comparison's)
    j_constant: float  # the machine's constant inertia [kg*m^2]
    j_mean: float  # the cycle mean of its inertia J_e [kg*m^2]
    scene_delta: float  # the δ allowed
    j_required: float  # J_F there [kg*m^2]
    flywheel_needed: bool
    stall_limited: bool
    delta_reached: float  # the δ a stall limit reaches

    @classmethod
    def of(
        cls, scene: Scene, analysis: Analysis, curve: tuple[npt.ArrayLike, npt.ArrayLike] | None = None
    ) -> InertiaDelta:
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
        return cls(
            title=str(scene.title),
            model=str(analysis.model),
            delta=np.array(delta, dtype=float),
            j=np.array(j, dtype=float),
            a_max=float(analysis.a_max),
            omega_mean=float(analysis.omega_mean),
            scene_omega_mean=float(scene.omega_mean),
            j_constant=float(analysis.j_constant),
            j_mean=float(j_mean),
            scene_delta=float(analysis.delta),
            j_required=float(analysis.j_required),
            flywheel_needed=bool(analysis.flywheel_needed),
            stall_limited=bool(analysis.stall_limited),
            delta_reached=float(analysis.delta_reached),
        )


def plot_inertia_delta(
    scene: Scene,
    analysis: Analysis,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
    curve: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
) -> Axes:
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
    display.check_system(units)  # first, as before the split: a wrong system is said before the data
    return draw_inertia_delta(InertiaDelta.of(scene, analysis, curve), ax, units, digits)


def draw_inertia_delta(
    data: InertiaDelta,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """:func:`plot_inertia_delta` of what it draws (:class:`InertiaDelta`)."""
    display.check_system(units)
    delta, j = data.delta, data.j
    ax, own = standard.axes(ax)
    inertia = standard.unit("inertia", units)[0]
    shown = standard.show(np.where(j > 0, j, np.nan), "inertia", units)
    exact = data.model != Model.ENERGY
    j_scale = standard.scale("inertia", units, digits=digits)
    (line,) = ax.plot(
        delta,
        shown,
        "-" if not exact else ".-",
        ms=3,
        color="tab:blue",
        lw=1.6,
        gid="j_delta",
        label=f"J_F(δ), {data.model} model"
        + (" (the scene analysed at each δ)" if exact else cite(f" = A_max/(ω_m² δ) − J_c ({NOTES}, section 5)")),
    )
    readout.curve(line, "J_F", j_scale)
    readout.abscissa(ax, "δ", standard.scale("dimensionless", units, digits=digits))
    if exact and data.a_max > 0:
        # the constant-inertia method of section 5, J_e replaced by its cycle mean, for comparison
        d = np.geomspace(delta[0], delta[-1], 200)
        approx = np.array([required_inertia(data.a_max, data.scene_omega_mean, v, data.j_mean) for v in d])
        (line,) = ax.plot(
            d,
            standard.show(np.where(approx > 0, approx, np.nan), "inertia", units),
            color="gray",
            ls="--",
            lw=1,
            label=cite(f"constant-inertia method, A_max/(ω_m² δ) − mean J_e ({NOTES}, section 5), for comparison"),
            gid="constant_inertia",
        )
        readout.curve(line, "J_F by the constant-inertia method", j_scale)
    free, about = _zero_crossing(delta, j), "≈ "
    if data.model == Model.ENERGY and data.j_constant > 0 and data.a_max > 0:
        free, about = data.a_max / (data.omega_mean**2 * data.j_constant), "= "  # section 5, exact
    if free is not None and delta[0] <= free <= delta[-1]:
        ax.axvline(
            free,
            color="gray",
            ls=":",
            lw=1,
            gid="delta_free",
            label=f"δ* {about}{display.number(free, digits if about == '= ' else 2)}: above it J_F = 0 "
            f"(the machine's own inertia suffices)",
        )
    if data.stall_limited and delta[0] <= data.delta_reached <= delta[-1]:
        ax.axvline(
            data.delta_reached,
            color="tab:orange",
            ls=":",
            lw=1.2,
            gid="delta_stall",
            label=f"δ = {display.number(data.delta_reached, digits)}: from it up J_F is the stall limit "
            f"(no periodic steady state with a smaller flywheel)",
        )
    if data.flywheel_needed:
        ax.plot(
            [data.scene_delta],
            [float(standard.show(data.j_required, "inertia", units))],
            "o",
            color=standard.DEFICIT,
            ms=7,
            zorder=5,
            gid="design_point",
            label=f"the scene: δ = {display.number(data.scene_delta, digits)}, "
            f"J_F = {standard.q(data.j_required, 'inertia', units, digits)}",
        )
    else:
        ax.axvline(
            data.scene_delta,
            color=standard.DEFICIT,
            lw=1,
            gid="design_point",
            label=f"the scene's δ = {display.number(data.scene_delta, digits)}: no flywheel needed",
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
    standard.title(ax, own, data.title, f"required flywheel J_F against δ ({data.model} model)")
    standard.legend(ax, own, ncol=1)
    return ax


#: The J_F–δ diagram as what it draws and how (the app keeps it where an edit leaves its data as they were).
INERTIA_DELTA = Plot("inertia_delta", InertiaDelta.of, draw_inertia_delta)


def _plain_log_ticks(ax: Axes) -> None:
    """Numbers as numbers on log axes (0.05, 200), not powers of ten, at 1, 2 and 5 of each decade."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: display.number(v, 3)))
        axis.set_minor_formatter(NullFormatter())


def _zero_crossing(delta: npt.NDArray[np.float64], j: npt.NDArray[np.float64]) -> float | None:
    """The δ where a sampled J_F(δ) falls through zero (log-linear interpolation), or None."""
    k = np.flatnonzero((j[:-1] > 0) & (j[1:] <= 0))
    if not len(k):
        return None
    k = k[0]
    t = j[k] / (j[k] - j[k + 1])
    return float(math.exp(math.log(delta[k]) + t * (math.log(delta[k + 1]) - math.log(delta[k]))))
