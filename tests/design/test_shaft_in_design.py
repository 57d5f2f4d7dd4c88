"""The described shaft in the design (issue 30, item 5): a post-check that makes a combination infeasible.

In the default run: the designer's post-check on a textbook rim (closed form, no solver), and the shipped
engine scene solved once (its torsional check binds): the JSON validates with every new field's unit, the
text shows the shaft, and the binding limit's sensitivity to the wheel's mass agrees with the two-inertia
closed form's derivative; the same scene with a 20 % margin is infeasible with the reason in numbers.
"""

import math
import sys
from pathlib import Path

import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.materials import builtin_materials
from flyopt.outputs.documents import solution_document
from flyopt.pipeline import solve

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "outputs"))
from output_cases import assert_units_cover, schema_errors  # noqa: E402

ENGINE = PROBLEMS / "four-cylinder-engine-shaft.toml"
RPM = math.pi / 30


def test_a_design_the_post_check_refuses_is_infeasible_and_the_next_one_wins():
    library = builtin_materials()
    materials = [library["cast_iron"], library["cast_steel"]]
    spec = DesignSpec(geometry="rim", max_outer_diameter=1.5)
    free = design_flywheel(50.0, 600 * RPM, [MountShaft("main", 1.0)], materials, spec)
    refused = free.best.material

    def accept(candidate):
        return f"{candidate.material}: the shaft says no" if candidate.material == refused else None

    result = design_flywheel(50.0, 600 * RPM, [MountShaft("main", 1.0)], materials, spec, accept=accept)
    assert result.status == "designed" and result.best.material != refused
    out = next(c for c in result.candidates if c.material == refused)
    assert not out.feasible and out.reason == f"{refused}: the shaft says no"
    assert out.mass == pytest.approx(free.best.mass)  # the wheel it refused is kept, with its numbers

    everything = design_flywheel(50.0, 600 * RPM, [MountShaft("main", 1.0)], materials, spec, accept=lambda c: "no")
    assert everything.status == "infeasible" and everything.best is None


@pytest.fixture(scope="module")
def engine():
    scene = flyopt.load(ENGINE)
    return scene, solve(scene)


def test_the_engine_scenes_shaft_check_binds_and_its_sensitivity_is_the_closed_forms(engine):
    scene, solution = engine
    (report,) = solution.shaft_checks
    binding = report.check.binding
    assert binding.kind == "torsional" and 0.9 < binding.utilisation <= 1.0
    # u = n_max (1 + m) / n_c with n_c proportional to omega = sqrt(k (J_1 + J_2) / (J_1 J_2)): scaling the
    # wheel's J_1 with its mass gives d ln u / d ln m = J_2 / (2 (J_1 + J_2))
    j1, j2 = solution.design.best.j_flywheel, scene.shafts[0].inertia
    expected = binding.utilisation * j2 / (2 * (j1 + j2)) / solution.design.best.mass
    assert report.sensitivity == pytest.approx(expected, rel=1e-5)


def test_the_engine_scenes_json_validates_and_gives_every_shaft_field_a_unit(engine):
    scene, solution = engine
    document = solution_document(solution, ENGINE)
    assert schema_errors(document) == []
    assert_units_cover(document)
    check = document["shaft_checks"][0]
    assert document["units"]["critical_speed"] == "rad/s" and document["units"]["dutilisation_dmass"] == "1/kg"
    # the cast steel disc's key, designed at the train's torque, is checked at it too
    kinds = {lim["kind"] for lim in check["limits"]}
    assert kinds == {"fatigue", "yield", "slope", "lateral", "torsional", "key"}
    assert document["units"]["key_torque"] == "N*m"


def test_a_wider_margin_makes_the_engine_infeasible_with_the_reason_in_numbers(write_scene):
    text = ENGINE.read_text(encoding="utf-8").replace("critical_margin = 0.1", "critical_margin = 0.2")
    result = solve(flyopt.load(write_scene(text)), extras=()).design
    assert result.status == "infeasible"
    reasons = {c.material: c.reason for c in result.candidates}
    # the cast steel disc's hub is refused before its shaft: on the 45 mm seat no key of at most 1.5 d carries
    # the train's torque at its 100 MPa
    assert set(reasons) == {"cast_iron", "cast_steel_keyed"}
    assert "no DIN 6885-1 key on the 45 mm seat carries it" in reasons["cast_steel_keyed"]
    iron = reasons["cast_iron"]
    assert "the shaft cannot carry this" in iron
    assert "torsional critical speed (mode 1 at order 10)" in iron and "rpm" in iron


@pytest.mark.slow  # the whole report of a scene (every diagram drawn); the default run keeps the JSON and text
def test_the_report_has_the_shaft_section_with_both_diagrams_drawn():
    from flyopt.cli.report import collect
    from flyopt.report.builder import build

    document = build(collect(ENGINE, "flyopt report"))
    try:
        (section,) = [s for s in document.sections if s.key == "shaft"]
        figures = {b.key: b for b in section.blocks if type(b).__name__ == "Figure"}
        assert set(figures) == {"shaft", "campbell"}
        assert all(f.figure is not None and not f.failed for f in figures.values())
        assert any(type(b).__name__ == "Table" and b.name == "shaft_limits" for b in section.blocks)
    finally:
        document.close()


def test_the_engine_scenes_text_names_the_shaft_material_as_the_library_does(engine):
    """One name per material (issue 29): the shaft's grade in the text by its designation ('42CrMo4+QT', from
    the materials' data), as every other text names a material; the JSON keeps its key."""
    from flyopt.report.shaft import shaft_report

    scene, solution = engine
    (report,) = solution.shaft_checks
    from flyopt.design.materials import get_material

    grade = get_material(report.material)
    text = "\n".join(shaft_report(solution.shaft_checks))
    assert f"({grade.display_name})" in text and grade.display_name != report.material
    assert solution_document(solution, ENGINE)["shaft_checks"][0]["material"] == report.material
