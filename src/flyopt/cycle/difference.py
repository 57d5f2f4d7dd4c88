"""M_d − M_r on its pieces, exactly: the knots, crossings, areas and ΔE chain of two torque curves.

The difference of two torque curves is cut at the union of their breakpoints
and the kinks of ``abs``, ``min`` and ``max`` (:func:`kinks_of`); on each piece
it is smooth. Where both curves are piecewise linear the crossings and areas
are closed forms; with an expression the pieces are sampled, their crossings
refined (:func:`flyopt.cycle.numerics.brentq_many`) and their areas integrated
(:func:`flyopt.cycle.numerics.quad_many`), all at once. The torques' values,
the pieces and their integrals are kept on the curves (immutable), so the work
balance, the energy indicator diagram and ΔE(φ) of one machine share them.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from flyopt.cycle.numerics import EPS, accurate_cumsum, brentq_many, dip_roots, grid_steps, poles, quad_many, roots
from flyopt.cycle.torque import Array, Constant, TorqueCurve
from flyopt.errors import SceneError

SAMPLES_PER_CYCLE = 4096
"""Grid on which expression torques are bracketed for crossings."""

MAX_KINKS = SAMPLES_PER_CYCLE // 4
"""Most kinks (of ``abs``, ``min``, ``max``) an expression torque may have in one cycle: 1,024, some four samples
of :data:`SAMPLES_PER_CYCLE` between two. More are not resolved by that grid: ``abs(sin(1e4*phi))``'s 20,000
were found as 3,615, and ``abs(sin(1e5*phi))``, its kinks hidden between the samples, did not end (an outside
audit). Each kink is also a piece the quadrature takes on its own: the 2,000 cusps of
``abs(sin(1e3*phi))**0.5`` took 17 s to check (2,000 plain ``abs`` kinks some 0.7 s); a rectified sine over
a cycle of 320 turns (636 kinks) is well within it (an outside review)."""

ROUNDOFF = 8 * EPS
"""|M_d − M_r| at or below ROUNDOFF·(|M_d| + |M_r|) is the round-off of the
subtraction (or of M = W/Φ for an unknown constant) and is taken as zero, so
that equal torques never report a flywheel of 1e-12 kg*m^2."""


@dataclass
class Segments:
    """M_d − M_r on the pieces between the union of both curves' breakpoints."""

    knots: np.ndarray  # (n+1,) angles [rad]
    start: np.ndarray  # (n,) difference just right of each knot [N*m]
    end: np.ndarray  # (n,) difference just left of the next knot [N*m]
    linear: bool
    driving: Any  # TorqueCurve; Any: the expressions' own methods (round_off, __call__) are used too
    resisting: Any
    peak: float  # largest |M_d − M_r| seen (at the knots or on the sampling grid) [N*m]
    at_knots: np.ndarray | None = None  # (n+1,) the difference at the knots when neither curve steps
    noise: float | Callable[[Array], Array] = (
        0.0  # round-off bound of M_d − M_r as evaluated, a function of φ (see _round_off) [N*m]
    )
    _cache: dict[Any, Any] = field(default_factory=dict, repr=False)  # integrals and a linear curve's piece ends

    def scale(self) -> float:
        """A work scale of the cycle, peak |M_d − M_r| times Φ, for tolerances [J]."""
        return float(self.peak * (self.knots[-1] - self.knots[0])) or 1.0

    def difference(self, k: int) -> Callable[[Array], Array]:
        """M_d − M_r inside piece k as a vectorized function of φ."""
        a, b = self.knots[k], self.knots[k + 1]

        def piece(curve: Any, phi: Array) -> Array:
            if curve.is_linear:
                left = curve.limits(np.array([a]))[1][0]
                right = curve.limits(np.array([b]))[0][0]
                return left + (right - left) * (phi - a) / (b - a)
            return curve(phi)

        def f(phi: Array) -> Array:
            return piece(self.driving, phi) - piece(self.resisting, phi)

        return f

    def _ends(self, curve: TorqueCurve) -> tuple[Array, Array]:
        """A linear curve's value just right of each knot and just left of the next, per piece [N*m]."""
        key = ("ends", id(curve))
        if key not in self._cache:
            left, right = curve.limits(self.knots)
            self._cache[key] = (
                np.broadcast_to(np.asarray(right, dtype=float), self.knots.shape)[:-1],
                np.broadcast_to(np.asarray(left, dtype=float), self.knots.shape)[1:],
            )
        return self._cache[key]

    def difference_many(self, phi: Array, k: Array, side: str = "right") -> Array:
        """M_d − M_r at the angles ``phi`` inside the pieces ``k`` (arrays of one length) [N*m].

        The values of :meth:`difference`, elementwise: a linear curve is
        interpolated between its limits at the piece's ends (so that a step
        at a knot is seen from the correct side), any other curve evaluated
        (its right limit, or with ``side="left"`` its left limit: at the
        end of a piece, where the piece's own value is the left limit).
        """
        phi = np.asarray(phi, dtype=float)

        def piece(curve: Any) -> Array:
            if curve.is_linear:
                left, right = self._ends(curve)
                a, b = self.knots[k], self.knots[k + 1]
                return left[k] + (right[k] - left[k]) * (phi - a) / (b - a)
            return _values(curve, phi) if side == "right" else _sample_left(curve, phi)

        return piece(self.driving) - piece(self.resisting)

    def integrals(self) -> Array:
        """Work of M_d − M_r over each piece [J] (computed once; all pieces in one vectorized quadrature)."""
        h = np.diff(self.knots)
        if self.linear:
            return 0.5 * (self.start + self.end) * h
        if "integrals" not in self._cache:
            with self._bounded():
                self._cache["integrals"] = quad_many(
                    self.difference_many, self.knots[:-1], self.knots[1:], self.scale(), self.noise
                )
        return self._cache["integrals"]

    @contextlib.contextmanager
    def _bounded(self) -> Iterator[None]:
        """A quadrature of the difference that cannot reach its tolerance where a torque is an expression: the
        expression is unbounded between the samples the pole check sees (``1/(φ − 1)``) or swings faster than
        any quadrature resolves; a SceneError naming it, as a pole on the samples is (:func:`_check_poles`)."""
        try:
            yield
        except ArithmeticError as err:
            where = next(iter(_expression_fields(self.driving) + _expression_fields(self.resisting)), None)
            if where is None:
                raise
            raise SceneError(
                where,
                f"the torque cannot be integrated over the cycle ({err}): an expression must be finite and "
                "bounded over the whole cycle (no pole, as 1/(phi - 1)), and its swings resolvable: none too "
                "fast, over no cycle of too many turns (some thousands)",
            ) from None

    def events(self) -> tuple[Array, Array, Array]:
        """Ordered points of the cycle with the sign of M_d − M_r and ΔE there.

        Returns
        -------
        angle, sign, delta_e : ndarray
            Each piece contributes its start and end, and each zero of the
            difference inside it, with the sign on each side.
        """
        if self.linear:
            return self._linear_events()
        return self._smooth_events()

    def linear_chain(self) -> tuple[Array, Array] | None:
        """Chain of a linear difference (start, every crossing, end), without an event list.

        ΔE is needed only at the crossings, where its extremes are. Between two
        crossings every piece has the same sign, so the areas between them are
        summed in one pass (``np.add.reduceat``: no cancellation, error bounded
        by the area itself) and only the m crossing values are chained, in
        extended precision. Returns None when the difference is exactly zero
        on a knot (curves touching or coinciding): the general event scan
        decides those.

        Returns
        -------
        chain_angle, chain_delta_e : ndarray
        """
        if self.at_knots is not None:
            return self._continuous_chain()
        a, b = self.start, self.end
        n = len(a)
        if not (np.all(a) and np.all(b)):
            return None
        h = np.diff(self.knots)
        areas = 0.5 * (a + b) * h
        signs = np.empty(2 * n, dtype=bool)
        signs[0::2] = a > 0
        signs[1::2] = b > 0
        flips = np.flatnonzero(signs[1:] != signs[:-1])
        inside = (flips & 1) == 0  # between a_j and b_j: a zero inside piece j
        piece = (flips + 1) >> 1  # inside: piece j; at a knot: the knot index j+1
        jk = piece[inside]
        t = a[jk] / (a[jk] - b[jk])
        angle = self.knots[piece].copy()
        angle[inside] += t * h[jk]
        partial = np.zeros(len(flips))
        partial[inside] = 0.5 * a[jk] * t * h[jk]
        # ΔE at the knot that opens each crossing's piece: sums of whole pieces up to it.
        # piece is sorted (flips are in order), so repeated indices are neighbours: no sort needed.
        bounds = np.concatenate(([0], piece))
        first = np.concatenate(([True], bounds[1:] != bounds[:-1]))
        starts, where = bounds[first], np.cumsum(first) - 1
        prefix = np.concatenate(([0.0], np.cumsum(np.add.reduceat(areas, starts), dtype=np.longdouble)))
        delta_e = (prefix[where[1:]] + partial).astype(float)
        chain_angle = np.concatenate(([self.knots[0]], angle, [self.knots[-1]]))
        chain_de = np.concatenate(([0.0], delta_e, [float(prefix[-1])]))
        return chain_angle, chain_de

    def _continuous_chain(self) -> tuple[Array, Array] | None:
        """:meth:`linear_chain` when neither curve steps: the difference is one
        continuous broken line, so every crossing lies inside a piece (no sign
        interleaving of piece ends is needed)."""
        v, knots = self.at_knots, self.knots
        if v is None:  # no values at the knots: the general chain applies
            return None
        positive = v > 0
        j = np.flatnonzero(positive[1:] != positive[:-1])  # pieces with a zero inside
        a, b = v[j], v[j + 1]
        if not (a.all() and b.all()):  # a zero on a knot that borders a sign change
            return None  # (a zero inside a run of one sign changes nothing)
        h = np.diff(knots)
        hj = h[j]
        t = a / (a - b)
        areas = 0.5 * (v[:-1] + v[1:]) * h
        # ΔE at the knot that opens each crossing piece: whole pieces summed between crossings
        # (one sign each, no cancellation), chained in extended precision.
        lead = 0 if len(j) and j[0] == 0 else 1
        starts = j if lead == 0 else np.concatenate(([0], j))
        prefix = np.zeros(len(starts) + 1, dtype=np.longdouble)
        np.cumsum(np.add.reduceat(areas, starts), dtype=np.longdouble, out=prefix[1:])
        delta_e = (prefix[lead : lead + len(j)] + 0.5 * a * t * hj).astype(float)
        chain_angle = np.concatenate(([knots[0]], knots[j] + t * hj, [knots[-1]]))
        chain_de = np.concatenate(([0.0], delta_e, [float(prefix[-1])]))
        return chain_angle, chain_de

    def _linear_events(self) -> tuple[Array, Array, Array]:
        a, b = self.start, self.end
        h = np.diff(self.knots)
        n = len(h)
        e_knot = np.concatenate(([0.0], accurate_cumsum(0.5 * (a + b) * h)))
        crosses = (a * b) < 0
        t = np.where(crosses, a / np.where(crosses, a - b, 1.0), 0.0)
        phi_c = self.knots[:-1] + t * h
        e_c = e_knot[:-1] + 0.5 * a * t * h
        # Five slots per piece: start, before crossing, crossing, after, end.
        angle = np.stack([self.knots[:-1], phi_c, phi_c, phi_c, self.knots[1:]], axis=1)
        sign = np.stack([np.sign(a), np.sign(a), np.zeros(n), np.sign(b), np.sign(b)], axis=1)
        de = np.stack([e_knot[:-1], e_c, e_c, e_c, e_knot[1:]], axis=1)
        keep = np.stack([np.ones(n, bool), crosses, crosses, crosses, np.ones(n, bool)], axis=1)
        return angle[keep], sign[keep], de[keep]

    def _smooth_events(self) -> tuple[Array, Array, Array]:
        """:meth:`events` with an expression: every piece sampled, its zeros found and its parts
        integrated, all pieces at once (see :func:`roots`, which this does piece by piece)."""
        scale = self.scale()
        knots = self.knots
        a_all, b_all = knots[:-1], knots[1:]
        n = len(a_all)
        total = knots[-1] - knots[0]
        # the sampling grid of each piece, as np.linspace(a, b, samples + 1) makes it
        samples = np.maximum(64, (SAMPLES_PER_CYCLE * (b_all - a_all) / total).astype(int))
        first = np.concatenate(([0], np.cumsum(samples + 1)))
        piece = np.repeat(np.arange(n), samples + 1)
        local = np.arange(first[-1]) - first[piece]
        step = (b_all - a_all) / samples
        x = local * step[piece] + a_all[piece]
        last = local == samples[piece]
        x[last] = b_all[piece[last]]
        y = self.difference_many(x, piece)
        # a piece's last sample is its own end value, the left limit there: a torque that steps at the
        # knot would otherwise show a sign change that is no crossing (the next piece's value)
        y[last] = self.difference_many(x[last], piece[last], side="left")
        # the grid steps worth a look: a zero on the grid, a sign change, a dip of |f| (numerics.grid_steps)
        step_at = np.flatnonzero(~last)  # grid step from x[i] to x[i + 1], inside a piece
        k = piece[step_at]
        y0, y1 = y[step_at], y[step_at + 1]
        interior = local[step_at] > 0
        y_prev = np.where(interior, y[np.maximum(step_at - 1, 0)], np.nan)
        zero, cross, dip = grid_steps(y_prev, y0, y1, interior)
        roots_of: list[list[float]] = [[] for _ in range(n)]
        for i in np.flatnonzero(zero):
            roots_of[k[i]].append(x[step_at[i]])
        c = np.flatnonzero(cross)
        if len(c):
            p, q = x[step_at[c]], x[step_at[c] + 1]
            span = np.maximum(np.maximum(np.abs(p), np.abs(q)), b_all[k[c]] - a_all[k[c]])
            found = brentq_many(
                lambda t, j: self.difference_many(t, k[c][j]),
                p,
                q,
                y0[c],
                y1[c],
                xtol=1e-15 * span,
                rtol=4 * EPS,
                maxiter=200,
            )
            for i, r in zip(c, found):
                roots_of[k[i]].append(float(r))
        for i in np.flatnonzero(dip):  # rare: a minimum of |f| between grid points, one at a time
            j = k[i]
            f = self.difference(j)
            roots_of[j] += dip_roots(
                f, x[step_at[i] - 1], x[step_at[i]], x[step_at[i] + 1], np.sign(y0[i]), a_all[j], b_all[j], scale
            )
        # the parts between zeros: their signs (one call) and integrals (whole pieces reuse integrals())
        lo: Any = []
        hi: Any = []
        owner: Any = []
        for j in range(n):
            points = [a_all[j], *sorted(r for r in set(roots_of[j]) if a_all[j] < r < b_all[j]), b_all[j]]
            lo += points[:-1]
            hi += points[1:]
            owner += [j] * (len(points) - 1)
        lo, hi, owner = np.array(lo), np.array(hi), np.array(owner)
        sign = np.sign(self.difference_many(0.5 * (lo + hi), owner))
        whole = (lo == a_all[owner]) & (hi == b_all[owner])
        area = np.empty(len(lo))
        area[whole] = self.integrals()[owner[whole]]
        split = np.flatnonzero(~whole)
        if len(split):
            with self._bounded():
                area[split] = quad_many(
                    lambda t, j: self.difference_many(t, owner[split][j]), lo[split], hi[split], scale, self.noise
                )
        e_after = np.cumsum(area)
        e_before = np.concatenate(([0.0], e_after[:-1]))
        inner = hi < b_all[owner]  # a part that ends at a zero inside its piece
        angle = np.stack([lo, hi, hi], axis=1)
        signs = np.stack([sign, sign, np.zeros(len(lo))], axis=1)
        delta_e = np.stack([e_before, e_after, e_after], axis=1)
        keep = np.stack([np.ones(len(lo), bool), np.ones(len(lo), bool), inner], axis=1)
        return angle[keep], signs[keep], delta_e[keep]


def segments(driving: TorqueCurve, resisting: TorqueCurve, cycle_angle: float) -> Segments:
    """M_d − M_r on its pieces (:class:`Segments`), made once per pair of curves and cycle.

    Curves are immutable, so the pieces (and the integrals over them that
    :meth:`Segments.integrals` keeps) are kept with the driving curve
    (:func:`_kept`): the ExcessWork and the energy indicator diagram of one
    machine share them.
    """
    cache = _kept(driving).setdefault("segments", {})
    key = (id(resisting), cycle_angle)
    if key not in cache or cache[key][0] is not resisting:
        if len(cache) > 8:
            cache.clear()
        cache[key] = (resisting, _new_segments(driving, resisting, cycle_angle))  # resisting kept: its id stays
    return cache[key][1]


def _new_segments(driving: Any, resisting: Any, cycle_angle: float) -> Segments:
    knots = _knots(_breakpoints(driving, cycle_angle), _breakpoints(resisting, cycle_angle), cycle_angle)
    pivot = next((c.pivot for c in (driving, resisting) if isinstance(c, Constant) and c.pivot is not None), None)
    d_left, d_right = _relative_limits(driving, knots, pivot)
    r_left, r_right = _relative_limits(resisting, knots, pivot)
    at_knots = None
    if d_left is d_right and r_left is r_right:  # no steps: one difference serves both sides
        at_knots = _difference(d_right, r_right)
        start, end = at_knots[:-1], at_knots[1:]
        peak = np.max(np.abs(at_knots), initial=0.0)
    else:
        start = _difference(d_right, r_right)[:-1]
        end = _difference(d_left, r_left)[1:]
        peak = max(np.max(np.abs(start), initial=0.0), np.max(np.abs(end), initial=0.0))
    linear = driving.is_linear and resisting.is_linear
    noise: Any = 0.0
    if not linear:
        phi = np.linspace(0.0, cycle_angle, SAMPLES_PER_CYCLE + 1)
        d_values, r_values = sample(driving, phi)[0], sample(resisting, phi)[0]
        for curve in (driving, resisting):
            if not curve.is_linear:
                sample(curve, knots)  # the kinks are knots off the grid
                _check_poles(curve, phi)
        peak = max(peak, float(np.max(np.abs(d_values - r_values))))

        def noise(phi):
            return _round_off(driving, phi, sample(driving, phi)[0]) + _round_off(
                resisting, phi, sample(resisting, phi)[0]
            )

    return Segments(knots, start, end, linear, driving, resisting, float(peak), at_knots, noise)


def _round_off(curve: Any, phi: Array, values: Array) -> Array:
    """A bound on a curve's round-off at ``phi`` [N*m]: its own (an expression's running
    error bound, which sees cancellation inside it) or ROUNDOFF of its values."""
    own = ROUNDOFF * np.abs(values)
    if hasattr(curve, "round_off"):
        # where the bound is not finite (sqrt at 0, 0 ** x) fall back to ROUNDOFF |M|: the quadrature
        # may then refuse what it cannot resolve, never accept a worse result
        return np.maximum(own, np.nan_to_num(curve.round_off(phi), nan=0.0, posinf=0.0))
    if hasattr(curve, "parts"):  # a sum: its parts' bounds add up
        parts = [_round_off(p, phi, sample(p, phi)[0]) for p in curve.parts]
        return np.maximum(own, np.sum(parts, axis=0))
    return own


def _breakpoints(curve: TorqueCurve, cycle_angle: float) -> Array:
    """A curve's breakpoints and, for expressions with abs/min/max, its kinks [rad]."""
    points = curve.breakpoints()
    kinks = kinks_of(curve, cycle_angle)
    return np.union1d(points, kinks) if len(kinks) else points


def kinks_of(curve: TorqueCurve, cycle_angle: float) -> Array:
    """Angles in (0, Φ) where ``abs``, ``min`` or ``max`` make a torque kink [rad].

    Each kink function of the curve (``kink_functions``: the argument of
    ``abs``, the difference of the arguments of ``min``/``max``) is searched
    like the crossings of two curves (:func:`roots`: sign changes on the
    sampling grid, dips that reach zero between grid points, Brent's method
    to a few ulps). An infinite value keeps its sign; a NaN step is skipped
    (the analysis reports a torque that is not finite). Kept on the curve
    per cycle angle: the analysis asks several times.
    """
    functions = curve.kink_functions() if hasattr(curve, "kink_functions") else []
    if not functions:
        return np.empty(0)
    cache = curve.__dict__.setdefault("_kinks_per_cycle", {})
    if cycle_angle not in cache:
        found: list[float] = []
        over = False
        for g in functions:

            def signed(phi, g=g):  # ±inf keeps its sign, as a number Brent's method can use
                return np.nan_to_num(g(phi), nan=np.nan, posinf=1e300, neginf=-1e300)

            grid = g(np.linspace(0.0, cycle_angle, SAMPLES_PER_CYCLE + 1))
            size = float(np.max(np.abs(grid[np.isfinite(grid)]), initial=0.0))
            if size > 0.0:
                found += roots(signed, 0.0, cycle_angle, SAMPLES_PER_CYCLE, size * cycle_angle, zero_runs="ends")
            if len(found) > MAX_KINKS:  # refused as soon as it is known: the other functions' search only adds
                over = True
                break
        kinks = np.unique(np.asarray(found, dtype=float))
        if over or len(kinks) > MAX_KINKS:
            where = next(iter(_expression_fields(curve)), "")
            raise SceneError(
                where,
                f"abs, min or max make the torque kink at least {len(found)} times in the cycle, more than the "
                f"{MAX_KINKS} its sampling grid of {SAMPLES_PER_CYCLE} points resolves (allowed: at most "
                f"{MAX_KINKS} kinks a cycle; give so fine a ripple as a table, or the cycle as fewer turns)",
            )
        kinks.setflags(write=False)
        cache[cycle_angle] = kinks
    return cache[cycle_angle]


def _relative_limits(curve: TorqueCurve, knots: Array, pivot: float | None) -> tuple[Array, Array]:
    """Left and right limits of a curve at the knots, less ``pivot`` when one is set."""
    if pivot is None:
        return curve.limits(knots)
    if isinstance(curve, Constant) and curve.pivot == pivot:
        v = np.full(len(knots), curve.excess)
        return v, v
    left, right = curve.limits(knots)
    if left is right:
        rel = left - pivot
        return rel, rel
    return left - pivot, right - pivot


def _knots(first: Array, second: Array, cycle_angle: float) -> Array:
    """Sorted union of two curves' breakpoints and the cycle ends, within [0, Φ].

    A table's own breakpoints span the cycle exactly and are returned as the
    same array when the other curve has none (so its limits are read directly).
    """
    for own, other in ((first, second), (second, first)):
        if len(other) == 0 and len(own) >= 2 and own[0] == 0.0 and own[-1] == cycle_angle:
            return own
    knots = np.union1d(np.union1d(first, second), [0.0, cycle_angle])
    return knots[(knots >= 0.0) & (knots <= cycle_angle)]


def _difference(driving: Array, resisting: Array) -> Array:
    """M_d − M_r with the round-off of the subtraction set to zero."""
    diff = driving - resisting
    diff[np.abs(diff) <= ROUNDOFF * (np.abs(driving) + np.abs(resisting))] = 0.0
    return diff


VALUES_KEPT = 4
"""Evaluations of a curve that it keeps (:func:`_values`)."""


class _Transient(dict[str, Any]):
    """A cache that pickles and copies as an empty one (see :func:`_kept`)."""

    def __reduce__(self):
        return _Transient, ()


def _kept(curve: object) -> dict[str, Any]:
    """The cycle analysis's caches for one curve (a dict kept on it).

    A curve is part of its scene, and a scene is pickled to workers: these
    caches of arrays (and of pieces holding functions that do not pickle)
    must not travel with it, so the dict pickles as an empty one. (Digests of
    a scene leave out attributes whose names start with an underscore.) A
    curve without a ``__dict__`` gets a fresh dict each time (no caching).
    """
    own = getattr(curve, "__dict__", None)
    return _Transient() if own is None else own.setdefault("_analysis_kept", _Transient())


def _values(curve: Any, phi: Array) -> Array:
    """``curve(phi)`` for a curve that is not linear, its last few evaluations kept on it.

    The analysis of one cycle asks a curve for the same angles more than once
    (the sampling grid and the quadrature nodes of its own work, then of its
    difference with the other curve); curves are immutable, so the values are
    reused when the angles are equal, element for element (kept beside the
    curve, :func:`_kept`). The kept arrays are read-only.
    """
    phi = np.asarray(phi, dtype=float)
    kept = _kept(curve).setdefault("values", [])
    for angles, values in kept:
        if angles.shape == phi.shape and np.array_equal(angles, phi):
            return values
    values = np.array(curve(phi), dtype=float)
    values.setflags(write=False)
    angles = phi.copy()
    angles.setflags(write=False)
    kept.insert(0, (angles, values))
    del kept[VALUES_KEPT:]
    return values


def sample(curve: Any, phi: Array) -> tuple[Array, Array]:
    """Limits of a curve at ``phi``; expressions checked finite there."""
    if curve.is_linear:
        return curve.limits(phi)
    try:
        values = _values(curve, phi)
    except (OverflowError, ZeroDivisionError, ValueError) as err:
        raise SceneError(curve.where, f"cannot be evaluated over the cycle: {err}") from None
    bad = ~np.isfinite(values)
    if bad.any():
        at = math.degrees(phi[np.argmax(bad)])
        raise SceneError(curve.where, f"is not finite over the cycle (first at phi = {at:.6g} deg)")
    return values, values


def _sample_left(curve: Any, phi: Array) -> Array:
    """Left limits of a curve at ``phi`` (expressions checked finite there, as by :func:`sample`)."""
    if curve.is_linear:
        return curve.limits(phi)[0]
    left = np.asarray(curve.limits(phi)[0], dtype=float)
    sample(curve, phi)
    return left


def _expressions(curve: Any) -> Iterator[Any]:
    """The expression torques a curve is made of (its parts', nested sums walked), in order."""
    for part in getattr(curve, "parts", (curve,)):
        if hasattr(part, "parts"):
            yield from _expressions(part)
        elif hasattr(part, "expression"):
            yield part


def _expression_fields(curve: Any) -> list[str]:
    """The fields of the expressions a curve is made of."""
    return [part.where for part in _expressions(curve)]


def _check_poles(curve: Any, phi: Array) -> None:
    """Refuse a torque expression with a pole on the grid ``phi`` [rad] (see :func:`poles`), or one whose
    samples there pass the largest torque a machine has (:data:`flyopt.units.MAGNITUDES`).

    A torque must be finite and bounded over the whole cycle; across a pole
    (``tan φ``, ``1/(φ − 1)``) the work and ΔE have no meaning, and the
    crossing search would take the pole for a crossing of the curves; beyond
    the largest torque the cycle's work overflows (``1e308`` ended in a
    division by zero). The poles are looked for first: near one |M| passes
    any bound.
    """
    from flyopt.units import MAGNITUDES

    largest = MAGNITUDES["torque"][1]
    for part in _expressions(curve):
        values = sample(part, phi)[0]
        found = poles(part, phi, values)
        if len(found):
            at = float(found[0])
            raise SceneError(
                part.where,
                f"the expression has a pole near φ = {at:.6g} rad "
                f"({math.degrees(at):.6g} deg; |M| grows without bound): a torque must be "
                "finite over the whole cycle",
            )
        over = np.abs(values) > largest  # the tables' bound (io.fields.first_too_large)
        if over.any():
            k = int(np.argmax(over))
            raise SceneError(
                part.where,
                f"the expression reaches {values[k]:.6g} N*m at φ = {phi[k]:.6g} rad ({math.degrees(phi[k]):.6g} deg): "
                f"beyond the largest torque a machine has, {largest:g} N*m (flyopt.units.MAGNITUDES)",
            )
