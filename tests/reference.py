"""Independent reference implementations for the tests (no flyopt code).

Exact rational arithmetic (fractions) for piecewise-linear torques: every
value a float can hold is a rational, so these results are exact for the
given float inputs.
"""

import bisect
from fractions import Fraction


def exact_chain(xd, yd, xr, yr):
    """ΔE at every knot and crossing in exact rational arithmetic; returns (max, min).

    Independent of flyopt: evaluates both polylines at the union of their
    breakpoints with Fractions, finds crossings of each linear piece exactly
    and integrates trapezoids exactly.
    """
    xd, yd, xr, yr = ([Fraction(v) for v in a] for a in (xd, yd, xr, yr))

    def at(x, y, p, side):
        first, last = bisect.bisect_left(x, p), bisect.bisect_right(x, p) - 1
        if first <= last:  # p is a point of the table (two points: a step)
            return y[first] if side == "left" else y[last]
        k = last
        return y[k] + (y[k + 1] - y[k]) * (p - x[k]) / (x[k + 1] - x[k])

    knots = sorted(set(xd) | set(xr))
    e, values = Fraction(0), [Fraction(0)]
    for p, q in zip(knots[:-1], knots[1:]):
        a = at(xd, yd, p, "right") - at(xr, yr, p, "right")
        b = at(xd, yd, q, "left") - at(xr, yr, q, "left")
        h = q - p
        if a * b < 0:
            t = a / (a - b)
            values.append(e + a * t * h / 2)
        e += (a + b) * h / 2
        values.append(e)
    return max(values), min(values), e


def exact_a_max_against_mean(x, y):
    """A_max of a table against the constant that balances it, all in rationals.

    The balancing constant W/Φ is kept exact (it is not a float).
    """
    xs = [Fraction(v) for v in x]
    ys = [Fraction(v) for v in y]
    work = sum((ys[k] + ys[k + 1]) * (xs[k + 1] - xs[k]) / 2 for k in range(len(xs) - 1))
    mean = work / (xs[-1] - xs[0])
    e, values = Fraction(0), [Fraction(0)]
    for k in range(len(xs) - 1):
        a, b, h = mean - ys[k], mean - ys[k + 1], xs[k + 1] - xs[k]
        if a * b < 0:
            t = a / (a - b)
            values.append(e + a * t * h / 2)
        e += (a + b) * h / 2
        values.append(e)
    return max(values) - min(values)
