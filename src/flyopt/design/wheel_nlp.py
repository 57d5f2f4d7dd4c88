"""The design NLP of a whole wheel: every dimension chosen by one NLP, every part counted and checked.

One NLP per structure (:class:`WheelStructure`: the geometry, the criterion,
ductile or brittle, a bore or not, the arm count, which limits are set, the
objective), built once with CasADi and cached; the numbers of a combination
(required inertia, speed, density, Poisson's ratio, torque, bore, the
allowable stress of each part) enter as parameters and bounds::

    minimize    log m(x)            (every part: rim, web or arms, hub)   objective "mass"/"cost"
           or   log D_outer                                               objective "outer_diameter"
    subject to  log J(x) >= log J'                                  inertia, every part counted
                D_outer <= D_env                                    envelope
                omega' D_outer / 2 <= v_max                        rim speed   (criterion "rim_speed")
                sigma(x) <= sigma_allow of its part at K radii of  stress      (criterion "stress")
                           every disc part (von Mises^2 for ductile materials, sigma_r and
                           sigma_t for brittle ones); the rim and arms of rim_arms by the texts' beams
                B, l_hub <= B_max;  hb_min <= H/B <= hb_max;  D_m = pinned
                H, B, t_web, arm minor axis, hub wall >= min_wall
                every wall >= the process's min_wall(D)              castability (section 23)
                1/r <= t_eq(a) / t_eq(b) <= r at each junction (a, b)  castability (section 23)
                hub diameter and length within the textbook proportions and long enough for the key
                t_web <= B, t_web <= l_hub;  the rim clears the hub;  n arms fit round the hub

Solved by CasADi's sqpmethod (its QPs by DAQP) with IPOPT behind it wherever the SQP
does not converge, or by IPOPT alone (:data:`SOLVER_OPTION`); either way the
return status is checked before a wheel is used.

The variables are the logarithms of the dimensions in metres, so every
dimension stays positive and mm and m sit side by side at order one. A
stress row is divided by S = rho omega'^2 r_s^2 (r_s a length of the
wheel), so it too is of order one.

The sampled stress rows (:data:`SAMPLES` radii per part) are checked after
the solve by the exact maxima (:mod:`flyopt.design.strength`); where a peak
between samples exceeds the allowable, the designer tightens that part's
row and solves again.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 9, 10 and 13.
.. [2] A. Waechter and L. T. Biegler, Math. Program. 106 (2006) 25-57 (IPOPT).
.. [3] J. Nocedal and S. J. Wright, Numerical Optimization, 2nd ed., Springer 2006, ch. 18 (SQP).
"""

from __future__ import annotations

import math
import time
import zlib
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import casadi as ca

from flyopt.design import castability, wheel
from flyopt.design.nlp import CONVERGED, WHEEL_SOLVER, cached_model
from flyopt.errors import SolverFailed
from flyopt.names import Criterion, Geometry, Objective

__all__ = [
    "WheelStructure",
    "WheelProblem",
    "WheelSolution",
    "SAMPLES",
    "get_model",
    "solve",
    "BUILDS",
    "variables_of",
    "dims_of",
    "starting_wheel",
]

#: Radii per disc part where the NLP writes the stress rows, as fractions of its radial extent.
SAMPLES = (0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0)

#: How many wheel NLPs this process has built.
BUILDS = {"count": 0}
_CACHE: dict = {}

#: Parameters of every wheel NLP, in order.
PARAMETERS = ("omega", "density", "poisson", "torque", "bore", "stress_scale", "log_half_omega")


class WheelStructure(NamedTuple):
    """What decides the shape of a wheel NLP."""

    geometry: str
    criterion: str  # "rim_speed" | "stress"
    ductile: bool
    bored: bool  # a bore (else a solid centre; rim and thin_rim have neither)
    n_arms: int  # rim_arms only (0 otherwise)
    envelope: bool  # an outer-diameter limit is set
    width: bool  # an axial width limit is set
    pinned: bool  # D_m pinned
    objective: str  # "mass" | "outer_diameter"
    castability: castability.Rules | None = None  # the process's rules (whole wheels only), None: none
    disc_hub: bool = False  # a bored disc stands on a hub (design.disc_hub); else an annulus on its bore

    @property
    def has_hub(self) -> bool:
        """Whether the wheel has a hub: web and arms wheels on a bore, a disc on a bore asked to have one."""
        if self.geometry == Geometry.DISC:
            return self.bored and self.disc_hub
        return self.bored and self.geometry in (Geometry.RIM_WEB, Geometry.RIM_ARMS)


def variables_of(structure: WheelStructure) -> tuple[str, ...]:
    """The dimensions IPOPT chooses for a structure, in order."""
    geo = structure.geometry
    if geo == Geometry.DISC:
        return ("d_outer", "b", "d_hub", "l_hub") if structure.has_hub else ("d_outer", "b")
    names = ["d_outer", "h", "b"]
    if geo == Geometry.RIM_WEB:
        names.append("t_web")
        if structure.bored:
            names += ["d_hub", "l_hub"]
    elif geo == Geometry.RIM_ARMS:
        names += ["arm_major", "d_hub", "l_hub"]
    return tuple(names)


def dims_of(structure: WheelStructure, values: Mapping[str, Any], bore: float) -> wheel.Dims:
    """A wheel's Dims from its variables (floats or symbols) by name [m]."""
    v = dict(values)
    geo = structure.geometry
    if geo == Geometry.DISC:
        bore = bore if structure.bored else 0.0
        return wheel.Dims(
            d_outer=v["d_outer"],
            h=(v["d_outer"] - bore) / 2.0,
            b=v["b"],
            bore=bore,
            d_hub=v.get("d_hub", 0.0),
            l_hub=v.get("l_hub", 0.0),
        )
    return wheel.Dims(
        d_outer=v["d_outer"],
        h=v["h"],
        b=v["b"],
        bore=bore if structure.bored else 0.0,
        t_web=v.get("t_web", 0.0),
        d_hub=v.get("d_hub", 0.0),
        l_hub=v.get("l_hub", 0.0),
        arm_major=v.get("arm_major", 0.0),
        n_arms=structure.n_arms,
    )


def stressed_parts(structure: WheelStructure) -> tuple[str, ...]:
    """The parts whose stress the NLP limits, in the order of the allowable-stress parameters."""
    geo = structure.geometry
    if geo == Geometry.DISC:
        return ("hub", "disc") if structure.has_hub else ("disc",)
    if geo in (Geometry.RIM, Geometry.THIN_RIM):
        return ("rim",)
    if geo == Geometry.RIM_WEB:
        return ("hub", "web", "rim") if structure.bored else ("web", "rim")
    return ("hub", "arms", "rim")


@dataclass
class WheelModel:
    """A built wheel NLP."""

    structure: WheelStructure
    solver: ca.Function
    variables: tuple[str, ...]
    constraints: tuple[str, ...]  # names of the rows of g
    stress_parts: tuple[str, ...]  # which part each allowable parameter belongs to
    build_time: float
    fast: ca.Function | None = None  # sqpmethod, tried before IPOPT (SOLVER_OPTION "sqpmethod", the default)
    rows: ca.Function | None = None  # g(x, p): the rows at a point (a warm start's multipliers are projected on them)
    #: The multipliers of this NLP's last converged sqpmethod solves, by their wheel (:func:`_wheel_key`):
    #: (lam_x, lam_g), a warm start's duals (:func:`solve`); at most :data:`DUALS_KEPT`.
    duals: dict[tuple[float, ...], tuple[list[float], list[float]]] = field(default_factory=dict)

    def describe(self) -> dict[str, Any]:
        """What the model is, for the report: geometry, objective, variables, constraint rows."""
        s = self.structure
        return {
            "geometry": s.geometry,
            "criterion": s.criterion,
            "objective": s.objective,
            "variables": list(self.variables),
            "constraints": sorted(set(self.constraints)),
            "pinned": ["d_mean"] if s.pinned else [],
            "formulation": (
                f"{'sqpmethod (DAQP), IPOPT where it fails' if self.fast is not None else 'IPOPT'} "
                "(CasADi nlpsol) on the logarithms of the dimensions; every part "
                "counted in J and mass; stresses by the stepped-disc solution at "
                f"{len(SAMPLES)} radii per part, verified by the exact maxima"
            ),
        }


#: Solver options of the wheel NLP over flyopt.design.nlp.DEFAULT_SOLVER_OPTIONS. A feasible wheel
#: converges in 10-60 iterations, but IPOPT can need several hundred to call a wheel NLP locally
#: infeasible (a rim_web whose hub, key and stress leave no room: 200 iterations ran out on one of
#: tests/design/test_prune.py's random problems, which IPOPT then proves infeasible within 1000).
WHEEL_SOLVER_OPTIONS = {"ipopt.max_iter": 1000}

#: The solver option that chooses the whole wheel's solver: "sqpmethod" (the default), CasADi's SQP
#: with the dense active-set QP solver DAQP (:data:`QP_SOLVER`), its status checked, and IPOPT on the same
#: NLP wherever it does not converge (IPOPT also proves a wheel infeasible, which an SQP cannot), so it answers every
#: wheel IPOPT answers; or "ipopt", IPOPT alone: the reference the tests hold sqpmethod to
#: (tests/design/test_wheel_nlp.py: the objective to 1e-9 on random wheels of every structure, the
#: shipped scenes' designs to 1e-8). sqpmethod is the default since castability (issue 28) gave each
#: whole wheel one optimum: before it, a rim whose H traded against its web at the same mass let the
#: two solvers stop at different wheels; now they stop at the same one (benchmarks/results/wheel.md:
#: several times faster per solve). Not an nlpsol option: it is taken out before IPOPT is built (here
#: and in flyopt.design.nlp).
SOLVER_OPTION = WHEEL_SOLVER

#: The whole wheel's solver where the options do not choose one (:data:`SOLVER_OPTION`).
DEFAULT_SOLVER = "sqpmethod"

#: sqpmethod's QP solver for the wheel NLP: DAQP, a dual active-set method for small dense QPs (CasADi's
#: daqp plugin, in CasADi's wheels since 3.7). On punch-press-wheel's δ sweep it solves each QP in about 0.01 ms
#: against qrqp's 0.27 ms (three QPs a warm solve: most of the solve before; benchmarks/results/wheel.md). It is
#: not strictly as robust: of 200 random wheels solved cold 159 converged against qrqp's 154, and two that qrqp
#: solved now go on to IPOPT, which answers them as before.
#: Its tolerances are set below sqpmethod's 1e-10, so a QP never takes as met a row the SQP does not; and
#: its zero_tol (what it takes for zero in its factorisation and steps) to 1e-15: at DAQP's default the
#: grey-iron arms wheel's SQP stalled with one row 4.8e-10 off its bound, step after step, until its 100
#: iterations (12 of a 40-point sweep's 94 solves), where qrqp met it to 4e-16.
QP_SOLVER = "daqp"
QP_OPTIONS: dict[str, Any] = {
    "error_on_fail": False,
    "daqp": {"primal_tol": 1e-14, "dual_tol": 1e-14, "zero_tol": 1e-15},
}

#: The smallest eigenvalue sqpmethod leaves in its Hessian (eigen-clip; CasADi's default 1e-7). DAQP works
#: on the Cholesky factor of the Hessian, whose condition then reached 1e7 and more: its multipliers carried
#: errors of 1e-9, and the SQP, which asks 1e-10 of stationarity, ended in Search_Direction_Becomes_Too_Small
#: or its 100 iterations on nearly every wheel (573 of a sweep's 580 solves). The Hessian of log mass in the
#: logarithms of the dimensions is of order one, so 1e-4 raises only its near-null directions: the converged
#: wheel is the same KKT point (the objectives to 1e-11 of qrqp's on the sweep), it only changes the path.
CONVEXIFY_MARGIN = 1e-4

#: sqpmethod stops with Search_Direction_Becomes_Too_Small below this step (CasADi's default 1e-10). A
#: step of 1e-12 is what the last iterations take while the multipliers settle to the 1e-10 asked of them;
#: stopping there (half the warm-started solves of a sweep) sent the wheel to a cold solve or IPOPT. Its
#: own tests (rows and stationarity to 1e-10, :func:`_solve_fast`'s complementarity) still decide.
MIN_STEP = 1e-16

#: sqpmethod's options for the wheel NLP: exact Hessian clipped to positive definite (the QP must be
#: convex), the rows met to 1e-10 as IPOPT's tol.
SQP_OPTIONS: dict[str, Any] = {
    "print_time": False,
    "error_on_fail": False,
    "print_header": False,
    "print_iteration": False,
    "print_status": False,
    "show_eval_warnings": False,  # a NaN on a trial step is its failure, which IPOPT then answers
    "qpsol": QP_SOLVER,
    "qpsol_options": QP_OPTIONS,
    "convexify_strategy": "eigen-clip",
    "convexify_margin": CONVEXIFY_MARGIN,
    "min_step_size": MIN_STEP,
    "max_iter": 100,
    "tol_pr": 1e-10,
    "tol_du": 1e-10,
}


def get_model(structure: WheelStructure, solver_options: Mapping | None = None) -> WheelModel:
    """The wheel NLP of a structure, built once per structure and solver options."""
    return cached_model(_CACHE, BUILDS, _build, structure, solver_options, WHEEL_SOLVER_OPTIONS)


class Formulation(NamedTuple):
    """A wheel NLP's symbols: its dimensions, mass, inertia, objective and constraint rows (named)."""

    dims: wheel.Dims
    mass: Any  # CasADi expressions
    inertia: Any
    objective: Any
    rows: tuple[Any, ...]
    row_names: tuple[str, ...]


def formulate(structure: WheelStructure, x: Any, par: Mapping[str, Any], allow: Any) -> Formulation:
    """The wheel NLP of a structure in CasADi symbols (:class:`Formulation`).

    Parameters
    ----------
    structure : WheelStructure
    x : casadi.SX
        The logarithms of the dimensions [ln m], in the order of :func:`variables_of`.
    par : mapping
        Each name of :data:`PARAMETERS` to a symbol or an expression: the
        wheel NLP's own parameters, or (:mod:`flyopt.drive.relaxation`) the
        shaft speed as an expression of the drive's variables.
    allow : casadi.SX
        The allowable of each part of :func:`stressed_parts`, (sigma_a / S)^2 if ductile, else sigma_a / S.

    The rows' bounds are :func:`row_bounds`'.
    """
    names = variables_of(structure)
    stress_parts = stressed_parts(structure)
    dims = dims_of(structure, {n: ca.exp(x[k]) for k, n in enumerate(names)}, par["bore"])
    density = par["density"]
    parts = wheel.parts(structure.geometry, dims, density)
    mass = wheel.wheel_mass(parts)
    inertia = wheel.wheel_inertia(parts)
    col = {n: x[k] for k, n in enumerate(names)}
    rows, row_names = [], []

    def row(name, expr):
        rows.append(expr)
        row_names.append(name)

    row("inertia", ca.log(inertia))
    if structure.envelope:
        row("max_outer_diameter", col["d_outer"])
    if structure.criterion == Criterion.RIM_SPEED:
        row("rim_speed", col["d_outer"] + par["log_half_omega"])
    if structure.width:
        row("max_width", col["b"])
        if "l_hub" in col:
            row("max_width_hub", col["l_hub"])
    if structure.geometry != Geometry.DISC:
        row("hb_ratio", col["h"] - col["b"])
        # the rim clears the hub (or is a ring whose inner diameter stays positive)
        inner = dims.d_inner
        row("inner_diameter", inner / dims.d_outer)
        if "d_hub" in col:
            row("rim_clears_hub", (inner - dims.d_hub) / dims.d_outer)
    elif "d_hub" in col:
        row("disc_clears_hub", (dims.d_outer - dims.d_hub) / dims.d_outer)
        row("disc_below_hub", col["b"] - col["l_hub"])  # the hub at least as long as the disc is wide
    else:
        row("bore_clear", (dims.d_outer - par["bore"]) / dims.d_outer)
    if structure.pinned:
        row("d_mean", ca.log(dims.d_mean))
    if "t_web" in col:
        row("web_below_rim", col["t_web"] - col["b"])
        if "l_hub" in col:
            row("web_below_hub", col["t_web"] - col["l_hub"])
    if "arm_major" in col:
        minor = wheel.ARM_MINOR_RATIO * dims.arm_major
        row("arms_fit_hub", structure.n_arms * dims.arm_major / (math.pi * dims.d_hub))
        row("arm_within_rim", ca.log(minor) - col["b"])
        row("arm_within_hub", ca.log(minor) - col["l_hub"])
    if "d_hub" in col:
        row("hub_wall", (dims.d_hub - par["bore"]) / 2.0)  # >= min_wall
    if structure.castability is not None:
        _castability_rows(structure, dims, row)
    if structure.criterion == Criterion.STRESS:
        scale = par["stress_scale"]
        samples = wheel.stress_samples(
            structure.geometry, dims, density, par["poisson"], par["omega"], par["torque"], SAMPLES
        )
        for part, _r, sr, st in samples:
            k = stress_parts.index(part)
            if structure.ductile:
                row(f"stress_{part}", (sr * sr - sr * st + st * st) / (scale * scale) / allow[k])
            else:
                row(f"stress_{part}", sr / scale / allow[k])
                row(f"stress_{part}", st / scale / allow[k])
    objective = col["d_outer"] if structure.objective == Objective.OUTER_DIAMETER else ca.log(mass)
    return Formulation(dims, mass, inertia, objective, tuple(rows), tuple(row_names))


def _castability_rows(structure, dims, row):
    """The castability rows of a whole wheel (:mod:`flyopt.design.castability`), each of order one and named
    by its part: ``castability_min_wall_<part>`` log(wall / min_wall(D)) >= 0, and
    ``castability_<a>_<b>_ratio`` log(t_eq(a) / t_eq(b)) within +-log r (:func:`row_bounds`)."""
    rules, geo = structure.castability, structure.geometry
    if rules.min_wall:
        log_wall = ca.log(castability.min_wall_at(rules, dims.d_outer, ca.fmin, ca.fmax))
        for part, wall in castability.walls(geo, dims):
            row(f"castability_min_wall_{part}", ca.log(wall) - log_wall)
    if math.isfinite(rules.section_ratio):
        t_eq = castability.sections(geo, dims)
        for a, b in castability.junctions(geo, structure.has_hub):
            row(f"castability_{a}_{b}_ratio", ca.log(t_eq[a]) - ca.log(t_eq[b]))


def _build(structure, options):
    start = time.perf_counter()
    options = dict(options)
    choice = options.pop(SOLVER_OPTION, DEFAULT_SOLVER)
    if choice not in ("ipopt", "sqpmethod"):
        raise ValueError(f"{SOLVER_OPTION} is 'ipopt' or 'sqpmethod', not {choice!r}")
    names = variables_of(structure)
    x = ca.SX.sym("x", len(names))
    p = ca.SX.sym("p", len(PARAMETERS))
    stress_parts = stressed_parts(structure)
    allow = ca.SX.sym("allow", len(stress_parts))  # (sigma_allow / S) per part, squared if ductile
    form = formulate(structure, x, {name: p[k] for k, name in enumerate(PARAMETERS)}, allow)
    nlp = {"x": x, "p": ca.vertcat(p, allow), "f": form.objective, "g": ca.vertcat(*form.rows)}
    name = "wheel_" + "_".join(str(v) for f, v in zip(structure._fields, structure, strict=True) if f != "castability")
    if structure.castability is not None:  # a function's name takes letters, digits and _ only
        name += f"_{structure.castability.process}_{zlib.crc32(repr(structure.castability).encode())}"
    solver = ca.nlpsol(name, "ipopt", nlp, options)
    fast = ca.nlpsol(name + "_sqp", "sqpmethod", nlp, SQP_OPTIONS) if choice == "sqpmethod" else None
    rows = ca.Function(name + "_rows", [x, nlp["p"]], [nlp["g"]]) if fast is not None else None
    return WheelModel(structure, solver, names, form.row_names, stress_parts, time.perf_counter() - start, fast, rows)


@dataclass(frozen=True)
class WheelProblem:
    """The numbers of one combination (SI).

    ``allowable`` maps each stressed part to its allowable stress [Pa];
    ``min_wall``, the hub bounds and ``l_hub_min`` (the key's) are lower
    bounds [m]; ``d_hub_range`` and ``l_hub_range`` the textbook proportions;
    ``caps`` upper bounds on chosen dimensions (``h``, ``b``, ``t_web``,
    ``arm_major``, ``d_hub``, ``l_hub``, ``d_outer``), which keep a section
    within its material's strength table.
    """

    j_shaft: float
    omega: float
    density: float
    poisson: float
    torque: float
    bore: float
    allowable: dict[str, float]
    envelope: float
    max_width: float
    max_rim_speed: float
    hb_ratio: tuple[float, float]
    d_mean: float | None
    min_wall: float
    d_hub_range: tuple[float, float] = (0.0, math.inf)
    l_hub_range: tuple[float, float] = (0.0, math.inf)
    start: dict[str, float] | None = None
    caps: dict[str, float] | None = None  # variable name -> upper bound [m] (a section kept within a strength table)
    fixed: dict[str, float] | None = None  # variable name -> its value [m] (a dimension rounded and held)
    warm: dict[str, float] | None = None  # a neighbouring wheel (variable name -> [m]): sqpmethod tried from it first
    ipopt_first: bool = False  # a neighbour had no wheel: IPOPT at once (it proves infeasibility; an SQP cannot)


@dataclass(frozen=True)
class WheelSolution:
    """A solved wheel: its dims, IPOPT's status and the multipliers of its limits."""

    dims: wheel.Dims
    objective: float
    status: str
    iterations: int
    elapsed: float
    lam_g: dict  # row name -> multiplier (summed over rows of one name)
    lam_x: dict  # variable name -> multiplier of its bounds
    lam_p: dict  # parameter name -> d f / d p
    stress_scale: float
    structure: WheelStructure
    allow_params: dict  # part -> the allowable's parameter, (sigma_a / S)^2 (ductile) or sigma_a / S
    caps: dict | None = None  # the caps that set a variable's upper bound (variable -> [m]), or None
    solver: str = "ipopt"  # which solver's converged result this is: "ipopt" or "sqpmethod"


def starting_wheel(structure: WheelStructure, problem: WheelProblem, names: Iterable[str]) -> dict[str, float]:
    """A starting wheel for IPOPT: the thin rim that gives J' at a diameter within every limit
    (variable name -> [m]; ``names``: the NLP's variables)."""
    rho, j = problem.density, problem.j_shaft
    cap = min(
        problem.envelope,
        2.0 * problem.max_rim_speed / problem.omega if structure.criterion == Criterion.RIM_SPEED else math.inf,
    )
    sigma = min(problem.allowable.values()) if problem.allowable else math.inf
    ring = 2.0 * math.sqrt(sigma / rho) / problem.omega if math.isfinite(sigma) else math.inf
    d = min(cap, 0.8 * ring)
    if problem.d_mean is not None:
        d = problem.d_mean * 1.1
    if not math.isfinite(d):
        d = (64.0 * j / (math.pi * rho)) ** 0.2
    hb = problem.hb_ratio[0]
    if structure.geometry == Geometry.DISC:
        b = max(32.0 * j / (math.pi * rho * max(d**4 - problem.bore**4, 1e-30 * d**4)), problem.min_wall)
        start = {"d_outer": d, "b": b}
        if "d_hub" in names:
            lo, hi = problem.d_hub_range
            start["d_hub"] = (
                min(max(lo, 1.9 * problem.bore), hi, 0.5 * d) if math.isfinite(hi) else max(lo, 2 * problem.bore)
            )
            start["l_hub"] = max(problem.l_hub_range[0], 1.2 * b)
        return start
    h = min(math.sqrt(4.0 * j * hb / (math.pi * rho * d**3)), 0.2 * d)
    h = max(h, problem.min_wall * 1.01)
    b = max(h / hb, problem.min_wall * 1.01)
    start = {"d_outer": d, "h": h, "b": b, "t_web": max(problem.min_wall * 1.2, 0.3 * b)}
    if "d_hub" in names:
        lo, hi = problem.d_hub_range
        start["d_hub"] = min(max(lo, 1.9 * problem.bore), hi) if math.isfinite(hi) else max(lo, 2 * problem.bore)
        lo, hi = problem.l_hub_range
        start["l_hub"] = max(lo, min(hi, b)) if math.isfinite(hi) else max(lo, b)
        start["t_web"] = min(start["t_web"], 0.9 * start["l_hub"])
    if "arm_major" in names:
        start["arm_major"] = max(2.2 * problem.min_wall, 0.5 * b)
    return start


def variable_bounds(
    structure: WheelStructure, problem: WheelProblem
) -> tuple[list[float], list[float], dict[str, float]]:
    """(lbx, ubx, capped) of a wheel NLP's variables (logarithms of metres) for a problem's limits.

    ``capped``: the caps of ``problem.caps`` tighter than every other upper bound (variable -> [m]).
    """
    names = variables_of(structure)
    inf = math.inf
    lbx = [-inf] * len(names)
    ubx = [inf] * len(names)
    col = {n: k for k, n in enumerate(names)}
    log_wall = math.log(problem.min_wall) if problem.min_wall > 0 else -inf
    for n in ("h", "b", "t_web"):
        if n in col:
            lbx[col[n]] = log_wall
    if structure.geometry == Geometry.DISC:
        lbx[col["b"]] = log_wall
    if "arm_major" in col:
        lbx[col["arm_major"]] = log_wall - math.log(wheel.ARM_MINOR_RATIO) if problem.min_wall > 0 else -inf
    if "d_hub" in col:
        lo, hi = problem.d_hub_range
        lbx[col["d_hub"]] = math.log(lo) if lo > 0 else -inf
        ubx[col["d_hub"]] = math.log(hi) if math.isfinite(hi) else inf
        lo, hi = problem.l_hub_range
        lbx[col["l_hub"]] = math.log(lo) if lo > 0 else -inf
        ubx[col["l_hub"]] = math.log(hi) if math.isfinite(hi) else inf
    capped = {}  # the caps tighter than every other upper bound
    for n, cap in (problem.caps or {}).items():
        if n in col and math.log(cap) < ubx[col[n]]:
            ubx[col[n]] = math.log(cap)
            capped[n] = cap
    for n, value in (problem.fixed or {}).items():  # held where rounding put it, whatever its other bounds
        if n in col:
            lbx[col[n]] = ubx[col[n]] = math.log(value)
    return lbx, ubx, capped


def row_bounds(
    structure: WheelStructure, constraints: Iterable[str], problem: WheelProblem
) -> tuple[list[float], list[float]]:
    """(lbg, ubg) of a wheel NLP's rows (``constraints``: their names, as :func:`formulate` gives them)."""
    s, inf = structure, math.inf
    bounds = {
        "inertia": (math.log(problem.j_shaft), inf),
        "max_outer_diameter": (-inf, math.log(problem.envelope) if s.envelope else inf),
        "rim_speed": (-inf, math.log(problem.max_rim_speed)),
        "max_width": (-inf, math.log(problem.max_width) if s.width else inf),
        "max_width_hub": (-inf, math.log(problem.max_width) if s.width else inf),
        "hb_ratio": (math.log(problem.hb_ratio[0]), math.log(problem.hb_ratio[1])),
        "inner_diameter": (0.0, inf),
        "rim_clears_hub": (0.0, inf),
        "bore_clear": (0.0, inf),
        "disc_clears_hub": (0.0, inf),
        "disc_below_hub": (-inf, 0.0),
        "d_mean": ((math.log(problem.d_mean),) * 2 if problem.d_mean is not None else (-inf, inf)),
        "web_below_rim": (-inf, 0.0),
        "web_below_hub": (-inf, 0.0),
        "arms_fit_hub": (-inf, 1.0),
        "arm_within_rim": (-inf, 0.0),
        "arm_within_hub": (-inf, 0.0),
        "hub_wall": (problem.min_wall, inf),
    }
    if s.castability is not None:
        ratio = math.log(s.castability.section_ratio)
        for name in constraints:
            if name.startswith("castability_min_wall_"):
                bounds[name] = (0.0, inf)
            elif name.startswith("castability_"):
                bounds[name] = (-ratio, ratio)
    stress_row = (-inf, 1.0)  # stress rows: sigma / allowable <= 1
    lbg, ubg = [], []
    for name in constraints:
        lo, hi = bounds.get(name, stress_row)
        lbg.append(lo)
        ubg.append(hi)
    return lbg, ubg


def allowable_parameters(structure: WheelStructure, allowable: Mapping[str, float], scale: float) -> list[float]:
    """The allowable parameters of a wheel NLP: sigma_a / S of each stressed part, squared if ductile
    (``allowable``: part -> sigma_a [Pa]; a part not given is not limited)."""
    out = []
    for part in stressed_parts(structure):
        a = allowable.get(part, math.inf) / scale
        out.append(a * a if structure.ductile else a)
    return out


def solve_arguments(
    structure: WheelStructure, constraints: Sequence[str], problem: WheelProblem
) -> tuple[dict[str, Any], float, list[float]]:
    """(the nlpsol arguments x0, lbx, ubx, lbg, ubg, p of a wheel, its stress scale, its allowables' parameters).

    The start is ``problem.start`` or the thin ring of :func:`starting_wheel`, clipped to the bounds; the
    stress scale is ρ ω² (D/2)² of that start. :func:`solve` passes exactly these, and a benchmark that
    solves the same NLP another way takes them from here.
    """
    names = variables_of(structure)
    lbx, ubx, _ = variable_bounds(structure, problem)
    start = problem.start or starting_wheel(structure, problem, names)
    x0 = _clipped(start, names, {"lbx": lbx, "ubx": ubx})
    scale = problem.density * problem.omega**2 * (start["d_outer"] / 2.0) ** 2
    lbg, ubg = row_bounds(structure, constraints, problem)
    _settle_ratio_row(names, list(constraints), lbx, ubx, lbg, ubg)
    allow = allowable_parameters(structure, problem.allowable, scale)
    values = {
        "omega": problem.omega,
        "density": problem.density,
        "poisson": problem.poisson,
        "torque": problem.torque,
        "bore": problem.bore,
        "stress_scale": scale,
        "log_half_omega": math.log(problem.omega / 2.0),
    }
    p = [values[n] for n in PARAMETERS] + allow
    return {"x0": x0, "lbx": lbx, "ubx": ubx, "lbg": lbg, "ubg": ubg, "p": p}, scale, allow


def _settle_ratio_row(
    names: Sequence[str], constraints: list[str], lbx: list[float], ubx: list[float], lbg: list[float], ubg: list[float]
) -> None:
    """Free a fixed H/B ratio's row (an equality) where the rounding has fixed both H and B at that ratio: the
    row is then a constant, and CasADi, counting it with the fixed variables, printed "NLP is overconstrained:
    There are 7 equality constraints but only 6 variables" at each of the rounding's solves (press-arms-wheel
    at ``hb_ratio = 1.5``). Fixed H and B off the ratio keep the row, and the solve finds no wheel."""
    if "hb_ratio" not in constraints or "h" not in names:
        return
    k, h, b = constraints.index("hb_ratio"), names.index("h"), names.index("b")
    fixed = lbx[h] == ubx[h] and lbx[b] == ubx[b]
    if lbg[k] == ubg[k] and fixed and abs(lbx[h] - lbx[b] - lbg[k]) <= 1e-12:
        lbg[k], ubg[k] = -math.inf, math.inf


def solve(model: WheelModel, problem: WheelProblem, label: str) -> WheelSolution:
    """Solve one combination's wheel NLP, its status checked.

    Returns
    -------
    WheelSolution

    With ``problem.warm`` (a neighbouring wheel: the last design of the same combination in a sweep),
    sqpmethod is tried from it first on the same NLP (the same bounds, parameters and stress scale, only
    the start differs): with that wheel's multipliers where this model solved it (:func:`_warm_duals`), else,
    or where that fails, from the wheel alone; where neither converges the solve goes on exactly as without
    it (sqpmethod from the cold start, then IPOPT). With ``problem.ipopt_first`` (the neighbour had no wheel)
    IPOPT solves it at once. Either way only a converged status gives a wheel (sqpmethod's at a KKT point:
    :func:`_solve_fast`).

    Raises
    ------
    SolverFailed
        IPOPT stopped with an error or did not converge (``status`` carries
        its return status; "Infeasible_Problem_Detected" means IPOPT found
        no wheel meeting every limit, which the designer reports as such).
    """
    s = model.structure
    names = model.variables
    lbx, ubx, capped = variable_bounds(s, problem)
    crossed = [n for n, lo, hi in zip(names, lbx, ubx) if lo > hi]
    if crossed:  # a cap below a lower bound: no wheel, and IPOPT is not asked
        failure = SolverFailed(
            f"{label}: the caps on {', '.join(crossed)} are below their lower bounds; no wheel meets both"
        )
        failure.status = "Infeasible_Problem_Detected"
        failure.combination = label
        raise failure
    args, scale, allow = solve_arguments(s, model.constraints, problem)
    begin = time.perf_counter()
    sol, stats, values = None, {}, None
    if model.fast is not None and problem.warm is not None:  # the same NLP from a neighbour's wheel
        warm = {**args, "x0": _clipped(problem.warm, names, args)}
        duals = _warm_duals(model, warm)
        if duals is not None:  # and its multipliers: the first QP starts from the neighbour's active set
            sol, stats, values = _solve_fast(model.fast, {**warm, **duals})
        if sol is None:
            sol, stats, values = _solve_fast(model.fast, warm)
    if sol is None and model.fast is not None and not problem.ipopt_first:  # cold, as without a neighbour
        sol, stats, values = _solve_fast(model.fast, args)
    solver = "sqpmethod" if sol is not None else "ipopt"
    if sol is None:  # IPOPT: where sqpmethod did not converge, or chosen alone
        try:
            sol = model.solver(**args)
        except RuntimeError as err:
            raise SolverFailed(f"{label}: IPOPT stopped with an error ({err}); no design is reported") from err
        stats = model.solver.stats()
    elapsed = time.perf_counter() - begin
    status = stats.get("return_status", "unknown")
    iterations = int(stats.get("iter_count", -1))
    if status not in CONVERGED:
        failure = SolverFailed(
            f"{label}: IPOPT did not converge on the whole wheel (return status "
            f"{status!r} after {iterations} iterations); no design is reported"
        )
        failure.status = status
        failure.combination = label
        raise failure
    if values is None:  # IPOPT's (sqpmethod's were read by _solve_fast)
        values = _values(sol)
    xs = values["x"]
    if solver == "sqpmethod":
        _remember_duals(model, values)
    dims = dims_of(s, {n: math.exp(v) for n, v in zip(names, xs)}, problem.bore)
    lam_g: dict = {}
    # a row off both its bounds has no multiplier: an interior point method leaves mu/slack there
    # (1e-9 on a 16.5 mm hub wall whose minimum is 8 mm), which would read as a binding limit
    for name, lam, g, lo, hi in zip(model.constraints, values["lam_g"], values["g"], args["lbg"], args["ubg"]):
        on = lam != 0.0 and _on_either(g, lo, hi, ACTIVE_ROW)  # (a zero adds nothing: the sums start at +0.0)
        lam_g[name] = lam_g.get(name, 0.0) + (float(lam) if on else 0.0)
    lam_x = {
        n: float(v) if _on_either(x, lo, hi, ACTIVE_ROW) else 0.0
        for n, v, x, lo, hi in zip(names, values["lam_x"], xs, args["lbx"], args["ubx"])
    }
    lam_p = {n: float(v) for n, v in zip(PARAMETERS, values["lam_p"])}
    for part, v in zip(model.stress_parts, values["lam_p"][len(PARAMETERS) :]):
        lam_p[f"allow_{part}"] = float(v)
    return WheelSolution(
        dims,
        float(sol["f"]),
        status,
        iterations,
        elapsed,
        lam_g,
        lam_x,
        lam_p,
        scale,
        s,
        dict(zip(model.stress_parts, allow)),
        capped or None,
        solver,
    )


#: A row within this of its bound (relative to the bound, absolute below 1) is active: its multiplier
#: counts. The rows are logarithms or lengths in metres; a converged row meets its bound to the solvers'
#: 1e-10, and a limit clear of its bound by a micrometre or a millionth is not binding.
ACTIVE_ROW = 1e-6


def _on_bound(value: float, bound: float, tol: float) -> bool:
    """Whether ``value`` meets ``bound`` to ``tol``, relative to the bound (absolute below 1); an infinite
    bound is never met. (Plain floats, element by element: the vectors are a few dozen long, and most
    multipliers are zero and need no test, where numpy's per-call cost was most of a sweep point's
    bookkeeping.)"""
    return math.isfinite(bound) and abs(value - bound) <= tol * max(1.0, abs(bound))


def _on_either(value: float, lower: float, upper: float, tol: float) -> bool:
    """Whether a row or variable meets one of its bounds to ``tol`` (:func:`_on_bound`)."""
    return _on_bound(value, lower, tol) or _on_bound(value, upper, tol)


def _on_named(lam: float, value: float, lower: float, upper: float, tol: float) -> bool:
    """Whether a row or variable meets the bound its multiplier's sign names (> 0 the upper, < 0 the lower,
    CasADi's convention) to ``tol``; never for a zero (or NaN) multiplier."""
    return (lam > 0 and _on_bound(value, upper, tol)) or (lam < 0 and _on_bound(value, lower, tol))


def _clipped(wheel_dims: Mapping[str, float], names: Sequence[str], args: Mapping[str, Any]) -> list[float]:
    """The logarithms of a wheel's dimensions by variable name, clipped to the NLP's bounds in ``args``."""
    return _clip([math.log(wheel_dims[n]) for n in names], args)


def _clip(xs: Sequence[float], args: Mapping[str, Any]) -> list[float]:
    """The NLP's variables ``xs`` clipped to its bounds in ``args``."""
    return [min(max(x, lo), hi) for x, lo, hi in zip(xs, args["lbx"], args["ubx"])]


def _solve_fast(fast, args):
    """(solution, stats, its values: :func:`_values`) of sqpmethod where it converged (its status checked) to a
    KKT point of the NLP, else (None, its stats, None).

    sqpmethod tests feasibility and stationarity, not complementarity (:func:`_complementary`): a stale
    multiplier passed in a warm start (a row the new problem leaves slack) makes the start look stationary,
    and a QP stopped short (at its iteration cap, or cycling) is a step sqpmethod takes as it is, so a status of
    convergence is kept only where every nonzero multiplier also sits on its bound.
    """
    try:
        sol = fast(**args)
        # (CasADi 3.8's sqpmethod cannot name some of its stops, e.g. a QP step to an overflowing row: its
        # stats then raise, and the solve is one that did not converge)
        stats = fast.stats()
    except RuntimeError:
        return None, {}, None
    if stats.get("success") and stats.get("return_status") in CONVERGED:
        values = _values(sol)
        # the SQP's last iterate may sit beyond an active variable bound by its last step (measured up to
        # 2.4e-12): put it on it, as the same wheel is when it starts the next point's solve. Only within the
        # SQP's own tolerance: a wheel further out is not its converged answer. (Its objective, sol["f"], is
        # that of the iterate, to the same 1e-12.)
        clipped = _clip(values["x"], args)
        if any(abs(c - v) > SQP_OPTIONS["tol_pr"] for c, v in zip(clipped, values["x"])):
            return None, stats, None
        values["x"] = clipped
        if _complementary(values, args):
            return sol, stats, values
    return None, stats, None


#: Converged solves whose multipliers a model keeps for warm starts (the oldest is dropped first): a
#: sweep's chunk asks for those of its previous point, one per combination and caps of the same NLP.
DUALS_KEPT = 64


def _wheel_key(xs: Sequence[float]) -> tuple[float, ...]:
    """A wheel's variables (logarithms of metres) rounded to 1e-12: a warm start's ``x0`` is the log of
    the exp of a solution's, which may differ from it in the last bit."""
    return tuple(round(v, 12) for v in xs)


def _values(sol: Mapping[str, Any]) -> dict[str, list[float]]:
    """An nlpsol's dense outputs (x, g, lam_x, lam_g, lam_p) as lists of floats."""
    return {name: sol[name].nonzeros() for name in ("x", "g", "lam_x", "lam_g", "lam_p")}


def _remember_duals(model: WheelModel, values: Mapping[str, list[float]]) -> None:
    """Keep a converged sqpmethod solution's multipliers (:func:`_values`) on its model, by its wheel
    (:data:`DUALS_KEPT`)."""
    key = _wheel_key(values["x"])
    model.duals.pop(key, None)
    model.duals[key] = (values["lam_x"], values["lam_g"])
    while len(model.duals) > DUALS_KEPT:
        try:  # the oldest; a thread that changed the dict meanwhile leaves the trim to the next call
            oldest = next(iter(model.duals))
        except (StopIteration, RuntimeError):
            break
        model.duals.pop(oldest, None)


def _warm_duals(model: WheelModel, args: Mapping[str, Any]) -> dict[str, list[float]] | None:
    """``lam_x0`` and ``lam_g0`` for a warm start from a wheel this model solved (None: none kept).

    The neighbour's multipliers, each kept only where its row (or variable) still meets the bound its sign
    names at the start under this problem's bounds and parameters (:func:`_active_at`); the others are set
    to 0. Passed as they were, the multiplier of a row the new problem leaves slack (the inertia row of a
    point that needs less J) makes the start look stationary, and sqpmethod, which tests stationarity and
    feasibility but not complementarity, reports Solve_Succeeded after 0 iterations at a wheel that is not
    the new optimum.
    """
    kept = model.duals.get(_wheel_key(args["x0"]))
    if kept is None or model.rows is None:
        return None
    rows = model.rows(args["x0"], args["p"]).nonzeros()
    lam_x, lam_g = kept
    return {
        "lam_x0": _active_at(lam_x, args["x0"], args["lbx"], args["ubx"], ACTIVE_ROW),
        "lam_g0": _active_at(lam_g, rows, args["lbg"], args["ubg"], ACTIVE_ROW),
    }


def _active_at(
    lams: Sequence[float], values: Sequence[float], lower: Sequence[float], upper: Sequence[float], tol: float
) -> list[float]:
    """Each multiplier where its value meets the bound its sign names to ``tol`` (:func:`_on_named`), else 0."""
    return [float(lam) if _on_named(lam, v, lo, hi, tol) else 0.0 for lam, v, lo, hi in zip(lams, values, lower, upper)]


#: A converged multiplier's row (or variable) meets its bound to this: ten times sqpmethod's tol_pr.
COMPLEMENTARY = 1e-9


def _complementary(values: Mapping[str, list[float]], args: Mapping[str, Any]) -> bool:
    """Whether every nonzero multiplier of a solution sits on the bound its sign names to
    :data:`COMPLEMENTARY` (:func:`_on_named`): with sqpmethod's own tests (feasibility, stationarity) the
    wheel is then a KKT point of this NLP."""
    for at, lams, lower, upper in (
        (values["x"], values["lam_x"], args["lbx"], args["ubx"]),
        (values["g"], values["lam_g"], args["lbg"], args["ubg"]),
    ):
        for lam, v, lo, hi in zip(lams, at, lower, upper):
            if lam != 0.0 and not _on_named(lam, v, lo, hi, COMPLEMENTARY):  # (a NaN is neither)
                return False
    return True
