"""What the diagrams over the cycle share: the crank-angle axis, the dead centres, the torques as the model that ran saw them, the marks of the speed extremes."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.torque import Constant
from flyopt.errors import BrokenInvariant
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.method import NOTES, cite
from flyopt.report.plots import readout, standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.axes._secondary_axes import SecondaryAxis

    from flyopt.analysis import Analysis
    from flyopt.cycle.torque import TorqueCurve
    from flyopt.io.scene import Scene

#: A vertical mark of a speed extreme: (angle [rad], label, colour, line style, gid).
Mark = tuple[float, str, str, str, str]


def angle_axis(ax: Axes, cycle_angle: float, units: str, digits: int = display.DEFAULT_DIGITS) -> float:
    """The x axis of every diagram of the cycle: the crank angle from 0 to Φ, ticks at whole fractions; read out
    as φ (:mod:`~flyopt.report.plots.readout`)."""
    from matplotlib.ticker import MultipleLocator

    end = float(standard.show(cycle_angle, "angle", units))
    ax.set_xlim(0.0, end)
    ax.set_xlabel(standard.axis_label("crank angle φ", "angle", units))
    readout.abscissa(ax, "φ", standard.scale("angle", units, digits=digits))
    if display.label("angle", units) == "deg":
        ax.xaxis.set_major_locator(MultipleLocator(90 if end > 400 else 45))
    return end


#: The dead centres of a scene's crank (:func:`dead_centres`): (major, minor, words), or None.
DeadCentres = tuple[tuple[tuple[float, str], ...], tuple[tuple[float, str], ...], str] | None


def dead_centres(scene: Scene) -> DeadCentres:
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
        return tuple(major), tuple(minor), words
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
        return (
            tuple(sorted(major)),
            (),
            "slider-crank dead centres: ODC outer (slider farthest from the crank), IDC inner",
        )
    return None


def mark_dead_centres(ax: Axes, marks: DeadCentres, units: str) -> SecondaryAxis | None:
    """The dead centres (and an engine's strokes) on a top axis, faint lines through the data (``marks``: the
    scene's :func:`dead_centres`)."""
    if marks is None:
        return None
    major, minor, words = marks
    top = ax.secondary_xaxis("top")
    top.set_gid("dead_centres")
    top.set_xticks([float(standard.show(a, "angle", units)) for a, _n in major], labels=[n for _a, n in major])
    top.set_xticks(
        [float(standard.show(a, "angle", units)) for a, _n in minor], labels=[n for _a, n in minor], minor=True
    )
    top.tick_params(axis="x", which="major", labelsize=7.5)
    top.tick_params(axis="x", which="minor", length=0, labelsize=7, labelcolor="dimgray")
    top.set_xlabel(words, fontsize=standard.FONT)
    for angle, _name in major:
        ax.axvline(float(standard.show(angle, "angle", units)), color="0.8", lw=0.6, zorder=0)
    return top


@dataclass(frozen=True, eq=False)
class CycleDiagram:
    """What every diagram over the cycle draws of its scene, the first fields of a split plot's data
    (:mod:`flyopt.report.plots.digest`): the scene's title, the model that ran, the cycle's angle [rad]."""

    title: str
    model: str
    cycle_angle: float

    @staticmethod
    def common(scene: Scene, analysis: Analysis) -> dict[str, Any]:
        """Those fields of ``scene`` and its ``analysis``."""
        return {"title": str(scene.title), "model": str(analysis.model), "cycle_angle": float(scene.cycle_angle)}


# --------------------------------------------------------------------------
# The torques over the cycle, as the model that ran saw them
# --------------------------------------------------------------------------


def excess_work(scene: Scene, analysis: Analysis) -> ExcessWork:
    """ΔE of the torques as the analysis saw them (members' loads joined, a motor at its mean).

    Raises
    ------
    ValueError
        A net-area scene: it has areas, no torques of the angle.
    """
    if analysis.machine is None:
        raise ValueError(f"{scene.title!r} is given as net areas: it has no ΔE(φ) to draw")
    return analysis.machine.angle_only()


def _unknown(curve):
    return isinstance(curve, Constant) and curve.unknown


def _solved(curve: TorqueCurve) -> float:
    """The value of a constant torque solved from the work balance [N*m]."""
    if not isinstance(curve, Constant):
        raise BrokenInvariant("the balanced curve of an unknown constant is the solved constant")
    return curve.known()


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


@dataclass(frozen=True, eq=False)
class Torques:
    """The driving and resisting torques over the cycle [N*m] as the model that ran saw them (:meth:`of`).

    The energy models see torques of the angle only (an unknown constant
    solved from the work balance); the dynamic model sees every torque along
    its periodic solution ω(φ), a motor on its characteristic, not at its
    mean (docs/flywheel-design.md, section 7). ``phi`` repeats an angle where a
    torque steps (left limit first), so lines and shading draw the steps.
    """

    phi: npt.NDArray[np.float64]
    driving: npt.NDArray[np.float64]
    resisting: npt.NDArray[np.float64]
    along: bool  # along the dynamic model's periodic solution ω(φ)
    driving_solved: bool  # an unknown constant solved from the work balance
    resisting_solved: bool
    motor: bool  # the driving torque is (or holds) a motor's
    resisting_speed: bool  # the resisting torque depends on speed

    @classmethod
    def of(cls, scene: Scene, analysis: Analysis) -> Torques:
        """The torques of ``scene`` as ``analysis`` saw them."""
        machine = analysis.machine
        if machine is None:
            raise ValueError("a net-area scene has no torque curves to draw over the cycle")
        balanced = machine.angle_only()
        along = analysis.model == Model.DYNAMIC
        driving_solved = bool(_unknown(machine.driving))
        resisting_solved = bool(_unknown(machine.resisting))
        if along:
            if analysis.requirement is None:
                raise BrokenInvariant("the dynamic model's analysis carries its requirement")
            speed = analysis.requirement.detail.solution  # the periodic solution the dynamic model found
            phi, omega = np.asarray(speed.phi, dtype=float), np.asarray(speed.omega, dtype=float)
            offset = float(getattr(speed, "torque_offset", 0.0) or 0.0)
            # the periodic model's net torque: an unknown constant is the balancing one plus the offset
            driving = (
                np.full(phi.shape, _solved(balanced.driving) + offset)
                if driving_solved
                else _along(machine.driving, phi, omega)
            )
            resisting = (
                np.full(phi.shape, _solved(balanced.resisting) - offset)
                if resisting_solved
                else _along(machine.resisting, phi, omega)
            )
        else:
            ind = analysis.indicator
            if ind is None or ind.chain_angle is None:
                raise BrokenInvariant("a machine's analysis has its diagram's angles")
            phi = np.union1d(np.linspace(0.0, scene.cycle_angle, 3001), np.asarray(balanced.knots, dtype=float))
            phi = np.union1d(phi, ind.chain_angle)
            steps = np.zeros(phi.shape, bool)
            for curve in (balanced.driving, balanced.resisting):
                left, right = curve.limits(phi)
                steps |= np.asarray(left != right)
            phi = np.sort(np.concatenate([phi, phi[steps]]))
            driving = _sides(phi, balanced.driving)
            resisting = _sides(phi, balanced.resisting)
        return cls(
            phi=np.array(phi, dtype=float),
            driving=np.array(driving, dtype=float),
            resisting=np.array(resisting, dtype=float),
            along=along,
            driving_solved=driving_solved,
            resisting_solved=resisting_solved,
            motor=_is_motor(machine.driving),
            resisting_speed=bool(getattr(machine.resisting, "speed_dependent", False)),
        )

    @property
    def net(self) -> npt.NDArray[np.float64]:
        """M_d − M_r on the drawn grid [N*m]."""
        return self.driving - self.resisting

    def excess_work(self) -> npt.NDArray[np.float64]:
        """ΔE(φ) = ∫_0^φ (M_d − M_r) dφ of the drawn torques, by the trapezoidal rule [J]."""
        from scipy.integrate import cumulative_trapezoid

        return cumulative_trapezoid(self.net, self.phi, initial=0.0)

    def areas(self) -> list[tuple[float, float, float]]:
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
# The turning-moment diagram
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Extremes:
    """Where the analysis puts the speed's extremes and ΔE's (the ends of A_max), and what decides them: what
    :func:`omega_marks` marks (:meth:`of` an analysis)."""

    model: str
    a_max: float
    variable_inertia: bool
    angle_omega_max: float | None
    angle_omega_min: float | None
    angle_delta_e_max: float | None
    angle_delta_e_min: float | None

    @classmethod
    def of(cls, analysis: Analysis) -> Extremes:
        def angle(value: float | None) -> float | None:
            return None if value is None else float(value)

        return cls(
            str(analysis.model),
            float(analysis.a_max),
            bool(analysis.machine is not None and analysis.machine.variable_inertia),
            angle(analysis.angle_omega_max),
            angle(analysis.angle_omega_min),
            angle(analysis.angle_delta_e_max),
            angle(analysis.angle_delta_e_min),
        )


def omega_marks(analysis: Extremes, units: str, digits: int = standard.DIGITS) -> tuple[list[Mark], str | None]:
    """The vertical marks of the speed extremes and of the ends of A_max: (angle, label, colour, style, gid).

    With a constant inertia and torques of the angle only the speed is extreme
    where ΔE is (docs/flywheel-design.md, section 4): one mark each. With a
    variable J_e(φ) the speed is extreme where the energy–mass tangents touch
    (section 6), with a speed-dependent torque where the periodic solution
    says (section 7): both pairs are marked, and the legend says why.
    """
    marks: list[Mark] = []
    note: str | None = None
    if analysis.a_max <= 0 and not analysis.variable_inertia:
        return marks, "steady running: M_d = M_r at every angle, A_max = 0, the speed does not fluctuate"
    model = {"energy": "energy method", "energy_mass": "energy–mass model", "dynamic": "periodic solution"}[
        analysis.model
    ]
    pairs = (
        ("max", analysis.angle_omega_max, analysis.angle_delta_e_max, "largest", standard.SURPLUS),
        ("min", analysis.angle_omega_min, analysis.angle_delta_e_min, "smallest", standard.DEFICIT),
    )
    differ = False
    for name, omega_at, delta_e_at, word, colour in pairs:
        if omega_at is None:
            continue
        apart = delta_e_at is not None and abs(omega_at - delta_e_at) > 1e-3
        differ |= apart
        # where the model's speed extreme and ΔE's extreme coincide, one mark says both; where they are
        # apart, each has its own, and the dynamic model (whose ΔE is not drawn) marks only the speed's
        separate = analysis.model != Model.DYNAMIC and apart
        label = f"ω_{name} ({model})" if analysis.model == Model.DYNAMIC or separate else f"ω_{name} where ΔE is {word}"
        marks.append(
            (omega_at, f"{label}: φ = {standard.q(omega_at, 'angle', units, digits)}", colour, "--", f"omega_{name}")
        )
        if separate and delta_e_at is not None:
            marks.append(
                (
                    delta_e_at,
                    f"ΔE {word} (an end of A_max): φ = {standard.q(delta_e_at, 'angle', units, digits)}",
                    colour,
                    ":",
                    f"delta_e_{name}",
                )
            )
    if differ and analysis.model == Model.ENERGY_MASS:
        note = cite(
            f"J_e varies with φ: the speed is extreme where the energy–mass tangents touch ({NOTES}, section 6), "
            "not where ΔE is, at the ends of A_max"
        )
    elif analysis.model == Model.DYNAMIC:
        note = cite(
            f"a torque depends on speed: the torques and the speed extremes along the periodic solution ({NOTES}, "
            "section 7)"
        )
    return marks, note
