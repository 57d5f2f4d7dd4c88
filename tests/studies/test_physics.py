"""flyopt.studies.physics: the cycle is analysed once per distinct physics; design-only variations reuse it.

A sweep, Pareto front or trade-off over the envelope, the material, the shaft,
H/B, the geometry or the objective changes nothing in the machine, so the
(exact, and on these scenes costly) analysis must not run again. Counted by
wrapping flyopt.analysis.analyse. Before, every sweep point of a
variable-inertia or motor scene was analysed afresh.
"""

import numpy as np
import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.studies.sweep import sweep


@pytest.fixture
def analyses(monkeypatch):
    from flyopt import analysis

    count = {"n": 0}
    original = analysis.analyse

    def counted(*args, **kwargs):
        count["n"] += 1
        return original(*args, **kwargs)

    monkeypatch.setattr(analysis, "analyse", counted)
    return count


def test_design_only_sweep_analyses_once(analyses):
    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")  # energy–mass: no shortcut by scaling
    table = flyopt.sweep(
        scene, {"envelope": [0.5, 0.8, 1.2, "none"], "material": ["cast_iron", "cast_steel"]}, workers=1
    )
    assert len(table) == 8
    assert analyses["n"] == 1


def test_sweep_analyses_each_distinct_physics_once(analyses):
    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    table = flyopt.sweep(scene, {"delta": "0.02,0.04,0.08", "envelope": [0.5, 0.8, 1.2, "none"]}, workers=1)
    assert len(table) == 12
    assert analyses["n"] == 3
    # and the reuse changes nothing: each row equals the solve of its own scene
    row = table[(table["delta"] == 0.04) & (table["design.max_outer_diameter"] == 0.8)].iloc[0]
    alone = flyopt.solve(flyopt.from_dict(_with(scene, delta=0.04, envelope=0.8))).design.best
    assert (row["best_material"], row["best_shaft"]) == (alone.material, alone.shaft)
    assert row["mass"] == pytest.approx(alone.mass, rel=1e-9)


def test_pareto_and_tradeoff_analyse_once(analyses):
    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    front = flyopt.pareto(scene, ("mass", "outer_diameter"), points=6)
    assert not front.empty
    assert analyses["n"] == 1
    flyopt.material_tradeoff(scene)
    assert analyses["n"] == 1  # the same scene object: its analysis is remembered


def _with(scene, delta, envelope):
    import tomllib

    data = tomllib.loads((PROBLEMS / "slider-crank-press.toml").read_text())
    data["machine"]["delta"] = delta
    data.setdefault("design", {})["max_outer_diameter"] = envelope
    return data


def test_a_sweep_computes_neither_the_model_comparison_nor_the_startup(monkeypatch):
    """Only what is asked is computed: a sweep point needs J_F and ω_max, not the comparison of
    the cheaper models (which solves them again) nor the run-up time; the JSON of solve has both."""
    from flyopt.analysis import startup_run  # noqa: F401  (the name the analysis calls)
    from flyopt.sizing import choose

    def refuse(*args, **kwargs):
        raise AssertionError("computed although nothing asked for it")

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    with monkeypatch.context() as patch:
        patch.setattr(choose, "compare", refuse)
        patch.setattr("flyopt.analysis.startup_run", refuse)
        table = flyopt.sweep(scene, {"delta": "0.02,0.04"}, workers=1)
    assert (table["status"] == "designed").all()
    data = flyopt.solve(flyopt.load(PROBLEMS / "slider-crank-press.toml")).to_dict()
    assert [m["model"] for m in data["models"]] == ["energy", "energy_mass"]


@pytest.mark.parametrize("model, speeds", [("energy_mass", "60,90rpm"), ("dynamic", "40,50rpm")])
def test_a_physics_differing_in_delta_alone_reuses_the_machine_and_gives_the_same_analysis(monkeypatch, model, speeds):
    """Along a δ axis each analysis is handed ``like`` an earlier one at the same speed (its reduced
    machine and indicator), never one at another speed; and what it gives equals a fresh analysis
    of the same point (the reference: flyopt.analysis.analyse without ``like``)."""
    from flyopt import analysis
    from flyopt.studies.points import point_scene

    original = analysis.analyse
    calls = []

    def analyse(scene, model=None, like=None):
        result = original(scene, model, like=like)
        calls.append((scene.delta, scene.omega_mean, like, result))
        return result

    monkeypatch.setattr(analysis, "analyse", analyse)
    scene = flyopt.load(PROBLEMS / {"energy_mass": "slider-crank-press.toml", "dynamic": "motor-press.toml"}[model])
    frame = sweep(scene, {"speed": speeds, "delta": "0.05,0.1,0.15"}, workers=1)
    assert len(calls) == 6 and {c[3].model for c in calls} == {model}
    physics = {id(result): (delta, speed) for delta, speed, _, result in calls}
    seen = set()
    for delta, speed, like, result in calls:
        if speed in seen:
            assert like is not None and physics[id(like)][1] == speed and physics[id(like)][0] != delta
            assert result.machine._cache is like.machine._cache and result.indicator is like.indicator
        else:
            assert like is None
        seen.add(speed)
    monkeypatch.setattr(analysis, "analyse", original)
    for (delta, speed, _like, result), row in zip(calls, frame.itertuples()):
        fresh = original(point_scene(scene, {"delta": delta, "speed": speed}))
        assert row.delta == delta and row.speed == speed
        np.testing.assert_allclose(result.j_required, fresh.j_required, rtol=1e-12)
        np.testing.assert_allclose(
            [result.omega_max, result.omega_min, result.a_max],
            [fresh.omega_max, fresh.omega_min, fresh.a_max],
            rtol=1e-12,
        )
