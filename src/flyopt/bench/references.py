"""The bench's own answers, written independently of flyopt, that errors are measured against.

Cycle: A_max of piecewise-linear torque tables in exact rational arithmetic
(:mod:`fractions`): every float is a rational, so the balancing constant, the
crossings inside pieces and the trapezoid areas are exact for the given float
table. Geometry: the integral of r² dm over an annulus, in rationals. Design:
the bench's own statement of one material on one shaft (:class:`Combination`,
its constraints and their violation) and the lightest rim of it by a 1-D root
search (:func:`lightest_rim_1d`), written without flyopt.design.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, cast

import numpy as np
from scipy import optimize

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec, MountShaft
__all__ = [
    "VERIFY_RTOL",
    "exact_a_max_against_mean",
    "exact_a_max_tables",
    "exact_annulus_inertia",
    "Combination",
    "combinations",
    "rim_inertia",
    "violation",
    "Outcome",
    "checked_design",
    "lightest_rim_1d",
    "largest_rim_inertia",
]

VERIFY_RTOL = 1e-6
"""A design violating a constraint by more than this (relative) is no design."""


# ------------------------------------------------------------------------------
# Cycle: A_max of piecewise-linear torque tables (rational arithmetic)
# ------------------------------------------------------------------------------


def _add_piece(
    e: Fraction, high: Fraction, low: Fraction, a: Fraction, b: Fraction, h: Fraction
) -> tuple[Fraction, Fraction, Fraction]:
    """ΔE and its running extremes after one piece of a linear excess torque, exactly.

    ``e``, ``high``, ``low``: ΔE at the piece's start and its largest and smallest so far [J]; ``a``, ``b``: the
    excess torque at the piece's ends [N*m]; ``h``: its width [rad]. Where the torque changes sign inside the
    piece (at t = a/(a − b) of it), ΔE has an extreme there.
    """
    if a * b < 0:
        t = a / (a - b)
        c = e + a * t * h / 2
        high, low = max(high, c), min(low, c)
    e += (a + b) * h / 2
    return e, max(high, e), min(low, e)


def exact_a_max_against_mean(x: Iterable[float], y: Iterable[float]) -> Fraction:
    """A_max of a table against the constant that balances its work, exactly.

    Every float is a rational, so with :class:`fractions.Fraction` the
    balancing constant W/Φ, the crossings t = a/(a − b) inside pieces and the
    trapezoid areas are exact for the given float table. Independent of
    flyopt's cycle code.

    Parameters
    ----------
    x, y : sequence of float
        Angles [rad] (non-decreasing, a repeated angle is a step) and
        resisting torque [N*m].

    Returns
    -------
    Fraction
        A_max [J].
    """
    xs = [Fraction(float(v)) for v in x]
    ys = [Fraction(float(v)) for v in y]
    work = sum(((ys[k] + ys[k + 1]) * (xs[k + 1] - xs[k]) for k in range(len(xs) - 1)), Fraction(0)) / 2
    mean = work / (xs[-1] - xs[0])
    e, high, low = Fraction(0), Fraction(0), Fraction(0)
    for k in range(len(xs) - 1):
        e, high, low = _add_piece(e, high, low, mean - ys[k], mean - ys[k + 1], xs[k + 1] - xs[k])
    return high - low


def exact_a_max_tables(
    xd: Iterable[float], yd: Iterable[float], xr: Iterable[float], yr: Iterable[float]
) -> tuple[Fraction, Fraction]:
    """A_max and net work of two tables (driving, resisting), exactly.

    Both polylines are evaluated at the union of their breakpoints with
    right limits at the start and left limits at the end of each piece.

    Returns
    -------
    a_max, net : Fraction
        max ΔE − min ΔE and ΔE at the cycle end [J].
    """
    xs_d, ys_d, xs_r, ys_r = ([Fraction(float(v)) for v in a] for a in (xd, yd, xr, yr))

    def at(x, y, p, side):
        first, last = bisect.bisect_left(x, p), bisect.bisect_right(x, p) - 1
        if first <= last:
            return y[first] if side == "left" else y[last]
        k = last
        return y[k] + (y[k + 1] - y[k]) * (p - x[k]) / (x[k + 1] - x[k])

    knots = sorted(set(xs_d) | set(xs_r))
    e, high, low = Fraction(0), Fraction(0), Fraction(0)
    for p, q in zip(knots[:-1], knots[1:]):
        a = at(xs_d, ys_d, p, "right") - at(xs_r, ys_r, p, "right")
        b = at(xs_d, ys_d, q, "left") - at(xs_r, ys_r, q, "left")
        e, high, low = _add_piece(e, high, low, a, b, q - p)
    return high - low, e


# ------------------------------------------------------------------------------
# Geometry: the exact inertia of an annulus
# ------------------------------------------------------------------------------


def exact_annulus_inertia(d_outer: float, d_inner: float, b: float, density: float) -> float:
    """∫ r² dm over an annulus, π ρ B (R₁⁴ − R₂⁴)/2, in rationals (π and ρ as floats at the end)."""
    r1, r2, bw = Fraction(d_outer) / 2, Fraction(d_inner) / 2, Fraction(b)
    return math.pi * density * float(bw * (r1**4 - r2**4) / 2)


# ------------------------------------------------------------------------------
# Design: one material on one shaft, its constraints, its lightest rim
# ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Combination:
    """One material on one shaft, with everything its NLP needs (SI).

    ``cap`` = min(2 v_max / ω', envelope) [m]; ``j`` the inertia required on
    this shaft [kg*m^2]; ``hb`` the H/B range; ``b_max`` the width limit [m]
    (inf for none).
    """

    geometry: str
    density: float
    j: float
    cap: float
    hb: tuple[float, ...]  # (lowest, highest) H/B
    b_max: float
    material: str = ""
    shaft: str = ""
    speed_ratio: float = 1.0


def combinations(
    j_required: float,
    omega_mean: float,
    shafts: Sequence[MountShaft],
    materials: Sequence[Material],
    spec: DesignSpec,
) -> list[Combination]:
    """The Combination of every material × shaft of a scene."""
    envelope = math.inf if spec.max_outer_diameter is None else spec.max_outer_diameter
    b_max = math.inf if spec.max_width is None else spec.max_width
    out = []
    for m in materials:
        for s in shafts:
            v_max = cast(float, m.max_rim_speed)  # the bench's materials (built-in irons) all give one
            cap = min(2.0 * v_max / (omega_mean * s.speed_ratio), envelope)
            out.append(
                Combination(
                    spec.geometry,
                    m.density,
                    j_required / s.speed_ratio**2,
                    cap,
                    tuple(spec.hb_ratio),
                    b_max,
                    m.name,
                    s.name,
                    s.speed_ratio,
                )
            )
    return out


def rim_inertia(geometry: str, density: float, d_mean: float, h: float, b: float) -> float:
    """J of a rim [kg*m^2]: π ρ D_m H B (D_m² + H²)/4 (annulus) or without H² (thin rim)."""
    k = d_mean * d_mean + (h * h if geometry == "rim" else 0.0)
    return math.pi * density * d_mean * h * b * k / 4.0


def violation(combo: Combination, d_mean: float, h: float, b: float) -> float:
    """Largest relative violation of the combination's constraints by a rim [-] (0 if none)."""
    j = rim_inertia(combo.geometry, combo.density, d_mean, h, b)
    hb = h / b
    terms = [
        (combo.j - j) / combo.j,
        (d_mean + h - combo.cap) / combo.cap,
        (h - d_mean) / (d_mean + h),
        (combo.hb[0] - hb) / combo.hb[0],
        (hb - combo.hb[1]) / combo.hb[1],
    ]
    if math.isfinite(combo.b_max):
        terms.append((b - combo.b_max) / combo.b_max)
    return max(0.0, *terms)


@dataclass
class Outcome:
    """What a method says about one combination: a design, infeasible, or failed."""

    verdict: str  # "design" | "infeasible" | "failed"
    mass: float | None = None
    dims: tuple[float, float, float] | None = None  # (d_mean, h, b) [m]
    violation: float = 0.0
    reason: str = ""


def checked_design(combo: Combination, d_mean: float, h: float, b: float, reason: str = "") -> Outcome:
    """An Outcome for a solved rim, checked against the constraints: a design, or failed
    when a dimension is not finite or a constraint is violated by more than VERIFY_RTOL."""
    v = violation(combo, d_mean, h, b)
    mass = math.pi * combo.density * d_mean * h * b
    if not all(map(math.isfinite, (d_mean, h, b, mass))) or v > VERIFY_RTOL:
        return Outcome("failed", mass, (d_mean, h, b), v, f"{reason}; violates a constraint by {v:.3g}".lstrip("; "))
    return Outcome("design", mass, (d_mean, h, b), v, reason)


def lightest_rim_1d(combo: Combination, points: int = 3000) -> Outcome:
    """Lightest rim of a combination by a 1-D root search (the design reference).

    With D_m free the lightest rim has its outer diameter at the cap and the
    smallest H whose rim gives the inertia, B = min(H/hb_min, B_max): the
    inertia binding gives m = 4 J'/k, k = D_m² + H² (or D_m²), which falls as
    D_m grows and as H shrinks (H < D_m). H is found by a log-spaced scan from
    far below the thin-rim estimate to min(cap/2, hb_max B_max), then
    ``brentq`` to 1e-15; no root and no refined peak above J' means
    infeasible. Independent of flyopt.design.optimize.
    """
    rho, j, cap = combo.density, combo.j, combo.cap
    hb_min, hb_max = combo.hb

    def inertia(h):
        return _inertia_at_cap(combo, h)

    h_top = min(cap / 2.0, hb_max * combo.b_max)
    h_est = math.sqrt(4.0 * j * hb_min / (math.pi * rho * cap**3))
    low = min(1e-3 * h_est, 1e-12 * h_top)
    while low > 1e-300 and inertia(low) >= j:
        low *= 1e-3
    if not 0.0 < low < h_top:
        return Outcome("infeasible", reason="no room for a rim")
    grid = np.geomspace(low, h_top, points)
    with np.errstate(all="ignore"):
        values = inertia(grid)
    above = np.flatnonzero(values >= j)
    if above.size == 0:
        i = int(np.argmax(values))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        peak = optimize.minimize_scalar(
            lambda h: -inertia(h) / j, bounds=(lo, hi), method="bounded", options={"xatol": 1e-15 * hi}
        )
        if -peak.fun < 1.0:
            return Outcome("infeasible", reason=f"largest rim gives {-peak.fun:.6g} of J'")
        lo_root, hi_root = grid[max(i - 1, 0)], peak.x
    else:
        lo_root, hi_root = grid[above[0] - 1], grid[above[0]]
    u = optimize.brentq(
        lambda u: math.log(inertia(math.exp(u)) / j),
        math.log(lo_root),
        math.log(hi_root),
        xtol=1e-15,
        rtol=1e-15,
        maxiter=500,
    )
    h = math.exp(u)
    d = cap - h
    k = d * d + (h * h if combo.geometry == "rim" else 0.0)
    b = float(_width_at(combo, h))
    mass = 4.0 * j / k
    return Outcome("design", mass, (d, h, b), violation(combo, d, h, b), "1-D root search")


def largest_rim_inertia(combo: Combination) -> float:
    """Largest inertia a combination's rim can give [kg*m^2]: a scan refined by ``minimize_scalar``.

    The rim has its outer diameter at the cap and B = min(H/hb_min, B_max), as
    in :func:`lightest_rim_1d`; H runs from 1e-12 to 1 of min(cap/2, hb_max B_max).
    """
    h_top = min(combo.cap / 2.0, combo.hb[1] * combo.b_max)

    def inertia(h):
        return _inertia_at_cap(combo, h)

    hs = np.geomspace(1e-12 * h_top, h_top, 20001)
    i = int(np.argmax(inertia(hs)))
    if i == hs.size - 1:
        return float(inertia(h_top))
    lo, hi = hs[max(i - 1, 0)], hs[i + 1]
    peak = optimize.minimize_scalar(
        lambda h: -inertia(h), bounds=(lo, hi), method="bounded", options={"xatol": 1e-15 * hi}
    )
    return float(max(-peak.fun, inertia(hs[i])))


def _width_at(combo, h):
    """B [m] of the lightest rim of height ``h`` [m]: min(H/hb_min, B_max)."""
    return np.minimum(h / combo.hb[0], combo.b_max)


def _inertia_at_cap(combo, h):
    """J [kg*m^2] of the rim of height ``h`` [m] (scalar or array) with its outer diameter at the cap."""
    return rim_inertia(combo.geometry, combo.density, combo.cap - h, h, _width_at(combo, h))
