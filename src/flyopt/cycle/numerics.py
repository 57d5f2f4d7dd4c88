"""Pure numerics of the cycle analysis, shared by the sizing models: quadrature, zeros, extremes.

Adaptive Gauss–Kronrod quadrature of many intervals at once (:func:`quad_many`,
:func:`quad`), Brent's method on many brackets at once (:func:`brentq_many`),
the zeros and poles of a function sampled on a grid (:func:`roots`,
:func:`poles`), prefix sums in extended precision (:func:`accurate_cumsum`),
and the exact extremes of a cubic Hermite interpolant (:func:`hermite_extremes`).
Nothing here knows a torque or a flywheel: functions of an angle in, numbers out.
"""

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy import ndarray

VectorFunction = Callable[[ndarray], ndarray]
"""A vectorized function of the angle: an array of φ [rad] in, an array of values out."""
IndexedFunction = Callable[[ndarray, ndarray], ndarray]
"""A vectorized function of many problems at once: f(x, index) is problem ``index[k]`` at ``x[k]``."""

QUAD_EPSREL = 1e-13
"""Relative tolerance of the adaptive quadrature of expression torques."""

POLE_GROWTH = 1e3
"""A sign change of a torque across which the smaller |M| at the bracket's ends grows
by more than this factor, as the grid bracket is halved down to adjacent floats, is
a pole: at a crossing of zero |M| falls by ~h/ulp (1e12), at a finite jump it stays,
at a pole it grows by ~h/ulp."""

EPS = float(np.finfo(float).eps)


CUMSUM_BLOCK = 64


def accurate_cumsum(terms: ndarray) -> ndarray:
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
    blocks: np.ndarray = np.zeros(-(-n // CUMSUM_BLOCK) * CUMSUM_BLOCK)
    blocks[:n] = terms
    blocks = blocks.reshape(-1, CUMSUM_BLOCK)
    inner = np.cumsum(blocks, axis=1)
    offsets = np.zeros(len(blocks), dtype=np.longdouble)
    np.cumsum(blocks.sum(axis=1)[:-1], dtype=np.longdouble, out=offsets[1:])
    return (inner + offsets.astype(float)[:, None]).ravel()[:n]


def poles(f: VectorFunction, phi: ndarray, values: ndarray) -> ndarray:
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


def roots(f: VectorFunction, a: float, b: float, samples: int, scale: float, zero_runs: str = "all") -> list[float]:
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
        return brentq(f, p, q, xtol=1e-15 * max(abs(p), abs(q), b - a), rtol=4 * EPS, maxiter=200)

    # the grid steps worth a look, found at once: a zero on the grid, a sign change, a dip of |f|
    y0 = y[:-1]
    zero, cross, dip = grid_steps(np.concatenate(([np.nan], y[:-2])), y0, y[1:], np.arange(samples) > 0, zero_runs)
    for k in np.flatnonzero(zero | cross | dip):
        if zero[k]:
            roots.append(x[k])
        elif cross[k]:
            roots.append(brent(x[k], x[k + 1]))
        else:
            roots += dip_roots(f, x[k - 1], x[k], x[k + 1], np.sign(y0[k]), a, b, scale)
    return sorted(r for r in set(roots) if a < r < b)


def grid_steps(
    y_prev: ndarray, y0: ndarray, y1: ndarray, interior: ndarray, zero_runs: str = "all"
) -> tuple[ndarray, ndarray, ndarray]:
    """Which steps of a sampled function are worth a look for its zeros: (zero, cross, dip), each a mask of
    the steps.

    A step runs from a sample of value ``y0`` to the next, ``y1``; ``y_prev`` is the sample before it, read
    only where ``interior`` (a step that is not the first of its grid: the first has no dip and no zero of its
    own, its start being an end of the interval searched). ``zero``: the
    step starts on an exact zero (with ``zero_runs="ends"`` only at the first or last point of a run of
    them); ``cross``: f changes sign over the step; ``dip``: |f| at the step's start is below both
    neighbours without a change of sign, where a minimum between the samples may reach zero
    (:func:`dip_roots`). :func:`roots` searches one grid this way, and
    :meth:`flyopt.cycle.difference.Segments.events` every piece's grid at once.
    """
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
    return zero, cross, dip


def dip_roots(
    f: VectorFunction,
    left: float,
    mid: float,
    right: float,
    sign: float,
    a: float,
    b: float,
    scale: float,
) -> list[float]:
    """Zeros of f near a grid point ``mid`` where |f| dips below both neighbours (see :func:`roots`).

    The minimum of sign·f on [left, right] is searched; if it crosses zero,
    the two crossings on either side are refined by Brent's method; if it
    only touches zero (to 1e-15 of the work scale), the touching point is a
    zero. ``a``, ``b`` are the ends of the whole interval searched.
    """
    from flyopt.cycle.minimize import bounded_minimum

    del mid  # the dip's grid point: the search covers both of its grid steps
    tiny = 1e-15 * scale / max(b - a, 1e-300)

    def brent(p, q):
        return brentq(f, p, q, xtol=1e-15 * max(abs(p), abs(q), b - a), rtol=4 * EPS, maxiter=200)

    res = bounded_minimum(lambda p: sign * f(np.array([p]))[0], left, right, xatol=1e-14 * (b - a))
    if res.fun < 0:  # res.fun = s·f at the dip: the dip crosses zero
        return [brent(left, res.x), brent(res.x, right)]
    if abs(res.fun) <= tiny:
        return [float(res.x)]  # touches zero without crossing
    return []


def brentq_many(
    f: IndexedFunction,
    a: ndarray,
    b: ndarray,
    fa: ndarray,
    fb: ndarray,
    xtol: float | ndarray,
    rtol: float = 4 * EPS,
    maxiter: int = 200,
) -> ndarray:
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
    if np.any(np.sign(fpre) * np.sign(fcur) > 0):  # signs: the product of two huge values overflows
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


def brentq(
    f: Callable[[Any], Any], a: float, b: float, xtol: float, rtol: float = 4 * EPS, maxiter: int = 100
) -> float:
    """``scipy.optimize.brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=maxiter)``, operation for operation, on one
    scalar function (:func:`brentq_many` on one bracket), without importing scipy.optimize (~0.3 s of a process).

    ``f`` is called at ``a``, then at ``b``, then at each iterate, with Python floats, as scipy calls it.
    """
    fa, fb = float(f(a)), float(f(b))

    def at(x: ndarray, index: ndarray) -> ndarray:
        return np.array([float(f(float(v))) for v in x])

    return float(brentq_many(at, np.array([a]), np.array([b]), np.array([fa]), np.array([fb]), xtol, rtol, maxiter)[0])


BRENT_SCALAR = 16
"""Up to this many brackets, :func:`brentq_many` keeps each bracket's state in Python floats
(numpy's per-call cost on arrays of a few elements exceeds the arithmetic); ``f`` is still
called once per iteration on all of them."""


class _Brent:
    """The state of one bracket of :func:`brentq_many`, in Python floats (IEEE doubles, as numpy's)."""

    __slots__ = ("xpre", "xcur", "xblk", "fpre", "fcur", "fblk", "spre", "scur", "xtol", "rtol", "root")

    def __init__(self, xa: float, xb: float, fa: float, fb: float, xtol: float, rtol: float) -> None:
        self.xpre, self.xcur, self.fpre, self.fcur = xa, xb, fa, fb
        self.xblk = self.fblk = self.spre = self.scur = 0.0
        self.xtol, self.rtol = xtol, rtol
        self.root = xa if fa == 0 else xb if fb == 0 else None

    def advance(self) -> bool:
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


def _brentq_few(
    f: IndexedFunction, a: ndarray, b: ndarray, fa: ndarray, fb: ndarray, xtol: ndarray, rtol: float, maxiter: int
) -> ndarray:
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
"""Most subintervals the adaptive quadrature of one piece refines at once, per turn (2π rad) of the piece: a
cycle of many turns (``cycle = "1e4 rad"``) swings as many times as it turns, and its 1,592 turns of a plain
``sin(phi)`` were refused with 2,000 subintervals in all (an outside audit)."""

QUAD_MOST_INTERVALS = 20_000
"""Most subintervals at once however many turns the piece spans: enough for the 1,592 turns above (10,000 are),
and a swing no quadrature resolves is refused in seconds and some 80 MB (200,000 took 22 s and 420 MB on a
twelve-term fast swing: an outside review); a plain sine over 15,915 turns (1e5 rad) is refused."""


def _gauss_kronrod(
    f: VectorFunction, lo: ndarray, hi: ndarray, noise: float | VectorFunction = 0.0
) -> tuple[ndarray, ndarray, ndarray]:
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


def _kronrod_gauss(values: ndarray) -> tuple[ndarray, ndarray]:
    """The K21 and G10 sums of rows of 21 values (per-row sums, so that a row's result does not
    depend on how many rows are summed with it, as a BLAS product's may)."""
    return (values * _K21_WEIGHTS).sum(axis=1), (values[:, 1::2] * _G10_WEIGHTS).sum(axis=1)


def quad_many(f: IndexedFunction, a: ndarray, b: ndarray, scale: float, noise: float | VectorFunction = 0.0) -> ndarray:
    """∫_{a_i}^{b_i} f dφ for many intervals at once, each as :func:`quad` computes it.

    The first round of :func:`quad` (the K21 rule on the whole interval and
    on its two halves) is done for every interval in one call of ``f``;
    an interval that it settles gets exactly the value :func:`quad` would
    return (the same rule, the same sums). The few that need halving
    further go through :func:`quad` one by one.

    Parameters
    ----------
    f : callable (phi, index) -> ndarray
        The integrands: values at the angles ``phi`` [rad] of the integrals
        ``index`` (arrays of one length) [N*m].
    a, b : ndarray
        Limits of each integral [rad].
    scale : float
        Work scale of the cycle [J] (see :func:`quad`).
    noise : callable or float
        Round-off bound of the integrands (see :func:`quad`).

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

    def problem(i: int) -> VectorFunction:
        return lambda phi: f(phi, np.full(len(phi), i))

    for i in open_[~settled]:
        out[i] = quad(problem(i), a[i], b[i], scale, noise)
    return out


def _halves(lo: ndarray, hi: ndarray) -> tuple[ndarray, ndarray]:
    """Each interval [lo_i, hi_i] split at its middle, the two halves side by side."""
    mid = 0.5 * (lo + hi)
    left, right = np.empty(2 * len(lo)), np.empty(2 * len(lo))
    left[0::2], left[1::2] = lo, mid
    right[0::2], right[1::2] = mid, hi
    return left, right


def quad(f: VectorFunction, a: float, b: float, scale: float, noise: float | VectorFunction = 0.0) -> float:
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
    (:func:`flyopt.cycle.difference.kinks_of`), so that its pieces are smooth.
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
    most = min(QUAD_MAX_INTERVALS * max(1, math.ceil((b - a) / (2 * math.pi))), QUAD_MOST_INTERVALS)
    floor = 0.1 * QUAD_EPSREL * scale
    whole, _, _ = _gauss_kronrod(f, np.array([a]), np.array([b]))
    lo, hi = _halves(np.array([a]), np.array([b]))
    kept: list[Any] = []
    kept_error, kept_roundoff = 0.0, 0.0
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
        if 2 * len(lo) > most:
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


def hermite(f0: float, f1: float, m0: float, m1: float, t: float) -> float:
    """Cubic Hermite interpolant on [0, 1] with end values f and end slopes m."""
    return f0 + t * (m0 + t * (3 * (f1 - f0) - 2 * m0 - m1 + t * (2 * (f0 - f1) + m0 + m1)))


#: How much steeper than the larger of the rises beside its node an end slope may be for the cubic to be
#: trusted between the nodes [-]: on a smooth function the scaled slope h f' lies between the rises
#: f_i - f_{i-1} and f_{i+1} - f_i up to O(h²) (near an extremum one rise vanishes, not both), and 3 is
#: where the cubic Hermite interpolant starts to overshoot (Fritsch & Carlson 1980).
STEEP = 3.0


def _neighbour_rises(phi: ndarray, f: ndarray, rise: ndarray) -> tuple[ndarray, ndarray]:
    """The rise of the interval before and after each one [same shape as ``rise``].

    Within a row, its neighbours'. At a row's ends, the adjacent row's end interval where the rows join
    (the same node: a periodic cycle's pieces, the last row joining the first when f closes); where
    nothing joins, +inf, so that the steepness test never refuses an extremum for want of a neighbour.
    """
    pieces = rise.shape[0]
    previous = np.roll(np.arange(pieces), 1)
    joins = phi[previous, -1] == phi[:, 0]  # row r starts where row r-1 ends
    joins[0] = pieces > 1 and abs(f[-1, -1] - f[0, 0]) <= 1e-9 * max(float(np.max(np.abs(f))), EPS)
    before = np.concatenate([np.where(joins, rise[previous, -1], np.inf)[:, None], rise[:, :-1]], axis=1)
    after = np.concatenate(
        [rise[:, 1:], np.where(np.roll(joins, -1), np.roll(rise[:, 0], -1), np.inf)[:, None]], axis=1
    )
    return before, after


def hermite_extremes(phi: ndarray, f: ndarray, df: ndarray) -> tuple[tuple[float, float], tuple[float, float]]:
    """Max and min of the piecewise cubic Hermite interpolant, with their angles.

    ``phi``, ``f``, ``df`` have shape (pieces, outputs); each row is
    interpolated on its own (slopes are one-sided at piece ends).

    An extremum inside an interval is taken only where the data say there is
    one: an end slope against the rise f1 − f0 (or the two end slopes of
    opposite signs). Where both end slopes go the way of the rise, the
    function is monotone between the nodes as far as the data show, and a
    cubic extremum there is overshoot, not the function's: it appears where
    the slopes are far steeper than the secant (Fritsch & Carlson, SIAM J.
    Numer. Anal. 17 (1980) 238, need α² + β² > 9 for it), as at a stiff
    motor's speed relaxing within a fraction of one grid step, whose cubic
    reached 12.68 rpm between nodes of at most 12.26. Nor is it taken where
    an end slope (times the step) exceeds :data:`STEEP` times the rises on
    both sides of its node: that slope is a boundary layer's, not the
    function's over the interval, whichever way it points. The extremes are
    then the nodes'.
    """
    h = np.diff(phi, axis=1)
    f0, f1 = f[:, :-1], f[:, 1:]
    m0, m1 = df[:, :-1] * h, df[:, 1:] * h
    rise = f1 - f0
    turning = (m0 * rise < 0) | (m1 * rise < 0) | (rise == 0)
    # an end slope far steeper than the rises on either side of its node is not the function's slope
    # over the interval but a boundary layer's (a stiff motor relaxing within a fraction of the step)
    before, after = _neighbour_rises(phi, f, rise)
    floor = 1e-12 * max(float(np.max(np.abs(f))), EPS)
    resolved = (np.abs(m0) <= STEEP * np.maximum(np.abs(rise), np.abs(before)) + floor) & (
        np.abs(m1) <= STEEP * np.maximum(np.abs(rise), np.abs(after)) + floor
    )
    turning &= resolved
    c = m0
    b = 3 * (f1 - f0) - 2 * m0 - m1
    a = 2 * (f0 - f1) + m0 + m1
    # p'(t) = 3a t² + 2b t + c = 0
    qa, qb, qc = 3 * a, 2 * b, c
    disc = qb * qb - 4 * qa * qc
    sq = np.sqrt(np.where(disc >= 0, disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        big = np.abs(qa) > 1e-14 * (np.abs(qb) + np.abs(qc))
        r1 = np.where(big, (-qb + sq) / (2 * qa), np.where(qb != 0, -qc / np.where(qb != 0, qb, 1), -1.0))
        r2 = np.where(big, (-qb - sq) / (2 * qa), -1.0)
    best_hi = (float(np.max(f)), np.unravel_index(np.argmax(f), f.shape))
    best_lo = (float(np.min(f)), np.unravel_index(np.argmin(f), f.shape))
    hi_val, hi_phi = best_hi[0], float(phi[best_hi[1]])
    lo_val, lo_phi = best_lo[0], float(phi[best_lo[1]])
    for r in (r1, r2):
        ok = (disc >= 0) & (r > 0) & (r < 1) & turning
        t = np.where(ok, r, 0.0)
        p = f0 + t * (c + t * (b + t * a))
        where = phi[:, :-1] + t * h
        if np.any(ok):
            pm = np.where(ok, p, -np.inf)
            i = np.unravel_index(np.argmax(pm), pm.shape)
            if pm[i] > hi_val:
                hi_val, hi_phi = float(pm[i]), float(where[i])
            pm = np.where(ok, p, np.inf)
            i = np.unravel_index(np.argmin(pm), pm.shape)
            if pm[i] < lo_val:
                lo_val, lo_phi = float(pm[i]), float(where[i])
    return (hi_phi, hi_val), (lo_phi, lo_val)
