"""The notebooks use only flyopt's public API (issue 15: "use only the public API").

Every code cell is parsed; an import from flyopt must name a module whose path
has no part starting with "_" and a name that does not start with "_", and no
attribute of a flyopt object reached in the code may start with "_" (``__``
dunders aside).
"""

import ast
import json
from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb"))


def _code(path):
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    return "\n".join(
        "".join(c["source"])
        for c in cells
        if c["cell_type"] == "code" and not "".join(c["source"]).lstrip().startswith(("%", "!"))
    )


def _private_names(source):
    tree = ast.parse(source)
    private = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "flyopt":
            if any(part.startswith("_") for part in node.module.split(".")):
                private.append(f"from {node.module}")
            private += [f"{node.module}.{a.name}" for a in node.names if a.name.startswith("_")]
        elif isinstance(node, ast.Import):
            private += [
                a.name
                for a in node.names
                if a.name.split(".")[0] == "flyopt" and any(part.startswith("_") for part in a.name.split("."))
            ]
        elif isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
            private.append(f".{node.attr}")
    return private


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_a_notebook_uses_the_public_api_only(path):
    private = _private_names(_code(path))
    assert not private, f"{path.name} reaches private names: {private}"


def test_the_scan_catches_a_private_call():
    """The check above can fail: private modules, names and attributes are each caught; public ones are not."""
    assert _private_names(
        "from flyopt.design.materials import _load_builtin\nfrom flyopt.sizing._numerics import quiet\n"
        "x = scene._lazy\nimport flyopt.sizing._numerics\n"
    ) == ["flyopt.design.materials._load_builtin", "from flyopt.sizing._numerics", "flyopt.sizing._numerics", "._lazy"]
    assert _private_names("import flyopt\nfrom flyopt.report import display\nx = scene.__class__\n") == []
