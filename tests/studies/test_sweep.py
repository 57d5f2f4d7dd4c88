"""Tests of flyopt.studies.sweep and the modules it joins: the --vary grammar, sweeps against individual solves,
files, resume after a crash, worker processes and a Dask LocalCluster.

The reference for every swept point is ``flyopt.solve`` of the scene of that
point (``point_scene``): the full pipeline, cycle analysed anew and every
combination designed by IPOPT. Masses agree within 1e-6 (the issue's
agreement; the closed form and IPOPT both reach ~1e-10).
"""

import importlib
import json
import math
import re

import numpy as np
import pandas as pd
import pytest
from conftest import PROBLEMS, run_flyopt
from numpy.testing import assert_allclose

import flyopt
from flyopt.cli.studies import sweep_main
from flyopt.design import nlp
from flyopt.errors import SceneError
from flyopt.io.sweep_spec import load_sweep, parse_vary
from flyopt.outputs.results import CORE_INPUTS, RESULT_COLUMNS, read_results
from flyopt.studies.plan import plan_sweep
from flyopt.studies.points import point_scene
from flyopt.studies.sweep import SUMMARY_COLUMNS, sweep

sweep_module = importlib.import_module("flyopt.studies.sweep")  # the module (flyopt.sweep is the function)

RPM = math.pi / 30.0
PUNCH = flyopt.load(PROBLEMS / "punch-press.toml")  # 3 materials (one user), 3 shafts
SHEAR = flyopt.load(PROBLEMS / "shear-press.toml")  # 2 materials, 1 shaft, envelope


def plain(summary):
    """A sweep's summary (the frame returned with an output file) with its categoricals as text."""
    assert list(summary.columns) == list(SUMMARY_COLUMNS)
    assert isinstance(summary["status"].dtype, pd.CategoricalDtype)
    return summary.astype({"status": str, "method": str})


def check_against_individual_solves(scene, frame, rtol=1e-6):
    """Every row equals flyopt.solve of its point's scene with every combination by IPOPT
    (status, winner, mass): the sweep's closed form against an independent solver."""
    inputs = [c for c in frame.columns if c in CORE_INPUTS or c not in RESULT_COLUMNS]
    for row in frame.to_dict("records"):
        point = {k: row[k] for k in inputs if k != "point"}
        solution = flyopt.solve(point_scene(scene, point), design_method="ipopt")
        assert row["status"] == solution.status, (point, row["message"])
        assert_allclose(row["j_margin"], solution.analysis.j_margin, rtol=1e-12)
        if solution.status == "designed":
            best = solution.design.best
            assert_allclose(row["mass"], best.mass, rtol=rtol)
            same = best
            if (row["best_material"], row["best_shaft"]) != (best.material, best.shaft):
                # an exact tie (e.g. discs of two materials at the envelope, 8 J / D^2):
                # the individual solve's design of the sweep's winner is as light
                (same,) = [
                    c
                    for c in solution.design.candidates
                    if (c.material, c.shaft) == (row["best_material"], row["best_shaft"])
                ]
                assert_allclose(same.mass, best.mass, rtol=1e-9)
            assert_allclose(row["d_outer"], same.dims.d_outer, rtol=1e-5)
            assert row["n_feasible"] == sum(c.feasible for c in solution.design.candidates)
        else:
            assert np.isnan(row["mass"]) and not row["feasible"]


# --------------------------------------------------------------------------
# The --vary grammar
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text, field, expected",
    [
        ("speed=300,600,1200rpm", "speed", [300 * RPM, 600 * RPM, 1200 * RPM]),
        ("speed=300 rpm, 20", "speed", [300 * RPM, 20.0]),  # a plain number is SI
        ("delta=0.01:0.1:log3", "delta", [0.01, math.sqrt(0.01 * 0.1), 0.1]),
        ("delta=1/20,1/10", "delta", [0.05, 0.1]),
        ("envelope=0.4:1.2:5 m", "design.max_outer_diameter", [0.4, 0.6, 0.8, 1.0, 1.2]),
        ("design.max_outer_diameter=400:1200:3 mm", "design.max_outer_diameter", [0.4, 0.8, 1.2]),
        ("max_width=0.1,none", "design.max_width", [0.1, math.nan]),
        ("hb_ratio=2", "design.hb_ratio", [2.0]),
        ("torque.scale=0.5:2:log3", "torque.scale", [0.5, 1.0, 2.0]),
        ("inertia=0,3 kg*m^2", "inertia", [0.0, 3.0]),
        ("shaft.motor.speed_ratio=12:36:3", "shaft.motor.speed_ratio", [12.0, 24.0, 36.0]),
        ("material.cast_iron.density=7.1,7.3 g/cm^3", "material.cast_iron.density", [7100.0, 7300.0]),
        ("material=cast_iron, ductile_iron", "material", ["cast_iron", "ductile_iron"]),
        ("shaft=motor,crankshaft", "shaft", ["motor", "crankshaft"]),
        ("geometry=rim,disc", "design.geometry", ["rim", "disc"]),
    ],
)
def test_vary_grammar(text, field, expected):
    (axis,) = parse_vary(PUNCH, [text])
    assert axis.field == field
    if isinstance(expected[0], str):
        assert list(axis.values) == expected
    else:
        assert_allclose(axis.values, expected, rtol=1e-14)


def test_vary_from_toml_values_numbers_and_lists():
    axes = parse_vary(
        PUNCH,
        {
            "delta": 0.05,
            "speed": ["30 rpm", 60 * RPM],
            "material": ["cast_iron", "cast_steel"],
            "design.max_width": [0.1, None],
        },
        where="sweep.vary",
    )
    assert [a.values for a in axes][:2] == [(0.05,), (30 * RPM, 60 * RPM)]
    assert axes[2].values == ("cast_iron", "cast_steel")
    assert axes[3].values[0] == 0.1 and math.isnan(axes[3].values[1])


@pytest.mark.parametrize(
    "text, field, match",
    [
        ("deltaa=0.1", "--vary deltaa", r"unknown sweep field \(did you mean 'delta'\?\); allowed: delta"),
        ("colour=red", "--vary colour", "unknown sweep field; allowed: .*shaft.<name>.speed_ratio"),
        ("delta", "--vary", "expected FIELD=VALUES"),
        ("=0.1", "--vary", "field name is missing"),
        ("delta=", "--vary delta", "no values given"),
        ("delta=0.01:0.1", "--vary delta", "a grid range needs a count"),
        ("delta=0.01:0.1:lg4", "--vary delta", "the third part must be a count n or logn"),
        ("delta=0.01:0.1:4:5", "--vary delta", "a range is a:b:n"),
        ("delta=0.01:0.1:0", "--vary delta", "the count must be at least 1"),
        ("delta=2.5", "--vary delta", "out of range: coefficient of speed fluctuation"),
        ("delta=-0.1:0.1:log3", "--vary delta", "out of range"),
        ("delta=0.1,,0.2", "--vary delta", "an empty value"),
        ("speed=100 m", "--vary speed", "wrong dimension: expected a rotational speed"),
        ("speed=fast", "--vary speed", "cannot read 'fast'"),
        ("envelope=-1 m", "--vary envelope", "out of range"),
        ("material=unobtainium", "--vary material", "unknown material 'unobtainium'"),
        ("material=cast_irn", "--vary material", "did you mean 'cast_iron'"),
        ("shaft=main", "--vary shaft", "unknown shaft 'main'"),
        ("geometry=0.1:0.2:3", "--vary geometry", "a range needs numbers"),
        ("shaft.main.speed_ratio=2", "--vary shaft.main.speed_ratio", "unknown shaft 'main'"),
        ("material.cast_iron.colour=1", "--vary material.cast_iron.colour", "a material's field"),
        ("material.steel.density=1", "--vary material.steel.density", "unknown material 'steel'"),
    ],
)
def test_vary_errors_name_the_field(text, field, match):
    with pytest.raises(SceneError, match=match) as info:
        parse_vary(PUNCH, [text])
    assert info.value.field == field
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "vary, field, match",
    [
        (["delta=0.1", "machine.delta=0.2"], "--vary machine.delta", "varied twice"),
        (["hb_ratio=2", "hb_min=1.5"], "--vary design.hb_ratio", "not both"),
        (["hb_min=1.8:2.4:4"], "--vary design.hb_min", r"H/B min 2.2 exceeds max 2 at point 2 \(and 1 other points\)"),
        (["objective=cost"], "--vary design", r"|--vary design.objective"),
        (["geometry=disc", "objective=outer_diameter", "max_width=none"], "--vary design", "needs max_width"),
    ],
)
def test_plan_errors(vary, field, match):
    with pytest.raises(SceneError, match=match) as info:
        plan_sweep(PUNCH, vary)
    assert info.value.field.startswith(field.split("|")[0])


def test_cost_objective_needs_costs():
    with pytest.raises(SceneError, match="'cost' needs a cost per kg.*cast_iron") as info:
        plan_sweep(SHEAR, ["objective=cost"])
    assert info.value.field == "--vary design.objective"
    # with costs given per material, it is accepted
    plan_sweep(SHEAR, ["objective=cost", "material.cast_iron.cost=1,2", "material=cast_iron"])


def test_grid_is_full_factorial_first_field_slowest():
    plan = plan_sweep(PUNCH, ["delta=0.05,0.1", "speed=30,60,90rpm", "material=cast_iron,cast_steel"])
    points = plan.points
    assert len(points) == 12 and list(points["point"]) == list(range(12))
    assert list(points["delta"][:6]) == [0.05] * 6
    assert list(points["material"][:2]) == ["cast_iron", "cast_steel"]
    assert len(points.drop(columns="point").drop_duplicates()) == 12


def test_latin_hypercube_is_stratified_and_reproducible():
    vary = {"delta": "0.01:0.1:log", "speed": "30:120 rpm", "material": "cast_iron,cast_steel"}
    plan = plan_sweep(PUNCH, vary, samples=50, seed=3)
    points = plan.points
    assert len(points) == 50
    # one sample in each of the 50 strata of every range (log-uniform for delta)
    u_delta = np.log(points["delta"] / 0.01) / np.log(10.0)
    u_speed = (points["speed"] - 30 * RPM) / (90 * RPM)
    for u in (u_delta, u_speed):
        assert sorted(np.floor(u * 50).astype(int)) == list(range(50))
    assert points["material"].value_counts().to_dict() == {"cast_iron": 25, "cast_steel": 25}
    again = plan_sweep(PUNCH, vary, samples=50, seed=3).points
    pd.testing.assert_frame_equal(points, again)
    with pytest.raises(SceneError, match="at least one varied field"):
        plan_sweep(PUNCH, {}, samples=5)


# --------------------------------------------------------------------------
# Sizes, seeds and options: refused before anything is made
# --------------------------------------------------------------------------


def peak_bytes(call):
    """Peak memory Python allocates while ``call()`` runs [bytes] (tracemalloc)."""
    import tracemalloc

    tracemalloc.start()
    try:
        call()
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return peak


@pytest.mark.parametrize(
    "vary, samples, field",
    [
        (["delta=0.01:0.1:1000000000"], None, "--vary delta"),  # 7.45 GB of values
        (["delta=0.01:0.1:20000001"], None, "--vary delta"),  # one past the cap
        (["delta=0.01:0.1:5000", "speed=1:2:5000"], None, "--vary speed"),  # 25e6 together
        ({"delta": "0.01:0.1"}, 10**9, "--samples"),
    ],
)
def test_too_many_points_refused_before_allocating(vary, samples, field):
    """Regression (issue 11): a grid or a sample count of 1e9 allocated 7.45 GB before
    the cap was checked, then MemoryError. The cap is checked on the counts first: the
    refusal is one line naming the field and the cap, and allocates (almost) nothing."""
    from flyopt.studies.plan import MAX_POINTS

    def plan():
        with pytest.raises(SceneError) as info:
            plan_sweep(PUNCH, vary, samples=samples)
        assert info.value.field == field and str(MAX_POINTS) in info.value.message
        assert "\n" not in str(info.value)

    # 2 MB: far below the 160 MB of the smallest grid refused here (2e7 float64)
    assert peak_bytes(plan) < 2e6


def test_samples_over_the_cap_in_a_sweep_table_name_the_file(tmp_path):
    from flyopt.studies.sweep import check_sweep

    path = scene_with_sweep(tmp_path, '[sweep]\nsamples = 1000000000\n[sweep.vary]\ndelta = "0.01:0.1"\n')
    scene, options = load_sweep(path)
    with pytest.raises(SceneError, match="more than the 20000000") as info:
        check_sweep(scene, options)
    assert info.value.field == "sweep.samples" and info.value.source == str(path)


@pytest.mark.parametrize("seed", [-1, 1.5, True, "7", 2**63])
def test_bad_seed_is_refused_by_the_plan(seed):
    """Regression (issue 11): ``--seed -1`` ended in numpy's traceback; 2**63, the first seed a 64-bit signed
    integer cannot hold, in "Python int too large to convert to C long" (exit 1) with the sweep's parts left
    behind, so that a rerun refused to start."""
    with pytest.raises(SceneError, match="must be a whole number from 0 to 9223372036854775807") as info:
        plan_sweep(PUNCH, {"delta": "0.01:0.1"}, samples=5, seed=seed)
    assert info.value.field == "--seed"


def test_latin_hypercube_without_a_seed_records_the_one_it_drew(tmp_path):
    """Regression (issue 11): a Latin hypercube run without a seed could not be repeated.
    The seed drawn is in the plan, in the table's ``seed`` column (so in the file, CSV
    or Parquet alike) and in ``attrs``; rerun with it, the points are the same."""
    vary = {"delta": "0.02:0.2:log", "speed": "30:120 rpm", "material": "cast_iron,cast_steel"}
    first, second = plan_sweep(PUNCH, vary, samples=12), plan_sweep(PUNCH, vary, samples=12)
    assert isinstance(first.seed, int) and 0 <= first.seed < 2**63
    assert first.seed != second.seed  # drawn afresh (a collision has odds 2**-63)
    pd.testing.assert_frame_equal(plan_sweep(PUNCH, vary, samples=12, seed=first.seed).points, first.points)
    out = tmp_path / "study.csv"
    frame = sweep(PUNCH, vary, samples=12, output=out)
    recorded = read_results(out)["seed"]
    assert recorded.nunique() == 1 and int(recorded.iloc[0]) == frame.attrs["sweep"]["seed"]
    again = sweep(PUNCH, vary, samples=12, seed=int(recorded.iloc[0]))
    assert list(again.columns[:2]) == ["point", "seed"]
    pd.testing.assert_frame_equal(again, read_results(out))
    assert "seed" not in sweep(PUNCH, {"delta": "0.1,0.2"}).columns  # a grid has no seed


def test_resume_of_a_latin_hypercube_reuses_its_recorded_seed(tmp_path):
    out = tmp_path / "study.parquet"
    vary = {"delta": "0.02:0.2:log", "speed": "30:120 rpm"}
    first = sweep(PUNCH, vary, samples=12, output=out, chunk_size=4, max_chunks=1)
    done = sweep(PUNCH, vary, samples=12, output=out, chunk_size=4, resume=True)
    assert done.attrs["sweep"]["chunks_reused"] == [0]
    assert done.attrs["sweep"]["seed"] == first.attrs["sweep"]["seed"]
    pd.testing.assert_frame_equal(
        read_results(out), sweep(PUNCH, vary, samples=12, chunk_size=4, seed=first.attrs["sweep"]["seed"])
    )


@pytest.mark.parametrize(
    "texts, field",
    [
        (["delta=0.1", "delta=0.2"], "--vary delta"),
        (["envelope=1 m", "design.max_outer_diameter=2 m"], "--vary design.max_outer_diameter"),
        (["material=cast_iron", "materials=cast_steel"], "--vary materials"),
    ],
)
def test_a_field_given_twice_is_refused(texts, field):
    """Regression (issue 11): a repeated ``--vary`` for one field (or an alias of it)
    silently kept the last. ``vary_from_texts`` (what the command line calls on its
    --vary list) and ``parse_vary`` refuse it, naming the second."""
    from flyopt.io.sweep_spec import vary_from_texts

    for call in (lambda: vary_from_texts(PUNCH, texts), lambda: parse_vary(PUNCH, texts)):
        with pytest.raises(SceneError, match="is varied twice") as info:
            call()
        assert info.value.field == field
    assert vary_from_texts(PUNCH, ["delta=0.1,0.2", "envelope=1 m"]) == {"delta": "0.1,0.2", "envelope": "1 m"}


@pytest.mark.parametrize(
    "table, field, words",
    [
        ('method = "fast"', "sweep.method", "'fast' is not known (allowed: auto, closed_form, ipopt)"),
        ("workers = 0", "sweep.workers", "must be 'auto' or a whole number from 1 to 256, got 0"),
        ('workers = "many"', "sweep.workers", "must be 'auto' or a whole number from 1 to 256, got 'many'"),
        ("workers = 100000", "sweep.workers", "from 1 to 256, got 100000"),  # a process a chunk, 150 MB each
        ('output = "study.xlsx"', "sweep.output", "must end in .parquet or .csv"),
        ("chunk_size = 0", "sweep.chunk_size", "must be a whole number >= 1"),
        ("seed = -1", "sweep.seed", "must be a whole number from 0 to 9223372036854775807"),
    ],
)
def test_sweep_table_options_are_checked_when_read(tmp_path, table, field, words):
    """Regression (issue 11): ``flyopt check`` said "ok" for [sweep] tables that
    ``flyopt sweep`` then refused; the options are checked where the table is read."""
    path = scene_with_sweep(tmp_path, f'[sweep]\n{table}\n[sweep.vary]\ndelta = "0.1,0.2"\n')
    with pytest.raises(SceneError) as info:
        load_sweep(path)
    assert (info.value.field, info.value.source) == (field, str(path))
    assert words in info.value.message


@pytest.mark.parametrize(
    "vary, field, words",
    [
        ('delta = "0.1:0.2"', "sweep.vary.delta", "a grid range needs a count"),
        ('deltaa = "0.1"', "sweep.vary.deltaa", "unknown sweep field"),
        ('hb_min = "1.8:2.4:4"', "sweep.vary.design.hb_min", "exceeds max"),
        ('objective = "cost"', "sweep.vary.design.objective", "needs a cost per kg"),
    ],
)
def test_check_sweep_finds_what_sweep_refuses(tmp_path, vary, field, words):
    """``check_sweep`` (what ``flyopt check`` calls) refuses the fields, values and
    points that the sweep refuses, with the same message, naming the file."""
    from flyopt.studies.sweep import check_sweep

    path = scene_with_sweep(tmp_path, f"[sweep.vary]\n{vary}\n")
    scene, options = load_sweep(path)
    with pytest.raises(SceneError) as info:
        check_sweep(scene, options)
    assert (info.value.field, info.value.source) == (field, str(path))
    assert words in info.value.message
    with pytest.raises(SceneError) as ran:
        sweep(scene, options["vary"])
    assert ran.value.message == info.value.message
    plan = check_sweep(*load_sweep(scene_with_sweep(tmp_path)))  # a sound table: its plan
    assert len(plan.points) == 3 * 2 * 2 * 2


def test_flyopt_sweep_is_the_function_and_the_modules_are_reachable():
    """Regression (issue 11): the function ``flyopt.sweep`` shadowed the module, so
    ``flyopt.sweep.read_results`` failed; the module is now flyopt.studies.sweep and the
    file functions are in flyopt.outputs.results."""
    import flyopt.outputs.results
    import flyopt.studies.sweep

    assert callable(flyopt.sweep) and flyopt.sweep is sweep_module.sweep
    assert flyopt.studies.sweep is sweep_module
    assert flyopt.outputs.results.read_results is read_results


def test_declared_scipy_floor_has_latin_hypercube_rng():
    """Regression (issue 11): plan_sweep calls ``qmc.LatinHypercube(rng=...)``, a keyword
    SciPy added in 1.15.0 (SPEC 7; before it was ``seed``, which draws other samples
    for the same integer), while pyproject.toml declared scipy>=1.10."""
    import re
    from pathlib import Path

    import tomllib

    pyproject = tomllib.loads((Path(__file__).parents[2] / "pyproject.toml").read_text())
    (floor,) = [
        re.match(r"scipy\s*>=\s*([\d.]+)", d).group(1)
        for d in pyproject["project"]["dependencies"]
        if d.startswith("scipy")
    ]
    assert tuple(int(x) for x in floor.split(".")[:2]) >= (1, 15)


# --------------------------------------------------------------------------
# Sweeps against individual solves
# --------------------------------------------------------------------------


def test_grid_sweep_matches_individual_solves_punch_press():
    """27 points (delta x speed x material) of a 3-shaft scene with envelope,
    width limit and a user material."""
    frame = sweep(PUNCH, ["delta=0.005:0.2:log3", "speed=30,60,120rpm", "material=cast_iron,cast_steel,ductile_iron"])
    assert len(frame) == 27
    assert set(frame["method"]) == {"closed_form"}
    assert (frame["n_combinations"] == 3).all()
    assert {"designed", "infeasible"} <= set(frame["status"])
    check_against_individual_solves(PUNCH, frame)
    designed = frame[frame["status"] == "designed"]
    assert (designed["binding"].str.contains("inertia")).all()
    assert_allclose(
        designed["hoop_stress"],
        designed["rim_speed"] ** 2
        * np.where(
            designed["best_material"] == "cast_iron",
            7200.0,
            np.where(designed["best_material"] == "cast_steel", 7800.0, 7100.0),
        ),
        rtol=1e-14,
    )


def test_sweep_of_design_fields_matches_individual_solves():
    """Shaft ratio, H/B, width limit, pinned diameter and geometry, including
    not-needed points (J_c large) and infeasible ones."""
    frame = sweep(
        PUNCH,
        {
            "shaft.motor.speed_ratio": "12,36",
            "design.hb_ratio": "1.5,2.5",
            "design.max_width": "0.02,none",
            "inertia": "0,2000",
        },
    )
    assert set(frame["status"]) == {"designed", "infeasible", "not_needed"}
    check_against_individual_solves(PUNCH, frame)
    pinned = sweep(SHEAR, {"design.d_mean": "0.3,0.45,0.55", "geometry": "rim,thin_rim,disc", "max_width": "0.05,none"})
    assert {"designed", "infeasible"} <= set(pinned["status"])
    check_against_individual_solves(SHEAR, pinned)


@pytest.mark.parametrize("scene_file", ["shear-press.toml", "compressor.toml", "example1-net-areas.toml"])
def test_torque_scale_is_exact(scene_file):
    """Scaling both torques (a table, an expression, net areas) scales A_max: the
    sweep's k A_max equals the analysis of the scaled scene."""
    scene = flyopt.load(PROBLEMS / scene_file)
    frame = sweep(scene, ["torque.scale=0.5,1,3.7"])
    for row in frame.to_dict("records"):
        analysis = flyopt.analyse(point_scene(scene, {"torque.scale": row["torque.scale"]}))
        assert_allclose(row["a_max"], analysis.a_max, rtol=1e-12)
        if analysis.power is not None:
            assert_allclose(row["power"], analysis.power, rtol=1e-12)
    check_against_individual_solves(scene, frame)


def test_outer_diameter_objective_falls_back_to_ipopt():
    frame = sweep(SHEAR, {"objective": "mass,outer_diameter", "delta": "0.02,0.05"})
    methods = dict(zip(frame["design.objective"], frame["method"]))
    assert methods == {"mass": "closed_form", "outer_diameter": "ipopt"}
    ipopt = frame[frame["method"] == "ipopt"]
    assert (ipopt["solver_status"] == "Solve_Succeeded").all() and (ipopt["iterations"] > 0).all()
    assert frame.loc[frame["method"] == "closed_form", "iterations"].isna().all()  # no iterations: null
    check_against_individual_solves(SHEAR, frame)
    with pytest.raises(SceneError, match="closed form does not cover"):
        sweep(SHEAR, {"objective": "outer_diameter"}, method="closed_form")


def test_closed_form_and_ipopt_sweeps_agree():
    vary = {"delta": "0.01:0.3:log4", "speed": "20,60,200rpm", "max_width": "0.05,none", "geometry": "rim,thin_rim"}
    closed = sweep(PUNCH, vary)
    ipopt = sweep(PUNCH, vary, method="ipopt")
    assert set(closed["method"]) == {"closed_form"} and set(ipopt["method"]) == {"ipopt"}
    assert list(closed["status"]) == list(ipopt["status"])
    assert list(closed["best_material"]) == list(ipopt["best_material"])
    assert_allclose(closed["mass"], ipopt["mass"], rtol=1e-6)


def test_failed_solve_is_a_failed_row_not_a_design():
    """IPOPT stopped after 2 iterations: status failed with IPOPT's status, no
    mass, and the sweep goes on (the closed-form points are designed)."""
    frame = sweep(
        SHEAR, {"objective": "mass,outer_diameter", "delta": "0.02,0.05"}, solver_options={"ipopt.max_iter": 2}
    )
    failed = frame[frame["design.objective"] == "outer_diameter"]
    assert (failed["status"] == "failed").all() and not failed["feasible"].any()
    assert (failed["solver_status"] == "Maximum_Iterations_Exceeded").all()
    assert failed["mass"].isna().all() and failed["best_material"].isna().all()  # no value: null
    assert failed["message"].str.contains("did not converge").all()
    assert (frame.loc[frame["design.objective"] == "mass", "status"] == "designed").all()


def test_nlp_built_once_per_structure_not_per_point(monkeypatch):
    import casadi

    builds = []
    original = casadi.nlpsol

    def counting(*args, **kwargs):
        builds.append(args[0])
        return original(*args, **kwargs)

    nlp.clear_model_cache()
    monkeypatch.setattr(casadi, "nlpsol", counting)
    frame = sweep(PUNCH, {"delta": "0.02:0.2:log6", "speed": "30,60,120rpm"}, method="ipopt")
    assert (frame["status"] == "designed").sum() == 18
    assert len(builds) == 1, builds


def test_cycle_analysed_once(monkeypatch):
    import flyopt.analysis

    calls = []
    original = flyopt.analysis.analyse
    monkeypatch.setattr(flyopt.analysis, "analyse", lambda s, **kw: calls.append(1) or original(s, **kw))
    scene = flyopt.load(PROBLEMS / "punch-press.toml")  # a scene object of its own: analyses are
    sweep(scene, {"delta": "0.02:0.2:log10", "speed": "30,60,120rpm", "torque.scale": "1,2"})  # memoized per scene
    assert len(calls) == 1


def test_row_holds_every_input_and_result_field():
    frame = sweep(PUNCH, ["delta=0.05", "material=cast_steel"])
    assert list(frame.columns[: 1 + len(CORE_INPUTS)]) == ["point", *CORE_INPUTS]
    assert "material" in frame.columns
    assert list(frame.columns[-len(RESULT_COLUMNS) :]) == list(RESULT_COLUMNS)
    row = frame.iloc[0]
    assert row["speed"] == PUNCH.omega_mean and row["design.max_width"] == 0.2
    assert row["binding"] and row["best_material"] == "cast_steel"


# --------------------------------------------------------------------------
# Files, resume
# --------------------------------------------------------------------------

VARY = {"delta": "0.02:0.2:log5", "speed": "30,60rpm", "objective": "mass,outer_diameter"}


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_output_round_trip(tmp_path, suffix):
    """The file streamed chunk by chunk holds the table the sweep gives in memory; the
    frame returned with an output is the summary of it."""
    out = tmp_path / f"study{suffix}"
    summary = sweep(PUNCH, VARY, output=out, chunk_size=7)
    assert out.exists() and not (tmp_path / f"study{suffix}.parts").exists()
    back = read_results(out)
    in_memory = sweep(PUNCH, VARY, chunk_size=7)
    assert not in_memory.attrs["sweep"]["summary"] and summary.attrs["sweep"]["summary"]
    pd.testing.assert_frame_equal(back, in_memory)
    pd.testing.assert_frame_equal(plain(summary), in_memory[list(SUMMARY_COLUMNS)])
    assert set(back["status"]) == {"designed"} and set(back["method"]) == {"closed_form", "ipopt"}


def test_output_suffix_checked(tmp_path):
    with pytest.raises(SceneError, match="must end in .parquet or .csv"):
        sweep(PUNCH, VARY, output=tmp_path / "study.xlsx")


def test_resume_after_stopping_and_after_a_lost_part(tmp_path):
    out = tmp_path / "study.parquet"
    whole = sweep(PUNCH, VARY, chunk_size=4)
    first = sweep(PUNCH, VARY, output=out, chunk_size=4, max_chunks=3)
    info = first.attrs["sweep"]
    assert not info["complete"] and info["chunks"] == 5 and info["chunks_run"] == [0, 1, 2]
    parts = tmp_path / "study.parquet.parts"
    assert sorted(p.name for p in parts.iterdir()) == [
        "chunk-00000.parquet",
        "chunk-00001.parquet",
        "chunk-00002.parquet",
        "lock",
        "sweep.json",
    ]
    assert not out.exists()
    pd.testing.assert_frame_equal(plain(first), whole[list(SUMMARY_COLUMNS)].iloc[:12])
    # a rerun without --resume refuses to start over on top of the parts
    with pytest.raises(SceneError, match="resume it"):
        sweep(PUNCH, VARY, output=out, chunk_size=4)
    # a part lost (e.g. the disk was cleaned while the sweep ran): only it reruns
    (parts / "chunk-00001.parquet").unlink()
    done = sweep(PUNCH, VARY, output=out, chunk_size=4, resume=True)
    info = done.attrs["sweep"]
    assert info["complete"] and info["chunks_run"] == [1, 3, 4] and info["chunks_reused"] == [0, 2]
    pd.testing.assert_frame_equal(plain(done), whole[list(SUMMARY_COLUMNS)])
    pd.testing.assert_frame_equal(read_results(out), whole)
    assert not parts.exists()


def test_resume_after_a_crash(tmp_path, monkeypatch):
    """A chunk raises: the finished chunks are on disk, the crash loses the chunk
    in flight only, and --resume completes the sweep."""
    out = tmp_path / "study.csv"
    original = sweep_module.evaluate_chunk
    calls = []

    def crashing(ctx, points):
        calls.append(1)
        if len(calls) == 3:
            raise MemoryError("simulated crash")
        return original(ctx, points)

    monkeypatch.setattr(sweep_module, "evaluate_chunk", crashing)
    with pytest.raises(MemoryError):
        sweep(PUNCH, VARY, output=out, chunk_size=4, workers=1)
    parts = tmp_path / "study.csv.parts"
    assert sorted(p.name for p in parts.glob("chunk-*")) == ["chunk-00000.parquet", "chunk-00001.parquet"]
    monkeypatch.setattr(sweep_module, "evaluate_chunk", original)
    done = sweep(PUNCH, VARY, output=out, chunk_size=4, resume=True)
    assert done.attrs["sweep"]["chunks_run"] == [2, 3, 4]
    pd.testing.assert_frame_equal(read_results(out), sweep(PUNCH, VARY, chunk_size=4))


def test_resume_refuses_parts_of_another_sweep(tmp_path):
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, output=out, chunk_size=4, max_chunks=1)
    other = dict(VARY, delta="0.02:0.2:log6")
    with pytest.raises(SceneError, match="come from a different sweep") as info:
        sweep(PUNCH, other, output=out, chunk_size=4, resume=True)
    assert info.value.field == "--resume"
    manifest = json.loads((tmp_path / "study.parquet.parts" / "sweep.json").read_text())
    assert manifest["points"] == 20 and manifest["chunks"] == 5


# --------------------------------------------------------------------------
# Parallel: processes and Dask
# --------------------------------------------------------------------------


def test_worker_processes_give_the_serial_result():
    serial = sweep(PUNCH, VARY, chunk_size=4, workers=1)
    parallel = sweep(PUNCH, VARY, chunk_size=4, workers=2)
    assert parallel.attrs["sweep"]["mode"] == "processes"
    pd.testing.assert_frame_equal(parallel, serial)


def test_dask_local_cluster_streams_parts_and_gives_the_serial_result(tmp_path):
    from dask.distributed import Client, LocalCluster

    out = tmp_path / "study.parquet"
    serial = sweep(PUNCH, VARY, chunk_size=4, workers=1)
    with (
        LocalCluster(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as cluster,
        Client(cluster) as client,
    ):
        first = sweep(PUNCH, VARY, chunk_size=4, scheduler=client, output=out, max_chunks=2)
        assert first.attrs["sweep"]["mode"] == "dask"
        assert len(list((tmp_path / "study.parquet.parts").glob("chunk-*"))) == 2
        done = sweep(PUNCH, VARY, chunk_size=4, scheduler=cluster, output=out, resume=True)
    assert done.attrs["sweep"]["chunks_run"] == [2, 3, 4]
    pd.testing.assert_frame_equal(plain(done), serial[list(SUMMARY_COLUMNS)])
    pd.testing.assert_frame_equal(read_results(out), serial)


# --------------------------------------------------------------------------
# [sweep] tables and the command line
# --------------------------------------------------------------------------

SWEEP_TABLE = """
[sweep]
output = "study.csv"
[sweep.vary]
delta = "0.02:0.2:log3"
speed = "30,60rpm"
"shaft.motor.speed_ratio" = [12, 24]
[sweep.vary.design]
max_width = ["0.05 m", "none"]
"""


def scene_with_sweep(tmp_path, table=SWEEP_TABLE):
    path = tmp_path / "press.toml"
    path.write_text((PROBLEMS / "punch-press.toml").read_text() + table, encoding="utf-8")
    return path


def test_sweep_table_in_a_scene_file(tmp_path):
    scene, options = load_sweep(scene_with_sweep(tmp_path))
    assert (scene.title, scene.omega_mean, scene.shafts) == (PUNCH.title, PUNCH.omega_mean, PUNCH.shafts)
    assert options == {
        "output": str(tmp_path / "study.csv"),  # relative to the scene file's folder
        "vary": {
            "delta": "0.02:0.2:log3",
            "speed": "30,60rpm",
            "shaft.motor.speed_ratio": [12, 24],
            "design.max_width": ["0.05 m", "none"],
        },
    }
    with pytest.raises(SceneError, match=r"sweep.sample: unknown key \(did you mean 'samples'"):
        load_sweep(scene_with_sweep(tmp_path, "[sweep]\nsample = 3\n"))


def test_cli_sweep_from_the_file_table_with_overrides(tmp_path, capsys):
    path = scene_with_sweep(tmp_path)
    assert sweep_main([str(path), "--vary", "delta=0.05,0.1", "--no-progress"]) == 0
    out = tmp_path / "study.csv"
    frame = read_results(out)
    assert len(frame) == 2 * 2 * 2 * 2  # --vary delta replaced the file's 3 values
    assert sorted(set(frame["delta"])) == [0.05, 0.1]
    err = capsys.readouterr().err
    assert f"wrote {out}" in err and "16 points" in err
    check_against_individual_solves(PUNCH, frame.iloc[::5])


def test_cli_sweep_to_stdout_and_progress(capsys):
    scene = str(PROBLEMS / "shear-press.toml")
    assert sweep_main([scene, "--vary", "delta=0.02,0.05", "--vary", "speed=1000,1500rpm"]) == 0
    captured = capsys.readouterr()
    lines = captured.out.strip().splitlines()
    assert lines[0].startswith("point,delta,speed,") and len(lines) == 5
    assert "4/4 points (100 %)" in captured.err and "designs/s" in captured.err


def test_cli_sweep_stop_and_resume(tmp_path, capsys):
    scene, out = str(PROBLEMS / "punch-press.toml"), str(tmp_path / "s.parquet")
    args = [scene, "--vary", "delta=0.02:0.2:log8", "-o", out, "--chunk-size", "3", "--no-progress"]
    assert sweep_main(args + ["--max-chunks", "1"]) == 0
    assert "continue with --resume" in capsys.readouterr().err
    assert sweep_main(args + ["--resume"]) == 0
    assert len(read_results(out)) == 8


@pytest.mark.parametrize(
    "args, match",
    [
        (["--vary", "deltaa=0.1"], "--vary deltaa: unknown sweep field"),
        (["--vary", "delta=0.1:0.2"], "--vary delta: '0.1:0.2': a grid range needs a count"),
        (["--vary", "delta=0.1", "-o", "x.txt"], "output: 'x.txt' must end in .parquet or .csv"),
        (["--vary", "delta=0.1", "--resume"], "resume: needs an output file"),
    ],
)
def test_cli_sweep_bad_input_is_one_line_exit_2(args, match, capsys):
    status = sweep_main([str(PROBLEMS / "shear-press.toml"), *args, "--no-progress"])
    err = capsys.readouterr().err
    assert status == 2
    assert err.startswith("flyopt: error: ") and match in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "scene, vary", [("slider-crank-press", {"delta": "0.1,0.15"}), ("motor-press", {"delta": "0.1,0.2"})]
)
def test_sweeps_of_member_and_motor_scenes_match_individual_solves(scene, vary):
    """Regression (outside review): a scene with members (varying J_e) or a motor is analysed
    per point by its exact model, so the sweep agrees with flyopt.solve of the same point."""
    base = flyopt.load(PROBLEMS / f"{scene}.toml")
    frame = flyopt.sweep(base, vary)
    for row in frame.to_dict("records"):
        single = flyopt.solve(point_scene(base, {"delta": row["delta"]}))
        assert_allclose(row["j_required"], single.analysis.j_required, rtol=1e-9)
        assert_allclose(row["mass"], single.design.best.mass, rtol=1e-6)


@pytest.mark.parametrize(
    "sweep_table, words",
    [
        (
            '[sweep]\nseed = "abc"\nsamples = 3\n[sweep.vary]\ndelta = "0.01:0.1"\n',
            "sweep.seed: must be a whole number",
        ),
        ('[sweep.vary]\nspeed = "1500 m"\n', "sweep.vary.speed: '1500 m' has the wrong dimension"),
    ],
)
def test_bad_sweep_table_names_the_file_and_field(tmp_path, capsys, sweep_table, words):
    """Regression (outside review): errors in a scene's [sweep] table name the file and the field."""
    from flyopt.cli.main import main

    path = tmp_path / "s.toml"
    path.write_text((PROBLEMS / "shear-press.toml").read_text() + "\n" + sweep_table)
    assert main(["sweep", str(path)]) == 2
    err = capsys.readouterr().err
    # the file, and the line of the field it writes
    assert err.count("\n") == 1 and re.search(rf"{re.escape(str(path))}:\d+: ", err) and words in err


def test_sweep_output_in_a_missing_folder_is_refused_not_created(tmp_path, capsys):
    from flyopt.cli.main import main

    target = tmp_path / "no" / "such" / "x.csv"
    assert main(["sweep", str(PROBLEMS / "shear-press.toml"), "--vary", "delta=0.1,0.2", "-o", str(target)]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert not (tmp_path / "no").exists()


@pytest.mark.parametrize("verb", ["check", "sweep"])
def test_a_sweep_tables_output_in_a_missing_folder_names_the_tables_field(tmp_path, capsys, verb):
    """A `[sweep] output` whose folder is missing was refused as the user's `--output` (never given), and
    `flyopt check` said ok (an outside audit)."""
    from flyopt.cli.main import main

    path = tmp_path / "s.toml"
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    path.write_text(text + '\n[sweep]\noutput = "sub/x.csv"\n[sweep.vary]\ndelta = "0.02,0.05"\n', encoding="utf-8")
    assert main([verb, str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:" in err and "sweep.output: the folder" in err and "does not exist" in err, err
    assert "--output" not in err and not (tmp_path / "sub").exists()


def test_max_chunks_zero_is_refused(tmp_path):
    """Issue 25, item 10: --max-chunks 0 made a parts folder, ran nothing and exited 0."""
    out = tmp_path / "study.parquet"
    with pytest.raises(SceneError, match="max-chunks: must be a whole number >= 1, got 0"):
        sweep(PUNCH, VARY, output=out, chunk_size=4, max_chunks=0)
    assert list(tmp_path.iterdir()) == []
    run = run_flyopt(
        "sweep", PROBLEMS / "punch-press.toml", "--vary", "delta=0.05:0.1:3", "-o", out, "--max-chunks", "0"
    )
    assert run.returncode == 2 and "--max-chunks" in run.stderr and len(run.stderr.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("beside", ["study.csv.json", "study.csv.parts"])
def test_a_sweep_table_in_the_scene_writes_nothing_beside_it_outside_the_folder(tmp_path, beside):
    """[sweep] output stays in the scene's folder, and so do the files written beside it: a link at its CSV's
    sidecar or at its parts folder that leads out of the folder is refused as the output itself would be."""
    folder = tmp_path / "scene"
    folder.mkdir()
    outside = tmp_path / "outside"
    outside.mkdir()
    (folder / beside).symlink_to(outside / "victim")
    path = folder / "press.toml"
    path.write_text((PROBLEMS / "punch-press.toml").read_text() + SWEEP_TABLE, encoding="utf-8")
    with pytest.raises(SceneError, match="leads outside the scene file's folder") as info:
        load_sweep(path)
    assert info.value.field == "sweep.output" and info.value.source == str(path)
    assert list(outside.iterdir()) == []


@pytest.mark.parametrize(
    ("vary", "allowed"),
    [
        ("delta=1e-9", "allowed: 1e-06 to 2; as machine.delta"),
        ("speed=1e-10:1e10:log5 rpm", "allowed: 1e-06 to 1e+06 rad/s"),
        ("material.cast_steel.density=1e9", "allowed: 1 to 100000 kg/m^3"),
        ("material.cast_steel.max_rim_speed=1e9", "allowed: 0.001 to 10000 m/s"),
        ("shaft.motor.speed_ratio=1e-9,2", "allowed: 1e-06 to 1e+06"),
        ("design.max_outer_diameter=1e-9 m", "allowed: 1e-06 to 1000 m"),
        ("design.hb_ratio=1e5", "allowed: 0.001 to 1000"),
        # fields with no range of their own: their dimension's sizes, as every field the loader reads
        ("inertia=0,1e300", "allowed: a size of 1e-09 to 1e+12 kg*m^2"),
        ("torque.scale=1e-300,1", "allowed: a size of 1e-09 to 1e+09"),
        ("material.cast_iron.cost=0,1e300", "allowed: a size of 1e-09 to 1e+09 1/kg"),
    ],
)
def test_a_varied_value_the_loader_refuses_is_refused(vary, allowed):
    """A point of a sweep is a scene the loader would accept: each varied field keeps the loader's range (a δ of
    1e-9 or a density of 1e9 kg/m³ made rows marked designed, of wheels no scene can state)."""
    path = str(PROBLEMS / "shear-press.toml")
    scene = flyopt.load(path)
    field, _, values = vary.partition("=")
    with pytest.raises(SceneError, match="is out of range") as info:
        plan_sweep(scene, {field: values})
    assert allowed in info.value.message, info.value.message


def test_a_seed_too_large_for_the_file_is_refused_by_the_command_leaving_nothing(tmp_path):
    """`flyopt sweep --seed 2**63` (or `[sweep] seed`): one line naming the option, exit 2, no parts folder."""
    from conftest import run_flyopt

    out = tmp_path / "out.csv"
    done = run_flyopt(
        "sweep",
        str(PROBLEMS / "punch-press.toml"),
        "--vary",
        "delta=0.01:0.1:3",
        "--samples",
        "3",
        "--seed",
        str(2**63),
        "-o",
        str(out),
    )
    assert done.returncode == 2 and done.stdout == "", done.stderr
    assert done.stderr.splitlines() == [
        "flyopt: error: --seed: must be a whole number from 0 to 9223372036854775807, got 9223372036854775808"
    ]
    assert list(tmp_path.iterdir()) == []
