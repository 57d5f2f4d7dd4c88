"""The step of the report that gives the required flywheel, by the model that ran (energy method, energy–mass, dynamic, an engine's textbook)."""

from __future__ import annotations

import math
from typing import Any

from flyopt.names import Model
from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number
from flyopt.report.document import Facts, Figure, Paragraph


class Requirement(BuilderBase):
    """The step of the report that gives the required flywheel, by the model that ran (energy method, energy–mass, dynamic, an engine's textbook).."""

    def step_requirement(self) -> None:
        a, si, res, sq = self.analysis, self.si, self.result, self.squared
        blocks = self.section("The required flywheel", "requirement", 2)
        from flyopt.report import plots

        textbook = next((m for m in a.models if m["model"] == Model.ENERGY), None)
        if a.model == Model.ENERGY:
            blocks.append(
                self.eq(
                    "j_energy",
                    "J_{F} = A_{max} / (ω_{m}² δ) − J_{c}",
                    f"{si(a.a_max, 'energy')} / ({sq(si(a.omega_mean, 'angular_speed'))} × "
                    f"{number(a.delta, self.worked)}) − {si(a.j_constant, 'inertia')}",
                    res(a.j_margin, "inertia"),
                    5,
                )
            )
        else:
            j_mean = self.inputs.j_machine[1] if self.inputs.j_machine is not None else a.j_constant
            if textbook is not None and textbook["j_required"] is not None:
                why = (
                    "J_e replaced by its cycle mean"
                    if a.machine is not None and a.machine.variable_inertia
                    else "the torques frozen at the mean speed"
                )
                blocks.append(Paragraph(f"The textbook step ({NOTES}, section 5), for comparison only ({why}):"))
                blocks.append(
                    self.eq(
                        "j_energy_textbook",
                        "J_{F} = A_{max} / (ω_{m}² δ) − J̄_{e}",
                        f"{si(a.a_max, 'energy')} / ({sq(si(self.omega_given(), 'angular_speed'))} × "
                        f"{number(a.delta, self.worked)}) − {si(j_mean, 'inertia')}",
                        res(textbook["j_required"], "inertia"),
                        5,
                    )
                )
            if a.model == Model.ENERGY_MASS:
                self.energy_mass_steps(blocks, textbook)
            else:
                self.dynamic_steps(blocks, textbook)
        if a.flywheel_needed:
            blocks.append(
                Paragraph(
                    ("J_F = ", self.q(a.j_required, "inertia", "j_required"), " at the reference shaft is needed.")
                )
            )
        elif a.delta_holds_at_any_inertia:
            blocks.append(
                Paragraph(
                    f"No flywheel is needed: with none the machine gives δ = {number(a.delta_reached, self.digits)}, "
                    f"within the allowed {number(a.delta, self.digits)}, and the speed stays within δ however small the "
                    "inertia, the motor's slip alone holding it (the periodic solution down to a vanishing "
                    f"inertia; {NOTES}, section 7).",
                    "ok",
                )
            )
        else:
            blocks.append(
                Paragraph(
                    (
                        "J_F ≤ 0: no flywheel is needed; the machine's own inertia suffices by ",
                        self.q(-a.j_margin, "inertia"),
                        f" ({NOTES}, section 5).",
                    ),
                    "ok",
                )
            )
        from flyopt.units import G_STANDARD

        blocks.append(
            self.eq(
                "gd2",
                "GD² = 4 g J_{F}",
                f"4 × {number(G_STANDARD, self.worked)} m/s² × {si(a.j_required, 'inertia')}",
                res(a.gd2_required, "flywheel_moment"),
                3,
            )
        )
        self.engine_step(blocks)
        caption = "Required flywheel against the allowed δ, the scene's δ marked"
        if self.inputs.inertia_note:
            blocks.append(Figure("inertia_delta", caption, note=f"Not drawn: {self.inputs.inertia_note}."))
        else:
            curve = {} if self.inputs.inertia_curve is None else {"curve": self.inputs.inertia_curve}
            self.figure(blocks, "inertia_delta", caption, plots.INERTIA_DELTA, self.scene, a, **curve)
        if self.inputs.energy_mass is not None:
            self.figure(
                blocks,
                "energy_mass",
                "Energy–mass (Wittenbauer) diagram: ΔE against J_e, with the tangents of slope ω_max²/2 and ω_min²/2",
                plots.plot_energy_mass,
                self.scene,
                self.inputs.energy_mass,
            )

    def energy_mass_steps(self, blocks: list[Any], textbook: dict[str, Any] | None) -> None:
        """Section 6's closed form, at the two tangent points of the energy–mass diagram."""
        a, sq = self.analysis, self.squared
        blocks.append(
            Paragraph(
                f"The inertia varies with the angle, so the exact energy–mass method replaces that "
                f"step ({NOTES}, section 6): with J(φ) = J_c + J_v(φ) the machine's whole inertia, "
                "J_F follows from the two tangent points of the energy–mass diagram, where the speed "
                "is lowest and highest. The terms are shown to 10 digits: J_F is a small difference "
                "of them."
            )
        )
        t = self.inputs.tangents
        if t is None:
            return

        def si(value, dimension):
            return self.si(value, dimension, 10)

        phi_min, j_min, e_min = t["min"]
        phi_max, j_max, e_max = t["max"]
        upper = 0.5 * a.omega_min**2 * j_min - e_min
        lower = 0.5 * a.omega_max**2 * j_max - e_max
        w_max, w_min = si(a.omega_max, "angular_speed"), si(a.omega_min, "angular_speed")
        at = "at φ = {}°".format
        blocks.append(
            self.eq(
                "em_upper",
                f"max_{{φ}}[½ ω_{{min}}² J(φ) − ΔE(φ)], {at(number(math.degrees(phi_min), self.worked))}",
                f"½ × {sq(w_min)} × {si(j_min, 'inertia')} − {si(e_min, 'energy')}",
                self.si(upper, "energy", 10, bracket=False),
                6,
            )
        )
        blocks.append(
            self.eq(
                "em_lower",
                f"min_{{φ}}[½ ω_{{max}}² J(φ) − ΔE(φ)], {at(number(math.degrees(phi_max), self.worked))}",
                f"½ × {sq(w_max)} × {si(j_max, 'inertia')} − {si(e_max, 'energy')}",
                self.si(lower, "energy", 10, bracket=False),
                6,
            )
        )
        blocks.append(
            self.eq(
                "j_energy_mass",
                "J_{F} = (max_{φ}[…] − min_{φ}[…]) / (½ (ω_{max}² − ω_{min}²))",
                f"({si(upper, 'energy')} − {si(lower, 'energy')}) / (½ × ({sq(w_max)} − {sq(w_min)}))",
                self.result(a.j_margin, "inertia"),
                6,
            )
        )
        if textbook is not None and textbook["j_required"] is not None and a.j_margin > 0:
            blocks.append(Paragraph(self.off_words(textbook), "note"))

    def dynamic_steps(self, blocks: list[Any], textbook: dict[str, Any] | None) -> None:
        a = self.analysis
        detail = getattr(a.requirement, "detail", None)
        blocks.append(
            Paragraph(
                f"A torque depends on speed, so the periodic solution of the equation of motion "
                f"replaces that step ({NOTES}, section 7): "
                "d(½ J_e(φ) ω²)/dφ = M_d(φ, ω) − M_r(φ, ω), with ω(Φ) = ω(0), J_F an unknown and δ "
                "an equation."
            )
        )
        from flyopt.report.text import ACHIEVED_RANGE, ALLOWED_RANGE

        # the solution is the machine as it will run: with the flywheel it needs, with none when none is
        # needed (flyopt.sizing.periodic.dynamic_requirement), so its J_F is the flywheel fitted, not j_margin
        fitted = detail.solution.j_flywheel if detail is not None else max(a.j_margin, 0.0)
        rows = [
            ("J_{F} of the periodic solution", self.q(fitted, "inertia", "j_flywheel")),
            (
                ACHIEVED_RANGE if detail is not None and detail.limit != "delta" else ALLOWED_RANGE + ", reached",
                (
                    self.q(a.omega_min, "angular_speed", "omega_min"),
                    " to ",
                    self.q(a.omega_max, "angular_speed", "omega_max"),
                ),
            ),
        ]
        if detail is not None:
            rows.append(("what was held", detail.held))
            limit = {
                "delta": "δ reaches the allowed value",
                "stall": "stall: the smallest flywheel that still runs steadily",
                "none": "none: δ ≤ the allowed value however small the inertia; it would reach it only at a "
                "J_F below the machine's own inertia taken away",
            }[detail.limit]
            rows.append(("limit", limit))
            rows.append(("δ of the solution", number(detail.solution.delta, self.digits)))
        blocks.append(Facts(tuple(rows), "dynamic"))
        if textbook is not None and textbook["j_required"] is not None and a.j_margin > 0:
            blocks.append(Paragraph(self.off_words(textbook), "note"))

    def engine_step(self, blocks: list[Any]) -> None:
        """An [engine]: the textbook's crank-effort method beside the exact one (section 14)."""
        tb = self.inputs.textbook
        if tb is None:
            return
        a, si = self.analysis, self.si
        exact = next((m for m in a.models if m["exact"]), None)
        blocks.append(
            Paragraph(
                f"The textbook's engine method ({NOTES}, section 14): the crank effort at the mean "
                "speed, gas torque plus the inertia torque −½ J_e′(φ) ω_m², taken as a torque curve "
                "on the constant mean J_e:"
            )
        )
        blocks.append(
            self.eq(
                "j_engine_textbook",
                "J_{F} = A_{max} / (ω_{m}² δ) − J̄_{e}",
                f"{si(tb.a_max, 'energy')} / ({self.squared(si(a.omega_mean, 'angular_speed'))} × "
                f"{number(a.delta, self.worked)}) − {si(tb.j_machine_mean, 'inertia')}",
                self.result(tb.j_required, "inertia"),
                14,
            )
        )
        if exact is not None and exact["j_required"] is not None and exact["j_required"] > 0:
            off = (tb.j_required - exact["j_required"]) / exact["j_required"]
            blocks.append(
                Paragraph(
                    f"The textbook's engine method is {100 * off:+.3g} % off the exact J_F ({exact['model']}).", "note"
                )
            )
