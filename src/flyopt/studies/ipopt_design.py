"""One point of a chunk designed by IPOPT (:func:`flyopt.design.design_flywheel`, its NLP built once
per structure and process); a failed solve is a ``failed`` row with IPOPT's status, never a mass."""

from __future__ import annotations

import dataclasses
import math
import threading
from typing import TYPE_CHECKING

import numpy as np

from flyopt.errors import SolverFailed
from flyopt.studies.chunk_arrays import WINNER_COLUMNS, ChunkInputs, point_material

if TYPE_CHECKING:
    from flyopt.design.result import DesignResult
    from flyopt.studies.context import ChunkContext

__all__ = ["IPOPT_LOCK", "design_ipopt", "fail_row", "fill_row"]

#: Held around every design of a point: a CasADi Function is not to be called from two threads at once (Dask
#: workers in threads).
IPOPT_LOCK = threading.Lock()


def design_ipopt(
    ctx: ChunkContext,
    inputs: ChunkInputs,
    k: int,
    j_required: float,
    res: dict[str, np.ndarray],
    torque: float | None = None,
) -> None:
    """One point by optimize.design_flywheel (IPOPT, NLP cached per structure)."""
    from flyopt.design import design_flywheel

    mats = [inputs.material[k]] if inputs.material is not None else inputs.material_names
    shafts = [inputs.shaft[k]] if inputs.shaft is not None else inputs.shaft_names
    materials = []
    for name in mats:  # the scene's material with this point's values: every other field kept
        materials.append(
            point_material(
                inputs.library[name],
                inputs.density[name][k],
                float(inputs.max_rim_speed[name][k]),
                float(inputs.material_cost[name][k]),
            )
        )
    mounts = [dataclasses.replace(inputs.mounts[name], speed_ratio=float(inputs.ratio[name][k])) for name in shafts]

    def opt(x):
        return None if math.isnan(x) else float(x)

    spec = dataclasses.replace(
        inputs.spec,
        geometry=inputs.geometry[k],
        hb_ratio=(inputs.hb_min[k], inputs.hb_max[k]),
        max_outer_diameter=inputs.envelope[k],
        max_width=inputs.width[k],
        d_mean=opt(inputs.d_mean[k]),
        objective=inputs.objective[k],
    )
    res["method"][k] = "ipopt"
    res["n_combinations"][k] = len(materials) * len(mounts)
    try:
        with IPOPT_LOCK:  # a CasADi Function is not to be called from two threads at once
            result = design_flywheel(
                float(j_required),
                float(inputs.omega_rim[k]),
                mounts,
                materials,
                spec,
                solver_options=ctx.solver_options,
                method="ipopt",
                torque=torque,
            )
    except SolverFailed as err:
        fail_row(res, k, err)
        return
    fill_row(res, k, result)


def fail_row(res: dict[str, np.ndarray], k: int, err: SolverFailed) -> None:
    """Row ``k`` of ``res`` for a point whose solve failed: ``failed`` with IPOPT's status, never a mass."""
    res["status"][k] = "failed"
    res["solver_status"][k] = str(getattr(err, "status", "") or "error")
    res["message"][k] = str(err)


def fill_row(res: dict[str, np.ndarray], k: int, result: DesignResult) -> None:
    """Row ``k`` of ``res`` from a point's design: its winner's values, or why there is none (the one reading of a
    :class:`~flyopt.design.result.DesignResult` into a sweep row, for IPOPT's points and a described shaft's)."""
    res["n_feasible"][k] = sum(c.feasible for c in result.candidates)
    best = result.best
    if best is None:
        res["status"][k] = "infeasible"
        res["message"][k] = result.message
        return
    res["status"][k] = "designed"
    res["feasible"][k] = True
    res["best_material"][k] = best.material
    res["best_shaft"][k] = best.shaft
    res["best_speed_ratio"][k] = best.speed_ratio
    limits = best.limits
    records = {"design": best, "dims": best.dims, "stresses": best.stresses}
    for name, record in WINNER_COLUMNS.items():
        res[name][k] = getattr(records[record], name)
    values = {
        "j_required_on_shaft": limits.j_required_on_shaft,
        "d_outer_limit": limits.d_outer_limit,
        "rim_speed_limit": limits.rim_speed_limit,
        "objective": best.objective,
    }
    for name, value in values.items():
        res[name][k] = value
    res["cost"][k] = math.nan if best.cost is None else best.cost
    safety = best.stresses.safety_factor
    res["safety_factor"][k] = math.nan if safety is None else safety
    res["binding"][k] = ",".join(limits.binding)
    res["solver_status"][k] = best.provenance.solver_status
    res["iterations"][k] = best.provenance.iterations
