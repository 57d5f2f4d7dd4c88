"""Sweep result tables: their columns (the schema) and their files, Parquet or CSV.

A result table has one row per point: ``point``, :data:`CORE_INPUTS`, the
other varied fields, then :data:`RESULT_COLUMNS`; the table of a Latin
hypercube has a ``seed`` column after ``point`` (the seed of its samples, in
CSV and Parquet alike). :func:`write_results` and :func:`read_results`
round-trip it exactly, whatever the format.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from flyopt.errors import SceneError

__all__ = ["CORE_INPUTS", "RESULT_COLUMNS", "output_format", "read_results", "write_results"]

#: Input columns present in every result table (SI; NaN for "none").
CORE_INPUTS = ("delta", "speed", "inertia", "torque.scale", "design.geometry",
               "design.objective", "design.hb_min", "design.hb_max",
               "design.max_outer_diameter", "design.max_width", "design.d_mean")

#: Result columns, with their pandas dtype. Strings are "" when absent (so that
#: CSV and Parquet read back the same), numbers NaN, ``iterations`` -1.
RESULT_COLUMNS = {
    "status": "str",            # designed | not_needed | infeasible | failed
    "feasible": "bool",         # a design was found
    "method": "str",            # closed_form | ipopt | none
    "best_material": "str",
    "best_shaft": "str",
    "best_speed_ratio": "float",
    "d_mean": "float", "d_outer": "float", "d_inner": "float", "h": "float", "b": "float",
    "hb_ratio": "float", "mass": "float", "cost": "float", "objective": "float",
    "rim_speed": "float", "rim_speed_limit": "float", "hoop_stress": "float",
    "safety_factor": "float", "j_flywheel": "float", "j_at_reference": "float",
    "j_required_on_shaft": "float", "d_outer_limit": "float",
    "binding": "str",           # comma-separated names of BINDING_NAMES
    "n_combinations": "int",    # material x shaft combinations decided
    "n_feasible": "int",
    "a_max": "float", "j_margin": "float", "j_required": "float",
    "driving_torque": "float", "power": "float", "motor_power": "float",
    "solver_status": "str", "iterations": "int", "message": "str",
}

_NAME_INPUTS = {"design.geometry", "design.objective", "material", "shaft"}


def _normalize(frame):
    """One dtype per column, whatever the source (evaluation, CSV or Parquet)."""
    for name in frame.columns:
        kind = RESULT_COLUMNS.get(name)
        if kind is None:
            kind = ("str" if name in _NAME_INPUTS else
                    "int" if name in ("point", "seed") else "float")
        if kind == "str":
            frame[name] = frame[name].fillna("").astype(str)
        elif kind == "bool":
            frame[name] = frame[name].astype(bool)
        elif kind == "int":
            frame[name] = frame[name].astype(np.int64)
        else:
            frame[name] = frame[name].astype(float)
    return frame


# --------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------

_SUFFIXES = {".parquet": "parquet", ".pq": "parquet", ".csv": "csv"}


def output_format(path, label="output"):
    """``"parquet"`` or ``"csv"``, by the suffix of ``path``; SceneError naming ``label`` else."""
    kind = _SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError(label, f"{str(path)!r} must end in .parquet or .csv "
                         f"(the suffix picks the format)")
    return kind


def write_results(frame, path, temporary_folder=None):
    """Write a result table to Parquet or CSV (by the suffix), atomically.

    The table is written to a temporary file and moved into place, so a
    crash never leaves a half-written file under the final name; an error
    or an interrupt while writing removes the temporary file.

    Parameters
    ----------
    frame : pandas.DataFrame
    path : str or Path
        ``.parquet`` (or ``.pq``) or ``.csv``.
    temporary_folder : str or Path, optional
        Where the temporary file goes (on the same file system as ``path``),
        e.g. the sweep's parts folder, which a rerun cleans even after a
        kill; default: beside ``path``.
    """
    path = Path(path)
    kind = output_format(path)
    _check_folder(path)
    folder = path.parent if temporary_folder is None else Path(temporary_folder)
    tmp = folder / f"{path.name}.tmp-{os.getpid()}"
    try:
        if kind == "parquet":
            frame.to_parquet(tmp, index=False)
        else:
            frame.to_csv(tmp, index=False)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def read_results(path):
    """Read a result table written by a sweep (Parquet or CSV), dtypes restored.

    Returns
    -------
    pandas.DataFrame
        Equal to the DataFrame the sweep returned.
    """
    path = Path(path)
    if output_format(path) == "parquet":
        frame = pd.read_parquet(path)
    else:
        header = pd.read_csv(path, nrows=0).columns
        strings = [c for c in header
                   if RESULT_COLUMNS.get(c) == "str" or c in _NAME_INPUTS]
        numbers = [c for c in header if c not in strings]
        frame = pd.read_csv(path, dtype={c: str for c in strings}, keep_default_na=False,
                            na_values={c: ["", "NaN", "nan"] for c in numbers})
    return _normalize(frame)


def _check_folder(path):
    """The folder of an output must exist: flyopt does not create folders the user did not ask for."""
    folder = Path(path).parent
    if not folder.is_dir():
        raise SceneError("output", f"the folder {str(folder)!r} of {str(path)!r} does not exist")
