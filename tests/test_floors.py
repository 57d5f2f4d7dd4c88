"""Stages as floors: a module imports only from its own floor or below.

The order is written here, once; docs/architecture.md draws it and a test
below checks that the drawing lists the same floors in the same order.

Every import statement counts, at module level or inside a function (flyopt
imports heavy modules where they are used), except those under
``if TYPE_CHECKING:``: an annotation may name a type from any floor, since it
never runs. ``flyopt`` itself (the package's ``__init__``) is on the bottom
floor: it imports nothing, and its public names are resolved by name on first
use.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from sources import parsed

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "flyopt"
ARCHITECTURE = Path(__file__).resolve().parents[1] / "docs" / "architecture.md"

#: Bottom to top: (floor, the modules and packages on it). A module belongs to the
#: floor of the longest prefix that names it.
FLOORS = (
    (
        "base",
        (
            "flyopt",
            "flyopt.errors",
            "flyopt.units",
            "flyopt.names",
            "flyopt.said",
            "flyopt.validate",
            "flyopt._toml",
            "flyopt.views",
        ),
    ),
    ("cycle", ("flyopt.cycle",)),
    ("machine", ("flyopt.machine",)),
    ("sizing", ("flyopt.sizing",)),
    ("analysis", ("flyopt.analysis", "flyopt.delta_curve")),
    ("design", ("flyopt.design",)),
    ("drive", ("flyopt.drive",)),
    ("pipeline", ("flyopt.pipeline",)),
    ("input and output rings", ("flyopt.io", "flyopt.outputs")),
    ("studies", ("flyopt.studies",)),
    ("report", ("flyopt.report",)),
    ("bench", ("flyopt.bench",)),
    ("cli", ("flyopt.cli", "flyopt.__main__", "flyopt.app")),
)


def floor_of(module):
    """Index of the floor a dotted module name belongs to (longest prefix)."""
    best, level = -1, None
    for index, (_, prefixes) in enumerate(FLOORS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best:
                best, level = len(prefix), index
    if level is None:
        raise LookupError(f"{module} is on no floor: add it to FLOORS in {Path(__file__).name}")
    return level


def module_name(path):
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _type_checking_only(node):
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def imported_modules(path):
    """(line, module) of every flyopt import in a file, function-level ones included."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []

    def visit(node):
        if isinstance(node, ast.If) and _type_checking_only(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            for alias in node.names:
                candidate = f"{target}.{alias.name}"
                # "from flyopt.cycle import indicator" imports the module flyopt.cycle.indicator
                is_module = (SRC / Path(*candidate.split("."))).with_suffix(".py").exists() or (
                    SRC / Path(*candidate.split("."))
                ).is_dir()
                found.append((node.lineno, candidate if is_module else target))
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(parsed(path))
    return [(line, module) for line, module in found if module == "flyopt" or module.startswith("flyopt.")]


SOURCES = sorted(PACKAGE.rglob("*.py"))


def test_every_module_is_on_a_floor():
    for path in SOURCES:
        floor_of(module_name(path))


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_import_runs_up(path):
    here = floor_of(module_name(path))
    upward = [
        f"{path.relative_to(SRC)}:{line} imports {module} ({FLOORS[floor_of(module)][0]}, above {FLOORS[here][0]})"
        for line, module in imported_modules(path)
        if floor_of(module) > here
    ]
    assert not upward, "\n".join(upward)


def test_an_upward_import_is_caught(tmp_path, monkeypatch):
    """The checker itself can fail: a function-level import from a higher floor is reported."""
    fake = SRC / "flyopt" / "cycle" / "_floors_probe.py"
    source = "def f():\n    from flyopt.design.materials import material_library\n    return material_library\n"
    monkeypatch.setattr(Path, "read_text", lambda self, encoding=None: source)
    [(line, module)] = imported_modules(fake)
    assert (line, module) == (2, "flyopt.design.materials")
    assert floor_of(module) > floor_of("flyopt.cycle._floors_probe")


def test_type_checking_imports_do_not_count(monkeypatch):
    fake = SRC / "flyopt" / "cycle" / "_floors_probe.py"
    source = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from flyopt.io.scene import Scene\n"
    monkeypatch.setattr(Path, "read_text", lambda self, encoding=None: source)
    assert imported_modules(fake) == []


def test_the_architecture_document_draws_these_floors():
    """docs/architecture.md lists the floors, top to bottom, in its table of floors."""
    text = ARCHITECTURE.read_text(encoding="utf-8")
    drawn = re.findall(r"^\| (\d+) \| ([^|]+?) \|", text, flags=re.M)
    assert [(int(n), name.strip()) for n, name in drawn] == [
        (index, name) for index, (name, _) in reversed(list(enumerate(FLOORS)))
    ]
