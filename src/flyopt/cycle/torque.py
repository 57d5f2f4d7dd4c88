"""Equivalent torque curves over one cycle of the reference shaft.

Three forms, all in SI (angle [rad], torque [N*m]):

- :class:`PiecewiseLinear`: a table of (angle, torque) points; a vertical step
  is two points at one angle. Integrated exactly.
- :class:`Constant`: one value, possibly still unknown (solved later from the
  cycle work balance).
- :class:`ExpressionTorque`: a whitelisted expression in ``phi`` [rad] times a
  unit factor; integrated by adaptive quadrature.

Each curve answers the same questions: where its breakpoints are, its left and
right limits at given angles, its value inside a segment, and (for symbolic
use) a CasADi expression.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias

import numpy as np

from flyopt.cycle.expression import Expression

if TYPE_CHECKING:  # the annotations only: the motors are on the floor above
    from flyopt.machine.motor import DCMotor, InductionMotor, TableMotor

Array: TypeAlias = np.ndarray
"""An array of floats: angles [rad] or torques [N*m]."""
Symbolic: TypeAlias = Any
"""A CasADi expression (casadi ships no type stubs) or a float where the curve is constant."""


class TorqueCurve(Protocol):
    """What every torque curve of the angle answers: the tables, constants and expressions here,
    their sums, and the machine's reduced curves (:mod:`flyopt.machine.reduce`)."""

    @property
    def is_linear(self) -> bool:
        """True when the curve is linear between its breakpoints (integrated exactly)."""
        ...

    def breakpoints(self) -> Array:
        """Angles where the value or the slope may jump [rad]."""
        ...

    def limits(self, phi: Array) -> tuple[Array, Array]:
        """Left and right limits at the angles ``phi`` [N*m]."""
        ...


@dataclass(frozen=True)
class PiecewiseLinear:
    """Piecewise-linear torque through the points ``(angles[k], values[k])``.

    Parameters
    ----------
    angles : ndarray
        Non-decreasing angles [rad] from 0 to the cycle angle; an angle that
        appears twice marks a vertical step.
    values : ndarray
        Torque at each point [N*m].
    """

    angles: np.ndarray
    values: np.ndarray
    is_linear = True

    @functools.cached_property
    def _own_limits(self) -> tuple[Array, Array, Array]:
        """(distinct angles, left limits, right limits) at the table's own points."""
        x, y = self.angles, self.values
        new = np.empty(len(x), dtype=bool)
        new[0] = True
        np.not_equal(x[1:], x[:-1], out=new[1:])
        if new.all():  # no steps: no copies
            return x, y, y
        last = np.empty(len(x), dtype=bool)
        last[-1] = True
        last[:-1] = new[1:]
        return x[new], y[new], y[last]

    @functools.cached_property
    def _no_steps(self) -> bool:
        return len(self._own_limits[0]) == len(self.angles)

    def breakpoints(self) -> Array:
        """Distinct angles where the slope or value may change [rad]."""
        return self._own_limits[0]

    @functools.cached_property
    def _work(self) -> float:
        x, y = self.angles, self.values
        return float(np.sum((y[1:] + y[:-1]) * np.diff(x))) / 2  # np.sum is pairwise: error ~ log2(n) eps

    def work(self, cycle_angle: float) -> float:
        """∫_0^Φ M dφ [J]: exact trapezoids (the table spans the cycle)."""
        return self._work

    def limits(self, phi: Array) -> tuple[Array, Array]:
        """Left and right limits of the torque at the angles ``phi`` [N*m].

        Inside a piece both equal the linear interpolation; at a vertical
        step the left limit is the first point and the right limit the last.
        Outside the table the end values are held.
        """
        x, y = self.angles, self.values
        own, left, right = self._own_limits
        if phi is own:
            return (left, left) if self._no_steps else (left, right)
        phi = np.asarray(phi, dtype=float)
        if self._no_steps:  # continuous: one array serves both sides
            values = np.interp(phi, x, y)
            return values, values
        first = np.searchsorted(x, phi, side="left")
        last = np.searchsorted(x, phi, side="right") - 1
        on_point = (first < len(x)) & (first <= last)
        # Interpolate where phi lies strictly between two points.
        k = np.clip(last, 0, len(x) - 2)
        x0, x1 = x[k], x[k + 1]
        span = np.where(x1 > x0, x1 - x0, 1.0)
        t = np.clip((phi - x0) / span, 0.0, 1.0)
        inside = y[k] + (y[k + 1] - y[k]) * t
        left = np.where(on_point, y[np.clip(first, 0, len(x) - 1)], inside)
        right = np.where(on_point, y[np.clip(last, 0, len(x) - 1)], inside)
        return left, right

    def casadi(self, phi: Symbolic) -> Symbolic:
        """Right-continuous CasADi expression of the curve in ``phi`` [rad]."""
        import casadi as ca

        x, y = self.angles, self.values
        expr = float(y[0])
        slope_prev = 0.0
        for k in range(len(x) - 1):
            if x[k + 1] == x[k]:  # vertical step of size y[k+1]-y[k] at x[k]
                expr = expr + float(y[k + 1] - y[k]) * ca.if_else(phi >= x[k], 1, 0)
                continue
            slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
            expr = expr + float(slope - slope_prev) * ca.fmax(phi - float(x[k]), 0)
            slope_prev = slope
        return expr


@dataclass(frozen=True)
class Constant:
    """A constant torque [N*m]; ``value`` is None while it is still unknown.

    A constant solved from the work balance against a table keeps its exact
    split ``pivot + excess`` (pivot a value of the table, excess the small
    mean of table − pivot), so that M_d − M_r can be formed without the
    cancellation of a large mean (10^6 N*m) against a small ripple.
    """

    value: float | None
    pivot: float | None = None
    excess: float = 0.0
    is_linear = True

    @property
    def unknown(self) -> bool:
        """True while the value is still to be solved from the work balance."""
        return self.value is None

    def known(self) -> float:
        """The value [N*m]; a ValueError while it is still unknown (solved by the work balance)."""
        if self.value is None:
            raise ValueError("the unknown constant torque has not been solved from the work balance yet")
        return float(self.value)

    def breakpoints(self) -> Array:
        """None: a constant has no breakpoints."""
        return np.empty(0)

    def limits(self, phi: Array) -> tuple[Array, Array]:
        """The value at every angle, twice (no steps)."""
        v = np.full(np.shape(phi), self.known())
        return v, v  # the same array twice: no steps

    def work(self, cycle_angle: float) -> float:
        """∫_0^Φ M dφ = M Φ [J]."""
        return self.known() * cycle_angle

    def casadi(self, phi: Symbolic) -> Symbolic:
        """The value (a constant needs no symbol)."""
        return self.known()


@dataclass(frozen=True)
class ExpressionTorque:
    """Torque given as an expression in ``phi`` [rad] (and ``omega`` [rad/s]) times ``scale``.

    Parameters
    ----------
    expression : Expression
        The parsed expression.
    scale : float
        Factor from the expression's unit to N*m.
    where : str
        Scene field it came from, for error messages.
    omega : float or None
        A fixed speed [rad/s] at which a speed-dependent expression is
        evaluated by the angle-only methods (see :meth:`at_speed`).
    """

    expression: Expression
    scale: float = 1.0
    where: str = field(default="", compare=False)
    omega: float | None = None
    is_linear = False

    @property
    def speed_dependent(self) -> bool:
        """True when the expression uses ``omega`` and no fixed speed is set."""
        return "omega" in self.expression.depends_on and self.omega is None

    def at_speed(self, omega: float) -> ExpressionTorque:
        """The same torque with ω held at ``omega`` [rad/s] (an angle-only curve)."""
        return ExpressionTorque(self.expression, self.scale, self.where, float(omega))

    def breakpoints(self) -> Array:
        """None: an expression's kinks are found from its arguments (:meth:`kink_functions`)."""
        return np.empty(0)

    def round_off(self, phi: Array) -> Array:
        """A bound on the round-off of the torque as evaluated at ``phi`` [N*m]
        (:meth:`Expression.error_bound`, scaled)."""
        phi = np.asarray(phi, dtype=float)
        extra = {"omega": self.omega} if "omega" in self.expression.depends_on and self.omega is not None else {}
        value, bound = self.expression.numpy_with_bound(phi=phi, **extra)
        with np.errstate(all="ignore"):
            torque = self.scale * np.asarray(value, dtype=float)
            bound = abs(self.scale) * np.asarray(bound, dtype=float)
        return np.broadcast_to(bound + 2.0 * np.finfo(float).eps * np.abs(torque), phi.shape)

    def kink_functions(self) -> list[Callable[[Array], Array]]:
        """Functions of the angle whose sign changes are kinks of the torque.

        One per ``abs``, ``min`` or ``max`` in the expression
        (:meth:`Expression.kink_argument`), vectorized in φ [rad]; none for a
        speed-dependent torque (its kinks move with the speed).
        """
        if self.speed_dependent:
            return []
        extra: dict[str, Any] = {"omega": self.omega} if "omega" in self.expression.depends_on else {}

        def argument(index: int) -> Callable[[Array], Array]:
            def g(phi: Array) -> Array:
                phi = np.asarray(phi, dtype=float)  # numpy scalars: 1/0 is inf, not an exception
                with np.errstate(all="ignore"):
                    return np.broadcast_to(
                        np.asarray(self.expression.kink_argument(index, phi=phi, **extra), dtype=float), np.shape(phi)
                    )

            return g

        return [argument(k) for k in range(self.expression.kink_count)]

    def _values(self, phi: Array) -> Any:
        if "omega" in self.expression.depends_on:
            if self.omega is None:
                raise ValueError(f"{self.where}: the torque depends on omega; give a speed (at_speed)")
            return self.expression.numpy(phi=phi, omega=self.omega)
        return self.expression.numpy(phi=phi)

    def __call__(self, phi: Array) -> Array:
        """The torque at the angles ``phi`` [N*m]."""
        with np.errstate(all="ignore"):
            return self.scale * np.asarray(self._values(phi), dtype=float) + 0.0 * phi

    def limits(self, phi: Array) -> tuple[Array, Array]:
        """The torque at every angle, twice (an expression has no steps)."""
        v = self(np.asarray(phi, dtype=float))
        return v, v

    def casadi(self, phi: Symbolic, omega: Symbolic | None = None) -> Symbolic:
        """CasADi expression in ``phi`` (and ``omega``, a symbol, when the torque depends on speed)."""
        if "omega" in self.expression.depends_on:
            speed = self.omega if self.omega is not None else omega
            if speed is None:
                raise ValueError(f"{self.where}: the torque depends on omega; pass it")
            return self.scale * self.expression.casadi(phi=phi, omega=speed)
        return self.scale * self.expression.casadi(phi=phi)


@dataclass(frozen=True)
class MotorTorque:
    """Driving torque of a motor, reduced to the reference shaft: M' = M(i ω) i η.

    Parameters
    ----------
    motor : flyopt.machine.motor.InductionMotor, DCMotor or TableMotor
    speed_ratio : float
        i = ω_motor / ω_reference [-].
    efficiency : float
        η of the transmission from the motor to the reference shaft [-].
    model : str or None
        Characteristic of an induction motor: "linear" (near the rated point)
        or "kloss" (the whole curve); None for a DC motor or a motor's table.
    where : str
        Scene field, for messages.
    shaft : str or None
        The ``[[shaft]]`` the motor turns with (its speed ratio is ``speed_ratio``), or None: the reference shaft.
    """

    motor: InductionMotor | DCMotor | TableMotor
    speed_ratio: float = 1.0
    efficiency: float = 1.0
    model: str | None = None
    where: str = field(default="", compare=False)
    shaft: str | None = field(default=None, compare=False)
    is_linear = False
    speed_dependent = True

    def breakpoints(self) -> Array:
        """None: a motor's torque depends on the speed, not on the angle."""
        return np.empty(0)

    def casadi(self, phi: Symbolic, omega: Symbolic | None = None) -> Symbolic:
        """The reduced motor torque at the speed symbol ``omega``."""
        if omega is None:
            raise ValueError(f"{self.where}: a motor torque depends on omega; pass it")
        return self.motor.reference_torque(omega, self.speed_ratio, self.efficiency, self.model) + 0 * phi

    def at_speed(self, omega: float) -> Constant:
        """The motor's torque at the reference speed ``omega`` [rad/s], as a Constant."""
        return Constant(
            float(self.motor.reference_torque(np.asarray(float(omega)), self.speed_ratio, self.efficiency, self.model))
        )


class TorqueSum:
    """The sum of torque curves (e.g. a resisting load plus members' forces)."""

    speed_dependent = False

    def __init__(self, parts: Iterable[Any], where: str = "") -> None:
        # The parts are duck-typed: TorqueCurves and MotorTorques (speed-dependent, no limits).
        self.parts = tuple(parts)
        self.where = where
        self.is_linear = all(p.is_linear for p in self.parts)
        self.speed_dependent = any(getattr(p, "speed_dependent", False) for p in self.parts)

    def breakpoints(self) -> Array:
        """The breakpoints of every part, sorted, once each."""
        points = [p.breakpoints() for p in self.parts]
        return np.unique(np.concatenate(points)) if points else np.empty(0)

    def kink_functions(self) -> list[Callable[[Array], Array]]:
        """The kink functions of the parts that have them (see :meth:`ExpressionTorque.kink_functions`)."""
        return [g for p in self.parts if hasattr(p, "kink_functions") for g in p.kink_functions()]

    def limits(self, phi: Array) -> tuple[Array, Array]:
        """Left and right limits of the sum: the sums of the parts' limits."""
        left: Any = 0.0
        right: Any = 0.0
        for p in self.parts:
            lp, rp = p.limits(phi)
            left, right = left + lp, right + rp
        return left, right

    def __call__(self, phi: Array) -> Array:
        """The sum at the angles ``phi`` (right limits) [N*m]."""
        return self.limits(np.asarray(phi, dtype=float))[1]

    def casadi(self, phi: Symbolic, omega: Symbolic | None = None) -> Symbolic:
        """The sum as one CasADi expression (ω passed to the speed-dependent parts)."""
        total: Symbolic = 0.0
        for p in self.parts:
            total = total + (p.casadi(phi, omega) if getattr(p, "speed_dependent", False) else p.casadi(phi))
        return total

    def at_speed(self, omega: float) -> TorqueSum:
        """The sum with every speed-dependent part held at ``omega`` [rad/s]."""
        return TorqueSum(
            [p.at_speed(omega) if getattr(p, "speed_dependent", False) else p for p in self.parts], self.where
        )
