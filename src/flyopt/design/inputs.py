"""The one translation from a scene to what the designer needs.

``flyopt solve``, the sweep, the Pareto fronts and the material trade-off all
take the materials, the mounting shafts and the design specification of a
scene from :func:`design_inputs`, so a scene means the same design problem
wherever it is used. A sweep point is first made a scene of its own
(:func:`flyopt.studies.points.point_scene`), or, vectorized, its columns
override exactly these defaults.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from flyopt.design.spec import DesignSpec, MountShaft

if TYPE_CHECKING:  # annotations only
    from flyopt.design.materials import Material
    from flyopt.io.scene import Scene

__all__ = ["DesignInputs", "design_inputs"]


@dataclass(frozen=True)
class DesignInputs:
    """The design problem of a scene, apart from the inertia and the speed.

    Attributes
    ----------
    materials : tuple of flyopt.design.materials.Material
        The materials to consider, in the scene's order (default: the scene's own and the
        built-in defaults, :func:`flyopt.design.materials.default_materials`).
    shafts : tuple of MountShaft
        The shafts the wheel may sit on, in the scene's order (default: every [[shaft]]).
    spec : DesignSpec
        Geometry, limits and objective.
    """

    materials: tuple[Material, ...]
    shafts: tuple[MountShaft, ...]
    spec: DesignSpec


def design_inputs(scene: Scene) -> DesignInputs:
    """The materials, mounting shafts and design specification of a scene.

    Parameters
    ----------
    scene : flyopt.io.scene.Scene

    Returns
    -------
    DesignInputs
    """
    from flyopt.design.materials import design_material_names

    library = scene.material_library()
    materials = tuple(library[name] for name in design_material_names(library, scene.design_materials))
    allowed = scene.design_shafts
    shafts = tuple(
        MountShaft(s.name, s.speed_ratio, s.diameter) for s in scene.shafts if allowed is None or s.name in allowed
    )
    spec = scene.design if scene.design is not None else DesignSpec()
    return DesignInputs(materials=materials, shafts=shafts, spec=spec)
