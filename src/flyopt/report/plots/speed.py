"""The speed over the cycle, ω(φ) with the required flywheel, from the model that ran."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.names import Model
from flyopt.report import display
from flyopt.report.plots import readout, standard
from flyopt.report.plots.cycle import CycleDiagram, DeadCentres, angle_axis, dead_centres, mark_dead_centres
from flyopt.report.plots.digest import Plot

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene
    from flyopt.sizing.energy_mass import SpeedFluctuation
    from flyopt.sizing.periodic import PeriodicSolution


@dataclass(frozen=True, eq=False)
class SpeedDiagram(CycleDiagram):
    """What the speed diagram draws, read off a scene, its analysis and the speeds given (:meth:`of`): all it
    depends on besides its units and digits (:func:`draw_speed` draws it from this alone, so that equal data,
    :func:`flyopt.report.plots.digest.digest`, draw the same diagram)."""

    dead_centres: DeadCentres
    phi: npt.NDArray[np.float64]  # the model's ω(φ): angles [rad]
    omega: npt.NDArray[np.float64]  # and speeds [rad/s]
    omega_max: float  # its extremes [rad/s] (the model's where it gives them, else the curve's)
    omega_min: float
    phi_omega_max: float | None  # where they are [rad], where the model says
    phi_omega_min: float | None
    achieved: float  # the δ the curve achieves
    allowed: float  # the δ allowed
    j_required: float  # the flywheel the curve is of [kg*m^2]
    given: bool  # a flywheel that exists (the analysis at the δ it reaches)
    simulation: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], float] | None  # (φ, ω, δ) simulated

    @classmethod
    def of(
        cls,
        scene: Scene,
        analysis: Analysis,
        speed: SpeedFluctuation | PeriodicSolution | None = None,
        simulation: PeriodicSolution | None = None,
    ) -> SpeedDiagram:
        if scene.net is not None:
            raise ValueError("a net-area scene has no angles: ω(φ) cannot be drawn")
        if speed is None:
            if analysis.requirement is None or analysis.requirement.model != Model.DYNAMIC:
                raise ValueError(
                    f"the {analysis.model} model's result carries no ω(φ): pass speed (Analysis.speed_curve())"
                )
            speed = analysis.speed_curve()
            if speed is None:
                raise standard.NothingToDraw(
                    "no flywheel is needed and the speed does not fluctuate (A_max = 0 J, no inertia at all): "
                    "nothing to draw"
                )
        omega = np.array(speed.omega, dtype=float)
        w_max = float(getattr(speed, "omega_max", float(np.max(omega))))
        w_min = float(getattr(speed, "omega_min", float(np.min(omega))))

        def angle(name: str) -> float | None:
            value = getattr(speed, name, None)
            return None if value is None else float(value)

        return cls(
            **CycleDiagram.common(scene, analysis),
            dead_centres=dead_centres(scene),
            phi=np.array(speed.phi, dtype=float),
            omega=omega,
            omega_max=w_max,
            omega_min=w_min,
            phi_omega_max=angle("phi_omega_max"),
            phi_omega_min=angle("phi_omega_min"),
            achieved=float(getattr(speed, "delta", (w_max - w_min) / (0.5 * (w_max + w_min)))),
            allowed=float(analysis.delta),
            j_required=float(analysis.j_required),
            given=scene.flywheel is not None,
            simulation=None
            if simulation is None
            else (
                np.array(simulation.phi, dtype=float),
                np.array(simulation.omega, dtype=float),
                float(simulation.delta),
            ),
        )


def plot_speed(
    scene: Scene,
    analysis: Analysis,
    speed: SpeedFluctuation | PeriodicSolution | None = None,
    simulation: PeriodicSolution | None = None,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
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
    display.check_system(units)  # first, as before the split: a wrong system is said before the data
    return draw_speed(SpeedDiagram.of(scene, analysis, speed, simulation), ax, units, digits)


def draw_speed(
    data: SpeedDiagram,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """:func:`plot_speed` of what it draws (:class:`SpeedDiagram`)."""
    display.check_system(units)
    ax, own = standard.axes(ax)
    omega = data.omega
    x = standard.show(data.phi, "angle", units)
    speed_scale = standard.scale("angular_speed", units, digits=digits)
    (line,) = ax.plot(
        x,
        speed_scale.show(omega),
        color="tab:blue",
        lw=1.6,
        gid="model",
        label=f"ω(φ), {data.model} model, J_F = {standard.q(data.j_required, 'inertia', units, digits)}",
    )
    readout.curve(line, "ω", speed_scale)
    if data.simulation is not None:
        simulated_phi, simulated_omega, simulated_delta = data.simulation
        (line,) = ax.plot(
            standard.show(simulated_phi, "angle", units),
            speed_scale.show(simulated_omega),
            color=standard.DEFICIT,
            ls="--",
            lw=1,
            gid="simulation",
            label=f"periodic simulation (δ = {display.number(simulated_delta, digits)})",
        )
        readout.curve(line, "ω (simulation)", speed_scale)
    w_max, w_min = data.omega_max, data.omega_min
    w_mean = 0.5 * (w_max + w_min)
    where = {"max": data.phi_omega_max, "min": data.phi_omega_min}
    apart = standard.digits_apart((w_max, w_mean, w_min), "angular_speed", units, digits)
    for value, name, colour, style in (
        (w_max, "max", standard.SURPLUS, ":"),
        (w_mean, "mean", "gray", "-."),
        (w_min, "min", standard.DEFICIT, ":"),
    ):
        at = where.get(name)
        angle = f" at φ = {standard.q(at, 'angle', units, digits)}" if at is not None and w_max > w_min else ""
        symbol = "ω_m = (ω_max + ω_min)/2" if name == "mean" else f"ω_{name}"
        ax.axhline(
            float(standard.show(value, "angular_speed", units)),
            color=colour,
            ls=style,
            lw=1,
            gid=f"omega_{name}",
            label=f"{symbol} = {standard.q(value, 'angular_speed', units, apart)}{angle}",
        )
        if at is not None and name != "mean" and w_max > w_min:
            ax.plot(
                [float(standard.show(at, "angle", units))],
                [float(standard.show(value, "angular_speed", units))],
                "o",
                color=colour,
                ms=5,
                zorder=5,
            )
    angle_axis(ax, data.cycle_angle, units, digits)
    mark_dead_centres(ax, data.dead_centres, units)
    span = max(w_max - w_min, 1e-9 * w_mean)
    ax.set_ylim(*(float(standard.show(v, "angular_speed", units)) for v in (w_min - 0.12 * span, w_max + 0.12 * span)))
    ax.set_ylabel(standard.axis_label("speed of the reference shaft ω", "angular_speed", units))
    ax.grid(True, alpha=0.25)
    achieved = data.achieved
    given = data.given  # a wheel that exists: the analysis is at the δ it reaches
    standard.title(
        ax,
        own,
        data.title,
        f"speed over the cycle with the flywheel given: δ = {display.number(achieved, digits)}"
        if given
        else f"speed over the cycle: δ = {display.number(achieved, digits)} achieved, "
        f"{display.number(data.allowed, digits)} allowed",
    )
    standard.legend(ax, own)
    return ax


#: The speed diagram as what it draws and how (the app keeps it where an edit leaves its data as they were).
SPEED = Plot("speed", SpeedDiagram.of, draw_speed)
