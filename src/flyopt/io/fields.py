"""Checked fields of a scene file: tables with known keys, numbers with units.

:class:`Table` refuses an unknown key (naming the closest allowed one) and
reads each value as a quantity of a dimension; :func:`unit_factor` and
:func:`scaled` read a section's ``unit`` and the numbers written in it.
"""

from flyopt.errors import SceneError, shorten
from flyopt.names import hint
from flyopt.units import quantity


def unit_factor(raw, dimension, where):
    if not isinstance(raw, str):
        raise SceneError(where, f"must be a unit string, got {shorten(raw)}")
    return quantity(f"1 {raw}", dimension, where)


def scaled(raw, dimension, where, factor):
    """A number times the section's unit, or a string with its own unit."""
    if isinstance(raw, str):
        return quantity(raw, dimension, where)
    return quantity(raw, "dimensionless", where) * factor


class Table:
    """A dictionary from TOML with checked keys and typed accessors."""

    def __init__(self, data, where, allowed):
        if not isinstance(data, dict):
            raise SceneError(where or "(top level)", f"must be a table, got {type(data).__name__}")
        unknown = sorted(set(data) - set(allowed))
        if unknown:
            key = unknown[0]
            path = f"{where}.{key}" if where else key
            raise SceneError(
                path, f"unknown key{hint(key, sorted(allowed))} (allowed here: {', '.join(sorted(allowed))})"
            )
        self.data, self.where = data, where

    def _path(self, key):
        return f"{self.where}.{key}" if self.where else key

    def has(self, key):
        return key in self.data

    def raw(self, key):
        return self.data.get(key)

    def get(self, key, default=None):
        return self.data.get(key, default)

    def require(self, key):
        if key not in self.data:
            raise SceneError(self._path(key), "is missing")
        return self.data[key]

    def quantity(self, key, dimension, required=False, default=None):
        if key not in self.data:
            if required:
                raise SceneError(self._path(key), "is missing")
            return default
        return quantity(self.data[key], dimension, self._path(key))
