"""The chunk context: what every chunk of a sweep needs, built once per sweep (and per worker)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flyopt.design import design_inputs
from flyopt.pipeline import describes_shafts
from flyopt.studies.physics import physics_analysis, reusable_cycle

if TYPE_CHECKING:
    from flyopt.io.scene import Scene

__all__ = ["ChunkContext", "chunk_context", "scene_needs_torque"]


@dataclass(frozen=True)
class ChunkContext:
    """What every chunk needs; picklable (the torques are left out when reusable)."""

    scene: Scene
    a_max: float | None
    driving_torque: float | None
    reusable: bool
    method: str = "auto"
    solver_options: dict[str, Any] | None = None
    axes: tuple[str, ...] = ()
    torque_peak: float | None = None  # max |M_d - M_r| of the cycle when reusable [N*m]


def chunk_context(
    scene: Scene, method: str = "auto", solver_options: Mapping[str, Any] | None = None, axes: Sequence[str] = ()
) -> ChunkContext:
    """The context of a sweep's chunks: the scene, and the cycle's A_max when one serves every point.

    Parameters
    ----------
    scene : Scene
    method : {"auto", "closed_form", "ipopt"}
    solver_options : mapping, optional
        CasADi/IPOPT options for the IPOPT points.
    axes : sequence of str
        The varied fields (their columns are kept in the results).

    Returns
    -------
    ChunkContext
        Where :func:`~flyopt.studies.physics.reusable_cycle`, the scene without its
        torques and the cycle's A_max, driving torque and peak torque (the
        latter only when the designs need it). A scene that describes a shaft keeps its
        torques and is analysed at each physics (:func:`~flyopt.studies.physics.physics_analysis`):
        its points' keys and shaft checks read the cycle's net torque there, as
        ``flyopt solve`` does (:mod:`flyopt.studies.described`).
    """
    if reusable_cycle(scene) and not describes_shafts(scene):
        analysis = physics_analysis(scene)
        stripped = scene.replace(driving=None, resisting=None, net=None)
        return ChunkContext(
            stripped,
            analysis.a_max,
            analysis.driving_torque,
            True,
            method,
            dict(solver_options) if solver_options else None,
            tuple(axes),
            analysis.net_torque_peak() if scene_needs_torque(scene) else None,
        )
    return ChunkContext(scene, None, None, False, method, dict(solver_options) if solver_options else None, tuple(axes))


def scene_needs_torque(scene: Scene) -> bool:
    """Whether the scene's designs have arms or a keyed hub, which the flywheel's peak torque loads
    (the same rule as :func:`flyopt.pipeline.design_scene`)."""
    from flyopt.design.wheel_design import needs_torque

    return needs_torque(design_inputs(scene))
