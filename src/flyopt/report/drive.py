"""The drive part of the text report: the motor, ratios and wheel designed together (flyopt.drive.codesign).

Quantities are shown in the reader's unit system through :mod:`flyopt.report.display`,
like the rest of the report (:mod:`flyopt.report.text`); the JSON stays SI.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from flyopt.report.characters import visible
from flyopt.report.display import DEFAULT, field_text, heading, label, number, unit
from flyopt.report.text import ACHIEVED_RANGE, formatters, table

if TYPE_CHECKING:
    from flyopt.drive.codesign import DriveCheck, DriveDesign

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


def drive_report(drive: DriveDesign, check: DriveCheck | None = None, units: str = DEFAULT) -> list[str]:
    """Lines of the report for a :class:`flyopt.drive.codesign.DriveDesign` (and its :class:`DriveCheck`).

    ``units``: the unit system of every quantity (:data:`flyopt.report.display.SYSTEMS`).
    """
    q, n = formatters(units)
    lines = ["", f"Drive designed with the flywheel (objective: {drive.objective}; {drive.note}):"]
    best = drive.best
    if best is None:
        lines.append(f"  INFEASIBLE: {drive.message}")
    else:
        m = best.motor
        lines += [
            f"  motor                {visible(m.name)}: {q(m.rated_power, 'rated_power')} at "
            f"{q(m.rated_speed, 'rated_speed', 5)} (rated torque {q(m.rated_torque, 'rated_torque', 4)}, "
            f"rotor {q(m.rotor_inertia, 'rotor_inertia', 4)})",
            f"  motor ratio          {number(best.motor_ratio, 6)} (motor speed over crank speed)",
            f"  flywheel             {q(best.j_flywheel, 'j_flywheel', 6)} at the crank, set by "
            f"{limit_words(best.limit)}"
            + (f" (δ alone needs {q(best.j_delta, 'j_delta', 6)})" if best.limit == "thermal" else ""),
        ]
        if best.flywheel_ratio is not None:
            lines.append(f"  flywheel shaft       ratio {number(best.flywheel_ratio, 6)} to the crank; the wheel below")
        lines += [
            f"  RMS torque           {q(best.rms_torque, 'rms_torque', 5)} of the rated "
            f"{q(best.rated_torque, 'rated_torque', 5)} (mean {q(best.mean_torque, 'mean_torque', 5)})",
            f"  start-up             {q(best.startup_time, 'startup_time', 4)} from rest (Kloss curve, declutched)",
            f"  masses               motor {q(best.motor_mass, 'motor_mass', 4)} + wheel "
            f"{q(best.wheel_mass, 'wheel_mass', 4)} = {q(best.total_mass, 'total_mass', 5)}"
            + (f"; cost {number(best.cost, 5)}" if best.cost is not None else ""),
        ]
        if drive.relaxation is not None:
            lines += _relaxation_lines(drive, units)
    head = [
        "motor",
        heading("P", "rated_power", units),
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
                n(run.motor.rated_power, "rated_power", 4),
                number(run.motor_ratio, 5),
                n(run.j_flywheel, "j_flywheel", 5),
                run.limit or "-",
                number(run.rms_torque / run.rated_torque, 4) if run.rms_torque and run.rated_torque else "-",
                n(run.startup_time, "startup_time", 4),
                number(run.flywheel_ratio, 4),
                n(run.wheel_mass, "wheel_mass", 5),
                n(run.total_mass, "total_mass", 5),
                ("best" if run is best else "ok") if run.feasible else run.reason,
            ]
        )
    lines += ["", "Every motor size solved:"] + ["  " + line for line in table(head, rows, ["<"] + [">"] * 9 + ["<"])]
    if check is not None:
        v = check.verification
        verdict = "FLAGGED: " + "; ".join(check.notes) if check.flagged else "ok"
        lines += [
            "",
            f"Drive verification (the machine simulated with the wheel as built): {verdict}",
            f"  achieved δ {number(v.achieved_delta)} against {number(v.delta_allowed)}; {ACHIEVED_RANGE} "
            f"{n(v.omega_min, 'omega_min', 6)} to {q(v.omega_max, 'omega_max', 6)}, mean "
            f"{q(v.omega_mean, 'omega_mean', 6)}; RMS torque {n(check.rms_torque, 'rms_torque', 5)} of "
            f"{q(check.rated_torque, 'rated_torque', 5)}; start-up {q(check.startup_time, 'startup_time', 4)}",
        ]
    return lines


def relaxation_summary(drive: DriveDesign, units: str) -> tuple[str, list[str]]:
    """(the relaxed optimum in words, what relaxing each binding limit by a round step saves, first order),
    in ``units``: the text report and the HTML/PDF document say the same."""
    r = drive.relaxation
    if r is None:
        raise ValueError("the drive has no relaxation to summarise")
    summary = (
        f"{field_text(r.rated_power, 'rated_power', units)}, motor ratio {number(r.motor_ratio, 5)}, "
        f"flywheel ratio {number(r.flywheel_ratio, 4)}, {field_text(r.j_flywheel, 'j_flywheel', units, 5)}, "
        f"wheel {r.wheel} {field_text(r.wheel_mass, 'wheel_mass', units, 5)}, D "
        f"{field_text(r.d_outer, 'd_outer', units, 4)} ({r.status}; the whole-wheel NLP at the strongest "
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
            field_text(change, "total_mass", units, 4)
            if drive.objective == "mass"
            else f"{number(change, 4)} (currency)"
        )
        sign = "+" if shown > 0 else "−"
        name = label(dimension, units)
        step_text = number(abs(shown), 4) + ("" if name == "-" else f" {name}")
        moved.append(f"{words} {sign}{step_text}: {amount}")
    return summary, moved


def _relaxation_lines(drive, units):
    """The relaxed optimum and what relaxing each binding limit by a round step would save (first order)."""
    summary, moved = relaxation_summary(drive, units)
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
