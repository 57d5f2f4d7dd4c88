"""The cycle is analysed once per distinct physics; design-only variations reuse it.

A sweep, Pareto front or trade-off over the envelope, the material, the shaft,
H/B, the geometry or the objective changes nothing in the machine, so the
(exact, and on these scenes costly) analysis must not run again. Counted by
wrapping flyopt.analysis.analyse. Before, every sweep point of a
variable-inertia or motor scene was analysed afresh.
"""

import pytest
from conftest import PROBLEMS

import flyopt


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
