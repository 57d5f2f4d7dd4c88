"""Whole-wheel sweeps of two flyopts side by side: the same table to a relative tolerance (issue 26).

Runs ``flyopt.sweep`` of each scene over δ (``--points`` points, serially, in one process each) with this
checkout's flyopt and with another's ``src`` folder (``--baseline``, e.g. ``git archive main src``
unpacked), in subprocesses, and compares the two tables column by column: every float column (masses,
dimensions, stresses, limits, multipliers' products) to ``--rtol`` relative, NaN where the other has NaN,
and every other column (status, method, best material and shaft, binding limits) equal. ``iterations`` and
``message`` are left out: they say how the solver got there (warm starts take fewer iterations), not what
it found. Where rows differ beyond the tolerance, each such point is solved a third way, by IPOPT alone at
a tolerance of 1e-12 (``flyopt.wheel_solver = "ipopt"``, no warm start: the referee), and the script says
which of the two is nearer it. Prints one line per scene (and per differing point) and exits 1 where a table
differs and this checkout's row is not the nearer to the referee.

Usage::

    python benchmarks/compare_sweep.py --baseline /tmp/main/src [--points 400] [--rtol 1e-9]
"""

import argparse
import json
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
#: The referee of rows that differ: IPOPT alone, to 1e-12 (its default 1e-8 leaves a wheel up to 7e-9 inside
#: an active bound).
REFEREE = {"flyopt.wheel_solver": "ipopt", "ipopt.tol": 1e-12}
#: What the referee is compared on.
DESIGN = ("mass", "d_outer", "d_inner", "h", "b", "hb_ratio")


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


def refereed(scene, deltas, out):
    """The points ``deltas`` of ``scene`` by IPOPT alone to 1e-12 (:data:`REFEREE`), this checkout's flyopt."""
    code = (
        "import json, sys, flyopt; s = flyopt.load(sys.argv[1]); "
        "f = flyopt.sweep(s, {'delta': json.loads(sys.argv[2])}, workers=1, solver_options=json.loads(sys.argv[3])); "
        "f.to_pickle(sys.argv[4])"
    )
    path = ROOT / "problems" / f"{scene}.toml"
    args = [sys.executable, "-c", code, str(path), json.dumps(deltas), json.dumps(REFEREE), str(out)]
    subprocess.run(args, env={**os.environ, "PYTHONPATH": str(ROOT / "src")}, check=True, capture_output=True)
    return pd.read_pickle(out)


def _distance(row, reference):
    """The largest relative difference of a row's design from the referee's (:data:`DESIGN`)."""
    return max(abs(row[c] - reference[c]) / abs(reference[c]) for c in DESIGN)


def differing_rows(new, old, rtol):
    """Positions of the rows whose float columns differ by more than ``rtol`` (relative)."""
    rows = set()
    for column in new.columns:
        if column in HOW or new[column].dtype.kind != "f":
            continue
        a, b = new[column].to_numpy(), old[column].to_numpy()
        with np.errstate(invalid="ignore", divide="ignore"):
            bad = np.abs(a - b) > rtol * np.abs(b)
        rows.update(np.flatnonzero(bad).tolist())
    return sorted(rows)


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
            new, old = pd.read_pickle(here), pd.read_pickle(there)
            worst, where, other = differences(new, old, args.rtol)
            same = worst <= args.rtol and not other
            print(
                f"{scene}: {args.points} points, largest relative difference {worst:.2g} ({where}), "
                f"other columns differing: {other or 'none'}; CPU {cpu_new:.2f} s here, {cpu_old:.2f} s baseline "
                f"-> {'same' if same else 'DIFFERENT'}"
            )
            if same:
                continue
            failed |= bool(other) or not np.isfinite(worst)
            rows = differing_rows(new, old, args.rtol)
            reference = refereed(scene, [float(new["delta"].iloc[k]) for k in rows], Path(folder) / "referee.pkl")
            for j, k in enumerate(rows):
                mine, theirs = _distance(new.iloc[k], reference.iloc[j]), _distance(old.iloc[k], reference.iloc[j])
                failed |= mine > theirs
                print(
                    f"  point {k} (delta {new['delta'].iloc[k]:.6g}): from IPOPT alone at tol 1e-12 this one "
                    f"{mine:.2g}, the baseline {theirs:.2g} (mass, D, d, H, B, H/B) -> "
                    f"{'this one nearer' if mine <= theirs else 'the baseline nearer'}"
                )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
