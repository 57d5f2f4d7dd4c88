"""Smoke tests of flyopt.bench, the speed-against-error benchmark.

They run the quick configuration into a temporary directory and check what
was written and that every measurement carries a time and an error. No
timing is asserted: the machine's speed is not the code's property. The
exact cycle analysis is held to 1e-12 against exact rational arithmetic
(flyopt's own claim; the hard suite's bar is 1e-9).
"""

import csv
import math
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flyopt import bench


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    status = bench.main(["--quick", "--no-pin", "--out", str(out)])
    with open(out / "speed_error.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    return status, out, rows


def test_quick_run_writes_the_results(quick_run):
    status, out, rows = quick_run
    assert status == 0
    for name in ("speed_error.csv", "speed_error.png", "speed_error.md"):
        assert (out / name).stat().st_size > 0, name
    assert (out / "speed_error.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    text = (out / "speed_error.md").read_text(encoding="utf-8")
    assert "## Targets" in text and "## cycle" in text and "## design" in text
    assert "[auto, the default]" in text and "[IPOPT]" in text
    assert "Beyond the targets:" in text and "integration alone of 100,000 samples" in text
    assert {r["section"] for r in rows} == set(bench.SECTIONS)


def test_every_method_has_a_time_and_an_error(quick_run):
    _, _, rows = quick_run
    measured = [r for r in rows if r["setting"] != "not built"]   # the hub-and-arms placeholder
    assert measured
    for r in measured:
        where = f"{r['section']}/{r['case']}/{r['method']}/{r['setting']}"
        assert float(r["time_median_s"]) > 0.0, where
        assert float(r["time_p25_s"]) <= float(r["time_median_s"]) <= float(r["time_p75_s"]), where
        error = float(r["error"])
        assert not math.isnan(error) and error >= 0.0, where
    methods = {(r["section"], r["method"]) for r in measured}
    for expected in [("cycle", "flyopt-exact"), ("cycle", "trapezoid"), ("cycle", "simpson"),
                     ("cycle", "cumtrapz"), ("design", "flyopt-ipopt"), ("design", "flyopt-auto"),
                     ("design", "slsqp"),
                     ("design", "grid"), ("geometry", "thin_rim"), ("geometry", "rim")]:
        assert expected in methods


def test_exact_cycle_analysis_is_exact(quick_run):
    _, _, rows = quick_run
    exact = [r for r in rows if r["method"] == "flyopt-exact"]
    assert len(exact) == 3
    for r in exact:
        assert float(r["error"]) <= 1e-12, r


@pytest.mark.parametrize("method", ["flyopt-ipopt", "flyopt-auto"])
def test_design_rows_decide_every_combination(quick_run, method):
    """flyopt's two design paths decide every combination of the quick scenes and land within
    1e-6 of the optimum."""
    _, _, rows = quick_run
    row = next(r for r in rows if r["method"] == method)
    assert int(row["verdicts_ok"]) == int(row["verdicts_total"]) > 0
    assert float(row["error"]) <= 1e-6


def test_quick_hard_run(tmp_path):
    assert bench.main(["--quick", "--hard", "--no-pin", "--out", str(tmp_path)]) == 0
    with open(tmp_path / "hard.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert {r["kind"] for r in rows} == {"cycle", "j_required", "design"}
    design = [r for r in rows if r["kind"] == "design"]
    assert design
    # every combination carries flyopt's verdict and the SLSQP baselines'
    for column in ("flyopt_verdict", "auto_verdict", "slsqp_1e-09_verdict", "slsqplog_1e-09_verdict"):
        assert all(r[column] in ("design", "infeasible", "failed") for r in design), column
    # flyopt's paths succeed on every combination of the quick set
    assert all(r["flyopt_passed"] == "True" and r["auto_passed"] == "True" for r in design)
    text = (tmp_path / "hard.md").read_text(encoding="utf-8")
    assert "success" in text and "Worst cases: flyopt-ipopt" in text and "Worst cases: flyopt-auto" in text
    assert "auto path (the default): 100 %" in text


def test_sampled_rules_against_a_closed_form():
    """A_max of M = 1000 + 300 sin(2 phi) sampled finely: 2 * 300 / 2 = 300 J to 1e-6."""
    x = np.linspace(0.0, bench.TWO_PI, 4001)
    y = 1000.0 + 300.0 * np.sin(2.0 * x)
    for rule in bench.SAMPLED_RULES:
        assert_allclose(bench.sampled_a_max(x, y, bench.TWO_PI, 100_000, rule), 300.0, rtol=1e-5)


def test_exact_reference_on_a_spike():
    """Domain-style press: the deficit of the stroke is (peak - mean) x stroke, in rationals."""
    x, y = bench.table_spike()
    stroke = Fraction(float(x[3])) - Fraction(float(x[1]))
    mean = (Fraction(100) * (Fraction(bench.TWO_PI) - stroke) + Fraction(5000) * stroke) / Fraction(bench.TWO_PI)
    assert bench.exact_a_max_against_mean(x, y) == (Fraction(5000) - mean) * stroke


def test_baselines_agree_with_the_reference_on_one_combination():
    """SLSQP and a fine grid land on the 1-D reference mass of a plain combination."""
    combo = bench.Combination("rim", 7200.0, 10.0, 1.2, (1.5, 2.0), math.inf)
    ref = bench.lightest_rim_1d(combo)
    assert ref.verdict == "design" and ref.violation <= 1e-12
    for variables in ("scaled", "log"):
        got = bench.slsqp_combination(combo, variables)
        assert got.verdict == "design", got.reason
        assert_allclose(got.mass, ref.mass, rtol=1e-6)
    grid = bench.grid_combination(combo, 3000, 5)
    assert grid.verdict == "design" and grid.mass >= ref.mass * (1 - 1e-12)
    assert_allclose(grid.mass, ref.mass, rtol=2e-3)


def test_bad_section_is_refused(capsys):
    with pytest.raises(SystemExit) as err:
        bench.main(["--sections", "cycle,nonsense", "--no-pin"])
    assert err.value.code == 2
    assert "nonsense" in capsys.readouterr().err


def test_required_inertia_section_compares_the_models():
    """Constant J: the periodic solution reproduces the closed form; variable J and a motor: the
    constant-inertia method is measurably off and the exact model is the reference."""
    from flyopt.bench import Config, section_required_inertia

    rows = {(r.case.split(" ")[0], r.method): r for r in section_required_inertia(Config(quick=True))}
    assert rows["constant", "energy"].error < 1e-12
    assert rows["constant", "dynamic"].error < 1e-8
    assert rows["variable", "energy"].error > 1e-3 and rows["variable", "energy_mass"].setting == "cheapest exact"
    assert rows["variable", "dynamic"].error < 1e-8
    assert rows["speed-dependent", "energy"].error > 1e-4
    assert rows["speed-dependent", "dynamic"].setting == "cheapest exact"
