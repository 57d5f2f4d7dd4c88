"""The flywheel designer: choose rim size, material and shaft by optimization.

Given the flywheel inertia the cycle analysis requires at the reference shaft,
J_F (already net of the machine's own J_c), every combination of material and
mounting shaft gets a small nonlinear program; the combinations are then
ranked by the objective. The NLP is solved with IPOPT through CasADi, or,
where its optimum is known in closed form (objectives mass and cost: the
outer diameter at its cap and a monotone 1-D root, :mod:`flyopt.design.closed_form`), by
that closed form: the default method "auto" takes the closed form where it is
exact and IPOPT elsewhere, and verifies either design against every
constraint. The closed form is tested against IPOPT to 1e-6 in mass.

For a flywheel mounted on a shaft turning at omega' = r omega_m (r the speed
ratio), the kinetic energy transfer (docs/flywheel-design.md, section 8) gives

    J_ref = J' r^2,   so the wheel must give J' >= J_F / r^2 on its shaft.

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
is built once (:func:`get_model`) and reused.

Feasibility is decided exactly in closed form before IPOPT is called: the
largest inertia any admissible wheel of the combination can give
(:func:`max_inertia`). IPOPT is only asked to optimize feasible combinations;
a non-converged solve of a feasible combination raises
:class:`~flyopt.errors.SolverFailed`.

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

import difflib
import math
import time
from dataclasses import asdict, dataclass, fields
from typing import Mapping, NamedTuple, Sequence

import casadi as ca
from scipy.optimize import brentq

from flyopt.design import geometry
from flyopt.errors import SolverFailed
from flyopt.design.materials import Material
from flyopt.machine.transmission import inertia_at_reference, inertia_on_shaft

__all__ = [
    "MountShaft",
    "DesignSpec",
    "Candidate",
    "DesignResult",
    "design_flywheel",
    "inertia_on_shaft",
    "inertia_at_reference",
    "max_inertia",
    "get_model",
    "ModelStructure",
    "NlpModel",
    "clear_model_cache",
    "OBJECTIVES",
    "BINDING_NAMES",
]

#: Objectives understood by :func:`design_flywheel`.
OBJECTIVES = {
    "mass": "minimize the flywheel mass [kg]",
    "outer_diameter": "minimize the outer diameter [m]",
    "cost": "minimize mass times the material's cost per kg",
}

#: Names that ``Candidate.binding`` may contain.
BINDING_NAMES = {
    "inertia": "the wheel gives exactly the required inertia",
    "rim_speed": "the outer diameter is at the material's rim speed limit",
    "max_outer_diameter": "the outer diameter is at the scene's envelope",
    "max_width": "the axial width is at the scene's limit",
    "hb_min": "H/B is at the lower end of its range",
    "hb_max": "H/B is at the upper end of its range",
    "inner_diameter": "the inner diameter has shrunk to zero (the rim became a disc)",
}

#: Relative tolerance for calling a constraint binding.
ACTIVE_RTOL = 1e-6
#: Relative tolerance when checking a solved design against its constraints.
VERIFY_RTOL = 1e-6
#: IPOPT statuses accepted as converged (the design is still verified).
_CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")

#: Solver options, merged in this one place; explicit options passed to
#: design_flywheel(..., solver_options=...) win.
DEFAULT_SOLVER_OPTIONS = {
    "print_time": False,
    "error_on_fail": False,
    "ipopt.print_level": 0,
    "ipopt.sb": "yes",
    "ipopt.tol": 1e-10,
    "ipopt.bound_relax_factor": 0.0,
    "ipopt.max_iter": 200,
}


# --------------------------------------------------------------------------
# Inputs
# --------------------------------------------------------------------------

def _finite(value, name):
    try:
        number = float(value)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{name} must be a number, got {value!r}") from err
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return number


def _positive(value, name, unit):
    number = _finite(value, f"{name} {unit}")
    if number <= 0.0:
        raise ValueError(f"{name} {unit} must be > 0, got {value!r}")
    return number


def _choice(value, allowed, name):
    if value in allowed:
        return value
    close = difflib.get_close_matches(str(value), list(allowed), n=2, cutoff=0.4)
    hint = f"; best matches are {close}" if close else ""
    raise ValueError(f"{name} {value!r} not recognised; allowed are {sorted(allowed)}{hint}")


@dataclass(frozen=True)
class MountShaft:
    """A shaft the flywheel may be mounted on.

    Parameters
    ----------
    name : str
        Shaft name for reports, e.g. ``"motor"``.
    speed_ratio : float
        omega_shaft / omega_reference [-], > 0.
    """

    name: str
    speed_ratio: float

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"shaft name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "speed_ratio",
                           _positive(self.speed_ratio, f"shaft {self.name!r}: speed_ratio", "[-]"))


@dataclass(frozen=True)
class DesignSpec:
    """What the design must satisfy and optimize, shared by every combination.

    Parameters
    ----------
    geometry : {"rim", "thin_rim", "disc"}
        Inertia model (see :data:`flyopt.design.geometry.GEOMETRIES`).
    hb_ratio : (float, float)
        Allowed range of H/B, radial thickness over axial width [-]; equal
        ends fix it. Ignored by ``disc``.
    max_outer_diameter : float or None
        Envelope on the outer diameter [m].
    max_width : float or None
        Limit on the axial width B [m].
    d_mean : float or None
        Pinned mean diameter D_m [m]; for ``disc`` the pinned diameter D.
    objective : {"mass", "outer_diameter", "cost"}
        What to minimize. ``cost`` needs a cost per kg on every material.

    Raises
    ------
    ValueError
        On an unknown name, a non-positive length, or a bad H/B range; and for
        ``outer_diameter`` with a ``disc`` and no ``max_width`` (an ever
        thinner, wider disc makes the diameter as small as one likes).
    """

    geometry: str = "rim"
    hb_ratio: tuple[float, float] = (1.5, 2.0)
    max_outer_diameter: float | None = None
    max_width: float | None = None
    d_mean: float | None = None
    objective: str = "mass"

    def __post_init__(self):
        _choice(self.geometry, geometry.GEOMETRIES, "geometry")
        _choice(self.objective, OBJECTIVES, "objective")
        try:
            low, high = self.hb_ratio
        except (TypeError, ValueError) as err:
            raise ValueError(f"hb_ratio must be a pair (min, max) of H/B, "
                             f"got {self.hb_ratio!r}") from err
        low = _positive(low, "hb_ratio min", "[-]")
        high = _positive(high, "hb_ratio max", "[-]")
        if low > high:
            raise ValueError(f"hb_ratio min {low} must not exceed max {high}")
        object.__setattr__(self, "hb_ratio", (low, high))
        for name in ("max_outer_diameter", "max_width", "d_mean"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _positive(value, name, "[m]"))
        if (self.objective == "outer_diameter" and self.geometry == "disc"
                and self.max_width is None):
            raise ValueError("objective 'outer_diameter' with geometry 'disc' needs "
                             "max_width: without it an ever thinner, wider disc makes "
                             "the diameter as small as one likes")


# --------------------------------------------------------------------------
# Closed forms: the largest inertia a combination can give
# --------------------------------------------------------------------------

def _wheel_inertia(geometry_name, density, d_mean, h, b):
    if geometry_name == "thin_rim":
        return geometry.thin_rim_inertia(geometry.rim_mass(d_mean, h, b, density), d_mean)
    return geometry.rim_inertia(geometry.rim_mass(d_mean, h, b, density), d_mean, h)


def max_inertia(geometry_name, density, d_outer_max, hb_ratio=(1.5, 2.0),
                max_width=None, d_mean=None):
    """Largest inertia any admissible wheel gives, in closed form.

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
        Inertia model.
    density : float
        Density [kg/m^3].
    d_outer_max : float
        Cap on the outer diameter (rim speed and envelope) [m].
    hb_ratio : (float, float)
        Range of H/B [-] (rims only).
    max_width : float or None
        Limit on B [m]; ``None`` for none.
    d_mean : float or None
        Pinned mean diameter (disc: diameter) [m].

    Returns
    -------
    j_max : float
        Supremum of J on the shaft [kg*m^2]; 0 if no wheel fits, ``inf`` for
        an unlimited disc.
    dims : tuple (d_mean, h, b) or None
        The wheel that attains it [m] (for a disc d_mean = h = D/2), or None.

    Notes
    -----
    J grows with the width B, so B = min(H/hb_min, B_max), and a width limit
    also caps H <= hb_max B_max. With D_m pinned, J grows with H up to
    min(D_1max - D_m, D_m, hb_max B_max). With D_m = D_1max - H free, put
    x = H/D_1max <= 1/2: the exact annulus gives J proportional to
    x u (1 - 2u) or u (1 - 2u), u = x (1 - x), both increasing on [0, 1/2],
    so H is as large as allowed; the thin rim gives x^2 (1-x)^3 (peak at
    x = 2/5) or x (1-x)^3 (peak at 1/4), so the maximum is at a clipped peak,
    at the change of piece or at the end of the range.
    """
    hb_min, hb_max = hb_ratio
    b_max = math.inf if max_width is None else max_width
    cap = d_outer_max
    if geometry_name == "disc":
        d = cap if d_mean is None else d_mean
        if d > cap:
            return 0.0, None
        if max_width is None:
            return math.inf, None
        j = geometry.disc_inertia(geometry.disc_mass(d, b_max, density), d)
        return j, (d / 2.0, d / 2.0, b_max)

    def width(h):
        return min(h / hb_min, b_max)

    if d_mean is not None:
        if d_mean >= cap:
            return 0.0, None
        h = min(cap - d_mean, d_mean, hb_max * b_max)
        return _wheel_inertia(geometry_name, density, d_mean, h, width(h)), (d_mean, h, width(h))

    h_top = min(cap / 2.0, hb_max * b_max)
    trials = [h_top]
    if geometry_name == "thin_rim":
        h_break = min(hb_min * b_max, h_top)
        trials += [h_break, min(0.4 * cap, h_break), min(max(0.25 * cap, h_break), h_top)]
    best = (0.0, None)
    for h in trials:
        if h <= 0.0:
            continue
        j = _wheel_inertia(geometry_name, density, cap - h, h, width(h))
        if j > best[0]:
            best = (j, (cap - h, h, width(h)))
    return best


def _cap_needed(geometry_name, density, j_needed, cap, hb_ratio, max_width, d_mean):
    """Smallest outer-diameter cap at which ``j_needed`` becomes reachable.

    Returns (cap_needed, j_sup): cap_needed is None when even an unlimited cap
    does not reach ``j_needed``; j_sup is then the largest reachable inertia.
    """
    def j_max(c):
        return max_inertia(geometry_name, density, c, hb_ratio, max_width, d_mean)[0]

    if d_mean is not None:
        if geometry_name == "disc":
            saturated = d_mean
        else:
            hb_max = hb_ratio[1]
            b_max = math.inf if max_width is None else max_width
            saturated = d_mean + min(d_mean, hb_max * b_max)
        j_sup = j_max(saturated)
        if j_sup < j_needed:
            return None, j_sup
        low, high = max(cap, d_mean), saturated
        if geometry_name == "disc" or j_max(low) >= j_needed:
            return low, j_sup
    else:
        # D_m free. J_max is homogeneous of degree 5 in (C, B_max): scaling an admissible
        # wheel by λ keeps it admissible. So without a width limit the cap needed is in
        # closed form (a disc of fixed width: degree 4 in C). With a width limit, growing
        # C by λ >= 1 multiplies J_max by at most λ^5 (scale down any wheel of the larger
        # cap) and at least λ^3 / 2 (keep H and B, push D_m out to >= λ D_m; with
        # H <= D_m, D_m^2 + H^2 <= 2 D_m^2), which brackets the root.
        j_cap = j_max(cap)
        if max_width is None or geometry_name == "disc":
            power = 4.0 if geometry_name == "disc" else 5.0
            return cap * (j_needed / j_cap) ** (1.0 / power), math.inf
        low = cap * (j_needed / j_cap) ** 0.2
        if j_max(low) >= j_needed:           # the width does not bind there: degree 5 is exact
            return low, math.inf
        high = cap * (2.0 * j_needed / j_cap) ** (1.0 / 3.0)
        while j_max(high) < j_needed:        # round-off at the bracket's edge only
            low, high = high, 2.0 * high
    root = brentq(lambda c: j_max(c) / j_needed - 1.0, low, high, xtol=1e-12 * high,
                  rtol=1e-12)
    return root, math.inf


# --------------------------------------------------------------------------
# The NLP models, one per structure, cached
# --------------------------------------------------------------------------

class ModelStructure(NamedTuple):
    """What decides the shape of an NLP (its variables and constraints)."""

    geometry: str          # "rim" | "thin_rim" | "disc"
    pinned: bool           # d_mean given: D_m is not a variable
    collapsed: bool        # hb_min == hb_max: B is not a variable (rims only)
    objective: str         # "mass" | "outer_diameter" (cost ranks by mass times cost)


@dataclass
class NlpModel:
    """A built NLP: the ``casadi.nlpsol`` function and what it contains."""

    structure: ModelStructure
    solver: ca.Function
    variables: tuple          # physical names of the decision variables
    constraints: tuple        # names of the rows of g
    uses_p: bool
    build_time: float

    def describe(self):
        s = self.structure
        return {
            "geometry": s.geometry,
            "inertia_model": geometry.GEOMETRIES[s.geometry],
            "objective": s.objective,
            "variables": list(self.variables),
            "constraints": list(self.constraints),
            "pinned": ["d_mean"] if s.pinned else [],
            "formulation": ("IPOPT (CasADi nlpsol) on the logarithms of non-dimensional "
                            "variables; numbers enter as parameters and bounds"),
        }


_MODEL_CACHE: dict = {}
#: Weight of the tie-break term in the log-mass objective (see _build_model).
_TIE_BREAK = 1e-3


def clear_model_cache():
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
    options = dict(DEFAULT_SOLVER_OPTIONS)
    options.update(solver_options or {})
    key = (structure, _options_key(options))
    model = _MODEL_CACHE.get(key)
    if model is None:
        model = _build_model(structure, options)
        _MODEL_CACHE[key] = model
    return model


def _build_model(structure, options):
    """Build the NLP of one structure in log-scaled variables.

    Variables (present ones only): x_d = log(D_m/L), x_h = log(H/H_s),
    x_b = log(B/B_s); for a disc x_d = log(D/L). Parameter p = log(H_s/L)
    where a nonlinear term needs it. With the scales of :func:`_scales` the
    inertia row reads ``>= 0``.
    """
    start = time.perf_counter()
    geo, pinned, collapsed, objective = structure
    names = []
    cols = {}
    order = ["d_mean", "h", "b"] if geo != "disc" else ["diameter", "b"]
    for name in order:
        if name in ("d_mean", "diameter") and pinned:
            continue
        if name == "b" and geo != "disc" and collapsed:
            continue
        cols[name] = len(names)
        names.append(name)
    x = ca.SX.sym("x", len(names))

    def var(name):
        return x[cols[name]] if name in cols else 0.0

    g, g_names = [], []
    uses_p = False
    p = ca.SX.sym("p", 1)
    if geo == "disc":
        xd, xb = var("diameter"), var("b")
        g.append(4.0 * xd + xb)
        g_names.append("inertia")
        if objective == "mass":
            f = 2.0 * xd + xb
        elif pinned:
            f = xb      # diameter fixed: pick the lightest disc of that diameter
        else:
            f = xd
    else:
        xd, xh = var("d_mean"), var("h")
        xb = xh if collapsed else var("b")
        # t = log(H/D_m) <= 0 by the inner-diameter constraint
        t = xh + p[0] - xd
        if geo == "rim":
            uses_p = True
            g.append(3.0 * xd + xh + xb + ca.log1p(ca.exp(2.0 * t)))
        else:
            g.append(3.0 * xd + xh + xb)
        g_names.append("inertia")
        if not pinned:
            uses_p = True
            g.append(xd + ca.log1p(ca.exp(t)))        # log(D_outer / L)
            g_names.append("outer_diameter")
            g.append(xh - xd)                          # log(H/D_m) - log(H_s/L)
            g_names.append("inner_diameter")
        if not collapsed:
            g.append(xh - xb)                          # log(H/B) - log(hb_min)
            g_names.append("hb_ratio")
        if objective == "mass":
            f = xd + xh + xb
            if not pinned or (geo == "thin_rim" and not collapsed):
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
            f = xh                                     # D_outer = D_m + H, D_m fixed
        else:
            uses_p = True
            f = xd + ca.log1p(ca.exp(t))
    nlp = {"x": x, "f": f, "g": ca.vertcat(*g)}
    if uses_p:
        nlp["p"] = p
    name = "flywheel_" + "_".join(str(v) for v in structure)
    solver = ca.nlpsol(name, "ipopt", nlp, options)
    return NlpModel(structure=structure, solver=solver, variables=tuple(names),
                    constraints=tuple(g_names), uses_p=uses_p,
                    build_time=time.perf_counter() - start)


# --------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class Candidate:
    """One combination of material and shaft, designed or shown infeasible.

    All lengths in [m], mass [kg], inertia [kg*m^2], speed [m/s], stress [Pa].
    For a disc, d_mean = h = D/2 and d_inner = 0 (the annulus with no hole),
    so that every rim formula holds. Dimensions are None when not feasible.

    Attributes
    ----------
    material, shaft : str
    speed_ratio : float
        omega_shaft / omega_reference.
    geometry : str
    feasible : bool
    reason : str
        Why infeasible, in words and numbers; for a design, what binds.
    d_mean, d_outer, d_inner, h, b, hb_ratio, mass : float or None
    rim_speed : float or None
        omega' D_outer / 2 [m/s].
    hoop_stress : float or None
        rho v^2 at the outer rim [Pa].
    safety_factor : float or None
        allowable_stress / hoop_stress, when the allowable stress is known.
    cost : float or None
        mass times cost per kg, when the material has a cost.
    j_flywheel : float or None
        Inertia of the wheel on its own shaft (the chosen model).
    j_at_reference : float or None
        j_flywheel moved to the reference shaft, J' r^2.
    binding : tuple of str
        Active constraints (see :data:`BINDING_NAMES`), relative tolerance
        :data:`ACTIVE_RTOL`.
    objective : float or None
        Value of the ranking objective.
    j_required_on_shaft : float
        J_F / r^2.
    d_outer_limit : float
        min(2 v_max / omega', max_outer_diameter).
    rim_speed_limit : float
        The material's v_max.
    j_max : float
        Largest inertia the combination can give on its shaft (closed form).
    d_outer_needed : float or None
        For a combination stopped by the outer-diameter cap: the cap it needs.
    solver_status : str or None
        IPOPT return status; None when the closed form proved infeasibility
        and no NLP was solved.
    iterations : int or None
    solve_time : float or None
        Wall time of the NLP solve [s].
    """

    material: str
    shaft: str
    speed_ratio: float
    geometry: str
    feasible: bool
    reason: str
    d_mean: float | None = None
    d_outer: float | None = None
    d_inner: float | None = None
    h: float | None = None
    b: float | None = None
    hb_ratio: float | None = None
    mass: float | None = None
    rim_speed: float | None = None
    hoop_stress: float | None = None
    safety_factor: float | None = None
    cost: float | None = None
    j_flywheel: float | None = None
    j_at_reference: float | None = None
    binding: tuple = ()
    objective: float | None = None
    j_required_on_shaft: float = math.nan
    d_outer_limit: float = math.nan
    rim_speed_limit: float = math.nan
    j_max: float = math.nan
    d_outer_needed: float | None = None
    solver_status: str | None = None
    iterations: int | None = None
    solve_time: float | None = None

    def to_dict(self):
        """Plain, JSON-ready dictionary (inf becomes None)."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, tuple):
                value = list(value)
            elif isinstance(value, float) and not math.isfinite(value):
                value = None
            out[f.name] = value
        return out


#: Fields of the top-level "design" object taken from the best candidate.
DESIGN_FIELDS = ("material", "shaft", "speed_ratio", "geometry", "d_mean", "d_outer",
                 "d_inner", "h", "b", "hb_ratio", "mass", "rim_speed", "hoop_stress",
                 "safety_factor", "cost", "j_flywheel", "j_at_reference", "binding",
                 "objective")


@dataclass(frozen=True)
class DesignResult:
    """Outcome of :func:`design_flywheel`.

    Attributes
    ----------
    status : {"designed", "not_needed", "infeasible"}
    message : str
    j_required : float
        J_F at the reference shaft [kg*m^2].
    omega : float
        Speed of the reference shaft at which the rim speed was checked (ω_max) [rad/s].
    spec : DesignSpec
    best : Candidate or None
    candidates : tuple of Candidate
        Every material x shaft combination, ranked: feasible ones by the
        objective (best first), then the infeasible ones in input order.
    model : dict or None
        Which geometry, variables and constraints the NLP holds.
    """

    status: str
    message: str
    j_required: float
    omega: float
    spec: DesignSpec
    best: Candidate | None = None
    candidates: tuple = ()
    model: dict | None = None

    def to_dict(self):
        """JSON-ready plain Python.

        Returns
        -------
        dict
            ``status``, ``message``, ``j_required``, ``omega``, ``spec``,
            ``model`` and ``design``. ``design`` is None when no flywheel is
            needed; otherwise it holds the best candidate's fields (all None
            when every combination is infeasible) and ``candidates``, one
            entry per combination.
        """
        design = None
        if self.status != "not_needed":
            best = self.best.to_dict() if self.best else {}
            design = {name: best.get(name) for name in DESIGN_FIELDS}
            design["binding"] = design["binding"] or []
            design["candidates"] = [c.to_dict() for c in self.candidates]
        spec = asdict(self.spec)
        spec["hb_ratio"] = list(spec["hb_ratio"])
        return {"status": self.status, "message": self.message,
                "j_required": self.j_required, "omega": self.omega,
                "spec": spec, "model": self.model, "design": design}


# --------------------------------------------------------------------------
# One combination
# --------------------------------------------------------------------------

@dataclass
class _Combination:
    material: Material
    shaft: MountShaft
    omega: float          # speed of the carrying shaft [rad/s]
    j_shaft: float        # required inertia on that shaft [kg*m^2]
    j_reference: float
    cap_speed: float      # outer-diameter cap of the rim speed [m]
    cap: float            # min(cap_speed, envelope) [m]
    j_max: float = 0.0

    @property
    def label(self):
        return f"{self.material.name.replace('_', ' ')} on the {_shaft_label(self.shaft.name)}"


def _shaft_label(name):
    return name if name.lower().endswith("shaft") else f"{name} shaft"


def _g(x):
    return f"{x:.3g}"


def _g_apart(a, b):
    """Format two numbers with as few significant digits as keep them apart."""
    for digits in range(3, 13):
        sa, sb = f"{a:.{digits}g}", f"{b:.{digits}g}"
        if sa != sb:
            return sa, sb
    return f"{a:.12g}", f"{b:.12g}"


def _explain_infeasible(combo, spec):
    """Say in words and numbers why a combination cannot give its inertia.

    Returns the sentence and the outer-diameter cap the combination would
    need (None when no cap would do).
    """
    m, geo = combo.material, spec.geometry
    word = {"rim": "rim", "thin_rim": "thin rim", "disc": "disc"}[geo]
    hb_min, hb_max = spec.hb_ratio
    if combo.cap_speed <= combo.cap:
        cap_text = f"the {_g(m.max_rim_speed)} m/s rim limit caps the outer diameter"
    else:
        cap_text = "the envelope (max_outer_diameter) caps the outer diameter"

    def need(j_text):
        text = f"{j_text} kg·m²"
        if combo.shaft.speed_ratio != 1.0:
            text += f" on this shaft ({_g(combo.j_reference)} kg·m² at the reference shaft)"
        return text

    pinned = spec.d_mean
    if pinned is not None and geo != "disc" and pinned >= combo.cap:
        cap, pin = _g_apart(combo.cap, pinned)
        return (f"{combo.label}: {cap_text} at {cap} m, which leaves no room for a rim "
                f"around the pinned mean diameter {pin} m"), None
    if pinned is not None and geo == "disc" and pinned > combo.cap:
        cap, pin = _g_apart(combo.cap, pinned)
        return (f"{combo.label}: {cap_text} at {cap} m, below the pinned diameter "
                f"{pin} m"), None
    needed, j_sup = _cap_needed(geo, m.density, combo.j_shaft, combo.cap, spec.hb_ratio,
                                spec.max_width, pinned)
    if needed is None:
        limits = []
        if pinned is not None:
            limits.append(f"{'D' if geo == 'disc' else 'D_m'} pinned at {_g(pinned)} m")
        if spec.max_width is not None:
            limits.append(f"B <= {_g(spec.max_width)} m")
        if geo != "disc":
            limits.append(f"{_g(hb_min)} <= H/B <= {_g(hb_max)}")
            limits.append("D_inner > 0")
        text = ", ".join(limits[:-1]) + " and " + limits[-1] if len(limits) > 1 else limits[0]
        j_sup_text, j_text = _g_apart(j_sup, combo.j_shaft)
        return (f"{combo.label}: even with no limit on the outer diameter, the largest "
                f"{word} with {text} gives {j_sup_text} kg·m², short of the "
                f"{need(j_text)} required"), None
    cap, needed_text = _g_apart(combo.cap, needed)
    return (f"{combo.label}: {cap_text} at {cap} m, where the smallest {word} that gives "
            f"{need(_g(combo.j_shaft))} still needs {needed_text} m"), needed


def _scales(combo, spec):
    """Scales (L, H_s, B_s) [m] of the non-dimensional variables.

    L is the outer-diameter cap (or the pinned diameter). For rims, H_s and
    B_s = H_s / hb_min are the thin-rim wheel of D_m = L and H/B = hb_min that
    gives exactly J' (so the inertia row reads >= 0 and x = 0 starts near the
    optimum); for a disc H_s is None and B_s is the width of the disc of
    diameter L that gives J'.
    """
    rho, j = combo.material.density, combo.j_shaft
    length = combo.cap if spec.d_mean is None else spec.d_mean
    if spec.geometry == "disc":
        b_s = 32.0 * j / (math.pi * rho * length ** 4)
        return length, None, b_s
    hb_min = spec.hb_ratio[0]
    h_s = math.sqrt(4.0 * j * hb_min / (math.pi * rho * length ** 3))
    return length, h_s, h_s / hb_min


def _solve(model, combo, spec):
    """Solve one feasible combination; return a Candidate or raise SolverFailed."""
    s = model.structure
    length, h_s, b_s = _scales(combo, spec)
    inf = math.inf
    n = len(model.variables)
    lbx, ubx, x0 = [-inf] * n, [inf] * n, [0.0] * n
    col = {name: i for i, name in enumerate(model.variables)}
    hb_min, hb_max = spec.hb_ratio
    p = []
    if s.geometry == "disc":
        if "diameter" in col:
            ubx[col["diameter"]] = 0.0                     # D <= cap = L
        if spec.max_width is not None:
            ubx[col["b"]] = math.log(spec.max_width / b_s)
        lbg, ubg = [0.0], [inf]
    else:
        log_eps = math.log(h_s / length)
        p = [log_eps]
        width_col = "h" if s.collapsed else "b"
        if spec.max_width is not None:
            ubx[col[width_col]] = math.log(spec.max_width / b_s)
        if s.pinned:
            room = min(combo.cap - spec.d_mean, spec.d_mean)
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
        raise SolverFailed(f"{combo.label}: IPOPT stopped with an error ({err}); "
                           f"no design is reported") from err
    elapsed = time.perf_counter() - start
    stats = model.solver.stats()
    status = stats.get("return_status", "unknown")
    iterations = int(stats.get("iter_count", -1))
    if status not in _CONVERGED:
        after = (f" after {iterations} iterations" if 0 <= iterations <= 10 ** 6 else "")
        err = SolverFailed(
            f"{combo.label}: IPOPT did not converge (return status {status!r}{after}), "
            f"although the closed-form bound shows the "
            f"combination is feasible (it can give up to {_g(combo.j_max)} kg·m², "
            f"{_g(combo.j_shaft)} needed); no design is reported")
        err.status = status
        err.combination = combo.label
        raise err
    xs = [float(v) for v in sol["x"].full().ravel()]

    def value(name, default=0.0):
        return xs[col[name]] if name in col else default

    rho = combo.material.density
    if s.geometry == "disc":
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
        j_wheel = _wheel_inertia(s.geometry, rho, d_mean, h, b)
    return _candidate_from_design(combo, spec, d_mean, h, b, mass, j_wheel,
                                  status, iterations, elapsed)


def _solve_closed_form(pending, spec):
    """Design feasible combinations by the exact closed form.

    Feasibility is already proven by :func:`max_inertia`; each design comes
    from :func:`flyopt.design.closed_form.lightest_one` (plain floats: a ranking is a few
    combinations, too few for numpy to pay), is recomputed with
    :mod:`flyopt.design.geometry` and verified like an IPOPT one.

    Returns (order, Candidate) pairs.
    """
    from flyopt.design import closed_form as batch

    hb_min, hb_max = spec.hb_ratio
    b_max = math.inf if spec.max_width is None else spec.max_width
    results = []
    for order, combo in pending:
        start = time.perf_counter()
        rho = combo.material.density
        d_mean, h, b = batch.lightest_one(spec.geometry, combo.j_shaft, rho, combo.cap, hb_min, hb_max,
                                          b_max, spec.d_mean)
        if spec.geometry == "disc":
            mass = geometry.disc_mass(2 * d_mean, b, rho)
            j_wheel = geometry.disc_inertia(mass, 2 * d_mean)
        else:
            mass = geometry.rim_mass(d_mean, h, b, rho)
            j_wheel = _wheel_inertia(spec.geometry, rho, d_mean, h, b)
        results.append((order, _candidate_from_design(combo, spec, d_mean, h, b, mass, j_wheel,
                                                      "closed_form", 0, time.perf_counter() - start)))
    return results


def _candidate_from_design(combo, spec, d_mean, h, b, mass, j_wheel, status, iterations,
                           elapsed):
    """Verify a solved design against every constraint and describe it."""
    m = combo.material
    d_outer = geometry.outer_diameter(d_mean, h)
    d_inner = geometry.inner_diameter(d_mean, h)
    speed = geometry.rim_speed(combo.omega, d_outer)
    stress = geometry.hoop_stress(m.density, speed)
    hb = h / b
    rim = spec.geometry != "disc"
    hb_min, hb_max = spec.hb_ratio
    tol = VERIFY_RTOL
    violations = []
    if j_wheel < combo.j_shaft * (1.0 - tol):
        violations.append(f"inertia {j_wheel:.9g} < {combo.j_shaft:.9g} kg·m²")
    if d_outer > combo.cap * (1.0 + tol):
        violations.append(f"outer diameter {d_outer:.9g} > cap {combo.cap:.9g} m")
    if spec.max_width is not None and b > spec.max_width * (1.0 + tol):
        violations.append(f"width {b:.9g} > {spec.max_width:.9g} m")
    if rim and not hb_min * (1.0 - tol) <= hb <= hb_max * (1.0 + tol):
        violations.append(f"H/B {hb:.9g} outside [{hb_min}, {hb_max}]")
    if rim and d_inner < -tol * d_outer:
        violations.append(f"inner diameter {d_inner:.9g} m < 0")
    if violations:
        source = ("the closed-form design" if status == "closed_form"
                  else f"IPOPT reported {status!r} but the design")
        err = SolverFailed(f"{combo.label}: {source} violates {'; '.join(violations)}; "
                           f"no design is reported")
        err.status = status
        err.combination = combo.label
        raise err
    rtol = ACTIVE_RTOL
    binding = []
    if j_wheel <= combo.j_shaft * (1.0 + rtol):
        binding.append("inertia")
    if d_outer >= combo.cap_speed * (1.0 - rtol):
        binding.append("rim_speed")
    if spec.max_outer_diameter is not None and d_outer >= spec.max_outer_diameter * (1 - rtol):
        binding.append("max_outer_diameter")
    if spec.max_width is not None and b >= spec.max_width * (1.0 - rtol):
        binding.append("max_width")
    if rim:
        if hb <= hb_min * (1.0 + rtol):
            binding.append("hb_min")
        if hb >= hb_max * (1.0 - rtol):
            binding.append("hb_max")
        if d_inner <= rtol * d_outer:
            binding.append("inner_diameter")
    cost = mass * m.cost if m.cost is not None else None
    objective = {"mass": mass, "outer_diameter": d_outer, "cost": cost}[spec.objective]
    return Candidate(
        material=m.name, shaft=combo.shaft.name, speed_ratio=combo.shaft.speed_ratio,
        geometry=spec.geometry, feasible=True,
        reason=f"{combo.label}: designed; binding: {', '.join(binding) or 'none'}",
        d_mean=d_mean, d_outer=d_outer, d_inner=max(d_inner, 0.0),
        h=h, b=b, hb_ratio=hb, mass=mass, rim_speed=speed, hoop_stress=stress,
        safety_factor=(m.allowable_stress / stress if m.allowable_stress else None),
        cost=cost, j_flywheel=j_wheel,
        j_at_reference=inertia_at_reference(j_wheel, combo.shaft.speed_ratio),
        binding=tuple(binding), objective=objective,
        j_required_on_shaft=combo.j_shaft, d_outer_limit=combo.cap,
        rim_speed_limit=m.max_rim_speed, j_max=combo.j_max, solver_status=status,
        iterations=iterations, solve_time=elapsed)


# --------------------------------------------------------------------------
# The designer
# --------------------------------------------------------------------------

def _check_unique(items, kind, cls):
    if isinstance(items, (str, bytes)) or not isinstance(items, Sequence):
        raise ValueError(f"{kind}s must be a sequence of {cls.__name__}, got {items!r}")
    if not items:
        raise ValueError(f"{kind}s must not be empty: give at least one {kind}")
    seen = set()
    for item in items:
        if not isinstance(item, cls):
            raise ValueError(f"{kind}s must hold {cls.__name__} objects, got {item!r}")
        if item.name in seen:
            raise ValueError(f"{kind} {item.name!r} is given twice")
        seen.add(item.name)


def design_flywheel(j_required: float, omega: float, shafts: Sequence[MountShaft],
                    materials: Sequence[Material], spec: DesignSpec = DesignSpec(), *,
                    solver_options: Mapping | None = None, method: str = "auto") -> DesignResult:
    """Design the flywheel: the best material, shaft and dimensions.

    Parameters
    ----------
    j_required : float
        J_F, the flywheel inertia required at the reference shaft [kg*m^2],
        already net of the machine's own inertia J_c (docs/flywheel-design.md, section 5:
        J_F = A_max / (omega_m^2 delta) - J_c). J_F <= 0: no flywheel needed.
    omega : float
        Speed of the reference shaft at which the rim speed is checked
        [rad/s]: the highest speed of the cycle, ω_max = ω_m (1 + δ/2) (or
        the periodic solution's maximum), where the hoop stress peaks.
    shafts : sequence of MountShaft
        Where the flywheel may go; speed ratios relative to the reference.
    materials : sequence of Material
        Materials to consider.
    spec : DesignSpec
        Geometry model, limits and objective.
    solver_options : mapping, optional
        CasADi/IPOPT options merged over :data:`DEFAULT_SOLVER_OPTIONS`; they
        act on the combinations IPOPT solves (all of them with method
        "ipopt", under "auto" only the structures the closed form does not
        cover).
    method : {"auto", "ipopt", "closed_form"}
        How a feasible combination is optimized: the exact closed form of
        :mod:`flyopt.design.closed_form` where it covers the structure (mass and cost
        objectives) and IPOPT elsewhere ("auto", the default; for the
        timings see benchmarks/results/speed_error.md); IPOPT on every NLP
        ("ipopt"); or the closed form only, refusing a
        structure it does not cover ("closed_form"). Either way the design
        is verified against every constraint before it is reported.

    Returns
    -------
    DesignResult
        ``status`` "designed" (with ``best``), "infeasible" (no combination
        can give the inertia; every candidate says why) or "not_needed".

    Raises
    ------
    ValueError
        On invalid arguments; for the ``cost`` objective when a material has
        no cost.
    SolverFailed
        When IPOPT does not converge on a combination the closed form shows
        feasible (the message carries IPOPT's return status), or when a
        solved or closed-form design fails its verification against the
        constraints. A design is never made from a non-converged solve.

    Notes
    -----
    Every combination is decided: the closed-form :func:`max_inertia` proves
    infeasibility exactly (no NLP is solved then); every feasible combination
    is solved to optimality. Ranking is by the objective, ties by mass.
    """
    j_required = _finite(j_required, "j_required [kg*m^2]")
    omega = _positive(omega, "omega", "[rad/s]")
    _check_unique(shafts, "shaft", MountShaft)
    _check_unique(materials, "material", Material)
    if not isinstance(spec, DesignSpec):
        raise ValueError(f"spec must be a DesignSpec, got {spec!r}")
    if spec.objective == "cost":
        missing = [m.name for m in materials if m.cost is None]
        if missing:
            raise ValueError(f"objective 'cost' needs a cost per kg on every material; "
                             f"missing for {missing}")
    _choice(method, ("ipopt", "auto", "closed_form"), "method")
    closed = False
    if method != "ipopt":
        from flyopt.design import closed_form as batch

        closed = batch.covers(spec.geometry, spec.objective, spec.d_mean is not None)
        if method == "closed_form" and not closed:
            raise ValueError(f"the closed form does not cover geometry {spec.geometry!r} with objective "
                             f"{spec.objective!r}; use method 'auto' or 'ipopt'")
    if j_required <= 0.0:
        return DesignResult(
            status="not_needed",
            message=(f"no flywheel needed: the required flywheel inertia J_F = "
                     f"{_g(j_required)} kg·m² is not positive, so the machine's own "
                     f"inertia already keeps the speed fluctuation within delta"),
            j_required=j_required, omega=omega, spec=spec)

    structure = ModelStructure(
        geometry=spec.geometry, pinned=spec.d_mean is not None,
        collapsed=spec.geometry != "disc" and spec.hb_ratio[0] == spec.hb_ratio[1],
        objective="outer_diameter" if spec.objective == "outer_diameter" else "mass")
    model = None if closed else get_model(structure, solver_options)
    envelope = math.inf if spec.max_outer_diameter is None else spec.max_outer_diameter

    feasible, infeasible, pending = [], [], []
    order = 0
    for material in materials:
        for shaft in shafts:
            shaft_omega = omega * shaft.speed_ratio
            cap_speed = geometry.outer_diameter_for_rim_speed(material.max_rim_speed, shaft_omega)
            combo = _Combination(
                material=material, shaft=shaft, omega=shaft_omega,
                j_shaft=inertia_on_shaft(j_required, shaft.speed_ratio),
                j_reference=j_required, cap_speed=cap_speed, cap=min(cap_speed, envelope))
            combo.j_max = max_inertia(spec.geometry, material.density, combo.cap,
                                      spec.hb_ratio, spec.max_width, spec.d_mean)[0]
            pinned_fits = spec.d_mean is None or (
                spec.d_mean <= combo.cap if spec.geometry == "disc"
                else spec.d_mean < combo.cap)
            if pinned_fits and combo.j_shaft <= combo.j_max:
                if closed:
                    pending.append((order, combo))
                else:
                    feasible.append((order, _solve(model, combo, spec)))
            else:
                reason, needed = _explain_infeasible(combo, spec)
                infeasible.append(Candidate(
                    material=material.name, shaft=shaft.name,
                    speed_ratio=shaft.speed_ratio, geometry=spec.geometry,
                    feasible=False, reason=reason, j_required_on_shaft=combo.j_shaft,
                    d_outer_limit=combo.cap, rim_speed_limit=material.max_rim_speed,
                    j_max=combo.j_max, d_outer_needed=needed))
            order += 1
    if pending:
        feasible += _solve_closed_form(pending, spec)
    feasible.sort(key=lambda item: (item[1].objective, item[1].mass, item[0]))
    ranked = tuple(c for _, c in feasible) + tuple(infeasible)
    best = feasible[0][1] if feasible else None
    if model is not None:
        description = model.describe()
    else:
        description = {"geometry": spec.geometry, "inertia_model": geometry.GEOMETRIES[spec.geometry],
                       "variables": [], "constraints": [], "pinned": ["d_mean"] if spec.d_mean is not None else [],
                       "formulation": ("exact closed form (flyopt.design.closed_form): outer diameter at its cap, "
                                       "a 1-D monotone root for the rim; verified against every constraint")}
    description["objective"] = spec.objective
    bounds = []
    if spec.max_width is not None:
        bounds.append("max_width: B <= max_width")
    if spec.geometry == "disc" and spec.d_mean is None:
        bounds.append("outer_diameter: D <= min(2 v_max/omega', max_outer_diameter)")
    if spec.geometry != "disc" and spec.d_mean is not None:
        bounds.append("outer_diameter and inner_diameter: H <= min(cap - D_m, D_m)")
    description["bounds"] = bounds
    description["limits"] = {"max_outer_diameter": spec.max_outer_diameter,
                             "max_width": spec.max_width, "hb_ratio": list(spec.hb_ratio),
                             "d_mean": spec.d_mean}
    if best is None:
        status = "infeasible"
        message = ("no material and shaft can give the required inertia: "
                   + "; ".join(c.reason for c in infeasible))
    else:
        status = "designed"
        message = (f"{best.material} on the {_shaft_label(best.shaft)}: {spec.geometry} "
                   f"D_outer {_g(best.d_outer)} m, B {_g(best.b)} m, mass "
                   f"{_g(best.mass)} kg ({len(feasible)} of {len(ranked)} combinations "
                   f"feasible)")
    return DesignResult(status=status, message=message, j_required=j_required,
                        omega=omega, spec=spec, best=best, candidates=ranked,
                        model=description)
