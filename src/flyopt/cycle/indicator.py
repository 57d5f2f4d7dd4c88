"""Cycle analysis: work balance, the energy indicator diagram and A_max.

The excess work from the start of the cycle is

    ΔE(φ) = ∫_0^φ (M_d − M_r) dφ,

its largest span over the cycle is the maximum fluctuation of energy
A_max = max ΔE − min ΔE, reached at crossings of the two torque curves
(docs/flywheel-design.md, section 4). flyopt computes it exactly rather than by sampling:

- where both curves are piecewise linear (tables and constants), the
  difference is linear between the union of their breakpoints; the crossing
  inside a piece is at t = a/(a − b) and every area is a closed-form
  trapezoid, summed in extended precision;
- where an expression is involved, crossings are found by bracketing on a
  fine grid plus a search for near-tangent dips, refined with Brent's method,
  the kinks of ``abs``, ``min`` and ``max`` likewise, and the areas between
  them by adaptive Gauss–Kronrod quadrature to 1e-13 relative (or to the
  round-off of the torques as evaluated, where that is larger). The pieces
  are sampled, their crossings refined and their areas integrated all at
  once, in vectorized calls of the torques (:func:`brentq_many`,
  :func:`_quad_many`).

A cycle whose net work does not vanish is refused (non-periodic fluctuation).
"""

import math
from dataclasses import dataclass, field

import numpy as np

from flyopt.cycle.torque import Constant, PiecewiseLinear
from flyopt.errors import NonPeriodicCycle, SceneError

BALANCE_TOLERANCE = 1e-9
"""Largest accepted |net work| per cycle, relative to the cycle work."""

SAMPLES_PER_CYCLE = 4096
"""Grid on which expression torques are bracketed for crossings."""

QUAD_EPSREL = 1e-13
"""Relative tolerance of the adaptive quadrature of expression torques."""

POLE_GROWTH = 1e3
"""A sign change of a torque across which the smaller |M| at the bracket's ends grows
by more than this factor, as the grid bracket is halved down to adjacent floats, is
a pole: at a crossing of zero |M| falls by ~h/ulp (1e12), at a finite jump it stays,
at a pole it grows by ~h/ulp."""

EPS = float(np.finfo(float).eps)
ROUNDOFF = 8 * EPS
"""|M_d − M_r| at or below ROUNDOFF·(|M_d| + |M_r|) is the round-off of the
subtraction (or of M = W/Φ for an unknown constant) and is taken as zero, so
that equal torques never report a flywheel of 1e-12 kg*m^2."""


@dataclass(frozen=True)
class EnergyIndicator:
    """The energy indicator diagram of one cycle and what follows from it.

    Attributes
    ----------
    cycle_angle : float
        Angle of one cycle Φ [rad].
    work_driving, work_resisting : float
        Work of each torque over one cycle [J].
    chain_angle : ndarray or None
        Angles of the chain points [rad]: the cycle start, every crossing of
        the curves, the cycle end (None for scenes given as net areas).
    chain_delta_e : ndarray
        Excess work ΔE at the chain points [J].
    a_max : float
        Maximum fluctuation of energy [J].
    index_max, index_min : int
        Chain points where ΔE is largest (ω_max) and smallest (ω_min).
    imbalance : float
        Net work over the cycle left by round-off [J].
    """

    cycle_angle: float
    work_driving: float
    work_resisting: float
    chain_angle: np.ndarray | None
    chain_delta_e: np.ndarray
    a_max: float
    index_max: int
    index_min: int
    imbalance: float

    @property
    def driving_mean(self):
        """Mean driving torque M_d = W_d/Φ [N*m]."""
        return self.work_driving / self.cycle_angle

    @property
    def resisting_mean(self):
        """Mean resisting torque M_r = W_r/Φ [N*m]."""
        return self.work_resisting / self.cycle_angle

    @property
    def angle_omega_max(self):
        """Angle of the highest speed [rad] (None for net-area scenes)."""
        return None if self.chain_angle is None else float(self.chain_angle[self.index_max])

    @property
    def angle_omega_min(self):
        """Angle of the lowest speed [rad] (None for net-area scenes)."""
        return None if self.chain_angle is None else float(self.chain_angle[self.index_min])

    @property
    def areas(self):
        """Signed areas between consecutive chain points [J] (+ surplus, − deficit)."""
        return np.diff(self.chain_delta_e)


def solve_unknown_constant(driving, resisting, cycle_angle):
    """Replace an unknown constant torque by the value that balances the cycle.

    M = W_other / Φ (docs/flywheel-design.md, section 4).

    Returns
    -------
    tuple
        ``(driving, resisting)`` with the unknown one made known.
    """
    if isinstance(driving, Constant) and driving.unknown:
        return _balancing_constant(resisting, cycle_angle), resisting
    if isinstance(resisting, Constant) and resisting.unknown:
        return driving, _balancing_constant(driving, cycle_angle)
    return driving, resisting


def _balancing_constant(curve, cycle_angle):
    """The constant whose work over the cycle equals that of ``curve``.

    Against a table it is kept as pivot + excess (a two-pass mean): the
    pivot is the plain mean W/Φ, the excess the mean of (table − pivot). For
    a large mean with a small ripple every difference is exact (Sterbenz:
    the values lie within a factor two of the pivot); otherwise the excess is
    a small correction of an already good mean.
    """
    if isinstance(curve, PiecewiseLinear):
        pivot = curve.work(cycle_angle) / cycle_angle
        rel = curve.values - pivot
        excess = float(np.sum((rel[1:] + rel[:-1]) * np.diff(curve.angles))) / (2 * cycle_angle)
        return Constant(pivot + excess, pivot=pivot, excess=excess)
    return Constant(work(curve, cycle_angle) / cycle_angle)


def work(curve, cycle_angle):
    """Work of one torque curve over one cycle, ∫_0^Φ M dφ [J].

    Curves are immutable, so the quadrature of a nonlinear one is done once
    per cycle angle and kept on the curve (solving an unknown constant and
    building the indicator diagram both need it).
    """
    if curve.is_linear:
        return curve.work(cycle_angle)
    cache = curve.__dict__.setdefault("_work_per_cycle", {})
    if cycle_angle not in cache:
        zero = Constant(0.0)
        cache[cycle_angle] = float(np.sum(_segments(curve, zero, cycle_angle).integrals(), dtype=np.longdouble))
    return cache[cycle_angle]


def energy_indicator(driving, resisting, cycle_angle):
    """Exact energy indicator diagram of two torque curves over one cycle.

    Parameters
    ----------
    driving, resisting : PiecewiseLinear, Constant or ExpressionTorque
        Equivalent torques at the reference shaft [N*m]; a Constant may be
        unknown and is then solved from the work balance.
    cycle_angle : float
        Angle of one cycle Φ [rad].

    Returns
    -------
    EnergyIndicator

    Raises
    ------
    NonPeriodicCycle
        When |W_d − W_r| exceeds ``BALANCE_TOLERANCE`` of the cycle work.
    """
    driving, resisting = solve_unknown_constant(driving, resisting, cycle_angle)
    w_d, w_r = work(driving, cycle_angle), work(resisting, cycle_angle)
    segments = _segments(driving, resisting, cycle_angle)
    fast = segments.linear_chain() if segments.linear else None
    if fast is not None:
        chain_angle, chain_de = fast
        imbalance = float(chain_de[-1])
    else:
        angle, sign, delta_e = segments.events()
        imbalance = float(delta_e[-1])
        crossings = _crossings(sign)
        chain = np.concatenate(([0], crossings, [len(angle) - 1]))
        chain = chain[np.concatenate(([True], np.diff(angle[chain]) > 0))] if len(chain) > 2 else chain
        chain_angle, chain_de = angle[chain], delta_e[chain]
    _check_balance(imbalance, max(abs(w_d), abs(w_r)), segments.scale())
    # Extremes of ΔE are at crossings (or the cycle ends): take them from the chain.
    index_max, index_min = _extremes(chain_de, segments.scale())
    return EnergyIndicator(
        cycle_angle=cycle_angle,
        work_driving=w_d,
        work_resisting=w_r,
        chain_angle=chain_angle,
        chain_delta_e=chain_de,
        a_max=float(chain_de[index_max] - chain_de[index_min]),
        index_max=index_max,
        index_min=index_min,
        imbalance=imbalance,
    )


def energy_indicator_from_areas(areas, cycle_angle):
    """Energy indicator diagram from the signed net areas between the curves.

    Parameters
    ----------
    areas : sequence of float
        Signed areas between the torque curves in their order over the cycle,
        already converted to energy [J] (+ surplus, − deficit).
    cycle_angle : float
        Angle of one cycle Φ [rad]; the crossing angles are not known.

    Returns
    -------
    EnergyIndicator
        With ``chain_angle`` None; works are the sums of surpluses/deficits.
    """
    areas = np.asarray(areas, dtype=float)
    chain = np.concatenate(([0.0], np.cumsum(areas.astype(np.longdouble)).astype(float)))
    surplus = math.fsum(a for a in areas if a > 0)
    deficit = -math.fsum(a for a in areas if a < 0)
    imbalance = math.fsum(areas)
    _check_balance(imbalance, max(surplus, deficit), surplus + deficit)
    index_max, index_min = _extremes(chain, surplus + deficit)
    return EnergyIndicator(
        cycle_angle=cycle_angle,
        work_driving=surplus,
        work_resisting=deficit,
        chain_angle=None,
        chain_delta_e=chain,
        a_max=float(chain[index_max] - chain[index_min]),
        index_max=index_max,
        index_min=index_min,
        imbalance=imbalance,
    )


class ExcessWork:
    """ΔE(φ) = ∫_0^φ (M_d − M_r) dφ as an exact function of the angle.

    Piecewise-linear torques give a piecewise-quadratic ΔE, evaluated in
    closed form; with an expression, ΔE is the knot value plus an adaptive
    quadrature from the piece's start.

    Attributes
    ----------
    knots : ndarray
        Angles where M_d − M_r may jump or change slope [rad]; ΔE is smooth
        between them.
    driving, resisting : torque curves (an unknown constant already solved)
    """

    def __init__(self, driving, resisting, cycle_angle):
        self.driving, self.resisting = solve_unknown_constant(driving, resisting, cycle_angle)
        self._segments = _segments(self.driving, self.resisting, cycle_angle)
        self.knots = self._segments.knots
        self._at_knots = np.concatenate(([0.0], accurate_cumsum(self._segments.integrals())))
        self.cycle_angle = cycle_angle

    def __call__(self, phi):
        """ΔE at the angles ``phi`` in [0, Φ] [J] (vectorized)."""
        phi = np.asarray(phi, dtype=float)
        k = np.clip(np.searchsorted(self.knots, phi, side="right") - 1, 0, len(self.knots) - 2)
        seg = self._segments
        h = np.diff(self.knots)[k]
        dx = phi - self.knots[k]
        if seg.linear:
            a, b = seg.start[k], seg.end[k]
            slope = np.where(h > 0, (b - a) / np.where(h > 0, h, 1.0), 0.0)
            return self._at_knots[k] + a * dx + 0.5 * slope * dx * dx
        flat = np.atleast_1d(phi).ravel()
        ks = np.atleast_1d(k).ravel()
        parts = _quad_many(lambda t, i: seg.difference_many(t, ks[i]), self.knots[ks], flat, seg.scale(), seg.noise)
        return (self._at_knots[ks] + parts).reshape(phi.shape)

    @property
    def at_knots(self):
        """ΔE at :attr:`knots` [J] (sums of the pieces' integrals, in extended precision)."""
        return self._at_knots

    def scale(self):
        """Work scale of the cycle, peak |M_d − M_r| times Φ, for tolerances [J]."""
        return self._segments.scale()

    def net_torque(self, phi):
        """M_d − M_r at ``phi`` [N*m] (right limits at steps; vectorized)."""
        phi = np.asarray(phi, dtype=float)
        return (_sample(self.driving, phi)[1] - _sample(self.resisting, phi)[1]).astype(float)


def required_inertia(a_max, omega_mean, delta, j_constant=0.0):
    """Flywheel inertia at the reference shaft by the constant-inertia method.

    J_F = A_max / (ω_m² δ) − J_c  (docs/flywheel-design.md, section 5).

    Parameters
    ----------
    a_max : float
        Maximum fluctuation of energy [J].
    omega_mean : float
        Mean speed of the reference shaft [rad/s].
    delta : float
        Allowed coefficient of speed fluctuation [-].
    j_constant : float
        Machine's own constant equivalent inertia J_c [kg*m^2].

    Returns
    -------
    float
        J_F [kg*m^2]; zero or negative means no flywheel is needed.
    """
    return a_max / (omega_mean**2 * delta) - j_constant


def speed_extremes(omega_mean, delta):
    """Highest and lowest speed of a cycle of mean speed ω_m and fluctuation δ [rad/s].

    ω_max = ω_m (1 + δ/2), ω_min = ω_m (1 − δ/2), from δ = (ω_max − ω_min)/ω_m
    and ω_m = (ω_max + ω_min)/2 (docs/flywheel-design.md, section 2): the
    speeds of the energy method, where the rim speed is checked.

    Parameters
    ----------
    omega_mean : float or ndarray
        ω_m [rad/s].
    delta : float or ndarray
        δ [-].

    Returns
    -------
    tuple
        (ω_max, ω_min) [rad/s].
    """
    return omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)


# -- internals -----------------------------------------------------------------


CUMSUM_BLOCK = 64


def accurate_cumsum(terms):
    """Prefix sums with an error of ~CUMSUM_BLOCK·eps instead of n·eps.

    Float64 running sums inside blocks of CUMSUM_BLOCK terms, plus block
    offsets summed in extended precision: exact enough for ΔE chains of
    10^5 pieces to stay within 1e-13 of exact rational arithmetic, at the
    cost of a few vectorized passes.
    """
    terms = np.asarray(terms, dtype=float)
    n = len(terms)
    if n <= 4 * CUMSUM_BLOCK:
        return np.cumsum(terms.astype(np.longdouble)).astype(float)
    blocks = np.zeros(-(-n // CUMSUM_BLOCK) * CUMSUM_BLOCK)
    blocks[:n] = terms
    blocks = blocks.reshape(-1, CUMSUM_BLOCK)
    inner = np.cumsum(blocks, axis=1)
    offsets = np.zeros(len(blocks), dtype=np.longdouble)
    np.cumsum(blocks.sum(axis=1)[:-1], dtype=np.longdouble, out=offsets[1:])
    return (inner + offsets.astype(float)[:, None]).ravel()[:n]


def _extremes(chain, scale):
    """First chain points of largest and smallest ΔE; ties within round-off go to the earlier one."""
    tie = 64 * EPS * scale
    return int(np.argmax(chain >= chain.max() - tie)), int(np.argmax(chain <= chain.min() + tie))


def _check_balance(imbalance, cycle_work, fluctuation_scale):
    """Refuse a cycle whose net work exceeds BALANCE_TOLERANCE of its work.

    The work is the larger of the cycle work of the torques and the work
    scale of their difference (peak |M_d − M_r| Φ): a zero-mean torque
    (a gravity load, sin φ) against an unknown constant has no cycle work
    to speak of, yet balances.
    """
    scale = max(cycle_work, fluctuation_scale)
    if abs(imbalance) > BALANCE_TOLERANCE * scale:
        raise NonPeriodicCycle(imbalance, cycle_work)


def _crossings(sign):
    """Indices of the events where the sign of M_d − M_r changes.

    A flip is placed at the first event after the last one of the old sign:
    a zero of a linear piece, the first point of a run where the curves
    coincide, or the right side of a vertical step.
    """
    nonzero = np.flatnonzero(sign)
    if len(nonzero) < 2:
        return np.empty(0, dtype=int)
    flips = np.flatnonzero(sign[nonzero[1:]] != sign[nonzero[:-1]])
    return nonzero[flips] + 1


@dataclass
class _Segments:
    """M_d − M_r on the pieces between the union of both curves' breakpoints."""

    knots: np.ndarray  # (n+1,) angles [rad]
    start: np.ndarray  # (n,) difference just right of each knot [N*m]
    end: np.ndarray  # (n,) difference just left of the next knot [N*m]
    linear: bool
    driving: object
    resisting: object
    peak: float  # largest |M_d − M_r| seen (at the knots or on the sampling grid) [N*m]
    at_knots: np.ndarray | None = None  # (n+1,) the difference at the knots when neither curve steps
    noise: object = 0.0  # round-off bound of M_d − M_r as evaluated, a function of φ (see _round_off) [N*m]
    _cache: dict = field(default_factory=dict, repr=False)  # integrals and a linear curve's piece ends

    def scale(self):
        """A work scale of the cycle, peak |M_d − M_r| times Φ, for tolerances [J]."""
        return float(self.peak * (self.knots[-1] - self.knots[0])) or 1.0

    def difference(self, k):
        """M_d − M_r inside piece k as a vectorized function of φ."""
        a, b = self.knots[k], self.knots[k + 1]

        def piece(curve, phi):
            if curve.is_linear:
                left = curve.limits(np.array([a]))[1][0]
                right = curve.limits(np.array([b]))[0][0]
                return left + (right - left) * (phi - a) / (b - a)
            return curve(phi)

        def f(phi):
            return piece(self.driving, phi) - piece(self.resisting, phi)

        return f

    def _ends(self, curve):
        """A linear curve's value just right of each knot and just left of the next, per piece [N*m]."""
        key = ("ends", id(curve))
        if key not in self._cache:
            left, right = curve.limits(self.knots)
            self._cache[key] = (
                np.broadcast_to(np.asarray(right, dtype=float), self.knots.shape)[:-1],
                np.broadcast_to(np.asarray(left, dtype=float), self.knots.shape)[1:],
            )
        return self._cache[key]

    def difference_many(self, phi, k, side="right"):
        """M_d − M_r at the angles ``phi`` inside the pieces ``k`` (arrays of one length) [N*m].

        The values of :meth:`difference`, elementwise: a linear curve is
        interpolated between its limits at the piece's ends (so that a step
        at a knot is seen from the correct side), any other curve evaluated
        (its right limit, or with ``side="left"`` its left limit: at the
        end of a piece, where the piece's own value is the left limit).
        """
        phi = np.asarray(phi, dtype=float)

        def piece(curve):
            if curve.is_linear:
                left, right = self._ends(curve)
                a, b = self.knots[k], self.knots[k + 1]
                return left[k] + (right[k] - left[k]) * (phi - a) / (b - a)
            return _values(curve, phi) if side == "right" else _sample_left(curve, phi)

        return piece(self.driving) - piece(self.resisting)

    def integrals(self):
        """Work of M_d − M_r over each piece [J] (computed once; all pieces in one vectorized quadrature)."""
        h = np.diff(self.knots)
        if self.linear:
            return 0.5 * (self.start + self.end) * h
        if "integrals" not in self._cache:
            self._cache["integrals"] = _quad_many(
                self.difference_many, self.knots[:-1], self.knots[1:], self.scale(), self.noise
            )
        return self._cache["integrals"]

    def events(self):
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

    def linear_chain(self):
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

    def _continuous_chain(self):
        """:meth:`linear_chain` when neither curve steps: the difference is one
        continuous broken line, so every crossing lies inside a piece (no sign
        interleaving of piece ends is needed)."""
        v, knots = self.at_knots, self.knots
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

    def _linear_events(self):
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

    def _smooth_events(self):
        """:meth:`events` with an expression: every piece sampled, its zeros found and its parts
        integrated, all pieces at once (see :func:`_roots`, which this does piece by piece)."""
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
        # the grid steps worth a look: a zero on the grid, a sign change, a dip of |f| (as in _roots)
        step_at = np.flatnonzero(~last)  # grid step from x[i] to x[i + 1], inside a piece
        k = piece[step_at]
        y0, y1 = y[step_at], y[step_at + 1]
        interior = local[step_at] > 0
        y_prev = np.where(interior, y[np.maximum(step_at - 1, 0)], np.nan)
        zero = interior & (y0 == 0.0)
        s0, s1, s_prev = np.sign(y0), np.sign(y1), np.sign(y_prev)
        cross = ~zero & (s0 * s1 < 0)
        dip = (
            ~zero
            & ~cross
            & interior
            & (np.abs(y0) < np.abs(y_prev))
            & (np.abs(y0) < np.abs(y1))
            & (s0 * s_prev > 0)
            & (s0 * s1 > 0)
        )
        roots_of = [[] for _ in range(n)]
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
            roots_of[j] += _dip_roots(
                f, x[step_at[i] - 1], x[step_at[i]], x[step_at[i] + 1], np.sign(y0[i]), a_all[j], b_all[j], scale
            )
        # the parts between zeros: their signs (one call) and integrals (whole pieces reuse integrals())
        lo, hi, owner = [], [], []
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
            area[split] = _quad_many(
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


def _segments(driving, resisting, cycle_angle):
    """M_d − M_r on its pieces (:class:`_Segments`), made once per pair of curves and cycle.

    Curves are immutable, so the pieces (and the integrals over them that
    :meth:`_Segments.integrals` keeps) are kept with the driving curve
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


def _new_segments(driving, resisting, cycle_angle):
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
    noise = 0.0
    if not linear:
        phi = np.linspace(0.0, cycle_angle, SAMPLES_PER_CYCLE + 1)
        d_values, r_values = _sample(driving, phi)[0], _sample(resisting, phi)[0]
        for curve in (driving, resisting):
            if not curve.is_linear:
                _sample(curve, knots)  # the kinks are knots off the grid
                _check_poles(curve, phi)
        peak = max(peak, float(np.max(np.abs(d_values - r_values))))

        def noise(phi):
            return _round_off(driving, phi, _sample(driving, phi)[0]) + _round_off(
                resisting, phi, _sample(resisting, phi)[0]
            )

    return _Segments(knots, start, end, linear, driving, resisting, float(peak), at_knots, noise)


def _round_off(curve, phi, values):
    """A bound on a curve's round-off at ``phi`` [N*m]: its own (an expression's running
    error bound, which sees cancellation inside it) or ROUNDOFF of its values."""
    own = ROUNDOFF * np.abs(values)
    if hasattr(curve, "round_off"):
        # where the bound is not finite (sqrt at 0, 0 ** x) fall back to ROUNDOFF |M|: the quadrature
        # may then refuse what it cannot resolve, never accept a worse result
        return np.maximum(own, np.nan_to_num(curve.round_off(phi), nan=0.0, posinf=0.0))
    if hasattr(curve, "parts"):  # a sum: its parts' bounds add up
        parts = [_round_off(p, phi, _sample(p, phi)[0]) for p in curve.parts]
        return np.maximum(own, np.sum(parts, axis=0))
    return own


def _breakpoints(curve, cycle_angle):
    """A curve's breakpoints and, for expressions with abs/min/max, its kinks [rad]."""
    points = curve.breakpoints()
    kinks = kinks_of(curve, cycle_angle)
    return np.union1d(points, kinks) if len(kinks) else points


def kinks_of(curve, cycle_angle):
    """Angles in (0, Φ) where ``abs``, ``min`` or ``max`` make a torque kink [rad].

    Each kink function of the curve (``kink_functions``: the argument of
    ``abs``, the difference of the arguments of ``min``/``max``) is searched
    like the crossings of two curves (:func:`_roots`: sign changes on the
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
        found = []
        for g in functions:

            def signed(phi, g=g):  # ±inf keeps its sign, as a number Brent's method can use
                return np.nan_to_num(g(phi), nan=np.nan, posinf=1e300, neginf=-1e300)

            grid = g(np.linspace(0.0, cycle_angle, SAMPLES_PER_CYCLE + 1))
            size = float(np.max(np.abs(grid[np.isfinite(grid)]), initial=0.0))
            if size > 0.0:
                found += _roots(signed, 0.0, cycle_angle, SAMPLES_PER_CYCLE, size * cycle_angle, zero_runs="ends")
        kinks = np.unique(np.asarray(found, dtype=float))
        kinks.setflags(write=False)
        cache[cycle_angle] = kinks
    return cache[cycle_angle]


def _relative_limits(curve, knots, pivot):
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


def _knots(first, second, cycle_angle):
    """Sorted union of two curves' breakpoints and the cycle ends, within [0, Φ].

    A table's own breakpoints span the cycle exactly and are returned as the
    same array when the other curve has none (so its limits are read directly).
    """
    for own, other in ((first, second), (second, first)):
        if len(other) == 0 and len(own) >= 2 and own[0] == 0.0 and own[-1] == cycle_angle:
            return own
    knots = np.union1d(np.union1d(first, second), [0.0, cycle_angle])
    return knots[(knots >= 0.0) & (knots <= cycle_angle)]


def _difference(driving, resisting):
    """M_d − M_r with the round-off of the subtraction set to zero."""
    diff = driving - resisting
    diff[np.abs(diff) <= ROUNDOFF * (np.abs(driving) + np.abs(resisting))] = 0.0
    return diff


VALUES_KEPT = 4
"""Evaluations of a curve that it keeps (:func:`_values`)."""


class _Transient(dict):
    """A cache that pickles and copies as an empty one (see :func:`_kept`)."""

    def __reduce__(self):
        return _Transient, ()


def _kept(curve):
    """The cycle analysis's caches for one curve (a dict kept on it).

    A curve is part of its scene, and a scene is pickled to workers: these
    caches of arrays (and of pieces holding functions that do not pickle)
    must not travel with it, so the dict pickles as an empty one. (Digests of
    a scene leave out attributes whose names start with an underscore.) A
    curve without a ``__dict__`` gets a fresh dict each time (no caching).
    """
    own = getattr(curve, "__dict__", None)
    return _Transient() if own is None else own.setdefault("_analysis_kept", _Transient())


def _values(curve, phi):
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


def _sample(curve, phi):
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


def _sample_left(curve, phi):
    """Left limits of a curve at ``phi`` (expressions checked finite there, as by :func:`_sample`)."""
    if curve.is_linear:
        return curve.limits(phi)[0]
    left = np.asarray(curve.limits(phi)[0], dtype=float)
    _sample(curve, phi)
    return left


def _check_poles(curve, phi):
    """Refuse a torque expression with a pole on the grid ``phi`` [rad] (see :func:`_poles`).

    A torque must be finite and bounded over the whole cycle; across a pole
    (``tan φ``, ``1/(φ − 1)``) the work and ΔE have no meaning, and the
    crossing search would take the pole for a crossing of the curves.
    """
    for part in getattr(curve, "parts", (curve,)):
        if hasattr(part, "parts"):
            _check_poles(part, phi)
        elif hasattr(part, "expression"):
            poles = _poles(part, phi, _sample(part, phi)[0])
            if len(poles):
                at = float(poles[0])
                raise SceneError(
                    part.where,
                    f"the expression has a pole near φ = {at:.6g} rad "
                    f"({math.degrees(at):.6g} deg; |M| grows without bound): a torque must be "
                    "finite over the whole cycle",
                )


def _poles(f, phi, values):
    """Angles of the sign changes of f on a grid across which |f| grows without bound.

    Every bracket [φ_k, φ_k+1] where f changes sign is halved (all at once)
    until its ends are adjacent floats, keeping the sign change inside. At a
    zero of a continuous f the end values shrink to round-off; at a pole the
    smaller of them grows past ``POLE_GROWTH`` times the smaller grid value
    (or f is not finite there).

    Parameters
    ----------
    f : callable
        Vectorized function of φ [rad].
    phi, values : ndarray
        The grid [rad] and f on it (finite).

    Returns
    -------
    ndarray
        The poles found [rad], in order.
    """
    k = np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)
    lo, hi, f_lo, f_hi = phi[k], phi[k + 1], values[k], values[k + 1]
    grid = np.minimum(np.abs(f_lo), np.abs(f_hi))  # the grid may land within an ulp of the pole
    infinite = np.zeros(len(k), dtype=bool)
    for _ in range(1100):  # a bracket in [0, 1e300] reaches adjacent floats in ~1100
        mid = 0.5 * (lo + hi)
        active = (lo < mid) & (mid < hi) & ~infinite
        if not active.any():
            break
        with np.errstate(all="ignore"):
            f_mid = np.asarray(f(mid[active]), dtype=float)
        infinite[active] = ~np.isfinite(f_mid)
        low_side = np.zeros(len(k), dtype=bool)
        low_side[active] = np.sign(f_mid) == np.sign(f_lo[active])
        high_side = active & ~low_side & ~infinite
        zero = np.zeros(len(k), dtype=bool)
        zero[active] = f_mid == 0.0
        values_mid = np.zeros(len(k))
        values_mid[active] = f_mid
        lo, f_lo = np.where(low_side, mid, lo), np.where(low_side, values_mid, f_lo)
        hi, f_hi = np.where(high_side, mid, hi), np.where(high_side, values_mid, f_hi)
        lo = np.where(zero, hi, lo)  # f = 0 exactly: a zero, bracket closed
    end = np.minimum(np.abs(f_lo), np.abs(f_hi))
    return np.sort(lo[infinite | (end > POLE_GROWTH * grid)])


def _roots(f, a, b, samples, scale, zero_runs="all"):
    """All zeros of f in the open interval (a, b), in order.

    Sign changes on a grid are refined by Brent's method; a grid point whose
    |f| dips below both neighbours is searched for a minimum that reaches
    zero (two close crossings or a tangent touch that the grid would miss).
    Grid points where f is exactly zero are zeros; with ``zero_runs="ends"``
    only the first and last point of a run of them are (f vanishing over a
    stretch: for a kink search only its ends matter).
    """
    x = np.linspace(a, b, samples + 1)
    y = f(x)
    roots = []

    def brent(p, q):
        from scipy import optimize  # only where a zero is refined: a constant-inertia solve never loads it

        return optimize.brentq(f, p, q, xtol=1e-15 * max(abs(p), abs(q), b - a), rtol=4 * EPS, maxiter=200)

    # the grid steps worth a look, found at once: a zero on the grid, a sign change, a dip of |f|
    y0, y1 = y[:-1], y[1:]
    y_prev = np.concatenate(([np.nan], y[:-2]))
    interior = np.arange(samples) > 0
    zero = interior & (y0 == 0.0)
    if zero_runs == "ends":
        zero &= (y_prev != 0.0) | (y1 != 0.0)
    s0, s1, s_prev = np.sign(y0), np.sign(y1), np.sign(y_prev)  # signs: products of huge values overflow
    cross = ~zero & (s0 * s1 < 0)
    dip = (
        ~zero
        & ~cross
        & interior
        & (np.abs(y0) < np.abs(y_prev))
        & (np.abs(y0) < np.abs(y1))
        & (s0 * s_prev > 0)
        & (s0 * s1 > 0)
    )
    for k in np.flatnonzero(zero | cross | dip):
        if zero[k]:
            roots.append(x[k])
        elif cross[k]:
            roots.append(brent(x[k], x[k + 1]))
        else:
            roots += _dip_roots(f, x[k - 1], x[k], x[k + 1], np.sign(y0[k]), a, b, scale)
    return sorted(r for r in set(roots) if a < r < b)


def _dip_roots(f, left, mid, right, sign, a, b, scale):
    """Zeros of f near a grid point ``mid`` where |f| dips below both neighbours (see :func:`_roots`).

    The minimum of sign·f on [left, right] is searched; if it crosses zero,
    the two crossings on either side are refined by Brent's method; if it
    only touches zero (to 1e-15 of the work scale), the touching point is a
    zero. ``a``, ``b`` are the ends of the whole interval searched.
    """
    from scipy import optimize

    del mid  # the dip's grid point: the search covers both of its grid steps
    tiny = 1e-15 * scale / max(b - a, 1e-300)

    def brent(p, q):
        return optimize.brentq(f, p, q, xtol=1e-15 * max(abs(p), abs(q), b - a), rtol=4 * EPS, maxiter=200)

    res = optimize.minimize_scalar(
        lambda p: sign * f(np.array([p]))[0], bounds=(left, right), method="bounded", options={"xatol": 1e-14 * (b - a)}
    )
    if res.fun < 0:  # res.fun = s·f at the dip: the dip crosses zero
        return [brent(left, res.x), brent(res.x, right)]
    if abs(res.fun) <= tiny:
        return [float(res.x)]  # touches zero without crossing
    return []


def brentq_many(f, a, b, fa, fb, xtol, rtol=4 * EPS, maxiter=200):
    """Zeros of many functions at once, each bracketed, by Brent's method.

    Brent's method (Brent 1973, ch. 4: inverse quadratic extrapolation
    or linear interpolation, bisection when a step would not shrink the
    bracket enough) in the form of scipy.optimize.brentq, operation for
    operation, run on every bracket in step: each iteration calls ``f``
    once on the brackets not yet converged. Each zero is found to
    ``xtol + rtol·|x|``, as scipy.optimize.brentq finds it.

    Parameters
    ----------
    f : callable (x, index) -> ndarray
        The functions: values at the points ``x`` of the problems ``index``
        (both arrays of the same length).
    a, b : ndarray
        Bracket ends.
    fa, fb : ndarray
        f at the ends, of opposite signs (or one zero).
    xtol, rtol : float
        Absolute and relative tolerance of each zero.
    maxiter : int

    Returns
    -------
    ndarray
        The zeros.

    Raises
    ------
    ValueError
        f(a) and f(b) of the same sign.
    RuntimeError
        A bracket did not converge in ``maxiter`` iterations.
    """
    xpre, xcur = np.array(a, dtype=float), np.array(b, dtype=float)
    fpre, fcur = np.array(fa, dtype=float), np.array(fb, dtype=float)
    n = len(xpre)
    if np.any(fpre * fcur > 0):
        raise ValueError("brentq_many: f(a) and f(b) must have different signs")
    if n <= BRENT_SCALAR:
        return _brentq_few(
            f, xpre, xcur, fpre, fcur, np.broadcast_to(np.asarray(xtol, dtype=float), (n,)), rtol, maxiter
        )
    root = np.where(fpre == 0, xpre, xcur)
    active = (fpre != 0) & (fcur != 0)
    xblk, fblk, spre, scur = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(maxiter):
            if not active.any():
                return root
            m = active
            flip = m & (fpre * fcur < 0)
            xblk, fblk = np.where(flip, xpre, xblk), np.where(flip, fpre, fblk)
            width = xcur - xpre
            spre, scur = np.where(flip, width, spre), np.where(flip, width, scur)
            swap = m & (np.abs(fblk) < np.abs(fcur))
            xpre, xcur, xblk = np.where(swap, xcur, xpre), np.where(swap, xblk, xcur), np.where(swap, xcur, xblk)
            fpre, fcur, fblk = np.where(swap, fcur, fpre), np.where(swap, fblk, fcur), np.where(swap, fcur, fblk)
            delta = (xtol + rtol * np.abs(xcur)) / 2
            sbis = (xblk - xcur) / 2
            converged = m & ((fcur == 0) | (np.abs(sbis) < delta))
            root = np.where(converged, xcur, root)
            active = m = m & ~converged
            if not m.any():
                return root
            step_ok = m & (np.abs(spre) > delta) & (np.abs(fcur) < np.abs(fpre))
            interpolate = xpre == xblk
            dpre = (fpre - fcur) / (xpre - xcur)
            dblk = (fblk - fcur) / (xblk - xcur)
            stry = np.where(
                interpolate,
                -fcur * (xcur - xpre) / (fcur - fpre),
                -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre)),
            )
            good = step_ok & (2 * np.abs(stry) < np.minimum(np.abs(spre), 3 * np.abs(sbis) - delta))
            spre, scur = np.where(m, np.where(good, scur, sbis), spre), np.where(m, np.where(good, stry, sbis), scur)
            xpre, fpre = np.where(m, xcur, xpre), np.where(m, fcur, fpre)
            step = np.where(np.abs(scur) > delta, scur, np.where(sbis > 0, delta, -delta))
            xcur = np.where(m, xcur + step, xcur)
            index = np.flatnonzero(m)
            fcur = fcur.copy()
            fcur[index] = f(xcur[index], index)
    if active.any():
        raise RuntimeError(f"brentq_many: {int(active.sum())} of {n} zeros did not converge in {maxiter} iterations")
    return root


BRENT_SCALAR = 16
"""Up to this many brackets, :func:`brentq_many` keeps each bracket's state in Python floats
(numpy's per-call cost on arrays of a few elements exceeds the arithmetic); ``f`` is still
called once per iteration on all of them."""


class _Brent:
    """The state of one bracket of :func:`brentq_many`, in Python floats (IEEE doubles, as numpy's)."""

    __slots__ = ("xpre", "xcur", "xblk", "fpre", "fcur", "fblk", "spre", "scur", "xtol", "rtol", "root")

    def __init__(self, xa, xb, fa, fb, xtol, rtol):
        self.xpre, self.xcur, self.fpre, self.fcur = xa, xb, fa, fb
        self.xblk = self.fblk = self.spre = self.scur = 0.0
        self.xtol, self.rtol = xtol, rtol
        self.root = xa if fa == 0 else xb if fb == 0 else None

    def advance(self):
        """One iteration of scipy's brentq from the current f value: True when converged
        (``root`` set), else ``xcur`` is the next point to evaluate."""
        if self.fpre * self.fcur < 0:
            self.xblk, self.fblk = self.xpre, self.fpre
            self.spre = self.scur = self.xcur - self.xpre
        if abs(self.fblk) < abs(self.fcur):
            self.xpre, self.xcur, self.xblk = self.xcur, self.xblk, self.xcur
            self.fpre, self.fcur, self.fblk = self.fcur, self.fblk, self.fcur
        delta = (self.xtol + self.rtol * abs(self.xcur)) / 2
        sbis = (self.xblk - self.xcur) / 2
        if self.fcur == 0 or abs(sbis) < delta:
            self.root = self.xcur
            return True
        bisect = True
        if abs(self.spre) > delta and abs(self.fcur) < abs(self.fpre):
            try:
                if self.xpre == self.xblk:
                    stry = -self.fcur * (self.xcur - self.xpre) / (self.fcur - self.fpre)
                else:
                    dpre = (self.fpre - self.fcur) / (self.xpre - self.xcur)
                    dblk = (self.fblk - self.fcur) / (self.xblk - self.xcur)
                    stry = -self.fcur * (self.fblk * dblk - self.fpre * dpre) / (dblk * dpre * (self.fblk - self.fpre))
                if 2 * abs(stry) < min(abs(self.spre), 3 * abs(sbis) - delta):
                    self.spre, self.scur = self.scur, stry
                    bisect = False
            except ZeroDivisionError:  # C gives inf or nan here, which fails the test above: bisection
                pass
        if bisect:
            self.spre = self.scur = sbis
        self.xpre, self.fpre = self.xcur, self.fcur
        self.xcur += self.scur if abs(self.scur) > delta else (delta if sbis > 0 else -delta)
        return False


def _brentq_few(f, a, b, fa, fb, xtol, rtol, maxiter):
    """:func:`brentq_many` for a few brackets: their state in Python floats, ``f`` on all at once."""
    states = [_Brent(float(a[i]), float(b[i]), float(fa[i]), float(fb[i]), float(xtol[i]), rtol) for i in range(len(a))]
    active = [i for i, st in enumerate(states) if st.root is None]
    for _ in range(maxiter):
        active = [i for i in active if not states[i].advance()]
        if not active:
            break
        index = np.array(active)
        values = f(np.array([states[i].xcur for i in active]), index)
        for i, v in zip(active, np.asarray(values, dtype=float)):
            states[i].fcur = float(v)
    else:
        if active:
            raise RuntimeError(f"brentq_many: {len(active)} of {len(a)} zeros did not converge in {maxiter} iterations")
    return np.array([st.root for st in states], dtype=float)


# Gauss–Kronrod (G10, K21) nodes on [-1, 1] and weights, from QUADPACK's qk21 (as in
# scipy.integrate.quad_vec); the Gauss nodes are the odd-indexed ones.
_GK21_NODES = np.array(
    [
        0.995657163025808080735527280689003,
        0.973906528517171720077964012084452,
        0.930157491355708226001207180059508,
        0.865063366688984510732096688423493,
        0.780817726586416897063717578345042,
        0.679409568299024406234327365114874,
        0.562757134668604683339000099272694,
        0.433395394129247190799265943165784,
        0.294392862701460198131126603103866,
        0.148874338981631210884826001129720,
        0.0,
        -0.148874338981631210884826001129720,
        -0.294392862701460198131126603103866,
        -0.433395394129247190799265943165784,
        -0.562757134668604683339000099272694,
        -0.679409568299024406234327365114874,
        -0.780817726586416897063717578345042,
        -0.865063366688984510732096688423493,
        -0.930157491355708226001207180059508,
        -0.973906528517171720077964012084452,
        -0.995657163025808080735527280689003,
    ]
)
_K21_WEIGHTS = np.array(
    [
        0.011694638867371874278064396062192,
        0.032558162307964727478818972459390,
        0.054755896574351996031381300244580,
        0.075039674810919952767043140916190,
        0.093125454583697605535065465083366,
        0.109387158802297641899210590325805,
        0.123491976262065851077958109831074,
        0.134709217311473325928054001771707,
        0.142775938577060080797094273138717,
        0.147739104901338491374841515972068,
        0.149445554002916905664936468389821,
        0.147739104901338491374841515972068,
        0.142775938577060080797094273138717,
        0.134709217311473325928054001771707,
        0.123491976262065851077958109831074,
        0.109387158802297641899210590325805,
        0.093125454583697605535065465083366,
        0.075039674810919952767043140916190,
        0.054755896574351996031381300244580,
        0.032558162307964727478818972459390,
        0.011694638867371874278064396062192,
    ]
)
_G10_WEIGHTS = np.array(
    [
        0.066671344308688137593568809893332,
        0.149451349150580593145776339657697,
        0.219086362515982043995534934228163,
        0.269266719309996355091226921569469,
        0.295524224714752870173892994651338,
        0.295524224714752870173892994651338,
        0.269266719309996355091226921569469,
        0.219086362515982043995534934228163,
        0.149451349150580593145776339657697,
        0.066671344308688137593568809893332,
    ]
)
QUAD_MAX_INTERVALS = 2000
"""Most subintervals the adaptive quadrature of one piece refines at once."""


def _gauss_kronrod(f, lo, hi, noise=0.0):
    """The K21 rule on every interval [lo_i, hi_i] at once (one call of f on all nodes).

    Returns the integrals, the differences |K21 − G10| and the round-off
    level of each: that of the rule (50 eps ∫|f|) or, when larger, twice
    the integral of the integrand's own round-off bound ``noise`` (a
    function of φ [N*m], evaluated on the same nodes, or a constant).
    """
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    nodes = (centre[:, None] + half[:, None] * _GK21_NODES).ravel()
    values = f(nodes).reshape(len(lo), 21)
    kronrod, gauss = _kronrod_gauss(values)
    own = (noise(nodes).reshape(len(lo), 21) * _K21_WEIGHTS).sum(axis=1) if callable(noise) else 2.0 * noise
    roundoff = np.maximum(50.0 * EPS * half * (np.abs(values) * _K21_WEIGHTS).sum(axis=1), 2.0 * own * half)
    return kronrod * half, np.abs(kronrod - gauss) * half, roundoff


def _kronrod_gauss(values):
    """The K21 and G10 sums of rows of 21 values (per-row sums, so that a row's result does not
    depend on how many rows are summed with it, as a BLAS product's may)."""
    return (values * _K21_WEIGHTS).sum(axis=1), (values[:, 1::2] * _G10_WEIGHTS).sum(axis=1)


def _quad_many(f, a, b, scale, noise=0.0):
    """∫_{a_i}^{b_i} f dφ for many intervals at once, each as :func:`_quad` computes it.

    The first round of :func:`_quad` (the K21 rule on the whole interval and
    on its two halves) is done for every interval in one call of ``f``;
    an interval that it settles gets exactly the value :func:`_quad` would
    return (the same rule, the same sums). The few that need halving
    further go through :func:`_quad` one by one.

    Parameters
    ----------
    f : callable (phi, index) -> ndarray
        The integrands: values at the angles ``phi`` [rad] of the integrals
        ``index`` (arrays of one length) [N*m].
    a, b : ndarray
        Limits of each integral [rad].
    scale : float
        Work scale of the cycle [J] (see :func:`_quad`).
    noise : callable or float
        Round-off bound of the integrands (see :func:`_quad`).

    Returns
    -------
    ndarray
        The integrals [J].
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    out = np.zeros(len(a))
    open_ = np.flatnonzero(b > a)
    if not len(open_):
        return out
    lo, hi = _halves(a[open_], b[open_])
    ends_lo, ends_hi = np.concatenate((a[open_], lo)), np.concatenate((b[open_], hi))
    owner = np.concatenate((open_, np.repeat(open_, 2)))
    centre, half = 0.5 * (ends_lo + ends_hi), 0.5 * (ends_hi - ends_lo)
    nodes = centre[:, None] + half[:, None] * _GK21_NODES
    values = np.asarray(f(nodes.ravel(), np.repeat(owner, 21)), dtype=float).reshape(len(owner), 21)
    kronrod, gauss = _kronrod_gauss(values)
    m = len(open_)
    value, error = kronrod * half, np.abs(kronrod - gauss) * half
    whole, value, error = value[:m], value[m:], error[m:]
    pair = value[0::2] + value[1::2]  # = math.fsum of the two halves: one correctly rounded sum
    pair_error = np.maximum(np.abs(whole - pair), error[0::2] + error[1::2])
    settled = pair_error <= np.maximum(0.1 * QUAD_EPSREL * scale, QUAD_EPSREL * np.abs(pair))
    out[open_[settled]] = pair[settled]
    for i in open_[~settled]:
        out[i] = _quad(lambda phi, i=i: f(phi, np.full(len(phi), i)), a[i], b[i], scale, noise)
    return out


def _halves(lo, hi):
    """Each interval [lo_i, hi_i] split at its middle, the two halves side by side."""
    mid = 0.5 * (lo + hi)
    left, right = np.empty(2 * len(lo)), np.empty(2 * len(lo))
    left[0::2], left[1::2] = lo, mid
    right[0::2], right[1::2] = mid, hi
    return left, right


def _quad(f, a, b, scale, noise=0.0):
    """∫_a^b f dφ by adaptive Gauss–Kronrod quadrature, vectorized.

    Accurate to QUAD_EPSREL of the result or, where the result is near zero
    (an area between curves that almost coincide), to QUAD_EPSREL/10 of the
    cycle's work scale. Each round evaluates the 21-point rule on the two
    halves of every open interval in one call of ``f`` (torque curves are
    vectorized). The error of a pair of halves is the larger of the change
    from the whole interval's K21 value and the halves' |K21 − G10|: both
    must have settled, which keeps the estimate honest at a kink (``abs``,
    ``min``, ``max`` in an expression) where either alone can vanish by
    chance (on |sin φ − 0.7639...| over [0, 3.03] QUADPACK, through
    scipy.integrate.quad, estimated 6e-14 and was 1.7e-6 off). A kink
    closer to an end or a halving point than the rule's outermost node (2e-3
    of the subinterval) is invisible to every local estimate: its error is
    about the jump in slope times that distance squared. The cycle analysis
    therefore makes the kinks of ``abs``, ``min`` and ``max`` knots
    (:func:`kinks_of`), so that its pieces are smooth.
    Pairs within their share of the tolerance, or at their round-off level,
    are kept, the others halved again. If round-off stops the halving, the
    result is accepted within ten times the target or within the round-off
    of the pieces kept, else refused.

    ``noise`` [N*m] bounds the round-off of f as evaluated, as a function of
    φ (or a constant): M_d − M_r of two curves of 10^6 N*m each is known to
    ~1e-10 N*m only, however small the difference, and no quadrature can do
    better than the integral of that.
    """
    if b <= a:
        return 0.0
    floor = 0.1 * QUAD_EPSREL * scale
    whole, _, _ = _gauss_kronrod(f, np.array([a]), np.array([b]))
    lo, hi = _halves(np.array([a]), np.array([b]))
    kept, kept_error, kept_roundoff = [], 0.0, 0.0
    while True:
        value, error, roundoff = _gauss_kronrod(f, lo, hi, noise)
        pair = value[0::2] + value[1::2]
        pair_error = np.maximum(np.abs(whole - pair), error[0::2] + error[1::2])
        total = math.fsum(kept) + math.fsum(value)
        target = max(floor, QUAD_EPSREL * abs(total))
        if kept_error + float(np.sum(pair_error)) <= target:
            return total
        width = hi[1::2] - lo[0::2]
        pair_roundoff = roundoff[0::2] + roundoff[1::2]
        done = (pair_error <= target * width / (b - a)) | (pair_error <= pair_roundoff)
        kept += pair[done].tolist()
        kept_error += float(np.sum(pair_error[done]))
        kept_roundoff += float(np.sum(pair_roundoff[done]))
        if done.all():
            break
        halves = np.repeat(~done, 2)
        lo, hi, whole = lo[halves], hi[halves], value[halves]
        if 2 * len(lo) > QUAD_MAX_INTERVALS:
            kept += whole.tolist()
            kept_error += float(np.sum(pair_error[~done]))
            break
        mid = 0.5 * (lo + hi)
        atomic = ~((lo < mid) & (mid < hi))  # too narrow to halve: keep as it is
        if atomic.any():
            kept += whole[atomic].tolist()
            kept_error += float(np.sum(np.repeat(pair_error[~done], 2)[atomic])) / 2
            lo, hi, whole = lo[~atomic], hi[~atomic], whole[~atomic]
            if not len(lo):
                break
        lo, hi = _halves(lo, hi)
    total = math.fsum(kept)
    if kept_error > max(10 * QUAD_EPSREL * abs(total), floor, kept_roundoff):
        raise ArithmeticError(
            f"quadrature of the torque difference on [{a:.6g}, {b:.6g}] rad reached only {kept_error:.3g} J"
        )
    return total
