"""flyopt.sizing._numerics.hermite_extremes: the speed extremes between grid nodes.

References are closed forms: the maximum of a sampled sine, and a first-order
relaxation (a stiff motor's speed) whose extremes are its end values.
"""

import math

import numpy as np
import pytest

from flyopt.sizing._numerics import hermite_extremes


def test_a_smooth_extremum_between_nodes_is_refined():
    """sin on 13 nodes whose maximum (π/2) falls between two of them: the cubic's maximum is within
    O(h⁴) of 1 and of π/2, where the nodes alone miss it by O(h²)."""
    phi = np.linspace(0.1, 3.0, 13)[None, :]
    (at_hi, hi), (at_lo, lo) = hermite_extremes(phi, np.sin(phi), np.cos(phi))
    nodes = float(np.max(np.sin(phi)))
    assert 1 - nodes > 2e-4                       # the nodes alone are off
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
    f = np.empty_like(phi)                         # the exact solution, started at its level
    f[0] = 1.0
    for k in range(1, len(phi)):
        f[k] = g[k] + (f[k - 1] - g[k]) * math.exp(-(phi[k] - phi[k - 1]) / tau)
    slope = (g - f) / tau
    (_, hi), (_, lo) = hermite_extremes(phi[None, :], f[None, :], slope[None, :])
    assert hi == pytest.approx(f.max(), rel=1e-12) and hi <= 1.0
    assert lo == pytest.approx(f.min(), abs=1e-12) and lo >= 0.0
