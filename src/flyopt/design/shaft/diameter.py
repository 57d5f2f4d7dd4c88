"""The seat diameter of a described shaft: the NLP's d* rounded up, then the series walk (issue 30, item 5; docs
section 26).

A ``[[shaft]]`` whose seat step says ``diameter = "design"`` leaves its diameter d
to the design. For each combination (material, shaft, arms) the seat's NLP
(:mod:`flyopt.design.shaft.seat_nlp`: the wheel and d in one NLP with the shaft's
smooth rows, fatigue, yield and slope) gives a continuous d*; d is then the
SMALLEST value of an ISO 3 preferred-number series (:mod:`flyopt.design.preferred`,
R40 by default), from the first at or above d*, at which the wheel designed on that
bore (its hub and DIN 6885-1 key follow d) passes every limit of its shaft
(:func:`flyopt.design.shaft.check.check_shaft` with the wheel's mass, inertia and
width): the wheel depends on d and the check on the wheel, so each d is a consistent
pair by construction.

The walk is outside the NLP: the post-check's lateral critical speed is a beam-FE
eigenvalue and feasibility need not be monotone in d (a torsional mode can cross an
order as the shaft stiffens), so the series is walked upwards and the first d that
passes is taken. It never starts below a lower bound: the DE-Goodman factor at the
keyseat of the seat (Shigley 9th ed. Eq. (7-7)) with the torque alone,
A = sqrt(3) K_fs T_a and B = 0, is an upper bound on the factor of any wheel on that
seat (A and B only grow with the bending and the midrange torque, and T_a with the
wheel's inertia, which is at least the required one); Eq. (7-8) gives the d where it
equals the factor required, below which fatigue must fail. Where the NLP gives no d*
the walk starts there. The series is capped at the range the checks support: the
Marin size factor's 2.79-254 mm (Shigley Eq. (6-20)) and the DIN 6885-1 key table
(over 6 up to 260 mm).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flyopt.design import key, preferred, rank
from flyopt.design.result import infeasible_message
from flyopt.design.shaft import strength
from flyopt.design.shaft.check import CRITERION, notch_factors
from flyopt.design.shaft.cycle import ShaftContext, acceptor, keyed_shafts, rekeyed, torque_curve
from flyopt.names import Geometry
from flyopt.said import join, removeprefix, said, said_by

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.design.result import Candidate, DesignResult
    from flyopt.design.spec import DesignSpec, MountShaft
    from flyopt.machine.shaft_layout import ShaftLayout

__all__ = ["SeatFloor", "seat_series", "seat_floor", "designs_seats", "design_with_seats", "seated", "on_seat"]


def _mm(d: float, digits: str = "g") -> tuple[float, str, str]:
    """A seat diameter [m] as a sentence's quantity, written in mm as the walk always wrote it."""
    return (d, "length", f"{d * 1e3:{digits}} mm")


@functools.lru_cache(maxsize=8)
def seat_series(series: str = "R40") -> tuple[float, ...]:
    """The seat diameters [m] of an ISO 3 series the design may choose, ascending: those inside both the Marin
    size factor's range (Shigley Eq. (6-20): 2.79-254 mm) and the DIN 6885-1 key table (d_over < d <= d_up_to)."""
    sizes = strength._data()["size"]["mm"]
    keys = key.key_table()
    low, high = sizes[0][0] * strength.MM, sizes[-1][1] * strength.MM
    values = []
    for k in range(0, 4):  # 1 mm to 9.5 m in mm: the decades the range can touch
        for m in preferred.mantissas(series):
            d = round(m * 10.0**k, 9) / 1000.0  # mm to m: 63 mm is the double nearest 0.063
            if keys[0].d_over < d <= keys[-1].d_up_to and low <= d <= high:
                values.append(d)
    return tuple(sorted(values))


@dataclass(frozen=True)
class SeatFloor:
    """Where the search for a designed seat starts and ends.

    Attributes
    ----------
    torque_alternating : float
        T_a of the least wheel (the required inertia on the shaft) [N*m].
    diameter : float
        The first series value whose keyseat passes the torque-only DE-Goodman factor [m] (nan: none).
    bound : float
        Eq. (7-8)'s d at that value's S_e, S_ut and K_fs (or at the last value tried) [m] (0 without torque).
    seats : tuple of float
        The series values the search may try, ascending [m]: from ``diameter`` up to the last one the shaft's
        material and the fits support.
    cap : str or None
        Why the series ends before the range of :func:`seat_series` (the material's strength table, Neuber's
        range), or None.
    """

    torque_alternating: float
    diameter: float
    bound: float
    seats: tuple[float, ...] = ()
    cap: str | None = None


def seat_floor(ctx: ShaftContext, name: str, j_shaft: float) -> SeatFloor:
    """The series values a designed seat of shaft ``name`` can take under a wheel of inertia at least ``j_shaft``
    [kg*m^2]: from the first whose keyseat passes the DE-Goodman factor with the torque alone (below it every
    wheel's fails) up to the last at which the shaft's material gives its strengths and the fits hold."""
    layout = _layout(ctx, name)
    material = ctx.materials[name]
    curve = torque_curve(ctx, name, j_shaft)
    ta = 0.5 * (float(curve.max()) - float(curve.min()))
    bound, first = 0.0, math.nan
    seats: list[float] = []
    supported = 0.0
    for d in seat_series(layout.diameter_series):
        try:
            sut, _ = strength.shaft_strengths(material, d)
            se = strength.endurance_limit(sut, d, layout.finish).se
            kf, kfs = notch_factors("keyseat", d, None, sut)
        except ValueError as err:  # beyond the material's table or Neuber's range: the series ends here
            cap = said("above {d}: ", d=_mm(supported)) + said_by(err) if supported else said_by(err)
            return SeatFloor(ta, first, bound, tuple(seats), cap)
        supported = d
        if math.isnan(first):
            bound = float(
                strength.fatigue_diameter(
                    layout.safety_factor, 0.0, ta, 0.0, 0.0, kf=kf, kfs=kfs, se=se, sut=sut, criterion=CRITERION
                )
            )
            if d >= bound:
                first = d
        if not math.isnan(first):
            seats.append(d)
    return SeatFloor(ta, first, bound, tuple(seats))


def seated(shafts: Sequence[MountShaft], designed: set[str]) -> tuple[MountShaft, ...]:
    """``shafts`` with each one named in ``designed`` (a described shaft that designs its seat) on the smallest
    seat of R40's range: a stand-in that says the wheel has a bore (so it is designed whole and its key checked);
    :func:`design_with_seats` gives each design its own d."""
    return tuple(
        dataclasses.replace(s, diameter=seat_series()[0]) if s.name in designed and s.diameter is None else s
        for s in shafts
    )


def on_seat(ctx: ShaftContext, shaft: MountShaft, d: float, j_required: float) -> MountShaft:
    """``shaft`` on the seat ``d`` [m] with its key's torque there (:func:`flyopt.design.shaft.cycle.keyed_shafts`,
    the train's stiffness depends on d) at the inertia the design must supply (``j_required`` at the reference,
    times the rim's share): the shaft the wheel is designed on at that seat."""
    return keyed_shafts(ctx, [dataclasses.replace(shaft, diameter=d, torque=None)], j_required)[0]


def _layout(ctx: ShaftContext, name: str) -> ShaftLayout:
    layout = ctx.shafts[name].layout
    if layout is None:
        raise ValueError(f"shaft {name!r} is not described as a part")
    return layout


def designs_seats(ctx: ShaftContext | None, shafts: Sequence[MountShaft]) -> bool:
    """Whether one of ``shafts`` designs its seat diameter."""
    return ctx is not None and any(_designed(ctx, s.name) for s in shafts)


def _designed(ctx: ShaftContext, name: str) -> bool:
    shaft = ctx.shafts.get(name)
    return shaft is not None and shaft.layout is not None and shaft.layout.designs_seat


def _arms(spec: DesignSpec) -> tuple[int | None, ...]:
    return tuple(spec.arms) if spec.geometry == Geometry.RIM_ARMS else (None,)


def _key(c: Candidate) -> tuple[str, str, int | None]:
    return (c.material, c.shaft, c.n_arms)


def design_with_seats(
    j_required: float,
    omega: float,
    shafts: Sequence[MountShaft],
    materials: Sequence[Material],
    spec: DesignSpec,
    *,
    ctx: ShaftContext,
    names: Mapping[str, str] | None = None,
    continuous: bool = True,
    **options: Any,
) -> DesignResult:
    """:func:`flyopt.design.designer.design_flywheel` with each designed seat chosen from its series.

    Every combination on a shaft that designs its seat is designed, continuous (no rounding, no pruning), on
    each series value from :func:`seat_floor` upwards with the shaft's post-check (:func:`acceptor`) until it
    passes; its candidate is the one at its first passing d (its ``bore``). Combinations on other shafts are
    designed once. The best of them by the one ranking rule (:func:`flyopt.design.rank.ranking`) is designed
    again as the scene asks (rounded, with the post-check), on its own d, and heads the candidates; a
    combination no d passes is infeasible, its reason at the largest d tried and the floor in numbers.

    Each combination's walk starts at its NLP's continuous seat d* rounded up to the series
    (:mod:`flyopt.design.shaft.seat_nlp`: the wheel and d in one NLP with the shaft's smooth rows), never below
    the floor; ``continuous=False`` starts every walk at the floor (the search before the NLP took d, kept as the
    reference the tests and the benchmark compare with).

    ``options``: ``solver_options``, ``method``, ``torque``, ``omega_mean`` of ``design_flywheel``.
    """
    from flyopt.design.designer import design_flywheel
    from flyopt.machine.transmission import inertia_on_shaft

    if not continuous:  # the reference walk records no seat choices in the scene's context
        ctx = dataclasses.replace(ctx, seats={}, _cache=ctx._cache)
    accept = acceptor(ctx, names)
    search = dataclasses.replace(spec, round_to=None, prune=False)
    found: dict[tuple[str, str, int | None], Candidate] = {}
    failed: dict[tuple[str, str, int | None], Candidate] = {}
    order = [(m.name, s.name, a) for m in materials for s in shafts for a in _arms(spec)]
    last: DesignResult | None = None

    given = [s for s in shafts if not _designed(ctx, s.name)]
    if given:
        last = design_flywheel(j_required, omega, given, materials, search, accept=accept, **options)
        for c in last.candidates:
            (found if c.feasible else failed)[_key(c)] = c
    for shaft in (s for s in shafts if _designed(ctx, s.name)):
        layout = _layout(ctx, shaft.name)
        j_shaft = inertia_on_shaft(j_required * spec.rim_share, shaft.speed_ratio)
        floor = seat_floor(ctx, shaft.name, j_shaft)
        pending = {(m.name, a) for m in materials for a in _arms(spec)}
        starts = (
            _continuous_starts(ctx, shaft, floor, j_required, omega, materials, search, options) if continuous else {}
        )
        for (m, a), start in starts.items():
            if math.isnan(start):  # d* above the series' end: no seat carries it
                pending.discard((m, a))
                failed[(m, shaft.name, a)] = _exhausted(
                    None, m, shaft, spec, a, floor, layout.diameter_series, [], _beyond(ctx, shaft.name, m, a)
                )
        tried: list[float] = []
        # each combination's last seat refused: the wheel its shaft refused, or the design that found no wheel there
        refused: dict[tuple[str, int | None], Candidate] = {}
        for d in floor.seats:  # none when no seat passes the floor
            # each combination from the first series value at or above its NLP's d* (rounded up), else the floor
            active = {(m, a) for m, a in pending if starts.get((m, a), 0.0) <= d}
            if not active:
                continue
            mats = [m for m in materials if any((m.name, a) in active for a in _arms(spec))]
            at = search
            if spec.geometry == Geometry.RIM_ARMS:
                at = dataclasses.replace(search, arms=tuple(sorted({a for _, a in active if a is not None})))
            seated = on_seat(ctx, shaft, d, j_required * spec.rim_share)
            try:
                last = design_flywheel(j_required, omega, [seated], mats, at, accept=accept, **options)
                again = rekeyed(ctx, last, [seated])  # a wheel refused for its key at its own inertia's torque
                if again is not None:
                    last = design_flywheel(j_required, omega, again, mats, at, accept=accept, **options)
            except ValueError as err:  # beyond a table the checks read: the series ends here
                floor = dataclasses.replace(floor, cap=said("at {d}: ", d=_mm(d)) + said_by(err))
                break
            tried.append(d)
            for c in last.candidates:
                if (c.material, c.n_arms) not in active:
                    continue
                if c.feasible:
                    found[_key(c)] = c
                    pending.discard((c.material, c.n_arms))
                    failed.pop(_key(c), None)
                    _settled(ctx, shaft.name, c, refused.get((c.material, c.n_arms)))
                elif c.mass is not None or _key(c) not in failed or failed[_key(c)].mass is None:
                    failed[_key(c)] = c  # the largest d whose wheel its shaft refused says most
                if not c.feasible and c.bore:
                    refused[(c.material, c.n_arms)] = c
            if not pending:
                break
        for m, a in pending:
            failed[(m, shaft.name, a)] = _exhausted(
                failed.get((m, shaft.name, a)), m, shaft, spec, a, floor, layout.diameter_series, tried
            )
    return _merged(j_required, omega, shafts, materials, spec, found, failed, order, last, accept, options, names, ctx)


def _continuous_starts(ctx, shaft, floor, j_required, omega, materials, search, options) -> dict:
    """Each combination's first series value: the NLP's d* (:func:`flyopt.design.shaft.seat_nlp.seat_optimum`)
    rounded up to the series, never below the floor; the floor itself where the NLP gives no d*; nan where d*
    lies above the series' end. Records each :class:`~flyopt.design.shaft.seat_nlp.SeatChoice` in ``ctx.seats``."""
    from flyopt.design.designer import combinations
    from flyopt.design.shaft.seat_nlp import SeatChoice, SeatOptimum, seat_optimum
    from flyopt.errors import SolverFailed

    if not floor.seats:
        return {}
    lower = floor.bound if floor.bound > 0.0 else floor.seats[0]
    d_range = (min(lower, floor.seats[0]), floor.seats[-1])
    seated = on_seat(ctx, shaft, floor.seats[0], j_required * search.rim_share)
    starts: dict[tuple[str, int | None], float] = {}
    combos = combinations(
        j_required, omega, options.get("omega_mean"), options.get("torque"), [seated], [False], materials, search
    )
    for _, combo, _ in combos:
        for arms in _arms(search):
            optimum: SeatOptimum | None = None
            try:
                found = seat_optimum(
                    ctx, shaft.name, combo, search, arms or 0, d_range, floor.seats[0], options.get("solver_options")
                )
            except (ValueError, RuntimeError, SolverFailed) as err:  # a table the rows read ends: the walk decides
                note = str(err)
            else:
                optimum, note = found, found.reason or ""
            start = floor.seats[0]
            if optimum is not None and math.isfinite(optimum.diameter):
                above = [d for d in floor.seats if d >= optimum.diameter * (1.0 - 1e-12)]
                start = above[0] if above else math.nan
            starts[(combo.material.name, arms)] = start
            ctx.seats[(shaft.name, combo.material.name, arms)] = SeatChoice(optimum, start, note=note)
    return starts


def _beyond(ctx, name, material, arms) -> str:
    """Why a combination's NLP put its seat above the series' end, in numbers."""
    choice = ctx.seats.get((name, material, arms))
    optimum = None if choice is None else choice.optimum
    if optimum is None or optimum.binding is None:
        return ""
    return said("the NLP's continuous seat is {d}, set by its ", d=_mm(optimum.diameter, ".4g")) + optimum.binding.name


def _settled(ctx, name, candidate, refused) -> None:
    """Record which limit set a combination's seat: the post-check that refused the series value below it, or the
    design that found no wheel there (a hub no key carries), where the walk went past the NLP's rounded d*; else
    the NLP's binding row, else the walk's floor."""
    from flyopt.design.shaft.cycle import check_candidate

    key = (name, candidate.material, candidate.n_arms)
    choice = ctx.seats.get(key)
    if choice is None:
        return
    optimum = choice.optimum
    if refused is not None and refused.mass is None:  # no wheel was designed on the seat below
        label, _, why = (refused.reason or "").partition(": ")  # the reason names its combination first
        words = removeprefix(refused.reason, label + ": ") if why and " on the " in label else refused.reason
        set_by = said("the design, which found no wheel on {d}: ", d=_mm(refused.bore)) + words
        ctx.seats[key] = dataclasses.replace(choice, diameter=candidate.bore, set_by=set_by, by_nlp=False)
    elif refused is not None:
        check = check_candidate(ctx, refused)
        worst = max(check.failed(), key=lambda lim: lim.utilisation) if check is not None and check.failed() else None
        words = worst.describe() if worst is not None else refused.reason
        set_by = said("the post-check, which refused {d}: ", d=_mm(refused.bore)) + words
        ctx.seats[key] = dataclasses.replace(choice, diameter=candidate.bore, set_by=set_by, by_nlp=False)
    elif optimum is not None and optimum.binding is not None:
        set_by = optimum.binding.name + ", a row of the NLP"
        ctx.seats[key] = dataclasses.replace(choice, diameter=candidate.bore, set_by=set_by, by_nlp=True)
    else:
        set_by = "the torque-only DE-Goodman bound at the keyseat (Shigley Eq. (7-8)), where the walk starts"
        if optimum is not None and math.isfinite(optimum.diameter):
            where = "at the lower end of the range" if optimum.lower_bound else "where the objective is least"
            set_by = said(
                "the NLP, no shaft row binding (d* {d}, " + where + ", rounded up)", d=_mm(optimum.diameter, ".4g")
            )
        ctx.seats[key] = dataclasses.replace(choice, diameter=candidate.bore, set_by=set_by, by_nlp=False)


def _exhausted(last, material, shaft, spec, arms, floor, series, tried, beyond=None) -> Candidate:
    """The combination no seat of the series carries: the floor, the series' end and the reason at the largest
    d whose wheel its shaft refused (else the largest tried), in numbers; ``beyond``: the NLP's d* above the
    series' end, in words."""
    # "from 45 to 60 mm": the first diameter's unit is the last's, written once (a report in other units gives both)
    span: str = (
        said("from {low} to {high}", low=(tried[0], "length", f"{tried[0] * 1e3:g}"), high=_mm(tried[-1]))
        if tried
        else "that the checks support"
    )
    words = ["no seat diameter on ISO 3 " + series + " " + span + " carries it"]
    if beyond:
        words.append(beyond)
    torque = (floor.torque_alternating, "torque", f"{floor.torque_alternating:.4g} N·m")
    if floor.torque_alternating > 0.0 and math.isfinite(floor.diameter):
        words.append(
            said(
                "below {d} the torque alone, T_a {torque}, fails DE-Goodman at the keyseat (Shigley Eq. (7-8): "
                "d >= {bound})",
                d=_mm(floor.diameter),
                torque=torque,
                bound=_mm(floor.bound, ".4g"),
            )
        )
    elif floor.torque_alternating > 0.0:
        words.append(
            said(
                "the torque alone, T_a {torque}, fails DE-Goodman at the keyseat of every seat the checks support "
                "(Shigley Eq. (7-8): d >= {bound} at the last)",
                torque=torque,
                bound=_mm(floor.bound, ".4g"),
            )
        )
    if floor.cap is not None:
        words.append(floor.cap)
    return _infeasible(last, material, shaft, spec, arms, join("; ", words))


def _infeasible(last, material, shaft, spec, arms, head) -> Candidate:
    from flyopt.design.result import Candidate

    if last is not None:
        return dataclasses.replace(
            last,
            feasible=False,
            reason=(
                head + said("; at {d}: ", d=_mm(last.bore)) + last.reason if last.bore else head + "; " + last.reason
            ),
        )
    return Candidate.infeasible(material, shaft, spec.geometry, head, n_arms=arms)


def _merged(
    j_required, omega, shafts, materials, spec, found, failed, order, last, accept, options, names, ctx
) -> DesignResult:
    """One DesignResult: the winner designed again as the spec asks on its seat, then the other feasible
    combinations by the ranking rule, then the infeasible ones in input order."""
    from flyopt.design.designer import design_flywheel

    designs = rank.ranking(list(found.values()))
    infeasible = [failed[k] for k in order if k in failed] + [c for k, c in failed.items() if k not in order]
    if not designs:
        message = infeasible_message(infeasible)
        if last is None:  # no seat passed the floor: nothing was designed
            from flyopt.design.result import DesignResult

            return DesignResult(
                status="infeasible",
                message=message,
                j_required=j_required,
                omega=omega,
                spec=spec,
                candidates=tuple(infeasible),
                omega_mean=options.get("omega_mean"),
                material_names=dict(names or {}),
            )
        return dataclasses.replace(last, status="infeasible", message=message, best=None, candidates=tuple(infeasible))
    winner = designs[0]
    shaft = next(s for s in shafts if s.name == winner.shaft)
    seated = (
        on_seat(ctx, shaft, winner.bore, j_required * spec.rim_share)
        if winner.bore and _designed(ctx, shaft.name)
        else dataclasses.replace(shaft, diameter=winner.bore if winner.bore else shaft.diameter)
    )
    material = next(m for m in materials if m.name == winner.material)
    final_spec = spec if winner.n_arms is None else dataclasses.replace(spec, arms=(winner.n_arms,))
    final = design_flywheel(j_required, omega, [seated], [material], final_spec, accept=accept, **options)
    again = rekeyed(ctx, final, [seated])  # the rounded wheel's key, refused at its own inertia's torque: as the walk
    if again is not None:
        final = design_flywheel(j_required, omega, again, [material], final_spec, accept=accept, **options)
    head = final.best if final.best is not None else (final.continuous or winner)
    candidates = (head, *designs[1:], *infeasible)
    total = len(candidates)
    message = final.message.replace(
        "(1 of 1 combinations feasible", f"({len(designs)} of {total} combinations feasible"
    )
    return dataclasses.replace(final, message=message, candidates=candidates)
