"""A scene as data: what a sweep sends to its workers, and a digest of what it computes.

Worker processes and Dask workers receive a sweep's scene as data, never as
live objects: the TOML text of its file (rebuilt there by the same reader),
plus, where the scene object differs from its file (a scene changed by
``scene.replace`` or :func:`flyopt.studies.points.point_scene`), the
fields that differ, as plain values. A scene without a file travels as its
fields when they are plain values. What cannot travel as data (a member
whose kinematics is a function made in this process, in a scene that has no
file to rebuild it from) is computed in this process instead.

:func:`digest` is an exact fingerprint of a scene (every float to the bit,
every table in full, functions by their code and the values they hold), so
that a resumed sweep never reuses the chunks of a different scene.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import pickle
import types
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

__all__ = ["ScenePayload", "digest", "payload"]

from flyopt._toml import tomllib

if TYPE_CHECKING:  # the annotations only
    from flyopt.io.scene import Scene


# --------------------------------------------------------------------------
# An exact digest of a scene
# --------------------------------------------------------------------------


#: A scene's fields that name its files and change nothing it computes: left out of its digest and not sent as
#: changes (:attr:`flyopt.io.scene.Scene.shown_as`: the app's name for its server's file;
#: :attr:`~flyopt.io.scene.Scene.inputs`: where its data files were read, whose numbers are in the scene).
NAMES_ONLY = ("source", "shown_as", "inputs")


def digest(obj: object, skip: Iterable[str] = NAMES_ONLY) -> str:
    """A SHA-256 hex digest of ``obj`` by value.

    Floats count to the bit, arrays in full (their dtype, shape and bytes),
    dataclasses by their fields (not by caches kept on them), functions by
    their code and the values they close over, bound methods by their
    object and name. Two scenes with equal digests compute the same.

    Parameters
    ----------
    obj : object
        A scene, or any part of one.
    skip : tuple of str
        Field names of dataclasses left out (by default :data:`NAMES_ONLY`,
        the scene's file names, which change nothing).

    Returns
    -------
    str
    """
    h = hashlib.sha256()
    _feed(h, obj, set(skip), set())
    return h.hexdigest()


def _feed(h: hashlib._Hash, obj: object, skip: set[str], seen: set[int]) -> None:
    def put(tag: str, data: bytes = b"") -> None:
        h.update(tag.encode() + len(data).to_bytes(8, "little") + data)

    if obj is None or isinstance(obj, (bool, int, str, bytes)):
        put(type(obj).__name__, repr(obj).encode())
    elif isinstance(obj, float):
        put("float", float.hex(obj).encode() if not math.isnan(obj) else b"nan")
    elif isinstance(obj, np.generic):
        _feed(h, obj.item(), skip, seen)
    elif isinstance(obj, np.ndarray):
        if obj.dtype == object:
            put("object-array", repr(obj.shape).encode())
            for item in obj.ravel():
                _feed(h, item, skip, seen)
        else:
            put("array", f"{obj.dtype.str}{obj.shape}".encode())
            h.update(np.ascontiguousarray(obj).tobytes())
    elif isinstance(obj, (tuple, list, frozenset, set)):
        items = sorted(obj, key=repr) if isinstance(obj, (set, frozenset)) else obj
        put(type(obj).__name__, str(len(items)).encode())
        for item in items:
            _feed(h, item, skip, seen)
    elif isinstance(obj, dict):
        put("dict", str(len(obj)).encode())
        for key in sorted(obj, key=repr):
            _feed(h, key, skip, seen)
            _feed(h, obj[key], skip, seen)
    elif id(obj) in seen:  # a cycle (an object that refers back to itself)
        put("seen", type(obj).__qualname__.encode())
    else:
        seen.add(id(obj))
        kind = type(obj)
        put("type", f"{kind.__module__}.{kind.__qualname__}".encode())
        if dataclasses.is_dataclass(obj):
            for f in dataclasses.fields(obj):
                if f.name not in skip:
                    put("field", f.name.encode())
                    _feed(h, getattr(obj, f.name), skip, seen)
        elif isinstance(obj, types.MethodType):
            put("method", obj.__func__.__qualname__.encode())
            _feed(h, obj.__self__, skip, seen)
        elif isinstance(obj, types.FunctionType):
            _feed_function(h, obj, skip, seen)
        elif isinstance(obj, (types.BuiltinFunctionType, type)):
            put("named", f"{getattr(obj, '__module__', '')}.{obj.__qualname__}".encode())
        elif type(obj).__reduce__ is not object.__reduce__:  # says how to rebuild it
            _feed(h, obj.__reduce__()[1:], skip, seen)
        elif hasattr(obj, "__dict__"):
            _feed(h, {k: v for k, v in vars(obj).items() if not k.startswith("_")}, skip, seen)
        else:
            put("repr", repr(obj).encode())


def _feed_function(h: hashlib._Hash, fn: Callable[..., Any], skip: set[str], seen: set[int]) -> None:
    code = fn.__code__
    h.update(f"{fn.__module__}.{fn.__qualname__}".encode())
    h.update(code.co_code)
    _feed(h, tuple(c for c in code.co_consts if not isinstance(c, types.CodeType)), skip, seen)
    _feed(h, code.co_names, skip, seen)
    _feed(h, fn.__defaults__, skip, seen)
    _feed(h, tuple(cell.cell_contents for cell in fn.__closure__ or ()), skip, seen)


# --------------------------------------------------------------------------
# A scene as data
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class ScenePayload:
    """A scene as data: the text of its file and the fields that differ, or its fields.

    Attributes
    ----------
    text : str or None
        TOML text of the scene's file.
    source : str or None
        The file's name (for messages; the text is already read).
    fields : dict
        Scene fields as values: the ones that differ from ``text``, or (no
        text) every field.
    key : str
        :func:`digest` of the scene, naming it in a worker's cache.
    """

    text: str | None
    source: str | None
    fields: dict[str, Any]
    key: str

    def scene(self) -> Scene:
        """The scene, rebuilt.

        Returns
        -------
        Scene
        """
        from flyopt.io.scene import Scene, from_dict

        if self.text is None:
            return Scene(**self.fields)
        base = from_dict(tomllib.loads(self.text), source=self.source)
        return base.replace(**self.fields) if self.fields else base


def payload(scene: Scene) -> tuple[ScenePayload | None, str]:
    """The scene as data for workers, or why it cannot travel.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    payload : ScenePayload or None
        None when the scene cannot travel as data.
    reason : str
        Why not ("" when it can).

    Notes
    -----
    The text route is used only when the scene rebuilt from its file has the
    scene's own :func:`digest` (field by field: the fields that differ go
    along as values, and must be plain data). The result is checked by
    rebuilding it here, so a worker computes exactly the parent's scene.
    """
    key = digest(scene)
    names = [f.name for f in dataclasses.fields(scene)]
    text = _file_text(scene.source)
    if text is not None:
        try:
            base = ScenePayload(text, scene.source, {}, key).scene()
        except Exception:  # noqa: BLE001 - the file changed, or no longer reads: use the fields
            base = None
        if base is not None:
            changed = {
                n: getattr(scene, n)
                for n in names
                if n not in NAMES_ONLY and digest(getattr(base, n)) != digest(getattr(scene, n))
            }
            if _plain(changed):
                candidate = ScenePayload(text, scene.source, changed, key)
                if not changed or digest(candidate.scene()) == key:
                    return candidate, ""
    fields = {n: getattr(scene, n) for n in names}
    if _plain(fields):
        return ScenePayload(None, scene.source, fields, key), ""
    why = (
        "its members' kinematics are functions of this process"
        if getattr(scene, "members", ())
        else "it holds objects that cannot be copied"
    )
    return None, (
        f"the scene cannot be sent to workers as data ({why}, and it "
        f"{'differs from' if text is not None else 'has no'} file to rebuild it from)"
    )


def _file_text(source: str | None) -> str | None:
    if not source:
        return None
    try:
        return Path(source).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError, ValueError):
        return None


def _plain(values: object) -> bool:
    """Whether ``values`` pickle (plain data: no function made at run time)."""
    try:
        pickle.dumps(values)
    except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
        return False
    return True
