"""Tests of flyopt.studies.task: the evaluation sent to workers is the scene's text and values.

A scene that cannot travel as data runs serially and says why; on Dask it is
refused before anything is written.
"""

import pickle

import pytest
from conftest import PROBLEMS
from test_evaluate import load

import flyopt
from flyopt.studies.context import chunk_context
from flyopt.studies.payload import digest, payload
from flyopt.studies.points import point_scene
from flyopt.studies.sweep import sweep
from flyopt.studies.task import task_of


def test_the_task_sent_to_workers_is_the_scene_text_and_values():
    """The task a worker gets holds the scene's file text (rebuilt there by the same
    reader, to the same digest), not the scene's objects."""
    scene = load("energy_mass")
    task, reason = task_of(chunk_context(scene), scene)
    assert reason == "" and task.scene.text == (PROBLEMS / "slider-crank-press.toml").read_text()
    assert task.scene.fields == {}
    shipped = pickle.loads(pickle.dumps(task))
    assert digest(shipped.scene.scene()) == digest(scene)
    # a point of it (a field changed after loading) travels as the text plus that field
    changed = point_scene(scene, {"delta": 0.07, "design.max_outer_diameter": 0.9})
    data, _ = payload(changed)
    assert set(data.fields) == {"delta", "design"}
    assert digest(pickle.loads(pickle.dumps(data)).scene()) == digest(changed)
    assert digest(data.scene()) != digest(scene)


def _scene_with_a_function():
    """A varying-inertia scene built in memory (no file) with a member whose velocity ratio
    is a function made here: nothing can send it to another process."""
    from flyopt.machine.mechanism import Member

    data = __import__("tomllib").loads((PROBLEMS / "slider-crank-press.toml").read_text())
    scene = flyopt.from_dict(data)
    # plain arithmetic, for numpy and CasADi alike; equal at 0 and 2 pi
    arm = Member("arm", mass=50.0, velocity_ratio=lambda phi: 0.05 + 0.002 * phi * (6.283185307179586 - phi))
    return scene.replace(members=scene.members + (arm,))


def test_a_scene_that_cannot_travel_runs_serially_and_says_why(tmp_path, fake_dask):
    """Such a scene's sweep runs in this process and says so; on Dask it is refused
    before anything is written."""
    scene = _scene_with_a_function()
    with pytest.raises((pickle.PicklingError, AttributeError, TypeError)):
        pickle.dumps(scene)
    assert payload(scene)[0] is None
    frame = sweep(scene, {"delta": "0.1,0.15"}, workers=2, chunk_size=1)
    info = frame.attrs["sweep"]
    assert info["mode"] == "serial" and "cannot be sent to workers as data" in info["serial_because"]
    with pytest.raises(flyopt.SceneError, match="cannot run on a Dask cluster"):
        sweep(scene, {"delta": "0.1,0.15"}, scheduler=_Client(), output=tmp_path / "x.csv")
    assert list(tmp_path.iterdir()) == []


class _Client:
    """Stands in for a dask.distributed Client (two worker threads)."""

    def scheduler_info(self):
        return {"workers": {"a": {"nthreads": 1}, "b": {"nthreads": 1}}}


@pytest.fixture
def fake_dask(monkeypatch):
    from dask import distributed

    monkeypatch.setattr(distributed, "Client", _Client)
