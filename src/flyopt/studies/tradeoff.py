"""The material trade-off: each material's lightest design, ranked (``flyopt tradeoff``).

For every material of a scene, the lightest wheel on any allowed shaft, its
size, rim speed, mass, cost and the limits that bind; the materials are
ordered by flyopt's one ranking rule (:mod:`flyopt.design.rank`), so the
first row is the material ``flyopt solve`` chooses with the objective mass.
The command line is in :mod:`flyopt.cli.studies`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Literal

import pandas as pd

from flyopt import said
from flyopt.design import design_inputs, rank
from flyopt.studies.physics import physics_analysis

if TYPE_CHECKING:  # the annotations only
    from flyopt.io.scene import Scene

__all__ = ["TRADEOFF_COLUMNS", "material_tradeoff"]

#: The trade-off's columns that hold numbers (floats; NaN for a material with no design).
_NUMBER_COLUMNS = (
    "speed_ratio",
    "d_outer",
    "d_mean",
    "h",
    "b",
    "hb_ratio",
    "rim_speed",
    "rim_speed_limit",
    "mass",
    "cost",
)

TRADEOFF_COLUMNS = (
    "material",
    "status",
    "shaft",
    *_NUMBER_COLUMNS,
    "binding",
    "limit",
    "reason",
    "method",
    "solver_status",
)


def material_tradeoff(
    scene: Scene,
    solver_options: Mapping[str, Any] | None = None,
    method: Literal["auto", "ipopt", "closed_form"] = "auto",
) -> pd.DataFrame:
    """For each material, its lightest design: size, rim speed, mass, cost, binding limit.

    Parameters
    ----------
    scene : Scene
        Its materials (``design.materials`` or every known one) and shafts;
        the objective is mass whatever the scene says.
    solver_options : mapping, optional
    method : {"auto", "ipopt", "closed_form"}
        Design method (see :func:`flyopt.design.designer.design_flywheel`).

    Returns
    -------
    pandas.DataFrame
        One row per material, lightest first, then the infeasible ones:
        ``material``, ``status`` (designed, infeasible, not_needed), the
        chosen ``shaft``, ``d_outer``, ``d_mean``, ``h``, ``b`` [m],
        ``rim_speed`` and its limit [m/s], ``mass`` [kg], ``cost``,
        ``binding`` (every active constraint), ``limit`` (the active limits
        other than the inertia itself), ``reason`` (for an infeasible
        material: why, for each shaft), ``method`` and ``solver_status``.

    Notes
    -----
    Each material is designed as ``flyopt solve`` designs it
    (:func:`flyopt.pipeline.design_scene`, continuous: the exact closed form, or IPOPT, after the closed-form
    infeasibility proof, with the flywheel's peak torque on the arms and the key and a described shaft's
    checks) on every allowed shaft; the materials are ordered by flyopt's one
    ranking rule (:mod:`flyopt.design.rank`), so the first row is the winner
    of ``flyopt solve`` with the objective mass.
    """
    from flyopt.design.designer import rim_speed_limit
    from flyopt.design.inputs import seat_given_only, wheel_alone_only
    from flyopt.pipeline import design_scene

    seat_given_only(scene, "a material trade-off")
    wheel_alone_only(scene, "a material trade-off")
    analysis = physics_analysis(scene)
    spec = dataclasses.replace(design_inputs(scene).spec, objective="mass")
    by_mass = dataclasses.replace(scene, design=spec)
    inputs = design_inputs(by_mass)
    rows, bests = [], {}
    for material in inputs.materials:
        name = material.name
        row = dict.fromkeys(TRADEOFF_COLUMNS)
        row.update(
            material=name,
            rim_speed_limit=rim_speed_limit(material, spec),
            binding="",
            limit="",
            reason="",
            method="",
            solver_status="",
            shaft="",
        )
        # the design flyopt solve makes of this material alone (its peak torque on the arms and the key, a
        # described shaft's post-check), continuous as every study compares it
        alone = dataclasses.replace(by_mass, design_materials=(name,))
        result = design_scene(alone, analysis, solver_options, method, continuous=True)
        row["status"] = result.status
        best = result.best
        if best is not None:
            bests[name] = best
            row.update(
                shaft=best.shaft,
                speed_ratio=best.speed_ratio,
                d_outer=best.dims.d_outer,
                d_mean=best.dims.d_mean,
                h=best.dims.h,
                b=best.dims.b,
                hb_ratio=best.dims.hb_ratio,
                rim_speed=best.stresses.rim_speed,
                mass=best.mass,
                cost=best.cost,
                binding=",".join(best.limits.binding),
                limit=",".join(b for b in best.limits.binding if b != "inertia"),
                method="closed_form" if best.provenance.solver_status == "closed_form" else "ipopt",
                solver_status=best.provenance.solver_status,
            )
        elif result.status == "infeasible":
            row["reason"] = said.join("; ", [c.reason for c in result.candidates])  # its quantities kept
            row["method"] = "closed_form"
        else:
            row["reason"] = result.message
            row["method"] = "none"
        rows.append(row)
    table = pd.DataFrame(rows, columns=list(TRADEOFF_COLUMNS))
    # the reasons as objects: a column of pandas' strings keeps the text and loses a reason's quantities, which
    # the command line says in the reader's units (flyopt.said)
    table["reason"] = pd.Series([row["reason"] for row in rows], dtype=object)
    for column in _NUMBER_COLUMNS:
        table[column] = pd.to_numeric(table[column]).astype(float)
    # the designed materials in the order of flyopt's one ranking rule, then the others
    ranked = [c.material for c in rank.ranking(list(bests.values()))]
    position = {name: k for k, name in enumerate(ranked)}
    order = sorted(range(len(table)), key=lambda k: (position.get(table["material"].iloc[k], len(ranked)), k))
    return table.iloc[order].reset_index(drop=True)
