"""flyopt: optimization-based flywheel design.

Pipeline: load a scene → analyse its cycle → design the flywheel.

>>> import flyopt
>>> scene = flyopt.load("problems/shear-press.toml")   # doctest: +SKIP
>>> flyopt.analyse(scene).j_required                  # doctest: +SKIP
1.0183...
>>> flyopt.solve(scene).design.best.mass              # doctest: +SKIP
"""

from flyopt.analysis import Analysis, analyse
from flyopt.errors import ExpressionError, FlyoptError, NonPeriodicCycle, SceneError, SolverFailed
from flyopt.pipeline import Solution, design_scene, solve
from flyopt.io.scene import Scene, Shaft, from_dict, load
from flyopt.studies.fronts import material_tradeoff, pareto
from flyopt.studies.sweep import sweep  # the function; the module is flyopt.studies.sweep

__version__ = "0.1.0"

__all__ = ["Analysis", "ExpressionError", "FlyoptError", "NonPeriodicCycle", "Scene", "SceneError",
           "Shaft", "Solution", "SolverFailed", "analyse", "design_scene", "from_dict", "load", "material_tradeoff", "pareto",
           "solve", "sweep", "__version__"]
