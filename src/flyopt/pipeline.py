"""The thin place where flyopt's pieces meet.

load scene → analyse the cycle → design the flywheel → report. Each step
lives in its own module; this one only joins them (the pvlib ModelChain /
PyBaMM Simulation pattern).
"""

from dataclasses import dataclass

from .analysis import Analysis, analyse


@dataclass(frozen=True)
class Solution:
    """A scene analysed and (unless asked not to) its flywheel designed.

    Attributes
    ----------
    scene : Scene
    analysis : Analysis
    design : DesignResult or None
        None when the design step was skipped.
    """

    scene: object
    analysis: Analysis
    design: object = None

    @property
    def status(self):
        """"designed", "not_needed", "infeasible", or "analysed" (design skipped)."""
        return self.design.status if self.design is not None else "analysed"

    def to_dict(self):
        """The JSON of ``flyopt solve``: the analysis fields plus a "design" object."""
        out = self.analysis.to_dict()
        if self.design is not None:
            out["design"] = design_dict(self.design)
        return out


def design_dict(result):
    """The "design" object: the winner's fields, its ranking, status and model."""
    raw = result.to_dict()
    design = raw["design"] or {"candidates": []}
    return {"status": raw["status"], "message": raw["message"], **design, "model": raw["model"]}


def design(scene, analysis, solver_options=None):
    """Design the flywheel a scene needs, from its analysis.

    Parameters
    ----------
    scene : Scene
        Supplies the design options, materials and shafts.
    analysis : Analysis
        Supplies J_F at the reference shaft (``j_margin``: zero or negative
        means no flywheel is needed).
    solver_options : mapping, optional
        CasADi/IPOPT options that override flyopt's defaults.

    Returns
    -------
    DesignResult

    Raises
    ------
    SolverFailed
        IPOPT did not converge on a combination that can be feasible.
    """
    from .optimize import MountShaft, design_flywheel

    library = scene.material_library()
    materials = [library[name] for name in (scene.design_materials or tuple(library))]
    allowed = scene.design_shafts
    shafts = [MountShaft(s.name, s.speed_ratio) for s in scene.shafts if allowed is None or s.name in allowed]
    return design_flywheel(analysis.j_margin, scene.omega_mean, shafts, materials, scene.design,
                           solver_options=solver_options)


def solve(scene, design_flywheel=True, solver_options=None):
    """Analyse a scene and design its flywheel.

    Parameters
    ----------
    scene : Scene
    design_flywheel : bool
        False stops after the cycle analysis.
    solver_options : mapping, optional
        CasADi/IPOPT options for the design NLPs.

    Returns
    -------
    Solution
    """
    analysis = analyse(scene)
    result = design(scene, analysis, solver_options) if design_flywheel else None
    return Solution(scene=scene, analysis=analysis, design=result)
