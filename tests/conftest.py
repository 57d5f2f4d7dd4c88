"""Shared test helpers."""

import functools
import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"


@pytest.fixture(autouse=True)
def figures_drawn_in_the_tests_process(monkeypatch):
    """Under pytest-xdist every worker already keeps a CPU busy: a report's figures are drawn in the test's own
    process (:func:`flyopt.report.figure_cores.workers_for` gives none), where forking figure workers beside
    the busy ones cost the report tests some 15 % more CPU and no time. The figures are the same either way;
    tests/report/test_figure_cores.py draws them by workers and here and compares, and overrides this
    fixture to test the rule itself."""
    if os.environ.get("PYTEST_XDIST_WORKER"):
        from flyopt.report import figure_cores

        monkeypatch.setattr(figure_cores, "workers_for", lambda count: 0)


@pytest.fixture
def close_figures():
    """Closes every matplotlib figure after the test. The app keeps its last answer's figures open for its
    downloads; a test's must not outlive it, or the worker's next tests see matplotlib's "more than 20 figures"
    warning (an error under the test settings). The app's test modules use it for every test (``pytestmark``)."""
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.fixture
def workspace():
    """An app workspace (:class:`flyopt.app.model.Workspace`, the ``app`` extra), closed after the test."""
    from flyopt.app import model

    space = model.Workspace()
    yield space
    space.close()


@pytest.fixture
def main_cli(capsys):
    """flyopt's command line in this process: call(*args) -> (exit status, stdout, stderr)."""
    from flyopt.cli.main import main

    def call(*args):
        status = main([str(a) for a in args])
        out, err = capsys.readouterr()
        return status, out, err

    return call


@functools.cache
def unit_registry():
    """pint's unit registry, the tests' independent reference for unit factors: built when first asked for,
    once per process (it takes a second, which every worker paid at collection when modules built their own)."""
    import pint

    return pint.UnitRegistry()


def run_flyopt(*args, cwd=None):
    """``flyopt ARGS`` in this process, as ``subprocess.run(..., capture_output=True, text=True)`` returns it.

    The same entry point, exit statuses and streams as ``python -m flyopt`` without the second of
    imports a new interpreter pays for each (about a third of the default run's CPU went to them).
    A process stays where a test is about the process itself: the console script, pipes, signals,
    start-up imports, a read that could hang or exhaust memory. An error the CLI does not turn into
    an exit status propagates here with its traceback, which fails the test as the traceback on a
    process's stderr did.
    """
    import contextlib
    import io
    import subprocess

    from flyopt.cli.main import main

    argv = [str(a) for a in args]
    out = io.TextIOWrapper(io.BytesIO(), encoding="utf-8")
    err = io.TextIOWrapper(io.BytesIO(), encoding="utf-8")
    with contextlib.ExitStack() as stack:
        if cwd is not None:
            stack.enter_context(contextlib.chdir(cwd))
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        try:
            status = main(argv)
        except SystemExit as exit_:  # argparse: --help, --version, a bad option
            status = exit_.code if isinstance(exit_.code, int) else (0 if exit_.code is None else 1)
    text = []
    for stream in (out, err):
        stream.flush()
        text.append(stream.buffer.getvalue().decode("utf-8"))
    return subprocess.CompletedProcess(["flyopt", *argv], status, text[0], text[1])


@pytest.fixture
def write_scene(tmp_path):
    """Write a scene text to a file and return its path."""

    def write(text, name="scene.toml"):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


def assert_published(actual, published):
    """Check a computed value against a figure as printed in a source.

    ``published`` is the printed text, e.g. "0.8223" or "72.65": the value
    must round to it, i.e. lie within half a unit of its last printed digit.
    """
    from decimal import Decimal

    figure = Decimal(published)
    half_unit = Decimal(1).scaleb(figure.as_tuple().exponent) / 2
    assert abs(Decimal(repr(float(actual))) - figure) <= half_unit, (
        f"{actual!r} does not round to the published {published} (±{half_unit})"
    )


def unplaced(text, path):
    """``text`` with the line a refusal places after the scene file's name taken out (``FILE:12: field`` becomes
    ``FILE: field``): for a test of the field and the words, where the line is not what it tests."""
    import re

    return re.sub(rf"({re.escape(str(path))}):\d+:", r"\1:", text)


def names_field(line, path, field):
    """Whether a refusal's line names the scene file and the field: ``flyopt: error: FILE:LINE: field: ...``
    as every command says it (``FILE:`` alone for a field the file does not write), or ``FILE:LINE: field: ...``
    as ``flyopt check`` lists it."""
    import re

    return re.match(rf"(flyopt: error: )?{re.escape(str(path))}(:\d+)?: {re.escape(field)}: ", line) is not None


#: Tests repeated over every problem scene (each a report, a page or a subprocess): the default run keeps them on
#: these scenes, which between them hold every kind of model and wheel (the energy, energy–mass and dynamic models;
#: a textbook rim, a web wheel, an arms wheel, a disc on its hub; a drive); the slow run takes every scene.
REPRESENTATIVE_SCENES = (
    "slider-crank-press",
    "punch-press-wheel",
    "press-arms-wheel",
    "four-cylinder-engine",
    "press-drive",
)
EVERY_SCENE_TESTS = frozenset(
    {
        "test_the_report_solves_once",
        "test_every_diagram_from_one_solve",
        "test_every_problem_scene_renders_a_whole_self_contained_page",
        "test_every_problem_scene_validates",
        "test_every_problem_scene_solves_with_a_checked_status",
    }
)


#: The notebooks nbmake runs in the default run (the others, longer, in the slow run).
DEFAULT_NOTEBOOKS = ("02-material-trade-off.ipynb",)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Mark the every-scene tests slow on scenes outside :data:`REPRESENTATIVE_SCENES`, and the notebooks but
    :data:`DEFAULT_NOTEBOOKS` (before ``-m`` selects)."""
    for item in items:
        if item.name.endswith(".ipynb") and item.name not in DEFAULT_NOTEBOOKS:
            item.add_marker(pytest.mark.slow)
        if getattr(item, "originalname", None) in EVERY_SCENE_TESTS and hasattr(item, "callspec"):
            # the scene by its whole name: "press-drive" is not motor-press-drive-train, nor "four-cylinder-engine"
            # four-cylinder-engine-shaft (a substring of the test's id took them in too)
            scenes = {getattr(v, "stem", v) for v in item.callspec.params.values() if isinstance(v, (str, Path))}
            if not scenes & set(REPRESENTATIVE_SCENES):
                item.add_marker(pytest.mark.slow)
