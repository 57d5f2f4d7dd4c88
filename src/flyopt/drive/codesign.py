"""The drive designed with the flywheel: the motor, its ratio and the wheel chosen together.

A press or shear is driven by an induction motor through a belt and gears;
the flywheel sits on one of the shafts between them. A bigger wheel lets a
smaller motor suffice (its torque then stays near the mean load, so its RMS
torque, which heats it, stays near the mean), and where the wheel sits (its
speed ratio r to the crank) decides how big it must be
(docs/flywheel-design.md, sections 7, 8 and 14).

For one motor of the catalogue the chain is exact, on flyopt's one path:

1. the motor's ratio i_m = ω_motor/ω_crank is the one that runs the crank at
   the scene's mean speed ω_m = (ω_max + ω_min)/2 (a closed form from the
   work balance on the motor's linear characteristic, then corrected on the
   periodic solution until the mean speed is the scene's to 1e-9);
2. the machine with that motor on its characteristic (rotor inertia J_rot i_m²
   added to J_c) is analysed by the periodic model: the least flywheel J_F at
   the crank that keeps δ (:func:`flyopt.sizing.periodic.dynamic_requirement`);
3. thermal: the motor's RMS torque over the cycle, sqrt(∫ M² dt / T), must not
   exceed its rated torque; it falls as J_F grows (toward the mean torque), so
   J_F is raised, by a bracketed root, until it holds (a motor whose mean
   torque exceeds its rating is refused at once);
4. the run-up from rest on the Kloss curve with that flywheel must end within
   ``max_startup`` (it only grows with J_F, so the least flywheel is checked);
5. the wheel for J_F at the crank is designed on a shaft of speed ratio r by
   :func:`flyopt.design.designer.design_flywheel`, r over the drive's range (a
   bounded scalar minimization; of equal masses the slowest shaft) or each of
   its fixed ratios. Where the scene describes that shaft as a part
   (``[[shaft]] name = "flywheel"``, :func:`flywheel_shaft`), the wheel the
   search chooses must pass the design's own shaft post-check at its ratio
   (:func:`_best_wheel`; docs/flywheel-design.md, sections 14 and 26).

Every motor size is so evaluated and the sizes ranked by the objective (total
mass of motor and wheel, or their cost); :func:`design_drive` returns the best
with every size tried. :func:`verify_drive` simulates the chosen machine again
with the wheel as built (its inertia, not the required one).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from flyopt.analysis import StartupRun, flywheel_torque, startup_run
from flyopt.errors import SceneError, SolverFailed
from flyopt.machine.reduce import Machine, reduce
from flyopt.names import Criterion, Geometry, Objective
from flyopt.said import join, said, said_by

if TYPE_CHECKING:
    from typing import Unpack  # Python 3.11; the annotations are never evaluated

    from flyopt.analysis import Analysis
    from flyopt.design.materials import Material
    from flyopt.design.result import Design, DesignResult
    from flyopt.design.spec import DesignSpec
    from flyopt.drive.relaxation import Relaxation
    from flyopt.drive.steady import DriveModel
    from flyopt.io.drive import DriveSpec
    from flyopt.io.scene import Scene
    from flyopt.machine.catalogue import CatalogueMotor
    from flyopt.machine.motor import InductionMotor
    from flyopt.machine.transmission import Shaft
    from flyopt.sizing.periodic import PeriodicSolution, Verification
#: Name of the shaft the drive puts the flywheel on, and of the motor's.
FLYWHEEL_SHAFT, MOTOR_SHAFT = "flywheel", "motor"

#: Mean crank speed held by the motor ratio, relative [-].
SPEED_RTOL = 1e-7

#: The flywheel and the motor ratio settled together, relative change of the flywheel [-].
SETTLE_RTOL = 1e-6

#: The thermal limit's flywheel, relative tolerance of the root [-].
THERMAL_RTOL = 1e-8

#: The motor's characteristic in the steady state: the Kloss curve, valid from rest to synchronous speed
#: (the linear line holds near the rated point only, and a press's slowdown of several per cent takes
#: a standard motor of 2-4 % rated slip far from it).
MOTOR_MODEL = "kloss"

if TYPE_CHECKING:
    from flyopt.design.result import Design
    from flyopt.drive.relaxation import Relaxation
    from flyopt.sizing.periodic import Verification


@dataclass(frozen=True)
class MotorRun:
    """One motor size of the catalogue, with the least flywheel it needs and that wheel designed.

    Attributes
    ----------
    motor : catalogue entry
    feasible : bool
    reason : str
        Why not (empty when feasible).
    refusal : str
        The kind of that reason: one of :data:`REFUSAL_KINDS` (the reason begins with it and a colon),
        :data:`NOT_SETTLED` or :data:`NO_WHEEL_KIND`; empty when feasible. Not in ``--json``: the reason is.
    motor_ratio : float or None
        i_m = ω_motor / ω_crank [-].
    j_flywheel : float or None
        Least flywheel inertia at the crank [kg*m^2] that keeps δ and the thermal limit.
    limit : str or None
        Which limit sets it: "delta", "thermal" or "none" (the machine needs no flywheel).
    j_delta : float or None
        The least flywheel for δ alone [kg*m^2].
    rms_torque, mean_torque, rated_torque : float or None
        Of the motor shaft over the cycle with ``j_flywheel`` [N*m].
    omega_mean, delta : float or None
        Mean crank speed [rad/s] and δ achieved with ``j_flywheel``.
    startup_time : float or None
        Run-up from rest [s] with ``j_flywheel``.
    flywheel_ratio : float or None
        r = ω_flywheel_shaft / ω_crank [-] of the wheel chosen.
    wheel : Design or None
    design : DesignResult or None
        The wheel's design on its shaft (every material ranked), for the report.
    shaft_checks : tuple of flyopt.design.shaft.cycle.ShaftReport
        The described flywheel shaft checked with the wheel at its ratio, as the search checked it (() when
        the scene does not describe the shaft).
    motor_mass, wheel_mass, total_mass : float or None
        [kg]
    cost : float or None
        Motor price plus wheel cost [currency], when both are known.
    objective : float or None
        The ranked value (``total_mass`` or ``cost``).
    """

    motor: CatalogueMotor
    feasible: bool
    reason: str = ""
    refusal: str = ""
    motor_ratio: float | None = None
    j_flywheel: float | None = None
    limit: str | None = None
    j_delta: float | None = None
    rms_torque: float | None = None
    mean_torque: float | None = None
    rated_torque: float | None = None
    omega_mean: float | None = None
    delta: float | None = None
    startup_time: float | None = None
    flywheel_ratio: float | None = None
    wheel: Design | None = None
    motor_mass: float | None = None
    wheel_mass: float | None = None
    total_mass: float | None = None
    cost: float | None = None
    objective: float | None = None
    design: DesignResult | None = field(default=None, compare=False, repr=False)
    shaft_checks: tuple[Any, ...] = field(default=(), compare=False, repr=False)

    def __post_init__(self) -> None:
        if not _consistent(self.feasible, self.refusal, self.reason):
            raise ValueError(
                f"MotorRun: a size is refused with a kind of reason and a reason of that kind, and feasible without "
                f"either (feasible {self.feasible}, refusal {self.refusal!r}, reason {self.reason[:60]!r})"
            )

    def to_dict(self) -> dict[str, Any]:
        out = {
            ("j_required" if k == "j_flywheel" else k): v  # the least inertia at the crank: named as everywhere
            for k, v in self.__dict__.items()
            if k not in ("motor", "wheel", "design", "shaft_checks", "refusal")
        }
        out["motor"] = _motor_dict(self.motor)
        out["wheel"] = None if self.wheel is None else self.wheel.to_dict()
        return out


@dataclass(frozen=True)
class DriveDesign:
    """The drive and flywheel designed together.

    Attributes
    ----------
    status : {"designed", "infeasible"}
    objective : {"mass", "cost"}
    best : MotorRun or None
    runs : tuple of MotorRun
        Every motor size solved, in order of rating.
    message : str
    relaxation : flyopt.drive.relaxation.Relaxation or None
        The continuous optimum that located the sizes solved (None: every size solved).
    note : str
        How the sizes were chosen.
    model : flyopt.drive.steady.DriveModel or None
        The compiled model the search solved (None: the CVODES search alone), for
        :func:`flywheel_delta`.
    """

    status: str
    objective: str
    best: MotorRun | None
    runs: tuple[MotorRun, ...]
    message: str = ""
    relaxation: Relaxation | None = None
    note: str = ""
    model: DriveModel | None = field(default=None, compare=False, repr=False)

    def to_dict(self) -> dict[str, Any]:
        relaxed = None if self.relaxation is None else self.relaxation.to_dict()
        return {
            "status": self.status,
            "objective": self.objective,
            "message": self.message,
            "note": self.note,
            "relaxation": relaxed,
            "best": None if self.best is None else self.best.to_dict(),
            "runs": [r.to_dict() for r in self.runs],
        }


def _motor_dict(motor):
    fields = (
        "name",
        "rated_power",
        "rated_speed",
        "synchronous_speed",
        "rotor_inertia",
        "breakdown_ratio",
        "mass",
        "price",
    )
    return {f: getattr(motor, f, None) for f in fields}


# -- one motor -------------------------------------------------------------------


def motor_ratio_estimate(
    motor: CatalogueMotor, load_torque: float, omega_crank: float, efficiency: float
) -> float | None:
    """The motor ratio that runs the crank at ``omega_crank`` on average, from the work balance [-].

    Over a cycle the motor's work equals the load's: with the linear
    characteristic M = M_n (ω_0 − ω)/(ω_0 − ω_n) on the motor shaft and
    ω_motor = i ω, the angle mean of i η M(i ω) equals the mean load M̄ at
    the crank when the angle-mean crank speed is ω:

        η M_n ω i² − η M_n ω_0 i + M̄ (ω_0 − ω_n) = 0,

    whose larger root is the stable, low-slip one. It is a first estimate:
    the scene's mean speed is (ω_max + ω_min)/2, not the angle mean, and
    :func:`evaluate_motor` corrects it on the periodic solution.

    Returns
    -------
    float or None
        None when no ratio gives the mean torque on the stable branch (the
        motor is too small: its torque at the crank cannot reach M̄).
    """
    m_n, w0, wn = motor.rated_torque, motor.synchronous_speed, motor.rated_speed
    a, b, c = efficiency * m_n * omega_crank, -efficiency * m_n * w0, load_torque * (w0 - wn)
    disc = b * b - 4 * a * c
    if disc < 0:
        return None
    return (-b + math.sqrt(disc)) / (2 * a)


def rms_torque(
    solution: PeriodicSolution, motor: InductionMotor, ratio: float, model: str = MOTOR_MODEL
) -> tuple[float, float]:
    """(RMS, mean) of the motor shaft's torque over the cycle, in time [N*m].

    T_rms² = ∫ M(i ω)² dt / T with dt = dφ/ω, by the trapezoidal rule on the
    periodic solution's grid (2048+ points a cycle, every knot; the error is
    O(h²) of the torque's curvature, below 1e-6 relative on the scenes tested).
    """
    from flyopt.drive.steady import rms_of

    omega = np.asarray(solution.omega, float)
    return rms_of(np.asarray(solution.phi, float), omega, np.asarray(motor.torque(ratio * omega, model), float))


def motor_scene(scene: Scene, motor: CatalogueMotor, ratio: float) -> Scene:
    """The scene driven by ``motor`` at speed ratio ``ratio``: its Kloss curve, its rotor's inertia at the crank."""
    from flyopt.cycle.torque import MotorTorque
    from flyopt.machine.transmission import inertia_at_reference

    drive = MotorTorque(motor.motor(), ratio, scene.efficiency, MOTOR_MODEL, "drive.motors")
    return dataclasses.replace(
        scene, driving=drive, j_constant=scene.j_constant + inertia_at_reference(motor.rotor_inertia, ratio)
    )


def chosen_scene(scene: Scene, run: MotorRun) -> Scene:
    """The scene as built: the run's motor at its ratio, and the flywheel's shaft and the motor's among its shafts."""
    from flyopt.machine.transmission import Shaft

    ratio = cast(float, run.motor_ratio)  # a feasible run has its ratio
    built = motor_scene(scene, run.motor, ratio)
    shafts = tuple(s for s in scene.shafts if s.name not in (FLYWHEEL_SHAFT, MOTOR_SHAFT))
    shafts += (Shaft(MOTOR_SHAFT, ratio),)
    if run.flywheel_ratio is not None:
        described = flywheel_shaft(scene)  # the scene's flywheel shaft as a part, at the ratio chosen
        shafts += (
            Shaft(FLYWHEEL_SHAFT, run.flywheel_ratio)
            if described is None
            else dataclasses.replace(described, speed_ratio=run.flywheel_ratio),
        )
    # the wheel is the drive's, on its flywheel shaft: a design of the scene as built puts it there too
    design_shafts = None if run.flywheel_ratio is None else (FLYWHEEL_SHAFT,)
    return dataclasses.replace(built, shafts=shafts, design_shafts=design_shafts)


def flywheel_shaft(scene: Scene) -> Shaft | None:
    """The scene's [[shaft]] named :data:`FLYWHEEL_SHAFT` described as a part (docs/flywheel-design.md,
    section 26), the shaft the drive puts its wheel on; None when the scene does not describe it."""
    return next((s for s in scene.shafts if s.name == FLYWHEEL_SHAFT and s.layout is not None), None)


def _seat(scene: Scene) -> float | None:
    """The seat diameter of the drive's flywheel shaft [m] (the wheel's bore), when the scene describes it."""
    described = flywheel_shaft(scene)
    return None if described is None else described.diameter


def _shaft_context(scene: Scene, machine: Machine, omega_mean: float) -> Any:
    """The shaft checks' context (:func:`flyopt.design.shaft.cycle.machine_context`) of the described flywheel
    shaft on ``machine`` (the motor's, its rotor in J_e) at the crank's mean speed ``omega_mean`` [rad/s] and
    the scene's δ; None when the scene does not describe the shaft. :func:`flyopt.design.shaft.cycle.at_ratio`
    turns it at each ratio the drive designs."""
    if flywheel_shaft(scene) is None:
        return None
    from flyopt.design.shaft.cycle import machine_context

    return machine_context(machine, omega_mean, scene.allowed_delta, scene.shafts, scene.material_library())


def evaluate_motor(
    scene: Scene,
    motor: CatalogueMotor,
    load_torque: float,
    spec: DriveSpec,
    ratios: tuple[str, Unpack[tuple[float, ...]]],
    materials: Sequence[Material],
    design_spec: DesignSpec,
    *,
    solver_options: Mapping[str, Any] | None = None,
    drive_model: DriveModel | None = None,
    start: dict[str, Any] | None = None,
) -> MotorRun:
    """One motor size: its ratio, the least flywheel it needs, the checks, and the wheel (:class:`MotorRun`).

    Parameters
    ----------
    scene : Scene
        The machine with its load (the driving torque is replaced by the motor).
    motor : catalogue entry
    load_torque : float
        Mean load torque at the crank M̄ [N*m] (the analysis's balancing driving torque).
    spec : DriveSpec
    ratios : tuple
        ("range", lo, hi) or ("fixed", r1, r2, ...) of the flywheel shaft.
    materials, design_spec
        As for :func:`flyopt.design.designer.design_flywheel`.
    drive_model : flyopt.drive.steady.DriveModel, optional
        The scene's compiled drive model (:func:`drive_model`): the ratio and
        the flywheel by one Newton solve on it, the CVODES search only should
        it not settle. Default: the CVODES search.
    start : dict, optional
        Carries the last size's solution to the next (a warm start); updated.
    """

    omega = scene.omega_mean
    rated = motor.rated_torque

    def run(kind, words, **facts):  # kind "" for the size that drives the machine
        reason = kind + ": " + words if kind in REFUSAL_KINDS else words
        return MotorRun(motor=motor, feasible=not kind, reason=reason, refusal=kind, rated_torque=rated, **facts)

    ratio = motor_ratio_estimate(motor, load_torque, omega, scene.efficiency)
    if ratio is None:
        return run(
            "too small",
            said(
                "its torque on the crank cannot reach the mean load {load} at {omega} on the stable branch",
                load=_torque(load_torque),
                omega=_speed(omega),
            ),
        )
    if spec.thermal and load_torque / (ratio * scene.efficiency) > rated * (1 + 1e-12):
        return run(
            "thermal",
            said(
                "its mean torque {mean} exceeds its rated torque {rated} whatever the flywheel",
                mean=_torque(load_torque / (ratio * scene.efficiency)),
                rated=_torque(rated),
            ),
            motor_ratio=ratio,
        )
    found = None
    if drive_model is not None:
        from flyopt.drive.steady import Unreachable
        from flyopt.sizing.shooting import NotSettled

        try:
            found = _settle_compiled(drive_model, motor, ratio, spec.thermal, {} if start is None else start)
        except Unreachable as err:
            return run(err.limit, said_by(err), motor_ratio=ratio)
        except NotSettled:
            found = None  # the CVODES search below handles every case
        except _Unsettled as err:
            return run(err.kind, said_by(err), motor_ratio=err.ratio, j_delta=err.j_delta)
    if found is not None:
        steady, j_delta = found
        ratio, j_need = steady.ratio, steady.j_flywheel
        machine = reduce(motor_scene(scene, motor, ratio))
        rms, mean = steady.rms_torque, steady.mean_torque
        omega_min, omega_mean, omega_max, delta = steady.omega_min, steady.omega_mean, steady.omega_max, steady.delta
    else:
        try:
            ratio, machine, solution, j_delta = _settle(scene, motor, ratio, spec.thermal)
        except _Unsettled as err:
            return run(err.kind, said_by(err), motor_ratio=err.ratio, j_delta=err.j_delta)
        except (SolverFailed, SceneError) as err:
            return run("no steady running", said_by(err), motor_ratio=ratio)
        j_need = solution.j_flywheel
        rms, mean = rms_torque(solution, motor.motor(), ratio)
        omega_min, omega_mean = float(np.min(solution.omega)), solution.omega_mean
        omega_max, delta = solution.omega_max, solution.delta
    limit = "thermal" if j_need > j_delta * (1 + 1e-8) else ("delta" if j_delta > 0 else "none")
    omega_min_motor = omega_min * ratio
    if omega_min_motor < motor.motor().breakdown_speed:
        return run(
            "breakdown",
            said(
                "the motor slows to {slowest} in the cycle, past its breakdown speed {breakdown}",
                slowest=_speed(omega_min_motor),
                breakdown=_speed(motor.motor().breakdown_speed),
            ),
            motor_ratio=ratio,
            j_delta=j_delta,
        )
    startup = _runup(machine, omega_mean, j_need)
    facts = dict(
        motor_ratio=ratio,
        j_flywheel=j_need,
        limit=limit,
        j_delta=j_delta,
        rms_torque=rms,
        mean_torque=mean,
        omega_mean=omega_mean,
        delta=delta,
        startup_time=startup.time,
    )
    if spec.max_startup is not None:
        if startup.time is None:
            return run("start-up", startup.note, **facts)
        if startup.time > spec.max_startup:
            return run(
                "start-up",
                said(
                    "{time} from rest, over max_startup {allowed}",
                    time=_time(startup.time),
                    allowed=_time(spec.max_startup),
                ),
                **facts,
            )
    torque = flywheel_torque(machine, j_need) if j_need > 0 else None
    shaft_ctx = _shaft_context(scene, machine, omega_mean)
    accept = keyed = None
    if shaft_ctx is not None:  # the design's post-check of the described flywheel shaft, turning at r
        from flyopt.design.shaft.cycle import acceptor, at_ratio, keyed_shafts

        names = {m.name: m.display_name for m in materials}

        def accept(r):
            return acceptor(at_ratio(shaft_ctx, FLYWHEEL_SHAFT, r), names)

        def keyed(shaft):  # the torque its train's forced response puts on the key at r: the post-check's
            on = at_ratio(shaft_ctx, FLYWHEEL_SHAFT, shaft.speed_ratio)
            return keyed_shafts(on, [shaft], j_need * design_spec.rim_share)[0]

    result, r = _best_wheel(
        j_need,
        omega_max,
        ratios,
        materials,
        design_spec,
        torque,
        spec.objective,
        solver_options,
        seat=_seat(scene),
        accept_at=accept,
        keyed=keyed,
    )
    wheel = None if result is None else result.best
    if j_need > 0 and wheel is None:
        refused = "" if result is None else _shaft_refusal(result)
        if refused:
            return run("shaft", refused, **facts, flywheel_ratio=r)
        return run(NO_WHEEL_KIND, NO_WHEEL, **facts)
    shaft_checks: tuple[Any, ...] = ()
    if shaft_ctx is not None and wheel is not None and r is not None:  # the report of the shaft the search checked
        from flyopt.design.shaft.cycle import at_ratio, report

        checked = report(at_ratio(shaft_ctx, FLYWHEEL_SHAFT, r), wheel)
        shaft_checks = () if checked is None else (checked,)
    wheel_mass = wheel.mass if wheel is not None else 0.0
    total = motor.mass + wheel_mass if motor.mass is not None else None
    cost = None
    wheel_cost = 0.0 if wheel is None else wheel.cost
    price = getattr(motor, "price", None)
    if price is not None and wheel_cost is not None:
        cost = price + wheel_cost
    objective = total if spec.objective == Objective.MASS else cost
    return run(
        "",
        "",
        **facts,
        flywheel_ratio=r,
        wheel=wheel,
        design=result,
        motor_mass=motor.mass,
        wheel_mass=wheel_mass,
        total_mass=total,
        cost=cost,
        objective=objective,
        shaft_checks=shaft_checks,
    )


def _runup(machine: Machine, omega: float, j_flywheel: float) -> StartupRun:
    """The declutched run-up of a drive's machine (:func:`flyopt.analysis.startup_run`), whose motor drives it."""
    startup = startup_run(machine, omega, j_flywheel)
    if startup is None:
        raise SolverFailed("the drive's machine has no motor driving it to run up")
    return startup


class _Unsettled(SolverFailed):
    """A motor for which no ratio and flywheel keep the limits (the message says which; ``kind`` is the
    refusal's, :attr:`MotorRun.refusal`)."""

    def __init__(self, message, ratio, j_delta=None, kind=None):
        super().__init__(message)
        self.ratio, self.j_delta = ratio, j_delta
        self.kind = NOT_SETTLED if kind is None else kind


def _steady(scene, motor, ratio, j_flywheel):
    """(machine, periodic solution) of the scene driven by ``motor`` at ``ratio`` with a flywheel at the crank."""
    from flyopt.sizing.periodic import periodic_solution

    machine = reduce(motor_scene(scene, motor, ratio))
    return machine, periodic_solution(
        machine.net_torque(), machine.j_machine, machine.cycle_angle, scene.omega_mean, j_flywheel, machine.knots()
    )


def _hold_speed(scene, motor, ratio, j_flywheel, memo=None):
    """(ratio, machine, solution) whose mean speed (ω_max + ω_min)/2 is the scene's to :data:`SPEED_RTOL`.

    A secant on ln i for ln(ω_mean/ω): the crank's mean speed is nearly ω_motor/i
    (a slope of −1 starts it, or the last call's slope kept in ``memo``), the
    motor's slip moving it a little.
    """
    omega = scene.omega_mean
    memo = {} if memo is None else memo
    x0 = math.log(ratio)
    machine, sol = _steady(scene, motor, ratio, j_flywheel)
    f0 = math.log(sol.omega_mean / omega)
    slope = memo.get("slope", -1.0)
    x1 = x0 - f0 / slope
    for _ in range(30):
        if abs(f0) <= SPEED_RTOL:
            return math.exp(x0), machine, sol
        machine, sol = _steady(scene, motor, math.exp(x1), j_flywheel)
        f1 = math.log(sol.omega_mean / omega)
        if x1 != x0 and (f1 - f0) / (x1 - x0) < 0:
            slope = memo["slope"] = (f1 - f0) / (x1 - x0)
        x0, f0, x1 = x1, f1, x1 - f1 / slope
    raise _Unsettled(f"the motor ratio did not settle the mean speed (last error {f0:.3g})", math.exp(x0))


def _settle(scene, motor, ratio, thermal):
    """(ratio, machine, solution with the least flywheel, J for δ alone): δ, the thermal limit and the mean speed together.

    At a ratio that holds the mean speed, the least flywheel for δ
    (:func:`flyopt.sizing.periodic.dynamic_requirement`, only when the
    machine alone misses δ) and for the thermal limit (a root of the RMS
    torque) is found, and the binding one kept; the flywheel moves the mean
    speed a little, so the ratio is held again with it and the binding limit's
    flywheel refined from where it was (a secant), until the flywheel settles.
    """

    delta, rated = scene.delta, motor.rated_torque
    memo: dict[str, float] = {}
    try:
        ratio, machine, sol = _hold_speed(scene, motor, ratio, 0.0, memo)
        j_delta = _delta_flywheel(scene, machine) if sol.delta > delta else 0.0
    except SolverFailed:  # without a flywheel the machine stalls: δ needs one (dynamic_requirement finds it)
        machine = reduce(motor_scene(scene, motor, ratio))
        j_delta = _delta_flywheel(scene, machine)
        if not j_delta > 0:
            raise
        sol = None
    j, limit = j_delta, ("delta" if j_delta > 0 else "none")
    held = None if sol is None else 0.0  # the flywheel the ratio was last held with
    if thermal:
        if j > 0:
            ratio, machine, sol = _hold_speed(scene, motor, ratio, j, memo)
            held = j
        if rms_torque(sol, motor.motor(), ratio)[0] > rated:
            j = _thermal_flywheel(machine, motor, ratio, scene.omega_mean, j, rated)
            if j is None:
                raise _Unsettled(
                    said("its RMS torque stays above its rated torque {rated} for any flywheel", rated=_torque(rated)),
                    ratio,
                    j_delta,
                    "thermal",
                )
            limit = "thermal"
    seq = [j]
    for _ in range(20):
        if limit == "none":
            return ratio, machine, sol, 0.0
        if held != j:
            ratio, machine, sol = _hold_speed(scene, motor, ratio, j, memo)
            held = j
        if limit == "delta":
            j_new = _delta_flywheel(scene, machine)
        else:
            j_new = _thermal_flywheel(machine, motor, ratio, scene.omega_mean, j_delta, rated, guess=j)
        seq.append(j_new)
        if len(seq) == 3 and abs(j_new - j) > SETTLE_RTOL * j_new:
            # the flywheel converges linearly (each step shrinks the change 10- to 50-fold): Aitken's
            # extrapolation of the last three, then three more
            d1, d2 = seq[1] - seq[0], seq[2] - seq[1]
            if d2 != d1:
                j_new = seq[2] - d2 * d2 / (d2 - d1)
            seq = [j_new]
        if abs(j_new - j) <= SETTLE_RTOL * j_new:
            if j_new != j:
                ratio, machine, sol = _hold_speed(scene, motor, ratio, j_new, memo)
                held = j_new
            if limit == "thermal":
                j_delta = _delta_flywheel(scene, machine) if sol.delta > delta or j_delta > 0 else 0.0
                if sol.delta > delta * (1 + 1e-9):  # δ binds after all at this ratio: size for it
                    limit, j = "delta", j_delta
                    continue
            else:
                j_delta = j_new
            return ratio, machine, sol, j_delta
        j = j_new
    raise _Unsettled("the flywheel and the motor ratio did not settle together", ratio, j_delta)


def drive_model(scene: Scene, analysis: Analysis, motor: CatalogueMotor) -> DriveModel:
    """The scene's load with a motor whose ratio and Kloss curve are parameters, compiled once for every size.

    The load is the analysed machine's (its resisting torque, members' loads
    included, and its inertia, the rotor's not in it); ``motor`` gives the
    parameters' first values.
    """
    from flyopt.cycle.torque import Constant
    from flyopt.drive.steady import DriveModel, MotorLoad, motor_parameters
    from flyopt.machine.reduce import NetTorque
    from flyopt.sizing.periodic_model import periodic_model

    machine = analysis.machine
    if machine is None:
        raise SceneError("drive", "the drive needs the machine's torque curves (not net areas)")
    load = NetTorque(Constant(0.0), machine.resisting, machine.net_torque().work)
    net = MotorLoad(load, scene.efficiency, motor_parameters(motor, 1.0))
    model = periodic_model(net, machine.j_machine, machine.cycle_angle, machine.knots())
    return DriveModel(model, scene.omega_mean, scene.allowed_delta, scene.efficiency)


def _settle_compiled(model, motor, ratio, thermal, start):
    """(Steady with the least flywheel, J for δ alone) of one motor by Newton on the compiled drive model.

    The same rule as :func:`_settle`: without a flywheel when δ and the thermal
    limit hold; else the least flywheel for δ; raised to the thermal limit's
    when the RMS torque still exceeds the rating (then J for δ alone is the
    one at that ratio). ``start`` carries the last size's solution.
    """
    from flyopt.sizing.shooting import NotSettled

    delta, rated = model.delta, motor.rated_torque
    v0 = start.get("v", math.log(model.omega_m))
    x = (v0, start.get("u", math.nan), math.log(ratio))
    try:
        free = model.steady(motor, "none", x)
    except SolverFailed:
        free = None  # without a flywheel the machine stalls or cannot be settled: δ needs one
    if free is not None:
        x = (free.x[0], x[1], free.x[2])
        if free.delta <= delta and not (thermal and free.rms_torque > rated):
            start.update(v=free.x[0])
            return free, 0.0
    if free is not None and free.delta <= delta:  # δ holds without a flywheel: the thermal limit binds
        current, j_delta = free, 0.0
    else:
        current = model.steady(motor, "delta", x)
        j_delta = current.j_flywheel
        x = current.x
        if not j_delta > 0:  # δ holds without a flywheel, yet the run without one did not settle
            raise NotSettled("the run without a flywheel did not settle, though δ needs none")
    if thermal and current.rms_torque > rated:
        current = model.steady(motor, "thermal", x)
        if j_delta > 0:
            j_delta = model.steady(motor, "delta", current.x, ratio=current.ratio).j_flywheel
        if current.delta > delta * (1 + 1e-9):  # δ binds after all at this ratio
            current = model.steady(motor, "delta", current.x)
            j_delta = current.j_flywheel
    start.update(v=current.x[0], u=current.x[1])
    return current, j_delta


def _delta_flywheel(scene, machine):
    """The least flywheel at the crank that keeps δ with the machine's motor (0 when none is needed)."""
    from flyopt.sizing.periodic import dynamic_requirement

    need = dynamic_requirement(
        machine.net_torque(), machine.j_machine, machine.cycle_angle, scene.omega_mean, scene.delta, machine.knots()
    )
    return max(need.j_required, 0.0)


def _thermal_flywheel(machine, motor, ratio, omega, j_low, rated, guess=None):
    """The least J_F (>= j_low) whose periodic solution keeps the motor's RMS torque at its rating [kg*m^2].

    From a ``guess`` (the last ratio's), a secant; otherwise (or should the
    secant leave the bracket) a bracket doubled from the machine's mean
    inertia, then Brent's root. None when no flywheel brings the RMS torque
    to the rating (it tends to the mean torque as J_F grows).
    """
    from flyopt.cycle.numerics import brentq
    from flyopt.sizing.periodic import periodic_solution

    net, knots = machine.net_torque(), machine.knots()

    def excess(j):
        sol = periodic_solution(net, machine.j_machine, machine.cycle_angle, omega, j, knots)
        return rms_torque(sol, motor.motor(), ratio)[0] / rated - 1.0

    if guess is not None and guess > j_low:
        x0, x1 = guess, guess * (1 + 1e-4)
        f0, f1 = excess(x0), excess(x1)
        for _ in range(20):
            if f1 == f0:
                break
            x0, f0, x1 = x1, f1, x1 - f1 * (x1 - x0) / (f1 - f0)
            if not x1 > j_low:
                break
            f1 = excess(x1)
            if abs(x1 - x0) <= THERMAL_RTOL * x1:
                return x1 * (1 + THERMAL_RTOL) if f1 > 0 else x1
    if excess(j_low) <= 0:
        return j_low
    high = max(j_low, machine.j_mean(), 1e-9)
    for _ in range(60):
        high *= 2.0
        if excess(high) <= 0:
            break
    else:
        return None
    xtol = 1e-14 * high
    j = brentq(excess, j_low, high, rtol=THERMAL_RTOL, xtol=xtol)
    # Brent stops within 2 (xtol + rtol |j|) of the root: that far above it the limit holds
    return j + 2.0 * (xtol + THERMAL_RTOL * j)


def _best_wheel(
    j_need, omega_max, ratios, materials, spec, torque, objective, solver_options, seat=None, accept_at=None, keyed=None
):
    """(best DesignResult, its shaft ratio) over the drive's flywheel ratios; (None, None) when no flywheel is needed.

    The wheel's share of the drive's objective (its mass, or its cost) is what is minimized over r. ``seat``:
    the described flywheel shaft's seat diameter [m] (the wheel's bore), None when not described.
    ``accept_at``: r -> the design's post-check of the described flywheel shaft at r (:func:`_shaft_accept`).
    ``keyed``: the flywheel shaft at r -> that shaft with the torque its train puts on the wheel's key
    (:func:`flyopt.design.shaft.cycle.keyed_shafts`), the torque the design and the post-check share.

    The shaft is checked only where a wheel could win: the search runs without the post-check, and the
    wheel it chooses is designed again at its ratio with it; where that wheel holds, it is the best of the
    checked search too (the post-check only removes designs), else the search runs again, every design
    checked. Where no ratio's wheel holds, the result is the unchecked winner's ratio designed with the
    post-check: its candidates give every failed limit in numbers (:func:`_shaft_refusal`).
    """
    unchecked = _designer(j_need, omega_max, materials, spec, torque, solver_options, seat, keyed=keyed)
    result, r = _wheel_search(
        j_need, omega_max, ratios, materials, spec, torque, objective, solver_options, seat, unchecked
    )
    if accept_at is None or result is None or result.best is None:
        return result, r
    design = _designer(j_need, omega_max, materials, spec, torque, solver_options, seat, accept_at, keyed)
    checked = design(r)
    best = checked.best
    if best is not None and _same_wheel(best, result.best):
        return checked, r
    found, r_found = _wheel_search(
        j_need, omega_max, ratios, materials, spec, torque, objective, solver_options, seat, design
    )
    if found is None or found.best is None:
        return checked, r  # no ratio's wheel holds: the unchecked winner's reasons say why
    return found, r_found


def _same_wheel(a, b) -> bool:
    """Two designs are the same wheel: one combination, one mass."""
    return (a.material, a.n_arms) == (b.material, b.n_arms) and math.isclose(
        cast(float, a.mass), cast(float, b.mass), rel_tol=1e-12
    )


def _shaft_refusal(result: DesignResult) -> str:
    """Why no wheel is designed where the described flywheel shaft refused them: the candidates' reasons
    (the post-check's, :func:`flyopt.design.shaft.cycle.reject_reason`, in numbers); "" when none is the shaft's."""
    from flyopt.design.shaft.cycle import REFUSED

    reasons = [c.reason for c in result.candidates if not c.feasible and REFUSED in c.reason]
    if not reasons:
        return ""
    return f"at ratio {result.candidates[0].speed_ratio:.4g}: " + join("; ", reasons)


def _designer(j_need, omega_max, materials, spec, torque, solver_options, seat, accept_at=None, keyed=None):
    """r -> the wheel's DesignResult on the flywheel shaft at r (memoized: the scan, the minimization and the
    tie-break revisit ratios), with the shaft's post-check at r where ``accept_at`` gives one, and the torque of
    its train on the key where ``keyed`` gives one (:func:`_best_wheel`)."""
    from flyopt.design.designer import design_flywheel
    from flyopt.design.spec import MountShaft

    designs = {}

    def design(r):
        r = float(r)
        if r not in designs:
            designs[r] = design_flywheel(
                j_need,
                omega_max,
                [MountShaft(FLYWHEEL_SHAFT, r, seat) if keyed is None else keyed(MountShaft(FLYWHEEL_SHAFT, r, seat))],
                materials,
                spec,
                solver_options=solver_options,
                torque=torque,
                accept=None if accept_at is None else accept_at(r),
            )
        return designs[r]

    return design


def _wheel_search(j_need, omega_max, ratios, materials, spec, torque, objective, solver_options, seat, design=None):
    """(best DesignResult, its ratio) over the drive's flywheel ratios by ``design`` (r -> DesignResult; default
    the designer without a post-check); (None, None) when no flywheel is needed or none fits."""
    if j_need <= 0:
        return None, None
    if design is None:
        design = _designer(j_need, omega_max, materials, spec, torque, solver_options, seat)

    def mass(r):
        best = design(r).best
        if best is None:
            return math.inf
        value = best.mass if objective == Objective.MASS else best.cost
        return math.inf if value is None else value

    kind, *values = ratios
    if kind == "fixed":
        found = [(mass(r), r) for r in values]
        m, r = min(found, key=lambda pair: (pair[0], pair[1]))
        return (None, None) if math.isinf(m) else (design(r), r)
    lo, hi = values
    from flyopt.cycle.minimize import bounded_minimum

    grid = np.geomspace(lo, hi, 9)
    grid[0], grid[-1] = lo, hi
    masses = [mass(r) for r in grid]
    k = int(np.argmin(masses))
    if math.isinf(masses[k]):
        return None, None
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    # any point it tried is a designed wheel: unconverged, its best is still a candidate against the grid's
    minimum = bounded_minimum(mass, a, b, xatol=1e-10 * b)
    r, m = min([(masses[k], grid[k]), (minimum.fun, minimum.x)], key=lambda pair: pair[0])[::-1]
    r = _slowest_equal(mass, lo, r, m)
    return design(r), r


def _slowest_equal(mass, lo, r, m, rtol=1e-9):
    """The smallest ratio in [lo, r] whose wheel is as light as ``m`` (to ``rtol``): of equal wheels, the slowest shaft.

    Above the ratio where the rim speed binds, a rim's least mass no longer
    depends on r (m = J_F ω² / v_max² · const): the optimum is a flat valley.
    """
    if mass(lo) <= m * (1 + rtol):
        return lo
    if mass(max(lo, r * (1 - 1e-6))) > m * (1 + rtol):
        return r  # no valley: the mass still falls toward r
    a, b = lo, r
    for _ in range(100):
        mid = 0.5 * (a + b)
        if mass(mid) <= m * (1 + rtol):
            b = mid
        else:
            a = mid
        if b - a <= 1e-10 * b:
            break
    return b


# -- the drive -------------------------------------------------------------------


def design_drive(
    scene: Scene,
    analysis: Analysis | None = None,
    *,
    solver_options: Mapping[str, Any] | None = None,
    every_size: bool = False,
) -> DriveDesign:
    """Design the motor, its ratio and the flywheel of a scene with a [drive] together.

    Parameters
    ----------
    scene : Scene
        With ``scene.drive`` and a driving torque that is an unknown constant
        (the motor replaces it).
    analysis : Analysis, optional
        The scene's own analysis (the mean load); default: analysed here.
    every_size : bool
        Solve every size of the catalogue (a front of wheel mass against
        motor power needs them all), not only those around the relaxation.

    Returns
    -------
    DriveDesign
    """
    from flyopt.analysis import analyse
    from flyopt.design import design_inputs

    spec = scene.drive
    if spec is None:
        raise ValueError("the scene has no [drive]")
    if analysis is None:
        analysis = analyse(scene)
    load = analysis.driving_torque
    if load is None or not load > 0:
        raise SceneError("drive", f"the drive needs a load to drive: the scene's mean driving torque is {load!r} N*m")
    inputs = design_inputs(scene)
    ratios = spec.ratio_choice()
    motors = spec.motors.motors  # a Catalogue keeps its sizes in increasing rated power
    done = {}
    compiled = drive_model(scene, analysis, motors[0])
    start: dict[str, Any] = {}  # each size starts from the last one's solution

    def evaluate(k):
        if k not in done:
            done[k] = evaluate_motor(
                scene,
                motors[k],
                load,
                spec,
                ratios,
                inputs.materials,
                inputs.spec,
                solver_options=solver_options,
                drive_model=compiled,
                start=start,
            )
        return done[k]

    relaxation, note = (
        (None, "every catalogue size solved")
        if every_size
        else _relaxation(scene, analysis, spec, motors, inputs, load)
    )
    if relaxation is None:
        for k in range(len(motors)):
            evaluate(k)
    else:
        skipped = _neighbours(
            spec.motors, relaxation.rated_power, evaluate, done, lambda k: _least_objective(motors[k], spec)
        )
        for k in skipped:  # the note says what the table of sizes no longer shows (words only: the text, the
            # report and the JSON each show the note as it is, whatever their units)
            alone = "weighs" if spec.objective == Objective.MASS else "costs"
            note += f"; {motor_name(motors[k])} left unsolved: its motor alone {alone} no less than the best drive"
    runs = tuple(done[k] for k in sorted(done))
    ranked = sorted(
        (r for r in runs if r.feasible and r.objective is not None), key=lambda r: (r.objective, r.motor.rated_power)
    )
    if not ranked:
        return DriveDesign(
            "infeasible",
            spec.objective,
            None,
            runs,
            f"{NO_MOTOR}: " + _refusals(runs, REFUSALS_SHOWN),
            relaxation=relaxation,
            note=note,
        )
    return DriveDesign("designed", spec.objective, ranked[0], runs, relaxation=relaxation, note=note, model=compiled)


def flywheel_delta(drive: DriveDesign, machine: Machine) -> Callable[[float], float] | None:
    """J_F ↦ the δ the chosen drive reaches with that flywheel at the crank (None without a chosen drive).

    By the compiled model the search solved (:meth:`flyopt.drive.steady.DriveModel.with_flywheel`,
    RK4 with its steps checked to 1e-9), not a CVODES periodic solution built again for the
    chosen machine (the analysis' comparison of the models asks it for the energy model's
    flywheel); where it does not settle, by CVODES on ``machine``, the chosen machine reduced
    (:func:`flyopt.sizing.choose.achieved_delta`).
    """
    best, model = drive.best, drive.model
    if best is None or model is None:
        return None
    motor, ratio = best.motor, cast(float, best.motor_ratio)  # a chosen run has its ratio

    def delta(j_flywheel: float) -> float:
        try:
            return model.with_flywheel(motor, ratio, j_flywheel).delta
        except SolverFailed:  # NotSettled: the fixed steps cannot settle it
            from flyopt.sizing.choose import achieved_delta

            return achieved_delta(machine, j_flywheel)

    return delta


def _relaxation(scene, analysis, spec, motors, inputs, load):
    """(Relaxation or None, note): the continuous relaxation, best over the design's materials (and arm counts)."""
    from flyopt.design.spec import MountShaft
    from flyopt.design.wheel_design import bore_of, missing_poisson
    from flyopt.drive.relaxation import CatalogueFit, RelaxedWheel, relax

    fit = CatalogueFit.of(motors)
    if (
        fit is None
        or (spec.objective == Objective.MASS and fit.mass is None)
        or (spec.objective == Objective.COST and fit.price is None)
    ):
        return None, "every catalogue size solved (too few sizes, or one lacks a value, for a continuous relaxation)"
    design = inputs.spec
    bore = bore_of(design, MountShaft(FLYWHEEL_SHAFT, 1.0, _seat(scene)))
    best, failures = None, []
    for material in inputs.materials:
        if spec.objective == Objective.COST and material.cost is None:
            continue
        if missing_poisson(material, design):
            continue  # the designer refuses it too
        for n_arms in design.arms if design.geometry == Geometry.RIM_ARMS else (0,):
            wheel = RelaxedWheel.of(material, design, bore, n_arms)
            if design.criterion == Criterion.RIM_SPEED and not math.isfinite(wheel.v_max):
                continue
            if design.criterion == Criterion.STRESS and not wheel.problem.allowable:
                continue  # no allowable stress (no safety factor on its strength): nothing to limit
            try:
                found = relax(analysis.machine, scene.omega_mean, scene.delta, scene.efficiency, fit, spec, wheel, load)
            except SolverFailed as err:
                failures.append(f"{wheel.label}: {err}")
                continue
            if best is None or found.objective < best.objective:
                best = found
    if best is None:
        return None, (
            "every catalogue size solved: the relaxation found no optimum"
            + (f" ({'; '.join(failures)})" if failures else "")
        )
    return best, "the catalogue sizes around the relaxed optimum solved exactly"


def _least_objective(motor, spec):
    """A lower bound of a motor size's objective before it is solved: its own mass, or price (the wheel adds
    to it, never takes away); None where the catalogue gives none."""
    return getattr(motor, "mass" if spec.objective == Objective.MASS else "price", None)


def _neighbours(catalogue, power, evaluate, done, least=lambda k: None):
    """Solve the sizes either side of the relaxed rating, then walk on while the best is at an end.

    Below the relaxed rating the motor is smaller than the continuous optimum
    wants, above it larger; the discrete optimum is one of the two unless the
    fitted laws mislead, so the search moves on past an end of the solved
    block as long as the best (or, when none is feasible yet, any) lies there.
    A size the walk reaches is not solved when it cannot win: ``least(k)``, a
    lower bound of its objective (its motor's own mass or price), is above the
    best's objective (or equal, of a larger rating: ties go to the smaller motor),
    and the walk stops there as it would have after solving it.

    Returns
    -------
    list of int
        The sizes so left unsolved.
    """
    motors = catalogue.motors  # in increasing rated power
    below, above = catalogue.neighbours(power)
    for motor in (below, above):
        if motor is not None:
            evaluate(motors.index(motor))
    skipped: list[int] = []
    while True:
        lo, hi = min(done), max(done)
        feasible = [k for k in done if done[k].feasible and done[k].objective is not None]
        if feasible:
            best = min(feasible, key=lambda k: (done[k].objective, motors[k].rated_power))
            key = (done[best].objective, motors[best].rated_power)
            ends = [
                k
                for k in ((lo - 1) if best == lo else None, (hi + 1) if best == hi else None)
                if k is not None and 0 <= k < len(motors)
            ]
            bounds = {k: least(k) for k in ends}
            moves = [k for k in ends if bounds[k] is None or (bounds[k], motors[k].rated_power) <= key]
            skipped += [k for k in ends if k not in moves and k not in skipped]
        else:
            moves = [k for k in (lo - 1, hi + 1) if 0 <= k < len(motors)]
        if not moves:
            return skipped
        for k in moves:
            evaluate(k)


def motor_power_front(drive: DriveDesign) -> tuple[MotorRun, ...]:
    """The runs no other run beats in both motor power and wheel mass (a Pareto front), by rising power."""
    feasible = sorted((r for r in drive.runs if r.feasible), key=lambda r: (r.motor.rated_power, r.wheel_mass))
    front, lightest = [], math.inf
    for run in feasible:
        mass = cast(float, run.wheel_mass)  # a feasible run has its wheel's mass (0 with no wheel)
        if mass < lightest:
            front.append(run)
            lightest = mass
    return tuple(front)


def motor_name(motor: CatalogueMotor) -> str:
    """A catalogue size as the drive's words name it: its name, or its rated power ("5.5 kW")."""
    return getattr(motor, "name", None) or f"{motor.rated_power / 1000:g} kW"


def refused_in_short(drive: DriveDesign) -> str:
    """An infeasible drive's verdict in one sentence, for the answer and the summary: for each kind of reason
    (:attr:`MotorRun.refusal`) how many sizes it refused, the first and the last of them in the
    catalogue's order ("no motor size of the catalogue drives the machine within the limits (thermal: 5 sizes,
    80B-4 0.75 kW … 100LB-4 3 kW; start-up: 13 sizes, 112M-4 4 kW … 280M-4 90 kW); each size's reason is in the
    drive's table of sizes", :func:`flyopt.report.drive.run_verdict`). The drive's message as it is where it did not refuse sizes."""
    refused = [run for run in drive.runs if not run.feasible]
    if drive.best is not None or not refused or not drive.message.startswith(NO_MOTOR):
        return drive.message
    kinds: dict[str, list[str]] = {}
    for run in refused:
        kinds.setdefault(run.refusal, []).append(motor_name(run.motor))
    parts = []
    for kind, names in kinds.items():
        sizes = f"{len(names)} size" if len(names) == 1 else f"{len(names)} sizes"
        named = names[:1] if len(names) == 1 else [names[0], names[-1]]  # a catalogue's names are its own
        parts.append(f"{kind}: {sizes}, " + (" and " if len(names) == 2 else " … ").join(named))
    return f"{NO_MOTOR} ({'; '.join(parts)}); each size's reason is in the drive's table of sizes"


# A motor's reasons keep their quantities (flyopt.said): written in SI at four figures, as the JSON has always
# carried them, and shown in the reader's units by the text and the report.


def _torque(value: float) -> tuple[float, str, str]:
    return (value, "torque", f"{value:.4g} N·m")


def _speed(value: float) -> tuple[float, str, str]:
    return (value, "angular_speed", f"{value:.4g} rad/s")


def _time(value: float) -> tuple[float, str, str]:
    return (value, "time", f"{value:.4g} s")


def _ratio(value: float) -> tuple[float, str, str]:
    return (value, "dimensionless", f"{value:.4g}")


#: What an infeasible drive's message begins with (its refused sizes' reasons follow).
NO_MOTOR = "no motor size of the catalogue drives the machine within the limits"

#: The reason of a size for whose flywheel no wheel is designed (no shaft refused it).
NO_WHEEL = "no wheel fits the design limits for the flywheel it needs"

#: The kinds of reason a size is refused for whose reason begins with the kind and a colon ("thermal: its mean
#: torque ..."): :func:`evaluate_motor` writes the two together (:attr:`MotorRun.refusal`).
REFUSAL_KINDS = ("too small", "thermal", "breakdown", "start-up", "shaft", "no steady running")
#: The kind of :data:`NO_WHEEL`'s refusal.
NO_WHEEL_KIND = "no wheel"
#: The kind of a size whose ratio and flywheel did not settle together (its reason says how).
NOT_SETTLED = "not settled"


def _consistent(feasible: bool, kind: str, reason: str) -> bool:
    """Whether a run's feasibility, kind of refusal and reason agree (:attr:`MotorRun.refusal`): a feasible run
    has neither; a refused one a known kind and a reason, which begins with "kind: " for a kind of
    :data:`REFUSAL_KINDS` and with no such prefix otherwise (:data:`NO_WHEEL` for :data:`NO_WHEEL_KIND`)."""
    if feasible:
        return not kind and not reason
    if kind in REFUSAL_KINDS:
        return reason.startswith(f"{kind}: ") and len(reason) > len(kind) + 2
    if kind == NO_WHEEL_KIND:
        return reason == NO_WHEEL
    return kind == NOT_SETTLED and bool(reason) and not any(reason.startswith(f"{k}: ") for k in REFUSAL_KINDS)


#: The most characters of refused sizes' reasons an infeasible drive's message lists (whole reasons: the table
#: of sizes gives every one).
REFUSALS_SHOWN = 2000


def _refusals(runs: Sequence[MotorRun], size: int) -> str:
    """Each refused size's name and reason, "; "-joined, as many whole reasons as ``size`` characters hold (at
    least one), then how many more there are; their quantities kept (:func:`flyopt.said.join`)."""
    parts = [f"{motor_name(r.motor)}: " + r.reason for r in runs if not r.feasible]
    kept = parts[:1]
    length = sum(map(len, kept))
    for part in parts[1:]:
        length += 2 + len(part)
        if length > size:
            break
        kept.append(part)
    more = len(parts) - len(kept)
    return join("; ", kept) + (f"; and {more} more (the table of sizes gives each)" if more else "")


# -- verification ----------------------------------------------------------------


@dataclass(frozen=True)
class DriveCheck:
    """The chosen drive simulated again with the wheel as built (its inertia, not the required one).

    Attributes
    ----------
    verification : flyopt.sizing.periodic.Verification
        δ achieved by the periodic simulation (CVODES shooting) of machine, motor and wheel.
    rms_torque, rated_torque : float
        The motor's RMS torque over the cycle and its rating [N*m].
    startup_time : float or None
        Run-up from rest [s] (None: not reached; ``notes`` say why).
    flagged : bool
        Any limit exceeded beyond the simulation's tolerance.
    notes : tuple of str
        Each limit exceeded, in words.
    """

    verification: Verification
    rms_torque: float
    rated_torque: float
    startup_time: float | None
    flagged: bool
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {
            **self.verification.to_dict(),
            "rms_torque": self.rms_torque,
            "rated_torque": self.rated_torque,
            "startup_time": self.startup_time,
            "flagged": self.flagged,
            "notes": list(self.notes),
        }


def verify_drive(scene: Scene, run: MotorRun, j_flywheel: float | None = None) -> DriveCheck:
    """Simulate the scene with the run's motor and flywheel and check δ, the thermal limit and the start-up.

    Parameters
    ----------
    scene : Scene
        The scene with its [drive] (the load; the driving torque is the motor's).
    run : MotorRun
    j_flywheel : float, optional
        The flywheel at the crank [kg*m^2]; default the wheel as designed
        (its inertia on its shaft times r²), else the run's requirement.

    Returns
    -------
    DriveCheck
    """
    from flyopt.sizing import periodic

    spec = scene.drive
    if spec is None:
        raise ValueError("the scene has no [drive]: a motor run is checked against its drive's limits")
    if j_flywheel is None:
        built_j = run.wheel.j_at_reference if run.wheel is not None else None
        j_flywheel = built_j if built_j is not None else (run.j_flywheel or 0.0)
    ratio = cast(float, run.motor_ratio)  # a feasible run has its ratio
    built = motor_scene(scene, run.motor, ratio)
    machine = reduce(built)
    checked = periodic.verify(
        machine.net_torque(),
        machine.j_machine,
        machine.cycle_angle,
        scene.omega_mean,
        scene.allowed_delta,
        j_flywheel,
        machine.knots(),
    )
    if checked.solution is None:
        raise SolverFailed(f"the chosen drive's simulation ({checked.method}) kept no speed curve to check")
    rms, _ = rms_torque(checked.solution, run.motor.motor(), ratio)
    startup = _runup(machine, checked.omega_mean, j_flywheel)
    notes = []
    if checked.flagged:
        notes.append(
            said(
                "delta {achieved} exceeds the allowed {allowed}",
                achieved=_ratio(checked.achieved_delta),
                allowed=_ratio(checked.delta_allowed),
            )
        )
    rated = run.motor.rated_torque
    if spec.thermal and rms > rated * (1 + 1e-6):
        notes.append(
            said("RMS torque {rms} exceeds the rated {rated} (thermal)", rms=_torque(rms), rated=_torque(rated))
        )
    if spec.max_startup is not None and (startup.time is None or startup.time > spec.max_startup):
        taken = (
            said("{time}", time=_time(startup.time)) if startup.time is not None and not startup.note else startup.note
        )
        notes.append("start-up " + taken + said(" over max_startup {allowed}", allowed=_time(spec.max_startup)))
    return DriveCheck(
        verification=checked,
        rms_torque=rms,
        rated_torque=rated,
        startup_time=startup.time,
        flagged=bool(notes),
        notes=tuple(notes),
    )
