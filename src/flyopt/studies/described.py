"""One sweep point of a scene whose shafts are described, designed as ``flyopt solve`` designs it.

A described shaft (docs/flywheel-design.md, section 26) decides two things a bare
:func:`flyopt.design.design_flywheel` does not: the torque its wheel's key and hub are
sized at (its train's forced response, :func:`flyopt.design.shaft.cycle.keyed_shafts`,
in place of the rigid body's peak torque), and whether the shaft carries the wheel
(strength and fatigue, deflection, lateral and torsional critical speeds, the key:
the post-check, :func:`flyopt.design.shaft.cycle.acceptor`, and the re-design of a
wheel refused for its key alone, :func:`flyopt.design.shaft.cycle.rekeyed`). Both
depend on the whole point: the cycle's net torque and its orders, ω_m and δ (the
point's analysis), the shaft's speed ratio and the materials of the shaft and its
train. So each such point is designed by the one function that decides them for
``flyopt solve``, :func:`flyopt.pipeline.design_scene` (continuous, as every study
compares designs, and as the material trade-off does), on the point's scene
(:func:`flyopt.studies.points.point_scene`) and its analysis
(:func:`flyopt.studies.physics.physics_analysis`).

What is reused: the analysis of each physics (δ, ω_m, J_c, torque scale), and with it
the shafts' context (:func:`flyopt.design.shaft.cycle.shaft_context`, one per analysis
and shafts: its net torque samples, its orders, the checks and key torques already
worked out); a point that changes only the design (envelope, width, H/B, geometry,
objective, a wheel material) reads them again. What is rebuilt: the context where the
point's shafts differ (a speed ratio), or where it changes a property of a material
the shaft or its train is made of (the context is then made afresh for that point's
materials, :func:`analysis_for`); the key torque at each point's inertia.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.errors import SolverFailed
from flyopt.studies.ipopt_design import IPOPT_LOCK, fail_row, fill_row
from flyopt.studies.points import point_scene

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene
    from flyopt.studies.context import ChunkContext

__all__ = ["design_described", "shaft_material_fields"]


def shaft_material_fields(scene: Scene, columns: Any) -> tuple[str, ...]:
    """The point columns that change a property of a material a described shaft or its train is made of
    (``material.NAME.*``): the shafts' context depends on them."""
    from flyopt.machine.drive_train import TrainSpring

    names = set()
    for s in scene.shafts:
        if s.layout is None:
            continue
        names.add(s.layout.material)
        names.update(e.material for e in s.layout.train if isinstance(e, TrainSpring) and e.kind == "piece")
    return tuple(c for c in columns if c.startswith("material.") and c.split(".")[1] in names)


def analysis_for(analysis: Analysis, point: Mapping[str, Any], fields: tuple[str, ...], kept: dict[Any, Any]) -> Any:
    """The analysis to design ``point`` on: the physics' own, or, where the point changes a shaft's material
    (``fields``, :func:`shaft_material_fields`), a copy of it per distinct set of those values (kept in ``kept``),
    whose shafts' context is then built with the point's materials (the context is one per analysis object)."""
    if not fields:
        return analysis
    key = (id(analysis), *(float(point[name]) for name in fields))
    if key not in kept:
        kept[key] = (analysis, copy.copy(analysis))  # the original held: its id stays unique while kept
    return kept[key][1]


def design_described(
    ctx: ChunkContext,
    points: pd.DataFrame,
    k: int,
    analysis: Analysis,
    res: dict[str, np.ndarray],
) -> None:
    """Point ``k`` of ``points`` designed by :func:`flyopt.pipeline.design_scene` (continuous) on its scene and
    ``analysis`` (the point's own): its key at its train's torque, its shaft's post-check; row ``k`` of ``res``
    filled as an IPOPT point's (:func:`~flyopt.studies.ipopt_design.fill_row`): a point whose shaft cannot carry
    any wheel is ``infeasible`` with every combination's reason in numbers, a failed solve ``failed`` with
    IPOPT's status."""
    from flyopt.design import design_inputs
    from flyopt.pipeline import design_scene

    row = {name: value for name, value in points.iloc[k].items() if name != "point"}
    scene = point_scene(ctx.scene, row)
    inputs = design_inputs(scene)
    res["n_combinations"][k] = len(inputs.materials) * len(inputs.shafts)
    try:
        with IPOPT_LOCK:  # a CasADi Function is not to be called from two threads at once
            result = design_scene(scene, analysis, ctx.solver_options, ctx.method, continuous=True)  # type: ignore[arg-type]
    except SolverFailed as err:
        res["method"][k] = "ipopt"
        fail_row(res, k, err)
        return
    best = result.best
    closed = best is not None and best.provenance.solver_status == "closed_form"
    res["method"][k] = "closed_form" if closed else "ipopt"
    fill_row(res, k, result)
