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

Each public name is imported on first use (as :mod:`flyopt`'s own): the scene loader reads the material
library, castability rules and spec of this package, and ``flyopt check`` needs no designer.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from flyopt._lazy import first_use

if TYPE_CHECKING:  # the real types, for type checkers and editors; at run time each is imported on first use
    from flyopt.design.designer import design_flywheel as design_flywheel
    from flyopt.design.inputs import DesignInputs as DesignInputs
    from flyopt.design.inputs import design_inputs as design_inputs
    from flyopt.design.result import Candidate as Candidate
    from flyopt.design.result import Design as Design
    from flyopt.design.result import DesignResult as DesignResult
    from flyopt.design.result import Dimensions as Dimensions
    from flyopt.design.result import Limits as Limits
    from flyopt.design.result import Parts as Parts
    from flyopt.design.result import Provenance as Provenance
    from flyopt.design.result import Stresses as Stresses
    from flyopt.design.spec import OBJECTIVES as OBJECTIVES
    from flyopt.design.spec import DesignSpec as DesignSpec
    from flyopt.design.spec import MountShaft as MountShaft

#: The public names and the module each lives in.
_API = {
    "design_flywheel": "flyopt.design.designer",
    "DesignInputs": "flyopt.design.inputs",
    "design_inputs": "flyopt.design.inputs",
    **dict.fromkeys(
        ("Candidate", "Design", "DesignResult", "Dimensions", "Limits", "Parts", "Provenance", "Stresses"),
        "flyopt.design.result",
    ),
    **dict.fromkeys(("OBJECTIVES", "DesignSpec", "MountShaft"), "flyopt.design.spec"),
}

__all__ = sorted(_API)


__getattr__ = first_use("flyopt.design", _API, globals())
