"""The points of a chunk designed by the vectorized closed form, grouped by geometry, materials and shafts.

Every combination of every point in one call of
:func:`flyopt.design.closed_form.design_combinations`; the winner of each
point by the one ranking rule (:func:`flyopt.design.rank.winners`), the
binding constraints by :func:`flyopt.design.check.binding_names`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from flyopt.design import closed_form as batch
from flyopt.design import rank
from flyopt.design.check import binding_names
from flyopt.studies.chunk_arrays import WINNER_COLUMNS, ChunkInputs

__all__ = ["design_closed_form"]


def design_closed_form(
    inputs: ChunkInputs, j_margin: NDArray[np.float64], mask: NDArray[np.bool_], res: dict[str, np.ndarray]
) -> None:
    """Fill the rows of ``mask`` from the vectorized closed form."""
    if not mask.any():
        return
    geometries = list(dict.fromkeys(inputs.geometry[mask]))
    m_names, s_names = inputs.material_names, inputs.shaft_names
    m_code = (
        np.array([m_names.index(m) for m in inputs.material]) if inputs.material is not None else np.full(inputs.n, -1)
    )
    s_code = np.array([s_names.index(s) for s in inputs.shaft]) if inputs.shaft is not None else np.full(inputs.n, -1)
    for geo in geometries:
        in_geo = mask & (inputs.geometry == geo)
        keys = np.stack([m_code[in_geo], s_code[in_geo]], axis=1)
        groups, inverse = np.unique(keys, axis=0, return_inverse=True)
        points_geo = np.flatnonzero(in_geo)
        for g, (mc, sc) in enumerate(groups):
            pts = points_geo[inverse.ravel() == g]
            mats = m_names if mc < 0 else [m_names[mc]]
            shafts = s_names if sc < 0 else [s_names[sc]]
            _design_group(inputs, geo, pts, mats, shafts, j_margin, res)


def _design_group(
    inputs: ChunkInputs,
    geo: str,
    pts: NDArray[np.intp],
    mats: Sequence[str],
    shafts: Sequence[str],
    j_margin: NDArray[np.float64],
    res: dict[str, np.ndarray],
) -> None:
    """One geometry, one material list and one shaft list, for points ``pts``."""
    n_m, n_s = len(mats), len(shafts)
    per = n_m * n_s
    p = np.repeat(pts, per)
    mi = np.tile(np.repeat(np.arange(n_m), n_s), len(pts))
    si = np.tile(np.tile(np.arange(n_s), n_m), len(pts))
    order = mi * n_s + si

    def table(values, names, index):
        return np.stack([values[name] for name in names])[index, p]

    density = table(inputs.density, mats, mi)
    v_max = table(inputs.rim_speed_limit, mats, mi)
    cost_per_kg = table(inputs.material_cost, mats, mi)
    allowable = table(inputs.allowable, mats, mi)
    ratio = table(inputs.ratio, shafts, si)
    out = batch.design_combinations(
        geo,
        j_margin[p],
        inputs.omega_rim[p],
        ratio,
        density,
        v_max,
        inputs.hb_min[p],
        inputs.hb_max[p],
        inputs.envelope[p],
        inputs.width[p],
        inputs.d_mean[p],
    )
    mass = out.mass
    cost = mass * cost_per_kg
    objective = np.where(inputs.objective[p] == "cost", cost, mass)
    feasible = out.feasible
    res["n_combinations"][pts] = per
    counts = np.bincount(p[feasible], minlength=inputs.n)
    res["n_feasible"][pts] = counts[pts]
    res["method"][pts] = batch.METHOD
    # the winner of each point, by the one ranking rule (flyopt.design.rank)
    f = np.flatnonzero(feasible)
    if f.size:
        local = np.searchsorted(pts, p[f])  # pts is sorted: each point's group number
        best = rank.winners(
            local,
            objective[f],
            cost[f],
            mass[f],
            out.rim_speed[f],
            np.asarray(mats, dtype=object)[mi[f]],
            np.asarray(shafts, dtype=object)[si[f]],
            n_groups=len(pts),
        )
        w = f[best[best >= 0]]
        q = p[w]
        res["status"][q] = "designed"
        res["feasible"][q] = True
        res["best_material"][q] = np.asarray(mats, dtype=object)[mi[w]]
        res["best_shaft"][q] = np.asarray(shafts, dtype=object)[si[w]]
        res["best_speed_ratio"][q] = ratio[w]
        for name in WINNER_COLUMNS:
            res[name][q] = out[name][w]
        res["j_required_on_shaft"][q] = out.j_shaft[w]
        res["d_outer_limit"][q] = out.cap[w]
        res["rim_speed_limit"][q] = v_max[w]
        res["cost"][q] = cost[w]
        res["objective"][q] = objective[w]
        res["safety_factor"][q] = allowable[w] / out.hoop_stress[w]
        res["binding"][q] = [",".join(binding_names(b)) for b in out.binding[w]]
    none = pts[counts[pts] == 0]
    if none.size:
        # the combination that comes closest: largest J_max / J' (for the message)
        closeness = out.j_max / out.j_shaft
        lost = np.isin(p, none)
        idx = np.flatnonzero(lost)
        ranked = idx[np.lexsort((order[idx], -closeness[idx], p[idx]))]
        _, first = np.unique(p[ranked], return_index=True)
        for c in ranked[first]:
            k = p[c]
            res["status"][k] = "infeasible"
            res["message"][k] = (
                f"no material and shaft can give the inertia; the closest, "
                f"{mats[mi[c]]} on the {shafts[si[c]]} shaft, can give at most "
                f"{out.j_max[c]:.4g} of the {out.j_shaft[c]:.4g} kg·m² it needs there"
            )
