"""Evaluation of sweep points: every point designed, the cycle analysed once where exact.

What is computed once, and why it is exact
------------------------------------------
The cycle is analysed once: for torques of the angle alone A_max does not
depend on δ, ω_m or J_c, and scaling both torques by k scales every ΔE, so
A_max(k) = k A_max. Each point then has J_F = k A_max / (ω_m² δ) − J_c,
the formula of the analysis itself. The designs come from
:mod:`flyopt.design.closed_form` (closed form, exact, vectorized over every point and
combination) where it covers the structure, and from
:func:`flyopt.design.designer.design_flywheel` (IPOPT on an NLP built once per
structure and process, fed parameters) elsewhere; each row says which
(``method``). A point whose IPOPT solve fails gets ``status = "failed"``
with IPOPT's status, never a mass.

Where one A_max does not serve every point (a varying inertia, a torque that
depends on speed), each point's physics (δ, ω_m, J_c, torque scale) is
analysed by :func:`flyopt.analysis.analyse`, once per distinct physics: the
points that vary only the design (envelope, material, shaft, H/B, geometry,
objective) reuse it.

Worker processes and Dask workers run a :class:`Task`: the scene as data
(its file's text, see :mod:`flyopt.studies.payload`) and the cycle's A_max
when one serves every point. Each worker rebuilds the scene once, so its
memo of analyses serves every chunk it runs.

One path for each decision: the scene's design problem comes from
:func:`flyopt.design.design_inputs` (the columns of a point override it), the
constraint check and the binding rule from :mod:`flyopt.design.check`, the
winner of each point from :func:`flyopt.design.rank.winners`; so a sweep
point and ``flyopt solve`` of the same scene name the same winner.
"""

from __future__ import annotations

import dataclasses
import math
import threading
import weakref
from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd
from numpy.typing import NDArray

from flyopt.cycle.indicator import required_inertia, speed_extremes
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.design import closed_form as batch
from flyopt.design import design_inputs, rank
from flyopt.design.check import binding_names
from flyopt.design.spec import MountShaft
from flyopt.errors import SceneError, SolverFailed
from flyopt.io.sweep_spec import field_path
from flyopt.io.torque_section import NetAreas
from flyopt.outputs.results import RESULT_COLUMNS
from flyopt.sizing.peak_torque import flywheel_peak_torque

if TYPE_CHECKING:
    from flyopt.io.scene import Scene
    from flyopt.studies.payload import ScenePayload

__all__ = [
    "PHYSICS_FIELDS",
    "Task",
    "design_counts",
    "evaluate_points",
    "physics_analysis",
    "physics_codes",
    "point_scene",
    "task_of",
]

#: The fields of a point that change its physics (its analysis); every other field changes
#: only the design, and points that differ only in those share one analysis.
PHYSICS_FIELDS = ("delta", "speed", "inertia", "torque.scale")


def check_points(scene, points, where):
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
                max_outer_diameter=math.inf if _is_none(envelope) else envelope,
                max_width=math.inf if _is_none(width) else width,
                d_mean=None if _is_none(d_mean) else d_mean,
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


def design_counts(scene, points, method="auto"):
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
        Per point: designed by IPOPT (the closed form does not cover its
        geometry and objective, or ``method`` is ``ipopt``).
    """
    inputs = design_inputs(scene)
    n_materials = 1 if "material" in points else len(inputs.materials)
    n_shafts = 1 if "shaft" in points else len(inputs.shafts)
    n = len(points)
    if method == "ipopt":
        return n_materials * n_shafts, np.ones(n, dtype=bool)
    spec = inputs.spec
    geometry = points["design.geometry"] if "design.geometry" in points else None
    objective = points["design.objective"] if "design.objective" in points else None
    if geometry is None and objective is None:
        ipopt = np.full(n, not _vectorized(inputs, spec.geometry, spec.objective))
    else:
        pairs = pd.DataFrame(
            {
                "g": geometry if geometry is not None else spec.geometry,
                "o": objective if objective is not None else spec.objective,
            },
            index=points.index,
        )
        codes, uniques = pd.MultiIndex.from_frame(pairs).factorize()
        covered = np.array([_vectorized(inputs, g, o) for g, o in uniques], dtype=bool)
        ipopt = ~covered[codes]
    return n_materials * n_shafts, ipopt


def _vectorized(inputs, geometry_name, objective):
    """Whether the vectorized closed form designs a point: the textbook design (a bare wheel, no bore,
    sized by the rim speed: :meth:`DesignSpec.textbook`) with an objective the closed form covers.
    Every other point goes through :func:`flyopt.design.designer.design_flywheel` one by one."""
    spec = dataclasses.replace(inputs.spec, geometry=geometry_name)
    return batch.covers(geometry_name, objective) and all(
        spec.textbook(spec.bore if spec.bore is not None else s.diameter) for s in inputs.shafts
    )


def physics_codes(points):
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


# --------------------------------------------------------------------------
# One point as a scene


# --------------------------------------------------------------------------


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


def point_scene(scene, point):
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
            low, high = design.get("hb_ratio", scene.design.hb_ratio)
            design["hb_ratio"] = (float(value), high) if name.endswith("min") else (low, float(value))
        elif name in ("design.max_outer_diameter", "design.max_width", "design.d_mean"):
            design[name.split(".")[1]] = None if _is_none(value) else float(value)
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
            user[material_name] = dataclasses.replace(base, **{prop: float(value)})
        else:
            raise SceneError(name, "unknown sweep field")
    if design:
        changes["design"] = dataclasses.replace(scene.design, **design)
    changes["shafts"] = tuple(shafts.values())
    changes["materials"] = tuple(user.values())
    return scene.replace(**changes)


def _is_none(value):
    return value is None or (isinstance(value, float) and math.isnan(value))


# --------------------------------------------------------------------------
# Evaluation of a chunk of points
# --------------------------------------------------------------------------


def _reusable(scene):
    """Whether J_F = A_max/(ω_m² δ) − J_c with one A_max holds at every point.

    True where the energy model is the exact one (flyopt's one model chooser
    decides): a constant inertia and torques of the angle only, so A_max does
    not depend on δ, ω_m or J_c, and scales with the torques. Otherwise each
    distinct physics is analysed by its exact model.
    """
    if scene.net is not None:
        return True
    from flyopt.machine.reduce import reduce
    from flyopt.sizing.choose import ENERGY, choose

    return choose(reduce(scene))[0] == ENERGY


@dataclass(frozen=True)
class ChunkContext:
    """What every chunk needs; picklable (the torques are left out when reusable)."""

    scene: Scene
    a_max: float | None
    driving_torque: float | None
    reusable: bool
    method: str = "auto"
    solver_options: dict | None = None
    axes: tuple = ()
    torque_peak: float | None = None  # max |M_d - M_r| of the cycle when reusable [N*m]


def chunk_context(scene, method="auto", solver_options=None, axes=()):
    reusable = _reusable(scene)
    if reusable:
        analysis = physics_analysis(scene)
        stripped = scene.replace(driving=None, resisting=None, net=None)
        return ChunkContext(
            stripped,
            analysis.a_max,
            analysis.driving_torque,
            True,
            method,
            dict(solver_options) if solver_options else None,
            tuple(axes),
            analysis.net_torque_peak() if _needs_torque(scene) else None,
        )
    return ChunkContext(scene, None, None, False, method, dict(solver_options) if solver_options else None, tuple(axes))


@dataclass(frozen=True)
class Task:
    """The evaluation of a sweep's chunks, as data for worker processes and Dask workers.

    Called with a table of points, it designs them as :func:`evaluate_points`
    does. It holds no live object: the scene travels as a
    :class:`~flyopt.studies.payload.ScenePayload` (its file's text, the
    fields that differ), the once-analysed cycle of a reusable scene as two
    numbers. Each worker rebuilds the scene once and keeps it (with its
    memo of analyses, :func:`physics_analysis`) for every chunk it runs.

    Attributes
    ----------
    scene : ScenePayload
    method : str
    solver_options : dict or None
    axes : tuple of str
    reusable : bool
        One A_max serves every point (see :func:`_reusable`).
    a_max : float or None
        The cycle's A_max [J] when reusable.
    driving_torque : float or None
        Its driving torque [N*m] when reusable and known.
    """

    scene: ScenePayload
    method: str = "auto"
    solver_options: dict | None = None
    axes: tuple = ()
    reusable: bool = False
    a_max: float | None = None
    driving_torque: float | None = None
    torque_peak: float | None = None

    def __call__(self, points):
        return evaluate_chunk(self.context(), points)

    def context(self):
        """The chunk context of this process, built on first use and kept."""
        key = (
            self.scene.key,
            self.method,
            repr(sorted((self.solver_options or {}).items())),
            self.axes,
            self.reusable,
            self.a_max,
            self.driving_torque,
            self.torque_peak,
        )
        with _TASK_LOCK:
            ctx = _TASK_CONTEXTS.get(key)
            if ctx is None:
                scene = self.scene.scene()
                if self.reusable:
                    scene = scene.replace(driving=None, resisting=None, net=None)
                ctx = ChunkContext(
                    scene,
                    self.a_max,
                    self.driving_torque,
                    self.reusable,
                    self.method,
                    self.solver_options,
                    self.axes,
                    self.torque_peak,
                )
                while len(_TASK_CONTEXTS) >= 4:  # a worker that serves several sweeps
                    _TASK_CONTEXTS.pop(next(iter(_TASK_CONTEXTS)))
                _TASK_CONTEXTS[key] = ctx
        return ctx


_TASK_CONTEXTS: dict = {}
_TASK_LOCK = threading.Lock()


def task_of(ctx, scene):
    """The :class:`Task` of a sweep context, or why it cannot leave this process.

    Parameters
    ----------
    ctx : ChunkContext
    scene : Scene
        The scene the sweep varies (``ctx.scene`` may have its torques stripped).

    Returns
    -------
    task : Task or None
    reason : str
        Why there is no task ("" when there is one).
    """
    from flyopt.studies.payload import payload

    data, reason = payload(scene)
    if data is None:
        return None, reason
    return Task(
        data, ctx.method, ctx.solver_options, ctx.axes, ctx.reusable, ctx.a_max, ctx.driving_torque, ctx.torque_peak
    ), ""


class _Inputs:
    """Per-point input arrays of a chunk, defaults from the scene."""

    omega_rim: NDArray[np.float64]  # ω_max of each point, where its rim is checked [rad/s]: set by the cycle step

    def __init__(self, scene, points):
        n = len(points)
        self.n = n
        defaults = design_inputs(scene)
        spec = defaults.spec
        self.spec = spec
        self.mounts = {s.name: MountShaft(s.name, s.speed_ratio, s.diameter) for s in scene.shafts}

        def col(name, default):
            if name in points:
                return points[name].to_numpy(dtype=float)
            return np.full(n, math.nan if default is None else float(default))

        def names(name, default):
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
        self.ratio = _PerName(lambda name: col(f"shaft.{name}.speed_ratio", shafts[name].speed_ratio))
        self.density = _PerName(lambda name: col(f"material.{name}.density", library[name].density))
        self.max_rim_speed = _PerName(lambda name: col(f"material.{name}.max_rim_speed", library[name].max_rim_speed))
        self.material_cost = _PerName(lambda name: col(f"material.{name}.cost", library[name].cost))
        self.allowable = _PerName(lambda name: col("", library[name].allowable_stress))
        self.rim_speed_limit = _PerName(self._rim_speed_limit)

    def _rim_speed_limit(self, name):
        """The material's safe rim speed [m/s] at each point: the one rule (:func:`designer.rim_speed_limit`,
        the design's safety factor winning over the material's) on the material with the point's values."""
        from flyopt.design.designer import rim_speed_limit

        density, speed = self.density[name], self.max_rim_speed[name]
        values = np.stack([density, np.where(np.isnan(speed), -1.0, speed)], axis=1)
        distinct, inverse = np.unique(values, axis=0, return_inverse=True)
        limits = np.array(
            [rim_speed_limit(_point_material(self.library[name], d, s), self.spec) for d, s in distinct], dtype=float
        )
        return limits[inverse.ravel()]


def _point_material(base, density, speed, cost=math.nan):
    """The scene's material with a point's density, rim speed and cost (NaN or negative: the scene's own)."""
    return dataclasses.replace(
        base,
        density=float(density),
        max_rim_speed=base.max_rim_speed if math.isnan(speed) or speed < 0 else float(speed),
        cost=base.cost if math.isnan(cost) else float(cost),
    )


class _PerName(dict):
    """Name to its per-point array, each made on first use by ``make(name)``."""

    def __init__(self, make):
        super().__init__()
        self._make = make

    def __missing__(self, name):
        value = self[name] = self._make(name)
        return value


def _empty_results(n):
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


def evaluate_points(scene_or_context, points, *, method="auto", solver_options=None):
    """Design every point of a table of sweep points.

    Parameters
    ----------
    scene_or_context : Scene
        The scene the points vary (its cycle is analysed once).
    points : pandas.DataFrame
        Rows of :attr:`SweepPlan.points`.
    method : {"auto", "closed_form", "ipopt"}
        ``auto``: the closed form of :mod:`flyopt.design.closed_form` where it is exact,
        IPOPT elsewhere; ``ipopt``: IPOPT for every point (for checks and
        benchmarks); ``closed_form``: refuse structures it does not cover.
    solver_options : mapping, optional
        CasADi/IPOPT options for the IPOPT points.

    Returns
    -------
    pandas.DataFrame
        One row per point: ``point``, :data:`CORE_INPUTS`, the other varied
        fields, then :data:`RESULT_COLUMNS`.
    """
    ctx = scene_or_context
    if not isinstance(ctx, ChunkContext):
        ctx = chunk_context(ctx, method, solver_options, tuple(c for c in points.columns if c != "point"))
    return evaluate_chunk(ctx, points)


def evaluate_chunk(ctx, points):
    scene = ctx.scene
    inputs = _Inputs(scene, points)
    n = inputs.n
    res = _empty_results(n)
    needs_torque = _needs_torque(scene)
    # -- the cycle: analysed once, A_max scaled (see the module notes) ------
    if ctx.reusable:
        a_max = inputs.scale * ctx.a_max
        driving = inputs.scale * ctx.driving_torque if ctx.driving_torque is not None else np.full(n, np.nan)
        j_margin = required_inertia(a_max, inputs.speed, inputs.delta, inputs.inertia)
        inputs.omega_rim = speed_extremes(inputs.speed, inputs.delta)[0]  # ω_max: the rim is checked there
        power = driving * inputs.speed
        motor_power = power / scene.efficiency
    else:  # varying inertia or speed-dependent torques: each distinct physics by its exact model
        a_max, driving, j_margin, power, motor_power = (np.empty(n) for _ in range(5))
        inputs.omega_rim = np.empty(n)
        torques = needs_torque and []
        for k, analysis in enumerate(_analyses(scene, points)):
            if needs_torque:
                torques.append(analysis.flywheel_torque())
            a_max[k], j_margin[k] = analysis.a_max, analysis.j_margin
            inputs.omega_rim[k] = analysis.omega_max
            driving[k] = _float(analysis.driving_torque)
            power[k], motor_power[k] = _float(analysis.power), _float(analysis.motor_power)
    res["a_max"], res["j_margin"] = a_max, j_margin
    res["j_required"] = np.maximum(j_margin, 0.0)
    res["driving_torque"] = driving
    res["power"] = power
    res["motor_power"] = motor_power
    needed = j_margin > 0.0
    idle = ~needed
    res["status"][idle] = "not_needed"
    res["method"][idle] = "none"
    for k in np.flatnonzero(idle).tolist():
        res["message"][k] = f"no flywheel needed: J_F = {j_margin[k]:.4g} kg·m² is not positive"
    design = design_inputs(scene)
    seen: dict[tuple[str, str], bool] = {}
    covered = (
        np.array(
            [
                seen[g, o] if (g, o) in seen else seen.setdefault((g, o), _vectorized(design, g, o))
                for g, o in zip(inputs.geometry, inputs.objective)
            ],
            dtype=np.bool_,
        )
        if n
        else np.zeros(0, dtype=np.bool_)
    )
    if ctx.method == "closed_form" and (needed & ~covered).any():
        k = int(np.flatnonzero(needed & ~covered)[0])
        raise SceneError(
            "method",
            f"the closed form does not cover objective "
            f"{inputs.objective[k]!r} (point {int(points['point'].iloc[k])}); "
            f"use method 'auto' or 'ipopt'",
        )
    use_batch = needed & covered if ctx.method != "ipopt" else np.zeros(n, dtype=bool)
    _design_closed_form(inputs, j_margin, use_batch, res)
    for k in np.flatnonzero(needed & ~use_batch).tolist():
        torque = None
        if needs_torque and ctx.reusable and ctx.torque_peak is not None:
            torque = flywheel_peak_torque(
                j_margin[k], j_margin[k] + inputs.inertia[k], inputs.scale[k] * ctx.torque_peak, 1.0
            )
        elif needs_torque and not ctx.reusable:
            torque = torques[k]
        _design_ipopt(ctx, inputs, k, j_margin[k], res, torque)
    return _table(inputs, points, ctx.axes, res)


def _float(value):
    return np.nan if value is None else float(value)


def _analyses(scene, points):
    """The analysis of each point, computed once per distinct physics (see PHYSICS_FIELDS)."""
    fields = [name for name in PHYSICS_FIELDS if name in points]
    if not fields:
        analysis = physics_analysis(scene)
        for _ in range(len(points)):
            yield analysis
        return
    for values in zip(*(points[name].to_numpy(dtype=float) for name in fields)):
        yield physics_analysis(scene, dict(zip(fields, values)))


#: Analyses of this process, per scene object: {id(scene): (weak reference, {physics: Analysis},
#: {physics but δ: the latest Analysis})}.
_ANALYSES: dict[int, tuple[Any, OrderedDict[Any, Any], OrderedDict[Any, Any]]] = {}
#: Analyses kept per scene, the most recently used (~0.1-0.2 MB each): a sweep's chunks hold
#: the points of one physics together, so only a chunk's own physics need to stay.
MEMO_SIZE = 256
_MEMO_LOCK = threading.Lock()


def physics_analysis(scene, point=None):
    """The analysis of a scene at one physics (δ, ω_m, J_c, torque scale), computed once.

    Every study (sweep chunks, the points of a Pareto front, the materials of
    a trade-off) asks here, so that variations of the design alone (envelope,
    material, shaft, H/B, geometry, objective) never analyse the cycle again.
    The memo lives as long as the scene object does, and keeps the
    :data:`MEMO_SIZE` most recently used analyses. A physics that differs
    from one analysed before in δ alone is analysed ``like`` it (the reduced
    machine, its compiled models and the energy indicator do not depend on
    δ), which makes the points of a δ axis several times cheaper.

    Parameters
    ----------
    scene : Scene
    point : mapping, optional
        Values of :data:`PHYSICS_FIELDS` (SI); the scene's own where absent.

    Returns
    -------
    flyopt.analysis.Analysis
    """
    from flyopt import analysis as _analysis

    point = dict(point or {})
    own = {"delta": scene.delta, "speed": scene.omega_mean, "inertia": scene.j_constant, "torque.scale": 1.0}
    key = tuple(float(point.get(name, own[name])) for name in PHYSICS_FIELDS)
    with _MEMO_LOCK:  # Dask workers in threads share this process's memo
        entry = _ANALYSES.get(id(scene))
        if entry is None or entry[0]() is not scene:
            for stale in [k for k, (ref, *_) in _ANALYSES.items() if ref() is None]:
                del _ANALYSES[stale]
            entry = _ANALYSES[id(scene)] = (weakref.ref(scene), OrderedDict(), OrderedDict())
        memo, by_rest = entry[1], entry[2]
        if key in memo:
            memo.move_to_end(key)
            return memo[key]
        # the same physics but δ (PHYSICS_FIELDS[0]): its reduced machine and indicator serve again
        like = by_rest.get(key[1:])
    changed = {name: value for name, value in zip(PHYSICS_FIELDS, key) if value != own[name]}
    result = _analysis.analyse(point_scene(scene, changed) if changed else scene, like=like)
    with _MEMO_LOCK:
        memo[key] = result
        by_rest[key[1:]] = result
        by_rest.move_to_end(key[1:])
        for kept in (memo, by_rest):
            while len(kept) > MEMO_SIZE:
                kept.popitem(last=False)
    return result


def _design_closed_form(inputs, j_margin, mask, res):
    """Fill the rows of ``mask`` from the vectorized closed form."""
    if not mask.any():
        return
    geometries = list(dict.fromkeys(inputs.geometry[mask]))
    m_names, s_names = inputs.material_names, inputs.shaft_names
    m_code = (
        np.array([m_names.index(m) for m in inputs.material]) if inputs.material is not None else np.full(inputs.n, -1)
    )
    s_code = np.array([s_names.index(s) for s in inputs.shaft]) if inputs.shaft is not None else np.full(inputs.n, -1)
    for geo in geometries:
        in_geo = mask & (inputs.geometry == geo)
        keys = np.stack([m_code[in_geo], s_code[in_geo]], axis=1)
        groups, inverse = np.unique(keys, axis=0, return_inverse=True)
        points_geo = np.flatnonzero(in_geo)
        for g, (mc, sc) in enumerate(groups):
            pts = points_geo[inverse.ravel() == g]
            mats = m_names if mc < 0 else [m_names[mc]]
            shafts = s_names if sc < 0 else [s_names[sc]]
            _design_group(inputs, geo, pts, mats, shafts, j_margin, res)


def _design_group(inputs, geo, pts, mats, shafts, j_margin, res):
    """One geometry, one material list and one shaft list, for points ``pts``."""
    n_m, n_s = len(mats), len(shafts)
    per = n_m * n_s
    p = np.repeat(pts, per)
    mi = np.tile(np.repeat(np.arange(n_m), n_s), len(pts))
    si = np.tile(np.tile(np.arange(n_s), n_m), len(pts))
    order = mi * n_s + si

    def table(values, names, index):
        return np.stack([values[name] for name in names])[index, p]

    density = table(inputs.density, mats, mi)
    v_max = table(inputs.rim_speed_limit, mats, mi)
    cost_per_kg = table(inputs.material_cost, mats, mi)
    allowable = table(inputs.allowable, mats, mi)
    ratio = table(inputs.ratio, shafts, si)
    out = batch.design_combinations(
        geo,
        j_margin[p],
        inputs.omega_rim[p],
        ratio,
        density,
        v_max,
        inputs.hb_min[p],
        inputs.hb_max[p],
        inputs.envelope[p],
        inputs.width[p],
        inputs.d_mean[p],
    )
    mass = out.mass
    cost = mass * cost_per_kg
    objective = np.where(inputs.objective[p] == "cost", cost, mass)
    feasible = out.feasible
    res["n_combinations"][pts] = per
    counts = np.bincount(p[feasible], minlength=inputs.n)
    res["n_feasible"][pts] = counts[pts]
    res["method"][pts] = batch.METHOD
    # the winner of each point, by the one ranking rule (flyopt.design.rank)
    f = np.flatnonzero(feasible)
    if f.size:
        local = np.searchsorted(pts, p[f])  # pts is sorted: each point's group number
        best = rank.winners(
            local,
            objective[f],
            cost[f],
            mass[f],
            out.rim_speed[f],
            np.asarray(mats, dtype=object)[mi[f]],
            np.asarray(shafts, dtype=object)[si[f]],
            n_groups=len(pts),
        )
        w = f[best[best >= 0]]
        q = p[w]
        res["status"][q] = "designed"
        res["feasible"][q] = True
        res["best_material"][q] = np.asarray(mats, dtype=object)[mi[w]]
        res["best_shaft"][q] = np.asarray(shafts, dtype=object)[si[w]]
        res["best_speed_ratio"][q] = ratio[w]
        for name in (
            "d_mean",
            "d_outer",
            "d_inner",
            "h",
            "b",
            "hb_ratio",
            "mass",
            "rim_speed",
            "hoop_stress",
            "j_flywheel",
            "j_at_reference",
        ):
            res[name][q] = out[name][w]
        res["j_required_on_shaft"][q] = out.j_shaft[w]
        res["d_outer_limit"][q] = out.cap[w]
        res["rim_speed_limit"][q] = v_max[w]
        res["cost"][q] = cost[w]
        res["objective"][q] = objective[w]
        res["safety_factor"][q] = allowable[w] / out.hoop_stress[w]
        res["binding"][q] = [",".join(binding_names(b)) for b in out.binding[w]]
    none = pts[counts[pts] == 0]
    if none.size:
        # the combination that comes closest: largest J_max / J' (for the message)
        closeness = out.j_max / out.j_shaft
        lost = np.isin(p, none)
        idx = np.flatnonzero(lost)
        ranked = idx[np.lexsort((order[idx], -closeness[idx], p[idx]))]
        _, first = np.unique(p[ranked], return_index=True)
        for c in ranked[first]:
            k = p[c]
            res["status"][k] = "infeasible"
            res["message"][k] = (
                f"no material and shaft can give the inertia; the closest, "
                f"{mats[mi[c]]} on the {shafts[si[c]]} shaft, can give at most "
                f"{out.j_max[c]:.4g} of the {out.j_shaft[c]:.4g} kg·m² it needs there"
            )


_IPOPT_LOCK = threading.Lock()


def _needs_torque(scene):
    """Whether the scene's designs have arms or a keyed hub, which the flywheel's peak torque loads
    (the same rule as :func:`flyopt.pipeline.design_scene`)."""
    from flyopt.design.wheel_design import needs_torque

    return needs_torque(design_inputs(scene))


def _design_ipopt(ctx, inputs, k, j_required, res, torque=None):
    """One point by optimize.design_flywheel (IPOPT, NLP cached per structure)."""
    from flyopt.design import design_flywheel

    mats = [inputs.material[k]] if inputs.material is not None else inputs.material_names
    shafts = [inputs.shaft[k]] if inputs.shaft is not None else inputs.shaft_names
    materials = []
    for name in mats:  # the scene's material with this point's values: every other field kept
        materials.append(
            _point_material(
                inputs.library[name],
                inputs.density[name][k],
                float(inputs.max_rim_speed[name][k]),
                float(inputs.material_cost[name][k]),
            )
        )
    mounts = [dataclasses.replace(inputs.mounts[name], speed_ratio=float(inputs.ratio[name][k])) for name in shafts]

    def opt(x):
        return None if math.isnan(x) else float(x)

    spec = dataclasses.replace(
        inputs.spec,
        geometry=inputs.geometry[k],
        hb_ratio=(inputs.hb_min[k], inputs.hb_max[k]),
        max_outer_diameter=inputs.envelope[k],
        max_width=inputs.width[k],
        d_mean=opt(inputs.d_mean[k]),
        objective=inputs.objective[k],
    )
    res["method"][k] = "ipopt"
    res["n_combinations"][k] = len(materials) * len(mounts)
    try:
        with _IPOPT_LOCK:  # a CasADi Function is not to be called from two threads at once
            result = design_flywheel(
                float(j_required),
                float(inputs.omega_rim[k]),
                mounts,
                materials,
                spec,
                solver_options=ctx.solver_options,
                method="ipopt",
                torque=torque,
            )
    except SolverFailed as err:
        res["status"][k] = "failed"
        res["solver_status"][k] = str(getattr(err, "status", "") or "error")
        res["message"][k] = str(err)
        return
    res["n_feasible"][k] = sum(c.feasible for c in result.candidates)
    best = result.best
    if best is None:
        res["status"][k] = "infeasible"
        res["message"][k] = result.message
        return
    res["status"][k] = "designed"
    res["feasible"][k] = True
    res["best_material"][k] = best.material
    res["best_shaft"][k] = best.shaft
    res["best_speed_ratio"][k] = best.speed_ratio
    for name in (
        "d_mean",
        "d_outer",
        "d_inner",
        "h",
        "b",
        "hb_ratio",
        "mass",
        "rim_speed",
        "hoop_stress",
        "j_flywheel",
        "j_at_reference",
        "j_required_on_shaft",
        "d_outer_limit",
        "rim_speed_limit",
        "objective",
    ):
        res[name][k] = getattr(best, name)
    res["cost"][k] = math.nan if best.cost is None else best.cost
    res["safety_factor"][k] = math.nan if best.safety_factor is None else best.safety_factor
    res["binding"][k] = ",".join(best.binding)
    res["solver_status"][k] = best.solver_status
    res["iterations"][k] = best.iterations


def _table(inputs, points, axes, res):
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
