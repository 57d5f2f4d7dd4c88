"""Tests of the whole-wheel design NLP (flyopt.design.wheel_nlp) and its drivers against independent references.

1. IPOPT against a second optimizer. The NLP's statement (its module docstring:
   every part counted in J and m by :func:`flyopt.design.wheel.parts`, the stress
   rows at the radii :data:`flyopt.design.wheel_nlp.SAMPLES` of
   :func:`flyopt.design.wheel.stress_samples`, the envelope, rim speed, width, H/B,
   wall, hub and arm limits) is written again here in plain floats and solved by
   scipy's SLSQP from several random starts; a point IPOPT calls infeasible is
   checked by an elastic phase one (minimize t with every row + t >= 0).
2. The sensitivities d(mass)/d(limit) that :func:`flyopt.design.wheel_design.sensitivities`
   takes from IPOPT's multipliers, against central differences of re-solves.
3. The free annular and the solid disc under the stress criterion, whose
   lightest form is known in closed form (Timoshenko and Goodier, art. 32).
4. Designs of :func:`flyopt.design.design_flywheel` re-evaluated: inertia from
   the parts, stress maxima by a dense grid refined around its best point (independent of the
   closed-form maxima of :func:`flyopt.design.stress.max_stress_per_step`)
   on a stepped disc written here from the design's dimensions, and every limit.
"""

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import minimize

from flyopt.bench.wheel import WHEEL_STRUCTURES, random_wheel
from flyopt.design import DesignSpec, MountShaft, design_flywheel, hub, stress, wheel, wheel_design, wheel_nlp
from flyopt.design.castability import Overrides
from flyopt.design.key import hub_length_for_key
from flyopt.design.materials import StrengthRow, make_material
from flyopt.errors import SolverFailed

#: Every structure of a wheel NLP: (geometry, bored, n_arms).
STRUCTURES = WHEEL_STRUCTURES

#: The fast set: every structure x criterion x (ductile, brittle) once.
FAST_SEEDS = range(4 * len(STRUCTURES))
#: The slow set: ten more of each.
SLOW_SEEDS = range(4 * len(STRUCTURES), 44 * len(STRUCTURES))

#: Mass agreement of two optimizers. IPOPT stops at tol 1e-10 on a log-mass objective with
#: constraint rows of order one, SLSQP at ftol 1e-15 with its own forward-difference gradients;
#: both land within ~1e-10 of the same optimum (measured over the fast and slow sets, 396 wheels:
#: at most 5.1e-10, IPOPT a hair heavier as its interior point stops just inside the limits), so
#: 1e-6 (the issue's figure) is three orders above what the solvers leave and far below the
#: difference of two local optima.
MASS_RTOL = 1e-6

#: A row of the statement counts as met at >= -FEASIBLE_ATOL (rows are relative: 1 - value/limit).
#: IPOPT's constraint violation at tol 1e-10 is below it; 1e-9 leaves a factor ten.
FEASIBLE_ATOL = 1e-9

#: IPOPT's "infeasible" is confirmed when an elastic phase one from every start leaves a violation
#: above this (evidence from several starts, not a proof: phase one is local too). Measured: the
#: least violation of an infeasible random wheel is 2.7e-3 or more (79 of the 396).
INFEASIBLE_T = 1e-6


# ------------------------------------------------------------------ random wheels


random_case = random_wheel  # one generator: flyopt.bench.wheel's


#: IPOPT alone: the reference the default (sqpmethod with IPOPT behind it) is held to.
IPOPT = {wheel_nlp.SOLVER_OPTION: "ipopt"}


def _ipopt(structure, problem):
    """IPOPT's wheel, or None where it reports the problem infeasible (any other failure raises)."""
    try:
        return wheel_nlp.solve(wheel_nlp.get_model(structure, IPOPT), problem, "random wheel")
    except SolverFailed as err:
        if getattr(err, "status", "") == "Infeasible_Problem_Detected":
            return None
        raise


# ------------------------------------------- the NLP written again, in floats


class Statement:
    """The wheel NLP of one combination, written from its statement and evaluated in floats.

    Variables are the logarithms of the dimensions (any parametrization would do; this one keeps
    them positive). ``rows(x) >= 0`` is every limit, each relative (1 - value/limit); the walls and
    the hub's proportions are bounds. Mass, inertia and stresses come from
    :mod:`flyopt.design.wheel`, the physics under both optimizers.
    """

    def __init__(self, structure, problem):
        self.s, self.p = structure, problem
        geometry = structure.geometry
        names = ["d_outer", "b"] if geometry == "disc" else ["d_outer", "h", "b"]
        if geometry == "disc" and structure.bored and structure.disc_hub:
            names += ["d_hub", "l_hub"]
        if geometry == "rim_web":
            names += ["t_web"] + (["d_hub", "l_hub"] if structure.bored else [])
        if geometry == "rim_arms":
            names += ["arm_major", "d_hub", "l_hub"]
        self.names = tuple(names)
        wall = math.log(problem.min_wall)
        low = {
            "d_outer": math.log(1e-3),
            "h": wall,
            "b": wall,
            "t_web": wall,
            "arm_major": wall - math.log(wheel.ARM_MINOR_RATIO),
        }
        high = {n: math.log(100.0) for n in names}
        if "d_hub" in names:
            low["d_hub"], high["d_hub"] = (math.log(v) for v in problem.d_hub_range)
            low["l_hub"], high["l_hub"] = (math.log(min(v, 100.0)) for v in problem.l_hub_range)
        self.bounds = [(low[n], high[n]) for n in names]
        self._size = len(self.rows(self.starts(np.random.default_rng(0), 1)[0]))

    def dims(self, x):
        v = {n: math.exp(float(xi)) for n, xi in zip(self.names, x)}
        bore = self.p.bore if self.s.bored else 0.0
        if self.s.geometry == "disc":
            hub = {"d_hub": v["d_hub"], "l_hub": v["l_hub"]} if "d_hub" in v else {}
            return wheel.Dims(d_outer=v["d_outer"], h=(v["d_outer"] - bore) / 2.0, b=v["b"], bore=bore, **hub)
        return wheel.Dims(
            d_outer=v["d_outer"],
            h=v["h"],
            b=v["b"],
            bore=bore,
            t_web=v.get("t_web", 0.0),
            d_hub=v.get("d_hub", 0.0),
            l_hub=v.get("l_hub", 0.0),
            arm_major=v.get("arm_major", 0.0),
            n_arms=self.s.n_arms,
        )

    def cap(self):
        """An outer diameter no design exceeds by much [m]: the envelope, the rim speed's, 1.5 x a free ring's."""
        p = self.p
        sigma = max(p.allowable.values()) if p.allowable else math.inf
        return min(
            p.envelope,
            2.0 * p.max_rim_speed / p.omega if self.s.criterion == "rim_speed" else math.inf,
            3.0 * math.sqrt(sigma / p.density) / p.omega,
        )

    def mass_scale(self):
        """The mass of a thin ring of the outer diameter :meth:`cap` giving J' [kg]: scales the objective."""
        return 4.0 * self.p.j_shaft / self.cap() ** 2

    def x_of(self, dims):
        return np.log([getattr(dims, n) for n in self.names])

    def mass(self, x):
        return wheel.wheel_mass(wheel.parts(self.s.geometry, self.dims(x), self.p.density))

    def rows(self, x):
        s, p, d = self.s, self.p, self.dims(x)
        out = [wheel.wheel_inertia(wheel.parts(s.geometry, d, p.density)) / p.j_shaft - 1.0]
        if s.envelope:
            out.append(1.0 - d.d_outer / p.envelope)
        if s.criterion == "rim_speed":
            out.append(1.0 - p.omega * d.d_outer / 2.0 / p.max_rim_speed)
        if s.width:
            out.append(1.0 - d.b / p.max_width)
            if "l_hub" in self.names:
                out.append(1.0 - d.l_hub / p.max_width)
        if s.geometry == "disc" and "d_hub" in self.names:  # the hub inside the disc, at least as long as it
            out += [1.0 - d.d_hub / d.d_outer, 1.0 - d.b / d.l_hub]
        elif s.geometry == "disc":
            out.append(1.0 - d.bore / d.d_outer)
        else:
            hb = d.h / d.b
            out += [hb / p.hb_ratio[0] - 1.0, 1.0 - hb / p.hb_ratio[1], d.d_inner / d.d_outer]
            if "d_hub" in self.names:
                out.append((d.d_inner - d.d_hub) / d.d_outer)
        if "t_web" in self.names:
            out.append(1.0 - d.t_web / d.b)
            if "l_hub" in self.names:
                out.append(1.0 - d.t_web / d.l_hub)
        if "arm_major" in self.names:
            minor = wheel.ARM_MINOR_RATIO * d.arm_major
            out += [1.0 - s.n_arms * d.arm_major / (math.pi * d.d_hub), 1.0 - minor / d.b, 1.0 - minor / d.l_hub]
        if "d_hub" in self.names:
            out.append((d.d_hub - d.bore) / 2.0 / p.min_wall - 1.0)
        if s.criterion == "stress":
            for part, _r, sr, st in wheel.stress_samples(
                s.geometry, d, p.density, p.poisson, p.omega, p.torque, wheel_nlp.SAMPLES
            ):
                allow = p.allowable[part]
                if s.ductile:
                    out.append(1.0 - (sr * sr - sr * st + st * st) / allow**2)
                else:
                    out += [1.0 - sr / allow, 1.0 - st / allow]
        return np.array([float(v) for v in out])

    def safe_rows(self, x):
        """rows for an optimizer that steps anywhere in the box: a nonsense wheel (a rim of no inner
        diameter, a negative web) is a large violation, never an exception or a NaN."""
        with np.errstate(all="ignore"):
            try:
                r = self.rows(x)
            except (ZeroDivisionError, OverflowError):
                r = np.full(self._size, np.nan)
        self._size = len(r)
        return np.nan_to_num(r, nan=-1e3, posinf=1e3, neginf=-1e3)

    def violation(self, x):
        """The largest violation of a row or bound at x (0: feasible)."""
        out = max(0.0, -float(np.min(self.safe_rows(x))))
        return max([out] + [max(lo - xi, xi - hi, 0.0) for xi, (lo, hi) in zip(x, self.bounds)])

    def starts(self, rng, count):
        """Random starting wheels drawn from the problem's numbers alone (nothing from IPOPT)."""
        p, cap = self.p, self.cap()
        out = []
        for _ in range(count):
            d = cap * rng.uniform(0.3, 1.0)
            h = math.exp(rng.uniform(math.log(p.min_wall), math.log(max(0.25 * d, p.min_wall))))
            v = {
                "d_outer": d,
                "h": h,
                "b": h / rng.uniform(*p.hb_ratio),
                "t_web": p.min_wall * rng.uniform(1.0, 3.0),
                "arm_major": p.min_wall * rng.uniform(2.0, 5.0),
            }
            if self.s.geometry == "disc":
                v["b"] = math.exp(rng.uniform(math.log(p.min_wall), math.log(max(0.3 * d, p.min_wall))))
            if "d_hub" in self.names:
                l_high = p.l_hub_range[1] if math.isfinite(p.l_hub_range[1]) else 3.0 * p.l_hub_range[0]
                v["d_hub"], v["l_hub"] = rng.uniform(*p.d_hub_range), rng.uniform(p.l_hub_range[0], l_high)
            x = np.log([v[n] for n in self.names])
            out.append(np.clip(x, [b[0] for b in self.bounds], [b[1] for b in self.bounds]))
        return out


def _slsqp(fun, x0, bounds, constraints):
    with np.errstate(all="ignore"):
        return minimize(
            fun, x0, method="SLSQP", bounds=bounds, constraints=constraints, options={"ftol": 1e-15, "maxiter": 1000}
        )


def scipy_lightest(statement, starts):
    """The lightest feasible wheel SLSQP finds from the starts: (mass, x), or None."""
    scale = statement.mass_scale()

    def objective(x):
        with np.errstate(all="ignore"):
            value = statement.mass(x) / scale
        return float(value) if math.isfinite(value) else 1e6

    best = None
    for x0 in starts:
        found = _slsqp(objective, x0, statement.bounds, [{"type": "ineq", "fun": statement.safe_rows}])
        if statement.violation(found.x) <= FEASIBLE_ATOL:
            mass = statement.mass(found.x)
            if best is None or mass < best[0]:
                best = (mass, found.x)
    return best


def scipy_least_violation(statement, starts):
    """Elastic phase one: the least t with every row + t >= 0 that SLSQP finds from the starts."""
    bounds = statement.bounds + [(0.0, 1e3)]
    constraints = [{"type": "ineq", "fun": lambda z: statement.safe_rows(z[:-1]) + z[-1]}]
    least = math.inf
    for x0 in starts:
        z0 = np.append(x0, max(0.0, -float(np.min(statement.safe_rows(x0)))) + 1e-3)
        found = _slsqp(lambda z: z[-1], z0, bounds, constraints)
        least = min(least, statement.violation(found.x[:-1]))
    return least


# ------------------------------------------------- 1. IPOPT against SLSQP


def compare_with_scipy(seed, starts=8, disc_hub=False):
    """IPOPT and SLSQP on one random wheel: same verdict, same mass; returns a line for the record.
    ``disc_hub``: a bored disc's case put on its hub (design.disc_hub: the hub at least as long as the disc
    is wide, and within its proportions)."""
    structure, problem = random_case(seed)
    if disc_hub:
        assert structure.geometry == "disc" and structure.bored
        structure = structure._replace(disc_hub=True)
        allowable = {**problem.allowable, "hub": problem.allowable["disc"]} if problem.allowable else {}
        problem = dataclasses.replace(problem, allowable=allowable)  # the hub within its proportions, as a rim's
    statement = Statement(structure, problem)
    solution = _ipopt(structure, problem)
    rng = np.random.default_rng(10_000 + seed)
    tries = statement.starts(rng, starts)
    lightest = scipy_lightest(statement, tries)
    what = f"seed {seed}: {structure}"
    if solution is None:
        assert lightest is None, (
            f"{what}: IPOPT reports the problem infeasible, SLSQP finds a feasible wheel "
            f"of {lightest[0]:.9g} kg at {statement.dims(lightest[1])}"
        )
        least = scipy_least_violation(statement, tries)
        assert least > INFEASIBLE_T, f"{what}: IPOPT says infeasible, phase one reaches a violation {least:.3g}"
        return seed, "infeasible", least
    x = statement.x_of(solution.dims)
    assert statement.violation(x) <= FEASIBLE_ATOL, (
        f"{what}: IPOPT's wheel violates the statement by {statement.violation(x):.3g}"
    )
    mass = statement.mass(x)
    assert_allclose(mass, math.exp(solution.objective), rtol=1e-12)
    more = lightest is None or lightest[0] > mass * (1.0 + MASS_RTOL)
    if more:  # SLSQP missed: more starts before any verdict
        found = [f for f in (lightest, scipy_lightest(statement, statement.starts(rng, 4 * starts))) if f]
        lightest = min(found, key=lambda f: f[0]) if found else None
    assert lightest is not None, f"{what}: IPOPT designs {mass:.9g} kg, SLSQP finds no feasible wheel"
    rel = lightest[0] / mass - 1.0
    which = "SLSQP lighter: IPOPT stopped at a worse point" if rel < 0 else "IPOPT lighter"
    assert abs(rel) <= MASS_RTOL, (
        f"{what}: IPOPT {mass:.12g} kg, SLSQP {lightest[0]:.12g} kg ({which}); "
        f"SLSQP's wheel {statement.dims(lightest[1])}, IPOPT's {solution.dims}"
    )
    # the box that keeps SLSQP's steps finite (1 mm to 100 m) must not be what stops it
    assert all(xi < math.log(50.0) for xi in lightest[1]) and lightest[1][0] > math.log(2e-3)
    return seed, "feasible", rel, more


@pytest.mark.parametrize("seed", FAST_SEEDS)
def test_ipopt_matches_scipy_on_random_wheels(seed):
    """Every structure, both criteria, ductile and brittle: IPOPT's verdict and mass match SLSQP's."""
    compare_with_scipy(seed)


#: The random bored discs of the fast set, each put on its hub.
DISC_SEEDS = [seed for seed in FAST_SEEDS if STRUCTURES[seed % len(STRUCTURES)][:2] == ("disc", True)]


@pytest.mark.parametrize("seed", DISC_SEEDS)
def test_ipopt_matches_scipy_on_random_discs_on_hubs(seed):
    """A disc on its hub (design.disc_hub), both criteria, ductile and brittle: IPOPT's verdict and mass match
    SLSQP's on the statement written here (two annuli, the hub inside the disc and at least as long as it)."""
    assert DISC_SEEDS and compare_with_scipy(seed, disc_hub=True)


@pytest.mark.slow
@pytest.mark.parametrize("seed", SLOW_SEEDS)
def test_ipopt_matches_scipy_on_random_wheels_slow(seed):
    compare_with_scipy(seed)


def test_random_set_has_both_verdicts():
    """The fast set holds feasible and infeasible wheels of every criterion (else test 1 tests little)."""
    verdicts = {}
    for seed in FAST_SEEDS:
        structure, problem = random_case(seed)
        key = (structure.criterion, _ipopt(structure, problem) is not None)
        verdicts[key] = verdicts.get(key, 0) + 1
    assert all(verdicts.get((c, v), 0) >= 2 for c in ("rim_speed", "stress") for v in (True, False)), verdicts


# ------------------------------------------------------- sqpmethod against IPOPT

#: sqpmethod (SOLVER_OPTION "sqpmethod") against IPOPT on the same NLP: both stop at 1e-10 (IPOPT's
#: tol, sqpmethod's tol_pr and tol_du); measured over the fast set and punch-press-wheel at most
#: 6.4e-11 apart in the objective (log mass), so 1e-9 leaves a factor of ten and still tells a
#: different local optimum. On the random wheels only the objective is compared: without
#: castability a rim's H may trade against its web at the same mass, and the two solvers stop at
#: different wheels of the same mass.
SQP_RTOL = 1e-9


def _sqp(structure, problem):
    """(solution or None where infeasible) by the sqpmethod model, with IPOPT behind it."""
    model = wheel_nlp.get_model(structure, {wheel_nlp.SOLVER_OPTION: "sqpmethod"})
    try:
        return wheel_nlp.solve(model, problem, "random wheel")
    except SolverFailed as err:
        if getattr(err, "status", "") == "Infeasible_Problem_Detected":
            return None
        raise


def test_sqpmethod_agrees_with_ipopt_on_random_wheels():
    """Every structure, both criteria, ductile and brittle (the fast set): the sqpmethod model gives
    IPOPT's verdict and IPOPT's objective to SQP_RTOL, and sqpmethod itself (not the IPOPT behind
    it) answers most feasible wheels, or the comparison would be of IPOPT with itself."""
    answered, feasible = 0, 0
    for seed in FAST_SEEDS:
        structure, problem = random_case(seed)
        reference, fast = _ipopt(structure, problem), _sqp(structure, problem)
        assert (reference is None) == (fast is None), seed
        if reference is None:
            continue
        feasible += 1
        answered += fast.solver == "sqpmethod"
        assert abs(fast.objective - reference.objective) <= SQP_RTOL, (seed, fast.objective, reference.objective)
    assert answered >= 0.8 * feasible, (answered, feasible)


#: sqpmethod's dimensions against IPOPT's, relative. Castability (issue 28) gave each of these wheels one
#: optimum, so the two solvers stop at the same wheel, not just the same mass: measured at most
#: 2.1e-9 apart (punch-press-wheel; the arms wheel 2.5e-10, the engine's disc 1.3e-10): each solver
#: stops at 1e-10, and a dimension the mass is flat in moves by more. 1e-8 still tells another
#: optimum, which moves a dimension by percent.
SQP_DIMS_RTOL = 1e-8


@pytest.mark.parametrize(
    "name",
    [
        "punch-press-wheel",
        # each scene makes some 30-50 whole-wheel solves with each solver: one stays in the default run
        pytest.param("press-arms-wheel", marks=pytest.mark.slow),
        pytest.param("four-cylinder-engine", marks=pytest.mark.slow),
        pytest.param("punch-press-shaft", marks=pytest.mark.slow),  # the wheels their shafts accept
        pytest.param("four-cylinder-engine-shaft", marks=pytest.mark.slow),
    ],
)
def test_sqpmethod_designs_the_shipped_wheels_as_ipopt(name):
    """Each shipped whole-wheel scene, designed by the default (sqpmethod, IPOPT behind it) and by IPOPT
    alone: the same material and shaft, the same feasible candidates, every candidate's mass to
    SQP_RTOL and its dimensions to SQP_DIMS_RTOL, and the rounded wheel (and the continuous optimum it
    came from) the same."""
    from conftest import PROBLEMS

    import flyopt

    scene = flyopt.load(PROBLEMS / f"{name}.toml")
    reference = flyopt.solve(scene, solver_options=IPOPT).design
    fast = flyopt.solve(scene).design
    assert (fast.best.material, fast.best.shaft) == (reference.best.material, reference.best.shaft)
    assert len(fast.candidates) == len(reference.candidates)
    pairs = list(zip(fast.candidates, reference.candidates))
    if reference.continuous is not None:
        pairs.append((fast.continuous, reference.continuous))
    pairs.append((fast.best, reference.best))
    for mine, theirs in pairs:
        assert (mine.material, mine.shaft, mine.feasible) == (theirs.material, theirs.shaft, theirs.feasible)
        if not theirs.feasible:
            continue
        assert abs(math.log(mine.mass / theirs.mass)) <= SQP_RTOL
        for field in dataclasses.fields(theirs.dims):
            want, got = getattr(theirs.dims, field.name), getattr(mine.dims, field.name)
            assert (want is None) == (got is None), field.name
            if want is not None:
                assert got == pytest.approx(want, rel=SQP_DIMS_RTOL), (mine.material, field.name)


@pytest.mark.parametrize(
    "options",
    # the interior point method is the one that leaves multipliers off the bounds: it stays in the default run
    [IPOPT, pytest.param(None, marks=pytest.mark.slow)],
    ids=["ipopt", "default"],
)
def test_only_rows_at_their_bounds_carry_multipliers(options):
    """A limit is binding only where its row meets its bound: IPOPT leaves mu/slack on every row (1e-9
    on punch-press-wheel's 16.5 mm hub wall, whose minimum is 8 mm: it was reported binding). The rows
    are evaluated again from the solved dimensions; a row clear of both bounds by 1e-3 has no multiplier,
    and every row with one is at a bound."""
    from flyopt.design import rounding

    checked = 0
    for seed in FAST_SEEDS:
        structure, problem = random_case(seed)
        model = wheel_nlp.get_model(structure, options)
        try:
            solution = wheel_nlp.solve(model, problem, "random wheel")
        except SolverFailed:
            continue
        rows_of = rounding._row_function(structure)  # the NLP's rows g(x, p), built once per structure
        args, _, _ = wheel_nlp.solve_arguments(structure, model.constraints, problem)
        at = [math.log(getattr(solution.dims, n)) for n in model.variables]
        rows = np.asarray(rows_of["function"](at, args["p"])).ravel()
        gap: dict[str, float] = {}
        for name, g, lo, hi in zip(rows_of["names"], rows, args["lbg"], args["ubg"]):
            gap[name] = min(gap.get(name, math.inf), abs(g - lo), abs(hi - g))
        for name, lam in solution.lam_g.items():
            if gap[name] > 1e-3:
                assert lam == 0.0, (seed, name, lam, gap[name])
            if lam != 0.0:
                assert gap[name] <= 1e-5, (seed, name, lam, gap[name])
        checked += 1
    assert checked >= len(FAST_SEEDS) // 3


def test_unknown_wheel_solver_is_refused():
    """A misspelt solver choice is an error naming both choices, never a silent IPOPT."""
    structure, _ = random_case(0)
    with pytest.raises(ValueError, match="'ipopt' or 'sqpmethod'"):
        wheel_nlp.get_model(structure, {wheel_nlp.SOLVER_OPTION: "sqp"})


# --------------------------------------------- 2. sensitivities against re-solves

#: Steps of the central differences, relative to the limit. A central difference errs by O(h^2)
#: (truncation) plus IPOPT's stopping noise over 2h (the mass repeats to ~1e-11 relative, so
#: ~1e-7 at h = 1e-4 and ~1e-6 at 1e-5). Each check measures the difference of the two steps,
#: which bounds the error at h = 1e-4, and requires it below a tenth of the tolerance. Measured
#: over the 396 random wheels (1354 limits, 718 of them binding): at most 7.7e-6 of the derivative
#: (seed 58, an envelope of elasticity -0.05; h = 1e-3 against 1e-4 differ by up to 4e-4 there and
#: on seed 190, the h^2 law), and the multipliers differ from the h = 1e-4 difference by no more
#: than that (7.7e-6): what is left is the difference's own truncation.
STEPS = (1e-4, 1e-5)

#: d(mass)/d(limit) from the multipliers against the finite difference, relative: the issue's
#: ~1e-4, ten times the worst truncation measured; a wrong factor, power or sign is far outside it.
SENSITIVITY_RTOL = 1e-4

#: ... and absolute, as an elasticity (dm/dL) L/m: a limit that does not bind gives 0 both ways.
ELASTICITY_ATOL = 1e-6


def _central(mass_at, h):
    """d(mass)/d(ln limit) by a central difference of relative step h."""
    return (mass_at(1.0 + h) - mass_at(1.0 - h)) / (2.0 * h)


def check_against_differences(what, reported, mass_at, mass, limit):
    """A reported d(mass)/d(limit) [kg per unit] against central differences at the two STEPS."""
    coarse, fine = (_central(mass_at, h) for h in STEPS)  # d m / d ln L
    truncation = abs(coarse - fine)
    allowed = SENSITIVITY_RTOL * abs(coarse) + ELASTICITY_ATOL * mass
    assert truncation <= 0.1 * allowed, (
        f"{what}: the differences at steps {STEPS} differ by {truncation:.3g} kg, more than a tenth of "
        f"the tolerance {allowed:.3g} kg (a kink near the point?)"
    )
    assert abs(reported * limit - coarse) <= allowed, (
        f"{what}: multipliers give d m/d L = {reported:.9g}, re-solves {coarse / limit:.9g} "
        f"(relative difference {abs(reported * limit / coarse - 1) if coarse else math.inf:.3g})"
    )
    return abs(reported * limit - coarse) / max(abs(coarse), ELASTICITY_ATOL * mass), truncation / allowed


def _reported(sensitivities):
    """{limit: d m / d L} with the width's two rows (rim and hub) summed: one limit moves both."""
    out = {}
    for item in sensitivities:
        key = "max_width" if item["limit"].startswith("max_width") else item["limit"]
        out[key] = out.get(key, 0.0) + item["dmass_dlimit"]
    return out


def compare_sensitivities(seed):
    """Every limit of one random wheel: the multipliers' d(mass)/d(limit) against re-solves."""
    structure, problem = random_case(seed)
    solution = _ipopt(structure, problem)
    if solution is None:
        return []
    mass = float(wheel.wheel_mass(wheel.parts(structure.geometry, solution.dims, problem.density)))
    limits = {
        "envelope": problem.envelope,
        "max_rim_speed": problem.max_rim_speed,
        "max_width": problem.max_width,
        "j_shaft": problem.j_shaft,
        "allowable": dict(problem.allowable),
        "allow_power": 2 if structure.ductile else 1,
        "allow_param": solution.allow_params,
        "min_wall": problem.min_wall,
    }
    reported = _reported(wheel_design.sensitivities(solution, mass, limits))
    # the default solver's multipliers (sqpmethod, an active-set method) give IPOPT's sensitivities, which
    # the re-solves below check: the default path's sensitivities by a second method
    default = wheel_nlp.solve(wheel_nlp.get_model(structure), problem, "random wheel")
    by_default = _reported(wheel_design.sensitivities(default, mass, {**limits, "allow_param": default.allow_params}))
    assert set(by_default) == set(reported), seed
    for name, value in reported.items():  # kg per unit of the limit: 1e-12 is below any that binds
        assert by_default[name] == pytest.approx(value, rel=SENSITIVITY_RTOL, abs=1e-12), (seed, name)
    moves = {"inertia": "j_shaft", "min_wall": "min_wall"}
    if structure.envelope:
        moves["max_outer_diameter"] = "envelope"
    if structure.criterion == "rim_speed":
        moves["rim_speed"] = "max_rim_speed"
    if structure.width:
        moves["max_width"] = "max_width"
    for part in problem.allowable:
        moves[f"stress_{part}"] = part
    errors = []
    for name, field in moves.items():
        if field in problem.allowable:
            value = problem.allowable[field]

            def moved(factor, part=field, value=value):
                return dataclasses.replace(problem, allowable={**problem.allowable, part: value * factor})
        else:
            value = getattr(problem, field)

            def moved(factor, field=field, value=value):
                return dataclasses.replace(problem, **{field: value * factor})

        def mass_at(factor, moved=moved):
            model = wheel_nlp.get_model(structure, IPOPT)  # the re-solves by the reference's own solver
            return math.exp(wheel_nlp.solve(model, moved(factor), "moved").objective)

        errors.append(
            check_against_differences(
                f"seed {seed} {structure.geometry} {name}", reported.get(name, 0.0), mass_at, mass, value
            )
        )
    return errors


@pytest.mark.parametrize("seed", FAST_SEEDS)
def test_sensitivities_match_re_solves(seed):
    """Envelope, rim speed, width, thinnest wall, required inertia and each part's allowable."""
    compare_sensitivities(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", SLOW_SEEDS)
def test_sensitivities_match_re_solves_slow(seed):
    compare_sensitivities(seed)


def _engine_material(allowable=60e6, max_rim_speed=None, ductile=True):
    """The engine scenes' material (docs examples engine-web/engine-arms): cast steel-like, 60 MPa allowable."""
    return make_material(
        "engine",
        7100.0,
        max_rim_speed=max_rim_speed,
        allowable_stress=allowable,
        elastic_modulus=169e9,
        poisson_ratio=0.275,
        tensile_strength=400e6,
        yield_strength=250e6,
        ductile=ductile,
        bearing_pressure=90e6,
        min_wall=0.008,
    )


#: The single-cylinder engine's flywheel (the example scenes engine-web/engine-arms, as flyopt solves
#: them): J_F [kg m^2], omega_max [rad/s], the peak torque on the crankshaft [N m].
ENGINE = {"j": 3.804126900905206, "omega": 157.8650308428871, "torque": 897.3561853659951}


def _design(j=ENGINE["j"], allowable=60e6, max_rim_speed=None, ductile=True, **spec):
    material = _engine_material(allowable, max_rim_speed, ductile)
    spec = {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.0), **spec}
    result = design_flywheel(
        j,
        ENGINE["omega"],
        [MountShaft("crankshaft", 1.0, 0.07)],
        [material],
        DesignSpec(**spec),
        torque=ENGINE["torque"],
    )
    assert result.status == "designed", result.message
    return result.best


#: (case, which limit moves, keyword arguments of _design, the moved keyword)
DESIGN_CASES = [
    ("engine-web: envelope", "max_outer_diameter", {"max_outer_diameter": 0.8}, "max_outer_diameter"),
    ("engine-web: inertia", "inertia", {"max_outer_diameter": 0.8}, "j"),
    ("engine-web: thinnest wall", "min_wall", {"max_outer_diameter": 0.8}, "min_wall"),
    (
        "engine-arms: envelope",
        "max_outer_diameter",
        {"geometry": "rim_arms", "arms": (6,), "max_outer_diameter": 0.8},
        "max_outer_diameter",
    ),
    (
        "engine-arms: allowable",
        "stress",
        {"geometry": "rim_arms", "arms": (6,), "max_outer_diameter": 0.8},
        "allowable",
    ),
    ("web, ductile, 25 MPa: allowable", "stress", {"j": 20.0, "allowable": 25e6}, "allowable"),
    ("web, brittle, 25 MPa: allowable", "stress", {"j": 20.0, "allowable": 25e6, "ductile": False}, "allowable"),
    ("web, ductile, 15 MPa (hub binds): allowable", "stress", {"j": 20.0, "allowable": 15e6}, "allowable"),
    (
        "web, rim speed 40 m/s: rim speed",
        "rim_speed",
        {"criterion": "rim_speed", "max_rim_speed": 40.0},
        "max_rim_speed",
    ),
    ("web, rim speed 40 m/s: inertia", "inertia", {"criterion": "rim_speed", "max_rim_speed": 40.0}, "j"),
]


@pytest.mark.parametrize("case, limit, kwargs, key", DESIGN_CASES, ids=[c[0] for c in DESIGN_CASES])
def test_design_flywheel_sensitivities_match_re_designs(case, limit, kwargs, key):
    """The Candidate's sensitivities against whole re-designs with one limit moved.

    The material's allowable stress moves every part's allowable, so its derivative is the sum of
    the parts' (stress_hub + stress_web + ...); the re-designs include design_combination's
    re-solves against the exact stress maxima.
    """
    base = {"j": ENGINE["j"], **kwargs}
    best = _design(**base)
    reported = _reported(best.limits.sensitivities)
    if limit == "stress":
        value = sum(v for k, v in reported.items() if k.startswith("stress_"))
        assert value < 0.0, f"{case}: no stress limit binds ({reported})"
    else:
        value = reported.get(limit, 0.0)
        assert value != 0.0, f"{case}: {limit} does not bind ({reported})"
    default = {"allowable": 60e6, "min_wall": 0.008}  # the engine material's
    limit_value = base.get(key, default.get(key))

    def mass_at(factor):
        return _design(**{**base, key: limit_value * factor}).mass

    check_against_differences(case, value, mass_at, best.mass, limit_value)


# ------------------------------------------ 3. the disc under the stress criterion

#: Mass of the lightest disc against its closed form. The governing stress of a free annulus is the
#: hoop stress at its bore and of a solid disc the stress at its centre; the NLP writes a stress row
#: at exactly that radius (SAMPLES starts at 0), so the NLP's optimum is the closed form's, with no
#: sampling error, and design_combination's exact check finds nothing to tighten. What is left is
#: IPOPT's stopping tolerance (1e-10 on rows of order one: the stress row and log J within ~1e-10,
#: and the mass's elasticity to either is at most 1), so 1e-9 leaves a factor ten (measured: IPOPT
#: 1.8e-11 on the mass, 3e-11 on B; the package's closed form to round-off).
DISC_RTOL = 1e-9

#: The closed-form sensitivities against the multipliers (IPOPT's) or the package's closed form:
#: the multipliers come from the KKT point IPOPT stops at, good to about its tolerance (measured:
#: 6e-11 relative); 1e-6 is the package's own figure for the disc and catches any factor or sign.
DISC_SENSITIVITY_RTOL = 1e-6


def lightest_disc(j, rho, nu, omega, sigma, bore, envelope):
    """The lightest disc of inertia j under the stress criterion (Timoshenko and Goodier, art. 32).

    A free annulus (bore radius a, outer radius b) at omega has its largest stress at the bore,
    sigma_t(a) = (3 + nu)/4 rho omega^2 [b^2 + (1 - nu)/(3 + nu) a^2] (sigma_r(a) = 0, so von Mises
    and the largest principal stress are both sigma_t(a)); a solid disc at its centre,
    (3 + nu)/8 rho omega^2 R^2 in both directions. J = m (a^2 + b^2)/2, so the lightest disc has the
    largest b the stress and the envelope allow: m = 2 J/(a^2 + b^2), B = 2 J/(pi rho (b^4 - a^4)).

    Returns
    -------
    dict : mass [kg], b [m], B [m], dm_dsigma [kg/Pa], dm_denvelope [kg/m] (0 where it does not bind)
    """
    a = bore / 2.0
    k = rho * omega**2
    if a > 0.0:
        b2_stress = 4.0 * sigma / ((3.0 + nu) * k) - (1.0 - nu) / (3.0 + nu) * a * a
        db2_dsigma = 4.0 / ((3.0 + nu) * k)
    else:
        b2_stress = 8.0 * sigma / ((3.0 + nu) * k)
        db2_dsigma = 8.0 / ((3.0 + nu) * k)
    stress_binds = b2_stress < (envelope / 2.0) ** 2
    b = math.sqrt(b2_stress) if stress_binds else envelope / 2.0
    mass = 2.0 * j / (a * a + b * b)
    dm_db2 = -2.0 * j / (a * a + b * b) ** 2
    return {
        "mass": mass,
        "b": b,
        "B": 2.0 * j / (math.pi * rho * (b**4 - a**4)),
        "dm_dsigma": dm_db2 * db2_dsigma if stress_binds else 0.0,
        "dm_denvelope": 0.0 if stress_binds else dm_db2 * b,
    }  # d(b^2)/d(envelope) = b


DISC_CASES = [
    # (case, ductile, bore [m], envelope [m]: inf, or below the stress's diameter)
    ("annulus, ductile, stress binds", True, 0.06, math.inf),
    ("annulus, brittle, stress binds", False, 0.06, math.inf),
    ("annulus, ductile, envelope binds", True, 0.06, 0.45),
    ("annulus, brittle, large bore", False, 0.2, math.inf),
    ("solid, ductile, stress binds", True, 0.0, math.inf),
    ("solid, brittle, envelope binds", False, 0.0, 0.5),
]


@pytest.mark.parametrize("method", ["ipopt", "auto"])
@pytest.mark.parametrize("case, ductile, bore, envelope", DISC_CASES, ids=[c[0] for c in DISC_CASES])
def test_disc_under_stress_matches_closed_form(case, ductile, bore, envelope, method):
    """design_flywheel's disc under the stress criterion: mass, D, B and d m/d limit by the closed form.

    Method "ipopt" is the wheel NLP (the reference is independent of it); "auto" is the package's
    own closed form of the disc (flyopt.design.wheel_design), checked against this one.
    """
    j, omega, rho, nu, sigma = 5.0, 300.0, 7200.0, 0.3, 40e6
    material = make_material(
        "steel",
        rho,
        allowable_stress=sigma,
        poisson_ratio=nu,
        tensile_strength=500e6,
        yield_strength=300e6,
        ductile=ductile,
        min_wall=0.005,
    )
    spec = DesignSpec(geometry="disc", criterion="stress", bore=bore, max_outer_diameter=envelope)
    best = design_flywheel(j, omega, [MountShaft("shaft", 1.0)], [material], spec, method=method).best
    if method == "ipopt":
        assert best.provenance.solver_status == "Solve_Succeeded"
    expected = lightest_disc(j, rho, nu, omega, sigma, bore, envelope)
    assert expected["B"] > 0.005  # the wall bound does not bind: the closed form holds
    assert_allclose(best.mass, expected["mass"], rtol=DISC_RTOL)
    assert_allclose(best.dims.d_outer, 2.0 * expected["b"], rtol=DISC_RTOL)
    assert_allclose(best.dims.b, expected["B"], rtol=10 * DISC_RTOL)  # B ~ 1/(b^4 - a^4): four times b's error
    reported = _reported(best.limits.sensitivities)
    assert_allclose(reported.get("stress_disc", 0.0), expected["dm_dsigma"], rtol=DISC_SENSITIVITY_RTOL)
    assert_allclose(reported.get("max_outer_diameter", 0.0), expected["dm_denvelope"], rtol=DISC_SENSITIVITY_RTOL)
    assert_allclose(reported["inertia"], expected["mass"] / j, rtol=DISC_SENSITIVITY_RTOL)  # m is linear in J


@pytest.mark.parametrize("case, ductile, bore, envelope", DISC_CASES, ids=[c[0] for c in DISC_CASES])
def test_disc_closed_form_names_the_binding_limits_ipopt_names(case, ductile, bore, envelope):
    """The closed-form disc (method "auto") and IPOPT's report the same binding limits.

    Where the stress decides the diameter IPOPT names "stress_disc" (check.WHEEL_BINDING_NAMES:
    "the disc's stress is at its allowable"); the closed form must too, as its own sensitivity
    (d m / d sigma_allow != 0) says the stress binds.
    """
    material = make_material(
        "steel",
        7200.0,
        allowable_stress=40e6,
        poisson_ratio=0.3,
        tensile_strength=500e6,
        yield_strength=300e6,
        ductile=ductile,
        min_wall=0.005,
    )
    spec = DesignSpec(geometry="disc", criterion="stress", bore=bore, max_outer_diameter=envelope)
    binding = {
        method: set(
            design_flywheel(5.0, 300.0, [MountShaft("shaft", 1.0)], [material], spec, method=method).best.limits.binding
        )
        for method in ("ipopt", "auto")
    }
    assert binding["auto"] == binding["ipopt"]


# ----------------------------------------------- 4. designs re-evaluated independently

#: Limits the NLP writes as rows or bounds (inertia, envelope, rim speed, width, H/B, walls, hub,
#: arms) hold to IPOPT's constraint tolerance 1e-10 on order-one rows; 1e-9 relative leaves a factor ten.
LIMIT_RTOL = 1e-9

#: The exact stress maxima fall between the NLP's sample radii; design_combination tightens the
#: rows until each part's exact peak is within the package's verification tolerance
#: (flyopt.design.check.VERIFY_RTOL = 1e-6) of its allowable, and that is what is promised.
STRESS_RTOL = 1e-6


def _grey_iron():
    """A grey cast iron whose strength falls with the wall (EN 1561-like rows), brittle, factor 4."""
    rows = [
        StrengthRow(0.010, 250e6),
        StrengthRow(0.020, 225e6),
        StrengthRow(0.040, 195e6),
        StrengthRow(0.080, 170e6),
        StrengthRow(0.150, 155e6),
        StrengthRow(0.300, 145e6),
    ]
    return make_material(
        "grey_iron",
        7200.0,
        poisson_ratio=0.26,
        elastic_modulus=110e9,
        strength_by_thickness=rows,
        thickness_rule="part",
        ductile=False,
        safety_factor=4.0,
        min_wall=0.006,
        bearing_pressure=60e6,
    )


def _dims_of(c):
    """The design's dimensions, read from the Candidate's fields (None: not a part of this geometry)."""
    bore = c.bore or 0.0
    if c.geometry == "disc":
        return wheel.Dims(d_outer=c.dims.d_outer, h=(c.dims.d_outer - bore) / 2.0, b=c.dims.b, bore=bore)
    return wheel.Dims(
        d_outer=c.dims.d_outer,
        h=c.dims.h,
        b=c.dims.b,
        bore=bore,
        t_web=c.dims.t_web or 0.0,
        d_hub=c.dims.d_hub or 0.0,
        l_hub=c.dims.l_hub or 0.0,
        arm_major=c.dims.arm_major or 0.0,
        n_arms=c.n_arms or 0,
    )


def _walls(geometry, d):
    """Each part's relevant wall [m]: the rim min(H, B), the web t, the hub min(radial wall, length),
    the arms their minor axis, the disc min(B, radial extent)."""
    if geometry == "disc":
        return {"disc": min(d.b, (d.d_outer - d.bore) / 2.0)}
    out = {"rim": min(d.h, d.b)}
    if geometry == "rim_web":
        out["web"] = d.t_web
    if d.d_hub:
        out["hub"] = min((d.d_hub - d.bore) / 2.0, d.l_hub)
    if geometry == "rim_arms":
        out["arms"] = wheel.ARM_MINOR_RATIO * d.arm_major
    return out


def governing_stresses(geometry, d, rho, nu, omega, torque, ductile):
    """Every part's governing stress [Pa], written here from the dimensions.

    Disc parts: the stepped disc (radii and thicknesses from the dimensions) solved by
    :func:`flyopt.design.stress.disc_coefficients`, its maxima found by :func:`dense_maxima` (von
    Mises for a ductile material, the largest principal stress for a brittle one). Rim and arms of an arms wheel by the machine-design texts
    (Khurmi and Gupta, ch. 22): the rim 3/4 rho v^2 + 1/4 (2 pi^2 rho omega^2 R^3/(n^2 H)), the arm
    M/Z + F/A at the hub with M = T/n (1 - r_h/R), Z = pi b_a a^2/32, A = pi a b_a/4, F its own
    centrifugal pull to the rim's inner radius plus the rim segment's 2 rho B H omega^2 R^2 sin(pi/n);
    the hub a free annulus pulled at its rim by n F/(2 pi r_h L).
    """
    r_o, r_i, a, r_h = d.d_outer / 2.0, (d.d_outer - 2.0 * d.h) / 2.0, d.bore / 2.0, d.d_hub / 2.0
    out, traction, solid = {}, 0.0, a == 0.0
    if geometry == "disc":
        radii, thick, names = [a, r_o], [d.b], ["disc"]
    elif geometry in ("rim", "thin_rim"):
        radii, thick, names, solid = [r_i, r_o], [d.b], ["rim"], False
    elif geometry == "rim_web" and solid:
        radii, thick, names = [0.0, r_i, r_o], [d.t_web, d.b], ["web", "rim"]
    elif geometry == "rim_web":
        radii, thick, names = [a, r_h, r_i, r_o], [d.l_hub, d.t_web, d.b], ["hub", "web", "rim"]
    else:
        n, r_m = d.n_arms, (d.d_outer - d.h) / 2.0
        major = d.arm_major
        minor = wheel.ARM_MINOR_RATIO * major
        area = math.pi * major * minor / 4.0
        k = rho * omega**2
        out["rim"] = 0.75 * k * r_m**2 + 0.25 * 2.0 * math.pi**2 * k * r_m**3 / (n * n * d.h)
        pull = k * area * (r_i**2 - r_h**2) / 2.0 + 2.0 * k * d.b * d.h * r_m**2 * math.sin(math.pi / n)
        out["arms"] = torque / n * (1.0 - r_h / r_m) / (math.pi * minor * major**2 / 32.0) + pull / area
        traction = n * pull / (2.0 * math.pi * r_h * d.l_hub)
        radii, thick, names = [a, r_h], [d.l_hub], ["hub"]
    coefficients = stress.disc_coefficients(radii, thick, rho, nu, omega, solid=solid, outer_traction=traction)
    measure = "von_mises" if ductile else "largest_principal"
    for step, value in enumerate(dense_maxima(coefficients, radii, rho, nu, omega, measure)):
        out[names[step]] = value
    return out


def dense_maxima(coefficients, radii, rho, nu, omega, measure):
    """The largest von Mises or principal stress of each step [Pa], by brute force: a grid of 2001 radii,
    then 2001 more between the best point's neighbours (a smooth maximum is then found to ~1e-13,
    from below: every value is the measure's at a point of the step)."""

    def values(c, r):
        sr, st = stress.disc_stresses(c, rho, nu, omega, r)
        return stress.von_mises(sr, st) if measure == "von_mises" else np.maximum(sr, st)

    out = []
    for i, (c1, c2) in enumerate(coefficients):
        c = (float(c1), 0.0 if isinstance(c2, (int, float)) and c2 == 0 else float(c2))
        grid = np.linspace(radii[i], radii[i + 1], 2001)
        k = int(np.argmax(values(c, grid)))
        fine = np.linspace(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)], 2001)
        out.append(float(max(np.max(values(c, grid)), np.max(values(c, fine)))))
    return out


REDESIGNS = [
    # (case, material, j [kg m^2], torque [N m], shaft diameter [m], DesignSpec keywords); method "auto"
    (
        "engine-web",
        "engine",
        ENGINE["j"],
        ENGINE["torque"],
        0.07,
        {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.0), "max_outer_diameter": 0.8},
    ),
    (
        "engine-arms",
        "engine",
        ENGINE["j"],
        ENGINE["torque"],
        0.07,
        {"geometry": "rim_arms", "criterion": "stress", "hb_ratio": (0.5, 2.0), "max_outer_diameter": 0.8},
    ),
    (
        "web, grey iron by wall, width",
        "grey_iron",
        20.0,
        400.0,
        0.06,
        {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.5), "max_width": 0.12},
    ),
    (
        "web without bore, brittle",
        "engine_brittle",
        20.0,
        0.0,
        None,
        {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.0)},
    ),
    (
        "arms, grey iron, rim speed",
        "grey_iron",
        8.0,
        700.0,
        0.07,
        {"geometry": "rim_arms", "criterion": "rim_speed", "hb_ratio": (0.8, 2.0), "safety_factor": 4.0},
    ),
    (
        "arms, grey iron, stress",
        "grey_iron",
        8.0,
        700.0,
        0.07,
        {"geometry": "rim_arms", "criterion": "stress", "hb_ratio": (0.8, 2.0)},
    ),
    (
        "web, 25 MPa (the web binds)",
        "engine_25",
        20.0,
        1000.0,
        0.07,
        {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.0)},
    ),
    (
        "web, 15 MPa (the hub binds)",
        "engine_15",
        20.0,
        1000.0,
        0.07,
        {"geometry": "rim_web", "criterion": "stress", "hb_ratio": (0.5, 2.0)},
    ),
    (
        "web, grey iron, factor 8",
        "grey_iron",
        20.0,
        400.0,
        0.06,
        # without the castability rules its key names (grey iron's section ratio leaves this wheel no room):
        # the limits checked here are the NLP's own; tests/design/test_castability.py checks castability
        {
            "geometry": "rim_web",
            "criterion": "stress",
            "hb_ratio": (0.5, 2.5),
            "safety_factor": 8.0,
            "castability": Overrides("none"),
        },
    ),
    (
        "disc with bore, brittle, stress binds",
        "engine_brittle_25",
        5.0,
        500.0,
        0.05,
        {"geometry": "disc", "criterion": "stress"},
    ),
    ("rim, stress, ductile", "engine", 20.0, 0.0, None, {"geometry": "rim", "criterion": "stress"}),
    ("thin rim, stress, brittle", "engine_brittle", 20.0, 0.0, None, {"geometry": "thin_rim", "criterion": "stress"}),
    (
        "disc with bore, grey iron",
        "grey_iron",
        5.0,
        500.0,
        0.05,
        {"geometry": "disc", "criterion": "stress", "max_outer_diameter": 0.6},
    ),
    ("solid disc, stress", "engine", 5.0, 0.0, None, {"geometry": "disc", "criterion": "stress"}),
    (
        "rim, rim speed (textbook closed form)",
        "engine_speed",
        3.0,
        0.0,
        None,
        {"geometry": "rim", "criterion": "rim_speed", "max_width": 0.1},
    ),
    ("web, rim speed", "engine_speed", 3.0, 1000.0, 0.07, {"geometry": "rim_web", "criterion": "rim_speed"}),
]


def _material(name):
    if name == "grey_iron":
        return _grey_iron()
    return {
        "engine": _engine_material(),
        "engine_brittle": _engine_material(ductile=False),
        "engine_25": _engine_material(25e6),
        "engine_15": _engine_material(15e6),
        "engine_brittle_25": _engine_material(25e6, ductile=False),
        "engine_speed": _engine_material(max_rim_speed=40.0),
    }[name]


#: The discs by stress again with IPOPT (under "auto" the closed form designs them).
REDESIGNS += [
    (f"{case}, IPOPT", material, j, torque, seat, {**spec, "method": "ipopt"})
    for case, material, j, torque, seat, spec in REDESIGNS
    if spec["geometry"] == "disc"
]


@pytest.mark.parametrize("case, material, j, torque, seat, spec", REDESIGNS, ids=[c[0] for c in REDESIGNS])
def test_designs_meet_every_limit(case, material, j, torque, seat, spec):
    """Every feasible candidate of design_flywheel meets its limits when evaluated again here."""
    material = _material(material)
    method = spec.get("method", "auto")
    spec = DesignSpec(**{k: v for k, v in spec.items() if k != "method"})
    omega = ENGINE["omega"]
    result = design_flywheel(
        j, omega, [MountShaft("shaft", 1.0, seat)], [material], spec, torque=torque or None, method=method
    )
    assert result.status == "designed", result.message
    feasible = [c for c in result.candidates if c.feasible]
    for c in feasible:
        what = f"{case} ({c.n_arms} arms)" if c.n_arms else case
        d = _dims_of(c)
        parts = wheel.parts(c.geometry, d, material.density)
        mass, inertia = sum(p.mass for p in parts), sum(p.inertia for p in parts)
        assert_allclose([c.mass, c.j_flywheel], [mass, inertia], rtol=1e-12, err_msg=what)
        assert inertia >= j * (1.0 - LIMIT_RTOL), what
        assert d.d_outer <= spec.max_outer_diameter * (1.0 + LIMIT_RTOL), what
        v_max = material.rim_speed_limit(safety_factor=spec.safety_factor) if spec.criterion == "rim_speed" else None
        if v_max is not None:
            assert omega * d.d_outer / 2.0 <= v_max * (1.0 + LIMIT_RTOL), what
        assert max(d.b, d.l_hub) <= spec.max_width * (1.0 + LIMIT_RTOL), what
        if c.geometry != "disc":
            lo, hi = spec.hb_ratio
            assert lo * (1.0 - LIMIT_RTOL) <= d.h / d.b <= hi * (1.0 + LIMIT_RTOL), what
            assert d.d_outer - 2.0 * d.h >= d.d_hub - LIMIT_RTOL * d.d_outer, f"{what}: the rim cuts the hub"
        if not spec.textbook(d.bore):  # the textbook design is left as the textbook makes it
            walls = _walls(c.geometry, d)
            if c.geometry == "disc":  # a disc's radial extent is no wall the NLP bounds
                walls = {"disc": d.b}
            assert min(walls.values()) >= (spec.min_wall or material.min_wall) * (1.0 - LIMIT_RTOL), what
        if c.geometry == "rim_web":
            assert d.t_web <= d.b * (1.0 + LIMIT_RTOL), what
            assert not d.l_hub or d.t_web <= d.l_hub * (1.0 + LIMIT_RTOL), what
        if c.geometry == "rim_arms":
            minor = wheel.ARM_MINOR_RATIO * d.arm_major
            assert d.n_arms * d.arm_major <= math.pi * d.d_hub * (1.0 + LIMIT_RTOL), f"{what}: arms do not fit"
            assert minor <= min(d.b, d.l_hub) * (1.0 + LIMIT_RTOL), what
        if d.d_hub:  # the textbook proportions of a keyed hub, and the key
            p = hub.hub_proportions(d.bore, material.hub_kind)
            l_low = p.l_hub_min
            if torque:
                l_low = max(l_low, hub_length_for_key(torque, d.bore, material.bearing_pressure))
            assert p.d_hub_min * (1 - LIMIT_RTOL) <= d.d_hub <= p.d_hub_max * (1 + LIMIT_RTOL), what
            assert l_low * (1 - LIMIT_RTOL) <= d.l_hub <= max(p.l_hub_max, l_low) * (1 + LIMIT_RTOL), what
        if spec.criterion == "stress":
            found = governing_stresses(
                c.geometry, d, material.density, material.poisson_ratio, omega, torque, material.ductile
            )
            walls = _walls(c.geometry, d)
            assert set(found) == set(walls), what
            for part, value in found.items():
                allowable = material.allowable(thickness=walls[part], safety_factor=spec.safety_factor)
                assert value <= allowable * (1.0 + STRESS_RTOL), (
                    f"{what}: {part} {value / 1e6:.9g} MPa > allowable {allowable / 1e6:.9g} MPa"
                )


def test_a_trial_point_beyond_floating_point_leaves_the_terminal_silent(capfd):
    """IPOPT meets a trial point whose rows overflow (the wheel started at e^5 = 148 m in every dimension, no
    bounds) and steps back from it to a converged wheel: CasADi's warning of each such evaluation ("nlp_g failed:
    Inf detected") is not printed, where it once reached the terminal above a design (a disc on a hub grown to
    metres); the status says how the solve ended."""
    structure, problem = random_case(5)
    model = wheel_nlp.get_model(structure, {wheel_nlp.SOLVER_OPTION: "ipopt"})
    args, _, _ = wheel_nlp.solve_arguments(structure, model.constraints, problem)
    n = len(model.variables)
    capfd.readouterr()
    model.solver(**{**args, "x0": np.full(n, 5.0), "lbx": np.full(n, -np.inf), "ubx": np.full(n, np.inf)})
    assert model.solver.stats()["return_status"] == "Solve_Succeeded"
    assert capfd.readouterr() == ("", "")


def test_a_problem_copied_with_fields_set_is_replaces_copy():
    """wheel_design._with (a copy with fields set, for speed) gives what dataclasses.replace gives, and
    refuses a field the problem does not have as replace does. It may, because WheelProblem has nothing that
    replace would run and a copy would not: no __post_init__, no init=False field, no slots."""
    assert not hasattr(wheel_nlp.WheelProblem, "__post_init__")
    assert not hasattr(wheel_nlp.WheelProblem, "__slots__")
    assert all(f.init for f in dataclasses.fields(wheel_nlp.WheelProblem))
    _, problem = random_wheel(7)
    changes = {"warm": {"d_outer": 0.5}, "caps": {"h": 0.1}, "ipopt_first": True}
    assert wheel_design._with(problem, **changes) == dataclasses.replace(problem, **changes)
    assert problem.warm is None  # the original is untouched
    with pytest.raises(TypeError):
        wheel_design._with(problem, no_such_field=1)
    with pytest.raises(TypeError):
        dataclasses.replace(problem, no_such_field=1)
