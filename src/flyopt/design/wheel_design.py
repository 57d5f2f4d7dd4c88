"""One combination designed as a whole wheel, and the structural fields of every design.

:func:`design_combination` sizes a material x shaft (x arm count) combination
whose structure the textbook closed forms do not cover: a web or arms wheel,
a disc with a bore, or any wheel under the stress criterion. It is the one
place that turns a combination into the numbers of the wheel NLP
(:mod:`flyopt.design.wheel_nlp`): the allowable stress of every part at its
wall thickness, the hub's proportions and the key's shortest hub, the
thinnest wall; it solves, checks the result independently
(:func:`flyopt.design.strength.check_wheel`: exact stress maxima, every part's
allowable at the wall it really has) and solves again where a peak between
the NLP's sample radii or a thicker wall's lower strength asks for it.

:func:`structure_fields` gives every design, the textbook ones included, its
parts, stresses, burst speed, permissible unbalance and key.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, section 13.
"""

from __future__ import annotations

import contextlib
import contextvars
import copy
import dataclasses
import math
from collections.abc import Callable, Iterator, Mapping
from typing import TYPE_CHECKING, Any, NamedTuple

from flyopt.design import balance, castability, check, geometry, hub, key, strength, wheel
from flyopt.design.combination import wheel_words
from flyopt.design.materials import ThicknessOutOfRange
from flyopt.design.result import Parts, Stresses
from flyopt.errors import BrokenInvariant, SolverFailed
from flyopt.names import Criterion, Geometry, Method, Objective
from flyopt.said import Said, join, said, said_by

if TYPE_CHECKING:  # annotations only: CasADi is imported where IPOPT is used
    from flyopt.design.combination import Combination
    from flyopt.design.inputs import DesignInputs
    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec, MountShaft
    from flyopt.design.strength import StrengthCheck
    from flyopt.design.wheel import Dims
    from flyopt.design.wheel_nlp import WheelProblem, WheelSolution, WheelStructure

__all__ = [
    "needs_torque",
    "bore_of",
    "min_wall_of",
    "castability_of",
    "designed_castable",
    "thin_walled",
    "thin_wall_note",
    "min_wall_at",
    "objective_bound",
    "stress_cap",
    "screen",
    "design_combination",
    "Structure",
    "structure_fields",
    "NoWheel",
    "sensitivities",
    "neighbours",
]

#: Re-solves allowed for the exact stress check and the strength of the walls to settle.
_MAX_ROUNDS = 8


class NoWheel(Exception):
    """The combination cannot be built: ``reason`` says why, in numbers."""

    def __init__(self, reason: str, j_max: float = math.nan) -> None:
        super().__init__(reason)
        self.reason = reason
        self.j_max = j_max


def bore_of(spec: DesignSpec, shaft: MountShaft) -> float:
    """The bore of a wheel on a shaft [m]: the design's, else the shaft's seat, else 0 (none)."""
    if spec.bore is not None:
        return spec.bore
    return shaft.diameter or 0.0


def needs_torque(inputs: DesignInputs) -> bool:
    """Whether a design problem (:class:`flyopt.design.inputs.DesignInputs`) has arms or a keyed hub,
    which the flywheel's peak torque loads (the textbook bare rim has neither)."""
    return inputs.spec.geometry == Geometry.RIM_ARMS or any(bore_of(inputs.spec, s) for s in inputs.shafts)


#: The thinnest section of a web or arms wheel when neither the design nor the material gives
#: ``min_wall`` [m]: not a process limit but a floor against a degenerate optimum (a strong
#: material's lightest web heads for a foil, where the stress rows lose their conditioning and
#: IPOPT fails). Bare rims and discs keep no floor.
DEFAULT_MIN_WALL = 1e-3


def min_wall_of(spec: DesignSpec, material: Material) -> float:
    """The thinnest wall a wheel may have [m]: the spec's, else the material's, else the default of a whole wheel."""
    if spec.min_wall is not None:
        return spec.min_wall
    own = getattr(material, "min_wall", None)
    if own:
        return own
    return DEFAULT_MIN_WALL if spec.geometry in geometry.WHEELS else 0.0


#: The geometries the castability rules bound: the wheels the NLP designs whole (a disc: its width alone).
CAST_GEOMETRIES = (Geometry.RIM_WEB, Geometry.RIM_ARMS, Geometry.DISC)


def designed_castable(spec: DesignSpec, bore: float = 0.0) -> bool:
    """Whether a wheel is designed to its process's castability rules: a wheel designed whole (rim_web,
    rim_arms, a disc not designed by the textbook); bare rims and textbook discs are not (the books' problems
    do not change), and are only checked against them (:func:`thin_walled`)."""
    return spec.geometry in CAST_GEOMETRIES and not spec.textbook(bore)


def castability_of(spec: DesignSpec, material: Material, bore: float = 0.0) -> castability.Rules | None:
    """The castability rules a wheel of a material is designed to, or None: the process of the scene or of the
    material (flyopt/data/castability.toml) with the scene's numbers over it, for a wheel designed whole
    (:func:`designed_castable`); bare rims and textbook discs have none."""
    if not designed_castable(spec, bore):
        return None
    return castability.rules_for(material.name, spec.castability)


def thin_walled(spec: DesignSpec, material: Material, geometry_name: str, dims: Dims) -> dict[str, Any] | None:
    """A wheel not designed to castability rules (:func:`designed_castable`: a bare rim, a textbook disc) whose
    thinnest section is thinner than the wall asked of it: its material's process's minimum at its size (the
    scene's process and numbers over it) or the design's (or the material's) ``min_wall``, whichever is larger
    (:func:`flyopt.design.castability.too_thin`); None otherwise, and for a wheel designed to the rules.

    Made once, by the structural check (:func:`structure_fields`), into the design's ``parts.thin_wall``, which
    its note, the answer's line and the report's summary read. ``dims``: the wheel's, its bore among them.
    """
    if designed_castable(spec, float(dims.bore)):
        return None
    rules = castability.rules_for(material.name, spec.castability)
    return castability.too_thin(rules, min_wall_of(spec, material), geometry_name, dims)


def min_wall_at(spec: DesignSpec, material: Material, d_outer: float, bore: float = 0.0) -> float:
    """The thinnest wall a wheel of outer diameter ``d_outer`` [m] may have [m]: the larger of
    :func:`min_wall_of` and the process's minimum at that size (the NLP writes the two as a bound and a row)."""
    return castability.wall_asked(castability_of(spec, material, bore), min_wall_of(spec, material), d_outer)


def hub_bounds(
    material: Material, bore: float, torque: float | None
) -> tuple[tuple[float, float], tuple[float, float], str]:
    """(d_hub range [m], l_hub range [m], the hub's kind) of a hub on a seat of diameter ``bore`` [m] carrying the
    peak ``torque`` [N*m] (the key's shortest hub: its bearing pressure on the hub where the material gives one,
    and the key's shear against the key steel's S_sy always, :func:`flyopt.design.key.hub_length_for_key`)."""
    kind = material.hub_kind
    p = hub.hub_proportions(bore, kind)
    l_low = p.l_hub_min
    pressure = getattr(material, "bearing_pressure", None)
    if torque:
        try:
            l_low = max(l_low, key.hub_length_for_key(torque, bore, pressure))
        except ValueError:
            pass  # no standard key carries it: check_key says so in the report
    return (p.d_hub_min, p.d_hub_max), (l_low, max(p.l_hub_max, l_low)), kind


def _strongest_allowable(material, spec):
    """The largest allowable stress any section of the material has [Pa] (its strength table's
    strongest row), or None when the material gives none (no safety factor to divide by)."""
    rows = getattr(material, "strength_by_thickness", ())
    try:
        if rows:
            return max(
                material.allowable(thickness=row.max_thickness, safety_factor=spec.safety_factor) for row in rows
            )
        return material.allowable(safety_factor=spec.safety_factor)
    except ValueError:
        return None


def stress_cap(combo: Combination, spec: DesignSpec, bore: float) -> float:
    """The largest outer diameter the stress allows a bare rim or disc [m] (inf where no closed form says).

    A free annulus a < b at speed omega has its largest stress at the bore,
    where sigma_r = 0 and sigma_t(a) = (3+nu)/4 rho omega^2 [b^2 + (1-nu)/(3+nu) a^2]
    >= (3+nu)/4 rho omega^2 b^2; a solid disc at its centre, sigma_r = sigma_t =
    (3+nu)/8 rho omega^2 b^2 (Timoshenko & Goodier, art. 32; docs/flywheel-design.md,
    section 13). Both measures (von Mises, largest principal) equal sigma_t there,
    so no rim (an annulus for the stress solver, :func:`flyopt.design.wheel.steps`)
    or disc whose stress stays within the material's strongest allowable can be wider
    than 2 b with (3+nu)/4 (or /8, solid) rho omega^2 b^2 = sigma_allow.
    """
    if spec.criterion != Criterion.STRESS or spec.geometry not in (Geometry.RIM, Geometry.DISC):
        return math.inf
    nu = getattr(combo.material, "poisson_ratio", None)
    sigma = _strongest_allowable(combo.material, spec)
    if nu is None or not sigma:
        return math.inf
    factor = 8.0 if spec.geometry == Geometry.DISC and not bore else 4.0
    return 2.0 * math.sqrt(factor * sigma / ((3.0 + nu) * combo.material.density * combo.omega**2))


def _upper_bound(combo, spec, bore=0.0):
    """An inertia no wheel of the combination can exceed [kg*m^2] (inf when nothing bounds it),
    and the outer diameter and width it is taken at [m]: a solid cylinder of that diameter (the smaller of
    the cap and :func:`stress_cap`) and of the width limit (for a rim, also H/B: B <= D/(2 hb_min))."""
    cap = min(combo.cap, stress_cap(combo, spec, bore))
    width = spec.max_width
    if spec.geometry in (Geometry.RIM, Geometry.THIN_RIM):
        width = min(width, cap / (2.0 * spec.hb_ratio[0]))
    if not (math.isfinite(cap) and math.isfinite(width)):
        return math.inf, cap, width
    return math.pi * combo.material.density * width * cap**4 / 32.0, cap, width


def objective_bound(combo: Combination, spec: DesignSpec) -> tuple[float, str]:
    """A lower bound on the objective of every wheel of a combination, and how it is found.

    No mass sits farther out than half the largest outer diameter the
    combination may have, D_cap (the rim speed cap or the envelope), so
    J' = ∫ r² dm <= m D_cap² / 4 and every wheel of the combination, whatever
    its parts, weighs m >= 4 J' / D_cap² (all of it in a thin ring at the
    cap: docs/flywheel-design.md, section 9); its cost is at least that mass
    times the cost per kg. No body of revolution within an axial width B_max
    has more inertia than the solid cylinder of that width, J' <= π ρ B_max
    D⁴ / 32, so its outer diameter is at least (32 J' / (π ρ B_max))^(1/4).
    Each bound is 0 where no limit makes it (no cap, no width limit).

    Parameters
    ----------
    combo : flyopt.design.combination.Combination
    spec : DesignSpec

    Returns
    -------
    (float, str)
        The bound in the objective's unit (kg, the material's currency or m) and a phrase saying why.
    """
    j = combo.j_shaft
    if spec.objective == Objective.OUTER_DIAMETER:
        if not math.isfinite(spec.max_width):
            return 0.0, "no width limit bounds the diameter"
        d = (32.0 * j / (math.pi * combo.material.density * spec.max_width)) ** 0.25
        return d, said(
            "no wheel within the {width} width limit gives {j} below D {d} (a solid cylinder of that width)",
            width=(spec.max_width, "length", f"{spec.max_width:.4g} m"),
            j=(j, "inertia", f"{j:.4g} kg·m²"),
            d=(d, "length", f"{d:.4g} m"),
        )
    cap = min(combo.cap, stress_cap(combo, spec, combo.bore))  # rim speed or stress cap, envelope
    if not math.isfinite(cap):
        return 0.0, "no cap on the outer diameter bounds the mass"
    mass = 4.0 * j / (cap * cap)
    why = said(
        "every wheel that gives {j} within D {cap} weighs at least {mass} (m >= 4 J/D²: all of it at the outer radius)",
        j=(j, "inertia", f"{j:.4g} kg·m²"),
        cap=(cap, "length", f"{cap:.4g} m"),
        mass=(mass, "mass", f"{mass:.4g} kg"),
    )
    if spec.objective == Objective.COST:
        price = combo.material.cost
        if price is None:
            raise BrokenInvariant("design_flywheel refuses the cost objective without a price")
        return mass * price, why + f", which costs at least {mass * price:.4g}"
    return mass, why


def missing_poisson(material: Material, spec: DesignSpec) -> str | None:
    """Why a material can make no wheel under a spec on any shaft for want of a Poisson's ratio, or None."""
    if (spec.criterion == Criterion.STRESS or spec.geometry in (Geometry.RIM_WEB, Geometry.RIM_ARMS)) and getattr(
        material, "poisson_ratio", None
    ) is None:
        return f"material {material.name!r} gives no poisson_ratio, which the stress of a {spec.geometry} needs"
    return None


def screen(combo: Combination, spec: DesignSpec, bore: float) -> None:
    """Raise :class:`NoWheel` where a combination is shown unable to make a wheel without solving:
    its inertia above that of a solid disc filling the envelope, arms with no hub, or a stress
    that needs a Poisson's ratio the material does not give."""
    material, geo = combo.material, spec.geometry
    j_sup, cap, width = _upper_bound(combo, spec, bore)
    if combo.j_shaft > j_sup:
        where = (
            "the envelope"
            if cap >= combo.cap
            else said(
                "the largest diameter its stress allows at {omega}",
                omega=(combo.omega, "angular_speed", f"{combo.omega:.4g} rad/s"),
            )
        )
        wide = said("B {width}", width=(width, "length", f"{width:.4g} m"))
        if width < spec.max_width:
            wide += f", the widest a rim of H/B >= {spec.hb_ratio[0]:g} can be"
        raise NoWheel(
            combo.label
            + ": even a solid disc filling "
            + where
            + said(" (D {cap}, ", cap=(cap, "length", f"{cap:.4g} m"))
            + wide
            + said(
                ") gives only {j_sup}, short of the {j} required",
                j_sup=(j_sup, "inertia", f"{j_sup:.4g} kg·m²"),
                j=(combo.j_shaft, "inertia", f"{combo.j_shaft:.4g} kg·m²"),
            ),
            j_sup,
        )
    if geo == Geometry.DISC and spec.disc_hub and bore and not spec.textbook(bore):
        _screen_disc_on_hub(combo, spec, bore, cap)
    if geo == Geometry.RIM_ARMS and not bore:
        raise NoWheel(
            f"{combo.label}: a wheel on arms needs a hub on a shaft: give design.bore or the shaft's diameter"
        )
    missing = missing_poisson(material, spec)
    if missing:
        raise NoWheel(f"{combo.label}: {missing}")
    keyed = (geo in (Geometry.RIM_WEB, Geometry.RIM_ARMS) or (geo == Geometry.DISC and spec.disc_hub)) and bore
    if keyed and combo.torque and not spec.textbook(bore):
        # the hub's key (design/key.py's one rule): where even the section's longest standard key cannot carry
        # the torque, no hub length helps (:func:`hub_bounds` would leave the hub at its longest key, failing)
        try:
            key.hub_length_for_key(combo.torque, bore, getattr(material, "bearing_pressure", None))
        except ValueError as err:
            raise NoWheel(
                combo.label
                + said(
                    ": no DIN 6885-1 key on the {bore} seat carries it: ",
                    bore=(bore, "length", f"{bore * 1e3:.4g} mm"),
                )
                + said_by(err)
            ) from err


def _screen_disc_on_hub(combo: Combination, spec: DesignSpec, bore: float, cap: float) -> None:
    """Raise :class:`NoWheel` where no disc on its hub can give the combination's inertia: the disc is at most as
    wide as the hub is long (the hub at least as long as the disc), at most the hub's longest proportion, and,
    under castability, at most the section ratio times the hub's thickest section 2V/A = w l/(w + l) (w its
    widest wall, l its longest length); within D_cap, on the hub at its widest and longest, no such wheel holds
    more than J = π ρ (B_max D_cap⁴ + l_max d_hub,max⁴)/32."""
    if not math.isfinite(cap):
        return
    (_, d_hub), (_, l_max), _ = hub_bounds(combo.material, bore, combo.torque)
    rules = castability_of(spec, combo.material, bore)
    ratio = rules.section_ratio if rules is not None else math.inf
    wall = (d_hub - bore) / 2.0
    section = wall * l_max / (wall + l_max)
    b_max = min(spec.max_width, l_max, ratio * section)
    j_sup = math.pi * combo.material.density * (b_max * cap**4 + l_max * d_hub**4) / 32.0
    if combo.j_shaft <= j_sup:
        return
    why = said("at most its hub's longest, {l_max}", l_max=(l_max, "length", f"{l_max * 1e3:.4g} mm"))
    if ratio * section < l_max:
        why = said(
            "at most {ratio} times the hub's thickest section, {section}",
            ratio=(ratio, "dimensionless", f"{ratio:g}"),
            section=(section, "length", f"{section * 1e3:.4g} mm"),
        )
    raise NoWheel(
        combo.label
        + said(": even the widest disc on its hub (B {b_max}: ", b_max=(b_max, "length", f"{b_max * 1e3:.4g} mm"))
        + why
        + said(
            ") within D {cap}, on the hub at its largest ({d_hub} by {l_max}), gives only {j_sup}, short of the {j} "
            "required; a disc wider than its hub is its own hub: design.disc_hub = false designs it as the bored plate",
            cap=(cap, "length", f"{cap:.4g} m"),
            d_hub=(d_hub, "length", f"{d_hub * 1e3:.4g} mm"),
            l_max=(l_max, "length", f"{l_max * 1e3:.4g} mm"),
            j_sup=(j_sup, "inertia", f"{j_sup:.4g} kg·m²"),
            j=(combo.j_shaft, "inertia", f"{combo.j_shaft:.4g} kg·m²"),
        ),
        j_sup,
    )


def wheel_problem(
    material: Material,
    spec: DesignSpec,
    bore: float,
    torque: float,
    n_arms: int,
    j_shaft: float,
    omega: float,
    v_max: float,
) -> tuple[WheelStructure, WheelProblem]:
    """(WheelStructure, WheelProblem) of a whole wheel of a material on a shaft, its allowables not yet set.

    The one place where a design's limits become a wheel NLP's structure and
    numbers: :func:`design_combination` solves it, and the drive's relaxation
    (:mod:`flyopt.drive.relaxation`) writes the same rows with the shaft's
    speed as a variable.
    """
    from flyopt.design import wheel_nlp

    geo = spec.geometry
    d_hub_range = l_hub_range = (0.0, math.inf)
    disc_hub = geo == Geometry.DISC and spec.disc_hub and bool(bore)
    if (geo in (Geometry.RIM_WEB, Geometry.RIM_ARMS) and bore) or disc_hub:
        d_hub_range, l_hub_range, _ = hub_bounds(material, bore, torque)
    structure = wheel_nlp.WheelStructure(
        geometry=geo,
        criterion=spec.criterion,
        ductile=bool(getattr(material, "ductile", False)),
        bored=bool(bore),
        n_arms=n_arms,
        envelope=spec.has_envelope,
        width=spec.max_width < math.inf,
        pinned=spec.d_mean is not None,
        objective="outer_diameter" if spec.objective == Objective.OUTER_DIAMETER else "mass",
        castability=castability_of(spec, material, bore),
        disc_hub=disc_hub,
    )
    problem = wheel_nlp.WheelProblem(
        j_shaft=j_shaft,
        omega=omega,
        density=material.density,
        poisson=getattr(material, "poisson_ratio", None) or 0.3,
        torque=torque,
        bore=bore,
        allowable={},
        envelope=spec.max_outer_diameter,
        max_width=spec.max_width,
        max_rim_speed=v_max,
        hb_ratio=spec.hb_ratio,
        d_mean=spec.d_mean,
        min_wall=min_wall_of(spec, material),
        d_hub_range=d_hub_range,
        l_hub_range=l_hub_range,
    )
    return structure, problem


#: The wheels designed so far within :func:`neighbours` (None outside it): ((structure, combination), caps) -> the
#: last point's dims [m], or None where IPOPT found no wheel there.
_NEIGHBOURS: contextvars.ContextVar[dict[Any, dict[str, float] | None] | None] = contextvars.ContextVar(
    "wheel_neighbours", default=None
)


@contextlib.contextmanager
def neighbours() -> Iterator[None]:
    """Within it, each whole wheel :func:`design_combination` designs is warm-started from the last one
    designed of the same combination and NLP structure (a sweep's previous point): sqpmethod is tried from
    that wheel first and, where it does not converge, the solve goes on cold (:func:`flyopt.design.wheel_nlp.solve`).
    Where IPOPT found no wheel for the combination at the last point, IPOPT solves it first (it proves a wheel
    infeasible, which the SQP cannot: its failed attempt would only precede IPOPT's).

    A start, not an answer: the NLP, its bounds and the stress check are the point's own, so a warm design
    is the cold one to the solvers' tolerance (tests/studies/test_wheel_warm.py holds them to 1e-8). The
    memory lasts as long as the outermost block (a sweep's chunk, or a whole Pareto front run serially: a
    block within one joins it), so no design outside it depends on another.

    It also keeps every NLP IPOPT found infeasible (:func:`_proven_infeasible`): a later NLP of the same
    combination, structure and caps whose every limit is the same or tighter (a smaller envelope, lower
    allowables) has no wheel either, and is not solved; its reason cites the proof's numbers.
    """
    if _NEIGHBOURS.get() is not None:  # within an outer block: its memory serves this one too
        yield
        return
    token = _NEIGHBOURS.set({})
    try:
        yield
    finally:
        _NEIGHBOURS.reset(token)


#: The fields of a :class:`~flyopt.design.wheel_nlp.WheelProblem` that only start a solve (not its feasible set).
_STARTS = frozenset({"start", "warm", "ipopt_first"})
#: Its fields that are upper bounds (a smaller value is a tighter limit): the envelope, the allowables, the caps.
_UPPER = frozenset({"envelope", "allowable", "caps"})


def _within(problem: WheelProblem, proof: WheelProblem) -> bool:
    """Whether every wheel feasible in ``problem`` is feasible in ``proof`` (the same NLP structure assumed).

    The wheel NLP (:mod:`flyopt.design.wheel_nlp`) writes the envelope as D_outer <= envelope, each allowable
    as sigma / allowable <= 1 and each cap as an upper bound of its variable; everything else (inertia,
    speed, density, widths, walls, hub ranges, held dimensions) must be equal. So the feasible set of
    ``problem`` lies in that of ``proof`` where each of those three is no larger.
    """
    for f in dataclasses.fields(problem):
        name = f.name
        if name in _STARTS or name in _UPPER:
            continue
        if getattr(problem, name) != getattr(proof, name):
            return False
    if not problem.envelope <= proof.envelope:
        return False
    for mine, theirs in ((problem.allowable, proof.allowable), (problem.caps or {}, proof.caps or {})):
        if any(not mine.get(k, math.inf) <= theirs.get(k, math.inf) for k in {*mine, *theirs}):
            return False
    return True


def _proven_infeasible(problem: WheelProblem, proofs: list[WheelProblem] | None) -> WheelProblem | None:
    """The NLP IPOPT found infeasible whose feasible set holds ``problem``'s (:func:`_within`), or None.

    Feasible sets nest: an NLP with every limit the same or tighter than one that has no wheel has none.
    """
    for proof in proofs or ():
        if _within(problem, proof):
            return proof
    return None


def strongest_allowables(material: Material, spec: DesignSpec, structure: WheelStructure) -> dict[str, float]:
    """Each stressed part of a structure to the largest allowable stress any section of the material has [Pa]
    (empty under the rim-speed criterion, or when the material gives none): no wheel's allowable is higher."""
    from flyopt.design import wheel_nlp

    sigma = _strongest_allowable(material, spec) if spec.criterion == Criterion.STRESS else None
    return {} if sigma is None else {part: sigma for part in wheel_nlp.stressed_parts(structure)}


def design_combination(
    combo: Combination,
    spec: DesignSpec,
    bore: float,
    torque: float,
    n_arms: int = 0,
    solver_options: Mapping[str, Any] | None = None,
    method: str = "auto",
    fixed: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
) -> tuple[Dims, WheelSolution, StrengthCheck | None]:
    """Design one combination as a whole wheel.

    Parameters
    ----------
    combo : flyopt.design.combination.Combination
        Material, shaft, speed on it (omega_max of the cycle) and inertia needed on it.
    spec : DesignSpec
    bore : float
        Shaft seat [m] (0: none).
    torque : float
        Peak torque the wheel exchanges with its shaft [N*m] (0 when unknown).
    n_arms : int
        For ``rim_arms``.
    solver_options : mapping or None
    method : {"auto", "ipopt", "closed_form"}
        "ipopt" solves the NLP even where the disc's closed form covers the combination.
    fixed : mapping or None
        Dimensions held at given values [m] (by name, as the NLP's variables):
        the rest are optimized around them (:mod:`flyopt.design.rounding`).
    start : mapping or None
        IPOPT's starting wheel by variable name [m] (a neighbouring design's, warm), with ``fixed`` over it;
        None: the thin ring of :func:`flyopt.design.wheel_nlp.starting_wheel`.

    Returns
    -------
    dims : flyopt.design.wheel.Dims
    solution : flyopt.design.wheel_nlp.WheelSolution
    checked : flyopt.design.strength.StrengthCheck or None

    Raises
    ------
    NoWheel
        The combination cannot give the inertia (proven by a bound, or IPOPT
        found no wheel within every limit: the reason says which).
    SolverFailed
        IPOPT did not converge, or the design fails its independent check.
    """
    from flyopt.design import wheel_nlp

    screen(combo, spec, bore)
    material, geo = combo.material, spec.geometry
    stressed = spec.criterion == Criterion.STRESS
    closed = method != Method.IPOPT and not fixed and not combo.stress_factors(spec)
    exact = _disc_closed_form(combo, spec, bore, material) if closed else None
    if exact is not None:
        dims, solution = exact
        return dims, solution, strength.check_wheel(material, geo, dims, combo.omega, torque, spec.safety_factor)
    structure, problem = wheel_problem(material, spec, bore, torque, n_arms, combo.j_shaft, combo.omega, combo.v_max)
    if fixed:
        problem = _with(problem, fixed=dict(fixed))
    model = wheel_nlp.get_model(structure, solver_options)
    memory = _NEIGHBOURS.get() if not (fixed or start) and model.fast is not None else None
    remembered = (structure, combo.label)
    if start:  # a neighbour's dimensions over the thin ring (a pinned D_m leaves D_outer out of a rounding's)
        ring = wheel_nlp.starting_wheel(structure, problem, model.variables)
        problem = _with(problem, start={n: {**ring, **start, **(fixed or {})}[n] for n in model.variables})
    parts = model.stress_parts
    # the allowable of each part, first at the walls of a starting wheel (the last point's, in a sweep), then at
    # the solved one's
    last = memory.get((remembered, ())) if memory is not None else None
    start = last or wheel_nlp.starting_wheel(structure, problem, model.variables)
    start_dims = wheel_nlp.dims_of(structure, start, bore)
    targets = {}
    if stressed:
        try:
            targets = {
                p: a
                for p, (a, _s, _w) in strength.allowables(
                    material, geo, start_dims, spec.safety_factor, combo.stress_factors(spec)
                ).items()
            }
        except ThicknessOutOfRange:  # the starting wheel is thicker than the table: its weakest row
            factors = combo.stress_factors(spec)
            targets = {p: material.allowable(safety_factor=spec.safety_factor) / factors.get(p, 1.0) for p in parts}
    table_end = _table_end(material) if stressed else None
    best = _branch_and_settle(
        model, problem, combo, material, geo, spec, bore, torque, parts, targets, table_end, memory, remembered
    )
    if best is None:
        # only sections beyond the strength table (raised only where a table exists) leave no design
        if table_end is None:
            raise RuntimeError(f"{combo.label}: no wheel, and no strength table to blame")
        raise NoWheel(
            combo.label
            + f": the lightest {geo.replace('_', ' ')} has a section beyond the material's strength table, "
            + said(
                "which ends at {end}, and no wheel whose sections stay within it meets every limit",
                end=(table_end, "length", f"{table_end * 1e3:g} mm"),
            )
        )
    return best


def _branch_and_settle(
    model, problem, combo, material, geo, spec, bore, torque, parts, targets, table_end, memory=None, remembered=None
):
    """The best settled wheel over the unconstrained NLP and its sections capped at the strength table's end
    (None: every capped choice left no wheel); NoWheel where the unconstrained NLP has none.

    ``memory`` (:func:`neighbours`, None outside it): each NLP (``remembered`` and its caps) to the wheel the
    last point designed with it (its warm start here) or None where IPOPT found none (IPOPT first here).
    """
    best, tried, queue = None, set(), [()]
    while queue:  # the unconstrained wheel first, then sections capped at the table's end
        caps = queue.pop(0)
        if caps in tried:
            continue
        tried.add(caps)
        branch = _with(problem, caps=dict(caps) or None)
        if memory is not None:
            last = memory.get((remembered, caps), memory.get((remembered, ())))
            if last is not None:
                branch = _with(branch, warm=last)
            elif (remembered, caps) in memory:
                branch = _with(branch, ipopt_first=True)
        proofs = memory.setdefault(("infeasible", remembered, caps), []) if memory is not None else None
        try:
            found = _settle(
                model,
                branch,
                combo,
                material,
                geo,
                spec,
                torque,
                parts,
                dict(targets),
                table_end,
                proofs,
            )
        except _OverTable as over:
            if len(tried) >= _MAX_BRANCHES:
                raise SolverFailed(
                    f"{combo.label}: keeping every section within the material's strength "
                    f"table took more than {_MAX_BRANCHES} capped solves; no design is "
                    f"reported"
                ) from None
            queue += _branches(over.walls, dict(caps), geo, bore, table_end)
            continue
        except NoWheel:
            if memory is not None:  # IPOPT found no wheel: the next point's solve of this NLP is IPOPT's at once
                memory[remembered, caps] = None
            if not caps:
                raise
            continue  # this choice of capped sections leaves no wheel; another may
        if memory is not None:
            memory[remembered, caps] = {n: float(getattr(found[0], n)) for n in model.variables}
        if best is None or found[1].objective < best[1].objective:
            best = found
    return best


#: Capped solves allowed while keeping a wheel's sections within a strength table.
_MAX_BRANCHES = 16


class _OverTable(Exception):
    """A solved wheel has sections beyond its material's strength table: ``walls`` part -> wall [m]."""

    def __init__(self, walls):
        super().__init__(walls)
        self.walls = walls


def _table_end(material):
    """The thickest section the material's strength table covers [m], or None (no table)."""
    rows = getattr(material, "strength_by_thickness", ())
    return rows[-1].max_thickness if rows else None


def _branches(walls, caps, geo, bore, end):
    """Caps that bring every section in ``walls`` within the table's ``end``: one child per choice.

    A part's wall is the smaller of its two section sizes (:func:`flyopt.design.wheel.walls`), so
    each of the rim, hub and disc may be brought within the table by either: H or B for the
    rim, the radial wall or the length for the hub, B or the radial extent for the disc; the
    web by its thickness and the arms by their minor axis alone.
    """
    import itertools

    end = end * (1.0 - 1e-9)  # inside the last row, whatever the round-off of exp(log(cap))
    options = {
        "rim": ({"h": end}, {"b": end}),
        "web": ({"t_web": end},),
        "arms": ({"arm_major": end / wheel.ARM_MINOR_RATIO},),
        "hub": ({"d_hub": bore + 2.0 * end}, {"l_hub": end}),
        "disc": ({"b": end}, {"d_outer": bore + 2.0 * end}),
    }
    children = []
    for choice in itertools.product(*(options[part] for part in sorted(walls))):
        child = dict(caps)
        for cap in choice:
            for name, value in cap.items():
                child[name] = min(child.get(name, math.inf), value)
        children.append(tuple(sorted(child.items())))
    return children


def _settle(model, problem, combo, material, geo, spec, torque, parts, used, table_end, proofs=None):
    """Solve, check the exact stresses and every part's strength at its wall, and solve again until
    they agree with the NLP's rows. Raises _OverTable where a section leaves the strength table.

    ``proofs`` (within :func:`neighbours`): the NLPs of this combination and caps IPOPT found infeasible
    so far; one whose limits are all as loose or looser than this NLP's shows it has no wheel without a
    solve (:func:`_proven_infeasible`), and an NLP IPOPT finds infeasible here is added to them."""
    from flyopt.design import wheel_nlp

    stressed = spec.criterion == Criterion.STRESS
    for _round in range(_MAX_ROUNDS):
        problem = _with(problem, allowable={p: used.get(p, math.inf) for p in parts})
        proof = _proven_infeasible(problem, proofs)
        if proof is not None:
            raise NoWheel(_inferred_reason(combo.label, geo, problem, proof))
        try:
            solution = wheel_nlp.solve(model, problem, combo.label)
        except SolverFailed as err:
            if getattr(err, "status", "") == "Infeasible_Problem_Detected":
                if proofs is not None:
                    proofs.append(problem)
                raise NoWheel(
                    f"{combo.label}: IPOPT found no {geo.replace('_', ' ')} within every "
                    f"limit (it reports the problem locally infeasible; no bound proves it)"
                ) from None
            raise
        dims = solution.dims
        try:
            checked = (
                strength.check_wheel(
                    material, geo, dims, combo.omega, torque, spec.safety_factor, combo.stress_factors(spec)
                )
                if getattr(material, "poisson_ratio", None) is not None
                else None
            )
        except ThicknessOutOfRange:
            if not stressed:  # sized by the rim speed: the report says why no stress is given
                return dims, solution, None
            # the parts whose wall is beyond the table (under the "wheel" rule the ruling section is the
            # thickest wall, so the same parts)
            raise _OverTable({p: w for p, w in wheel.walls(geo, dims).items() if w > table_end}) from None
        if not stressed:
            return dims, solution, checked
        # under the stress criterion screen() has refused a material without poisson_ratio
        if checked is None:
            raise RuntimeError("a stressed wheel was designed without its strength check")
        settled = True
        for part in checked.parts:
            target = part.allowable
            old = used[part.part]
            binding = part.stress >= old * (1.0 - 1e-6)
            new = old * target / part.stress if binding else target
            if part.stress > target * (1.0 + check.VERIFY_RTOL) or abs(new - old) > 1e-9 * old:
                settled = False
            used[part.part] = min(new, target) if not binding else new
        if settled:
            return dims, solution, checked
    raise SolverFailed(
        f"{combo.label}: the stress check of the whole wheel did not settle in "
        f"{_MAX_ROUNDS} solves (a part's stress peak or wall strength keeps moving); "
        f"no design is reported"
    )


def _inferred_reason(label: str, geo: str, problem: WheelProblem, proof: WheelProblem) -> str:
    """Why an NLP has no wheel, shown by an infeasible one whose limits are all as loose or looser."""

    def looser_than(words: str, theirs: float, mine: float, dimension: str, written: Callable[[float], str]) -> str:
        return words + said(
            " {theirs} (here {mine})",
            theirs=(theirs, dimension, written(theirs)),
            mine=(mine, dimension, written(mine)),
        )

    looser = [looser_than("D <=", proof.envelope, problem.envelope, "length", lambda v: f"{v:.4g} m")]
    for part in sorted(problem.allowable):
        theirs, mine = proof.allowable.get(part, math.inf), problem.allowable[part]
        if math.isfinite(mine):
            looser.append(looser_than(f"{part} allowable", theirs, mine, "stress", lambda v: f"{v / 1e6:.4g} MPa"))
    for name, cap in sorted((problem.caps or {}).items()):
        bound = (proof.caps or {}).get(name, math.inf)
        looser.append(looser_than(f"{name} <=", bound, cap, "length", lambda v: f"{v * 1e3:.4g} mm"))
    return (
        label
        + f": IPOPT found no {geo.replace('_', ' ')} within every limit at "
        + join(", ", looser)
        + ", every other limit the same; these limits are as tight or tighter, so no wheel meets them either "
        "(not solved again)"
    )


def _disc_closed_form(combo, spec, bore, material):
    """The lightest disc under the stress criterion, exactly, where the closed form covers it.

    A free disc peaks at its bore (sigma_r = 0, sigma_t largest) or, solid, at
    its centre (sigma_r = sigma_t), so both measures are the hoop stress there
    (Timoshenko & Goodier, art. 32): sigma_t(a) = (3+nu)/4 rho w^2 [b^2 + (1-nu)/(3+nu) a^2],
    or (3+nu)/8 rho w^2 b^2 solid. The lightest disc of inertia J is the widest one,
    m = 2 J/(a^2 + b^2), at the largest b the stress and the envelope allow, and
    B = 2 J/(pi rho (b^4 - a^4)).

    Returns
    -------
    (Dims, WheelSolution) or None
        None where the closed form does not cover the combination (another
        objective, a pinned diameter, strength that depends on the wall, no
        Poisson's ratio, or a width below min_wall or above max_width, which
        the NLP then settles).
    """
    from flyopt.design import wheel_nlp

    if (
        spec.geometry != Geometry.DISC
        or (bore and spec.disc_hub)  # a disc on its hub is a stepped disc: the NLP's
        or spec.criterion != Criterion.STRESS
        or spec.objective == Objective.OUTER_DIAMETER
        or spec.d_mean is not None
        or getattr(material, "strength_by_thickness", ())
        or getattr(material, "poisson_ratio", None) is None
    ):
        return None
    a, rho, nu, j = bore / 2.0, material.density, material.poisson_ratio, combo.j_shaft
    sigma = material.allowable(safety_factor=spec.safety_factor)
    k = rho * combo.omega**2
    if a > 0:
        slope = 4.0 / ((3.0 + nu) * k)
        b2_stress = slope * sigma - (1.0 - nu) / (3.0 + nu) * a * a
    else:
        slope = 8.0 / ((3.0 + nu) * k)
        b2_stress = slope * sigma
    if b2_stress <= a * a:
        raise NoWheel(
            combo.label
            + said(
                ": at {omega} the hoop stress at a {bore} bore exceeds the allowable {sigma} for any disc",
                omega=(combo.omega, "angular_speed", f"{combo.omega:.4g} rad/s"),
                bore=(bore, "length", f"{bore * 1e3:.4g} mm"),
                sigma=(sigma, "stress", f"{sigma / 1e6:.4g} MPa"),
            )
        )
    b_stress = math.sqrt(b2_stress)
    half_envelope = spec.max_outer_diameter / 2.0
    by_stress = b_stress <= half_envelope
    b = b_stress if by_stress else half_envelope
    width = 2.0 * j / (math.pi * rho * (b**4 - a**4))
    wall = min_wall_at(spec, material, 2.0 * b, bore)
    if width > spec.max_width or width < wall or b - a < min_wall_of(spec, material):
        return None
    mass = 2.0 * j / (a * a + b * b)
    dims = wheel.Dims(d_outer=2.0 * b, h=b - a, b=width, bore=bore)
    # multipliers of the log-scaled rows, as IPOPT would give them (see sensitivities)
    lam_g = {"inertia": -1.0}
    lam_p = {}
    power = 2 if getattr(material, "ductile", False) else 1
    dm_db = -4.0 * j * b / (a * a + b * b) ** 2
    if by_stress:
        dm_dsigma = dm_db * slope / (2.0 * b)
        lam_p["allow_disc"] = -dm_dsigma * sigma / (mass * power)
        lam_g["stress_disc"] = lam_p["allow_disc"]  # the stress row binds (its name in the binding list)
    else:
        lam_g["max_outer_diameter"] = -(dm_db / 2.0) * spec.max_outer_diameter / mass
    structure = wheel_nlp.WheelStructure(
        "disc", "stress", power == 2, bool(bore), 0, spec.has_envelope, spec.max_width < math.inf, False, "mass"
    )
    return dims, wheel_nlp.WheelSolution(
        dims, math.log(mass), "closed_form", 0, 0.0, lam_g, {}, lam_p, 1.0, structure, {"disc": 1.0}
    )


def _with(problem: WheelProblem, **changes: Any) -> WheelProblem:
    """``dataclasses.replace(problem, **changes)`` of a WheelProblem, which has no ``__post_init__`` to run:
    a copy with the fields set, at a fraction of replace's cost (four or five a solve)."""
    fields = problem.__dataclass_fields__
    for name in changes:
        if name not in fields:
            raise TypeError(f"WheelProblem has no field {name!r}")
    new = copy.copy(problem)
    for name, value in changes.items():
        object.__setattr__(new, name, value)
    return new


class Structure(NamedTuple):
    """What :func:`structure_fields` finds of a designed wheel."""

    parts: Parts
    stresses: Stresses
    notes: tuple[str, ...]
    castability: dict[str, Any] | None = None  # castability.record of the wheel, None where no rules apply


def structure_fields(
    material: Material,
    geometry_name: str,
    dims: Dims,
    omega: float,
    torque: float,
    spec: DesignSpec,
    bore: float,
    checked: StrengthCheck | None = None,
    stress_factors: Mapping[str, float] | None = None,
) -> Structure:
    """The structure of a design (any geometry, any criterion): its parts, key, speed and stresses.

    Returns
    -------
    Structure
        ``parts`` (the parts and the key), ``stresses`` (the rim speed and
        hoop stress at ``omega`` and the wheel's stresses, None where the
        material lacks what they need), ``notes`` (why) and ``castability``
        (:func:`flyopt.design.castability.record`, None where no rules apply). ``checked``: the
        :func:`flyopt.design.strength.check_wheel` of these dims, when the
        designer has made it already (it is not made twice). ``stress_factors``: the combination's factors on
        its parts' modelled stresses (:meth:`flyopt.design.combination.Combination.stress_factors`).
    """
    notes: list[str] = []
    parts = wheel.parts(geometry_name, dims, material.density)
    items = tuple(
        {
            "name": p.name,
            "mass": float(p.mass),
            "inertia": float(p.inertia),
            "r_inner": float(p.r_inner),
            "r_outer": float(p.r_outer),
            "thickness": float(p.thickness),
        }
        for p in parts
    )
    mass = float(wheel.wheel_mass(parts))
    unbalance = balance.permissible_unbalance(mass, omega, balance.BALANCE_GRADE)
    speed = geometry.rim_speed(omega, float(dims.d_outer))
    hoop = geometry.hoop_stress(material.density, speed)
    if getattr(material, "poisson_ratio", None) is None:
        notes.append(f"{material.display_name} gives no poisson_ratio: stresses not computed")
        checked = None
    else:
        try:
            if checked is None:
                checked = strength.check_wheel(
                    material, geometry_name, dims, omega, torque, spec.safety_factor, stress_factors
                )
        except ValueError as err:
            notes.append("stresses not computed: " + said_by(err))
    found: dict[str, Any] = {}
    if checked is not None:
        found = dict(
            stress={**checked.to_dict(), "mean_hoop": checked.mean_hoop},
            allowable_stress=checked.allowable_stress,
            strength_safety=_finite_or_none(checked.strength_safety),
            burst_speed=_finite_or_none(checked.burst_speed),
            speed_margin=_finite_or_none(checked.speed_margin),
        )
    stresses = Stresses(
        rim_speed=speed,
        hoop_stress=hoop,
        safety_factor=material.allowable_stress / hoop if material.allowable_stress else None,
        unbalance_permissible=float(unbalance.u_per),
        **found,
    )
    key_check = None
    hub_length = {"rim_web": dims.l_hub, "rim_arms": dims.l_hub, "disc": dims.l_hub or dims.b}.get(geometry_name)
    pressure = getattr(material, "bearing_pressure", None)
    if bore and hub_length and not torque:
        # the key's section is the shaft's (DIN 6885-1 by the seat diameter) and its length the hub's: a keyway
        # to cut, whose pressure and shear cannot be checked without a torque
        why = "the cycle gives no torque curves"
        try:
            sized = key.key_for_shaft(bore)
            length = key.key_length_for_hub(sized, float(hub_length), bore)
        except ValueError as err:
            notes.append("no key: " + said_by(err))
        else:
            notes.append(f"{why}: the key is sized by the seat (DIN 6885-1) and the hub, and not checked")
            key_check = {
                "size": sized.size,
                "b": sized.b,
                "h": sized.h,
                "t1": sized.t1,
                "t2": sized.t2,
                "length": length,
                "effective_length": length - sized.b,
                "torque": torque or None,
                "bearing_pressure": None,
                "allowable_pressure": None,
                "shear": None,
                "allowable_shear": None,
                "ok": None,
            }
    elif bore and hub_length:
        try:
            k = key.check_key(torque, bore, float(hub_length), pressure)
        except ValueError as err:
            notes.append("key not checked: " + said_by(err))
        else:
            if pressure is None:  # the key's shear by the key steel's S_sy; the hub's pressure has no allowable
                notes.append(
                    f"{material.display_name} gives no bearing_pressure: the key's shear is checked (against the "
                    "key steel's S_sy), the hub's bearing pressure is not"
                )
            key_check = {
                "size": k.key.size,
                "b": k.key.b,
                "h": k.key.h,
                "t1": k.key.t1,
                "t2": k.key.t2,
                "length": k.length,
                "effective_length": k.effective_length,
                "torque": k.torque,
                "bearing_pressure": k.pressure,
                "allowable_pressure": k.allowable_pressure,
                "shear": k.shear,
                "allowable_shear": k.allowable_shear,
                # True only where both are checked: a key whose shear holds on a hub whose pressure has no
                # allowable is not called sound (null, as the schema says), one that fails either is False
                "ok": False if not k.ok else (True if k.allowable_pressure is not None else None),
            }
    rules = castability_of(spec, material, bore)
    if rules is None and designed_castable(spec, bore):
        notes.append(
            f"no casting process is known for {material.display_name}: castability not checked (give design.process)"
        )
    thin = thin_walled(spec, material, geometry_name, dims)
    if thin is not None:
        notes.append(thin_wall_note(thin, geometry_name, spec.textbook(bore)))
    cast = castability.record(rules, min_wall_of(spec, material), geometry_name, dims)
    return Structure(Parts(items, key_check, thin), stresses, tuple(notes), cast)


def thin_wall_note(thin: Mapping[str, Any], geometry_name: str, textbook: bool) -> Said:
    """The structural check's note on a wheel thinner than the wall asked of it (:func:`thin_walled`): both
    walls, who asks (the process, or design.min_wall), why nothing held the section to it, and what to do."""
    part, wall, asked = thin["thinnest_part"], thin["thinnest_wall"], thin["min_wall"]
    shape = wheel_words(geometry_name)
    by = castability.who_asks(thin).replace("{", "{{").replace("}", "}}") + " in a wheel {size} across"
    sized = "its inertia and rim speed alone" if textbook else "its inertia and stresses alone"
    other = 'design the wheel whole (design.geometry = "rim_web")'
    if geometry_name == Geometry.DISC:
        other = 'give it a bore (design.bore) so that it is designed whole, or design a wheel with a web (design.geometry = "rim_web")'
    named = f"the {part}'s width" if part == "disc" else f"the {part}'s thinnest wall"
    return said(
        f"{named}, {{wall}}, is thinner than the {{asked}} {by}: a bare {shape} is not designed to the "
        f"castability rules (its section is sized by {sized}), so nothing held it to a wall that can be made; "
        f"set an envelope (design.max_outer_diameter) or {other}",
        wall=(wall, "length", f"{wall * 1e3:.4g} mm"),
        asked=(asked, "length", f"{asked * 1e3:.4g} mm"),
        size=(thin["casting_size"], "length", f"{thin['casting_size']:.4g} m"),
    )


def _finite_or_none(x):
    return float(x) if math.isfinite(x) else None


#: Sensitivities whose elasticity |d m / d limit| limit / m is below this are round-off, not reported.
ELASTICITY_FLOOR = 1e-7

#: What each limit's sensitivity is called, its unit, the step a report quotes it for [that unit] and what the
#: step is of.
_LIMITS = {
    "max_outer_diameter": ("the envelope", "m", 0.010, "of outer diameter"),
    "rim_speed": ("the rim speed limit", "m/s", 1.0, "of rim speed"),
    "max_width": ("the width limit", "m", 0.010, "of width"),
    "max_width_hub": ("the width limit (hub)", "m", 0.010, "of width"),
}


def sensitivity(
    limit: str, unit: str, dmass_dlimit: float, sentence: str, step: float, dmass: float | None = None
) -> dict[str, Any]:
    """One binding limit's sensitivity as the results carry it (JSON ``design.sensitivities[]``).

    ``sentence`` says it with ``{step}`` for the limit's change (``step`` [``unit``], signed) and ``{dmass}`` for
    the mass's (``dmass``, by default ``dmass_dlimit * step`` [kg]); ``text`` is the sentence in engineering
    units with three significant figures of the mass, and a report fills the sentence in its reader's units
    instead (:func:`flyopt.report.display.sensitivity_text`).
    """
    dmass = dmass_dlimit * step if dmass is None else dmass
    return {
        "limit": limit,
        "unit": unit,
        "dmass_dlimit": dmass_dlimit,
        "step": step,
        "dmass": dmass,
        "sentence": sentence,
        "text": sentence.format(step=_engineering_step(step, unit), dmass=f"{dmass:+.3g} kg"),
    }


def _engineering_step(step: float, unit: str) -> str:
    """A sensitivity's step in engineering units, signed: "+10 mm", "-1 mm", "+1 MPa", "+1 m/s", "+0.01"."""
    shown, label = {"m": (step * 1e3, " mm"), "Pa": (step * 1e-6, " MPa"), "m/s": (step, " m/s")}.get(unit, (step, ""))
    return f"{shown:+g}{label}"


def sensitivities(solution: WheelSolution, mass: float, problem_limits: dict[str, Any]) -> tuple[dict[str, Any], ...]:
    """The multipliers of the binding limits in engineering units: d(mass)/d(limit).

    Parameters
    ----------
    solution : WheelSolution
    mass : float
        The design's mass [kg].
    problem_limits : dict
        ``envelope``, ``max_rim_speed``, ``max_width``, ``j_shaft``, ``allowable`` (part to Pa); and
        ``castability`` (the rules, or None) with ``size`` (the design's outer diameter [m]).

    Returns
    -------
    tuple of dict
        :func:`sensitivity`'s entries (``limit``, ``unit``, ``dmass_dlimit`` [kg per unit], the step quoted and
        the sentence), for every limit whose multiplier is not zero. The objective is log m, and IPOPT's
        multiplier lambda of a row ``g <= u`` (or ``>= l``) is -d f*/du, so d m / d u = -m lambda d(row)/d(limit).
    """
    out = []
    lam = solution.lam_g

    def add(limit, unit, dm, sentence, step, value, dmass=None):
        # a limit that does not bind has a multiplier of round-off size: keep elasticities above 1e-7
        if math.isfinite(dm) and abs(dm * value) > ELASTICITY_FLOOR * mass:
            out.append(sensitivity(limit, unit, dm, sentence, step, dmass))

    for row, (what, unit, step, words) in _LIMITS.items():
        if abs(lam.get(row, 0.0)) > 0:
            value = {
                "max_outer_diameter": problem_limits["envelope"],
                "rim_speed": problem_limits["max_rim_speed"],
                "max_width": problem_limits["max_width"],
                "max_width_hub": problem_limits["max_width"],
            }[row]
            dm = -mass * lam[row] / value  # rows are log(limit)
            add(row, unit, dm, f"{what} binds: {{step}} {words} changes the mass by {{dmass}}", step, value)
    wall = problem_limits.get("min_wall") or 0.0
    at_wall = sum(v for n, v in solution.lam_x.items() if v < 0 and n in ("h", "b", "t_web", "arm_major"))
    if wall > 0 and (at_wall or lam.get("hub_wall", 0.0)):
        # variables are log(dimension) with lower bounds log(min_wall); the hub's wall row is in metres
        dm = -mass * at_wall / wall - mass * lam.get("hub_wall", 0.0)
        add(
            "min_wall",
            "m",
            dm,
            "the minimum wall (min_wall) binds: {step} of the thinnest section changes the mass by {dmass}",
            -1e-3,
            wall,
        )
    rules = problem_limits.get("castability")
    for row, value in sorted(lam.items()):
        if rules is None or not row.startswith("castability_") or value == 0.0:
            continue
        if row.startswith("castability_min_wall_"):
            # log(wall) - log(min_wall(D)) >= 0: the process's wall at this size scaled by (1 + e) moves the
            # row's bound by e, so d m / d min_wall = -m lam / min_wall
            wall = float(castability.min_wall_at(rules, problem_limits["size"]))
            dm = -mass * value / wall
            part = row[len("castability_min_wall_") :]
            add(
                row,
                "m",
                dm,
                f"the {rules.process.replace('_', ' ')} minimum wall binds ({part}): {{step}} of it changes the "
                "mass by {dmass}",
                1e-3,
                wall,
            )
        else:
            # -log r <= log(t_a / t_b) <= log r: a larger ratio r loosens whichever side binds
            ratio = rules.section_ratio
            dm = -mass * abs(value) / ratio
            pair = row[len("castability_") : -len("_ratio")].replace("_", "-")
            add(
                row,
                "-",
                dm,
                f"the section ratio binds ({pair}): {{step}} on the allowed {ratio:g} changes the mass by {{dmass}}",
                0.1,
                ratio,
            )
    if abs(lam.get("inertia", 0.0)) > 0:
        dm = -mass * lam["inertia"] / problem_limits["j_shaft"]
        # the step is 1 % of the inertia required: said in words, a share needs no unit
        add(
            "inertia",
            "kg*m^2",
            dm,
            "each +1 % of required inertia adds {dmass}",
            0.01 * problem_limits["j_shaft"],
            problem_limits["j_shaft"],
            dm * 0.01 * problem_limits["j_shaft"],  # as its text was always worked out
        )
    for param, value in solution.lam_p.items():
        if not param.startswith("allow_") or value == 0.0:
            continue
        part = param[len("allow_") :]
        allowable = problem_limits["allowable"].get(part)
        if not allowable or not math.isfinite(allowable):
            continue
        # the parameter is P = (sigma_a / S)^k, k = 2 (ductile) or 1, and CasADi's lam_p is -d f*/d P
        # (checked against re-solving in tests/design/test_wheel_nlp.py): d m / d sigma_a = -m lam_p k P / sigma_a
        k, param = problem_limits["allow_power"], problem_limits["allow_param"][part]
        dm = -mass * value * k * param / allowable
        add(
            f"stress_{part}",
            "Pa",
            dm,
            f"the stress limit of the {part} binds: {{step}} allowable changes the mass by {{dmass}}",
            1e6,
            allowable,
        )
    return tuple(out)
