"""The outer-diameter cap an infeasible combination needs: the smallest float that reaches the inertia.

``closed_form.cap_needed`` narrows a bracket to adjacent floats (no
scipy.optimize at start-up). The property is checked directly (the cap
reaches J, the float below it does not), and the cap against scipy's brentq,
an independent solver, within brentq's own tolerance.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from flyopt.design import closed_form


def cases(n=400, seed=3):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        geometry = str(rng.choice(["rim", "thin_rim", "disc"]))
        width = float(10 ** rng.uniform(-2, -0.3)) if geometry == "disc" or rng.random() < 0.7 else math.inf
        pin = float(rng.uniform(0.1, 1.5)) if geometry != "disc" and rng.random() < 0.3 else None
        case = geometry, 7200.0, float(rng.uniform(0.2, 2.0)), (1.5, 2.0), width, pin, float(10 ** rng.uniform(0.01, 2))
        if 0 < closed_form.max_inertia_one(*case[:5], pin)[0] < math.inf:  # a wheel fits, and J is bounded
            yield case


@pytest.mark.parametrize("geometry, density, cap, hb, width, pin, factor", list(cases()))
def test_the_cap_needed_is_the_smallest_float_that_reaches_the_inertia(geometry, density, cap, hb, width, pin, factor):
    def j_max(c):
        return closed_form.max_inertia_one(geometry, density, c, hb, width, pin)[0]

    j = j_max(cap) * factor
    needed, _ = closed_form.cap_needed(geometry, density, j, cap, hb, width, pin)
    if needed is None:  # only a pinned mean diameter limits what any cap gives
        assert pin is not None
        return
    assert j_max(needed) >= j * (1 - 1e-14)
    low = max(cap, pin or 0.0)
    reference = brentq(lambda c: j_max(c) / j - 1.0, low, 2 * needed, xtol=1e-15 * needed, rtol=1e-15)
    assert math.isclose(needed, reference, rel_tol=1e-12)


def test_bisection_finds_the_change_of_a_step():
    """A step at 0.3: the smallest float reaching 1 is 0.3 itself (a tolerance-based solver stops near it)."""
    assert closed_form.smallest_reaching(lambda c: 1.0 if c >= 0.3 else 0.0, 1.0, 0.1, 2.0) == 0.3
    assert closed_form.smallest_reaching(lambda c: c * c, 2.0, 1.0, 2.0) == math.sqrt(2.0)


def test_the_cap_needed_of_a_problem_scene_is_where_its_inertia_is_first_reached():
    """punch-press: the crankshaft combinations need more than the 1.2 m envelope; each cap is the first
    float at which the largest admissible rim reaches the inertia."""
    from conftest import PROBLEMS

    import flyopt

    result = flyopt.solve(flyopt.load(PROBLEMS / "punch-press.toml")).design
    checked = 0
    for c in result.candidates:
        if c.feasible or c.limits.d_outer_needed is None:
            continue
        density = {"cast_iron": 7200.0, "cast_steel": 7800.0, "ductile_iron": 7100.0}[c.material]
        hb = (1.5, 2.0)
        j = c.limits.j_required_on_shaft

        def j_max(cap):
            return closed_form.max_inertia_one("rim", density, cap, hb, 0.2, None)[0]

        assert j_max(c.limits.d_outer_needed) >= j > j_max(np.nextafter(c.limits.d_outer_needed, 0.0))
        checked += 1
    assert checked == 3
