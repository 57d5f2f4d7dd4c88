"""A chunk of sweep points as arrays: each point's inputs (the scene's defaults where it varies
nothing), the result columns filled in by the designs, and the table they make."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd
from numpy.typing import NDArray

from flyopt.design import design_inputs
from flyopt.design.spec import MountShaft
from flyopt.outputs.results import RESULT_COLUMNS

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.io.scene import Scene

__all__ = ["WINNER_COLUMNS", "ChunkInputs", "PerName", "empty_results", "point_material", "result_table"]

#: The result columns a point's winner fills under their own names, each with the record of a
#: :class:`~flyopt.design.result.Design` it is read from (the design itself, its ``dims`` or its ``stresses``):
#: IPOPT's rows (:func:`flyopt.studies.ipopt_design.fill_row`) read them there, and the closed form's
#: (:func:`flyopt.studies.closed_form_design.design_closed_form`) from its arrays
#: (:class:`~flyopt.design.closed_form.Designs`) of the same names, so that both fill the same columns.
WINNER_COLUMNS = {
    "d_mean": "dims",
    "d_outer": "dims",
    "d_inner": "dims",
    "h": "dims",
    "b": "dims",
    "hb_ratio": "dims",
    "mass": "design",
    "rim_speed": "stresses",
    "hoop_stress": "stresses",
    "j_flywheel": "design",
    "j_at_reference": "design",
}


class ChunkInputs:
    """Per-point input arrays of a chunk, defaults from the scene."""

    omega_rim: NDArray[np.float64]  # ω_max of each point, where its rim is checked [rad/s]: set by the cycle step

    def __init__(self, scene: Scene, points: pd.DataFrame) -> None:
        n = len(points)
        self.n = n
        defaults = design_inputs(scene)
        spec = defaults.spec
        self.spec = spec
        self.mounts = {s.name: MountShaft(s.name, s.speed_ratio, s.diameter) for s in scene.shafts}

        def col(name: str, default: float | None) -> NDArray[np.float64]:
            if name in points:
                return points[name].to_numpy(dtype=float)
            return np.full(n, math.nan if default is None else float(default))

        def names(name: str, default: str | None) -> NDArray[np.object_]:
            if name in points:
                return points[name].to_numpy(dtype=object)
            return np.full(n, default, dtype=object)

        self.delta = col("delta", scene.delta)
        self.speed = col("speed", scene.omega_mean)
        self.inertia = col("inertia", scene.j_constant)
        self.scale = col("torque.scale", 1.0)
        self.geometry = names("design.geometry", spec.geometry)
        self.objective = names("design.objective", spec.objective)
        if "design.hb_ratio" in points:
            self.hb_min = self.hb_max = points["design.hb_ratio"].to_numpy(dtype=float)
        else:
            self.hb_min = col("design.hb_min", spec.hb_ratio[0])
            self.hb_max = col("design.hb_max", spec.hb_ratio[1])
        # one representation of a limit that is not set: inf (a sweep's "none" arrives as NaN)
        self.envelope = np.where(np.isnan(e := col("design.max_outer_diameter", spec.max_outer_diameter)), np.inf, e)
        self.width = np.where(np.isnan(w := col("design.max_width", spec.max_width)), np.inf, w)
        self.d_mean = col("design.d_mean", spec.d_mean)
        library = scene.material_library()
        self.library = library
        self.material_names = [m.name for m in defaults.materials]
        self.material = names("material", None) if "material" in points else None
        if self.material is not None:
            self.material_names = list(dict.fromkeys(self.material_names + [m for m in dict.fromkeys(self.material)]))
        self.shaft_names = [s.name for s in defaults.shafts]
        self.shaft = names("shaft", None) if "shaft" in points else None
        if self.shaft is not None:
            self.shaft_names = [s.name for s in scene.shafts if s.name in self.shaft_names or s.name in set(self.shaft)]
        shafts = {s.name: s for s in scene.shafts}
        # per-point properties, made for the materials and shafts a chunk uses (on first use)
        self.ratio = PerName(lambda name: col(f"shaft.{name}.speed_ratio", shafts[name].speed_ratio))
        self.density = PerName(lambda name: col(f"material.{name}.density", library[name].density))
        self.max_rim_speed = PerName(lambda name: col(f"material.{name}.max_rim_speed", library[name].max_rim_speed))
        self.material_cost = PerName(lambda name: col(f"material.{name}.cost", library[name].cost))
        self.allowable = PerName(lambda name: col("", library[name].allowable_stress))
        self.rim_speed_limit = PerName(self._rim_speed_limit)

    def _rim_speed_limit(self, name: str) -> NDArray[np.float64]:
        """The material's safe rim speed [m/s] at each point: the one rule (:func:`designer.rim_speed_limit`,
        the design's safety factor winning over the material's) on the material with the point's values."""
        from flyopt.design.designer import rim_speed_limit

        density, speed = self.density[name], self.max_rim_speed[name]
        values = np.stack([density, np.where(np.isnan(speed), -1.0, speed)], axis=1)
        distinct, inverse = np.unique(values, axis=0, return_inverse=True)
        limits = np.array(
            [rim_speed_limit(point_material(self.library[name], d, s), self.spec) for d, s in distinct], dtype=float
        )
        return limits[inverse.ravel()]


def point_material(base: Material, density: float, speed: float, cost: float = math.nan) -> Material:
    """The scene's material with a point's density, rim speed and cost (NaN or negative: the scene's own);
    the scene's material itself where the point changes none of them (a sweep that varies no material)."""
    same_speed = math.isnan(speed) or speed < 0 or (type(base.max_rim_speed) is float and speed == base.max_rim_speed)
    same_cost = math.isnan(cost) or (type(base.cost) is float and cost == base.cost)
    if type(base.density) is float and float(density) == base.density and same_speed and same_cost:
        return base
    return dataclasses.replace(
        base,
        density=float(density),
        max_rim_speed=base.max_rim_speed if math.isnan(speed) or speed < 0 else float(speed),
        cost=base.cost if math.isnan(cost) else float(cost),
    )


class PerName(dict[str, NDArray[np.float64]]):
    """Name to its per-point array, each made on first use by ``make(name)``."""

    def __init__(self, make: Callable[[str], NDArray[np.float64]]) -> None:
        super().__init__()
        self._make = make

    def __missing__(self, name: str) -> NDArray[np.float64]:
        value = self[name] = self._make(name)
        return value


def empty_results(n: int) -> dict[str, np.ndarray]:
    """The result columns (:data:`RESULT_COLUMNS`) of ``n`` points, each empty: "", False, 0 or NaN
    (``iterations`` -1)."""
    out = {}
    for name, kind in RESULT_COLUMNS.items():
        if kind == "str":
            out[name] = np.full(n, "", dtype=object)
        elif kind == "bool":
            out[name] = np.zeros(n, dtype=bool)
        elif kind == "int":
            out[name] = np.zeros(n, dtype=np.int64)
        else:
            out[name] = np.full(n, np.nan)
    out["iterations"][:] = -1
    return out


def result_table(
    inputs: ChunkInputs, points: pd.DataFrame, axes: Sequence[str], res: dict[str, np.ndarray]
) -> pd.DataFrame:
    """The chunk's table: ``point``, the core inputs of every point, the other varied fields (``axes``),
    then the results ``res``."""
    n = inputs.n
    data = {"point": points["point"].to_numpy(dtype=np.int64)}
    core = {
        "delta": inputs.delta,
        "speed": inputs.speed,
        "inertia": inputs.inertia,
        "torque.scale": inputs.scale,
        "design.geometry": inputs.geometry,
        "design.objective": inputs.objective,
        "design.hb_min": inputs.hb_min,
        "design.hb_max": inputs.hb_max,
        "design.max_outer_diameter": inputs.envelope,
        "design.max_width": inputs.width,
        "design.d_mean": inputs.d_mean,
    }
    data.update(core)
    for name in axes:
        if name not in data:
            data[name] = points[name].to_numpy()
    data.update(res)
    return pd.DataFrame(data, index=pd.RangeIndex(n), copy=False)
