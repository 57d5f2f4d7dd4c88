"""A sweep's warm-started whole wheels are the cold ones (issue 26).

Within a sweep's chunk each whole wheel's SQP starts from the wheel the
chunk's previous point designed for the same combination
(:func:`flyopt.design.wheel_design.neighbours`). A start is not an answer:
every point must come out as its own cold design, made alone (a one-point
table, no neighbour), to 1e-8 in every dimension; the Pareto front's points
likewise. The warm starts must really be taken (else these tests would
compare cold with cold), and a wheel designed outside a sweep must not
depend on one designed before it.
"""

import math
from pathlib import Path

import pandas as pd
import pytest

from flyopt.design import wheel_nlp
from flyopt.io.scene import load
from flyopt.studies.evaluate import evaluate_points
from flyopt.studies.pareto import pareto
from flyopt.studies.sweep import sweep

SCENE = Path(__file__).parents[2] / "problems" / "punch-press-wheel.toml"
#: Every reported dimension and the mass, relative.
COLUMNS = ("mass", "d_outer", "d_inner", "h", "b", "objective")
RTOL = 1e-8


@pytest.fixture
def warm_solves(monkeypatch):
    """Counts the whole-wheel solves that were given a neighbour's wheel (problem.warm)."""
    counts = {"warm": 0, "cold": 0}
    original = wheel_nlp.solve

    def counting(model, problem, label):
        counts["warm" if problem.warm is not None else "cold"] += 1
        return original(model, problem, label)

    monkeypatch.setattr(wheel_nlp, "solve", counting)
    return counts


def _cold(scene, row: dict) -> pd.Series:
    """One point designed alone: a one-point table, so no neighbour."""
    return evaluate_points(scene, pd.DataFrame({"point": [0], **{k: [v] for k, v in row.items()}})).iloc[0]


def _same(warm: pd.Series, cold: pd.Series) -> None:
    assert warm["status"] == cold["status"] == "designed"
    assert warm["best_material"] == cold["best_material"]
    assert warm["best_shaft"] == cold["best_shaft"]
    for name in COLUMNS:
        assert warm[name] == pytest.approx(cold[name], rel=RTOL, abs=0.0), name


def test_a_sweeps_warm_designs_are_the_cold_single_designs(warm_solves):
    scene = load(SCENE)
    deltas = [0.06, 0.09, 0.12, 0.15]
    table = sweep(scene, {"delta": deltas}, workers=1)
    assert warm_solves["warm"] >= len(deltas) - 1  # every point after the first started from its neighbour
    warm_solves["warm"] = 0
    for k, delta in enumerate(deltas):
        _same(table.iloc[k], _cold(scene, {"delta": delta}))
    assert warm_solves["warm"] == 0  # the single designs were cold


def test_the_pareto_front_is_its_points_designed_cold(warm_solves):
    scene = load(SCENE)
    front = pareto(scene, ("mass", "outer_diameter"), points=5)
    assert warm_solves["warm"] > 0
    assert len(front) >= 3
    for k in range(len(front)):
        row = front.iloc[k]
        if row["epsilon"] == row["d_outer"] and k == 0:  # the smallest wheel: designed alone by its own objective
            continue
        _same(row, _cold(scene, {"design.max_outer_diameter": row["epsilon"], "design.objective": "mass"}))


def test_the_neighbours_last_one_chunk(warm_solves):
    """Outside a sweep's chunk no design starts from an earlier one (flyopt solve's, and so the golden results)."""
    from flyopt.design import wheel_design

    scene = load(SCENE)
    evaluate_points(scene, pd.DataFrame({"point": [0, 1], "delta": [0.08, 0.1]}))
    assert warm_solves["warm"] > 0
    assert wheel_design._NEIGHBOURS.get() is None


def test_a_fronts_inferred_infeasibilities_are_ipopts_own_verdicts(monkeypatch):
    """The front runs from the largest envelope down and does not solve an NLP whose limits are all as tight
    or tighter than one IPOPT found infeasible (flyopt.design.wheel_design._proven_infeasible): each NLP left
    unsolved so, solved cold here (no neighbour: the thin ring, SQP then IPOPT), is infeasible by IPOPT."""
    import dataclasses

    from flyopt.design import wheel_design
    from flyopt.errors import SolverFailed

    inferred, current = [], {}
    settle, proven = wheel_design._settle, wheel_design._proven_infeasible

    def settling(model, *args, **kwargs):
        current["model"] = model
        return settle(model, *args, **kwargs)

    def proving(problem, proofs):
        proof = proven(problem, proofs)
        if proof is not None:
            inferred.append((current["model"], problem, proof))
        return proof

    monkeypatch.setattr(wheel_design, "_settle", settling)
    monkeypatch.setattr(wheel_design, "_proven_infeasible", proving)
    pareto(load(SCENE), ("mass", "outer_diameter"), points=25)
    assert len(inferred) >= 10  # (measured 20: the ductile iron's capped branches, the keyed iron's smallest wheels)
    for model, problem, proof in inferred:
        assert problem.envelope < proof.envelope
        cold = dataclasses.replace(problem, warm=None, start=None, ipopt_first=False)
        with pytest.raises(SolverFailed) as failed:
            wheel_nlp.solve(model, cold, "inferred")
        assert failed.value.status == "Infeasible_Problem_Detected"


def test_an_nlp_is_within_an_infeasible_one_only_where_every_limit_is_as_tight():
    """Nestedness (wheel_design._within): a larger envelope, a higher allowable, a looser cap or any other
    changed number (the inertia) leaves the feasible set no longer inside the proof's."""
    import dataclasses

    from flyopt.design import wheel_design
    from flyopt.design.wheel_nlp import WheelProblem

    proof = WheelProblem(
        j_shaft=2.0,
        omega=150.0,
        density=7100.0,
        poisson=0.28,
        torque=100.0,
        bore=0.055,
        allowable={"rim": 50e6, "web": 50e6},
        envelope=0.5,
        max_width=0.2,
        max_rim_speed=math.inf,
        hb_ratio=(0.5, 2.0),
        d_mean=None,
        min_wall=0.008,
        caps={"h": 0.03},
    )
    same = dataclasses.replace(proof, warm={"d_outer": 0.4}, ipopt_first=True)  # a start is no limit
    assert wheel_design._within(same, proof)
    assert wheel_design._within(dataclasses.replace(proof, envelope=0.45, allowable={"rim": 40e6, "web": 50e6}), proof)
    assert wheel_design._within(dataclasses.replace(proof, caps={"h": 0.02, "b": 0.03}), proof)
    assert not wheel_design._within(dataclasses.replace(proof, envelope=0.55), proof)
    assert not wheel_design._within(dataclasses.replace(proof, allowable={"rim": 60e6, "web": 50e6}), proof)
    assert not wheel_design._within(dataclasses.replace(proof, allowable={"rim": 50e6}), proof)  # web unlimited
    assert not wheel_design._within(dataclasses.replace(proof, caps=None), proof)
    assert not wheel_design._within(dataclasses.replace(proof, j_shaft=1.9), proof)
