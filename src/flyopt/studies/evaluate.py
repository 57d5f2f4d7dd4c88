"""Evaluation of sweep points: every point designed, the cycle analysed once where exact.

What is computed once, and why it is exact
------------------------------------------
The cycle is analysed once: for torques of the angle alone A_max does not
depend on δ, ω_m or J_c, and scaling both torques by k scales every ΔE, so
A_max(k) = k A_max. Each point then has J_F = k A_max / (ω_m² δ) − J_c,
the formula of the analysis itself. The designs come from
:mod:`flyopt.design.closed_form` (closed form, exact, vectorized over every point and
combination) where it covers the structure, and from
:func:`flyopt.design.designer.design_flywheel` (IPOPT on an NLP built once per
structure and process, fed parameters) elsewhere; each row says which
(``method``). A point whose IPOPT solve fails gets ``status = "failed"``
with IPOPT's status, never a mass.

Where one A_max does not serve every point (a varying inertia, a torque that
depends on speed), each point's physics (δ, ω_m, J_c, torque scale) is
analysed once (:mod:`flyopt.studies.physics`): the points that vary only the
design (envelope, material, shaft, H/B, geometry, objective) reuse it. The
points themselves (their checks, counts and scenes) are
:mod:`flyopt.studies.points`.

A scene that describes a shaft (docs/flywheel-design.md, section 26) has every
point designed as ``flyopt solve`` designs it, by
:func:`flyopt.pipeline.design_scene` on the point's own analysis: its key at its
train's torque and its shaft's post-check (:mod:`flyopt.studies.described`); its
cycle is then analysed at each physics, never scaled (the shaft's checks read the
net torque), and none of its points takes the vectorized closed form.

Worker processes and Dask workers run the same evaluation as a
:class:`~flyopt.studies.task.Task` (:mod:`flyopt.studies.task`).

One path for each decision: the scene's design problem comes from
:func:`flyopt.design.design_inputs` (the columns of a point override it), the
constraint check and the binding rule from :mod:`flyopt.design.check`, the
winner of each point from :func:`flyopt.design.rank.winners`; so a sweep
point and ``flyopt solve`` of the same scene name the same winner.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from flyopt.cycle.indicator import required_inertia, speed_extremes
from flyopt.design import design_inputs
from flyopt.design.wheel_design import neighbours
from flyopt.errors import BrokenInvariant, SceneError
from flyopt.pipeline import describes_shafts
from flyopt.sizing.peak_torque import flywheel_peak_torque
from flyopt.studies.chunk_arrays import ChunkInputs, empty_results, result_table
from flyopt.studies.closed_form_design import design_closed_form
from flyopt.studies.context import ChunkContext, chunk_context, scene_needs_torque
from flyopt.studies.described import analysis_for, design_described, shaft_material_fields
from flyopt.studies.ipopt_design import design_ipopt
from flyopt.studies.physics import analyses_of
from flyopt.studies.points import vectorized

if TYPE_CHECKING:
    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene

__all__ = ["evaluate_chunk", "evaluate_points"]


def evaluate_points(
    scene_or_context: Scene | ChunkContext,
    points: pd.DataFrame,
    *,
    method: str = "auto",
    solver_options: Mapping[str, Any] | None = None,
) -> pd.DataFrame:
    """Design every point of a table of sweep points.

    Parameters
    ----------
    scene_or_context : Scene
        The scene the points vary (its cycle is analysed once).
    points : pandas.DataFrame
        Rows of :attr:`SweepPlan.points`.
    method : {"auto", "closed_form", "ipopt"}
        ``auto``: the closed form of :mod:`flyopt.design.closed_form` where it is exact,
        IPOPT elsewhere; ``ipopt``: IPOPT for every point (for checks and
        benchmarks); ``closed_form``: refuse structures it does not cover.
    solver_options : mapping, optional
        CasADi/IPOPT options for the IPOPT points.

    Returns
    -------
    pandas.DataFrame
        One row per point: ``point``, :data:`CORE_INPUTS`, the other varied
        fields, then :data:`RESULT_COLUMNS`.
    """
    ctx = scene_or_context
    if not isinstance(ctx, ChunkContext):
        ctx = chunk_context(ctx, method, solver_options, tuple(c for c in points.columns if c != "point"))
    return evaluate_chunk(ctx, points)


def evaluate_chunk(ctx: ChunkContext, points: pd.DataFrame) -> pd.DataFrame:
    scene = ctx.scene
    inputs = ChunkInputs(scene, points)
    n = inputs.n
    res = empty_results(n)
    needs_torque = scene_needs_torque(scene)
    # a scene whose shafts are described: every point designed as flyopt solve designs it, on its own analysis
    # (flyopt.studies.described; chunk_context never reuses one A_max for it)
    described = describes_shafts(scene)
    analyses: list[Analysis] = []
    # -- the cycle: analysed once, A_max scaled (see the module notes) ------
    if ctx.reusable:
        if ctx.a_max is None:
            raise BrokenInvariant("a reusable context carries the cycle's A_max (chunk_context)")
        if described:
            raise BrokenInvariant("a scene whose shafts are described is analysed at each physics (chunk_context)")
        a_max = inputs.scale * ctx.a_max
        driving = inputs.scale * ctx.driving_torque if ctx.driving_torque is not None else np.full(n, np.nan)
        j_margin = required_inertia(a_max, inputs.speed, inputs.delta, inputs.inertia)
        inputs.omega_rim = speed_extremes(inputs.speed, inputs.delta)[0]  # ω_max: the rim is checked there
        power = driving * inputs.speed
        motor_power = power / scene.efficiency
    else:  # varying inertia or speed-dependent torques, or described shafts: each distinct physics analysed
        a_max, driving, j_margin, power, motor_power = (np.empty(n) for _ in range(5))
        inputs.omega_rim = np.empty(n)
        torques: list[float | None] = []
        for k, analysis in enumerate(analyses_of(scene, points)):
            if described:
                analyses.append(analysis)
            if needs_torque:
                torques.append(analysis.flywheel_torque())
            a_max[k], j_margin[k] = analysis.a_max, analysis.j_margin
            inputs.omega_rim[k] = analysis.omega_max
            driving[k] = _float(analysis.driving_torque)
            power[k], motor_power[k] = _float(analysis.power), _float(analysis.motor_power)
    res["a_max"], res["j_margin"] = a_max, j_margin
    res["j_required"] = np.maximum(j_margin, 0.0)
    res["driving_torque"] = driving
    res["power"] = power
    res["motor_power"] = motor_power
    needed = j_margin > 0.0
    idle = ~needed
    res["status"][idle] = "not_needed"
    res["method"][idle] = "none"
    for k in np.flatnonzero(idle).tolist():
        res["message"][k] = f"no flywheel needed: J_F = {j_margin[k]:.4g} kg·m² is not positive"
    design = design_inputs(scene)
    seen: dict[tuple[str, str], bool] = {}
    covered = (
        np.array(
            [
                seen[g, o] if (g, o) in seen else seen.setdefault((g, o), vectorized(design, g, o))
                for g, o in zip(inputs.geometry, inputs.objective)
            ],
            dtype=np.bool_,
        )
        if n
        else np.zeros(0, dtype=np.bool_)
    )
    if ctx.method == "closed_form" and (needed & ~covered).any():
        k = int(np.flatnonzero(needed & ~covered)[0])
        raise SceneError(
            "method",
            f"the closed form does not cover objective "
            f"{inputs.objective[k]!r} (point {int(points['point'].iloc[k])}); "
            f"use method 'auto' or 'ipopt'",
        )
    use_batch = needed & covered if ctx.method != "ipopt" and not described else np.zeros(n, dtype=bool)
    design_closed_form(inputs, j_margin, use_batch, res)
    materials = shaft_material_fields(scene, points.columns) if described else ()
    kept: dict[Any, Any] = {}
    with neighbours():  # each whole wheel warm-started from the chunk's previous point (the same answers)
        for k in np.flatnonzero(needed & ~use_batch).tolist():
            if described:
                design_described(ctx, points, k, analysis_for(analyses[k], points.iloc[k], materials, kept), res)
                continue
            torque = None
            if needs_torque and ctx.reusable and ctx.torque_peak is not None:
                torque = flywheel_peak_torque(
                    j_margin[k], j_margin[k] + inputs.inertia[k], inputs.scale[k] * ctx.torque_peak, 1.0
                )
            elif needs_torque and not ctx.reusable:
                torque = torques[k]
            design_ipopt(ctx, inputs, k, j_margin[k], res, torque)
    return result_table(inputs, points, ctx.axes, res)


def _float(value: float | None) -> float:
    return np.nan if value is None else float(value)
