"""Section 6 of the report: the ranking of every combination of material and shaft."""

from __future__ import annotations

from flyopt.design.check import binding_label
from flyopt.design.result import Design
from flyopt.report import display
from flyopt.report.builder.base import BuilderBase
from flyopt.report.display import rounded_rank_note
from flyopt.report.document import Paragraph, Table


class Ranking(BuilderBase):
    """Section 6 of the report."""

    def ranking_section(self) -> None:
        d = self.design
        if d is None or d.status == "not_needed" or not d.candidates:
            return
        blocks = self.section("Ranking of every combination", "ranking")
        blocks.append(
            Paragraph(
                f"Ranked by the objective ({d.spec.objective}), then cost, mass and rim speed, each "
                "within a relative 1e-9, then the material's and the shaft's names."
            )
        )
        arms = any(c.n_arms for c in d.candidates)
        rows, rank = [], 0
        for c in d.candidates:
            if isinstance(c, Design):
                rank += 1
                row = [
                    str(rank),
                    self.material_name(c.material),
                    c.shaft,
                    self.n(c.mass, "mass"),
                    self.n(c.dims.d_outer, "length"),
                    self.n(c.dims.h, "length"),
                    self.n(c.dims.b, "length"),
                    self.n(c.stresses.rim_speed, "speed"),
                    ", ".join(map(binding_label, c.limits.binding)),
                ]
            else:
                row = [
                    "-",
                    self.material_name(c.material),
                    c.shaft,
                    "cannot win" if c.provenance.pruned else "infeasible",
                    "",
                    "",
                    "",
                    "",
                    "",
                ]
            if arms:
                row.insert(3, str(c.n_arms or "-"))
            rows.append(row)
        head = [
            "rank",
            "material",
            "shaft",
            self.head("mass", "mass"),
            self.head("D_{outer}", "length"),
            self.head("H", "length"),
            self.head("B", "length"),
            self.head("rim speed", "speed"),
            "binding",
        ]
        align = ["<", "<", "<", ">", ">", ">", ">", ">", "<"]
        if arms:
            head.insert(3, "arms")
            align.insert(3, ">")
        blocks.append(Table(tuple(head), tuple(rows), tuple(align), "Every material × shaft combination", "ranking"))
        if d.best is not None and d.continuous is not None:
            mass = self.q(d.continuous.mass, "mass", "mass")
            note = rounded_rank_note(mass.text)
            blocks.append(Paragraph(note[:1].upper() + note[1:] + "."))
        reasons = [
            display.said_text(c.reason, self.units, self.digits)
            for c in d.candidates
            if not c.feasible and not c.provenance.pruned
        ]
        if reasons:
            blocks.append(
                Table(
                    ("why infeasible",),
                    tuple([r] for r in reasons),
                    ("<",),
                    "The combinations that cannot give the required flywheel",
                    "infeasible",
                )
            )
        reasons = [display.said_text(c.reason, self.units, self.digits) for c in d.candidates if c.provenance.pruned]
        if reasons:
            blocks.append(
                Table(
                    ("why not designed",),
                    tuple([r] for r in reasons),
                    ("<",),
                    "The combinations a bound shows cannot win (design.prune = false designs them)",
                    "pruned",
                )
            )
