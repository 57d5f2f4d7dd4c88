"""What other codes do, measured against flyopt: sampled quadrature of A_max, SLSQP and grids.

Cycle peers resample a torque table at N equally spaced angles and chain the
excess work by a quadrature rule (what spreadsheets and student codes do).
Design peers solve the same rim model as flyopt's NLP: scipy's SLSQP (in
scaled physical variables and in flyopt's own log-variables) and a
brute-force grid over mean diameter × H/B, each point sized exactly to the
required inertia. Each answer is checked by
:func:`flyopt.bench.references.checked_design`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from scipy import integrate, optimize

from flyopt.bench.references import Combination, Outcome, checked_design, violation

__all__ = [
    "SAMPLED_RULES",
    "sampled_a_max",
    "integrate_samples",
    "SLSQP_FTOLS",
    "SLSQP_FTOL",
    "slsqp_combination",
    "grid_combination",
]


# ------------------------------------------------------------------------------
# Cycle: sampled integration rules
# ------------------------------------------------------------------------------


SAMPLED_RULES = ("rectangle", "trapezoid", "cumtrapz", "simpson")


def sampled_a_max(
    x: Sequence[float] | NDArray[np.float64],
    y: Sequence[float] | NDArray[np.float64],
    cycle_angle: float,
    samples: int | None,
    rule: str,
) -> float:
    """A_max of a table against its mean by sampling and a quadrature rule.

    The table is resampled at ``samples`` equally spaced angles (``np.interp``),
    the mean torque is the rule's work over the cycle angle, and ΔE is the
    rule's running integral of (mean − M): ``rectangle`` a left Riemann sum,
    ``trapezoid`` numpy cumulative trapezoids, ``cumtrapz``
    ``scipy.integrate.cumulative_trapezoid``, ``simpson``
    ``scipy.integrate.cumulative_simpson``. A_max = max ΔE − min ΔE.
    With ``samples`` None the table's own points are used (trapezoid only).
    """
    if samples is None:
        phi, m = np.asarray(x, float), np.asarray(y, float)
    else:
        phi = np.linspace(0.0, cycle_angle, samples)
        m = np.interp(phi, x, y)
    return integrate_samples(phi, m, cycle_angle, rule)


def integrate_samples(phi: NDArray[np.float64], m: NDArray[np.float64], cycle_angle: float, rule: str) -> float:
    """A_max of torque samples ``m`` at angles ``phi`` against their mean, by one rule."""
    if rule == "rectangle":
        dphi = np.diff(phi)
        w = m[:-1] * dphi
        mean = w.sum() / cycle_angle
        de = np.cumsum(mean * dphi - w)
        return float(max(de.max(), 0.0) - min(de.min(), 0.0))
    if rule == "trapezoid":
        dphi = np.diff(phi)
        w = 0.5 * (m[1:] + m[:-1]) * dphi
        mean = w.sum() / cycle_angle
        de = np.cumsum(mean * dphi - w)
        return float(max(de.max(), 0.0) - min(de.min(), 0.0))
    if rule == "cumtrapz":
        mean = integrate.trapezoid(m, phi) / cycle_angle
        de = integrate.cumulative_trapezoid(mean - m, phi, initial=0.0)
        return float(de.max() - de.min())
    if rule == "simpson":
        mean = integrate.simpson(m, x=phi) / cycle_angle
        de = integrate.cumulative_simpson(mean - m, x=phi, initial=0.0)
        return float(de.max() - de.min())
    raise ValueError(f"rule {rule!r} not recognised; allowed are {SAMPLED_RULES}")


# ------------------------------------------------------------------------------
# Design: SLSQP and brute-force grids on the rim model
# ------------------------------------------------------------------------------


def _scales(combo):
    """(L, H_s, B_s, ε = H_s/L): the thin rim at D_m = L = cap, H/B = hb_min, giving J'."""
    length = combo.cap
    h_s = math.sqrt(4.0 * combo.j * combo.hb[0] / (math.pi * combo.density * length**3))
    return length, h_s, h_s / combo.hb[0], h_s / length


SLSQP_FTOLS = (1e-6, 1e-9, 1e-12)
"""SLSQP's ``ftol`` settings: scipy's default, a competent choice for 1e-6 in mass, and a tight one."""
SLSQP_FTOL = 1e-9
"""The SLSQP setting the targets compare with (tight enough for 1e-6 in mass, loose enough to converge)."""


def slsqp_combination(
    combo: Combination, variables: str = "scaled", ftol: float = SLSQP_FTOL, maxiter: int = 200
) -> Outcome:
    """One combination by ``scipy.optimize.minimize(method="SLSQP")`` on the same model.

    Same variables (D_m, H, B), constraints and scales as flyopt's NLP, with
    analytic gradients and the thin-rim start (outer diameter at the cap,
    H/B = hb_min), written as a competent scipy user would:

    ``variables="scaled"``
        z = (D_m/L, H/H_s, B/B_s): mass ∝ z_d z_h z_b; inertia
        z_d z_h z_b (z_d² + ε² z_h²) >= 1; z_d + ε z_h <= 1; z_d >= ε z_h;
        z_b <= z_h <= (hb_max/hb_min) z_b (or z_h = z_b); bounds z > 0 and
        z_b <= B_max/B_s.
    ``variables="log"``
        flyopt's own formulation: the logarithms of the same z, objective
        log mass + 1e-3 x_h (flyopt's tie-break), the same rows of g.

    A result that does not report success, or that violates a constraint by
    more than 1e-6 relative, gives no design ("failed" if the combination is
    feasible, which the caller decides). Warnings are recorded in the reason.
    """
    length, h_s, b_s, eps = _scales(combo)
    hb_min, hb_max = combo.hb
    ratio = hb_max / hb_min
    rim = combo.geometry == "rim"
    b_top = combo.b_max / b_s
    cons = []
    if variables == "scaled":

        def f(z):
            return z[0] * z[1] * z[2]

        def df(z):
            return np.array([z[1] * z[2], z[0] * z[2], z[0] * z[1]])

        def g_inertia(z):
            d, h, b = z
            return d * h * b * (d * d + (eps * eps * h * h if rim else 0.0)) - 1.0

        def dg_inertia(z):
            d, h, b = z
            e2 = eps * eps if rim else 0.0
            return np.array(
                [h * b * (3 * d * d + e2 * h * h), d * b * (d * d + 3 * e2 * h * h), d * h * (d * d + e2 * h * h)]
            )

        cons.append({"type": "ineq", "fun": g_inertia, "jac": dg_inertia})
        cons.append(
            {"type": "ineq", "fun": lambda z: 1.0 - z[0] - eps * z[1], "jac": lambda z: np.array([-1.0, -eps, 0.0])}
        )
        cons.append({"type": "ineq", "fun": lambda z: z[0] - eps * z[1], "jac": lambda z: np.array([1.0, -eps, 0.0])})
        if ratio > 1.0:
            cons.append({"type": "ineq", "fun": lambda z: z[1] - z[2], "jac": lambda z: np.array([0.0, 1.0, -1.0])})
            cons.append(
                {"type": "ineq", "fun": lambda z: ratio * z[2] - z[1], "jac": lambda z: np.array([0.0, -1.0, ratio])}
            )
        else:
            cons.append({"type": "eq", "fun": lambda z: z[1] - z[2], "jac": lambda z: np.array([0.0, 1.0, -1.0])})
        bounds: list[tuple[float | None, float | None]] = [
            (1e-12, None),
            (1e-12, None),
            (1e-12, b_top if math.isfinite(b_top) else None),
        ]
        x0 = np.array([1.0 - min(eps, 0.5), 1.0, min(1.0, b_top)])

        def dims(z):
            return length * z[0], h_s * z[1], b_s * z[2]
    elif variables == "log":
        log_eps = math.log(eps)

        def f(x):
            return x[0] + x[1] + x[2] + 1e-3 * x[1]

        def df(x):
            return np.array([1.0, 1.001, 1.0])

        def g_inertia(x):
            t = x[1] + log_eps - x[0]
            return 3 * x[0] + x[1] + x[2] + (math.log1p(math.exp(2 * t)) if rim else 0.0)

        def dg_inertia(x):
            if not rim:
                return np.array([3.0, 1.0, 1.0])
            t = x[1] + log_eps - x[0]
            s = 2.0 / (1.0 + math.exp(-2 * t))
            return np.array([3.0 - s, 1.0 + s, 1.0])

        def g_outer(x):
            t = x[1] + log_eps - x[0]
            return -(x[0] + math.log1p(math.exp(t)))

        def dg_outer(x):
            t = x[1] + log_eps - x[0]
            s = 1.0 / (1.0 + math.exp(-t))
            return -np.array([1.0 - s, s, 0.0])

        cons.append({"type": "ineq", "fun": g_inertia, "jac": dg_inertia})
        cons.append({"type": "ineq", "fun": g_outer, "jac": dg_outer})
        cons.append(
            {"type": "ineq", "fun": lambda x: -log_eps - (x[1] - x[0]), "jac": lambda x: np.array([1.0, -1.0, 0.0])}
        )
        if ratio > 1.0:
            cons.append({"type": "ineq", "fun": lambda x: x[1] - x[2], "jac": lambda x: np.array([0.0, 1.0, -1.0])})
            cons.append(
                {
                    "type": "ineq",
                    "fun": lambda x: math.log(ratio) - (x[1] - x[2]),
                    "jac": lambda x: np.array([0.0, -1.0, 1.0]),
                }
            )
        else:
            cons.append({"type": "eq", "fun": lambda x: x[1] - x[2], "jac": lambda x: np.array([0.0, 1.0, -1.0])})
        bounds = [(None, None), (None, None), (None, math.log(b_top) if math.isfinite(b_top) else None)]
        x0 = np.array([math.log1p(-min(eps, 0.5)), 0.0, min(0.0, math.log(b_top))])

        def dims(x):
            return length * math.exp(x[0]), h_s * math.exp(x[1]), b_s * math.exp(x[2])
    else:
        raise ValueError(f"variables {variables!r} not recognised; allowed are 'scaled', 'log'")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with np.errstate(all="ignore"):
            try:
                res = optimize.minimize(
                    f,
                    x0,
                    jac=df,
                    method="SLSQP",
                    bounds=bounds,
                    constraints=cons,
                    options={"ftol": ftol, "maxiter": maxiter},
                )
            except (ValueError, OverflowError, ZeroDivisionError) as err:
                return Outcome("failed", reason=f"SLSQP raised {type(err).__name__}: {err}")
    note = "; ".join(sorted({str(w.message).splitlines()[0] for w in caught}))
    message = f"SLSQP: {res.message} (status {res.status}, {res.nit} iterations)"
    if note:
        message += f"; warning: {note}"
    try:
        d, h, b = dims(res.x)
    except OverflowError:
        return Outcome("failed", reason=message + "; overflow")
    if not res.success:  # keep the last point: how far it was from a design is worth knowing
        v = violation(combo, d, h, b) if min(d, h, b) > 0 else math.inf
        return Outcome("failed", math.pi * combo.density * d * h * b, (d, h, b), v, message)
    return checked_design(combo, d, h, b, message)


def grid_combination(combo: Combination, n_diameters: int, n_ratios: int) -> Outcome:
    """Lightest rim on a brute-force grid of mean diameter × H/B (what flywheel scripts do).

    D_m takes ``n_diameters`` equally spaced values in (0, cap], H/B
    ``n_ratios`` values in [hb_min, hb_max]. At each grid point the cross
    section is sized exactly to the required inertia (thin rim:
    H² = 4 J k/(π ρ D³); annulus: the positive root u = H² of
    u² + D² u = 4 J k/(π ρ D)), B = H/k; points breaking the outer-diameter
    cap, the inner diameter or the width limit are dropped and the lightest
    remaining one is taken. No grid point feasible: reported infeasible.
    """
    rho, j, cap = combo.density, combo.j, combo.cap
    d = cap * np.arange(1, n_diameters + 1)[:, None] / n_diameters
    k = np.linspace(combo.hb[0], combo.hb[1], n_ratios if combo.hb[1] > combo.hb[0] else 1)[None, :]
    c = 4.0 * j * k / (math.pi * rho * d)
    if combo.geometry == "rim":
        d2 = d * d
        h = np.sqrt(2.0 * c / (d2 + np.sqrt(d2 * d2 + 4.0 * c)))
    else:
        h = np.sqrt(c / (d * d))
    b = h / k
    ok = (d + h <= cap) & (h <= d) & (b <= combo.b_max)
    if not ok.any():
        return Outcome("infeasible", reason=f"no feasible point on the {n_diameters}x{n_ratios} grid")
    mass = np.where(ok, math.pi * rho * d * h * b, np.inf)
    i = np.unravel_index(int(np.argmin(mass)), mass.shape)
    return checked_design(combo, float(d[i[0], 0]), float(h[i]), float(b[i]), "grid")
