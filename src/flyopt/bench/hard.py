"""The hard set: generated extremes, each checked against an exact reference.

Cycle tables of 2 to 100,000 points with steps, spikes, near-tangent
crossings and 10^6 N·m offsets, checked against exact rational arithmetic or
closed forms (relative error <= 1e-9); and design scenes over δ 1e-5..0.5,
J_F 1e-6..1e6 kg·m², 1..50,000 rpm and shafts 1/20..50 × the reference, each
combination checked against the 1-D root search (mass within 1e-6, or a
correct infeasible verdict), for flyopt's two paths and for SLSQP. Run by
``flyopt bench --hard``; written by :func:`flyopt.bench.output.write_hard_csv`
and summarised by :func:`flyopt.bench.output.hard_summary`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any, cast

import numpy as np

from flyopt.bench.cycle import (
    TWO_PI,
    CycleCase,
    case_near_tangent,
    flyopt_a_max,
    flyopt_curve,
    reference_a_max,
    table_noisy,
    table_ripple,
    table_spike,
    table_staircase,
)
from flyopt.bench.design import RPM, ipopt_combinations
from flyopt.bench.peers import SLSQP_FTOL, SLSQP_FTOLS, slsqp_combination
from flyopt.bench.references import combinations, exact_a_max_tables, largest_rim_inertia, lightest_rim_1d, violation
from flyopt.bench.timing import Config
from flyopt.cycle.indicator import energy_indicator, required_inertia
from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.materials import builtin_materials

__all__ = ["CYCLE_BAR", "MASS_BAR", "hard_cycle_cases", "hard_design_scenes", "run_hard"]

CYCLE_BAR = 1e-9
"""Relative error allowed on A_max and J_F in the hard set."""
MASS_BAR = 1e-6
"""Relative error allowed on an optimized mass in the hard set."""


def hard_cycle_cases(config: Config, rng: np.random.Generator) -> list[CycleCase]:
    """Generated cycles across the extremes, each with an exact reference."""
    sizes = (2, 3, 10, 1000) if config.quick else (2, 3, 10, 100, 1000, 10_000, 100_000)
    cases = []
    for n in sizes:
        x, y = table_noisy(n, rng)
        cases.append(CycleCase(f"noisy table {n} points", ("mean",), ("table", x, y), kind="size"))
        x = np.linspace(0.0, TWO_PI, n)
        cases.append(
            CycleCase(
                f"smooth table {n} points",
                ("mean",),
                ("table", x, 800.0 + 600.0 * np.sin(x) + 150.0 * np.cos(3.0 * x + 0.3)),
                kind="size",
            )
        )
    x, y = table_staircase(40 if config.quick else 200)
    cases.append(CycleCase(f"staircase {len(x) // 2} steps", ("mean",), ("table", x, y), kind="steps"))
    xs = np.sort(np.concatenate((rng.uniform(0, TWO_PI, 50), np.repeat(rng.uniform(0, TWO_PI, 25), 2))))
    xs = np.concatenate(([0.0], xs, [TWO_PI]))
    cases.append(CycleCase("random steps", ("mean",), ("table", xs, rng.uniform(0, 1000, xs.size)), kind="steps"))
    for offset in (0.0, 1e3, 1e6):
        cases.append(
            CycleCase(f"spike 2% at 50x, offset {offset:g}", ("mean",), ("table", *table_spike(offset)), kind="spike")
        )
    for gap in (0.0, 1e-12, 1e-6):
        cases.append(case_near_tangent(gap))
    for offset, n in ((1e3, 300), (1e6, 300), (1e6, 10_000), (1e9, 300)):
        if config.quick and n > 1000:
            continue
        cases.append(
            CycleCase(
                f"offset {offset:g} + 1 N*m ripple, {n} points",
                ("mean",),
                ("table", *table_ripple(offset, n, rng)),
                kind="offset",
            )
        )
    x = np.linspace(0.0, TWO_PI, 1001)
    cases.append(
        CycleCase(
            "zero-mean table 300 sin 2phi (a balanced load)",
            ("mean",),
            ("table", x, 300.0 * np.sin(2.0 * x)),
            kind="zero mean",
        )
    )
    x = np.linspace(0.0, TWO_PI, 400)
    yr = 1e6 + rng.uniform(-1.0, 1.0, x.size)
    yd = 1e6 + np.sin(x)
    _, net = exact_a_max_tables(x, yd, x, yr)
    cases.append(
        CycleCase(
            "two tables at 1e6 N*m, 1 N*m apart",
            ("table", x, yd),
            ("table", x, yr + float(net) / TWO_PI),
            kind="offset",
        )
    )
    for offset, k in ((0.0, 1), (0.0, 3), (1e3, 2), (1e6, 1)):
        text = f"{offset!r} + sin({k}*phi)" if k != 1 else f"{offset!r} + sin(phi)"
        cases.append(
            CycleCase(f"expression {text}", ("mean",), ("expr", text, 2.0 / k), kind="expression (closed form 2A/k)")
        )
    return cases


def hard_design_scenes(config: Config, rng: np.random.Generator, cycles: list[CycleCase]) -> list[dict[str, Any]]:
    """Scenes over δ 1e-5..0.5, J_F 1e-6..1e6, 1..50,000 rpm, shafts 1/20..50.

    Each scene takes a cycle case, scales its torques by a power of two so
    that J_F = A_max/(ω² δ) lands near a target drawn log-uniform in
    1e-6..1e6 kg*m^2 (the reference scales exactly), and draws the design:
    3 shafts (one at 1/20 or 50 in a third of the scenes), rim or thin_rim,
    H/B range or fixed, envelope and width limit sometimes. The first scenes
    pin the extremes (J_F, rpm, δ and ratio at their ends).
    """
    materials = [builtin_materials()[name] for name in ("cast_iron", "cast_steel")]
    small = [c for c in cycles if c.points <= 1000]
    corners = [(j, rpm, dl) for j in (1e-6, 1e6) for rpm in (1.0, 50_000.0) for dl in (1e-5, 0.5)]
    scenes = []
    for i in range(config.hard_scenes):
        if i < len(corners) and not config.quick:
            j_target, rpm, delta = corners[i]
        else:
            j_target = 10 ** rng.uniform(-6, 6)
            rpm = 10 ** rng.uniform(0, math.log10(50_000))
            delta = 10 ** rng.uniform(-5, math.log10(0.5))
        cycle = small[i % len(small)]
        omega = rpm * RPM
        a_ref = reference_a_max(cycle)
        power = round(math.log2(j_target * omega**2 * delta / a_ref))
        ratios = [1.0, float(10 ** rng.uniform(math.log10(1 / 20), 0)), float(10 ** rng.uniform(0, math.log10(50)))]
        if i % 3 == 0:
            ratios[1 + (i // 3) % 2] = (1 / 20, 50.0)[(i // 3) % 2]
        shafts = [MountShaft(f"shaft{k}", r) for k, r in enumerate(ratios)]
        low = float(rng.uniform(1.0, 2.5))
        high = low if rng.random() < 0.2 else low + float(rng.uniform(0.0, 1.0))
        cap = 2.0 * cast(float, materials[0].max_rim_speed) / omega  # built-in cast iron has one
        envelope = float(cap * rng.uniform(0.3, 1.5)) if rng.random() < 0.3 else math.inf
        width = math.inf  # no limit (DesignSpec reads None as inf)
        if rng.random() < 0.25:
            j_est = a_ref * math.ldexp(1.0, power) / (omega**2 * delta)
            h_s = math.sqrt(4 * j_est * low / (math.pi * materials[0].density * cap**3))
            width = float(h_s / low * 10 ** rng.uniform(-0.5, 1.0))
        spec = DesignSpec(
            geometry=str(rng.choice(["rim", "thin_rim"])),
            hb_ratio=(low, high),
            max_outer_diameter=envelope,
            max_width=width,
        )
        scenes.append(
            {
                "cycle": cycle,
                "power": power,
                "rpm": rpm,
                "omega_mean": omega,
                "delta": delta,
                "shafts": shafts,
                "materials": materials,
                "spec": spec,
            }
        )
    return scenes


def _boundary_scenes(config, base):
    """Scenes whose J_F puts the first combination just inside or outside its largest inertia.

    Factors 1 − 1e-4, 1 + 1e-4, 1 − 1e-7 and 1 + 1e-5 (outside by more than
    the 1e-6 tolerance a design is verified to, so that a verdict is decidable).

    Only base scenes where that inertia lies within 1e-6..1e6 kg*m^2 are used.
    """
    factors = (1 - 1e-4, 1 + 1e-4, 1 - 1e-7, 1 + 1e-5)
    count = 2 if config.quick else 16
    out: list[dict[str, Any]] = []
    for scene in base:
        if len(out) >= count:
            break
        combo = combinations(1.0, scene["omega_mean"], scene["shafts"][:1], scene["materials"][:1], scene["spec"])[0]
        j_max = largest_rim_inertia(combo)
        if not 1e-6 <= j_max <= 1e6:
            continue
        factor = factors[len(out) % len(factors)]
        scene = dict(
            scene,
            j_override=j_max * factor,
            boundary=f"J' = (1 {'-' if factor < 1 else '+'} {abs(factor - 1):.0e}) x largest inertia "
            f"of {combo.material} on {combo.shaft}",
        )
        out.append(scene)
    return out


def run_hard(
    config: Config, progress: Callable[[str], object] | None = None
) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The hard set: cycle checks against exact references, design checks against the 1-D root search.

    Returns
    -------
    cycle_rows, design_rows : list of dict
        One dict per cycle check and per (scene, combination, method).
    """
    rng = np.random.default_rng(config.seed + 1000)
    cycles = hard_cycle_cases(config, rng)
    cycle_rows = []
    for case in cycles:
        start = time.perf_counter()
        a_max_ref = reference_a_max(case)
        ref_time = time.perf_counter() - start
        try:
            start = time.perf_counter()
            ind = energy_indicator(flyopt_curve(case.driving), flyopt_curve(case.resisting), case.cycle_angle)
            elapsed = time.perf_counter() - start
            value, status = ind.a_max, "ok"
        except (ArithmeticError, ValueError) as exc:
            value, status, elapsed = math.nan, f"{type(exc).__name__}: {exc}", math.nan
        cycle_error = abs(value - a_max_ref) / a_max_ref if math.isfinite(value) else math.inf
        cycle_rows.append(
            {
                "kind": "cycle",
                "case": case.name,
                "points": case.points,
                "check": "a_max",
                "value": value,
                "reference": a_max_ref,
                "reference_how": case.reference_how,
                "rel_error": cycle_error,
                "bar": CYCLE_BAR,
                "passed": cycle_error <= CYCLE_BAR,
                "status": status,
                "time_s": elapsed,
                "reference_time_s": ref_time,
            }
        )
    if progress:
        progress(f"hard: {len(cycle_rows)} cycle cases checked")
    scenes = hard_design_scenes(config, rng, cycles)
    scenes += _boundary_scenes(config, scenes)
    for geometry in ("rim", "thin_rim"):  # build the NLPs outside the timings
        design_flywheel(1.0, 100.0, scenes[0]["shafts"], scenes[0]["materials"], DesignSpec(geometry), method="ipopt")
    design_rows = []
    solvers: dict[str, Any] = {"flyopt-ipopt": "ipopt", "flyopt-auto": "auto"}  # flyopt's design paths
    for ftol in SLSQP_FTOLS:
        solvers[f"slsqp(ftol={ftol:g})"] = lambda c, ftol=ftol: slsqp_combination(c, "scaled", ftol)
    solvers[f"slsqp-log(ftol={SLSQP_FTOL:g})"] = lambda c: slsqp_combination(c, "log", SLSQP_FTOL)
    for index, scene in enumerate(scenes):
        cycle = scene["cycle"].scaled(scene["power"])
        omega, delta = scene["omega_mean"], scene["delta"]
        a_ref = reference_a_max(cycle)
        if "j_override" in scene:
            j_ref = j_fly = scene["j_override"]
            check_j = None
        else:
            # independent: 900 A / (π² n² δ) in rationals of the float inputs (π as a float)
            j_ref = float(
                Fraction(900)
                * Fraction(a_ref)
                / (Fraction(math.pi) ** 2 * Fraction(scene["rpm"]) ** 2 * Fraction(delta))
            )
            try:
                j_fly = required_inertia(flyopt_a_max(cycle), omega, delta)
                status = "ok"
            except (ArithmeticError, ValueError) as exc:
                # the cycle analysis refused the scene: record it, and design for the exact J_F
                j_fly, status = j_ref, f"{type(exc).__name__}: {exc}"
            check_j = abs(j_fly - j_ref) / j_ref if status == "ok" else math.inf
            cycle_rows.append(
                {
                    "kind": "j_required",
                    "case": f"scene {index}: {cycle.name} x 2^{scene['power']}",
                    "points": cycle.points,
                    "check": "j_required",
                    "value": j_fly if status == "ok" else math.nan,
                    "reference": j_ref,
                    "reference_how": "900 A_max/(pi^2 n^2 delta), exact A_max",
                    "rel_error": check_j,
                    "bar": CYCLE_BAR,
                    "passed": check_j <= CYCLE_BAR,
                    "status": status,
                    "time_s": math.nan,
                    "reference_time_s": math.nan,
                }
            )
        ref_combos = combinations(j_ref, omega, scene["shafts"], scene["materials"], scene["spec"])
        fly_combos = combinations(j_fly, omega, scene["shafts"], scene["materials"], scene["spec"])
        references = [lightest_rim_1d(c) for c in ref_combos]
        for name, solver in solvers.items():
            for ref_combo, combo, ref in zip(ref_combos, fly_combos, references):
                start = time.perf_counter()
                if isinstance(solver, str):
                    outcome = ipopt_combinations(
                        combo.j * combo.speed_ratio**2,
                        omega,
                        [MountShaft(combo.shaft, combo.speed_ratio)],
                        [m for m in scene["materials"] if m.name == combo.material],
                        scene["spec"],
                        method=solver,
                    )[0]
                else:
                    outcome = solver(combo)
                elapsed = time.perf_counter() - start
                ref_mass = cast(float, ref.mass) if ref.verdict == "design" else math.inf  # a design has its mass
                if outcome.verdict == "design":
                    # measured against the reference combination (J from the exact A_max)
                    outcome.violation = (
                        violation(ref_combo, *cast(tuple[float, float, float], outcome.dims))
                        if ref.verdict == "design"
                        else outcome.violation
                    )
                err = None
                last = last_error = None
                if outcome.verdict == "failed" and outcome.mass is not None and math.isfinite(ref_mass):
                    last_error = (outcome.mass - ref_mass) / ref_mass
                    last = f"last point: mass error {last_error:.2e}, violation {outcome.violation:.2e}"
                if outcome.verdict == "design" and math.isfinite(ref_mass):
                    err = abs(cast(float, outcome.mass) - ref_mass) / ref_mass  # a design has its mass
                    passed = err <= MASS_BAR
                elif outcome.verdict == "design":
                    passed = False
                else:  # no design: right when infeasible (SLSQP's failure counts as a verdict)
                    passed = not math.isfinite(ref_mass)
                design_rows.append(
                    {
                        "kind": "design",
                        "scene": index,
                        "cycle": cycle.name,
                        "rpm": scene["rpm"],
                        "delta": delta,
                        "j_required": j_fly,
                        "j_check": check_j,
                        "geometry": combo.geometry,
                        "hb_ratio": f"{combo.hb[0]:.4g}..{combo.hb[1]:.4g}",
                        "envelope": scene["spec"].max_outer_diameter,
                        "max_width": scene["spec"].max_width,
                        "material": combo.material,
                        "speed_ratio": combo.speed_ratio,
                        "j_on_shaft": combo.j,
                        "cap": combo.cap,
                        "boundary": scene.get("boundary", ""),
                        "reference_verdict": ref.verdict,
                        "reference_mass": ref.mass,
                        "method": name,
                        "verdict": outcome.verdict,
                        "mass": outcome.mass,
                        "rel_error": err,
                        "violation": outcome.violation,
                        "passed": passed,
                        "time_s": elapsed,
                        "last_error": last_error,
                        "last_violation": outcome.violation if last else None,
                        "reason": (f"{last}; " if last else "") + outcome.reason,
                    }
                )
        if progress and (index + 1) % 50 == 0:
            progress(f"hard: {index + 1}/{len(scenes)} design scenes")
    return cycle_rows, design_rows
