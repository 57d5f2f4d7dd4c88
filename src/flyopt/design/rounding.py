"""The winning wheel rounded to a manufacturing step, every limit checked again on the rounded wheel.

Issue 28, item 2 (first part). A shop works to whole millimetres (or
another step): :func:`round_design` puts each free dimension of the
continuous optimum on the step below or above it and keeps the best wheel
that meets every limit the continuous one was designed to, checked by the
same rules:

- a bare wheel (``rim``, ``thin_rim``, ``disc``) by
  :func:`flyopt.design.check.violations` (inertia, outer-diameter cap,
  width, H/B, a positive inner diameter), the rule every bare design is
  verified by, and the courses' cap on D_m where it applies;
- a whole wheel by the rows and bounds of its own NLP
  (:func:`flyopt.design.wheel_nlp.formulate`, ``variable_bounds``,
  ``row_bounds``: inertia, envelope, rim speed, width, H/B, the rim
  clearing the hub, web and arm proportions, hub wall and the hub's range,
  the minimum wall), and under the stress criterion by the exact strength
  check (:func:`flyopt.design.strength.check_wheel`) every design is
  verified by.

The bore (the shaft seat) is not rounded: it is the shaft's. A pinned mean
diameter (given, or set by a rim speed) stays as pinned; the rim's
thickness and width are rounded around it. What rounding cost is the
rounded wheel's objective against the continuous one's. A bare wheel's
rounded form is the best corner of the optimum's grid cell (2^n wheels),
or where none meets every limit the best wheel within two steps (4^n, at
most :data:`MAX_WHEELS`). A whole wheel's dimensions are coupled (arms
that fit the hub, a web below the rim): each in turn is rounded down and
up with the others optimized again around it by the wheel's NLP, and the
lighter kept (round, fix, re-optimize what is left). Either is a search
near the optimum, not an optimization over the whole grid.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Mapping
from typing import Any

from flyopt.design import check, preferred, wheel, wheel_design
from flyopt.design.combination import Combination
from flyopt.design.result import Design, Dimensions, Provenance
from flyopt.design.spec import DesignSpec
from flyopt.names import Criterion, Geometry, Objective

__all__ = ["round_design", "grid_values"]

#: Relative slack of a dimension already on the step (round-off of the solve): it is not moved.
ON_GRID = 1e-9


def grid_values(value: float, step: float, reach: int = 1) -> tuple[float, ...]:
    """The positive multiples of ``step`` within ``reach`` steps below and above ``value`` [m] (``value`` itself,
    reach 1, when it is on the grid)."""
    k = value / step
    nearest = round(k)
    if abs(k - nearest) <= ON_GRID * max(abs(k), 1.0):
        low, high = nearest - (reach - 1), nearest + (reach - 1)
    else:
        low, high = math.floor(k) - (reach - 1), math.floor(k) + reach
    return tuple(j * step for j in range(low, high + 1) if j > 0)


#: The dimensions a preferred-number series rounds (design.diameter_series): the outer and hub diameters.
SERIES_DIMENSIONS = ("d_outer", "d_hub")


def _grid(spec: DesignSpec, step: float) -> Any:
    """The values a dimension may round to, ``grid(name, value, reach=1)``: the step's multiples
    (:func:`grid_values`), or for a diameter the scene's preferred-number series (:data:`SERIES_DIMENSIONS`)."""

    def grid(name: str, value: float, reach: int = 1) -> tuple[float, ...]:
        if spec.diameter_series and name in SERIES_DIMENSIONS:
            return preferred.series_values(value, spec.diameter_series, reach)
        return grid_values(value, step, reach)

    return grid


#: Most NLP solves one order of a whole wheel's rounding makes (each dimension rounded with the rest optimized
#: again, backing up where a dimension leaves no wheel on either side): about 0.5 s of solves on this machine.
MAX_SOLVES = 24

#: Most wheels one rounding checks: the grid cell's corners, then (when none meets every limit) two steps out.
MAX_WHEELS = 4096


def _free_values(design: Design, names: tuple[str, ...], pinned: bool) -> dict[str, float]:
    """The dimensions rounding may move, by name, from the continuous design [m]; a pinned D_m keeps D_outer
    = D_m + H out of them (it follows H)."""
    return {n: float(getattr(design.dims, n)) for n in names if not (pinned and n == "d_outer")}


def _bare_dims(design: Design, values: dict[str, float], disc: bool) -> wheel.Dims:
    """A bare wheel's Dims (a disc's H is its radius, as the designer writes it)."""
    d_outer = values.get("d_outer", design.dims.d_mean + values.get("h", design.dims.h))
    h = d_outer / 2.0 if disc else values["h"]
    return wheel.Dims(d_outer=d_outer, h=h, b=values["b"])


def _bare_violations(dims: wheel.Dims, j_wheel: float, combo: Combination, spec: DesignSpec) -> list[str]:
    """The limits a rounded bare wheel breaks, by the rule bare designs are verified by."""
    disc = spec.geometry == Geometry.DISC
    d_inner = 0.0 if disc else float(dims.d_inner)
    hb = 1.0 if disc else dims.h / dims.b
    low, high = (1.0, 1.0) if disc else spec.hb_ratio
    found = check.violations(
        spec.geometry, j_wheel, combo.j_shaft, dims.d_outer, d_inner, dims.b, hb, combo.cap, spec.max_width, low, high
    )
    if not disc and float(dims.d_mean) > combo.cap_mean * (1.0 + check.VERIFY_RTOL):
        found.append(f"mean diameter {float(dims.d_mean):.9g} > {combo.cap_mean:.9g} m (mean_rim_speed)")
    return found


def _whole_violations(
    dims: wheel.Dims, combo: Combination, spec: DesignSpec, rows: Any, structure: Any, problem: Any
) -> list[str]:
    """The limits a rounded whole wheel breaks: its NLP's own rows and bounds, and the exact strength check."""
    from flyopt.design import strength, wheel_nlp

    names = wheel_nlp.variables_of(structure)
    values = {n: float(getattr(dims, n)) for n in names}
    x = [math.log(values[n]) for n in names]
    lbx, ubx, _ = wheel_nlp.variable_bounds(structure, problem)
    tol = check.VERIFY_RTOL
    found = [
        f"{n} {values[n]:.9g} m outside its bounds"
        for n, xi, lo, hi in zip(names, x, lbx, ubx, strict=True)
        if xi < lo - tol or xi > hi + tol
    ]
    p = [problem.omega, problem.density, problem.poisson, problem.torque, problem.bore, 1.0]
    p.append(math.log(problem.omega / 2.0))
    allow = [math.inf] * len(wheel_nlp.stressed_parts(structure))  # stresses: by the exact check below
    g = rows["function"](x, p + allow).full().ravel()
    lbg, ubg = wheel_nlp.row_bounds(structure, rows["names"], problem)
    for name, value, lo, hi in zip(rows["names"], g, lbg, ubg, strict=True):
        if name.startswith("stress_"):
            continue
        if value < lo - tol * max(1.0, abs(lo)) or value > hi + tol * max(1.0, abs(hi)):
            found.append(f"{name} ({value:.9g} outside [{lo:.9g}, {hi:.9g}])")
    if spec.criterion == Criterion.STRESS:
        checked = strength.check_wheel(
            combo.material,
            spec.geometry,
            dims,
            combo.omega,
            combo.torque,
            spec.safety_factor,
            combo.stress_factors(spec),
        )
        found += [
            f"{part.part} stress {part.stress / 1e6:.9g} MPa > allowable {part.allowable / 1e6:.9g} MPa"
            for part in checked.parts
            if part.stress > part.allowable * (1.0 + tol)
        ]
    return found


_ROWS: dict[Any, dict[str, Any]] = {}


def _row_function(structure: Any) -> dict[str, Any]:
    """The rows g(x, p) of a whole wheel's NLP as a CasADi Function, once per structure."""
    if structure not in _ROWS:
        import casadi as ca

        from flyopt.design import wheel_nlp

        names = wheel_nlp.variables_of(structure)
        x = ca.SX.sym("x", len(names))
        p = ca.SX.sym("p", len(wheel_nlp.PARAMETERS))
        allow = ca.SX.sym("allow", len(wheel_nlp.stressed_parts(structure)))
        form = wheel_nlp.formulate(structure, x, {name: p[k] for k, name in enumerate(wheel_nlp.PARAMETERS)}, allow)
        function = ca.Function("rounded_rows", [x, ca.vertcat(p, allow)], [ca.vertcat(*form.rows)])
        _ROWS[structure] = {"function": function, "names": form.row_names}
    return _ROWS[structure]


def round_design(
    design: Design,
    combo: Combination,
    spec: DesignSpec,
    step: float,
    solver_options: Mapping[str, Any] | None = None,
) -> tuple[Design | None, str]:
    """The best wheel on the ``step`` grid near ``design`` that meets every limit, and what was done, in words.

    A bare wheel: the best of the wheels on the grid around the optimum (:func:`_round_bare`). A whole wheel:
    each dimension in turn rounded down and up with the others optimized again around it by the wheel's NLP
    (IPOPT, its status checked), the lighter kept (:func:`_round_whole`); the wheel so made is checked
    against every limit at its exact grid values.

    Parameters
    ----------
    design : Design
        The continuous optimum of ``combo`` (its material, shaft and arm count).
    combo : Combination
        The combination it was designed as (``combo.n_arms`` its arm count).
    spec : DesignSpec
    step : float
        The manufacturing step [m], e.g. 0.001.
    solver_options : mapping or None
        The solver options the continuous optimum was designed with: its re-solves use the same.

    Returns
    -------
    (Design or None, str)
        The rounded design (None when no wheel near the optimum meets every limit) and a sentence saying
        what rounding did or why it found no wheel.
    """
    bore = design.bore or 0.0
    if spec.textbook(bore):
        found, words = _round_bare(design, combo, spec, step)
    else:
        found, words = _round_whole(design, combo, spec, step, bore, solver_options)
    on = f"the {step * 1e3:g} mm grid" + (f" (diameters on {spec.diameter_series})" if spec.diameter_series else "")
    if found is None:
        hint = (
            f"; H/B is fixed at {spec.hb_ratio[0]:g} (hb_ratio): a range lets the rounded rim keep it nearly"
            if spec.hb_ratio[0] == spec.hb_ratio[1] and spec.geometry != Geometry.DISC
            else ""
        )
        return None, f"no wheel near the optimum on {on} meets every limit: {words}{hint}"
    objective, dims, mass, j_wheel = found
    if spec.diameter_series:
        words += f"; the diameters on ISO 3's {spec.diameter_series} series"
    return _rounded_design(design, combo, spec, dims, mass, j_wheel, objective), words


Found = tuple[float, wheel.Dims, float, float]  # (objective, dims, mass [kg], J [kg*m^2])


def _measure(dims: wheel.Dims, combo: Combination, spec: DesignSpec) -> Found:
    """A wheel's objective, dims, mass and inertia, by the parts every design is measured by."""
    parts = wheel.parts(spec.geometry, dims, combo.material.density)
    mass, j_wheel = float(wheel.wheel_mass(parts)), float(wheel.wheel_inertia(parts))
    cost = mass * combo.material.cost if combo.material.cost is not None else None
    return _objective(spec, mass, float(dims.d_outer), cost), dims, mass, j_wheel


def _round_bare(design: Design, combo: Combination, spec: DesignSpec, step: float) -> tuple[Found | None, str]:
    """The best bare wheel on the grid cell around the optimum (2^n wheels), or within two steps (4^n, at most
    :data:`MAX_WHEELS`) where none of the cell meets every limit."""
    disc = spec.geometry == Geometry.DISC
    names = ("d_outer", "b") if disc else ("d_outer", "h", "b")
    free = _free_values(design, names, spec.pins_d_mean and not disc)
    grid = _grid(spec, step)
    best: Found | None = None
    tried = 0
    for reach in (1, 2):
        grids = [grid(n, v, reach) for n, v in free.items()]
        if best is not None or (reach > 1 and math.prod(len(g) for g in grids) > MAX_WHEELS):
            break
        for corner in itertools.product(*grids):
            tried += 1
            found = _measure(_bare_dims(design, dict(zip(free, corner, strict=True)), disc), combo, spec)
            if not _bare_violations(found[1], found[3], combo, spec) and (best is None or found[0] < best[0]):
                best = found
    return best, f"{len(free)} dimensions rounded ({tried} wheels on the grid checked)"


def _round_whole(
    design: Design,
    combo: Combination,
    spec: DesignSpec,
    step: float,
    bore: float,
    solver_options: Mapping[str, Any] | None = None,
) -> tuple[Found | None, str]:
    """The better of two searches: the corners of the optimum's grid cell (2^n wheels, each checked against every
    limit), and each free dimension in turn rounded down and up with the others optimized again around it."""
    from flyopt.design import wheel_nlp
    from flyopt.errors import SolverFailed

    structure, problem = wheel_design.wheel_problem(
        combo.material, spec, bore, combo.torque, combo.n_arms, combo.j_shaft, combo.omega, combo.v_max
    )
    names = wheel_nlp.variables_of(structure)
    rows = _row_function(structure)
    grid = _grid(spec, step)
    current = _free_values(design, names, spec.pins_d_mean)

    def on_grid(values: dict[str, float]) -> wheel.Dims:
        if spec.pins_d_mean:
            values = {**values, "d_outer": float(design.dims.d_mean) + values["h"]}
        return wheel_nlp.dims_of(structure, values, bore)

    corner_best: Found | None = None
    corners = list(itertools.product(*(grid(n, v) for n, v in current.items())))
    for corner in corners:
        dims = on_grid(dict(zip(current, corner, strict=True)))
        found = _measure(dims, combo, spec)
        if (corner_best is None or found[0] < corner_best[0]) and not _whole_violations(
            dims, combo, spec, rows, structure, problem
        ):
            corner_best = found
    # two orders: the thinnest first (a step moves it most), and the outer diameter first (where the stress
    # and the inertia both bind, only the diameter trades one for the other: fixed last, neither side of it
    # may meet both, while fixed first the thinner sections round up around it)
    thinnest = sorted(current, key=current.__getitem__)
    orders = [thinnest] + ([["d_outer"] + [n for n in thinnest if n != "d_outer"]] if "d_outer" in current else [])
    solves, budget = 0, MAX_SOLVES

    def options(
        fixed: dict[str, float], name: str, values: tuple[float, ...], around: dict[str, float]
    ) -> list[tuple[float, float, dict]]:
        """The wheels with ``name`` at each of ``values`` and the rest optimized again from ``around`` (the wheel
        the level above solved: a warm start, where a cold one may stop locally infeasible), lightest first."""
        nonlocal solves
        found = []
        for value in values:
            if solves >= budget:
                break
            solves += 1
            try:
                dims, _solution, _checked = wheel_design.design_combination(
                    combo,
                    spec,
                    bore,
                    combo.torque,
                    combo.n_arms,
                    solver_options,
                    method="ipopt",
                    fixed={**fixed, name: value},
                    start=around,
                )
            except (wheel_design.NoWheel, SolverFailed):
                continue  # no wheel with this dimension here: another value may have one
            found.append((_measure(dims, combo, spec)[0], value, {n: float(getattr(dims, n)) for n in current}))
        return sorted(found, key=lambda o: o[0])

    def descend(order: list[str], fixed: dict[str, float], level: int, around: dict[str, float]) -> Found | None:
        """Round ``order[level:]`` in turn, the lightest choice first; where a dimension leaves no wheel on
        either side, back up and take the level above's next choice (then two steps out)."""
        if level == len(order):
            dims = on_grid(dict(fixed))
            return (
                None if _whole_violations(dims, combo, spec, rows, structure, problem) else _measure(dims, combo, spec)
            )
        name = order[level]
        near = grid(name, around[name])
        far = tuple(v for v in grid(name, around[name], reach=2) if v not in near)
        for values in (near, far):
            for _objective_value, value, solved in options(fixed, name, values, around):
                found = descend(order, {**fixed, name: value}, level + 1, {**solved, **fixed, name: value})
                if found is not None:
                    return found
        return None

    sequential: Found | None = None
    for k, order in enumerate(orders):
        budget = MAX_SOLVES * (k + 1)  # each order its own share of the solves
        this = descend(order, {}, 0, current)
        if this is not None and (sequential is None or this[0] < sequential[0]):
            sequential = this
    words = (
        f"{len(current)} dimensions rounded: the {len(corners)} corners of the optimum's grid "
        f"cell, and each dimension rounded in turn with the rest optimized again ({solves} solves)"
    )
    best = corner_best
    if sequential is not None and (best is None or sequential[0] < best[0]):
        best = sequential
    return best, words


def _objective(spec: DesignSpec, mass: float, d_outer: float, cost: float | None) -> float:
    if spec.objective == Objective.COST and cost is not None:
        return cost
    return d_outer if spec.objective == Objective.OUTER_DIAMETER else mass


def _rounded_design(
    design: Design,
    combo: Combination,
    spec: DesignSpec,
    dims: wheel.Dims,
    mass: float,
    j_wheel: float,
    objective: float,
) -> Design:
    """The continuous design's record at the rounded dimensions: its mass, inertia, parts and stresses anew."""
    material = combo.material
    structure = wheel_design.structure_fields(
        material,
        spec.geometry,
        dims,
        combo.omega,
        combo.torque,
        spec,
        dims.bore or 0.0,
        None,
        combo.stress_factors(spec),
    )
    bare_disc = spec.geometry == Geometry.DISC and spec.textbook(float(dims.bore or 0.0))
    h = float(dims.h)

    def dim(name: str) -> float | None:
        value = float(getattr(dims, name))
        return value if value else None

    return dataclasses.replace(
        design,
        reason=f"{combo.label}: rounded; every limit checked again",
        mass=mass,
        cost=mass * material.cost if material.cost is not None else None,
        j_flywheel=j_wheel,
        j_at_reference=j_wheel * combo.shaft.speed_ratio**2,
        objective=objective,
        dims=Dimensions(
            d_mean=float(dims.d_outer) / 2.0 if bare_disc else float(dims.d_mean),  # as the designer writes them
            d_outer=float(dims.d_outer),
            d_inner=max(float(dims.d_inner), 0.0),
            h=h,
            b=float(dims.b),
            t_web=dim("t_web"),
            d_hub=dim("d_hub"),
            l_hub=dim("l_hub"),
            arm_major=dim("arm_major"),
        ),
        parts=structure.parts,
        stresses=structure.stresses,
        # what drives the design is the continuous optimum's: its binding limits and their sensitivities
        # (a wheel on the grid sits on none of them exactly)
        limits=dataclasses.replace(
            design.limits,
            j_required_on_shaft=combo.j_shaft,
            d_outer_limit=combo.cap,
            rim_speed_limit=combo.v_max,
            castability=structure.castability,  # the rules, and what the rounded wheel has
        ),
        provenance=Provenance(solver_status="rounded", iterations=0, solve_time=0.0, notes=structure.notes),
    )
