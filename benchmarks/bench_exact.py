"""Benchmark of the exact models (issue 12): analyses, sweeps, Pareto, start-up, tables, memory.

Each figure is a median over repeats, and every target is judged against a
ratio or a limit measured in the same run:

* ``analyse`` of every problem scene by every model that applies to it
  (energy, energy_mass, dynamic), in this process after a warm-up;
* sweep points per second, serial and with 2 worker processes
  (``flyopt.sweep``, no output file): slider-crank-press speed × δ and
  motor-press δ × envelope;
* ``flyopt pareto problems/motor-press.toml`` (25 points), the whole process;
* start-up: ``flyopt check`` and ``flyopt solve`` of a constant-inertia scene
  (problems/punch-press.toml), the whole process, against
  ``python -c "import numpy"`` run alternately with them;
* loading a scene with a 10,000-point torque table, inline and from a CSV file,
  and the verification (CVODES periodic simulation) of a design for it;
* peak memory (ru_maxrss) of a 10⁶-point sweep written to Parquet.

Writes ``benchmarks/results/exact.md`` and ``exact.csv`` beside this script.

Usage::

    python benchmarks/bench_exact.py [--repeat 7] [--quick]
"""

import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from common import CHILD_ENV, TABLE_SCENE, median_time, write_results

import flyopt
from flyopt.analysis import analyse

ROOT = Path(__file__).resolve().parent.parent
PROBLEMS = ROOT / "problems"
RESULTS = Path(__file__).resolve().parent / "results"
FLYOPT = [sys.executable, "-m", "flyopt"]

#: Issue 12's targets.
ANALYSE_TARGET = {"slider-crank-press": 10e-3, "engine-members": 10e-3, "motor-press": 20e-3}
SWEEP_TARGET = {"slider-crank-press": 300.0, "motor-press": 50.0}
PARETO_TARGET = 2.0
STARTUP_RATIO = 3.0
TABLE_TARGET = 10e-3
VERIFY_TARGET = 2.0
MEMORY_TARGET = 400.0  # MB


def process_time(command, repeat, env=None):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, env=env, cwd=ROOT)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def models_of(scene):
    from flyopt.sizing.choose import ORDER, choose, reduce

    machine = reduce(scene)
    exact, _ = choose(machine)
    models = [m for m in ORDER if ORDER.index(m) <= ORDER.index(exact)]
    if not machine.variable_inertia and "energy_mass" in models and exact != "energy_mass":
        models.remove("energy_mass")
    return exact, models


def bench_analyses(repeat, rows):
    for path in sorted(PROBLEMS.glob("*.toml")):
        scene = flyopt.load(path)
        exact, models = models_of(scene)
        for model in models:
            try:
                med, lo, hi = median_time(lambda: analyse(scene, model), repeat)
            except Exception as err:  # noqa: BLE001 -- a model that does not apply is reported
                rows.append(
                    {
                        "section": "analyse",
                        "case": path.stem,
                        "setting": model,
                        "median_s": "",
                        "note": f"not applicable: {str(err).splitlines()[0][:80]}",
                    }
                )
                continue
            rows.append(
                {
                    "section": "analyse",
                    "case": path.stem,
                    "setting": model + (" (exact)" if model == exact else ""),
                    "median_s": med,
                    "note": f"min {lo * 1e3:.3g} ms, max {hi * 1e3:.3g} ms",
                }
            )


SWEEPS = {
    "slider-crank-press": {"speed": "60:180:20rpm", "delta": "0.05:0.3:20"},
    "motor-press": {"delta": "0.02:0.3:log10", "design.max_outer_diameter": "0.6:1.4:10 m"},
}


def bench_sweeps(repeat, rows, quick):
    for name, vary in SWEEPS.items():
        scene = flyopt.load(PROBLEMS / f"{name}.toml")
        if quick:
            vary = {k: v.replace(":20", ":6").replace(":10", ":4").replace("log10", "log4") for k, v in vary.items()}
        for workers in (1, 2):
            times, points = [], 0
            for _ in range(max(1, repeat // 3)):
                start = time.perf_counter()
                frame = flyopt.sweep(flyopt.load(PROBLEMS / f"{name}.toml"), vary, workers=workers, progress=False)
                times.append(time.perf_counter() - start)
                points = len(frame)
            med = statistics.median(times)
            rows.append(
                {
                    "section": "sweep",
                    "case": name,
                    "setting": f"{workers} worker(s)",
                    "median_s": med,
                    "note": f"{points} points, {points / med:.4g} points/s, mode "
                    f"{frame.attrs.get('sweep', {}).get('mode')}",
                }
            )
        del scene


def bench_pareto(repeat, rows):
    med = process_time(FLYOPT + ["pareto", "problems/motor-press.toml"], max(1, repeat // 2))
    rows.append(
        {"section": "pareto", "case": "motor-press", "setting": "25 points, whole process", "median_s": med, "note": ""}
    )


def bench_startup(repeat, rows):
    numpy_times, check_times, solve_times = [], [], []
    commands = (
        ([sys.executable, "-c", "import numpy"], numpy_times),
        (FLYOPT + ["check", "problems/punch-press.toml"], check_times),
        (FLYOPT + ["solve", "problems/punch-press.toml"], solve_times),
    )
    for command, _ in commands:  # the warm-up writes the bytecode every timed run reads (CHILD_ENV)
        subprocess.run(command, check=True, capture_output=True, cwd=ROOT, env=CHILD_ENV)
    for _ in range(repeat):  # alternately, so that the machine's load hits all alike
        for command, times in commands:
            start = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True, cwd=ROOT, env=CHILD_ENV)
            times.append(time.perf_counter() - start)
    base = statistics.median(numpy_times)
    rows.append(
        {
            "section": "startup",
            "case": "python -c 'import numpy'",
            "setting": "whole process",
            "median_s": base,
            "note": "",
        }
    )
    for label, times in (("flyopt check punch-press", check_times), ("flyopt solve punch-press", solve_times)):
        med = statistics.median(times)
        rows.append(
            {
                "section": "startup",
                "case": label,
                "setting": "whole process",
                "median_s": med,
                "note": f"{med / base:.3g}x import numpy",
            }
        )


def bench_table(repeat, rows, folder):
    rng = np.random.default_rng(1)
    angles = np.linspace(0.0, 360.0, 10_000)
    torques = 1000 + 300 * np.sin(np.radians(angles) * 3) + rng.normal(0, 20, angles.size)
    torques[-1] = torques[0]
    inline = folder / "inline.toml"
    inline.write_text(
        TABLE_SCENE.format(
            title="10,000-point torque table",
            points="points = [" + ", ".join(f"[{a!r}, {t!r}]" for a, t in zip(angles.tolist(), torques.tolist())) + "]",
        )
    )
    med, _, _ = median_time(lambda: flyopt.load(inline), repeat)
    rows.append(
        {"section": "table", "case": "10k-point table", "setting": "inline points", "median_s": med, "note": ""}
    )
    table = folder / "torque.csv"
    table.write_text("angle,torque\n" + "".join(f"{a!r},{t!r}\n" for a, t in zip(angles.tolist(), torques.tolist())))
    from_file = folder / "from_csv.toml"
    from_file.write_text(TABLE_SCENE.format(title="10,000-point torque table", points='points_file = "torque.csv"'))
    try:
        med, _, _ = median_time(lambda: flyopt.load(from_file), repeat)
        same = analyse(flyopt.load(from_file)).a_max == analyse(flyopt.load(inline)).a_max
        rows.append(
            {
                "section": "table",
                "case": "10k-point table",
                "setting": "points_file (CSV)",
                "median_s": med,
                "note": f"same A_max as inline: {same}",
            }
        )
        from flyopt.pipeline import verify

        scene = flyopt.load(from_file).replace(delta=0.02)
        solution = flyopt.solve(scene)
        med, _, _ = median_time(lambda: verify(scene, solution.analysis, solution.design), max(3, repeat // 2))
        check = verify(scene, solution.analysis, solution.design)
        rows.append(
            {
                "section": "verify",
                "case": "10k-point table",
                "setting": "CVODES periodic simulation",
                "median_s": med,
                "note": f"achieved δ {check.achieved_delta:.10g} (allowed 0.02), flagged {check.flagged}",
            }
        )
    except Exception as err:  # noqa: BLE001 -- reported, not hidden
        rows.append(
            {
                "section": "table",
                "case": "10k-point table",
                "setting": "points_file (CSV)",
                "median_s": "",
                "note": f"failed: {str(err).splitlines()[0][:100]}",
            }
        )


MEMORY_DRIVER = """
import resource, subprocess, sys
subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
"""


def bench_memory(rows, folder, quick):
    n = 100 if quick else 1000
    out = folder / "big.parquet"
    command = FLYOPT + [
        "sweep",
        "problems/punch-press.toml",
        "--vary",
        f"delta=0.01:0.2:{n}",
        "--vary",
        f"speed=30:120:{n}rpm",
        "-o",
        str(out),
        "--no-progress",
    ]
    start = time.perf_counter()
    run = subprocess.run(
        [sys.executable, "-c", MEMORY_DRIVER, *command], capture_output=True, text=True, cwd=ROOT, check=True
    )
    seconds = time.perf_counter() - start
    peak = int(run.stdout.strip()) / 1024  # kB -> MB (Linux)
    rows.append(
        {
            "section": "memory",
            "case": f"{n * n:,}-point sweep to Parquet",
            "setting": "ru_maxrss",
            "median_s": seconds,
            "note": f"peak {peak:.0f} MB (largest process); file {out.stat().st_size / 1e6:.0f} MB",
        }
    )
    return peak


def summary(rows, header):
    def find(section, case, setting=None):
        for row in rows:
            if (
                row["section"] == section
                and row["case"] == case
                and (setting is None or row["setting"].startswith(setting))
            ):
                return row
        return None

    def verdict(ok):
        return "met" if ok else "**NOT met**"

    lines = [
        "# Exact models: speed",
        "",
        "Command: `python benchmarks/bench_exact.py`",
        "",
        header,
        "",
        "Medians; ratios from the same run. A whole-process time includes the interpreter's start.",
        "",
        "## Targets (issue 12)",
        "",
        "| target | status | measured |",
        "|---|---|---|",
    ]
    for case, limit in ANALYSE_TARGET.items():
        exact, _ = models_of(flyopt.load(PROBLEMS / f"{case}.toml"))
        row = find("analyse", case, exact)
        if row and row["median_s"] != "":
            lines.append(
                f"| analyse {case} ({exact}) <= {limit * 1e3:g} ms | {verdict(row['median_s'] <= limit)} "
                f"| {row['median_s'] * 1e3:.3g} ms |"
            )
    for case, target in SWEEP_TARGET.items():
        row = find("sweep", case, "2 worker")
        serial = find("sweep", case, "1 worker")
        rate = float(row["note"].split(", ")[1].split()[0])
        lines.append(
            f"| sweep {case}, 2 workers >= {target:g} points/s | {verdict(rate >= target)} | "
            f"{row['note']}; serial: {serial['note']} |"
        )
    row = find("pareto", "motor-press")
    lines.append(
        f"| flyopt pareto motor-press <= {PARETO_TARGET:g} s | {verdict(row['median_s'] <= PARETO_TARGET)} "
        f"| {row['median_s']:.3g} s |"
    )
    base = find("startup", "python -c 'import numpy'")["median_s"]
    for label in ("flyopt check punch-press", "flyopt solve punch-press"):
        row = find("startup", label)
        ratio = row["median_s"] / base
        lines.append(
            f"| {label} <= {STARTUP_RATIO:g}x import numpy | {verdict(ratio <= STARTUP_RATIO)} | "
            f"{row['median_s'] * 1e3:.0f} ms vs {base * 1e3:.0f} ms: {ratio:.2f}x |"
        )
    for setting in ("inline points", "points_file (CSV)"):
        row = find("table", "10k-point table", setting)
        if row is None or row["median_s"] == "":
            lines.append(f"| load 10k-point table, {setting} <= 10 ms | **NOT met** | {row and row['note']} |")
        else:
            lines.append(
                f"| load 10k-point table, {setting} <= {TABLE_TARGET * 1e3:g} ms | "
                f"{verdict(row['median_s'] <= TABLE_TARGET)} | {row['median_s'] * 1e3:.3g} ms "
                f"{row['note']} |"
            )
    row = find("verify", "10k-point table")
    if row is not None:
        lines.append(
            f"| solve --verify of a 10k-point table <= {VERIFY_TARGET:g} s (the verification) | "
            f"{verdict(row['median_s'] <= VERIFY_TARGET)} | {row['median_s']:.3g} s, {row['note']} |"
        )
    row = [r for r in rows if r["section"] == "memory"][0]
    peak = float(row["note"].split()[1])
    lines.append(
        f"| peak memory, {row['case']} <= {MEMORY_TARGET:g} MB | {verdict(peak <= MEMORY_TARGET)} | "
        f"{row['note']}, {row['median_s']:.3g} s |"
    )
    lines += ["", "## Every row", "", "| section | case | setting | median | note |", "|---|---|---|---|---|"]
    for row in rows:
        value = row["median_s"]
        shown = "" if value == "" else f"{value * 1e3:.4g} ms" if value < 1 else f"{value:.4g} s"
        lines.append(f"| {row['section']} | {row['case']} | {row['setting']} | {shown} | {row['note']} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="fewer points and repeats; writes nothing")
    args = parser.parse_args(argv)
    repeat = 3 if args.quick else args.repeat
    rows = []
    header = (
        f"Machine: {platform.platform()}, {os.cpu_count()} CPUs; Python {platform.python_version()}, "
        f"numpy {np.__version__}."
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for step, run in (
            ("analyses", lambda: bench_analyses(repeat, rows)),
            ("sweeps", lambda: bench_sweeps(repeat, rows, args.quick)),
            ("pareto", lambda: bench_pareto(repeat, rows)),
            ("start-up", lambda: bench_startup(repeat, rows)),
            ("tables", lambda: bench_table(repeat, rows, folder)),
            ("memory", lambda: bench_memory(rows, folder, args.quick)),
        ):
            print(f"bench_exact: {step}", file=sys.stderr, flush=True)
            run()
    text = summary(rows, header)
    if not args.quick:
        write_results(RESULTS, "exact", text, rows, ["section", "case", "setting", "median_s", "note"])
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
