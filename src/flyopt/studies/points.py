"""The points of a sweep: their checks, their counts of designs, their physics and each one's scene.

A point is a row of the sweep's table of points: values of scene fields
(:mod:`flyopt.io.sweep_spec` names them). :data:`PHYSICS_FIELDS` are those that
change the cycle's analysis; every other field changes only the design, and the
points that differ only in those share one analysis (:mod:`flyopt.studies.physics`).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.design import closed_form as batch
from flyopt.design import design_inputs
from flyopt.errors import SceneError
from flyopt.io.sweep_spec import field_path
from flyopt.io.torque_section import NetAreas
from flyopt.names import Geometry

if TYPE_CHECKING:
    from flyopt.design.inputs import DesignInputs
    from flyopt.io.scene import Scene


__all__ = [
    "PHYSICS_FIELDS",
    "check_points",
    "design_counts",
    "design_seconds",
    "is_none",
    "physics_codes",
    "point_scene",
    "vectorized",
]

#: The fields of a point that change its physics (its analysis); every other field changes
#: only the design, and points that differ only in those share one analysis.
PHYSICS_FIELDS = ("delta", "speed", "inertia", "torque.scale")


def check_points(scene: Scene, points: pd.DataFrame, where: str) -> None:
    """Reject points whose design settings are invalid, naming the field.

    Works on the varied columns only (a 10⁶-point plan is checked without
    per-point copies of the scene's defaults).
    """
    spec = design_inputs(scene).spec

    def column(name, default):
        if name in points:
            return points[name].to_numpy(dtype=float)
        return np.asarray(math.nan if default is None else float(default))

    if "design.hb_ratio" in points:
        hb_min = hb_max = points["design.hb_ratio"].to_numpy(dtype=float)
    else:
        hb_min = column("design.hb_min", spec.hb_ratio[0])
        hb_max = column("design.hb_max", spec.hb_ratio[1])
    bad = np.flatnonzero(np.broadcast_to(hb_min > hb_max, (len(points),)))
    if bad.size:
        k = int(bad[0])
        low, high = np.broadcast_to(hb_min, (len(points),)), np.broadcast_to(hb_max, (len(points),))
        raise SceneError(
            field_path(where, "design.hb_min"),
            f"H/B min {low[k]:.6g} exceeds max {high[k]:.6g} at point {k} (and {bad.size - 1} other points)",
        )
    varied = [name for name in _SPEC_COLUMNS if name in points]
    settings = points[varied].drop_duplicates().to_dict("records") if varied and len(points) else [{}]
    for row in settings:
        hb = (
            (row["design.hb_ratio"],) * 2
            if "design.hb_ratio" in row
            else (row.get("design.hb_min", spec.hb_ratio[0]), row.get("design.hb_max", spec.hb_ratio[1]))
        )
        envelope = row.get("design.max_outer_diameter", spec.max_outer_diameter)
        width = row.get("design.max_width", spec.max_width)
        d_mean = row.get("design.d_mean", spec.d_mean)
        try:
            dataclasses.replace(
                spec,
                geometry=row.get("design.geometry", spec.geometry),
                hb_ratio=hb,
                objective=row.get("design.objective", spec.objective),
                max_outer_diameter=math.inf if is_none(envelope) else envelope,
                max_width=math.inf if is_none(width) else width,
                d_mean=None if is_none(d_mean) else d_mean,
            )
        except ValueError as err:
            raise SceneError(field_path(where, "design"), str(err)) from None
    inputs = design_inputs(scene)
    material_names = [m.name for m in inputs.materials]
    if "material" in points:
        material_names = list(dict.fromkeys(material_names + list(points["material"].unique())))
    if len(points) and not material_names:
        raise SceneError("design.materials", "no material to design with")
    objective = (
        points["design.objective"].to_numpy(dtype=object) == "cost"
        if "design.objective" in points
        else np.asarray(spec.objective == "cost")
    )
    cost = np.broadcast_to(objective, (len(points),))
    if not cost.any():
        return
    library = scene.material_library()
    for name in material_names:
        used = cost & (points["material"].to_numpy(dtype=object) == name if "material" in points else True)
        if not used.any():
            continue
        field = f"material.{name}.cost"
        missing = (
            np.isnan(points[field].to_numpy(dtype=float)[used]).any() if field in points else library[name].cost is None
        )
        if missing:
            raise SceneError(
                field_path(where, "design.objective"),
                f"'cost' needs a cost per kg for every material; none is given for {name}",
            )


#: Point columns that set the design specification (checked together by DesignSpec).
_SPEC_COLUMNS = (
    "design.geometry",
    "design.objective",
    "design.hb_ratio",
    "design.hb_min",
    "design.hb_max",
    "design.max_outer_diameter",
    "design.max_width",
    "design.d_mean",
)


def design_counts(scene: Scene, points: pd.DataFrame, method: str = "auto") -> tuple[int, np.ndarray]:
    """How many designs each point asks for, and how many of them need IPOPT.

    Parameters
    ----------
    scene : Scene
    points : pandas.DataFrame
        Rows of :attr:`SweepPlan.points`.
    method : {"auto", "closed_form", "ipopt"}

    Returns
    -------
    per_point : int
        Material × shaft combinations of every point.
    ipopt : ndarray of bool
        Per point: designed one by one, by IPOPT (the closed form does not cover its
        geometry and objective, or ``method`` is ``ipopt``), or as ``flyopt solve``
        designs it where the scene describes a shaft (:mod:`flyopt.studies.described`).
    """
    from flyopt.pipeline import describes_shafts

    inputs = design_inputs(scene)
    n_materials = 1 if "material" in points else len(inputs.materials)
    n_shafts = 1 if "shaft" in points else len(inputs.shafts)
    n = len(points)
    if method == "ipopt" or describes_shafts(scene):
        return n_materials * n_shafts, np.ones(n, dtype=bool)
    spec = inputs.spec
    geometry = points["design.geometry"] if "design.geometry" in points else None
    objective = points["design.objective"] if "design.objective" in points else None
    if geometry is None and objective is None:
        ipopt = np.full(n, not vectorized(inputs, spec.geometry, spec.objective))
    else:
        pairs = pd.DataFrame(
            {
                "g": geometry if geometry is not None else spec.geometry,
                "o": objective if objective is not None else spec.objective,
            },
            index=points.index,
        )
        codes, uniques = pd.MultiIndex.from_frame(pairs).factorize()
        covered = np.array([vectorized(inputs, g, o) for g, o in uniques], dtype=bool)
        ipopt = ~covered[codes]
    return n_materials * n_shafts, ipopt


def design_seconds(scene: Scene, points: pd.DataFrame, method: str = "auto") -> tuple[np.ndarray, np.ndarray]:
    """The estimated seconds of each point's designs in one process, and of a chunk's start at each point.

    A point's designs: its combinations (:func:`design_counts`) times the cost of one, by how it is designed:
    the closed form, IPOPT on a bare wheel, IPOPT on a whole wheel (rim_web; rim_arms once per arm count it
    considers), or ``flyopt solve``'s design where the scene describes a shaft
    (:data:`~flyopt.studies.chunks.SECONDS_CLOSED_FORM` ... :data:`~flyopt.studies.chunks.SECONDS_DESCRIBED`).
    A chunk's start: what its first point costs beyond the others, its NLPs solved without a neighbour's
    wheel to start from (:data:`~flyopt.studies.chunks.COLD_START_POINTS` of its designs, as measured on whole
    wheels: a bare wheel's NLP and a described shaft's designs warm-start within a chunk too); none for the
    closed form, which has no start.

    Returns
    -------
    seconds, start : ndarray of float
        One estimate per point [s] each.
    """
    from flyopt.pipeline import describes_shafts
    from flyopt.studies.chunks import (
        COLD_START_POINTS,
        SECONDS_CLOSED_FORM,
        SECONDS_DESCRIBED,
        SECONDS_IPOPT,
        SECONDS_WHOLE_WHEEL,
    )

    per_point, ipopt = design_counts(scene, points, method)
    if describes_shafts(scene):
        seconds = np.full(len(points), per_point * SECONDS_DESCRIBED)
        return seconds, COLD_START_POINTS * seconds
    spec = design_inputs(scene).spec
    if "design.geometry" in points:
        geometry = points["design.geometry"].astype(str).to_numpy()
    else:
        geometry = np.full(len(points), str(spec.geometry))
    wheels = ipopt & np.isin(geometry, [str(Geometry.RIM_WEB), str(Geometry.RIM_ARMS)])
    whole = np.where(geometry == str(Geometry.RIM_ARMS), len(spec.arms), 1.0) * SECONDS_WHOLE_WHEEL
    seconds = per_point * np.where(wheels, whole, np.where(ipopt, SECONDS_IPOPT, SECONDS_CLOSED_FORM))
    return seconds, np.where(ipopt, COLD_START_POINTS * seconds, 0.0)


def vectorized(inputs: DesignInputs, geometry_name: str, objective: str) -> bool:
    """Whether the vectorized closed form designs a point: the textbook design (a bare wheel, no bore,
    sized by the rim speed: :meth:`DesignSpec.textbook`) with an objective the closed form covers.
    Every other point goes through :func:`flyopt.design.designer.design_flywheel` one by one."""
    spec = dataclasses.replace(inputs.spec, geometry=geometry_name)
    return batch.covers(geometry_name, objective) and all(
        spec.textbook(spec.bore if spec.bore is not None else s.diameter) for s in inputs.shafts
    )


def physics_codes(points: pd.DataFrame) -> tuple[np.ndarray, int]:
    """A number per point naming its physics (see :data:`PHYSICS_FIELDS`), by first appearance.

    Parameters
    ----------
    points : pandas.DataFrame

    Returns
    -------
    codes : ndarray of int
        Equal for points of equal physics; 0, 1, 2, ... in the order each
        physics first appears.
    count : int
        Distinct physics.
    """
    fields = [name for name in PHYSICS_FIELDS if name in points]
    if not fields or not len(points):
        return np.zeros(len(points), dtype=np.int64), min(len(points), 1)
    if len(fields) == 1:
        codes, uniques = pd.factorize(points[fields[0]], sort=False)
    else:
        codes, uniques = pd.MultiIndex.from_frame(points[fields]).factorize()
    return np.asarray(codes, dtype=np.int64), len(uniques)


def check_scalable(scene: Scene, label: str) -> None:
    """Refuse a ``torque.scale`` axis (``label``) of a scene whose torques are not all tables, constants or
    expressions: a motor's characteristic depends on speed, and scaling it would be another motor (the sweep
    stopped at its first point with "cannot scale a torque of type MotorTorque", naming no option)."""
    from flyopt.cycle.torque import MotorTorque

    for which, curve in (("driving", scene.driving), ("resisting", scene.resisting)):
        try:
            _scale_curve(curve, 1.0)
        except SceneError:
            kind = "a motor's characteristic, which depends on speed" if isinstance(curve, MotorTorque) else "no table"
            raise SceneError(
                label,
                f"scales the scene's torque tables and expressions, and its {which} torque is {kind}: give the torques "
                "as tables or expressions to scale them (a motor is sized by [drive])",
            ) from None


def _scale_curve(curve, k):
    if curve is None:
        return None
    if isinstance(curve, PiecewiseLinear):
        return PiecewiseLinear(curve.angles, curve.values * k)
    if isinstance(curve, Constant):
        return curve if curve.unknown else Constant(curve.value * k)
    if isinstance(curve, ExpressionTorque):
        return dataclasses.replace(curve, scale=curve.scale * k)
    raise SceneError("torque.scale", f"cannot scale a torque of type {type(curve).__name__}")


def point_scene(scene: Scene, point: Mapping[str, Any]) -> Scene:
    """The scene of one sweep point (for individual solves and checks).

    Parameters
    ----------
    scene : Scene
    point : mapping
        Canonical field name to value (SI, names, NaN for none), e.g. a row
        of :attr:`SweepPlan.points`.

    Returns
    -------
    Scene
    """
    from flyopt.design.materials import material_library

    changes: dict[str, Any] = {}
    design: dict[str, Any] = {}
    # the scene's [design], or the defaults (one rule: design_inputs), built only for a point that varies it:
    # a point of a physics axis (δ, speed) is made for every analysis and needs none of it
    spec = functools.cache(lambda: design_inputs(scene).spec)
    shafts = {s.name: s for s in scene.shafts}
    library = material_library(scene.materials)
    user = {m.name: m for m in scene.materials}
    for name, value in point.items():
        if name == "point":
            continue
        if name == "delta":
            changes["delta"] = float(value)
        elif name == "speed":
            changes["omega_mean"] = float(value)
        elif name == "inertia":
            changes["j_constant"] = float(value)
        elif name == "torque.scale":
            k = float(value)
            changes["driving"] = _scale_curve(scene.driving, k)
            changes["resisting"] = _scale_curve(scene.resisting, k)
            if scene.net is not None:
                changes["net"] = NetAreas(tuple(e * k for e in scene.net.energies))
        elif name == "design.hb_ratio":
            design["hb_ratio"] = (float(value), float(value))
        elif name in ("design.hb_min", "design.hb_max"):
            low, high = design.get("hb_ratio", spec().hb_ratio)
            design["hb_ratio"] = (float(value), high) if name.endswith("min") else (low, float(value))
        elif name in ("design.max_outer_diameter", "design.max_width", "design.d_mean"):
            design[name.split(".")[1]] = None if is_none(value) else float(value)
        elif name in ("design.geometry", "design.objective"):
            design[name.split(".")[1]] = str(value)
        elif name == "material":
            changes["design_materials"] = (str(value),)
        elif name == "shaft":
            changes["design_shafts"] = (str(value),)
        elif name.startswith("shaft."):
            shaft_name = name.split(".")[1]
            shafts[shaft_name] = dataclasses.replace(shafts[shaft_name], speed_ratio=float(value))
        elif name.startswith("material."):
            _, material_name, prop = name.split(".")
            base = user.get(material_name, library[material_name])
            changed: dict[str, Any] = {prop: float(value)}  # a numeric property named by the sweep
            user[material_name] = dataclasses.replace(base, **changed)
        else:
            raise SceneError(name, "unknown sweep field")
    if design:
        changes["design"] = dataclasses.replace(spec(), **design)
    changes["shafts"] = tuple(shafts.values())
    changes["materials"] = tuple(user.values())
    return scene.replace(**changes)


def is_none(value: object) -> bool:
    """Whether a point's value means \"no value\" (None, or NaN in a float column)."""
    return value is None or (isinstance(value, float) and math.isnan(value))
