"""The parts folder of a sweep: each finished chunk on disk, checked before a resume reuses it.

With an output file every finished chunk is written to
``OUTPUT.parts/chunk-NNNNN.parquet`` at once, so a crash loses at most the
chunks in flight; ``resume`` reuses the chunks on disk after checking that
each is the chunk it claims to be (a damaged one is computed again), and
only when the folder's manifest holds the same :func:`fingerprint`. Every
temporary file lives in ``OUTPUT.parts/`` too, so nothing is left that a
rerun does not see.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import stat
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from flyopt.errors import SceneError
from flyopt.io.input_files import read_input
from flyopt.outputs.files import check_folder
from flyopt.outputs.results import PARTS_SUFFIX, parts_folder, read_results, write_results

#: The descriptors of the parts folders this process holds. A worker process forked from it gets copies,
#: and a flock lasts while any copy is open: each child closes them at once, so the lock is the sweep's alone
#: (a pool that outlives the sweep would otherwise keep its folder from --resume).
_HELD: set[int] = set()


def _close_held() -> None:
    for fd in list(_HELD):
        try:
            os.close(fd)
        except OSError:  # pragma: no cover - already closed
            pass
    _HELD.clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_close_held)

__all__ = ["Parts", "fingerprint"]


def fingerprint(identity: object, points: pd.DataFrame, layout: object) -> str:
    """A digest of what a sweep computes: parts of another sweep are never reused.

    Parameters
    ----------
    identity : str
        Everything the results depend on besides the points (the scene, the
        method, solver options), as a text stable across processes.
    points : pandas.DataFrame
    layout : object
        How the points are cut into chunks (its ``repr`` is hashed).
    """
    digest = hashlib.sha256(repr(identity).encode())
    digest.update(repr(layout).encode())
    digest.update(pd.util.hash_pandas_object(points, index=False).to_numpy().tobytes())
    return digest.hexdigest()


class Parts:
    """The folder ``OUTPUT.parts``: one file per finished chunk, a manifest, temporary files.

    Parameters
    ----------
    output : str or Path
        The sweep's output file; the folder is beside it.
    """

    MANIFEST = "sweep.json"
    LOCK = "lock"
    """Held (``flock``) by the sweep writing the folder, with its process id: a second sweep of the same
    output is refused while the first runs; the lock goes with its process (a kill -9 frees it)."""

    def __init__(self, output: str | os.PathLike[str]) -> None:
        self.folder = parts_folder(output)
        self._lock: int | None = None

    def lock(self) -> None:
        """Take the folder for this process, or refuse (SceneError) while another sweep writes it."""
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not POSIX: no lock, as before
            return
        if self._lock is not None:
            return
        try:  # never through a link planted at the lock's name: it would empty the file it points at
            fd = os.open(self.folder / self.LOCK, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
        except OSError as err:
            raise SceneError(
                "--output", f"{str(self.folder / self.LOCK)!r} cannot be opened as the sweep's lock: {err.strerror}"
            ) from None
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            os.close(fd)
            raise SceneError("--output", f"{str(self.folder / self.LOCK)!r} is not a regular file: remove it")
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = os.read(fd, 20).decode("ascii", errors="replace").strip() or "?"
            os.close(fd)
            raise SceneError(
                "--output",
                f"{str(self.folder)!r} is being written by the sweep of process {holder}, still running: "
                "wait for it, or stop it and continue with --resume",
            ) from None
        os.ftruncate(fd, 0)
        os.write(fd, str(os.getpid()).encode("ascii"))
        self._lock = fd
        _HELD.add(fd)

    def release(self) -> None:
        """Let the folder go (the end of the sweep; the process's end does it too)."""
        if self._lock is not None:
            _HELD.discard(self._lock)
            os.close(self._lock)  # closing the descriptor drops the flock
            self._lock = None

    def _temporary(self, name: str) -> bool:
        """Whether ``name`` is one of this sweep's temporary files, left in its folder by a killed run: a part's, the
        manifest's or the output's (written in the folder, then moved), ``NAME.tmp-PID-RANDOM``, NAME maybe cut to
        fit a file name's length. Nothing else in the folder is removed on a resume."""
        head, sep, tail = name.rpartition(".tmp-")
        if not sep or not head or not _TEMPORARY_TAIL.fullmatch(tail):
            return False
        output = self.folder.name[: -len(PARTS_SUFFIX)]
        return bool(_PART_NAME.fullmatch(head)) or head == output or (len(name) >= 240 and output.startswith(head))

    def path(self, index: int) -> Path:
        """The file of chunk ``index``."""
        return self.folder / f"chunk-{index:05d}.parquet"

    def manifest(self) -> dict[str, Any]:
        """What the folder's manifest records (``{}`` when there is none); SceneError if it is not a JSON object.

        Read as any input is (:func:`~flyopt.io.input_files.read_input`): a regular file within the size cap,
        so a FIFO or a link to ``/dev/zero`` planted at its name is refused (SceneError), not read forever."""
        self.check_folder()
        path = self.folder / self.MANIFEST
        if not os.path.lexists(path):
            return {}
        text = read_input(path, "--resume", f"the sweep's manifest {str(path)!r}")
        try:
            record = json.loads(text)
        except (ValueError, RecursionError):  # RecursionError: arrays nested a hundred thousand deep
            record = None
        if not isinstance(record, dict):
            raise SceneError(
                "--resume",
                f"the sweep's manifest {str(path)!r} is damaged: not a JSON object as flyopt writes it; "
                f"delete the folder {str(self.folder)!r} to start over",
            )
        return record

    def check_folder(self) -> None:
        """Refuse a parts folder that is not a folder of its own: a symbolic link (the sweep would write its
        lock, its chunks and its removals where the link leads) or another kind of file."""
        try:
            mode = os.lstat(self.folder).st_mode
        except FileNotFoundError:
            return
        if stat.S_ISLNK(mode) or not stat.S_ISDIR(mode):
            kind = "a symbolic link" if stat.S_ISLNK(mode) else "not a folder"
            raise SceneError(
                "--output",
                f"{str(self.folder)!r} is {kind}: the sweep keeps its finished chunks in a folder of its own "
                "there; remove it or name another output",
            )

    def open(self, record: Mapping[str, Any], chunks: Sequence[tuple[int, pd.DataFrame]], resume: bool) -> list[int]:
        """Create the folder, or (``resume``) find the chunks already in it.

        Parameters
        ----------
        record : dict
            The manifest: ``fingerprint`` and what else identifies the sweep.
        chunks : list of (int, pandas.DataFrame)
            Every chunk of the sweep, to check the parts against.
        resume : bool

        Returns
        -------
        list of int
            The chunks whose part is sound (each read and checked, then let
            go: the results are read again when they are needed). A part
            that cannot be read or does not hold its chunk's points is said
            on stderr (one line), removed and left to be computed again.

        Raises
        ------
        SceneError
            The folder exists without ``resume``, or holds another sweep.
        """
        self.check_folder()
        if not os.path.lexists(self.folder):
            check_folder(self.folder)
            try:
                self.folder.mkdir()
            except FileExistsError:  # another sweep made it a moment ago: its lock says so below
                pass
            else:
                self.lock()
                (self.folder / self.MANIFEST).write_text(json.dumps(record), encoding="utf-8")
                return []
        self.lock()  # before anything is read: a running sweep's folder is neither resumed nor reported stale
        try:
            return self._reopen(record, chunks, resume)
        except BaseException:
            self.release()  # refused (or interrupted): the folder is not this sweep's
            raise

    def _reopen(self, record: Mapping[str, Any], chunks: Sequence[tuple[int, pd.DataFrame]], resume: bool) -> list[int]:
        """:meth:`open` of a folder that exists, held by this process."""
        if not resume:
            raise SceneError(
                "--output",
                f"{str(self.folder)!r} holds the chunks of an earlier, "
                f"unfinished sweep: resume it (--resume) or delete the folder",
            )
        if self.manifest().get("fingerprint") != record["fingerprint"]:
            raise SceneError(
                "--resume",
                f"the parts in {str(self.folder)!r} come from a "
                f"different sweep (scene, fields, values or chunk size differ); "
                f"delete the folder to start over",
            )
        for stale in self.folder.iterdir():  # left by a killed run: this sweep's own temporaries alone
            if self._temporary(stale.name) and stat.S_ISREG(os.lstat(stale).st_mode):
                stale.unlink(missing_ok=True)
        done = []
        for i, chunk in chunks:
            path = self.path(i)
            if path.is_symlink():  # no part of this sweep's: a chunk written there would go where it leads
                print(
                    f"flyopt sweep: {path}: a symbolic link, not a part; removed, chunk {i} computed", file=sys.stderr
                )
                path.unlink()
                continue
            if not path.exists():
                continue
            if path.is_dir():  # (a folder is not unlinked: it said "computing again", then failed every resume)
                raise SceneError(
                    "--resume",
                    f"{str(path)!r} is a folder where chunk {i}'s part belongs: move it away, then resume "
                    "(flyopt removes only files of its own)",
                )
            problem = _damage(path, chunk)
            if problem:
                print(f"flyopt sweep: {path}: {problem}; computing chunk {i} again", file=sys.stderr)
                path.unlink()
            else:
                done.append(i)
        return done

    def read(self, index: int, columns: Sequence[str] | None = None) -> pd.DataFrame:
        """The results of chunk ``index`` (``columns`` only, when given)."""
        return read_results(self.path(index), columns=columns)

    def save(self, index: int, frame: pd.DataFrame) -> None:
        """Write the results of chunk ``index`` (atomically)."""
        write_results(frame, self.path(index), temporary_folder=self.folder)

    def remove(self) -> None:
        """Remove the folder and everything in it."""
        shutil.rmtree(self.folder, ignore_errors=True)
        self.release()


#: The tail of a temporary file's name (:class:`flyopt.outputs.files.Temporary`: ``NAME.tmp-PID-RANDOM``).
_TEMPORARY_TAIL = re.compile(r"\d+(-[0-9a-f]+)?")

#: The parts of a sweep, and its manifest: the names its temporary files in the folder take.
_PART_NAME = re.compile(r"chunk-\d{5}\.parquet|sweep\.json")


def _damage(path: Path, chunk: pd.DataFrame) -> str:
    """What is wrong with the part file of ``chunk`` ("" when it is sound)."""
    try:
        frame = read_results(path)
    except Exception as err:  # noqa: BLE001 - whatever the reader says, the part is unusable
        text = str(err).strip().splitlines()
        return f"cannot be read ({type(err).__name__}: {text[0] if text else ''})"
    if len(frame) != len(chunk):
        return f"holds {len(frame)} rows, not the chunk's {len(chunk)}"
    missing = [c for c in chunk.columns if c not in frame.columns]
    if missing:
        return f"lacks the column {missing[0]!r}"
    if not (frame["point"].to_numpy() == chunk["point"].to_numpy()).all():
        return "holds other points than its chunk"
    for column in chunk.columns:  # each point's inputs as planned (a part edited to δ = 99 was copied as it was)
        if not _same(frame[column], chunk[column]):
            return f"holds other values of {column!r} than its chunk's points"
    if "status" in frame.columns and "mass" in frame.columns:
        mass = frame["mass"].to_numpy(dtype=float)[(frame["status"] == "designed").to_numpy(dtype=bool)]
        if not (np.isfinite(mass) & (mass > 0)).all():
            return "holds a designed point without a finite, positive mass"
    return ""


def _same(stored: pd.Series, planned: pd.Series) -> bool:
    """Whether a part's column holds the values its chunk planned, where the plan gives one (numbers to the bit,
    texts as written); a value the plan leaves out ("none": NaN) is the table's to write (a limit not set is
    written as the infinite one), and is not compared."""
    from pandas.api.types import is_numeric_dtype

    given = planned.notna().to_numpy()
    if is_numeric_dtype(planned.dtype):
        if not is_numeric_dtype(stored.dtype):
            return False
        return bool(np.array_equal(stored.to_numpy(dtype=float)[given], planned.to_numpy(dtype=float)[given]))
    return [str(v) for v in stored[given]] == [str(v) for v in planned[given]]
