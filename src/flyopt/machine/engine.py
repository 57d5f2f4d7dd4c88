"""Engines from indicator data: one exact slider-crank per cylinder, the gas force as a table.

An [engine] section of a scene (flyopt.io.scene) becomes an :class:`Engine`:
its cylinders, their firing angles, the crank train's dimensions and masses,
and the absolute cylinder pressure of one cylinder over its cycle (the
indicator diagram over the crank angle). The engine is then nothing but
members of the machine (flyopt.machine.mechanism): per cylinder a piston
(the reciprocating mass, a slider of the cylinder's slider-crank) that
carries the net gas force as a force table over the crank angle, and, when
given, the rest of its connecting rod. The reduction to the reference shaft
(docs/flywheel-design.md, section 3) then gives the gas torque and the
equivalent inertia J_e(φ) with exact kinematics, and the energy–mass method
(section 6) sizes the flywheel with the variable inertia: the inertia forces
of the reciprocating masses need no separate treatment.

Conventions (docs/flywheel-design.md, "Engines from indicator data"):

- φ is the crankshaft angle [rad], positive in the sense of rotation; φ = 0
  is the top dead centre at which a cylinder of firing angle 0 starts its
  cycle, and the pressure table's angle 0 is that top dead centre (for a
  four-stroke engine the start of the intake stroke, so that combustion
  follows the top dead centre at 360°);
- cylinder i starts its cycle at φ = θ_i (its firing angle, 0 <= θ_i < Φ):
  its own crank angle is ψ_i = φ − θ_i, its kinematics repeat every 360°,
  its pressure every cycle angle Φ (720° four-stroke, 360° two-stroke);
- top dead centre is the slider-crank's outer dead centre (the piston
  farthest from the crankshaft); the gas pushes the piston towards the
  crankshaft, so its force along the slider axis (+ away from the crank) is
  F = −(p − p_crankcase) π d²/4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flyopt.cycle.torque import PiecewiseLinear
from flyopt.machine.kinematics import SliderCrank
from flyopt.machine.mechanism import EquivalentInertia, Member, equivalent_inertia, equivalent_torque

if TYPE_CHECKING:
    from flyopt.machine.reduce import Machine

CYCLE_ANGLES = {"4-stroke": 4 * math.pi, "2-stroke": 2 * math.pi}
"""Cycle angle Φ of each kind of engine [rad]: two crank turns per cycle, or one."""

MAX_CYLINDERS = 64
"""Most cylinders an engine may have (the largest piston engines built have 56)."""

STANDARD_ATMOSPHERE = 101325.0
"""Crankcase pressure when none is given [Pa] (ISO 2533 standard atmosphere)."""


@dataclass(frozen=True, eq=False)
class Engine:
    """A reciprocating engine: cylinders on one crankshaft, each a slider-crank.

    Parameters
    ----------
    cycle : {"4-stroke", "2-stroke"}
        Sets the cycle angle Φ (720° or 360°).
    firing_angles : tuple of float
        θ_i, the crank angle at which cylinder i starts its cycle [rad],
        0 <= θ_i < Φ; one per cylinder.
    bore : float
        Cylinder bore d [m].
    stroke : float
        Piston stroke [m]; the crank radius is r = stroke/2.
    rod : float
        Connecting-rod length l, centre to centre [m]; l > r.
    reciprocating_mass : float
        Per cylinder: piston, pin, rings and the rod's small-end share [kg].
    pressure : PiecewiseLinear
        Absolute cylinder pressure of one cylinder over its cycle [Pa], from
        angle 0 (top dead centre at the cycle's start) to Φ [rad]; >= 0.
    crankcase_pressure : float
        Pressure under the piston [Pa] (default: the standard atmosphere).
    rod_mass : float
        Per cylinder, the rest of the connecting rod [kg] (0: none).
    rod_centre : float
        Its centre of mass, from the crank pin along the rod [m], 0..l.
    rod_inertia : float
        Its moment of inertia about that centre [kg*m^2].

    Raises
    ------
    ValueError
        A value outside what is allowed (scene files check each field first
        and name it; this is the check for callers from Python).
    """

    cycle: str
    firing_angles: tuple[float, ...]
    bore: float
    stroke: float
    rod: float
    reciprocating_mass: float
    pressure: PiecewiseLinear
    crankcase_pressure: float = STANDARD_ATMOSPHERE
    rod_mass: float = 0.0
    rod_centre: float = 0.0
    rod_inertia: float = 0.0

    def __post_init__(self) -> None:
        if self.cycle not in CYCLE_ANGLES:
            raise ValueError(f"engine cycle {self.cycle!r} is not known (allowed: {', '.join(CYCLE_ANGLES)})")
        cycle = CYCLE_ANGLES[self.cycle]
        angles = tuple(float(a) for a in self.firing_angles)
        if not 1 <= len(angles) <= MAX_CYLINDERS:
            raise ValueError(f"an engine has 1 to {MAX_CYLINDERS} cylinders, got {len(angles)} firing angles")
        for k, a in enumerate(angles):
            if not (math.isfinite(a) and 0.0 <= a < cycle):
                raise ValueError(
                    f"firing angle {k + 1} is {a!r} rad: it must lie in [0, {cycle!r}) rad, within the cycle"
                )
        object.__setattr__(self, "firing_angles", angles)
        for name in ("bore", "stroke", "rod"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"engine {name} must be a positive length [m], got {value!r}")
        if not self.rod > self.crank:
            raise ValueError(
                f"the connecting rod ({self.rod!r} m) must be longer than the crank radius stroke/2 = {self.crank!r} m"
            )
        for name in ("reciprocating_mass", "rod_mass", "rod_inertia", "crankcase_pressure"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ValueError(f"engine {name} must be a finite number >= 0, got {value!r}")
        if not 0.0 <= self.rod_centre <= self.rod:
            raise ValueError(
                f"the rod's centre of mass must lie between the pins, 0..{self.rod!r} m from the "
                f"crank pin, got {self.rod_centre!r}"
            )
        x, p = np.asarray(self.pressure.angles), np.asarray(self.pressure.values)
        if x[0] != 0.0 or x[-1] != cycle:
            raise ValueError(
                f"the pressure table must span the cycle, 0 to {cycle!r} rad; it spans {x[0]!r} to {x[-1]!r}"
            )
        if np.any(p < 0) or not np.all(np.isfinite(p)):
            raise ValueError("the pressure table holds absolute pressures: each must be finite and >= 0 [Pa]")

    # -- geometry -------------------------------------------------------------------------

    @property
    def cycle_angle(self) -> float:
        """Φ [rad]: 4π for a four-stroke engine, 2π for a two-stroke one."""
        return CYCLE_ANGLES[self.cycle]

    @property
    def crank(self) -> float:
        """Crank radius r = stroke/2 [m]."""
        return 0.5 * self.stroke

    @property
    def piston_area(self) -> float:
        """π d²/4 [m^2]."""
        return math.pi * self.bore**2 / 4.0

    @property
    def cylinder_count(self) -> int:
        return len(self.firing_angles)

    @cached_property
    def cylinders(self) -> tuple[SliderCrank, ...]:
        """One :class:`SliderCrank` per cylinder, phased by its firing angle (its outer dead centre at θ_i)."""
        return tuple(SliderCrank(self.crank, self.rod, 0.0, theta % (2 * math.pi)) for theta in self.firing_angles)

    # -- the gas force ----------------------------------------------------------------------

    def gas_force(self, cylinder: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Net gas force on the piston of one cylinder along the slider axis, as a table over φ.

        F_i(φ) = −(p(φ − θ_i) − p_crankcase) π d²/4, the pressure table
        shifted by the firing angle θ_i and wrapped over the cycle (positive
        along +x, away from the crank: the gas pushes towards it).

        Parameters
        ----------
        cylinder : int
            0-based index.

        Returns
        -------
        angles, values : ndarray
            The table over [0, Φ] [rad], [N]; a step is two rows at one angle.
        """
        angles, pressures = phase_table(self.pressure, self.firing_angles[cylinder], self.cycle_angle)
        return angles, -(pressures - self.crankcase_pressure) * self.piston_area

    # -- the members and what they reduce to -------------------------------------------------

    @cached_property
    def members(self) -> tuple[Member, ...]:
        """The engine as members of the machine: per cylinder its piston and, when given, the rest of its rod.

        The piston (``cylinder i piston``) is the slider of cylinder i with
        the reciprocating mass and the gas force (force_sense "axial"); the
        rod (``cylinder i rod``) has ``rod_mass`` and ``rod_inertia`` at
        ``rod_centre`` from the crank pin (flyopt.machine.mechanism).
        """
        members = []
        for k, cylinder in enumerate(self.cylinders):
            piston = cylinder.kinematics("slider")
            members.append(
                Member(
                    f"cylinder {k + 1} piston",
                    self.reciprocating_mass,
                    0.0,
                    piston.velocity_ratio,
                    piston.angular_ratio,
                    self.gas_force(k),
                    "axial",
                    owner=self,
                )
            )
            if self.rod_mass > 0 or self.rod_inertia > 0:
                rod = cylinder.kinematics("rod", self.rod_centre)
                members.append(
                    Member(
                        f"cylinder {k + 1} rod",
                        self.rod_mass,
                        self.rod_inertia,
                        rod.velocity_ratio,
                        rod.angular_ratio,
                        owner=self,
                    )
                )
        return tuple(members)

    @cached_property
    def _torque(self):
        return equivalent_torque(self.members)

    @cached_property
    def _inertia(self):
        return equivalent_inertia(self.members)

    def gas_torque(self, phi: ArrayLike) -> NDArray[np.float64]:
        """The gas forces' torque on the crankshaft [N*m] (positive drives; right limits at a step).

        Σ_i F_i(φ) (v_Bi/ω)(φ), exact kinematics (docs/flywheel-design.md, section 3).
        """
        return self._torque(phi)

    def inertia(self, phi: ArrayLike) -> NDArray[np.float64]:
        """The crank train's equivalent inertia at the crankshaft, without J_c [kg*m^2]."""
        return self._inertia(phi)

    def inertia_torque(self, phi: ArrayLike, omega: float) -> NDArray[np.float64]:
        """The torque of the moving masses at the constant speed ω: −½ J_e'(φ) ω² [N*m].

        From d(½ J_e ω²)/dφ = M with ω constant. For a reciprocating mass
        alone it is −m a_B (v_B/ω), the inertia force times the velocity
        ratio, with the exact piston acceleration a_B = ω² d(v_B/ω)/dφ.
        """
        return -0.5 * float(omega) ** 2 * self._inertia.derivative(phi)

    def crank_effort(self, phi: ArrayLike, omega: float) -> NDArray[np.float64]:
        """Gas torque plus inertia torque at the constant speed ω [N*m]: the textbook's turning moment."""
        return self.gas_torque(phi) + self.inertia_torque(phi, omega)


def phase_table(table: PiecewiseLinear, shift: float, cycle: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A periodic table over [0, Φ] moved later by ``shift``: g(φ) = f(φ − shift), wrapped.

    Parameters
    ----------
    table : PiecewiseLinear
        f over [0, Φ] (Φ = ``cycle``); a step is two rows at one angle.
    shift : float
        [rad], 0 <= shift < Φ.
    cycle : float
        Φ [rad].

    Returns
    -------
    angles, values : ndarray
        g's rows: f's rows from Φ − shift to Φ moved to 0..shift, then those
        from 0 to Φ − shift moved to shift..Φ. Where f(Φ) differs from f(0)
        g steps at ``shift``; where f steps at Φ − shift, g steps at 0 and Φ
        (its first and last values are f's right and left limits there).
    """
    x, y = np.asarray(table.angles, dtype=float), np.asarray(table.values, dtype=float)
    if shift == 0.0:
        return x.copy(), y.copy()
    cut = cycle - shift
    left, right = (float(v[0]) for v in table.limits(np.array([cut])))
    later, earlier = x > cut, x < cut
    angles = np.concatenate(([0.0], np.minimum(x[later] - cut, shift), np.maximum(x[earlier] + shift, shift), [cycle]))
    values = np.concatenate(([right], y[later], y[earlier], [left]))
    angles = np.minimum(np.maximum.accumulate(angles), cycle)
    # a run of rows at one angle keeps its first (left limit) and last (right limit) row
    first = np.concatenate(([True], angles[1:] != angles[:-1]))
    last = np.concatenate((angles[1:] != angles[:-1], [True]))
    keep = first | last
    return angles[keep], values[keep]


# -- the textbook method ----------------------------------------------------------------------


class InertiaTorque:
    """−½ J_e'(φ) ω² at a constant speed ω: the inertia torque of a machine's varying inertia [N*m].

    A torque curve (the questions of flyopt.cycle.torque: ``breakpoints``,
    ``limits``, ``__call__``, ``casadi``) that drives the reference shaft
    where J_e falls. Its work over a cycle is zero (J_e is periodic).

    Parameters
    ----------
    inertia : flyopt.machine.mechanism.EquivalentInertia
        J_e(φ) [kg*m^2].
    omega : float
        The constant speed [rad/s].
    """

    is_linear = False
    speed_dependent = False

    def __init__(
        self, inertia: EquivalentInertia, omega: float, where: str = "inertia torque at the mean speed"
    ) -> None:
        self.inertia, self.omega, self.where = inertia, float(omega), where

    def breakpoints(self) -> NDArray[np.float64]:
        """Angles where J_e kinks (a table of a velocity ratio) [rad]."""
        return self.inertia.knots

    def __call__(self, phi: ArrayLike) -> NDArray[np.float64]:
        return -0.5 * self.omega**2 * self.inertia.derivative(np.asarray(phi, dtype=float))

    def limits(self, phi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Left and right limits [N*m]: they differ only at a kink of J_e (the slope of a table's pieces)."""
        phi = np.asarray(phi, dtype=float)
        right = self(phi)
        at = np.isin(phi, self.inertia.knots)
        if not at.any():
            return right, right
        return self(np.where(at, np.nextafter(phi, -np.inf), phi)), right

    def casadi(self, phi: Any) -> Any:
        return -0.5 * self.omega**2 * self.inertia.casadi_derivative(phi)


def engine_of(machine: Machine) -> Engine | None:
    """The :class:`Engine` whose pistons and rods are members of the machine, or None."""
    members = list(getattr(machine.j_machine, "members", ()))
    curves = [machine.driving, machine.resisting]
    while curves:
        curve = curves.pop()
        curves += list(getattr(curve, "parts", ()))
        members += list(getattr(curve, "members", ()))
    return next((m.owner for m in members if isinstance(m.owner, Engine)), None)
