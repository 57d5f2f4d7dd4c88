"""The mounting shaft's section of the report: its limits with the chosen wheel, the moments and torque along
it, and the Campbell diagram of its torsional modes (docs/flywheel-design.md, section 26)."""

from __future__ import annotations

from typing import Any

from flyopt.design.combination import shaft_label
from flyopt.report import display
from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number
from flyopt.report.document import Facts, Paragraph, Table
from flyopt.report.shaft import binding_words, seat_choice_words
from flyopt.units import rpm_to_rad_s


class ShaftSection(BuilderBase):
    """The described shaft of the chosen wheel, where the scene describes it as a part."""

    def shaft_section(self) -> None:
        """A subsection of the design where the chosen wheel's shaft is described as a part."""
        if self.solution.shaft_checks:
            self.shaft_checks(self.section("The mounting shaft with the chosen wheel", "shaft", level=2))

    def shaft_checks(self, blocks: list[Any]) -> None:
        """Each described shaft's checks with the chosen wheel: a table of limits, the loads, two diagrams."""
        from flyopt.report.plots.shaft import plot_campbell, plot_shaft
        from flyopt.report.shaft import limit_row

        for report in self.solution.shaft_checks:
            c = report.check
            layout = report.layout or next(s.layout for s in self.scene.shafts if s.name == report.shaft)
            blocks.append(
                Paragraph(
                    (
                        f"The {shaft_label(report.shaft)} described as a part ({report.material_name or report.material}), checked with "
                        f"the chosen wheel over the cycle ({NOTES}, section 26): DE-Goodman fatigue and "
                        "first-cycle yield (Shigley 9th ed., Eqs. (7-7), (7-15)) at the keyseat, the shoulders "
                        "and the plain sections, the slope at the bearings, the first forward whirl and the "
                        "torsional modes against the running range widened by the margin. A post-check of each "
                        "design (not a row of the NLP): a combination whose shaft fails is infeasible.",
                    )
                )
            )
            rows = [limit_row(lim, self.units, self.digits) for lim in c.limits]
            blocks.append(
                Table(
                    ("limit", "where", "value", "allowed", "utilisation", ""),
                    tuple(rows),
                    ("<", "<", ">", ">", ">", "<"),
                    "The shaft's limits with the chosen wheel",
                    "shaft_limits",
                )
            )
            facts: list[Any] = [
                *(
                    []
                    if report.seat_diameter is None
                    else [
                        (
                            "seat diameter (designed)",
                            (
                                self.q(report.seat_diameter, "length", "seat_diameter"),
                                ", " + seat_choice_words(report, self.units, self.digits),
                            ),
                        )
                    ]
                ),
                ("weight of the wheel", self.q(c.weight, "force", "weight")),
                (
                    "permissible unbalance force (ISO 21940-11)",
                    self.q(c.unbalance, "force", "unbalance_force"),
                ),
                (
                    (
                        "torque at the seat (the train's forced response)"
                        if c.torque_source == "forced response"
                        else "torque the wheel exchanges"
                    ),
                    (
                        "midrange ",
                        self.q(c.torque_mean, "torque", "torque_mean"),
                        ", alternating ",
                        self.q(c.torque_alternating, "torque", "torque_alternating"),
                        *(
                            (
                                ": the orders superposed in time, which the fatigue check takes; the rigid body's "
                                "alternating ",
                                self.q(c.torque_alternating_rigid, "torque", "torque_alternating"),
                            )
                            if c.torque_source == "forced response"
                            else ()
                        ),
                    ),
                ),
                ("binding", binding_words(c, report.sensitivity, self.units, self.digits)),
            ]
            blocks.append(Facts(tuple(facts), "shaft_facts"))
            self.train_tables(blocks, c)
            self.figure(
                blocks,
                "shaft",
                f"The {shaft_label(report.shaft)}: bending moments and torque along it, with the utilisation",
                plot_shaft,
                report,
                layout,
            )
            self.figure(
                blocks,
                "campbell",
                f"Campbell diagram of the {shaft_label(report.shaft)}: torsional modes against the cycle's orders",
                plot_campbell,
                report,
                layout,
            )

    def train_tables(self, blocks: list[Any], check: Any) -> None:
        """The drive train's modes with their shapes and nearest critical speeds, and the forced response's
        alternating torque in each elastic element (nothing without a train)."""
        train, torsional = check.train, check.torsional
        if train is None or torsional is None:
            return
        built = train.built
        blocks.append(
            Paragraph(
                (
                    f"The drive train as a lumped chain seen from this shaft, motor end first ({NOTES}, "
                    f"section 26): {len(built.nodes)} inertias ({', '.join(built.nodes)}), each element reflected "
                    f"by its speed ratio squared; the cycle's net torque enters at the {built.nodes[built.load_node]}. "
                    "Each mode's shape is scaled to a largest entry of 1; the forced response is at the mean speed "
                    f"to the orders present, each mode damped {number(100 * train.damping_ratio, 3)} %.",
                )
            )
        )
        from flyopt.report.shaft import train_rows

        found = train_rows(check)
        if found is None:
            return
        modes, springs = found
        rows: list[list[Any]] = []
        for mode in modes:
            near = mode.nearest
            rows.append(
                [
                    str(mode.mode),
                    f"{number(mode.frequency_hz, self.digits)} Hz",
                    display.mode_shape(mode.shape),
                    "-"
                    if near is None
                    else f"order {near.order:.4g} at "
                    + display.quantity_text(rpm_to_rad_s(near.speed_rpm), "angular_speed", self.units, self.digits),
                    "-" if near is None else ("in the range" if near.in_range else f"{number(100 * near.margin, 3)} %"),
                ]
            )
        blocks.append(
            Table(
                ("mode", "frequency", "shape", "nearest critical speed", "clear of the range by"),
                tuple(rows),
                ("<", ">", "<", "<", ">"),
                "The drive train's torsional modes",
                "train_modes",
            )
        )
        rows = [
            [
                spring.name,
                spring.kind,
                display.quantity_text(spring.stiffness, "torsional_stiffness", self.units, self.digits),
                self.q(spring.torque_bound, "torque", "torque_alternating"),
                "-" if spring.top_order is None else f"{spring.top_order:.4g}",
            ]
            for spring in springs
        ]
        blocks.append(
            Table(
                ("element", "kind", "stiffness", "Σ|T_q| over the orders (a bound)", "largest order"),
                tuple(rows),
                ("<", "<", ">", ">", ">"),
                "Forced response at the mean speed: each element's alternating torque on its own shaft, the sum of "
                "its orders' amplitudes (a bound whatever their phases; the seat's torque in the shaft check is "
                "the orders superposed with their phases)",
                "train_response",
            )
        )
