"""Reduction of a real mechanism to the reference shaft: the members and J_e(φ), M_e(φ).

The machine's members are replaced by one shaft (angle φ, speed ω) with the
same kinetic energy and the same instantaneous power (docs/flywheel-design.md, section 3):

    J_e(φ) = J_c + Σ_i [ J_Si (ω_i/ω)² + m_i (v_Si/ω)² ],
    M_e(φ) = Σ_i [ T_i (ω_i/ω) + F_i (v_i/ω) cos α_i ].

Both need only the velocity *ratios* v_S/ω [m/rad] and ω_i/ω [-], which a
member takes as numbers, tables or functions of φ (those of the slider-crank
and the gear train are in :mod:`flyopt.machine.kinematics`, those of the
guide-bar, the four-bar and the cam in :mod:`flyopt.machine.linkages`). Every function
here accepts a numpy array **or** a CasADi SX/MX symbol and returns the same
kind, so one definition serves the numpy analysis and the CasADi models.

Sign convention of the equivalent torque: positive drives the reference
shaft (acts in its sense of rotation), negative resists it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import casadi as ca
import numpy as np
from numpy.typing import ArrayLike, NDArray

from flyopt.cycle.torque import PiecewiseLinear
from flyopt.machine.kinematics import ClosedFormRatio, StateCache, is_casadi, known_ratio

FORCE_SENSES = ("resisting", "driving", "axial")
"""How a member's force (or torque) does work:

- ``"resisting"``: it always opposes the motion of its point: power −F|v|;
- ``"driving"``: it always acts along the motion: power +F|v|;
- ``"axial"``: it acts along the fixed axis on which the (scalar, signed)
  velocity ratio is measured: power F·v, F positive along +axis.
"""


class _Curve:
    """A quantity over the crank angle: a constant, a table or a function.

    Tables are ``(angles, values)`` pairs (or a :class:`PiecewiseLinear`),
    linear between points, ends held. Functions map φ to a value (or a pair
    (x, y) for a planar velocity ratio) and must work on numpy arrays and
    CasADi symbols alike.
    """

    def __init__(self, value, what, steps_allowed):
        self.what = what
        self.kind = None
        if value is None:
            value = 0.0
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if not math.isfinite(value):
                raise ValueError(f"{what} must be finite, got {value!r}")
            self.kind, self.value = "constant", float(value)
        elif isinstance(value, PiecewiseLinear):
            self.kind, self.table = "table", value
        elif isinstance(value, (tuple, list)) and len(value) == 2 and not callable(value[0]):
            angles = np.asarray(value[0], dtype=float)
            values = np.asarray(value[1], dtype=float)
            if angles.ndim != 1 or angles.shape != values.shape or len(angles) < 2:
                raise ValueError(f"{what} table needs two equal-length lists of at least 2 angles [rad] and values")
            if not (np.all(np.isfinite(angles)) and np.all(np.isfinite(values))):
                raise ValueError(f"{what} table has non-finite entries")
            if np.any(np.diff(angles) < 0):
                raise ValueError(f"{what} table angles must be non-decreasing")
            self.kind, self.table = "table", PiecewiseLinear(angles, values)
        elif callable(value):
            self.kind, self.function = "function", known_ratio(value) or value
        else:
            raise ValueError(f"{what} must be a number, a table (angles, values) or a function of phi, got {value!r}")
        if self.kind == "table" and not steps_allowed and np.any(np.diff(self.table.angles) == 0):
            raise ValueError(f"{what} table has a step (two points at one angle): a velocity ratio cannot jump")

    @property
    def is_constant(self):
        return self.kind == "constant"

    def breakpoints(self):
        return self.table.breakpoints() if self.kind == "table" else np.empty(0)

    def numpy(self, phi, side="right", cache=None):
        phi = np.asarray(phi, dtype=float)
        if self.kind == "constant":
            return np.full(phi.shape, self.value)
        if self.kind == "table":
            left, right = self.table.limits(phi)
            return right if side == "right" else left
        if isinstance(self.function, ClosedFormRatio):
            return self.function.numpy(phi, cache)
        out = self.function(phi)
        if isinstance(out, tuple):
            return tuple(np.broadcast_to(np.asarray(o, dtype=float), phi.shape) for o in out)
        return np.broadcast_to(np.asarray(out, dtype=float), phi.shape)

    def both_sides(self, phi, cache=None):
        """Left and right limits at ``phi`` in one evaluation (a table's steps; otherwise the same array)."""
        if self.kind == "table":
            return self.table.limits(np.asarray(phi, dtype=float))
        value = self.numpy(phi, cache=cache)
        return value, value

    @property
    def has_slope(self):
        """Whether :meth:`slope` is available (constants, tables, a linkage's closed-form ratios)."""
        return self.kind != "function" or isinstance(self.function, ClosedFormRatio)

    def slope(self, phi, cache=None):
        """d/dφ at ``phi`` (numpy): 0 for a constant, the piece's slope for a table (the right
        one at a point), the closed form for a linkage's ratio (:class:`ClosedFormRatio`)."""
        phi = np.asarray(phi, dtype=float)
        if self.kind == "constant":
            return np.zeros(phi.shape)
        if self.kind == "table":
            x, y = self.table.angles, self.table.values
            k = np.searchsorted(x, phi, side="right") - 1
            inside = (k >= 0) & (k < len(x) - 1)
            k = np.clip(k, 0, len(x) - 2)
            h = x[k + 1] - x[k]
            return np.where(inside & (h > 0), (y[k + 1] - y[k]) / np.where(h > 0, h, 1.0), 0.0)
        if isinstance(self.function, ClosedFormRatio):
            return self.function.slope(phi, cache)
        raise ValueError(f"{self.what}: the derivative of a function is taken by CasADi, not here")

    def casadi(self, phi):
        if self.kind == "constant":
            return self.value
        if self.kind == "table":
            return self.table.casadi(phi)
        return self.function(phi)


def _square(v):
    return v[0] * v[0] + v[1] * v[1] if isinstance(v, tuple) else v * v


def _magnitude(v, lib):
    if isinstance(v, tuple):
        return lib.sqrt(v[0] * v[0] + v[1] * v[1])
    return lib.fabs(v) if lib is ca else np.abs(v)


@dataclass(frozen=True, eq=False)
class Member:
    """One member of the machine, described for the reduction.

    Parameters
    ----------
    name : str
    mass : float
        m [kg].
    inertia : float
        J_S about the centre of mass [kg*m^2].
    velocity_ratio : float, table, or callable
        v_S/ω of the centre of mass [m/rad]: a number, a table
        ``(angles [rad], values [m/rad])``, or a function of φ returning a
        scalar (signed along a fixed axis) or a pair (v_x/ω, v_y/ω) — e.g.
        from :meth:`flyopt.machine.kinematics.SliderCrank.kinematics`.
    angular_ratio : float, table, or callable
        ω_member/ω [-].
    force : float, table, or callable, optional
        A force on the member at its centre [N]; may step (two table points
        at one angle).
    force_sense : {"resisting", "driving", "axial"}
        How the force does work (see :data:`FORCE_SENSES`): "resisting"
        (default) opposes the motion, power −F|v|; "driving" follows it,
        power +F|v|; "axial" acts along the axis of a signed scalar velocity
        ratio, power F·v.
    torque : float, table, or callable, optional
        A moment on the member [N*m], doing work with ω_member in the same
        ``force_sense``.
    owner : object, optional
        What the member was made from, when a scene section makes members
        (an [engine]'s :class:`flyopt.machine.engine.Engine` owns its pistons
        and rods), so that a report can name the machine. It takes no part
        in the reduction.
    """

    name: str
    mass: float = 0.0
    inertia: float = 0.0
    velocity_ratio: Any = 0.0  # a number, a table (angles, values) or a function of φ
    angular_ratio: Any = 0.0
    force: Any = None
    force_sense: str = "resisting"
    torque: Any = None
    owner: object = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"a member needs a non-empty name, got {self.name!r}")
        for what in ("mass", "inertia"):
            value = getattr(self, what)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ValueError(f"member {self.name!r}: {what} must be a finite number >= 0, got {value!r}")
        if self.force_sense not in FORCE_SENSES:
            raise ValueError(
                f"member {self.name!r}: force_sense {self.force_sense!r} is not known "
                f"(allowed: {', '.join(FORCE_SENSES)})"
            )

    @cached_property
    def _curves(self):
        where = f"member {self.name!r}: "
        return {
            "v": _Curve(self.velocity_ratio, where + "velocity_ratio", steps_allowed=False),
            "w": _Curve(self.angular_ratio, where + "angular_ratio", steps_allowed=False),
            "f": _Curve(self.force, where + "force", steps_allowed=True),
            "t": _Curve(self.torque, where + "torque", steps_allowed=True),
        }

    def ratios(self, phi: ArrayLike) -> tuple[Any, Any]:
        """v_S/ω and ω_i/ω at ``phi`` (numpy), as the reduction evaluates them: v_S/ω a scalar (signed along a
        fixed axis) or a pair (v_x/ω, v_y/ω) [m/rad], ω_i/ω [-] (what flyopt.machine.equivalents reports)."""
        c = self._curves
        phi = np.asarray(phi, dtype=float)
        return c["v"].numpy(phi), c["w"].numpy(phi)

    def inertia_contribution(self, phi: Any, cache: StateCache | None = None) -> Any:
        """J_S (ω_i/ω)² + m (v_S/ω)² at ``phi`` [kg*m^2] (numpy or CasADi).

        ``cache`` shares a mechanism's trigonometry between the members of
        one numpy evaluation (:meth:`flyopt.machine.kinematics.SliderCrank._state`).
        """
        c = self._curves
        if is_casadi(phi):
            return self.inertia * _square(c["w"].casadi(phi)) + self.mass * _square(c["v"].casadi(phi))
        return self.inertia * _square(c["w"].numpy(phi, cache=cache)) + self.mass * _square(
            c["v"].numpy(phi, cache=cache)
        )

    @property
    def has_inertia_slope(self) -> bool:
        """Whether :meth:`inertia_slope` can give d/dφ of the contribution in numpy."""
        c = self._curves
        return (self.inertia == 0 or c["w"].has_slope) and (self.mass == 0 or c["v"].has_slope)

    def inertia_slope(self, phi: NDArray[np.float64], cache: StateCache | None = None) -> NDArray[np.float64] | float:
        """d/dφ [J_S (ω_i/ω)² + m (v_S/ω)²] = 2 J_S (ω_i/ω)(ω_i/ω)' + 2 m (v_S/ω)·(v_S/ω)' [kg*m^2/rad]."""
        c = self._curves
        total = 0.0
        for coefficient, curve in ((self.inertia, c["w"]), (self.mass, c["v"])):
            if coefficient == 0 or curve.is_constant:
                continue
            v, dv = curve.numpy(phi, cache=cache), curve.slope(phi, cache)
            dot = v[0] * dv[0] + v[1] * dv[1] if isinstance(v, tuple) else v * dv
            total = total + 2.0 * coefficient * dot
        return total

    def torque_contribution(self, phi: Any, side: str = "right") -> Any:
        """Equivalent torque of the member's force and moment at ``phi`` [N*m].

        Positive drives the reference shaft. ``side`` picks the left or right
        limit where a force table steps (numpy only).
        """
        c = self._curves
        symbolic = is_casadi(phi)
        if not symbolic:
            left, right = self.torque_limits(phi)
            return right if side == "right" else left
        lib = ca
        total = 0.0
        for load, ratio in (("f", "v"), ("t", "w")):
            if c[load].is_constant and c[load].value == 0.0:
                continue
            f = c[load].casadi(phi) if symbolic else c[load].numpy(phi, side)
            v = c[ratio].casadi(phi) if symbolic else c[ratio].numpy(phi)
            if self.force_sense == "axial":
                if isinstance(v, tuple):
                    raise ValueError(
                        f"member {self.name!r}: an 'axial' force needs a scalar (signed) "
                        f"velocity ratio, not a planar one"
                    )
                total = total + f * v
            else:
                sign = 1.0 if self.force_sense == "driving" else -1.0
                total = total + sign * f * _magnitude(v, lib)
        return total

    def torque_limits(self, phi: ArrayLike, cache: StateCache | None = None) -> tuple[Any, Any]:
        """Left and right limits of :meth:`torque_contribution` at ``phi`` (numpy) [N*m].

        The velocity ratio is evaluated once for both sides, a table of
        force once for both of its limits.
        """
        c = self._curves
        phi = np.asarray(phi, dtype=float)
        left = right = 0.0
        for load, ratio in (("f", "v"), ("t", "w")):
            if c[load].is_constant and c[load].value == 0.0:
                continue
            f_left, f_right = c[load].both_sides(phi, cache)
            v = c[ratio].numpy(phi, cache=cache)
            if self.force_sense == "axial":
                if isinstance(v, tuple):
                    raise ValueError(
                        f"member {self.name!r}: an 'axial' force needs a scalar (signed) "
                        f"velocity ratio, not a planar one"
                    )
                left, right = left + f_left * v, right + f_right * v
            else:
                sign = 1.0 if self.force_sense == "driving" else -1.0
                size = _magnitude(v, np)
                left, right = left + sign * f_left * size, right + sign * f_right * size
        return left, right

    def knots(self) -> NDArray[np.float64]:
        """Angles where a table of this member breaks [rad]."""
        return np.unique(np.concatenate([c.breakpoints() for c in self._curves.values()]))

    @property
    def inertia_is_constant(self) -> bool:
        c = self._curves
        return (c["v"].is_constant or self.mass == 0) and (c["w"].is_constant or self.inertia == 0)


def _check_members(members):
    members = list(members)
    for m in members:
        if not isinstance(m, Member):
            raise ValueError(f"expected Member objects, got {m!r}")
    names = [m.name for m in members]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ValueError(f"member names must be unique; repeated: {', '.join(duplicates)}")
    return members


class EquivalentInertia:
    """J_e(φ) = J_c + Σ [J_S (ω_i/ω)² + m (v_S/ω)²] as numpy and CasADi.

    Build it with :func:`equivalent_inertia`.

    Attributes
    ----------
    members : tuple of Member
    j_constant : float
        Constant part J_c added to the members [kg*m^2].
    knots : ndarray
        Angles where a ratio table breaks (J_e kinks there) [rad].
    is_constant : bool
        True when no member's ratios depend on φ.
    """

    def __init__(self, members: Iterable[Member], j_constant: float = 0.0) -> None:
        if not (isinstance(j_constant, (int, float)) and math.isfinite(j_constant) and j_constant >= 0):
            raise ValueError(f"j_constant must be a finite number >= 0 [kg*m^2], got {j_constant!r}")
        self.members = tuple(_check_members(members))
        self.j_constant = float(j_constant)
        self.knots = np.unique(np.concatenate([m.knots() for m in self.members])) if self.members else np.empty(0)
        self.is_constant = all(m.inertia_is_constant for m in self.members)

    def __call__(self, phi: ArrayLike) -> NDArray[np.float64]:
        """J_e at the angles ``phi`` [kg*m^2] (numpy, vectorized)."""
        phi = np.asarray(phi, dtype=float)
        total = np.full(phi.shape, self.j_constant)
        cache: StateCache = {}
        for m in self.members:
            total = total + m.inertia_contribution(phi, cache)
        return total

    def casadi(self, phi: Any) -> Any:
        """J_e as a CasADi expression of ``phi`` [kg*m^2]."""
        total = self.j_constant
        for m in self.members:
            total = total + m.inertia_contribution(phi)
        return total

    def contributions(self, phi: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Each member's part of J_e at ``phi``: dict name → array [kg*m^2]."""
        phi = np.asarray(phi, dtype=float)
        return {m.name: m.inertia_contribution(phi) for m in self.members}

    @cached_property
    def _derivative_function(self):
        phi = ca.SX.sym("phi")
        j = self.casadi(phi)
        return ca.Function("dJ", [phi], [ca.jacobian(ca.SX(j), phi)])

    @cached_property
    def has_numpy_derivative(self) -> bool:
        """True when every member's ratios are constants, tables or a slider-crank's (closed-form slopes)."""
        return all(m.has_inertia_slope for m in self.members)

    def value_and_derivative(self, phi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """J_e and dJ_e/dφ at ``phi`` in one numpy evaluation [kg*m^2], [kg*m^2/rad].

        The derivative is the closed form of each ratio's slope (a table's
        slope is the right one at its points); a member given by a function
        of its own has none here, and the derivative is then CasADi's
        (:meth:`derivative`).
        """
        phi = np.asarray(phi, dtype=float)
        if not self.has_numpy_derivative:
            return self(phi), self.derivative(phi)
        total = np.full(phi.shape, self.j_constant)
        slope = np.zeros(phi.shape)
        cache: StateCache = {}
        for m in self.members:
            total = total + m.inertia_contribution(phi, cache)
            slope = slope + m.inertia_slope(phi, cache)
        return total, slope

    def casadi_derivative(self, phi: Any) -> Any:
        """dJ_e/dφ as a CasADi expression of ``phi`` [kg*m^2/rad] (algorithmic differentiation)."""
        return self._derivative_function(phi)

    def derivative(self, phi: ArrayLike) -> NDArray[np.float64]:
        """dJ_e/dφ at ``phi`` [kg*m^2/rad] (exact: closed forms, or CasADi's algorithmic differentiation)."""
        phi = np.asarray(phi, dtype=float)
        if self.has_numpy_derivative:
            slope = np.zeros(phi.shape)
            cache: StateCache = {}
            for m in self.members:
                slope = slope + m.inertia_slope(phi, cache)
            return slope
        n = phi.size
        if n == 0:
            return np.zeros(phi.shape)
        function = self._derivative_function.map(n) if n > 1 else self._derivative_function
        return np.asarray(function(phi.reshape(1, -1))).reshape(phi.shape)


class EquivalentTorque:
    """M_e(φ) = Σ [T_i (ω_i/ω) + F_i (v_i/ω) cos α_i] as numpy and CasADi.

    Build it with :func:`equivalent_torque`. Positive M_e drives the
    reference shaft; :meth:`resisting` gives the same curve with the sign of
    a resisting torque, M_r = −M_e.

    It answers the torque-curve questions of :mod:`flyopt.cycle.torque`
    (``breakpoints``, ``limits``, ``__call__``, ``casadi``), so it can enter
    :class:`flyopt.cycle.indicator.ExcessWork` directly as a driving or resisting curve.
    """

    is_linear = False

    def __init__(self, members: Iterable[Member], sign: float = 1.0, where: str = "members") -> None:
        self.members = tuple(_check_members(members))
        self.sign = float(sign)
        self.where = where

    def resisting(self) -> EquivalentTorque:
        """The same torque with the resisting sign, M_r = −M_e."""
        return EquivalentTorque(self.members, -self.sign, self.where)

    def breakpoints(self) -> NDArray[np.float64]:
        """Angles where a table of a member breaks [rad]."""
        if not self.members:
            return np.empty(0)
        return np.unique(np.concatenate([m.knots() for m in self.members]))

    def __call__(self, phi: ArrayLike) -> NDArray[np.float64]:
        """Torque at ``phi`` [N*m] (numpy; right limits where a force steps)."""
        return self.limits(phi)[1]

    def limits(self, phi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Left and right limits of the torque at ``phi`` [N*m]."""
        phi = np.asarray(phi, dtype=float)
        left = np.zeros(phi.shape)
        right = np.zeros(phi.shape)
        cache: StateCache = {}
        for m in self.members:
            lm, rm = m.torque_limits(phi, cache)
            left, right = left + lm, right + rm
        return self.sign * left, self.sign * right

    def casadi(self, phi: Any) -> Any:
        """The torque as a CasADi expression of ``phi`` [N*m] (right-continuous)."""
        total = 0.0
        for m in self.members:
            total = total + m.torque_contribution(phi)
        return self.sign * total

    def contributions(self, phi: ArrayLike) -> dict[str, Any]:
        """Each member's part at ``phi``: dict name → array [N*m]."""
        phi = np.asarray(phi, dtype=float)
        return {m.name: self.sign * m.torque_contribution(phi) for m in self.members}


def equivalent_inertia(members: Iterable[Member], j_constant: float = 0.0) -> EquivalentInertia:
    """Equivalent inertia of a machine at the reference shaft.

    J_e(φ) = J_c + Σ_i [ J_Si (ω_i/ω)² + m_i (v_Si/ω)² ]  (docs/flywheel-design.md, section 3).

    Parameters
    ----------
    members : iterable of Member
    j_constant : float
        Inertia already reduced to the reference shaft and constant, J_c
        [kg*m^2] (e.g. a motor rotor given directly).

    Returns
    -------
    EquivalentInertia
        Callable on numpy arrays, with ``.casadi(phi)`` and an exact
        ``.derivative(phi)``.
    """
    return EquivalentInertia(members, j_constant)


def equivalent_torque(members: Iterable[Member]) -> EquivalentTorque:
    """Equivalent torque of the members' forces and moments at the reference shaft.

    M_e(φ) = Σ_i [ T_i (ω_i/ω) + F_i (v_i/ω) cos α_i ]  (docs/flywheel-design.md, section 3),
    with cos α_i = −1 for a resisting force (it opposes the motion), +1 for a
    driving one, and the signed component for an axial one.

    Parameters
    ----------
    members : iterable of Member

    Returns
    -------
    EquivalentTorque
        Positive drives the reference shaft; ``.resisting()`` flips it to the
        resisting-torque sign.
    """
    return EquivalentTorque(members)
