"""Sections 2 and 3 of the report: the scene file as given, and the model chosen and why."""

from __future__ import annotations

from flyopt.names import Model
from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number
from flyopt.report.document import Facts, Paragraph, Table, listing


class SceneAndModel(BuilderBase):
    """Sections 2 and 3 of the report."""

    def scene_section(self) -> None:
        scene = self.scene
        blocks = self.section("The scene as given", "scene")
        rows = [
            ("title", scene.title),
            ("file", self.inputs.scene_file),
            ("cycle angle Φ", self.q(scene.cycle_angle, "angle", "cycle_angle")),
            ("mean speed (as given)", self.q(self.inputs.scene.omega_mean, "angular_speed")),
            (
                "allowed δ",
                number(self.inputs.scene.delta, self.digits)
                if self.inputs.scene.delta is not None
                else "not given: the δ the flywheel given reaches is found",
            ),
            ("efficiency motor → reference shaft", number(scene.efficiency, self.digits)),
            ("J_{c} (machine and shafts)", self.q(scene.j_constant, "inertia", "j_constant")),
        ]
        if scene.net is not None:
            rows.append(("torques", f"{len(scene.net.energies)} net areas between the curves (no angles)"))
        if self.inputs.scene_tables:
            rows.append(("tables in the file", ", ".join(f"[{t}]" for t in self.inputs.scene_tables)))
        blocks.append(Facts(tuple(rows), "scene"))
        shafts = [
            [
                s.name,
                number(s.speed_ratio, self.digits),
                number(s.efficiency, self.digits),
                self.n(s.diameter, "length")
                if s.diameter
                else f"designed ({s.layout.diameter_series})"
                if s.layout is not None and s.layout.designs_seat
                else "-",
                self.n(s.inertia, "inertia") if s.inertia else "-",
            ]
            for s in scene.shafts
        ]
        blocks.append(
            Table(
                (
                    "shaft",
                    "speed ratio i = ω'/ω",
                    "efficiency",
                    self.head("seat diameter", "length"),
                    self.head("inertia on it", "inertia"),
                ),
                tuple(shafts),
                ("<", ">", ">", ">", ">"),
                "Shafts a flywheel may sit on",
                "shafts",
            )
        )
        if self.design is not None:
            spec = self.design.spec
            brief = [
                ("geometry", spec.geometry),
                ("criterion", spec.criterion),
                ("objective", spec.objective),
                ("H/B range", f"{number(spec.hb_ratio[0], self.digits)} to {number(spec.hb_ratio[1], self.digits)}"),
                ("envelope: outer diameter", self.limit(spec.max_outer_diameter)),
                ("envelope: width", self.limit(spec.max_width)),
            ]
            if spec.safety_factor is not None:
                brief.append(("safety factor", number(spec.safety_factor, self.digits)))
            if spec.min_wall is not None:
                brief.append(("thinnest section", self.q(spec.min_wall, "length")))
            materials = sorted({self.material_name(c.material) for c in self.design.candidates})
            if materials:
                brief.append(("materials considered", ", ".join(materials)))
            blocks.append(Facts(tuple(brief), "brief"))
        blocks.append(listing(self.inputs.scene_text, f"{self.inputs.scene_file}, as given"))

    def model_section(self) -> None:
        a = self.analysis
        blocks = self.section("The model and why", "model")
        blocks.append(Paragraph(f"Model: {a.model}, the {self.model_description(a.model)}. Why: {a.model_reason}."))
        models = a.models
        if models:
            rows = []
            for m in models:
                rows.append(
                    [
                        m["model"] + (" (exact)" if m["exact"] else ""),
                        # δ holds at any inertia: the exact model asks for no flywheel (its j_required is the
                        # bound −min J_e, not a flywheel), as the text's table says
                        "none" if m["exact"] and a.delta_holds_at_any_inertia else self.n(m["j_required"], "inertia"),
                        "-" if m["j_error"] is None else f"{100 * m['j_error']:+.3g} %",
                        "-" if m["achieved_delta"] is None else number(m["achieved_delta"], self.digits),
                        m["note"] or "",
                    ]
                )
            blocks.append(
                Table(
                    ("model", self.head("J_{F}", "inertia"), "vs exact", "δ it really gives", "note"),
                    tuple(rows),
                    ("<", ">", ">", ">", "<"),
                    "Every model that applies: the flywheel each asks for, and the δ it really gives "
                    "by the exact model",
                    "models",
                )
            )
            exact = next((m for m in models if m["exact"]), None)
            textbook = next((m for m in models if m["model"] == Model.ENERGY), None)
            if (
                exact is not None
                and textbook is not None
                and textbook is not exact
                and textbook["j_required"] is not None
            ):
                off = "" if textbook["j_error"] is None else f" ({100 * textbook['j_error']:+.3g} % against the exact)"
                gives = (
                    ""
                    if textbook["achieved_delta"] is None
                    else f", which really gives δ = {number(textbook['achieved_delta'], self.digits)} instead of {number(a.delta, self.digits)}"
                )
                blocks.append(
                    Paragraph(
                        (
                            f"The textbook constant-inertia method ({NOTES}, section 5) would ask for J_F = ",
                            self.q(textbook["j_required"], "inertia"),
                            off,
                            gives,
                            f". The {exact['model']} model replaces it here.",
                        )
                    )
                )
            elif exact is not None and exact["model"] == Model.ENERGY:
                blocks.append(
                    Paragraph(f"The textbook constant-inertia method ({NOTES}, section 5) is exact for this machine.")
                )
