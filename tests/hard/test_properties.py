"""Property-based invariants of the cycle analysis and the design (hypothesis)."""

import math

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from flyopt.cycle.indicator import energy_indicator, required_inertia
from flyopt.cycle.torque import Constant, PiecewiseLinear
from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.materials import builtin_materials
from flyopt.machine.transmission import inertia_on_shaft

TWO_PI = 2 * math.pi
# derandomize: CI runs the same examples every time (a failure is reproducible, not a lottery)
SETTINGS = settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def tables(draw, min_points=3, max_points=40):
    n = draw(st.integers(min_points, max_points))
    inner = draw(st.lists(st.floats(0.01, TWO_PI - 0.01), min_size=n - 2, max_size=n - 2))
    x = np.concatenate(([0.0], np.sort(inner), [TWO_PI]))
    y = np.array(draw(st.lists(st.floats(-1e4, 1e4, allow_subnormal=False), min_size=n, max_size=n)))
    return x, y


def a_max(x, y):
    return energy_indicator(Constant(None), PiecewiseLinear(x, y), TWO_PI).a_max


def scale(x, y):
    return max(float(np.ptp(y)) * TWO_PI, 1e-300)


@SETTINGS
@given(tables(), st.floats(-1e5, 1e5))
def test_adding_a_constant_to_both_torques_changes_nothing(table, c):
    """Up to the round-off of y + c itself: a ripple of 5.7e-174 N·m on top of c = 1 N·m
    is not representable (hypothesis found it), so the shifted table has lost it."""
    x, y = table
    lost = 4 * np.finfo(float).eps * (abs(c) + float(np.max(np.abs(y)))) * TWO_PI
    assert_allclose(a_max(x, y + c), a_max(x, y), rtol=1e-9, atol=1e-12 * scale(x, y) + lost)


@SETTINGS
@given(tables(), st.floats(1e-3, 1e3))
def test_scaling_torques_scales_a_max_and_j(table, k):
    x, y = table
    base = a_max(x, y)
    assert_allclose(a_max(x, k * y), k * base, rtol=1e-9, atol=1e-12 * k * scale(x, y))
    omega, delta = 100.0, 0.05
    assert_allclose(required_inertia(k * base, omega, delta), k * required_inertia(base, omega, delta), rtol=1e-12)


def rotate(x, y, shift):
    """The same periodic table, its cycle starting at ``shift`` (not one of its angles).

    Every point moves to (x − shift) mod 2π in order, so steps stay steps; the old cycle
    end and start meet at 2π − shift (a step when y[-1] != y[0]); the cut at ``shift``
    gets the interpolated value at both new ends.
    """
    k = int(np.searchsorted(x, shift))  # x[k-1] < shift < x[k]
    cut = y[k - 1] + (y[k] - y[k - 1]) * (shift - x[k - 1]) / (x[k] - x[k - 1])
    xr = np.concatenate(([0.0], x[k:] - shift, x[:k] - shift + TWO_PI, [TWO_PI]))
    yr = np.concatenate(([cut], y[k:], y[:k], [cut]))
    # the old start and end both sit at 2π − shift; the old x = 0 point is dropped if it
    # duplicates a third point there
    return xr, yr


@SETTINGS
@given(tables(), st.floats(0.05, TWO_PI - 0.05))
def test_shifting_the_cycle_start_keeps_a_max(table, shift):
    """Start the cycle at another angle: the same periodic torque, the same A_max."""
    x, y = table
    assume(not np.any(x == shift))
    xr, yr = rotate(x, y, shift)
    assert_allclose(a_max(xr, yr), a_max(x, y), rtol=1e-9, atol=1e-12 * scale(x, y))


@SETTINGS
@given(st.floats(1e-6, 1e6), st.floats(0.02, 50.0))
def test_moving_the_flywheel_to_a_shaft_divides_j_by_ratio_squared(j, ratio):
    assert_allclose(inertia_on_shaft(j, ratio) * ratio**2, j, rtol=1e-14)


@SETTINGS
@given(st.floats(1.0, 1e5), st.floats(1.0, 1e4), st.floats(1e-5, 0.5), st.floats(1e-5, 0.5))
def test_j_decreases_monotonically_in_delta(a, omega, d1, d2):
    lo, hi = sorted((d1, d2))
    assert required_inertia(a, omega, hi) <= required_inertia(a, omega, lo)


MATERIALS = list(builtin_materials().values())


@settings(max_examples=25, deadline=None)
@given(st.floats(1e-3, 1e4), st.floats(50.0, 5000.0), st.lists(st.floats(0.1, 20.0), min_size=1, max_size=3))
def test_more_materials_or_shafts_never_make_the_optimum_heavier(j, rpm, ratios):
    omega = rpm * TWO_PI / 60
    shafts = [MountShaft(f"s{k}", r) for k, r in enumerate(ratios)]
    spec = DesignSpec(geometry="rim", max_outer_diameter=2.0)

    def best_mass(materials, shafts):
        result = design_flywheel(j, omega, shafts, materials, spec)
        return result.best.mass if result.best else math.inf

    few = best_mass(MATERIALS[:1], shafts[:1])
    more_materials = best_mass(MATERIALS, shafts[:1])
    more_both = best_mass(MATERIALS, shafts)
    assert more_materials <= few * (1 + 1e-9)
    assert more_both <= more_materials * (1 + 1e-9)
