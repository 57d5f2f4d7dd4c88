"""How a result is shown to people: a registry the result classes consult, filled from above.

The result classes stand on low floors (``Solution`` on the pipeline's,
``DesignResult`` on the design's), but what they look like in a notebook is
decided on the report's floor: the text report's answer
(:func:`flyopt.report.text.answer_report`), the units of the reader's choice
(:mod:`flyopt.report.display`), the SI unit of every column
(:mod:`flyopt.outputs.quantities`). A low floor may not import those, not
even inside a function (tests/test_floors.py). So the dependency is
inverted: a result's ``_repr_html_`` or ``to_frame`` asks this registry for
the view of its kind, and the module that draws it (on its own floor)
registers it here.

Who registers is named once, by the package's composition root:
``flyopt._VIEW_MODULES`` (``flyopt/__init__.py``, which already names the
module of every public name). The first view asked for imports them, so a
result shows itself whether it came from ``flyopt.solve`` or from
``flyopt.pipeline.solve``, and ``import flyopt`` stays as light as before.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["register", "view"]

#: (kind, view) -> the function drawing it: ``function(result, *args, **kwargs)``.
_VIEWS: dict[tuple[str, str], Callable[..., Any]] = {}


def register(kind: str, name: str, function: Callable[..., Any]) -> None:
    """Register ``function`` as the view ``name`` (``"html"``, ``"frame"``) of results of ``kind``.

    Parameters
    ----------
    kind : str
        The result's kind: ``"solution"``, ``"design"``.
    name : str
        The view: ``"html"`` (a notebook's ``_repr_html_``), ``"frame"`` (``to_frame``).
    function : callable
        ``function(result, *args, **kwargs)``, the view of one result.
    """
    _VIEWS[(kind, name)] = function


def view(kind: str, name: str, result: object, *args: Any, **kwargs: Any) -> Any:
    """The view ``name`` of ``result`` (a result of ``kind``), by the function registered for it.

    Raises
    ------
    LookupError
        No module of ``flyopt._VIEW_MODULES`` registers that view.
    """
    function = _VIEWS.get((kind, name))
    if function is None:
        import flyopt

        flyopt._load_views()
        function = _VIEWS.get((kind, name))
    if function is None:
        raise LookupError(f"no view {name!r} of a {kind} result is registered (flyopt._VIEW_MODULES)")
    return function(result, *args, **kwargs)
