"""flyopt: optimization-based flywheel design.

Pipeline: load a scene → analyse its cycle → design the flywheel.

>>> import flyopt
>>> scene = flyopt.load("problems/shear-press.toml")   # doctest: +SKIP
>>> flyopt.analyse(scene).j_required                  # doctest: +SKIP
1.0183...
>>> flyopt.solve(scene).design.best.mass              # doctest: +SKIP
"""

import importlib

__version__ = "0.1.0"

#: The public API and the module each name lives in. Imported on first use, so that
#: ``import flyopt`` costs nothing: pandas and pyarrow come with the studies, CasADi with
#: a model that needs it (the periodic solution, IPOPT), scipy.optimize where it is used.
_API = {
    "Analysis": "flyopt.analysis", "analyse": "flyopt.analysis",
    "ExpressionError": "flyopt.errors", "FlyoptError": "flyopt.errors", "NonPeriodicCycle": "flyopt.errors",
    "SceneError": "flyopt.errors", "SolverFailed": "flyopt.errors", "Interrupted": "flyopt.errors",
    "Solution": "flyopt.pipeline", "design_scene": "flyopt.pipeline", "solve": "flyopt.pipeline",
    "Scene": "flyopt.io.scene", "Shaft": "flyopt.io.scene", "from_dict": "flyopt.io.scene", "load": "flyopt.io.scene",
    "material_tradeoff": "flyopt.studies.tradeoff", "pareto": "flyopt.studies.pareto",
    "sweep": "flyopt.studies.sweep",   # the function; the module is flyopt.studies.sweep
}

__all__ = sorted(_API) + ["__version__"]


def __getattr__(name):
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'flyopt' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__():
    return __all__
