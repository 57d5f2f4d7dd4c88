"""The package's metadata: ``--version`` and ``__version__``, LICENSE, py.typed and the
annotations of the public API (issue 15, part 5).
"""

import dataclasses
import importlib.metadata
import inspect
import subprocess
import sys
from pathlib import Path

from conftest import ROOT

import flyopt

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib


# --------------------------------------------------------------------------
# Version, licence, typing
# --------------------------------------------------------------------------


def test_version_comes_from_the_package_metadata():
    run = subprocess.run([sys.executable, "-m", "flyopt", "--version"], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stderr == ""
    assert run.stdout == f"flyopt {importlib.metadata.version('flyopt')}\n"
    assert flyopt.__version__ == importlib.metadata.version("flyopt")


def test_version_is_fast_to_ask_for():
    """``flyopt --version`` builds the argparse tree and reads the metadata, nothing else: no numpy,
    pandas, CasADi; ``import flyopt`` does not even read the metadata."""
    code = (
        "import sys\nfrom flyopt.cli.main import main\n"
        "try:\n    main(['--version'])\nexcept SystemExit as stop:\n    assert stop.code in (0, None)\n"
        "print(sorted(m for m in ('numpy', 'pandas', 'casadi', 'scipy', 'pint', 'matplotlib') "
        "if m in sys.modules))\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[-1] == "[]"
    run = subprocess.run(
        [sys.executable, "-c", "import sys, flyopt; print('importlib.metadata' in sys.modules)"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.stdout.strip() == "False"


def test_an_uninstalled_source_tree_reads_its_pyproject(monkeypatch, tmp_path):
    def not_installed(name):
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "version", not_installed)
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert flyopt._version() == declared
    monkeypatch.setattr(flyopt, "__file__", str(tmp_path / "a" / "b" / "flyopt" / "__init__.py"))
    assert flyopt._version() == "unknown"  # no pyproject.toml above it


def test_the_licence_is_mit_and_pyproject_agrees():
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n") and "Copyright (c) 2026 the flyopt developers" in text
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"] == {"text": "MIT"}
    assert "License :: OSI Approved :: MIT License" in project["classifiers"]


def test_the_public_api_is_typed():
    """py.typed marks the package as typed (PEP 561); every public function annotates every
    parameter and its return."""
    assert (Path(flyopt.__file__).parent / "py.typed").is_file()
    functions = [getattr(flyopt, name) for name in flyopt.__all__ if inspect.isfunction(getattr(flyopt, name))]
    assert len(functions) >= 7
    for function in functions:
        signature = inspect.signature(function)
        missing = [p for p, v in signature.parameters.items() if v.annotation is inspect.Parameter.empty]
        assert not missing, (function.__qualname__, missing)
        assert signature.return_annotation is not inspect.Signature.empty, function.__qualname__
    for name in ("Scene", "Shaft", "Solution", "Analysis"):
        assert dataclasses.is_dataclass(getattr(flyopt, name))


def test_the_readmes_notebook_instruction_installs_jupyterlab():
    """The README's way to open the notebooks names an extra that brings JupyterLab and a kernel (issue 29:
    `jupyter lab notebooks/` failed from a fresh clone, no extra installed jupyterlab)."""
    import re

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    found = re.search(r'pip install -e "\.\[(\w+)\]" && \.venv/bin/jupyter lab notebooks/', readme)
    assert found, "the README no longer says how to open the notebooks"
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    names = {re.split(r"[<>=!~\[; ]", dep, maxsplit=1)[0].lower() for dep in extras[found.group(1)]}
    assert {"jupyterlab", "ipykernel"} <= names
