"""The drive part of the text report: the motor, ratios and wheel designed together (flyopt.drive.codesign).

Quantities are shown in the reader's unit system through :mod:`flyopt.report.display`,
like the rest of the report (:mod:`flyopt.report.text`); the JSON stays SI.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from flyopt.report.characters import visible
from flyopt.report.display import DEFAULT, DEFAULT_DIGITS, field_text, heading, label, number, said_text, unit
from flyopt.report.text import ACHIEVED_RANGE, achieved_speed_range, formatters, table

if TYPE_CHECKING:
    from flyopt.drive.codesign import DriveCheck, DriveDesign, MotorRun

#: The step of a relaxed limit that the report gives the objective's change for, in the shown
#: unit of the limit's dimension: a round amount in each system (the envelope +100 mm, +0.1 m
#: or +4 in; the safe rim speed +1 m/s or +1 ft/s). Dimensionless limits and time step the same
#: in every system. Rows: (limit, words, dimension, the step by system or one for all).
RELAXED_STEPS = (
    ("delta", "δ", "dimensionless", 0.01),
    ("max_startup", "max_startup", "time", 1.0),
    ("rim_speed", "safe rim speed", "speed", 1.0),
    ("ratio_max", "largest flywheel ratio", "dimensionless", 1.0),
    ("ratio_min", "smallest flywheel ratio", "dimensionless", -1.0),
    ("max_outer_diameter", "envelope", "length", {"engineering": 100.0, "si": 0.1, "imperial": 4.0}),
)


def run_verdict(run: MotorRun, best: MotorRun | None, units: str, digits: int) -> str:
    """A motor size's verdict in the table of sizes: "best", "ok", or why it is refused, in the reader's units
    (its reason keeps its quantities: :mod:`flyopt.said`)."""
    return ("best" if run is best else "ok") if run.feasible else said_text(run.reason, units, digits)


def check_verdict(check: DriveCheck, units: str, digits: int) -> str:
    """The verdict of the chosen drive's verification: "ok", or "FLAGGED: " and its notes in the reader's units."""
    return "FLAGGED: " + "; ".join(said_text(n, units, digits) for n in check.notes) if check.flagged else "ok"


def drive_report(
    drive: DriveDesign, check: DriveCheck | None = None, units: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> list[str]:
    """Lines of the report for a :class:`flyopt.drive.codesign.DriveDesign` (and its :class:`DriveCheck`).

    ``units``: the unit system of every quantity (:data:`flyopt.report.display.SYSTEMS`); ``digits``: the
    significant figures of every number.
    """
    q, n = formatters(units, digits)
    lines = ["", f"Drive designed with the flywheel (objective: {drive.objective}; {drive.note}):"]
    best = drive.best
    if best is None:
        lines.append(f"  INFEASIBLE: {said_text(drive.message, units, digits)}")
    else:
        m = best.motor
        lines += [
            f"  motor                {visible(m.name)}: {q(m.rated_power, 'rated_power')} at "
            f"{q(m.rated_speed, 'rated_speed')} (rated torque {q(m.rated_torque, 'rated_torque')}, "
            f"rotor {q(m.rotor_inertia, 'rotor_inertia')})",
            f"  motor ratio          {number(best.motor_ratio, digits)} (motor speed over crank speed)",
            f"  flywheel             {q(best.j_flywheel, 'j_flywheel')} at the crank, set by "
            f"{limit_words(best.limit)}"
            + (f" (δ alone needs {q(best.j_delta, 'j_delta')})" if best.limit == "thermal" else ""),
        ]
        if best.flywheel_ratio is not None:
            lines.append(
                f"  flywheel shaft       ratio {number(best.flywheel_ratio, digits)} to the crank; the wheel below"
            )
        lines += [
            f"  RMS torque           {q(best.rms_torque, 'rms_torque')} of the rated "
            f"{q(best.rated_torque, 'rated_torque')} (mean {q(best.mean_torque, 'mean_torque')})",
            f"  start-up             {q(best.startup_time, 'startup_time')} from rest (Kloss curve, declutched)",
            f"  masses               motor {q(best.motor_mass, 'motor_mass')} + wheel "
            f"{q(best.wheel_mass, 'wheel_mass')} = {q(best.total_mass, 'total_mass')}"
            + (f"; cost {number(best.cost, digits)}" if best.cost is not None else ""),
        ]
        if drive.relaxation is not None:
            lines += _relaxation_lines(drive, units, digits)
    rated = [run.motor.rated_power for run in drive.runs]  # one unit for the column, chosen from its largest
    head = [
        "motor",
        heading("P", "rated_power", units, rated, digits),
        "ratio",
        heading("J_F", "j_flywheel", units),
        "limit",
        "RMS/rated",
        heading("start", "startup_time", units),
        "r",
        heading("wheel", "wheel_mass", units),
        heading("total", "total_mass", units),
        "verdict",
    ]
    rows = []
    for run in drive.runs:
        rows.append(
            [
                run.motor.name,
                n(run.motor.rated_power, "rated_power", rated),
                number(run.motor_ratio, digits),
                n(run.j_flywheel, "j_flywheel"),
                run.limit or "-",
                number(run.rms_torque / run.rated_torque, digits) if run.rms_torque and run.rated_torque else "-",
                n(run.startup_time, "startup_time"),
                number(run.flywheel_ratio, digits),
                n(run.wheel_mass, "wheel_mass"),
                n(run.total_mass, "total_mass"),
                run_verdict(run, best, units, digits),
            ]
        )
    lines += ["", "Every motor size solved:"] + ["  " + line for line in table(head, rows, ["<"] + [">"] * 9 + ["<"])]
    if check is not None:
        v = check.verification
        verdict = check_verdict(check, units, digits)
        pair = [check.rms_torque, check.rated_torque]  # "31.22 of 36.1 N·m": one unit for the two
        shown = achieved_speed_range(v)
        lines += [
            "",
            f"Drive verification (the machine simulated with the wheel as built): {verdict}",
            f"  achieved δ {number(v.achieved_delta, digits)} against {number(v.delta_allowed, digits)}; {ACHIEVED_RANGE} "
            f"{n(shown[0], 'omega_min')} to {q(shown[1], 'omega_max')}, mean "
            f"{q(v.omega_mean, 'omega_mean')}; RMS torque {n(check.rms_torque, 'rms_torque', pair)} of "
            f"{q(check.rated_torque, 'rated_torque', pair)}; start-up {q(check.startup_time, 'startup_time')}",
        ]
    return lines


def relaxation_summary(drive: DriveDesign, units: str, digits: int = DEFAULT_DIGITS) -> tuple[str, list[str]]:
    """(the relaxed optimum in words, what relaxing each binding limit by a round step saves, first order),
    in ``units``: the text report and the HTML/PDF document say the same."""
    r = drive.relaxation
    if r is None:
        raise ValueError("the drive has no relaxation to summarise")
    material, comma, arms = r.wheel.partition(", ")  # the relaxation's label: the material's key[, n arms]
    named = next((run.design for run in drive.runs if run.design is not None), None)
    wheel = (named.material_name(material) if named is not None else material.replace("_", " ")) + comma + arms
    summary = (
        f"{field_text(r.rated_power, 'rated_power', units, digits)}, motor ratio {number(r.motor_ratio, digits)}, "
        f"flywheel ratio {number(r.flywheel_ratio, digits)}, {field_text(r.j_flywheel, 'j_flywheel', units, digits)}, "
        f"wheel {wheel} {field_text(r.wheel_mass, 'wheel_mass', units, digits)}, D "
        f"{field_text(r.d_outer, 'd_outer', units, digits)} ({r.status}; the whole-wheel NLP at the strongest "
        f"allowable, no torque on the hub)"
    )
    moved = []
    for name, words, dimension, steps in RELAXED_STEPS:
        sensitivity = r.sensitivities.get(name, 0.0)  # objective per SI unit of the limit
        if abs(sensitivity) <= 1e-9 * max(abs(r.objective), 1.0):
            continue
        shown = steps[units] if isinstance(steps, dict) else steps
        step = shown * unit(dimension, units)[1]  # the step in SI
        change = sensitivity * step
        amount = (
            field_text(change, "total_mass", units, digits)
            if drive.objective == "mass"
            else f"{number(change, digits)} (currency)"
        )
        sign = "+" if shown > 0 else "−"
        name = label(dimension, units)
        step_text = number(abs(shown), digits) + ("" if name == "-" else f" {name}")
        moved.append(f"{words} {sign}{step_text}: {amount}")
    return summary, moved


def _relaxation_lines(drive, units, digits):
    """The relaxed optimum and what relaxing each binding limit by a round step would save (first order)."""
    summary, moved = relaxation_summary(drive, units, digits)
    lines = [f"  relaxation           {summary}"]
    if moved:
        lines.append("  binding limits       " + "; ".join(moved) + " (relaxed optimum, first order)")
    return lines


def limit_words(limit: str | None) -> str:
    """What a binding limit of the drive is, in words."""
    return {
        "delta": "the speed fluctuation δ",
        "thermal": "the motor's thermal limit (RMS torque = rated)",
        "none": "nothing: the machine needs no flywheel",
    }.get(str(limit), str(limit))
