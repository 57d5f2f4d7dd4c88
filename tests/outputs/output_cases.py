"""Problem scenes solved once and what the output tests do with their documents: validate them
against the schema, mutate them, check that their units cover every number.
"""

import json

import jsonschema
import pytest
from conftest import PROBLEMS, ROOT

import flyopt
from flyopt.outputs.documents import json_text, schema, solution_document
from flyopt.outputs.quantities import COUNTS

SCENES = sorted(PROBLEMS.glob("*.toml"))
VALIDATOR = jsonschema.Draft202012Validator(schema(), format_checker=jsonschema.FormatChecker())


def schema_errors(document):
    return [f"{e.json_path}: {e.message[:200]}" for e in VALIDATOR.iter_errors(document)]


#: Problem scenes whose solve takes long: their documents are checked in the slow set only
#: (press-drive designs its motor with the flywheel, some 50 s).
SLOW_SCENES = {"press-drive"}
#: The scenes the fast checks of the schema and the units use (every branch of the schema occurs).
FAST = ("punch-press-wheel", "conveyor", "motor-press", "example1-net-areas", "punch-press", "slider-crank-press")
_SOLVED = {}


def solved_documents(stem):
    """The JSON of ``flyopt solve --verify --timings`` for a problem scene, as the CLI prints it
    (through JSON text and back), and of ``--no-design``; computed once per scene."""
    if stem not in _SOLVED:
        path = PROBLEMS / f"{stem}.toml"
        scene, name = flyopt.load(path), str(path.relative_to(ROOT))
        solution = flyopt.solve(scene, verify_design=True)
        bare = flyopt.solve(scene, design_flywheel=False)
        _SOLVED[stem] = [
            json.loads(json_text(solution_document(s, name, timings=t))) for s, t in ((solution, True), (bare, False))
        ]
    return _SOLVED[stem]


def scene_params():
    return [pytest.param(p.stem, marks=pytest.mark.slow) if p.stem in SLOW_SCENES else p.stem for p in SCENES]


def variant(tmp_path, name, text):
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def punch(**changes):
    """problems/punch-press.toml with some of its lines replaced."""
    text = (PROBLEMS / "punch-press.toml").read_text()
    for old, new in changes.items():
        assert old in text
        text = text.replace(old, new)
    return text


def solve_document(path, **options):
    solution = flyopt.solve(flyopt.load(path), **options)
    return json.loads(json_text(solution_document(solution, str(path))))


def set_at(path, value):
    def mutate(document):
        target = document
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value

    return mutate


def delete_at(path):
    def mutate(document):
        target = document
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]

    return mutate


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


def assert_units_cover(document):
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
