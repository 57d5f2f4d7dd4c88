"""The wheel section of the speed-against-error run: whole wheels by flyopt, SLSQP and a grid.

One small case of each kind (a seeded random wheel; the first combination of
punch-press-wheel), the quick configuration. No timing is asserted: the rows
must be well formed, flyopt's design must be the best known wheel to 1e-6
(SLSQP on the same NLP is the second method it is held against), and a grid,
which only samples, can never beat it.
"""

import math

import numpy as np
import pytest

from flyopt.bench import wheel
from flyopt.bench.sections import SECTIONS
from flyopt.bench.timing import Config
from flyopt.design import wheel_design, wheel_nlp

MASS_RTOL = 1e-6


def _check_rows(rows, case):
    methods = [r.method for r in rows if r.case == case.name]
    assert methods[0] == "flyopt-ipopt" and "slsqp" in methods and "grid" in methods
    for r in rows:
        where = f"{r.case}/{r.method}/{r.setting}"
        assert r.section == "wheel", where
        assert r.time_median_s > 0.0 and r.time_p25_s <= r.time_median_s <= r.time_p75_s, where
        assert r.repeats >= 1 and r.number >= 1, where
        assert not math.isnan(r.error) and r.error >= 0.0, where
        assert r.verdicts_ok + r.failures == r.verdicts_total == 1, where
        if r.verdicts_ok:  # a counted design: its rows hold and its error is finite
            assert r.violation <= wheel.COUNT_TOL and math.isfinite(r.error), where
        else:
            assert r.error == math.inf, where
    by_method = {r.method: r for r in rows}
    flyopt = by_method["flyopt-ipopt"]
    assert flyopt.verdicts_ok == 1 and flyopt.time_ratio == 1.0
    assert flyopt.error <= MASS_RTOL
    # the best known mass is one of the methods' own (some row has error exactly 0)
    assert min(r.error for r in rows) == 0.0
    # SLSQP with CasADi gradients converges on these small cases and agrees with IPOPT
    assert by_method["slsqp"].verdicts_ok == 1 and by_method["slsqp"].error <= MASS_RTOL


@pytest.fixture(scope="module")
def config():
    return Config.make(quick=True)


def test_wheel_section_is_registered():
    assert SECTIONS["wheel"] is wheel.section_wheel


def test_random_wheel_rows(config):
    (case,) = wheel.random_wheel_cases(1, seed=config.seed)
    rows = wheel.wheel_rows([case], config)
    assert [r.method for r in rows] == ["flyopt-ipopt", "slsqp"] + ["grid"] * len(wheel.QUICK_GRIDS)
    _check_rows(rows, case)


@pytest.mark.slow  # 4 s: the whole-wheel benchmark's scene rows
def test_scene_rows_and_the_watch_is_undone(config):
    """The scene's first combination: flyopt's whole design (stress check included) and its NLP alone."""
    before = (wheel_design.design_combination, wheel_nlp.solve)
    cases = wheel.scene_cases()
    assert (wheel_design.design_combination, wheel_nlp.solve) == before
    assert cases and len({c.name for c in cases}) == len(cases)
    rows = wheel.wheel_rows(cases[:1], config)
    assert "flyopt-nlp" in {r.method for r in rows}
    _check_rows(rows, cases[0])


def test_the_bench_nlp_is_flyopts(config):
    """The bench's CasADi functions evaluate flyopt's design as flyopt reports it: its mass (by
    flyopt.design.wheel, not through the bench) and rows within their bounds."""
    (case,) = wheel.random_wheel_cases(1, seed=config.seed)
    nlp = wheel.WheelNlp(case)
    dims = case.flyopt()
    from flyopt.design import wheel as wheel_model

    mass = float(wheel_model.wheel_mass(wheel_model.parts(case.structure.geometry, dims, case.problem.density)))
    x = nlp.x_of(dims)
    assert nlp.mass_of(x) == pytest.approx(mass, rel=1e-12)
    assert nlp.violation(x) <= wheel.REFERENCE_TOL
    # a wheel 1 % thinner in every dimension has too little inertia: the rows see it
    assert nlp.violation(x + np.log(0.99)) > 1e-3
