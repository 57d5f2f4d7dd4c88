"""flyopt: optimization-based flywheel design.

Pipeline: load a scene → analyse its cycle → design the flywheel.

>>> import flyopt
>>> scene = flyopt.load("problems/shear-press.toml")   # doctest: +SKIP
>>> flyopt.analyse(scene).j_required                  # doctest: +SKIP
1.0183...
>>> flyopt.solve(scene).design.best.mass              # doctest: +SKIP
"""

from .analysis import Analysis, analyse
from .errors import ExpressionError, FlyoptError, NonPeriodicCycle, SceneError, SolverFailed
from .pipeline import Solution, design, solve
from .scene import Scene, Shaft, from_dict, load
from .studies import material_tradeoff, pareto
from .sweep import sweep  # noqa: E402  (the function; the module stays importable as flyopt.sweep)

__version__ = "0.1.0"

__all__ = ["Analysis", "ExpressionError", "FlyoptError", "NonPeriodicCycle", "Scene", "SceneError",
           "Shaft", "Solution", "SolverFailed", "analyse", "design", "from_dict", "load", "material_tradeoff", "pareto",
           "solve", "sweep", "__version__"]
