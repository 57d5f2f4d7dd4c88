"""flyopt.outputs.documents: the JSON documents and the schema they follow (issue 15, part 3).

Every JSON document validates against the JSON Schema shipped with the package, and the
schema refuses a wrong type, a missing field and an unknown one (mutations of valid documents).
"""

import dataclasses
import importlib.metadata
import json

import jsonschema
import pytest
from conftest import PROBLEMS, ROOT

import flyopt
from flyopt.cli.main import main
from flyopt.outputs.documents import SCHEMA_FILE, json_text, schema, schema_version, solution_document

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from output_cases import (
    FAST,
    assert_units_cover,
    delete_at,
    punch,
    scene_params,
    schema_errors,
    set_at,
    solve_document,
    solved_documents,
    variant,
)


@pytest.fixture(scope="module")
def documents():
    return {f"{stem}/{k}": d for stem in FAST for k, d in enumerate(solved_documents(stem))}


# --------------------------------------------------------------------------
# The JSON Schema
# --------------------------------------------------------------------------


def test_the_schema_is_a_valid_draft_2020_12_schema():
    jsonschema.Draft202012Validator.check_schema(schema())
    assert schema()["$schema"] == "https://json-schema.org/draft/2020-12/schema"


@pytest.mark.parametrize("stem", scene_params())
def test_every_problem_scene_validates(stem):
    """The document of every problem scene (designed, verified, timed; and without a design)
    validates, and every number in it has its unit (or is a count)."""
    for document in solved_documents(stem):
        assert schema_errors(document) == []
        assert document["schema_version"] == schema_version() and document["kind"] == "solve"
        assert document["flyopt_version"] == importlib.metadata.version("flyopt")
        assert_units_cover(document)


def test_the_documents_cover_every_branch_of_the_schema(documents, tmp_path):
    """Designed, not needed and infeasible designs, the key, arms, costs, --verify, startup, timings:
    each occurs in a document that validates (a schema tested on none of them tests nothing)."""
    more = {
        "infeasible": solve_document(variant(tmp_path, "tiny", punch(**{'"1.2 m"': '"0.1 m"'}))),
        "cost": solve_document(
            variant(
                tmp_path,
                "cost",
                punch(
                    **{
                        'materials = ["cast_iron", "cast_steel", "ductile_iron"]': 'materials = ["ductile_iron"]\nobjective = "cost"',
                        'density = "7100 kg/m^3"': 'density = "7100 kg/m^3"\ncost = "2.1 1/kg"',
                    }
                ),
            )
        ),
        "arms": solve_document(ROOT / "tests" / "data" / "wheels" / "engine-rim_arms.toml"),
    }
    more["drive"] = _drive_document()
    for name, document in more.items():
        assert schema_errors(document) == [], name
        assert_units_cover(document)
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
        runs=(run, MotorRun(motor=motor, feasible=False, reason="too small: ...", refusal="too small")),
        relaxation=Relaxation(5000.0, 24.0, 24.0, 800.0, 57.0, "Solve_Succeeded"),
        note="relaxation",
    )
    check = DriveCheck(
        verification=solution.verification, rms_torque=30.0, rated_torque=36.0, startup_time=5.0, flagged=False
    )
    with_drive = dataclasses.replace(solution, drive=drive, drive_check=check)
    return json.loads(json_text(solution_document(with_drive, "drive.toml")))


@pytest.mark.parametrize(
    "mutate, why",
    [
        (set_at(["a_max"], "1256 J"), "a number as text"),
        (set_at(["flywheel_needed"], "yes"), "a boolean as text"),
        (set_at(["flywheel_needed"], None), "null where a value must be"),
        (set_at(["index_omega_max"], 1.5), "a fraction for an index"),
        (set_at(["energy_chain"], {}), "an object for a list"),
        (set_at(["design", "mass"], "heavy"), "the winner's mass as text"),
        (set_at(["design", "candidates", 0, "feasible"], 1), "a number for a boolean"),
        (set_at(["design", "candidates", 0, "parts", 0, "mass"], None), "a part without mass"),
        (set_at(["design", "binding"], "inertia"), "text for a list"),
        (set_at(["units", "mass"], 1), "a unit that is no text"),
        (set_at(["schema_version"], "0.9"), "another schema version"),
        (set_at(["kind"], "report"), "an unknown kind"),
        (set_at(["design", "status"], "maybe"), "an unknown design status"),
        (set_at(["surprise"], 1), "a field the schema does not know"),
        (set_at(["design", "candidates", 0, "stress", "surprise"], 1.0), "a field deep inside"),
        (delete_at(["a_max"]), "a missing analysis field"),
        (delete_at(["units"]), "no units"),
        (delete_at(["schema_version"]), "no version"),
        (delete_at(["design", "candidates", 0, "reason"]), "a candidate without its reason"),
        (delete_at(["design", "key"]), "a design without its key field"),
        (delete_at(["shafts", 0, "omega"]), "a shaft without its speed"),
    ],
)
def test_a_mutated_document_fails(documents, mutate, why):
    document = json.loads(json.dumps(documents["punch-press-wheel/0"]))
    assert schema_errors(document) == []
    mutate(document)
    assert schema_errors(document), why


def test_the_not_needed_design_has_its_own_form(documents):
    document = json.loads(json.dumps(documents["conveyor/0"]))
    assert document["design"]["status"] == "not_needed" and schema_errors(document) == []
    document["design"]["mass"] = 1.0  # a not-needed design carries no wheel
    assert schema_errors(document)


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
    assert schema_errors(json.loads(capsys.readouterr().out)) == []


def _entries_with(document, key, path=""):
    """(path, the dict) of every object of ``document`` that holds ``key``."""
    if isinstance(document, dict):
        if key in document:
            yield path, document
        for name, value in document.items():
            yield from _entries_with(value, key, f"{path}.{name}")
    elif isinstance(document, list):
        for k, value in enumerate(document):
            yield from _entries_with(value, key, f"{path}[{k}]")


@pytest.mark.parametrize("scene, options", [("press-drive", ()), ("punch-press-wheel", ("--verify",))])
def test_each_inertia_has_one_name_in_a_solve_document(main_cli, scene, options):
    """One meaning per name in ``solve --json``: ``j_flywheel`` is a wheel's inertia about its own axis on its
    own shaft wherever it appears, which cannot exceed its mass times its outer radius squared. A drive's motor
    size said ``j_flywheel`` for the least inertia at the crank (press-drive's 4 kW size: 45,926 kg·m² for a wheel
    of 1.2 m), and the verification for the wheel at the reference shaft: they are ``j_required`` and
    ``j_at_reference``, as the design's and a sweep's columns name them, and the numbers agree across them."""
    status, out, err = main_cli("solve", PROBLEMS / f"{scene}.toml", "--json", *options)
    assert status == 0, err
    document = json.loads(out)
    assert document["units"]["j_flywheel"] == "kg*m**2"  # the document's one unit per name
    wheels = [(path, entry) for path, entry in _entries_with(document, "j_flywheel") if path != ".units"]
    assert wheels
    for path, wheel in wheels:
        if wheel["j_flywheel"] is not None:  # null: a combination with no wheel
            assert wheel["j_flywheel"] <= wheel["mass"] * (wheel["d_outer"] / 2) ** 2, path
    if scene == "press-drive":
        drive = document["drive"]
        for run in drive["runs"]:
            assert run["j_required"] >= run["j_delta"]
            if run["wheel"] is not None:  # the wheel built gives at least what the size needs, at the crank
                assert run["wheel"]["j_at_reference"] >= run["j_required"] * (1 - 1e-9)
                ratio = run["flywheel_ratio"]
                assert run["wheel"]["j_flywheel"] * ratio**2 == pytest.approx(run["wheel"]["j_at_reference"], rel=1e-12)
        assert drive["relaxation"]["j_required"] > 0
        best_wheel = drive["best"]["wheel"]
        built = 0.0 if best_wheel is None else best_wheel["j_at_reference"]
        assert drive["verification"]["j_at_reference"] == pytest.approx(built, abs=1e-12)
    else:
        assert document["verification"]["j_at_reference"] == document["design"]["j_at_reference"]
