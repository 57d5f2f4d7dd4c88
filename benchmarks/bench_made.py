"""Benchmark of what making a wheel costs: rounding it, checking it by FE, accepting it by FE (issue 28).

For each shipped whole wheel, the design of the scene (``flyopt.design_scene`` on one analysis, so the
cycle is not timed) is timed in process, after a first design (NLPs built, scikit-fem imported), as:

* ``no castability``: ``round_to = false``, ``fem_check = false``, ``process = "none"`` (the NLP without the
  castability rows: what castability costs is ``continuous`` against it);
* ``continuous``: ``round_to = false``, ``fem_check = false`` (the design as sweeps compare it);
* ``rounded``: the default whole-millimetre rounding, ``fem_check = false``;
* ``rounded + FE``: what ``flyopt solve`` does by default (the FE check reported);
* ``FE accepted``: ``fem_check = true`` (the design accepted against the larger of FE and Lamé).

Medians and ranges of ``--repeat`` runs, pinned to one core; the ratios are of medians in the same run.
Writes ``benchmarks/results/made.md`` and ``made.csv``.

Usage::

    python benchmarks/bench_made.py [--repeat 5] [--out benchmarks/results]

Target (issue 28 and the speed issue 26): rounding and castability add "a small, measured cost" to a
design; the whole-wheel design itself stays within issue 26's targets (bench_wheel.py).
"""

import argparse
import dataclasses
import platform
import statistics
import time
from pathlib import Path

from common import load_average, pin_one_core, write_results

import flyopt
from flyopt.analysis import analyse
from flyopt.design.castability import Overrides

ROOT = Path(__file__).resolve().parents[1]

#: The shipped whole wheels (problems/: a web wheel, a wheel on arms, an engine's disc on its hub) and two wheels
#: of the tests (an engine's arms wheel, a disc under the stress criterion).
SCENES = [
    ROOT / "problems" / "punch-press-wheel.toml",
    ROOT / "problems" / "press-arms-wheel.toml",
    ROOT / "problems" / "four-cylinder-engine.toml",
    ROOT / "tests" / "data" / "wheels" / "engine-rim_arms.toml",
    ROOT / "tests" / "data" / "wheels" / "engine-disc.toml",
]

MODES = {
    "no castability": {"round_to": 0.0, "fem_check": False, "castability": Overrides(process="none")},
    "continuous": {"round_to": 0.0, "fem_check": False},
    "rounded": {"fem_check": False},
    "rounded + FE": {},
    "FE accepted": {"fem_check": True},
}


def designer(path, changes):
    scene = flyopt.load(path)
    scene = dataclasses.replace(scene, design=dataclasses.replace(scene.design, **changes))
    analysis = analyse(scene)

    def run():
        result = flyopt.design_scene(scene, analysis)
        if result.best is None:
            raise RuntimeError(f"{path.name}: no design ({result.status}: {result.message})")
        return result

    return run


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results")
    args = parser.parse_args()
    pinning = pin_one_core()
    load_before = load_average()
    rows = []
    for path in SCENES:
        medians = {}
        for mode, changes in MODES.items():
            run = designer(path, changes)
            result = run()  # first: NLPs built, scikit-fem imported
            times = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                result = run()
                times.append(time.perf_counter() - start)
            medians[mode] = statistics.median(times)
            best = result.best
            rows.append(
                {
                    "scene": path.stem,
                    "mode": mode,
                    "median_s": medians[mode],
                    "min_s": min(times),
                    "max_s": max(times),
                    "mass_kg": best.mass,
                    "fe_rounds": result.fem.rounds if result.fem is not None else "",
                }
            )
        for row in rows:
            if row["scene"] == path.stem:
                row["ratio_to_continuous"] = row["median_s"] / medians["continuous"]
    load_after = load_average()
    lines = [
        "# What making a wheel costs: castability, rounding, the FE check, the FE acceptance",
        "",
        "`python benchmarks/bench_made.py` (benchmarks/bench_made.py: what each mode is). The design of the "
        "scene on one analysis (`flyopt.design_scene`), after a first one; medians of "
        f"{args.repeat} runs, {pinning}; host load {load_before} before, {load_after} after (1, 5, 15 min; "
        "a shared 2-core host: absolute times move with it, the ratios in one run less). "
        f"Python {platform.python_version()}, {platform.machine()}.",
        "",
        "| scene | mode | median [s] | range [s] | x continuous | mass [kg] | FE designs |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scene']} | {r['mode']} | {r['median_s']:.3f} | {r['min_s']:.3f}–{r['max_s']:.3f} | "
            f"{r['ratio_to_continuous']:.1f} | {r['mass_kg']:.3f} | {r['fe_rounds']} |"
        )
    write_results(args.out, "made", "\n".join(lines) + "\n", rows)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
