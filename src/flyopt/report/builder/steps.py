"""Section 4 of the report: every step of the calculation in the order of docs/flywheel-design.md, each with its equation and the numbers substituted."""

from __future__ import annotations

from typing import Any

from flyopt.errors import BrokenInvariant
from flyopt.names import Model
from flyopt.report import display
from flyopt.report.builder.base import NOTES
from flyopt.report.builder.requirement import Requirement
from flyopt.report.display import number
from flyopt.report.document import Facts, Paragraph, Table


class Steps(Requirement):
    """Section 4 of the report."""

    def steps(self) -> None:
        a = self.analysis
        self.section("The calculation, step by step", "steps")
        self.sections[-1].blocks.append(
            Paragraph(
                f"Each step gives the formula, the numbers substituted and the section of {NOTES} (flyopt's engineering "
                "notes) it comes from. Equations are worked in coherent SI units (rad, rad/s, N·m, J, kg·m², m, Pa, W); "
                f"results are repeated in the report's units ({self.units})."
            )
        )
        if self.solution.drive_failed:
            from flyopt.report.text import WITHOUT_DRIVE

            self.sections[-1].blocks.append(Paragraph(WITHOUT_DRIVE, "warning"))
        self.step_speeds()
        self.step_reduction()
        if a.work_per_cycle is not None:
            self.step_work()
        self.step_a_max()
        self.step_requirement()
        self.step_shafts()

    def step_speeds(self) -> None:
        a, si, res = self.analysis, self.si, self.result
        blocks = self.section("Speeds and the allowed fluctuation", "speeds", 2)
        w = self.omega_given()
        from flyopt.units import rad_s_to_rpm

        blocks.append(
            self.eq(
                "omega_mean",
                "ω_{m} = 2π n / 60",
                f"2π × {number(rad_s_to_rpm(w), self.worked)} / 60",
                res(w, "angular_speed"),
                2,
            )
        )
        if a.model == Model.DYNAMIC:
            blocks.append(
                Paragraph(
                    "A torque depends on speed: the mean speed is an outcome of the torque–speed balance, and the "
                    f"speed above is only the scene's guess ({NOTES}, section 7). The periodic solution with the "
                    "required flywheel gives:"
                )
            )
            blocks.append(
                self.eq(
                    "omega_mean_dynamic",
                    "ω_{m} = (ω_{max} + ω_{min}) / 2",
                    f"({si(a.omega_max, 'angular_speed')} + {si(a.omega_min, 'angular_speed')}) / 2",
                    res(a.omega_mean, "angular_speed"),
                    2,
                )
            )
            blocks.append(
                Paragraph(
                    f"The ω_max and ω_min of the periodic solution are the speeds the wheel's "
                    f"rim is checked at ({NOTES}, section 10)."
                )
            )
            return
        blocks.append(
            Paragraph(
                f"From δ = (ω_max − ω_min)/ω_m and ω_m = (ω_max + ω_min)/2 ({NOTES}, section 2), "
                "the highest and lowest speeds of the cycle, where the rim is checked:"
            )
        )
        w_si = si(a.omega_mean, "angular_speed")
        blocks.append(
            self.eq(
                "omega_max",
                "ω_{max} = ω_{m} (1 + δ/2)",
                f"{w_si} × (1 + {number(a.delta, self.worked)}/2)",
                res(a.omega_max, "angular_speed"),
                2,
            )
        )
        blocks.append(
            self.eq(
                "omega_min",
                "ω_{min} = ω_{m} (1 − δ/2)",
                f"{w_si} × (1 − {number(a.delta, self.worked)}/2)",
                res(a.omega_min, "angular_speed"),
                2,
            )
        )

    def step_reduction(self) -> None:
        scene, a = self.scene, self.analysis
        blocks = self.section("The machine reduced to one shaft", "reduction", 2)
        tables = set(self.inputs.scene_tables)
        text = [
            f"The whole machine is reduced to the reference shaft with the same power and kinetic energy "
            f"({NOTES}, section 3)."
        ]
        if "press" in tables:
            text.append(
                f" The [press] is written into this model from its process data: one crank turn per "
                f"stroke, the working stroke's load a resisting torque ({NOTES}, section 14)."
            )
        if "engine" in tables:
            text.append(
                f" The [engine]'s pistons and rods are exact slider-cranks, one per cylinder, so J_e(φ) "
                f"varies with the angle ({NOTES}, section 14)."
            )
        if "drive" in tables:
            text.append(
                f" The motor is the one the drive design chose, on its Kloss curve at its ratio ({NOTES}, section 14)."
            )
        blocks.append(Paragraph("".join(text)))
        inertia = [s for s in scene.shafts if s.inertia]
        if inertia:
            rows: list[Any] = [
                [
                    s.name,
                    self.n(s.inertia, "inertia"),
                    number(s.speed_ratio, self.digits),
                    self.n(s.inertia * s.speed_ratio**2, "inertia"),
                ]
                for s in inertia
            ]
            blocks.append(
                Table(
                    (
                        "shaft",
                        self.head("inertia J_{k} on it", "inertia"),
                        "speed ratio i_{k}",
                        self.head("J_{k} i_{k}² at the reference", "inertia"),
                    ),
                    tuple(rows),
                    ("<", ">", ">", ">"),
                    f"Inertia already turning on the shafts joins J_c as J_k i_k² ({NOTES}, sections 3 and 14)",
                    "shaft_inertia",
                )
            )
        rows = [("constant part J_{c}", self.q(scene.j_constant, "inertia", "j_constant"))]
        if self.inputs.j_machine is not None and a.machine is not None and a.machine.variable_inertia:
            low, mean, high = self.inputs.j_machine
            rows += [
                ("J_{e}(φ) = J_{c} + J_{v}(φ), from", (self.q(low, "inertia"), " to ", self.q(high, "inertia"))),
                ("cycle mean J̄_{e}", self.q(mean, "inertia")),
            ]
        rows.append(("efficiency motor → reference shaft η", number(scene.efficiency, self.digits)))
        blocks.append(Facts(tuple(rows), "reduction"))

    def step_work(self) -> None:
        a, si, res = self.analysis, self.si, self.result
        blocks = self.section("Work balance and power", "work", 2)
        ind = a.indicator
        if ind is None:
            raise BrokenInvariant("every analysis carries its energy indicator diagram (flyopt.analysis)")
        from flyopt.cycle.torque import Constant

        solved = [
            name
            for name, curve in (
                ("driving", getattr(self.inputs.scene, "driving", None)),
                ("resisting", getattr(self.inputs.scene, "resisting", None)),
            )
            if isinstance(curve, Constant) and curve.unknown
        ]
        phi = si(ind.cycle_angle, "angle")
        if a.model == Model.DYNAMIC:
            blocks.append(
                Paragraph(
                    f"The torques are taken at the mean speed, a motor replaced by the constant "
                    f"torque that balances the cycle ({NOTES}, section 7)."
                )
            )
        if solved == ["resisting"]:
            blocks.append(
                self.eq(
                    "resisting_torque",
                    "M_{r} = W_{d} / Φ",
                    f"{si(ind.work_driving, 'energy')} / {phi}",
                    res(a.resisting_torque, "torque"),
                    4,
                )
            )
        elif solved == ["driving"] or a.model == Model.DYNAMIC:
            blocks.append(
                self.eq(
                    "driving_torque",
                    "M_{d} = W_{r} / Φ",
                    f"{si(ind.work_resisting, 'energy')} / {phi}",
                    res(a.driving_torque, "torque"),
                    4,
                )
            )
        else:
            blocks.append(
                self.eq(
                    "driving_torque",
                    "M_{d} = W_{d} / Φ (its mean)",
                    f"{si(ind.work_driving, 'energy')} / {phi}",
                    res(a.driving_torque, "torque"),
                    4,
                )
            )
        net = ind.work_driving - ind.work_resisting
        blocks.append(
            Paragraph(
                (
                    "The cycle balances: W_d − W_r = ",
                    self.q(display.without_noise(net, ind.work_driving), "energy"),  # round-off of the work: 0
                    " (work per cycle ",
                    self.q(a.work_per_cycle, "energy", "work_per_cycle"),
                    f"; a cycle is refused beyond 1e-9 of its work, {NOTES}, section 1).",
                )
            )
        )
        blocks.append(
            self.eq(
                "power",
                "P = M_{d} ω_{m}",
                f"{si(a.driving_torque, 'torque')} × {si(a.omega_mean, 'angular_speed')}",
                res(a.power, "power"),
                11,
            )
        )
        blocks.append(
            self.eq(
                "motor_power",
                "P_{motor} = P / η",
                f"{si(a.power, 'power')} / {number(a.efficiency, self.worked)}",
                res(a.motor_power, "power"),
                11,
            )
        )

    def step_a_max(self) -> None:
        a, scene = self.analysis, self.scene
        blocks = self.section("Energy indicator diagram and A_max", "a_max", 2)
        from flyopt.report import plots

        self.figure(
            blocks,
            "turning_moment",
            "Turning-moment diagram: the torques over the cycle, surplus and deficit areas between them",
            plots.TURNING_MOMENT,
            scene,
            a,
        )
        same = (a.angle_delta_e_max, a.angle_delta_e_min) == (a.angle_omega_max, a.angle_omega_min)
        top, bottom = ("ω_max", "ω_min") if same else ("ΔE max", "ΔE min")
        rows = []
        chain = display.Column(
            e["delta_e"] for e in a.energy_chain
        )  # one column: its unit and round-off by its largest
        for e in a.energy_chain:
            mark = top if e["index"] == a.index_omega_max else bottom if e["index"] == a.index_omega_min else ""
            where = self.n(e["angle"], "angle") if e["angle"] is not None else display.chain_point(e["index"])
            rows.append([str(e["index"]), where, self.n(e["delta_e"], "energy", "delta_e", among=chain), mark])
        blocks.append(
            Table(
                ("point", self.head("angle φ", "angle"), self.head("ΔE", "energy", chain), ""),
                tuple(rows),
                ("<", ">", ">", "<"),
                "The chain of the energy indicator diagram: ΔE at the cycle start, at every crossing of "
                "the torque curves and at the cycle end",
                "chain",
            )
        )
        if not same and a.angle_omega_max is not None:
            blocks.append(
                Paragraph(
                    (
                        "ΔE is extreme at ",
                        self.q(a.angle_delta_e_max, "angle"),
                        " and ",
                        self.q(a.angle_delta_e_min, "angle"),
                        ", but the speed is extreme at ",
                        self.q(a.angle_omega_max, "angle"),
                        " (ω_max) and ",
                        self.q(a.angle_omega_min, "angle"),
                        " (ω_min): with a varying inertia or a speed-dependent torque the speed "
                        f"extremes lie elsewhere ({NOTES}, section 4).",
                    ),
                    "note",
                )
            )
        energies = [e["delta_e"] for e in a.energy_chain]
        blocks.append(
            self.eq(
                "a_max",
                "A_{max} = max ΔE − min ΔE",
                f"{self.si(max(energies), 'energy')} − {self.si(min(energies), 'energy')}",
                self.result(a.a_max, "energy"),
                4,
            )
        )
        self.figure(
            blocks,
            "energy",
            "Energy indicator diagram: the excess work ΔE from the cycle start, A_max its largest span",
            plots.ENERGY,
            scene,
            a,
        )

    def step_shafts(self) -> None:
        a = self.analysis
        blocks = self.section("The flywheel on each shaft", "shafts", 2)
        blocks.append(
            Paragraph(
                f"Same kinetic energy on a shaft of speed ratio i = ω'/ω: J' = J_F (ω/ω')² = "
                f"J_F / i² ({NOTES}, section 8)."
            )
        )
        for s in a.shafts:
            blocks.append(
                self.eq(
                    f"j_shaft:{s.name}",
                    f"J'_{{{s.name}}} = J_{{F}} / i²",
                    f"{self.si(a.j_required, 'inertia')} / {number(s.speed_ratio, self.worked)}²",
                    self.result(s.j_required, "inertia"),
                    8,
                )
            )
        rows = [
            [
                s.name,
                number(s.speed_ratio, self.digits),
                self.n(s.omega, "angular_speed"),
                self.n(s.j_required, "inertia"),
                self.n(s.gd2_required, "flywheel_moment"),
            ]
            for s in a.shafts
        ]
        blocks.append(
            Table(
                (
                    "shaft",
                    "speed ratio",
                    self.head("mean speed", "angular_speed"),
                    self.head("J'", "inertia"),
                    self.head("GD²", "flywheel_moment"),
                ),
                tuple(rows),
                ("<", ">", ">", ">", ">"),
                "The flywheel each shaft would need",
                "shaft_table",
            )
        )
