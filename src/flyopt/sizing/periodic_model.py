"""The periodic model: the equation of motion of one machine, built once for CasADi.

d(½ J(φ) ω²)/dφ = M(φ, ω) over one cycle (docs/flywheel-design.md, section 7),
cut at every knot and into pieces, integrated by CVODES in the scaled energy
y = (E − E_ref)/W_s with exact sensitivities, a torque table entering as its
values at the ends of each piece. :func:`periodic_model` caches one model per
net torque, inertia, cycle and knots (:data:`BUILDS` counts the builds), so the
requirement, the comparison of models and the verification of one machine share
it; the searches for a periodic solution (:mod:`flyopt.sizing.periodic`) and the
one-solve requirement (:mod:`flyopt.sizing.shooting`) run on it.
"""

from __future__ import annotations

import copy
import weakref
from collections.abc import Iterable
from functools import cached_property
from typing import Any, cast

import casadi as ca
import numpy as np
from numpy.typing import ArrayLike

from flyopt.errors import SolverFailed
from flyopt.sizing import shooting
from flyopt.sizing._numerics import (
    EDGE,
    FloatArray,
    Inertia,
    InertiaLike,
    NetTorqueLike,
    check_cycle,
    evaluate,
    quiet,
)

PIECES_PER_CYCLE = 32
"""The simulation splits the cycle at every knot and into at least this many pieces."""

OUTPUTS_PER_PIECE = 64
"""Integrator outputs per piece (the simulation grid: at least 2048 per cycle)."""

MAX_OUTPUTS = 2**17
"""Outputs per cycle above which a piece gets fewer than :data:`OUTPUTS_PER_PIECE`
(a table of many points cuts the cycle into many short pieces; memory stays bounded)."""

CHUNK = 256
"""Pieces integrated by one CasADi call (a ``mapaccum``); longer cycles are chained in chunks."""

BUILDS = shooting.BUILDS
"""CasADi structures built, by kind ("periodic model", "integrator", "timed integrator",
"cycle function", "shooting function", "balancing function", and the one-solve's
"fixed-step function"). Each is built once per machine and reused for every flywheel and
speed; tests count them. (The counter lives in :mod:`flyopt.sizing.shooting`, which this
module imports.)"""

RELTOL = 1e-11
ABSTOL = 1e-12
"""CVODES tolerances on the scaled energy y = (E − E_ref)/W_s, of order one."""

MAX_STEPS = 20_000
"""CVODES steps one piece of a periodic cycle may take. The problems, the hard cases and the golden results
need under 1,000 (300 is too few for three of them); a trial that needs more is stiff beyond what a steady
state needs (its speed near zero, or a motor geared so far down that its time constant is a millionth of the
cycle) and counts as one that stalls, as a failed integration always has (:func:`flyopt.sizing.periodic`).
With 200,000 such trials took seconds each, one after another: motor-press with its motor 1e5 times faster
than the crank had not ended after ten minutes (tests/sizing/test_speed_stiff.py)."""

MAX_STEPS_RUN_UP = 200_000
"""CVODES steps one piece of a run-up (:mod:`flyopt.sizing.startup`) may take: from rest, where the speed
starts at zero, the run-ups of the tests need over 1,000."""

STILL = 1e-6
"""The speed, in parts of the cycle's starting speed √(2 E_ref/J), below which the torques are read at it: a
machine that slow has stalled (a periodic speed that low would have δ within 2e-6 of 2). Below it ω = √(2E/J)
would make the torque's slope in E, ∂M/∂ω / (J ω), grow without bound where a cycle that stalls grazes zero
energy, and CVODES's sensitivities of it shrink their steps to its limit (10 s a cycle) before they give up."""


class PeriodicModel:
    """The equation of motion of one machine, built once for CasADi.

    d(½ J ω²)/dφ = M(φ, ω) over one cycle, cut at every knot and into at
    least :data:`PIECES_PER_CYCLE` pieces. Each piece is integrated by CVODES
    in a normalized time τ ∈ [0, 1] with the piece's ends, the flywheel and
    the energy scales as parameters, so one integrator serves every piece,
    flywheel and speed. The cycle is integrated in chunks of at most
    :data:`CHUNK` pieces (a CasADi ``mapaccum`` each), so that time and
    memory grow linearly with the number of pieces. Build it through
    :func:`periodic_model` (cached).

    Parameters
    ----------
    net_torque : callable (phi, omega) -> torque
        M_d − M_r at the reference shaft [N*m]; must accept CasADi symbols.
        A :class:`flyopt.machine.reduce.NetTorque` is taken apart: its
        ``table`` (piecewise linear in the angle) enters each piece as its
        two end values, its ``rest`` as CasADi, its ``work`` sets the scale of
        the work balance and ``balanced`` says that an unknown constant
        holds the mean speed (see :func:`flyopt.sizing.periodic.periodic_solution`).
    j_machine : float, EquivalentInertia or callable
        J(φ) of the machine [kg*m^2].
    cycle_angle : float
        Φ [rad].
    knots : sequence of float
        Angles where the torque steps or kinks [rad].
    """

    def __init__(
        self, net_torque: NetTorqueLike, j_machine: InertiaLike, cycle_angle: float, knots: Iterable[float] = ()
    ) -> None:
        BUILDS["periodic model"] += 1
        self.cycle = check_cycle(cycle_angle)
        self.inertia = Inertia(j_machine)
        self.table = getattr(net_torque, "table", None)
        # a torque with a table (flyopt.machine.reduce.NetTorque) carries the rest of itself as ``rest``
        rest = cast(Any, net_torque).rest if self.table is not None else net_torque
        knots = np.asarray(list(knots), dtype=float).reshape(-1)
        if not np.all(np.isfinite(knots)):
            raise ValueError("knots must be finite angles [rad]")
        table_knots = self.table.breakpoints() if self.table is not None else np.empty(0)
        inner = np.concatenate((knots, table_knots, self.inertia.knots))
        inner = inner[(inner > 0) & (inner < self.cycle)]
        edges = np.union1d([0.0, self.cycle], inner)
        counts = np.maximum(1, np.ceil((edges[1:] - edges[:-1]) / self.cycle * PIECES_PER_CYCLE - 1e-9)).astype(int)
        pieces = [np.linspace(a, b, n + 1) for a, b, n in zip(edges[:-1], edges[1:], counts)]
        self.pieces = np.concatenate([np.column_stack((c[:-1], c[1:])) for c in pieces])
        self.segments = np.column_stack((edges[:-1], edges[1:]))
        outputs = OUTPUTS_PER_PIECE
        if len(self.pieces) * OUTPUTS_PER_PIECE > MAX_OUTPUTS:
            outputs = max(2, MAX_OUTPUTS // len(self.pieces) // 2 * 2)
        self.tau = np.linspace(0.0, 1.0, outputs + 1)
        self.table_ends = self.table_at(self.pieces[:, 0], self.pieces[:, 1])
        self.work = float(getattr(net_torque, "work", 0.0))

        phi, omega = ca.SX.sym("phi"), ca.SX.sym("omega")
        # a net torque with parameters (a motor whose ratio and curve a drive search varies) takes them
        # as symbols: every function below has them as inputs, so one build serves every value
        self.n_theta = int(getattr(net_torque, "parameters", 0))
        theta = [ca.SX.sym(f"theta{k}") for k in range(self.n_theta)]
        #: The parameters' values (:meth:`bind` gives the model at others).
        self.theta: tuple[float, ...] = (
            tuple(float(v) for v in cast(Any, net_torque).parameter_values()) if self.n_theta else ()
        )
        try:
            m = ca.SX(rest(phi, omega, *theta))
        except Exception as err:  # noqa: BLE001 -- any failure means "not CasADi-capable"
            raise ValueError(f"net_torque(phi, omega) must accept CasADi symbols: {err}") from err
        if m.shape != (1, 1):
            raise ValueError(f"net_torque must return a scalar, got shape {m.shape}")
        self.speed_dependent = bool(ca.depends_on(m, omega))
        self.balanced = self.speed_dependent and bool(getattr(net_torque, "balanced", False))
        self.steady = (
            self.inertia.is_constant
            and not ca.depends_on(m, phi)
            and bool(np.all(self.table_ends == self.table_ends[0, 0]))
        )
        self.torque_function = ca.Function("M", [phi, omega, *theta], [m])
        self._rest_constant = not (ca.depends_on(m, phi) or self.speed_dependent)
        self.torque_slope_function = ca.Function("dM", [phi, omega, *theta], [ca.jacobian(m, omega)])
        #: CasADi maps of the torque functions over arrays, by size (for :func:`flyopt.sizing._numerics.evaluate`).
        self.maps: dict[Any, Any] = {}
        #: The largest flywheel J_F [kg*m^2] at which a search found no periodic steady state, by θ: whether
        #: one exists does not depend on δ, so a search at another δ (the J_F–δ curve) starts above it.
        self.stalls: dict[tuple[float, ...], float] = {}
        self._table_values: dict[str, FloatArray] = {}

    def bind(self, theta: Iterable[float]) -> PeriodicModel:
        """The model at other values of its parameters (it shares every compiled function with this one)."""
        values = tuple(float(v) for v in theta)
        if len(values) != self.n_theta:
            raise ValueError(f"the model has {self.n_theta} parameters, got {len(values)} values")
        self.structure  # noqa: B018 -- computed once here, so that every bound copy shares it
        bound = copy.copy(self)
        bound.theta = values
        return bound

    def table_at(self, a: ArrayLike, b: ArrayLike) -> FloatArray:
        """The table's values at the ends of pieces [a, b], seen from inside them [N*m], shape (n, 2)."""
        a, b = np.atleast_1d(np.asarray(a, dtype=float)), np.atleast_1d(np.asarray(b, dtype=float))
        if self.table is None:
            return np.zeros((len(a), 2))
        return np.column_stack((self.table.limits(a)[1], self.table.limits(b)[0]))

    # -- CasADi building blocks --------------------------------------------------
    def rhs(self, with_time: bool) -> dict[str, Any]:
        """States [y, stall(, t)], parameters [φ_a, φ_b, J_F, E_ref, W_s, c, M_a, M_b(, T_s), θ...].

        c is a constant added to the net torque (the correction of a
        balancing constant); M_a and M_b are the table's values at the
        piece's ends, between which it is linear; θ the net torque's own
        parameters (none for most machines).
        """
        tau = ca.SX.sym("tau")
        x = ca.SX.sym("x", 3 if with_time else 2)
        first = 9 if with_time else 8
        p = ca.SX.sym("p", first + self.n_theta)
        a, b, j_f, e_ref, w_s, c, m_a, m_b = (p[k] for k in range(8))
        theta = [p[first + k] for k in range(self.n_theta)]
        h = b - a
        phi = a + tau * h
        tau_torque = ca.fmin(ca.fmax(tau, EDGE), 1 - EDGE)
        phi_torque = a + tau_torque * h
        j = self.inertia.casadi(phi) + j_f
        energy = e_ref + w_s * x[0]
        omega = ca.sqrt(ca.fmax(2 * energy / j, ca.fmax(STILL**2 * 2 * e_ref / j, 0) + 1e-300))  # a start-up's E_ref: 0
        torque = self.torque_function(phi_torque, omega, *theta) + (m_a + (m_b - m_a) * tau_torque) + c
        ode = [h * torque / w_s, h * ca.fmax(-energy / w_s, 0)]
        if with_time:
            ode.append(h / (omega * p[8]))
        return {"x": x, "p": p, "t": tau, "ode": ca.vertcat(*ode)}

    def _integrator(self, with_time):
        BUILDS["timed integrator" if with_time else "integrator"] += 1
        opts = {
            "abstol": ABSTOL,
            "reltol": RELTOL,
            "max_num_steps": MAX_STEPS_RUN_UP if with_time else MAX_STEPS,
            "disable_internal_warnings": True,
            "print_stats": False,
            "verbose": False,
        }
        return ca.integrator("piece_t" if with_time else "piece", "cvodes", self.rhs(with_time), 0.0, self.tau, opts)

    @cached_property
    def _compiled(self) -> dict[Any, Any]:
        """The CVODES functions of this model's structure, shared by every model of it (:data:`_COMPILED`).

        They depend on the torque law, the inertia and the output grid (:attr:`structure`; the grid
        is ``tau``, fixed by its length), not on the pieces, the table's values or θ, which are
        inputs: the drive's verification of the chosen machine, its analysis and the comparison of
        models reduce the same machine apart, and compiled it three times.
        """
        key = self.structure
        if key in _COMPILED:
            _COMPILED[key] = _COMPILED.pop(key)  # most recently used last
        else:
            if len(_COMPILED) >= shooting.MAX_STRUCTURES:
                _COMPILED.pop(next(iter(_COMPILED)))
            _COMPILED[key] = {}
        return _COMPILED[key]

    @property
    def piece(self) -> ca.Function:
        """CVODES over one piece: states [y, stall], outputs at ``tau``."""
        if "piece" not in self._compiled:
            self._compiled["piece"] = self._integrator(False)
        return self._compiled["piece"]

    @property
    def piece_timed(self) -> ca.Function:
        """CVODES over one piece with time: states [y, stall, t]."""
        if "piece_timed" not in self._compiled:
            self._compiled["piece_timed"] = self._integrator(True)
        return self._compiled["piece_timed"]

    def _chunk(self, kind, size):
        """A CasADi function over ``size`` consecutive pieces (built once per kind and size).

        Inputs: the states at the chunk's start, q = [J_F, E_ref, W_s, c, θ...], and
        the pieces' data [φ_a, φ_b, M_a, M_b] (4 × size). Outputs by kind:
        "cycle": the states at the chunk's end and at every output;
        "shooting": the states at the end and ∂y/∂E_ref there;
        "balancing": the same and ∂y/∂c.
        """
        key = (kind, size)
        chunks = self._compiled.setdefault("chunks", {})
        if key not in chunks:
            BUILDS[f"{kind} function"] += 1
            x0, q, data = ca.MX.sym("x0", 2), ca.MX.sym("q", 4 + self.n_theta), ca.MX.sym("data", 4)
            xf = self.piece(x0=x0, p=ca.vertcat(data[0], data[1], q[:4], data[2], data[3], q[4:]))["xf"]
            if kind == "cycle":
                step = ca.Function("step", [x0, q, data], [xf[:, -1], xf])
                chunks[key] = step.mapaccum(f"cycle_{size}", size)
            else:
                step = ca.Function("step", [x0, q, data], [xf[:, -1]])
                chain = step.mapaccum(f"chain_{size}", size)
                xs, ds = ca.MX.sym("x0", 2), ca.MX.sym("data", 4, size)
                qs = [ca.MX.sym(name) for name in ("j_f", "e_ref", "w_s", "c")]
                qs += [ca.MX.sym(f"theta{k}") for k in range(self.n_theta)]
                end = chain(xs, ca.vertcat(*qs), ds)[:, -1]
                wrt = [qs[1]] if kind == "shooting" else [qs[1], qs[3]]
                outs = [end] + [ca.jacobian(end[0], v) for v in wrt]
                chunks[key] = ca.Function(f"{kind}_{size}", [xs, ca.vertcat(*qs), ds], outs)
        return chunks[key]

    def chunked(self) -> list[tuple[int, FloatArray]]:
        """(start, data) of each chunk of at most :data:`CHUNK` pieces."""
        data = np.column_stack((self.pieces, self.table_ends)).T
        return [(k, data[:, k : k + CHUNK]) for k in range(0, len(self.pieces), CHUNK)]

    def shoot(
        self, j_flywheel: float, e_ref: float, w_s: float, offset: float = 0.0, balancing: bool = False
    ) -> tuple[float, ...]:
        """One cycle from y = 0: (y(Φ), stall(Φ), dy(Φ)/dE_ref[, dy(Φ)/dc]).

        The chunks are chained by the chain rule: y depends on the energy
        E_ref + W_s y only, so ∂y_end/∂y_start = 1 + W_s ∂y_end/∂E_ref.

        Raises
        ------
        RuntimeError
            When CVODES fails (CasADi's message).
        """
        kind = "balancing" if balancing else "shooting"
        key = (kind, float(j_flywheel), float(e_ref), float(w_s), float(offset))
        known = self._known(key)
        if known is not None:
            return cast(tuple[float, ...], known)
        q = [j_flywheel, e_ref, w_s, offset, *self.theta]
        x, d_e, d_c = np.zeros(2), 0.0, 0.0
        for _, data in self.chunked():
            out = self._chunk(kind, data.shape[1])(x, q, data)
            b_e = float(out[1])
            gain = 1.0 + w_s * b_e
            d_e = gain * d_e + b_e
            if balancing:
                d_c = gain * d_c + float(out[2])
            x = np.asarray(out[0], dtype=float).reshape(-1)
        return self._keep(key, (x[0], x[1], d_e, d_c) if balancing else (x[0], x[1], d_e))

    def _known(self, key: tuple[Any, ...]) -> Any:
        """A cycle this model's structure integrated before from the same pieces, table, θ and inputs, or None.

        CVODES gives the same numbers for the same inputs: a machine reduced apart (the drive's
        verification of the chosen machine repeats its analysis's periodic solution without a
        flywheel) is not integrated again. The ends of :data:`MAX_RESULTS` shots are kept per
        structure, the whole curves of the last :data:`MAX_CYCLES` cycles of any.
        """
        if key[0] == "cycle":
            return _CYCLES.get((self.structure, self._content, key))
        return self._compiled.get("results", {}).get(self._content + key)

    def _keep(self, key: tuple[Any, ...], value: Any) -> Any:
        results, size, full = self._compiled.setdefault("results", {}), MAX_RESULTS, self._content + key
        if key[0] == "cycle":
            results, size, full = _CYCLES, MAX_CYCLES, (self.structure, self._content, key)
        if len(results) >= size:
            results.pop(next(iter(results)))
        results[full] = value
        return value

    @cached_property
    def _content(self) -> tuple[Any, ...]:
        """What a cycle depends on besides the structure and its inputs: the pieces, the table's values, θ."""
        return (self.pieces.tobytes(), self.table_ends.tobytes(), self.theta)

    @cached_property
    def structure(self) -> tuple[Any, ...]:
        """What functions compiled from this model depend on (:mod:`flyopt.sizing.shooting` caches them by it):
        the net torque's and the inertia's expressions, the grid and the balancing constant; the pieces and
        the table's values are inputs."""
        return (
            self.torque_function.serialize(),
            self.inertia.function.serialize(),
            len(self.tau),
            bool(self.balanced),
        )

    # -- numbers --------------------------------------------------------------
    def grid_angles(self) -> FloatArray:
        """Angles of the simulation outputs, piece by piece, shape (pieces, outputs) (read-only)."""
        return self._grid

    @cached_property
    def _grid(self) -> FloatArray:
        a, b = self.pieces[:, :1], self.pieces[:, 1:]
        grid = a + self.tau[None, :] * (b - a)
        grid.setflags(write=False)
        return grid

    @cached_property
    def inner_angles(self) -> FloatArray:
        """The output angles seen from inside each piece (:data:`EDGE` in from its ends), where the
        torques are evaluated so that a step at a knot is taken from the correct side (read-only)."""
        h = self.pieces[:, 1] - self.pieces[:, 0]
        inner = self.pieces[:, :1] + np.clip(self.tau, EDGE, 1 - EDGE)[None, :] * h[:, None]
        inner.setflags(write=False)
        return inner

    def torque(self, phi: ArrayLike, omega: ArrayLike) -> FloatArray:
        """Net torque at numpy arrays (broadcast) [N*m]; on a knot, the value right of it."""
        if self._rest_constant:  # a table alone: no CasADi call per point
            shape = np.broadcast_shapes(np.shape(phi), np.shape(omega))
            values = np.full(shape, float(self.torque_function(0.0, 0.0, *self.theta)))
        else:
            values = evaluate(self.torque_function, self.maps, phi, omega, *self.theta)[0]
        if self.table is not None:
            values = values + self._table_right(phi, values.shape)
        return values

    def _table_right(self, phi, shape):
        """The table's values right of ``phi``, broadcast to ``shape``; kept for the model's own grids,
        at which every solve evaluates the torque again and again."""
        table = self.table
        if table is None:
            raise RuntimeError("the model has no table of the angle to evaluate")
        grid = "grid" if phi is self._grid else "inner" if phi is self.inner_angles else None
        if grid is None or phi.shape != shape:
            return table.limits(np.broadcast_to(np.asarray(phi, dtype=float), shape))[1]
        if grid not in self._table_values:
            values = table.limits(phi)[1]
            values.setflags(write=False)
            self._table_values[grid] = values
        return self._table_values[grid]

    def torque_slope(self, phi: ArrayLike, omega: ArrayLike) -> FloatArray:
        """∂M/∂ω at numpy arrays (broadcast) [N*m*s/rad] (a table of the angle has none)."""
        return evaluate(self.torque_slope_function, self.maps, phi, omega, *self.theta)[0]

    def falls_with_speed(self, omega: float) -> bool:
        """Whether ∂M/∂ω <= 0 on the grid for speeds up to 4 ω (sampled; the torque
        then has a unique periodic solution, see :func:`flyopt.sizing.periodic._periodic_energy`)."""
        if not self.speed_dependent:
            return True
        phi = self.grid_angles()[:, :-1].reshape(-1)
        speeds = np.linspace(0.0, 4 * omega, 65)[1:]
        slope = self.torque_slope(phi[:, None], speeds[None, :])
        return bool(np.all(slope <= 0))

    def check_finite(self, omega: float) -> None:
        """Raise ValueError when the net torque is not finite on the grid at speed ``omega``."""
        phi = self.grid_angles()
        m = self.torque(phi, omega)
        bad = ~np.isfinite(m)
        if bad.any():
            raise ValueError(
                f"net_torque is not finite at phi = {float(phi[bad][0]):.6g} rad, omega = {omega:.6g} "
                f"rad/s; it must accept CasADi symbols (casadi functions, not math or numpy) and "
                f"be finite over the cycle"
            )

    def work_scale(self, omega: float) -> float:
        """An upper bound of the energy swing over the cycle at speed ``omega`` [J].

        The larger of Φ · max |M(φ, ω)| and ½ (max J − min J) ω² (the energy
        a varying inertia trades at that speed, even when M is nil).
        """
        phi = self.grid_angles()
        m = self.torque(phi[:, :-1].reshape(-1), omega)
        j = self.inertia(phi)
        scale = max(self.cycle * float(np.max(np.abs(m))), 0.5 * float(np.ptp(j)) * omega**2)
        return scale if scale > 0 else 1.0

    def absolute_work(self, omega: float) -> float:
        """∫ |M(φ, ω)| dφ over the cycle at speed ``omega`` [J] (trapezoid on the simulation grid)."""
        phi = self.grid_angles()
        m = np.abs(self.torque(self.inner_angles, omega))
        return float(np.sum(0.5 * (m[:, 1:] + m[:, :-1]) * np.diff(phi, axis=1)))

    def trajectory(self, j_flywheel: float, e_ref: float, w_s: float, offset: float = 0.0) -> tuple[FloatArray, float]:
        """Integrate one cycle from y = 0; returns y (pieces, outputs) and the stall measure.

        Raises
        ------
        SolverFailed
            When CVODES fails (its status in the message).
        """
        key = ("cycle", float(j_flywheel), float(e_ref), float(w_s), float(offset))
        known = self._known(key)
        if known is not None:
            return known[0].copy(), known[1]
        q = [j_flywheel, e_ref, w_s, offset, *self.theta]
        x, parts = np.zeros(2), []
        try:
            with quiet():
                for _, data in self.chunked():
                    ends, outs = self._chunk("cycle", data.shape[1])(x, q, data)
                    parts.append(np.asarray(outs, dtype=float))
                    x = np.asarray(ends, dtype=float)[:, -1]
        except RuntimeError as err:
            raise SolverFailed(
                f"the integration of the cycle failed (CVODES: {str(err).strip().splitlines()[-1]})"
            ) from err
        out = np.concatenate(parts, axis=1)
        y = out[0].reshape(len(self.pieces), len(self.tau))
        self._keep(key, (y.copy(), float(out[1, -1])))
        return y, float(out[1, -1])

    def speed_profile(
        self, y: FloatArray, j_flywheel: float, e_ref: float, w_s: float, shift: float = 0.0, offset: float = 0.0
    ) -> tuple[FloatArray, FloatArray | None, FloatArray | None, FloatArray]:
        """q = E/J = ω²/2 and its slope dq/dφ = (M J − E J')/J² on the simulation grid.

        q is smooth even where ω is small (ω itself has a square-root
        singularity at zero speed), so extremes are located on q.

        Returns
        -------
        phi, q, dq, energy : ndarray (pieces, outputs)
            q and dq are None when the energy is not positive everywhere.
        """
        phi = self.grid_angles()
        j = self.inertia(phi) + j_flywheel
        dj = self.inertia.derivative(phi)
        energy = e_ref + w_s * (y + shift)
        if np.any(energy <= 0):
            return phi, None, None, energy
        q = energy / j
        m = self.torque(self.inner_angles, np.sqrt(2 * q)) + offset
        return phi, q, (m * j - energy * dj) / j**2, energy


_MODELS: weakref.WeakKeyDictionary[Any, Any] = weakref.WeakKeyDictionary()

#: Shots kept per structure, and whole cycles kept in all (:meth:`PeriodicModel._known`), the oldest dropped first.
MAX_RESULTS, MAX_CYCLES = 256, 8
_CYCLES: dict[Any, tuple[FloatArray, float]] = {}


def forget_cycles() -> None:
    """Drop every cycle kept by its inputs (the compiled functions stay): a benchmark times their integration."""
    _CYCLES.clear()
    for compiled in _COMPILED.values():
        compiled.pop("results", None)


_COMPILED: dict[Any, dict[Any, Any]] = {}
"""CVODES functions by model structure (see :attr:`PeriodicModel._compiled`), the least recently used dropped
past :data:`flyopt.sizing.shooting.MAX_STRUCTURES`."""
"""Periodic models by net torque, then by (inertia, cycle, knots). A machine's
net torque is one object (flyopt.machine.reduce.Machine.net_torque), so the
requirement, the comparison of models and the verification of one machine
share one model; the entry lives as long as that torque."""


def periodic_model(
    net_torque: NetTorqueLike, j_machine: InertiaLike, cycle_angle: float, knots: Iterable[float] = ()
) -> PeriodicModel:
    """The (cached) :class:`PeriodicModel` of one machine structure.

    The CasADi integrators and cycle functions are built once per net torque
    (its identity: the physics it stands for), inertia, cycle angle and
    knots, and reused for every flywheel and speed. :data:`BUILDS` counts
    the builds.
    """
    knots = tuple(float(k) for k in np.asarray(list(knots), dtype=float).reshape(-1))
    inertia = ("value", float(j_machine)) if isinstance(j_machine, (int, float)) else ("object", id(j_machine))
    key = (inertia, float(cycle_angle), knots)
    try:
        models = _MODELS.setdefault(net_torque, {})
    except TypeError:  # not weakly referenceable: build without the cache
        return PeriodicModel(net_torque, j_machine, cycle_angle, knots)
    if key not in models:  # the model keeps j_machine alive, so its id is not reused meanwhile
        models[key] = PeriodicModel(net_torque, j_machine, cycle_angle, knots)
    return models[key]
