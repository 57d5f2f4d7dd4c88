"""Which model sizes the flywheel: the cheapest one that is exact for the scene.

Three models (docs/flywheel-design.md, sections 5–7), from the cheapest:

- ``energy``: constant equivalent inertia, torques of the angle only:
  J_F = A_max/(ω_m² δ) − J_c (flyopt.cycle.indicator);
- ``energy_mass``: the inertia varies with the angle, torques of the angle
  only: Wittenbauer's energy–mass closed form (flyopt.sizing.energy_mass);
- ``dynamic``: a torque depends on speed: the periodic solution of
  d(½ J_e ω²)/dφ = M_d(φ, ω) − M_r(φ, ω) (flyopt.sizing.periodic).

A scene is first reduced to a :class:`flyopt.machine.reduce.Machine` (J_e(φ), the driving and
resisting torques with the members' loads joined in); :func:`choose` names
the cheapest exact model and why; :func:`requirement` runs one model, and
:func:`compare` runs every model that applies, so that the report can say how
far a cheaper method would be off — in J_F and in the δ it would really give.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from flyopt.cycle.indicator import EnergyIndicator, required_inertia
from flyopt.errors import NonPeriodicCycle, SolverFailed
from flyopt.machine.reduce import Machine, reduce  # noqa: F401 -- callers reach the reduction as models.reduce
from flyopt.names import Model

ENERGY, ENERGY_MASS, DYNAMIC = Model.ENERGY, Model.ENERGY_MASS, Model.DYNAMIC
MODELS = {
    ENERGY: "constant-inertia energy method, J_F = A_max/(ω_m² δ) − J_c",
    ENERGY_MASS: "energy–mass (Wittenbauer) closed form for an inertia that varies with the angle",
    DYNAMIC: "periodic solution of the equation of motion (CasADi/CVODES shooting)",
}
ORDER = (ENERGY, ENERGY_MASS, DYNAMIC)


def choose(machine: Machine) -> tuple[Model, str]:
    """The cheapest model that is exact for the machine, and why (a sentence)."""
    if machine.speed_dependent:
        return DYNAMIC, "a torque depends on speed, so only the periodic solution of the equation of motion is exact"
    if machine.variable_inertia:
        return ENERGY_MASS, (
            "the equivalent inertia varies with the angle and the torques depend on the angle "
            "only, so the energy–mass closed form is exact"
        )
    return ENERGY, (
        "the equivalent inertia is constant and the torques depend on the angle only, so the "
        "constant-inertia energy method is exact"
    )


@dataclass(frozen=True)
class Requirement:
    """The flywheel one model asks for, and what it achieves.

    Attributes
    ----------
    model : str
    j_required : float
        J_F at the reference shaft [kg*m^2] (zero or negative: none needed).
    omega_mean, omega_max, omega_min : float
        Speeds with that flywheel [rad/s] (the mean is held by the torque
        balance in the dynamic model with a speed-dependent torque).
    angle_omega_max, angle_omega_min : float or None
        Where they occur [rad].
    detail : object
        The model's own result (EnergyMassRequirement, DynamicRequirement).
    note : str
    """

    model: str
    j_required: float
    omega_mean: float
    omega_max: float
    omega_min: float
    angle_omega_max: float | None
    angle_omega_min: float | None
    detail: Any = None
    note: str = ""


def requirement(
    machine: Machine, model: str, indicator: EnergyIndicator | None = None, *, slip_first: bool = False
) -> Requirement:
    """Size the flywheel with one model.

    Parameters
    ----------
    machine : Machine
    model : {"energy", "energy_mass", "dynamic"}
    indicator : EnergyIndicator, optional
        The energy indicator diagram of the angle-only torques (reused by the
        energy model).
    slip_first : bool
        The dynamic model: ask first whether the motor's slip alone keeps δ
        (:func:`flyopt.sizing.periodic.dynamic_requirement`).

    Returns
    -------
    Requirement

    Raises
    ------
    SolverFailed
        The periodic solution did not converge (stall, runaway, no steady state).
    """
    w, d = machine.omega_mean, machine.delta
    if model == ENERGY:
        if indicator is None:
            from flyopt.cycle.indicator import energy_indicator

            ew = machine.angle_only()
            indicator = energy_indicator(ew.driving, ew.resisting, machine.cycle_angle)
        j = required_inertia(indicator.a_max, w, d, machine.j_mean())
        note = "" if not machine.variable_inertia else "J_e replaced by its cycle mean"
        return Requirement(
            ENERGY,
            j,
            w,
            w * (1 + d / 2),
            w * (1 - d / 2),
            indicator.angle_omega_max,
            indicator.angle_omega_min,
            None,
            note,
        )
    if model == ENERGY_MASS:
        from flyopt.sizing import energy_mass

        em = energy_mass.energy_mass_requirement(machine.angle_only(), machine.j_machine, w, d)
        return Requirement(
            ENERGY_MASS,
            em.j_required,
            em.omega_mean,
            em.omega_max,
            em.omega_min,
            em.phi_omega_max,
            em.phi_omega_min,
            em,
        )
    if model == DYNAMIC:
        from flyopt.sizing import periodic  # CasADi: only for a machine whose torque depends on speed

        dyn = periodic.dynamic_requirement(
            machine.net_torque(), machine.j_machine, machine.cycle_angle, w, d, machine.knots(), slip_first=slip_first
        )
        sol = dyn.solution
        note = dyn.held
        if dyn.limit == "stall":
            note += "; δ stays within the limit down to the smallest flywheel that still runs steadily (stall)"
        elif dyn.limit == "none":
            note += "; no flywheel needed: δ stays within the allowed value however small the inertia"
        return Requirement(
            DYNAMIC,
            dyn.j_required,
            sol.omega_mean,
            sol.omega_max,
            sol.omega_min,
            sol.phi_omega_max,
            sol.phi_omega_min,
            dyn,
            note,
        )
    raise ValueError(f"model {model!r} is not known (allowed: {', '.join(ORDER)})")


def achieved_delta(machine: Machine, j_flywheel: float) -> float:
    """δ the machine really reaches with a flywheel J_F at the reference shaft (by the exact model)."""
    from flyopt.sizing import energy_mass, periodic, periodic_model

    exact, _ = choose(machine)
    if exact in (ENERGY, ENERGY_MASS):
        if machine.j_mean() + j_flywheel <= 0:  # no inertia: the speed is constant only if nothing fluctuates
            model = periodic_model.periodic_model(
                machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.knots()
            )
            return 0.0 if model.steady else float("inf")
        return energy_mass.achieved_speed(machine.angle_only(), machine.j_machine, machine.omega_mean, j_flywheel).delta
    sol = periodic.periodic_solution(
        machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.omega_mean, j_flywheel, machine.knots()
    )
    return sol.delta


def compare(
    machine: Machine,
    chosen: str,
    indicator: EnergyIndicator | None = None,
    known: Requirement | None = None,
    simulate: Callable[[float], float] | None = None,
) -> list[dict[str, Any]]:
    """Every applicable model's J_F and the δ it really gives (by the exact model).

    ``known`` is a :class:`Requirement` already computed (the chosen model's,
    by :func:`requirement`): it is reused, not solved again (a periodic
    dynamic solution takes about a second). ``simulate``: J_F ↦ the δ the
    machine reaches with it by the exact model, where the caller has that
    model compiled already (a drive's chosen machine, flyopt.drive.steady);
    default :func:`achieved_delta`.

    Returns a list of dicts: model, exact (bool), j_required, achieved_delta,
    j_error (relative to the exact model's J_F), note.
    """
    if known is not None and known.model != chosen:
        raise ValueError(f"the known requirement is of model {known.model!r}, not of the chosen {chosen!r}")
    exact, _ = choose(machine)
    rows: list[dict[str, Any]] = []
    results: dict[str, Requirement] = {}
    model: str  # a Model, or the name a caller gave
    for model in ORDER:
        if model != chosen and ORDER.index(model) > ORDER.index(exact):
            continue  # a costlier model than the exact one adds nothing
        if model == ENERGY_MASS and model != chosen and not machine.variable_inertia:
            continue  # with a constant inertia it is the energy method again
        if known is not None and known.model == model:
            results[model] = known
            continue
        try:
            results[model] = requirement(machine, model, indicator if model == ENERGY else None)
        except (NonPeriodicCycle, SolverFailed, ValueError) as err:
            rows.append(
                {
                    "model": model,
                    "exact": model == exact,
                    "j_required": None,
                    "achieved_delta": None,
                    "j_error": None,
                    "note": f"not applicable: {err}",
                }
            )
    reference = results.get(exact) or results.get(chosen)
    for model, res in results.items():
        j = res.j_required
        # the exact model's δ: the allowed one where its flywheel reaches it; the dynamic model's own periodic
        # solution where no flywheel does (a stall limit, or "none": the machine with no flywheel, J_F = 0 as
        # for the other rows' max(J_F, 0), whose δ stays below the allowed one)
        delta = machine.delta if model == exact else None
        if model == exact and model == DYNAMIC and res.detail.limit != "delta":
            delta = res.detail.solution.delta
        note = res.note
        if model != exact:
            try:
                delta = achieved_delta(machine, max(j, 0.0)) if simulate is None else simulate(max(j, 0.0))
            except (SolverFailed, NonPeriodicCycle, ValueError) as err:
                note = f"{note}; its δ could not be simulated: {err}".lstrip("; ")
        error = None
        if reference is not None and reference.j_required > 0:
            error = (j - reference.j_required) / reference.j_required
        rows.append(
            {
                "model": model,
                "exact": model == exact,
                "j_required": j,
                "achieved_delta": delta,
                "j_error": error,
                "note": note,
            }
        )
    rows.sort(key=lambda r: ORDER.index(r["model"]))
    return rows
