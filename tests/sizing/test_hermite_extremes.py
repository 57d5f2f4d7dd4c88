"""flyopt.cycle.numerics.hermite_extremes: the speed extremes between grid nodes.

References are closed forms: the maximum of a sampled sine, and a first-order
relaxation (a stiff motor's speed) whose extremes are its end values.
"""

import math

import numpy as np
import pytest

from flyopt.cycle.numerics import hermite_extremes


def test_a_smooth_extremum_between_nodes_is_refined():
    """sin on 13 nodes whose maximum (π/2) falls between two of them: the cubic's maximum is within
    O(h⁴) of 1 and of π/2, where the nodes alone miss it by O(h²)."""
    phi = np.linspace(0.1, 3.0, 13)[None, :]
    (at_hi, hi), (at_lo, lo) = hermite_extremes(phi, np.sin(phi), np.cos(phi))
    nodes = float(np.max(np.sin(phi)))
    assert 1 - nodes > 2e-4  # the nodes alone are off
    assert hi == pytest.approx(1.0, abs=1e-5) and at_hi == pytest.approx(math.pi / 2, abs=1e-3)
    assert lo == pytest.approx(math.sin(0.1), rel=1e-12)


@pytest.mark.parametrize("tau", [1e-2, 1e-3, 1e-5])
def test_a_boundary_layer_does_not_overshoot(tau):
    """A first-order relaxation f' = (g − f)/τ sampled far more coarsely than τ, g stepping from 1 to 0 and
    back: f moves monotonically between its levels (f stays within [0, 1] for all φ), so its extremes
    are the node values; the cubic through the ODE's slopes overshot them by far."""
    h = 0.05
    phi = np.arange(0.0, 2.0 + h / 2, h)
    g = np.where((phi > 0.5) & (phi <= 1.5), 0.0, 1.0)
    f = np.empty_like(phi)  # the exact solution, started at its level
    f[0] = 1.0
    for k in range(1, len(phi)):
        f[k] = g[k] + (f[k - 1] - g[k]) * math.exp(-(phi[k] - phi[k - 1]) / tau)
    slope = (g - f) / tau
    (_, hi), (_, lo) = hermite_extremes(phi[None, :], f[None, :], slope[None, :])
    assert hi == pytest.approx(f.max(), rel=1e-12) and hi <= 1.0
    assert lo == pytest.approx(f.min(), abs=1e-12) and lo >= 0.0


def test_an_extremum_in_a_rows_first_interval_is_refined():
    """The rows are the cycle's pieces, joined node to node: an extremum mid-way in a row's first interval
    (where that row's own first rise vanishes) is refined like any other, the rise before it taken from the
    row that ends there. 32 rows of 65 nodes (the periodic model's layout), cos(k(φ − x0)) with its maximum
    half a step into row 5."""
    cycle = 2 * math.pi
    starts = np.linspace(0, cycle, 33)[:-1]
    phi = starts[:, None] + np.linspace(0, 1, 65)[None, :] * (cycle / 32)
    h, k = cycle / 32 / 64, 4.0
    x0 = 5 * cycle / 32 + h / 2
    (at_hi, hi), (_, lo) = hermite_extremes(phi, np.cos(k * (phi - x0)), -k * np.sin(k * (phi - x0)))
    turns = k * (at_hi - x0) / (2 * math.pi)  # the maxima repeat every 2π/k, each as high
    assert hi == pytest.approx(1.0, abs=1e-9) and turns == pytest.approx(round(turns), abs=1e-5)
    assert lo == pytest.approx(-1.0, abs=1e-9)


def test_delta_of_a_sine_torque_against_its_closed_form():
    """M = M0 sin(kφ + p) on a constant inertia J at a prescribed mean speed: ω²/2 swings by 2 M0/(k J), so
    δ = (ω_max − ω_min)/ω_m = 2 M0 / (J k ω_m²) exactly (ω_m the midrange); the speed's maximum placed half
    a step into a piece of the periodic model's grid."""
    import casadi as ca

    from flyopt.sizing.periodic import periodic_solution

    cycle, j, m0, omega, k = 2 * math.pi, 2.0, 50.0, 30.0, 4.0
    x0 = 5 * cycle / 32 + cycle / 32 / 64 / 2
    phase = math.pi - k * x0

    def net(phi, w):
        return m0 * ca.sin(k * phi + phase)

    solution = periodic_solution(net, j, cycle, omega)
    assert solution.delta == pytest.approx(2 * m0 / (j * k * omega**2), rel=1e-7)
