"""Sections 8 and 9 of the report: the verification by simulation, and the provenance of the numbers."""

from __future__ import annotations

from typing import Any

from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number, said_text
from flyopt.report.document import Equation, Facts, Figure, Paragraph


class VerificationAndProvenance(BuilderBase):
    """Sections 8 and 9 of the report."""

    def verification_section(self) -> None:
        from flyopt.report.text import ACHIEVED_RANGE

        v = self.solution.verification
        a = self.analysis
        blocks = self.section("Verification", "verification")
        if v is None and self.solution.drive_check is None:
            nothing = (
                "Nothing to verify: the flywheel was given, and its check is its own section."
                if self.solution.flywheel is not None
                else "Nothing to verify: no flywheel was designed."
            )
            blocks.append(Paragraph(nothing, "note"))
        if v is not None:
            verdict = "FLAGGED: the design misses the allowed δ" if v.flagged else "ok"
            blocks.append(
                Paragraph(
                    f"The machine simulated with the flywheel as designed ({v.method}): {verdict}.",
                    "warning" if v.flagged else "ok",
                )
            )
            blocks.append(
                Facts(
                    (
                        (
                            "achieved δ",
                            (
                                self.q(v.achieved_delta, "dimensionless", "achieved_delta"),
                                f" against the allowed {number(v.delta_allowed, self.digits)} (tolerance {number(v.tolerance, 3)})",
                            ),
                        ),
                        (
                            ACHIEVED_RANGE,
                            (
                                self.q(v.omega_min, "angular_speed"),
                                " to ",
                                self.q(v.omega_max, "angular_speed"),
                                ", mean ",
                                self.q(v.omega_mean, "angular_speed"),
                            ),
                        ),
                        (
                            "flywheel simulated",
                            (self.q(v.j_flywheel, "inertia", "j_flywheel"), " at the reference shaft"),
                        ),
                    ),
                    "verification",
                )
            )
            if v.omega_mean:
                blocks.append(
                    Equation(
                        "achieved_delta",
                        (
                            "δ = (ω_{max} − ω_{min}) / ω_{m}",
                            f"= ({self.si(v.omega_max, 'angular_speed', 10)} − "
                            f"{self.si(v.omega_min, 'angular_speed', 10)}) / "
                            f"{self.si(v.omega_mean, 'angular_speed', 10)}",
                            f"= {number(v.achieved_delta, self.digits)}",
                        ),
                        f"{NOTES}, section 2",
                    )
                )
        if a.startup is not None:
            st = a.startup
            if st.time is not None:
                text: str | tuple[Any, ...] = (
                    "Start-up from rest: ",
                    self.q(st.time, "time"),
                    f" ({number(st.cycles, self.digits)} cycles) to ",
                    self.q(st.omega_target, "angular_speed"),
                    f"; {st.method}.",
                )
            else:
                text = f"Start-up from rest: not reached: {said_text(st.note, self.units, self.digits)}; {st.method}."
            blocks.append(Paragraph(text))
        from flyopt.report import plots

        if self.scene.net is not None:
            blocks.append(
                Figure(
                    "speed",
                    "Speed over the cycle",
                    note="Not drawn: a scene given as net areas has no angles, so ω(φ) cannot be drawn.",
                )
            )
        elif self.inputs.speed is None:
            blocks.append(Figure("speed", "Speed over the cycle", note=f"Not drawn: {self.inputs.speed_note}."))
        else:
            check = self.solution.drive_check
            simulation = v.solution if v is not None else check.verification.solution if check is not None else None
            self.figure(
                blocks,
                "speed",
                (
                    "Speed over the cycle with the flywheel given"
                    if self.solution.flywheel is not None
                    else "Speed over the cycle with the required flywheel"
                )
                + (", and the simulation of the design over it" if simulation is not None else ""),
                plots.SPEED,
                self.scene,
                a,
                self.inputs.speed,
                simulation,
            )

    def provenance_section(self) -> None:
        blocks = self.section("Provenance", "provenance")
        blocks.append(Facts(tuple(self.inputs.provenance), "provenance"))
