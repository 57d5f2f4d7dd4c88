"""Smoke tests of flyopt.bench, the speed-against-error benchmark.

They run the quick configuration into a temporary directory and check what
was written and that every measurement carries a time and an error. No
timing is asserted: the machine's speed is not the code's property. The
exact cycle analysis is held to 1e-12 against exact rational arithmetic
(flyopt's own claim; the hard suite's bar is 1e-9). A quick run is a smoke
run: it must leave the committed benchmarks/results alone.
"""

import ast
import csv
import math
import runpy
import shutil
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from sources import parsed

from flyopt.bench import cycle, main, peers, references
from flyopt.bench.sections import SECTIONS

ROOT = Path(__file__).resolve().parents[2]
COMMITTED = ("speed_error.csv", "speed_error.md", "speed_error.png", "hard.csv", "hard.md")


def _read_csv(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    status = main(["--quick", "--no-pin", "--output-dir", str(out)])
    return status, out, _read_csv(out / "speed_error.csv")


@pytest.mark.slow  # the quick bench run (some 8 s); the default run keeps the harness's refusals and rules
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
    assert {r["section"] for r in rows} == set(SECTIONS)


@pytest.mark.slow  # the quick bench run (some 8 s); the default run keeps the harness's refusals and rules
def test_every_method_has_a_time_and_an_error(quick_run):
    _, _, rows = quick_run
    measured = [r for r in rows if r["setting"] != "not built"]  # the hub-and-arms placeholder
    assert measured
    for r in measured:
        where = f"{r['section']}/{r['case']}/{r['method']}/{r['setting']}"
        assert float(r["time_median_s"]) > 0.0, where
        assert float(r["time_p25_s"]) <= float(r["time_median_s"]) <= float(r["time_p75_s"]), where
        error = float(r["error"])
        assert not math.isnan(error) and error >= 0.0, where
    methods = {(r["section"], r["method"]) for r in measured}
    for expected in [
        ("cycle", "flyopt-exact"),
        ("cycle", "trapezoid"),
        ("cycle", "simpson"),
        ("cycle", "cumtrapz"),
        ("design", "flyopt-ipopt"),
        ("design", "flyopt-auto"),
        ("design", "slsqp"),
        ("design", "grid"),
        ("geometry", "thin_rim"),
        ("geometry", "rim"),
    ]:
        assert expected in methods


@pytest.mark.slow  # the quick bench run (some 8 s); the default run keeps the harness's refusals and rules
def test_exact_cycle_analysis_is_exact(quick_run):
    _, _, rows = quick_run
    exact = [r for r in rows if r["method"] == "flyopt-exact"]
    assert len(exact) == 3
    for r in exact:
        assert float(r["error"]) <= 1e-12, r


@pytest.mark.slow  # the quick bench run (some 8 s); the default run keeps the harness's refusals and rules
@pytest.mark.parametrize("method", ["flyopt-ipopt", "flyopt-auto"])
def test_design_rows_decide_every_combination(quick_run, method):
    """flyopt's two design paths decide every combination of the quick scenes and land within
    1e-6 of the optimum."""
    _, _, rows = quick_run
    row = next(r for r in rows if r["method"] == method)
    assert int(row["verdicts_ok"]) == int(row["verdicts_total"]) > 0
    assert float(row["error"]) <= 1e-6


@pytest.mark.slow  # the quick bench run (some 8 s); the default run keeps the harness's refusals and rules
def test_required_inertia_section_compares_the_models(quick_run):
    """Constant J: the periodic solution reproduces the closed form; variable J and a motor: the
    constant-inertia method is measurably off and the exact model is the reference."""
    _, _, rows = quick_run
    rows = {(r["case"].split(" ")[0], r["method"]): r for r in rows if r["section"] == "required_inertia"}
    assert float(rows["constant", "energy"]["error"]) < 1e-12
    assert float(rows["constant", "dynamic"]["error"]) < 1e-8
    assert float(rows["variable", "energy"]["error"]) > 1e-3
    assert rows["variable", "energy_mass"]["setting"] == "cheapest exact"
    assert float(rows["variable", "dynamic"]["error"]) < 1e-8
    assert float(rows["speed-dependent", "energy"]["error"]) > 1e-4
    assert rows["speed-dependent", "dynamic"]["setting"] == "cheapest exact"


def test_quick_hard_run(tmp_path):
    assert main(["--quick", "--hard", "--no-pin", "--output-dir", str(tmp_path)]) == 0
    rows = _read_csv(tmp_path / "hard.csv")
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


# ------------------------------------------------------------------------------
# Where a run writes
# ------------------------------------------------------------------------------


def _committed_results(folder):
    """A benchmarks/results folder with sentinel copies of the committed files; returns their bytes."""
    results = folder / "benchmarks" / "results"
    results.mkdir(parents=True)
    for name in COMMITTED:
        (results / name).write_bytes(f"committed {name}\n".encode())
    return {path: path.read_bytes() for path in folder.rglob("*") if path.is_file()}


def _run_the_wrapper(folder, argv, monkeypatch):
    """benchmarks/bench_speed_error.py run as a script from a copy inside ``folder``."""
    script = folder / "benchmarks" / "bench_speed_error.py"
    shutil.copy(ROOT / "benchmarks" / "bench_speed_error.py", script)
    monkeypatch.setattr(sys, "argv", [str(script), *argv])
    with pytest.raises(SystemExit) as done:
        runpy.run_path(str(script), run_name="__main__")
    return done.value.code


@pytest.mark.parametrize(
    "how, extra, title",
    [
        ("flyopt bench", ["--sections", "geometry"], "# Speed against error"),
        ("flyopt bench", ["--hard"], "# Hard set"),
        ("benchmarks/bench_speed_error.py", ["--sections", "geometry"], "# Speed against error"),
    ],
)
def test_quick_run_leaves_the_committed_results_alone(tmp_path, monkeypatch, capsys, how, extra, title):
    """A --quick run without --output-dir prints its summary and writes no file, wherever it runs
    (it used to overwrite benchmarks/results of the working directory, or beside the script)."""
    before = _committed_results(tmp_path)
    monkeypatch.chdir(tmp_path)
    argv = ["--quick", "--no-pin", *extra]
    status = main(argv) if how == "flyopt bench" else _run_the_wrapper(tmp_path, argv, monkeypatch)
    assert status == 0
    after = {
        path: path.read_bytes()
        for path in tmp_path.rglob("*")
        if path.is_file() and path.name != "bench_speed_error.py"
    }
    assert after == before
    assert title in capsys.readouterr().out


def test_full_run_writes_into_benchmarks_results(tmp_path, monkeypatch, capsys):
    """Without --quick and --output-dir the run writes where the committed figures live."""
    monkeypatch.chdir(tmp_path)
    assert main(["--sections", "geometry", "--repeats", "1", "--scenes", "1", "--no-pin"]) == 0
    results = tmp_path / "benchmarks" / "results"
    assert sorted(p.name for p in results.iterdir()) == ["speed_error.csv", "speed_error.md", "speed_error.png"]
    assert (results / "speed_error.md").read_text(encoding="utf-8") in capsys.readouterr().out


def test_output_dir_that_is_a_file_is_refused(tmp_path, capsys):
    """Refused before anything runs, naming the option and the path; the file is left as it was."""
    target = tmp_path / "results"
    target.write_text("not a folder", encoding="utf-8")
    with pytest.raises(SystemExit) as err:
        main(["--quick", "--no-pin", "--output-dir", str(target)])
    assert err.value.code == 2
    message = capsys.readouterr().err.strip().splitlines()[-1]
    assert "--output-dir" in message and str(target) in message and "not a directory" in message
    assert target.read_text(encoding="utf-8") == "not a folder"


def test_bad_section_is_refused(capsys):
    with pytest.raises(SystemExit) as err:
        main(["--sections", "cycle,nonsense", "--no-pin"])
    assert err.value.code == 2
    assert "nonsense" in capsys.readouterr().err


@pytest.mark.slow  # 6 s: imports every module in a fresh process; the floors test holds the import graph by default
def test_nothing_in_flyopt_imports_the_bench():
    """The bench is a leaf: only the command line's dispatch (flyopt.cli) reaches it."""
    package = ROOT / "src" / "flyopt"
    importers = []
    for path in package.rglob("*.py"):
        if {"bench", "cli"} & set(path.relative_to(package).parts[:-1]):
            continue
        for node in ast.walk(parsed(path)):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [f"{node.module}.{a.name}" for a in node.names]
                if isinstance(node, ast.ImportFrom)
                else []
            )
            if any(n == "flyopt.bench" or n.startswith("flyopt.bench.") for n in names):
                importers.append(str(path.relative_to(package)))
    assert importers == []


# ------------------------------------------------------------------------------
# The bench's references and peers against closed forms
# ------------------------------------------------------------------------------


def test_sampled_rules_against_a_closed_form():
    """A_max of M = 1000 + 300 sin(2 phi) sampled finely: 2 * 300 / 2 = 300 J to 1e-6."""
    x = np.linspace(0.0, cycle.TWO_PI, 4001)
    y = 1000.0 + 300.0 * np.sin(2.0 * x)
    for rule in peers.SAMPLED_RULES:
        assert_allclose(peers.sampled_a_max(x, y, cycle.TWO_PI, 100_000, rule), 300.0, rtol=1e-5)


def test_exact_reference_on_a_spike():
    """Domain-style press: the deficit of the stroke is (peak - mean) x stroke, in rationals."""
    x, y = cycle.table_spike()
    stroke = Fraction(float(x[3])) - Fraction(float(x[1]))
    mean = (Fraction(100) * (Fraction(cycle.TWO_PI) - stroke) + Fraction(5000) * stroke) / Fraction(cycle.TWO_PI)
    assert references.exact_a_max_against_mean(x, y) == (Fraction(5000) - mean) * stroke


def test_rim_inertia_is_the_annulus_integral():
    """J = pi rho D_m H B (D_m^2 + H^2)/4 is the integral of r^2 dm over the annulus D_m +- H, B
    wide (R1^4 - R2^4 = (R1^2 - R2^2)(R1^2 + R2^2) = D_m H (D_m^2 + H^2)/2); to round-off."""
    for d_mean, h, b in ((1.0, 0.1, 0.07), (0.3, 0.29, 0.5), (2.5, 0.01, 0.02)):
        assert_allclose(
            references.rim_inertia("rim", 7200.0, d_mean, h, b),
            references.exact_annulus_inertia(d_mean + h, d_mean - h, b, 7200.0),
            rtol=1e-13,
        )


def test_largest_rim_inertia_bounds_the_root_search():
    """Just below the largest inertia a rim can give, the 1-D root search finds a design; just
    above, it reports the combination infeasible (a width limit makes the largest inertia finite)."""
    combo = references.Combination("rim", 7200.0, 1.0, 1.2, (1.5, 2.0), 0.05)
    j_max = references.largest_rim_inertia(combo)
    # the largest rim fills the cap at H = hb_max B_max = 0.1 m: D_m = 1.1 m, B = 0.05 m
    assert_allclose(j_max, math.pi * 7200.0 * 1.1 * 0.1 * 0.05 * (1.1**2 + 0.1**2) / 4.0, rtol=1e-14)
    inside = references.lightest_rim_1d(
        references.Combination("rim", 7200.0, j_max * (1 - 1e-4), 1.2, (1.5, 2.0), 0.05)
    )
    outside = references.lightest_rim_1d(
        references.Combination("rim", 7200.0, j_max * (1 + 1e-4), 1.2, (1.5, 2.0), 0.05)
    )
    assert inside.verdict == "design" and inside.violation <= 1e-12
    assert outside.verdict == "infeasible"


def test_baselines_agree_with_the_reference_on_one_combination():
    """SLSQP and a fine grid land on the 1-D reference mass of a plain combination."""
    combo = references.Combination("rim", 7200.0, 10.0, 1.2, (1.5, 2.0), math.inf)
    ref = references.lightest_rim_1d(combo)
    assert ref.verdict == "design" and ref.violation <= 1e-12
    for variables in ("scaled", "log"):
        got = peers.slsqp_combination(combo, variables)
        assert got.verdict == "design", got.reason
        assert_allclose(got.mass, ref.mass, rtol=1e-6)
    grid = peers.grid_combination(combo, 3000, 5)
    assert grid.verdict == "design" and grid.mass >= ref.mass * (1 - 1e-12)
    assert_allclose(grid.mass, ref.mass, rtol=2e-3)
