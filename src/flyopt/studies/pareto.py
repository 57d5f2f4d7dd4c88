"""Pareto fronts of mass against a second objective (``flyopt pareto``, in :mod:`flyopt.cli.studies`).

Pareto fronts (two objectives, both minimized) come from an ε-constraint
swept through the design model, then the dominated points are removed:

- ``mass`` vs ``outer_diameter``: minimize the mass subject to
  D_outer <= ε, for ε from the smallest wheel that can give the inertia
  (objective ``outer_diameter``, solved by IPOPT) to the outer diameter of the
  lightest wheel (beyond it the constraint no longer binds). The constraint is
  the scene's envelope, so each ε is one sweep point
  ``design.max_outer_diameter = ε``. The points are designed from the
  largest ε down (warm-started from their neighbours, in one process,
  always serial): each only tightens the envelope, so an NLP IPOPT found infeasible
  at one ε is not solved again at a smaller one
  (:func:`flyopt.design.wheel_design.neighbours`).
- ``mass`` vs ``cost``: for one material and shaft the lightest wheel is also
  the cheapest (cost = mass × cost per kg), so the constraint cost <= ε only
  changes the answer at the cost of some combination's lightest design: the
  front is the non-dominated set of the material × shaft designs (a sweep of
  ``material`` × ``shaft``). Needs a cost on every material.
- ``mass`` vs ``delta``: the lightest wheel for δ <= ε has δ = ε (J_F falls
  as δ grows), so the front is a sweep of δ; where no flywheel is needed the
  mass is 0.

Each front point is a row of the sweep table (the design, how it was
computed) with the two objectives as columns and ``epsilon``, the constraint
value that produced it; ``attrs["objectives"]`` names the objectives, which
``flyopt pareto`` writes into the front's file for ``flyopt plot``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
import numpy.typing as npt
import pandas as pd

from flyopt.design import DesignSpec, design_inputs
from flyopt.design.inputs import seat_given_only, single_design_only, wheel_alone_only
from flyopt.design.wheel_design import neighbours
from flyopt.errors import SceneError, shorten
from flyopt.io.design_section import LENGTH_RANGE, LENGTH_WHY
from flyopt.io.fields import check_delta, check_magnitude
from flyopt.outputs.results import normalize
from flyopt.studies.evaluate import evaluate_points
from flyopt.studies.physics import physics_analysis
from flyopt.studies.sweep import sweep

if TYPE_CHECKING:  # the annotations only
    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene

__all__ = ["MAX_FRONT_POINTS", "PARETO_OBJECTIVES", "non_dominated", "pareto"]

#: Worker processes of a front's sweep of cost or δ: "auto" runs it serially unless its points are
#: estimated to take over a second (a front of δ on a scene analysed at every δ). The front of the outer
#: diameter runs serially always: each point is warm-started from the larger envelope's design before it.
WORKERS: Literal["auto"] = "auto"

#: Most ε values of a front: a front of a thousand designs is drawn as finely as a plot shows,
#: and (at some 100 whole-wheel designs a second) computed within seconds; more is refused.
MAX_FRONT_POINTS = 1000

#: Second objectives a front may trade against mass, with the unit of --range.
PARETO_OBJECTIVES = {
    "outer_diameter": "length",
    "cost": None,
    "delta": "dimensionless",
    "motor_power": None,  # the motor sizes of a scene's [drive], each with its lightest wheel
}


# --------------------------------------------------------------------------
# Pareto fronts
# --------------------------------------------------------------------------


def non_dominated(first: npt.ArrayLike, second: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    """Mask of the points no other point dominates (both objectives minimized).

    A point is dominated when another is no worse in both objectives and
    better in one; of several equal points the first is kept.

    Parameters
    ----------
    first, second : array_like
        Objective values (NaN: not a candidate).

    Returns
    -------
    ndarray of bool
    """
    f1, f2 = np.asarray(first, dtype=float), np.asarray(second, dtype=float)
    keep = np.zeros(f1.shape, dtype=bool)
    valid = np.flatnonzero(~(np.isnan(f1) | np.isnan(f2)))
    order = valid[np.lexsort((valid, f2[valid], f1[valid]))]
    best = math.inf
    for k in order:
        if f2[k] < best:
            keep[k] = True
            best = f2[k]
    return keep


def objective_pair(objectives: str | Sequence[str]) -> tuple[tuple[str, ...], str]:
    if isinstance(objectives, str):
        objectives = [o.strip() for o in objectives.split(",")]
    objectives = tuple(objectives)
    other = [o for o in objectives if o != "mass"]
    if len(objectives) != 2 or objectives.count("mass") != 1 or other[0] not in PARETO_OBJECTIVES:
        raise SceneError(
            "objectives",
            f"{','.join(objectives)!r} is not a known pair: "
            f"give mass and one of {', '.join(PARETO_OBJECTIVES)} "
            f"(e.g. mass,outer_diameter)",
        )
    return objectives, other[0]


def check_points(points: object, label: str = "points") -> None:
    """Refuse a front of other than 2 to :data:`MAX_FRONT_POINTS` points, naming ``label`` (``--points`` on the
    command line): the one rule of both."""
    if not isinstance(points, (int, np.integer)) or isinstance(points, bool) or not 2 <= points <= MAX_FRONT_POINTS:
        raise SceneError(label, f"must be a whole number from 2 to {MAX_FRONT_POINTS}, got {shorten(points)}")


def pareto(
    scene: Scene,
    objectives: str | Sequence[str] = ("mass", "outer_diameter"),
    *,
    points: int = 25,
    span: tuple[float, float] | None = None,
    method: Literal["auto", "closed_form", "ipopt"] = "auto",
    solver_options: Mapping[str, Any] | None = None,
) -> pd.DataFrame:
    """Pareto front of mass against a second objective, by an ε-constraint.

    Parameters
    ----------
    scene : Scene
    objectives : pair of str or "mass,OTHER"
        ``mass`` and one of ``outer_diameter``, ``cost``, ``delta``, ``motor_power`` (the
        flywheel's mass against the motor's rated power, over the sizes of the scene's [drive]).
    points : int
        Number of ε values (outer diameter, δ).
    span : (float, float), optional
        Range of ε in SI ([m] for the outer diameter, δ for delta); by
        default the whole front for the outer diameter and δ/10 .. 10 δ
        (below 1) for delta.
    method : {"auto", "closed_form", "ipopt"}
        How each ε point is designed (see :func:`flyopt.studies.sweep.evaluate_points`):
        ``ipopt`` sends every point through the CasADi/IPOPT model.
    solver_options : mapping, optional

    Returns
    -------
    pandas.DataFrame
        The non-dominated designs, sorted by the second objective: the sweep
        columns plus ``epsilon`` and one column per objective. Empty (with
        ``attrs["message"]``) when no flywheel is needed or none is feasible.

    Raises
    ------
    SceneError
        Unknown objectives, bad span, materials without a cost for ``cost``.
    """
    objectives, other = objective_pair(objectives)
    single_design_only(design_inputs(scene).spec, "a Pareto front", scene.source)
    seat_given_only(scene, "a Pareto front")
    if other != "motor_power":  # the front of the drive's motor sizes is the drive's own
        wheel_alone_only(scene, f"a Pareto front of mass and {other}")
    check_points(points)
    analysis = physics_analysis(scene)
    empty = pd.DataFrame()
    if other == "motor_power":
        if scene.drive is None:
            raise SceneError(
                "objectives",
                "a front of flywheel mass against motor power needs the scene's "
                "[drive] (the motor sizes to choose from)",
            )
    elif analysis.j_margin <= 0.0 and other != "delta":
        empty.attrs["message"] = f"no flywheel needed (J_F = {analysis.j_margin:.4g} kg·m²): nothing to trade"
        return empty
    if other == "outer_diameter":
        # the front's designs in one memory of neighbours (in this process): the lightest wheel (the scene's
        # envelope, the largest of all), then the ε points from the largest down, each warm-started from the one
        # before and spared the NLPs an earlier one proved infeasible with limits as loose or looser
        with neighbours():
            rows = _front_outer_diameter(scene, points, span, method, solver_options)
    elif other == "cost":
        rows = _front_cost(scene, method, solver_options)
    elif other == "motor_power":
        rows = _front_motor_power(scene, analysis, solver_options)
    else:
        rows = _front_delta(scene, points, span, method, solver_options)
    if rows.empty:
        rows.attrs["message"] = "no material and shaft can give the inertia anywhere on the range"
        return rows
    rows = rows.copy()
    rows["mass"] = np.where(rows["status"] == "not_needed", 0.0, rows["mass"])
    rows[other] = rows[
        {"outer_diameter": "d_outer", "cost": "cost", "delta": "delta", "motor_power": "rated_power"}[other]
    ]
    if other == "outer_diameter":
        rows[other] = np.where(rows["status"] == "not_needed", 0.0, rows[other])
    usable = rows["status"].isin(["designed", "not_needed"]).to_numpy()
    keep = non_dominated(np.where(usable, rows[other], np.nan), rows["mass"])
    front = rows[keep].sort_values([other, "mass"], kind="stable").reset_index(drop=True)
    front = normalize(front)  # the rows of single designs and of sweeps alike: nulls where no value
    front.attrs["objectives"] = list(objectives)
    front.attrs["evaluated"] = len(rows)
    return front


def _front_outer_diameter(
    scene: Scene,
    points: int,
    span: tuple[float, float] | None,
    method: Literal["auto", "closed_form", "ipopt"],
    solver_options: Mapping[str, Any] | None,
) -> pd.DataFrame:
    spec = scene.design
    if not isinstance(spec, DesignSpec):  # the loader always gives one
        raise TypeError(f"a Pareto front needs the scene's design spec, got {spec!r}")
    envelope = spec.max_outer_diameter
    if span is not None:  # checked before any solve
        low, high = span[0], min(span[1], envelope)  # a high end beyond the envelope is the envelope
        for end in (low, high):  # the rule of the field the front sweeps, named as the range
            if end > 0:
                check_magnitude(end, "range", f"{end:g} m", *LENGTH_RANGE, "m", f"{LENGTH_WHY}, as max_outer_diameter")
        if not 0 < low < high:  # one point (low = high) is no front: it gave an "empty front", exit 3
            raise SceneError("range", f"the outer diameter range {low:.6g}..{high:.6g} m is empty or not positive")
    lightest = evaluate_points(
        scene, pd.DataFrame({"point": [0], "design.objective": ["mass"]}), method=method, solver_options=solver_options
    )
    if span is None:
        if spec.geometry == "disc" and spec.max_width == math.inf:
            raise SceneError(
                "design.max_width",
                "a disc with no width limit can be made as "
                "small as one likes (thinner and wider): give max_width or a "
                "range for the outer diameter",
            )
        smallest = evaluate_points(
            scene, pd.DataFrame({"point": [1], "design.objective": ["outer_diameter"]}), solver_options=solver_options
        )
        if lightest["status"].iloc[0] != "designed" or smallest["status"].iloc[0] != "designed":
            return pd.DataFrame()
        low, high = float(smallest["d_outer"].iloc[0]), float(lightest["d_outer"].iloc[0])
        smallest = smallest.assign(epsilon=low)
        # the smallest wheel is the end of the front; the ε points start just above it,
        # where the lightest wheel under the cap exists without rounding doubts
        grid = np.geomspace(low, high, points)[1:] if high > low else np.array([])
    else:  # low and high as checked above
        grid = np.geomspace(low, high, points)
        smallest = None
    frames = [] if smallest is None else [smallest]
    if grid.size:
        # from the largest envelope down: each point's NLP only tightens D_outer <= ε, so an NLP IPOPT finds
        # infeasible at one ε shows the same NLP infeasible at every smaller one without a solve
        swept = sweep(  # serially: each point starts from its larger neighbour and its infeasibility proofs
            scene,
            {"design.max_outer_diameter": list(grid[::-1]), "design.objective": "mass"},
            method=method,
            solver_options=solver_options,
            workers=1,
        )
        swept = swept.iloc[::-1].reset_index(drop=True)
        swept["point"] = np.arange(len(swept))
        frames.append(swept.assign(epsilon=swept["design.max_outer_diameter"]))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def _front_cost(
    scene: Scene, method: Literal["auto", "closed_form", "ipopt"], solver_options: Mapping[str, Any] | None
) -> pd.DataFrame:
    inputs = design_inputs(scene)
    names = [m.name for m in inputs.materials]
    missing = [m.name for m in inputs.materials if m.cost is None]
    if missing:
        raise SceneError(
            "material",
            f"a mass-cost front needs a cost per kg on every "
            f"material; none is given for {', '.join(missing)} "
            f'(add cost = "... 1/kg" in [[material]])',
        )
    shafts = [s.name for s in inputs.shafts]
    swept = sweep(
        scene,
        {"material": names, "shaft": shafts, "design.objective": "mass"},
        method=method,
        solver_options=solver_options,
        workers=WORKERS,
    )
    return swept.assign(epsilon=swept["cost"])


def _front_motor_power(scene: Scene, analysis: Analysis, solver_options: Mapping[str, Any] | None) -> pd.DataFrame:
    """Every motor size of the drive with its lightest wheel (flyopt.drive.codesign, every size solved).

    ``mass`` is the flywheel's (0 where the motor needs none), ``rated_power``
    the motor's; the drive's own objective (motor plus wheel) is ``total_mass``.
    The inertias are named as a sweep's and ``solve``'s: ``j_flywheel`` the
    wheel's on its own shaft [kg*m^2], ``j_at_reference`` the same moved to the
    crank (J' r²), ``j_required`` the least the motor size needs at the crank
    for δ and its thermal limit (``MotorRun.j_flywheel``, the drive's ``j_required`` in ``--json``; 0 where it
    needs none).
    """
    from flyopt.drive.codesign import design_drive

    drive = design_drive(scene, analysis, solver_options=solver_options, every_size=True)
    rows = []
    for run in drive.runs:
        wheel = run.wheel
        status = "infeasible" if not run.feasible else ("designed" if wheel is not None else "not_needed")
        rows.append(
            {
                "motor": run.motor.name,
                "rated_power": run.motor.rated_power,
                "status": status,
                "mass": wheel.mass if wheel is not None else math.nan,
                "total_mass": run.total_mass if run.total_mass is not None else math.nan,
                "motor_ratio": run.motor_ratio if run.motor_ratio is not None else math.nan,
                "flywheel_ratio": run.flywheel_ratio if run.flywheel_ratio is not None else math.nan,
                "j_flywheel": wheel.j_flywheel if wheel is not None else math.nan,
                "j_at_reference": wheel.j_at_reference if wheel is not None else math.nan,
                "j_required": run.j_flywheel if run.j_flywheel is not None else math.nan,
                "limit": run.limit,
                "best_material": wheel.material if wheel is not None else None,
                "d_outer": wheel.dims.d_outer if wheel is not None else math.nan,
                "epsilon": run.motor.rated_power,
                "message": run.reason,
            }
        )
    return pd.DataFrame(rows)


def _front_delta(
    scene: Scene,
    points: int,
    span: tuple[float, float] | None,
    method: Literal["auto", "closed_form", "ipopt"],
    solver_options: Mapping[str, Any] | None,
) -> pd.DataFrame:
    if span is None:
        span = (scene.allowed_delta / 10.0, min(scene.allowed_delta * 10.0, 1.0))
    low, high = span
    for end in (low, high):  # the rule of machine.delta, named as the range
        if 0 < end < 2:
            check_delta(end, "range", f"{end:g}", "the δ range runs through the allowed values of machine.delta")
    if not 0 < low < high < 2:
        raise SceneError(
            "range", f"the δ range {low:.6g}..{high:.6g} must lie in (0, 2), its low end below its high one"
        )
    grid = np.geomspace(low, high, points)
    swept = sweep(
        scene,
        {"delta": list(grid), "design.objective": "mass"},
        method=method,
        solver_options=solver_options,
        workers=WORKERS,
    )
    return swept.assign(epsilon=swept["delta"])
