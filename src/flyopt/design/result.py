"""Results of a design: one Candidate per material x shaft combination, and the DesignResult.

A Candidate holds its identity (the combination) and its outcome, and nested
records along their ideas: the wheel's dimensions (:class:`Dimensions`), its
parts (:class:`Parts`), its stresses (:class:`Stresses`), the limits it was
designed against (:class:`Limits`) and how it was found (:class:`Provenance`).
The JSON (``to_dict``) is flat, as before the records: one key per number.

Every number in SI: lengths [m], mass [kg], inertia [kg*m^2], speed [m/s],
stress [Pa]. Wall-clock times are kept out of the JSON unless asked for
(``timings=True``): they are not results, and a result must be reproducible.
"""

from __future__ import annotations

import dataclasses
import math
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar

from flyopt.design.spec import DesignSpec, MountShaft
from flyopt.design.wheel import ARM_MINOR_RATIO, Dims
from flyopt.said import join
from flyopt.views import view

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.design.fem import FemCheck

__all__ = [
    "Candidate",
    "Design",
    "Dimensions",
    "Parts",
    "Stresses",
    "Limits",
    "Provenance",
    "BookRim",
    "DesignResult",
    "CANDIDATE_FIELDS",
    "DESIGN_FIELDS",
    "TIMING_FIELDS",
    "CHECKED_FIELDS",
    "EXPLAINED_FIELDS",
    "DEFERRABLE_FIELDS",
    "NO_DESIGN",
    "infeasible_message",
]

#: What a design says when no combination gives the required flywheel (the message's head, the text's line).
NO_DESIGN = "no material and shaft can give the required inertia"


def infeasible_message(infeasible: Iterable[Candidate]) -> str:
    """The message of a design no combination can give: :data:`NO_DESIGN`, then each combination's reason (their
    quantities kept for the reader's units, :mod:`flyopt.said`)."""
    return NO_DESIGN + ": " + join("; ", (c.reason for c in infeasible))


#: Fields that hold wall-clock times, left out of ``to_dict`` unless ``timings=True``.
TIMING_FIELDS = ("solve_time",)


@dataclass(frozen=True)
class Dimensions:
    """The dimensions of a designed wheel, as reported [m] (``n_arms`` a count is the candidate's).

    The rim's ``d_outer``, ``h``, ``b`` and its ``d_mean`` and ``d_inner`` as
    the design found them (a textbook design's NLP solves for ``d_mean`` and
    ``h``, so ``d_outer - h`` may differ from its ``d_mean`` in the last bit);
    the web, hub and arms of a whole wheel, None where the geometry has no such
    part. For a disc, d_mean = h = D/2 and d_inner = 0 (the annulus with no
    hole), so that every rim formula holds. :meth:`wheel` gives the
    :class:`flyopt.design.wheel.Dims` the wheel's arithmetic takes.
    """

    d_mean: float
    d_outer: float
    d_inner: float
    h: float
    b: float
    t_web: float | None = None
    d_hub: float | None = None
    l_hub: float | None = None
    arm_major: float | None = None

    @property
    def hb_ratio(self) -> float:
        """H/B [-]."""
        return self.h / self.b

    @property
    def arm_minor(self) -> float | None:
        """The arms' minor axis [m] (:data:`flyopt.design.wheel.ARM_MINOR_RATIO` of the major), None: no arms."""
        return None if self.arm_major is None else self.arm_major * ARM_MINOR_RATIO

    def wheel(self, n_arms: int | None = None, bore: float | None = None) -> Dims:
        """The :class:`flyopt.design.wheel.Dims` of these dimensions (0 where the wheel has no such part)."""
        return Dims(
            d_outer=self.d_outer,
            h=self.h,
            b=self.b,
            bore=bore or 0.0,
            t_web=self.t_web or 0.0,
            d_hub=self.d_hub or 0.0,
            l_hub=self.l_hub or 0.0,
            arm_major=self.arm_major or 0.0,
            n_arms=n_arms or 0,
        )


@dataclass(frozen=True)
class Parts:
    """The parts of a designed wheel and the key of its hub.

    Attributes
    ----------
    items : tuple of dict
        One per part: ``name``, ``mass`` [kg], ``inertia`` [kg*m^2],
        ``r_inner``, ``r_outer``, ``thickness`` [m].
    key : dict or None
        The DIN 6885-1 key of the hub and its check at the peak torque.
    thin_wall : dict or None
        A wheel not designed to the castability rules (a bare rim, a textbook disc) whose thinnest section is
        thinner than the wall asked of it (:func:`flyopt.design.castability.too_thin`); None otherwise.
    """

    items: tuple[dict[str, Any], ...] = ()
    key: dict[str, Any] | None = None
    thin_wall: dict[str, Any] | None = None


@dataclass(frozen=True)
class Stresses:
    """The speed and stresses of a designed wheel at omega_max on its shaft.

    Attributes
    ----------
    rim_speed : float
        omega' D_outer / 2 [m/s].
    hoop_stress : float
        rho v^2 at the outer rim [Pa].
    safety_factor : float or None
        allowable_stress / hoop_stress, when the material's allowable stress is known.
    stress : dict or None
        [Pa]: ``max_principal``, ``von_mises``, ``hoop_max``, ``radial_max``,
        ``where`` (part and radius of the governing stress), ``mean_hoop`` and
        ``parts`` (each part's governing stress, radius, allowable, strength and wall).
    allowable_stress : float or None
        The governing part's allowable stress [Pa].
    strength_safety : float or None
        The smallest strength / governing stress of any part [-].
    burst_speed : float or None
        [rad/s] on the wheel's shaft; ``speed_margin`` = burst_speed / omega_max.
    unbalance_permissible : float or None
        ISO 21940-11 G6.3: U_per = e_per m [kg*m].
    """

    rim_speed: float
    hoop_stress: float
    safety_factor: float | None = None
    stress: dict[str, Any] | None = None
    allowable_stress: float | None = None
    strength_safety: float | None = None
    burst_speed: float | None = None
    speed_margin: float | None = None
    unbalance_permissible: float | None = None


@dataclass(frozen=True)
class Limits:
    """What a combination was designed against, and what binds.

    Attributes
    ----------
    j_required_on_shaft : float
        J_F / r^2 [kg*m^2].
    d_outer_limit : float
        min(2 v_max / omega', max_outer_diameter) [m].
    rim_speed_limit : float
        The material's v_max [m/s].
    j_max : float
        Largest inertia the combination can give on its shaft (closed form); NaN: not computed.
    d_outer_needed : float or None
        For a combination stopped by the outer-diameter cap: the cap it needs [m].
    binding : tuple of str
        Active constraints (see :data:`flyopt.design.check.BINDING_NAMES`).
    sensitivities : tuple of dict
        For a design by the wheel NLP: d(mass)/d(limit) of every binding limit.
    castability : dict or None
        The castability rules the wheel was designed to and what it has
        (:func:`flyopt.design.castability.record`); None where none apply.
    """

    j_required_on_shaft: float = math.nan
    d_outer_limit: float = math.nan
    rim_speed_limit: float = math.nan
    j_max: float = math.nan
    d_outer_needed: float | None = None
    binding: tuple[str, ...] = ()
    sensitivities: tuple[dict[str, Any], ...] = ()
    castability: dict[str, Any] | None = None


@dataclass(frozen=True)
class Provenance:
    """How a candidate was found.

    Attributes
    ----------
    solver_status : str or None
        IPOPT return status ("closed_form" for a closed-form design); None when
        no NLP was solved.
    iterations : int or None
    solve_time : float or None
        Wall time of the solve [s].
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

    solver_status: str | None = None
    iterations: int | None = None
    solve_time: float | None = None
    notes: tuple[str, ...] = ()
    pruned: bool = False
    objective_bound: float | None = None


#: The structural fields of a design the check gives (:func:`flyopt.design.wheel_design.structure_fields`), which
#: :meth:`Design.checked_when_read` leaves to be computed when first read (with the design's description).
CHECKED_FIELDS = ("parts", "stresses", "provenance")

#: What an infeasible combination's explanation gives (its reason in numbers, and its limits with the cap it
#: needs): what :meth:`Candidate.explained_when_read` leaves to be computed when first read.
EXPLAINED_FIELDS = ("reason", "limits")

#: Every field a candidate can leave to be made when first read (:meth:`Candidate.made_when_read`).
DEFERRABLE_FIELDS = (*EXPLAINED_FIELDS, *CHECKED_FIELDS)
_DEFERRABLE = frozenset(DEFERRABLE_FIELDS)

#: What makes a candidate's deferred fields: () -> {name: value} for each of them.
Deferred = Callable[[], Mapping[str, Any]]

#: A structural check to be made: () -> (parts, stresses, notes), the notes joining the provenance's.
StructureCheck = Callable[[], "tuple[Parts, Stresses, tuple[str, ...]]"]

#: A design's description to be made: () -> (reason, limits, provenance); what binds, in words and in its limits.
Description = Callable[[], "tuple[str, Limits, Provenance]"]

_C = TypeVar("_C", bound="Candidate")


@dataclass(frozen=True, kw_only=True)
class Candidate:
    """One combination of material and shaft (and arm count), designed or shown infeasible.

    All lengths in [m], mass [kg], inertia [kg*m^2]. A :class:`Design` is a
    feasible one, with its dimensions, parts and stresses; an infeasible or
    pruned one has none of them.

    Attributes
    ----------
    material, shaft : str
    speed_ratio : float
        omega_shaft / omega_reference.
    geometry : str
    feasible : bool
    reason : str
        Why infeasible, in words and numbers; for a design, what binds.
    n_arms : int or None
        The arm count of a wheel with arms (part of the combination).
    bore : float or None
        The shaft seat [m] (the shaft's); None: no bore.
    mass : float or None
    cost : float or None
        mass times cost per kg, when the material has a cost.
    j_flywheel : float or None
        Inertia of the wheel on its own shaft (the chosen model).
    j_at_reference : float or None
        j_flywheel moved to the reference shaft, J' r^2.
    objective : float or None
        Value of the ranking objective.
    dims, parts, stresses : Dimensions, Parts, Stresses or None
        None unless designed.
    limits : Limits
    provenance : Provenance
    """

    material: str
    shaft: str
    speed_ratio: float
    geometry: str
    feasible: bool
    reason: str
    n_arms: int | None = None
    bore: float | None = None
    mass: float | None = None
    cost: float | None = None
    j_flywheel: float | None = None
    j_at_reference: float | None = None
    objective: float | None = None
    dims: Dimensions | None = None
    parts: Parts | None = None
    stresses: Stresses | None = None
    limits: Limits = field(default_factory=Limits)
    provenance: Provenance = field(default_factory=Provenance)

    @classmethod
    def made_when_read(cls: type[_C], make: Deferred, deferred: tuple[str, ...], **fields: Any) -> _C:
        """A candidate whose ``deferred`` fields are made by ``make`` the first time any of them is read.

        The ranking needs a candidate's identity, objective and dimensions; what a reader alone needs (a
        design's structural check, :meth:`Design.checked_when_read`; an infeasible combination's reason in
        numbers, the cap it needs) is made when first read, once, by the same call as when made at once
        (docs/flywheel-design.md, section 13). Equality, ``repr``, ``dataclasses.replace``, a copy and a pickle
        (a sweep's worker sends its results pickled) read every field, so they see the candidate made whole:
        nothing can tell it from one built with its fields given. ``make``: () -> {name: value} for each of
        ``deferred`` (of :data:`DEFERRABLE_FIELDS`); ``fields``: every other field.
        """
        if type(deferred) is not tuple:  # a list, say: the plans are keyed by the tuple
            deferred = tuple(deferred)
        plan = _plan_of(cls, deferred)
        given = fields.keys()
        if not (given <= plan.names and plan.required <= given):
            _refuse(cls, plan, given, deferred)
        # every field but the deferred ones in declared order, the given values over the defaults: what __init__
        # would hold, without its cost (a ranking builds one per design; a frozen dataclass's __init__ sets each
        # field through object.__setattr__)
        values = {**plan.defaults, **fields}
        for name, factory in plan.factories:
            if values[name] is _FACTORY:
                values[name] = factory()
        values["_make"] = make
        candidate = object.__new__(cls)
        object.__setattr__(candidate, "__dict__", values)
        return candidate

    def _make_deferred(self) -> None:
        """Make the deferred fields and hold every field in the declared order (as ``__init__`` would), once:
        under :data:`_MAKING`, so that two threads reading one candidate at once (the app's workers) make it
        once and the second finds it made."""
        with _MAKING:
            values = self.__dict__
            make = values.get("_make")
            if make is None:  # made meanwhile (another thread read it first)
                return
            try:
                made = make()
            except AttributeError as err:  # not to be taken for a missing attribute by the attribute's reader
                raise RuntimeError(f"the deferred fields of {self.material} on {self.shaft} failed: {err}") from err
            order = _plan_of(type(self), ()).defaults  # every field, in declared order
            missing = [name for name in order if name not in values and name not in made]
            if missing:
                raise TypeError(f"the deferred fields of {self.material} on {self.shaft} were not all made: {missing}")
            object.__setattr__(self, "__dict__", {name: made[name] if name in made else values[name] for name in order})

    def __getstate__(self) -> dict[str, Any]:
        """The fields, made (a pickle or a copy carries what was deferred, never the means to make it)."""
        if "_make" in self.__dict__:
            self._make_deferred()
        return self.__dict__

    @classmethod
    def infeasible(cls, material: str, shaft: MountShaft, geometry: str, reason: str, **fields: Any) -> Candidate:
        """A combination that gives no design (shown infeasible, or pruned): its identity from the material's key,
        the mounting shaft (its name and speed ratio) and the geometry, ``reason`` saying why in numbers, and any
        further field (``n_arms``, ``bore``, ``limits``, ``provenance``)."""
        return cls(**_no_design(material, shaft, geometry), reason=reason, **fields)

    @classmethod
    def explained_when_read(
        cls, material: str, shaft: MountShaft, geometry: str, explain: Deferred, **fields: Any
    ) -> Candidate:
        """An infeasible combination whose reason in numbers and limits (:data:`EXPLAINED_FIELDS`) ``explain``
        makes when first read (:meth:`made_when_read`): the ranking needs only that it gives no design."""
        return cls.made_when_read(explain, EXPLAINED_FIELDS, **_no_design(material, shaft, geometry), **fields)

    def to_dict(self, timings: bool = False) -> dict[str, Any]:
        """Plain, JSON-ready dictionary, flat (inf becomes None; wall times only with ``timings``).

        The keys are :data:`CANDIDATE_FIELDS` in that order (``solve_time`` only with ``timings``).
        """
        d, p, s, lim, prov = self.dims, self.parts, self.stresses, self.limits, self.provenance
        values: dict[str, Any] = {
            "material": self.material,
            "shaft": self.shaft,
            "speed_ratio": self.speed_ratio,
            "geometry": self.geometry,
            "feasible": self.feasible,
            "reason": self.reason,
            "d_mean": d and d.d_mean,
            "d_outer": d and d.d_outer,
            "d_inner": d and d.d_inner,
            "h": d and d.h,
            "b": d and d.b,
            "hb_ratio": d and d.hb_ratio,
            "mass": self.mass,
            "rim_speed": s and s.rim_speed,
            "hoop_stress": s and s.hoop_stress,
            "safety_factor": s and s.safety_factor,
            "cost": self.cost,
            "j_flywheel": self.j_flywheel,
            "j_at_reference": self.j_at_reference,
            "binding": list(lim.binding),
            "objective": self.objective,
            "j_required_on_shaft": lim.j_required_on_shaft,
            "d_outer_limit": lim.d_outer_limit,
            "rim_speed_limit": lim.rim_speed_limit,
            "j_max": lim.j_max,
            "d_outer_needed": lim.d_outer_needed,
            "solver_status": prov.solver_status,
            "iterations": prov.iterations,
            "solve_time": prov.solve_time,
            "n_arms": self.n_arms,
            "t_web": d and d.t_web,
            "d_hub": d and d.d_hub,
            "l_hub": d and d.l_hub,
            "arm_major": d and d.arm_major,
            "arm_minor": d and d.arm_minor,
            "bore": self.bore,
            "parts": [dict(v) for v in p.items] if p else [],
            "stress": s and s.stress,
            "allowable_stress": s and s.allowable_stress,
            "strength_safety": s and s.strength_safety,
            "burst_speed": s and s.burst_speed,
            "speed_margin": s and s.speed_margin,
            "unbalance_permissible": s and s.unbalance_permissible,
            "key": p and p.key,
            "thin_wall": p and p.thin_wall,
            "sensitivities": [dict(v) for v in lim.sensitivities],
            "castability": lim.castability,
            "notes": list(prov.notes),
            "pruned": prov.pruned,
            "objective_bound": prov.objective_bound,
        }
        out = {}
        for name, value in values.items():
            if name in TIMING_FIELDS and not timings:
                continue
            out[name] = None if isinstance(value, float) and not math.isfinite(value) else value
        return out


@dataclass(frozen=True, kw_only=True)
class Design(Candidate):
    """A feasible Candidate: one with its dimensions, parts, stresses, mass, inertia and objective.

    Each of them is required (``field()``: without it the Candidate's default None would be inherited).
    A design made by :meth:`checked_when_read` computes its structural check and its description the first time
    either is read.
    """

    feasible: bool = True
    mass: float = field()
    j_flywheel: float = field()
    j_at_reference: float = field()
    objective: float = field()
    dims: Dimensions = field()
    parts: Parts = field()
    stresses: Stresses = field()

    @classmethod
    def checked_when_read(cls, check: StructureCheck, describe: Description, **fields: Any) -> Design:
        """A design whose report is made the first time any of it is read (:meth:`Candidate.made_when_read`): its
        structural check by ``check`` (its ``parts``, ``stresses`` and the check's notes in its ``provenance``),
        its description by ``describe`` (its ``reason``, what binds; its ``limits``; its ``provenance`` before
        the check's notes): every field of :data:`DEFERRABLE_FIELDS`.

        The ranking needs a design's objective, cost, mass and dimensions, not what binds nor its stresses; a
        design that is reported (the text, the JSON, the report, a DataFrame) reads them, so each reported
        design is checked and described, once, by the same calls as when made at once. ``fields``: every other
        field.
        """

        def checked() -> dict[str, Any]:
            parts, stresses, notes = check()
            reason, limits, provenance = describe()
            noted = dataclasses.replace(provenance, notes=provenance.notes + notes) if notes else provenance
            return {"reason": reason, "limits": limits, "parts": parts, "stresses": stresses, "provenance": noted}

        return cls.made_when_read(checked, DEFERRABLE_FIELDS, **fields)


class _MadeWhenRead:
    """A field of a :class:`Candidate` read before it is made (see :meth:`Candidate.made_when_read`).

    A non-data descriptor on the class: a candidate that holds the field (every one once made, and every
    one built with its fields given) reads it from its own ``__dict__`` without coming here.
    """

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, candidate: Candidate | None, owner: type | None = None) -> Any:
        if candidate is None:
            return self
        values = candidate.__dict__  # one dict: another thread that makes the fields swaps in a new one
        if self.name in values:  # made by another thread since this read found the field missing
            return values[self.name]
        if "_make" not in values:
            raise AttributeError(f"{type(candidate).__name__!r} object has no attribute {self.name!r}")
        candidate._make_deferred()
        return candidate.__dict__[self.name]


def _no_design(material: str, shaft: MountShaft, geometry: str) -> dict[str, Any]:
    """The identity of a combination that gives no design: the material's key, the mounting shaft's name and speed
    ratio, the geometry, and that it is not feasible."""
    return {
        "material": material,
        "shaft": shaft.name,
        "speed_ratio": shaft.speed_ratio,
        "geometry": geometry,
        "feasible": False,
    }


#: Held while a candidate's deferred fields are made (:meth:`Candidate._make_deferred`): re-entrant, as making
#: one may read another's.
_MAKING = threading.RLock()


#: A field whose default is made by its ``default_factory`` (in :attr:`_Plan.defaults`).
_FACTORY = object()


@dataclass(frozen=True)
class _Plan:
    """How :meth:`Candidate.made_when_read` builds a Candidate class with some fields deferred, as ``__init__``
    would: the other fields in declared order with their defaults (:data:`_FACTORY` where a factory makes it),
    the fields that may be given, those that must be, and the factories."""

    defaults: dict[str, Any]
    names: frozenset[str]
    required: frozenset[str]
    factories: tuple[tuple[str, Callable[[], Any]], ...]


_PLANS: dict[tuple[type, tuple[str, ...]], _Plan] = {}


def _plan_of(cls: type[Candidate], deferred: tuple[str, ...]) -> _Plan:
    """The :class:`_Plan` of ``cls`` with ``deferred`` fields (with none: every field in declared order), made once
    for each."""
    return _PLANS.get((cls, deferred)) or _plan(cls, deferred)


def _plan(cls: type[Candidate], deferred: tuple[str, ...]) -> _Plan:
    """Make the :class:`_Plan` of ``cls`` with ``deferred`` fields (:func:`_plan_of` keeps it)."""
    if not _DEFERRABLE.issuperset(deferred):
        unknown = sorted(set(deferred) - _DEFERRABLE)
        raise TypeError(f"fields {unknown} cannot be made when read (only {list(DEFERRABLE_FIELDS)})")
    if hasattr(cls, "__post_init__"):  # made_when_read builds without __init__, which would call it
        raise TypeError(f"{cls.__name__} has a __post_init__, which Candidate.made_when_read would not call")
    defaults: dict[str, Any] = {}
    required, factories = [], []
    for f in dataclasses.fields(cls):
        if f.name in deferred:
            continue
        if f.default is not dataclasses.MISSING:
            defaults[f.name] = f.default
        elif f.default_factory is not dataclasses.MISSING:
            defaults[f.name] = _FACTORY
            factories.append((f.name, f.default_factory))
        else:
            defaults[f.name] = None  # always given: refused otherwise
            required.append(f.name)
    plan = _PLANS[cls, deferred] = _Plan(defaults, frozenset(defaults), frozenset(required), tuple(factories))
    return plan


def _refuse(cls: type[Candidate], plan: _Plan, given: Iterable[str], deferred: Iterable[str]) -> None:
    """Raise the TypeError for fields ``given`` beside ``deferred`` ones (made when read), as ``cls(...)`` would: a
    field unknown, given and deferred, or missing."""
    given, deferred = set(given), set(deferred)
    problems = [
        f"{words} {names}"
        for words, names in (
            ("unknown fields", sorted(given - plan.names - deferred)),
            ("fields both given and deferred", sorted(given & deferred)),
            ("missing fields", sorted(plan.required - given)),
        )
        if names
    ]
    raise TypeError(f"{cls.__name__}: " + "; ".join(problems))


# set after both dataclasses are made, so that neither takes them for defaults
for _name in DEFERRABLE_FIELDS:
    setattr(Candidate, _name, _MadeWhenRead(_name))
del _name


#: The keys of :meth:`Candidate.to_dict`, in order (the JSON of every candidate; flat since before the records):
#: read off the dictionary itself, so that the list and the JSON are one.
CANDIDATE_FIELDS = tuple(
    Candidate(material="", shaft="", speed_ratio=1.0, geometry="", feasible=False, reason="").to_dict(timings=True)
)


#: The candidate's fields that say how it was found, not what it is: left out of the top-level "design".
SEARCH_FIELDS = frozenset(
    {
        "feasible",
        "reason",
        "j_required_on_shaft",
        "d_outer_limit",
        "rim_speed_limit",
        "j_max",
        "d_outer_needed",
        "solver_status",
        "iterations",
        "solve_time",
        "pruned",
        "objective_bound",
    }
)

#: Fields of the top-level "design" object taken from the best candidate (the candidate's, in its order).
DESIGN_FIELDS = tuple(name for name in CANDIDATE_FIELDS if name not in SEARCH_FIELDS)


@dataclass(frozen=True)
class BookRim:
    """A rim sized by the courses' convention (criterion mean_rim_speed), and what it really sees.

    The book puts the rim's safe speed at the MEAN diameter and the MEAN
    speed; the rim's largest stress comes at the top speed ω_max, at its
    outer diameter by the thin-ring estimate and at its bore by Lamé
    (docs/flywheel-design.md, section 13).

    Attributes
    ----------
    rim_share : float
        Share of J_F the rim gives (the arms and hub, not designed, the rest) [-].
    mean_rim_speed : float
        ω_m' D_m / 2, the speed the book checks [m/s].
    book_stress : float
        ρ v_m², the stress the book checks [Pa].
    outer_rim_speed, outer_hoop_stress : float
        ω_max' D_o / 2 [m/s] and the thin ring's ρ v_o² [Pa].
    largest_stress, largest_at : float or None
        The rim's governing stress at ω_max (Lamé; the stress check's) [Pa] and its radius [m].
    allowable : float or None
        The allowable stress [Pa].
    """

    rim_share: float
    mean_rim_speed: float
    book_stress: float
    outer_rim_speed: float
    outer_hoop_stress: float
    largest_stress: float | None
    largest_at: float | None
    allowable: float | None

    def excess(self, stress: float | None) -> float | None:
        """How far ``stress`` exceeds the allowable, as a fraction (0.2: 20 % over; negative: within)."""
        if stress is None or not self.allowable:
            return None
        return stress / self.allowable - 1.0


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
    best : Design or None
    candidates : tuple of Candidate
        Every material x shaft combination, ranked: feasible ones by the
        objective (best first), then the infeasible ones in input order.
    model : dict or None
        Which geometry, variables and constraints the NLP holds.
    omega_mean : float or None
        Mean speed of the reference shaft [rad/s], where the design was
        given it (the courses' rim convention sizes the rim there).
    fem : FemCheck or None
        The best design's axisymmetric finite-element check
        (:func:`flyopt.design.fem.fem_check`), where the spec asks for it
        (``fem_check``); None otherwise.
    continuous : Design or None
        With a ``spec.round_to``: the continuous optimum the rounded ``best`` comes from.
    rounding : str or None
        With a ``spec.round_to``: what rounding did, in words.
    material_names : mapping
        Each material's key to its name for people (not in the JSON, which names materials by key).
    """

    status: str
    message: str
    j_required: float
    omega: float
    spec: DesignSpec
    best: Design | None = None
    candidates: tuple[Candidate, ...] = ()
    model: dict[str, Any] | None = None
    omega_mean: float | None = None
    fem: FemCheck | None = None
    continuous: Design | None = None
    rounding: str | None = None
    material_names: Mapping[str, str] = field(default_factory=dict)

    def material_name(self, key: str) -> str:
        """A material's name for people (:attr:`flyopt.design.materials.Material.display_name`) from its key."""
        return self.material_names.get(key) or key.replace("_", " ")

    def to_frame(self, units: str | None = None) -> pd.DataFrame:
        """The ranking as a DataFrame: every combination, best first, the JSON's candidate fields as columns.

        In SI (``units=None``) or a unit system of :mod:`flyopt.report.display`; ``attrs["flyopt"]["units"]``
        gives each column's unit. Built on the report's floor (:func:`flyopt.report.notebook.ranking_frame`),
        through :mod:`flyopt.views`.
        """
        return view("design", "frame", self, units)

    def _repr_html_(self) -> str:
        """The ranking as a table in a notebook, in the engineer's units (:func:`flyopt.report.notebook.ranking_html`)."""
        return str(view("design", "html", self))

    def book_rim(self) -> BookRim | None:
        """What the courses' rim (criterion mean_rim_speed) really sees, beside what the book checks; None for
        any other criterion or without a design."""
        best = self.best
        if not self.spec.by_mean_rim_speed or best is None or self.omega_mean is None:
            return None
        v_mean = self.omega_mean * best.speed_ratio * best.dims.d_mean / 2.0
        v_outer, hoop_outer = best.stresses.rim_speed, best.stresses.hoop_stress
        governing = best.stresses.stress or {}
        return BookRim(
            rim_share=self.spec.rim_share,
            mean_rim_speed=v_mean,
            book_stress=hoop_outer * (v_mean / v_outer) ** 2,  # ρ v_m²: the same ρ as ρ v_o²
            outer_rim_speed=v_outer,
            outer_hoop_stress=hoop_outer,
            largest_stress=max((part["stress"] for part in governing.get("parts", ())), default=None),
            largest_at=(governing.get("where") or {}).get("radius"),
            allowable=best.stresses.allowable_stress,
        )

    def to_dict(self, timings: bool = False) -> dict[str, Any]:
        """JSON-ready plain Python (wall-clock times only with ``timings``).

        Returns
        -------
        dict
            ``status``, ``message``, ``j_required``, ``omega``, ``spec``,
            ``model`` and ``design``. ``design`` is None when no flywheel is
            needed; otherwise it holds the best candidate's fields (all None
            when every combination is infeasible), ``fem`` (the FE check, or
            None) and ``candidates``, one entry per combination.
        """
        design = None
        if self.status != "not_needed":
            best = self.best.to_dict() if self.best else {}
            design = {name: best.get(name) for name in DESIGN_FIELDS}
            for name in ("binding", "parts", "sensitivities", "notes"):
                design[name] = design[name] or []
            design["fem"] = self.fem.to_dict() if self.fem is not None else None
            design["candidates"] = [c.to_dict(timings) for c in self.candidates]
            if self.spec.round_to:  # the rounded winner above, the continuous optimum here
                design["rounding"] = self.rounding
                design["continuous"] = self.continuous.to_dict(timings) if self.continuous is not None else None
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
