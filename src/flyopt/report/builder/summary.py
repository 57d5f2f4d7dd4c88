"""Section 1 of the report: the answer first (required J_F, the chosen wheel, its mass and dimensions, the binding limits, the verified δ)."""

from __future__ import annotations

from flyopt.design.check import binding_label
from flyopt.design.combination import shaft_label, wheel_words
from flyopt.errors import BrokenInvariant
from flyopt.report import display
from flyopt.report.builder.base import BuilderBase
from flyopt.report.display import number, one_in
from flyopt.report.document import Facts, Paragraph
from flyopt.said import indefinite


class Summary(BuilderBase):
    """Section 1 of the report."""

    def summary(self) -> None:
        a, d, best = self.analysis, self.design, self.best()
        blocks = self.section("Summary", "summary")
        best_made = best is None or best.parts.thin_wall is None  # a wheel that cannot be made as sized: a warning
        bad = self.solution.status in ("infeasible", "insufficient") or self.flagged() or not best_made
        blocks.append(Paragraph(self.answer(), "warning" if bad else "ok"))
        book = d.book_rim() if d is not None else None
        if book is not None:  # the courses' rim: its verdict is the design section's, said here too
            blocks.append(self.book_rim_verdict(book))
        rows = [
            ("model", f"{a.model} ({self.model_description(a.model)})"),
            ("mean speed ω_{m}", self.q(a.omega_mean, "angular_speed", "omega_mean")),
            (
                "δ reached with the flywheel given" if self.solution.flywheel is not None else "allowed δ",
                (
                    self.q(a.delta, "dimensionless", "delta"),
                    f" ({one_in(a.delta, self.digits)})" if a.delta > 0 else "",
                ),
            ),
        ]
        from flyopt.report.text import (
            ACHIEVED_RANGE,
            ALLOWED_RANGE,
            achieved_speed_range,
            allowed_speed_range,
            reached_below_allowed,
        )

        v = self.solution.verification or (
            self.solution.drive_check.verification if self.solution.drive_check is not None else None
        )
        if self.solution.flywheel is None:
            low, high = allowed_speed_range(a)
            rows.append(
                (
                    ALLOWED_RANGE,
                    (self.q(low, "angular_speed"), " to ", self.q(high, "angular_speed"), " (ω_{m} (1 ± δ/2))"),
                )
            )
            # achieved: the machine as designed, simulated; or, unverified, the dynamic model's own solution
            # where it stays below the allowed δ (no flywheel needed)
            # (the simulation's speeds are not the analysis' omega_max/omega_min: named only where they are)
            if v is not None:
                shown = achieved_speed_range(v, (low, high))
                reached = (self.q(shown[0], "angular_speed"), self.q(shown[1], "angular_speed"), "verified")
            elif reached_below_allowed(a):
                reached = (
                    self.q(a.omega_min, "angular_speed", "omega_min"),
                    self.q(a.omega_max, "angular_speed", "omega_max"),
                    "the periodic solution",
                )
            if v is not None or reached_below_allowed(a):
                rows.append((ACHIEVED_RANGE, (reached[0], " to ", reached[1], f" ({reached[2]})")))
        rows.append(("A_{max}", self.q(a.a_max, "energy", "a_max")))
        if a.flywheel_needed:
            rows.append(
                (
                    "required flywheel J_{F}",
                    (
                        self.q(a.j_required, "inertia", "j_required"),
                        " at the reference shaft (GD² ",
                        self.q(a.gd2_required, "flywheel_moment", "gd2_required"),
                        ")",
                    ),
                )
            )
        else:
            from flyopt.report.text import no_flywheel_words

            before, after = no_flywheel_words(a)
            rows.append(
                ("required flywheel J_{F}", (f"none: {before} ", self.q(a.j_margin, "inertia", "j_margin"), after))
            )
        if a.motor_power is not None:
            rows.append(
                (
                    "motor power",
                    (
                        self.q(a.motor_power, "power", "motor_power"),
                        f" (efficiency {number(a.efficiency, self.digits)})",
                    ),
                )
            )
        if best is not None:
            rows += [
                (
                    "chosen wheel",
                    f"{wheel_words(best.geometry, best.n_arms)} of {self.material_name(best.material)} on the "
                    f"{shaft_label(best.shaft)} "
                    f"(speed ratio {number(best.speed_ratio, self.digits)})",
                ),
                ("mass", self.q(best.mass, "mass", "mass")),
                ("outer diameter", self.q(best.dims.d_outer, "length", "d_outer")),
                self.width_row(best),
                ("inertia on its shaft", self.q(best.j_flywheel, "inertia", "j_flywheel")),
                (
                    "rim speed",
                    tuple(
                        display.rim_speed_answer(
                            best.stresses.rim_speed,
                            best.limits.rim_speed_limit,
                            book,
                            lambda v, name: self.q(v, "speed", name),
                        )
                    ),
                ),
                ("binding limits", ", ".join(binding_label(b) for b in best.limits.binding) or "none"),
            ]
            k = best.parts.key
            if k and k.get("shear") is not None:  # the hub's key at the peak torque (section 13)
                parts = display.key_answer(
                    k, self.material_name(best.material), lambda v, name: self.q(v, display.dimension_of(name), name)
                )
                rows.append(("hub key", tuple(parts)))
            if best.stresses.stress and (best.stresses.stress.get("where") or {}).get("part"):
                governing = self.governing(best)
                if governing is not None:
                    rows.append(
                        (
                            "governing stress",
                            (
                                self.q(governing["stress"], "stress", "stress"),
                                f" in the {governing['part']}, ",
                                display.share_of_allowable(governing["stress"] / governing["allowable"])
                                if governing.get("allowable")
                                else "",
                            ),
                        )
                    )
            thin = best.parts.thin_wall
            if thin is not None:  # a bare wheel thinner than can be made (the design's notes say more)
                parts = display.thin_wall_answer(thin, lambda v, name: self.q(v, "length", name))
                rows.append(("thinnest wall", tuple(parts)))
        elif d is not None and d.status == "infeasible":
            rows.append(("design", "no feasible design: " + display.said_text(d.message, self.units, self.digits)))
        drive = self.solution.drive
        if drive is not None and drive.best is not None:
            m = drive.best.motor
            rows += [
                ("motor", m.name),  # the catalogue's name, which may carry its power: the rating on its own row
                ("rated power", self.q(m.rated_power, "power", "rated_power")),
                ("motor ratio", number(drive.best.motor_ratio, self.digits)),
                ("motor + wheel mass", self.q(drive.best.total_mass, "mass", "total_mass")),
            ]
        if v is not None:
            verdict = "FLAGGED" if self.flagged() else "ok"
            rows.append(
                (
                    "verified δ",
                    (
                        self.q(v.achieved_delta, "dimensionless", "achieved_delta"),
                        f" against the allowed {number(v.delta_allowed, self.digits)}: {verdict}",
                    ),
                )
            )
        blocks.append(Facts(tuple(rows), "summary"))

    def answer(self) -> str:
        """The answer in one sentence."""
        a, best, status = self.analysis, self.best(), self.solution.status
        check = self.solution.flywheel
        if check is not None:  # a wheel that exists: the analysis is at the δ it reaches
            given = (
                f"The flywheel given ({display.quantity_text(check.flywheel.j_at_reference, 'inertia', self.units)} "
                f"at the reference shaft) leaves δ = {number(check.achieved_delta, self.digits)}, the speed between "
                f"{display.quantity_text(check.omega_min, 'angular_speed', self.units)} and "
                f"{display.quantity_text(check.omega_max, 'angular_speed', self.units)}"
            )
            if check.delta_allowed is None:
                return given + "."
            holds = "within" if check.suffices else "NOT within"
            return given + f": {holds} the allowed δ = {number(check.delta_allowed, self.digits)}."
        drive = self.solution.drive
        if self.solution.drive_failed and drive is not None:
            from flyopt.drive.codesign import refused_in_short
            from flyopt.report.text import WITHOUT_DRIVE

            return f"No feasible drive: {display.said_text(refused_in_short(drive), self.units, self.digits)}. {WITHOUT_DRIVE}"
        if status == "infeasible":
            said = self.design if self.design is not None else self.solution.drive
            if said is None:
                raise BrokenInvariant("an infeasible solution is the design's or the drive design's")
            return "No feasible design: " + display.said_text(said.message, self.units, self.digits)
        if best is None:
            if self.solution.drive is not None and self.solution.drive.best is not None:
                drive_check = self.solution.drive_check
                held = drive_check.verification.achieved_delta if drive_check is not None else a.delta_reached
                return (
                    f"The drive needs no flywheel: the motor {self.solution.drive.best.motor.name} at ratio "
                    f"{number(self.solution.drive.best.motor_ratio, self.digits)} holds δ = {number(held, self.digits)} by itself, "
                    f"within the allowed {number(a.delta, self.digits)}."
                )
            if not a.flywheel_needed:
                from flyopt.report.text import no_flywheel_holder

                holder, however = no_flywheel_holder(a)
                return (
                    f"No flywheel is needed: {holder} keeps δ within {number(a.delta, self.digits)}{however} "
                    f"(J_F would be {display.quantity_text(a.j_margin, 'inertia', self.units)})."
                )
            return (
                f"The machine needs a flywheel of {display.quantity_text(a.j_required, 'inertia', self.units)}"
                f"{self.stall_words()}."
            )
        v = self.solution.verification or (
            self.solution.drive_check.verification if self.solution.drive_check is not None else None
        )
        checked = (
            ""
            if v is None
            else (
                f"; simulated, it gives δ = {number(v.achieved_delta, self.digits)}"
                + (" (FLAGGED)" if self.flagged() else "")
            )
        )
        return (
            f"{indefinite(self.material_name(best.material), capital=True)} {wheel_words(best.geometry, best.n_arms)} on the "
            f"{shaft_label(best.shaft)}, "
            f"{display.quantity_text(best.mass, 'mass', self.units, 4)}, outer diameter "
            f"{display.quantity_text(best.dims.d_outer, 'length', self.units, 4)}, keeps the speed fluctuation "
            f"within δ = {number(a.delta, self.digits)}{checked}{self.stall_words(with_delta=v is None)}"
            f"{self.casting_words()}."
        )

    def casting_words(self) -> str:
        """Where the chosen wheel is too thin to be made as sized, what the answer adds; nothing otherwise."""
        best = self.best()
        thin = best.parts.thin_wall if best is not None else None
        return display.thin_wall_words(thin) if thin is not None else ""

    def stall_words(self, with_delta: bool = True) -> str:
        """Where a stall sets the flywheel, what the answer adds: the flywheel is the smallest that runs steadily,
        and δ there (unless a simulation has said it, ``with_delta`` False); nothing otherwise."""
        a = self.analysis
        if not a.stall_limited:
            return ""
        there = f", at δ = {number(a.delta_reached, self.digits)}" if with_delta else ""
        return f"; its inertia is the least with which the machine runs steadily (with less the drive stalls){there}"
