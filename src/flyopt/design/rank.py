"""The one ranking rule of designs: which material x shaft combination wins.

``flyopt solve`` ranks the combinations of one scene, ``flyopt sweep``,
``pareto`` and ``tradeoff`` pick the winner of each of many points; all of
them call :func:`winners`, so they cannot name different winners.

The rule, applied to the feasible designs of one point:

1. the objective of the scene (mass, cost or outer diameter), lowest first;
2. then the cost (mass times cost per kg; a material with no cost counts as
   dearer than any with one);
3. then the mass;
4. then the rim speed (the lower hoop stress, ρ v²);
5. then the material's name, then the shaft's name (alphabetical).

At each numeric step, values within :data:`TIE_RTOL` (relative) of the
lowest count as equal and go on to the next step. Such ties are exact in the
mathematics and common: a disc at its envelope weighs m = 8 J / D² whatever
its density, so cast iron and cast steel tie; without a tolerance, round-off
would pick the winner, and two computations of the same design (IPOPT and the
closed form, or a scalar and a vectorized one) could pick differently. The
tolerance is far above round-off (1e-16) and far below any difference an
engineer would act on; the closed form and IPOPT agree to 1e-6 in mass, so a
tie decided by IPOPT's last digits is left to the later steps only when the
two designs are the same wheel to 1e-9.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:  # annotations only
    from flyopt.design.result import Design

__all__ = ["TIE_RTOL", "winners", "ranking"]

#: Objectives (and costs, masses, rim speeds) within this relative distance rank as equal.
TIE_RTOL = 1e-9
#: Up to this many designs of one point the rule runs in plain Python (numpy's per-call cost dominates).
_FEW = 64


def _numeric(values, n):
    out = np.asarray(values, dtype=float).reshape(n) if n else np.zeros(0)
    return np.where(np.isnan(out), np.inf, out)


def winners(
    group: ArrayLike,
    objective: ArrayLike,
    cost: ArrayLike,
    mass: ArrayLike,
    rim_speed: ArrayLike,
    material: ArrayLike,
    shaft: ArrayLike,
    n_groups: int | None = None,
) -> NDArray[np.int64]:
    """The winning design of each group (point) by the ranking rule of this module.

    Parameters
    ----------
    group : array_like of int
        The group (sweep point) of each feasible design, 0 ... n_groups - 1.
    objective, cost, mass, rim_speed : array_like of float
        Per design: the objective's value, the cost (NaN where the material has
        none), the mass [kg] and the rim speed [m/s].
    material, shaft : array_like of str
        Names, for the last step of the rule.
    n_groups : int, optional
        Number of groups (default: max(group) + 1).

    Returns
    -------
    ndarray of int
        For each group, the index (into the arrays) of its winner; -1 for a
        group with no design.
    """
    group = np.asarray(group, dtype=np.int64)
    n = group.size
    if n_groups is None:
        n_groups = int(group.max()) + 1 if n else 0
    if n_groups == 1 and 0 < n <= _FEW:  # one point with a few designs (a solve's ranking)
        return np.array([_winner_of_few(objective, cost, mass, rim_speed, material, shaft)], dtype=np.int64)
    alive = np.ones(n, dtype=bool)
    for key in (objective, cost, mass, rim_speed):
        values = np.where(alive, _numeric(key, n), np.inf)
        lowest = np.full(n_groups, np.inf)
        np.minimum.at(lowest, group, values)
        with np.errstate(invalid="ignore"):
            alive &= values <= lowest[group] * (1.0 + TIE_RTOL)
    best = np.full(n_groups, -1, dtype=np.int64)
    index = np.flatnonzero(alive)
    if index.size:
        _, material_code = np.unique(np.asarray(material, dtype=str)[index], return_inverse=True)
        _, shaft_code = np.unique(np.asarray(shaft, dtype=str)[index], return_inverse=True)
        order = index[np.lexsort((shaft_code.ravel(), material_code.ravel(), group[index]))]
        first = np.unique(group[order], return_index=True)[1]
        best[group[order[first]]] = order[first]
    return best


def _winner_of_few(objective, cost, mass, rim_speed, material, shaft):
    """The rule of :func:`winners` for one point in plain Python (numpy's per-call cost dominates there).

    The same steps in the same order: NaN counts as inf, each numeric key keeps
    the designs within TIE_RTOL of its lowest, then the names decide.
    """
    alive: Sequence[int] = range(len(material))
    for key in (objective, cost, mass, rim_speed):
        values = [math.inf if v is None or v != v else float(v) for v in key]
        lowest = min(values[k] for k in alive)
        alive = [k for k in alive if values[k] <= lowest * (1.0 + TIE_RTOL)]
    return min(alive, key=lambda k: (str(material[k]), str(shaft[k])))


def ranking(candidates: Iterable[Design]) -> list[Design]:
    """Feasible candidates of one point, best first, by the rule of :func:`winners`.

    Parameters
    ----------
    candidates : sequence of flyopt.design.result.Design
        Feasible designs (``objective``, ``cost``, ``mass``, ``rim_speed``,
        ``material``, ``shaft``).

    Returns
    -------
    list
        The same candidates, best first.
    """
    left = list(candidates)
    order = _clearly_apart(left)
    if order is not None:
        return [left[k] for k in order]
    ordered = []
    while left:
        k = _winner_of_few(
            [c.objective for c in left],
            [c.cost for c in left],
            [c.mass for c in left],
            [c.stresses.rim_speed for c in left],
            [c.material for c in left],
            [c.shaft for c in left],
        )
        ordered.append(left.pop(k))
    return ordered


def _clearly_apart(candidates):
    """The order of the rule when every objective is positive and beyond TIE_RTOL of the next one; else None.

    Then each step of :func:`ranking` has one design within TIE_RTOL of the
    lowest objective, which wins on the first step of the rule: the order is
    the objectives' order, found by one sort instead of a pick per place.
    """
    values = [c.objective for c in candidates]
    if any(v is None or not 0.0 < v < math.inf for v in values):
        return None
    order = sorted(range(len(values)), key=values.__getitem__)
    for k, next_k in zip(order, order[1:]):
        if not values[next_k] > values[k] * (1.0 + TIE_RTOL):
            return None
    return order
