"""What a diagram draws, as data with an exact digest: a diagram whose data are the same draws the same figure.

A diagram split this way (:class:`Plot`) reads everything it draws off its inputs first (``data``: a frozen
dataclass of numbers, arrays, strings and such dataclasses), then draws from that alone (``draw``, with the
units and digits). Two inputs whose data have the same :func:`digest` draw the same figure, to the byte: the app
keeps a diagram an edit leaves unchanged (a δ edit leaves the turning-moment and energy diagrams as they were)
instead of drawing it again (issue 29, docs/app.md "Latency").

The digest is exact: every float by its 8 bytes, every numpy scalar and array by its dtype (and shape) and
bytes, every string by its characters, every sequence and dataclass by its type; a value of any other type is
refused (TypeError), so nothing a diagram draws can be left out of its digest. Values equal in number but not in bytes (0.0 and -0.0) digest apart: the diagram is then drawn again.
"""

from __future__ import annotations

import dataclasses
import hashlib
import struct
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def digest(*values: Any) -> str:
    """The exact digest of ``values`` (hex): None, bools, ints, floats, strings, numpy arrays of numbers,
    tuples and lists of these, and dataclasses of these (their type's name and every field)."""
    hasher = hashlib.blake2b(digest_size=20)
    for value in values:
        _feed(hasher, value)
    return hasher.hexdigest()


def _feed(hasher: Any, value: Any) -> None:
    add = hasher.update
    if value is None:
        add(b"N")
    elif isinstance(value, np.generic):  # a numpy scalar by its dtype and bytes (a float32 is not a float)
        if value.dtype.kind not in "biuf":
            raise TypeError(f"digest: a numpy {value.dtype} is not data a diagram draws")
        add(b"G" + value.dtype.str.encode() + b":" + value.tobytes())
    elif isinstance(value, bool):
        add(b"B1" if value else b"B0")
    elif isinstance(value, int):
        add(b"I" + str(value).encode() + b";")
    elif isinstance(value, float):
        add(b"F" + struct.pack("<d", value))
    elif isinstance(value, str):
        data = value.encode("utf-8", "surrogatepass")
        add(b"S" + str(len(data)).encode() + b":" + data)
    elif isinstance(value, np.ndarray):
        if value.dtype.kind not in "biuf":
            raise TypeError(f"digest: an array of {value.dtype} is not data a diagram draws")
        add(b"A" + value.dtype.str.encode() + repr(value.shape).encode())
        add(np.ascontiguousarray(value).tobytes())
    elif isinstance(value, (tuple, list)):  # by its type too: a list is not a tuple, nor a named tuple
        add(b"T" + type(value).__qualname__.encode() + b":" + str(len(value)).encode() + b"(")
        for item in value:
            _feed(hasher, item)
        add(b")")
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        kind = type(value)
        add(b"D" + f"{kind.__module__}.{kind.__qualname__}".encode() + b"(")
        for item in dataclasses.fields(value):
            add(item.name.encode() + b"=")
            _feed(hasher, getattr(value, item.name))
        add(b")")
    else:
        raise TypeError(f"digest: a {type(value).__name__} is not data a diagram draws")


@dataclass(frozen=True)
class Plot:
    """A diagram as what it draws and how: ``data(*inputs)`` reads its data off the inputs (a scene and its
    analysis), ``draw(data, ax=None, units=..., digits=...)`` draws them and returns the Axes; ``name`` tells
    diagrams apart in a digest (:meth:`digest`)."""

    name: str
    data: Callable[..., Any]
    draw: Callable[..., Axes]

    def digest(self, data: Any, units: str, digits: int) -> str:
        """The digest of the figure :attr:`draw` makes of ``data`` in ``units`` to ``digits`` figures."""
        return digest(self.name, data, units, digits)
