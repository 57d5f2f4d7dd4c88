"""Stability of the cycle analysis on hard cases, against exact rational arithmetic.

Each case is generated, solved by flyopt and compared with an independent
exact reference (tests/reference.py, fractions): relative error <= 1e-9 is
the suite's bar (flyopt's own claim is 1e-12; the bar leaves room for
float inputs that are themselves rounded).
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from reference import exact_a_max_against_mean, exact_chain

from flyopt.cycle.indicator import energy_indicator, required_inertia
from flyopt.cycle.torque import Constant, PiecewiseLinear

TWO_PI = 2 * math.pi
BAR = 1e-9


def table_against_mean(x, y):
    ind = energy_indicator(Constant(None), PiecewiseLinear(np.asarray(x, float), np.asarray(y, float)), x[-1])
    return ind.a_max, float(exact_a_max_against_mean(x, y))


@pytest.mark.parametrize("n", [2, 3, 10, 1000, 10_000])
def test_table_sizes(n):
    """Tables of 2 to 10,000 points (100,000 in the slow variant)."""
    rng = np.random.default_rng(n)
    x = np.linspace(0, TWO_PI, n)
    y = 500 + 300 * np.sin(2 * x) + rng.normal(0, 40, n)
    got, ref = table_against_mean(x, y)
    if n == 2:  # a single linear piece against its mean: ΔE = quadratic, A_max = (y1-y0) Φ / 8
        assert_allclose(ref, abs(y[1] - y[0]) * TWO_PI / 8, rtol=1e-15)
    assert_allclose(got, ref, rtol=BAR)


@pytest.mark.slow
def test_table_of_100000_points():
    rng = np.random.default_rng(5)
    x = np.linspace(0, TWO_PI, 100_000)
    y = 500 + 300 * np.sin(2 * x) + rng.normal(0, 40, x.size)
    got, ref = table_against_mean(x, y)
    assert_allclose(got, ref, rtol=BAR)


def test_many_steps():
    """A staircase torque: 200 vertical steps, every crossing at a step."""
    k = np.arange(200)
    x = np.repeat(np.linspace(0, TWO_PI, 201), 2)[1:-1]
    y = np.repeat(1000 + 500 * np.sin(3 * k * TWO_PI / 200) + 37 * (k % 7), 2)
    got, ref = table_against_mean(x, y)
    assert_allclose(got, ref, rtol=BAR)


@pytest.mark.parametrize("offset", [0.0, 1e3, 1e6])
def test_working_stroke_spike(offset):
    """A press: a 2 % working stroke at 50 times the mean resisting torque, on top of an offset."""
    stroke = 0.02 * TWO_PI
    x = [0.0, 1.0, 1.0, 1.0 + stroke, 1.0 + stroke, TWO_PI]
    mean_idle = 100.0
    y = [offset + mean_idle] * 2 + [offset + 50 * mean_idle] * 2 + [offset + mean_idle] * 2
    got, ref = table_against_mean(x, y)
    assert_allclose(got, ref, rtol=BAR)
    # and the closed form: the deficit during the stroke is (peak − mean) × stroke
    mean = mean_idle + 49 * mean_idle * 0.02
    assert_allclose(got, (50 * mean_idle - mean) * stroke, rtol=1e-12)


@pytest.mark.parametrize("gap", [0.0, 1e-12, 1e-6])
def test_near_tangent_crossings(gap):
    """A peak that touches (gap 0) or almost touches the driving level without crossing it.

    The work is balanced by a block of height c over [5, 6] rad (steps at both ends), so the
    peak at 3 rad keeps its exact distance to the level.
    """
    level = 300.0
    x = np.array([0, 1, 2, 3, 4, 5, 5, 6, 6, TWO_PI])

    def table(c):
        return np.array([100.0, 200.0, 100.0, level - gap, 100.0, 100.0, 100.0 + c, 100.0 + c, 100.0, 100.0])

    _, _, net = exact_chain([0.0, TWO_PI], [level, level], x, table(0.0))
    y = table(float(net))  # a block of c·1 rad of resisting work absorbs the surplus
    hi, lo, net = exact_chain([0.0, TWO_PI], [level, level], x, y)
    assert abs(float(net)) < 1e-12 * level * TWO_PI
    ind = energy_indicator(Constant(level), PiecewiseLinear(x, y), TWO_PI)
    assert_allclose(ind.a_max, float(hi - lo), rtol=BAR)
    # touching is not crossing: no chain point at the peak
    assert not np.any(np.isclose(ind.chain_angle, 3.0, rtol=0, atol=1e-9))


@pytest.mark.parametrize("offset", [1e3, 1e6, 1e9])
def test_huge_offset_small_ripple(offset):
    """10^6 N·m mean with a 1 N·m ripple: no loss to cancellation."""
    rng = np.random.default_rng(int(math.log10(offset)))
    x = np.concatenate(([0.0], np.sort(rng.uniform(0, TWO_PI, 300)), [TWO_PI]))
    y = offset + rng.uniform(-1, 1, x.size)
    got, ref = table_against_mean(x, y)
    assert_allclose(got, ref, rtol=BAR)


def test_huge_offset_on_both_tables():
    rng = np.random.default_rng(3)
    x = np.linspace(0, TWO_PI, 400)
    yd = 1e6 + np.sin(x)
    yr = 1e6 + rng.uniform(-1, 1, x.size)
    _, _, net = exact_chain(x, yd, x, yr)
    yr = yr + float(net) / TWO_PI
    hi, lo, _ = exact_chain(x, yd, x, yr)
    ind = energy_indicator(PiecewiseLinear(x, yd), PiecewiseLinear(x, yr), TWO_PI)
    assert_allclose(ind.a_max, float(hi - lo), rtol=BAR)


@pytest.mark.parametrize("text", ["(1000000.0 + sin(phi)) - 1000000.0 + 3", "3 + (sin(phi) + 1000000.0) - 1e6"])
def test_cancellation_inside_an_expression(text):
    """An expression whose own evaluation cancels (1e6 − 1e6): its running error bound,
    not the size of its result, sets the round-off the quadrature accepts (regression: it
    was refused like the offset case before the noise existed). A_max = 2 J."""
    from flyopt.cycle.expression import Expression
    from flyopt.cycle.torque import ExpressionTorque

    ind = energy_indicator(ExpressionTorque(Expression(text), 1.0), Constant(None), TWO_PI)
    assert_allclose(ind.a_max, 2.0, rtol=BAR)


@pytest.mark.parametrize("offset, bar", [(0.0, 1e-12), (1e3, 1e-12), (1e6, BAR)])
def test_huge_offset_on_an_expression(offset, bar):
    """offset + sin φ against its (unknown) mean: A_max = 2 J exactly. An expression has no
    pivot, so M_d − M_r is known only to the round-off of the offset (1e6 N·m: ~1e-10 N·m):
    the quadrature must accept that level, not refuse it (regression: the vectorized
    quadrature refused it until it was told the integrand's noise), and stay within the bar."""
    from flyopt.cycle.expression import Expression
    from flyopt.cycle.torque import ExpressionTorque

    ind = energy_indicator(ExpressionTorque(Expression(f"{offset!r} + sin(phi)"), 1.0), Constant(None), TWO_PI)
    assert_allclose(ind.a_max, 2.0, rtol=bar)


@pytest.mark.parametrize("delta", [1e-5, 1e-3, 0.1, 0.5])
@pytest.mark.parametrize("rpm", [1.0, 100.0, 50_000.0])
def test_required_inertia_extremes(delta, rpm):
    """J_F = 900 A_max / (π² n² δ) over δ 1e-5..0.5 and 1..50,000 rpm (the hyperbola in δ)."""
    a_max = 1256.33
    omega = rpm * TWO_PI / 60
    j = required_inertia(a_max, omega, delta)
    assert_allclose(j, 900 * a_max / (math.pi**2 * rpm**2 * delta), rtol=1e-14)
    assert_allclose(j * delta, required_inertia(a_max, omega, 1.0), rtol=1e-14)
