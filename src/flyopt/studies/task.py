"""The evaluation of a sweep's chunks as data: what worker processes and Dask workers run.

Worker processes and Dask workers run a :class:`Task`: the scene as data
(its file's text, see :mod:`flyopt.studies.payload`) and the cycle's A_max
when one serves every point. Each worker rebuilds the scene once, so its
memo of analyses serves every chunk it runs.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import pandas as pd

from flyopt.studies.context import ChunkContext
from flyopt.studies.evaluate import evaluate_chunk

if TYPE_CHECKING:
    from flyopt.io.scene import Scene
    from flyopt.studies.payload import ScenePayload

__all__ = ["Task", "task_of"]


@dataclass(frozen=True)
class Task:
    """The evaluation of a sweep's chunks, as data for worker processes and Dask workers.

    Called with a table of points, it designs them as :func:`evaluate_points`
    does. It holds no live object: the scene travels as a
    :class:`~flyopt.studies.payload.ScenePayload` (its file's text, the
    fields that differ), the once-analysed cycle of a reusable scene as two
    numbers. Each worker rebuilds the scene once and keeps it (with its
    memo of analyses, :func:`physics_analysis`) for every chunk it runs.

    Attributes
    ----------
    scene : ScenePayload
    method : str
    solver_options : dict or None
    axes : tuple of str
    reusable : bool
        One A_max serves every point (see :func:`~flyopt.studies.physics.reusable_cycle`).
    a_max : float or None
        The cycle's A_max [J] when reusable.
    driving_torque : float or None
        Its driving torque [N*m] when reusable and known.
    """

    scene: ScenePayload
    method: str = "auto"
    solver_options: dict[str, Any] | None = None
    axes: tuple[str, ...] = ()
    reusable: bool = False
    a_max: float | None = None
    driving_torque: float | None = None
    torque_peak: float | None = None

    def __call__(self, points: pd.DataFrame) -> pd.DataFrame:
        """The results of the chunk ``points`` (one row per point)."""
        return evaluate_chunk(self.context(), points)

    def context(self) -> ChunkContext:
        """The chunk context of this process, built on first use and kept."""
        key = (
            self.scene.key,
            self.method,
            repr(sorted((self.solver_options or {}).items())),
            self.axes,
            self.reusable,
            self.a_max,
            self.driving_torque,
            self.torque_peak,
        )
        with _TASK_LOCK:
            ctx = _TASK_CONTEXTS.get(key)
            if ctx is None:
                scene = self.scene.scene()
                if self.reusable:
                    scene = scene.replace(driving=None, resisting=None, net=None)
                ctx = ChunkContext(
                    scene,
                    self.a_max,
                    self.driving_torque,
                    self.reusable,
                    self.method,
                    self.solver_options,
                    self.axes,
                    self.torque_peak,
                )
                while len(_TASK_CONTEXTS) >= 4:  # a worker that serves several sweeps
                    _TASK_CONTEXTS.pop(next(iter(_TASK_CONTEXTS)))
                _TASK_CONTEXTS[key] = ctx
        return ctx


_TASK_CONTEXTS: dict[tuple[object, ...], ChunkContext] = {}
_TASK_LOCK = threading.Lock()


def task_of(ctx: ChunkContext, scene: Scene) -> tuple[Task | None, str]:
    """The :class:`Task` of a sweep context, or why it cannot leave this process.

    Parameters
    ----------
    ctx : ChunkContext
    scene : Scene
        The scene the sweep varies (``ctx.scene`` may have its torques stripped).

    Returns
    -------
    task : Task or None
    reason : str
        Why there is no task ("" when there is one).
    """
    from flyopt.studies.payload import payload

    data, reason = payload(scene)
    if data is None:
        return None, reason
    return Task(
        data, ctx.method, ctx.solver_options, ctx.axes, ctx.reusable, ctx.a_max, ctx.driving_torque, ctx.torque_peak
    ), ""
