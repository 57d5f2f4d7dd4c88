"""The section of the report for a flywheel that exists ([flywheel]): the δ it leaves, its speeds and accelerations."""

from __future__ import annotations

from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number, one_in
from flyopt.report.document import Facts, Paragraph


class ExistingFlywheelSection(BuilderBase):
    """The check of a [flywheel] that exists, in place of a design (docs/flywheel-design.md, section 15)."""

    def existing_flywheel_section(self) -> None:
        check = self.solution.flywheel
        if check is None:
            return
        wheel = check.flywheel
        blocks = self.section("The flywheel that exists", "flywheel")
        blocks.append(Paragraph(f"Given, not designed; {check.method} ({NOTES}, section 15)."))
        given: tuple = (self.q(wheel.inertia, "inertia", "j_flywheel"),)
        if wheel.mass is not None and wheel.radius_of_gyration is not None:
            given += (
                " (m = ",
                self.q(wheel.mass, "mass", "mass"),
                ", k = ",
                self.q(wheel.radius_of_gyration, "length", "radius_of_gyration"),
                ")",
            )
        given += (f" on the shaft {wheel.shaft} (speed ratio {number(wheel.speed_ratio, self.digits)})",)
        from flyopt.report.text import ACHIEVED_RANGE

        rows: list[tuple] = [
            ("flywheel given", given),
            (
                "at the reference shaft",
                (
                    self.q(wheel.j_at_reference, "inertia", "j_at_reference"),
                    ", with the machine's own ",
                    self.q(check.j_machine, "inertia", "j_machine"),
                ),
            ),
            (
                "δ reached",
                (
                    self.q(check.achieved_delta, "dimensionless", "achieved_delta"),
                    f" ({one_in(check.achieved_delta, self.digits)})" if check.achieved_delta > 0 else "",
                ),
            ),
            (
                ACHIEVED_RANGE,
                (
                    self.q(check.omega_min, "angular_speed", "omega_min"),
                    " to ",
                    self.q(check.omega_max, "angular_speed", "omega_max"),
                ),
            ),
        ]
        if check.angle_omega_max is not None and check.angle_omega_min is not None:
            rows.append(
                (
                    "ω_{max} / ω_{min} at",
                    (
                        self.q(check.angle_omega_max, "angle", "angle_omega_max"),
                        " / ",
                        self.q(check.angle_omega_min, "angle", "angle_omega_min"),
                    ),
                )
            )
        rows += [
            ("A_{max}", self.q(check.a_max, "energy", "a_max")),
            ("energy swing", self.q(check.energy_swing, "energy", "energy_swing")),
        ]
        for label, value, angle in (
            ("largest acceleration", check.acceleration_max, check.angle_acceleration_max),
            (
                "largest deceleration",
                None if check.acceleration_min is None else -check.acceleration_min,
                check.angle_acceleration_min,
            ),
        ):
            if value is not None and angle is not None:
                rows.append(
                    (label, (self.q(value, "angular_acceleration", "acceleration_max"), " at ", self.q(angle, "angle")))
                )
        for angle, value in check.accelerations_at:  # flywheel.angles: dω/dt where the scene asks it
            rows.append(
                (
                    ("acceleration at ", self.q(angle, "angle")),
                    self.q(value, "angular_acceleration", "angular_acceleration"),
                )
            )
        blocks.append(Facts(tuple(rows), "flywheel"))
        if check.delta_allowed is None:
            return
        if check.suffices:
            verdict = f"It suffices for the allowed δ = {number(check.delta_allowed, self.digits)}"
        else:
            verdict = f"It does NOT suffice for the allowed δ = {number(check.delta_allowed, self.digits)}"
        if check.j_required is not None and check.j_required > 0 and check.margin is not None:
            verdict += (
                f": it gives {number(wheel.j_at_reference, self.worked)} kg·m² at the reference shaft where "
                f"{number(check.j_required, self.worked)} kg·m² are needed ({number(abs(100 * check.margin), self.worked)} % "
                f"{'over' if check.suffices else 'short'})."
            )
        else:
            verdict += ": the machine holds δ without any flywheel."
        blocks.append(Paragraph(verdict, "ok" if check.suffices else "warning"))
