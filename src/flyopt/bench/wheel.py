"""The wheel section: whole wheels by flyopt's IPOPT path, by SLSQP with CasADi gradients and by a grid.

Cases: the whole-wheel combinations that ``flyopt solve problems/punch-press-wheel.toml``
designs (each material × shaft the designer hands to
:func:`flyopt.design.wheel_design.design_combination`, captured from one solve of
the scene), and a few seeded random wheels (:func:`random_wheel_cases`). Each
case is one wheel NLP (:func:`flyopt.design.wheel_nlp.formulate`): its
structure, its bounds (:func:`~flyopt.design.wheel_nlp.variable_bounds`,
:func:`~flyopt.design.wheel_nlp.row_bounds`), its parameters and its start
(:func:`~flyopt.design.wheel_nlp.starting_wheel`), with the allowable stresses
and caps of the scene's design where the stress check settled them. Methods:

``flyopt-ipopt``
    flyopt's own path, the call a user's solve makes: for the scene's
    combinations the whole design (``design_combination`` with method
    "ipopt", the NLP path: the NLP by the wheel's default solver, sqpmethod
    with IPOPT behind it, its status checked, the exact stress check and
    any re-solve); for a random wheel :func:`flyopt.design.wheel_nlp.solve`.
    A non-converged solve raises and gives no design. (The label is the
    method's name, "ipopt" as against the closed form.)
``flyopt-nlp``
    For the scene's combinations, the same NLP alone by
    :func:`flyopt.design.wheel_nlp.solve` (status checked): what SLSQP
    and the grid do, without the design's stress check.
``slsqp``
    ``scipy.optimize.minimize(method="SLSQP")`` on the same NLP: the
    objective, the rows and their Jacobians evaluated by CasADi functions of
    the same :func:`~flyopt.design.wheel_nlp.formulate`, from the same start.
    Counted only where SLSQP reports success and the rows hold to
    :data:`COUNT_TOL` when evaluated again.
``grid``
    A brute-force grid over the NLP's variables, log-spaced in a box read
    from the problem's limits (:func:`grid_box`), every point checked by the
    same rows to :data:`REFERENCE_TOL`; the lightest feasible point.

Error: relative excess mass over the best known mass of the case, the least
mass of every method's result whose rows hold to :data:`REFERENCE_TOL`.
Time: median per call over ``design_repeats`` repeats after a warm-up (the
wheel's CasADi functions and IPOPT's NLP built beforehand).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import optimize

from flyopt.bench.peers import SLSQP_FTOL
from flyopt.bench.timing import Config, Row, measure, set_ratios
from flyopt.design.check import VERIFY_RTOL
from flyopt.design.wheel import Dims
from flyopt.errors import SolverFailed

__all__ = [
    "SCENE",
    "COUNT_TOL",
    "REFERENCE_TOL",
    "GRIDS",
    "QUICK_GRIDS",
    "WheelCase",
    "WheelNlp",
    "scene_cases",
    "WHEEL_STRUCTURES",
    "random_wheel",
    "random_wheel_cases",
    "grid_box",
    "slsqp_wheel",
    "grid_wheel",
    "wheel_rows",
    "section_wheel",
]

SCENE = Path(__file__).resolve().parents[3] / "problems" / "punch-press-wheel.toml"
"""The shipped whole-wheel scene (in a source checkout; the section runs the random wheels alone without it)."""
COUNT_TOL = VERIFY_RTOL
"""A result counts as a design if no row or bound of its NLP is violated by more than this (rows are of order one)."""
REFERENCE_TOL = 1e-9
"""A result may set the best known mass only if no row or bound is violated by more than this."""
GRIDS = (5, 8)
"""Grid points per variable of a full run (a 6-variable wheel on 8 per variable: 262,144 points)."""
QUICK_GRIDS = (5,)
"""Grid points per variable of a quick run."""
_CHUNK = 20_000  # grid points per CasADi map call


@dataclass
class WheelCase:
    """One whole wheel: its NLP and flyopt's call that designs it (returns the wheel's Dims)."""

    name: str
    structure: Any  # flyopt.design.wheel_nlp.WheelStructure
    problem: Any  # flyopt.design.wheel_nlp.WheelProblem
    flyopt: Callable[[], Dims]
    path: str  # what the flyopt call is, for the note
    solution: Any = None  # flyopt's WheelSolution of this NLP, to check the bench's parameters against
    nlp_only: Callable[[], Dims] | None = None  # flyopt's IPOPT solve of the NLP alone, where flyopt does more


class WheelNlp:
    """A case's wheel NLP as numbers: CasADi functions of (x, p) and its bounds, start and parameters.

    The arguments are those :func:`flyopt.design.wheel_nlp.solve` hands IPOPT; the
    stress scale and allowable parameters are checked against flyopt's own
    solution where one is given.
    """

    def __init__(self, case: WheelCase) -> None:
        import casadi as ca

        from flyopt.design import wheel_nlp

        s, problem = case.structure, case.problem
        self.names = wheel_nlp.variables_of(s)
        n_par = len(wheel_nlp.PARAMETERS)
        parts = wheel_nlp.stressed_parts(s)
        x = ca.SX.sym("x", len(self.names))
        p = ca.SX.sym("p", n_par + len(parts))
        form = wheel_nlp.formulate(s, x, {n: p[k] for k, n in enumerate(wheel_nlp.PARAMETERS)}, p[n_par:])
        g = ca.vertcat(*form.rows)
        self.f = ca.Function("f", [x, p], [form.objective])
        self.grad = ca.Function("grad_f", [x, p], [ca.gradient(form.objective, x)])
        self.g = ca.Function("g", [x, p], [g])
        self.jac = ca.Function("jac_g", [x, p], [ca.jacobian(g, x)])
        self.mass = ca.Function("mass", [x, p], [form.mass])
        self.row_names = form.row_names
        args, self.scale, self.allow = wheel_nlp.solve_arguments(s, self.row_names, problem)  # as flyopt solves it
        self.lbx, self.ubx = np.array(args["lbx"]), np.array(args["ubx"])
        self.x0 = np.array(args["x0"])
        self.lbg, self.ubg = np.array(args["lbg"]), np.array(args["ubg"])
        self.p = np.array(args["p"])
        start = problem.start or wheel_nlp.starting_wheel(s, problem, self.names)
        self.start = start
        if case.solution is not None:
            self.check_against(case.solution)

    def check_against(self, solution: Any) -> None:
        """Raise RuntimeError if flyopt's WheelSolution was solved with other parameters than these."""
        mine = dict(zip(solution.allow_params, self.allow))
        if solution.stress_scale != self.scale or mine != solution.allow_params:
            raise RuntimeError(
                "the bench's parameters of the wheel NLP disagree with wheel_nlp.solve's "
                f"(stress scale {self.scale} vs {solution.stress_scale}, allowables {mine} vs {solution.allow_params})"
            )

    def x_of(self, dims: Dims) -> NDArray[np.float64]:
        """The NLP's variables (logarithms of metres) of a wheel."""
        return np.array([math.log(float(getattr(dims, n))) for n in self.names])

    def violation(self, x: NDArray[np.float64]) -> float:
        """Largest violation of a row or a bound at x (rows as the NLP writes them, mostly of order one)."""
        g = np.asarray(self.g(x, self.p)).ravel()
        with np.errstate(invalid="ignore"):
            parts = [self.lbg - g, g - self.ubg, self.lbx - x, x - self.ubx]
            worst = max(float(np.nanmax(np.where(np.isfinite(v), v, -np.inf))) for v in parts)
        if not np.all(np.isfinite(g)):
            return math.inf
        return max(worst, 0.0)

    def mass_of(self, x: NDArray[np.float64]) -> float:
        return float(self.mass(x, self.p))


@dataclass
class _Result:
    """One method's answer on one case: the variables (None: no design), their mass and violation, a note."""

    x: NDArray[np.float64] | None
    mass: float
    violation: float
    note: str


def slsqp_wheel(nlp: WheelNlp, ftol: float = SLSQP_FTOL, maxiter: int = 500) -> _Result:
    """The wheel NLP by scipy's SLSQP with CasADi gradients, from IPOPT's start; None where it fails.

    Counted only where SLSQP reports success and every row holds to :data:`COUNT_TOL`.
    """
    p = nlp.p
    cons: list[dict[str, Any]] = []
    for k, (lo, hi) in enumerate(zip(nlp.lbg, nlp.ubg)):
        if lo == hi:
            cons.append({"type": "eq", "k": k, "sign": 1.0, "bound": lo})
            continue
        if math.isfinite(lo):
            cons.append({"type": "ineq", "k": k, "sign": 1.0, "bound": lo})
        if math.isfinite(hi):
            cons.append({"type": "ineq", "k": k, "sign": -1.0, "bound": hi})

    def stacked(kind):
        chosen = [c for c in cons if c["type"] == kind]
        if not chosen:
            return None
        rows = np.array([c["k"] for c in chosen])
        sign = np.array([c["sign"] for c in chosen])
        bound = np.array([c["bound"] for c in chosen])
        return {
            "type": kind,
            "fun": lambda x: sign * (np.asarray(nlp.g(x, p)).ravel()[rows] - bound),
            "jac": lambda x: sign[:, None] * np.asarray(nlp.jac(x, p))[rows],
        }

    constraints = [c for c in (stacked("ineq"), stacked("eq")) if c is not None]
    bounds = [
        (lo if math.isfinite(lo) else None, hi if math.isfinite(hi) else None) for lo, hi in zip(nlp.lbx, nlp.ubx)
    ]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with np.errstate(all="ignore"):
            try:
                res = optimize.minimize(
                    lambda x: float(nlp.f(x, p)),
                    nlp.x0,
                    jac=lambda x: np.asarray(nlp.grad(x, p)).ravel(),
                    method="SLSQP",
                    bounds=bounds,
                    constraints=constraints,
                    options={"ftol": ftol, "maxiter": maxiter},
                )
            except (ValueError, OverflowError, ZeroDivisionError) as err:
                return _Result(None, math.nan, math.inf, f"SLSQP raised {type(err).__name__}: {err}")
    note = f"SLSQP: {res.message} (status {res.status}, {res.nit} it)"
    if caught:
        note += "; warning: " + "; ".join(sorted({str(w.message).splitlines()[0] for w in caught}))
    x = np.asarray(res.x, float)
    v = nlp.violation(x)
    if not res.success:
        return _Result(None, math.nan, v, note)
    if not v <= COUNT_TOL:
        return _Result(None, math.nan, v, note + f"; rows violated by {v:.1e} > {COUNT_TOL:g}")
    return _Result(x, nlp.mass_of(x), v, note)


def grid_box(nlp: WheelNlp, case: WheelCase) -> list[tuple[float, float]]:
    """(low, high) of each variable's logarithm for the grid, read from the problem's limits.

    The outer diameter up to twice the starting wheel's (IPOPT's start: the
    largest diameter the limits and the ring's stress allow, times 0.8),
    within the envelope and the rim-speed limit, down to a fifth of that; the
    rim's H up to a quarter, B up to a half of it (within the width limit),
    the web up to B, the arm's major axis up to a quarter, the hub within its
    range; every lower end at the variable's lower bound (min_wall) or
    1/1000 of the outer diameter. Nothing is read from any method's answer.
    """
    problem, s = case.problem, case.structure
    d_hi = 2.0 * nlp.start["d_outer"]
    if s.envelope:
        d_hi = min(d_hi, problem.envelope)
    if s.criterion == "rim_speed":
        d_hi = min(d_hi, 2.0 * problem.max_rim_speed / problem.omega)
    width = problem.max_width if s.width else math.inf
    upper = {"d_outer": d_hi, "h": d_hi / 4.0, "b": min(width, d_hi / 2.0), "arm_major": d_hi / 4.0}
    upper["t_web"] = upper["b"]
    upper["d_hub"] = upper["l_hub"] = d_hi / 2.0
    box = []
    for k, n in enumerate(nlp.names):
        hi = min(math.log(upper[n]), nlp.ubx[k])
        lo = math.log(d_hi / 5.0) if n == "d_outer" else max(nlp.lbx[k], math.log(d_hi * 1e-3))
        box.append((float(lo), float(max(hi, lo))))
    return box


def grid_wheel(nlp: WheelNlp, box: Sequence[tuple[float, float]], points: int) -> _Result:
    """The lightest point of a log-spaced grid of ``points`` per variable whose rows hold to REFERENCE_TOL."""
    axes = [np.linspace(lo, hi, points) for lo, hi in box]
    n, total = len(axes), points ** len(axes)
    chunk = min(total, _CHUNK)
    g_map = nlp.g.map(chunk)
    m_map = nlp.mass.map(chunk)
    best_mass, best_x = math.inf, None
    lbg, ubg = nlp.lbg[:, None], nlp.ubg[:, None]
    for begin in range(0, total, chunk):
        index = np.arange(begin, begin + chunk) % total  # the last chunk wraps round (points seen twice)
        x = np.array([axes[k][i] for k, i in enumerate(np.unravel_index(index, (points,) * n))])
        g = np.asarray(g_map(x, nlp.p))
        with np.errstate(invalid="ignore"):
            ok = np.all((g >= lbg - REFERENCE_TOL) & (g <= ubg + REFERENCE_TOL), axis=0)
        if not ok.any():
            continue
        mass = np.where(ok, np.asarray(m_map(x, nlp.p)).ravel(), np.inf)
        i = int(np.argmin(mass))
        if mass[i] < best_mass:
            best_mass, best_x = float(mass[i]), x[:, i]
    if best_x is None:
        return _Result(None, math.nan, math.inf, f"no feasible point among {total} points")
    return _Result(best_x, best_mass, nlp.violation(best_x), f"{total} points")


def _flyopt(call: Callable[[], Dims], note: str, nlp: WheelNlp) -> _Result:
    try:
        dims = call()
    except SolverFailed as err:
        return _Result(None, math.nan, math.inf, f"no design: {err}")
    x = nlp.x_of(dims)
    v = nlp.violation(x)
    if not v <= COUNT_TOL:
        return _Result(None, math.nan, v, note + f"; rows violated by {v:.1e} > {COUNT_TOL:g}")
    return _Result(x, nlp.mass_of(x), v, note)


def wheel_rows(cases: Sequence[WheelCase], config: Config, grids: Sequence[int] | None = None) -> list[Row]:
    """Rows of flyopt-ipopt, slsqp and each grid on each case; ratios against flyopt-ipopt."""
    grids = tuple(grids) if grids is not None else (QUICK_GRIDS if config.quick else GRIDS)
    rows = []
    for case in cases:
        nlp = WheelNlp(case)
        box = grid_box(nlp, case)
        methods: list[tuple[str, str, Callable[[], _Result]]] = [
            ("flyopt-ipopt", "casadi/ipopt", partial(_flyopt, case.flyopt, case.path, nlp))
        ]
        if case.nlp_only is not None:
            methods.append(
                ("flyopt-nlp", "casadi/ipopt", partial(_flyopt, case.nlp_only, "wheel_nlp.solve (IPOPT) alone", nlp))
            )
        methods.append(("slsqp", f"ftol={SLSQP_FTOL:g}", partial(slsqp_wheel, nlp)))
        for points in grids:
            methods.append(("grid", f"{points}^{len(nlp.names)}", partial(grid_wheel, nlp, box, points)))
        results = []
        for method, setting, call in methods:
            result = call()
            timing = measure(call, config.design_repeats)
            results.append((method, setting, result, timing))
        known = [r.mass for _, _, r, _ in results if r.x is not None and r.violation <= REFERENCE_TOL]
        best = min(known, default=math.nan)
        for method, setting, result, timing in results:
            designed = result.x is not None and result.violation <= COUNT_TOL  # a grid point outside a bound too
            rows.append(
                Row.timed(
                    "wheel",
                    case.name,
                    method,
                    setting,
                    timing,
                    error=(result.mass - best) / best if designed else math.inf,
                    error_median=(result.mass - best) / best if designed else math.inf,
                    violation=result.violation if math.isfinite(result.violation) else math.inf,
                    verdicts_ok=int(designed),
                    failures=int(not designed),
                    reference=(
                        f"best known mass: the least of every method's results whose rows hold to "
                        f"{REFERENCE_TOL:g} (a result counts with rows to {COUNT_TOL:g})"
                    ),
                    note=f"{result.note}; mass {result.mass:.10g} kg, best known {best:.10g} kg"
                    if designed
                    else result.note,
                )
            )
    set_ratios(rows, lambda r: r.method == "flyopt-ipopt")
    return rows


def scene_cases(path: Path = SCENE) -> list[WheelCase]:
    """The whole-wheel combinations a solve of the scene designs, each as the NLP of its design.

    One ``flyopt`` solve of the scene is run with
    :func:`flyopt.design.wheel_design.design_combination` and
    :func:`flyopt.design.wheel_nlp.solve` watched (restored afterwards): each
    combination designed gives its arguments (what the timed call repeats)
    and the last NLP it solved (with the allowables and caps the stress check
    settled), which SLSQP and the grid solve. Combinations the designer
    prunes (their objective bound cannot win) are not designed and not cases;
    a combination designed again later in the solve is kept once, as first designed.
    """
    from flyopt.design import wheel_design, wheel_nlp
    from flyopt.io.scene import load
    from flyopt.pipeline import solve

    designs: list[tuple[tuple[Any, ...], Any, Any, Any]] = []
    solves: list[tuple[Any, Any, Any]] = []
    original_design, original_solve = wheel_design.design_combination, wheel_nlp.solve

    def watch_solve(model, problem, label):
        solution = original_solve(model, problem, label)
        solves.append((model.structure, problem, solution))
        return solution

    def watch_design(*args, **kwargs):
        found = original_design(*args, **kwargs)
        last = next((s for s in reversed(solves) if s[2] is found[1]), None)
        if last is not None:  # None: the disc's closed form, no NLP solved
            designs.append((args, last[0], last[1], last[2]))
        return found

    wheel_design.design_combination, wheel_nlp.solve = watch_design, watch_solve
    try:
        solve(load(path))
    finally:
        wheel_design.design_combination, wheel_nlp.solve = original_design, original_solve
    cases, seen = [], set()
    for args, structure, problem, solution in designs:
        combo, spec, bore, torque, n_arms = args[:5]
        if combo.label in seen:  # a later design of the same combination (the solve's re-designs near it)
            continue
        seen.add(combo.label)
        cases.append(
            WheelCase(
                f"{path.stem}: {combo.label}",
                structure,
                problem,
                partial(_designed, combo, spec, bore, torque, n_arms),
                "design_combination (IPOPT, stress check)",
                solution,
                partial(_solved, structure, problem, combo.label),
            )
        )
    return cases


def _designed(combo: Any, spec: Any, bore: float, torque: float, n_arms: int) -> Dims:
    """flyopt's whole-wheel design of a combination by its NLP path (what the designer calls), its Dims."""
    from flyopt.design import wheel_design

    return wheel_design.design_combination(combo, spec, bore, torque, n_arms, None, "ipopt")[0]


def _solved(structure: Any, problem: Any, label: str) -> Dims:
    """flyopt's solve of a wheel NLP as shipped (status checked: SolverFailed otherwise), its Dims."""
    from flyopt.design import wheel_nlp

    return wheel_nlp.solve(wheel_nlp.get_model(structure), problem, label).dims


#: (geometry, bored, arms) of the random wheels: :func:`random_wheel` cycles through them with its seed.
WHEEL_STRUCTURES = (
    ("rim", False, 0),
    ("thin_rim", False, 0),
    ("disc", False, 0),
    ("disc", True, 0),
    ("rim_web", False, 0),
    ("rim_web", True, 0),
    ("rim_arms", True, 4),
    ("rim_arms", True, 6),
    ("rim_arms", True, 8),
)


def random_wheel(seed: int) -> tuple[Any, Any]:
    """(WheelStructure, WheelProblem) of one seeded random whole wheel, in SI.

    The structure cycles with the seed through :data:`WHEEL_STRUCTURES`, then
    the criterion (rim speed, stress), then brittle or ductile. Cast irons and
    steels (density 6800..7900 kg/m^3, Poisson 0.2..0.3), 60..400 rad/s,
    allowables 30..200 MPa (or a rim speed of 25..80 m/s; the natural diameter
    is that of a free ring at the limit), an envelope of 0.3..1.2 natural
    diameters in 60 % of the wheels, a width limit of 20..300 mm in 40 %, J'
    from 2 % to 300 % of a ring of H = B = D/10 (50 % on arms), H/B from 0.3..2
    over a span of 1..3, min_wall 3..12 mm, bores of 20..80 mm with hubs in the
    textbook's proportions. Some draws have no wheel at all: the NLP's tests
    and benchmarks use them as they come (tests/design/test_wheel_nlp.py,
    benchmarks/bench_wheel.py, :func:`random_wheel_cases`).
    """
    from flyopt.design import wheel_nlp

    geometry, bored, n_arms = WHEEL_STRUCTURES[seed % len(WHEEL_STRUCTURES)]
    criterion = ("rim_speed", "stress")[(seed // len(WHEEL_STRUCTURES)) % 2]
    ductile = bool((seed // (2 * len(WHEEL_STRUCTURES))) % 2)
    rng = np.random.default_rng(seed)
    rho, nu = rng.uniform(6800.0, 7900.0), rng.uniform(0.2, 0.3)
    omega = math.exp(rng.uniform(math.log(60.0), math.log(400.0)))
    sigma = math.exp(rng.uniform(math.log(30e6), math.log(200e6)))
    v_max = rng.uniform(25.0, 80.0)
    parts = wheel_nlp.stressed_parts(
        wheel_nlp.WheelStructure(geometry, criterion, ductile, bored, n_arms, False, False, False, "mass")
    )
    allowable = {p: sigma * rng.uniform(0.6, 1.0) for p in parts}
    d_natural = 2.0 * (v_max if criterion == "rim_speed" else math.sqrt(sigma / rho)) / omega
    envelope = d_natural * rng.uniform(0.3, 1.2) if rng.random() < 0.6 else math.inf
    max_width = math.exp(rng.uniform(math.log(0.02), math.log(0.3))) if rng.random() < 0.4 else math.inf
    low = rng.uniform(0.3, 2.0)
    hb_ratio = (low, low if rng.random() < 0.1 else low * rng.uniform(1.0, 3.0))
    min_wall = rng.uniform(0.003, 0.012)
    bore = rng.uniform(0.02, 0.08) if bored else 0.0
    d_hub_range = (bore * rng.uniform(1.6, 1.8), bore * rng.uniform(1.8, 2.0)) if bored else (0.0, math.inf)
    l_hub_range = (bore * rng.uniform(1.2, 1.5), bore * rng.uniform(1.5, 2.5)) if bored else (0.0, math.inf)
    # the inertia asked: a ring of H = B = D/10 within the limits, times a random factor (a wheel on
    # arms gives less: its rim bends between the arms, its arms must fit round the hub)
    d = min(d_natural / (1.5 if geometry == "rim_arms" and criterion == "stress" else 1.0), envelope)
    ring = rho * math.pi * (0.1 * d) ** 2 * d**3 / 4.0
    j_shaft = ring * math.exp(rng.uniform(math.log(0.02), math.log(0.5 if geometry == "rim_arms" else 3.0)))
    torque = rng.uniform(0.0, 1500.0) if geometry == "rim_arms" else rng.uniform(0.0, 500.0)
    structure = wheel_nlp.WheelStructure(
        geometry, criterion, ductile, bored, n_arms, math.isfinite(envelope), math.isfinite(max_width), False, "mass"
    )
    problem = wheel_nlp.WheelProblem(
        j_shaft=j_shaft,
        omega=omega,
        density=rho,
        poisson=nu,
        torque=torque,
        bore=bore,
        allowable=allowable if criterion == "stress" else {},
        envelope=envelope,
        max_width=max_width,
        max_rim_speed=v_max,
        hb_ratio=hb_ratio,
        d_mean=None,
        min_wall=min_wall,
        d_hub_range=d_hub_range,
        l_hub_range=l_hub_range,
    )
    return structure, problem


def random_wheel_cases(count: int, seed: int) -> list[WheelCase]:
    """``count`` random wheels (:func:`random_wheel`, seeds from ``1000 * seed`` on) that IPOPT solves.

    The seeds run through every structure in turn; a draw IPOPT does not solve (no wheel, or no
    convergence) is passed over: a case needs a known optimum.
    """
    from flyopt.design import wheel_nlp

    cases: list[WheelCase] = []
    for k in range(20 * count + len(WHEEL_STRUCTURES)):
        if len(cases) >= count:
            break
        structure, problem = random_wheel(1000 * seed + k)
        arms = f" {structure.n_arms} arms" if structure.n_arms else ""
        name = f"random {1000 * seed + k}: {structure.geometry}{arms}, {structure.criterion}"
        try:
            solution = wheel_nlp.solve(wheel_nlp.get_model(structure), problem, name)
        except SolverFailed:
            continue  # no wheel, or IPOPT fails: not a case with a known optimum
        cases.append(
            WheelCase(
                name,
                structure,
                problem,
                partial(_solved, structure, problem, name),
                "wheel_nlp.solve (IPOPT)",
                solution,
            )
        )
    return cases


def section_wheel(config: Config) -> list[Row]:
    """Whole wheels: punch-press-wheel's combinations and six seeded random wheels of several structures
    (a quick run: the scene's first combination and one random wheel)."""
    cases = scene_cases() if SCENE.is_file() else []
    random = random_wheel_cases(1 if config.quick else 6, config.seed)
    if config.quick:
        cases = cases[:1]
    return wheel_rows(cases + random, config)
