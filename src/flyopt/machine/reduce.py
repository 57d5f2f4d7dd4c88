"""The machine reduced to the reference shaft: the stage between the scene and the sizing models.

A scene's torques, its constant inertia J_c and its members (links whose
inertia and loads vary with the angle) become one :class:`Machine`: the
equivalent inertia J_e(φ) = J_c + J_v(φ) and the driving and resisting
torques at the reference shaft, the members' loads joined into the side that
is known (docs/flywheel-design.md, sections 5–7).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.torque import Constant, MotorTorque, TorqueSum
from flyopt.errors import SceneError
from flyopt.machine.motor import DCMotor, InductionMotor, TableMotor

T = TypeVar("T")

#: Angles of the grid on which the net torque's peaks are looked for (every knot is added).
NET_TORQUE_GRID = 4097


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

    # torque curves (flyopt.cycle.torque's, or an EquivalentTorque): duck-typed, no common base class
    driving: Any
    resisting: Any
    # a float, or an EquivalentInertia when ``variable_inertia``
    j_machine: Any
    cycle_angle: float
    omega_mean: float
    delta: float
    speed_dependent: bool
    variable_inertia: bool
    _cache: dict[Hashable, Any] = field(default_factory=dict, compare=False, repr=False)

    def memo(self, key: Hashable, build: Callable[[], T]) -> T:
        """``build()`` once per machine and ``key``, kept with the machine (and with its copy at another δ,
        :func:`flyopt.analysis.analyse` ``like=``): what the stages above compute from the machine alone,
        such as the textbook method's indicator or the drive relaxation's NLP."""
        if key not in self._cache:
            self._cache[key] = build()
        return cast(T, self._cache[key])

    def with_delta(self, delta: float) -> Machine:
        """The same machine at another allowed δ, sharing everything computed from it (nothing of it depends on δ)."""
        return dataclasses.replace(self, delta=delta, _cache=self._cache)

    def angle_only(self, omega: float | None = None) -> ExcessWork:
        """ExcessWork of the torques with every speed dependence frozen.

        A motor becomes the constant that balances the cycle (its mean
        torque in steady running); an expression in ``omega`` is taken at
        ``omega`` (default: the scene's mean speed).
        """
        omega = self.omega_mean if omega is None else float(omega)
        key = ("angle_only", omega)
        if key not in self._cache:  # built once: its knot integrals may cost many quadratures
            self._cache[key] = ExcessWork(
                _frozen(self.driving, omega), _frozen(self.resisting, omega), self.cycle_angle
            )
        return self._cache[key]

    def net_torque(self) -> NetTorque:
        """M_d − M_r at the reference shaft, as the periodic model takes it (:class:`NetTorque`).

        An unknown constant is first solved from the work balance (at the
        mean speed when another torque depends on speed). Built once per
        machine: the periodic model's CasADi functions are cached on this
        object (flyopt.sizing.periodic_model.periodic_model), so every model run
        on the machine shares them.
        """
        if "net_torque" not in self._cache:
            balanced = self.angle_only()
            driving = balanced.driving if _unknown(self.driving) else self.driving
            resisting = balanced.resisting if _unknown(self.resisting) else self.resisting
            phi = np.linspace(0.0, self.cycle_angle, 4097)
            work = self.cycle_angle * float(np.mean(np.abs(balanced.driving.limits(phi)[1])))
            self._cache["net_torque"] = NetTorque(
                driving,
                resisting,
                work,
                balanced=self.speed_dependent and (_unknown(self.driving) or _unknown(self.resisting)),
            )
        return self._cache["net_torque"]

    def net_torque_grid(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """(φ, M_d − M_r just before φ, just after φ) at the reference shaft [rad, N*m, N*m]: on
        :data:`NET_TORQUE_GRID` angles and every knot, both sides of a step, with every speed dependence
        frozen at the mean speed (:meth:`angle_only`). Where the net torque's peaks are looked for: the
        flywheel's peak torque, the largest acceleration of a wheel that exists."""
        balanced = self.angle_only()
        phi = np.union1d(np.linspace(0.0, self.cycle_angle, NET_TORQUE_GRID), np.asarray(balanced.knots, dtype=float))
        driving, resisting = balanced.driving.limits(phi), balanced.resisting.limits(phi)
        return phi, driving[0] - resisting[0], driving[1] - resisting[1]

    def knots(self) -> NDArray[np.float64]:
        """Angles where a torque steps or kinks [rad] (the simulation cuts there).

        The kinks of a speed-dependent expression are those at the mean speed
        (the angle-only torques): with the speed free they move a little, and
        a cut there is merely one more step of the integrator.
        """
        return self.angle_only().knots

    def j_mean(self) -> float:
        """Cycle mean of J_e [kg*m^2] (J_c for a constant inertia)."""
        if not self.variable_inertia:
            return float(self.j_machine)
        phi = np.linspace(0.0, self.cycle_angle, 4097)
        return float(np.mean(self.j_machine(phi[:-1])))


class NetTorque:
    """The net torque M_d − M_r at the reference shaft [N*m], split for the periodic model.

    Calling it, ``net(phi, omega)``, gives the whole net torque for CasADi
    symbols. The periodic model (flyopt.sizing.periodic) takes it apart:

    - ``table``: the part that depends on the angle only and is piecewise
      linear (tables and constants, with their signs). Linear between its
      breakpoints, it enters each integration piece as the two values at the
      piece's ends, so a table of n points costs O(n), not O(n) per step;
    - ``rest(phi, omega)``: every other part (expressions, motors, members'
      loads), for CasADi.

    Parameters
    ----------
    driving, resisting : torque curves
        The torques, an unknown constant already balanced [N*m].
    work : float
        The work of the torques over a cycle, ∫|M_d| dφ [J]: the scale of
        the work balance's tolerance (the difference of two balanced torques
        is round-off, and cannot say how large the torques are).
    balanced : bool
        An unknown constant torque balances the cycle while another torque
        depends on speed: the scene's mean speed then holds, and the
        constant follows from the periodic steady state (only a motor's
        characteristic sets the mean speed).
    """

    def __init__(self, driving: Any, resisting: Any, work: float, balanced: bool = False) -> None:
        self.work = float(work)
        self.balanced = bool(balanced)
        parts = [(1.0, p) for p in _parts(driving)] + [(-1.0, p) for p in _parts(resisting)]
        linear = [p.is_linear and not getattr(p, "speed_dependent", False) for _, p in parts]
        self.table = LinearTable([part for part, flag in zip(parts, linear) if flag])
        self._rest = [part for part, flag in zip(parts, linear) if not flag]

    def rest(self, phi: Any, omega: Any) -> Any:
        """The parts that are not tables, as a CasADi expression [N*m]."""
        total = 0.0
        for sign, part in self._rest:
            total = total + sign * _casadi(part, phi, omega)
        return total

    def __call__(self, phi: Any, omega: Any) -> Any:
        return self.table.casadi(phi) + self.rest(phi, omega)


class LinearTable:
    """A signed sum of piecewise-linear torques of the angle (tables and constants) [N*m].

    Parameters
    ----------
    parts : list of (sign, curve)
        Curves with ``limits(phi)``, ``breakpoints()`` and ``casadi(phi)``.
    """

    def __init__(self, parts: list[tuple[float, Any]]) -> None:
        self.parts = list(parts)

    def breakpoints(self) -> NDArray[np.float64]:
        """Angles where the sum kinks or steps [rad]."""
        points = [np.asarray(p.breakpoints(), dtype=float) for _, p in self.parts]
        return np.unique(np.concatenate(points)) if points else np.empty(0)

    def limits(self, phi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Left and right limits at the angles ``phi`` [N*m]."""
        phi = np.asarray(phi, dtype=float)
        left, right = np.zeros(phi.shape), np.zeros(phi.shape)
        for sign, part in self.parts:
            lp, rp = part.limits(phi)
            left, right = left + sign * np.asarray(lp, dtype=float), right + sign * np.asarray(rp, dtype=float)
        return left, right

    def casadi(self, phi: Any) -> Any:
        total = 0.0
        for sign, part in self.parts:
            total = total + sign * part.casadi(phi)
        return total


def reduce(scene: Any) -> Machine:
    """Reduce a scene (torques, J_c, members) to a :class:`Machine`.

    ``scene`` is a :class:`flyopt.io.scene.Scene`, typed ``Any`` because naming it would
    make machine and io import each other (tests/test_package.py forbids the cycle).
    """
    scene.require_cycle()  # a calculation's scene has no torques (its members' loads are reduced at one position)
    driving, resisting = scene.driving, scene.resisting
    j_machine: Any = scene.j_constant  # a float, or an EquivalentInertia below
    if scene.members:
        from flyopt.machine.mechanism import equivalent_inertia, equivalent_torque  # CasADi: only with members

        j_machine = equivalent_inertia(scene.members, scene.j_constant)
        if j_machine.is_constant:
            j_machine = float(j_machine(np.array([0.0]))[0])
        if any(m.force is not None or m.torque is not None for m in scene.members):
            loads = equivalent_torque(scene.members)  # positive drives
            if _unknown(resisting):
                driving = TorqueSum([driving, loads], "torque.driving + members")
            else:
                resisting = TorqueSum([resisting, loads.resisting()], "torque.resisting + members")
    speed = any(getattr(c, "speed_dependent", False) for c in (driving, resisting))
    if (
        speed
        and (_unknown(driving) or _unknown(resisting))
        and any(isinstance(c, MotorTorque) for c in (driving, resisting))
    ):
        raise SceneError("torque.resisting", "with a motor driving, the load must be given (not an unknown constant)")
    machine = Machine(
        driving=driving,
        resisting=resisting,
        j_machine=j_machine,
        cycle_angle=scene.cycle_angle,
        omega_mean=scene.omega_mean,
        delta=scene.delta,
        speed_dependent=speed,
        variable_inertia=not isinstance(j_machine, (int, float)),
    )
    _check_drive(machine)
    return machine


def _check_drive(machine: Machine) -> None:
    """Refuse a motor whose largest torque is below the mean load: it cannot run steadily at any speed.

    The largest torque on the reference shaft is the breakdown torque of an
    induction motor (the stall torque of a DC motor, the largest torque of a
    motor's table) times i η
    (docs/flywheel-design.md, sections 3 and 7); the mean load is the work
    balance's constant (flyopt.cycle.indicator), at the scene's speed and,
    for a load that depends on speed, the least of it up to the motor's
    no-load speed.

    Raises
    ------
    SceneError
        Field ``torque.driving``: the scene asks for something no periodic
        solution can give, which is an error of the input, not of a solver.
    """
    curve = machine.driving
    if not isinstance(curve, MotorTorque):
        return
    motor: Any = curve.motor
    gain = curve.speed_ratio * curve.efficiency
    if isinstance(motor, InductionMotor):
        largest, what, no_load = motor.breakdown_torque * gain, "breakdown", motor.synchronous_speed
    elif isinstance(motor, TableMotor):
        largest, what, no_load = motor.largest_torque * gain, "the largest of its table", motor.no_load_speed
    else:  # the third kind of motor a MotorTorque holds (flyopt.cycle.torque types it loosely)
        dc = cast(DCMotor, motor)
        largest, what, no_load = dc.stall_torque * gain, "stall", dc.no_load_speed
    speeds = [machine.omega_mean]
    if getattr(machine.resisting, "speed_dependent", False):
        speeds += list(np.linspace(0.0, no_load / curve.speed_ratio, 17)[1:])
    load = min(cast(Constant, machine.angle_only(w).driving).known() for w in speeds)  # a motor's is a Constant
    if largest < load:
        raise SceneError(
            "torque.driving",
            f"the motor's largest torque on the reference shaft, {largest:.6g} N*m "
            f"({what}), is below the mean load {load:.6g} N*m: no steady running",
        )


# -- internals -------------------------------------------------------------------


def _parts(curve):
    """The curves a torque is the sum of (a TorqueSum taken apart, recursively)."""
    if isinstance(curve, TorqueSum):
        return [q for p in curve.parts for q in _parts(p)]
    return [curve]


def _unknown(curve):
    return isinstance(curve, Constant) and curve.unknown


def _frozen(curve, omega):
    """An angle-only version of a curve: motors become the balancing unknown, ω held elsewhere."""
    if isinstance(curve, MotorTorque):
        return Constant(None)
    if getattr(curve, "speed_dependent", False):
        return curve.at_speed(omega)
    return curve


def _casadi(curve, phi, omega):
    if getattr(curve, "speed_dependent", False):
        return curve.casadi(phi, omega)
    return curve.casadi(phi)
