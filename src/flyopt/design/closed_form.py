"""Exact flywheel designs in closed form: for arrays of combinations (numpy), or one at a time.

An NLP per material × shaft combination solved by IPOPT takes about 2 ms.
For the structures whose optimum is known analytically, or is the root of a
monotone function of one variable, this module computes the same optimum:
for whole arrays of combinations at once (:func:`lightest`, used by sweeps),
or one combination in plain floats (:func:`lightest_one`, used by
:func:`flyopt.design.designer.design_flywheel`, whose default method "auto" takes
it). It is a model choice ("the cheapest model that is exact"): every design
made here says ``method = "closed_form"``, and a structure it does not cover
is left to IPOPT (see :func:`covers`).

Covered: objective ``mass`` or ``cost`` (cost ranks the mass-optimal design of
each combination by mass times the material's cost per kg, exactly as the
NLP does), for ``thin_rim``, ``rim`` and ``disc``, mean diameter free or
pinned, with or without envelope, width limit and H/B range. Not covered:
objective ``outer_diameter``.

Derivations
-----------
Notation per combination: J' the inertia needed on the wheel's shaft,
rho the density, C = min(2 v_max / omega', envelope) the cap on the outer
diameter, a <= H/B <= c the H/B range, B_max the width limit (inf if none).
For rims m = pi rho D_m H B and J = m k / 4 with k = D_m^2 (thin rim) or
D_m^2 + H^2 (exact annulus); for a disc m = pi rho D^2 B / 4, J = m D^2 / 8.

*Feasibility* is decided by J' <= J_max, the largest inertia an admissible
wheel gives, by :func:`max_inertia`: the vectorized twin of
:func:`max_inertia_one`, written with the same operations in the
same order so that both give bitwise the same J_max, and thus the same verdict
(including at the edge).

*Rim, D_m free.* With the inertia binding, m = 4 J' / k, so the lightest
wheel has the largest k. k grows with D_m, and along D_m + H = s it grows as
H shrinks (H < D_m), so the outer diameter sits at the cap, D_m = C - H, and
H is the smallest value at which a wheel of the widest admissible width
B(H) = min(H / a, B_max) still gives J': the smallest root of

    J_line(H) = pi rho (C - H) H B(H) k(H) / 4 = J'.

Any lighter wheel (D', H') would have D' + H' <= C and, moved onto the line
D_m + H = C with the same H', a larger J: a smaller root, a contradiction.
At that root H/B = max(a, H / B_max) <= c, so the upper end of the H/B range
never binds. In x = H / C, J_line is proportional to x^2 (1-x)^3 (thin rim,
B = H/a), x (1-x)^3 (thin rim, B = B_max), x u (1 - 2u) or u (1 - 2u) with
u = x (1 - x) (annulus): the thin rim is unimodal with its peak at
clip(a B_max, C/4, 2C/5), the annulus increasing up to H = C/2. So the
smallest root lies where J_line increases. Moreover log J_line is concave in
log H (each factor is: log(C - H), log H, the minimum of two linear
functions, and for the annulus log k + log(C - H) has a non-positive second
derivative on (0, C/2], zero only at C/2), so Newton's method on
log J_line(e^u) = log J' started left of the root climbs to it monotonically;
it is safeguarded by bisection anyway. It starts at the lower bound
H_0 = max(sqrt(4 a J' / (pi rho C^3)), 4 J' / (pi rho C^3 B_max)), valid since
C - H <= C, k <= C^2, B <= H/a and B <= B_max.

*Rim, D_m pinned.* The thin rim's mass 4 J' / D_m^2 does not depend on H;
flyopt (and its NLP's tie-break) takes the thinnest such rim: with
B = 4 J' / (pi rho D_m^3 H) <= min(H/a, B_max),
H = max(sqrt(4 a J' / (pi rho D_m^3)), 4 J' / (pi rho D_m^3 B_max)).
The annulus' mass 4 J' / (D_m^2 + H^2) falls with H, so H is as large as the
room min(C - D_m, D_m) and H/B <= c allow; H/B = c gives
H^2 (D_m^2 + H^2) = 4 c J' / (pi rho D_m), a quadratic in H^2:
H^2 = 2 q / (D_m^2 + sqrt(D_m^4 + 4 q)), q = 4 c J' / (pi rho D_m).

*Disc.* m = 8 J' / D^2 falls with D: D = C (or the pinned D), and
B = 32 J' / (pi rho D^4).

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 8-10.
.. [2] flyopt.design.nlp (the NLP these closed forms reproduce).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flyopt.design import check, geometry
from flyopt.names import Geometry

Rim = tuple[float, float, float]
"""A wheel's (d_mean, h, b) [m] (a disc: d_mean = h = D/2)."""

__all__ = [
    "METHOD",
    "COVERED_OBJECTIVES",
    "covers",
    "max_inertia",
    "max_inertia_one",
    "cap_needed",
    "smallest_reaching",
    "lightest",
    "lightest_one",
    "design_combinations",
]

#: Name of the method recorded with every design made here.
METHOD = "closed_form"
#: Objectives whose optimum is in closed form (cost ranks the mass optimum).
COVERED_OBJECTIVES = ("mass", "cost")

_NEWTON_MAX_ITER = 200
#: Newton stops when a step moves log H by less than this (relative to max(1, |log H|)):
#: a few ulps, so H is exact to ~1e-14 relative (IPOPT's designs: ~1e-10).
_NEWTON_RTOL = 16 * np.finfo(float).eps
#: Interpolation steps of :func:`smallest_reaching` before it only halves its bracket.
_INTERPOLATION_STEPS = 12


def covers(geometry_name: str, objective: str, pinned: bool = False) -> bool:
    """Whether the closed form is exact for a structure.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
    objective : {"mass", "cost", "outer_diameter"}
    pinned : bool
        Mean diameter pinned (every pinned and free case is covered).

    Returns
    -------
    bool
        True for the mass and cost objectives (any geometry, free or pinned
        D_m); False for ``outer_diameter``, which is left to IPOPT.
    """
    return geometry_name in geometry.BARE and objective in COVERED_OBJECTIVES


def _array(x):
    return np.asarray(x, dtype=float)


def max_inertia_one(
    geometry_name: str,
    density: float,
    d_outer_max: float,
    hb_ratio: tuple[float, float] = (1.5, 2.0),
    max_width: float = math.inf,
    d_mean: float | None = None,
) -> tuple[float, Rim | None]:
    """Largest inertia any admissible wheel gives, in closed form (one combination, plain floats).

    The scalar twin of :func:`max_inertia`, written with the same operations
    in the same order so that both give bitwise the same J_max, and thus the
    same feasibility verdict (including at the edge).

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
        Inertia model.
    density : float
        Density [kg/m^3].
    d_outer_max : float
        Cap on the outer diameter (rim speed and envelope) [m].
    hb_ratio : (float, float)
        Range of H/B [-] (rims only).
    max_width : float
        Limit on B [m]; ``inf`` for none.
    d_mean : float or None
        Pinned mean diameter (disc: diameter) [m].

    Returns
    -------
    j_max : float
        Supremum of J on the shaft [kg*m^2]; 0 if no wheel fits, ``inf`` for
        an unlimited disc.
    dims : tuple (d_mean, h, b) or None
        The wheel that attains it [m] (for a disc d_mean = h = D/2), or None.

    Notes
    -----
    J grows with the width B, so B = min(H/hb_min, B_max), and a width limit
    also caps H <= hb_max B_max. With D_m pinned, J grows with H up to
    min(D_1max - D_m, D_m, hb_max B_max). With D_m = D_1max - H free, put
    x = H/D_1max <= 1/2: the exact annulus gives J proportional to
    x u (1 - 2u) or u (1 - 2u), u = x (1 - x), both increasing on [0, 1/2],
    so H is as large as allowed; the thin rim gives x^2 (1-x)^3 (peak at
    x = 2/5) or x (1-x)^3 (peak at 1/4), so the maximum is at a clipped peak,
    at the change of piece or at the end of the range.
    """
    hb_min, hb_max = hb_ratio
    b_max = max_width
    cap = d_outer_max
    if geometry_name == Geometry.DISC:
        d = cap if d_mean is None else d_mean
        if d > cap:
            return 0.0, None
        if max_width == math.inf:
            return math.inf, None
        j = geometry.disc_inertia(geometry.disc_mass(d, b_max, density), d)
        return j, (d / 2.0, d / 2.0, b_max)

    if d_mean is not None:
        if d_mean >= cap:
            return 0.0, None
        h = min(cap - d_mean, d_mean, hb_max * b_max)
        b = min(h / hb_min, b_max)
        return geometry.wheel_inertia(geometry_name, density, d_mean, h, b), (d_mean, h, b)

    h_top = min(cap / 2.0, hb_max * b_max)
    if geometry_name != Geometry.THIN_RIM:  # the annulus: H as large as allowed, one trial
        if h_top <= 0.0:
            return 0.0, None
        b = min(h_top / hb_min, b_max)
        j = geometry.wheel_inertia(geometry_name, density, cap - h_top, h_top, b)
        return (j, (cap - h_top, h_top, b)) if j > 0.0 else (0.0, None)
    h_break = min(hb_min * b_max, h_top)
    best_j, best_h = 0.0, 0.0
    for h in (h_top, h_break, min(0.4 * cap, h_break), min(max(0.25 * cap, h_break), h_top)):
        if h <= 0.0 or h == best_h:  # a trial equal to the best so far cannot beat it
            continue
        d = cap - h
        j = geometry.thin_rim_inertia(geometry.rim_mass(d, h, min(h / hb_min, b_max), density), d)
        if j > best_j:
            best_j, best_h = j, h
    if best_j > 0.0:
        return best_j, (cap - best_h, best_h, min(best_h / hb_min, b_max))
    return 0.0, None


def cap_needed(
    geometry_name: str,
    density: float,
    j_needed: float,
    cap: float,
    hb_ratio: tuple[float, float],
    max_width: float,
    d_mean: float | None,
    *,
    j_cap: float | None = None,
) -> tuple[float | None, float]:
    """Smallest outer-diameter cap at which ``j_needed`` becomes reachable.

    Returns (cap_needed, j_sup): cap_needed is None when even an unlimited cap
    does not reach ``j_needed``; j_sup is then the largest reachable inertia.
    ``j_cap``: :func:`max_inertia_one` at ``cap`` when the caller has it.
    """

    def j_max(c):
        return max_inertia_one(geometry_name, density, c, hb_ratio, max_width, d_mean)[0]

    if d_mean is not None:
        if geometry_name == Geometry.DISC:
            saturated = d_mean
        else:
            hb_max = hb_ratio[1]
            saturated = d_mean + min(d_mean, hb_max * max_width)
        j_sup = j_max(saturated)
        if j_sup < j_needed:
            return None, j_sup
        low, high = max(cap, d_mean), saturated
        if geometry_name == Geometry.DISC:
            return low, j_sup
        j_low, j_high = j_max(low), j_sup
        if j_low >= j_needed:
            return low, j_sup
    else:
        # D_m free. J_max is homogeneous of degree 5 in (C, B_max): scaling an admissible
        # wheel by λ keeps it admissible. So without a width limit the cap needed is in
        # closed form (a disc of fixed width: degree 4 in C). With a width limit, growing
        # C by λ >= 1 multiplies J_max by at most λ^5 (scale down any wheel of the larger
        # cap) and at least λ^3 / 2 (keep H and B, push D_m out to >= λ D_m; with
        # H <= D_m, D_m^2 + H^2 <= 2 D_m^2), which brackets the root.
        if j_cap is None:
            j_cap = j_max(cap)
        if max_width == math.inf or geometry_name == Geometry.DISC:
            power = 4.0 if geometry_name == Geometry.DISC else 5.0
            return cap * (j_needed / j_cap) ** (1.0 / power), math.inf
        low = cap * (j_needed / j_cap) ** 0.2
        j_low = j_max(low)
        if j_low >= j_needed:  # the width does not bind there: degree 5 is exact
            return low, math.inf
        high = cap * (2.0 * j_needed / j_cap) ** (1.0 / 3.0)
        j_high = j_max(high)
        while j_high < j_needed:  # round-off at the bracket's edge only
            low, j_low, high = high, j_high, 2.0 * high
            j_high = j_max(high)
    return smallest_reaching(j_max, j_needed, low, high, j_low=j_low, j_high=j_high), math.inf


def smallest_reaching(
    j_max: Callable[[float], float],
    j_needed: float,
    low: float,
    high: float,
    *,
    j_low: float | None = None,
    j_high: float | None = None,
) -> float:
    """The smallest float ``c`` in (low, high] with ``j_max(c) >= j_needed``: a bracket narrowed to adjacent floats.

    The bracket is narrowed first by interpolation in log-log (Illinois
    regula falsi on log j_max(c) - log j_needed against log c: J_max is a
    power of the cap piece by piece, so a few steps land within ulps of the
    root), then halved down to two adjacent floats. Every step keeps
    ``j_max(low) < j_needed <= j_max(high)``, so the answer is that of a
    bisection over the whole bracket (for a monotone function, the same
    float) after about 10 calls of ``j_max`` instead of about 60, and does
    not depend on a tolerance (a bracketing solver stops within its
    tolerance of it; scipy.optimize, which took 0.5 s to import, is not
    needed).

    Parameters
    ----------
    j_max : callable
        Non-decreasing function of the cap ``c`` [m] (kg*m^2).
    j_needed : float
        The inertia to reach [kg*m^2].
    low, high : float
        A bracket [m]: ``j_max(low) < j_needed <= j_max(high)``.
    j_low, j_high : float, optional
        ``j_max(low)`` and ``j_max(high)`` when the caller has them (else they are computed).

    Returns
    -------
    float
        ``c`` with ``j_max(c) >= j_needed`` and ``j_max`` of the float below
        ``c`` short of it (for a function that is not monotone to the last
        bit, one such change within the bracket).
    """
    if j_low is None:
        j_low = j_max(low)
    if j_high is None:
        j_high = j_max(high)
    f_low, f_high = _log_excess(j_low, j_needed), _log_excess(j_high, j_needed)
    side = 0  # which end the last interpolated step moved: -1 low, +1 high (Illinois)
    previous = math.nan
    for _ in range(_INTERPOLATION_STEPS):
        if not (0.0 < low and -math.inf < f_low < 0.0 <= f_high < math.inf):
            break  # J_max(low) = 0 (a pinned mean diameter at its cap) or overflow: halving only
        log_low, log_high = math.log(low), math.log(high)
        mid = math.exp(log_low + (log_high - log_low) * f_low / (f_low - f_high))
        if not low < mid < high:  # the root is within round-off of an end: close the bracket from there
            side = -1 if mid <= low else 1
            break
        j = j_max(mid)
        f_mid = _log_excess(j, j_needed)
        if j >= j_needed:
            high, f_high = mid, f_mid
            if side > 0:
                f_low *= 0.5
            side = 1
        else:
            low, f_low = mid, f_mid
            if side < 0:
                f_high *= 0.5
            side = -1
        if abs(mid - previous) <= 1e-9 * mid:  # within ulps of the root: close the other end
            break
        previous = mid
    # the end moved last sits within ulps of the root; step from it across the root, 4 ulps and growing
    step = 4.0 * math.ulp(high)
    while side and step < high - low:
        probe = high - step if side > 0 else low + step
        if j_max(probe) >= j_needed:
            high = probe
            if side < 0:
                break
        else:
            low = probe
            if side > 0:
                break
        step *= 8.0
    while True:
        mid = low + 0.5 * (high - low)
        if not low < mid < high:  # adjacent floats
            return high
        if j_max(mid) >= j_needed:
            high = mid
        else:
            low = mid


def _log_excess(j: float, j_needed: float) -> float:
    """log(j / j_needed), -inf for j = 0 (the sign tells whether ``j`` reaches ``j_needed``)."""
    return math.log(j / j_needed) if j > 0.0 else -math.inf


def max_inertia(
    geometry_name: str,
    density: ArrayLike,
    d_outer_max: ArrayLike,
    hb_min: ArrayLike,
    hb_max: ArrayLike,
    max_width: ArrayLike = np.inf,
    d_mean: ArrayLike = np.nan,
) -> NDArray[np.float64]:
    """Largest inertia any admissible wheel gives, for arrays of combinations.

    The vectorized :func:`max_inertia_one`, written with the
    same floating-point operations so that both agree bitwise.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
        One model for the whole array.
    density : array_like
        rho [kg/m^3].
    d_outer_max : array_like
        Cap on the outer diameter C [m].
    hb_min, hb_max : array_like
        H/B range [-] (ignored for a disc).
    max_width : array_like
        B_max [m]; ``inf`` for no limit.
    d_mean : array_like
        Pinned mean diameter (disc: diameter) [m]; NaN where free.

    Returns
    -------
    ndarray
        J_max [kg*m^2]; 0 where no wheel fits, ``inf`` for a disc with no
        width limit and free diameter.
    """
    rho, cap, a, c, b_max, pin = np.broadcast_arrays(
        _array(density), _array(d_outer_max), _array(hb_min), _array(hb_max), _array(max_width), _array(d_mean)
    )
    pinned = ~np.isnan(pin)
    out = np.zeros(rho.shape)
    if geometry_name == Geometry.DISC:
        d = np.where(pinned, pin, cap)
        fits = d <= cap
        limited = np.isfinite(b_max)
        j = geometry.disc_inertia(geometry.disc_mass(d, np.where(limited, b_max, 1.0), rho), d)
        return np.where(fits, np.where(limited, j, np.inf), 0.0)

    def inertia(d, h):
        b = np.minimum(h / a, b_max)
        mass = geometry.rim_mass(d, h, b, rho)
        if geometry_name == Geometry.THIN_RIM:
            return geometry.thin_rim_inertia(mass, d)
        return geometry.rim_inertia(mass, d, h)

    with np.errstate(invalid="ignore", divide="ignore"):
        # pinned: H = min(C - D_m, D_m, hb_max B_max)
        h_pin = np.minimum(np.minimum(cap - pin, pin), c * b_max)
        j_pin = np.where(pin >= cap, 0.0, inertia(pin, h_pin))
        # free: the same trial thicknesses as max_inertia_one, best of them
        h_top = np.minimum(cap / 2.0, c * b_max)
        trials = [h_top]
        if geometry_name == Geometry.THIN_RIM:
            h_break = np.minimum(a * b_max, h_top)
            trials += [h_break, np.minimum(0.4 * cap, h_break), np.minimum(np.maximum(0.25 * cap, h_break), h_top)]
        best = np.zeros(rho.shape)
        for h in trials:
            j = np.where(h > 0.0, inertia(cap - h, h), 0.0)
            best = np.where(j > best, j, best)
    out = np.where(pinned, j_pin, best)
    return out


def _rim_free_peak(thin, cap, a, c, b_max):
    """Upper end of the increasing part of J_line(H) on (0, C/2] [m]."""
    h_top = np.minimum(cap / 2.0, c * b_max)
    if not thin:
        return h_top
    return np.minimum(h_top, np.clip(a * b_max, 0.25 * cap, 0.4 * cap))


def _log_j_line(thin, u, log_coef, cap, a, b_max):
    """log J_line(e^u) and its derivative in u (see the module notes)."""
    h = np.exp(u)
    d = cap - h
    narrow = h / a < b_max
    log_b = np.where(narrow, u - np.log(a), np.log(np.where(narrow, 1.0, b_max)))
    dlog_b = np.where(narrow, 1.0, 0.0)
    if thin:
        log_k = 2.0 * np.log(d)
        dlog_k = -2.0 * h / d
    else:
        k = d * d + h * h
        log_k = np.log(k)
        dlog_k = 2.0 * h * (2.0 * h - cap) / k
    value = log_coef + np.log(d) + u + log_b + log_k
    slope = 1.0 - h / d + dlog_b + dlog_k
    return value, slope


def _rim_free_root(thin, j, rho, cap, a, c, b_max):
    """Smallest H with J_line(H) = J' (feasible combinations only) [m]."""
    h_hi = _rim_free_peak(thin, cap, a, c, b_max)
    with np.errstate(divide="ignore"):
        base = math.pi * rho * cap**3
        h_lo = np.maximum(np.sqrt(4.0 * a * j / base), 4.0 * j / (base * b_max))
    h_lo = np.minimum(h_lo, h_hi)
    lo, hi = np.log(h_lo), np.log(h_hi)
    log_target = np.log(j)
    log_coef = np.log(math.pi * rho / 4.0) - log_target
    u = lo.copy()
    active = np.arange(u.size)
    for _ in range(_NEWTON_MAX_ITER):
        if active.size == 0:
            break
        ua = u[active]
        f, df = _log_j_line(thin, ua, log_coef[active], cap[active], a[active], b_max[active])
        below = f < 0.0
        lo[active] = np.where(below, ua, lo[active])
        hi[active] = np.where(below, hi[active], ua)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(f == 0.0, 0.0, -f / df)
        # converged: the Newton step, or the bracket around the root, is a few ulps of
        # u (tested before the bracket: a last step of an ulp may land on its edge).
        # (Near the fold of J_line, where J' is close to J_max, the slope vanishes
        # and Newton slows to halving the distance; the bracket stops round-off
        # from making it oscillate.)
        tol = _NEWTON_RTOL * np.maximum(1.0, np.abs(ua))
        converged = (np.abs(step) <= tol) | (hi[active] - lo[active] <= tol)
        new = ua + step
        inside = (new >= lo[active]) & (new <= hi[active])
        outside = ~((new > lo[active]) & (new < hi[active]))  # strictly inside, or bisect
        new = np.where(converged, np.where(inside, new, ua), np.where(outside, 0.5 * (lo[active] + hi[active]), new))
        u[active] = new
        active = active[~converged]
    else:  # pragma: no cover - the iteration converges quadratically in a few steps
        raise ArithmeticError(f"closed-form rim root did not converge for {active.size} combinations")
    return np.exp(u)


def _rim_free_root_one(thin, j, rho, cap, a, c, b_max):
    """Scalar :func:`_rim_free_root`: the smallest H with J_line(H) = J' [m].

    The same safeguarded Newton iteration on log J_line(e^u) in plain floats:
    a ranking of a few combinations (:func:`lightest_one`) pays numpy's
    per-call overhead on every vectorized pass, about 40 times the arithmetic.
    """
    h_top = min(cap / 2.0, c * b_max)
    h_hi = h_top if not thin else min(h_top, min(max(a * b_max, 0.25 * cap), 0.4 * cap))
    base = math.pi * rho * cap**3
    h_lo = min(max(math.sqrt(4.0 * a * j / base), 4.0 * j / (base * b_max)), h_hi)
    lo, hi = math.log(h_lo), math.log(h_hi)
    log_coef = math.log(math.pi * rho / 4.0) - math.log(j)
    log_a, log_b_max = math.log(a), (math.log(b_max) if b_max < math.inf else math.inf)
    u = lo
    for _ in range(_NEWTON_MAX_ITER):
        h = math.exp(u)
        d = cap - h
        if h / a < b_max:
            log_b, dlog_b = u - log_a, 1.0
        else:
            log_b, dlog_b = log_b_max, 0.0
        if thin:
            log_k, dlog_k = 2.0 * math.log(d), -2.0 * h / d
        else:
            k = d * d + h * h
            log_k, dlog_k = math.log(k), 2.0 * h * (2.0 * h - cap) / k
        f = log_coef + math.log(d) + u + log_b + log_k
        if f == 0.0:
            return h
        if f < 0.0:
            lo = u
        else:
            hi = u
        df = 1.0 - h / d + dlog_b + dlog_k
        tol = _NEWTON_RTOL * max(1.0, abs(u))
        step = -f / df if df != 0.0 else math.inf
        if abs(step) <= tol or hi - lo <= tol:
            return math.exp(u + step) if lo <= u + step <= hi else h
        u = u + step
        if not lo < u < hi:  # strictly inside the bracket, or bisect
            u = 0.5 * (lo + hi)
    raise ArithmeticError("closed-form rim root did not converge")  # pragma: no cover


def lightest_one(
    geometry_name: str,
    j_shaft: float,
    density: float,
    d_outer_max: float,
    hb_min: float,
    hb_max: float,
    max_width: float = math.inf,
    d_mean: float | None = None,
) -> Rim:
    """Lightest admissible wheel of one feasible combination, exactly (plain floats).

    The scalar twin of :func:`lightest` for a ranking of a few combinations,
    whose feasibility the caller has already decided
    (:func:`max_inertia_one`); the same closed forms and the same
    Newton iteration (see the module notes). It does not check feasibility:
    for an infeasible combination it returns the wheel nearest to one, which
    :func:`flyopt.design.designer.design_flywheel` (its only caller) would refuse in
    its verification of every design.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
    j_shaft : float
        Inertia needed on the wheel's shaft J' [kg*m^2], > 0.
    density : float
        rho [kg/m^3].
    d_outer_max : float
        C = min(2 v_max / omega', envelope) [m].
    hb_min, hb_max : float
        H/B range [-].
    max_width : float
        B_max [m], ``inf`` for none.
    d_mean : float or None
        Pinned mean diameter (disc: diameter) [m]; None or NaN where free.

    Returns
    -------
    tuple
        ``(d_mean, h, b)`` [m]; for a disc ``d_mean = h = D/2``.
    """
    j, rho, cap, a, c, b_max = j_shaft, density, d_outer_max, hb_min, hb_max, max_width
    if d_mean is not None and math.isnan(d_mean):
        d_mean = None
    if geometry_name == Geometry.DISC:
        d = cap if d_mean is None else d_mean
        return d / 2.0, d / 2.0, 32.0 * j / (math.pi * rho * d**4)
    if d_mean is None:
        h = _rim_free_root_one(geometry_name == Geometry.THIN_RIM, j, rho, cap, a, c, b_max)
        return cap - h, h, min(h / a, b_max)
    d = d_mean
    if geometry_name == Geometry.THIN_RIM:
        base = math.pi * rho * d**3
        h = max(math.sqrt(4.0 * a * j / base), 4.0 * j / (base * b_max))
        return d, h, 4.0 * j / (base * h)
    q = 4.0 * c * j / (math.pi * rho * d)
    h = min(cap - d, d, math.sqrt(2.0 * q / (d * d + math.sqrt(d**4 + 4.0 * q))))
    return d, h, 4.0 * j / (math.pi * rho * d * h * (d * d + h * h))


class Designs(dict):
    """Arrays describing one design per combination (a dict of ndarrays).

    Keys: ``feasible`` (bool), ``j_max``, ``d_mean``, ``h``, ``b``, ``mass``,
    ``j_flywheel`` (NaN where infeasible) and, from
    :func:`design_combinations`, also ``j_shaft``, ``omega``, ``cap``,
    ``cap_speed``, ``d_outer``, ``d_inner``, ``hb_ratio``, ``rim_speed``,
    ``hoop_stress``, ``j_at_reference``, ``binding`` (int bit mask, see
    :func:`flyopt.design.check.binding_names`).
    """

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None


def lightest(
    geometry_name: str,
    j_shaft: ArrayLike,
    density: ArrayLike,
    d_outer_max: ArrayLike,
    hb_min: ArrayLike,
    hb_max: ArrayLike,
    max_width: ArrayLike = np.inf,
    d_mean: ArrayLike = np.nan,
) -> Designs:
    """Lightest admissible wheel of each combination, exactly, or its infeasibility.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
        One model for the whole array.
    j_shaft : array_like
        Inertia needed on the wheel's shaft J' [kg*m^2], > 0.
    density : array_like
        rho [kg/m^3].
    d_outer_max : array_like
        C = min(2 v_max / omega', envelope) [m].
    hb_min, hb_max : array_like
        H/B range [-].
    max_width : array_like
        B_max [m], ``inf`` for none.
    d_mean : array_like
        Pinned mean diameter (disc: diameter) [m], NaN where free.

    Returns
    -------
    Designs
        ``feasible``, ``j_max``, ``d_mean``, ``h``, ``b``, ``mass`` [kg],
        ``j_flywheel`` [kg*m^2]. For a disc ``d_mean = h = D/2`` (the
        convention of :class:`flyopt.design.result.Candidate`).

    Notes
    -----
    See the module notes for the derivation of each case.
    """
    j, rho, cap, a, c, b_max, pin = np.broadcast_arrays(
        _array(j_shaft),
        _array(density),
        _array(d_outer_max),
        _array(hb_min),
        _array(hb_max),
        _array(max_width),
        _array(d_mean),
    )
    shape = j.shape
    j_max = max_inertia(geometry_name, rho, cap, a, c, b_max, pin)
    pinned = ~np.isnan(pin)
    fits = np.where(geometry_name == Geometry.DISC, pin <= cap, pin < cap) | ~pinned
    feasible = fits & (j > 0.0) & (j <= j_max)
    nan = np.full(shape, np.nan)
    d_mean_out, h_out, b_out = nan.copy(), nan.copy(), nan.copy()

    def put(mask, d, h, b):
        d_mean_out[mask], h_out[mask], b_out[mask] = d, h, b

    if geometry_name == Geometry.DISC:
        for mask in (feasible & ~pinned, feasible & pinned):
            if mask.any():
                d = np.where(pinned[mask], pin[mask], cap[mask])
                b = 32.0 * j[mask] / (math.pi * rho[mask] * d**4)
                put(mask, d / 2.0, d / 2.0, b)
        mass = geometry.disc_mass(2.0 * d_mean_out, b_out, rho)
        j_wheel = geometry.disc_inertia(mass, 2.0 * d_mean_out)
    else:
        thin = geometry_name == Geometry.THIN_RIM
        free = feasible & ~pinned
        if free.any():
            h = _rim_free_root(thin, j[free], rho[free], cap[free], a[free], c[free], b_max[free])
            put(free, cap[free] - h, h, np.minimum(h / a[free], b_max[free]))
        fixed = feasible & pinned
        if fixed.any():
            jj, rr, d, aa, cc, bm = (x[fixed] for x in (j, rho, pin, a, c, b_max))
            if thin:
                base = math.pi * rr * d**3
                h = np.maximum(np.sqrt(4.0 * aa * jj / base), 4.0 * jj / (base * bm))
                b = 4.0 * jj / (base * h)
            else:
                room = np.minimum(cap[fixed] - d, d)
                q = 4.0 * cc * jj / (math.pi * rr * d)
                h_c = np.sqrt(2.0 * q / (d * d + np.sqrt(d**4 + 4.0 * q)))
                h = np.minimum(room, h_c)
                b = 4.0 * jj / (math.pi * rr * d * h * (d * d + h * h))
            put(fixed, d, h, b)
        mass = geometry.rim_mass(d_mean_out, h_out, b_out, rho)
        if thin:
            j_wheel = geometry.thin_rim_inertia(mass, d_mean_out)
        else:
            j_wheel = geometry.rim_inertia(mass, d_mean_out, h_out)
    return Designs(feasible=feasible, j_max=j_max, d_mean=d_mean_out, h=h_out, b=b_out, mass=mass, j_flywheel=j_wheel)


def design_combinations(
    geometry_name: str,
    j_required: ArrayLike,
    omega_ref: ArrayLike,
    speed_ratio: ArrayLike,
    density: ArrayLike,
    max_rim_speed: ArrayLike,
    hb_min: ArrayLike,
    hb_max: ArrayLike,
    max_outer_diameter: ArrayLike = np.inf,
    max_width: ArrayLike = np.inf,
    d_mean: ArrayLike = np.nan,
) -> Designs:
    """Design many material × shaft combinations at once (mass objective).

    The array counterpart of what :func:`flyopt.design.designer.design_flywheel`
    does for each combination: move J_F to the shaft, cap the outer
    diameter by the rim speed and the envelope, decide feasibility, and find
    the lightest wheel.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
    j_required : array_like
        J_F at the reference shaft [kg*m^2], > 0.
    omega_ref : array_like
        Speed of the reference shaft at which the rim speed is checked [rad/s]
        (the highest speed of the cycle, ω_max).
    speed_ratio : array_like
        omega_shaft / omega_reference [-].
    density, max_rim_speed : array_like
        Material: rho [kg/m^3], v_max [m/s].
    hb_min, hb_max : array_like
        H/B range [-].
    max_outer_diameter, max_width : array_like
        Envelope and width limit [m], ``inf`` for none.
    d_mean : array_like
        Pinned mean diameter [m], NaN where free.

    Returns
    -------
    Designs
        The keys of :func:`lightest` and ``j_shaft``, ``omega``, ``cap``,
        ``cap_speed``, ``d_outer``, ``d_inner``, ``hb_ratio``, ``rim_speed``,
        ``hoop_stress``, ``j_at_reference``, ``binding`` (bit mask).
    """
    arrays = np.broadcast_arrays(
        _array(j_required),
        _array(omega_ref),
        _array(speed_ratio),
        _array(density),
        _array(max_rim_speed),
        _array(hb_min),
        _array(hb_max),
        _array(max_outer_diameter),
        _array(max_width),
        _array(d_mean),
    )
    j_ref, omega_ref, ratio, rho, v_max, a, c, envelope, b_max, pin = arrays
    omega = omega_ref * ratio
    j_shaft = j_ref / (ratio * ratio)  # transmission.inertia_on_shaft
    cap_speed = geometry.outer_diameter_for_rim_speed(v_max, omega)
    cap = np.minimum(cap_speed, envelope)
    out = lightest(geometry_name, j_shaft, rho, cap, a, c, b_max, pin)
    d_outer = geometry.outer_diameter(out.d_mean, out.h)
    d_inner = geometry.inner_diameter(out.d_mean, out.h)
    speed = geometry.rim_speed(omega, d_outer)
    hb = out.h / out.b
    out.update(
        j_shaft=j_shaft,
        omega=omega,
        cap=cap,
        cap_speed=cap_speed,
        d_outer=d_outer,
        d_inner=np.maximum(d_inner, 0.0),
        hb_ratio=hb,
        rim_speed=speed,
        hoop_stress=geometry.hoop_stress(rho, speed),
        j_at_reference=out.j_flywheel * ratio * ratio,
    )
    out["binding"] = np.where(
        out.feasible,
        check.binding_mask(
            geometry_name, out.j_flywheel, j_shaft, d_outer, d_inner, out.b, hb, cap_speed, envelope, b_max, a, c
        ),
        0,
    )
    return out
