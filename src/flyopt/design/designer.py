"""The flywheel designer: every material x shaft combination decided, then ranked.

Given the flywheel inertia the cycle analysis requires at the reference shaft,
J_F (already net of the machine's own J_c), every combination of material and
mounting shaft is decided: the exact closed-form bound
(:func:`flyopt.design.closed_form.max_inertia_one`) proves the infeasible ones
infeasible and says why in numbers; each feasible one is optimized, by the
exact closed form where it covers the structure (:mod:`flyopt.design.closed_form`)
or by IPOPT on the NLP of :mod:`flyopt.design.nlp`; every design is verified
against every constraint by :mod:`flyopt.design.check`; and the combinations
are ranked by the one rule of :mod:`flyopt.design.rank`.

For a flywheel mounted on a shaft turning at omega' = r omega_m (r the speed
ratio), the kinetic energy transfer (docs/flywheel-design.md, section 8) gives

    J_ref = J' r^2,   so the wheel must give J' >= J_F / r^2 on its shaft.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 5, 8, 9, 10 and
   worked example 6.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, cast

from flyopt.design import check, closed_form, geometry, rank, wheel, wheel_design
from flyopt.design.combination import Combination, combination_label, shaft_label
from flyopt.design.materials import Material
from flyopt.design.result import Candidate, Design, DesignResult, Dimensions, Limits, Provenance, infeasible_message
from flyopt.design.spec import DesignSpec, MountShaft
from flyopt.design.wheel_design import bore_of
from flyopt.errors import SolverFailed
from flyopt.machine.transmission import inertia_at_reference, inertia_on_shaft
from flyopt.names import Criterion, Geometry, Method, Objective
from flyopt.said import join, said
from flyopt.validate import choice, finite, positive

__all__ = ["design_flywheel", "rim_speed_limit", "METHODS"]

#: How a feasible combination is optimized (see :func:`design_flywheel`).
METHODS = ("auto", "ipopt", "closed_form")


def _g(x):
    return f"{x:.3g}"


def _g_apart(a, b):
    """Format two numbers with as few significant digits as keep them apart."""
    for digits in range(3, 13):
        sa, sb = f"{a:.{digits}g}", f"{b:.{digits}g}"
        if sa != sb:
            return sa, sb
    return f"{a:.12g}", f"{b:.12g}"


def _explain_infeasible(combo, spec):
    """Say in words and numbers why a combination cannot give its inertia.

    Returns the sentence and the outer-diameter cap the combination would
    need (None when no cap would do).
    """
    m, geo = combo.material, spec.geometry
    word = {"rim": "rim", "thin_rim": "thin rim", "disc": "disc"}[geo]
    hb_min, hb_max = spec.hb_ratio
    v_max = (combo.v_max, "speed", f"{_g(combo.v_max)} m/s")
    if combo.cap_speed <= combo.cap:
        cap_text: str = said("the {v_max} rim limit caps the outer diameter", v_max=v_max)
    else:
        cap_text = "the envelope (max_outer_diameter) caps the outer diameter"

    def need(j_text):
        text = said("{j}", j=(combo.j_shaft, "inertia", f"{j_text} kg·m²"))
        if combo.shaft.speed_ratio != 1.0:
            text += said(
                " on this shaft ({j} at the reference shaft)",
                j=(combo.j_reference, "inertia", f"{_g(combo.j_reference)} kg·m²"),
            )
        return text

    def length(value, text):
        return (value, "length", f"{text} m")

    pinned = combo.d_mean
    if pinned is not None and pinned > combo.cap_mean:
        cap, pin = _g_apart(combo.cap_mean, pinned)
        return combo.label + said(
            ": the pinned mean diameter {pin} turns faster at the mean speed than the {v_max} rim limit allows "
            "(mean_rim_speed: D_m <= {cap})",
            pin=length(pinned, pin),
            v_max=v_max,
            cap=length(combo.cap_mean, cap),
        ), None
    if pinned is not None and geo != Geometry.DISC and pinned >= combo.cap:
        cap, pin = _g_apart(combo.cap, pinned)
        return combo.label + ": " + cap_text + said(
            " at {cap}, which leaves no room for a rim around the pinned mean diameter {pin}",
            cap=length(combo.cap, cap),
            pin=length(pinned, pin),
        ), None
    if pinned is not None and geo == Geometry.DISC and pinned > combo.cap:
        cap, pin = _g_apart(combo.cap, pinned)
        return combo.label + ": " + cap_text + said(
            " at {cap}, below the pinned diameter {pin}", cap=length(combo.cap, cap), pin=length(pinned, pin)
        ), None
    needed, j_sup = closed_form.cap_needed(
        geo, m.density, combo.j_shaft, combo.cap, spec.hb_ratio, spec.max_width, pinned, j_cap=combo.j_max
    )
    if needed is None:
        limits: list[str] = []
        if pinned is not None:
            limits.append(said(("D" if geo == "disc" else "D_m") + " pinned at {pin}", pin=length(pinned, _g(pinned))))
        if spec.max_width < math.inf:
            limits.append(said("B <= {width}", width=length(spec.max_width, _g(spec.max_width))))
        if geo != Geometry.DISC:
            limits.append(f"{_g(hb_min)} <= H/B <= {_g(hb_max)}")
            limits.append("D_inner > 0")
        text = join(", ", limits[:-1]) + " and " + limits[-1] if len(limits) > 1 else limits[0]
        j_sup_text, j_text = _g_apart(j_sup, combo.j_shaft)
        return (
            combo.label
            + f": even with no limit on the outer diameter, the largest {word} with "
            + text
            + said(" gives {j_sup}, short of the ", j_sup=(j_sup, "inertia", f"{j_sup_text} kg·m²"))
            + need(j_text)
            + " required"
        ), None
    cap, needed_text = _g_apart(combo.cap, needed)
    return (
        combo.label
        + ": "
        + cap_text
        + said(" at {cap}, where the smallest " + word + " that gives ", cap=length(combo.cap, cap))
        + need(_g(combo.j_shaft))
        + said(" still needs an outer diameter of {needed}", needed=length(needed, needed_text))
    ), needed


def _solve_closed_form(pending, spec):
    """Design feasible combinations by the exact closed form.

    Feasibility is already proven by :func:`flyopt.design.closed_form.max_inertia_one`; each design comes
    from :func:`flyopt.design.closed_form.lightest_one` (plain floats: a ranking is a few
    combinations, too few for numpy to pay), is recomputed with
    :mod:`flyopt.design.geometry` and verified like an IPOPT one.

    Returns (order, Candidate) pairs.
    """
    hb_min, hb_max = spec.hb_ratio
    b_max = spec.max_width
    geometry_name = spec.geometry
    disc = geometry_name == Geometry.DISC
    results = []
    for order, combo in pending:
        start = time.perf_counter()
        rho = combo.material.density
        d_mean, h, b = closed_form.lightest_one(
            geometry_name, combo.j_shaft, rho, combo.cap, hb_min, hb_max, b_max, combo.d_mean
        )
        if disc:
            mass = geometry.disc_mass(2 * d_mean, b, rho)
            j_wheel = geometry.disc_inertia(mass, 2 * d_mean)
        else:
            mass = geometry.rim_mass(d_mean, h, b, rho)
            j_wheel = geometry.wheel_inertia(geometry_name, rho, d_mean, h, b)
        results.append(
            (
                order,
                _candidate_from_design(
                    combo, spec, d_mean, h, b, mass, j_wheel, "closed_form", 0, time.perf_counter() - start
                ),
            )
        )
    return results


def _candidate_from_design(combo, spec, d_mean, h, b, mass, j_wheel, status, iterations, elapsed):
    """Verify a solved design against every constraint; its structural check and its description (what binds,
    its limits, how it was found) are made when first read (:meth:`flyopt.design.result.Design.checked_when_read`).
    """
    m = combo.material
    geometry_name = spec.geometry
    d_outer = geometry.outer_diameter(d_mean, h)
    d_inner = geometry.inner_diameter(d_mean, h)
    hb_min, hb_max = spec.hb_ratio
    violations = check.violations(
        geometry_name, j_wheel, combo.j_shaft, d_outer, d_inner, b, h / b, combo.cap, spec.max_width, hb_min, hb_max
    )
    if violations:
        source = "the closed-form design" if status == "closed_form" else f"IPOPT reported {status!r} but the design"
        err = SolverFailed(f"{combo.label}: {source} violates {'; '.join(violations)}; no design is reported")
        err.status = status
        err.combination = combo.label
        raise err
    cost = mass * m.cost if m.cost is not None else None
    shaft = combo.shaft
    return Design.checked_when_read(
        functools.partial(_structure, m, geometry_name, d_outer, h, b, combo.omega, combo.torque, spec),
        functools.partial(_described, combo, spec, j_wheel, d_outer, d_inner, b, h, status, iterations, elapsed),
        material=m.name,
        shaft=shaft.name,
        speed_ratio=shaft.speed_ratio,
        geometry=geometry_name,
        mass=mass,
        cost=cost,
        j_flywheel=j_wheel,
        j_at_reference=inertia_at_reference(j_wheel, shaft.speed_ratio),
        objective=_objective(spec.objective, mass, d_outer, cost),
        dims=Dimensions(d_mean=d_mean, d_outer=d_outer, d_inner=max(d_inner, 0.0), h=h, b=b),
    )


def _described(combo, spec, j_wheel, d_outer, d_inner, b, h, status, iterations, elapsed):
    """A verified textbook design's description: its reason (what binds), its limits and its provenance (without
    the structural check's notes), made when first read (:meth:`flyopt.design.result.Design.checked_when_read`)."""
    hb_min, hb_max = spec.hb_ratio
    binding = check.binding_names(
        check.binding_mask(
            spec.geometry,
            j_wheel,
            combo.j_shaft,
            d_outer,
            d_inner,
            b,
            h / b,
            combo.cap_speed,
            spec.max_outer_diameter,
            spec.max_width,
            hb_min,
            hb_max,
        )
    )
    if combo.d_mean is not None and combo.d_mean == combo.cap_mean:
        binding = (*binding, "mean_rim_speed")  # the courses' convention put D_m where v_max is reached
    return (
        f"{combo.label}: designed; binding: {', '.join(binding) or 'none'}",
        _limits(combo, j_max=combo.j_max, binding=binding),
        Provenance(solver_status=status, iterations=iterations, solve_time=elapsed),
    )


def _structure(material, geometry_name, d_outer, h, b, omega, torque, spec):
    """The structural check of a textbook design (:func:`flyopt.design.wheel_design.structure_fields`, no bore)
    of outer diameter ``d_outer``, rim depth ``h`` (a disc's is its radius) and width ``b``: its parts, stresses
    and notes, made when the design's structural fields are first read
    (:meth:`flyopt.design.result.Design.checked_when_read`)."""
    dims = wheel.Dims(d_outer=d_outer, h=d_outer / 2.0 if geometry_name == Geometry.DISC else h, b=b)
    structure = wheel_design.structure_fields(material, geometry_name, dims, omega, torque, spec, 0.0)
    return structure.parts, structure.stresses, structure.notes


def _objective(objective: str, mass: float, d_outer: float, cost: float | None) -> float:
    """The value of the ranking objective of a design."""
    if objective == Objective.COST:
        if cost is None:  # design_flywheel refuses the cost objective unless every material has a cost
            raise ValueError("objective 'cost' needs a cost per kg on the material")
        return cost
    return d_outer if objective == Objective.OUTER_DIAMETER else mass


def rim_speed_limit(material: Material, spec: DesignSpec) -> float:
    """The material's safe rim speed [m/s] under a design spec: :meth:`Material.rim_speed_limit` with the
    design's safety factor (the one rule; the design's factor wins over the material's).

    Under the stress criterion, which needs no rim speed limit, a material given by strengths with no
    factor from either gives NaN instead of refusing.
    """
    if spec.criterion == Criterion.STRESS:
        try:
            return material.rim_speed_limit(safety_factor=spec.safety_factor)
        except ValueError:
            return math.nan  # no factor on its strength: the stress criterion needs none
    return material.rim_speed_limit(safety_factor=spec.safety_factor)


def _design_whole(combo, spec, n_arms, solver_options, method="auto"):
    """One combination (and arm count) as a whole wheel: its Candidate, designed or not, and the model."""
    from flyopt.design import wheel_nlp

    combo_n = Combination(**{**combo.__dict__, "n_arms": n_arms})
    label = combo_n.label
    m = combo.material
    start = time.perf_counter()
    try:
        dims, solution, checked = wheel_design.design_combination(
            combo_n, spec, combo.bore, combo.torque, n_arms, solver_options, method
        )
    except wheel_design.NoWheel as err:
        return Candidate.infeasible(
            m.name,
            combo.shaft,
            spec.geometry,
            err.reason,
            n_arms=n_arms or None,
            bore=combo.bore or None,
            limits=_limits(combo, j_max=err.j_max),
        ), None
    except SolverFailed as err:
        err.combination = label
        raise
    model = wheel_nlp.get_model(solution.structure, solver_options) if solution.status != "closed_form" else None
    parts = wheel.parts(spec.geometry, dims, m.density)
    mass = float(wheel.wheel_mass(parts))
    j_wheel = float(wheel.wheel_inertia(parts))
    d_outer, h, b = float(dims.d_outer), float(dims.h), float(dims.b)
    d_inner = float(dims.d_inner)
    found = _whole_violations(combo, spec, dims, j_wheel, checked)
    if found:
        failure = SolverFailed(
            f"{label}: IPOPT reported {solution.status!r} but the wheel violates "
            f"{'; '.join(found)}; no design is reported"
        )
        failure.status = solution.status
        failure.combination = label
        raise failure
    binding = sorted(name for name, lam in solution.lam_g.items() if abs(lam) > 1e-9)
    binding += sorted(
        {
            "strength_table" if lam > 0 and name in (solution.caps or {}) else _BOUND_NAMES[name, lam > 0]
            for name, lam in solution.lam_x.items()
            if abs(lam) > 1e-9
        }
    )
    cost = mass * m.cost if m.cost is not None else None
    objective = _objective(spec.objective, mass, d_outer, cost)
    structure = wheel_design.structure_fields(
        m, spec.geometry, dims, combo.omega, combo.torque, spec, combo.bore, checked, combo.stress_factors(spec)
    )
    limits = {
        "envelope": spec.max_outer_diameter,
        "max_rim_speed": combo.v_max,
        "max_width": spec.max_width,
        "j_shaft": combo.j_shaft,
        "allowable": {p.part: p.allowable for p in checked.parts} if checked else {},
        "allow_power": 2 if getattr(m, "ductile", False) else 1,
        "allow_param": solution.allow_params,
        "min_wall": wheel_design.min_wall_of(spec, m),
        "castability": solution.structure.castability,
        "size": d_outer,
    }
    sensitivities = (
        wheel_design.sensitivities(solution, mass, limits) if spec.objective != Objective.OUTER_DIAMETER else ()
    )
    return Design(
        reason=f"{label}: designed; binding: {', '.join(binding) or 'none'}",
        mass=mass,
        cost=cost,
        j_flywheel=j_wheel,
        j_at_reference=inertia_at_reference(j_wheel, combo.shaft.speed_ratio),
        objective=objective,
        dims=Dimensions(
            d_mean=d_outer - h,
            d_outer=d_outer,
            d_inner=max(d_inner, 0.0),
            h=h,
            b=b,
            t_web=_dim(dims.t_web),
            d_hub=_dim(dims.d_hub),
            l_hub=_dim(dims.l_hub),
            arm_major=_dim(dims.arm_major),
        ),
        parts=structure.parts,
        stresses=structure.stresses,
        limits=_limits(combo, binding=tuple(binding), sensitivities=sensitivities, castability=structure.castability),
        provenance=Provenance(
            solver_status=solution.status,
            iterations=solution.iterations,
            solve_time=time.perf_counter() - start,
            notes=structure.notes,
        ),
        material=m.name,
        shaft=combo.shaft.name,
        speed_ratio=combo.shaft.speed_ratio,
        geometry=spec.geometry,
        n_arms=n_arms or None,
        bore=combo.bore or None,
    ), model


def _rejected(design: Candidate, reason: str) -> Candidate:
    """A designed combination a post-check refuses: infeasible, its dimensions kept, ``reason`` saying why."""
    fields = {f.name: getattr(design, f.name) for f in dataclasses.fields(Candidate)}
    return Candidate(**{**fields, "feasible": False, "reason": reason})


def _accepted(feasible, accept, infeasible):
    """The feasible (order, design)s ``accept`` passes; the others go to ``infeasible`` with its reason."""
    kept = []
    for order, design in feasible:
        reason = accept(design)
        if reason is None:
            kept.append((order, design))
        else:
            infeasible.append(((order, 0), _rejected(design, reason)))
    return kept


def _design_wholes(whole, spec, solver_options, method, feasible, infeasible, pruned, names, accept=None):
    """Design the whole-wheel combinations, the most promising first, leaving out those that cannot win.

    Each combination (and arm count) is taken in the order of its objective
    bound (:func:`flyopt.design.wheel_design.objective_bound`, a lower bound
    on the objective of every wheel it can make). With ``spec.prune``, one
    whose bound exceeds the best objective already designed by more than the
    ranking's tie tolerance (:data:`flyopt.design.rank.TIE_RTOL`) cannot win
    or tie: it is reported as pruned, with the bound and the design that
    beats it, and IPOPT is not run on it. The winner and its design are the
    same as with every combination designed.

    Appends (order, Candidate) to ``feasible``, ((order, arm index), Candidate) to ``infeasible`` and
    Candidates to ``pruned`` (whose reasons name the winner by ``names``, material key -> name for people); returns
    the last wheel model built (for the description), or None.
    """
    tasks = []
    for order, combo in whole:
        bound, why = wheel_design.objective_bound(combo, spec)
        for n_arms in spec.arms if spec.geometry == Geometry.RIM_ARMS else (0,):
            tasks.append((bound, order, n_arms, combo, why))
    tasks.sort(key=lambda t: t[:3])
    model = None
    for bound, order, n_arms, combo, why in tasks:
        try:  # a combination shown unable to make any wheel is infeasible, not pruned
            wheel_design.screen(Combination(**{**combo.__dict__, "n_arms": n_arms}), spec, combo.bore)
        except wheel_design.NoWheel:
            pass  # _design_whole reports it, without solving
        else:
            if spec.prune and feasible and _cannot_win(bound, feasible):
                pruned.append(_pruned(combo, spec, n_arms, bound, why, feasible, names))
                continue
        result, built = _design_whole(combo, spec, n_arms, solver_options, method)
        model = built or model
        reason = accept(result) if accept is not None and result.feasible else None
        if reason is not None:
            result = _rejected(result, reason)
        if result.feasible:
            feasible.append((order, result))
        else:
            infeasible.append(((order, spec.arms.index(n_arms) if n_arms else 0), result))
    return model


def _best_of(feasible):
    return min((c for _, c in feasible), key=lambda c: c.objective)


def _cannot_win(bound, feasible):
    """Whether an objective bound exceeds the best design's objective beyond the ranking's tie tolerance."""
    return bound > _best_of(feasible).objective * (1.0 + rank.TIE_RTOL)


#: The unit and the dimension of each objective, for the reasons of pruned combinations (a cost has neither).
_OBJECTIVE_UNIT = {"mass": (" kg", "mass"), "outer_diameter": (" m", "length"), "cost": ("", None)}


def _pruned(combo, spec, n_arms, bound, why, feasible, names):
    """The Candidate of a combination left undesigned because its bound shows it cannot win."""
    best = _best_of(feasible)
    label = Combination(**{**combo.__dict__, "n_arms": n_arms}).label
    winner = combination_label(names.get(best.material, best.material), best.shaft, best.n_arms)
    unit, dimension = _OBJECTIVE_UNIT[spec.objective]
    written = f"{best.objective:.4g}{unit}"
    objective = written if dimension is None else said("{best}", best=(best.objective, dimension, written))
    return Candidate.infeasible(
        combo.material.name,
        combo.shaft,
        spec.geometry,
        label + ": not designed, it cannot win: " + why + ", more than the " + objective + " of " + winner,
        n_arms=n_arms or None,
        bore=combo.bore or None,
        limits=_limits(combo),
        provenance=Provenance(pruned=True, objective_bound=bound),
    )


#: What an active bound on a wheel NLP variable means: (variable, upper bound) -> binding name.
_BOUND_NAMES = {
    ("h", False): "min_wall",
    ("b", False): "min_wall",
    ("t_web", False): "min_wall",
    ("arm_major", False): "min_wall",
    ("d_hub", False): "hub_diameter_min",
    ("d_hub", True): "hub_diameter_max",
    ("l_hub", False): "hub_length_min",
    ("l_hub", True): "hub_length_max",
}


def _dim(value):
    value = float(value)
    return value if value > 0 else None


def _whole_violations(combo, spec, dims, j_wheel, checked):
    """Every limit of a whole wheel checked on the solved dimensions, in words (empty: all hold)."""
    tol = check.VERIFY_RTOL
    found = []
    if j_wheel < combo.j_shaft * (1.0 - tol):
        found.append(f"inertia {j_wheel:.9g} < {combo.j_shaft:.9g} kg·m²")
    if dims.d_outer > combo.cap * (1.0 + tol):
        found.append(f"outer diameter {dims.d_outer:.9g} > cap {combo.cap:.9g} m")
    if dims.b > spec.max_width * (1.0 + tol) or dims.l_hub > spec.max_width * (1.0 + tol):
        found.append(f"width {max(dims.b, dims.l_hub):.9g} > {spec.max_width:.9g} m")
    if spec.geometry != Geometry.DISC:
        hb = dims.h / dims.b
        if not spec.hb_ratio[0] * (1.0 - tol) <= hb <= spec.hb_ratio[1] * (1.0 + tol):
            found.append(f"H/B {hb:.9g} outside [{spec.hb_ratio[0]}, {spec.hb_ratio[1]}]")
        if dims.d_inner < max(dims.d_hub, 0.0) - tol * dims.d_outer:  # to the wheel's size: the hub may be 0
            found.append(f"the rim's inner diameter {dims.d_inner:.9g} m is inside the hub ({dims.d_hub:.9g} m)")
    if spec.criterion == Criterion.STRESS and checked is not None:
        for part in checked.parts:
            if part.stress > part.allowable * (1.0 + tol):
                found.append(
                    f"{part.part} stress {part.stress / 1e6:.9g} MPa > allowable "
                    f"{part.allowable / 1e6:.9g} MPa at r = {part.radius:.6g} m"
                )
    return found


def _check_unique(items, kind, cls):
    if type(items) not in (list, tuple) and (isinstance(items, (str, bytes)) or not isinstance(items, Sequence)):
        raise ValueError(f"{kind}s must be a sequence of {cls.__name__}, got {items!r}")
    if not items:
        raise ValueError(f"{kind}s must not be empty: give at least one {kind}")
    seen = set()
    for item in items:
        if not isinstance(item, cls):
            raise ValueError(f"{kind}s must hold {cls.__name__} objects, got {item!r}")
        if item.name in seen:
            raise ValueError(f"{kind} {item.name!r} is given twice")
        seen.add(item.name)


def design_flywheel(
    j_required: float,
    omega: float,
    shafts: Sequence[MountShaft],
    materials: Sequence[Material],
    spec: DesignSpec | None = None,
    *,
    solver_options: Mapping | None = None,
    method: str = "auto",
    torque: float | None = None,
    omega_mean: float | None = None,
    accept: Callable[[Candidate], str | None] | None = None,
) -> DesignResult:
    """Design the flywheel: the best material, shaft and dimensions.

    Parameters
    ----------
    j_required : float
        J_F, the flywheel inertia required at the reference shaft [kg*m^2],
        already net of the machine's own inertia J_c (docs/flywheel-design.md, section 5:
        J_F = A_max / (omega_m^2 delta) - J_c). J_F <= 0: no flywheel needed.
    omega : float
        Speed of the reference shaft at which the rim speed is checked
        [rad/s]: the highest speed of the cycle, ω_max = ω_m (1 + δ/2) (or
        the periodic solution's maximum), where the hoop stress peaks.
    shafts : sequence of MountShaft
        Where the flywheel may go; speed ratios relative to the reference.
    materials : sequence of Material
        Materials to consider.
    spec : DesignSpec, optional
        Geometry model, limits and objective (default: ``DesignSpec()``).
    solver_options : mapping, optional
        CasADi/IPOPT options merged over :data:`flyopt.design.nlp.DEFAULT_SOLVER_OPTIONS`; they
        act on the combinations IPOPT solves (all of them with method
        "ipopt", under "auto" only the structures the closed form does not
        cover).
    torque : float or None
        The largest torque the flywheel exchanges with the reference shaft
        over the cycle [N*m] (:meth:`flyopt.analysis.Analysis.flywheel_torque`);
        on a shaft of speed ratio r it is torque / r, or the shaft's own where it gives one (the train's forced
        response, :attr:`flyopt.design.spec.MountShaft.torque`). It bends the arms and
        loads the key; None when unknown (net areas): then the arms are
        checked for their centrifugal load only and the key is not checked.
    omega_mean : float or None
        The mean speed of the reference shaft [rad/s], at most ``omega``: the
        speed at which the courses' rim convention (criterion
        ``mean_rim_speed``) sizes the rim, which needs it; unused otherwise.
    accept : callable, optional
        A post-check of each feasible design, before it is ranked or bounds a pruning: None
        accepts it, a sentence makes that combination infeasible with the sentence as its
        reason (the mounting shaft's checks, :mod:`flyopt.design.shaft.check`, which are not
        rows of the NLP).
    method : {"auto", "ipopt", "closed_form"}
        How a feasible combination is optimized: the exact closed form of
        :mod:`flyopt.design.closed_form` where it covers the structure (mass and cost
        objectives) and IPOPT elsewhere ("auto", the default; for the
        timings see benchmarks/results/speed_error.md); IPOPT on every NLP
        ("ipopt"); or the closed form only, refusing a
        structure it does not cover ("closed_form"). Either way the design
        is verified against every constraint before it is reported.

    Returns
    -------
    DesignResult
        ``status`` "designed" (with ``best``), "infeasible" (no combination
        can give the inertia; every candidate says why) or "not_needed".

    Raises
    ------
    ValueError
        On invalid arguments; for the ``cost`` objective when a material has
        no cost.
    SolverFailed
        When IPOPT does not converge on a combination the closed form shows
        feasible (the message carries IPOPT's return status), or when a
        solved or closed-form design fails its verification against the
        constraints. A design is never made from a non-converged solve.

    Notes
    -----
    Every combination is decided: the closed-form :func:`flyopt.design.closed_form.max_inertia_one` proves
    infeasibility exactly (no NLP is solved then); every feasible combination
    is solved to optimality. Ranking is by the one rule of :mod:`flyopt.design.rank`.
    """
    j_required, omega, spec = _check_arguments(j_required, omega, shafts, materials, spec, method)
    textbook = [spec.textbook(bore_of(spec, shaft)) for shaft in shafts]
    closed = _closed_form_covers(spec, method, textbook)
    if j_required <= 0.0:
        return _not_needed(j_required, omega, spec)
    model = _textbook_model(spec, solver_options) if not closed and any(textbook) else None
    decided = _Decided()
    combos: dict[int, Combination] = {}
    for order, combo, plain in combinations(j_required, omega, omega_mean, torque, shafts, textbook, materials, spec):
        combos[order] = combo
        if plain:
            _decide_textbook(order, combo, spec, closed, model, decided)
        else:
            decided.whole.append((order, combo))
    if decided.pending:
        decided.feasible += _solve_closed_form(decided.pending, spec)
    if accept is not None:
        decided.feasible = _accepted(decided.feasible, accept, decided.infeasible)
    wheel_model = None
    names = {m.name: m.display_name for m in materials}
    if decided.whole:
        wheel_model = _design_wholes(
            decided.whole,
            spec,
            solver_options,
            method,
            decided.feasible,
            decided.infeasible,
            decided.pruned,
            names,
            accept,
        )
    ranked, infeasible, best = _rank(decided)
    description = _describe_model(spec, wheel_model if wheel_model is not None else model)
    result = _result(j_required, omega, spec, ranked, best, infeasible, decided, description, omega_mean, names)
    if spec.round_to and best is not None:
        order = next(o for o, c in decided.feasible if c is best)
        combo = Combination(**{**combos[order].__dict__, "n_arms": best.n_arms or 0})
        result = _rounded(result, combo, spec, solver_options, accept)
    return result


def _rounded(
    result: DesignResult,
    combo: Combination,
    spec: DesignSpec,
    solver_options: Mapping[str, Any] | None,
    accept: Callable[[Candidate], str | None] | None = None,
) -> DesignResult:
    """The result with its winner rounded to ``spec.round_to`` (:func:`flyopt.design.rounding.round_design`) and
    the continuous optimum kept beside it; "infeasible" when no wheel of the grid cell meets every limit.
    The rounded wheel passes ``accept`` (the post-check its continuous optimum passed) or is not the design."""
    from flyopt.design import rounding

    best = cast(Design, result.best)
    rounded, words = rounding.round_design(best, combo, spec, cast(float, spec.round_to), solver_options)
    refused = accept(rounded) if accept is not None and rounded is not None else None
    if refused:  # rounding moved a post-checked limit (the shaft's) past its bound: no rounded wheel
        rounded, words = None, f"the rounded wheel fails its post-check: {refused}"
    if rounded is None and not spec.round_strict:  # the default step: the continuous optimum stands, said so
        return dataclasses.replace(
            result,
            rounding=f"NOT rounded ({words}): the continuous optimum is the design; give design.round_to "
            "a coarser step, or round_to = false to ask for the continuous optimum",
        )
    if rounded is None:
        return dataclasses.replace(
            result,
            status="infeasible",
            message=f"{result.message}; but {words}",
            best=None,
            continuous=best,
            rounding=words,
        )
    candidates = tuple(rounded if c is best else c for c in result.candidates)
    names = result.material_names
    message = result.message.replace(_design_words(best, spec, names), _design_words(rounded, spec, names), 1)
    return dataclasses.replace(
        result, message=message, best=rounded, candidates=candidates, continuous=best, rounding=words
    )


def _check_arguments(
    j_required: float,
    omega: float,
    shafts: Sequence[MountShaft],
    materials: Sequence[Material],
    spec: DesignSpec | None,
    method: str,
) -> tuple[float, float, DesignSpec]:
    """Check the arguments of :func:`design_flywheel`; return J_F, omega and the spec (default filled in).

    Raises ValueError naming the bad argument and what is allowed.
    """
    j_required = finite(j_required, "j_required [kg*m^2]")
    omega = positive(omega, "omega [rad/s]")
    _check_unique(shafts, "shaft", MountShaft)
    _check_unique(materials, "material", Material)
    if spec is None:
        spec = DesignSpec()
    if not isinstance(spec, DesignSpec):
        raise ValueError(f"spec must be a DesignSpec, got {spec!r}")
    if spec.objective == Objective.COST:
        missing = [m.name for m in materials if m.cost is None]
        if missing:
            raise ValueError(f"objective 'cost' needs a cost per kg on every material; missing for {missing}")
    choice(method, Method, "method")
    return j_required, omega, spec


def _closed_form_covers(spec: DesignSpec, method: str, textbook: Sequence[bool]) -> bool:
    """Whether the exact closed form designs the feasible combinations (else IPOPT does).

    Only when every shaft carries the textbook design and the method allows it; ``method``
    "closed_form" on a structure the closed form does not cover raises ValueError.
    """
    closed = False
    if method != Method.IPOPT and all(textbook):
        closed = closed_form.covers(spec.geometry, spec.objective, spec.pins_d_mean)
        if method == Method.CLOSED_FORM and not closed:
            raise ValueError(
                f"the closed form does not cover geometry {spec.geometry!r} with objective "
                f"{spec.objective!r}; use method 'auto' or 'ipopt'"
            )
    return closed


def _not_needed(j_required: float, omega: float, spec: DesignSpec) -> DesignResult:
    """The result when J_F <= 0: the machine keeps the fluctuation within delta without a flywheel (its own inertia,
    nothing fluctuating, or torques that hold the speed by falling with it)."""
    return DesignResult(
        status="not_needed",
        message=said(
            "no flywheel needed: the required flywheel inertia J_F = {j} is not positive: the machine keeps the "
            "speed fluctuation within delta without one",
            j=(j_required, "inertia", f"{_g(j_required)} kg·m²"),
        ),
        j_required=j_required,
        omega=omega,
        spec=spec,
    )


def _textbook_model(spec: DesignSpec, solver_options: Mapping | None) -> Any:
    """The cached NLP of :mod:`flyopt.design.nlp` for the textbook combinations IPOPT solves."""
    from flyopt.design import nlp  # CasADi only when IPOPT is asked for

    structure = nlp.ModelStructure(
        geometry=spec.geometry,
        pinned=spec.pins_d_mean,
        collapsed=spec.geometry != Geometry.DISC and spec.hb_ratio[0] == spec.hb_ratio[1],
        objective="outer_diameter" if spec.objective == Objective.OUTER_DIAMETER else "mass",
    )
    return nlp.get_model(structure, solver_options)


def combinations(
    j_required: float,
    omega: float,
    omega_mean: float | None,
    torque: float | None,
    shafts: Sequence[MountShaft],
    textbook: Sequence[bool],
    materials: Sequence[Material],
    spec: DesignSpec,
) -> Iterator[tuple[int, Combination, bool]]:
    """Every material x shaft combination in input order: (order, combination, textbook design?).

    Each carries its shaft's speed, the inertia required on that shaft (J_F / r^2), the material's safe
    rim speed and the outer-diameter cap it sets (with the envelope), the bore and the peak torque on
    that shaft (:func:`shaft_torque_of`). A generator, so that each combination is decided before the next is built.

    Under the courses' rim convention (criterion mean_rim_speed) the rim supplies ``spec.rim_share`` of
    J_F, nothing caps its outer diameter but the envelope, and its mean diameter is pinned where the rim
    reaches v_max at the shaft's mean speed, D_m = 2 v_max / omega'_mean (or at a given d_mean that is
    no larger).
    """
    envelope = spec.max_outer_diameter
    by_speed = spec.criterion == Criterion.RIM_SPEED
    book = spec.by_mean_rim_speed
    if (book or spec.rim_speed is not None) and (omega_mean is None or not 0.0 < omega_mean <= omega):
        what = "criterion 'mean_rim_speed'" if book else "a given rim_speed"
        raise ValueError(f"{what} needs the mean speed omega_mean in (0, omega], got {omega_mean!r}")
    j_required *= spec.rim_share
    # what depends on the shaft alone, once per shaft (not once per material and shaft)
    per_shaft = [
        (
            shaft,
            plain,
            omega * shaft.speed_ratio,
            inertia_on_shaft(j_required, shaft.speed_ratio),
            bore_of(spec, shaft),
            shaft_torque_of(torque, shaft),
        )
        for shaft, plain in zip(shafts, textbook)
    ]
    order = 0
    for material in materials:
        v_max = rim_speed_limit(material, spec)
        for shaft, plain, shaft_omega, j_shaft, bore, shaft_torque in per_shaft:
            cap_speed = geometry.outer_diameter_for_rim_speed(v_max, shaft_omega) if by_speed else math.inf
            cap_mean = (
                geometry.outer_diameter_for_rim_speed(v_max, cast(float, omega_mean) * shaft.speed_ratio)
                if book
                else math.inf
            )
            combo = Combination(
                material=material,
                shaft=shaft,
                omega=shaft_omega,
                j_shaft=j_shaft,
                j_reference=j_required,
                cap_speed=cap_speed,
                cap=min(cap_speed, envelope),
                bore=bore,
                torque=shaft_torque,
                v_max=v_max,
                d_mean=_pinned_mean_diameter(spec, cap_mean, omega_mean, shaft.speed_ratio),
                cap_mean=cap_mean,
            )
            yield order, combo, plain
            order += 1


def shaft_torque_of(torque: float | None, shaft: MountShaft) -> float:
    """The peak torque [N*m] a wheel on ``shaft`` is designed at (its arms, its hub's length, its key): the
    shaft's own where its drive train is modelled (:attr:`flyopt.design.spec.MountShaft.torque`, the train's
    forced response J_w theta''_w, the torque the shaft's post-check checks the key at), else the rigid body's
    ``torque`` / r (``torque`` at the reference shaft); 0 where neither is known (net areas).

    The arms take the same torque as the key: the wheel turns as one body (its rim and hub at the same theta''_w),
    so the rim's share of J_w theta''_w that the arms carry is the share of the rigid body's torque they carried
    (docs/flywheel-design.md, section 26)."""
    if shaft.torque is not None:
        return shaft.torque
    return torque / shaft.speed_ratio if torque else 0.0


def _pinned_mean_diameter(spec: DesignSpec, cap_mean: float, omega_mean: float | None, ratio: float) -> float | None:
    """A combination's pinned D_m [m]: a given d_mean, the courses' D_m (``cap_mean``) under criterion mean_rim_speed,
    or where a given rim_speed is reached at the shaft's mean speed, 2 v / (ω_m i); None when free."""
    if spec.d_mean is not None:
        return spec.d_mean
    if spec.by_mean_rim_speed:
        return cap_mean
    if spec.rim_speed is not None:
        return geometry.outer_diameter_for_rim_speed(spec.rim_speed, cast(float, omega_mean) * ratio)
    return None


@dataclass
class _Decided:
    """The combinations as they are decided, each keyed by its input order for the ranking."""

    feasible: list[tuple[int, Design]] = field(default_factory=list)
    infeasible: list[tuple[tuple[int, int], Candidate]] = field(default_factory=list)  # key: (order, arm index)
    pending: list[tuple[int, Combination]] = field(default_factory=list)  # feasible, for the closed form
    whole: list[tuple[int, Combination]] = field(default_factory=list)  # whole wheels, designed last
    pruned: list[Candidate] = field(default_factory=list)


def _decide_textbook(
    order: int, combo: Combination, spec: DesignSpec, closed: bool, model: Any, decided: _Decided
) -> None:
    """Decide one textbook combination: prove it infeasible, or design it (IPOPT now, the closed form later).

    The exact bound :func:`flyopt.design.closed_form.max_inertia_one` sets ``combo.j_max``; a combination
    whose pinned mean diameter fits under its cap and whose required inertia is within the bound is
    feasible: it is solved by IPOPT on ``model`` at once or, when ``closed``, queued in ``decided.pending``
    for the closed form. Otherwise it is infeasible, with the reason in numbers.
    """
    material = combo.material
    pin = combo.d_mean
    combo.j_max = closed_form.max_inertia_one(
        spec.geometry, material.density, combo.cap, spec.hb_ratio, spec.max_width, pin
    )[0]
    pinned_fits = pin is None or (
        (pin <= combo.cap if spec.geometry == Geometry.DISC else pin < combo.cap) and pin <= combo.cap_mean
    )
    if pinned_fits and combo.j_shaft <= combo.j_max:
        if closed:
            decided.pending.append((order, combo))
        else:
            from flyopt.design import nlp  # CasADi only when IPOPT is asked for

            decided.feasible.append(
                (order, _candidate_from_design(combo, spec, *nlp.solve_combination(model, combo, spec)))
            )
        return
    explain = functools.partial(_explained, combo, spec)
    decided.infeasible.append(
        ((order, 0), Candidate.explained_when_read(material.name, combo.shaft, spec.geometry, explain))
    )


def _explained(combo: Combination, spec: DesignSpec) -> dict[str, Any]:
    """An infeasible textbook combination's reason and limits (the outer-diameter cap it needs among them), made
    when first read (:meth:`flyopt.design.result.Candidate.explained_when_read`)."""
    reason, needed = _explain_infeasible(combo, spec)
    return {"reason": reason, "limits": _limits(combo, j_max=combo.j_max, d_outer_needed=needed)}


def _limits(combo: Combination, **found: Any) -> Limits:
    """What a combination was designed against (the inertia on its shaft, its outer-diameter cap, its rim speed
    limit), with what its design or its explanation ``found`` (the largest inertia it can give, what binds, the
    cap it needs)."""
    return Limits(j_required_on_shaft=combo.j_shaft, d_outer_limit=combo.cap, rim_speed_limit=combo.v_max, **found)


def _rank(decided: _Decided) -> tuple[tuple[Candidate, ...], list[Candidate], Design | None]:
    """The candidates in reported order, the infeasible ones in input order, and the best design (None: none).

    Feasible ones by the one rule of :func:`flyopt.design.rank.ranking`, then the pruned ones by their
    objective bound, then the infeasible ones in input order.
    """
    infeasible = [c for _, c in sorted(decided.infeasible, key=lambda item: item[0])]  # in input order
    designs = rank.ranking([c for _, c in decided.feasible])
    ranked = (
        tuple(designs)
        + tuple(sorted(decided.pruned, key=lambda c: cast(float, c.provenance.objective_bound)))  # it has its bound
        + tuple(infeasible)
    )
    return ranked, infeasible, (designs[0] if designs else None)


def _describe_model(spec: DesignSpec, model: Any) -> dict[str, Any]:
    """The description of the optimization model used (the last one built), for the report.

    ``model`` is the whole-wheel or textbook NLP model, or None when only the closed form was used.
    """
    if model is not None:
        description = model.describe()
    else:
        description = {
            "geometry": spec.geometry,
            "inertia_model": geometry.GEOMETRIES[spec.geometry],
            "variables": [],
            "constraints": [],
            "pinned": ["d_mean"] if spec.pins_d_mean else [],
            "formulation": (
                "exact closed form (flyopt.design.closed_form): outer diameter at its cap, "
                "a 1-D monotone root for the rim; verified against every constraint"
            ),
        }
    description["objective"] = spec.objective
    description["criterion"] = spec.criterion
    bounds = []
    if spec.max_width < math.inf:
        bounds.append("max_width: B <= max_width")
    if spec.geometry == Geometry.DISC and spec.d_mean is None:
        bounds.append("outer_diameter: D <= min(2 v_max/omega', max_outer_diameter)")
    if spec.geometry != Geometry.DISC and spec.pins_d_mean:
        bounds.append("outer_diameter and inner_diameter: H <= min(cap - D_m, D_m)")
    if spec.by_mean_rim_speed:
        bounds.append("mean_rim_speed: D_m = 2 v_max / omega'_mean (or a given D_m at most that)")
    description["bounds"] = bounds
    limits = spec.to_dict()
    description["limits"] = {
        name: limits[name]
        for name in ("max_outer_diameter", "max_width", "hb_ratio", "d_mean", "rim_speed", "rim_share")
    }
    return description


def _design_words(best: Design, spec: DesignSpec, names: Mapping[str, str]) -> str:
    """The design in the result's message: its material on its shaft, its outer diameter, width and mass."""
    return (
        f"{names.get(best.material, best.material)} on the {shaft_label(best.shaft)}: {spec.geometry} "
        f"D_outer {_g(best.dims.d_outer)} m, B {_g(best.dims.b)} m, mass {_g(best.mass)} kg"
    )


def _result(
    j_required: float,
    omega: float,
    spec: DesignSpec,
    ranked: tuple[Candidate, ...],
    best: Design | None,
    infeasible: Sequence[Candidate],
    decided: _Decided,
    description: dict[str, Any],
    omega_mean: float | None = None,
    material_names: Mapping[str, str] | None = None,
) -> DesignResult:
    """The DesignResult: "designed" with the best candidate, or "infeasible" with every reason."""
    names = dict(material_names or {})
    if best is None:
        status = "infeasible"
        message = infeasible_message(infeasible)
    else:
        status = "designed"
        message = (
            f"{_design_words(best, spec, names)} ({len(decided.feasible)} of {len(ranked)} combinations "
            f"feasible"
            + (f", {len(decided.pruned)} not designed: a bound shows they cannot win" if decided.pruned else "")
            + ")"
        )
    return DesignResult(
        status=status,
        message=message,
        j_required=j_required,
        omega=omega,
        spec=spec,
        best=best,
        candidates=ranked,
        model=description,
        omega_mean=omega_mean,
        material_names=names,
    )
