"""A package's public names imported on first use: the one way :mod:`flyopt` and :mod:`flyopt.design` do it."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def first_use(package: str, api: Mapping[str, str], namespace: dict[str, Any]) -> Callable[[str], Any]:
    """A module ``__getattr__`` that imports ``name`` from the module ``api`` says it lives in, and keeps it in
    the package's ``namespace`` (its ``globals()``), so that the next use finds it there.

    Raises
    ------
    AttributeError
        ``name`` is not in ``api`` (as Python says it of any module).
    """

    def attribute(name: str) -> Any:
        module = api.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    return attribute
