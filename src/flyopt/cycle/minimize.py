"""The minimum of a function of one variable on an interval, by Brent's bounded method.

Brent's method for a minimum (Brent 1973, ch. 5: parabolic interpolation
through the three best points, a golden-section step where the parabola is not
acceptable) on a closed interval, in the form of scipy.optimize's ``bounded``
``minimize_scalar`` (its ``fminbound``), operation for operation: the same
points are tried in the same order and the same point is returned. Importing
scipy.optimize costs about 0.3 s of a process's start, more than the drive
search it served (issue 26); this is the one place flyopt itself minimizes a
function of one variable on an interval.
"""

import math
from collections.abc import Callable
from typing import NamedTuple

#: Brent's sqrt(eps) (scipy's: the square root of 2.2e-16).
_SQRT_EPS = math.sqrt(2.2e-16)
_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))


class BoundedMinimum(NamedTuple):
    """The point found ``x``, its value ``fun``, the calls of the function, and whether it converged."""

    x: float
    fun: float
    calls: int
    converged: bool


def bounded_minimum(
    func: Callable[[float], float], low: float, high: float, xatol: float = 1e-5, maxiter: int = 500
) -> BoundedMinimum:
    """A local minimum of ``func`` on [low, high] to ``xatol`` (:class:`BoundedMinimum`).

    The same iterates, and the same answer, as
    ``scipy.optimize.minimize_scalar(func, bounds=(low, high), method="bounded",
    options={"xatol": xatol, "maxiter": maxiter})``. ``converged`` is False
    when ``maxiter`` calls did not reach the tolerance or a value was NaN.
    """
    if not (math.isfinite(low) and math.isfinite(high)):
        raise ValueError("bounded_minimum: the bounds must be finite")
    if low > high:
        raise ValueError("bounded_minimum: the lower bound exceeds the upper bound")
    a, b = low, high
    fulc = a + _GOLDEN * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = func(x)
    num = 1
    fu = math.inf
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    converged = True
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = True
        if abs(e) > tol1:  # a parabola through the three best points
            golden = False
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):  # acceptable
                rat = (p + 0.0) / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    rat = tol1 * _sign_or_one(xm - xf)
            else:
                golden = True
        if golden:
            e = a - xf if xf >= xm else b - xf
            rat = _GOLDEN * e
        x = xf + _sign_or_one(rat) * max(abs(rat), tol1)
        fu = func(x)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= maxiter:
            converged = False
            break
    if math.isnan(xf) or math.isnan(fx) or math.isnan(fu):
        converged = False
    return BoundedMinimum(float(xf), float(fx), num, converged)


def _sign_or_one(value: float) -> float:
    """The sign of ``value``, and 1 for zero (scipy's ``np.sign(v) + (v == 0)``)."""
    return 1.0 if value >= 0 else (-1.0 if value < 0 else math.nan)
