"""Which model sizes the flywheel: the cheapest one that is exact for the scene.

Three models (docs/flywheel-design.md, sections 5–7), from the cheapest:

- ``energy``: constant equivalent inertia, torques of the angle only:
  J_F = A_max/(ω_m² δ) − J_c (flyopt.cycle.indicator);
- ``energy_mass``: the inertia varies with the angle, torques of the angle
  only: Wittenbauer's energy–mass closed form (flyopt.sizing.dynamics);
- ``dynamic``: a torque depends on speed: the periodic solution of
  d(½ J_e ω²)/dφ = M_d(φ, ω) − M_r(φ, ω) (flyopt.sizing.dynamics).

A scene is first reduced to a :class:`Machine` (J_e(φ), the driving and
resisting torques with the members' loads joined in); :func:`choose` names
the cheapest exact model and why; :func:`requirement` runs one model, and
:func:`compare` runs every model that applies, so that the report can say how
far a cheaper method would be off — in J_F and in the δ it would really give.
"""

from dataclasses import dataclass, field

import numpy as np

from flyopt.sizing import dynamics
from flyopt.cycle.indicator import ExcessWork, required_inertia
from flyopt.errors import NonPeriodicCycle, SceneError, SolverFailed
from flyopt.machine.torque import Constant, TorqueSum

ENERGY, ENERGY_MASS, DYNAMIC = dynamics.MODEL_ENERGY, dynamics.MODEL_ENERGY_MASS, dynamics.MODEL_PERIODIC
MODELS = {
    ENERGY: "constant-inertia energy method, J_F = A_max/(ω_m² δ) − J_c",
    ENERGY_MASS: "energy–mass (Wittenbauer) closed form for an inertia that varies with the angle",
    DYNAMIC: "periodic solution of the equation of motion (CasADi/CVODES shooting)",
}
ORDER = (ENERGY, ENERGY_MASS, DYNAMIC)


@dataclass(frozen=True)
class Machine:
    """A scene reduced to the reference shaft.

    Attributes
    ----------
    driving, resisting : torque curves
        Equivalent torques [N*m]; the members' loads are joined into the
        side that is known. May depend on speed.
    j_machine : float or flyopt.machine.mechanism.EquivalentInertia
        J_e(φ) = J_c + J_v(φ) [kg*m^2], without the flywheel.
    cycle_angle, omega_mean, delta : float
        Φ [rad], the scene's mean speed [rad/s], the allowed δ.
    speed_dependent, variable_inertia : bool
    """

    driving: object
    resisting: object
    j_machine: object
    cycle_angle: float
    omega_mean: float
    delta: float
    speed_dependent: bool
    variable_inertia: bool
    _cache: dict = field(default_factory=dict, compare=False, repr=False)

    def angle_only(self, omega=None):
        """ExcessWork of the torques with every speed dependence frozen.

        A motor becomes the constant that balances the cycle (its mean
        torque in steady running); an expression in ``omega`` is taken at
        ``omega`` (default: the scene's mean speed).
        """
        omega = self.omega_mean if omega is None else float(omega)
        if omega not in self._cache:  # built once: its knot integrals may cost many quadratures
            self._cache[omega] = ExcessWork(_frozen(self.driving, omega), _frozen(self.resisting, omega),
                                            self.cycle_angle)
        return self._cache[omega]

    def net_torque(self):
        """M_d − M_r as a callable (phi, omega) that accepts CasADi symbols [N*m].

        An unknown constant is first solved from the work balance (at the
        mean speed when another torque depends on speed).
        """
        if not self.speed_dependent:
            return dynamics.angle_torque(self.angle_only())
        balanced = self.angle_only()
        driving = balanced.driving if _unknown(self.driving) else self.driving
        resisting = balanced.resisting if _unknown(self.resisting) else self.resisting

        def net(phi, omega):
            return _casadi(driving, phi, omega) - _casadi(resisting, phi, omega)
        return net

    def knots(self):
        """Angles where a torque steps or kinks [rad] (the simulation cuts there).

        The kinks of a speed-dependent expression are those at the mean speed
        (the angle-only torques): with the speed free they move a little, and
        a cut there is merely one more step of the integrator.
        """
        return self.angle_only().knots

    def j_mean(self):
        """Cycle mean of J_e [kg*m^2] (J_c for a constant inertia)."""
        if not self.variable_inertia:
            return float(self.j_machine)
        phi = np.linspace(0.0, self.cycle_angle, 4097)
        return float(np.mean(self.j_machine(phi[:-1])))


def reduce(scene):
    """Reduce a scene (torques, J_c, members) to a :class:`Machine`."""
    from flyopt.machine.mechanism import equivalent_inertia, equivalent_torque

    driving, resisting = scene.driving, scene.resisting
    j_machine = scene.j_constant
    if scene.members:
        j_machine = equivalent_inertia(scene.members, scene.j_constant)
        if j_machine.is_constant:
            j_machine = float(j_machine(np.array([0.0]))[0])
        if any(m.force is not None or m.torque is not None for m in scene.members):
            loads = equivalent_torque(scene.members)          # positive drives
            if _unknown(resisting):
                driving = TorqueSum([driving, loads], "torque.driving + members")
            else:
                resisting = TorqueSum([resisting, loads.resisting()], "torque.resisting + members")
    speed = any(getattr(c, "speed_dependent", False) for c in (driving, resisting))
    if speed and (_unknown(driving) or _unknown(resisting)) and \
            any(type(c).__name__ == "MotorTorque" for c in (driving, resisting)):
        raise SceneError("torque.resisting", "with a motor driving, the load must be given (not an unknown constant)")
    return Machine(driving=driving, resisting=resisting, j_machine=j_machine, cycle_angle=scene.cycle_angle,
                   omega_mean=scene.omega_mean, delta=scene.delta, speed_dependent=speed,
                   variable_inertia=not isinstance(j_machine, (int, float)))


def choose(machine):
    """The cheapest model that is exact for the machine, and why (a sentence)."""
    if machine.speed_dependent:
        return DYNAMIC, "a torque depends on speed, so only the periodic solution of the equation of motion is exact"
    if machine.variable_inertia:
        return ENERGY_MASS, ("the equivalent inertia varies with the angle and the torques depend on the angle "
                             "only, so the energy–mass closed form is exact")
    return ENERGY, ("the equivalent inertia is constant and the torques depend on the angle only, so the "
                    "constant-inertia energy method is exact")


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
    detail: object = None
    note: str = ""


def requirement(machine, model, indicator=None):
    """Size the flywheel with one model.

    Parameters
    ----------
    machine : Machine
    model : {"energy", "energy_mass", "dynamic"}
    indicator : EnergyIndicator, optional
        The energy indicator diagram of the angle-only torques (reused by the
        energy model).

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
        return Requirement(ENERGY, j, w, w * (1 + d / 2), w * (1 - d / 2), indicator.angle_omega_max,
                           indicator.angle_omega_min, None, note)
    if model == ENERGY_MASS:
        em = dynamics.energy_mass_requirement(machine.angle_only(), machine.j_machine, w, d)
        return Requirement(ENERGY_MASS, em.j_required, em.omega_mean, em.omega_max, em.omega_min,
                           em.phi_omega_max, em.phi_omega_min, em)
    if model == DYNAMIC:
        dyn = dynamics.dynamic_requirement(machine.net_torque(), machine.j_machine, machine.cycle_angle, w, d,
                                           machine.knots())
        sol = dyn.solution
        note = dyn.held
        if dyn.limit == "stall":
            note += "; δ stays within the limit down to the smallest flywheel that still runs steadily (stall)"
        return Requirement(DYNAMIC, dyn.j_required, sol.omega_mean, sol.omega_max, sol.omega_min,
                           sol.phi_omega_max, sol.phi_omega_min, dyn, note)
    raise ValueError(f"model {model!r} is not known (allowed: {', '.join(ORDER)})")


def achieved_delta(machine, j_flywheel):
    """δ the machine really reaches with a flywheel J_F at the reference shaft (by the exact model)."""
    exact, _ = choose(machine)
    if exact in (ENERGY, ENERGY_MASS):
        if machine.j_mean() + j_flywheel <= 0:
            return float("inf")
        return dynamics.achieved_speed(machine.angle_only(), machine.j_machine, machine.omega_mean,
                                       j_flywheel).delta
    sol = dynamics.periodic_solution(machine.net_torque(), machine.j_machine, machine.cycle_angle,
                                     machine.omega_mean, j_flywheel, machine.knots())
    return sol.delta


def compare(machine, chosen, indicator=None, known=None):
    """Every applicable model's J_F and the δ it really gives (by the exact model).

    ``known`` is a :class:`Requirement` already computed (the chosen model's,
    by :func:`requirement`): it is reused, not solved again (a periodic
    dynamic solution takes about a second).

    Returns a list of dicts: model, exact (bool), j_required, achieved_delta,
    j_error (relative to the exact model's J_F), note.
    """
    if known is not None and known.model != chosen:
        raise ValueError(f"the known requirement is of model {known.model!r}, not of the chosen {chosen!r}")
    exact, _ = choose(machine)
    rows, results = [], {}
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
            rows.append({"model": model, "exact": model == exact, "j_required": None, "achieved_delta": None,
                         "j_error": None, "note": f"not applicable: {err}"})
    reference = results.get(exact) or results.get(chosen)
    for model, res in results.items():
        j = res.j_required
        delta = machine.delta if model == exact else None
        note = res.note
        if model != exact:
            try:
                delta = achieved_delta(machine, max(j, 0.0))
            except (SolverFailed, NonPeriodicCycle, ValueError) as err:
                note = f"{note}; its δ could not be simulated: {err}".lstrip("; ")
        error = None
        if reference is not None and reference.j_required > 0:
            error = (j - reference.j_required) / reference.j_required
        rows.append({"model": model, "exact": model == exact, "j_required": j, "achieved_delta": delta,
                     "j_error": error, "note": note})
    rows.sort(key=lambda r: ORDER.index(r["model"]))
    return rows


# -- internals -------------------------------------------------------------------


def _unknown(curve):
    return isinstance(curve, Constant) and curve.unknown


def _frozen(curve, omega):
    """An angle-only version of a curve: motors become the balancing unknown, ω held elsewhere."""
    if type(curve).__name__ == "MotorTorque":
        return Constant(None)
    if getattr(curve, "speed_dependent", False):
        return curve.at_speed(omega)
    return curve


def _casadi(curve, phi, omega):
    if getattr(curve, "speed_dependent", False):
        return curve.casadi(phi, omega)
    return curve.casadi(phi)
