"""The text report of ``flyopt solve``: the cycle analysis, the design, the whole wheel, the verification.

Every quantity is shown in the unit system the reader chose (``--units``:
engineering, the default, si or imperial) through :mod:`flyopt.report.display`,
the one table of display units; a field's dimension is the one flyopt.outputs.results
gives it for the JSON, which stays SI. A table's heading carries its column's
unit ("mass [kg]"), a line its numbers' ("1.25633 kJ"). Prose written by the
design itself (why a combination fails, notes) is shown as the design wrote
it; a sensitivity's sentence is filled in the reader's units
(:func:`flyopt.report.display.sensitivity_text`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

from flyopt.design.check import binding_label
from flyopt.design.combination import shaft_label, wheel_words
from flyopt.design.key import key_verdict
from flyopt.design.result import NO_DESIGN, Design
from flyopt.errors import BrokenInvariant
from flyopt.names import Geometry
from flyopt.report.characters import visible
from flyopt.report.display import (
    DEFAULT,
    DEFAULT_DIGITS,
    SENSITIVITY_HEADING,
    UTILISATION_DIGITS,
    Column,
    chain_point,
    dimension_of,
    field_number,
    field_text,
    heading,
    key_answer,
    largest,
    number,
    one_in,
    quantity_text,
    rim_speed_answer,
    rounded_rank_note,
    said_text,
    sensitivity_text,
    share,
    share_of_allowable,
    thin_wall_answer,
    unit,
)
from flyopt.said import counted

if TYPE_CHECKING:
    from flyopt.analysis import Analysis
    from flyopt.design.fem import FemCheck
    from flyopt.design.result import BookRim, Candidate, DesignResult
    from flyopt.design.spec import DesignSpec
    from flyopt.machine.crank_forces import CrankForces
    from flyopt.machine.electric_drive import ReducedDrive
    from flyopt.machine.equivalents import PositionEquivalents
    from flyopt.machine.transmission import BranchFlow, PowerFlow
    from flyopt.pipeline import Solution
    from flyopt.sizing.existing import FlywheelCheck
    from flyopt.sizing.operation import OperationResult
    from flyopt.sizing.periodic import Verification

__all__ = [
    "analysis_report",
    "answer_report",
    "castability_words",
    "design_report",
    "engine_report",
    "formatters",
    "number",
    "power",
    "table",
    "verification_report",
    "wheel_report",
]


def power(watts: float | None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A power [W] in the unit system's unit ("72.6493 kW"; "-" for None)."""
    return field_text(watts, "power", units, digits)


def formatters(units: str, digits: int = DEFAULT_DIGITS) -> tuple[Callable[..., str], Callable[..., str]]:
    """The two ways a report line shows a field in a unit system, by the field's name, to ``digits`` figures.

    Returns ``(q, n)``: ``q(value, name, among=None)`` gives "<number> <label>" ("1.256 kJ" for ``a_max``),
    ``n(value, name, among=None)`` the number alone, for a table under a heading that carries the unit or a
    list that ends in it. ``among``: the SI values read together (a range's ends, a column, a list), whose
    largest chooses their one unit and is the scale of their round-off
    (:func:`flyopt.report.display.field_number`).
    """

    def q(value: Any, name: str, among: Sequence[float | None] | None = None) -> str:
        return field_text(value, name, units, digits, among)

    def n(value: Any, name: str, among: Sequence[float | None] | None = None) -> str:
        return field_number(value, name, units, digits, among)

    return q, n


def _label(name: str, units: str, among: Sequence[float | None] | None = None, digits: int = DEFAULT_DIGITS) -> str:
    """The label of a field's unit in the system ("mm"), for a list of numbers that ends in one: ``among``, the
    SI values of that list, chooses a prefixed unit (as :func:`flyopt.report.display.heading` does a column's)."""
    return unit(dimension_of(name), units, None if among is None else largest(among), digits)[0]


def table(header: Sequence[str], rows: Sequence[Sequence[Any]], align: Sequence[str] | None = None) -> list[str]:
    """Fixed-width table: a header row, a rule, then the rows."""
    cells = [[visible(str(c)) for c in r] for r in [header, *rows]]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    align = align or ["<"] + [">"] * (len(header) - 1)
    lines = ["  ".join(f"{c:{a}{w}}" for c, a, w in zip(r, align, widths)).rstrip() for r in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return lines


#: The two speed ranges, named once (the text, the HTML/PDF report): the range the allowed δ permits,
#: ω_m (1 ± δ/2), and the range the machine as designed reaches (its simulation, a flywheel that exists).
ALLOWED_RANGE = "allowed speed range"
ACHIEVED_RANGE = "achieved speed range"


def allowed_speed_range(analysis: Analysis) -> tuple[float, float]:
    """(ω_min, ω_max) the allowed δ permits about the mean speed, ω_m (1 ∓ δ/2) [rad/s] (docs/flywheel-design.md,
    section 2)."""
    from flyopt.cycle.indicator import speed_extremes

    high, low = speed_extremes(analysis.omega_mean, analysis.delta)
    return float(low), float(high)


def achieved_speed_range(v: Verification, allowed: tuple[float, float] | None = None) -> tuple[float, float]:
    """(ω_min, ω_max) a verification achieved, as shown beside the allowed range ``allowed`` (default ω_m
    (1 ∓ δ/2) at the simulated mean) [rad/s]: an extreme within the simulation's accuracy (its ``tolerance`` on δ,
    times the mean speed) of the allowed bound is that bound. A wheel sized to δ reaches the bound to that
    accuracy, and 1492.4999999994 rpm beside the allowed 1492.5000000000002 printed "1,492" under "1,493", as
    though the limit were broken by half a revolution a minute."""
    from flyopt.cycle.indicator import speed_extremes

    if allowed is None:
        high, low = speed_extremes(v.omega_mean, v.delta_allowed)
        allowed = (float(low), float(high))
    slack = v.tolerance * v.omega_mean
    low, high = allowed
    return (
        low if abs(v.omega_min - low) <= slack else v.omega_min,
        high if abs(v.omega_max - high) <= slack else v.omega_max,
    )


def reached_below_allowed(analysis: Analysis) -> bool:
    """Whether the analysis' own speed extremes are a range the machine achieves below the allowed one: the
    dynamic model's periodic solution where the flywheel it fits does not reach the allowed δ (none needed, or
    a stall limit). The energy models' extremes are the allowed range."""
    return abs(analysis.delta_reached - analysis.delta) > 1e-9 * analysis.delta


#: What the steps of a scene whose [drive] found no motor are (:attr:`flyopt.pipeline.Solution.drive_failed`):
#: said under the answer by the text and the report alike.
WITHOUT_DRIVE = (
    "No motor was chosen: the numbers that follow are the scene without its [drive] (its torques as its other "
    "tables give them), not a machine flyopt designed."
)

#: Why a diagram of such a scene is not drawn (the report's figures; ``flyopt plot`` refuses in the same terms).
NO_MACHINE = "no drive meets the limits, so no machine to draw"


def no_flywheel_words(analysis: Analysis, digits: int = DEFAULT_DIGITS) -> tuple[str, str]:
    """(before, after) ``j_margin``: why no flywheel is needed (the text and the document say the same)."""
    if analysis.delta_holds_at_any_inertia:
        return (
            f"with no flywheel the machine gives δ = {number(analysis.delta_reached, digits)}, within the allowed "
            f"{number(analysis.delta, digits)}, and stays within it however small the inertia (the torques' fall with speed holds "
            "it, as a motor's slip does): δ would reach the allowed value only at a J_F below",
            ", less inertia than none",
        )
    return "the machine's own inertia suffices (J_F would be", ")"


def no_flywheel_holder(analysis: Analysis) -> tuple[str, str]:
    """(what holds δ, "however small the inertia" or nothing) where no flywheel is needed: the text's answer and
    the document's summary say the same. A motor's slip, or any torque falling steeply enough with speed, holds it
    at any inertia; otherwise the machine's own inertia does."""
    if analysis.delta_holds_at_any_inertia:
        return "the torques' fall with speed", " however small the inertia"
    return "the machine's own inertia", ""


def answer_report(solution: Solution, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The answer first (issue 29): what to make, or what the machine needs, and whether it holds, in at most
    six lines under the scene's title; the steps that give it follow (``units``: the unit system)."""
    q, _n = formatters(units, digits)
    r, design = solution.analysis, solution.design
    if solution.flywheel is not None:
        check = solution.flywheel
        verdict = ""
        if check.delta_allowed is not None:
            verdict = (
                f": within the allowed {number(check.delta_allowed, digits)}"
                if check.suffices
                else f": the allowed {number(check.delta_allowed, digits)} is NOT held"
            )
        return [
            f"Answer: the flywheel given ({q(check.flywheel.j_at_reference, 'j_at_reference')} at the reference "
            f"shaft) leaves δ = {number(check.achieved_delta, digits)}{verdict}",
            "",
        ]
    if r.flywheel_needed:
        need = f"J_F {q(r.j_required, 'j_required')} at the reference shaft"
    else:
        holder, however = no_flywheel_holder(r)
        need = f"no flywheel: {holder} holds δ{however}"
    drive = solution.drive
    if drive is not None:  # the drive designed with the flywheel: the motor, its ratio and the wheel
        run = drive.best
        if run is None:
            from flyopt.drive.codesign import refused_in_short

            return [
                f"Answer: no drive: {visible(said_text(refused_in_short(drive), units, digits))}",
                WITHOUT_DRIVE,
                "",
            ]
        wheel = (
            f"a flywheel of {q(run.j_flywheel, 'j_flywheel')} ({q(run.wheel_mass, 'mass')})"
            if run.j_flywheel
            else "no flywheel (the motor's slip holds δ)"
        )
        return [
            f"Answer: motor {visible(run.motor.name)} at a ratio of {number(run.motor_ratio, digits)}, {wheel}; "
            f"δ {number(run.delta, digits)} against the allowed {number(r.delta, digits)}",
            *_wall_lines(design.best if design is not None else None, q),
            "",
        ]
    best = design.best if design is not None else None
    if design is None:
        return [f"Answer: {need} (no [design]: the wheel is not sized)", ""]
    if best is None:
        return [
            f"Answer: {need}"
            + (
                ""
                if design.status == "not_needed"
                else f"; no wheel: {visible(said_text(design.message, units, digits))}"
            ),
            "",
        ]
    shape = wheel_words(best.geometry, best.n_arms)
    lines = [
        f"Answer: {design.material_name(best.material)} {shape}, {q(best.mass, 'mass')}, "
        f"on the {visible(shaft_label(best.shaft))}"
    ]
    d = best.dims
    if best.geometry == Geometry.DISC:
        size = f"D {q(d.d_outer, 'd_outer')}, B {q(d.b, 'b')}"
        if best.bore:
            size += f", bore {q(best.bore, 'bore')}"
        if d.d_hub:
            size += f", hub {q(d.d_hub, 'd_hub')} x {q(d.l_hub, 'l_hub')}"
    else:
        size = f"D {q(d.d_outer, 'd_outer')}, rim H {q(d.h, 'h')} x B {q(d.b, 'b')}"
        if d.t_web:
            size += f", web {q(d.t_web, 't_web')}"
        if d.d_hub:
            size += f", hub {q(d.d_hub, 'd_hub')} x {q(d.l_hub, 'l_hub')}"
        if best.bore:
            size += f", bore {q(best.bore, 'bore')}"
    lines.append(f"    size    {size}")
    lines.append(
        f"    J       {q(best.j_flywheel, 'j_flywheel')} on its shaft, {q(best.j_at_reference, 'j_at_reference')}"
        f" at the reference shaft (needed {q(r.j_required, 'j_required')})"
    )
    speed = rim_speed_answer(best.stresses.rim_speed, best.limits.rim_speed_limit, design.book_rim(), q)
    limits = "rim speed " + "".join(speed)
    parts = [p for p in (best.stresses.stress or {}).get("parts", []) if p.get("allowable")]
    if parts:
        worst = max(parts, key=lambda p: p["stress"] / p["allowable"])
        limits += (
            f"; {worst['part']} stress {q(worst['stress'], 'stress')} of {q(worst['allowable'], 'allowable')} "
            f"({share_of_allowable(worst['stress'] / worst['allowable'])})"
        )
    lines.append(f"    limits  {limits}")
    lines += _wall_lines(best, q)
    k = best.parts.key
    if k and k.get("shear") is not None:  # the hub's key, checked at the peak torque (section 13)
        said = key_answer(k, design.material_name(best.material), q)
        lines.append(f"    key     {''.join(said)}")
    for shaft_check in solution.shaft_checks:  # the shaft described as a part (flyopt.report.shaft)
        binding = shaft_check.check.binding
        lines.append(
            f"    shaft   {binding.kind} {said_text(binding.where, units, digits)} binds, utilisation {number(binding.utilisation, UTILISATION_DIGITS)}"
        )
    v = solution.verification
    held = (
        f"δ {number(v.achieved_delta, digits)} by the periodic simulation ({'FLAGGED' if v.flagged else 'holds'})"
        if v is not None
        else f"δ {number(r.delta_reached, digits)} at the stall limit (the smallest flywheel that runs steadily)"
        if r.stall_limited
        else "held by the inertia"
    )
    lines.append(f"    δ       allowed {number(r.delta, digits)}; {held}")
    return [*lines, ""]


def _wall_lines(best: Design | None, q: Callable[..., str]) -> list[str]:
    """The answer's line for a bare wheel thinner than can be made (its note says more); none otherwise."""
    thin = best.parts.thin_wall if best is not None else None
    return [f"    wall    {''.join(thin_wall_answer(thin, q))}"] if thin is not None else []


def analysis_report(
    result: Analysis,
    source: str | None = None,
    units: str = DEFAULT,
    delta_label: str = "allowed δ",
    answer: Sequence[str] = (),
    digits: int = DEFAULT_DIGITS,
) -> str:
    """The report of ``flyopt solve`` for the cycle analysis, as text.

    Parameters
    ----------
    result : flyopt.analysis.Analysis
    source : str, optional
        The scene file, named after the title.
    units : str
        The unit system of every quantity (:data:`flyopt.report.display.SYSTEMS`).
    delta_label : str
        What the analysis' δ is: the allowed one, or the δ a [flywheel] that exists reaches.
    answer : sequence of str
        The answer's lines (:func:`answer_report`), put under the title, before the steps.
    """
    r = result
    q, n = formatters(units, digits)
    lines = [
        visible(r.title) + (f"  ({visible(source)})" if source else ""),
        *answer,
        f"model: {r.model}: {r.model_reason}",
        "",
    ]
    facts = [
        ("mean speed", q(r.omega_mean, "omega_mean")),
        (delta_label, number(r.delta, digits) + (f" ({one_in(r.delta, digits)})" if r.delta > 0 else "")),
    ]
    if delta_label == "allowed δ":
        low, high = allowed_speed_range(r)
        facts.append((ALLOWED_RANGE, f"{n(low, 'omega_min')} to {q(high, 'omega_max')}"))  # ω_m (1 ∓ δ/2)
        if reached_below_allowed(r):
            facts.append(
                (
                    ACHIEVED_RANGE,
                    f"{n(r.omega_min, 'omega_min')} to {q(r.omega_max, 'omega_max')} (δ = {number(r.delta_reached, digits)}, "
                    f"the periodic solution with J_F = {q(max(r.j_required, 0.0), 'j_required')})",
                )
            )
    else:  # the δ a flywheel that exists reaches: the range is the one it achieves
        facts.append((ACHIEVED_RANGE, f"{n(r.omega_min, 'omega_min')} to {q(r.omega_max, 'omega_max')}"))
    facts.append(("cycle", q(r.cycle_angle, "cycle_angle")))
    if r.work_per_cycle is not None:
        facts += [
            ("driving torque (mean)", q(r.driving_torque, "driving_torque")),
            ("resisting torque (mean)", q(r.resisting_torque, "resisting_torque")),
            ("work per cycle", q(r.work_per_cycle, "work_per_cycle")),
            ("mean driving power", q(r.power, "power")),
            ("motor power", f"{q(r.motor_power, 'motor_power')} (efficiency {number(r.efficiency, digits)})"),
        ]
    facts.append(("A_max", q(r.a_max, "a_max")))
    if r.angle_omega_max is not None:
        facts.append(
            (
                "ω_max / ω_min at",
                f"{n(r.angle_omega_max, 'angle_omega_max')} / {q(r.angle_omega_min, 'angle_omega_min')}",
            )
        )
        if (r.angle_delta_e_max, r.angle_delta_e_min) != (r.angle_omega_max, r.angle_omega_min):
            facts.append(
                (
                    "ΔE max / min at",
                    f"{n(r.angle_delta_e_max, 'angle_delta_e_max')} / "
                    f"{q(r.angle_delta_e_min, 'angle_delta_e_min')} (where the speed is extreme differs: "
                    f"the inertia varies or a torque depends on speed)",
                )
            )
    else:
        facts.append(("ω_max / ω_min at", f"{chain_point(r.index_omega_max)} / {chain_point(r.index_omega_min)}"))
    if r.j_constant:
        facts.append(("J_c (machine and shafts)", q(r.j_constant, "j_constant")))
    if r.flywheel_needed:
        facts.append(
            (
                "required flywheel J_F",
                f"{q(r.j_required, 'j_required')} (GD² {q(r.gd2_required, 'gd2_required')}) at the reference shaft",
            )
        )
    else:
        before, after = no_flywheel_words(r, digits)
        facts.append(("required flywheel", f"none: {before} {q(r.j_margin, 'j_margin')}{after}"))
    width = max(len(k) for k, _ in facts)
    lines += [f"  {k:<{width}}  {v}" for k, v in facts]

    if r.startup is not None:
        st = r.startup
        facts_text = (
            f"{q(st.time, 'time')} ({number(st.cycles, digits)} cycles) to {q(st.omega_target, 'omega_target')}"
            if st.time is not None
            else f"not reached: {said_text(st.note, units, digits)}"
        )
        lines.append(f"  {'start-up':<{width}}  {facts_text}; {st.method}")
    if len(r.models) > 1 or (r.models and not r.models[0]["exact"]):
        lines += ["", "Models (J_F each asks for, and the δ it really gives by the exact model):"]
        rows = []
        for m in r.models:
            rows.append(
                [
                    m["model"] + (" (exact)" if m["exact"] else ""),
                    "none" if m["exact"] and r.delta_holds_at_any_inertia else n(m["j_required"], "j_required"),
                    "-" if m["j_error"] is None else f"{100 * m['j_error']:+.3g} %",
                    number(m["achieved_delta"], digits),
                    m["note"],
                ]
            )
        head = ["model", heading("J_F", "j_required", units), "vs exact", "achieved δ", "note"]
        lines += ["  " + line for line in table(head, rows, ["<", ">", ">", ">", "<"])]
    lines += engine_report(r, units, digits)
    lines += ["", "Energy indicator diagram (excess work from the cycle start):"]
    rows = []
    chain = Column(e["delta_e"] for e in r.energy_chain)  # one column: its unit and its round-off by its largest
    angles = Column(e["angle"] for e in r.energy_chain)
    for e in r.energy_chain:
        same = (r.angle_delta_e_max, r.angle_delta_e_min) == (r.angle_omega_max, r.angle_omega_min)
        top, bottom = ("ω_max", "ω_min") if same else ("ΔE max", "ΔE min")
        mark = top if e["index"] == r.index_omega_max else bottom if e["index"] == r.index_omega_min else ""
        where = n(e["angle"], "angle", angles) if e["angle"] is not None else chain_point(e["index"])
        rows.append([where, n(e["delta_e"], "delta_e", chain), mark])
    head = [
        heading("angle", "angle", units) if r.angle_omega_max is not None else "point",
        heading("ΔE", "delta_e", units, chain, digits),
        "",
    ]
    lines += ["  " + line for line in table(head, rows, ["<", ">", "<"])]

    lines += ["", "Flywheel needed on each shaft (same kinetic energy, J' = J (ω/ω')²):"]
    rows = [
        [
            s.name,
            number(s.speed_ratio, digits),
            n(s.omega, "omega"),
            n(s.j_required, "j_required"),
            n(s.gd2_required, "gd2_required"),
        ]
        for s in r.shafts
    ]
    head = [
        "shaft",
        "speed ratio",
        heading("speed", "omega", units),
        heading("J", "j_required", units),
        heading("GD²", "gd2_required", units),
    ]
    lines += ["  " + line for line in table(head, rows)]
    return "\n".join(lines)


def engine_report(result: Analysis, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """For an [engine]: the textbook's flywheel beside the exact one, and by how much it is off.

    The textbook's method (flyopt.sizing.textbook.textbook_requirement, ``result.textbook``) takes
    the crank effort at the mean speed (gas torque plus the inertia torque
    −½ J_e' ω_m²) as a torque curve on a constant inertia; the exact model
    keeps J_e(φ) varying (docs/flywheel-design.md, sections 5 and 6). The
    difference is (J_textbook − J_exact)/J_exact. No lines for a machine that
    is not an engine, or whose inertia is constant (no moving masses: the
    two methods are one).
    """
    textbook = result.textbook  # computed by the solve (flyopt.analysis.complete): read here
    if textbook is None:
        return []
    from flyopt.machine.engine import engine_of

    if result.machine is None:
        raise BrokenInvariant("an engine's textbook flywheel is of its machine")
    engine = engine_of(result.machine)
    if engine is None:  # a variable inertia of members, not of an [engine]
        return []
    q, _ = formatters(units, digits)
    exact = next((m for m in result.models if m["exact"]), None)
    angles = ", ".join(field_number(a, "angle", units, digits) for a in engine.firing_angles)
    found = f"A_max {q(textbook.a_max, 'a_max')}, J_F {q(textbook.j_required, 'j_required')}"
    if exact is None or exact["j_required"] is None:
        found += "; the exact model gave no J_F to compare with"
    elif exact["j_required"] > 0:
        off = (textbook.j_required - exact["j_required"]) / exact["j_required"]
        found += f", {100 * off:+.3g} % against the exact J_F {q(exact['j_required'], 'j_required')} ({exact['model']})"
    else:
        found += (
            f"; the exact model ({exact['model']}) needs no flywheel (J_F would be "
            f"{q(exact['j_required'], 'j_required')})"
        )
    return [
        "",
        f"Engine: {counted(engine.cylinder_count, 'cylinder')}, "
        f"{engine.cycle}, cycles starting at {angles} {_label('angle', units)}",
        f"  textbook method (the crank effort at the mean speed, gas torque − ½ J_e′(φ) ω_m², on the constant "
        f"mean J_e {q(textbook.j_machine_mean, 'inertia')}):",
        f"    {found}",
    ]


def solver_words(candidate: Candidate) -> str:
    """How a design was found, in words: the exact closed form or IPOPT with its status."""
    if candidate.provenance.solver_status == "closed_form":
        return "the exact closed form of the lightest wheel, checked against every constraint"
    if candidate.provenance.solver_status == "rounded":
        return "the continuous optimum rounded to the manufacturing step (design.round_to), checked against every limit"
    return f"IPOPT ({candidate.provenance.solver_status}, {candidate.provenance.iterations} iterations), checked against every constraint"


def book_rim_report(book: BookRim, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The lines that put the courses' rim (criterion mean_rim_speed) beside what it really sees at ω_max."""
    q, _ = formatters(units, digits)

    def over(stress: float | None) -> str:
        excess = book.excess(stress)
        if excess is None:
            return ""
        return f": {share(abs(excess))} {'OVER' if excess > 1e-9 else 'within'} the allowable"

    lines = [
        "  criterion mean_rim_speed (the courses' convention): the rim's speed at the MEAN diameter and the "
        f"MEAN speed, {q(book.mean_rim_speed, 'rim_speed')}, gives ρv² {q(book.book_stress, 'hoop_stress')}"
        + (f" = the allowable {q(book.allowable, 'hoop_stress')}" if book.allowable else ""),
        f"  what the rim really sees at ω_max: {q(book.outer_rim_speed, 'rim_speed')} at the OUTER diameter, "
        f"ρv² {q(book.outer_hoop_stress, 'hoop_stress')}{over(book.outer_hoop_stress)}",
    ]
    if book.largest_stress is not None and book.largest_at is not None:
        lines.append(
            f"  and by Lamé {q(book.largest_stress, 'hoop_stress')} at r = {q(book.largest_at, 'radius')}"
            f"{over(book.largest_stress)} (flyopt's rim_speed or stress criterion keeps within it)"
        )
    if book.rim_share < 1.0:
        lines.append(
            f"  the rim gives {book.rim_share:.4g} of the required inertia (design.rim_share); the arms and hub, "
            "not designed here, must give the rest"
        )
    return lines


def castability_words(cast: dict[str, Any], units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A whole wheel's castability in one line: the process, the wall used and the thinnest wall, and each
    junction's section ratio against the allowed one (docs/flywheel-design.md, section 23)."""
    q, _n = formatters(units, digits)
    words = (
        f"{cast['process'].replace('_', ' ')}: min wall {q(cast['min_wall'], 'min_wall')} at D "
        f"{q(cast['casting_size'], 'd_outer')} (process {q(cast['process_min_wall'], 'min_wall')}), "
        f"thinnest {cast['thinnest_part']} {q(cast['thinnest_wall'], 'min_wall')}"
    )
    if cast["section_ratio"] is not None and cast["junctions"]:
        ratios = ", ".join(f"{j['junction']} {number(j['ratio'], min(3, digits))}" for j in cast["junctions"])
        words += f"; section ratios (2V/A) {ratios} (at most {number(cast['section_ratio'], min(3, digits))})"
    return words


def rounding_report(result: DesignResult, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The lines that put the rounded winner beside the continuous optimum it comes from (design.round_to)."""
    q, n = formatters(units, digits)
    c, best = result.continuous, result.best
    if c is None:
        return []
    section = (
        f"B {q(c.dims.b, 'b')}" if c.geometry == Geometry.DISC else f"H x B {n(c.dims.h, 'h')} x {q(c.dims.b, 'b')}"
    )
    optimum = f"the continuous optimum: {q(c.mass, 'mass')}, D_outer {q(c.dims.d_outer, 'd_outer')}, {section}"
    if best is None:
        return [f"  {optimum}"]
    if best is c:  # the default step found no wheel: the continuous optimum is the design
        return [f"  {result.rounding}"]
    extra = best.mass - c.mass
    return [
        f"  rounded to {q(result.spec.round_to, 'd_outer')} (design.round_to): {'+' if extra >= 0 else ''}"
        f"{q(extra, 'mass')} "
        f"({100 * extra / c.mass:+.2f} %) over {optimum}; every limit checked again on the rounded wheel ({result.rounding})"
    ]


def _size_facts(best: Design, units: str, digits: int = DEFAULT_DIGITS) -> list[tuple[str, str]]:
    """A design's size in words: a rim's outer, mean and inner diameters and its section H x B; a disc's outer
    diameter, its bore where it has one, and its width (a disc has no rim)."""
    q, n = formatters(units, digits)
    d = best.dims
    if best.geometry == Geometry.DISC:
        outer = (
            ("outer diameter / bore", f"{n(d.d_outer, 'd_outer')} / {q(best.bore, 'bore')}")
            if best.bore
            else ("outer diameter", q(d.d_outer, "d_outer"))
        )
        hub = [("hub diameter x length", f"{n(d.d_hub, 'd_hub')} x {q(d.l_hub, 'l_hub')}")] if d.d_hub else []
        return [outer, ("disc width B", q(d.b, "b")), *hub]
    return [
        (
            "outer / mean / inner diameter",
            f"{n(d.d_outer, 'd_outer')} / {n(d.d_mean, 'd_mean')} / {q(d.d_inner, 'd_inner')}",
        ),
        ("rim H x B", f"{n(d.h, 'h')} x {q(d.b, 'b')} (H/B {number(d.hb_ratio, digits)})"),
    ]


def design_report(
    result: DesignResult, spec: DesignSpec | None = None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> list[str]:
    """The design part of the ``flyopt solve`` report: the winner and the ranking of every combination.

    ``units``: the unit system of every quantity (:data:`flyopt.report.display.SYSTEMS`).
    """
    q, n = formatters(units, digits)
    lines = ["", f"Flywheel design ({result.spec.geometry}, objective: {result.spec.objective}):"]
    if result.status == "not_needed":
        return lines + [f"  {said_text(result.message, units, digits)}"]
    best = result.best
    if best is not None:
        facts = [
            (
                "material / shaft",
                f"{result.material_name(best.material)} on {best.shaft} (speed ratio {number(best.speed_ratio, digits)})",
            ),
            ("mass", q(best.mass, "mass") + (f" (cost {number(best.cost, digits)})" if best.cost is not None else "")),
            *_size_facts(best, units, digits),
            (
                "inertia",
                f"{q(best.j_flywheel, 'j_flywheel')} on its shaft = "
                f"{q(best.j_at_reference, 'j_at_reference')} at the reference shaft",
            ),
            (
                "rim speed",
                f"{q(best.stresses.rim_speed, 'rim_speed')} (limit {q(best.limits.rim_speed_limit, 'rim_speed_limit')}), "
                f"hoop stress ρv² {q(best.stresses.hoop_stress, 'hoop_stress')}"
                + (
                    f", safety factor {number(best.stresses.safety_factor, min(3, digits))}"
                    if best.stresses.safety_factor
                    else ""
                ),
            ),
            (
                "binding",
                (", ".join(map(binding_label, best.limits.binding)) or "none")
                + (" (of the continuous optimum)" if best.provenance.solver_status == "rounded" else ""),
            ),
            ("solved by", solver_words(best)),
        ]
        if best.limits.castability is not None:
            facts.append(("castability", castability_words(best.limits.castability, units, digits)))
        width = max(len(k) for k, _ in facts)
        lines += [f"  {k:<{width}}  {visible(v)}" for k, v in facts]
        if result.continuous is not None:
            lines += rounding_report(result, units, digits)
        book = result.book_rim()
        if book is not None:
            lines += book_rim_report(book, units, digits)
        elif not result.spec.has_envelope and not result.spec.pins_d_mean:
            lines.append(
                "  note: no envelope (design.max_outer_diameter) is set, so only the rim speed limit "
                "bounds the diameter"
            )
        lines += wheel_report(best, result.omega * best.speed_ratio, units, digits)
        if result.fem is not None:
            lines += fem_report(result.fem, units, digits)
    elif result.continuous is not None:
        lines.append(f"  no rounded design: {result.rounding}")
        lines += rounding_report(result, units, digits)
    else:
        lines.append(f"  no feasible design: {NO_DESIGN}")
    rows = []
    for k, c in enumerate(result.candidates, 1):
        if isinstance(c, Design):
            rows.append(
                [
                    str(k),
                    result.material_name(c.material),
                    c.shaft,
                    n(c.mass, "mass"),
                    n(c.dims.d_outer, "d_outer"),
                    n(c.dims.h, "h"),
                    n(c.dims.b, "b"),
                    n(c.stresses.rim_speed, "rim_speed"),
                    ", ".join(map(binding_label, c.limits.binding)),
                ]
            )
        else:
            verdict = "cannot win" if c.provenance.pruned else "infeasible"
            rows.append(["-", result.material_name(c.material), c.shaft, verdict, *[""] * 5])
    head = [
        "rank",
        "material",
        "shaft",
        heading("mass", "mass", units),
        heading("D_outer", "d_outer", units),
        heading("H", "h", units),
        heading("B", "b", units),
        heading("v", "rim_speed", units),
        "binding",
    ]
    align = ["<", "<", "<", ">", ">", ">", ">", ">", "<"]
    if any(c.n_arms for c in result.candidates):  # one combination per arm count: say which
        for row, c in zip(rows, result.candidates):
            row.insert(3, str(c.n_arms or "-"))
        head.insert(3, "arms")
        align.insert(3, ">")
    lines += ["", "Every combination (ranked):"]
    lines += ["  " + line for line in table(head, rows, align)]
    if result.best is not None and result.continuous is not None:
        lines += ["", f"  note: {rounded_rank_note(q(result.continuous.mass, 'mass'))}"]
    reasons = [
        said_text(c.reason, units, digits) for c in result.candidates if not c.feasible and not c.provenance.pruned
    ]
    if reasons:
        lines += ["", "Why the infeasible ones fail:"] + [f"  - {r}" for r in reasons]
    reasons = [said_text(c.reason, units, digits) for c in result.candidates if c.provenance.pruned]
    if reasons:
        lines += ["", "Not designed, since a bound shows they cannot win (design.prune = false designs them):"]
        lines += [f"  - {r}" for r in reasons]
    return lines


def _finite(value):
    """Whether a reported value exists: not None and a finite number."""
    return value is not None and math.isfinite(value)


def fem_report(check: FemCheck, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The FE check of the best design (``[design] fem_check = true``): each part's peak beside the Lamé/arm
    model's, the junction factors, and how far the two models differ."""
    q, n = formatters(units, digits)
    measure = "von Mises" if check.measure == "von_mises" else "largest principal"
    lines = [
        "",
        f"FEM check (axisymmetric, {check.elements} quadratic triangles; {measure} stress, as the design is judged):",
    ]
    for p in check.parts:
        peak, at = (
            (p.von_mises, p.von_mises_at) if check.measure == "von_mises" else (p.max_principal, p.max_principal_at)
        )
        text = f"  {p.part} peak {q(peak, 'stress')} at r, z = {n(at[0], 'radius')}, {q(at[1], 'radius')}"
        if p.model_stress is not None:
            text += f"; Lamé/arm {q(p.model_stress, 'stress')}"
        if p.utilisation is not None:
            text += f"; {share_of_allowable(p.utilisation)}"
        lines.append(text)
    if check.junctions:
        factors = ", ".join(
            f"{j.name} {j.factor:.3f}" + (f" (fillet {q(j.fillet, 'radius')})" if j.fillet else " (no step)")
            for j in check.junctions
        )
        lines.append(f"  junction factors (FE peak near the junction / Lamé there): {factors}")
    if check.difference is not None and check.model_peak is not None:
        word = "above" if check.difference >= 0 else "below"
        lines.append(
            f"  the two models: FE peak {q(check.peak, 'stress')}, Lamé/arm {q(check.model_peak, 'stress')}: "
            f"the FE is {share(abs(check.difference))} {word}"
        )
    verdict = fem_verdict(check)
    if verdict is not None:
        lines.append(f"  {verdict}")
    lines += [f"  note: {said_text(note, units, digits)}" for note in check.notes]
    return lines


def fem_verdict(check: FemCheck) -> str | None:
    """Whether every FE peak is within its part's allowable, and how the design was accepted, in the words the
    text and the report both say."""
    if check.within_allowable is None:
        return None
    accepted = check.accepted_by == "fem"
    if check.within_allowable:
        text = "every part's FE peak is within its allowable stress"
    elif accepted:  # an arms wheel: its arms and rim are the equivalent web's in the FE, judged by the beams
        text = (
            "the hub's FE peak is within its allowable stress (the arms and the rim are judged by the texts' "
            "beams: the FE's equivalent web cannot represent them)"
        )
    else:
        return (
            "WARNING: an FE peak exceeds its part's allowable stress (the design was sized by the Lamé/arm model; "
            "the check reports, it does not re-design: [design] fem_check = true accepts against the larger)"
        )
    if not accepted:
        return text
    text += "; the design is accepted against the larger of the FE peak and the Lamé/arm model"
    if check.stress_factors:
        factors = ", ".join(f"the {part}'s divided by {factor:.3f}" for part, factor in check.stress_factors)
        designs = "design" if check.rounds == 1 else "designs"
        text += f" (allowable of {factors}, the concentration the FE found; {check.rounds} {designs})"
    return text


def wheel_report(candidate: Design, omega: float, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The whole wheel of a design: its parts, stress check, burst speed, balance, key, sensitivities, notes.

    Parameters
    ----------
    candidate : flyopt.design.result.Design
        A feasible design.
    omega : float
        omega_max on the wheel's own shaft [rad/s] (the speed the stresses were checked at).
    units : str
        The unit system of every quantity (:data:`flyopt.report.display.SYSTEMS`).

    Returns
    -------
    list of str
        Report lines; a block appears only where the design carries its data
        (a textbook rim has parts and stresses, but no key).
    """
    c = candidate

    def n(value, name):  # a number of a table or list whose unit is written once; "-" if none
        return field_number(value, name, units, digits) if _finite(value) else "-"

    def q(value, name):  # a number with its unit; "-" if none
        return field_text(value, name, units, digits) if _finite(value) else "-"

    lines = []
    if c.parts.items:
        total_j = sum(p["inertia"] for p in c.parts.items)
        rows = [
            [
                p["name"],
                f"{n(p['r_inner'], 'r_inner')} – {n(p['r_outer'], 'r_outer')}",
                n(p["thickness"], "thickness"),
                n(p["mass"], "mass"),
                n(p["inertia"], "inertia"),
                share(p["inertia"] / total_j) if total_j > 0 else "-",
            ]
            for p in c.parts.items
        ]
        rows.append(
            [
                "total",
                f"{n(min(p['r_inner'] for p in c.parts.items), 'r_inner')} – "
                f"{n(max(p['r_outer'] for p in c.parts.items), 'r_outer')}",
                "",
                n(sum(p["mass"] for p in c.parts.items), "mass"),
                n(total_j, "inertia"),
                "100.0 %" if total_j > 0 else "-",
            ]
        )
        head = [
            "part",
            heading("r_inner – r_outer", "r_inner", units),
            heading("thickness", "thickness", units),
            heading("mass", "mass", units),
            heading("inertia", "inertia", units),
            "share of J",
        ]
        lines += ["", "Parts of the wheel (thickness: axial):"]
        body = table(head, rows, ["<", ">", ">", ">", ">", ">"])
        body.insert(len(body) - 1, "  ".join("-" * len(cell) for cell in body[1].split("  ")))
        lines += ["  " + line for line in body]
        if c.n_arms and c.dims.arm_major:
            lines.append(
                f"  arms: {c.n_arms} of elliptical section {n(c.dims.arm_major, 'arm_major')} x "
                f"{q(c.dims.arm_minor, 'arm_minor')} (major axis in the plane of rotation, minor axial)"
            )
    if c.stresses.stress:
        s = c.stresses.stress
        lines += ["", f"Stress check at ω_max = {q(omega, 'omega_max')} on its shaft:"]
        rows = []
        for p in s.get("parts", []):
            utilisation = p["stress"] / p["allowable"] if _finite(p["allowable"]) and p["allowable"] > 0 else None
            rows.append(
                [
                    p["part"],
                    n(p["stress"], "stress"),
                    n(p["radius"], "radius"),
                    n(p["allowable"], "allowable"),
                    "-" if utilisation is None else share(utilisation),
                    n(p.get("strength"), "strength"),
                    n(p.get("wall"), "wall"),
                ]
            )
        head = [
            "part",
            heading("stress", "stress", units),
            heading("at r", "radius", units),
            heading("allowable", "allowable", units),
            "utilisation",
            heading("strength", "strength", units),
            heading("at wall", "wall", units),
        ]
        lines += ["  " + line for line in table(head, rows)]
        lines.append(
            "  (stress: von Mises if ductile, largest principal if brittle; strength: yield if ductile, "
            "tensile if brittle, at the part's wall)"
        )
        where = s.get("where") or {}
        facts = []
        if where:
            facts.append(("governing", f"{where['part']} at r = {q(where['radius'], 'radius')}"))
        facts.append(
            (
                "largest σ_t / σ_r",
                f"{n(s.get('hoop_max'), 'hoop_max')} / "
                f"{q(s.get('radial_max'), 'radial_max')} "
                f"(von Mises {q(s.get('von_mises'), 'von_mises')})",
            )
        )
        if _finite(s.get("mean_hoop")):
            facts.append(("mean hoop stress", f"{q(s['mean_hoop'], 'mean_hoop')} over the radial section"))
        if _finite(c.stresses.strength_safety):
            facts.append(("safety on strength", number(c.stresses.strength_safety, min(3, digits))))
        if _finite(c.stresses.burst_speed):
            margin = (
                f" ({number(c.stresses.speed_margin, min(3, digits))} x ω_max)"
                if _finite(c.stresses.speed_margin)
                else ""
            )
            facts.append(("burst speed", f"{q(c.stresses.burst_speed, 'burst_speed')} on its shaft{margin}"))
        width = max(len(k) for k, _ in facts)
        lines += [f"  {k:<{width}}  {v}" for k, v in facts]
    if c.stresses.unbalance_permissible is not None and _finite(c.stresses.unbalance_permissible):
        eccentricity = (
            quantity_text(c.stresses.unbalance_permissible / c.mass, "eccentricity", units, digits) if c.mass else None
        )
        lines += [
            "",
            f"Permissible unbalance (ISO 21940-11, G6.3 at ω_max): "
            f"{q(c.stresses.unbalance_permissible, 'unbalance_permissible')}"
            + (f" (e_per {eccentricity})" if eccentricity else ""),
        ]
    if c.parts.key:
        k = c.parts.key
        verdict = key_verdict(k) + (" (see the notes)" if k["ok"] is None else "")
        lines += [
            "",
            f"Key (DIN 6885-1 form A) on a {q(c.bore, 'bore')} bore: {k['size']}, length "
            f"{q(k['length'], 'length')} (effective {q(k['effective_length'], 'effective_length')}): "
            f"{verdict}",
        ]
        if k["shear"] is not None:
            pressure = (
                "not checked: the hub's material gives no allowable"
                if k["allowable_pressure"] is None
                else f"allowable {q(k['allowable_pressure'], 'allowable_pressure')}"
            )
            lines.append(
                f"  at the peak torque {q(k['torque'], 'torque')} of the flywheel the cycle requires: bearing pressure "
                f"{q(k['bearing_pressure'], 'bearing_pressure')} ({pressure}), shear {q(k['shear'], 'shear')} "
                f"(allowable {q(k['allowable_shear'], 'allowable_shear')})"
            )
    if c.limits.sensitivities:
        lines += ["", f"{SENSITIVITY_HEADING}:"]
        lines += [f"  - {sensitivity_text(s, units, digits)}" for s in c.limits.sensitivities]
    if c.provenance.notes:
        lines += ["", "Notes:"] + [f"  - {said_text(n, units, digits)}" for n in c.provenance.notes]
    return lines


def verification_report(v: Verification, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The verification part of the ``flyopt solve --verify`` report (``units``: the unit system)."""
    q, _ = formatters(units, digits)
    verdict = "FLAGGED: the design misses the allowed δ" if v.flagged else "ok"
    shown = achieved_speed_range(v)
    return [
        "",
        f"Verification ({v.method}): {verdict}",
        f"  achieved δ {number(v.achieved_delta, digits)} against the allowed {number(v.delta_allowed, digits)} "
        f"(tolerance {number(v.tolerance, min(3, digits))}); {ACHIEVED_RANGE} {field_number(shown[0], 'omega_min', units, digits)} to "
        f"{q(shown[1], 'omega_max')}, mean {q(v.omega_mean, 'omega_mean')}; flywheel "
        f"{q(v.j_flywheel, 'j_flywheel')} at the reference shaft",
    ]


def flywheel_report(check: FlywheelCheck, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The part of ``flyopt solve`` for a [flywheel] that exists: the δ it leaves and what it does."""
    q, n = formatters(units, digits)
    wheel = check.flywheel
    given = q(wheel.inertia, "j_flywheel")
    if wheel.mass is not None and wheel.radius_of_gyration is not None:
        given += f" (m = {q(wheel.mass, 'mass')}, k = {q(wheel.radius_of_gyration, 'radius_of_gyration')})"
    facts = [
        (
            "flywheel given",
            f"{given} on shaft {visible(wheel.shaft)} (speed ratio {number(wheel.speed_ratio, digits)})",
        ),
        (
            "at the reference shaft",
            f"{q(wheel.j_at_reference, 'j_at_reference')}, with the machine's {q(check.j_machine, 'j_machine')}",
        ),
        (
            "δ reached",
            f"{number(check.achieved_delta, digits)} ({one_in(check.achieved_delta, digits)}, "
            f"±{number(50 * check.achieved_delta, digits)} % of the mean speed)"
            if check.achieved_delta > 0
            else "0",
        ),
        (ACHIEVED_RANGE, f"{n(check.omega_min, 'omega_min')} to {q(check.omega_max, 'omega_max')}"),
    ]
    if check.angle_omega_max is not None and check.angle_omega_min is not None:
        facts.append(
            (
                "ω_max / ω_min at",
                f"{n(check.angle_omega_max, 'angle_omega_max')} / {q(check.angle_omega_min, 'angle_omega_min')}",
            )
        )
    facts += [("A_max", q(check.a_max, "a_max")), ("energy swing", q(check.energy_swing, "energy_swing"))]
    if check.acceleration_max is not None and check.angle_acceleration_max is not None:
        facts.append(
            (
                "largest acceleration",
                f"{q(check.acceleration_max, 'acceleration_max')} at {q(check.angle_acceleration_max, 'angle')}",
            )
        )
    if check.acceleration_min is not None and check.angle_acceleration_min is not None:
        facts.append(
            (
                "largest deceleration",
                f"{q(-check.acceleration_min, 'acceleration_min')} at {q(check.angle_acceleration_min, 'angle')}",
            )
        )
    for angle, value in check.accelerations_at:  # flywheel.angles: dω/dt where the scene asks it
        facts.append((f"acceleration at {q(angle, 'angle')}", q(value, "angular_acceleration")))
    if check.delta_allowed is not None:
        if check.suffices:
            verdict = "suffices"
        else:
            verdict = "does NOT suffice"
        if check.j_required is not None and check.j_required > 0:
            share = f"{number(abs(100 * (check.margin or 0.0)), digits)} %"
            verdict += f": it gives {q(wheel.j_at_reference, 'j_at_reference')} at the reference shaft where "
            verdict += (
                f"{q(check.j_required, 'j_required')} is needed ({share} {'over' if check.suffices else 'short'})"
            )
        else:
            verdict += ": the machine holds δ without any flywheel"
        facts.append((f"against the allowed δ {number(check.delta_allowed, digits)}", verdict))
    width = max(len(label) for label, _ in facts)
    return [
        "",
        f"The flywheel that exists ({check.method}):",
        *(f"  {label:<{width}}  {text}" for label, text in facts),
    ]


def operation_report(
    result: OperationResult, title: str, source: str | None = None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> str:
    """``flyopt solve`` of an [operation]: one load on the flywheel, the speed after it, the rate the motor sustains."""
    q, n = formatters(units, digits)
    op = result.operation
    facts = [
        (
            "operation",
            f"{q(op.energy, 'energy')} in {q(op.duration, 'duration')}, the motor giving {q(op.motor_power, 'motor_power')}",
        ),
        ("inertia", f"{q(result.inertia, 'inertia')} at the reference shaft (machine and flywheel)"),
        ("from the motor meanwhile", q(result.energy_from_motor, "energy_from_motor")),
        ("from the flywheel", q(result.energy_from_flywheel, "energy_from_flywheel")),
        ("speed before / after", f"{n(result.omega_before, 'omega_before')} / {q(result.omega_after, 'omega_after')}"),
        (
            "speed drop",
            f"{number(100 * result.speed_drop, digits)} % (δ = {number(result.delta, digits)} about the mean of the two)",
        ),
        ("recovery time", f"{q(result.recovery_time, 'recovery_time')} (the motor refills the flywheel, unloaded)"),
        ("shortest interval", q(result.shortest_interval, "shortest_interval")),
        ("operations a minute", f"{number(60.0 * result.operation_rate, digits)} at most (60 P / E)"),
    ]
    if result.delta_allowed is not None:
        facts.append(
            (
                f"against the allowed δ {number(result.delta_allowed, digits)}",
                "holds" if result.holds else "does NOT hold",
            )
        )
    width = max(len(label) for label, _ in facts)
    head = visible(title) + (f"  ({visible(source)})" if source else "")
    return "\n".join(
        [
            head,
            "model: one operation, not a cycle: energy balance over its duration",
            "",
            *(f"  {a:<{width}}  {b}" for a, b in facts),
        ]
    )


def position_report(
    forces: CrankForces | PositionEquivalents,
    title: str,
    source: str | None = None,
    units: str = DEFAULT,
    digits: int = DEFAULT_DIGITS,
) -> str:
    """``flyopt solve`` of a [position]: a slider-crank engine's kinematics and forces at one crank angle, or
    (beside [[member]]s) a mechanism's equivalents at one position (:func:`equivalents_report`)."""
    from flyopt.machine.crank_forces import CrankForces

    if not isinstance(forces, CrankForces):
        return equivalents_report(forces, title, source, units, digits)
    q, _ = formatters(units, digits)
    p = forces.position
    load = f"{q(p.pressure, 'pressure')} on a {q(p.bore, 'bore')} bore" if p.gas_force is None else "given directly"
    facts = [
        ("crank angle", f"{q(p.angle, 'angle')} from the inner dead centre"),
        ("crank / rod", f"{q(p.crank, 'crank')} / {q(p.rod, 'rod')} (n = l/r = {number(p.rod / p.crank, digits)})"),
        ("speed", q(forces.omega, "omega")),
        ("obliquity of the rod β", q(forces.obliquity, "obliquity")),
        ("piston from the i.d.c.", q(forces.displacement, "displacement")),
        ("piston velocity", q(forces.velocity, "velocity")),
        ("piston acceleration", f"{q(forces.acceleration, 'acceleration')} (towards the crank +)"),
        ("gas force F_L", f"{q(forces.gas_force, 'gas_force')} ({load})"),
        (
            "inertia force F_I",
            f"{q(forces.inertia_force, 'inertia_force')} (m_R a, m_R = {q(p.reciprocating_mass, 'mass')})",
        ),
    ]
    if p.orientation == "vertical":
        facts.append(("weight m_R g", q(forces.weight, "weight")))
    facts += [
        ("piston effort F_P", q(forces.piston_effort, "piston_effort")),
        ("force in the rod F_Q", q(forces.rod_force, "rod_force")),
        ("thrust on the walls F_N", q(forces.thrust, "thrust")),
        ("crank pin, tangential F_T", q(forces.tangential_force, "tangential_force")),
        ("crank pin, radial F_R", q(forces.radial_force, "radial_force")),
        ("turning moment T", q(forces.turning_moment, "turning_moment")),
    ]
    width = max(len(label) for label, _ in facts)
    head = visible(title) + (f"  ({visible(source)})" if source else "")
    model = "one crank position of a slider-crank engine: exact kinematics, forces along the line of stroke"
    return "\n".join([head, f"model: {model}", "", *(f"  {a:<{width}}  {b}" for a, b in facts)])


#: The sense of an equivalent moment or force, in words (flyopt.machine.equivalents.SENSES).
_SENSE_WORDS = {
    "driving": "driving: it acts along the motion",
    "resisting": "resisting: it acts against the motion",
    "none": "none at this position",
}


def equivalents_report(
    result: PositionEquivalents,
    title: str,
    source: str | None = None,
    units: str = DEFAULT,
    digits: int = DEFAULT_DIGITS,
) -> str:
    """``flyopt solve`` of a [position] beside [[member]]s: each member's velocity ratios, the equivalent
    inertia and moment at the reference shaft, and (``reduce_to``) at another member and a point of it."""
    q, n = formatters(units, digits)
    p = result.position
    where = "any angle (nothing varies with it)" if p.angle is None else q(result.angle, "angle")
    if result.input_angle is not None and p.angle is not None:
        where += f" (the mechanism's input at {q(result.input_angle, 'input_angle')})"
    shares = [m.torque_share for m in result.members]  # one column, one unit
    rows = [
        [
            m.name,
            n(m.angular_ratio, "angular_ratio"),
            n(m.velocity_ratio, "velocity_ratio"),
            n(m.inertia_share, "inertia_share"),
            n(m.torque_share, "torque_share", shares),
        ]
        for m in result.members
    ]
    length = _label("velocity_ratio", units)
    lines = [
        visible(title) + (f"  ({visible(source)})" if source else ""),
        "model: a mechanism at one position reduced to the reference shaft (equal kinetic energy and power)",
        "",
        f"  angle of the reference shaft  {where}",
        "",
        *table(
            [
                "member",
                "ω_k/ω",
                f"v_S/ω [{length}/rad]",
                f"J share [{_label('inertia_share', units)}]",
                f"M share [{_label('torque_share', units, shares, digits)}]",
            ],
            rows,
        ),
        "",
    ]
    sense = _SENSE_WORDS[result.sense]
    facts = [
        (
            "equivalent inertia J_e",
            q(result.equivalent_inertia, "equivalent_inertia")
            + (f" (J_c = {q(result.j_constant, 'j_constant')} of it)" if result.j_constant else ""),
        ),
        ("equivalent moment M_e", f"{q(result.equivalent_moment, 'equivalent_moment')} ({sense})"),
    ]
    r = result.reduced
    if r is not None and r.turns and r.equivalent_inertia is not None and r.equivalent_moment is not None:
        facts += [
            (f"reduced to {visible(r.member)}", f"ω_1/ω_k = {number(1.0 / r.angular_ratio, digits)}"),
            ("  equivalent inertia", f"{q(r.equivalent_inertia, 'equivalent_inertia')} (J_e (ω_1/ω_k)²)"),
            ("  equivalent moment", f"{q(r.equivalent_moment, 'equivalent_moment')} ({sense}; M_e |ω_1/ω_k|)"),
        ]
        if r.radius is not None and r.equivalent_force is not None and r.equivalent_mass is not None:
            facts += [
                (
                    f"  at {q(r.radius, 'radius')} from its axis",
                    f"force {q(r.equivalent_force, 'equivalent_force')} ({sense}), "
                    f"mass {q(r.equivalent_mass, 'equivalent_mass')}",
                )
            ]
    elif r is not None and r.equivalent_force is not None and r.equivalent_mass is not None:
        facts += [
            (
                f"reduced to {visible(r.member)}",
                f"it translates here: v/ω_1 = {q(r.velocity_ratio, 'velocity_ratio')}/rad",
            ),
            ("  equivalent mass", f"{q(r.equivalent_mass, 'equivalent_mass')} (J_e (ω_1/v)²)"),
            ("  equivalent force", f"{q(r.equivalent_force, 'equivalent_force')} ({sense}; M_e |ω_1/v|)"),
        ]
    width = max(len(visible(a)) for a, _ in facts)
    return "\n".join([*lines, *(f"  {a:<{width}}  {b}" for a, b in facts)])


class DriveShaft(NamedTuple):
    """One shaft of an [electric_drive] reduced to the motor (:func:`drive_shafts`); SI, GD² in N·m²."""

    name: str
    ratio: float | None  # j_k of the stage before it (None: the motor's own shaft)
    efficiency: float | None  # η_k of that stage
    ratio_to_motor: float  # j_1 ⋯ j_k
    efficiency_to_motor: float  # η_1 ⋯ η_k
    speed: float  # ω [rad/s]
    gd2: float  # GD²_k on it
    gd2_reduced: float  # GD²_k / (j_1 ⋯ j_k)²
    gd2_with_losses: float  # GD²_k / ((j_1 ⋯ j_k)² η_1 ⋯ η_k)


def drive_shafts(drive: ReducedDrive) -> list[DriveShaft]:
    """The motor's shaft and the shaft after each stage, with their GD² at the motor plain and with the
    losses: the terms whose sums are ``gd2_total`` and ``gd2_with_losses`` (flyopt.machine.electric_drive),
    for the text report and the engineering report alike."""
    d = drive.drive
    shafts = [DriveShaft("motor", None, None, 1.0, 1.0, d.motor_speed, d.motor_gd2, d.motor_gd2, d.motor_gd2)]
    ratio = eta = 1.0
    for k, (stage, speed) in enumerate(zip(d.stages, drive.shaft_speeds, strict=True)):
        ratio *= stage.ratio
        eta *= stage.efficiency
        shafts.append(
            DriveShaft(
                f"after stage {k + 1}",
                stage.ratio,
                stage.efficiency,
                ratio,
                eta,
                speed,
                stage.gd2,
                stage.gd2 / ratio**2,
                stage.gd2 / (ratio**2 * eta),
            )
        )
    return shafts


def electric_drive_report(
    drive: ReducedDrive, title: str, source: str | None = None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> str:
    """``flyopt solve`` of an [electric_drive]: the drive reduced to the motor shaft, in the texts' terms."""
    q, n = formatters(units, digits)
    d = drive.drive
    rows = [
        [
            s.name,
            "-" if s.ratio is None else number(s.ratio, digits),
            "-" if s.efficiency is None else number(s.efficiency, digits),
            n(s.speed, "omega"),
            number(s.gd2, digits),
            number(s.gd2_reduced, digits),
            number(s.gd2_with_losses, digits),
        ]
        for s in drive_shafts(drive)
    ]
    speed_unit = _label("omega", units)
    lines = [
        visible(title) + (f"  ({visible(source)})" if source else ""),
        "model: an electric drive reduced to the motor shaft (equal kinetic energy; the texts' GD² with losses)",
        "",
        *table(
            ["shaft", "ratio", "efficiency", f"speed [{speed_unit}]", "GD² [N·m²]", "GD²/j²", "GD²/(j² η)"],
            rows,
        ),
        "",
    ]
    facts = [
        ("total ratio / efficiency", f"{number(drive.total_ratio, digits)} / {number(drive.efficiency, digits)}"),
        ("load", f"{q(d.load_torque, 'torque')} at {q(drive.load_speed, 'omega')}: {q(drive.load_power, 'power')}"),
        ("motor output power", f"{q(drive.motor_power, 'power')} (the load's over the efficiency)"),
        ("load torque at the motor", f"{q(drive.load_torque_at_motor, 'torque')} (T_L / (j η))"),
        (
            "GD² at the motor",
            f"{number(drive.gd2_total, digits)} N·m² (J = {q(drive.inertia_total, 'inertia')}, equal kinetic energy)",
        ),
        (
            "GD² with the losses",
            f"{number(drive.gd2_with_losses, digits)} N·m² (J = {q(drive.inertia_with_losses, 'inertia')}, the texts' convention for accelerating)",
        ),
    ]
    if drive.accelerating_torque is not None and drive.motor_torque is not None and d.acceleration is not None:
        facts += [
            (
                "accelerating torque",
                f"{q(drive.accelerating_torque, 'torque')} at dω/dt = {q(d.acceleration, 'motor_acceleration')}",
            ),
            ("motor torque, loaded", f"{q(drive.motor_torque, 'torque')} (load at the motor + accelerating)"),
        ]
    width = max(len(a) for a, _ in facts)
    return "\n".join([*lines, *(f"  {a:<{width}}  {b}" for a, b in facts)])


def power_chain_report(
    flow: PowerFlow, title: str, source: str | None = None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> str:
    """``flyopt solve`` of a [power_chain]: the motor's power, the overall efficiency, each branch's powers."""
    q, n = formatters(units, digits)

    def powers(branch: BranchFlow) -> list[float]:  # every power the table and the list show [W]
        own = [branch.power, branch.motor_power, branch.losses, *branch.stage_powers]
        return own + [p for child in branch.branches for p in powers(child)]

    every = powers(flow.trunk)  # one unit for the table and the list, chosen from their largest
    unit = _label("power", units, every, digits)
    rows: list[list[str]] = []
    through: list[str] = []

    def visit(branch: BranchFlow, depth: int) -> None:
        name = "  " * depth + branch.branch.name
        stages = " × ".join(number(eta, digits) for eta in branch.branch.stages) or "-"
        rows.append(
            [
                name,
                stages,
                number(branch.path_efficiency, digits),
                n(branch.power, "power", every),
                n(branch.motor_power, "motor_power", every),
                n(branch.losses, "power", every),
            ]
        )
        steps = [
            n(p, "power", every) + f" →({number(eta, digits)})→ "
            for p, eta in zip(branch.stage_powers, branch.branch.stages)
        ]
        through.append(f"  {name}: " + "".join(steps) + f"{n(branch.power, 'power', every)} {unit}")
        for child in branch.branches:
            visit(child, depth + 1)

    visit(flow.trunk, 0)
    facts = [
        ("motor power P_in", f"{q(flow.motor_power, 'motor_power')} (Σ P_k / η_k over the machines)"),
        ("delivered Σ P_out", q(flow.delivered, "load_power")),
        ("overall efficiency", f"{number(flow.efficiency, digits)} (Σ P_out / P_in)"),
        ("losses", q(flow.losses, "power")),
    ]
    width = max(len(a) for a, _ in facts)
    return "\n".join(
        [
            visible(title) + (f"  ({visible(source)})" if source else ""),
            "model: a power chain from one motor: stages in series, branches in parallel (P = P_out / η per stage)",
            "",
            *table(
                [
                    "branch",
                    "stages η",
                    "η from the motor",
                    f"at its end [{unit}]",
                    f"drawn at the motor [{unit}]",
                    f"losses on its way [{unit}]",
                ],
                rows,
            ),
            "",
            f"power through the stages [{unit}] (entering each stage, its η, and so on to the branch's end):",
            *through,
            "",
            *(f"  {a:<{width}}  {b}" for a, b in facts),
        ]
    )


#: The text of ``flyopt solve`` for each kind of scene that is one calculation (flyopt.io.scene.CALCULATIONS).
CALCULATION_REPORTS: dict[str, Callable[..., str]] = {
    "operation": operation_report,
    "position": position_report,
    "electric_drive": electric_drive_report,
    "power_chain": power_chain_report,
}
