"""The drive part of the text report: the motor, ratios and wheel designed together (flyopt.design.drive)."""

from flyopt.report.text import number, power, table
from flyopt.units import rad_s_to_rpm


def drive_report(drive, check=None):
    """Lines of the report for a :class:`flyopt.design.drive.DriveDesign` (and its :class:`DriveCheck`)."""
    lines = ["", f"Drive designed with the flywheel (objective: {drive.objective}; {drive.note}):"]
    best = drive.best
    if best is None:
        lines.append(f"  INFEASIBLE: {drive.message}")
    else:
        m = best.motor
        lines += [
            f"  motor                {m.name}: {power(m.rated_power)} at {number(rad_s_to_rpm(m.rated_speed), 5)} rpm "
            f"(rated torque {number(m.rated_torque, 4)} N·m, rotor {number(m.rotor_inertia, 4)} kg·m²)",
            f"  motor ratio          {number(best.motor_ratio, 6)} (motor speed over crank speed)",
            f"  flywheel             {number(best.j_flywheel, 6)} kg·m² at the crank, set by "
            f"{_limit_words(best.limit)}" + (f" (δ alone needs {number(best.j_delta, 6)})"
                                              if best.limit == "thermal" else ""),
        ]
        if best.flywheel_ratio is not None:
            lines.append(f"  flywheel shaft       ratio {number(best.flywheel_ratio, 6)} to the crank; the wheel below")
        lines += [
            f"  RMS torque           {number(best.rms_torque, 5)} N·m of the rated {number(best.rated_torque, 5)} N·m "
            f"(mean {number(best.mean_torque, 5)} N·m)",
            f"  start-up             {number(best.startup_time, 4)} s from rest (Kloss curve, declutched)",
            f"  masses               motor {number(best.motor_mass, 4)} kg + wheel {number(best.wheel_mass, 4)} kg "
            f"= {number(best.total_mass, 5)} kg" + (f"; cost {number(best.cost, 5)}" if best.cost is not None else ""),
        ]
        if drive.relaxation is not None:
            r = drive.relaxation
            lines.append(f"  relaxation           {power(r.rated_power)}, motor ratio {number(r.motor_ratio, 5)}, "
                         f"flywheel ratio {number(r.flywheel_ratio, 4)}, {number(r.j_flywheel, 5)} kg·m² "
                         f"({r.status}; a thin-ring wheel, a lower bound)")
            unit = "kg" if drive.objective == "mass" else "(currency)"
            steps = (("delta", 0.01, "δ +0.01"), ("max_startup", 1.0, "max_startup +1 s"),
                     ("rim_speed", 1.0, "safe rim speed +1 m/s"), ("ratio_max", 1.0, "largest flywheel ratio +1"),
                     ("ratio_min", -1.0, "smallest flywheel ratio −1"),
                     ("max_outer_diameter", 0.1, "envelope +100 mm"))
            moved = [f"{words}: {number(r.sensitivities[name] * step, 4)} {unit}" for name, step, words in steps
                     if abs(r.sensitivities.get(name, 0.0)) > 1e-9 * max(abs(r.objective), 1.0)]
            if moved:
                lines.append("  binding limits       " + "; ".join(moved) + " (relaxed optimum, first order)")
    head = ["motor", "P [kW]", "ratio", "J_F [kg·m²]", "limit", "RMS/rated", "start [s]", "r", "wheel [kg]",
            "total [kg]", "verdict"]
    rows = []
    for run in drive.runs:
        rows.append([run.motor.name, number(run.motor.rated_power / 1000, 4), number(run.motor_ratio, 5),
                     number(run.j_flywheel, 5), run.limit or "-",
                     number(run.rms_torque / run.rated_torque, 4) if run.rms_torque else "-",
                     number(run.startup_time, 4), number(run.flywheel_ratio, 4), number(run.wheel_mass, 5),
                     number(run.total_mass, 5),
                     ("best" if run is best else "ok") if run.feasible else run.reason])
    lines += ["", "Every motor size solved:"] + ["  " + line for line in table(head, rows, ["<"] + [">"] * 9 + ["<"])]
    if check is not None:
        v = check.verification
        verdict = "FLAGGED: " + "; ".join(check.notes) if check.flagged else "ok"
        lines += ["", f"Drive verification (the machine simulated with the wheel as built): {verdict}",
                  f"  achieved δ {number(v.achieved_delta)} against {number(v.delta_allowed)}; mean speed "
                  f"{number(rad_s_to_rpm(v.omega_mean), 6)} rpm; RMS torque {number(check.rms_torque, 5)} of "
                  f"{number(check.rated_torque, 5)} N·m; start-up {number(check.startup_time, 4)} s"]
    return lines


def _limit_words(limit):
    return {"delta": "the speed fluctuation δ", "thermal": "the motor's thermal limit (RMS torque = rated)",
            "none": "nothing: the machine needs no flywheel"}.get(limit, str(limit))
