"""Options that a command would silently ignore are refused in one line, exit 2, nothing written.

An engineer who passes ``--verify``, ``--seed`` or ``--keep-parts`` expects it to change what flyopt does; where
it cannot (a results table has no simulation, a grid no randomness, stdout no parts), saying so
beats an answer that looks like it took the option into account.
"""

from __future__ import annotations

import pytest
from conftest import PROBLEMS, run_flyopt

SHEAR = PROBLEMS / "shear-press.toml"


def _refused(run, words):
    assert run.returncode == 2, run
    assert len(run.stderr.splitlines()) == 1 and run.stderr.startswith("flyopt: error: "), run.stderr
    assert words in run.stderr, run.stderr
    assert "Traceback" not in run.stderr


@pytest.fixture(scope="module")
def sweep_table(tmp_path_factory):
    out = tmp_path_factory.mktemp("table") / "s.csv"
    run = run_flyopt("sweep", SHEAR, "--vary", "delta=0.02,0.05", "-o", out, "--no-progress")
    assert run.returncode == 0, run.stderr
    return out


@pytest.mark.parametrize("what", ["energy", "turning_moment", "inertia_delta"])
def test_verify_on_a_diagram_without_the_simulation_is_refused(tmp_path, what):
    out = tmp_path / "d.png"
    run = run_flyopt("plot", SHEAR, "--what", what, "--verify", "-o", out)
    _refused(run, f"--verify: draws the periodic simulation on the speed diagram (--what speed or all), not on {what}")
    assert not out.exists()


def test_verify_on_a_results_table_is_refused(tmp_path, sweep_table):
    out = tmp_path / "s.png"
    run = run_flyopt("plot", sweep_table, "--what", "sweep", "--x", "delta", "--verify", "-o", out)
    _refused(run, "--verify: draws the periodic simulation on a scene's speed diagram; a table of results has none")
    assert not out.exists()


def test_y_on_a_scene_diagram_is_refused_and_defaults_to_mass_on_results(tmp_path, sweep_table):
    out = tmp_path / "e.png"
    _refused(run_flyopt("plot", SHEAR, "--what", "energy", "--y", "mass", "-o", out), "--y: choose the columns")
    assert not out.exists()
    drawn, named = tmp_path / "s.png", tmp_path / "named.png"
    assert run_flyopt("plot", sweep_table, "--what", "sweep", "--x", "delta", "-o", drawn).returncode == 0
    assert (
        run_flyopt("plot", sweep_table, "--what", "sweep", "--x", "delta", "--y", "mass", "-o", named).returncode == 0
    )
    assert drawn.read_bytes() == named.read_bytes()


def test_seed_without_samples_is_refused_everywhere(tmp_path):
    import flyopt
    from flyopt.errors import SceneError

    run = run_flyopt("sweep", SHEAR, "--vary", "delta=0.02,0.05", "--seed", "3", "--no-progress")
    _refused(run, "--seed: seeds the Latin hypercube of --samples, which is not given")
    with pytest.raises(SceneError) as info:
        flyopt.sweep(flyopt.load(SHEAR), {"delta": "0.02,0.05"}, seed=3)
    assert info.value.field == "--seed"
    scene = tmp_path / "s.toml"
    scene.write_text(SHEAR.read_text(encoding="utf-8") + '\n[sweep]\nseed = 3\n[sweep.vary]\ndelta = "0.02,0.05"\n')
    run = run_flyopt("sweep", scene, "--no-progress")
    _refused(run, "sweep.seed: seeds the Latin hypercube of sweep.samples, which is not given")
    assert f"{scene}" in run.stderr


def test_seed_with_samples_still_runs():
    run = run_flyopt(
        "sweep", SHEAR, "--vary", "delta=0.02:0.05", "--samples", "3", "--seed", "3", "--no-progress", "--quiet"
    )
    assert run.returncode == 0, run.stderr
    assert len(run.stdout.strip().splitlines()) == 4  # header and three samples


@pytest.mark.parametrize(
    ("option", "words"),
    [
        (["--keep-parts"], "--keep-parts: needs an output file (its parts are OUTPUT.parts/)"),
        (["--max-chunks", "1"], "--max-chunks: needs an output file (-o)"),
    ],
)
def test_sweep_options_about_the_output_file_need_one(tmp_path, option, words):
    run = run_flyopt("sweep", SHEAR, "--vary", "delta=0.02,0.05", *option, "--no-progress", cwd=tmp_path)
    _refused(run, words)
    assert list(tmp_path.iterdir()) == []


def test_keep_parts_without_an_output_is_refused_by_the_api():
    import flyopt
    from flyopt.errors import SceneError

    with pytest.raises(SceneError) as info:
        flyopt.sweep(flyopt.load(SHEAR), {"delta": "0.02,0.05"}, keep_parts=True)
    assert info.value.field == "--keep-parts"
