"""J_F against δ: the scene sized again at other δ by its own model (the J_F–δ diagram, the report).

The δ at which it is computed (:func:`delta_range`) are decided here, once:
:func:`flyopt.report.plots.plot_inertia_delta` draws its axis from the same
rule, and :func:`flyopt.pipeline.solve` computes the curve when a reader asks
for it (``extras=("inertia_curve",)``).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene


def flywheel_at_some_delta(analysis: Analysis) -> bool:
    """Whether J_F(δ) has anything to show: False for a steady machine of constant inertia (A_max = 0 J,
    torques of the angle only), which needs no flywheel at any δ."""
    machine = analysis.machine
    return analysis.a_max > 0 or (machine is not None and (machine.variable_inertia or machine.speed_dependent))


def delta_range(analysis: Analysis, points: int = 41) -> np.ndarray:
    """The δ at which J_F(δ) is drawn: log-spaced about the scene's δ, the scene's δ itself among them.

    From a fifth of the smaller of the scene's δ and δ* (where J_F reaches 0;
    the constant-inertia estimate A_max/(ω_m² J_e,mean) for the others) to five
    times the scene's δ, at most 0.5 (the classical table of
    docs/flywheel-design.md, section 2, ends at 1/5) unless the scene's δ is
    larger.
    """
    j_mean = analysis.machine.j_mean() if analysis.machine is not None else analysis.j_constant
    free = analysis.a_max / (analysis.omega_mean**2 * j_mean) if j_mean > 0 and analysis.a_max > 0 else math.inf
    lo = min(analysis.delta, free) / 5.0
    hi = min(5.0 * analysis.delta, max(0.5, 1.5 * analysis.delta), 1.9)
    return np.union1d(np.geomspace(lo, hi, points), [analysis.delta])


def inertia_curve(scene: Scene, analysis: Analysis, deltas: ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """J_F at each δ by the analysis' own model: the scene analysed again at that δ.

    With a variable inertia or a speed-dependent torque, J_F is not
    A_max/(ω_m² δ) − J_c (docs/flywheel-design.md, sections 6 and 7): each
    δ is a new sizing by the exact model. The reduced machine and its
    compiled models are reused (``analyse(..., like=analysis)``).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    deltas : sequence of float, optional
        δ [-], each in (0, 2). By default those of :func:`delta_range` (41;
        25 for the dynamic model, whose every point is a periodic solution),
        and where J_F falls to zero between two of them (δ*, where the
        machine's own inertia starts to suffice, and the curve is steep)
        eight more between those two.

    Returns
    -------
    (ndarray, ndarray)
        δ and J_F there (``j_margin``: negative where none is needed)
        [kg*m^2]; NaN where the model has no answer at that δ (the periodic
        solution stalls, say).
    """
    import dataclasses

    from flyopt.analysis import analyse
    from flyopt.errors import SolverFailed
    from flyopt.names import Model

    if deltas is None:
        delta, j = inertia_curve(scene, analysis, delta_range(analysis, 25 if analysis.model == "dynamic" else 41))
        falls = np.flatnonzero((j[:-1] > 0) & (j[1:] <= 0))
        if len(falls):
            k = falls[0]
            more = inertia_curve(scene, analysis, np.geomspace(delta[k], delta[k + 1], 10)[1:-1])
            order = np.argsort(np.concatenate([delta, more[0]]))
            return np.concatenate([delta, more[0]])[order], np.concatenate([j, more[1]])[order]
        return delta, j
    deltas = np.asarray(deltas, dtype=float)
    j = np.full(deltas.shape, np.nan)
    for k, delta in enumerate(deltas):
        if analysis.stall_sets_flywheel_at(float(delta)):
            # a search at each would locate that limit again, some 10 s a δ
            j[k] = analysis.j_margin
            continue
        try:
            j[k] = analyse(
                dataclasses.replace(scene, delta=float(delta)), Model(analysis.model), like=analysis
            ).j_margin
        except SolverFailed:
            continue
    return deltas, j
