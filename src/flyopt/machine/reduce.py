"""The machine reduced to the reference shaft: the stage between the scene and the sizing models.

A scene's torques, its constant inertia J_c and its members (links whose
inertia and loads vary with the angle) become one :class:`Machine`: the
equivalent inertia J_e(φ) = J_c + J_v(φ) and the driving and resisting
torques at the reference shaft, the members' loads joined into the side that
is known (docs/flywheel-design.md, sections 5–7).
"""

from dataclasses import dataclass, field

import numpy as np

from flyopt.cycle.indicator import ExcessWork
from flyopt.errors import SceneError
from flyopt.machine.torque import Constant, TorqueSum


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
