"""Start-up: a command imports only what it uses (issue 12).

``flyopt check`` and ``flyopt solve`` on a constant-inertia scene, designed by
the closed form, need neither the studies (pandas, pyarrow), nor pint (the
built-in unit table reads the scene), nor CasADi and scipy.optimize (no model
that needs them runs), nor matplotlib. Each command runs in a fresh
interpreter through ``flyopt.cli.main.main``; what it imported is read from
``sys.modules`` at the end, with the module that first imported each one.
No timing is asserted here (benchmarks measure it).
"""

import json
import subprocess
import sys

import pytest
from conftest import PROBLEMS

DRIVER = """
import builtins, contextlib, io, json, sys
watched = {watched!r}
first = {{}}
real_import = builtins.__import__

def watching_import(name, globals=None, locals=None, fromlist=(), level=0):
    before = {{m for m in watched if m in sys.modules}}
    module = real_import(name, globals, locals, fromlist, level)
    for m in watched:
        if m not in before and m in sys.modules and m not in first:
            first[m] = (globals or {{}}).get("__name__", "?")
    return module

builtins.__import__ = watching_import
{setup}
print(json.dumps(first))
"""

STUDIES_AND_PLOTS = ("pandas", "pyarrow", "pint", "matplotlib")
SOLVERS = ("casadi", "scipy.optimize")


def imported(setup, watched=STUDIES_AND_PLOTS + SOLVERS + ("scipy",)):
    """{module: the module that imported it first} for the watched modules a piece of code imports."""
    code = DRIVER.format(watched=tuple(watched), setup=setup)
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


def command(*args):
    """Run ``flyopt ARGS`` through ``main`` with stdout captured; it must succeed."""
    return (
        "from flyopt.cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    status = main({list(map(str, args))!r})\n"
        "assert status == 0, status\n"
    )


def test_the_command_line_parser_imports_nothing_heavy():
    """Building the argparse tree (every subcommand's options) imports no study, solver, units or plots."""
    found = imported("from flyopt.cli.main import _parser\n_parser().parse_args(['check', 'x.toml'])\n")
    assert found == {}, found


SCENES = ["shear-press.toml", "punch-press.toml", "four-stroke-engine-csv.toml"]


@pytest.mark.parametrize("verb", ["check", "solve"])
@pytest.mark.parametrize("scene", SCENES)
def test_a_constant_inertia_command_imports_no_study_units_or_plots(verb, scene):
    found = imported(command(verb, PROBLEMS / scene))
    assert not {m: found[m] for m in STUDIES_AND_PLOTS if m in found}, found


@pytest.mark.parametrize("verb", ["check", "solve"])
def test_a_constant_inertia_closed_form_solve_imports_no_solver(verb):
    found = imported(command(verb, PROBLEMS / "shear-press.toml"))
    assert not {m: found[m] for m in SOLVERS if m in found}, found


def test_the_watch_sees_an_import():
    """The driver does report a heavy import: a sweep imports pandas (a test that could not fail is none)."""
    found = imported("import flyopt.studies.sweep\n", watched=("pandas",))
    assert "pandas" in found


def test_a_dynamic_solve_that_needs_no_root_search_imports_no_scipy_optimize():
    """The one-solve of the variable-inertia press (CasADi) never needs scipy.optimize (~0.3 s to import):
    periodic.py and startup.py import it only where Brent's method or a bounded minimum is called."""
    found = imported(command("solve", PROBLEMS / "slider-crank-press.toml"))
    assert "casadi" in found and "scipy.optimize" not in found, found


@pytest.mark.parametrize(
    "args",
    [
        ("solve", "slider-crank-press.toml", "--verify"),  # the verification's root searches (the ported Brent)
        ("solve", "motor-press.toml"),  # a motor: the start-up and the speed balance
        ("solve", "compressor.toml", "--verify"),  # expression torques: the crossings refined by Brent
    ],
)
def test_no_solve_imports_scipy_optimize(args):
    """Brent's root and the bounded minimum are scipy's, ported operation for operation (flyopt.cycle.numerics.brentq,
    flyopt.cycle.minimize.bounded_minimum, tested bit for bit against scipy): no solve pays ~0.3 s to import it."""
    verb, scene, *rest = args
    found = imported(command(verb, PROBLEMS / scene, *rest))
    assert "scipy.optimize" not in found, found


SHAFT_CHECKS = ("flyopt.design.shaft.check", "flyopt.design.shaft.diameter", "flyopt.machine.torsion")


@pytest.mark.parametrize("scene", ["punch-press.toml", "shear-press.toml"])
def test_a_scene_without_a_described_shaft_imports_no_shaft_check(scene):
    """Every design imported the seat search and with it the shaft checks (beam, lateral and torsional models,
    the drive train: ten modules) to learn that no shaft is described."""
    found = imported(command("solve", PROBLEMS / scene), watched=SHAFT_CHECKS)
    assert found == {}, found


def test_a_described_shaft_imports_its_checks():
    """The watch sees them where they are used (a test that could not fail is none)."""
    found = imported(command("solve", PROBLEMS / "punch-press-shaft.toml"), watched=SHAFT_CHECKS)
    assert set(found) == set(SHAFT_CHECKS), found


def test_a_report_without_a_described_shaft_imports_no_shaft_check(tmp_path):
    """The report's shaft section imported the checks for the name of a JSON field (ten modules, some 60 ms)."""
    found = imported(
        command("report", PROBLEMS / "slider-crank-press.toml", "-o", tmp_path / "r.html"), watched=SHAFT_CHECKS
    )
    assert found == {}, found
