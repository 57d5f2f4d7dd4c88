"""Benchmark of ``flyopt plot`` of a large results table: a sweep of 2 million points drawn as PNG and SVG.

The table is made once: a real sweep of punch-press.toml over δ (200 points, by ``flyopt sweep``), its rows
repeated to 2,000,000 with δ spread evenly over the sweep's range and every number column that follows δ (the
mass) interpolated along it, so that the curve is the sweep's own, drawn through 2 million points; the file keeps
the sweep's metadata (its recorded ``vary``) and all of its 47 columns.

Each figure is a whole process, ``python -m flyopt plot FILE --what sweep --x delta -o OUT`` as a user runs it:
its wall time and its peak resident memory (``resource.getrusage`` of the child), medians over ``--repeat`` runs
with their ranges, and the size of the file written. With ``--baseline SRC`` (another flyopt tree's ``src``,
e.g. ``git archive c51072c src``) the same plots by that code run in turn with this one's, and the ratios are of
medians from this run. The host is shared: its load averages are written at the start and the end.

Writes ``benchmarks/results/plot_results.md`` and ``plot_results.csv`` beside this script.

Usage::

    python benchmarks/bench_plot_results.py [--repeat 3] [--baseline /tmp/base/src]
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
from common import CHILD_ENV, load_average, write_results

RESULTS = Path(__file__).resolve().parent / "results"
ROOT = Path(__file__).resolve().parents[1]
ROWS = 2_000_000


def make_table(folder):
    """The 2-million-row sweep table (see the module's notes); its path."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    small = folder / "sweep.parquet"
    subprocess.run(
        [sys.executable, "-m", "flyopt", "sweep", str(ROOT / "problems" / "punch-press.toml"), "--vary",
         "delta=0.02:0.3:200", "-o", str(small), "-q"],
        check=True, env=CHILD_ENV,
    )  # fmt: skip
    table = pq.read_table(small)
    big = pa.concat_tables([table] * (ROWS // table.num_rows))
    delta0, mass0 = table.column("delta").to_numpy(), table.column("mass").to_numpy()
    order = np.argsort(delta0)
    delta = np.linspace(delta0.min(), delta0.max(), big.num_rows)
    big = big.set_column(big.schema.get_field_index("delta"), "delta", pa.array(delta))
    mass = np.interp(delta, delta0[order], mass0[order])
    big = big.set_column(big.schema.get_field_index("mass"), "mass", pa.array(mass))
    path = folder / "large.parquet"
    pq.write_table(big.replace_schema_metadata(table.schema.metadata), path)
    return path, big.num_columns


def plot_once(src, table, out):
    """(wall seconds, bytes written) of one ``flyopt plot`` process of ``src``'s code."""
    env = {**CHILD_ENV, "PYTHONPATH": str(src)}
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "flyopt", "plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(out)],
        check=True, env=env, capture_output=True,
    )  # fmt: skip
    wall = time.perf_counter() - start
    size = out.stat().st_size
    out.unlink()
    return wall, size


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--baseline", type=Path, help="another flyopt tree's src folder, run in turn with this one")
    args = parser.parse_args(argv)
    load_start = load_average()
    trees = {"this": ROOT / "src"}
    if args.baseline:
        trees["baseline"] = args.baseline
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        table, columns = make_table(folder)
        table_bytes = table.stat().st_size
        runs = {(tree, fmt): [] for tree in trees for fmt in ("png", "svg")}
        # a warm-up of each tree (bytecode written), then the runs in turn
        for tree in reversed(list(trees)):
            plot_once(trees[tree], table, folder / "warm.png")
        for _ in range(args.repeat):
            for tree in reversed(list(trees)):
                for fmt in ("png", "svg"):
                    runs[tree, fmt].append(plot_once(trees[tree], table, folder / f"out.{fmt}"))
        peak = {}
        for tree in trees:  # the peak memory of a PNG plot: a process of its own, whose child is that plot alone
            code = (
                "import resource, subprocess, sys;"
                "subprocess.run([sys.executable, '-m', 'flyopt', 'plot', sys.argv[1], '--what', 'sweep', '--x', "
                "'delta', '-o', sys.argv[2]], check=True, capture_output=True);"
                "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
            )
            env = {**CHILD_ENV, "PYTHONPATH": str(trees[tree])}
            done = subprocess.run(
                [sys.executable, "-c", code, str(table), str(folder / "p.png")],
                check=True, env=env, capture_output=True, text=True,
            )  # fmt: skip
            peak[tree] = int(done.stdout.strip().splitlines()[-1]) / 1e3
    summary = {}
    for (tree, fmt), found in runs.items():
        walls = [w for w, _ in found]
        summary[tree, fmt] = (statistics.median(walls), min(walls), max(walls), found[-1][1])
        rows.append(
            {
                "code": tree,
                "format": fmt,
                "wall_median_s": f"{statistics.median(walls):.3f}",
                "wall_min_s": f"{min(walls):.3f}",
                "wall_max_s": f"{max(walls):.3f}",
                "bytes_written": found[-1][1],
                "peak_memory_png_mb": f"{peak[tree]:.0f}",
            }
        )
    load_end = load_average()
    lines = [
        "# flyopt plot of a large results table: speed and memory",
        "",
        f"Command: `python benchmarks/bench_plot_results.py --repeat {args.repeat}"
        + (f" --baseline {args.baseline}`" if args.baseline else "`"),
        "",
        f"Machine: {platform.platform()}, {os.cpu_count()} CPUs, Python {platform.python_version()}. Load averages "
        f"(1, 5, 15 min) at the start {load_start}, at the end {load_end} (a shared host: figures are medians).",
        "",
        f"Table: a sweep of punch-press.toml over δ (200 points) repeated to {ROWS:,} rows of {columns} columns, δ "
        f"spread evenly over its range and the mass interpolated along it; Parquet, {table_bytes / 1e6:.1f} MB. Each "
        "figure is a whole process, `python -m flyopt plot FILE --what sweep --x delta -o OUT`, "
        f"{args.repeat} runs each, in turn.",
        "",
        "| code | format | wall median [s] | range [s] | file written | peak memory of a PNG plot [MB] |",
        "|---|---|---|---|---|---|",
    ]
    for (tree, fmt), (median, low, high, size) in summary.items():
        lines.append(
            f"| {tree} | {fmt} | {median:.2f} | {low:.2f}-{high:.2f} | {size / 1e3:,.0f} kB | {peak[tree]:,.0f} |"
        )
    if args.baseline:
        lines += ["", "Ratios of medians, this run (the baseline's over this code's):", ""]
        for fmt in ("png", "svg"):
            ratio = summary["baseline", fmt][0] / summary["this", fmt][0]
            size = summary["baseline", fmt][3] / summary["this", fmt][3]
            lines.append(f"- {fmt}: wall time {ratio:.1f}x; file size {size:,.2g}x")
        lines.append(f"- peak memory of a PNG plot: {peak['baseline'] / peak['this']:.1f}x")
        lines += [
            "",
            "The PNG this code writes is somewhat larger: where a line has over 2,000 points its markers are drawn "
            "one in each 1/800 of the span (a marker covers some ten such cells), so the antialiased edge of the "
            "band of markers is no longer one solid blot; the two images look the same.",
        ]
    write_results(RESULTS, "plot_results", "\n".join(lines) + "\n", rows)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
