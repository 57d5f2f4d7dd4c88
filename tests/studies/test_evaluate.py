"""Sweeps of every model, in every mode: energy, energy–mass and the dynamic model.

A sweep of a constant-inertia scene (the energy method, one A_max scaled), of a
slider-crank press (varying inertia: the energy–mass closed form at each physics)
and of a press with an induction motor (the dynamic model: a periodic solution at
each physics) must name, at every point, the winner and mass that ``flyopt.solve``
of that point's scene names (to 1e-9), whether it runs serially, in worker
processes or on a Dask cluster; the worker processes and Dask workers get the
scene as data (its file's text) and the points as values. A sweep stopped
mid-way (by ``max_chunks`` or by SIGKILL) and resumed gives the file an
uninterrupted run gives, also from a scene loaded afresh. The streamed file equals
the table a sweep returns in memory, also when the points of one physics are
gathered into chunks out of point order.
"""

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pandas as pd
import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.outputs.results import read_results
from flyopt.studies import sweep as sweep_module
from flyopt.studies.context import chunk_context
from flyopt.studies.payload import digest
from flyopt.studies.points import point_scene
from flyopt.studies.sweep import SUMMARY_COLUMNS, sweep

#: The solve of a point and the sweep's row of it run the same analysis and the same
#: closed form, so they agree to round-off; 1e-9 is the issue's bar.
RTOL = 1e-9

#: model -> scene file and a small grid of physics (δ, speed) and design (envelope) fields.
MODELS = {
    "energy": ("punch-press.toml", {"delta": "0.02,0.1", "speed": "30,60rpm", "envelope": "1.0 m,none"}),
    "energy_mass": ("slider-crank-press.toml", {"speed": "100,140rpm", "delta": "0.08,0.15", "envelope": "0.8 m,none"}),
    "dynamic": ("motor-press.toml", {"delta": "0.08,0.15", "envelope": "1.0,1.4 m"}),
}


def load(model):
    return flyopt.load(PROBLEMS / MODELS[model][0])


@pytest.fixture(scope="module")
def serial():
    """Each model's sweep, serially in this process, with its scene."""
    out = {}
    for model, (_, vary) in MODELS.items():
        scene = load(model)
        out[model] = scene, sweep(scene, vary, workers=1, chunk_size=2)
    return out


@pytest.mark.parametrize("model", list(MODELS))
def test_serial_sweep_of_every_model_equals_individual_solves(serial, model):
    scene, frame = serial[model]
    assert frame.attrs["sweep"]["mode"] == "serial"
    inputs = [c for c in frame.columns if c in ("delta", "speed", "design.max_outer_diameter")]
    designed = 0
    for row in frame.to_dict("records"):
        point = {name: row[name] for name in inputs}
        solution = flyopt.solve(point_scene(scene, point))
        assert solution.analysis.model == model, solution.analysis.model
        assert row["status"] == solution.status, point
        if solution.status != "designed":
            continue
        best = solution.design.best
        assert (row["best_material"], row["best_shaft"]) == (best.material, best.shaft), point
        np.testing.assert_allclose(row["mass"], best.mass, rtol=RTOL, err_msg=str(point))
        np.testing.assert_allclose(row["j_required"], solution.analysis.j_required, rtol=RTOL)
        designed += 1
    assert designed >= len(frame) // 2  # the comparison is not vacuous


@pytest.mark.parametrize("model", list(MODELS))
def test_worker_processes_give_the_serial_table(serial, model):
    scene, expected = serial[model]
    frame = sweep(load(model), MODELS[model][1], workers=2, chunk_size=2)
    assert frame.attrs["sweep"]["mode"] == "processes", frame.attrs["sweep"]
    pd.testing.assert_frame_equal(frame, expected)


@pytest.fixture(scope="module")
def dask_client():
    """A Dask cluster of two worker processes: the chunks travel to them pickled."""
    from dask.distributed import Client, LocalCluster

    with (
        LocalCluster(processes=True, n_workers=2, threads_per_worker=1, dashboard_address=":0") as cluster,
        Client(cluster) as client,
    ):
        yield client


# one model in the default run: the Dask path is the runner's, whatever a point computes (the models are
# compared on worker processes above); the other two with the slow set
@pytest.mark.parametrize(
    "model", [m if k == 0 else pytest.param(m, marks=pytest.mark.slow) for k, m in enumerate(MODELS)]
)
def test_dask_local_cluster_gives_the_serial_table(serial, dask_client, model, tmp_path):
    _, expected = serial[model]
    out = tmp_path / "study.parquet"
    summary = sweep(load(model), MODELS[model][1], scheduler=dask_client, chunk_size=2, output=out)
    assert summary.attrs["sweep"]["mode"] == "dask"
    pd.testing.assert_frame_equal(read_results(out), expected)
    # the workers really were other processes that rebuilt the scene
    pids = dask_client.run(os.getpid)
    assert os.getpid() not in pids.values()


@pytest.mark.parametrize("model", list(MODELS))
def test_stopped_sweep_resumed_from_a_scene_loaded_afresh_gives_the_same_file(serial, model, tmp_path):
    """Regression: the parts of a slider-crank sweep could never be resumed: the sweep's
    fingerprint held the repr of the scene, in which a member's kinematics is a function
    shown with its address (another at every load), and numpy's repr of a table rounds
    its numbers and elides long tables. The fingerprint is now a digest of the scene's
    values."""
    _, expected = serial[model]
    out = tmp_path / "study.csv"
    first = sweep(load(model), MODELS[model][1], workers=1, chunk_size=2, output=out, max_chunks=1)
    assert not first.attrs["sweep"]["complete"] and not out.exists()
    done = sweep(load(model), MODELS[model][1], workers=1, chunk_size=2, output=out, resume=True)
    assert done.attrs["sweep"]["chunks_reused"] == [0]
    pd.testing.assert_frame_equal(read_results(out), expected)


def test_a_scene_differing_inside_a_long_table_is_another_sweep(tmp_path):
    """numpy's repr of a 2,000-point table shows 6 of its values: two scenes differing
    elsewhere had the same fingerprint, and --resume mixed their chunks."""
    angles = np.linspace(0.0, 360.0, 2000)
    values = 1000.0 + 500.0 * np.sin(np.radians(angles)) ** 2

    def scene(bump):
        table = values.copy()
        table[1000] += bump
        return flyopt.from_dict(
            {
                "machine": {"speed": "300 rpm", "delta": 0.05},
                "torque": {
                    "resisting": {
                        "angle_unit": "deg",
                        "unit": "N*m",
                        "points": [[a, v] for a, v in zip(angles, table)],
                    },
                    "driving": {"constant": "unknown"},
                },
            }
        )

    assert digest(scene(0.0)) != digest(scene(1e-9))
    out = tmp_path / "study.parquet"
    sweep(scene(0.0), {"delta": "0.02,0.04,0.06"}, chunk_size=1, output=out, max_chunks=1)
    with pytest.raises(flyopt.SceneError, match="come from a different sweep"):
        sweep(scene(1e-9), {"delta": "0.02,0.04,0.06"}, chunk_size=1, output=out, resume=True)


DRIVER = textwrap.dedent("""
    import sys

    import flyopt

    scene = flyopt.load(sys.argv[1])
    flyopt.sweep(scene, {vary!r}, workers=2, chunk_size=1, output=sys.argv[2],
                 resume=sys.argv[3] == "resume")
    print("done", flush=True)
""")


def test_killed_slider_crank_sweep_resumes_to_the_same_file(tmp_path):
    """SIGKILL in the middle of a varying-inertia sweep in two worker processes, then
    --resume in a new process: the file of an uninterrupted run."""
    vary = {"delta": "0.05:0.2:12"}
    scene_file = PROBLEMS / "slider-crank-press.toml"
    expected = sweep(flyopt.load(scene_file), vary, workers=1)
    script = tmp_path / "driver.py"
    script.write_text(DRIVER.format(vary=vary))
    out = tmp_path / "study.parquet"
    parts = tmp_path / "study.parquet.parts"

    def start(mode):
        return subprocess.Popen(
            [sys.executable, str(script), str(scene_file), str(out), mode],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
        )

    driver = start("new")
    try:
        deadline = time.monotonic() + 120
        while not any(parts.glob("chunk-*.parquet")) and driver.poll() is None:
            assert time.monotonic() < deadline, "no chunk within 120 s"
            time.sleep(0.01)
        assert driver.poll() is None, driver.communicate()
        os.killpg(driver.pid, signal.SIGKILL)
    finally:
        if driver.poll() is None:
            os.killpg(driver.pid, signal.SIGKILL)
        driver.communicate(timeout=60)
    assert not out.exists()
    saved = len(list(parts.glob("chunk-*.parquet")))
    assert 1 <= saved < 12
    again = start("resume")
    stdout, stderr = again.communicate(timeout=300)
    assert (again.returncode, stdout) == (0, "done\n"), stderr
    pd.testing.assert_frame_equal(read_results(out), expected)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", "study.parquet"]


# --------------------------------------------------------------------------
# Chunks sized by cost, physics kept together
# --------------------------------------------------------------------------


def test_a_costly_sweep_is_cut_for_the_workers(monkeypatch):
    """Regression (issue 12): chunks were sized by the designs alone (2,500 closed-form
    points a chunk), so a 60-point motor sweep, ~1 s of periodic solutions a point, was
    one serial chunk. The first point's analysis is timed and counted for every physics."""
    scene = load("dynamic")
    monkeypatch.setattr(sweep_module, "_time_first_analysis", lambda scene, points, codes: 0.5)
    monkeypatch.setattr(sweep_module, "cpu_count", lambda: 2)
    plan_points = flyopt.studies.plan.plan_sweep(scene, {"delta": "0.05:0.2:6", "envelope": "0.8:1.6:10 m"}).points
    ctx = chunk_context(scene)
    layout = sweep_module._layout(scene, ctx, plan_points, "auto", "auto", None, None, {})
    assert layout["mode"] == "processes" and layout["workers"] == 2
    assert layout["physics"] == 6 and layout["estimate"] == pytest.approx(3.0, rel=0.01)
    # whole physics in each chunk (each analysed once), 5 chunks for 2 workers
    assert layout["bounds"].tolist() == [0, 20, 30, 40, 50, 60]
    # a closed-form sweep of the same size is estimated to take milliseconds: serial
    punch = load("energy")
    small = sweep_module._layout(punch, chunk_context(punch), plan_points, "auto", "auto", None, None, {})
    assert small["mode"] == "serial" and len(small["bounds"]) == 2


def test_interleaved_physics_are_gathered_into_chunks_and_the_file_is_in_point_order(tmp_path, monkeypatch):
    """With the envelope varied first, the points of one δ come back every 3 points. They
    are gathered so that each δ is analysed in one chunk (here one part file each), and
    the rows are put back in point order: the streamed files (CSV and Parquet) and the
    table in memory equal the sweep of the same points one chunk each."""
    scene = load("energy_mass")
    vary = {"envelope": "0.6,0.8,1.0,none", "delta": "0.05,0.1,0.15"}
    monkeypatch.setattr(sweep_module, "_time_first_analysis", lambda scene, points, codes: 1.0)
    gathered = sweep(scene, vary, workers=1)
    assert gathered.attrs["sweep"]["chunks"] == 3
    reference = sweep(scene, vary, workers=1, chunk_size=1)  # point order, a chunk a point
    pd.testing.assert_frame_equal(gathered, reference)
    assert gathered["point"].tolist() == list(range(12))
    for suffix in (".csv", ".parquet"):
        out = tmp_path / f"study{suffix}"
        summary = sweep(scene, vary, workers=2, output=out, keep_parts=True)
        pd.testing.assert_frame_equal(read_results(out), reference)
        assert summary["point"].tolist() == list(range(12))
        parts = sorted((tmp_path / f"study{suffix}.parts").glob("chunk-*.parquet"))
        deltas = [sorted(set(read_results(p)["delta"])) for p in parts]
        assert deltas == [[0.05], [0.1], [0.15]]


def test_resume_keeps_the_chunks_of_the_run_it_continues(tmp_path, monkeypatch):
    """Chunks sized by a timed analysis differ from run to run; a resumed sweep must cut
    its points as the run it continues did (recorded with the parts), or its parts would
    be refused as another sweep's."""
    scene = load("energy_mass")
    vary = {"envelope": "0.6,0.8,1.0,none", "delta": "0.05,0.1,0.15"}
    out = tmp_path / "study.parquet"
    monkeypatch.setattr(sweep_module, "_time_first_analysis", lambda scene, points, codes: 1.0)
    first = sweep(scene, vary, workers=1, output=out, max_chunks=1)
    assert first.attrs["sweep"]["chunks"] == 3
    monkeypatch.setattr(sweep_module, "_time_first_analysis", lambda scene, points, codes: 0.01)
    assert sweep(scene, vary, workers=1).attrs["sweep"]["chunks"] == 1  # cut otherwise now
    done = sweep(load("energy_mass"), vary, workers=1, output=out, resume=True)
    assert done.attrs["sweep"]["chunks"] == 3 and done.attrs["sweep"]["chunks_reused"] == [0]
    pd.testing.assert_frame_equal(read_results(out), sweep(scene, vary, workers=1))


# --------------------------------------------------------------------------
# Streaming
# --------------------------------------------------------------------------


def test_with_an_output_the_table_is_not_returned_but_summarized(tmp_path):
    scene = load("energy")
    vary = {"delta": "0.01:0.2:30", "speed": "30:120:20rpm"}
    out = tmp_path / "study.parquet"
    summary = sweep(scene, vary, output=out, chunk_size=37)
    whole = sweep(scene, vary, chunk_size=37)
    assert list(summary.columns) == list(SUMMARY_COLUMNS) and summary.attrs["sweep"]["summary"]
    assert summary["status"].value_counts().to_dict() == whole["status"].value_counts().to_dict()
    pd.testing.assert_frame_equal(read_results(out), whole)
    import pyarrow.parquet as pq

    schema = pq.read_schema(out)
    assert str(schema.field("status").type) == "dictionary<values=string, indices=int32, ordered=0>"
    assert str(schema.field("mass").type) == "double"
    assert pq.ParquetFile(out).num_row_groups == 1  # 600 rows in 17 chunks, one row group


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_result_writer_appends_pieces_and_puts_the_file_in_place_only_when_complete(tmp_path, suffix):
    from flyopt.outputs.results import ResultWriter, write_results

    whole = sweep(load("energy"), {"delta": "0.01:0.2:7", "material": "cast_iron,cast_steel"}, chunk_size=3)
    one = tmp_path / f"one{suffix}"
    write_results(whole, one)
    out = tmp_path / f"pieces{suffix}"
    with ResultWriter(out, temporary_folder=tmp_path) as writer:
        for start in range(0, len(whole), 5):
            writer.append(whole.iloc[start : start + 5])
        assert not out.exists()
        writer.close()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([one.name, out.name])
    pd.testing.assert_frame_equal(read_results(out), read_results(one))
    pd.testing.assert_frame_equal(read_results(out), whole)
    # an error while writing leaves neither the file nor its temporary
    broken = tmp_path / f"broken{suffix}"
    with pytest.raises(ValueError, match="columns differ"):
        with ResultWriter(broken, temporary_folder=tmp_path) as writer:
            writer.append(whole.iloc[:3])
            writer.append(whole.iloc[3:6].drop(columns=["mass"]))
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([one.name, out.name])


def test_resume_without_the_chunk_size_uses_the_recorded_one(tmp_path):
    out = tmp_path / "study.parquet"
    vary = {"delta": "0.01:0.2:9"}
    sweep(load("energy"), vary, chunk_size=2, output=out, max_chunks=2)
    done = sweep(load("energy"), vary, output=out, resume=True)
    assert done.attrs["sweep"]["chunks_reused"] == [0, 1]
    assert done.attrs["sweep"]["chunk_size"] == 2 and done.attrs["sweep"]["chunks"] == 5
    pd.testing.assert_frame_equal(read_results(out), sweep(load("energy"), vary))


# --------------------------------------------------------------------------
# Longer runs (pytest -m slow)
# --------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize(
    "model, vary, fields",
    [
        ("energy_mass", {"speed": "80:160:6rpm", "delta": "0.05:0.2:6"}, ("speed", "delta")),
        ("dynamic", {"delta": "0.05:0.2:6", "envelope": "0.8:1.6:5 m"}, ("delta", "design.max_outer_diameter")),
    ],
)
def test_larger_sweeps_in_processes_equal_individual_solves(model, vary, fields):
    """Chunks of 6 points in 2 processes (left to itself, the sweep now finds the 36 energy_mass points too
    cheap to split: one chunk, run serially), each row equal to the point solved on its own."""
    scene = load(model)
    frame = sweep(scene, vary, workers=2, chunk_size=6)
    assert frame.attrs["sweep"]["mode"] == "processes"
    for row in frame.to_dict("records"):
        solution = flyopt.solve(point_scene(scene, {name: row[name] for name in fields}))
        assert row["status"] == solution.status
        if solution.status == "designed":
            best = solution.design.best
            assert (row["best_material"], row["best_shaft"]) == (best.material, best.shaft)
            np.testing.assert_allclose(row["mass"], best.mass, rtol=RTOL)


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_a_large_streamed_sweep_equals_the_sweep_in_memory(tmp_path, suffix):
    """40,000 points in 2 processes, streamed in chunks of 10,000 (a row group of
    65,536 rows gathers several): the file equals the table of a serial run in memory."""
    scene = load("energy")
    vary = {"delta": "0.01:0.2:200", "speed": "30:120:200rpm"}
    out = tmp_path / f"study{suffix}"
    summary = sweep(scene, vary, workers=2, output=out, chunk_size=10_000)
    assert summary.attrs["sweep"]["mode"] == "processes" and summary.attrs["sweep"]["chunks"] == 4
    pd.testing.assert_frame_equal(read_results(out), sweep(scene, vary, workers=1))
