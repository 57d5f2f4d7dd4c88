"""flyopt.names: the closed vocabularies, the one "did you mean" rule, and the one choice message.

The vocabularies are checked against what the user-facing documents list
(README's scene format and command table, the output schema), not against
the code's own constants.
"""

import json
import re
from pathlib import Path

import pytest

from flyopt import names
from flyopt.errors import QUOTE_LENGTH
from flyopt.names import Criterion, Geometry, Method, Model, Objective, choice, closest, hint, unknown

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
SCHEMA = json.loads((ROOT / "src" / "flyopt" / "data" / "output.schema.json").read_text(encoding="utf-8"))


def _design_block():
    """The commented ``[design]`` example of README's scene format."""
    start = README.index("[design]\ngeometry =")
    return README[start : README.index("```", start)]


def _alternatives(key):
    """The names README's ``[design]`` example lists for ``key`` (``a | b (words) | c``, continued lines too)."""
    lines = _design_block().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith(f"{key} ="))
    comment = lines[k].split("#", 1)[1]
    for line in lines[k + 1 :]:
        if not line.lstrip().startswith("# |"):
            break
        comment += " " + line.split("#", 1)[1]
    given = re.match(rf'{key} = "(\w+)"', lines[k]).group(1)
    listed = [re.fullmatch(r"\s*(\w+)\s*(\(.*\))?\s*", part) for part in comment.split("|")]
    return sorted({given} | {m.group(1) for m in listed if m})  # "the textbook limit (default)" names no value


@pytest.mark.parametrize(
    "vocabulary, documented",
    [
        (Geometry, lambda: _alternatives("geometry")),
        (Objective, lambda: _alternatives("objective")),
        (Criterion, lambda: _alternatives("criterion")),
        (Model, lambda: re.findall(r"^\| `(\w+)` \|", README[README.index("| model | when |") :], re.M)[:3]),
        (Model, lambda: SCHEMA_MODEL),
        (Model, lambda: re.search(r"--model (\S+)`", README).group(1).split("\\|")),
    ],
)
def test_vocabulary_is_what_the_documents_list(vocabulary, documented):
    assert sorted(vocabulary.values()) == sorted(documented())


def _schema_model(node):
    """The ``enum`` of the schema's ``model`` property, wherever it sits."""
    if isinstance(node, dict):
        if isinstance(node.get("model"), dict) and "enum" in node["model"]:
            return node["model"]["enum"]
        for value in node.values():
            found = _schema_model(value)
            if found:
                return found
    elif isinstance(node, list):
        for value in node:
            found = _schema_model(value)
            if found:
                return found
    return None


SCHEMA_MODEL = _schema_model(SCHEMA)


def test_design_methods_are_the_ones_the_command_table_names():
    row = next(line for line in README.splitlines() if line.startswith("| `flyopt solve SCENE.toml --design-method"))
    assert {m for m in Method.values() if f"`{m}`" in row or f"method {m}`" in row} == set(Method.values())


@pytest.mark.parametrize("member", [*Model, *Geometry, *Objective, *Criterion, *Method])
def test_a_member_is_its_string(member):
    text = member.value
    assert member == text and text == member
    assert json.dumps(member) == json.dumps(text)
    assert json.dumps({member: [member]}) == json.dumps({text: [text]})
    assert f"{member}" == str(member) == text
    assert repr(member) == repr(text)
    assert {text: 1}[member] == 1 and {member: 1}[text] == 1  # the hash is the string's
    assert type(member)(text) is member


@pytest.mark.parametrize(
    "name, allowed, expected",
    [
        ("rimm", Geometry, "rim"),
        ("thinrim", Geometry, "thin_rim"),
        ("energy-mass", Model, "energy_mass"),
        ("outer_diamter", Objective, "outer_diameter"),
        ("cast_irn", ["cast_iron", "cast_steel"], "cast_iron"),
        ("zzzz", Geometry, None),  # nothing near: no hint at all
        ("flywheel", Model, None),
        (42, Criterion, None),
    ],
)
def test_closest_offers_the_near_name_only(name, allowed, expected):
    assert closest(name, allowed) == expected
    assert hint(name, allowed) == (f"; did you mean {expected!r}?" if expected else "")


def test_closest_returns_a_plain_string():
    assert type(closest("dynamc", Model)) is str


def test_choice_words_one_line_naming_field_value_hint_and_allowed():
    assert choice("disc", Geometry, "geometry") == "disc"
    with pytest.raises(ValueError) as err:
        choice("rimm", Geometry, "geometry")
    assert str(err.value) == (
        "geometry 'rimm' is not known; did you mean 'rim'? (allowed: thin_rim, rim, disc, rim_web, rim_arms)"
    )
    with pytest.raises(ValueError, match=r"^method 'newton' is not known \(allowed: auto, ipopt, closed_form\)$"):
        choice("newton", Method, "method")
    # a long value is quoted cut (about QUOTE_LENGTH characters and its length), beside the allowed names
    long = unknown("x" * 1000, Criterion)
    assert long.count("\n") == 0 and len(long) - len(unknown("x", Criterion)) < QUOTE_LENGTH + 30


def test_only_names_asks_difflib():
    """One closest-match rule: no other module of the package calls difflib."""
    src = ROOT / "src" / "flyopt"
    users = sorted(str(p.relative_to(src)) for p in src.rglob("*.py") if "difflib" in p.read_text(encoding="utf-8"))
    assert users == ["names.py"]


def test_one_toml_reader():
    """tomllib/tomli are imported in flyopt._toml alone."""
    src = ROOT / "src" / "flyopt"
    pattern = re.compile(r"^\s*(import tomllib|import tomli|from tomllib|from tomli)", re.M)
    users = sorted(str(p.relative_to(src)) for p in src.rglob("*.py") if pattern.search(p.read_text(encoding="utf-8")))
    assert users == ["_toml.py"]


def test_names_imports_nothing_of_flyopt_but_errors():
    text = Path(names.__file__).read_text(encoding="utf-8")
    assert set(re.findall(r"^\s*(?:from|import) (flyopt\S*)", text, re.M)) == {"flyopt.errors"}
