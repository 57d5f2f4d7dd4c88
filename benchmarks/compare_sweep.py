"""Whole-wheel sweeps of two flyopts side by side: the same table to a relative tolerance (issue 26).

Runs ``flyopt.sweep`` of each scene over δ (``--points`` points, serially, in one process each) with this
checkout's flyopt and with another's ``src`` folder (``--baseline``, e.g. ``git archive main src``
unpacked), in subprocesses, and compares the two tables column by column: every float column (masses,
dimensions, stresses, limits, multipliers' products) to ``--rtol`` relative, NaN where the other has NaN,
and every other column (status, method, best material and shaft, binding limits) equal. ``iterations`` and
``message`` are left out: they say how the solver got there (warm starts take fewer iterations), not what
it found. Prints one line per scene and exits 1 where a table differs.

Usage::

    python benchmarks/compare_sweep.py --baseline /tmp/main/src [--points 400] [--rtol 1e-9]
"""

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parent.parent
SCENES = ("punch-press-wheel", "press-arms-wheel")
#: Columns that say how a solve went, not what it found.
HOW = ("iterations", "message")


def run(src, scene, points, out):
    """The sweep of ``scene`` over δ by the flyopt in ``src``, pickled to ``out``."""
    code = (
        "import sys, time, flyopt; s = flyopt.load(sys.argv[1]); b = time.process_time(); "
        "f = flyopt.sweep(s, {'delta': f'0.02:0.3:{sys.argv[2]}'}, workers=1); "
        "print(time.process_time() - b); f.to_pickle(sys.argv[3])"
    )
    env = {**os.environ, "PYTHONPATH": str(src)}
    path = ROOT / "problems" / f"{scene}.toml"
    done = subprocess.run(
        [sys.executable, "-c", code, str(path), str(points), str(out)], env=env, capture_output=True, text=True
    )
    if done.returncode:
        raise SystemExit(f"{src}: sweep of {scene} failed:\n{done.stderr}")
    return float(done.stdout.split()[-1])


def differences(new, old, rtol):
    """(largest relative difference of the float columns, its column, the other columns that differ)."""
    if list(new.columns) != list(old.columns) or len(new) != len(old):
        return np.inf, "the columns or rows", []
    worst, where, other = 0.0, "-", []
    for column in new.columns:
        if column in HOW:
            continue
        a, b = new[column].to_numpy(), old[column].to_numpy()
        if a.dtype.kind == "f" and b.dtype.kind == "f":
            if not np.array_equal(np.isnan(a), np.isnan(b)):
                return np.inf, f"{column} (NaN in one only)", other
            keep = ~np.isnan(a)
            scale = np.maximum(np.abs(b[keep]), np.finfo(float).tiny)
            error = float(np.max(np.abs(a[keep] - b[keep]) / scale)) if keep.any() else 0.0
            if error > worst:
                worst, where = error, column
        else:
            missing = new[column].isna().to_numpy()
            if (
                not np.array_equal(missing, old[column].isna().to_numpy())
                or not (new[column][~missing].astype(str) == old[column][~missing].astype(str)).all()
            ):
                other.append(column)
    return worst, where, other


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", required=True, help="the other flyopt's src folder")
    parser.add_argument("--points", type=int, default=400)
    parser.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args(argv)
    failed = False
    with tempfile.TemporaryDirectory() as folder:
        for scene in SCENES:
            here, there = Path(folder) / f"{scene}-new.pkl", Path(folder) / f"{scene}-old.pkl"
            cpu_new = run(ROOT / "src", scene, args.points, here)
            cpu_old = run(args.baseline, scene, args.points, there)
            worst, where, other = differences(pd.read_pickle(here), pd.read_pickle(there), args.rtol)
            same = worst <= args.rtol and not other
            failed |= not same
            print(
                f"{scene}: {args.points} points, largest relative difference {worst:.2g} ({where}), "
                f"other columns differing: {other or 'none'}; CPU {cpu_new:.2f} s here, {cpu_old:.2f} s baseline "
                f"-> {'same' if same else 'DIFFERENT'}"
            )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
