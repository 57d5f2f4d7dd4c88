"""The points of a sweep: a full-factorial grid, or Latin hypercube samples.

:func:`plan_sweep` turns the varied fields (see :mod:`flyopt.io.sweep_spec`)
into a table of points, one row per point, and refuses points whose design
settings are invalid before anything runs.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from flyopt.errors import SceneError
from flyopt.io.sweep_spec import (
    FIELDS,
    OPTION_MAXIMUMS,
    OPTION_MINIMUMS,
    SweepField,
    TooManyPoints,
    option_label,
    parse_vary,
    whole_number,
)
from flyopt.studies.points import check_points

if TYPE_CHECKING:  # the annotations only
    from flyopt.io.scene import Scene
    from flyopt.io.sweep_spec import Axis

__all__ = ["MAX_POINTS", "SweepPlan", "plan_sweep"]


#: Largest number of points a sweep may have.
MAX_POINTS = 20_000_000


@dataclass
class SweepPlan:
    """The points of a sweep: a DataFrame of inputs, one row per point.

    Attributes
    ----------
    axes : list of Axis
    points : pandas.DataFrame
        Column ``point`` and one column per axis (SI values, names, NaN for none).
    samples : int or None
        Latin hypercube sample count (None: full factorial grid).
    seed : int or None
        Seed of the Latin hypercube: the one given, or the one drawn when none
        was given (so that the samples can be made again); None for a grid.
    """

    axes: list[Axis]
    points: pd.DataFrame
    samples: int | None = None
    seed: int | None = None


def plan_sweep(
    scene: Scene,
    vary: Mapping[str, Any] | Iterable[str],
    *,
    samples: int | None = None,
    seed: int | None = None,
    where: str = "--vary",
    max_points: int = MAX_POINTS,
) -> SweepPlan:
    """The points of a sweep: a full-factorial grid, or Latin hypercube samples.

    Parameters
    ----------
    scene : Scene
    vary : mapping or iterable of str
        See :func:`flyopt.io.sweep_spec.parse_vary`.
    samples : int, optional
        Number of Latin hypercube samples; without it the full grid.
    seed : int, optional
        Seed of the Latin hypercube (a whole number >= 0). Without it one is
        drawn from the operating system's entropy and recorded in the plan.
    where : str
        Where ``vary`` comes from, for messages (``--vary``, ``sweep.vary``);
        ``samples`` and ``seed`` are named after it (``--samples``,
        ``sweep.samples``).
    max_points : int
        Most points a grid may have (:data:`MAX_POINTS`; the app's are fewer): more are refused by
        :class:`~flyopt.io.sweep_spec.TooManyPoints`, which says how many, before the grid is made.

    Returns
    -------
    SweepPlan

    Raises
    ------
    SceneError
        Bad fields or values, a bad sample count or seed, more than
        ``max_points`` points (refused before anything is allocated), or
        points whose design settings are invalid (e.g. an H/B range with
        min > max).

    Notes
    -----
    The samples are those of :class:`scipy.stats.qmc.LatinHypercube` with
    ``rng=seed``: each range is cut into ``samples`` equal strata (of the
    logarithm for a log range) with one sample in each; a list is sampled
    as categories, each equally often.
    """
    from flyopt.design.inputs import design_inputs, seat_given_only, single_design_only, wheel_alone_only

    single_design_only(design_inputs(scene).spec, "a sweep", scene.source)
    seat_given_only(scene, "a sweep")
    wheel_alone_only(scene, "a sweep")
    if seed is not None:
        seed = whole_number(seed, option_label(where, "seed"), OPTION_MINIMUMS["seed"], OPTION_MAXIMUMS["seed"])
        if samples is None:  # it would be dropped: a grid has no randomness
            raise SceneError(
                option_label(where, "seed"),
                f"seeds the Latin hypercube of {option_label(where, 'samples')}, which is not given: a grid has no "
                "randomness (give the samples too, or leave the seed out)",
            )
    if samples is not None:
        samples = whole_number(samples, option_label(where, "samples"), OPTION_MINIMUMS["samples"])
        if samples > MAX_POINTS:
            raise SceneError(
                option_label(where, "samples"), f"{samples} samples, more than the {MAX_POINTS} points a sweep may have"
            )
        if seed is None:
            seed = _drawn_seed()
    axes = parse_vary(scene, vary, where=where, samples=samples, max_points=max_points)
    if any(axis.field == "torque.scale" for axis in axes):
        from flyopt.io.sweep_spec import field_path
        from flyopt.studies.points import check_scalable

        check_scalable(scene, field_path(where, "torque.scale"))
    if samples is not None:
        if not axes:
            raise SceneError(option_label(where, "samples"), "Latin hypercube sampling needs at least one varied field")
        from scipy.stats import qmc

        unit = qmc.LatinHypercube(d=len(axes), rng=seed).random(samples)
        columns = {}
        for k, axis in enumerate(axes):
            u = unit[:, k]
            if axis.kind == "range":
                low, high = axis.ends()
                if axis.log:
                    lo, hi = math.log(low), math.log(high)
                    columns[axis.field] = np.exp(lo + u * (hi - lo))
                else:
                    columns[axis.field] = low + u * (high - low)
            else:
                index = np.minimum((u * len(axis.values)).astype(int), len(axis.values) - 1)
                columns[axis.field] = np.asarray(axis.values, dtype=object)[index]
        n = samples
    else:
        n = math.prod(len(a.values) for a in axes)
        if n > max_points:  # before the grid is made
            raise TooManyPoints(
                n,
                where,
                f"the grid has {n} points, more than the {max_points} a "
                f"sweep may have; use fewer values or Latin hypercube samples",
            )
        columns = {}
        if axes:
            grids = np.meshgrid(*[np.arange(len(a.values)) for a in axes], indexing="ij")
            for axis, index in zip(axes, grids):
                columns[axis.field] = np.asarray(axis.values, dtype=object)[index.ravel()]
    points = pd.DataFrame({"point": np.arange(n, dtype=np.int64)})
    for axis in axes:
        values = columns[axis.field]
        if FIELDS.get(axis.field, SweepField("number")).kind == "name":
            points[axis.field] = np.asarray(values, dtype=object)
        else:
            points[axis.field] = np.asarray(values, dtype=float)
    check_points(scene, points, where)
    return SweepPlan(axes=axes, points=points, samples=samples, seed=seed)


def _drawn_seed() -> int:
    """A fresh seed from the operating system's entropy, in 0 <= seed < 2**63 (an int64)."""
    # a SeedSequence made without entropy draws an int; numpy's stubs give the type of any entropy argument
    return int(np.random.SeedSequence().entropy % 2**63)  # type: ignore[operator]
