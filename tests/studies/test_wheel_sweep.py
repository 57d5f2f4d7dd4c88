"""A sweep designs whole wheels exactly as ``solve`` does (one pipeline, issue 13).

The flywheel's peak torque loads the arms and the key; a sweep must give
each point the same torque the point's own ``solve`` does: scaled from the
cycle's once-analysed |M_d - M_r| for a constant-inertia machine (the engine
on arms), from each point's own analysis otherwise (the press on a web,
whose ram makes the inertia vary).
"""

import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from flyopt.io.scene import load
from flyopt.pipeline import solve
from flyopt.studies.chunks import COLD_START_POINTS
from flyopt.studies.points import design_seconds
from flyopt.studies.sweep import sweep

DATA = Path(__file__).parents[1] / "data" / "wheels"
PROBLEMS = Path(__file__).parents[2] / "problems"


@pytest.mark.parametrize("name", ["engine-arms-sweep.toml", "press-web-sweep.toml"])
def test_sweep_of_whole_wheels_equals_solve_point_by_point(name):
    scene = load(DATA / name)
    deltas = [0.005, 0.02]
    table = sweep(scene, {"delta": deltas}, workers=1)
    for k, delta in enumerate(deltas):
        # a sweep compares continuous optima: solve's own (design.continuous) where solve rounds its wheel
        design = solve(dataclasses.replace(scene, delta=delta)).design
        best = design.continuous if design.continuous is not None else design.best
        # solve rounded it (whole millimetres), or said that no wheel on the grid meets every limit: the arms wheel
        # at delta 0.005 has none. Its hub is 110 mm long (the key's length, over the steel rule's 1.8 d = 108 mm)
        # and at most 108 mm across, so the arms-hub ratio 1.3 allows arms of at most 78.98 mm (2V/A 0.324 a),
        # and their stress needs 78.5 mm: no whole millimetre between
        assert design.spec.round_to
        assert design.best is not best or design.rounding.startswith("NOT rounded")
        assert table["status"][k] == "designed"
        assert table["best_material"][k] == best.material
        assert table["mass"][k] == pytest.approx(best.mass, rel=1e-9)


def test_a_small_whole_wheel_sweep_runs_a_chunk_on_each_worker():
    # each chunk starts its NLPs cold (no neighbour's wheel): 40 points of punch-press-wheel on 2 workers are
    # 2 chunks (the guided cut alone made 9: 7 more cold starts), and give the designs of a sweep cut in 8,
    # 6 of whose chunks start elsewhere (warm starts agree with cold designs to 1e-8: tests/studies/test_wheel_warm.py)
    scene = load(PROBLEMS / "punch-press-wheel.toml")
    vary = {"delta": "0.02:0.3:40"}
    both = sweep(scene, vary, workers=2)
    assert both.attrs["sweep"]["chunks"] == 2 and both.attrs["sweep"]["mode"] == "processes"
    serial = sweep(scene, vary, workers=1, chunk_size=5)
    assert serial.attrs["sweep"]["chunks"] == 8
    assert (both["status"] == "designed").all() and (both["best_material"] == serial["best_material"]).all()
    for column in ("mass", "d_outer", "b", "h", "j_flywheel"):
        assert both[column].to_numpy() == pytest.approx(serial[column].to_numpy(), rel=1e-8), column
    # the estimate behind the cut: a whole wheel's chunk start is COLD_START_POINTS of its point
    points = pd.DataFrame({"delta": np.linspace(0.02, 0.3, 4)})
    seconds, start = design_seconds(scene, points)
    assert (seconds > 0).all() and (start == COLD_START_POINTS * seconds).all()
