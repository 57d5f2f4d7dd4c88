"""The analysis pipeline: scene → cycle → required inertia → result.

Reads like the domain notes (docs/flywheel-design.md): solve an unknown constant torque from the work
balance, build the energy indicator diagram, take A_max, size the flywheel
by J_F = A_max/(ω_m² δ) − J_c, and move it to every shaft by the
ratio-squared transfer.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable
from dataclasses import asdict, dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal, TypedDict

from flyopt.cycle.indicator import energy_indicator, energy_indicator_from_areas, required_inertia, speed_extremes
from flyopt.errors import BrokenInvariant, NonPeriodicCycle, SceneError

if TYPE_CHECKING:  # for the annotations only: importing them would load CasADi
    import numpy as np

    from flyopt.cycle.indicator import EnergyIndicator
    from flyopt.io.scene import Scene
    from flyopt.machine.reduce import Machine
    from flyopt.sizing.choose import Requirement
    from flyopt.sizing.energy_mass import SpeedFluctuation
    from flyopt.sizing.periodic import PeriodicSolution
    from flyopt.sizing.textbook import TextbookRequirement
from flyopt.machine.transmission import inertia_on_shaft
from flyopt.names import Model
from flyopt.said import said_by
from flyopt.units import gd2_from_inertia

#: What an analysis carries beyond the sizing, each computed only when asked for (:func:`complete`): the
#: comparison of the models, the start-up, an engine's textbook flywheel, ω(φ) with the required flywheel.
EXTRAS = ("models", "startup", "textbook", "speed")


class NotComputed(LookupError):
    """A result read from an analysis or a solution that was not asked to compute it.

    Readers (the reports, the diagrams) never compute: what they show is asked
    for when the scene is solved (``flyopt.pipeline.solve(..., extras=...)``).
    """


class ChainPoint(TypedDict):
    """One point of the energy indicator diagram's chain (:attr:`Analysis.energy_chain`)."""

    index: int
    angle: float | None  # [rad]; None for a scene given as net areas (it has no angles)
    delta_e: float  # excess work ΔE there [J]


@dataclass(frozen=True)
class ShaftRequirement:
    """The required flywheel on one shaft."""

    name: str
    speed_ratio: float  # ω_shaft/ω_reference [-]
    omega: float  # mean speed of the shaft [rad/s]
    efficiency: float  # from the motor to this shaft [-]
    j_required: float  # [kg*m^2], 0 when no flywheel is needed
    gd2_required: float  # [N*m^2]

    def to_dict(self) -> dict[str, Any]:
        return dict(self.__dict__)


@dataclass(frozen=True)
class StartupRun:
    """The run-up from rest to the mean speed with the motor on its curve.

    Attributes
    ----------
    method : str
    time : float or None
        Time to reach ``omega_target`` [s]; None when it is not reached (``note`` says why).
    cycles : float or None
        Cycles turned meanwhile [-].
    omega_target : float
        [rad/s]
    note : str
    """

    method: str
    time: float | None
    cycles: float | None
    omega_target: float
    note: str


@dataclass(frozen=True)
class Analysis:
    """Result of the cycle analysis of a scene (all SI; names as in docs/nomenclature.md).

    ``j_required`` is the flywheel inertia at the reference shaft, 0 when the
    machine's own inertia suffices (``flywheel_needed`` False; ``j_margin``
    then tells by how much it suffices, as a negative number).

    ``omega_max``/``omega_min`` are the speed extremes by the model that ran,
    with the flywheel it sizes: the allowed range ω_m(1 ± δ/2) for the energy
    models; for the dynamic model those of its periodic solution, which is
    the machine as it will run (with no flywheel, J_F = 0, when none is
    needed: then its δ, :attr:`delta_reached`, is below the allowed one).

    Two pairs of angles, which differ where the inertia varies or a torque
    depends on speed: ``angle_omega_max``/``angle_omega_min`` are where the
    *speed* is highest and lowest for the model that ran (with the flywheel
    it sizes, none when none is needed); ``angle_delta_e_max``/``angle_delta_e_min`` are where the
    excess work ΔE of the energy indicator diagram is largest and smallest
    (the ends of A_max; ``index_omega_max``/``_min`` index them in
    ``energy_chain``). For the energy model the pairs are the same angles.

    ``indicator``, ``machine`` and ``requirement`` are the computed results
    the report and the plots draw from (they never run a model again); so
    are ``models``, ``startup``, ``textbook`` and ``speed_curve()``, computed
    by :func:`complete` when asked for (:data:`EXTRAS`) and read only:
    reading one that was not asked for raises :class:`NotComputed`.
    """

    title: str
    model: str
    omega_mean: float
    delta: float
    cycle_angle: float
    j_constant: float
    a_max: float
    work_per_cycle: float | None
    driving_torque: float | None
    resisting_torque: float | None
    power: float | None
    efficiency: float
    motor_power: float | None
    omega_max: float
    omega_min: float
    angle_omega_max: float | None
    angle_omega_min: float | None
    angle_delta_e_max: float | None
    angle_delta_e_min: float | None
    model_reason: str
    index_omega_max: int
    index_omega_min: int
    j_margin: float
    j_required: float
    gd2_required: float
    flywheel_needed: bool
    energy_chain: tuple[ChainPoint, ...]
    shafts: tuple[ShaftRequirement, ...]
    indicator: EnergyIndicator | None = None
    machine: Machine | None = None
    requirement: Requirement | None = None
    _extras: MappingProxyType[str, Any] = field(default_factory=lambda: MappingProxyType({}), compare=False, repr=False)
    # flywheel_torque() for the stages that need it (the design, its stress profile), computed once
    _lazy: dict[str, float | None] = field(default_factory=dict, compare=False, repr=False)

    @property
    def delta_holds_at_any_inertia(self) -> bool:
        """Whether δ stays below the allowed value however small the inertia (the dynamic model, a motor
        stiff enough that its slip alone holds the speed): ``j_margin`` is then not a flywheel at which δ
        reaches its limit but the bound −min J_e, where the machine would have no inertia left."""
        return self._dynamic_limit == "none"

    @property
    def stall_limited(self) -> bool:
        """Whether the flywheel is set by a stall, not by δ (the dynamic model): the smallest flywheel with a
        periodic steady state keeps δ below the allowed value (``delta_reached``), so a change of the allowed δ
        that keeps it above that does not move the flywheel (:meth:`stall_sets_flywheel_at`)."""
        return self._dynamic_limit == "stall"

    def stall_sets_flywheel_at(self, delta: float) -> bool:
        """Whether the flywheel this analysis found is also the one an allowed ``delta`` asks for, because a stall
        sets it: δ at the stall limit (``delta_reached``) is within ``delta``, so the search at that δ ends at
        the same limit (the J_F–δ curve and the δ sensitivity do not search again)."""
        return self.stall_limited and delta >= self.delta_reached

    @property
    def _dynamic_limit(self) -> str | None:
        """What limits the dynamic model's flywheel ("delta", "stall", "none"), decided once by the search
        (:class:`flyopt.sizing.periodic.DynamicRequirement`); None for the other models."""
        if self.requirement is None or self.requirement.model != Model.DYNAMIC:
            return None
        return str(self.requirement.detail.limit)

    @property
    def delta_reached(self) -> float:
        """δ of the speed extremes ``omega_max``/``omega_min`` [-]: the allowed δ where the flywheel the model
        sizes reaches it, the machine's own below it where no flywheel is needed and the dynamic model ran
        (its periodic solution with none, J_F = 0), or where a stall limits the flywheel."""
        if self.requirement is not None and self.requirement.model == Model.DYNAMIC:
            return float(self.requirement.detail.solution.delta)
        return self.delta

    @property
    def models(self) -> tuple[dict[str, Any], ...]:
        """Every applicable model's J_F and the δ it really gives (flyopt.sizing.choose.compare).

        Computed only when asked for (:func:`complete`), not by every analysis: a
        sweep point needs only J_F and ω_max, and the comparison solves the
        cheaper models again.
        """
        return self._extra("models")

    @property
    def startup(self) -> StartupRun | None:
        """The run-up from rest with the motor (:class:`StartupRun`), or None without a motor (:func:`complete`)."""
        return self._extra("startup")

    @property
    def textbook(self) -> TextbookRequirement | None:
        """An [engine]'s textbook flywheel (flyopt.sizing.textbook.textbook_requirement), or None for a
        machine that is not an engine or whose inertia is constant (:func:`complete`)."""
        return self._extra("textbook")

    def _repr_html_(self) -> str:
        """The answer card of the cycle in a notebook, the card a solution shows (drawn on the report's floor,
        :func:`flyopt.report.notebook.analysis_card`, through :mod:`flyopt.views`)."""
        from flyopt.views import view

        return str(view("analysis", "html", self))

    def speed_curve(self) -> SpeedFluctuation | PeriodicSolution | None:
        """ω(φ) over the cycle with the required flywheel, by the model that sized it (:func:`complete`).

        The dynamic model's periodic solution; for the energy models the forward
        use of the energy–mass method, ω² = 2 (E_0 + ΔE)/J_e with E_0 such that
        (ω_max + ω_min)/2 = ω_m (docs/flywheel-design.md, section 6;
        flyopt.sizing.energy_mass.achieved_speed). It has ``phi`` [rad],
        ``omega`` [rad/s] and ``delta``.

        Returns
        -------
        SpeedFluctuation or PeriodicSolution or None
            None when nothing turns with inertia and nothing fluctuates
            (A_max = 0, no inertia): the speed stays at ω_m.

        Raises
        ------
        ValueError
            A net-area scene (it has no angles), or no inertia at all while
            the energy fluctuates (ω(φ) is undefined).
        NotComputed
            The analysis was not asked for it.
        """
        speed, error = self._extra("speed")
        if error is not None:
            raise ValueError(error)
        return speed

    def _extra(self, name: str) -> Any:
        try:
            return self._extras[name]
        except KeyError:
            raise NotComputed(
                f"Analysis.{name} was not computed: ask for it when the scene is solved "
                f"(flyopt.pipeline.solve(scene, extras=...) or flyopt.analysis.complete(analysis, ({name!r},)))"
            ) from None

    def flywheel_torque(self, j_flywheel: float | None = None) -> float | None:
        """The largest torque a flywheel exchanges with the reference shaft [N*m], or None.

        ``j_flywheel``: the flywheel at the reference shaft [kg*m^2]; default
        the required one (``j_margin``).

        Its share J_F / J(phi) of the net torque |M_d - M_r| at the worst angle
        (:func:`flyopt.sizing.peak_torque.flywheel_peak_torque`), over the torque curves
        on a grid of 4097 angles and every knot, both sides of a step; speed-
        dependent torques are taken at the mean speed. None for a net-area scene
        (no curves) or when no flywheel is needed. Computed once, by the stages that need it (the design's
        arms and key, the stress profile, a sweep's points); no reader asks for it (tests/test_computed_once.py).
        """
        if j_flywheel is not None:
            return flywheel_torque(self.machine, j_flywheel)
        if "flywheel_torque" not in self._lazy:
            self._lazy["flywheel_torque"] = flywheel_torque(self.machine, self.j_margin)
        return self._lazy["flywheel_torque"]

    def net_torque_peak(self) -> float | None:
        """The largest |M_d - M_r| of the cycle at the reference shaft [N*m] (None for net areas).

        A sweep that scales the torques of a constant-inertia machine scales this and
        takes the flywheel's share of it (:func:`flyopt.sizing.peak_torque.flywheel_peak_torque`)."""
        samples = _net_torque_samples(self.machine)
        return None if samples is None else float(abs(samples[1]).max())

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON-ready dictionary, every number in SI (the comparison and start-up where computed)."""
        out = {
            k: v
            for k, v in self.__dict__.items()
            if k not in ("indicator", "machine", "requirement", "shafts", "energy_chain", "_extras", "_lazy")
        }
        if "startup" in self._extras:
            out["startup"] = None if self.startup is None else asdict(self.startup)
        if "models" in self._extras:
            out["models"] = [dict(m) for m in self.models]
        out["energy_chain"] = [dict(e) for e in self.energy_chain]
        out["shafts"] = [s.to_dict() for s in self.shafts]
        return out


def flywheel_torque(machine: Machine | None, j_flywheel: float) -> float | None:
    """The largest torque a flywheel ``j_flywheel`` [kg*m^2] exchanges with the reference shaft of ``machine`` [N*m].

    None for a net-area scene (``machine`` None) or no flywheel; see :meth:`Analysis.flywheel_torque`.
    """
    from flyopt.sizing.peak_torque import flywheel_peak_torque

    samples = _net_torque_samples(machine)
    if samples is None or j_flywheel <= 0.0:
        return None
    j_machine, differences = samples
    return flywheel_peak_torque(j_flywheel, j_machine + j_flywheel, differences, 1.0)


def _net_torque_samples(machine: Machine | None) -> tuple[np.ndarray, np.ndarray] | None:
    """(J_e, M_d - M_r) at the reference shaft on 4097 angles and every knot, both sides of a step;
    None for a net-area scene (no machine)."""
    import numpy as np

    if machine is None:
        return None
    phi, before, after = machine.net_torque_grid()
    differences = np.concatenate([before, after])
    j_machine = machine.j_machine(phi) if machine.variable_inertia else np.full(phi.shape, float(machine.j_machine))
    return np.concatenate([j_machine, j_machine]), differences


def analyse(
    scene: Scene,
    model: Model | Literal["energy", "energy_mass", "dynamic"] | None = None,
    *,
    like: Analysis | None = None,
    extras: Collection[str] = (),
    slip_first: bool = False,
) -> Analysis:
    """Analyse a scene's cycle and size the flywheel it needs.

    Parameters
    ----------
    scene : Scene
    model : {"energy", "energy_mass", "dynamic"}, optional
        Force a model; by default the cheapest one that is exact for the
        scene (flyopt.sizing.models.choose).
    like : Analysis, optional
        The analysis of the same scene at another delta: its reduced machine
        (and the compiled models cached on it) and its energy indicator,
        none of which depends on delta, are reused instead of reducing the
        scene and integrating its torques again.
    extras : collection of str
        What else to compute (:data:`EXTRAS`, see :func:`complete`); nothing
        beyond the sizing by default.
    slip_first : bool
        The dynamic model: ask first whether the motor's slip alone keeps δ
        (:func:`flyopt.sizing.periodic.dynamic_requirement`): the drive's chosen
        motor where its search found it needs no flywheel.

    Returns
    -------
    Analysis

    Raises
    ------
    NonPeriodicCycle
        The cycle's work does not balance.
    SolverFailed
        The periodic solution did not converge.
    """
    try:
        return complete(_analyse(scene, model, like, slip_first), extras)
    except (SceneError, NonPeriodicCycle) as err:
        raise err.with_source(scene.source) from None


def refuse_negative_work(scene: Scene, work: float, a_max: float) -> None:
    """Refuse a cycle whose driving side takes work out of the machine (docs/flywheel-design.md, section 4).

    flyopt's signs are those of the cycle balance ∫(M_d − M_r) dφ = 0: the driving torque supplies
    the work the resisting torque absorbs. A load that gives work over the cycle (W < 0) drives the
    machine, and the "motor" balancing it would brake it: its power would be negative and divided by
    the efficiency as if it drove. The same machine, with its torques named for what they do, gives
    the same flywheel, so it is refused with the way to say it.

    Raises
    ------
    SceneError
        ``W < 0`` beyond rounding (one part in 10⁹ of A_max).
    """
    if not work < -1e-9 * a_max:
        return
    from flyopt.cycle.torque import Constant

    def unknown(curve: object) -> bool:
        return isinstance(curve, Constant) and curve.unknown

    field = "torque.resisting" if unknown(scene.driving) else "torque.driving" if unknown(scene.resisting) else "torque"
    raise SceneError(
        field,
        f"the work per cycle is negative ({work:.6g} J): the load drives the machine and the driving torque "
        "would brake it; give the torque that supplies the work as [torque.driving] and the braking one as "
        "[torque.resisting], each positive where it does what it is named for (the flywheel is the same)",
    )


def _powers(driving: float, omega_mean: float, efficiency: float) -> tuple[float, float]:
    """(the mean driving power M_d ω_m, the motor's power M_d ω_m / η) [W] (docs/flywheel-design.md, section 11)."""
    power = driving * omega_mean
    return power, power / efficiency


def _analyse(
    scene: Scene, forced: str | None = None, like: Analysis | None = None, slip_first: bool = False
) -> Analysis:
    from flyopt.machine.reduce import reduce
    from flyopt.sizing import choose as models

    delta = scene.allowed_delta  # refuses a calculation's scene, and a cycle without machine.delta, in words
    if forced is not None and forced not in models.MODELS:
        raise SceneError("--model", f"{forced!r} is not known (allowed: {', '.join(models.ORDER)})")
    machine = requirement = None
    if scene.net is not None:
        if forced not in (None, models.ENERGY):
            raise SceneError("--model", "a scene given as net areas has no curves: only the energy model applies")
        ind = energy_indicator_from_areas(scene.net.energies, scene.cycle_angle)
        work = driving = resisting = power = motor_power = None
        if scene.net.work is not None:  # the work per cycle given: the mean torques and the power follow
            work = scene.net.work
            driving = resisting = work / scene.cycle_angle
            power, motor_power = _powers(driving, scene.omega_mean, scene.efficiency)
        chain = tuple(ChainPoint(index=k, angle=None, delta_e=float(e)) for k, e in enumerate(ind.chain_delta_e))
        model, reason = models.ENERGY, "net areas of a constant-inertia machine: the energy method is exact"
        j_margin = required_inertia(ind.a_max, scene.omega_mean, delta, scene.j_constant)
        omega_mean = scene.omega_mean
        omega_max, omega_min = speed_extremes(omega_mean, delta)
        angles = (ind.angle_omega_max, ind.angle_omega_min)
    else:
        if like is not None and like.machine is not None:
            machine = like.machine.with_delta(delta)
            if like.indicator is None:
                raise BrokenInvariant("a machine's analysis has its diagram")
            ind = like.indicator  # the torques at the frozen speed do not depend on δ
        else:
            machine = reduce(scene)
            ew = machine.angle_only()
            ind = energy_indicator(ew.driving, ew.resisting, scene.cycle_angle)
        model, reason = models.choose(machine)
        if forced is not None and forced != model:
            reason = f"forced by --model; the exact model for this scene is {model}: {reason}"
            model = Model(forced)
        requirement = models.requirement(machine, model, ind, slip_first=slip_first)
        j_margin = requirement.j_required
        omega_mean, omega_max, omega_min = requirement.omega_mean, requirement.omega_max, requirement.omega_min
        angles = (requirement.angle_omega_max, requirement.angle_omega_min)
        work, driving, resisting = ind.work_driving, ind.driving_mean, ind.resisting_mean
        refuse_negative_work(scene, work, ind.a_max)
        power, motor_power = _powers(driving, omega_mean, scene.efficiency)
        if ind.chain_angle is None:
            raise BrokenInvariant("a machine's diagram has its angles (only net areas have none)")
        chain = tuple(
            ChainPoint(index=k, angle=float(a), delta_e=float(e))
            for k, (a, e) in enumerate(zip(ind.chain_angle, ind.chain_delta_e))
        )
    needed = j_margin > 0
    j_req = j_margin if needed else 0.0
    shafts = tuple(
        ShaftRequirement(
            name=s.name,
            speed_ratio=s.speed_ratio,
            omega=s.speed_ratio * omega_mean,
            efficiency=s.efficiency,
            j_required=inertia_on_shaft(j_req, s.speed_ratio),
            gd2_required=gd2_from_inertia(inertia_on_shaft(j_req, s.speed_ratio)),
        )
        for s in scene.shafts
    )
    return Analysis(
        title=scene.title,
        model=model,
        model_reason=reason,
        omega_mean=omega_mean,
        delta=delta,
        cycle_angle=scene.cycle_angle,
        j_constant=scene.j_constant,
        a_max=ind.a_max,
        work_per_cycle=work,
        driving_torque=driving,
        resisting_torque=resisting,
        power=power,
        efficiency=scene.efficiency,
        motor_power=motor_power,
        omega_max=omega_max,
        omega_min=omega_min,
        angle_omega_max=angles[0],
        angle_omega_min=angles[1],
        angle_delta_e_max=ind.angle_omega_max,
        angle_delta_e_min=ind.angle_omega_min,
        index_omega_max=ind.index_max,
        index_omega_min=ind.index_min,
        j_margin=j_margin,
        j_required=j_req,
        gd2_required=gd2_from_inertia(j_req),
        flywheel_needed=needed,
        energy_chain=chain,
        shafts=shafts,
        indicator=ind,
        machine=machine,
        requirement=requirement,
    )


def complete(
    analysis: Analysis, extras: Iterable[str] = EXTRAS, *, simulate: Callable[[float], float] | None = None
) -> Analysis:
    """The analysis with ``extras`` computed (:data:`EXTRAS`), those it already has kept.

    Parameters
    ----------
    analysis : Analysis
    extras : iterable of str
        "models" (every applicable model's J_F and the δ it gives,
        flyopt.sizing.choose.compare), "startup" (:func:`startup_run` with the
        required flywheel), "textbook" (an engine's textbook flywheel,
        flyopt.sizing.textbook.textbook_requirement), "speed" (ω(φ) with the
        required flywheel, or why it cannot be drawn).

    simulate : callable, optional
        J_F ↦ the δ the machine reaches with it by the exact model, for the
        comparison of the models (flyopt.sizing.choose.compare): a drive's
        chosen machine by the compiled model its search solved
        (:func:`flyopt.drive.codesign.flywheel_delta`).

    Returns
    -------
    Analysis
        A new, frozen analysis; ``analysis`` itself when nothing is missing.
    """
    missing = [name for name in extras if name not in analysis._extras]
    unknown = [name for name in missing if name not in EXTRAS]
    if unknown:
        raise ValueError(f"unknown extras {unknown} (known: {', '.join(EXTRAS)})")
    if not missing:
        return analysis
    have = dict(analysis._extras)
    for name in EXTRAS:  # in one order, whatever the caller's
        if name in missing:
            have[name] = _models(analysis, simulate) if name == "models" else _COMPUTE[name](analysis)
    return replace(analysis, _extras=MappingProxyType(have))


def _models(analysis: Analysis, simulate: Callable[[float], float] | None = None) -> tuple[dict[str, Any], ...]:
    if analysis.machine is None:  # net areas: the energy method alone, exact
        return (
            {
                "model": analysis.model,
                "exact": True,
                "j_required": analysis.j_margin,
                "achieved_delta": analysis.delta,
                "j_error": 0.0,
                "note": "",
            },
        )
    from flyopt.sizing import choose as models

    return tuple(
        models.compare(
            analysis.machine, analysis.model, analysis.indicator, known=analysis.requirement, simulate=simulate
        )
    )


def _startup(analysis: Analysis) -> StartupRun | None:
    if analysis.machine is None:
        return None
    return startup_run(analysis.machine, analysis.omega_mean, max(analysis.j_margin, 0.0))


def _textbook(analysis: Analysis) -> TextbookRequirement | None:
    machine = analysis.machine
    if machine is None or not machine.variable_inertia:
        return None  # no moving masses: the textbook method and the exact one are one
    from flyopt.machine.engine import engine_of  # CasADi: loaded with the members
    from flyopt.sizing.textbook import textbook_requirement

    if engine_of(machine) is None:
        return None
    return textbook_requirement(machine, analysis.omega_mean, analysis.delta)


def _speed(analysis: Analysis) -> tuple[SpeedFluctuation | PeriodicSolution | None, str | None]:
    """(ω(φ) or None, None), or (None, why it cannot be drawn)."""
    try:
        return _speed_curve(analysis), None
    except ValueError as err:
        return None, str(err)


_COMPUTE: dict[str, Callable[[Analysis], Any]] = {
    "models": _models,
    "startup": _startup,
    "textbook": _textbook,
    "speed": _speed,
}


def startup_run(machine: Machine, omega_target: float, j_flywheel: float) -> StartupRun | None:
    """Run-up from rest to the mean speed, declutched: the motor against the inertia alone (:class:`StartupRun`).

    Induction motors use the Kloss curve here (the linear line is valid only
    near the rated point: at rest it would give 25 times the rated torque).
    Returns None when no motor drives the machine, and when there is nothing to run up: no flywheel (none
    is needed) on a machine the scene gives no inertia (no J_c, no moving members, no rotor), whose run-up
    takes no time (it was reported as "not reached: the total inertia at phi_start must be positive").
    """
    from flyopt.cycle.torque import MotorTorque

    motor = machine.driving if isinstance(machine.driving, MotorTorque) else None
    if motor is None:
        return None
    if j_flywheel <= 0 and not machine.variable_inertia and not float(machine.j_machine) > 0:
        return None
    from flyopt.errors import SolverFailed
    from flyopt.sizing.startup import startup_time  # CasADi, scipy.optimize: only with a motor

    curve = MotorTorque(
        motor.motor, motor.speed_ratio, motor.efficiency, "kloss" if motor.model is not None else None, motor.where
    )
    from flyopt.machine.motor import TableMotor

    line = (
        ", Kloss curve"
        if motor.model is not None
        else ", the motor's torque-speed table"
        if isinstance(motor.motor, TableMotor)
        else ", DC motor line"
    )
    method = "declutched run-up: the motor against the inertia of machine and flywheel alone" + line
    closed = _kloss_runup(machine, curve, omega_target, j_flywheel)
    if closed is not None:
        return StartupRun(method + ", in closed form", closed[0], closed[1], omega_target, "")
    try:
        run = startup_time(
            lambda phi, omega: curve.casadi(phi, omega),
            machine.j_machine,
            machine.cycle_angle,
            omega_target,
            j_flywheel,
        )
    except (SolverFailed, ValueError) as err:
        return StartupRun(method, None, None, omega_target, said_by(err))  # its quantities kept (flyopt.said)
    return StartupRun(method, run.time, run.cycles, omega_target, "")


def _kloss_runup(machine: Machine, curve: Any, omega_target: float, j_flywheel: float) -> tuple[float, float] | None:
    """(time [s], cycles) of the declutched run-up in closed form, or None where it does not apply.

    Exact for a constant inertia on an induction motor's Kloss curve
    (:func:`flyopt.sizing.startup.kloss_runup_time`, ``kloss_runup_angle``):
    the speed then rises monotonically, so the target is first reached at the
    end. Anything else (an inertia varying with the angle, another motor, a
    target at or above the synchronous speed, a run-up longer than the
    integration allows) is integrated by :func:`flyopt.sizing.startup.startup_time`.
    """
    from flyopt.machine.motor import InductionMotor
    from flyopt.sizing.startup import MAX_CYCLES, kloss_runup_angle, kloss_runup_time

    motor = curve.motor
    if machine.variable_inertia or curve.model != "kloss" or not isinstance(motor, InductionMotor):
        return None
    inertia = float(machine.j_machine) + j_flywheel
    ratio, efficiency = curve.speed_ratio, curve.efficiency
    if not (inertia > 0 and 0 < ratio * omega_target < motor.synchronous_speed):
        return None
    args = (inertia, ratio, efficiency, motor.breakdown_torque, motor.breakdown_slip, motor.synchronous_speed)
    cycles = kloss_runup_angle(*args, omega_target) / machine.cycle_angle
    if not cycles <= MAX_CYCLES:
        return None
    return float(kloss_runup_time(*args, omega_target)), cycles


def _speed_curve(analysis: Analysis) -> SpeedFluctuation | PeriodicSolution | None:
    """See :meth:`Analysis.speed_curve`."""
    machine = analysis.machine
    if machine is None:
        raise ValueError("a net-area scene has no angles: ω(φ) cannot be drawn")
    if analysis.requirement is None:
        raise BrokenInvariant("a machine's analysis has its requirement")
    if analysis.requirement.model == Model.DYNAMIC:
        solution: PeriodicSolution = analysis.requirement.detail.solution
        if solution.j_flywheel == analysis.j_required or not analysis.j_margin < 0:
            return solution
        # no flywheel needed and δ reached at a J_F < 0 (limit "delta"): the requirement's solution is the one at
        # that margin; the machine runs with none. (Where δ is reached at none, limit "none", the requirement's
        # solution is already the machine with none, or, with no inertia of its own, the limit it tends to.)
        from flyopt.sizing.periodic import periodic_solution

        return periodic_solution(
            machine.net_torque(),
            machine.j_machine,
            machine.cycle_angle,
            analysis.omega_mean,
            analysis.j_required,
            machine.knots(),
        )
    if machine.j_mean() + analysis.j_required <= 0:
        if analysis.a_max <= 0:
            return None
        raise ValueError("the scene has no inertia at all (J_c = 0 and no flywheel needed): ω(φ) is undefined")
    from flyopt.sizing.energy_mass import achieved_speed

    return achieved_speed(machine.angle_only(), machine.j_machine, analysis.omega_mean, analysis.j_required)
