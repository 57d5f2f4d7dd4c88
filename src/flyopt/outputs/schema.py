"""The JSON Schema of what flyopt writes (``flyopt/data/output.schema.json``), its version, and a table's metadata
held to it.

Every JSON object flyopt writes carries ``schema_version`` and ``kind`` and is
described by this schema; :mod:`flyopt.outputs.documents` builds the
documents, :mod:`flyopt.outputs.results` writes and reads the tables whose
metadata :func:`metadata_errors` checks.
"""

from __future__ import annotations

import functools
import json
from typing import Any

from flyopt.io.json_shape import shape_errors

__all__ = ["SCHEMA_FILE", "metadata_errors", "schema", "schema_version"]

SCHEMA_FILE = "output.schema.json"


@functools.lru_cache(maxsize=1)
def schema() -> dict[str, Any]:
    """The JSON Schema of every JSON document flyopt writes (``flyopt/data/output.schema.json``)."""
    from importlib import resources

    loaded: dict[str, Any] = json.loads(
        resources.files("flyopt").joinpath("data", SCHEMA_FILE).read_text(encoding="utf-8")
    )
    return loaded


def schema_version() -> str:
    """The version of flyopt's output schema, which every document and file metadata carries."""
    version: str = schema()["$defs"]["schema_version"]["const"]
    return version


def metadata_errors(metadata: object) -> list[tuple[str, str]]:
    """Every shape error of a table's metadata against the output schema's ``table``, keys present only.

    The one rule for what a sweep, Pareto or trade-off file may say about
    itself (:func:`flyopt.outputs.documents.table_metadata` writes it):
    :func:`flyopt.outputs.results.write_results` refuses metadata that breaks it and
    :func:`~flyopt.outputs.results.read_results` a file whose metadata does. An open walk
    (:func:`flyopt.io.json_shape.shape_errors`): a key it does not know, or
    one it lacks, is a file of another minor version of the schema, not an error.

    Returns
    -------
    list of (str, str)
        (field, what is wrong); empty when sound.
    """
    return shape_errors(metadata, _open_table(), schema(), open_=True)


@functools.lru_cache(maxsize=1)
def _open_table() -> dict[str, Any]:
    """The schema's ``table`` with its ``schema_version`` of any minor number of this major one ("3.0" reads
    "3.1"'s metadata: the minor number grows when fields are added, which the open walk lets pass)."""
    table = schema()["$defs"]["table"]
    major = schema_version().split(".")[0]
    version = {"type": "string", "pattern": rf"^{major}\.[0-9]+$"}
    return {**table, "properties": {**table["properties"], "schema_version": version}}
