"""Results of a design: one Candidate per material x shaft combination, and the DesignResult.

Every number in SI: lengths [m], mass [kg], inertia [kg*m^2], speed [m/s],
stress [Pa]. Wall-clock times are kept out of the JSON unless asked for
(``timings=True``): they are not results, and a result must be reproducible.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

from flyopt.design.spec import DesignSpec

__all__ = ["Candidate", "DesignResult", "DESIGN_FIELDS", "TIMING_FIELDS"]

#: Fields that hold wall-clock times, left out of ``to_dict`` unless ``timings=True``.
TIMING_FIELDS = ("solve_time",)


@dataclass(frozen=True)
class Candidate:
    """One combination of material and shaft, designed or shown infeasible.

    All lengths in [m], mass [kg], inertia [kg*m^2], speed [m/s], stress [Pa].
    For a disc, d_mean = h = D/2 and d_inner = 0 (the annulus with no hole),
    so that every rim formula holds. Dimensions are None when not feasible.

    Attributes
    ----------
    material, shaft : str
    speed_ratio : float
        omega_shaft / omega_reference.
    geometry : str
    feasible : bool
    reason : str
        Why infeasible, in words and numbers; for a design, what binds.
    d_mean, d_outer, d_inner, h, b, hb_ratio, mass : float or None
    rim_speed : float or None
        omega' D_outer / 2 [m/s].
    hoop_stress : float or None
        rho v^2 at the outer rim [Pa].
    safety_factor : float or None
        allowable_stress / hoop_stress, when the allowable stress is known.
    cost : float or None
        mass times cost per kg, when the material has a cost.
    j_flywheel : float or None
        Inertia of the wheel on its own shaft (the chosen model).
    j_at_reference : float or None
        j_flywheel moved to the reference shaft, J' r^2.
    binding : tuple of str
        Active constraints (see :data:`BINDING_NAMES`), relative tolerance
        :data:`ACTIVE_RTOL`.
    objective : float or None
        Value of the ranking objective.
    j_required_on_shaft : float
        J_F / r^2.
    d_outer_limit : float
        min(2 v_max / omega', max_outer_diameter).
    rim_speed_limit : float
        The material's v_max.
    j_max : float
        Largest inertia the combination can give on its shaft (closed form).
    d_outer_needed : float or None
        For a combination stopped by the outer-diameter cap: the cap it needs.
    solver_status : str or None
        IPOPT return status; None when the closed form proved infeasibility
        and no NLP was solved.
    iterations : int or None
    solve_time : float or None
        Wall time of the NLP solve [s].
    n_arms, t_web, d_hub, l_hub, arm_major, arm_minor : int or float or None
        The arm count and the dimensions of the web, hub and arms of a whole
        wheel [m] (None where the geometry has no such part).
    bore : float or None
        The shaft seat [m]; None: no bore.
    parts : tuple of dict
        One per part: ``name``, ``mass`` [kg], ``inertia`` [kg*m^2],
        ``r_inner``, ``r_outer``, ``thickness`` [m].
    stress : dict or None
        At omega_max on the wheel's shaft [Pa]: ``max_principal``,
        ``von_mises``, ``hoop_max``, ``radial_max``, ``where`` (part and
        radius of the governing stress), ``mean_hoop`` and ``parts`` (each
        part's governing stress, radius, allowable, strength and wall).
    allowable_stress : float or None
        The governing part's allowable stress [Pa].
    strength_safety : float or None
        The smallest strength / governing stress of any part [-].
    burst_speed : float or None
        [rad/s] on the wheel's shaft; ``speed_margin`` = burst_speed / omega_max.
    unbalance_permissible : float or None
        ISO 21940-11 G6.3: U_per = e_per m [kg*m].
    key : dict or None
        The DIN 6885-1 key of the hub and its check at the peak torque.
    sensitivities : tuple of dict
        For a design by the wheel NLP: d(mass)/d(limit) of every binding limit.
    notes : tuple of str
        What could not be computed, and why.
    pruned : bool
        Not designed because a bound shows it cannot win (``feasible`` is then
        False and says nothing of whether the combination could give its
        inertia; ``reason`` gives the bound and the design that beats it).
    objective_bound : float or None
        For a pruned combination: a lower bound on its objective that every
        wheel of it meets (:func:`flyopt.design.wheel_design.objective_bound`),
        in the unit of the objective.
    """

    material: str
    shaft: str
    speed_ratio: float
    geometry: str
    feasible: bool
    reason: str
    d_mean: float | None = None
    d_outer: float | None = None
    d_inner: float | None = None
    h: float | None = None
    b: float | None = None
    hb_ratio: float | None = None
    mass: float | None = None
    rim_speed: float | None = None
    hoop_stress: float | None = None
    safety_factor: float | None = None
    cost: float | None = None
    j_flywheel: float | None = None
    j_at_reference: float | None = None
    binding: tuple[str, ...] = ()
    objective: float | None = None
    j_required_on_shaft: float = math.nan
    d_outer_limit: float = math.nan
    rim_speed_limit: float = math.nan
    j_max: float = math.nan
    d_outer_needed: float | None = None
    solver_status: str | None = None
    iterations: int | None = None
    solve_time: float | None = None
    n_arms: int | None = None
    t_web: float | None = None
    d_hub: float | None = None
    l_hub: float | None = None
    arm_major: float | None = None
    arm_minor: float | None = None
    bore: float | None = None
    parts: tuple[dict[str, Any], ...] = ()
    stress: dict[str, Any] | None = None
    allowable_stress: float | None = None
    strength_safety: float | None = None
    burst_speed: float | None = None
    speed_margin: float | None = None
    unbalance_permissible: float | None = None
    key: dict[str, Any] | None = None
    sensitivities: tuple[dict[str, Any], ...] = ()
    notes: tuple[str, ...] = ()
    pruned: bool = False
    objective_bound: float | None = None

    def to_dict(self, timings: bool = False) -> dict[str, Any]:
        """Plain, JSON-ready dictionary (inf becomes None; wall times only with ``timings``)."""
        out = {}
        for f in fields(self):
            if f.name in TIMING_FIELDS and not timings:
                continue
            value = getattr(self, f.name)
            if isinstance(value, tuple):
                value = [dict(v) if isinstance(v, dict) else v for v in value]
            elif isinstance(value, float) and not math.isfinite(value):
                value = None
            out[f.name] = value
        return out


#: Fields of the top-level "design" object taken from the best candidate.
DESIGN_FIELDS = (
    "material",
    "shaft",
    "speed_ratio",
    "geometry",
    "d_mean",
    "d_outer",
    "d_inner",
    "h",
    "b",
    "hb_ratio",
    "mass",
    "rim_speed",
    "hoop_stress",
    "safety_factor",
    "cost",
    "j_flywheel",
    "j_at_reference",
    "binding",
    "objective",
    "n_arms",
    "t_web",
    "d_hub",
    "l_hub",
    "arm_major",
    "arm_minor",
    "bore",
    "parts",
    "stress",
    "allowable_stress",
    "strength_safety",
    "burst_speed",
    "speed_margin",
    "unbalance_permissible",
    "key",
    "sensitivities",
    "notes",
)


@dataclass(frozen=True)
class DesignResult:
    """Outcome of :func:`flyopt.design.designer.design_flywheel`.

    Attributes
    ----------
    status : {"designed", "not_needed", "infeasible"}
    message : str
    j_required : float
        J_F at the reference shaft [kg*m^2].
    omega : float
        Speed of the reference shaft at which the rim speed was checked (ω_max) [rad/s].
    spec : DesignSpec
    best : Candidate or None
    candidates : tuple of Candidate
        Every material x shaft combination, ranked: feasible ones by the
        objective (best first), then the infeasible ones in input order.
    model : dict or None
        Which geometry, variables and constraints the NLP holds.
    """

    status: str
    message: str
    j_required: float
    omega: float
    spec: DesignSpec
    best: Candidate | None = None
    candidates: tuple[Candidate, ...] = ()
    model: dict[str, Any] | None = None

    def to_dict(self, timings: bool = False) -> dict[str, Any]:
        """JSON-ready plain Python (wall-clock times only with ``timings``).

        Returns
        -------
        dict
            ``status``, ``message``, ``j_required``, ``omega``, ``spec``,
            ``model`` and ``design``. ``design`` is None when no flywheel is
            needed; otherwise it holds the best candidate's fields (all None
            when every combination is infeasible) and ``candidates``, one
            entry per combination.
        """
        design = None
        if self.status != "not_needed":
            best = self.best.to_dict() if self.best else {}
            design = {name: best.get(name) for name in DESIGN_FIELDS}
            for name in ("binding", "parts", "sensitivities", "notes"):
                design[name] = design[name] or []
            design["candidates"] = [c.to_dict(timings) for c in self.candidates]
        spec = self.spec.to_dict()
        return {
            "status": self.status,
            "message": self.message,
            "j_required": self.j_required,
            "omega": self.omega,
            "spec": spec,
            "model": self.model,
            "design": design,
        }
