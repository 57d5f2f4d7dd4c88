"""A document's shape against one of flyopt's JSON Schemas: every error, each at its field.

flyopt ships two schemas, the scene's (``flyopt/data/scene.schema.json``,
read by ``flyopt check``) and that of what it writes
(``flyopt/data/output.schema.json``, whose ``table`` definition is the
metadata of a sweep, Pareto or trade-off file, read back by
:func:`flyopt.outputs.results.read_results`). The core installs no JSON
Schema library; :func:`shape_errors` walks a document against a schema node
with the keywords those two use for shape: ``$ref``, ``anyOf``, ``type`` (one
or a list), ``properties``, ``additionalProperties``, ``required``,
``items``, ``prefixItems``, ``minItems``, ``maxItems``, ``enum``, ``const``
and ``pattern``. The test suite holds its verdicts to ``jsonschema``'s.
Conditional keywords (``if``/``then``, ``allOf``, ``oneOf``) and bounds
(``minimum``) are not walked: the loaders decide what lies beyond shape.

An *open* walk (``open_=True``) checks only the keys a document has: no key
is missing and none unknown. A table written by another minor version of the
schema (whose minor number grows when fields are added) is read so, each
field flyopt uses held to its shape.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import Any

from flyopt.errors import shorten
from flyopt.names import hint

__all__ = ["JSON_NAMES", "JSON_WORDS", "shape_errors"]

#: Each JSON type in words, for "must be ..." (a schema definition with a ``title`` names itself instead).
JSON_WORDS = {
    "object": "an object",
    "array": "an array",
    "string": "a string",
    "number": "a number",
    "integer": "an integer",
    "boolean": "a boolean (true or false)",
    "null": "null",
}

#: The name of a value's type, for "..., got NAME".
JSON_NAMES = {
    "bool": "boolean",
    "int": "integer",
    "float": "number",
    "str": "string",
    "dict": "object",
    "list": "array",
}


def shape_errors(
    value: object,
    node: Mapping[str, Any],
    root: Mapping[str, Any],
    *,
    open_: bool = False,
    words: Mapping[str, str] = JSON_WORDS,
    names: Mapping[str, str] = JSON_NAMES,
) -> list[tuple[str, str]]:
    """Every shape error of ``value`` against the schema ``node`` of the schema document ``root``.

    Parameters
    ----------
    value : object
        The document as read (JSON or TOML).
    node : mapping
        The schema node it must match (``root`` itself, or one of its ``$defs``).
    root : mapping
        The schema document whose ``$defs`` each ``$ref`` names.
    open_ : bool
        Skip ``required`` and ``additionalProperties``: check only the keys present.
    words, names : mapping
        Each schema type in words, and the name of each Python type of a
        value (by ``type(value).__name__``): a scene says "a table" where JSON says "an object".

    Returns
    -------
    list of (str, str)
        (field path, what is wrong), the path as the loaders spell fields
        (``member[0].mass``, zero-based; ``(top level)`` for the document),
        in the order of the document. Empty when the shape is sound.
    """
    errors: list[tuple[str, str]] = []
    walk = _Walk(root, open_, words, names)
    if not walk.ok(value, node):  # a sound document (the usual one) is read once, no message or path made
        walk.walk(value, node, "", errors)
    return errors


class _Walk:
    def __init__(self, root: Mapping[str, Any], open_: bool, words: Mapping[str, str], names: Mapping[str, str]):
        self.root, self.open, self.words, self.names = root, open_, words, names

    def resolve(self, node: Mapping[str, Any]) -> Mapping[str, Any]:
        while "$ref" in node:
            node = self.root["$defs"][node["$ref"].removeprefix("#/$defs/")]
        return node

    def expected(self, node: Mapping[str, Any]) -> list[str]:
        """What a node accepts, in words."""
        node = self.resolve(node)
        if "title" in node:  # a definition that names itself ("a number, or a string with its unit")
            return [node["title"]]
        if "anyOf" in node:
            said: list[str] = []
            for branch in node["anyOf"]:
                said += [w for w in self.expected(branch) if w not in said]
            return said
        if "const" in node:
            return [_literal(node["const"])]
        if "enum" in node:
            return [f"one of {', '.join(_literal(v) for v in node['enum'])}"]
        return [self.words.get(kind, kind) for kind in _kinds(node) or ()]

    def typed(self, value: object, node: Mapping[str, Any]) -> bool:
        """Whether ``node`` names a type and ``value`` is of it (the form of an ``anyOf`` the value takes)."""
        return any(_type_ok(value, kind) for kind in _kinds(self.resolve(node)) or ())

    def got(self, value: object) -> str:
        if value is None:
            return "null"
        if hasattr(value, "array"):  # io.toml_file.InlineRows stands for a list
            return self.names.get("list", "array")
        name = type(value).__name__
        return self.names.get(name, name)

    def ok(self, value: object, node: Mapping[str, Any]) -> bool:
        """Whether :meth:`walk` would find no error in ``value``: its verdict alone, at a fraction of its cost."""
        node = self.resolve(node)
        if "anyOf" in node:
            return any(self.ok(value, branch) for branch in node["anyOf"])
        kinds = _kinds(node)
        if kinds is not None and not any(_type_ok(value, kind) for kind in kinds):
            return False
        if "const" in node and not _same(value, node["const"]):
            return False
        if "enum" in node and not any(_same(value, choice) for choice in node["enum"]):
            return False
        if isinstance(value, str):
            return "pattern" not in node or re.search(node["pattern"], value) is not None
        if isinstance(value, dict):
            properties = node.get("properties", {})
            more = node.get("additionalProperties")
            for key, item in value.items():
                if key in properties:
                    if not self.ok(item, properties[key]):
                        return False
                elif more is False:
                    if not self.open:
                        return False
                elif isinstance(more, Mapping) and not self.ok(item, more):
                    return False
            return self.open or all(key in value for key in node.get("required", ()))
        if isinstance(value, list):
            low, high = node.get("minItems"), node.get("maxItems")
            if (low is not None and len(value) < low) or (high is not None and len(value) > high):
                return False
            first, rest = node.get("prefixItems", ()), node.get("items")
            for k, item in enumerate(value):
                each = first[k] if k < len(first) else rest
                if each is not None and not self.ok(item, each):
                    return False
        return True

    def walk(self, value: object, node: Mapping[str, Any], path: str, errors: list[tuple[str, str]]) -> None:
        """Every error of ``value`` (one :meth:`ok` finds unsound) against ``node``, at ``path``."""
        node = self.resolve(node)
        where = path or "(top level)"
        if "anyOf" in node:
            trials = []
            for branch in node["anyOf"]:
                trial: list[tuple[str, str]] = []
                self.walk(value, branch, path, trial)
                if not trial:
                    return
                if self.typed(value, branch):
                    trials.append(trial)
            if len(trials) == 1:  # one form of its type (an array where a number or an array is allowed): said
                # within it, at this field (where jsonschema, and a loader's own words, put it)
                errors.extend((where, f"{field.removeprefix(path)} {message}".lstrip()) for field, message in trials[0])
                return
            errors.append((where, f"must be {' or '.join(self.expected(node))}, got {self.got(value)}"))
            return
        kinds = _kinds(node)
        if kinds is not None and not any(_type_ok(value, kind) for kind in kinds):
            errors.append((where, f"must be {' or '.join(self.words.get(k, k) for k in kinds)}, got {self.got(value)}"))
            return
        if "const" in node and not _same(value, node["const"]):
            errors.append((where, f"must be {_literal(node['const'])}, got {_literal(value)}"))
            return
        if "enum" in node and not any(_same(value, choice) for choice in node["enum"]):
            errors.append(
                (where, f"must be one of {', '.join(_literal(v) for v in node['enum'])}, got {_literal(value)}")
            )
            return
        if isinstance(value, str) and "pattern" in node and re.search(node["pattern"], value) is None:
            errors.append((where, f"must match {node['pattern']}, got {_literal(value)}"))
        elif isinstance(value, dict):
            self.walk_object(value, node, path, errors)
        elif isinstance(value, list) or hasattr(value, "array"):
            self.walk_array(value, node, path, errors)

    def walk_object(self, value: dict[Any, Any], node: Mapping[str, Any], path: str, errors: list[tuple[str, str]]):
        properties: Mapping[str, Any] = node.get("properties", {})
        allowed = sorted(properties)
        for key, item in value.items():
            where = f"{path}.{key}" if path else str(key)
            if key in properties:
                if not self.ok(item, properties[key]):
                    self.walk(item, properties[key], where, errors)
            elif node.get("additionalProperties") is False and not self.open:
                errors.append((where, f"unknown key{hint(str(key), allowed)} (allowed here: {', '.join(allowed)})"))
            elif isinstance(node.get("additionalProperties"), Mapping) and not self.ok(
                item, node["additionalProperties"]
            ):
                self.walk(item, node["additionalProperties"], where, errors)
        if not self.open:
            for key in node.get("required", ()):
                if key not in value:
                    errors.append((f"{path}.{key}" if path else key, "is missing"))

    def walk_array(self, value: Any, node: Mapping[str, Any], path: str, errors: list[tuple[str, str]]) -> None:
        where = path or "(top level)"
        if not isinstance(value, list):  # an inline table of rows: its length and items are the loader's to read
            return
        low, high = node.get("minItems"), node.get("maxItems")
        if (low is not None and len(value) < low) or (high is not None and len(value) > high):
            if low == high:
                count = f"exactly {low}"
            elif high is None:
                count = f"at least {low}"
            else:
                count = f"at most {high}" if low is None else f"{low} to {high}"
            errors.append((where, f"must have {count} items, got {len(value)}"))
            return
        first, rest = node.get("prefixItems", ()), node.get("items")
        for k, item in enumerate(value):
            each = first[k] if k < len(first) else rest
            if each is not None and not self.ok(item, each):  # the path is made for an item in error only
                self.walk(item, each, f"{path}[{k}]", errors)


def _kinds(node: Mapping[str, Any]) -> Sequence[str] | None:
    """A node's ``type`` as a list (one or several), or None where it names none."""
    kinds = node.get("type")
    return [kinds] if isinstance(kinds, str) else kinds


def _type_ok(value: object, kind: str) -> bool:
    if kind == "object":
        return isinstance(value, dict)
    if kind == "array":
        return isinstance(value, list) or hasattr(value, "array")  # io.toml_file.InlineRows stands for a list
    if kind == "string":
        return isinstance(value, str)
    if kind == "boolean":
        return isinstance(value, bool)
    if kind == "integer":  # as JSON Schema: 4.0 is an integer
        return (isinstance(value, int) and not isinstance(value, bool)) or (
            isinstance(value, float) and value.is_integer()
        )
    if kind == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if kind == "null":
        return value is None
    return True


def _same(value: object, expected: object) -> bool:
    """JSON Schema's equality: true is not 1, and 1 is 1.0."""
    if isinstance(value, bool) != isinstance(expected, bool):
        return False
    if isinstance(value, (int, float)) and isinstance(expected, (int, float)):
        return value == expected
    return type(value) is type(expected) and value == expected


def _literal(value: object) -> str:
    """A value as JSON writes it, cut short: 'design', true, null, 3."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return "null" if value is None else shorten(value)
