"""The scene schema (flyopt/data/scene.schema.json) against the loader, and check's walk against jsonschema.

The schema is written by hand; these tests keep it from drifting from the
loader: the keys of every table the loader reads (recorded from the loader's
own ``Table`` calls) are the keys of the schema's table, both ways; every
shipped scene validates; scenes the loader refuses for structure are refused
by the schema too, at the same fields by ``jsonschema`` (the reference) and by
the walk ``flyopt check`` uses.
"""

import json
import re
from pathlib import Path

import pytest
from conftest import PROBLEMS, ROOT

from flyopt.cli.scene_schema import schema, structural_errors
from flyopt.errors import SceneError

jsonschema = pytest.importorskip("jsonschema")  # the test extra brings it

SCHEMA_PATH = ROOT / "src" / "flyopt" / "data" / "scene.schema.json"
SHIPPED = sorted([*PROBLEMS.rglob("*.toml"), *(ROOT / "tests" / "data").rglob("*.toml")])
TEMPLATES = sorted((ROOT / "src" / "flyopt" / "data" / "templates").glob("*.toml"))

# Tables the shipped scenes do not reach: a snippet that makes the loader build each one's Table (the
# loader may refuse the rest of the snippet; its list of keys is recorded before).
REACH = [
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.driving]\nmotor = { kind = "dc" }\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.driving]\nmotor = { kind = "table" }\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.resisting]\nmotor = { kind = "induction" }\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[mechanism]\nkind = "gear_train"\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[mechanism]\nkind = "four_bar"\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.net]\nareas = [1, -1]\n[drive]\nratio = [2, 8]\n'
    '[[motor_option]]\nname = "m"\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.net]\nareas = [1, -1]\n[design]\ngeometry = "rim_web"\n'
    "[design.castability]\nsection_ratio = 1.2\n",
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.net]\nareas = [1, -1]\n[[shaft]]\nname = "s"\n'
    "speed_ratio = 1\nsegments = [{ to = 1, diameter = 0.1 }]\nbearings = [0, 1]\nwheel_at = 0.5\ntorque_at = 1\n"
    'material = "m"\nloads = [{ at = 0.5, force = 1 }]\n',
    '[machine]\nspeed = "100 rpm"\ndelta = 0.1\n[torque.net]\nareas = [1, -1]\n[[shaft]]\nname = "s"\n'
    "speed_ratio = 1\nsegments = [{ to = 1, diameter = 0.1 }]\nbearings = [0, 1]\nwheel_at = 0.5\ntorque_at = 1\n"
    'material = "m"\ntrain = [{ flywheel = true }, { stiffness = 1 }, { inertia = 1 }]\n',
]


def _text(path):
    return Path(path).read_text(encoding="utf-8")


def _toml(path):
    from flyopt._toml import tomllib

    return tomllib.loads(_text(path))


def _node(node):
    """A schema node with its $ref followed and, for a value of several forms, its table form."""
    while "$ref" in node:
        node = schema()["$defs"][node["$ref"].removeprefix("#/$defs/")]
    for branch in node.get("anyOf", ()):
        if _node(branch).get("type") == "object":
            return _node(branch)
    return node


def _schema_table(where):
    """The schema's node of a loader's table path, e.g. ``member[]`` or ``torque.driving.motor``."""
    node = _node(schema())
    trail = "/properties"
    for part in where.split(".") if where else ():
        name, arrays = part.rstrip("[]"), part.count("[]")
        if name not in node.get("properties", {}):
            return None, trail
        node = _node(node["properties"][name])
        trail += f"/{name}"
        for _ in range(arrays):
            node = _node(node["items"])
            trail += "/items"
        trail += "/properties"
    return node, trail


@pytest.fixture(scope="module")
def loader_tables():
    """Every table the loader reads from the shipped scenes and REACH: its path and the keys it allows."""
    import flyopt.io.fields as fields
    from flyopt.io.scene import from_dict, load
    from flyopt.io.toml_file import read_toml

    recorded = {}
    original = fields.Table.__init__

    def recording(self, data, where, allowed):
        allowed = set(allowed)
        recorded.setdefault(re.sub(r"\[\d+\]", "[]", where), set()).update(allowed)
        original(self, data, where, allowed)

    fields.Table.__init__ = recording
    try:
        for path in [*SHIPPED, *TEMPLATES]:
            try:
                load(path, read_toml(path))
            except SceneError:
                pass  # a scene kept to be refused: its tables up to the refusal still count
        from flyopt._toml import tomllib

        for text in REACH:
            try:
                from_dict(tomllib.loads(text))
            except (SceneError, ValueError):
                pass
    finally:
        fields.Table.__init__ = original
    return recorded


def test_the_schema_is_a_valid_draft_2020_12_schema():
    document = json.loads(_text(SCHEMA_PATH))
    assert document["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    jsonschema.Draft202012Validator.check_schema(document)
    assert document == schema()  # the file check reads is the one shipped


def test_every_key_the_loader_accepts_is_in_the_schema_and_no_other(loader_tables):
    """Per schema table, the union of the loader's keys of every path that lands there (a motor's kinds,
    a mechanism's kinds and the curves of driving and resisting share one table) equals its properties."""
    by_node, trails = {}, {}
    tables = dict(loader_tables)
    # from_dict reads [press], [energy] and [strokes] before the top level (it rewrites them into a scene):
    # every section the loader reads is a key of the top level
    tables[""] = tables[""] | {where.split(".")[0].rstrip("[]") for where in tables if where}
    for where, keys in tables.items():
        node, trail = _schema_table(where)
        assert node is not None, (
            f"the loader reads a table [{where}] that src/flyopt/data/scene.schema.json lacks: "
            f"add it at {trail} (type object, its keys {sorted(keys)}, additionalProperties false)"
        )
        by_node.setdefault(id(node), (node, set()))[1].update(keys)
        trails.setdefault(id(node), trail)
    for key, (node, keys) in by_node.items():
        written = set(node["properties"])
        assert keys <= written, (
            f"the loader accepts {sorted(keys - written)} where src/flyopt/data/scene.schema.json has no such key: "
            f"add {', '.join(repr(k) for k in sorted(keys - written))} at {trails[key]}, each with its type "
            "(a quantity with units: {'$ref': '#/$defs/quantity'}) and a description"
        )
        assert written <= keys, (
            f"src/flyopt/data/scene.schema.json allows {sorted(written - keys)} at {trails[key]}, which the "
            "loader refuses: remove them from the schema"
        )
    node = _node(schema())  # every table of the schema is one the loader reads (else it goes unchecked here)
    unreached = [path for path in _object_paths(node, "") if id(_schema_table(path)[0]) not in by_node]
    assert unreached == ["sweep"], f"tables of the schema no shipped scene nor REACH makes the loader read: {unreached}"


def _object_paths(node, where, seen=None):
    """The loader-style paths of every table with declared properties in the schema (each table once)."""
    seen = set() if seen is None else seen
    seen.add(id(node))
    paths = [where]
    for name, child in node.get("properties", {}).items():
        path = f"{where}.{name}" if where else name
        child = _node(child)
        while child.get("type") == "array" and "items" in child:
            child, path = _node(child["items"]), path + "[]"
        if child.get("type") == "object" and "properties" in child and id(child) not in seen:
            paths += _object_paths(child, path, seen)
    return paths


def test_the_sweep_keys_are_the_loaders(tmp_path):
    """[sweep] is read by flyopt.io.sweep_spec, which names what it allows when it refuses a key."""
    from flyopt.io.sweep_spec import load_sweep

    path = tmp_path / "s.toml"
    path.write_text(_text(PROBLEMS / "shear-press.toml") + "\n[sweep]\nnot_a_key = 1\n")
    with pytest.raises(SceneError) as refusal:
        load_sweep(path)
    loader = set(re.search(r"allowed here: ([^)]*)\)", refusal.value.message).group(1).split(", "))
    assert set(schema()["properties"]["sweep"]["properties"]) == loader


@pytest.mark.parametrize("path", SHIPPED + TEMPLATES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_shipped_scene_that_loads_validates(path):
    from flyopt.io.scene import load

    try:
        load(path)
    except SceneError:
        return  # kept to be refused
    errors = list(jsonschema.Draft202012Validator(schema()).iter_errors(_toml(path)))
    assert not errors, [(list(e.absolute_path), e.message) for e in errors]
    assert structural_errors(_toml(path)) == []


def _reference_fields(document):
    """jsonschema's errors as field paths spelled as the loader spells them (its unknown and missing keys
    are reported at the table: here at the key)."""
    fields = set()
    for error in jsonschema.Draft202012Validator(schema()).iter_errors(document):
        path = ""
        for part in error.absolute_path:
            path += f"[{part}]" if isinstance(part, int) else (f".{part}" if path else part)
        if error.validator == "additionalProperties":
            for key in re.findall(r"'([^']*)'", error.message.split("(")[1]):
                fields.add(f"{path}.{key}" if path else key)
        elif error.validator == "required":
            key = re.match(r"'([^']*)'", error.message).group(1)
            fields.add(f"{path}.{key}" if path else key)
        else:
            fields.add(path or "(top level)")
    return fields


GOOD = '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.net]\nareas = [1, -1]\n'
BROKEN = [
    ("unknown top-level key", GOOD + "[desing]\ngeometry = 'rim'\n", {"desing"}),
    ("unknown key", GOOD.replace("delta", "deltaa"), {"machine.deltaa"}),
    ("wrong type, boolean quantity", GOOD.replace("0.05", "true"), {"machine.delta"}),
    ("wrong type, table for a quantity", GOOD.replace("0.05", "{ a = 1 }"), {"machine.delta"}),
    ("wrong type, section not a table", "machine = 3\n[torque.net]\nareas = [1, -1]\n", {"machine"}),
    ("wrong type, title", 'title = ["a"]\n' + GOOD, {"title"}),
    ("array of tables given as a table", GOOD + "[material]\nname = 'x'\n", {"material"}),
    ("missing required", GOOD + "[[material]]\ndensity = 7000\n", {"material[0].name"}),
    ("wrong type in an array", GOOD.replace("[1, -1]", "[1, true]"), {"torque.net.areas[1]"}),
    (
        "unknown key in an inline table",
        GOOD.replace("[torque.net]\nareas = [1, -1]", "[torque.driving]\nmotor = { kind = 'dc', rated = 1 }"),
        {"torque.driving.motor.rated"},
    ),
    ("a name not in the schema's list", GOOD + "[design]\ndiameter_series = 'R7'\n", {"design.diameter_series"}),
    (
        "an array of the wrong length",
        GOOD + '[[shaft]]\nname = "s"\nspeed_ratio = 1\nsegments = [{ to = 1, diameter = 0.1 }]\n'
        'bearings = [0, 0.5, 1]\nwheel_at = 0.5\ntorque_at = 1\nmaterial = "m"\n',
        {"shaft[0].bearings"},
    ),
    (
        "three errors at once",
        GOOD.replace("delta", "deltaa") + "[design]\nmaterials = 'cast_iron'\nfem_check = 'yes'\n",
        {"machine.deltaa", "design.materials", "design.fem_check"},
    ),
]


@pytest.mark.parametrize("what, text, fields", BROKEN, ids=[case[0] for case in BROKEN])
def test_a_scene_refused_for_structure_is_refused_by_the_schema_at_the_same_fields(tmp_path, what, text, fields):
    from flyopt._toml import tomllib
    from flyopt.io.scene import from_dict

    document = tomllib.loads(text)
    with pytest.raises(SceneError) as refusal:  # the loader refuses it ...
        from_dict(document)
    assert refusal.value.field in fields
    assert _reference_fields(document) == fields  # ... jsonschema too, at these fields ...
    assert {field for field, _ in structural_errors(document)} == fields  # ... and check's walk


def test_an_unknown_key_is_said_with_the_loaders_hint():
    errors = dict(structural_errors({"machine": {"sped": 1}}))
    assert errors["machine.sped"].startswith("unknown key; did you mean 'speed'? (allowed here: ")


def test_the_schemas_lists_of_names_are_the_loaders():
    """The schema's enums, which `flyopt check` now walks, name what the loader allows, no more and no less."""
    from flyopt.design.preferred import SERIES
    from flyopt.design.shaft.strength import FINISHES

    properties = schema()["properties"]
    shaft = properties["shaft"]["items"]["properties"]
    assert properties["design"]["properties"]["diameter_series"]["enum"] == list(SERIES)
    assert shaft["diameter_series"]["enum"] == list(SERIES)
    assert shaft["finish"]["enum"] == list(FINISHES)


def _mutated(document, rng):
    """``document`` with one to three of its values replaced, keys removed or added, or array items repeated."""
    import copy

    values = [0, 1, 3.0, 2.5, -1, "x", "design", "R7", "10 mm", True, [], [1, 2, 3], {}, {"a": 1}, ["a", "b"]]
    document = copy.deepcopy(document)
    for _ in range(rng.randint(1, 3)):
        spots, stack = [], [((), document)]
        while stack:
            path, node = stack.pop()
            if path:
                spots.append(path)
            items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
            stack.extend((path + (key,), child) for key, child in items)
        path = rng.choice(spots)
        parent = document
        for key in path[:-1]:
            parent = parent[key]
        if rng.random() < 0.7:
            parent[path[-1]] = copy.deepcopy(rng.choice(values))
        elif isinstance(parent, dict):
            parent.pop(path[-1]) if rng.random() < 0.5 else parent.setdefault("zz_unknown", 1)
        else:
            parent.append(copy.deepcopy(parent[path[-1]]))
    return document


def test_the_walk_and_jsonschema_agree_on_mutated_scenes():
    """The walk's verdict (and its quick pass, which decides alone for a sound document) is jsonschema's on 400
    shipped scenes mutated at random (seeded)."""
    import random

    rng = random.Random(20261201)
    validator = jsonschema.Draft202012Validator(schema())
    for k in range(400):
        document = _mutated(_toml(SHIPPED[k % len(SHIPPED)]), rng)
        mine, theirs = structural_errors(document), list(validator.iter_errors(document))
        assert bool(mine) == bool(theirs), (SHIPPED[k % len(SHIPPED)].name, mine[:2], [e.message for e in theirs[:2]])
