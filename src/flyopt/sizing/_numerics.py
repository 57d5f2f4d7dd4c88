"""Numerical helpers shared by the sizing models (private).

The inertia J(φ) as a CasADi function, elementwise evaluation of CasADi
functions on numpy arrays, and argument checks (docs/flywheel-design.md,
sections 6–7). The cubic Hermite interpolant and its exact extremes, pure
numerics, are in :mod:`flyopt.cycle.numerics`.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from typing import Any

import casadi as ca
import numpy as np
import numpy.typing as npt

EPS = float(np.finfo(float).eps)

FloatArray = npt.NDArray[np.float64]
"""An array of floats (angles [rad], speeds [rad/s], torques [N*m], energies [J])."""

NetTorqueLike = Callable[[Any, Any], Any]
"""A net torque M(φ [rad], ω [rad/s]) [N*m] that accepts floats, numpy arrays and CasADi symbols
(e.g. :class:`flyopt.machine.reduce.NetTorque`, which also carries its table and its work)."""

InertiaLike = float | Callable[[Any], Any]
"""The machine's inertia J(φ) [kg*m^2]: a number, or a CasADi-capable callable such as
:class:`flyopt.machine.mechanism.EquivalentInertia`."""

EDGE = 1e-10
"""Torques are evaluated this fraction of a piece inside its ends, so a step at
a knot is seen from the correct side."""


class Inertia:
    _is_constant: bool | None  # None: not known until CasADi is asked
    """J(φ) from a number, an EquivalentInertia or a CasADi-capable callable.

    ``inertia(phi)`` and ``inertia.derivative(phi)`` evaluate on numpy
    arrays: in numpy directly when the source offers its value and
    derivative on arrays (``value_and_derivative``, e.g. an
    :class:`flyopt.machine.mechanism.EquivalentInertia` of slider-crank
    members and tables), else by the CasADi function, mapped over the array
    in one call. The CasADi function (``function``, ``casadi``) is built on
    first use; a callable is checked at once by calling it on a symbol.
    """

    def __init__(self, j: Any, what: str = "j_machine") -> None:
        self._maps: dict[Any, Any] = {}
        self._numpy = None
        self._expr: Any = None
        self._phi: Any = None
        self._function: Any = None
        self._constant_value = None
        if isinstance(j, (int, float)) and not isinstance(j, bool):
            if not (math.isfinite(j) and j >= 0):
                raise ValueError(f"{what} must be a finite number >= 0 [kg*m^2], got {j!r}")
            self._constant_value = float(j)
            self.knots, self._is_constant = np.empty(0), True
        elif hasattr(j, "casadi"):
            self.knots = np.asarray(getattr(j, "knots", np.empty(0)), dtype=float)
            self._is_constant = bool(getattr(j, "is_constant", False)) or None  # None: ask CasADi
            if getattr(j, "has_numpy_derivative", False) and hasattr(j, "value_and_derivative"):
                self._numpy = j
        elif callable(j):
            phi = ca.SX.sym("phi")
            try:
                self._expr = ca.SX(j(phi))
            except Exception as err:  # noqa: BLE001 -- any failure means "not CasADi-capable"
                raise ValueError(
                    f"{what} must accept a CasADi symbol (use numpy-free arithmetic or an EquivalentInertia): {err}"
                ) from err
            self._phi = phi
            self.knots, self._is_constant = np.empty(0), None
        else:
            raise ValueError(f"{what} must be a number [kg*m^2] or a function of phi, got {j!r}")
        self.source = j

    def _symbolic(self):
        """(φ symbol, J expression), built once."""
        if self._expr is None:
            phi = ca.SX.sym("phi")
            j = self.source
            self._expr = ca.SX(self._constant_value) if self._constant_value is not None else ca.SX(j.casadi(phi))
            self._phi = phi
        return self._phi, self._expr

    @property
    def is_constant(self) -> bool:
        """True when J does not depend on φ (asked of CasADi when the source does not say)."""
        if self._is_constant is None:
            phi, expr = self._symbolic()
            self._is_constant = not ca.depends_on(expr, phi)
        return self._is_constant

    @property
    def function(self) -> Any:
        """The CasADi Function φ ↦ (J, dJ/dφ)."""
        if self._function is None:
            phi, expr = self._symbolic()
            self._function = ca.Function("J", [phi], [expr, ca.jacobian(expr, phi)])
        return self._function

    def casadi(self, phi: Any) -> Any:
        """J at the symbol ``phi`` (a CasADi expression)."""
        return self.function(phi)[0]

    def __call__(self, phi: npt.ArrayLike) -> Any:
        """J at ``phi`` (numpy) [kg*m^2]."""
        return self._eval(phi, 0)

    def derivative(self, phi: npt.ArrayLike) -> Any:
        """dJ/dφ at ``phi`` (numpy) [kg*m^2/rad]."""
        return self._eval(phi, 1)

    def value_and_derivative(self, phi: npt.ArrayLike) -> Any:
        """J and dJ/dφ at ``phi`` (numpy) [kg*m^2], [kg*m^2/rad]."""
        if self._numpy is not None:
            return self._numpy.value_and_derivative(np.asarray(phi, dtype=float))
        return self._eval(phi, None)

    def _eval(self, phi, which):
        if self._numpy is not None:
            phi = np.asarray(phi, dtype=float)
            return self._numpy(phi) if which == 0 else self._numpy.derivative(phi)
        if self._constant_value is not None or self.is_constant:  # no CasADi call per angle for a constant
            shape = np.shape(phi)
            value = self._constant_value if self._constant_value is not None else float(self.function(0.0)[0])
            pair: tuple[FloatArray, ...] = (np.full(shape, value), np.zeros(shape))
        else:
            pair = evaluate(self.function, self._maps, phi)
        return pair if which is None else pair[which]


def call(function: Any, *args: npt.ArrayLike) -> tuple[FloatArray, ...]:
    """Evaluate a CasADi Function on numpy inputs into numpy outputs.

    The inputs are copied once into column-major buffers and the outputs
    written straight into numpy arrays (CasADi's ``buffer``), without the DM
    conversions of an ordinary call, which cost more than the evaluation for
    the small functions of the sizing models. Each input must hold as many
    numbers as the function's (dense) input; the outputs come back in their
    own shapes (a column vector as a 1-D array). A function with a sparse input or
    output is called the ordinary way.
    """
    if not all(function.sparsity_in(i).is_dense() for i in range(function.n_in())) or not all(
        function.sparsity_out(i).is_dense() for i in range(function.n_out())
    ):
        out = function(*args)
        out = out if isinstance(out, tuple) else (out,)
        return tuple(np.asarray(o, dtype=float) for o in out)
    buffer, run = function.buffer()
    inputs = []
    for i, a in enumerate(args):
        flat = np.asarray(a, dtype=float).ravel(order="F")
        if flat.size != function.nnz_in(i):
            raise ValueError(f"{function.name()}: input {i} has {flat.size} numbers, {function.nnz_in(i)} expected")
        flat = np.ascontiguousarray(flat)
        inputs.append(flat)  # the buffer keeps no reference: these must live
        buffer.set_arg(i, flat.data)  # the array's buffer, as a memoryview
    outputs = []
    for i in range(function.n_out()):
        rows, cols = function.size_out(i)
        out = np.empty(rows * cols)
        buffer.set_res(i, out.data)
        outputs.append(out.reshape((rows, cols), order="F") if cols > 1 else out)
    run()
    return tuple(outputs)


def evaluate(function: Any, maps: dict[Any, Any], *args: npt.ArrayLike) -> tuple[FloatArray, ...]:
    """Evaluate a scalar CasADi Function elementwise on broadcast numpy arrays.

    The mapped function for each function and size is built once and kept in ``maps`` (keyed by the
    function's name and the size: one dictionary may serve several functions of a model).
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
    shape = arrays[0].shape
    n = arrays[0].size
    if n == 0:
        return tuple(np.zeros(shape) for _ in range(function.n_out()))
    key = (function.name(), n)
    if key not in maps:
        if len(maps) > 64:
            maps.clear()
        maps[key] = function.map(n) if n > 1 else function
    return tuple(o.reshape(shape) for o in call(maps[key], *(a.reshape(1, -1) for a in arrays)))


def check_speed_delta(omega_mean: float, delta: float | None, delta_max: float = 2.0) -> None:
    """Refuse a mean speed that is not a positive finite number, or δ outside (0, delta_max) (ValueError)."""
    if not (isinstance(omega_mean, (int, float)) and math.isfinite(omega_mean) and omega_mean > 0):
        raise ValueError(f"omega_mean must be a positive finite speed [rad/s], got {omega_mean!r}")
    if delta is not None and not (isinstance(delta, (int, float)) and math.isfinite(delta) and 0 < delta < delta_max):
        raise ValueError(f"delta must lie in (0, {delta_max:g}), got {delta!r}")


def check_cycle(cycle_angle: float) -> float:
    """The cycle angle as a float; a ValueError unless it is a positive finite angle [rad]."""
    if not (isinstance(cycle_angle, (int, float)) and math.isfinite(cycle_angle) and cycle_angle > 0):
        raise ValueError(f"cycle_angle must be a positive finite angle [rad], got {cycle_angle!r}")
    return float(cycle_angle)


class _Discard:
    """A text stream that keeps nothing."""

    def write(self, text):
        return len(text)

    def flush(self):
        pass


@contextlib.contextmanager
def quiet() -> Iterator[None]:
    """Keep CasADi's diagnostics off stderr while CasADi evaluates.

    When a function called inside a CasADi graph fails (CVODES giving up
    on a trial that stalls), CasADi prints its every input to stderr before
    it raises; the exception, which flyopt turns into a message with
    numbers, is all that is wanted.
    """
    with contextlib.redirect_stderr(_Discard()):
        yield
