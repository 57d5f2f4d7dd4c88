"""The seat diameter d as a continuous variable of the whole-wheel NLP (issue 30, item 5; docs section 26).

Where a described shaft designs its seat (``diameter = "design"``), :func:`seat_optimum`
solves the wheel's NLP (:func:`flyopt.design.wheel_nlp.formulate`, the same rows, with
``bore`` the expression exp(x_d) of one more variable) together with the shaft's smooth
limits, rows of the same NLP:

- the hub on the bore: D_hub/d and L_hub/d within the textbook proportions
  (:func:`flyopt.design.hub.hub_proportions`, linear in d) and the hub wall on it, all
  symbolic in d; the key's shortest hub (:func:`flyopt.design.key.hub_length_for_key`,
  a step function of d through DIN 6885-1's sections and standard lengths) frozen at
  the round's d;
- DE-Goodman fatigue (Shigley 9th ed. Eq. (7-7)) and first-cycle yield (7-15, 7-16) at
  every section :func:`flyopt.design.shaft.check.check_shaft` checks (the keyseat of the
  seat, each shoulder, the plain sections at the bearings and loads), with
  :mod:`~flyopt.design.shaft.strength`'s own expressions written on the symbols: the
  bending moments linear in the NLP's wheel mass m (weight m g, permissible unbalance
  m G Omega_max) and the pulls (statics: a shaft on two bearings is statically
  determinate, so M does not depend on d); the section's d where its step is designed;
  the Marin size factor k_b = c d^e on the branch of Eq. (6-20) that holds the round's d;
  the keyseat's notch radius r = 0.02 d in q = 1/(1 + sqrt(a)/sqrt(r)) (6-34);
- the slope at each bearing and, where limited, the deflection at the wheel: the elastic
  line is affine in 1/(E I) of each step, so where the designed steps share d it is
  a + b (d_0/d)^4, a and b from :func:`flyopt.design.shaft.beam.elastic_line` at two d.

Frozen per round, the NLP re-solved with them at its own d until d moves by less than
:data:`TOLERANCE` (a fixed point): the torque T_m, T_a at the seat (the train's forced
response, :func:`flyopt.design.shaft.train.seat_torque`, a resonance effect: not smooth
in d), S_ut and S_y (the material's table by thickness: steps), the notch table's row and
which side of a shoulder is the smaller, the k_b branch and the key's hub length.

The objective is the wheel's mass and the steel of the designed steps (the wheel's alone can fall as the bore
grows: an annulus on its bore), with ln d weighted :data:`TIE_BREAK`. The wheel's stress rows take the material's
strongest allowable (a relaxation: the
designer's own wheel, designed on the series value, settles them by the exact maxima).
Not rows: the lateral critical speed (a beam-FE eigenvalue) and the torsional modes
against the cycle's orders (which a mode crosses non-monotonically as d grows): the
post-check of the wheel designed on the series value (:mod:`flyopt.design.shaft.diameter`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from flyopt.design import hub
from flyopt.design.balance import BALANCE_GRADE, permissible_unbalance
from flyopt.design.nlp import CONVERGED, DEFAULT_SOLVER_OPTIONS
from flyopt.design.shaft import strength
from flyopt.design.shaft.beam import SteppedShaft, elastic_line
from flyopt.design.shaft.check import bearing_place, carries_torque, notch_geometry, section_name, section_strengths
from flyopt.design.shaft.lateral import GRAVITY
from flyopt.names import Objective

if TYPE_CHECKING:
    from flyopt.design.combination import Combination
    from flyopt.design.materials import Material
    from flyopt.design.shaft.cycle import ShaftContext
    from flyopt.design.spec import DesignSpec
    from flyopt.machine.shaft_layout import ShaftLayout

__all__ = ["SeatOptimum", "SeatRow", "SeatChoice", "seat_optimum", "TOLERANCE", "MAX_ROUNDS"]

#: The fixed point is reached when d moves by less than this, relative, between two rounds.
TOLERANCE = 1e-7
#: Rounds of the fixed point before it is given up (its last two d then reported, the smaller used).
MAX_ROUNDS = 12
#: Weight of ln d in the objective: where the wheel's objective does not grow with d (no hub, or the outer
#: diameter objective) the smallest d the rows allow is taken; elsewhere it moves ln m's multipliers by ~1e-6.
TIE_BREAK = 1e-6
#: Added to squares under a root [N^2 m^2 or rad^2]: keeps a row differentiable where a load vanishes.
_TINY = 1e-18
_IPOPT: dict[str, Any] = {**DEFAULT_SOLVER_OPTIONS, "ipopt.max_iter": 1000}
#: IPOPT from the last round's solution and multipliers (the rounds move d by a little): a small barrier
#: parameter and pushes, so it starts where the last round ended; a round it does not solve is solved cold.
_WARM: dict[str, Any] = {
    "ipopt.warm_start_init_point": "yes",
    "ipopt.mu_init": 1e-6,
    "ipopt.warm_start_bound_push": 1e-9,
    "ipopt.warm_start_slack_bound_push": 1e-9,
    "ipopt.warm_start_mult_bound_push": 1e-9,
}


@dataclass(frozen=True)
class SeatRow:
    """A shaft row of the seat's NLP at its solution: its kind (fatigue, yield, slope, deflection), where, the
    utilisation (<= 1 holds) and its multiplier d(ln m)/d(ln limit) (0: not binding)."""

    kind: str
    where: str
    utilisation: float
    multiplier: float

    @property
    def name(self) -> str:
        """The row in words, e.g. ``"fatigue at the keyseat at the wheel seat"``."""
        return f"{self.kind} " + self.where


@dataclass(frozen=True)
class SeatOptimum:
    """The NLP's continuous seat diameter and what set it.

    Attributes
    ----------
    diameter : float
        d* [m] (nan: the NLP gave none; ``reason`` says why).
    mass : float
        The NLP's wheel mass at d* [kg] (``inertia``: its J [kg*m^2]; ``shaft_mass``: the designed steps' [kg]).
    status : str
        IPOPT's return status of the last round.
    rounds : int
        NLP solves of the fixed point.
    converged : bool
        Whether the frozen values met their d (the last two rounds' d within :data:`TOLERANCE`).
    history : tuple of float
        d of each round [m].
    rows : tuple of SeatRow
        The shaft's rows at the solution, binding first.
    lower_bound : bool
        d* sits on the lower end of the range searched (no shaft row sets it).
    reason : str or None
        Why there is no d*.
    """

    diameter: float
    mass: float
    status: str
    rounds: int
    converged: bool
    history: tuple[float, ...]
    rows: tuple[SeatRow, ...] = ()
    lower_bound: bool = False
    reason: str | None = None
    inertia: float = math.nan
    shaft_mass: float = 0.0

    @property
    def binding(self) -> SeatRow | None:
        """The shaft row with the largest multiplier, where one binds."""
        active = [r for r in self.rows if r.multiplier > 0.0]
        return max(active, key=lambda r: r.multiplier) if active else None

    def mass_sensitivity(self, safety_factor: float) -> float:
        """d(m)/d(n) [kg] of the binding row's required factor n, m the objective's mass (the wheel and the
        designed steps: its multiplier is d(ln m)/d(ln n)) with the
        round's frozen values held (the seat torque, the strengths): where the torque moves with d the fixed
        point's own slope differs (docs section 26); nan: no row binds."""
        row = self.binding
        return (self.mass + self.shaft_mass) * row.multiplier / safety_factor if row is not None else math.nan


@dataclass(frozen=True)
class SeatChoice:
    """A combination's designed seat: the NLP's d* (None: not run), where the series walk started, the series
    value chosen and which limit set it (with d(m)/d(n) [kg] where a row of the NLP did)."""

    optimum: SeatOptimum | None
    start: float
    diameter: float = math.nan
    set_by: str = ""
    by_nlp: bool = False
    note: str = ""

    def sensitivity(self, safety_factor: float) -> float:
        """d(wheel mass)/d(required factor of the binding row) [kg]; nan where no row of the NLP set the seat."""
        if not self.by_nlp or self.optimum is None:
            return math.nan
        return self.optimum.mass_sensitivity(safety_factor)


@dataclass(frozen=True)
class _Frozen:
    """What a round holds fixed: the seat torque, each section's strengths and notch and the key's hub length."""

    diameter: float
    torque_mean: float
    torque_alternating: float
    sections: tuple[dict[str, Any], ...]
    key_length: float


def _designed_length(layout: ShaftLayout) -> float:
    """The length of the shaft's designed steps [m] (their diameter is d)."""
    starts = (0.0, *layout.steps[:-1])
    return sum(end - start for j, (start, end) in enumerate(zip(starts, layout.steps)) if j in layout.designed)


def _designed_at(layout: ShaftLayout, x: float) -> bool:
    """Whether the step holding x (at a step end, the step that ends there) is a designed one."""
    for j, end in enumerate(layout.steps):
        if x <= end:
            return j in layout.designed
    return len(layout.steps) - 1 in layout.designed


def _sections(layout: ShaftLayout, d: float) -> list[dict[str, Any]]:
    """Every section the check looks at with the shaft's designed steps at ``d``, and whether its diameter is d:
    the keyseat, a shoulder beside a designed step (also where the two sides are equal at d: a neighbour of d),
    the plain sections at the bearings and loads (:func:`flyopt.design.shaft.check._sections`' list)."""
    seated = layout.with_seat(d)
    out = [
        {
            "x": layout.wheel_at,
            "name": "keyseat at the wheel seat",
            "kind": "keyseat",
            "d": seated.diameter_at(layout.wheel_at),
            "designed": _designed_at(layout, layout.wheel_at),
        }
    ]
    for j, end in enumerate(layout.steps[:-1]):
        d0, d1 = seated.diameters[j], seated.diameters[j + 1]
        either = j in layout.designed or j + 1 in layout.designed
        if d0 != d1 or (either and not (j in layout.designed and j + 1 in layout.designed)):
            small = min(d0, d1)
            # the smaller side is the designed one where d is the smaller (at equality: the side that moves)
            designed = (j in layout.designed and d0 <= d1) or (j + 1 in layout.designed and d1 <= d0)
            out.append(
                {
                    "x": end,
                    "name": section_name("shoulder", end),
                    "kind": "shoulder",
                    "d": small,
                    "designed": designed,
                }
            )
    for x, what in [(b, "bearing") for b in layout.bearings] + [(load.position, "load") for load in layout.loads]:
        out.append(
            {
                "x": x,
                "name": section_name(what, x),
                "kind": None,
                "d": seated.diameter_at(x),
                "designed": _designed_at(layout, x),
            }
        )
    return out


def _freeze(ctx, name, layout, material, d, mass, inertia, key_length) -> _Frozen:
    """The round's frozen values at seat d [m] with the last round's wheel (m [kg], J [kg m^2])."""
    from flyopt.design.shaft.cycle import checked_at

    check = checked_at(ctx, name, mass, inertia, 0.0, d)  # the post-check's own torque at the seat
    sections = []
    for s in _sections(layout, d):
        sut, sy, se = section_strengths(material, s["d"], layout.finish)
        s = {**s, "sut": sut, "sy": sy, "se": se, "e": strength.size_exponent(s["d"])}
        if s["kind"] is not None:
            kt, kts, r_over_d = notch_geometry(s["kind"], s["d"], layout.fillet)
            fixed = s["kind"] == "shoulder" and layout.fillet is not None
            s.update(
                kt=kt,
                kts=kts,
                radius=layout.fillet if fixed else None,
                r_over_d=r_over_d,
                root_a=float(strength.neuber_root_a(sut, "bending")),
                root_as=float(strength.neuber_root_a(sut, "torsion")),
            )
        sections.append(s)
    return _Frozen(d, abs(check.torque_mean), check.torque_alternating, tuple(sections), key_length)


def _line_terms(layout: ShaftLayout, material: Material, d: float, positions, forces, at) -> dict[str, np.ndarray]:
    """Moment, and slope and deflection as a + b (d/x)^4 in the designed steps' x, at ``at`` under the forces."""
    e = float(material.elastic_modulus or 0.0)
    lines = []
    for scale in (1.0, 2.0):
        seated = layout.with_seat(d * scale)
        beam = SteppedShaft(seated.steps, seated.diameters, e, seated.bearings, density=material.density)
        lines.append(elastic_line(beam, positions, forces, at=at))
    out = {"moment": lines[0].moment}
    for what in ("slope", "deflection"):
        v1, v2 = getattr(lines[0], what), getattr(lines[1], what)
        b = (v1 - v2) * 16.0 / 15.0  # v(d) = a + b (d_0/d)^4: v(d_0) = a + b, v(2 d_0) = a + b/16
        out[what + "_a"], out[what + "_b"] = v1 - b, b
    return out


def _loads(layout: ShaftLayout, material: Material, d: float, omega_max: float, at: np.ndarray) -> dict[str, Any]:
    """Per unit wheel mass and from the pulls: the moments, slopes and deflections at ``at`` (two planes and the
    unbalance), as :func:`flyopt.design.shaft.check.check_shaft` assembles them."""
    grade = BALANCE_GRADE if layout.balance_grade is None else layout.balance_grade * 1e3  # [mm/s]
    per_kg = permissible_unbalance(1.0, omega_max, grade).u_per * omega_max**2  # F_u = U_per Omega^2 [N/kg]
    pulls_x = [load.position for load in layout.loads]
    weight = _line_terms(layout, material, d, [layout.wheel_at], [-GRAVITY], at)  # per kg, downward
    unbalance = _line_terms(layout, material, d, [layout.wheel_at], [per_kg], at)
    if pulls_x:
        fy = [-load.force * math.cos(load.angle) for load in layout.loads]
        fz = [load.force * math.sin(load.angle) for load in layout.loads]
        py = _line_terms(layout, material, d, pulls_x, fy, at)
        pz = _line_terms(layout, material, d, pulls_x, fz, at)
    else:
        zero = {k: np.zeros(len(at)) for k in weight}
        py = pz = zero
    return {"weight": weight, "unbalance": unbalance, "y": py, "z": pz}


def _affine(terms: dict[str, np.ndarray], what: str, i: int, ratio4: Any) -> Any:
    return float(terms[what + "_a"][i]) + float(terms[what + "_b"][i]) * ratio4


def seat_optimum(
    ctx: ShaftContext,
    name: str,
    combo: Combination,
    spec: DesignSpec,
    n_arms: int,
    d_range: tuple[float, float],
    d_start: float,
    solver_options: Mapping[str, Any] | None = None,
    *,
    fixed_point: bool = True,
    wheel: tuple[float, float] | None = None,
) -> SeatOptimum:
    """d* of a combination's wheel on the designed seat of shaft ``name``, by the fixed point above.

    ``d_range`` [m] bounds d (the series' range the checks support); ``d_start`` [m] is the first round's d.
    ``fixed_point=False`` solves one round, its values frozen at ``d_start`` with the wheel ``wheel`` (m [kg],
    J [kg*m^2]; default: the thin ring of the required inertia): the NLP whose multipliers the sensitivity reads.
    The fixed point d = F(d), F the NLP's d with the values frozen at d, is found by the secant method on
    F(d) - d, bracketed (Illinois) once two rounds fall on either side; a round IPOPT does not solve ends the
    search with its status (the walk then starts at its floor).
    """
    from flyopt.design import wheel as wheel_module
    from flyopt.design import wheel_nlp
    from flyopt.design.shaft.cycle import key_torque_on
    from flyopt.design.wheel_design import hub_bounds, strongest_allowables, wheel_problem

    layout = ctx.shafts[name].layout
    if layout is None or not layout.designs_seat:
        raise ValueError(f"shaft {name!r} does not design its seat")
    material = ctx.materials[name]
    wheel_material = combo.material
    structure, problem = wheel_problem(
        wheel_material, spec, d_start, combo.torque, n_arms, combo.j_shaft, combo.omega, combo.v_max
    )
    problem = dataclasses.replace(
        problem,
        allowable=strongest_allowables(wheel_material, spec, structure),
        d_hub_range=(0.0, math.inf),
        l_hub_range=(0.0, math.inf),
    )
    names = wheel_nlp.variables_of(structure)
    start = wheel_nlp.starting_wheel(structure, problem, names)
    ring = wheel_nlp.dims_of(structure, start, d_start)
    r = ctx.shafts[name].speed_ratio
    omega_max = ctx.omega_mean * r * (1.0 + 0.5 * ctx.delta)
    model = _Model(
        structure, problem, names, layout, material, wheel_material, omega_max, d_range, start, solver_options
    )
    state: dict[str, Any] = {
        "mass": float(wheel_module.wheel_mass(wheel_module.parts(structure.geometry, ring, wheel_material.density))),
        "inertia": combo.j_shaft,
        "wheel": start,
    }
    if wheel is not None:
        state.update(mass=wheel[0], inertia=wheel[1])
    evaluations: list[tuple[float, float, dict[str, Any]]] = []  # (d frozen at, F(d), the round's result)

    def round_at(d: float) -> dict[str, Any]:
        key_length = 0.0  # the key's shortest hub where it is longer than the proportions' shortest, else none
        if structure.has_hub:
            # the key's torque at this round's d (the train stiffens with d), as the designer's on the series value
            keyed = key_torque_on(ctx, name, combo.j_shaft, d)
            shortest = hub_bounds(wheel_material, d, combo.torque if keyed is None else keyed)[1][0]
            if shortest > hub.hub_proportions(d, wheel_material.hub_kind).l_hub_min * (1.0 + 1e-12):
                key_length = shortest
        frozen = _freeze(ctx, name, layout, material, d, state["mass"], state["inertia"], key_length)
        result = model.solve(frozen, state["wheel"])
        if result["status"] not in CONVERGED:
            return result
        state.update(mass=result["mass"], inertia=result["inertia"], wheel=result["wheel"])
        evaluations.append((d, result["d"], result))
        return result

    d = min(max(d_start, d_range[0]), d_range[1])
    status = "not run"
    for _ in range(MAX_ROUNDS):
        result = round_at(d)
        status = result["status"]
        if status not in CONVERGED:
            return SeatOptimum(
                math.nan,
                math.nan,
                status,
                len(evaluations) + 1,
                False,
                tuple(e[1] for e in evaluations),
                reason=f"IPOPT did not solve the seat's NLP (return status {status!r})",
            )
        if abs(result["d"] - d) <= TOLERANCE * d or not fixed_point:
            break
        d = _next(evaluations, d_range)
    last_d, f_last, result = evaluations[-1]
    converged = abs(f_last - last_d) <= TOLERANCE * last_d or not fixed_point
    history = tuple(e[1] for e in evaluations)
    d_star = f_last if converged else min(history[-2:])
    return SeatOptimum(
        d_star,
        result["mass"],
        status,
        len(evaluations),
        converged,
        history,
        result["rows"],
        result["lower"],
        None if converged else "the fixed point did not settle: the smaller of its last two d is used",
        result["inertia"],
        result["steel"],
    )


def _next(evaluations: list[tuple[float, float, dict[str, Any]]], d_range: tuple[float, float]) -> float:
    """The next d of the fixed point: F(d) after one round, then the secant on h = F(d) - d through the last
    two rounds, bracketed by the latest rounds on either side of h = 0 once there are such (regula falsi)."""
    d, f, _ = evaluations[-1]
    if len(evaluations) < 2:
        return f
    h = [(e[0], e[1] - e[0]) for e in evaluations]
    above = [p for p in h if p[1] > 0.0]
    below = [p for p in h if p[1] < 0.0]
    if above and below:
        (d0, h0), (d1, h1) = above[-1], below[-1]
    else:
        (d0, h0), (d1, h1) = h[-2], h[-1]
    if h1 == h0:
        return f
    nxt = d1 - h1 * (d1 - d0) / (h1 - h0)
    if above and below and not min(d0, d1) < nxt < max(d0, d1):
        nxt = 0.5 * (d0 + d1)
    return min(max(nxt, d_range[0]), d_range[1])


class _Model:
    """The seat's NLP, built once per shape of its shaft rows (which sections have d, the notch rows, the
    k_b branches, the hub's key rows), with every frozen value a parameter."""

    def __init__(
        self, structure, problem, names, layout, material, wheel_material, omega_max, d_range, start, solver_options
    ) -> None:
        self.structure, self.problem, self.names = structure, problem, names
        self.layout, self.material, self.wheel_material = layout, material, wheel_material
        self.omega_max, self.d_range = omega_max, d_range
        self.scale = problem.density * problem.omega**2 * (start["d_outer"] / 2.0) ** 2
        self.options = {**_IPOPT, **{k: v for k, v in (solver_options or {}).items() if k.startswith("ipopt.")}}
        self.built: dict[tuple[Any, ...], Any] = {}
        self.iterations: list[int] = []  # IPOPT's iterations of each round
        self.last: tuple[Any, ...] | None = None  # the last round's (shape, x, lam_x, lam_g), its warm start
        self.loads: dict[str, Any] | None = None

    def _shape(self, frozen: _Frozen) -> tuple[Any, ...]:
        sections = tuple(
            (
                s["x"],
                s["designed"],
                s["kind"],
                s.get("kt"),
                s.get("kts"),
                s.get("radius"),
                s.get("r_over_d") if s.get("radius") is None else None,  # a fillet's r/d follows d: not the shape
                None if s["designed"] else s["d"],
            )
            for s in frozen.sections
        )
        return sections

    def solve(self, frozen: _Frozen, wheel_start: Mapping[str, float]) -> dict[str, Any]:
        """One round: IPOPT on the NLP with ``frozen`` as its parameters, from ``wheel_start`` and the round's d."""
        from flyopt.design import wheel_nlp

        shape = self._shape(frozen)
        if shape not in self.built:
            self.built[shape] = self._build(frozen)
        solvers, evaluate, shaft_rows, lbg, ubg, first = self.built[shape]
        warm = solvers[1]
        lbx, ubx, _ = wheel_nlp.variable_bounds(self.structure, self.problem)
        lo_d, hi_d = math.log(self.d_range[0]), math.log(self.d_range[1])
        x0 = [min(max(math.log(wheel_start[n]), lo), hi) for n, lo, hi in zip(self.names, lbx, ubx)]
        x0.append(min(max(math.log(frozen.diameter), lo_d), hi_d))
        longer = 0.0
        if self.structure.has_hub:
            ratios = hub.hub_proportions(1.0, self.wheel_material.hub_kind)
            longer = 1.0 if frozen.key_length > ratios.l_hub_max * frozen.diameter else 0.0
        log_key = math.log(frozen.key_length) if frozen.key_length > 0.0 else math.log(1e-6)
        p = [frozen.torque_alternating, frozen.torque_mean, log_key, longer]
        for s in frozen.sections:
            p += [s["sut"], s["sy"], s["se"], s["d"], s.get("root_a", 0.0), s.get("root_as", 0.0), s["e"]]
        bounds = {"lbx": lbx + [lo_d], "ubx": ubx + [hi_d], "lbg": lbg, "ubg": ubg, "p": p}
        if self.last is not None and self.last[0] == shape:  # from the last round's point and multipliers
            sol = warm(x0=self.last[1], lam_x0=self.last[2], lam_g0=self.last[3], **bounds)
        else:  # the first round: from the start, no multipliers
            sol = warm(x0=x0, **bounds)
        stats = warm.stats()
        if stats.get("return_status") not in CONVERGED:  # IPOPT cold, its own start (built where first needed)
            if not isinstance(solvers[0], ca.Function):
                solvers[0] = ca.nlpsol("seat", "ipopt", solvers[0], self.options)
            sol = solvers[0](x0=x0, **bounds)
            stats = solvers[0].stats()
        status = stats.get("return_status", "unknown")
        if status in CONVERGED:
            self.last = (shape, sol["x"], sol["lam_x"], sol["lam_g"])
        self.iterations.append(int(stats.get("iter_count", -1)))
        nw = len(self.names)
        xv = sol["x"].full().ravel()
        g = sol["g"].full().ravel()
        lam = sol["lam_g"].full().ravel()
        rows = []
        for k, (kind, where) in enumerate(shaft_rows):
            j = first + k
            active = abs(float(g[j])) <= wheel_nlp.ACTIVE_ROW
            rows.append(SeatRow(kind, where, math.exp(float(g[j])), float(lam[j]) if active and lam[j] > 0 else 0.0))
        rows.sort(key=lambda row: (-row.multiplier, -row.utilisation))
        mass, inertia, steel = (float(v) for v in evaluate(xv))
        return {
            "status": status,
            "d": math.exp(float(xv[nw])),
            "mass": mass,
            "steel": steel,
            "inertia": inertia,
            "wheel": {n: math.exp(float(v)) for n, v in zip(self.names, xv[:nw])},
            "rows": tuple(rows),
            "lower": abs(float(xv[nw]) - lo_d) <= wheel_nlp.ACTIVE_ROW,
        }

    def _build(self, frozen: _Frozen) -> tuple[Any, ...]:
        from flyopt.design import wheel_nlp

        structure, problem, layout = self.structure, self.problem, self.layout
        nw = len(self.names)
        x = ca.SX.sym("x", nw)
        xd = ca.SX.sym("log_d")
        d = ca.exp(xd)
        ta, tm, log_key, key_longer = ca.SX.sym("ta"), ca.SX.sym("tm"), ca.SX.sym("log_key"), ca.SX.sym("key_longer")
        params = [ta, tm, log_key, key_longer]
        par = {
            "omega": problem.omega,
            "density": problem.density,
            "poisson": problem.poisson,
            "torque": problem.torque,
            "bore": d,
            "stress_scale": self.scale,
            "log_half_omega": math.log(problem.omega / 2.0),
        }
        allow = wheel_nlp.allowable_parameters(structure, problem.allowable, self.scale)
        form = wheel_nlp.formulate(structure, x, par, allow)
        rows, names_g = list(form.rows), list(form.row_names)
        lbg, ubg = wheel_nlp.row_bounds(structure, names_g, problem)
        col = {n: x[k] for k, n in enumerate(self.names)}
        inf = math.inf

        def add(name, expr, lo, hi):
            rows.append(expr)
            names_g.append(name)
            lbg.append(lo)
            ubg.append(hi)

        d0 = frozen.diameter
        if structure.has_hub:  # the textbook proportions on the bore, symbolic; the key's length frozen
            p = hub.hub_proportions(1.0, self.wheel_material.hub_kind)
            add("hub_diameter", col["d_hub"] - xd, math.log(p.d_hub_min), math.log(p.d_hub_max))
            add("hub_length_min", col["l_hub"] - xd, math.log(p.l_hub_min), inf)
            # the key's shortest hub, ln l_key frozen (a parameter: ln of a micrometre where no key is asked)
            add("hub_length_key", col["l_hub"] - log_key, 0.0, inf)
            # at most the proportions' longest, or the key's where it is longer (key_longer 1, frozen); a disc's
            # hub as a web wheel's (wheel_design.wheel_problem: the same hub_bounds)
            longest = key_longer * log_key + (1.0 - key_longer) * (xd + math.log(p.l_hub_max))
            add("hub_length_max", col["l_hub"] - longest, -inf, 0.0)

        m = form.mass
        xs = np.array([s["x"] for s in frozen.sections])
        if self.loads is None:  # moments, and slopes as a + b' / d^4: the same at every round's d
            self.loads = _loads(layout, self.material, d0, self.omega_max, xs)
            self.loads["d0"] = d0
        loads = self.loads
        ratio4 = (loads["d0"] / d) ** 4
        on = carries_torque(layout, xs)
        n_req = layout.safety_factor
        shaft_rows: list[tuple[str, str]] = []
        first = len(rows)
        for i, s in enumerate(frozen.sections):
            sut, sy, se0, d_frozen, root_a, root_as, e = (
                ca.SX.sym(f"{k}_{i}") for k in ("sut", "sy", "se", "d", "ra", "rs", "e")
            )
            params += [sut, sy, se0, d_frozen, root_a, root_as, e]
            ds = d if s["designed"] else s["d"]
            my = m * float(loads["weight"]["moment"][i]) + float(loads["y"]["moment"][i])
            mz = float(loads["z"]["moment"][i])
            ma = ca.sqrt(my * my + mz * mz + _TINY)
            mm = m * abs(float(loads["unbalance"]["moment"][i]))
            t_a, t_m = (ta, tm) if on[i] else (0.0, 0.0)
            if s["kind"] is None:
                kf = kfs = 1.0
            else:
                radius = s["radius"] if s["radius"] is not None else s["r_over_d"] * ds
                q = strength.sensitivity_of(root_a, radius, ca.sqrt)
                qs = strength.sensitivity_of(root_as, radius, ca.sqrt)
                kf, kfs = 1.0 + q * (s["kt"] - 1.0), 1.0 + qs * (s["kts"] - 1.0)
            se = se0 * (ds / d_frozen) ** e if s["designed"] else se0
            a, b = strength.de_terms(ma, t_a, mm, t_m, kf, kfs, lambda v: ca.sqrt(v + _TINY))
            bracket = strength._criterion_sum("goodman", a, b, se, sut, sy)
            add(f"shaft_fatigue {i}", ca.log(n_req * 16.0 * bracket / (math.pi * ds**3)), -inf, 0.0)
            shaft_rows.append(("fatigue", "at the " + s["name"]))
            peak = strength.von_mises_peak(ds, mm + ma, t_m + t_a, kf, kfs, lambda v: ca.sqrt(v + _TINY))
            add(f"shaft_yield {i}", ca.log(n_req * peak / sy), -inf, 0.0)
            shaft_rows.append(("yield", "at the " + s["name"]))
        for label, bearing in zip(("A", "B"), layout.bearings):
            i = int(np.argmin(np.abs(xs - bearing)))
            add(f"shaft_slope {label}", ca.log(_slope_expr(loads, "slope", i, m, ratio4) / layout.max_slope), -inf, 0.0)
            shaft_rows.append(("slope", bearing_place(label, bearing)))
        if layout.max_deflection is not None:  # section 0, the keyseat, is at the wheel
            deflection = _slope_expr(loads, "deflection", 0, m, ratio4)
            add("shaft_deflection", ca.log(deflection / layout.max_deflection), -inf, 0.0)
            shaft_rows.append(("deflection", "at the wheel"))
        xall = ca.vertcat(x, xd)
        steel = _designed_length(layout) * self.material.density * math.pi / 4.0 * d * d  # the designed steps
        objective = form.objective + TIE_BREAK * xd
        if structure.objective == Objective.MASS:  # the wheel and the shaft's designed steps (their reason: above)
            objective = ca.log(form.mass + steel) + TIE_BREAK * xd
        nlp = {"x": xall, "p": ca.vertcat(*params), "f": objective, "g": ca.vertcat(*rows)}
        warm = ca.nlpsol("seat_warm", "ipopt", nlp, {**self.options, **_WARM})
        evaluate = ca.Function("mass_inertia", [xall], [form.mass, form.inertia, steel])
        return [nlp, warm], evaluate, shaft_rows, lbg, ubg, first


def _slope_expr(loads, what, i, m, ratio4):
    """|theta| (or |y|) at point i as the check adds them: the two planes as a vector, the unbalance in magnitude."""
    vy = m * _affine(loads["weight"], what, i, ratio4) + _affine(loads["y"], what, i, ratio4)
    vz = _affine(loads["z"], what, i, ratio4)
    vu = m * _affine(loads["unbalance"], what, i, ratio4)
    return ca.sqrt(vy * vy + vz * vz + _TINY) + ca.sqrt(vu * vu + _TINY)
