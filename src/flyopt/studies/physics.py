"""The analysis of one physics of a sweep (δ, ω_m, J_c, torque scale), computed once per process.

Where one A_max serves every point (:func:`reusable_cycle`: the energy model is the
exact one), a sweep analyses the cycle once and scales it. Elsewhere (a
varying inertia, a torque that depends on speed) each distinct physics is
analysed by :func:`flyopt.analysis.analyse`, once: the points that vary only
the design (envelope, material, shaft, H/B, geometry, objective) reuse it.
"""

from __future__ import annotations

import threading
import weakref
from collections import OrderedDict
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any

from flyopt.studies.points import PHYSICS_FIELDS, point_scene

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene

__all__ = ["MEMO_SIZE", "analyses_of", "physics_analysis", "reusable_cycle"]


def reusable_cycle(scene: Scene) -> bool:
    """Whether J_F = A_max/(ω_m² δ) − J_c with one A_max holds at every point.

    True where the energy model is the exact one (flyopt's one model chooser
    decides): a constant inertia and torques of the angle only, so A_max does
    not depend on δ, ω_m or J_c, and scales with the torques. Otherwise each
    distinct physics is analysed by its exact model.
    """
    if scene.net is not None:
        return True
    from flyopt.machine.reduce import reduce
    from flyopt.sizing.choose import ENERGY, choose

    return choose(reduce(scene))[0] == ENERGY


def analyses_of(scene: Scene, points: pd.DataFrame) -> Iterator[Analysis]:
    """The analysis of each point, computed once per distinct physics (see PHYSICS_FIELDS)."""
    fields = [name for name in PHYSICS_FIELDS if name in points]
    if not fields:
        analysis = physics_analysis(scene)
        for _ in range(len(points)):
            yield analysis
        return
    for values in zip(*(points[name].to_numpy(dtype=float) for name in fields)):
        yield physics_analysis(scene, dict(zip(fields, values)))


#: Analyses of this process, per scene object: {id(scene): (weak reference, {physics: Analysis},
#: {physics but δ: the latest Analysis})}.
_ANALYSES: dict[int, tuple[Any, OrderedDict[Any, Any], OrderedDict[Any, Any]]] = {}

#: Analyses kept per scene, the most recently used (~0.1-0.2 MB each): a sweep's chunks hold
#: the points of one physics together, so only a chunk's own physics need to stay.
MEMO_SIZE = 256

_MEMO_LOCK = threading.Lock()


def physics_analysis(scene: Scene, point: Mapping[str, Any] | None = None) -> Analysis:
    """The analysis of a scene at one physics (δ, ω_m, J_c, torque scale), computed once.

    Every study (sweep chunks, the points of a Pareto front, the materials of
    a trade-off) asks here, so that variations of the design alone (envelope,
    material, shaft, H/B, geometry, objective) never analyse the cycle again.
    The memo lives as long as the scene object does, and keeps the
    :data:`MEMO_SIZE` most recently used analyses. A physics that differs
    from one analysed before in δ alone is analysed ``like`` it (the reduced
    machine, its compiled models and the energy indicator do not depend on
    δ), which makes the points of a δ axis several times cheaper.

    Parameters
    ----------
    scene : Scene
    point : mapping, optional
        Values of :data:`PHYSICS_FIELDS` (SI); the scene's own where absent.

    Returns
    -------
    flyopt.analysis.Analysis
    """
    from flyopt import analysis as _analysis

    point = dict(point or {})
    own = {"delta": scene.allowed_delta, "speed": scene.omega_mean, "inertia": scene.j_constant, "torque.scale": 1.0}
    key = tuple(float(point.get(name, own[name])) for name in PHYSICS_FIELDS)
    with _MEMO_LOCK:  # Dask workers in threads share this process's memo
        entry = _ANALYSES.get(id(scene))
        if entry is None or entry[0]() is not scene:
            for stale in [k for k, (ref, *_) in _ANALYSES.items() if ref() is None]:
                del _ANALYSES[stale]
            entry = _ANALYSES[id(scene)] = (weakref.ref(scene), OrderedDict(), OrderedDict())
        memo, by_rest = entry[1], entry[2]
        if key in memo:
            memo.move_to_end(key)
            return memo[key]
        # the same physics but δ (PHYSICS_FIELDS[0]): its reduced machine and indicator serve again
        like = by_rest.get(key[1:])
    changed = {name: value for name, value in zip(PHYSICS_FIELDS, key) if value != own[name]}
    result = _analysis.analyse(point_scene(scene, changed) if changed else scene, like=like)
    with _MEMO_LOCK:
        memo[key] = result
        by_rest[key[1:]] = result
        by_rest.move_to_end(key[1:])
        for kept in (memo, by_rest):
            while len(kept) > MEMO_SIZE:
                kept.popitem(last=False)
    return result
