"""Outputs that describe themselves, and the command-line conventions (issue 15, parts 3 and 5).

- Every JSON document validates against the JSON Schema shipped with the
  package, and the schema refuses a wrong type, a missing field and an
  unknown one (mutations of valid documents).
- The ``units`` map is checked against two independent sources: the
  dimensions that the engineering relations of docs/flywheel-design.md give
  each quantity (pint's dimensional analysis of J_F = A_max/(omega_m^2 delta),
  v = omega D/2, sigma = rho v^2 ...), and the unit column of
  docs/nomenclature.md.
- Missing values are nulls in Parquet, CSV and JSON, read from the files by
  pyarrow, the csv module and json, not through flyopt's reader.
- Parquet metadata and the CSV sidecar carry the units and the provenance,
  compared with a SHA-256 of the scene file and SI values computed here.
- ``-o FILE``, ``--quiet``, ``--version``, ``__version__``, LICENSE, py.typed
  and the annotations of the public API.
"""

import csv
import dataclasses
import hashlib
import importlib.metadata
import inspect
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import jsonschema
import numpy as np
import pandas as pd
import pint
import pyarrow.compute as pc
import pyarrow.parquet as pq
import pytest
from conftest import PROBLEMS, ROOT

import flyopt
from flyopt.cli.main import main
from flyopt.outputs import quantities, results
from flyopt.outputs.documents import SCHEMA_FILE, json_text, schema, schema_version, solution_document, table_metadata
from flyopt.outputs.files import write_text
from flyopt.outputs.quantities import COUNTS, QUANTITIES, UNIT_SET_BY, unit_of
from flyopt.outputs.results import read_results
from flyopt.studies.payload import digest

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

SCENES = sorted(PROBLEMS.glob("*.toml"))
VALIDATOR = jsonschema.Draft202012Validator(schema(), format_checker=jsonschema.FormatChecker())
UREG = pint.UnitRegistry()


def _errors(document):
    return [f"{e.json_path}: {e.message[:200]}" for e in VALIDATOR.iter_errors(document)]


#: Problem scenes whose solve takes long: their documents are checked in the slow set only
#: (press-drive designs its motor with the flywheel, some 50 s).
SLOW_SCENES = {"press-drive"}
#: The scenes the fast checks of the schema and the units use (every branch of the schema occurs).
FAST = ("punch-press-wheel", "conveyor", "motor-press", "example1-net-areas", "punch-press", "slider-crank-press")
_DOCUMENTS = {}


def _documents(stem):
    """The JSON of ``flyopt solve --verify --timings`` for a problem scene, as the CLI prints it
    (through JSON text and back), and of ``--no-design``; computed once per scene."""
    if stem not in _DOCUMENTS:
        path = PROBLEMS / f"{stem}.toml"
        scene, name = flyopt.load(path), str(path.relative_to(ROOT))
        solution = flyopt.solve(scene, verify_design=True)
        bare = flyopt.solve(scene, design_flywheel=False)
        _DOCUMENTS[stem] = [
            json.loads(json_text(solution_document(s, name, timings=t))) for s, t in ((solution, True), (bare, False))
        ]
    return _DOCUMENTS[stem]


@pytest.fixture(scope="module")
def documents():
    return {f"{stem}/{k}": d for stem in FAST for k, d in enumerate(_documents(stem))}


def _scene_params():
    return [pytest.param(p.stem, marks=pytest.mark.slow) if p.stem in SLOW_SCENES else p.stem for p in SCENES]


def _variant(tmp_path, name, text):
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _punch(**changes):
    """problems/punch-press.toml with some of its lines replaced."""
    text = (PROBLEMS / "punch-press.toml").read_text()
    for old, new in changes.items():
        assert old in text
        text = text.replace(old, new)
    return text


def _solve_document(path, **options):
    solution = flyopt.solve(flyopt.load(path), **options)
    return json.loads(json_text(solution_document(solution, str(path))))


# --------------------------------------------------------------------------
# The JSON Schema
# --------------------------------------------------------------------------


def test_the_schema_is_a_valid_draft_2020_12_schema():
    jsonschema.Draft202012Validator.check_schema(schema())
    assert schema()["$schema"] == "https://json-schema.org/draft/2020-12/schema"


@pytest.mark.parametrize("stem", _scene_params())
def test_every_problem_scene_validates(stem):
    """The document of every problem scene (designed, verified, timed; and without a design)
    validates, and every number in it has its unit (or is a count)."""
    for document in _documents(stem):
        assert _errors(document) == []
        assert document["schema_version"] == schema_version() and document["kind"] == "solve"
        assert document["flyopt_version"] == importlib.metadata.version("flyopt")
        _assert_units_cover(document)


def test_the_documents_cover_every_branch_of_the_schema(documents, tmp_path):
    """Designed, not needed and infeasible designs, the key, arms, costs, --verify, startup, timings:
    each occurs in a document that validates (a schema tested on none of them tests nothing)."""
    more = {
        "infeasible": _solve_document(_variant(tmp_path, "tiny", _punch(**{'"1.2 m"': '"0.1 m"'}))),
        "cost": _solve_document(
            _variant(
                tmp_path,
                "cost",
                _punch(
                    **{
                        'materials = ["cast_iron", "cast_steel", "ductile_iron"]': 'materials = ["ductile_iron"]\nobjective = "cost"',
                        'density = "7100 kg/m^3"': 'density = "7100 kg/m^3"\ncost = "2.1 1/kg"',
                    }
                ),
            )
        ),
        "arms": _solve_document(ROOT / "tests" / "data" / "wheels" / "engine-rim_arms.toml"),
    }
    more["drive"] = _drive_document()
    for name, document in more.items():
        assert _errors(document) == [], name
        _assert_units_cover(document)
    everything = list(documents.values()) + list(more.values())
    designs = [d["design"] for d in everything if "design" in d]
    assert {d["status"] for d in designs} == {"designed", "not_needed", "infeasible"}
    candidates = [c for d in designs for c in d["candidates"]]
    assert any(c["key"] is not None for c in candidates) and any(c["key"] is None for c in candidates)
    assert any(isinstance(c["n_arms"], int) for c in candidates)
    assert any(isinstance(c["cost"], float) for c in candidates)
    assert any(isinstance(c.get("solve_time"), float) for c in candidates)
    assert any(c["stress"] is not None for c in candidates) and any(c["sensitivities"] for c in candidates)
    assert any(d.get("startup") is not None for d in everything)
    assert any("verification" in d for d in everything) and any("design" not in d for d in everything)
    assert more["cost"]["units"]["objective"] == "1" and more["arms"]["units"]["objective"] == "kg"
    assert more["drive"]["drive"]["best"]["wheel"] is not None and "verification" in more["drive"]["drive"]


def _drive_document():
    """A solution with a drive, assembled from the drive's own result types around punch-press's
    design and verification (designing a drive takes a minute: the real one is the slow
    press-drive scene). Its numbers are placeholders; its structure is what to_dict writes."""
    from flyopt.drive.codesign import DriveCheck, DriveDesign, MotorRun
    from flyopt.drive.relaxation import Relaxation
    from flyopt.machine.catalogue import CatalogueMotor

    solution = flyopt.solve(flyopt.load(PROBLEMS / "punch-press.toml"), verify_design=True)
    motor = CatalogueMotor(
        name="5.5 kW",
        rated_power=5500.0,
        rated_speed=151.8,
        synchronous_speed=157.1,
        rotor_inertia=0.022,
        breakdown_ratio=2.7,
        mass=40.0,
    )
    run = MotorRun(
        motor=motor,
        feasible=True,
        motor_ratio=24.0,
        j_flywheel=800.0,
        limit="delta",
        j_delta=800.0,
        rms_torque=30.0,
        mean_torque=20.0,
        rated_torque=36.0,
        omega_mean=6.28,
        delta=0.1,
        startup_time=5.0,
        flywheel_ratio=24.0,
        wheel=solution.design.best,
        motor_mass=40.0,
        wheel_mass=17.0,
        total_mass=57.0,
        objective=57.0,
    )
    drive = DriveDesign(
        status="designed",
        objective="mass",
        best=run,
        runs=(run, MotorRun(motor=motor, feasible=False, reason="too small")),
        relaxation=Relaxation(5000.0, 24.0, 24.0, 800.0, 57.0, "Solve_Succeeded"),
        note="relaxation",
    )
    check = DriveCheck(
        verification=solution.verification, rms_torque=30.0, rated_torque=36.0, startup_time=5.0, flagged=False
    )
    with_drive = dataclasses.replace(solution, drive=drive, drive_check=check)
    return json.loads(json_text(solution_document(with_drive, "drive.toml")))


def _set(path, value):
    def mutate(document):
        target = document
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value

    return mutate


def _delete(path):
    def mutate(document):
        target = document
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]

    return mutate


@pytest.mark.parametrize(
    "mutate, why",
    [
        (_set(["a_max"], "1256 J"), "a number as text"),
        (_set(["flywheel_needed"], "yes"), "a boolean as text"),
        (_set(["flywheel_needed"], None), "null where a value must be"),
        (_set(["index_omega_max"], 1.5), "a fraction for an index"),
        (_set(["energy_chain"], {}), "an object for a list"),
        (_set(["design", "mass"], "heavy"), "the winner's mass as text"),
        (_set(["design", "candidates", 0, "feasible"], 1), "a number for a boolean"),
        (_set(["design", "candidates", 0, "parts", 0, "mass"], None), "a part without mass"),
        (_set(["design", "binding"], "inertia"), "text for a list"),
        (_set(["units", "mass"], 1), "a unit that is no text"),
        (_set(["schema_version"], "0.9"), "another schema version"),
        (_set(["kind"], "report"), "an unknown kind"),
        (_set(["design", "status"], "maybe"), "an unknown design status"),
        (_set(["surprise"], 1), "a field the schema does not know"),
        (_set(["design", "candidates", 0, "stress", "surprise"], 1.0), "a field deep inside"),
        (_delete(["a_max"]), "a missing analysis field"),
        (_delete(["units"]), "no units"),
        (_delete(["schema_version"]), "no version"),
        (_delete(["design", "candidates", 0, "reason"]), "a candidate without its reason"),
        (_delete(["design", "key"]), "a design without its key field"),
        (_delete(["shafts", 0, "omega"]), "a shaft without its speed"),
    ],
)
def test_a_mutated_document_fails(documents, mutate, why):
    document = json.loads(json.dumps(documents["punch-press-wheel/0"]))
    assert _errors(document) == []
    mutate(document)
    assert _errors(document), why


def test_the_not_needed_design_has_its_own_form(documents):
    document = json.loads(json.dumps(documents["conveyor/0"]))
    assert document["design"]["status"] == "not_needed" and _errors(document) == []
    document["design"]["mass"] = 1.0  # a not-needed design carries no wheel
    assert _errors(document)


def test_the_schema_ships_with_the_package():
    """The schema is package data (found through importlib.resources, listed in pyproject's
    package-data), not a file of the source tree only."""
    from fnmatch import fnmatch
    from importlib import resources

    assert resources.files("flyopt").joinpath("data", SCHEMA_FILE).is_file()
    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["flyopt"]
    assert any(fnmatch(f"data/{SCHEMA_FILE}", p) for p in patterns)
    assert any(fnmatch("py.typed", p) for p in patterns)


def test_the_command_line_json_validates(capsys):
    assert main(["solve", str(PROBLEMS / "punch-press-wheel.toml"), "--json"]) == 0
    assert _errors(json.loads(capsys.readouterr().out)) == []


# --------------------------------------------------------------------------
# Units
# --------------------------------------------------------------------------


def _numeric_keys(document):
    found = set()

    def visit(key, value):
        if isinstance(value, dict):
            for k, v in value.items():
                visit(k, v)
        elif isinstance(value, list):
            for v in value:
                visit(key, v)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            found.add(key)

    visit(None, {k: v for k, v in document.items() if k != "units"})
    return found


def _assert_units_cover(document):
    """Every field that holds a number is in the document's units map, or is a count; the map
    names nothing the document does not hold."""
    numeric = _numeric_keys(document)
    units = document["units"]
    assert numeric - COUNTS <= set(units), sorted(numeric - COUNTS - set(units))
    assert not set(units) & COUNTS
    assert all(k in numeric or _only_null(document, k) for k in units)


def _only_null(document, key):
    """Whether ``key`` is null somewhere in the document (its unit then says what it would be)."""
    found = []

    def visit(value):
        if isinstance(value, dict):
            for k, v in value.items():
                if k == key:
                    found.append(v)
                visit(v)
        elif isinstance(value, list):
            for v in value:
                visit(v)

    visit({k: v for k, v in document.items() if k != "units"})
    return any(v is None for v in found)  # a quantity with no value here (text elsewhere: model.objective)


def _q(unit):
    return UREG.Quantity(1.0, unit)


#: Relations of docs/flywheel-design.md between quantities: the unit of the name on the left
#: must have the dimension of the expression on the right, written with the units of other names
#: (pint's dimensional analysis; rad is a plain number, as in SI).
RELATIONS = {
    # section 5: J_F = A_max / (omega_m^2 delta); J_F is what j_margin clips and J_c adds to
    "j_required": "a_max / omega_mean**2 / delta",
    "j_margin": "j_required",
    "j_constant": "j_required",
    # section 4: the work of a torque over the cycle angle; the excess work delta E; an angle
    # is a work over a torque
    "angle": "a_max / driving_torque",
    "work_per_cycle": "driving_torque * cycle_angle",
    "delta_e": "a_max",
    "a_max": "driving_torque * angle",
    "resisting_torque": "driving_torque",
    # section 2: omega_m (1 +- delta/2); delta = (omega_max - omega_min)/omega_m
    "omega_max": "omega_mean * (1 + delta)",
    "omega_min": "omega_mean",
    "omega": "omega_mean",
    "omega_target": "omega_mean",
    "achieved_delta": "omega_max / omega_mean",
    "delta_allowed": "delta",
    "tolerance": "delta",
    "j_error": "j_required / j_required",
    # angles of the cycle
    "cycle_angle": "angle",
    "angle_omega_max": "angle",
    "angle_omega_min": "angle",
    "angle_delta_e_max": "angle",
    "angle_delta_e_min": "angle",
    # section 3: GD^2 = 4 g J (g in m/s^2)
    "gd2_required": "j_required * meter / second**2",
    # section 11: P = M_d omega_m, P_motor = P / eta
    "power": "driving_torque * omega_mean",
    "motor_power": "power / efficiency",
    # section 8: J' = J_F / i^2, omega' = i omega
    "j_required_on_shaft": "j_required / speed_ratio**2",
    "j_at_reference": "j_flywheel * speed_ratio**2",
    "speed_ratio": "omega / omega_mean",
    "best_speed_ratio": "speed_ratio",
    # section 9: J = m D_m^2 / 4, H/B, D_1 = D_m + H
    "j_flywheel": "mass * d_mean**2",
    "j_max": "j_flywheel",
    "hb_ratio": "h / b",
    "d_outer": "d_mean + h",
    "d_inner": "d_mean - h",
    "d_mean": "h",
    "b": "h",
    "outer_diameter": "d_outer",
    "d_outer_limit": "d_outer",
    "d_outer_needed": "d_outer",
    "max_outer_diameter": "d_outer",
    "max_width": "b",
    # section 10: v = omega' D_1 / 2, sigma = rho v^2 (rho = m / volume), safety factor
    "rim_speed": "omega_max * d_outer",
    "rim_speed_limit": "rim_speed",
    "hoop_stress": "mass / d_outer**3 * rim_speed**2",
    "allowable_stress": "hoop_stress",
    "safety_factor": "allowable_stress / hoop_stress",
    # section 13: parts, stresses, burst, balance (U = e m), the key (p = 2 T / (d t2 l), tau = 2 T / (d b l))
    "inertia": "mass * r_outer**2",
    "r_outer": "d_outer",
    "r_inner": "d_inner",
    "thickness": "b",
    "bore": "d_inner",
    "t_web": "b",
    "d_hub": "d_outer",
    "l_hub": "b",
    "arm_major": "b",
    "arm_minor": "b",
    "radius": "r_outer",
    "wall": "b",
    "stress": "hoop_stress",
    "allowable": "stress",
    "strength": "stress",
    "max_principal": "stress",
    "von_mises": "stress",
    "hoop_max": "stress",
    "radial_max": "stress",
    "mean_hoop": "stress",
    "strength_safety": "strength / stress",
    "burst_speed": "omega_max",
    "speed_margin": "burst_speed / omega_max",
    "unbalance_permissible": "mass * d_outer",
    "torque": "driving_torque",
    "length": "l_hub",
    "effective_length": "length",
    "t1": "h",
    "t2": "h",
    "bearing_pressure": "torque / (bore * t2 * effective_length)",
    "shear": "torque / (bore * b * effective_length)",
    "allowable_pressure": "bearing_pressure",
    "allowable_shear": "shear",
    # section 11 and money: a cost is mass times a price per kg (the sweep field material.NAME.cost)
    "efficiency": "power / power",
    "cost": "mass * material.x.cost",
    # section 7: cycles turned in the run-up, omega t / Phi; wall-clock times
    "time": "cycle_angle / omega_target",
    "cycles": "omega_target * time / cycle_angle",
    "solve_time": "time",
    # section 9: m = J / (D_m^2 / 4); section 11: omega_m = P / M_d
    "mass": "j_flywheel / d_mean**2",
    "omega_mean": "power / driving_torque",
    # section 9: m = rho pi D_m H B
    "density": "mass / (d_mean * h * b)",
    "driving_torque": "work_per_cycle / cycle_angle",
    "h": "d_outer - d_inner",
    # section 14, the drive: ratios of speeds, M_n = P_n / omega_n, inertias, the run-up, masses, price
    "motor_ratio": "omega / omega_mean",
    "flywheel_ratio": "omega / omega_mean",
    "breakdown_ratio": "torque / rated_torque",
    "rated_torque": "rated_power / rated_speed",
    "rms_torque": "rated_torque",
    "mean_torque": "rated_torque",
    "rated_power": "power",
    "rated_speed": "omega_mean",
    "synchronous_speed": "omega_mean",
    "rotor_inertia": "j_required",
    "j_delta": "j_required",
    "startup_time": "time",
    "motor_mass": "mass",
    "wheel_mass": "mass",
    "total_mass": "motor_mass + wheel_mass",
    "price": "cost",
}


def _value(expression):
    names = set(re.findall(r"[a-z_][a-z_0-9.]*", expression)) - {"meter", "second"}
    scope = {"meter": UREG.meter, "second": UREG.second}
    text = expression
    for k, name in enumerate(sorted(names, key=len, reverse=True)):
        text = re.sub(rf"(?<![a-z_0-9.]){re.escape(name)}(?![a-z_0-9.])", f"_v{k}", text)
        unit = "radian" if name == "angle" else unit_of(name)
        assert unit is not None, f"{name} has no unit"
        scope[f"_v{k}"] = _q(unit)
    return eval(text, {"__builtins__": {}}, scope)  # noqa: S307 - expressions of this file


@pytest.mark.parametrize("name", sorted(RELATIONS))
def test_units_agree_with_the_relations_of_the_engineering_notes(name):
    unit = unit_of(name)
    assert unit is not None
    assert _q(unit).dimensionality == _value(RELATIONS[name]).dimensionality, (name, unit, RELATIONS[name])


def test_every_quantity_is_in_a_relation_and_every_unit_is_coherent_si():
    """No unit escapes the dimensional check, and each is SI without a prefix (1 of it is 1 in
    base units): "mm" or "MPa" would pass the dimension and still be wrong."""
    assert set(QUANTITIES) <= set(RELATIONS)
    names = set(QUANTITIES) | {
        "delta",
        "speed",
        "inertia",
        "design.max_outer_diameter",
        "design.max_width",
        "design.d_mean",
        "material.x.density",
        "material.x.max_rim_speed",
        "material.x.cost",
        "shaft.x.speed_ratio",
        "torque.scale",
    }
    for name in names:
        unit = unit_of(name)
        assert _q(unit).to_base_units().magnitude == pytest.approx(1.0, rel=1e-15), (name, unit)


def test_the_sweep_inputs_have_the_dimensions_their_values_are_read_in():
    """quantities.INPUTS against the sweep grammar itself (flyopt.io.sweep_spec), field by field:
    a new sweep field, or one read in another dimension, fails here."""
    from flyopt.io import sweep_spec

    assert set(quantities.INPUTS) == set(sweep_spec.FIELDS)
    for name, field in sweep_spec.FIELDS.items():
        assert quantities.INPUTS[name] == (field.dimension if field.kind == "number" else None), name
    for table, mine in (
        (sweep_spec._MATERIAL_FIELDS, quantities.MATERIAL_INPUTS),
        (sweep_spec._SHAFT_FIELDS, quantities.SHAFT_INPUTS),
    ):
        assert {k: f.dimension for k, f in table.items()} == mine
    assert not set(quantities.INPUTS) & set(QUANTITIES)  # one entry per name
    assert unit_of("material.cast_iron.density") == "kg/m**3" and unit_of("shaft.motor.speed_ratio") == "1"


def test_units_set_by_another_field():
    assert unit_of("objective", objective="mass") == "kg"
    assert unit_of("objective", objective="outer_diameter") == "m"
    assert unit_of("objective", objective="cost") == "1"
    assert unit_of("objective") is None and unit_of("dmass_dlimit") is None
    assert unit_of("epsilon", front="outer_diameter") == "m" and unit_of("epsilon", front="delta") == "1"
    assert unit_of("objective_bound", objective="mass") == "kg" and unit_of("objective_bound") is None
    assert unit_of("dobjective_dlimit") is None
    assert set(UNIT_SET_BY) == {"objective", "objective_bound", "epsilon", "dmass_dlimit", "dobjective_dlimit"}
    assert unit_of("status") is None and unit_of("iterations") is None and unit_of("design.geometry") is None


_NOMENCLATURE_UNITS = {"kg·m²": "kg*m**2", "N·m": "N*m", "N·m²": "N*m**2", "–": "1"}


def test_units_agree_with_the_nomenclature():
    """docs/nomenclature.md, written as documentation, gives each JSON name its SI unit: every
    row with one unit and JSON names agrees with the units map (56 names when written)."""
    checked = 0
    for line in (ROOT / "docs" / "nomenclature.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("| ") or len(cells) < 3 or cells[0] in ("symbol", "---"):
            continue
        names, unit = cells[1], cells[2]
        if any(ch in unit for ch in ",; ") or unit in ("—", "bool", ""):
            continue
        unit = _NOMENCLATURE_UNITS.get(unit, unit)
        for segment in names.split(";"):
            if "(" in segment:  # code or scene names, not JSON
                continue
            for path in re.findall(r"`([^`]+)`", segment):
                field = [p for p in re.split(r"\.|\[\]", path) if p][-1]
                if field in COUNTS:
                    continue
                mine = unit_of(field)
                assert mine is not None, path
                assert _q(unit).to(mine).magnitude == pytest.approx(1.0, rel=1e-15), (path, unit, mine)
                checked += 1
    assert checked >= 50


# --------------------------------------------------------------------------
# Tables: missing values, metadata, provenance
# --------------------------------------------------------------------------

#: Points that are designed by the closed form and by IPOPT, and infeasible (a 0.3 m envelope).
VARY = {
    "delta": "0.01,0.1",
    "design.max_outer_diameter": "0.3,1.2",
    "objective": "mass,outer_diameter",
    "speed": "60,120rpm",
}


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    folder = tmp_path_factory.mktemp("study")
    scene = flyopt.load(PROBLEMS / "punch-press.toml")
    frame = flyopt.sweep(scene, VARY, workers=1)
    for suffix in ("parquet", "csv"):
        flyopt.sweep(scene, VARY, output=folder / f"study.{suffix}", workers=1)
    return scene, frame, folder


def test_a_sweep_has_points_of_every_kind(study):
    _, frame, _ = study
    assert set(frame["status"]) == {"designed", "infeasible"}
    assert set(frame["method"]) == {"closed_form", "ipopt"}


def test_parquet_holds_nulls_not_empty_text_or_minus_one(study):
    """Read by pyarrow itself: where a point has no value the cell is null, never "" or -1 or NaN."""
    _, frame, folder = study
    table = pq.read_table(folder / "study.parquet")
    designed = np.array(table.column("status").to_pylist()) == "designed"
    ipopt = np.array(table.column("method").to_pylist()) == "ipopt"
    for name in ("best_material", "best_shaft", "binding"):
        column = table.column(name)
        assert (np.array(column.is_null().to_pylist()) == ~designed).all(), name
        assert "" not in column.to_pylist()
    iterations = table.column("iterations")
    assert str(iterations.type) == "int64"
    assert (np.array(iterations.is_null().to_pylist()) == ~(designed & ipopt)).all()
    assert -1 not in iterations.to_pylist()
    for name in ("mass", "d_outer", "cost", "design.d_mean"):
        column = table.column(name)
        assert not pc.any(pc.is_nan(column)).as_py(), name  # NaN is a value; no value is null
    assert table.column("mass").null_count == int((~designed).sum())
    assert table.column("design.d_mean").null_count == len(frame)  # no pinned mean diameter
    assert table.column("message").null_count > 0 and "" not in table.column("message").to_pylist()


def test_csv_holds_empty_cells_and_its_sidecar_says_so(study):
    _, frame, folder = study
    with open(folder / "study.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == len(frame)
    for row in rows:
        if row["status"] != "designed":
            assert row["best_material"] == row["mass"] == row["binding"] == ""
        if row["method"] != "ipopt" or row["status"] != "designed":
            assert row["iterations"] == ""
        assert "-1" not in (row["iterations"], row["n_feasible"]) and "nan" not in row.values()
    plain = pd.read_csv(folder / "study.csv")  # pandas without flyopt reads an empty cell as NaN
    assert plain["best_material"].isna().sum() == int((frame["status"] != "designed").sum())
    sidecar = json.loads((folder / "study.csv.json").read_text())
    assert _errors(sidecar) == []
    assert sidecar["csv"] == {"delimiter": ",", "header": True, "null": ""}
    assert [c["name"] for c in sidecar["columns"]] == list(plain.columns)
    types = {c["name"]: c["type"] for c in sidecar["columns"]}
    assert types["iterations"] == "integer" and types["best_material"] == "string" and types["mass"] == "number"


def test_the_frame_in_memory_has_the_same_nulls(study):
    _, frame, folder = study
    assert frame["best_material"].isna().equals(frame["status"] != "designed")
    assert str(frame["iterations"].dtype) == "Int64"
    assert frame["iterations"].isna().equals((frame["method"] != "ipopt") | (frame["status"] != "designed"))
    text = [c for c in frame.columns if results.column_kind(c, frame[c]) == "str"]
    assert len(text) >= 9 and not any(frame[c].dropna().eq("").any() for c in text)
    for suffix in ("parquet", "csv"):
        pd.testing.assert_frame_equal(read_results(folder / f"study.{suffix}"), frame)


def test_sweep_files_carry_units_and_provenance(study):
    """The metadata against values computed here: the scene file's SHA-256, flyopt's digest of the
    scene, the swept speeds in rad/s (60 rpm = 2 pi rad/s), the installed version."""
    scene, frame, folder = study
    stored = json.loads(pq.read_schema(folder / "study.parquet").metadata[b"flyopt"])
    sidecar = json.loads((folder / "study.csv.json").read_text())
    assert {k: v for k, v in sidecar.items() if k != "csv"} == stored
    assert _errors(stored) == []
    assert stored["kind"] == "sweep" and stored["flyopt_version"] == importlib.metadata.version("flyopt")
    assert stored["scene"] == str(PROBLEMS / "punch-press.toml")
    assert stored["scene_file_sha256"] == hashlib.sha256((PROBLEMS / "punch-press.toml").read_bytes()).hexdigest()
    assert stored["scene_digest"] == digest(flyopt.load(PROBLEMS / "punch-press.toml"))
    vary = stored["sweep"]["vary"]
    # 60 and 120 rpm in rad/s, to round-off (flyopt multiplies by pint's factor 2 pi/60 in one step)
    np.testing.assert_allclose(
        vary["speed"]["values"], [60 * 2 * math.pi / 60, 120 * 2 * math.pi / 60], rtol=1e-15, atol=0
    )
    assert vary["design.objective"]["values"] == ["mass", "outer_diameter"]
    assert stored["sweep"]["method"] == "auto" and stored["sweep"]["points"] == len(frame)
    units = stored["units"]
    assert units["speed"] == "rad/s" and units["mass"] == "kg" and units["design.max_outer_diameter"] == "m"
    assert units["a_max"] == "J" and units["delta"] == "1" and "status" not in units and "point" not in units
    assert units["objective"] is None  # the sweep varies the objective: kg or m by row
    assert [c["name"] for c in stored["columns"]] == list(frame.columns)
    assert read_results(folder / "study.parquet").attrs["flyopt"] == stored
    assert frame.attrs["flyopt"] == stored


def test_a_sweep_of_one_objective_gives_its_unit(tmp_path):
    out = tmp_path / "one.parquet"
    flyopt.sweep(flyopt.load(PROBLEMS / "shear-press.toml"), {"delta": "0.02,0.05"}, output=out)
    assert read_results(out).attrs["flyopt"]["units"]["objective"] == "kg"


def test_pareto_files_record_their_objectives_and_plot_needs_no_x(tmp_path, capsys, monkeypatch):
    """The objectives are read from the file's metadata, not guessed from its columns: a front
    whose columns were put in another order still plots its second objective along x."""
    from flyopt.report import plots

    drawn = []
    original = plots.plot_pareto
    monkeypatch.setattr(
        plots, "plot_pareto", lambda frame, x, y, ax=None, **kw: drawn.append(x) or original(frame, x, y, **kw)
    )
    for suffix in ("parquet", "csv", "json"):
        out = tmp_path / f"front.{suffix}"
        assert (
            main(
                [
                    "pareto",
                    str(PROBLEMS / "punch-press.toml"),
                    "--objectives",
                    "mass,delta",
                    "--points",
                    "4",
                    "-o",
                    str(out),
                    "-q",
                ]
            )
            == 0
        )
        assert capsys.readouterr().out == ""
        if suffix == "json":
            document = json.loads(out.read_text())
        else:
            document = read_results(out).attrs["flyopt"]
            frame = read_results(out)
            assert list(frame.columns[:2]) == ["mass", "delta"]
            shuffled = tmp_path / f"shuffled.{suffix}"
            columns = [c for c in frame.columns if c not in ("mass", "delta")] + ["delta", "mass"]
            assert plots.pareto_objectives(frame[columns]) is None  # the columns alone tell nothing
            results.write_results(
                frame[columns],
                shuffled,
                metadata=table_metadata("pareto", columns, objectives=document["objectives"]),
            )
            assert main(["plot", str(shuffled), "--what", "pareto", "-o", str(tmp_path / f"{suffix}.png")]) == 0
            assert drawn[-1] == "delta" and capsys.readouterr().out.startswith("wrote ")
        assert _errors(document) == [] and document["objectives"] == ["mass", "delta"]
        assert document["kind"] == "pareto" and document["units"]["epsilon"] == "1"
    assert "rows" in document and len(document["rows"]) == 4


def test_pareto_and_tradeoff_json_are_documents_with_nulls(tmp_path, capsys):
    scene = _variant(
        tmp_path, "s", (PROBLEMS / "shear-press.toml").read_text().replace("delta = 0.05", "delta = 0.004")
    )  # cast iron cannot give J_F (tests/studies/test_pareto_tradeoff.py)
    assert main(["tradeoff", str(scene), "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert _errors(document) == [] and document["kind"] == "tradeoff"
    rows = {r["material"]: r for r in document["rows"]}
    assert rows["cast_iron"]["status"] == "infeasible"
    assert rows["cast_iron"]["mass"] is None and rows["cast_iron"]["shaft"] is None
    assert rows["cast_iron"]["binding"] is None and rows["cast_steel"]["reason"] is None
    assert "" not in [v for r in document["rows"] for v in r.values()]
    assert document["units"]["mass"] == "kg" and document["units"]["rim_speed"] == "m/s"
    assert document["scene_file_sha256"] == hashlib.sha256(scene.read_bytes()).hexdigest()


def test_a_tradeoff_writes_parquet(tmp_path):
    """Regression: the trade-off's text columns (shaft, limit) were taken for numbers and
    ``flyopt tradeoff -o table.parquet`` failed with exit 1."""
    out = tmp_path / "table.parquet"
    assert main(["tradeoff", str(PROBLEMS / "punch-press.toml"), "-o", str(out), "-q"]) == 0
    table = read_results(out)
    assert list(table["material"]) == ["cast_steel", "ductile_iron", "cast_iron"]
    assert set(table["limit"]) == {"rim_speed,hb_min"}
    assert table.attrs["flyopt"]["kind"] == "tradeoff" and _errors(table.attrs["flyopt"]) == []


def test_a_mutated_table_document_fails(study):
    _, _, folder = study
    stored = json.loads(pq.read_schema(folder / "study.parquet").metadata[b"flyopt"])
    for mutate in (
        _delete(["units"]),
        _delete(["sweep"]),
        _set(["kind"], "pareto"),
        _set(["scene_file_sha256"], "abc"),
        _set(["columns", 0, "type"], "float"),
        _set(["sweep", "seed"], "none"),
    ):
        changed = json.loads(json.dumps(stored))
        mutate(changed)
        assert _errors(changed)


# --------------------------------------------------------------------------
# -o FILE and --quiet
# --------------------------------------------------------------------------


@pytest.mark.parametrize("options", [[], ["--json"]])
def test_solve_to_a_file_writes_what_it_prints(tmp_path, capsys, options):
    scene = str(PROBLEMS / "shear-press.toml")
    assert main(["solve", scene, *options]) == 0
    printed = capsys.readouterr().out
    out = tmp_path / "result.txt"
    assert main(["solve", scene, *options, "-o", str(out)]) == 0
    said = capsys.readouterr()
    assert said.out == f"wrote {out}\n" and said.err == ""
    assert out.read_text() == printed
    assert main(["solve", scene, *options, "-o", str(out), "--quiet"]) == 0
    assert capsys.readouterr() == ("", "") and out.read_text() == printed
    assert [p.name for p in tmp_path.iterdir()] == ["result.txt"]  # no temporary file left


def test_solve_to_a_file_is_all_or_nothing(tmp_path, capsys, monkeypatch):
    """A failure after part of the result was printed, or Ctrl-C, leaves the old file as it was
    and no temporary file."""
    import flyopt.cli.scene

    out = tmp_path / "result.json"
    out.write_text("earlier result\n")

    def half_then(error):
        def handler(args):
            print('{"a_max": 1,')
            raise error

        return handler

    for error, status in ((flyopt.SolverFailed("did not converge"), 1), (KeyboardInterrupt(), 130)):
        monkeypatch.setattr(flyopt.cli.scene, "run_solve", half_then(error))
        assert main(["solve", str(PROBLEMS / "shear-press.toml"), "-o", str(out)]) == status
        assert out.read_text() == "earlier result\n"
        assert [p.name for p in tmp_path.iterdir()] == ["result.json"]
        assert capsys.readouterr().out == ""


def test_a_text_file_is_written_whole_or_not_at_all(tmp_path):
    out = tmp_path / "result.txt"
    out.write_text("earlier\n")
    with pytest.raises(UnicodeEncodeError):
        write_text(out, "A_max = 1 J\n" * 1000 + "\ud800")  # fails half-way through
    assert out.read_text() == "earlier\n" and [p.name for p in tmp_path.iterdir()] == ["result.txt"]
    write_text(out, "A_max = 1 J")
    assert out.read_text() == "A_max = 1 J\n"


@pytest.mark.parametrize(
    "args, match",
    [
        (
            ["solve", str(PROBLEMS / "shear-press.toml"), "-o", "no/such/folder/x.json"],
            "-o/--output: the folder 'no/such/folder' of 'no/such/folder/x.json' does not exist",
        ),
        (
            ["solve", str(PROBLEMS / "shear-press.toml"), "-o", str(PROBLEMS / "shear-press.toml")],
            "is the scene file itself",
        ),
        (
            ["pareto", str(PROBLEMS / "shear-press.toml"), "-o", "front.txt"],
            "-o/--output: 'front.txt' must end in .csv, .parquet or .json",
        ),
        (
            ["tradeoff", str(PROBLEMS / "shear-press.toml"), "-o", "no/such/folder/t.json", "-q"],
            "-o/--output: the folder 'no/such/folder'",
        ),
        (["solve", str(PROBLEMS / "missing.toml"), "-q"], "missing.toml"),
    ],
)
def test_a_bad_output_is_one_line_and_status_2_even_when_quiet(args, match, capsys):
    assert main(args) == 2
    said = capsys.readouterr()
    assert said.out == "" and said.err.count("\n") == 1 and match in said.err
    assert "Traceback" not in said.err


def test_quiet_leaves_the_result_and_nothing_else(tmp_path, capsys):
    scene = str(PROBLEMS / "shear-press.toml")
    assert main(["check", scene, "--quiet"]) == 0
    assert capsys.readouterr() == ("", "")
    assert main(["plot", scene, "--what", "energy", "-o", str(tmp_path / "e.png"), "-q"]) == 0
    assert capsys.readouterr() == ("", "") and (tmp_path / "e.png").stat().st_size > 0
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-o", str(tmp_path / "s.csv"), "-q"]) == 0
    assert capsys.readouterr() == ("", "") and len(read_results(tmp_path / "s.csv")) == 2
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-q"]) == 0  # the result is stdout
    said = capsys.readouterr()
    assert said.err == "" and said.out.splitlines()[0].startswith("point,delta,")
    assert main(["solve", scene, "-q"]) == 0 and "A_max" in capsys.readouterr().out
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-o", str(tmp_path / "t.csv")]) == 0
    assert "flyopt sweep: wrote" in capsys.readouterr().err  # and without --quiet, the summary


# --------------------------------------------------------------------------
# Version, licence, typing
# --------------------------------------------------------------------------


def test_version_comes_from_the_package_metadata():
    run = subprocess.run([sys.executable, "-m", "flyopt", "--version"], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stderr == ""
    assert run.stdout == f"flyopt {importlib.metadata.version('flyopt')}\n"
    assert flyopt.__version__ == importlib.metadata.version("flyopt")


def test_version_is_fast_to_ask_for():
    """``flyopt --version`` builds the argparse tree and reads the metadata, nothing else: no numpy,
    pandas, CasADi; ``import flyopt`` does not even read the metadata."""
    code = (
        "import sys\nfrom flyopt.cli.main import main\n"
        "try:\n    main(['--version'])\nexcept SystemExit as stop:\n    assert stop.code in (0, None)\n"
        "print(sorted(m for m in ('numpy', 'pandas', 'casadi', 'scipy', 'pint', 'matplotlib') "
        "if m in sys.modules))\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[-1] == "[]"
    run = subprocess.run(
        [sys.executable, "-c", "import sys, flyopt; print('importlib.metadata' in sys.modules)"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.stdout.strip() == "False"


def test_an_uninstalled_source_tree_reads_its_pyproject(monkeypatch, tmp_path):
    def not_installed(name):
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "version", not_installed)
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert flyopt._version() == declared
    monkeypatch.setattr(flyopt, "__file__", str(tmp_path / "a" / "b" / "flyopt" / "__init__.py"))
    assert flyopt._version() == "unknown"  # no pyproject.toml above it


def test_the_licence_is_mit_and_pyproject_agrees():
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n") and "Copyright (c) 2026 the flyopt developers" in text
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"] == {"text": "MIT"}
    assert "License :: OSI Approved :: MIT License" in project["classifiers"]


def test_the_public_api_is_typed():
    """py.typed marks the package as typed (PEP 561); every public function annotates every
    parameter and its return."""
    assert (Path(flyopt.__file__).parent / "py.typed").is_file()
    functions = [getattr(flyopt, name) for name in flyopt.__all__ if inspect.isfunction(getattr(flyopt, name))]
    assert len(functions) >= 7
    for function in functions:
        signature = inspect.signature(function)
        missing = [p for p, v in signature.parameters.items() if v.annotation is inspect.Parameter.empty]
        assert not missing, (function.__qualname__, missing)
        assert signature.return_annotation is not inspect.Signature.empty, function.__qualname__
    for name in ("Scene", "Shaft", "Solution", "Analysis"):
        assert dataclasses.is_dataclass(getattr(flyopt, name))
