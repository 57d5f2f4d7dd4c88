"""Benchmark of the flywheel designer (flyopt.design.designer.design_flywheel).

Times `flyopt.solve` (cycle analysis + design, default design method "auto")
on every scene of problems/, with its design step by "auto" and by IPOPT alone,
and, on a batch of random scenes, the IPOPT path:

* the build of each NLP structure (``casadi.nlpsol`` with IPOPT), once;
* the full ranking of a scene, 2 materials x 3 shafts, after the first build;
* each single NLP solve inside it.

Runs pinned to one core when the OS allows it. Writes the figures to
``benchmarks/results/design.md`` and one row per scene to
``benchmarks/results/design.csv``.

Usage::

    python benchmarks/bench_design.py [--scenes 300] [--seed 1] [--out benchmarks/results]

Target (issue): ranking of a 2 x 3 scene under 30 ms after the first build, on
one core of a 2-core machine.
"""

import argparse
import csv
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import casadi as ca
import numpy as np
from common import pin_one_core

import flyopt
from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.materials import builtin_materials
from flyopt.design.nlp import ModelStructure, clear_model_cache, get_model

TARGET_MS = 30.0


def random_scenes(count, seed):
    """Random scenes: J_F log-uniform 1e-3..1e4 kg*m^2, 50..5000 rpm, 3 shafts."""
    rng = np.random.default_rng(seed)
    scenes = []
    for _ in range(count):
        rpm = 10 ** rng.uniform(math.log10(50), math.log10(5000))
        shafts = [
            MountShaft("reference", 1.0),
            MountShaft("slower", float(10 ** rng.uniform(-1.0, 0.0))),
            MountShaft("faster", float(10 ** rng.uniform(0.0, 1.0))),
        ]
        spec = DesignSpec(geometry=str(rng.choice(["rim", "thin_rim"])))
        scenes.append(
            {
                "j_required": float(10 ** rng.uniform(-3, 4)),
                "omega_mean": rpm * math.pi / 30.0,
                "rpm": rpm,
                "shafts": shafts,
                "spec": spec,
            }
        )
    return scenes


def time_builds():
    """Build time of every NLP structure from a cold cache [s]."""
    clear_model_cache()
    times = {}
    for geometry in ("rim", "thin_rim", "disc"):
        for pinned in (False, True):
            for collapsed in (False, True) if geometry != "disc" else (False,):
                for objective in ("mass", "outer_diameter"):
                    structure = ModelStructure(geometry, pinned, collapsed, objective)
                    start = time.perf_counter()
                    get_model(structure)
                    times[structure] = time.perf_counter() - start
    return times


PROBLEMS = Path(__file__).resolve().parents[1] / "problems"


def time_problems(repeats):
    """Median wall time of flyopt.solve and of its design step (auto, IPOPT) per problems/ scene [ms]."""
    rows = []
    for path in sorted(PROBLEMS.glob("*.toml")):
        scene = flyopt.load(path)
        solution = flyopt.solve(scene)
        flyopt.design_scene(scene, solution.analysis, method="ipopt")  # warm-up: builds the NLP structure
        total, design, ipopt = [], [], []
        for _ in range(repeats):
            start = time.perf_counter()
            solution = flyopt.solve(scene)
            total.append(time.perf_counter() - start)
            start = time.perf_counter()
            flyopt.design_scene(scene, solution.analysis)
            design.append(time.perf_counter() - start)
            start = time.perf_counter()
            flyopt.design_scene(scene, solution.analysis, method="ipopt")
            ipopt.append(time.perf_counter() - start)
        rows.append(
            {
                "scene": path.name,
                "status": solution.status,
                "combinations": len(solution.design.candidates),
                "solve_ms": 1e3 * statistics.median(total),
                "design_ms": 1e3 * statistics.median(design),
                "design_ipopt_ms": 1e3 * statistics.median(ipopt),
            }
        )
    return rows


def run(count, seed):
    materials = list(builtin_materials().values())
    builds = time_builds()
    scenes = random_scenes(count, seed)
    # one warm-up design per geometry so that no ranking below includes a build
    for geometry in ("rim", "thin_rim"):
        design_flywheel(1.0, 100.0, scenes[0]["shafts"], materials, DesignSpec(geometry), method="ipopt")
    rows, nlp_times, nlp_iters = [], [], []
    for index, scene in enumerate(scenes):
        start = time.perf_counter()
        result = design_flywheel(
            scene["j_required"], scene["omega_mean"], scene["shafts"], materials, scene["spec"], method="ipopt"
        )
        elapsed = time.perf_counter() - start
        solved = [c for c in result.candidates if c.provenance.solve_time is not None]
        nlp_times += [c.provenance.solve_time for c in solved]
        nlp_iters += [c.provenance.iterations for c in solved]
        rows.append(
            {
                "scene": index,
                "geometry": scene["spec"].geometry,
                "j_required": scene["j_required"],
                "rpm": scene["rpm"],
                "combinations": len(result.candidates),
                "nlps_solved": len(solved),
                "feasible": sum(c.feasible for c in result.candidates),
                "status": result.status,
                "ranking_ms": 1e3 * elapsed,
            }
        )
    return builds, rows, nlp_times, nlp_iters


def write_results(out, builds, rows, nlp_times, nlp_iters, pinning, seed, problems=()):
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "design.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    ranking = [r["ranking_ms"] for r in rows]
    full = [r["ranking_ms"] for r in rows if r["nlps_solved"] == r["combinations"]]
    build_ms = [1e3 * t for t in builds.values()]
    first = next(iter(builds))
    quantile = lambda data, q: float(np.quantile(data, q))  # noqa: E731
    lines = [
        "# Flywheel designer benchmark",
        "",
        f"Command: `python benchmarks/bench_design.py --scenes {len(rows)} --seed {seed}`",
        "",
        f"Machine: {platform.platform()}, {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} CPUs, {pinning}; Python {platform.python_version()}, "
        f"CasADi {ca.__version__} (IPOPT bundled).",
        "",
        f"Scenes: {len(rows)} random scenes, 2 built-in materials x 3 shafts = 6 "
        f"combinations each, J_F log-uniform 1e-3..1e4 kg*m^2, 50..5000 rpm, "
        f"geometry rim or thin_rim; feasible combinations are solved by IPOPT, "
        f"infeasible ones decided in closed form.",
        "",
        "| figure | value |",
        "|---|---|",
        f"| median ranking time per scene (all 6 combinations) | {statistics.median(ranking):.2f} ms |",
        f"| 90th percentile / max ranking time | {quantile(ranking, 0.9):.2f} / {max(ranking):.2f} ms |",
        f"| median ranking time, scenes with all 6 NLPs solved ({len(full)} scenes) | "
        + (f"{statistics.median(full):.2f} ms |" if full else "n/a |"),
        f"| median time per single NLP solve ({len(nlp_times)} solves) | {1e3 * statistics.median(nlp_times):.3f} ms |",
        f"| 90th percentile NLP solve | {1e3 * quantile(nlp_times, 0.9):.3f} ms |",
        f"| IPOPT iterations per NLP, median / max | {statistics.median(nlp_iters):.0f} / {max(nlp_iters)} |",
        f"| first NLP build (cold, includes loading IPOPT) | {build_ms[0]:.1f} ms "
        f"({'/'.join(str(v) for v in first)}) |",
        f"| later NLP builds, median of {len(build_ms) - 1} structures | {statistics.median(build_ms[1:]):.1f} ms |",
        f"| target: ranking under {TARGET_MS:.0f} ms | "
        f"{'met' if statistics.median(ranking) < TARGET_MS else 'NOT met'} "
        f"(median) |",
        "",
        "Per-scene rows: `design.csv`.",
        "",
    ]
    if problems:
        lines += [
            "## problems/ scenes",
            "",
            "`flyopt.solve` (load excluded, default design method auto) and its design step alone, by "
            "auto and by IPOPT on every combination; medians of 20 runs after a warm-up.",
            "",
            "| scene | status | combinations | solve [ms] | design, auto [ms] | design, IPOPT [ms] |",
            "|---|---|---|---|---|---|",
        ]
        lines += [
            f"| {r['scene']} | {r['status']} | {r['combinations']} | {r['solve_ms']:.2f} | "
            f"{r['design_ms']:.2f} | {r['design_ipopt_ms']:.2f} |"
            for r in problems
        ]
        lines.append("")
    (out / "design.md").write_text("\n".join(lines), encoding="utf-8")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve().parent / "results")
    args = parser.parse_args(argv)
    pinning = pin_one_core()
    builds, rows, nlp_times, nlp_iters = run(args.scenes, args.seed)
    problems = time_problems(repeats=20)
    print(write_results(args.out, builds, rows, nlp_times, nlp_iters, pinning, args.seed, problems))
    return 0


if __name__ == "__main__":
    sys.exit(main())
