"""flyopt's own invariants are checked by code that ``python -O`` keeps: no ``assert`` in src
(they raise flyopt.errors.BrokenInvariant), and nothing is built by exec or eval."""

import ast
from pathlib import Path

from sources import parsed

SRC = Path(__file__).resolve().parents[1] / "src" / "flyopt"


def test_no_assert_exec_or_eval_in_src():
    found = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Assert):
                found.append(f"{path.relative_to(SRC)}:{node.lineno}: assert")
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("exec", "eval"):
                found.append(f"{path.relative_to(SRC)}:{node.lineno}: {node.func.id}")
    assert found == [], found
