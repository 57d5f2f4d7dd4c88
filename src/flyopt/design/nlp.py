"""The design NLP of one combination: built once per structure with CasADi, solved by IPOPT.

The NLP of one combination (rim models, D_m free)::

    minimize    m = pi rho D_m H B                         (objective "mass")
    subject to  J'(D_m, H, B) >= J_F / r^2                 inertia
                D_m + H <= min(2 v_max / omega', D_env)     rim speed, envelope
                D_m - H >= 0                               inner diameter
                hb_min <= H / B <= hb_max                   H/B range
                B <= B_max                                 width (if set)

with J' = m D_m^2/4 (``thin_rim``) or m (D_m^2 + H^2)/4 (``rim``), and for a
disc J' = m D^2/8, m = pi rho D^2 B / 4 with D <= the same cap. Only what a
scene uses is built into its NLP: a pinned mean diameter removes D_m from the
variables (the outer and inner diameter limits become bounds on H), a
collapsed H/B range removes B, a missing width limit or envelope leaves no
trace, and a disc has no H/B constraint.

Scaling. IPOPT sees the logarithms of non-dimensional variables,

    D_m = L e^{x_d},   H = H_s e^{x_h},   B = B_s e^{x_b},

with L the outer-diameter cap (or the pinned diameter) and H_s, B_s the
thin-rim estimate at D_m = L, H/B = hb_min. Then x = 0 is a near-optimal start
for any J from 1e-6 to 1e6 kg*m^2 and any speed, mass and thin-rim inertia are
linear in x (the thin-rim and disc problems are convex), and positivity of
every dimension holds without bounds. The numbers that vary from scene to
scene enter as the parameter vector ``p`` and as bounds, so each NLP structure
is built once (:func:`get_model`) and reused. IPOPT's return status is
checked on every solve: a non-converged solve raises SolverFailed.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 5, 8, 9, 10 and
   worked example 6.
.. [2] A. Waechter and L. T. Biegler, "On the implementation of an
   interior-point filter line-search algorithm for large-scale nonlinear
   programming", Math. Program. 106 (2006) 25-57 (IPOPT).
.. [3] J. A. E. Andersson et al., "CasADi: a software framework for nonlinear
   optimization and optimal control", Math. Prog. Comp. 11 (2019) 1-36.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple

import casadi as ca

from flyopt.design import geometry
from flyopt.errors import BrokenInvariant, SolverFailed
from flyopt.names import Geometry, Objective

if TYPE_CHECKING:  # annotations only
    from flyopt.design.combination import Combination
    from flyopt.design.spec import DesignSpec

__all__ = [
    "DEFAULT_SOLVER_OPTIONS",
    "ModelStructure",
    "NlpModel",
    "get_model",
    "clear_model_cache",
    "solve_combination",
    "BUILDS",
    "CONVERGED",
    "WHEEL_SOLVER",
]

#: IPOPT statuses accepted as converged (the design is still verified).
CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")

#: The solver option that chooses the whole wheel's solver (flyopt.design.wheel_nlp: "ipopt" or
#: "sqpmethod"); not an nlpsol option, so it is taken out before a solver is built.
WHEEL_SOLVER = "flyopt.wheel_solver"

#: IPOPT silent: no banner, no iterations, no timings, and no CasADi warning of a NaN or Inf met on a trial
#: point (IPOPT answers it by a shorter step, or ends in a status that the caller checks): a warning of
#: CasADi's own printed to the terminal is not one of flyopt's lines (a disc whose hub ran to metres printed
#: "nlp_g failed: Inf detected" above a design once).
QUIET_IPOPT: dict[str, Any] = {
    "print_time": False,
    "show_eval_warnings": False,
    "ipopt.print_level": 0,
    "ipopt.sb": "yes",
}

#: Solver options, merged in this one place; explicit options passed to
#: design_flywheel(..., solver_options=...) win.
DEFAULT_SOLVER_OPTIONS = {
    **QUIET_IPOPT,
    "error_on_fail": False,
    "ipopt.tol": 1e-10,
    "ipopt.bound_relax_factor": 0.0,
    "ipopt.max_iter": 200,
}


class ModelStructure(NamedTuple):
    """What decides the shape of an NLP (its variables and constraints)."""

    geometry: str  # "rim" | "thin_rim" | "disc"
    pinned: bool  # d_mean given: D_m is not a variable
    collapsed: bool  # hb_min == hb_max: B is not a variable (rims only)
    objective: str  # "mass" | "outer_diameter" (cost ranks by mass times cost)


@dataclass
class NlpModel:
    """A built NLP: the ``casadi.nlpsol`` function and what it contains."""

    structure: ModelStructure
    solver: ca.Function
    variables: tuple[str, ...]  # physical names of the decision variables
    constraints: tuple[str, ...]  # names of the rows of g
    uses_p: bool
    build_time: float

    def describe(self) -> dict[str, Any]:
        """What the model is, for the report: geometry, objective, variables, constraint rows."""
        s = self.structure
        return {
            "geometry": s.geometry,
            "inertia_model": geometry.GEOMETRIES[s.geometry],
            "objective": s.objective,
            "variables": list(self.variables),
            "constraints": list(self.constraints),
            "pinned": ["d_mean"] if s.pinned else [],
            "formulation": (
                "IPOPT (CasADi nlpsol) on the logarithms of non-dimensional "
                "variables; numbers enter as parameters and bounds"
            ),
        }


_MODEL_CACHE: dict[Any, Any] = {}
#: How many NLPs have been built in this process (one per structure and solver options).
BUILDS = {"count": 0}

#: Weight of the tie-break term in the log-mass objective (see _build_model).
_TIE_BREAK = 1e-3


def clear_model_cache() -> None:
    """Forget every built NLP (the next design rebuilds them)."""
    _MODEL_CACHE.clear()


def _options_key(options):
    return tuple(sorted((k, repr(v)) for k, v in options.items()))


def get_model(structure: ModelStructure, solver_options: Mapping | None = None) -> NlpModel:
    """The NLP solver of one structure, built once and cached.

    Parameters
    ----------
    structure : ModelStructure
    solver_options : mapping, optional
        Options merged over :data:`DEFAULT_SOLVER_OPTIONS`.

    Returns
    -------
    NlpModel
        Holds the ``casadi.nlpsol`` function and the names of its variables
        and constraint rows.
    """
    return cached_model(_MODEL_CACHE, BUILDS, _build_model, structure, solver_options)


def cached_model(
    cache: dict[Any, Any],
    builds: dict[str, int],
    build: Callable[[Any, dict[str, Any]], Any],
    structure: Any,
    solver_options: Mapping | None = None,
    defaults: Mapping | None = None,
) -> Any:
    """The NLP of ``structure`` from ``cache``, built by ``build(structure, options)`` on first use.

    The one place where solver options are merged: :data:`DEFAULT_SOLVER_OPTIONS`, then the
    model's own ``defaults``, then the caller's ``solver_options``. A built NLP is kept per
    structure and options (``builds["count"]`` counts the builds); the textbook NLP and the
    whole wheel's (flyopt.design.wheel_nlp) share it.
    """
    options = dict(DEFAULT_SOLVER_OPTIONS)
    options.update(defaults or {})
    options.update(solver_options or {})
    key = (structure, _options_key(options))
    model = cache.get(key)
    if model is None:
        model = build(structure, options)
        cache[key] = model
        builds["count"] += 1
    return model


def _build_model(structure, options):
    """Build the NLP of one structure in log-scaled variables.

    Variables (present ones only): x_d = log(D_m/L), x_h = log(H/H_s),
    x_b = log(B/B_s); for a disc x_d = log(D/L). Parameter p = log(H_s/L)
    where a nonlinear term needs it. With the scales of :func:`_scales` the
    inertia row reads ``>= 0``.
    """
    start = time.perf_counter()
    options = {k: v for k, v in options.items() if k != WHEEL_SOLVER}  # the whole wheel's choice, not IPOPT's
    geo, pinned, collapsed, objective = structure
    names: list[str] = []
    cols = {}
    order = ["d_mean", "h", "b"] if geo != Geometry.DISC else ["diameter", "b"]
    for name in order:
        if name in ("d_mean", "diameter") and pinned:
            continue
        if name == "b" and geo != Geometry.DISC and collapsed:
            continue
        cols[name] = len(names)
        names.append(name)
    x = ca.SX.sym("x", len(names))

    def var(name):
        return x[cols[name]] if name in cols else 0.0

    g, g_names = [], []
    uses_p = False
    p = ca.SX.sym("p", 1)
    if geo == Geometry.DISC:
        xd, xb = var("diameter"), var("b")
        g.append(4.0 * xd + xb)
        g_names.append("inertia")
        if objective == Objective.MASS:
            f = 2.0 * xd + xb
        elif pinned:
            f = xb  # diameter fixed: pick the lightest disc of that diameter
        else:
            f = xd
    else:
        xd, xh = var("d_mean"), var("h")
        xb = xh if collapsed else var("b")
        # t = log(H/D_m) <= 0 by the inner-diameter constraint
        t = xh + p[0] - xd
        if geo == Geometry.RIM:
            uses_p = True
            g.append(3.0 * xd + xh + xb + ca.log1p(ca.exp(2.0 * t)))
        else:
            g.append(3.0 * xd + xh + xb)
        g_names.append("inertia")
        if not pinned:
            uses_p = True
            g.append(xd + ca.log1p(ca.exp(t)))  # log(D_outer / L)
            g_names.append("outer_diameter")
            g.append(xh - xd)  # log(H/D_m) - log(H_s/L)
            g_names.append("inner_diameter")
        if not collapsed:
            g.append(xh - xb)  # log(H/B) - log(hb_min)
            g_names.append("hb_ratio")
        if objective == Objective.MASS:
            f = xd + xh + xb
            if not pinned or (geo == Geometry.THIN_RIM and not collapsed):
                # Tie-break towards a thinner rim. With D_m pinned, the thin
                # rim's mass 4 J / D_m^2 does not depend on H at all: take the
                # thinnest of the equally light rims. With D_m free the
                # lightest rim is the thinnest one at the outer-diameter cap,
                # but its mass gains only ~2 H/D_m per unit of log H, which
                # leaves H loosely settled when H << D_m; the tie-break pulls
                # the same way, into the constraints that stop H, so the
                # optimum vertex (and its mass) is unchanged.
                f = f + _TIE_BREAK * xh
        elif pinned:
            f = xh  # D_outer = D_m + H, D_m fixed
        else:
            uses_p = True
            f = xd + ca.log1p(ca.exp(t))
    nlp = {"x": x, "f": f, "g": ca.vertcat(*g)}
    if uses_p:
        nlp["p"] = p
    name = "flywheel_" + "_".join(str(v) for v in structure)
    solver = ca.nlpsol(name, "ipopt", nlp, options)
    return NlpModel(
        structure=structure,
        solver=solver,
        variables=tuple(names),
        constraints=tuple(g_names),
        uses_p=uses_p,
        build_time=time.perf_counter() - start,
    )


def _scales(combo, spec):
    """Scales (L, H_s, B_s) [m] of the non-dimensional variables.

    L is the outer-diameter cap (or the pinned diameter). For rims, H_s and
    B_s = H_s / hb_min are the thin-rim wheel of D_m = L and H/B = hb_min that
    gives exactly J' (so the inertia row reads >= 0 and x = 0 starts near the
    optimum); for a disc H_s is None and B_s is the width of the disc of
    diameter L that gives J'.
    """
    rho, j = combo.material.density, combo.j_shaft
    length = combo.cap if combo.d_mean is None else combo.d_mean
    if spec.geometry == Geometry.DISC:
        b_s = 32.0 * j / (math.pi * rho * length**4)
        return length, None, b_s
    hb_min = spec.hb_ratio[0]
    h_s = math.sqrt(4.0 * j * hb_min / (math.pi * rho * length**3))
    return length, h_s, h_s / hb_min


def solve_combination(
    model: NlpModel, combo: Combination, spec: DesignSpec
) -> tuple[float, float, float, float, float, str, int, float]:
    """Solve one feasible combination by IPOPT, its status checked.

    Returns
    -------
    tuple
        ``(d_mean, h, b, mass, j_wheel, status, iterations, elapsed)`` [m, m, m, kg,
        kg*m^2, -, -, s]; the caller verifies the design against every constraint.

    Raises
    ------
    SolverFailed
        IPOPT stopped with an error or did not converge.
    """
    s = model.structure
    length, h_s, b_s = _scales(combo, spec)
    inf = math.inf
    n = len(model.variables)
    lbx, ubx, x0 = [-inf] * n, [inf] * n, [0.0] * n
    col = {name: i for i, name in enumerate(model.variables)}
    hb_min, hb_max = spec.hb_ratio
    p = []
    if s.geometry == Geometry.DISC:
        if "diameter" in col:
            ubx[col["diameter"]] = 0.0  # D <= cap = L
        if spec.max_width < math.inf:
            ubx[col["b"]] = math.log(spec.max_width / b_s)
        lbg, ubg = [0.0], [inf]
    else:
        log_eps = math.log(h_s / length)
        p = [log_eps]
        width_col = "h" if s.collapsed else "b"
        if spec.max_width < math.inf:
            ubx[col[width_col]] = math.log(spec.max_width / b_s)
        if s.pinned:
            if combo.d_mean is None:
                raise BrokenInvariant("a pinned structure is one whose combinations pin d_mean")
            room = min(combo.cap - combo.d_mean, combo.d_mean)
            ubx[col["h"]] = min(ubx[col["h"]], math.log(room / h_s))
        lbg, ubg = [0.0], [inf]
        if not s.pinned:
            lbg += [-inf, -inf]
            ubg += [0.0, -log_eps]
            x0[col["d_mean"]] = math.log1p(-min(h_s / length, 0.5))
        if not s.collapsed:
            lbg.append(0.0)
            ubg.append(math.log(hb_max / hb_min))
    x0 = [min(max(v, lo), hi) for v, lo, hi in zip(x0, lbx, ubx)]
    args = {"x0": x0, "lbx": lbx, "ubx": ubx, "lbg": lbg, "ubg": ubg}
    if model.uses_p:
        args["p"] = p
    start = time.perf_counter()
    try:
        sol = model.solver(**args)
    except RuntimeError as err:
        raise SolverFailed(f"{combo.label}: IPOPT stopped with an error ({err}); no design is reported") from err
    elapsed = time.perf_counter() - start
    stats = model.solver.stats()
    status = stats.get("return_status", "unknown")
    iterations = int(stats.get("iter_count", -1))
    if status not in CONVERGED:
        after = f" after {iterations} iterations" if 0 <= iterations <= 10**6 else ""
        failure = SolverFailed(
            f"{combo.label}: IPOPT did not converge (return status {status!r}{after}), "
            f"although the closed-form bound shows the "
            f"combination is feasible (it can give up to {combo.j_max:.3g} kg·m², "
            f"{combo.j_shaft:.3g} needed); no design is reported"
        )
        failure.status = status
        failure.combination = combo.label
        raise failure
    xs = [float(v) for v in sol["x"].full().ravel()]

    def value(name, default=0.0):
        return xs[col[name]] if name in col else default

    rho = combo.material.density
    if s.geometry == Geometry.DISC:
        d = length * math.exp(value("diameter"))
        b = b_s * math.exp(value("b"))
        d_mean = h = d / 2.0
        mass = geometry.disc_mass(d, b, rho)
        j_wheel = geometry.disc_inertia(mass, d)
    else:
        d_mean = length * math.exp(value("d_mean"))
        h = h_s * math.exp(value("h"))
        b = b_s * math.exp(value("h") if s.collapsed else value("b"))
        mass = geometry.rim_mass(d_mean, h, b, rho)
        j_wheel = geometry.wheel_inertia(s.geometry, rho, d_mean, h, b)
    return d_mean, h, b, mass, j_wheel, status, iterations, elapsed
