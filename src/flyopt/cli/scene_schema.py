"""The JSON Schema of the scene format (``flyopt/data/scene.schema.json``) and every structural error of a scene.

The schema is for editors (completion and checks as one types, see
docs/scene-schema.md) and for ``flyopt check``, which lists every error it
finds at once. It says what the loader (:mod:`flyopt.io.scene` and its
sections) accepts: which keys each table has, and whether a value is a table,
an array, a string, a boolean or a quantity (a number, or a string with its
unit); ``tests/cli/test_scene_schema.py`` holds the two to the same keys.
What lies beyond structure (a unit's dimension, a range, a name that must
exist) stays the loader's alone.

:func:`structural_errors` walks a scene against the schema by
:func:`flyopt.io.json_shape.shape_errors` (the core installs no JSON Schema
library; the test suite holds the walk to ``jsonschema``'s verdicts), in TOML's
words: "a table", "got float".
"""

from __future__ import annotations

import functools
import json
from importlib import resources
from typing import Any

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

_TOML_NAMES = {"bool": "boolean", "int": "integer", "float": "float", "str": "string", "dict": "table", "list": "array"}


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
    from flyopt.io.json_shape import shape_errors

    return shape_errors(data, schema(), schema(), words=_TOML_TYPES, names=_TOML_NAMES)
