"""Design: geometry, materials and the optimization that chooses the wheel.

The stage after the cycle analysis: from J_F and ω_max, choose material,
shaft and dimensions. One module per idea: :mod:`~flyopt.design.spec` (what a
design must satisfy), :mod:`~flyopt.design.inputs` (the one translation of a
scene), :mod:`~flyopt.design.geometry` and :mod:`~flyopt.design.materials`,
:mod:`~flyopt.design.closed_form` (exact optima, scalar and array forms side
by side), :mod:`~flyopt.design.nlp` (the CasADi/IPOPT model, imported only
when IPOPT is used), :mod:`~flyopt.design.check` (the one constraint check and
binding rule), :mod:`~flyopt.design.rank` (the one ranking rule),
:mod:`~flyopt.design.result` and :mod:`~flyopt.design.designer` (every
combination decided and ranked).
"""

from flyopt.design.designer import design_flywheel
from flyopt.design.inputs import DesignInputs, design_inputs
from flyopt.design.result import Candidate, Design, DesignResult, Dimensions, Limits, Parts, Provenance, Stresses
from flyopt.design.spec import OBJECTIVES, DesignSpec, MountShaft

__all__ = [
    "Candidate",
    "Design",
    "DesignInputs",
    "DesignResult",
    "DesignSpec",
    "Dimensions",
    "Limits",
    "MountShaft",
    "OBJECTIVES",
    "Parts",
    "Provenance",
    "Stresses",
    "design_flywheel",
    "design_inputs",
]
