"""Sweep points and Pareto-front points of a scene whose shaft is described (flyopt.studies.described).

The reference for each point is :func:`flyopt.pipeline.design_scene` (continuous, as every study compares designs)
run here on the scene with the point's values written by hand (``scene.replace``) and a cycle analysed anew
(:func:`flyopt.analyse`): the design ``flyopt solve`` makes, its key sized at the train's torque and its shaft's
post-check included. That the key's torque is the train's and not the rigid body's, and that the shaft's check is
what refuses a point, is told apart by the bare :func:`flyopt.design.design_flywheel` at the rigid body's peak
torque: the design a sweep made before.

The scene is problems/four-cylinder-engine-shaft.toml: the disc overhung on the crankshaft's rear end, whose key
carries about three times the rigid body's peak torque by the train's forced response; with its critical margin
widened from 0.1 to 0.2 (``WIDE``) the cast iron disc's torsional mode meets order 10 of the engine's torque in the
running range at the scene's δ.
"""

import dataclasses
import re

import pandas as pd
import pytest
from conftest import PROBLEMS
from numpy.testing import assert_allclose

import flyopt
from flyopt._toml import tomllib
from flyopt.cycle.torque import PiecewiseLinear
from flyopt.design import design_flywheel, design_inputs
from flyopt.pipeline import design_scene, shaft_context_of
from flyopt.studies import described
from flyopt.studies.described import analysis_for, shaft_material_fields
from flyopt.studies.pareto import pareto
from flyopt.studies.physics import physics_analysis
from flyopt.studies.points import design_counts, point_scene
from flyopt.studies.sweep import sweep

ENGINE = flyopt.load(PROBLEMS / "four-cylinder-engine-shaft.toml")
#: The same scene with the torsional modes kept 20 % (not 10 %) clear of the running range.
WIDE = flyopt.load(
    PROBLEMS / "four-cylinder-engine-shaft.toml",
    tomllib.loads(
        (PROBLEMS / "four-cylinder-engine-shaft.toml")
        .read_text(encoding="utf-8")
        .replace("critical_margin = 0.1", "critical_margin = 0.2")
    ),
)


def reference(scene):
    """``flyopt solve``'s continuous design of ``scene``, on a cycle analysed anew."""
    return design_scene(scene, flyopt.analyse(scene), continuous=True)


def bare(scene):
    """The design a sweep made before: design_flywheel at the rigid body's peak torque, no shaft check."""
    analysis = flyopt.analyse(scene)
    inputs = design_inputs(scene)
    return design_flywheel(
        analysis.j_margin,
        analysis.omega_max,
        inputs.shafts,
        inputs.materials,
        inputs.spec,
        torque=analysis.flywheel_torque(),
        omega_mean=analysis.omega_mean,
    )


@pytest.fixture
def designs(monkeypatch):
    """The DesignResult each described point's row was filled from, in the order the rows were."""
    seen = []
    fill = described.fill_row

    def spy(res, k, result):
        seen.append(result)
        fill(res, k, result)

    monkeypatch.setattr(described, "fill_row", spy)
    return seen


def test_a_sweep_point_is_flyopt_solve_s_design_with_its_key_at_the_train_s_torque(designs):
    """The scene's own values, and the envelope narrowed: same status, material, mass, and key torque as
    design_scene; the key carries the train's torque (about 3x the rigid body's), which the bare design does not
    size the hub at (its mass differs), so the test tells the two paths apart."""
    frame = sweep(ENGINE, {"design.max_outer_diameter": [0.28, 0.25]}, workers=1)
    narrow = ENGINE.replace(design=dataclasses.replace(ENGINE.design, max_outer_diameter=0.25))
    assert len(designs) == 2
    for row, result, scene in zip(frame.to_dict("records"), designs, (ENGINE, narrow), strict=True):
        expected = reference(scene)
        assert row["status"] == expected.status == "designed"
        assert row["best_material"] == expected.best.material
        assert row["best_shaft"] == expected.best.shaft
        assert_allclose(row["mass"], expected.best.mass, rtol=1e-9)
        assert_allclose(row["d_outer"], expected.best.dims.d_outer, rtol=1e-9)
        key, expected_key = result.best.parts.key, expected.best.parts.key
        assert_allclose(key["torque"], expected_key["torque"], rtol=1e-9)
        assert key["length"] == expected_key["length"] and key["size"] == expected_key["size"]
        rigid = flyopt.analyse(scene).flywheel_torque() / expected.best.speed_ratio
        assert key["torque"] > 2.0 * rigid  # the train's forced response near its torsional mode
        old = bare(scene).best
        assert old is not None and abs(old.mass / row["mass"] - 1.0) > 1e-3


def test_a_point_whose_shaft_refuses_every_wheel_is_infeasible_with_the_reason_in_numbers():
    """With the critical margin widened to 0.2, at δ = 0.005 the cast iron disc puts the shaft's torsional mode in
    the running range and the cast steel disc's hub takes no key that carries the train's torque: the row is
    infeasible with design_scene's reason (the critical speed and the widened range in rpm; the key in numbers),
    where the bare design, which has no shaft check, designed a wheel. At δ = 0.0055 the wheel is designed."""
    frame = sweep(WIDE, {"delta": [0.005, 0.0055]}, workers=1)
    refused, held = frame.to_dict("records")
    scene = WIDE.replace(delta=0.005)
    expected = reference(scene)
    assert refused["status"] == expected.status == "infeasible" and not refused["feasible"]
    assert refused["message"] == expected.message
    found = re.findall(
        r"torsional critical speed \(mode 1 at order 10\) (\d+) rpm inside the running range", refused["message"]
    )
    assert len(found) == 1  # cast iron refused by the mode
    assert "cast steel keyed on the crankshaft: no DIN 6885-1 key on the 45 mm seat carries it" in refused["message"]
    assert bare(scene).best is not None  # without the shaft's check the point was "designed"
    assert held["status"] == reference(WIDE.replace(delta=0.0055)).status == "designed"


def test_a_press_whose_cycle_one_a_max_serves_is_analysed_at_each_point_for_its_shaft():
    """punch-press-shaft: the energy method is exact there, so a sweep of a bare scene scales one A_max; with the
    intermediate shaft described each point is analysed (the net torque its key and checks read). The scene's
    own point is design_scene's design; with the punching torque doubled the key and the shaft's fatigue at the
    shoulder refuse every wheel (in numbers, as design_scene says), where the bare design gave one."""
    scene = flyopt.load(PROBLEMS / "punch-press-shaft.toml")
    frame = sweep(scene, {"torque.scale": [1.0, 2.0]}, workers=1)
    own, doubled = frame.to_dict("records")
    expected = reference(scene).best
    assert own["status"] == "designed" and own["best_material"] == expected.material
    assert_allclose(own["mass"], expected.mass, rtol=1e-9)
    resisting = scene.resisting
    heavy = scene.replace(resisting=PiecewiseLinear(resisting.angles, 2.0 * resisting.values))
    refused = reference(heavy)
    assert doubled["status"] == refused.status == "infeasible" and doubled["message"] == refused.message
    assert "fatigue factor of safety at the shoulder at 520 mm" in doubled["message"]
    assert re.search(r"no DIN 6885-1 key on the 80 mm seat carries it: torque [\d.]+ N·m", doubled["message"])
    assert bare(heavy).best is not None


def test_a_pareto_front_point_is_flyopt_solve_s_design_and_a_refused_delta_is_not_on_it():
    """Mass against δ: the front's points are design_scene's designs at δ = ε; an ε no wheel serves (the cast
    steel disc's key refused at the train's torque, no cast iron disc within its limits) is evaluated and left off
    (infeasible), never a front point."""
    front = pareto(WIDE, "mass,delta", points=4, span=(0.0042, 0.0066))
    assert front.attrs["evaluated"] == 4
    assert len(front) == 2 and front["epsilon"].min() > 0.0055  # 0.0042 and 0.00488 refused
    for row in front.to_dict("records"):
        expected = reference(WIDE.replace(delta=float(row["epsilon"])))
        assert row["status"] == expected.status == "designed" and row["best_material"] == expected.best.material
        assert_allclose(row["mass"], expected.best.mass, rtol=1e-9)
    refused = reference(WIDE.replace(delta=0.0042 ** (2 / 3) * 0.0066 ** (1 / 3)))  # the second ε of the grid
    assert refused.status == "infeasible" and "no DIN 6885-1 key on the 45 mm seat carries it" in refused.message


def test_a_point_that_changes_the_shaft_s_steel_checks_it_with_that_steel():
    """The shafts' context is kept per analysis: a point that changes a property of the material the described
    shaft is made of is designed on a copy of its analysis, whose context is built with the point's material."""
    assert shaft_material_fields(ENGINE, ["delta", "material.cast_iron.density", "material.42crmo4_qt.density"]) == (
        "material.42crmo4_qt.density",
    )
    analysis = physics_analysis(ENGINE)
    assert shaft_context_of(ENGINE, analysis).materials["crankshaft"].density == 7840.0  # EN 10083-3's 42CrMo4
    fields = ("material.42crmo4_qt.density",)
    kept = {}
    point = {"material.42crmo4_qt.density": 9000.0}
    on = analysis_for(analysis, point, fields, kept)
    assert on is not analysis and analysis_for(analysis, dict(point), fields, kept) is on
    assert shaft_context_of(point_scene(ENGINE, point), on).materials["crankshaft"].density == 9000.0
    assert analysis_for(analysis, {"delta": 0.01}, (), kept) is analysis


def test_a_closed_form_structure_beside_a_described_shaft_is_designed_and_estimated_one_point_at_a_time():
    """punch-press-shaft with a bare rim on its motor shaft (no bore): the vectorized closed form covers the
    structure, but the scene describes a shaft, so each point is design_scene's (here its closed form, the wheel
    not on the described shaft), and the sweep's cost estimate counts it as a design one by one; the same scene
    with no shaft described is the vectorized closed form's, as before."""
    scene = flyopt.load(PROBLEMS / "punch-press-shaft.toml")
    shafts = tuple(dataclasses.replace(s, diameter=None) if s.name == "motor" else s for s in scene.shafts)
    spec = dataclasses.replace(scene.design, geometry="rim", criterion="rim_speed", min_wall=None)
    rim = scene.replace(shafts=shafts, design_shafts=("motor",), design=spec)
    bare_shafts = rim.replace(shafts=tuple(dataclasses.replace(s, layout=None) for s in rim.shafts))
    points = pd.DataFrame({"point": [0], "delta": [0.1]})
    assert design_counts(rim, points)[1].all() and not design_counts(bare_shafts, points)[1].any()
    row = sweep(rim, {"delta": [0.1]}, workers=1).iloc[0]
    expected = reference(rim).best
    assert row["method"] == "closed_form" and row["best_shaft"] == "motor"
    assert_allclose(row["mass"], expected.mass, rtol=1e-9)
    assert sweep(bare_shafts, {"delta": [0.1]}, workers=1)["method"].iloc[0] == "closed_form"


def test_the_cost_estimate_takes_each_way_a_point_is_designed():
    """The estimate (``design_seconds``) per point: combinations (materials x shafts) times the cost of one by how
    it is designed, each way routed to its own figure: the closed form (punch-press's textbook rims), IPOPT on a
    bare wheel (the same points with method "ipopt"), a whole wheel (punch-press-wheel's rim_web), a rim_arms wheel
    once per arm count it considers (press-arms-wheel: 4, 6 and 8), and a described shaft's design."""
    from flyopt.studies import chunks
    from flyopt.studies.points import design_seconds

    points = pd.DataFrame({"point": [0, 1], "delta": [0.1, 0.2]})

    def per_point(file, method="auto"):
        values, _ = design_seconds(flyopt.load(PROBLEMS / file), points, method)
        assert values[0] == values[1]
        return values[0]

    assert per_point("punch-press.toml") == pytest.approx(9 * chunks.SECONDS_CLOSED_FORM)
    assert per_point("punch-press.toml", "ipopt") == pytest.approx(9 * chunks.SECONDS_IPOPT)
    assert per_point("punch-press-wheel.toml") == pytest.approx(9 * chunks.SECONDS_WHOLE_WHEEL)
    assert per_point("press-arms-wheel.toml") == pytest.approx(2 * 3 * chunks.SECONDS_WHOLE_WHEEL)
    assert per_point("punch-press-shaft.toml") == pytest.approx(3 * chunks.SECONDS_DESCRIBED)
