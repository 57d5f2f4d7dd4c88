"""The thin place where flyopt's pieces meet.

load scene → analyse the cycle → design the flywheel → report. Each step
lives in its own module; this one only joins them (the pvlib ModelChain /
PyBaMM Simulation pattern).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal

from flyopt.analysis import EXTRAS as ANALYSIS_EXTRAS
from flyopt.analysis import Analysis, NotComputed, analyse, complete
from flyopt.cycle.indicator import speed_extremes
from flyopt.errors import BrokenInvariant
from flyopt.views import view

if TYPE_CHECKING:  # the annotations only: importing Verification loads CasADi
    import numpy as np

    from flyopt.design.materials import Material
    from flyopt.design.result import DesignResult
    from flyopt.design.spec import StressFactor
    from flyopt.drive.codesign import DriveCheck, DriveDesign
    from flyopt.io.scene import Scene
    from flyopt.machine.crank_forces import CrankForces
    from flyopt.machine.electric_drive import ReducedDrive
    from flyopt.machine.equivalents import PositionEquivalents
    from flyopt.machine.transmission import PowerFlow
    from flyopt.sizing.existing import FlywheelCheck
    from flyopt.sizing.operation import OperationResult
    from flyopt.sizing.periodic import PeriodicSolution, Verification


#: What ``flyopt solve`` shows beyond the sizing and the design (its text and its JSON): computed by default.
SHOWN = ("models", "startup", "textbook")
#: What the solution itself can carry beyond the analysis' :data:`flyopt.analysis.EXTRAS`: J_F at other δ
#: (``inertia_curve``), the analysis by the energy–mass model (``energy_mass``), the chosen wheel's stresses
#: over its radius (``stress``), the simulation with the required flywheel (``speed_simulation``).
SOLUTION_EXTRAS = ("inertia_curve", "energy_mass", "stress", "speed_simulation")
#: Every extra: what the engineering report and every diagram of a scene show, computed in one solve.
COMPLETE = (*ANALYSIS_EXTRAS, *SOLUTION_EXTRAS)


@dataclass(frozen=True)
class Solution:
    """A scene analysed and (unless asked not to) its flywheel designed.

    Everything a report or a diagram shows is computed here, by :func:`solve`,
    when asked for (its ``extras``), and only read afterwards: the analysis'
    extras (:data:`flyopt.analysis.EXTRAS`) and those of :data:`SOLUTION_EXTRAS`,
    read through the properties of the same names; one that was not asked for
    raises :class:`flyopt.analysis.NotComputed`.

    Attributes
    ----------
    scene : Scene
    analysis : Analysis
    design : DesignResult or None
        None when the design step was skipped.
    verification : Verification or None
    drive : DriveDesign or None
        The motor, ratios and wheel designed together (a scene with a [drive]);
        ``scene`` and ``analysis`` are then those of the machine as built (the
        chosen motor at its ratio) and ``design`` its wheel's.
    drive_check : DriveCheck or None
        The chosen drive simulated with the wheel as built.
    flywheel : FlywheelCheck or None
        What the scene's [flywheel] that exists does: the δ it leaves, the
        speeds, the accelerations (:func:`check_flywheel`); ``analysis`` is
        then the machine's own, at machine.delta or, without one, at that δ.
    inertia_curve : (ndarray, ndarray) or None
        δ and J_F there by the analysis' own model
        (:func:`flyopt.delta_curve.inertia_curve`); None for the energy
        method (its closed form is drawn), a steady machine, or when it could
        not be found (``inertia_error``).
    energy_mass : Analysis or None
        The analysis by the energy–mass model where it applies (an inertia
        that varies, torques of the angle only).
    stress : tuple or None
        ``(profile, beams, omega, material)`` of :func:`stress_profile` for the
        chosen wheel, or None (no wheel; ``stress_note`` says why when it failed).
    speed_simulation : PeriodicSolution or None
        The periodic simulation with the required flywheel (:func:`verify`
        without a design), for a scene with curves.
    shaft_checks : tuple of ShaftReport
        The chosen wheel's shaft, where the scene describes it as a part: strength, fatigue,
        slope, lateral and torsional critical speeds (:func:`shaft_reports`); () otherwise.
    """

    scene: Scene
    analysis: Analysis
    design: DesignResult | None = None
    verification: Verification | None = None
    drive: DriveDesign | None = None  # of a scene with a [drive]
    drive_check: DriveCheck | None = None  # of the chosen drive
    flywheel: FlywheelCheck | None = None  # of a scene's [flywheel] that exists (no design then)
    shaft_checks: tuple[Any, ...] = ()  # the chosen wheel's described shaft (flyopt.design.shaft.cycle.ShaftReport)
    _extras: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}), compare=False, repr=False)

    def _repr_html_(self) -> str:
        """The answer card in a notebook, the app's card (drawn on the report's floor,
        :func:`flyopt.report.notebook.answer_card`, through :mod:`flyopt.views`)."""
        return str(view("solution", "html", self))

    def _extra(self, name: str) -> Any:
        try:
            return self._extras[name]
        except KeyError:
            raise NotComputed(
                f"Solution.{name} was not computed: ask for it when the scene is solved "
                f"(flyopt.pipeline.solve(scene, extras=({name!r},)))"
            ) from None

    @property
    def inertia_curve(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(δ, J_F at each δ [kg*m^2]) by the scene's own model, or None where there is no curve to draw."""
        return self._extra("inertia_curve")[0]

    @property
    def inertia_error(self) -> Exception | None:
        """The exception that kept J_F from being found at every δ, or None."""
        return self._extra("inertia_curve")[1]

    @property
    def energy_mass(self) -> Analysis | None:
        """The analysis by the energy–mass model where its diagram applies (J_e varies, torques of the angle only)."""
        return self._extra("energy_mass")

    @property
    def stress(self) -> tuple[Any, Any, float, Material] | None:
        """The chosen wheel's :func:`stress_profile`, or None (no wheel, or see :attr:`stress_note`)."""
        return self._extra("stress")[0]

    @property
    def stress_note(self) -> str:
        """Why there is no stress profile of a chosen wheel ("" when there is one, or no wheel)."""
        return self._extra("stress")[1]

    @property
    def speed_simulation(self) -> PeriodicSolution | None:
        """The periodic simulation of the machine with its flywheel (None for net areas)."""
        return self._extra("speed_simulation")

    @property
    def drive_failed(self) -> bool:
        """Whether the scene's [drive] found no motor size that drives the machine within its limits: its analysis
        is then the scene without the drive (its torques as its other tables give them), a machine no motor was
        chosen for, and no diagram draws it."""
        return self.drive is not None and self.drive.best is None

    @property
    def status(self) -> str:
        """ "designed", "not_needed", "infeasible", "analysed" (design skipped), or for a [flywheel] that
        exists "checked" (it holds machine.delta, or none was given) or "insufficient"."""
        if self.drive_failed:
            return "infeasible"
        if self.drive is not None and self.design is None:
            return "not_needed"  # the chosen motor holds δ without a flywheel
        if self.flywheel is not None:
            return "insufficient" if self.flywheel.suffices is False else "checked"
        return self.design.status if self.design is not None else "analysed"

    def to_dict(self, timings: bool = False) -> dict[str, Any]:
        """The JSON of ``flyopt solve``: the analysis fields plus a "design" object.

        Wall-clock times (``solve_time`` of each design) only with ``timings``:
        without them the same scene always gives the same JSON.
        """
        out = self.analysis.to_dict()
        if self.design is not None:
            out["design"] = design_dict(self.design, timings)
        if self.verification is not None:
            out["verification"] = self.verification.to_dict()
        if self.flywheel is not None:
            out["flywheel"] = self.flywheel.to_dict()
        if self.shaft_checks:
            out["shaft_checks"] = [r.to_dict() for r in self.shaft_checks]
        if self.drive is not None:
            out["drive"] = self.drive.to_dict()
            if self.drive_check is not None:
                out["drive"]["verification"] = self.drive_check.to_dict()
        return out


def design_dict(result: DesignResult, timings: bool = False) -> dict[str, Any]:
    """The "design" object: the winner's fields, its ranking, status and model."""
    raw = result.to_dict(timings)
    design = raw["design"] or {"candidates": []}
    return {"status": raw["status"], "message": raw["message"], **design, "model": raw["model"]}


def design_scene(
    scene: Scene,
    analysis: Analysis,
    solver_options: Mapping[str, Any] | None = None,
    method: Literal["auto", "ipopt", "closed_form"] = "auto",
    *,
    continuous: bool = False,
) -> DesignResult:
    """Design the flywheel a scene needs, from its analysis.

    Parameters
    ----------
    scene : Scene
        Supplies the design options, materials and shafts.
    analysis : Analysis
        Supplies J_F at the reference shaft (``j_margin``: zero or negative
        means no flywheel is needed).
    solver_options : mapping, optional
        CasADi/IPOPT options that override flyopt's defaults, for the
        combinations IPOPT solves (see ``method``).
    method : {"auto", "ipopt", "closed_form"}
        The exact closed form where it covers the structure and IPOPT
        elsewhere (default), IPOPT on every combination, or the closed form
        only (see flyopt.design.designer.design_flywheel).
    continuous : bool
        The continuous design a study compares (the material trade-off): not rounded to flyopt's default
        grid (:func:`flyopt.design.inputs.one_design`; a scene's own ``round_to`` still applies), without the δ sensitivity and the finite-element
        report of the winner; every limit, the peak torque on the arms and the key, and a described shaft's
        post-check and key torque as ``flyopt solve`` designs with (one path). A scene's own ``fem_check =
        true`` still re-designs against the FE.

    Returns
    -------
    DesignResult

    Raises
    ------
    SolverFailed
        IPOPT did not converge on a combination that can be feasible, or a
        design failed its verification against the constraints.
    """
    from flyopt.design import design_inputs
    from flyopt.design.inputs import builds_whole, one_design
    from flyopt.design.wheel_design import needs_torque

    inputs = _seated(_keyed(scene, analysis, design_inputs(scene)), scene)
    if not continuous:
        inputs = one_design(inputs)
    # the rim is checked at the highest speed of the cycle, from the model that ran (for a motor
    # scene the mean speed itself follows from the torque balance, not from the scene's nominal speed)
    # the peak torque loads the arms and the key: asked for only where the design has them
    torque = analysis.flywheel_torque() if needs_torque(inputs) else None
    names = {m.name: m.display_name for m in inputs.materials}
    accept = _shaft_acceptor(scene, analysis, names)
    design_flywheel = _seat_designer(scene, analysis, inputs.shafts, names)  # or the designed seat's search

    def design(shafts: Sequence[Any]) -> DesignResult:
        return design_flywheel(
            analysis.j_margin,
            analysis.omega_max,
            shafts,
            inputs.materials,
            inputs.spec,
            solver_options=solver_options,
            method=method,
            torque=torque,
            omega_mean=analysis.omega_mean,
            accept=accept,
        )

    result = design(inputs.shafts)
    again = _rekeyed(scene, analysis, result, inputs.shafts)
    if again is not None:  # a wheel refused for its key at its own inertia's torque: its shaft's hub designed at it
        inputs = replace(inputs, shafts=again)
        result = design(again)
    if result.spec.fem_check:
        from flyopt.design.fem import accept as accept_fem  # numpy, and scikit-fem when it runs

        def redesign(factors: tuple[StressFactor, ...]) -> DesignResult:
            return design_flywheel(
                analysis.j_margin,
                analysis.omega_max,
                inputs.shafts,
                inputs.materials,
                replace(inputs.spec, stress_factors=factors),
                solver_options=solver_options,
                method=method,
                torque=torque,
                omega_mean=analysis.omega_mean,
                accept=accept,
            )

        result = accept_fem(result, inputs.materials, redesign)
    elif continuous:
        return result
    elif result.spec.fem_check is None and builds_whole(inputs):
        from flyopt.design.fem import check_result  # numpy and scikit-fem

        result = check_result(result, inputs.materials)
    return result if continuous else _with_delta_sensitivity(scene, analysis, result, solver_options, method)


def _shaft_acceptor(scene: Scene, analysis: Analysis, names: Mapping[str, str]) -> Any:
    """The designer's post-check of the scene's described shafts (:mod:`flyopt.design.shaft.cycle`), or None;
    its reasons name the materials by ``names`` (key -> name for people)."""
    context = shaft_context_of(scene, analysis)
    if context is None:
        return None
    from flyopt.design.shaft.cycle import acceptor

    return acceptor(context, names)


def _keyed(scene: Scene, analysis: Analysis, inputs: Any) -> Any:
    """The design inputs with each described shaft carrying the torque its train's forced response puts on the
    wheel's key (:func:`flyopt.design.shaft.cycle.keyed_shafts`): the torque the post-check checks the key at,
    so the design sizes the hub and key at it (docs/flywheel-design.md, section 26)."""
    context = shaft_context_of(scene, analysis)
    if context is None:
        return inputs
    from flyopt.design.shaft.cycle import keyed_shafts

    shafts = keyed_shafts(context, inputs.shafts, analysis.j_margin * inputs.spec.rim_share)
    return replace(inputs, shafts=shafts)


def _rekeyed(scene: Scene, analysis: Analysis, result: DesignResult, shafts: Sequence[Any]) -> Any:
    """The given-seat shafts to design again on at a larger key torque (:func:`flyopt.design.shaft.cycle.rekeyed`),
    or None."""
    context = shaft_context_of(scene, analysis)
    if context is None:
        return None
    from flyopt.design.shaft.cycle import rekeyed

    return rekeyed(context, result, shafts)


def _seated(inputs: Any, scene: Scene) -> Any:
    """The design inputs with a designed seat standing for a bore (:func:`flyopt.design.shaft.diameter.seated`):
    its wheel is designed whole, with its key, on the diameter the search gives it."""
    designed = {s.name for s in scene.shafts if s.layout is not None and s.layout.designs_seat}
    if not designed:
        return inputs
    from flyopt.design.shaft.diameter import seated

    return replace(inputs, shafts=seated(inputs.shafts, designed))


def _seat_designer(scene: Scene, analysis: Analysis, shafts: Sequence[Any], names: Mapping[str, str]) -> Any:
    """``design_flywheel``, or where a described shaft designs its seat diameter the search over its series
    (:func:`flyopt.design.shaft.diameter.design_with_seats`, which checks each wheel with its own shaft)."""
    from flyopt.design import design_flywheel

    context = shaft_context_of(scene, analysis)
    if context is None:  # no described shaft: nor the shaft checks' modules, some 30 ms to import
        return design_flywheel
    from flyopt.design.shaft.diameter import design_with_seats, designs_seats

    if not designs_seats(context, shafts):
        return design_flywheel

    def design(*args: Any, accept: Any = None, **options: Any) -> Any:
        return design_with_seats(*args, ctx=context, names=names, **options)

    return design


def describes_shafts(scene: Scene) -> bool:
    """Whether the scene describes a shaft as a part (docs/flywheel-design.md, section 26): its designs are then
    keyed at the train's torque and checked with the shaft (:func:`design_scene`), in a sweep's points too."""
    return any(s.layout is not None for s in scene.shafts)


def shaft_context_of(scene: Scene, analysis: Analysis) -> Any:
    """The shaft checks' context of a scene (None when it describes no shaft)."""
    if not describes_shafts(scene):
        return None
    from flyopt.design.shaft.cycle import shaft_context

    return shaft_context(analysis, scene.shafts, scene.material_library())


def shaft_reports(scene: Scene, analysis: Analysis, design: DesignResult | None) -> tuple[Any, ...]:
    """The chosen wheel's described shaft checked with it (:class:`flyopt.design.shaft.cycle.ShaftReport`), or ()."""
    if design is None or design.best is None:
        return ()
    context = shaft_context_of(scene, analysis)
    if context is None:
        return ()
    from flyopt.design.shaft.cycle import report

    found = report(context, design.best)
    return () if found is None else (found,)


#: Relative step of the central difference of the design's mass in delta.
DELTA_STEP = 1e-4


def delta_step(delta: float) -> float:
    """The step of δ a design's sensitivity is said for: a tenth of δ to one significant figure (0.1 → +0.01,
    0.05 → +0.005, 0.01 → +0.001). The mass's change is the slope times this step, a first-order estimate that
    holds for a small step: a fixed +0.01 was all of a δ of 0.01, where the estimate (−99 kg for a 74 kg wheel)
    meant nothing."""
    return float(f"{delta / 10:.0e}")


def _with_delta_sensitivity(
    scene: Scene,
    analysis: Analysis,
    result: DesignResult,
    solver_options: Mapping[str, Any] | None,
    method: str,
) -> DesignResult:
    """The winner's d(mass)/d(delta), by designing its combination again at delta (1 +- DELTA_STEP).

    Each re-design passes the same post-checks as the design (a described shaft's): where a moved wheel
    fails one, the slope is not given (the combination is not feasible on both sides).

    delta moves the required inertia and the highest speed together, through
    whichever model sized the flywheel, so the whole requirement is recomputed
    (the same model, forced) rather than differentiated; the truncation error
    of the central difference is O(DELTA_STEP^2) of the curvature, the
    round-off that of the requirement (1e-10 relative) over 2e-4.
    """
    import dataclasses

    from flyopt.design import design_flywheel, design_inputs
    from flyopt.design.wheel_design import needs_torque, sensitivity
    from flyopt.names import Model

    best = result.best
    if best is None or scene.delta is None or analysis.machine is None and analysis.indicator is None:
        return result
    step = delta_step(scene.delta)
    if analysis.stall_sets_flywheel_at(scene.delta * (1.0 - DELTA_STEP)):
        # δ does not set the flywheel on either side of the step: re-solving at δ (1 +- DELTA_STEP) would locate
        # the same stall limit twice more, each to its tolerance (STALL_RTOL), and difference that noise into a
        # slope
        sentence = (
            f"delta: {{step}} (e.g. {scene.delta:.3g} to {scene.delta + step:.3g}) changes the mass by {{dmass}}: "
            f"the flywheel is set by the stall limit, where δ reaches {analysis.delta_reached:.3g}"
        )
        return _with_sensitivity(result, sensitivity("delta", "-", 0.0, sentence, step))
    masses: list[float] = []
    for sign in (1.0, -1.0):
        delta = scene.delta * (1.0 + sign * DELTA_STEP)
        try:
            moved = analyse(dataclasses.replace(scene, delta=delta), Model(analysis.model), like=analysis)
            inputs = design_inputs(dataclasses.replace(scene, delta=delta))
            # on the winner's seat: a designed one (its bore) is held, a discrete variable has no slope; its key's
            # torque that of the moved cycle
            on = tuple(
                dataclasses.replace(s, diameter=best.bore or s.diameter) for s in inputs.shafts if s.name == best.shaft
            )
            inputs = _seated(_keyed(scene, moved, dataclasses.replace(inputs, shafts=on)), scene)
            # the continuous design's slope: a rounded wheel's mass steps with the grid, and rounding it
            # twice more would only cost solves
            spec = dataclasses.replace(inputs.spec, round_to=None, stress_factors=result.spec.stress_factors)
            if best.n_arms is not None:
                spec = dataclasses.replace(spec, arms=(best.n_arms,))
            torque = moved.flywheel_torque() if needs_torque(inputs) else None
            again = design_flywheel(
                moved.j_margin,
                moved.omega_max,
                inputs.shafts,
                [m for m in inputs.materials if m.name == best.material],
                spec,
                solver_options=solver_options,
                method=method,
                torque=torque,
                omega_mean=moved.omega_mean,
                # the described shaft carries the moved wheel too
                accept=_shaft_acceptor(scene, moved, {m.name: m.display_name for m in inputs.materials}),
            )
        except (ValueError, RuntimeError):
            return result
        if again.best is None:
            return result
        masses.append(again.best.mass)
    slope = (masses[0] - masses[1]) / (2.0 * DELTA_STEP * scene.delta)
    entry = sensitivity(
        "delta",
        "-",
        slope,
        f"delta: {{step}} (e.g. {scene.delta:.3g} to {scene.delta + step:.3g}) changes the mass by {{dmass}} "
        f"(central difference of the whole {'continuous ' if result.spec.round_to else ''}design)",
        step,
    )
    return _with_sensitivity(result, entry)


def _with_sensitivity(result: DesignResult, entry: dict[str, Any]) -> DesignResult:
    """The result with one more sensitivity on its winner (none: as it is)."""
    best = result.best
    if best is None:
        return result
    winner = replace(best, limits=replace(best.limits, sensitivities=best.limits.sensitivities + (entry,)))
    candidates = tuple(winner if c is best else c for c in result.candidates)
    return replace(result, best=winner, candidates=candidates)


def verify(
    scene: Scene, analysis: Analysis, design_result: DesignResult | None = None, j_flywheel: float | None = None
) -> Verification | None:
    """Simulate the machine with its flywheel and report the δ it really achieves.

    The periodic solution of the equation of motion (flyopt.sizing.periodic.verify)
    with the chosen flywheel moved to the reference shaft (J' i²); with no
    flywheel needed, the machine alone. A design whose δ exceeds the allowed
    one by more than the simulation tolerance is ``flagged``. ``j_flywheel`` [kg*m^2], at the reference
    shaft, simulates that wheel instead (a [flywheel] that exists, :func:`check_flywheel`).

    Returns
    -------
    Verification or None
        None when there is no flywheel to verify (infeasible design).
    """
    from flyopt.cycle.indicator import speed_extremes
    from flyopt.errors import SceneError
    from flyopt.sizing import periodic

    if design_result is not None and design_result.status == "infeasible":
        return None
    if j_flywheel is None and design_result is not None and design_result.best is not None:
        j_chosen = design_result.best.j_at_reference
        if j_chosen is None:
            raise BrokenInvariant("a designed wheel has its inertia")
        # a rim that gives rim_share of J_F: the arms and hub the design leaves to others give the rest
        j_flywheel = j_chosen / design_result.spec.rim_share
    elif j_flywheel is None:
        j_flywheel = max(analysis.j_margin, 0.0)
    machine = analysis.machine
    if machine is None:  # net areas: no curves to simulate; the energy method is exact for them
        j = analysis.j_constant + j_flywheel
        if analysis.a_max == 0:
            achieved = 0.0  # no fluctuation of energy: no fluctuation of speed
        else:
            achieved = analysis.a_max / (j * analysis.omega_mean**2) if j > 0 else float("inf")
        omega_max, omega_min = speed_extremes(analysis.omega_mean, achieved)
        return periodic.Verification(
            method="energy method (net areas give no curves to simulate; exact for constant inertia)",
            achieved_delta=achieved,
            delta_allowed=analysis.delta,
            omega_max=omega_max,
            omega_min=omega_min,
            omega_mean=analysis.omega_mean,
            tolerance=1e-12 * analysis.delta,
            flagged=achieved > analysis.delta * (1 + 1e-12),
            j_flywheel=j_flywheel,
        )
    try:
        result = periodic.verify(
            machine.net_torque(),
            machine.j_machine,
            machine.cycle_angle,
            analysis.omega_mean,
            analysis.delta,
            j_flywheel,
            machine.knots(),
        )
    except SceneError as err:
        raise err.with_source(scene.source) from None
    return result


def solve(
    scene: Scene,
    design_flywheel: bool = True,
    solver_options: Mapping[str, Any] | None = None,
    model: Literal["energy", "energy_mass", "dynamic"] | None = None,
    verify_design: bool = False,
    design_method: Literal["auto", "ipopt", "closed_form"] = "auto",
    extras: Collection[str] = SHOWN,
) -> Solution:
    """Analyse a scene and design its flywheel.

    Parameters
    ----------
    scene : Scene
    design_flywheel : bool
        False stops after the cycle analysis.
    solver_options : mapping, optional
        CasADi/IPOPT options for the design NLPs that IPOPT solves (every one
        with ``design_method="ipopt"``; under "auto" only the structures the
        closed form does not cover).
    model : {"energy", "energy_mass", "dynamic"}, optional
        Force the model that sizes the flywheel (default: the cheapest exact one).
    verify_design : bool
        Simulate the machine with the chosen flywheel (:func:`verify`).
    design_method : {"auto", "ipopt", "closed_form"}
        How each combination is optimized (see :func:`design_scene`).
    extras : collection of str
        What else to compute, of :data:`COMPLETE`: by default what ``flyopt
        solve`` shows (:data:`SHOWN`); the report and the diagrams ask for
        what they draw, and then only read the solution.

    Returns
    -------
    Solution
    """
    unknown = [name for name in extras if name not in COMPLETE]
    if unknown:
        raise ValueError(f"unknown extras {unknown} (known: {', '.join(COMPLETE)})")
    if scene.calculation is not None:
        from flyopt.errors import SceneError

        raise SceneError(
            scene.calculation,
            "is one calculation, not a cycle: solve_calculation(scene) answers it (as flyopt solve does)",
        ).with_source(scene.source)
    if scene.flywheel is not None:
        analysis, checked_wheel = check_flywheel(scene, model)
        solution = Solution(scene=scene.replace(delta=analysis.delta), analysis=analysis, flywheel=checked_wheel)
        return with_extras(solution, extras)
    analysis = analyse(scene, model)
    if scene.drive is not None and design_flywheel:
        solution = solve_drive(scene, analysis, solver_options, extras)
    else:
        result = design_scene(scene, analysis, solver_options, design_method) if design_flywheel else None
        checked = verify(scene, analysis, result) if verify_design else None
        solution = Solution(
            scene=scene,
            analysis=analysis,
            design=result,
            verification=checked,
            shaft_checks=shaft_reports(scene, analysis, result),
        )
    return with_extras(solution, extras)


def solve_calculation(scene: Scene) -> OperationResult | CrankForces | PositionEquivalents | ReducedDrive | PowerFlow:
    """The answer of a scene that is one calculation rather than a cycle: an [operation] (:func:`solve_operation`),
    a [position] (:func:`solve_position`), an [electric_drive] (flyopt.machine.electric_drive.reduce_drive) or a
    [power_chain] (flyopt.machine.transmission.power_flow)."""
    what = scene.calculation
    if what == "operation":
        return solve_operation(scene)
    if what == "position":
        return solve_position(scene)
    if what == "electric_drive" and scene.electric_drive is not None:
        from flyopt.machine.electric_drive import reduce_drive

        return reduce_drive(scene.electric_drive)
    if what == "power_chain" and scene.power_chain is not None:
        from flyopt.machine.transmission import power_flow

        return power_flow(scene.power_chain)
    raise ValueError(
        "solve_calculation needs a scene with an [operation], a [position], an [electric_drive] or a [power_chain]"
    )


def solve_operation(scene: Scene) -> OperationResult:
    """One operation of a scene's [operation] on its [flywheel] (flyopt.sizing.operation): the speed after it,
    the recovery time and the operations a minute the motor sustains; J is the machine's J_c plus the wheel's."""
    from flyopt.errors import SceneError
    from flyopt.sizing.operation import one_operation

    if scene.operation is None or scene.flywheel is None:
        raise ValueError("solve_operation needs a scene with an [operation] and a [flywheel]")
    try:
        return one_operation(
            scene.operation, scene.j_constant + scene.flywheel.j_at_reference, scene.omega_mean, scene.delta
        )
    except SceneError as err:
        raise err.with_source(scene.source) from None


def solve_position(scene: Scene) -> CrankForces | PositionEquivalents:
    """The answer of a scene's [position]: beside [[member]]s, their equivalents at that position
    (flyopt.machine.equivalents, no speed needed); alone, a slider-crank engine's forces
    (flyopt.machine.crank_forces) at its machine.speed."""
    from flyopt.errors import SceneError
    from flyopt.machine.crank_forces import CrankPosition, crank_forces

    if scene.position is None:
        raise ValueError("solve_position needs a scene with a [position]")
    if isinstance(scene.position, CrankPosition):
        return crank_forces(scene.position, scene.omega_mean)
    from flyopt.machine.equivalents import equivalents_at

    try:
        return equivalents_at(scene.position, scene.members, scene.j_constant, scene.mechanism)
    except SceneError as err:
        raise err.with_source(scene.source) from None


#: δ of the first, energy-method look at a scene whose [flywheel] is given without machine.delta: only its
#: A_max is read (the energy method's A_max does not depend on δ), so any allowed value serves.
PROVISIONAL_DELTA = 0.01


def check_flywheel(
    scene: Scene, model: Literal["energy", "energy_mass", "dynamic"] | None = None
) -> tuple[Analysis, FlywheelCheck]:
    """Analyse a scene whose [flywheel] exists: the δ, speeds and accelerations it leaves.

    The analysis returned is the machine's own (the wheel left out) at the δ the wheel reaches,
    so that its J_F is the wheel's (to the model's tolerance, a check of the two methods against
    each other) and everything drawn from it (the speed over the cycle) is the machine with that
    wheel; where the scene gives machine.delta, the J_F it asks for, whether the wheel suffices and
    by what margin are in the check. The energy method inverts in closed form for a constant
    inertia and torques of the angle only; any other model is answered by the periodic
    simulation with the wheel.
    """
    from flyopt.sizing import existing

    wheel = scene.flywheel
    if wheel is None:
        raise ValueError("check_flywheel needs a scene with a [flywheel]")
    j_wheel = wheel.j_at_reference
    allowed = analyse(scene, model) if scene.delta is not None else None  # the J_F machine.delta asks for
    first = allowed if allowed is not None else analyse(scene.replace(delta=PROVISIONAL_DELTA), "energy")
    guess = existing.energy_delta(first.a_max, scene.omega_mean, first.j_constant + j_wheel)
    analysis = analyse(scene.replace(delta=min(guess, 1.9)), model, like=first)
    machine = analysis.machine
    accelerations: tuple[float | None, ...] = (None, None, None, None)  # net areas: no torques over the angle
    accelerations_at: tuple[tuple[float, float], ...] = ()  # at flywheel.angles (none for net areas)
    if analysis.model == "energy" or machine is None:  # net areas: the energy method alone
        achieved = existing.energy_delta(analysis.a_max, analysis.omega_mean, analysis.j_constant + j_wheel)
        omega_max, omega_min = speed_extremes(analysis.omega_mean, achieved)
        angles: tuple[float | None, float | None] = (analysis.angle_omega_max, analysis.angle_omega_min)
        swing, tolerance = analysis.a_max, 1e-12 * achieved
        method = "energy method, exact for a constant inertia and torques of the angle only: δ = A_max/(ω_m² J)"
        if machine is not None:  # dω/dt = (M_d - M_r)/J at every angle
            high, at_high, low, at_low = existing.net_torque_extremes(machine)
            j_total = analysis.j_constant + j_wheel
            accelerations = (high / j_total, at_high, low / j_total, at_low)
            if wheel.angles:
                at = existing.net_torque_at(machine, wheel.angles) / j_total
                accelerations_at = tuple((a, float(e)) for a, e in zip(wheel.angles, at, strict=True))
    else:
        simulation = verify(scene.replace(delta=analysis.delta), analysis, j_flywheel=j_wheel)
        sol = simulation.solution if simulation is not None else None
        if simulation is None or sol is None:
            raise RuntimeError("the periodic simulation returned no speed curve")
        achieved, omega_max, omega_min = simulation.achieved_delta, sol.omega_max, sol.omega_min
        angles = (sol.phi_omega_max, sol.phi_omega_min)
        swing = existing.kinetic_energy_swing(sol, _plus(machine.j_machine, j_wheel))
        tolerance = simulation.tolerance
        method = f"{simulation.method} with the flywheel given"
        accelerations = existing.solution_accelerations(sol)
        if wheel.angles:
            at = existing.solution_acceleration_at(sol, wheel.angles)
            accelerations_at = tuple((a, float(e)) for a, e in zip(wheel.angles, at, strict=True))
        analysis = analyse(scene.replace(delta=achieved), model, like=analysis)  # at the δ the wheel reaches
    required = suffices = margin = None
    if scene.delta is not None and allowed is not None:
        required = max(allowed.j_margin, 0.0)
        suffices = achieved <= scene.delta + tolerance
        margin = j_wheel / required - 1.0 if required > 0 else None
    check = existing.FlywheelCheck(
        flywheel=wheel,
        j_machine=analysis.j_constant if machine is None or not machine.variable_inertia else machine.j_mean(),
        achieved_delta=achieved,
        omega_mean=analysis.omega_mean,
        omega_max=omega_max,
        omega_min=omega_min,
        angle_omega_max=angles[0],
        angle_omega_min=angles[1],
        a_max=analysis.a_max,
        energy_swing=swing,
        acceleration_max=accelerations[0],
        angle_acceleration_max=accelerations[1],
        acceleration_min=accelerations[2],
        angle_acceleration_min=accelerations[3],
        method=method,
        tolerance=tolerance,
        delta_allowed=scene.delta,
        j_required=required,
        suffices=suffices,
        margin=margin,
        accelerations_at=accelerations_at,
    )
    return analysis, check


def _plus(inertia: Any, extra: float) -> Any:
    """J(φ) + a constant, for a number or a function of φ."""
    return (lambda phi: inertia(phi) + extra) if callable(inertia) else float(inertia) + extra


def with_extras(solution: Solution, extras: Iterable[str] = COMPLETE) -> Solution:
    """``solution`` with ``extras`` (of :data:`COMPLETE`) computed on its scene, analysis and design."""
    analysis = complete(solution.analysis, [name for name in extras if name in ANALYSIS_EXTRAS])
    have = dict(solution._extras)
    scene, design = solution.scene, solution.design
    for name in SOLUTION_EXTRAS:
        if name not in extras or name in have:
            continue
        if name == "inertia_curve":
            have[name] = _inertia_curve(scene, analysis)
        elif name == "energy_mass":
            have[name] = _energy_mass(scene, analysis)
        elif name == "stress":
            have[name] = _stress(scene, analysis, design)
        else:
            checked = verify(scene, analysis) if scene.net is None else None  # no design: never None
            have[name] = checked.solution if checked is not None else None
    return replace(solution, analysis=analysis, _extras=MappingProxyType(have))


def _inertia_curve(scene: Scene, analysis: Analysis) -> tuple[tuple[np.ndarray, np.ndarray] | None, Exception | None]:
    """(curve or None, the error that kept it from being found or None); see :data:`SOLUTION_EXTRAS`."""
    from flyopt.delta_curve import flywheel_at_some_delta, inertia_curve

    if analysis.model == "energy" or not flywheel_at_some_delta(analysis):
        return None, None  # the energy method's closed form is drawn as it is; a steady machine has no curve
    try:
        return inertia_curve(scene, analysis), None
    except (ValueError, RuntimeError) as err:
        return None, err


def _energy_mass(scene: Scene, analysis: Analysis) -> Analysis | None:
    """The analysis by the energy–mass model where its diagram applies (J_e varies, torques of the angle only)."""
    machine = analysis.machine
    if machine is None or not machine.variable_inertia or machine.speed_dependent:
        return None
    if analysis.model == "energy_mass":
        return analysis
    return analyse(scene, "energy_mass", like=analysis)


def _stress(
    scene: Scene, analysis: Analysis, design: DesignResult | None
) -> tuple[tuple[Any, Any, float, Material] | None, str]:
    """(the chosen wheel's :func:`stress_profile` or None, why it could not be computed or "")."""
    if design is None or design.best is None:
        return None, ""
    try:
        return stress_profile(scene, analysis, design), ""
    except ValueError as err:
        return None, str(err)


def stress_profile(scene: Scene, analysis: Analysis, design: DesignResult) -> tuple[Any, Any, float, Material]:
    """The stresses of the design's best wheel over its radius, at omega_max on its own shaft.

    Returns
    -------
    profile, beams : see :func:`flyopt.design.strength.profile`
    omega : float
        omega_max on the wheel's shaft [rad/s].
    material : flyopt.design.materials.Material
    """
    from flyopt.design import strength

    best = design.best
    if best is None:
        raise ValueError("no wheel was designed: there are no stresses to compute")
    material = scene.material_library()[best.material]
    if getattr(material, "poisson_ratio", None) is None:
        raise ValueError(f"material {best.material!r} gives no poisson_ratio: its stresses cannot be computed")
    omega = design.omega * best.speed_ratio
    key = best.parts.key if best.parts is not None else None
    if key and key.get("torque"):
        # the torque the design took on this shaft (flyopt.design.designer.shaft_torque_of: a modelled train's
        # J_w theta''_w, else the rigid body's): it bent the arms and loaded the key the design checked
        torque = float(key["torque"])
    else:
        rigid = analysis.flywheel_torque()
        torque = rigid / best.speed_ratio if rigid else 0.0
    profile, beams = strength.profile(material, best.geometry, best.dims.wheel(best.n_arms, best.bore), omega, torque)
    return profile, beams, omega, material


def solve_drive(
    scene: Scene,
    analysis: Analysis,
    solver_options: Mapping[str, Any] | None = None,
    extras: Collection[str] = (),
) -> Solution:
    """Design the drive and the flywheel together (flyopt.drive.codesign), then analyse and check the machine as built.

    The Solution's scene and analysis are the machine with the chosen motor
    on its curve at its ratio (the periodic model), its design the wheel on
    the chosen shaft, and ``drive_check`` the simulation with the wheel as built
    (δ, the motor's RMS torque, the start-up); an infeasible drive gives the
    scene's own analysis and no design. With "models" in ``extras`` the
    analysis' comparison of the models takes the δ of a flywheel from the
    compiled model the search solved (:func:`flyopt.drive.codesign.flywheel_delta`).
    """
    from flyopt.drive.codesign import chosen_scene, design_drive, flywheel_delta, verify_drive

    drive = design_drive(scene, analysis, solver_options=solver_options)
    if drive.best is None:
        return Solution(scene=scene, analysis=analysis, drive=drive)
    built = chosen_scene(scene, drive.best)
    # a motor the search found to need no flywheel: whether its slip alone keeps δ is asked first (one CVODES
    # solution of the machine as it is, which the verification below reads again) before a search for a flywheel
    chosen = analyse(built, "dynamic", slip_first=drive.best.limit == "none")
    if "models" in extras and chosen.machine is not None:
        chosen = complete(chosen, ("models",), simulate=flywheel_delta(drive, chosen.machine))
    return Solution(
        scene=built,
        analysis=chosen,
        design=drive.best.design,
        drive=drive,
        drive_check=verify_drive(scene, drive.best),
        shaft_checks=drive.best.shaft_checks,  # the described flywheel shaft, as the drive's search checked it
    )
