"""flyopt's source files parsed once per test process: the static checks (floors, imports, annotations,
no assert) each walk every module, and parsing them all takes ~1-2 s."""

from __future__ import annotations

import ast
import functools
from pathlib import Path


def parsed(path: Path) -> ast.Module:
    """The syntax tree of one source file (read as UTF-8 each time; parsed once per distinct text, so a test
    that fakes a file's text gets its own tree). Callers must not change the tree."""
    return _parse(Path(path).read_text(encoding="utf-8"))


@functools.cache
def _parse(text: str) -> ast.Module:
    return ast.parse(text)
