"""The design section: flyopt's ranking against SLSQP, grids and the 1-D root search.

Design ranking, 2 materials × 3 shafts. flyopt's two paths through
:func:`flyopt.design.design_flywheel`: the default ``auto`` (the exact
closed form where it covers the structure) and IPOPT on every NLP, each timed
as the one call a user makes (the default's structural check and description
of each design and explanation of each infeasible combination are made when
first read, so
``flyopt-auto-read`` times it again with every reported candidate read whole,
as ``flyopt solve`` prints them); scipy's
SLSQP on the same model, once in scaled physical variables and once in
flyopt's own log-variables; a brute-force grid
over mean diameter × H/B at several resolutions, each grid point sized exactly
to the required inertia (:mod:`flyopt.bench.peers`); and the bench's own 1-D
root search (:func:`flyopt.bench.references.lightest_rim_1d`), written
independently of flyopt. Reference: the best verified optimum, the least mass
over the 1-D root search and every method's candidates that satisfy all
constraints to 1e-9. Error: relative excess mass of the ranking's winner, plus
the constraint violation. The random scenes also feed the geometry section.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from functools import partial
from typing import Any, cast

import numpy as np

from flyopt.bench.peers import SLSQP_FTOL, SLSQP_FTOLS, grid_combination, slsqp_combination
from flyopt.bench.references import Combination, Outcome, checked_design, combinations, lightest_rim_1d
from flyopt.bench.timing import Config, Row, measure, set_ratios
from flyopt.design import Design, DesignResult, DesignSpec, MountShaft, design_flywheel, wheel, wheel_design
from flyopt.design.materials import Material, builtin_materials
from flyopt.errors import SolverFailed

__all__ = [
    "RPM",
    "REFERENCE_RTOL",
    "ipopt_combinations",
    "design_methods",
    "structural_checks",
    "random_design_scenes",
    "section_design",
]

RPM = math.pi / 30.0
"""One revolution per minute [rad/s]."""
REFERENCE_RTOL = 1e-12
"""A candidate may join the reference optimum only if it violates nothing by more than this."""


def ipopt_combinations(
    j_required: float,
    omega_mean: float,
    shafts: Sequence[MountShaft],
    materials: Sequence[Material],
    spec: DesignSpec,
    method: str = "ipopt",
) -> list[Outcome]:
    """flyopt's ranking (one design_flywheel call) as one Outcome per combination."""
    combos = combinations(j_required, omega_mean, shafts, materials, spec)
    try:
        result = design_flywheel(j_required, omega_mean, shafts, materials, spec, method=method)
    except SolverFailed as err:
        return [Outcome("failed", reason=f"SolverFailed: {err}") for _ in combos]
    found = {(c.material, c.shaft): c for c in result.candidates}
    out = []
    for combo in combos:
        c = found[(combo.material, combo.shaft)]
        if c.dims is None:  # infeasible: no dimensions
            out.append(Outcome("infeasible", reason=c.reason))
        else:
            solved = f"IPOPT {c.provenance.solver_status}, {c.provenance.iterations} it"
            out.append(checked_design(combo, c.dims.d_mean, c.dims.h, c.dims.b, solved))
    return out


class _PerCombination:
    """A solver of one combination run over a scene's combinations: solve(j, ω, shafts, materials, spec)."""

    def __init__(self, solver: Callable[[Combination], Outcome]) -> None:
        self.per_combination = solver  # timed on combinations built outside the timing

    def __call__(
        self,
        j_required: float,
        omega_mean: float,
        shafts: list[MountShaft],
        materials: list[Material],
        spec: DesignSpec,
    ) -> list[Outcome]:
        return [self.per_combination(c) for c in combinations(j_required, omega_mean, shafts, materials, spec)]


def _per_combination(solver: Callable[[Combination], Outcome]) -> _PerCombination:
    return _PerCombination(solver)


def _flyopt_ranking(method):
    """The call a user makes: one design_flywheel over every combination (what is timed).

    A textbook design's structural check and description (what binds, its limits, how it was found) are made
    when its fields are first read (:meth:`flyopt.design.result.Design.checked_when_read`), and an infeasible
    one's explanation too, so they are not in this time; :func:`_flyopt_ranking_read` times the ranking with
    every candidate read whole.
    """

    def rank(j_required, omega_mean, shafts, materials, spec):
        return design_flywheel(j_required, omega_mean, shafts, materials, spec, method=method)

    return rank


def _flyopt_ranking_read(method):
    """The ranking with every field of every candidate it reports read, as ``flyopt solve`` reads them (what is
    timed): the parts, stresses and notes of each design (its structural check) and its reason and limits (what
    binds), the reason and limits of each infeasible combination (its explanation in numbers)."""

    def rank_and_read(j_required, omega_mean, shafts, materials, spec):
        result = design_flywheel(j_required, omega_mean, shafts, materials, spec, method=method)
        for c in result.candidates:
            c.parts, c.stresses, c.provenance, c.reason, c.limits  # noqa: B018 (read to be made)
        return result

    return rank_and_read


def design_methods(config: Config) -> list[tuple[Any, ...]]:
    """Name, setting and solver of every design method: solver(j, ω, shafts, materials, spec).

    flyopt's entries carry a fourth item, the call that is timed: its ranking
    alone, without the bench's conversion of the result into Outcomes. The
    other methods are timed on their combinations built beforehand (the caps
    and inertias per material and shaft, which flyopt's timing includes).
    """
    methods: list[tuple[Any, ...]] = [
        ("flyopt-ipopt", "casadi/ipopt", ipopt_combinations, _flyopt_ranking("ipopt")),
        (
            "flyopt-auto",
            "closed form where exact",
            lambda j, omega, shafts, materials, spec: ipopt_combinations(
                j, omega, shafts, materials, spec, method="auto"
            ),
            _flyopt_ranking("auto"),
        ),
        (
            "flyopt-auto-read",
            "every candidate read whole",
            lambda j, omega, shafts, materials, spec: ipopt_combinations(
                j, omega, shafts, materials, spec, method="auto"
            ),
            _flyopt_ranking_read("auto"),
        ),
    ]
    for ftol in SLSQP_FTOLS:
        methods.append(
            ("slsqp", f"ftol={ftol:g}", _per_combination(partial(slsqp_combination, variables="scaled", ftol=ftol)))
        )
    methods += [
        ("slsqp-log", f"ftol={SLSQP_FTOL:g}", _per_combination(lambda c: slsqp_combination(c, "log", SLSQP_FTOL))),
        ("root-1d", "bench reference", _per_combination(lightest_rim_1d)),
    ]
    for n_d, n_k in config.grids:
        methods.append(
            ("grid", f"{n_d}x{n_k}", _per_combination(partial(grid_combination, n_diameters=n_d, n_ratios=n_k)))
        )
    return methods


def structural_checks(result: DesignResult, omega: float, materials: Sequence[Material]) -> Callable[[], list[Any]]:
    """The structural check of every design a ranking reports, made again on its dimensions (to be timed).

    The check each reported candidate carries (made when its fields are first read),
    :func:`flyopt.design.wheel_design.structure_fields` (parts, stresses, burst
    speed, unbalance), with the arguments the designer gives it on a bare
    wheel without a bore or torque: the part of the time of a ranking whose
    every candidate is read that no faster closed form removes.
    """
    by_name = {m.name: m for m in materials}
    calls = []
    for c in result.candidates:
        if isinstance(c, Design):
            disc = c.geometry == "disc"
            dims = wheel.Dims(d_outer=c.dims.d_outer, h=c.dims.d_outer / 2.0 if disc else c.dims.h, b=c.dims.b)
            calls.append((by_name[c.material], c.geometry, dims, omega * c.speed_ratio, result.spec))

    def check_all() -> list[Any]:
        return [wheel_design.structure_fields(m, g, d, w, 0.0, spec, 0.0) for m, g, d, w, spec in calls]

    return check_all


def random_design_scenes(count: int, seed: int) -> list[dict[str, Any]]:
    """Random scenes of 2 built-in materials × 3 shafts (as benchmarks/bench_design.py).

    J_F log-uniform 1e-3..1e4 kg*m^2, 50..5000 rpm, shafts 1, 0.1..1 and
    1..10 × the reference, rim or thin_rim, H/B 1.5..2; a third of the scenes
    with an envelope (0.3..1.5 of the cast-iron rim-speed diameter of the
    reference shaft), a quarter with a width limit (0.5..3 × the thin-rim
    width at that diameter).
    """
    materials = [builtin_materials()[name] for name in ("cast_iron", "cast_steel")]
    rng = np.random.default_rng(seed)
    scenes = []
    for _ in range(count):
        rpm = 10 ** rng.uniform(math.log10(50), math.log10(5000))
        omega = rpm * RPM
        j = float(10 ** rng.uniform(-3, 4))
        shafts = [
            MountShaft("reference", 1.0),
            MountShaft("slower", float(10 ** rng.uniform(-1.0, 0.0))),
            MountShaft("faster", float(10 ** rng.uniform(0.0, 1.0))),
        ]
        geometry = str(rng.choice(["rim", "thin_rim"]))
        cap = 2.0 * cast(float, materials[0].max_rim_speed) / omega  # built-in cast iron has one
        envelope = float(cap * rng.uniform(0.3, 1.5)) if rng.random() < 1 / 3 else math.inf
        width = math.inf  # no limit (DesignSpec reads None as inf)
        if rng.random() < 0.25:
            h_s = math.sqrt(4 * j * 1.5 / (math.pi * materials[0].density * cap**3))
            width = float(h_s / 1.5 * rng.uniform(0.5, 3.0))
        spec = DesignSpec(geometry=geometry, hb_ratio=(1.5, 2.0), max_outer_diameter=envelope, max_width=width)
        scenes.append(
            {"j_required": j, "omega_mean": omega, "rpm": rpm, "shafts": shafts, "materials": materials, "spec": spec}
        )
    return scenes


def _reference_optimum(reference, outcomes_by_method, combo):
    """Best verified optimum of a combination: least mass over the reference and verified candidates."""
    best = reference.mass if reference.verdict == "design" else math.inf
    for outcome in outcomes_by_method:
        if outcome.verdict == "design" and outcome.violation <= REFERENCE_RTOL:
            best = min(best, outcome.mass)
    return best


def _judge(outcome, ref_mass):
    """(correct verdict, relative excess mass or None) of one outcome against the reference mass."""
    feasible = math.isfinite(ref_mass)
    if outcome.verdict == "design":
        if not feasible:  # a verified design where the reference found none: reference wrong
            return True, 0.0
        return True, (outcome.mass - ref_mass) / ref_mass
    # no design: right when the combination is infeasible, whether the method proved it
    # (flyopt's closed form, an empty grid) or only failed to converge (SLSQP)
    return not feasible, None


def section_design(config: Config) -> list[Row]:
    """Design ranking, 2 materials × 3 shafts: IPOPT, SLSQP, grids, 1-D root search."""
    scenes = random_design_scenes(config.scenes, config.seed)
    methods = design_methods(config)
    # warm-up: build every NLP structure the scenes use, outside the timings
    for geometry in ("rim", "thin_rim"):
        design_flywheel(1.0, 100.0, scenes[0]["shafts"], scenes[0]["materials"], DesignSpec(geometry), method="ipopt")
    stats = {
        name + setting: {
            "times": [],
            "errors": [],
            "viol": 0.0,
            "ok": 0,
            "total": 0,
            "fail": 0,
            "reasons": {},
            "name": name,
            "setting": setting,
            "repeats": 0,
            "checks": [],
        }
        for name, setting, *_ in methods
    }
    beat_reference, beat_by = 0, 0.0
    for scene in scenes:
        args = (scene["j_required"], scene["omega_mean"], scene["shafts"], scene["materials"], scene["spec"])
        combos = combinations(*args)
        results = {}
        for name, setting, solve, *timed in methods:
            outcomes = solve(*args)
            if timed:
                timing = measure(lambda: timed[0](*args), config.design_repeats)
                if name == "flyopt-auto-read":  # what of its time is the structural check of what it reports
                    check_all = structural_checks(timed[0](*args), scene["omega_mean"], scene["materials"])
                    stats[name + setting]["checks"].append(measure(check_all, config.design_repeats).median)
            else:
                per = solve.per_combination
                timing = measure(lambda: [per(c) for c in combos], config.design_repeats)
            results[name + setting] = outcomes
            s = stats[name + setting]
            s["times"].append(timing.median)
            s["repeats"] = timing.repeats
        ref_outcomes = results["root-1dbench reference"]
        ref_mass = []
        for i, combo in enumerate(combos):
            best = _reference_optimum(ref_outcomes[i], [r[i] for r in results.values()], combo)
            if ref_outcomes[i].verdict == "design" and best < ref_outcomes[i].mass * (1 - REFERENCE_RTOL):
                beat_reference += 1
                beat_by = max(beat_by, 1.0 - best / ref_outcomes[i].mass)
            ref_mass.append(best)
        winner = min(ref_mass)
        for key, outcomes in results.items():
            s = stats[key]
            for outcome, m_ref in zip(outcomes, ref_mass):
                ok, _ = _judge(outcome, m_ref)
                s["total"] += 1
                s["ok"] += ok
                if outcome.verdict == "design":
                    s["viol"] = max(s["viol"], outcome.violation)
                if not ok:
                    s["fail"] += 1
                    reason = outcome.reason.split(" (status")[0][:90] or outcome.verdict
                    s["reasons"][reason] = s["reasons"].get(reason, 0) + 1
            masses = [o.mass for o in outcomes if o.verdict == "design"]
            if masses and math.isfinite(winner):
                s["errors"].append(abs(min(masses) - winner) / winner)
            elif math.isfinite(winner):
                s["errors"].append(math.inf)  # no design where there is one
    rows = []
    for s in stats.values():
        times = np.array(s["times"])
        errors = [e for e in s["errors"] if math.isfinite(e)]
        missing = len(s["errors"]) - len(errors)
        reasons = "; ".join(f"{n}x {r}" for r, n in sorted(s["reasons"].items(), key=lambda t: -t[1])[:3])
        note = f"{len(scenes)} scenes x {s['total'] // len(scenes)} combinations"
        if missing:
            note += f"; no design at all in {missing} scenes"
        if reasons:
            note += f"; wrong verdicts: {reasons}"
        if s["name"] == "flyopt-auto":
            note += (
                "; each design's structural check and description (what binds, its limits, how it was found) and each "
                "infeasible combination's explanation are made when first read (Candidate.made_when_read), not in "
                "this time; every design is verified against every constraint in it: flyopt-auto-read reads them all"
            )
        if s["checks"]:
            share = np.array(s["checks"]) / times
            note += (
                f"; of which the structural check of the reported candidates (wheel_design.structure_fields, "
                f"timed again on the same candidates): median {1e3 * np.median(s['checks']):.3g} ms per ranking "
                f"({1e3 * np.quantile(s['checks'], 0.25):.3g}–{1e3 * np.quantile(s['checks'], 0.75):.3g}), "
                f"{100 * np.median(share):.0f} % of the ranking's time (median over scenes)"
            )
        if s["name"] == "root-1d" and beat_reference:
            note += (
                f"; beaten by a verified candidate (violation <= {REFERENCE_RTOL:g}) in {beat_reference} "
                f"combinations, by at most {beat_by:.1e} in mass"
            )
        rows.append(
            Row(
                "design",
                "ranking 2x3",
                s["name"],
                s["setting"],
                float(np.median(times)),
                float(np.quantile(times, 0.25)),
                float(np.quantile(times, 0.75)),
                s["repeats"],
                1,
                error=max(errors) if errors else math.inf,
                error_median=float(np.median(errors)) if errors else math.inf,
                violation=s["viol"],
                verdicts_ok=s["ok"],
                verdicts_total=s["total"],
                failures=s["fail"],
                reference="best verified optimum (1-D root search)",
                note=note,
            )
        )
    set_ratios(rows, lambda r: r.method == "flyopt-ipopt")
    return rows
