"""Benchmark of motor-driven presses whose flywheel is set by a stall: `flyopt solve`, against a baseline.

Three presses from an audit of Kloss-motor machines (tests/data/stall/; a load pulse the motor's breakdown
torque cannot carry; below some flywheel no periodic steady state exists, and δ there is below the allowed
value): a load given as an expression (the 2,225 s case), as a table of points, and as a slider-crank's ram
force. Each is solved
by whole ``flyopt solve`` processes, this checkout's and, with ``--baseline OTHER/src``, the baseline's in
turn, pinned to one core; a baseline run longer than ``--timeout`` seconds is stopped and reported as such.
Every finished run's flywheel is read from ``--json`` (the requirement J_F and its limit), and the two
checkouts' are compared (a stall limit is located to 1e-4 of J_F).

Writes ``benchmarks/results/stall.md`` and ``stall.csv`` beside this script.

Usage::

    python benchmarks/bench_stall.py [--repeat 3] [--baseline OTHER/src] [--timeout 600] [--baseline-repeat 1]
"""

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

from common import CHILD_ENV, load_average, pin_one_core, write_results

RESULTS = Path(__file__).resolve().parent / "results"

SCENES = {  # the presses, shared with the tests
    name: Path(__file__).resolve().parent.parent / "tests" / "data" / "stall" / f"{file}.toml"
    for name, file in (
        ("expression", "press-pulse-expression"),
        ("table", "press-pulse-table"),
        ("slider-crank", "press-slider-crank"),
    )
}


def run(path, src, timeout):
    """(wall s, CPU s, J_F, limit) of one ``flyopt solve --json`` process; J_F and limit None where it was stopped."""
    env = dict(CHILD_ENV)
    if src is not None:
        env["PYTHONPATH"] = str(src)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    try:
        done = subprocess.run(
            [sys.executable, "-m", "flyopt", "solve", str(path), "--json"],
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
        )
    except subprocess.TimeoutExpired:
        return time.perf_counter() - start, None, None, None
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    if done.returncode != 0:
        raise RuntimeError(f"flyopt solve {path} failed: {done.stderr.strip()[-400:]}")
    out = json.loads(done.stdout)
    notes = " ".join(m.get("note") or "" for m in out.get("models") or ())
    return wall, cpu, out["j_required"], "stall" if "(stall)" in notes else "delta or none"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--baseline", type=Path, default=None, help="another checkout's src folder")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds after which a baseline run stops")
    parser.add_argument("--baseline-repeat", type=int, default=1, help="runs of the baseline (minutes each)")
    args = parser.parse_args()
    pinned = pin_one_core()
    rows = []
    for name, path in SCENES.items():
        this = Path(__file__).resolve().parent.parent / "src"  # this checkout's, whatever is installed
        variants = {"this": this} if args.baseline is None else {"this": this, "baseline": args.baseline}
        runs = {v: [] for v in variants}
        for k in range(args.repeat):
            for variant, src in variants.items():
                if variant == "baseline" and k >= args.baseline_repeat:
                    continue  # minutes a run: fewer runs
                runs[variant].append(run(path, src, args.timeout))
                print(name, variant, runs[variant][-1], flush=True)
        for variant, got in runs.items():
            finished = [r for r in got if r[1] is not None]
            walls = [r[0] for r in finished]
            rows.append(
                {
                    "scene": name,
                    "variant": variant,
                    "runs": len(got),
                    "stopped": len(got) - len(finished),
                    "wall_median_s": statistics.median(walls) if walls else None,
                    "wall_min_s": min(walls) if walls else None,
                    "wall_max_s": max(walls) if walls else None,
                    "cpu_median_s": statistics.median(r[1] for r in finished) if finished else None,
                    "j_required": finished[0][2] if finished else None,
                    "limit": finished[0][3] if finished else None,
                }
            )
    lines = [
        "# Stall-limited presses: `flyopt solve`",
        "",
        f"`python benchmarks/bench_stall.py --repeat {args.repeat}"
        + (
            f" --baseline {args.baseline} --timeout {args.timeout:g} --baseline-repeat {args.baseline_repeat}`"
            if args.baseline
            else "`"
        ),
        f"on {platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} CPUs, {pinned}, "
        f"load {load_average()} at the end, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}.",
        "",
        "| scene | checkout | runs | wall median [s] (range) | CPU median [s] | J_F [kg·m²] | limit |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        wall = (
            f"{r['wall_median_s']:.2f} ({r['wall_min_s']:.2f}-{r['wall_max_s']:.2f})"
            if r["wall_median_s"] is not None
            else f"stopped after {args.timeout:g} s"
        )
        cpu = f"{r['cpu_median_s']:.2f}" if r["cpu_median_s"] is not None else "-"
        j = f"{r['j_required']:.6g}" if r["j_required"] is not None else "-"
        lines.append(f"| {r['scene']} | {r['variant']} | {r['runs']} | {wall} | {cpu} | {j} | {r['limit'] or '-'} |")
    if args.baseline is not None:
        lines += ["", "Ratios (baseline / this, wall medians) and the flywheels' relative difference:", ""]
        for name in SCENES:
            mine, base = (
                next(r for r in rows if r["scene"] == name and r["variant"] == v) for v in ("this", "baseline")
            )
            if base["wall_median_s"] is None:
                lines.append(
                    f"- {name}: the baseline was stopped after {args.timeout:g} s: more than "
                    f"{args.timeout / mine['wall_median_s']:.0f}x"
                )
                continue
            diff = abs(mine["j_required"] / base["j_required"] - 1)
            lines.append(f"- {name}: {base['wall_median_s'] / mine['wall_median_s']:.1f}x; J_F differs by {diff:.1e}")
    write_results(RESULTS, "stall", "\n".join(lines) + "\n", rows)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
