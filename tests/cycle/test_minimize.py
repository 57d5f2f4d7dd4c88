"""flyopt.cycle.minimize.bounded_minimum against scipy.optimize's bounded minimize_scalar, point for point."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from flyopt.cycle.minimize import bounded_minimum

CASES = [
    (lambda x: (x - 2.0) ** 2, 0.0, 5.0, 1e-5),
    (lambda x: (x - 2.0) ** 2, 0.0, 5.0, 1e-12),
    (lambda x: math.cos(x), 0.0, 2 * math.pi, 1e-10),
    (lambda x: abs(x - 0.3) + 0.1 * x, -1.0, 1.0, 1e-9),
    (lambda x: x, 1.0, 3.0, 1e-10),  # the minimum at the lower end
    (lambda x: -x, 1.0, 3.0, 1e-10),  # at the upper end
    (lambda x: max(5.0, (x - 7.0) ** 2), 0.0, 25.0, 1e-10 * 25.0),  # a flat valley, as a rim's mass above its speed
    (lambda x: math.exp(x) - 4 * x, -3.0, 4.0, 1e-8),
    (lambda x: 3.0, 8.0, 25.0, 1e-9),  # constant
]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_same_points_and_answer_as_scipy(case):
    f, lo, hi, xatol = CASES[case]
    ours, theirs = [], []

    def mine(x):
        ours.append(x)
        return f(x)

    def scipys(x):
        theirs.append(x)
        return f(x)

    found = bounded_minimum(mine, lo, hi, xatol=xatol)
    ref = minimize_scalar(scipys, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    assert ours == theirs  # bit for bit, in the same order
    assert found.x == float(ref.x) and found.fun == float(ref.fun)
    assert found.calls == ref.nfev and found.converged == bool(ref.success)


def test_maxiter_reported_as_not_converged():
    found = bounded_minimum(lambda x: (x - 1.0) ** 2, -10.0, 10.0, xatol=1e-14, maxiter=5)
    ref = minimize_scalar(
        lambda x: (x - 1.0) ** 2, bounds=(-10.0, 10.0), method="bounded", options={"xatol": 1e-14, "maxiter": 5}
    )
    assert not found.converged and not ref.success
    assert found.x == float(ref.x) and found.calls == ref.nfev == 5


def test_nan_is_not_converged():
    assert not bounded_minimum(lambda x: math.nan, 0.0, 1.0).converged


def test_bad_bounds():
    with pytest.raises(ValueError):
        bounded_minimum(lambda x: x, 2.0, 1.0)
    with pytest.raises(ValueError):
        bounded_minimum(lambda x: x, 0.0, np.inf)


def test_the_scalar_brentq_is_scipys_bit_for_bit():
    """flyopt.cycle.numerics.brentq against scipy.optimize.brentq on functions whose zeros need every kind of step."""
    import math

    from scipy import optimize

    from flyopt.cycle.numerics import brentq

    cases = [
        (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),
        (lambda x: math.cos(x) - x, 0.0, 1.0),
        (lambda x: math.exp(x) - 1e6, 0.0, 30.0),
        (lambda x: (x - 1.0) ** 5, 0.0, 3.0),
        (lambda x: math.atan(1e6 * (x - 0.3)), -1.0, 1.0),
        (lambda x: 0.0 if x == 0.25 else x - 0.25, 0.25, 2.0),
    ]
    failed = 0
    for f, a, b in cases:
        for xtol, rtol in ((2e-12, 8.881784197001252e-16), (1e-15, 4 * 2.220446049250313e-16), (1e-3, 1e-3)):
            try:
                expected = optimize.brentq(f, a, b, xtol=xtol, rtol=rtol)
            except RuntimeError:  # the flat quintic's zero at the tightest tolerances: neither converges in 100
                failed += 1
                with pytest.raises(RuntimeError):
                    brentq(f, a, b, xtol=xtol, rtol=rtol)
                continue
            assert brentq(f, a, b, xtol=xtol, rtol=rtol) == expected
    assert failed == 2
