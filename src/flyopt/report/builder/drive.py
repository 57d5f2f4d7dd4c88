"""Section 7 of the report: the drive (motor, start-up, relaxation)."""

from __future__ import annotations

from typing import Any

from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import Column, number, said_text
from flyopt.report.document import Facts, Paragraph, Table


class DriveSection(BuilderBase):
    """Section 7 of the report."""

    def drive_section(self) -> None:
        drive, check = self.solution.drive, self.solution.drive_check
        if drive is None:
            return
        from flyopt.report.drive import check_verdict, limit_words, run_verdict

        blocks = self.section("The drive designed with the flywheel", "drive")
        blocks.append(
            Paragraph(
                f"The motor, its ratio and the flywheel's shaft designed together (objective: "
                f"{drive.objective}; {drive.note}; {NOTES}, section 14)."
            )
        )
        best = drive.best
        if best is None:
            blocks.append(Paragraph(f"INFEASIBLE: {said_text(drive.message, self.units, self.digits)}", "warning"))
        else:
            m = best.motor
            rows: list[Any] = [
                (
                    "motor",
                    (
                        f"{m.name}: ",
                        self.q(m.rated_power, "power", "rated_power"),
                        " at ",
                        self.q(m.rated_speed, "angular_speed", "rated_speed"),
                        " (rated torque ",
                        self.q(m.rated_torque, "torque", "rated_torque"),
                        ", rotor ",
                        self.q(m.rotor_inertia, "inertia", "rotor_inertia"),
                        ")",
                    ),
                ),
                ("motor ratio", f"{number(best.motor_ratio, self.digits)} (motor speed over crank speed)"),
                (
                    "flywheel",
                    (
                        self.q(best.j_flywheel, "inertia", "j_flywheel"),
                        " at the crank, set by ",
                        limit_words(best.limit),
                    ),
                ),
                (
                    "RMS torque",
                    (
                        self.q(best.rms_torque, "torque", "rms_torque"),
                        " of the rated ",
                        self.q(best.rated_torque, "torque"),
                        " (mean ",
                        self.q(best.mean_torque, "torque", "mean_torque"),
                        ")",
                    ),
                ),
                (
                    "start-up",
                    (self.q(best.startup_time, "time", "startup_time"), " from rest (Kloss curve, declutched)"),
                ),
                (
                    "masses",
                    (
                        "motor ",
                        self.q(best.motor_mass, "mass"),
                        " + wheel ",
                        self.q(best.wheel_mass, "mass"),
                        " = ",
                        self.q(best.total_mass, "mass", "total_mass"),
                    ),
                ),
            ]
            if best.flywheel_ratio is not None:
                rows.insert(3, ("flywheel shaft ratio", number(best.flywheel_ratio, self.digits)))
            if best.cost is not None:
                rows.append(("cost", number(best.cost, self.digits)))
            if drive.relaxation is not None:
                from flyopt.report.drive import relaxation_summary

                summary, moved = relaxation_summary(drive, self.units, self.digits)
                rows.append(("relaxed optimum", summary))
                if moved:
                    rows.append(("binding limits", "; ".join(moved) + " (relaxed optimum, first order)"))
            blocks.append(Facts(tuple(rows), "drive"))
        rows = []
        rated = Column(run.motor.rated_power for run in drive.runs)  # one unit for the column, chosen from its largest
        for run in drive.runs:
            rows.append(
                [
                    run.motor.name,
                    self.n(run.motor.rated_power, "power", among=rated),
                    number(run.motor_ratio, self.digits),
                    self.n(run.j_flywheel, "inertia"),
                    run.limit or "-",
                    number(run.rms_torque / run.rated_torque, self.digits)
                    if run.rms_torque and run.rated_torque
                    else "-",
                    self.n(run.startup_time, "time"),
                    number(run.flywheel_ratio, self.digits),
                    self.n(run.wheel_mass, "mass"),
                    self.n(run.total_mass, "mass"),
                    run_verdict(run, best, self.units, self.digits),
                ]
            )
        blocks.append(
            Table(
                (
                    "motor",
                    self.head("rated power", "power", rated),
                    "motor ratio",
                    self.head("J_{F}", "inertia"),
                    "limit",
                    "RMS / rated torque",
                    self.head("start-up", "time"),
                    "flywheel ratio r",
                    self.head("wheel", "mass"),
                    self.head("total", "mass"),
                    "verdict",
                ),
                tuple(rows),
                ("<",) + (">",) * 9 + ("<",),
                "Every motor size solved",
                "drive_runs",
            )
        )
        if check is not None:
            v = check.verification
            verdict = check_verdict(check, self.units, self.digits)
            blocks.append(
                Paragraph(
                    (
                        f"Drive verification (the machine simulated with the wheel as built): {verdict}. "
                        f"Achieved δ {number(v.achieved_delta, self.digits)} against {number(v.delta_allowed, self.digits)}; mean "
                        "speed ",
                        self.q(v.omega_mean, "angular_speed"),
                        "; RMS torque ",
                        self.q(check.rms_torque, "torque"),
                        " of ",
                        self.q(check.rated_torque, "torque"),
                        "; start-up ",
                        self.q(check.startup_time, "time"),
                        ".",
                    ),
                    "warning" if check.flagged else "ok",
                )
            )
