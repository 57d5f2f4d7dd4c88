"""Benchmark of reading torque tables (issue 26): 10⁶ rows by the compiled reader, 10,000 rows as before.

Times ``flyopt.load`` of a scene whose resisting torque is a table, in this
process after a warm-up (the first load, which imports pyarrow, is timed
apart in a fresh process):

* 10⁶ rows from a CSV file (``points_file``) and inline in the scene's TOML
  (``points = [[a, b], ...]``), by the reading flyopt uses (pyarrow's CSV
  reader for a table of at least ``COMPILED_READER_BYTES``) and, in the same
  run, by the reading before issue 26 (Python's ``float`` of every number),
  which is the same code with the threshold set out of reach;
* 10,000 rows (issue 12's table, 0.4 MB), inline and from CSV, target 10 ms
  each: by the compiled reader in this process, which has imported pyarrow
  (``LOADED_READER_BYTES``), and by ``float`` as in a process that has not;
* a table just over the threshold (30,000 rows, about 1.1 MB) both ways, and the
  import of ``pyarrow.csv`` in a fresh process after numpy: what sets it.

Each figure is a median over repeats with its range, wall-clock and CPU time
(all threads) side by side; the ratios are of medians from this run. Runs
pinned to one core when the OS allows it; the host is shared, so its load
average is written before and after.

Writes ``benchmarks/results/tables.md`` and ``tables.csv`` beside this script.

Usage::

    python benchmarks/bench_tables.py [--repeat 7] [--quick]
"""

import argparse
import contextlib
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from unittest import mock

import numpy as np
from common import TABLE_SCENE, load_average, pin_one_core, write_results

import flyopt
from flyopt.io import compiled_reader

RESULTS = Path(__file__).resolve().parent / "results"

#: Issue 26's targets [s] and issue 12's, which are kept.
TARGETS = {
    ("1M rows", "points_file (CSV)"): 0.3,
    ("1M rows", "inline points"): 1.0,
    ("10k rows", "points_file (CSV)"): 10e-3,
    ("10k rows", "inline points"): 10e-3,
}


def timed(call, repeat, warm=1):
    """Medians and ranges of wall-clock and CPU time [s] of ``call()``."""
    for _ in range(warm):
        call()
    wall, cpu = [], []
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        call()
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - w)
    return {
        "wall_s": statistics.median(wall),
        "wall_min_s": min(wall),
        "wall_max_s": max(wall),
        "cpu_s": statistics.median(cpu),
        "cpu_min_s": min(cpu),
        "cpu_max_s": max(cpu),
    }


@contextlib.contextmanager
def reading(compiled):
    """flyopt's reading (``compiled``), or the reading before issue 26: the compiled reader out of reach."""
    if compiled:
        yield
        return
    with (
        mock.patch.object(compiled_reader, "COMPILED_READER_BYTES", sys.maxsize),
        mock.patch.object(compiled_reader, "LOADED_READER_BYTES", sys.maxsize),
    ):
        yield


def write_tables(folder, rows):
    """The scene files of a table of ``rows`` rows, inline and from CSV: {setting: (scene file, bytes of the table)}."""
    rng = np.random.default_rng(1)
    angles = np.linspace(0.0, 360.0, rows)
    torques = 1000 + 300 * np.sin(np.radians(angles) * 3) + rng.normal(0, 20, rows)
    torques[-1] = torques[0]
    pairs = list(zip(angles.tolist(), torques.tolist()))
    inline = folder / f"inline-{rows}.toml"
    inline.write_text(
        TABLE_SCENE.format(
            title="torque table", points="points = [" + ", ".join(f"[{a!r}, {t!r}]" for a, t in pairs) + "]"
        )
    )
    table = folder / f"torque-{rows}.csv"
    table.write_text("angle,torque\n" + "".join(f"{a!r},{t!r}\n" for a, t in pairs))
    from_csv = folder / f"csv-{rows}.toml"
    from_csv.write_text(TABLE_SCENE.format(title="torque table", points=f'points_file = "{table.name}"'))
    return {"points_file (CSV)": (from_csv, table.stat().st_size), "inline points": (inline, inline.stat().st_size)}


def bench(results, case, rows, repeat, folder, both):
    """Rows of ``case``: each setting by flyopt's reading, and by the reading before when ``both``."""
    for setting, (path, size) in write_tables(folder, rows).items():
        scenes = {}
        for compiled in (True, False) if both else (True,):
            with reading(compiled):
                figures = timed(lambda path=path: flyopt.load(path), repeat)
                scenes[compiled] = flyopt.load(path)
            label = "flyopt (compiled reader)" if compiled and compiled_reader.compiled_reader_reads(size) else ""
            label = label or ("flyopt (float)" if compiled else "before issue 26 (float)")
            results.append({"case": case, "setting": setting, "reading": label, "bytes": size, **figures, "note": ""})
        if both:
            a, b = scenes[True].resisting, scenes[False].resisting
            same = np.array_equal(a.angles.view(np.int64), b.angles.view(np.int64)) and np.array_equal(
                a.values.view(np.int64), b.values.view(np.int64)
            )
            results[-2]["note"] = f"same floats as the reading before, bit for bit: {same}"


def first_load(results, folder, repeat):
    """The first load of a process (pyarrow imported by it), and the import of pyarrow.csv alone."""
    commands = {
        "import pyarrow.csv after numpy": "import numpy, time; t = time.perf_counter(); import pyarrow.csv; "
        "print(time.perf_counter() - t)",
        "first flyopt.load, 1M rows CSV": "import flyopt, time, sys; t = time.perf_counter(); "
        f"flyopt.load({str(folder / 'csv-1000000.toml')!r}); print(time.perf_counter() - t)",
        "first flyopt.load, 1M rows inline": "import flyopt, time, sys; t = time.perf_counter(); "
        f"flyopt.load({str(folder / 'inline-1000000.toml')!r}); print(time.perf_counter() - t)",
        "first flyopt.load, 10k rows inline (pyarrow not imported: float)": "import flyopt, time, sys; "
        f"t = time.perf_counter(); flyopt.load({str(folder / 'inline-10000.toml')!r}); "
        "print(time.perf_counter() - t); assert 'pyarrow' not in sys.modules",
    }
    for label, code in commands.items():
        times = [
            float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)
            for _ in range(repeat)
        ]
        results.append(
            {
                "case": "fresh process",
                "setting": label,
                "reading": "flyopt",
                "bytes": "",
                "wall_s": statistics.median(times),
                "wall_min_s": min(times),
                "wall_max_s": max(times),
                "cpu_s": "",
                "cpu_min_s": "",
                "cpu_max_s": "",
                "note": "wall clock, in the process, from the call (flyopt defers its modules to it: their import is in this time)",
            }
        )


def shown(seconds):
    return f"{seconds * 1e3:.3g} ms" if seconds < 1 else f"{seconds:.3g} s"


def summary(results, header):
    def find(case, setting, reading_prefix):
        return next(
            r
            for r in results
            if r["case"] == case and r["setting"] == setting and r["reading"].startswith(reading_prefix)
        )

    lines = [
        "# Torque tables: reading speed",
        "",
        "Command: `python benchmarks/bench_tables.py`",
        "",
        header,
        "",
        "`flyopt.load` of a scene with the table, in one process after a warm-up; medians with [min–max] over the "
        "repeats, wall clock and CPU time (all threads) side by side; each target is judged on the CPU-time median, "
        "as the host is shared (2 cores, other sessions' work: see the load average) and the wall clock of a "
        "process pinned to a busy core includes the time others ran on it. "
        "'before issue 26' is the same code with the compiled reader's threshold out of reach (Python's `float` "
        "reads every number, as before), timed in the same run. This process has imported pyarrow (as pandas, a "
        "sweep's Parquet files and the app do), so the compiled reader reads every table from "
        f"{compiled_reader.LOADED_READER_BYTES:,} bytes; a process that has not reads a table below "
        f"{compiled_reader.COMPILED_READER_BYTES:,} bytes as 'before issue 26' does (its targets below, and "
        "the first load of a fresh process at the end).",
        "",
        "## Targets",
        "",
        "| target | status | CPU | wall | before issue 26 (CPU) | speed-up (CPU) |",
        "|---|---|---|---|---|---|",
    ]
    for (case, setting), limit in TARGETS.items():
        row = find(case, setting, "flyopt")
        before = [
            r for r in results if r["case"] == case and r["setting"] == setting and r["reading"].startswith("before")
        ]
        judged = [(row, "", f"{shown(before[0]['cpu_s'])}" if before else "—")]
        judged[0] += (f"{before[0]['cpu_s'] / row['cpu_s']:.1f}x" if before else "—",)
        if before and row["bytes"] < compiled_reader.COMPILED_READER_BYTES:  # how a process without pyarrow reads it
            judged.append((before[0], " (pyarrow not imported: float)", "—", "—"))
        for r, which, old, ratio in judged:
            status = "met" if r["cpu_s"] <= limit else "**NOT met**"
            lines.append(
                f"| {case}, {setting}{which} <= {shown(limit)} | {status} | {shown(r['cpu_s'])} "
                f"[{shown(r['cpu_min_s'])}–{shown(r['cpu_max_s'])}] | {shown(r['wall_s'])} "
                f"[{shown(r['wall_min_s'])}–{shown(r['wall_max_s'])}] | {old} | {ratio} |"
            )
    lines += [
        "",
        "## Every row",
        "",
        "| case | setting | reading | bytes | wall | CPU | note |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in results:
        cpu = "" if r["cpu_s"] == "" else f"{shown(r['cpu_s'])} [{shown(r['cpu_min_s'])}–{shown(r['cpu_max_s'])}]"
        lines.append(
            f"| {r['case']} | {r['setting']} | {r['reading']} | {r['bytes']} | {shown(r['wall_s'])} "
            f"[{shown(r['wall_min_s'])}–{shown(r['wall_max_s'])}] | {cpu} | {r['note']} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="fewer repeats; writes nothing")
    args = parser.parse_args(argv)
    repeat = 3 if args.quick else args.repeat
    pinned = pin_one_core()
    import pyarrow

    before = load_average("/")
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for case, rows, both in (("10k rows", 10_000, True), ("30k rows", 30_000, True), ("1M rows", 1_000_000, True)):
            print(f"bench_tables: {case}", file=sys.stderr, flush=True)
            bench(results, case, rows, repeat if rows < 10**6 else max(3, repeat // 2 + 1), folder, both)
        print("bench_tables: fresh processes", file=sys.stderr, flush=True)
        first_load(results, folder, 3)
    header = (
        f"Machine: {platform.platform()}, {platform.machine()}, {os.cpu_count()} CPUs, {pinned}; "
        f"Python {platform.python_version()}, numpy {np.__version__}, pyarrow {pyarrow.__version__}. "
        f"Load average (1/5/15 min) {before} before the run, {load_average('/')} after. "
        f"Compiled reader from {compiled_reader.COMPILED_READER_BYTES:,} bytes."
    )
    text = summary(results, header)
    if not args.quick:
        write_results(RESULTS, "tables", text, results)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
