"""flyopt: optimization-based flywheel design.

Pipeline: load a scene → analyse its cycle → design the flywheel.

>>> import flyopt
>>> scene = flyopt.load("problems/shear-press.toml")   # doctest: +SKIP
>>> flyopt.analyse(scene).j_required                  # doctest: +SKIP
1.0183...
>>> flyopt.solve(scene).design.best.mass              # doctest: +SKIP
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from flyopt._lazy import first_use

if TYPE_CHECKING:  # the real types, for type checkers and editors (``X as X``: re-exported);
    # at run time each name is imported on first use, by __getattr__
    from flyopt.analysis import Analysis as Analysis
    from flyopt.analysis import analyse as analyse
    from flyopt.errors import ExpressionError as ExpressionError
    from flyopt.errors import FlyoptError as FlyoptError
    from flyopt.errors import Interrupted as Interrupted
    from flyopt.errors import NonPeriodicCycle as NonPeriodicCycle
    from flyopt.errors import SceneError as SceneError
    from flyopt.errors import SolverFailed as SolverFailed
    from flyopt.io.scene import Scene as Scene
    from flyopt.io.scene import from_dict as from_dict
    from flyopt.io.scene import load as load
    from flyopt.machine.transmission import Shaft as Shaft
    from flyopt.pipeline import Solution as Solution
    from flyopt.pipeline import design_scene as design_scene
    from flyopt.pipeline import solve as solve
    from flyopt.report.notebook import read_results as read_results
    from flyopt.report.notebook import to_units as to_units
    from flyopt.studies.pareto import pareto as pareto
    from flyopt.studies.sweep import sweep as sweep
    from flyopt.studies.tradeoff import material_tradeoff as material_tradeoff

    __version__: str

#: The public API and the module each name lives in. Imported on first use, so that
#: ``import flyopt`` costs nothing: pandas and pyarrow come with the studies, CasADi with
#: a model that needs it (the periodic solution, IPOPT), scipy.optimize where it is used.
_API: dict[str, str] = {
    "Analysis": "flyopt.analysis",
    "analyse": "flyopt.analysis",
    "ExpressionError": "flyopt.errors",
    "FlyoptError": "flyopt.errors",
    "NonPeriodicCycle": "flyopt.errors",
    "SceneError": "flyopt.errors",
    "SolverFailed": "flyopt.errors",
    "Interrupted": "flyopt.errors",
    "Solution": "flyopt.pipeline",
    "design_scene": "flyopt.pipeline",
    "solve": "flyopt.pipeline",
    "Scene": "flyopt.io.scene",
    "Shaft": "flyopt.machine.transmission",
    "from_dict": "flyopt.io.scene",
    "load": "flyopt.io.scene",
    "material_tradeoff": "flyopt.studies.tradeoff",
    "pareto": "flyopt.studies.pareto",
    "sweep": "flyopt.studies.sweep",  # the function; the module is flyopt.studies.sweep
    "read_results": "flyopt.report.notebook",  # a table file back, in SI or the user's units
    "to_units": "flyopt.report.notebook",
}

#: The modules that register how results are shown (:mod:`flyopt.views`: a notebook's HTML,
#: ``to_frame``), imported by :func:`_load_views` when a result is first shown.
_VIEW_MODULES = ("flyopt.report.notebook",)

__all__ = sorted(_API) + ["__version__"]


_first_use = first_use("flyopt", _API, globals())


def __getattr__(name: str) -> Any:
    if name == "__version__":
        globals()[name] = _version()
        return globals()[name]
    return _first_use(name)


def _load_views() -> None:
    """Import the modules of :data:`_VIEW_MODULES`, which register their views in :mod:`flyopt.views`."""
    for module in _VIEW_MODULES:
        importlib.import_module(module)


def _version() -> str:
    """The version of flyopt: the installed distribution's metadata, the one source.

    Read on first use of ``flyopt.__version__`` (importing importlib.metadata
    costs some 30 ms, which ``import flyopt`` does not pay). A source tree
    that is not installed has no metadata: its pyproject.toml says the
    version, and without one (or without a TOML reader) it is "unknown".
    """
    from importlib import metadata

    try:
        return metadata.version("flyopt")
    except metadata.PackageNotFoundError:
        pass
    from pathlib import Path

    try:
        from flyopt._toml import tomllib  # ImportError: Python 3.10 without tomli

        project = tomllib.loads(
            (Path(__file__).resolve().parents[2] / "pyproject.toml").read_text(encoding="utf-8")
        ).get("project", {})
    except (ImportError, OSError, ValueError):
        return "unknown"
    version = project.get("version")
    return version if project.get("name") == "flyopt" and isinstance(version, str) else "unknown"


def __dir__() -> list[str]:
    return __all__
