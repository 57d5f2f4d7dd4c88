"""What ``flyopt report`` imports (issue 26): a report pays only for what its scene uses.

The report of slider-crank-press (a rigid machine, no torsional chain) imported all of
scipy.linalg through :mod:`flyopt.machine.torsion` (about 0.2 s of a 2.6 s report), for modes
and responses it never solves; the module imports it where it solves them. The import is
watched in a fresh interpreter by the start-up tests' driver (:mod:`test_startup_imports`);
no time is asserted (benchmarks/bench_report.py measures it).
"""

from conftest import PROBLEMS
from test_startup_imports import command, imported


def test_the_report_of_a_machine_without_a_torsional_chain_imports_no_scipy(tmp_path):
    found = imported(command("report", PROBLEMS / "slider-crank-press.toml", "-o", tmp_path / "report.html"))
    assert "matplotlib" in found, found  # the watch sees the report's own heavy import: it could fail
    assert "scipy" not in found, found
    assert "pandas" not in found, found  # drawing its figures on every CPU asks how many without the sweeps' module
