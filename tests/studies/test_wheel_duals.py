"""A sweep's whole wheels started from the neighbour's multipliers are IPOPT's optimum (issue 26).

Within a sweep's chunk each whole wheel's sqpmethod starts from the previous point's wheel and, since
issue 26's second round, from its multipliers too (:func:`flyopt.design.wheel_nlp._warm_duals`), each
kept only where its row still meets its bound at the start. The reference is an independent method:
every point solved by IPOPT alone (``flyopt.wheel_solver = "ipopt"``, no warm start: the IPOPT-only
models have no neighbours) to a tolerance of 1e-12, so that its wheel sits on its active bounds.

The sweeps run over δ upwards: each point needs less inertia than the one before, so the neighbour's
inertia row is slack at the start. Given that row's multiplier as it was, sqpmethod (which tests
feasibility and stationarity, not complementarity) reports Solve_Succeeded after 0 iterations at the
neighbour's wheel; the second test passes the multipliers unprojected and requires the complementarity
check of :func:`flyopt.design.wheel_nlp.solve` to catch it.
"""

from pathlib import Path

import pytest

from flyopt.design import wheel_nlp
from flyopt.io.scene import load
from flyopt.studies.sweep import sweep

PROBLEMS = Path(__file__).parents[2] / "problems"
#: IPOPT alone, to 1e-12 (its default 1e-8 leaves a wheel up to 7e-9 inside an active H/B bound).
REFERENCE = {"flyopt.wheel_solver": "ipopt", "ipopt.tol": 1e-12}
#: The mass and the objective, relative: IPOPT's optimum to 1e-9 (measured: 5.4e-11 at worst).
MASS = ("mass", "objective")
MASS_RTOL = 1e-9
#: Every reported dimension, relative: 1e-8, since where sqpmethod does not converge (a chunk's cold first
#: point at δ 0.03 here) IPOPT answers at its default tolerance, 1e-8, which leaves the wheel up to 7e-9
#: inside an active H/B bound (measured 3.6e-9 in H; 4.5e-11 where sqpmethod answered).
DIMS = ("d_outer", "d_inner", "h", "b")
DIMS_RTOL = 1e-8
CASES = [
    ("punch-press-wheel.toml", [0.03, 0.05, 0.08, 0.12, 0.17]),
    ("press-arms-wheel.toml", [0.05, 0.08, 0.12]),
]


@pytest.fixture
def dual_starts(monkeypatch):
    """Counts the warm starts given the neighbour's multipliers."""
    counts = {"dual": 0}
    original = wheel_nlp._warm_duals

    def counting(model, args):
        duals = original(model, args)
        counts["dual"] += duals is not None
        return duals

    monkeypatch.setattr(wheel_nlp, "_warm_duals", counting)
    return counts


def _same_as_ipopt(table, reference):
    for k in range(len(table)):
        row, ref = table.iloc[k], reference.iloc[k]
        assert row["status"] == ref["status"] == "designed"
        assert (row["best_material"], row["best_shaft"]) == (ref["best_material"], ref["best_shaft"])
        for names, rtol in ((MASS, MASS_RTOL), (DIMS, DIMS_RTOL)):
            for name in names:
                assert row[name] == pytest.approx(ref[name], rel=rtol, abs=0.0), (k, name)


@pytest.mark.parametrize(("scene", "deltas"), CASES)
def test_a_sweep_started_from_its_neighbours_multipliers_is_ipopts(scene, deltas, dual_starts):
    scene = load(PROBLEMS / scene)
    table = sweep(scene, {"delta": deltas}, workers=1)
    assert dual_starts["dual"] >= len(deltas) - 1  # the multipliers were really passed
    _same_as_ipopt(table, sweep(scene, {"delta": deltas}, workers=1, solver_options=REFERENCE))


def test_a_stale_multiplier_does_not_end_a_solve(monkeypatch):
    """The neighbour's multipliers passed as they were: the complementarity check refuses the 0-iteration
    'success' at the neighbour's wheel, and the solve goes on to the point's own wheel."""
    refused = {"n": 0}
    check = wheel_nlp._complementary

    def unprojected(model, args):
        kept = model.duals.get(wheel_nlp._wheel_key(args["x0"]))
        return None if kept is None else {"lam_x0": kept[0], "lam_g0": kept[1]}

    def counting(sol, args):
        ok = check(sol, args)
        refused["n"] += not ok
        return ok

    monkeypatch.setattr(wheel_nlp, "_warm_duals", unprojected)
    monkeypatch.setattr(wheel_nlp, "_complementary", counting)
    scene, deltas = load(PROBLEMS / CASES[0][0]), CASES[0][1]
    table = sweep(scene, {"delta": deltas}, workers=1)
    assert refused["n"] > 0
    _same_as_ipopt(table, sweep(scene, {"delta": deltas}, workers=1, solver_options=REFERENCE))
