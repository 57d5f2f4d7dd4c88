"""The JSON Schema of the scene format (``flyopt/data/scene.schema.json``) and every structural error of a scene.

The schema is for editors (completion and checks as one types, see
docs/scene-schema.md) and for ``flyopt check``, which lists every error it
finds at once. It says what the loader (:mod:`flyopt.io.scene` and its
sections) accepts: which keys each table has, and whether a value is a table,
an array, a string, a boolean or a quantity (a number, or a string with its
unit); ``tests/cli/test_scene_schema.py`` holds the two to the same keys.
What lies beyond structure (a unit's dimension, a range, a name that must
exist) stays the loader's alone.

:func:`structural_errors` walks a scene against the schema with the few
keywords the schema uses (``type``, ``properties``, ``additionalProperties``,
``required``, ``items``, ``anyOf``, ``$ref``): the core installs no JSON Schema
library, and the test suite holds this walk to ``jsonschema``'s verdicts.
"""

from __future__ import annotations

import functools
import json
from importlib import resources
from typing import Any

from flyopt.names import hint

__all__ = ["SCHEMA_FILE", "schema", "structural_errors"]

SCHEMA_FILE = "scene.schema.json"
"""The schema's file name in the package's data folder."""

_TOML_TYPES = {
    "object": "a table",
    "array": "an array",
    "string": "a string",
    "number": "a number",
    "integer": "an integer",
    "boolean": "a boolean (true or false)",
}


@functools.cache
def schema() -> dict[str, Any]:
    """The scene schema, read once from the package's data."""
    text = resources.files("flyopt").joinpath("data", SCHEMA_FILE).read_text(encoding="utf-8")
    loaded: dict[str, Any] = json.loads(text)
    return loaded


def structural_errors(data: object) -> list[tuple[str, str]]:
    """Every structural error of a scene, as (field path, message), in the order of the document.

    Parameters
    ----------
    data : object
        The scene as read from TOML (:func:`flyopt.io.toml_file.read_toml`).

    Returns
    -------
    list of (str, str)
        Field paths spelled as the loader names fields (``member[0].mass``,
        zero-based), each with what is wrong: an unknown key (with the
        closest allowed one, :func:`flyopt.names.hint`), a value of the wrong
        type, a missing required key. Empty when the structure is sound.
    """
    errors: list[tuple[str, str]] = []
    _walk(data, schema(), "", errors)
    return errors


def _resolve(node: dict[str, Any]) -> dict[str, Any]:
    while "$ref" in node:
        name = node["$ref"].removeprefix("#/$defs/")
        node = schema()["$defs"][name]
    return node


def _type_ok(value: object, kind: str) -> bool:
    if kind == "object":
        return isinstance(value, dict)
    if kind == "array":
        return isinstance(value, list) or hasattr(value, "array")  # io.toml_file.InlineRows stands for a list
    if kind == "string":
        return isinstance(value, str)
    if kind == "boolean":
        return isinstance(value, bool)
    if kind == "integer":
        return isinstance(value, int) and not isinstance(value, bool)
    if kind == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    return True


def _expected(node: dict[str, Any]) -> list[str]:
    """What a node accepts, in words."""
    node = _resolve(node)
    if "title" in node:  # a definition that names itself ("a number, or a string with its unit")
        return [node["title"]]
    if "anyOf" in node:
        words: list[str] = []
        for branch in node["anyOf"]:
            words += [w for w in _expected(branch) if w not in words]
        return words
    kind = node.get("type")
    return [_TOML_TYPES[kind]] if kind else []


def _toml_type(value: object) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "string"
    if isinstance(value, dict):
        return "table"
    if isinstance(value, list) or hasattr(value, "array"):
        return "array"
    return type(value).__name__


def _walk(value: object, node: dict[str, Any], path: str, errors: list[tuple[str, str]]) -> None:
    node = _resolve(node)
    if "anyOf" in node:
        for branch in node["anyOf"]:
            trial: list[tuple[str, str]] = []
            _walk(value, branch, path, trial)
            if not trial:
                return
        words = _expected(node)
        errors.append((path or "(top level)", f"must be {' or '.join(words)}, got {_toml_type(value)}"))
        return
    kind = node.get("type")
    if kind is not None and not _type_ok(value, kind):
        errors.append((path or "(top level)", f"must be {_TOML_TYPES[kind]}, got {_toml_type(value)}"))
        return
    if isinstance(value, dict):
        properties: dict[str, Any] = node.get("properties", {})
        allowed = sorted(properties)
        for key, item in value.items():
            where = f"{path}.{key}" if path else key
            if key in properties:
                _walk(item, properties[key], where, errors)
            elif node.get("additionalProperties") is False:
                errors.append((where, f"unknown key{hint(key, allowed)} (allowed here: {', '.join(allowed)})"))
        for key in node.get("required", ()):
            if key not in value:
                errors.append((f"{path}.{key}" if path else key, "is missing"))
    elif "items" in node and isinstance(value, list):
        for k, item in enumerate(value):
            _walk(item, node["items"], f"{path}[{k}]", errors)
