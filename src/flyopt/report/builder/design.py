"""Section 5 of the report: the design with its geometry, parts, stress check, hub, key and balance."""

from __future__ import annotations

import inspect
import math
from typing import TYPE_CHECKING, Any, cast

from flyopt.design.check import binding_label
from flyopt.design.key import key_verdict
from flyopt.errors import BrokenInvariant
from flyopt.names import Geometry
from flyopt.report import display
from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number
from flyopt.report.document import Facts, Figure, Paragraph, Table

if TYPE_CHECKING:
    from flyopt.design.fem import FemCheck
    from flyopt.design.materials import Material
    from flyopt.design.result import Design


class DesignSection(BuilderBase):
    """Section 5 of the report."""

    def design_section(self) -> None:
        d, best = self.design, self.best()
        if d is None and self.solution.drive is None:
            return
        blocks = self.section("The design", "design")
        if d is None:
            blocks.append(Paragraph("The chosen drive needs no flywheel: no wheel is designed (see the drive).", "ok"))
            return
        blocks.append(
            Paragraph(
                f"Geometry {d.spec.geometry}, criterion {d.spec.criterion}, objective "
                f"{d.spec.objective}: every material and shaft is designed and ranked ({NOTES}, "
                "sections 9, 10 and 13)."
            )
        )
        if d.status == "not_needed":
            blocks.append(Paragraph(display.said_text(d.message, self.units, self.digits), "ok"))
            return
        if best is None:
            blocks.append(
                Paragraph(f"No feasible design: {display.said_text(d.message, self.units, self.digits)}", "warning")
            )
            return
        material = self.scene.material_library().get(best.material)
        rows: list[tuple[str, Any]] = [
            (
                "material / shaft",
                f"{self.material_name(best.material)} on {best.shaft} (speed ratio {number(best.speed_ratio, self.digits)})",
            ),
            (
                "mass",
                (
                    self.q(best.mass, "mass", "mass"),
                    "" if best.cost is None else f" (cost {number(best.cost, self.digits)})",
                ),
            ),
            self.diameter_row(best),
            self.width_row(best),
            (
                "inertia",
                (
                    self.q(best.j_flywheel, "inertia", "j_flywheel"),
                    " on its shaft = ",
                    self.q(best.j_at_reference, "inertia", "j_at_reference"),
                    " at the reference shaft",
                ),
            ),
            (
                "rim speed",
                (
                    self.q(best.stresses.rim_speed, "speed", "rim_speed"),
                    " (limit ",
                    self.q(best.limits.rim_speed_limit, "speed", "rim_speed_limit"),
                    ")",
                ),
            ),
            ("binding", ", ".join(map(binding_label, best.limits.binding)) or "none"),
            ("solved by", self.solved_by(best)),
        ]
        if best.limits.castability is not None:  # the text's words (one function)
            from flyopt.report.text import castability_words

            rows.append(("castability", castability_words(best.limits.castability, self.units)))
        if best.bore:
            rows.insert(3, ("bore", self.q(best.bore, "length", "bore")))
        blocks.append(Facts(tuple(rows), "design"))
        if d.continuous is not None:  # rounded to design.round_to: the same words as the text's
            from flyopt.report.text import rounding_report

            blocks.append(Paragraph(" ".join(line.strip() for line in rounding_report(d, self.units)), "note"))
        if not d.spec.has_envelope and not d.spec.pins_d_mean:  # a pinned D_m (given, or by a speed) bounds it
            blocks.append(
                Paragraph(
                    "No envelope (design.max_outer_diameter) is set, so only the rim speed limit bounds the diameter.",
                    "note",
                )
            )
        self.geometry_steps(blocks, best, material)
        self.parts(blocks, best)
        self.stress(blocks, best)
        if d.fem is not None:
            self.fem(blocks, d.fem)
        self.hub_key_balance(blocks, best)
        from flyopt.report import plots

        self.figure(
            blocks,
            "cross_section",
            "Axial section of the chosen wheel, dimensioned",
            plots.plot_cross_section,
            best,
            material=self.material_name(best.material),
        )
        from flyopt.report.drawing import drawing_axes

        self.figure(
            blocks,
            "drawing",
            "The manufacturing drawing, as flyopt export writes it (DXF, SVG, PDF)",
            drawing_axes,
            best,
            self.scene,
        )
        if best.limits.sensitivities:
            blocks.append(
                Table(
                    ("sensitivity of the mass",),
                    tuple([display.sensitivity_text(s, self.units, self.digits)] for s in best.limits.sensitivities),
                    ("<",),
                    display.SENSITIVITY_HEADING,
                    "sensitivities",
                )
            )
        if best.provenance.notes:
            blocks.append(
                Table(
                    ("note",),
                    tuple([display.said_text(n, self.units, self.digits)] for n in best.provenance.notes),
                    ("<",),
                    "Notes of the design",
                    "notes",
                )
            )

    def geometry_steps(self, blocks: list[Any], c: Design, material: Material | None) -> None:
        """The wheel's mass and inertia (section 9) and its rim speed (section 10), numbers substituted."""
        if self.design is None:
            raise BrokenInvariant("a candidate comes from the design")
        si, res, sq = self.si, self.result, self.squared
        rho = getattr(material, "density", None)
        if c.geometry == Geometry.DISC and not c.dims.d_inner and len(c.parts.items) <= 1 and rho:
            d = si(c.dims.d_outer, "length")
            blocks.append(
                self.eq(
                    "disc_mass",
                    "m = π D² B ρ / 4",
                    f"π × {sq(d)} × {si(c.dims.b, 'length')} × {si(rho, 'density')} / 4",
                    res(c.mass, "mass"),
                    9,
                )
            )
            blocks.append(
                self.eq(
                    "disc_inertia",
                    "J = m D² / 8",
                    f"{si(c.mass, 'mass')} × {sq(d)} / 8",
                    res(c.j_flywheel, "inertia"),
                    9,
                )
            )
        elif c.geometry in ("rim", "thin_rim", "disc") and len(c.parts.items) <= 1 and rho:
            d_m, h = si(c.dims.d_mean, "length"), si(c.dims.h, "length")
            blocks.append(
                self.eq(
                    "rim_mass",
                    "m = π D_{m} H B ρ",
                    f"π × {d_m} × {h} × {si(c.dims.b, 'length')} × {si(rho, 'density')}",
                    res(c.mass, "mass"),
                    9,
                )
            )
            if c.geometry == Geometry.THIN_RIM:
                blocks.append(
                    self.eq(
                        "rim_inertia_thin",
                        "J = m D_{m}² / 4",
                        f"{si(c.mass, 'mass')} × {sq(d_m)} / 4",
                        res(c.j_flywheel, "inertia"),
                        9,
                    )
                )
            else:
                blocks.append(
                    self.eq(
                        "rim_inertia",
                        "J = m (D_{m}² + H²) / 4",
                        f"{si(c.mass, 'mass')} × ({sq(d_m)} + {sq(h)}) / 4",
                        res(c.j_flywheel, "inertia"),
                        9,
                    )
                )
        elif c.parts.items:
            blocks.append(
                self.eq(
                    "parts_inertia",
                    "J = Σ J_{part}",
                    " + ".join(si(p["inertia"], "inertia") for p in c.parts.items),
                    res(c.j_flywheel, "inertia"),
                    9,
                )
            )
            blocks.append(
                self.eq(
                    "parts_mass",
                    "m = Σ m_{part}",
                    " + ".join(si(p["mass"], "mass") for p in c.parts.items),
                    res(c.mass, "mass"),
                    9,
                )
            )
        blocks.append(
            self.eq(
                "j_at_reference",
                "J_{F} = J' i²",
                f"{si(c.j_flywheel, 'inertia')} × {number(c.speed_ratio, self.worked)}²",
                res(c.j_at_reference, "inertia"),
                8,
            )
        )
        book = self.design.book_rim() if c is self.design.best else None
        if book is not None:
            blocks.append(
                self.eq(
                    "mean_rim_speed",
                    "v_{m} = i ω_{m} D_{m} / 2",
                    f"{number(c.speed_ratio, self.worked)} × {si(cast(float, self.design.omega_mean), 'angular_speed')} × "
                    f"{si(c.dims.d_mean, 'length')} / 2",
                    res(book.mean_rim_speed, "speed"),
                    20,
                )
            )
            blocks.append(self.book_rim_verdict(book))
        blocks.append(
            self.eq(
                "rim_speed",
                "v = i ω_{max} D_{1} / 2",
                f"{number(c.speed_ratio, self.worked)} × {si(self.design.omega, 'angular_speed')} × {si(c.dims.d_outer, 'length')} / 2",
                res(c.stresses.rim_speed, "speed"),
                10,
            )
        )
        within = c.stresses.rim_speed <= c.limits.rim_speed_limit * (1 + 1e-9)
        blocks.append(
            Paragraph(
                (
                    "The rim speed is ",
                    "within" if within else "BEYOND",
                    " the limit v_max = ",
                    self.q(c.limits.rim_speed_limit, "speed", "rim_speed_limit"),
                    f" of {self.material_name(c.material)} ({NOTES}, section 10).",
                ),
                "ok" if within else "warning",
            )
        )
        if rho and c.stresses.hoop_stress is not None:
            blocks.append(
                self.eq(
                    "hoop_stress",
                    "σ ≈ ρ v²",
                    f"{si(rho, 'density')} × {sq(si(c.stresses.rim_speed, 'speed'))}",
                    res(c.stresses.hoop_stress, "stress"),
                    10,
                )
            )
            if c.stresses.stress:
                blocks.append(
                    Paragraph(
                        f"ρv² is the thin ring's hoop stress at the outer diameter, the textbook's "
                        f"estimate; the stress check below takes every part exactly ({NOTES}, "
                        "section 13)."
                    )
                )

    def parts(self, blocks: list[Any], c: Design) -> None:
        if not c.parts.items:
            return
        n = self.n
        total_j = sum(p["inertia"] for p in c.parts.items)
        rows = [
            [
                p["name"],
                (n(p["r_inner"], "length"), " – ", n(p["r_outer"], "length")),
                n(p["thickness"], "length"),
                n(p["mass"], "mass"),
                n(p["inertia"], "inertia"),
                display.share(p["inertia"] / total_j) if total_j > 0 else "-",
            ]
            for p in c.parts.items
        ]
        rows.append(
            [
                "total",
                (
                    n(min(p["r_inner"] for p in c.parts.items), "length"),
                    " – ",
                    n(max(p["r_outer"] for p in c.parts.items), "length"),
                ),
                "",
                n(sum(p["mass"] for p in c.parts.items), "mass"),
                n(total_j, "inertia"),
                "100.0 %" if total_j > 0 else "-",
            ]
        )
        blocks.append(
            Table(
                (
                    "part",
                    self.head("r_{inner} – r_{outer}", "length"),
                    self.head("thickness (axial)", "length"),
                    self.head("mass", "mass"),
                    self.head("inertia", "inertia"),
                    "share of J",
                ),
                tuple(rows),
                ("<", ">", ">", ">", ">", ">"),
                "Parts of the wheel",
                "parts",
                total=True,
            )
        )
        if c.n_arms and c.dims.arm_major:
            blocks.append(
                Paragraph(
                    (
                        f"Arms: {c.n_arms} of elliptical section ",
                        self.q(c.dims.arm_major, "length"),
                        " × ",
                        self.q(c.dims.arm_minor, "length"),
                        " (major axis in the plane of rotation, minor axial).",
                    )
                )
            )

    def fem(self, blocks: list[Any], check: FemCheck) -> None:
        """The axisymmetric FE check of the best design ([design] fem_check): each part's peak beside the Lamé/arm
        model's, the junction factors and how far the two models differ (section 13)."""
        n = self.n
        von_mises = check.measure == "von_mises"
        rows = []
        for p in check.parts:
            peak, at = (p.von_mises, p.von_mises_at) if von_mises else (p.max_principal, p.max_principal_at)
            rows.append(
                [
                    p.part,
                    n(peak, "stress", "stress", 4),
                    n(at[0], "length"),
                    n(at[1], "length"),
                    n(p.model_stress, "stress", "stress", 4),
                    "-" if p.utilisation is None else display.share(p.utilisation),
                ]
            )
        blocks.append(
            Table(
                (
                    "part",
                    self.head("FE peak", "stress"),
                    self.head("at r", "length"),
                    self.head("at z", "length"),
                    self.head("Lamé/arm", "stress"),
                    "of its allowable",
                ),
                tuple(rows),
                ("<", ">", ">", ">", ">", ">"),
                f"The second opinion: an axisymmetric FE model ({check.elements} quadratic triangles, "
                f"{'von Mises' if von_mises else 'largest principal'} stress as the design is judged; "
                f"{NOTES}, section 13)",
                "fem",
            )
        )
        if check.junctions:
            blocks.append(
                Table(
                    ("junction", "factor (FE peak / Lamé there)", self.head("fillet", "length")),
                    tuple(
                        [j.name, f"{j.factor:.3f}", n(j.fillet, "length") if j.fillet else "no step"]
                        for j in check.junctions
                    ),
                    ("<", ">", ">"),
                    "Stress concentration at the junctions",
                    "fem_junctions",
                )
            )
        text: list[Any] = []
        if check.difference is not None and check.model_peak is not None:
            text += [
                "The two models: FE peak ",
                self.q(check.peak, "stress"),
                ", Lamé/arm ",
                self.q(check.model_peak, "stress"),
                f": the FE is {display.share(abs(check.difference))} {'above' if check.difference >= 0 else 'below'}. ",
            ]
        from flyopt.report.text import fem_verdict

        verdict = fem_verdict(check)
        if verdict is not None:
            text.append(verdict[:1].upper() + verdict[1:] + ".")
        text += [f" Note: {display.said_text(note, self.units, self.digits)}." for note in check.notes]
        if text:
            blocks.append(Paragraph(tuple(text), "warning" if check.within_allowable is False else "note"))

    def stress(self, blocks: list[Any], c: Design) -> None:
        """The stress check of each part and the diagram of the stresses over the radius (section 10)."""
        if self.design is None:
            raise BrokenInvariant("a candidate comes from the design")
        if not c.stresses.stress:
            return
        from flyopt.report import plots

        s, n = c.stresses.stress, self.n
        omega = self.design.omega * c.speed_ratio
        blocks.append(
            Paragraph(
                (
                    "Stress check at ω_max on the wheel's shaft, ",
                    self.q(omega, "angular_speed"),
                    f" ({NOTES}, section 13): von Mises against the yield strength for a ductile "
                    "material, the largest principal stress against the tensile strength for a brittle "
                    "one, each over the safety factor.",
                )
            )
        )
        rows = []
        for p in s.get("parts", []):
            allowable = p.get("allowable")
            use = p["stress"] / allowable if allowable and math.isfinite(allowable) and allowable > 0 else None
            rows.append(
                [
                    p["part"],
                    n(p["stress"], "stress", "stress", 4),
                    n(p["radius"], "length"),
                    n(allowable, "stress", "allowable", 4),
                    "-" if use is None else display.share(use),
                    n(p.get("strength"), "stress"),
                    n(p.get("wall"), "length"),
                ]
            )
        blocks.append(
            Table(
                (
                    "part",
                    self.head("stress", "stress"),
                    self.head("at r", "length"),
                    self.head("allowable", "stress"),
                    "utilisation",
                    self.head("strength", "stress"),
                    self.head("at wall", "length"),
                ),
                tuple(rows),
                ("<", ">", ">", ">", ">", ">", ">"),
                "Each part's governing stress against its allowable",
                "stress",
            )
        )
        facts: list[Any] = []
        where = s.get("where") or {}
        if where:
            facts.append(("governing", (f"{where['part']} at r = ", self.q(where["radius"], "length"))))
        facts.append(
            (
                "largest σ_{t} / σ_{r}",
                (
                    self.q(s.get("hoop_max"), "stress"),
                    " / ",
                    self.q(s.get("radial_max"), "stress"),
                    " (von Mises ",
                    self.q(s.get("von_mises"), "stress"),
                    ")",
                ),
            )
        )
        if s.get("mean_hoop") is not None and math.isfinite(s["mean_hoop"]):
            facts.append(("mean hoop stress over the radial section", self.q(s["mean_hoop"], "stress")))
        if c.stresses.strength_safety is not None and math.isfinite(c.stresses.strength_safety):
            facts.append(("safety on strength", number(c.stresses.strength_safety, 3)))
        if c.stresses.burst_speed is not None and math.isfinite(c.stresses.burst_speed):
            margin = "" if c.stresses.speed_margin is None else f" ({number(c.stresses.speed_margin, 3)} × ω_max)"
            facts.append(
                ("burst speed on its shaft", (self.q(c.stresses.burst_speed, "angular_speed", "burst_speed"), margin))
            )
        blocks.append(Facts(tuple(facts), "stress_facts"))
        if self.inputs.stress is not None:
            profile, beams, omega_w, material = self.inputs.stress
            self.figure(
                blocks,
                "stress",
                "Stresses over the radius at ω_max, each part's allowable and the governing point",
                plots.plot_stress,
                c,
                profile,
                beams,
                omega_w,
                ductile=bool(getattr(material, "ductile", False)),
                material=self.material_name(c.material),
            )
        elif self.inputs.stress_note:
            blocks.append(Figure("stress", "Stresses over the radius", note=f"Not drawn: {self.inputs.stress_note}."))

    def hub_key_balance(self, blocks: list[Any], c: Design) -> None:
        """The permissible unbalance and the key, numbers substituted (section 13)."""
        if self.design is None:
            raise BrokenInvariant("a candidate comes from the design")
        si, res = self.si, self.result
        omega = self.design.omega * c.speed_ratio
        if c.stresses.unbalance_permissible is not None and math.isfinite(c.stresses.unbalance_permissible) and c.mass:
            from flyopt.design.balance import permissible_unbalance

            grade = inspect.signature(permissible_unbalance).parameters["grade"].default
            e_per = c.stresses.unbalance_permissible / c.mass
            blocks.append(
                Paragraph(
                    f"Permissible residual unbalance, ISO 21940-11 grade G{number(grade, self.digits)} at the "
                    f"highest speed of the wheel's shaft ({NOTES}, section 13):"
                )
            )
            blocks.append(
                self.eq(
                    "e_per",
                    "e_{per} = G / Ω",
                    f"{number(grade * 1e-3, self.worked)} m/s / {si(omega, 'angular_speed')}",
                    res(e_per, "length"),
                    13,
                )
            )
            blocks.append(
                self.eq(
                    "u_per",
                    "U_{per} = e_{per} m",
                    f"{si(e_per, 'length')} × {si(c.mass, 'mass')}",
                    res(c.stresses.unbalance_permissible, "unbalance"),
                    13,
                )
            )
        if not c.parts.key:
            return
        k = c.parts.key
        head = (
            f"Key (DIN 6885-1 form A) {k['size']} on the ",
            self.q(c.bore, "length"),
            " bore, length ",
            self.q(k["length"], "length"),
            " (effective ",
            self.q(k["effective_length"], "length"),
        )
        if k["shear"] is None:  # sized by the seat and the hub; nothing to check it against
            said = f"): sized by the seat and the hub, not checked (the design's notes say why; {NOTES}, section 13)."
            blocks.append(Paragraph((*head, said), "warning"))
            return
        blocks.append(
            Paragraph(
                (
                    *head,
                    "): "
                    + key_verdict(k)
                    + (" (the hub's material gives no allowable)" if k["ok"] is None else "")
                    + ", at the peak torque the flywheel the cycle requires exchanges with its shaft ",
                    self.q(k["torque"], "torque", "torque"),
                    f" ({NOTES}, section 13).",
                ),
                "ok" if k["ok"] else "warning",
            )
        )
        if all(name in k for name in ("h", "t1", "b")) and c.bore:
            torque, d, length = si(k["torque"], "torque"), si(c.bore, "length"), si(k["effective_length"], "length")
            blocks.append(
                self.eq(
                    "key_pressure",
                    "p = 2 T / (d (h − t_{1}) l_{eff})",
                    f"2 × {torque} / ({d} × ({si(k['h'], 'length')} − {si(k['t1'], 'length')}) × {length})",
                    res(k["bearing_pressure"], "stress"),
                    13,
                )
            )
            blocks.append(
                self.eq(
                    "key_shear",
                    "τ = 2 T / (d b l_{eff})",
                    f"2 × {torque} / ({d} × {si(k['b'], 'length')} × {length})",
                    res(k["shear"], "stress"),
                    13,
                )
            )
        q = self.q
        blocks.append(
            Facts(
                (
                    (
                        "bearing pressure",
                        (
                            (
                                q(k["bearing_pressure"], "stress"),
                                " (not checked: the hub's material gives no allowable)",
                            )
                            if k["allowable_pressure"] is None
                            else (
                                q(k["bearing_pressure"], "stress"),
                                " (allowable ",
                                q(k["allowable_pressure"], "stress"),
                                ")",
                            )
                        ),
                    ),
                    (
                        "shear",
                        (
                            q(k["shear"], "stress"),
                            " (allowable ",
                            q(k["allowable_shear"], "stress"),
                            ")",
                        ),
                    ),
                ),
                "key",
            )
        )
