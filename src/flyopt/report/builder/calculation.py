"""The engineering report of a scene that is one calculation rather than a cycle (:data:`flyopt.names.CALCULATIONS`).

An [operation] on its [flywheel] (docs/flywheel-design.md, section 16), a [position] (section 17:
a slider-crank's forces, or a mechanism's equivalents beside [[member]]s), an [electric_drive]
(section 18) and a [power_chain] (section 21) each answer one question, as the book asks it. Their
report is what an engineer hands on for one: the title block of every report, the answer first,
the given data in the book's terms, the method with each formula and the numbers substituted
(in SI, so that each can be checked on a calculator) citing its section, and the provenance.

Every number shown is the calculation's own result (:func:`flyopt.pipeline.solve_calculation`,
gathered by ``flyopt.cli.report.collect``) or the scene's given data; the only arithmetic here is
the substitution shown to the reader, and the terms of an electric drive's GD² sums are those of
the text report (:func:`flyopt.report.text.drive_shafts`). A calculation has no cycle, so the
report has no diagram, and says so.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flyopt.report import display
from flyopt.report.builder.base import NOTES, BuilderBase
from flyopt.report.display import number
from flyopt.report.document import Document, Facts, Paragraph, Quantity, Table, listing

if TYPE_CHECKING:
    from flyopt.io.scene import Scene
    from flyopt.machine.crank_forces import CrankForces
    from flyopt.machine.electric_drive import ReducedDrive
    from flyopt.machine.equivalents import PositionEquivalents
    from flyopt.machine.transmission import BranchFlow, PowerFlow
    from flyopt.sizing.operation import OperationResult

#: What each calculation is, in the title block and the method's first words.
KINDS = {
    "operation": "one operation on a flywheel, not a cycle: the energy balance over its duration",
    "position": "one crank position of a slider-crank engine: exact kinematics, forces along the line of stroke",
    "equivalents": "a mechanism at one position reduced to the reference shaft (equal kinetic energy and power)",
    "electric_drive": "an electric drive reduced to the motor shaft (equal kinetic energy; the texts' GD² with losses)",
    "power_chain": "a power chain from one motor: stages in series, branches in parallel (P = P_out / η per stage)",
}

#: The section of docs/flywheel-design.md each calculation's method is in.
SECTIONS = {"operation": 16, "position": 17, "equivalents": 17, "electric_drive": 18, "power_chain": 21}

#: The sense of an equivalent moment or force, in words (flyopt.machine.equivalents.SENSES).
SENSES = {
    "driving": "driving: it acts along the motion",
    "resisting": "resisting: it acts against the motion",
    "none": "none at this position",
}


def subscript(name: str) -> str:
    """A scene's name as a subscript of the report's markup: without the braces and marks that would end or
    open one ("_{name}" must stay one subscript whatever the name holds)."""
    return re.sub(r"[{}_^]", "", name) or "?"


@dataclass
class CalculationInputs:
    """What the report of a calculation is built from (``flyopt.cli.report.collect``).

    Attributes
    ----------
    scene_file : str
        The scene file as given on the command line.
    scene_text : str
        Its contents, shown as given.
    scene : Scene
    what : str
        Its section, one of :data:`flyopt.names.CALCULATIONS`.
    result : object
        ``solve_calculation(scene)``: an OperationResult, CrankForces, PositionEquivalents,
        ReducedDrive or PowerFlow.
    provenance : tuple of (str, str)
        Versions, file hash, date, command line.
    """

    scene_file: str
    scene_text: str
    scene: Scene
    what: str
    result: Any
    provenance: tuple[tuple[str, str], ...] = ()

    @property
    def form(self) -> str:
        """The calculation's key in :data:`KINDS`: its section, or "equivalents" for a [position] beside [[member]]s."""
        from flyopt.machine.equivalents import PositionEquivalents

        return "equivalents" if isinstance(self.result, PositionEquivalents) else self.what

    @property
    def flagged(self) -> bool:
        """An operation whose speed falls beyond machine.delta (``flyopt solve`` exits 4 on it too)."""
        return getattr(self.result, "holds", None) is False


def build_calculation(
    inputs: CalculationInputs,
    units: str = display.DEFAULT,
    title_block: tuple[tuple[str, Any], ...] = (),
    digits: int = display.DEFAULT_DIGITS,
) -> Document:
    """The report of a scene that is one calculation, in a unit system.

    Parameters
    ----------
    inputs : CalculationInputs
    units : {"engineering", "si", "imperial"}
        The units of the answer, facts and tables (equations stay SI).
    title_block : tuple of (str, str)
        Lines added to the title block (the date, the flyopt version, the file's hash).
    digits : int
        Significant figures of every number shown (:func:`flyopt.report.display.check_digits`).

    Returns
    -------
    Document
    """
    display.check_system(units)
    return CalculationReport(inputs, units, display.check_digits(digits)).document(title_block)


class CalculationReport(BuilderBase):
    """Builds the report of one calculation: the answer, the given data, the method, the provenance.

    It shares the report's tools (:class:`BuilderBase`: numbers in the reader's units and in SI, numbered
    sections, worked equations) but has no cycle solution: only the calculation's result.
    """

    def __init__(  # noqa: D107 -- no Solution to read
        self, inputs: CalculationInputs, units: str, digits: int = display.DEFAULT_DIGITS
    ) -> None:
        self.calc = inputs
        self.units = units
        self.digits = digits
        self.scene = inputs.scene
        self.sections = []
        self.failures = []
        self._numbers = [0, 0]

    def f(self, value: float | None, name: str, digits: int | None = None) -> Quantity:
        """An output field's value with its unit, its dimension by its name (as the text report and the JSON)."""
        return self.q(value, display.dimension_of(name), name, digits)

    def fn(self, value: float | None, name: str, digits: int | None = None) -> Quantity:
        """An output field's value without its unit (a table cell under :meth:`fhead`)."""
        return self.n(value, display.dimension_of(name), name, digits)

    def fhead(self, title: str, name: str) -> str:
        """A column's head with the unit of the output field ``name``."""
        return display.heading(title, name, self.units)

    def document(self, extra: tuple[tuple[str, Any], ...]) -> Document:
        """Every section in order, and the title block with ``extra`` lines."""
        form = self.calc.form
        builders = {
            "operation": self.operation,
            "position": self.crank_position,
            "equivalents": self.equivalents,
            "electric_drive": self.electric_drive,
            "power_chain": self.power_chain,
        }
        builders[form]()
        blocks = self.section("Provenance", "provenance")
        blocks.append(Facts(tuple(self.calc.provenance), "provenance"))
        status = "calculated" + (" flagged" if self.calc.flagged else "")
        words = "calculated" + (
            "; FLAGGED: the speed falls beyond the allowed δ (machine.delta)" if self.calc.flagged else ""
        )
        head = (
            (("scene file", self.calc.scene_file),)
            + tuple(extra)
            + (
                ("calculation", f"[{self.calc.what}]: {KINDS[form]}"),
                ("units", f"{self.units}: {self.units_words()}; equations in SI"),
                ("status", words),
            )
        )
        return Document(
            self.scene.title, head, self.sections, self.units, status, self.failures, kind="calculation report"
        )

    # ------------------------------------------------------------------
    # What every calculation's report has
    # ------------------------------------------------------------------

    def answer(self, rows: list[tuple[Any, Any]], verdict: Paragraph | None = None) -> None:
        """Section 1: the answers, first."""
        blocks = self.section("The answer", "summary")
        if verdict is not None:
            blocks.append(verdict)
        blocks.append(Facts(tuple(rows), "answer"))

    def given(self, rows: list[tuple[Any, Any]], *tables: Table) -> None:
        """Section 2: the given data in the book's terms, then the scene file as given."""
        blocks = self.section("The given data", "scene")
        blocks.append(Facts((("title", self.scene.title), ("file", self.calc.scene_file), *rows), "given"))
        blocks.extend(tables)
        blocks.append(listing(self.calc.scene_text, f"{self.calc.scene_file}, as given"))

    def method(self) -> list[Any]:
        """Section 3, opened: what the calculation is and how its equations are written; its blocks to fill."""
        form = self.calc.form
        blocks = self.section("The method, step by step", "steps")
        blocks.append(
            Paragraph(
                f"The model: {KINDS[form]} ({NOTES}, section {SECTIONS[form]}). Each step gives the formula, the "
                "numbers substituted and the section it comes from; equations are worked in coherent SI units, "
                f"results repeated in the report's units ({self.units}). One calculation has no cycle, so this "
                "report has no diagram of the speed or the torques over one."
            )
        )
        return blocks

    def speed_step(self, blocks: list[Any], omega: float, symbol: str, section: int) -> None:
        """ω from the speed given in rpm (machine.speed)."""
        from flyopt.units import rad_s_to_rpm

        blocks.append(
            self.eq(
                "omega",
                f"{symbol} = 2π n / 60",
                f"2π × {number(rad_s_to_rpm(omega), self.worked)} / 60",
                self.result(omega, "angular_speed"),
                section,
            )
        )

    # ------------------------------------------------------------------
    # [operation] (section 16)
    # ------------------------------------------------------------------

    def operation(self) -> None:
        r: OperationResult = self.calc.result
        op, wheel, si, res = r.operation, self.scene.flywheel, self.si, self.result
        verdict = None
        if r.delta_allowed is not None:
            holds = "holds" if r.holds else "does NOT hold"
            verdict = Paragraph(
                f"Against the allowed δ = {number(r.delta_allowed, self.digits)} (machine.delta): the speed drop {holds} "
                f"(δ = {number(r.delta, self.digits)} about the mean of ω₁ and ω₂).",
                "ok" if r.holds else "warning",
            )
        self.answer(
            [
                ("speed after the operation ω₂", self.f(r.omega_after, "omega_after")),
                (
                    "speed drop",
                    f"{number(100 * r.speed_drop, self.digits)} % of ω₁ (δ = {number(r.delta, self.digits)} about the mean of ω₁ and ω₂)",
                ),
                ("energy from the flywheel ΔE", self.f(r.energy_from_flywheel, "energy_from_flywheel")),
                (
                    "recovery time t_{r}",
                    (self.f(r.recovery_time, "recovery_time"), " (the motor refills the flywheel, unloaded)"),
                ),
                ("shortest interval τ + t_{r}", self.f(r.shortest_interval, "shortest_interval")),
                ("operations a minute", f"{number(60.0 * r.operation_rate, self.digits)} at most (60 P / E)"),
            ],
            verdict,
        )
        rows: list[tuple[Any, Any]] = [
            ("energy of one operation E", self.f(op.energy, "energy")),
            ("its duration τ", self.f(op.duration, "duration")),
            ("motor power P (constant, as the book takes it)", self.f(op.motor_power, "motor_power")),
            ("speed before the operation n₁ (machine.speed)", self.f(r.omega_before, "omega_before")),
        ]
        if wheel is not None:
            shown: tuple[Any, ...] = (self.f(wheel.inertia, "j_flywheel"),)
            if wheel.mass is not None and wheel.radius_of_gyration is not None:
                shown = (
                    "m = ",
                    self.f(wheel.mass, "mass"),
                    " at k = ",
                    self.f(wheel.radius_of_gyration, "radius_of_gyration"),
                )
            rows.append(
                (
                    "flywheel",
                    (*shown, f" on the shaft {wheel.shaft} (speed ratio {number(wheel.speed_ratio, self.digits)})"),
                )
            )
        if self.scene.j_constant:
            rows.append(("the machine's own inertia J_{c}", self.f(self.scene.j_constant, "j_constant")))
        if r.delta_allowed is not None:
            rows.append(("allowed δ (machine.delta)", number(r.delta_allowed, self.digits)))
        self.given(rows)

        blocks = self.method()
        blocks.append(
            Paragraph(
                "The operation takes E over τ; the motor goes on giving P meanwhile and the flywheel supplies the "
                "rest, so its kinetic energy falls by ΔE = E − P τ = ½ J (ω₁² − ω₂²). The motor's power is taken "
                "constant, as the book does (a motor of constant torque gives a little less as the speed falls)."
            )
        )
        self.speed_step(blocks, r.omega_before, "ω_{1}", 16)
        if wheel is not None and wheel.mass is not None and wheel.radius_of_gyration is not None:
            blocks.append(
                self.eq(
                    "j_flywheel",
                    "J_{F} = m k²",
                    f"{si(wheel.mass, 'mass')} × {self.squared(si(wheel.radius_of_gyration, 'length'))}",
                    res(wheel.inertia, "inertia"),
                    15,
                )
            )
        if wheel is not None and wheel.speed_ratio != 1.0:
            blocks.append(
                self.eq(
                    "j_at_reference",
                    "J_{F}' = J_{F} (ω_{shaft}/ω)²",
                    f"{si(wheel.inertia, 'inertia')} × {number(wheel.speed_ratio, self.worked)}²",
                    res(wheel.j_at_reference, "inertia"),
                    8,
                )
            )
        if wheel is not None:  # J at the reference shaft: the machine's own and the wheel's
            prime = "'" if wheel.speed_ratio != 1.0 else ""
            blocks.append(
                self.eq(
                    "inertia",
                    f"J = J_{{c}} + J_{{F}}{prime}",
                    f"{si(self.scene.j_constant, 'inertia')} + {si(wheel.j_at_reference, 'inertia')}",
                    res(r.inertia, "inertia"),
                    16,
                )
            )
        motor_alone = r.energy_from_flywheel <= 0  # the result's ΔE: 0 where P τ covers E
        difference = f"{si(op.energy, 'energy')} − {si(r.energy_from_motor, 'energy')}"
        blocks.append(
            self.eq(
                "energy_from_motor",
                "E_{motor} = P τ",
                f"{si(op.motor_power, 'power')} × {si(op.duration, 'time')}",
                res(r.energy_from_motor, "energy"),
                16,
            )
        )
        blocks.append(
            self.eq(
                "energy_from_flywheel",
                "ΔE = max(0, E − P τ)" if motor_alone else "ΔE = E − P τ",
                f"max(0, {difference})" if motor_alone else difference,
                res(r.energy_from_flywheel, "energy"),
                16,
            )
        )
        if motor_alone:
            blocks.append(Paragraph("The motor alone gives the operation's energy: the flywheel gives none (ΔE = 0)."))
        blocks.append(
            self.eq(
                "omega_after",
                "ω_{2} = √(ω_{1}² − 2 ΔE / J)",
                f"√({self.squared(si(r.omega_before, 'angular_speed'))} − 2 × {si(r.energy_from_flywheel, 'energy')}"
                f" / {si(r.inertia, 'inertia')})",
                res(r.omega_after, "angular_speed"),
                16,
            )
        )
        w1, w2 = si(r.omega_before, "angular_speed"), si(r.omega_after, "angular_speed")
        blocks.append(
            self.eq(
                "speed_drop", "(ω_{1} − ω_{2}) / ω_{1}", f"({w1} − {w2}) / {w1}", number(r.speed_drop, self.worked), 16
            )
        )
        blocks.append(
            self.eq(
                "delta",
                "δ = (ω_{1} − ω_{2}) / ((ω_{1} + ω_{2})/2)",
                f"({w1} − {w2}) / (({w1} + {w2})/2)",
                number(r.delta, self.worked),
                2,
            )
        )
        blocks.append(
            Paragraph(
                "After the operation the motor, unloaded, refills the flywheel; it sustains at most P / E operations a second:"
            )
        )
        blocks.append(
            self.eq(
                "recovery_time",
                "t_{r} = ΔE / P",
                f"{si(r.energy_from_flywheel, 'energy')} / {si(op.motor_power, 'power')}",
                res(r.recovery_time, "time"),
                16,
            )
        )
        blocks.append(
            self.eq(
                "shortest_interval",
                "τ + t_{r} = E / P",
                f"{si(op.duration, 'time')} + {si(r.recovery_time, 'time')}",
                res(r.shortest_interval, "time"),
                16,
            )
        )
        blocks.append(
            self.eq(
                "operation_rate",
                "z = 60 P / E   [a minute]",
                f"60 × {si(op.motor_power, 'power')} / {si(op.energy, 'energy')}",
                number(60.0 * r.operation_rate, self.worked),
                16,
            )
        )

    # ------------------------------------------------------------------
    # [position] alone: a slider-crank engine's forces (section 17)
    # ------------------------------------------------------------------

    def crank_position(self) -> None:
        r: CrankForces = self.calc.result
        p, si, res = r.position, self.si, self.result
        self.answer(
            [
                ("gas force on the piston F_{L}", self.f(r.gas_force, "gas_force")),
                ("inertia force of the reciprocating parts F_{I}", self.f(r.inertia_force, "inertia_force")),
                ("piston effort F_{P}", self.f(r.piston_effort, "piston_effort")),
                ("force in the rod F_{Q}", self.f(r.rod_force, "rod_force")),
                ("thrust on the cylinder walls F_{N}", self.f(r.thrust, "thrust")),
                ("crank pin, tangential F_{T}", self.f(r.tangential_force, "tangential_force")),
                ("crank pin, radial F_{R}", self.f(r.radial_force, "radial_force")),
                ("turning moment T", self.f(r.turning_moment, "turning_moment")),
                (
                    "piston: from the i.d.c. / velocity",
                    (self.f(r.displacement, "displacement"), " / ", self.f(r.velocity, "velocity")),
                ),
                ("piston acceleration a", (self.f(r.acceleration, "acceleration"), " (towards the crank +)")),
            ]
        )
        rows: list[tuple[Any, Any]] = [
            ("crank angle θ (from the inner dead centre)", self.f(p.angle, "angle")),
            ("crank radius r", self.f(p.crank, "crank")),
            ("connecting rod l", (self.f(p.rod, "rod"), f" (n = l/r = {number(p.rod / p.crank, self.digits)})")),
            ("speed n (machine.speed)", self.f(r.omega, "omega")),
        ]
        if p.gas_force is None:
            rows += [("net gas pressure p", self.f(p.pressure, "pressure")), ("bore d", self.f(p.bore, "bore"))]
        else:
            rows.append(("gas force F_{L} (given directly)", self.f(p.gas_force, "gas_force")))
        rows += [
            ("reciprocating mass m_{R}", self.f(p.reciprocating_mass, "mass")),
            (
                "engine",
                f"{p.orientation}"
                + (" (cylinder above the crank: m_R g adds to F_P)" if p.orientation == "vertical" else ""),
            ),
        ]
        self.given(rows)

        blocks = self.method()
        theta = f"{number(math.degrees(p.angle), self.worked)}°"
        ratio = number(p.rod / p.crank, self.worked)
        self.speed_step(blocks, r.omega, "ω", 17)
        blocks.append(Paragraph("The rod's obliquity β, with n = l/r:"))
        blocks.append(
            self.eq(
                "obliquity",
                "β = asin(sin θ / n)",
                f"asin(sin {theta} / {ratio})",
                f"{number(math.degrees(r.obliquity), self.worked)}°",
                17,
            )
        )
        rw = f"{si(p.crank, 'length')}"
        w = si(r.omega, "angular_speed")
        blocks.append(
            Paragraph(
                "The piston's kinematics, exact (the courses' a ≈ ω² r (cos θ + cos 2θ / n) drops the higher harmonics):"
            )
        )
        blocks.append(
            self.eq(
                "displacement",
                "x = r [(1 − cos θ) + (n − √(n² − sin² θ))]",
                f"{rw} × [(1 − cos {theta}) + ({ratio} − √({ratio}² − sin² {theta}))]",
                res(r.displacement, "length"),
                17,
            )
        )
        blocks.append(
            self.eq(
                "velocity",
                "v = ω r (sin θ + sin 2θ / (2 √(n² − sin² θ)))",
                f"{w} × {rw} × (sin {theta} + sin 2×{theta} / (2 √({ratio}² − sin² {theta})))",
                res(r.velocity, "speed"),
                17,
            )
        )
        blocks.append(
            self.eq(
                "acceleration",
                "a = ω² r (cos θ + (n² cos 2θ + sin⁴ θ) / (n² − sin² θ)^{3/2})",
                f"{self.squared(w)} × {rw} × (cos {theta} + ({ratio}² cos 2×{theta} + sin⁴ {theta}) / (√({ratio}² − sin² {theta}))³)",
                res(r.acceleration, "acceleration"),
                17,
            )
        )
        blocks.append(Paragraph("The forces along the line of stroke, then through the rod to the crank pin:"))
        if p.gas_force is None:
            blocks.append(
                self.eq(
                    "gas_force",
                    "F_{L} = p π d² / 4",
                    f"{si(p.pressure, 'stress')} × π × {self.squared(si(p.bore, 'length'))} / 4",
                    res(r.gas_force, "force"),
                    17,
                )
            )
        blocks.append(
            self.eq(
                "inertia_force",
                "F_{I} = m_{R} a",
                f"{si(p.reciprocating_mass, 'mass')} × {si(r.acceleration, 'acceleration')}",
                res(r.inertia_force, "force"),
                17,
            )
        )
        if p.orientation == "vertical":
            blocks.append(
                self.eq(
                    "piston_effort",
                    "F_{P} = F_{L} − F_{I} + m_{R} g",
                    f"{si(r.gas_force, 'force')} − {si(r.inertia_force, 'force')} + {si(r.weight, 'force')}",
                    res(r.piston_effort, "force"),
                    17,
                )
            )
        else:
            blocks.append(
                self.eq(
                    "piston_effort",
                    "F_{P} = F_{L} − F_{I}",
                    f"{si(r.gas_force, 'force')} − {si(r.inertia_force, 'force')}",
                    res(r.piston_effort, "force"),
                    17,
                )
            )
        beta = f"{number(math.degrees(r.obliquity), self.worked)}°"
        fp, fq = si(r.piston_effort, "force"), si(r.rod_force, "force")
        for key, formula, numbers, value in (
            ("rod_force", "F_{Q} = F_{P} / cos β", f"{fp} / cos {beta}", r.rod_force),
            ("thrust", "F_{N} = F_{P} tan β", f"{fp} × tan {beta}", r.thrust),
            ("tangential_force", "F_{T} = F_{Q} sin(θ + β)", f"{fq} × sin({theta} + {beta})", r.tangential_force),
            ("radial_force", "F_{R} = F_{Q} cos(θ + β)", f"{fq} × cos({theta} + {beta})", r.radial_force),
        ):
            blocks.append(self.eq(key, formula, numbers, res(value, "force"), 17))
        blocks.append(
            self.eq(
                "turning_moment",
                "T = F_{T} r",
                f"{si(r.tangential_force, 'force')} × {rw}",
                res(r.turning_moment, "torque"),
                17,
            )
        )

    # ------------------------------------------------------------------
    # [position] beside [[member]]s: a mechanism's equivalents (section 17)
    # ------------------------------------------------------------------

    def equivalents(self) -> None:
        r: PositionEquivalents = self.calc.result
        p, si, res = r.position, self.si, self.result
        sense = SENSES[r.sense]
        rows: list[tuple[Any, Any]] = [
            (
                "equivalent inertia J_{e} at the reference shaft",
                (self.f(r.equivalent_inertia, "equivalent_inertia"),),
            ),
            ("equivalent moment M_{e}", (self.f(r.equivalent_moment, "equivalent_moment"), f" ({sense})")),
        ]
        red = r.reduced
        if red is not None and red.turns and red.equivalent_inertia is not None and red.equivalent_moment is not None:
            rows += [
                (f"speed ratio ω/ω_{{k}} to {red.member}", number(1.0 / red.angular_ratio, self.digits)),
                (f"J_{{e}} reduced to {red.member}", self.f(red.equivalent_inertia, "equivalent_inertia")),
                (
                    f"M_{{e}} reduced to {red.member}",
                    (self.f(red.equivalent_moment, "equivalent_moment"), f" ({r.sense})"),
                ),
            ]
            if red.radius is not None and red.equivalent_force is not None and red.equivalent_mass is not None:
                rows += [
                    (
                        f"equivalent force at {display.field_text(red.radius, 'radius', self.units)} on {red.member}",
                        (self.f(red.equivalent_force, "equivalent_force"), f" ({r.sense})"),
                    ),
                    ("equivalent mass there", self.f(red.equivalent_mass, "equivalent_mass")),
                ]
        elif red is not None and red.equivalent_force is not None and red.equivalent_mass is not None:
            rows += [
                (
                    f"equivalent mass of {red.member} (it translates here)",
                    self.f(red.equivalent_mass, "equivalent_mass"),
                ),
                (
                    "equivalent force at its centre",
                    (self.f(red.equivalent_force, "equivalent_force"), f" ({r.sense})"),
                ),
            ]
        self.answer(rows)

        where: tuple[Any, ...] = (
            ("any angle (nothing varies with it)",) if p.angle is None else (self.f(r.angle, "angle"),)
        )
        given: list[tuple[Any, Any]] = []
        mechanism = self.scene.mechanism
        if mechanism is not None:
            given.append(("mechanism", re.sub(r"(?<!^)(?=[A-Z])", " ", type(mechanism).__name__).lower()))
        if p.input_angle is not None:
            given.append(("the mechanism's input at (position.input_angle)", self.f(p.input_angle, "input_angle")))
            given.append(("the reference shaft's angle φ there", where))
        else:
            given.append(("angle of the reference shaft φ (position.angle)", where))
            if r.input_angle is not None:
                given.append(("the mechanism's input there", self.f(r.input_angle, "input_angle")))
        if p.reduce_to is not None:
            given.append(("reduced also to (position.reduce_to)", p.reduce_to))
        if p.force_at is not None:
            given.append(("force at (position.force_at)", (self.f(p.force_at, "radius"), " from its axis")))
        if r.j_constant:
            given.append(("J_{c} at the reference shaft", self.f(r.j_constant, "j_constant")))
        members = []
        for m in self.scene.members:
            loads = []
            for what, load, dim in (("M", m.torque, "torque"), ("F", m.force, "force")):
                if load is None:
                    continue
                text = (
                    display.quantity_text(float(load), dim, self.units)
                    if isinstance(load, (int, float))
                    else "over the angle"
                )
                loads.append(f"{what} = {text}")
            members.append(
                [
                    m.name,
                    self.fn(m.mass, "mass"),
                    self.fn(m.inertia, "inertia"),
                    ", ".join(loads) + (f" ({m.force_sense})" if loads else "") or "-",
                ]
            )
        table = Table(
            ("member", self.fhead("mass m", "mass"), self.fhead("J_{S}", "inertia"), "load on it (its sense)"),
            tuple(members),
            ("<", ">", ">", "<"),
            "The members as given ([[member]])",
            "members",
        )
        self.given(given, table)

        blocks = self.method()
        blocks.append(
            Paragraph(
                "The book reads each member's velocity ratios from a velocity diagram drawn at the position; flyopt "
                f"evaluates the exact closed forms of the mechanism ({NOTES}, section 19), the same J_e(φ) and M_e(φ) "
                "its cycle models integrate. Each member's share of J_e is J_S (ω_k/ω)² + m (v_S/ω)², of M_e its "
                "load's power over ω (M_k ω_k/ω or F_k v_k/ω cos α_k, positive driving):"
            )
        )
        blocks.append(
            Table(
                (
                    "member",
                    "ω_{k}/ω",
                    f"|v_{{S}}|/ω [{display.label('length', self.units)}/rad]",
                    self.fhead("share of J_{e}", "inertia_share"),
                    self.fhead("share of M_{e}", "torque_share"),
                ),
                tuple(
                    [
                        m.name,
                        self.fn(m.angular_ratio, "angular_ratio"),
                        self.fn(m.velocity_ratio, "velocity_ratio"),
                        self.fn(m.inertia_share, "inertia_share"),
                        self.fn(m.torque_share, "torque_share"),
                    ]
                    for m in r.members
                ),
                ("<", ">", ">", ">", ">"),
                "Each member at the position: its velocity ratios and its shares",
                "ratios",
            )
        )
        given_members = {g.name: g for g in self.scene.members}
        for at in r.members:
            g = given_members.get(at.name)
            if g is None or not (g.mass or g.inertia):
                continue
            blocks.append(
                self.eq(
                    f"inertia_share_{at.name}",
                    f"J_{{{subscript(at.name)}}} = J_{{S}} (ω_{{k}}/ω)² + m (v_{{S}}/ω)²",
                    f"{si(g.inertia, 'inertia')} × {self.squared(number(at.angular_ratio, self.worked))} + {si(g.mass, 'mass')} × "
                    f"{self.squared(si(at.velocity_ratio, 'length') + '/rad')}",
                    res(at.inertia_share, "inertia"),
                    3,
                )
            )
        shares = [r.j_constant] if r.j_constant else []
        shares += [m.inertia_share for m in r.members]
        blocks.append(
            self.eq(
                "equivalent_inertia",
                "J_{e} = " + ("J_{c} + " if r.j_constant else "") + "Σ [J_{S} (ω_{k}/ω)² + m (v_{S}/ω)²]",
                " + ".join(si(x, "inertia") for x in shares),
                res(r.equivalent_inertia, "inertia"),
                3,
            )
        )
        blocks.append(
            self.eq(
                "equivalent_moment",
                "M_{e} = Σ [M_{k} (ω_{k}/ω) + F_{k} (v_{k}/ω) cos α_{k}]",
                " + ".join(si(m.torque_share, "torque") for m in r.members),
                res(r.equivalent_moment, "torque") + f"   ({sense})",
                3,
            )
        )
        if red is None:
            return
        blocks.append(
            Paragraph(
                f"Reduced to {red.member} by the same kinetic energy and power ({NOTES}, section 17); a moment stays "
                "positive driving."
            )
        )
        je, me = si(r.equivalent_inertia, "inertia"), si(r.equivalent_moment, "torque")
        if red.turns and red.equivalent_inertia is not None and red.equivalent_moment is not None:
            wk = number(red.angular_ratio, self.worked)
            blocks.append(
                self.eq(
                    "reduced_inertia",
                    "J_{k} = J_{e} (ω/ω_{k})² = J_{e} / (ω_{k}/ω)²",
                    f"{je} / {self.squared(wk)}",
                    res(red.equivalent_inertia, "inertia"),
                    17,
                )
            )
            blocks.append(
                self.eq(
                    "reduced_moment",
                    "M_{k} = M_{e} |ω/ω_{k}| = M_{e} / |ω_{k}/ω|",
                    f"{me} / {number(abs(red.angular_ratio), self.worked)}",
                    res(red.equivalent_moment, "torque"),
                    17,
                )
            )
            if red.radius is not None and red.equivalent_force is not None and red.equivalent_mass is not None:
                rk = si(red.radius, "length")
                blocks.append(
                    self.eq(
                        "reduced_force",
                        "P = M_{k} / r",
                        f"{si(red.equivalent_moment, 'torque')} / {rk}",
                        res(red.equivalent_force, "force"),
                        17,
                    )
                )
                blocks.append(
                    self.eq(
                        "reduced_mass",
                        "m = J_{k} / r²",
                        f"{si(red.equivalent_inertia, 'inertia')} / {self.squared(rk)}",
                        res(red.equivalent_mass, "mass"),
                        17,
                    )
                )
        elif red.equivalent_force is not None and red.equivalent_mass is not None:
            v = si(red.velocity_ratio, "length") + "/rad"
            blocks.append(
                self.eq(
                    "reduced_mass",
                    "m = J_{e} (ω/v_{k})²",
                    f"{je} / {self.squared(v)}",
                    res(red.equivalent_mass, "mass"),
                    17,
                )
            )
            blocks.append(
                self.eq("reduced_force", "F = M_{e} |ω/v_{k}|", f"{me} / {v}", res(red.equivalent_force, "force"), 17)
            )

    # ------------------------------------------------------------------
    # [electric_drive] (section 18)
    # ------------------------------------------------------------------

    def electric_drive(self) -> None:
        from flyopt.report.text import drive_shafts
        from flyopt.units import rad_s_to_rpm

        r: ReducedDrive = self.calc.result
        d, si, res = r.drive, self.si, self.result
        shafts = drive_shafts(r)
        answer: list[tuple[Any, Any]] = [
            ("load power P_{L}", (self.f(r.load_power, "load_power"), " at ", self.f(r.load_speed, "load_speed"))),
            ("motor output power P_{L}/η", self.f(r.motor_power, "motor_power")),
            ("load torque at the motor T_{L}'", self.f(r.load_torque_at_motor, "load_torque_at_motor")),
            (
                "GD² at the motor (equal kinetic energy)",
                (self.f(r.gd2_total, "gd2_total"), " (J = ", self.f(r.inertia_total, "inertia_total"), ")"),
            ),
            (
                "GD²_{η} with the losses (the texts' convention for accelerating)",
                (
                    self.f(r.gd2_with_losses, "gd2_with_losses"),
                    " (J = ",
                    self.f(r.inertia_with_losses, "inertia_with_losses"),
                    ")",
                ),
            ),
        ]
        if r.accelerating_torque is not None and r.motor_torque is not None:
            answer += [
                ("accelerating torque T_{a}", self.f(r.accelerating_torque, "accelerating_torque")),
                ("motor torque, loaded and accelerating", (self.f(r.motor_torque, "motor_torque"), " (T_L' + T_a)")),
            ]
        self.answer(answer)
        given: list[tuple[Any, Any]] = [
            ("motor speed n_{M} (machine.speed)", self.f(d.motor_speed, "motor_speed")),
            ("GD²_{M} of the motor's shaft", self.f(d.motor_gd2, "motor_gd2")),
            ("load torque T_{L}", self.f(d.load_torque, "load_torque")),
        ]
        if d.acceleration is not None:
            given.append(
                (
                    "acceleration of the motor dω/dt",
                    (
                        self.f(d.acceleration, "motor_acceleration"),
                        f" (dn/dt = {number(rad_s_to_rpm(d.acceleration), self.digits)} rpm/s)",
                    ),
                )
            )
        stages = Table(
            (
                "stage",
                "ratio j_{k} (speed in / out)",
                "efficiency η_{k}",
                self.fhead("speed after it", "omega"),
                self.fhead("GD²_{k} on the shaft after it", "gd2"),
            ),
            tuple(
                [
                    str(k),
                    number(s.ratio, self.digits),
                    number(s.efficiency, self.digits),
                    self.fn(speed, "omega"),
                    self.fn(s.gd2, "gd2"),
                ]
                for k, (s, speed) in enumerate(zip(d.stages, r.shaft_speeds, strict=True), start=1)
            ),
            ("<", ">", ">", ">", ">"),
            "The stages as given, from the motor (a stage given by its speed has the ratio of the speeds)",
            "stages",
        )
        self.given(given, stages)

        blocks = self.method()
        self.speed_step(blocks, d.motor_speed, "ω_{M}", 18)
        ratios = " × ".join(number(s.ratio, self.worked) for s in d.stages) or "1"
        effs = " × ".join(number(s.efficiency, self.worked) for s in d.stages) or "1"
        blocks.append(self.eq("total_ratio", "j = Π j_{k}", ratios, number(r.total_ratio, self.worked), 18))
        blocks.append(self.eq("efficiency", "η = Π η_{k}", effs, number(r.efficiency, self.worked), 18))
        blocks.append(
            self.eq(
                "load_speed",
                "ω_{L} = ω_{M} / j",
                f"{si(d.motor_speed, 'angular_speed')} / {number(r.total_ratio, self.worked)}",
                res(r.load_speed, "angular_speed"),
                18,
            )
        )
        blocks.append(
            self.eq(
                "load_power",
                "P_{L} = T_{L} ω_{L}",
                f"{si(d.load_torque, 'torque')} × {si(r.load_speed, 'angular_speed')}",
                res(r.load_power, "power"),
                18,
            )
        )
        blocks.append(
            self.eq(
                "motor_power",
                "P_{M} = P_{L} / η",
                f"{si(r.load_power, 'power')} / {number(r.efficiency, self.worked)}",
                res(r.motor_power, "power"),
                18,
            )
        )
        blocks.append(
            self.eq(
                "load_torque_at_motor",
                "T_{L}' = T_{L} / (j η)",
                f"{si(d.load_torque, 'torque')} / ({number(r.total_ratio, self.worked)} × {number(r.efficiency, self.worked)})",
                res(r.load_torque_at_motor, "torque"),
                18,
            )
        )
        blocks.append(
            Table(
                (
                    "shaft",
                    "j_{1}⋯j_{k}",
                    "η_{1}⋯η_{k}",
                    self.fhead("speed", "omega"),
                    self.fhead("GD²_{k}", "gd2"),
                    self.fhead("GD²_{k}/(j_{1}⋯j_{k})²", "gd2"),
                    self.fhead("GD²_{k}/((j_{1}⋯j_{k})² η_{1}⋯η_{k})", "gd2"),
                ),
                tuple(
                    [
                        s.name,
                        number(s.ratio_to_motor, self.digits),
                        number(s.efficiency_to_motor, self.digits),
                        self.fn(s.speed, "omega"),
                        self.fn(s.gd2, "gd2"),
                        self.fn(s.gd2_reduced, "gd2"),
                        self.fn(s.gd2_with_losses, "gd2"),
                    ]
                    for s in shafts
                ),
                ("<", ">", ">", ">", ">", ">", ">"),
                "Each shaft's GD² reduced to the motor, plain and with the losses",
                "shafts",
            )
        )
        gd2 = "N·m²"
        blocks.append(
            self.eq(
                "gd2_total",
                "GD² = GD²_{M} + Σ GD²_{k} / (j_{1}⋯j_{k})²",
                f"{number(d.motor_gd2, self.worked)} + "
                + " + ".join(
                    f"{number(s.gd2, self.worked)}/{number(s.ratio_to_motor, self.worked)}²" for s in shafts[1:]
                )
                + f"  [{gd2}]",
                f"{number(r.gd2_total, self.worked)} {gd2}",
                18,
            )
        )
        blocks.append(
            self.eq(
                "gd2_with_losses",
                "GD²_{η} = GD²_{M} + Σ GD²_{k} / ((j_{1}⋯j_{k})² η_{1}⋯η_{k})",
                f"{number(d.motor_gd2, self.worked)} + "
                + " + ".join(
                    f"{number(s.gd2, self.worked)}/({number(s.ratio_to_motor, self.worked)}² × {number(s.efficiency_to_motor, self.worked)})"
                    for s in shafts[1:]
                )
                + f"  [{gd2}]",
                f"{number(r.gd2_with_losses, self.worked)} {gd2}",
                18,
            )
        )
        from flyopt.units import G_STANDARD

        for key, value, j in (
            ("inertia_total", r.gd2_total, r.inertia_total),
            ("inertia_with_losses", r.gd2_with_losses, r.inertia_with_losses),
        ):
            symbol = "GD²" if key == "inertia_total" else "GD²_{η}"
            blocks.append(
                self.eq(
                    key,
                    f"J = {symbol} / (4 g)",
                    f"{number(value, self.worked)} N·m² / (4 × {number(G_STANDARD, self.worked)} m/s²)",
                    res(j, "inertia"),
                    18,
                )
            )
        if r.accelerating_torque is not None and r.motor_torque is not None and d.acceleration is not None:
            blocks.append(
                Paragraph(
                    "The torque that accelerates the drive takes the texts' GD²_η (the motor also supplies the losses "
                    "of the power that accelerates what lies beyond them): T_a = GD²_η/(4 g) · dω/dt, the texts' "
                    "GD²_η/375 · dn/dt (375 is 4 g · 60/2π = 374.7 rounded)."
                )
            )
            blocks.append(
                self.eq(
                    "accelerating_torque",
                    "T_{a} = GD²_{η} / (4 g) · dω/dt",
                    f"{si(r.inertia_with_losses, 'inertia')} × {si(d.acceleration, 'angular_acceleration')}",
                    res(r.accelerating_torque, "torque"),
                    18,
                )
            )
            blocks.append(
                self.eq(
                    "motor_torque",
                    "T_{M} = T_{L}' + T_{a}",
                    f"{si(r.load_torque_at_motor, 'torque')} + {si(r.accelerating_torque, 'torque')}",
                    res(r.motor_torque, "torque"),
                    18,
                )
            )

    # ------------------------------------------------------------------
    # [power_chain] (section 21)
    # ------------------------------------------------------------------

    def power_chain(self) -> None:
        r: PowerFlow = self.calc.result
        si, res = self.si, self.result
        given_rows: list[list[Any]] = []
        flows: list[tuple[int, BranchFlow, tuple[float, ...]]] = []

        def visit(flow: BranchFlow, depth: int, upstream: tuple[float, ...]) -> None:
            b = flow.branch
            given_rows.append(
                [
                    "  " * depth + b.name,
                    " × ".join(number(eta, self.worked) for eta in b.stages) or "-",
                    (
                        "splits into " + ", ".join(c.name for c in b.branches)
                        if b.power is None
                        else self.fn(b.power, "load_power")
                    ),
                ]
            )
            flows.append((depth, flow, upstream + b.stages))
            for child in flow.branches:
                visit(child, depth + 1, upstream + b.stages)

        visit(r.trunk, 0, ())
        leaves = [(flow, path) for _, flow, path in flows if flow.branch.power is not None]
        answer: list[tuple[Any, Any]] = [("motor power P_{in}", self.f(r.motor_power, "motor_power"))]
        if len(leaves) > 1:
            answer += [
                (
                    f"drawn at the motor by {flow.branch.name} P_{{d,{subscript(flow.branch.name)}}}",
                    (
                        self.f(flow.motor_power, "motor_power"),
                        " (it delivers ",
                        self.f(flow.delivered, "load_power"),
                        f" at η = {number(flow.path_efficiency, self.digits)} from the motor)",
                    ),
                )
                for flow, _ in leaves
            ]
        answer += [
            ("delivered Σ P_{out}", self.f(r.delivered, "load_power")),
            ("overall efficiency Σ P_{out} / P_{in}", number(r.efficiency, self.digits)),
            ("losses P_{in} − Σ P_{out}", self.f(r.losses, "losses")),
        ]
        self.answer(answer)
        self.given(
            [
                (
                    "what is given",
                    "each branch's stages in series from its start, and at its end the power its machine delivers",
                )
            ],
            Table(
                ("branch (from the motor)", "stages η in series", self.fhead("power delivered P_{out}", "load_power")),
                tuple(given_rows),
                ("<", "<", ">"),
                "The chain as given: a leaf's last stage is its machine's own efficiency",
                "chain",
            ),
        )

        blocks = self.method()
        blocks.append(
            Paragraph(
                "Machines in series multiply their efficiencies; machines in parallel each draw, at the motor, their "
                "own power over the efficiency of their own path, and the motor gives the sum (the books' "
                "P_d = P_r / (η_1 η_2 ⋯), added over the branches)."
            )
        )
        for flow, path in leaves:
            name = subscript(flow.branch.name)
            blocks.append(
                self.eq(
                    f"path_efficiency_{name}",
                    f"η_{{{name}}} = " + " × ".join(f"η_{{{k + 1}}}" for k in range(len(path))),
                    " × ".join(number(eta, self.worked) for eta in path),
                    number(flow.path_efficiency, self.worked),
                    21,
                )
            )
            blocks.append(
                self.eq(
                    f"motor_power_{name}",
                    f"P_{{d,{name}}} = P_{{{name}}} / η_{{{name}}}",
                    f"{si(flow.delivered, 'power')} / {number(flow.path_efficiency, self.worked)}",
                    res(flow.motor_power, "power"),
                    21,
                )
            )
        blocks.append(
            self.eq(
                "motor_power",
                "P_{in} = Σ P_{d,k}",
                " + ".join(si(flow.motor_power, "power") for flow, _ in leaves),
                res(r.motor_power, "power"),
                21,
            )
        )
        blocks.append(
            self.eq(
                "efficiency",
                "η = Σ P_{out} / P_{in}",
                f"{si(r.delivered, 'power')} / {si(r.motor_power, 'power')}",
                number(r.efficiency, self.worked),
                21,
            )
        )
        blocks.append(
            self.eq(
                "losses",
                "P_{loss} = P_{in} − Σ P_{out}",
                f"{si(r.motor_power, 'power')} − {si(r.delivered, 'power')}",
                res(r.losses, "power"),
                21,
            )
        )
        unit = display.label("power", self.units)
        blocks.append(
            Table(
                (
                    "branch",
                    "η from the motor",
                    self.fhead("at its end", "power"),
                    self.fhead("drawn at the motor", "motor_power"),
                    self.fhead("lost on its way", "power"),
                    f"entering each stage [{unit}] (its η)",
                ),
                tuple(
                    [
                        "  " * depth + flow.branch.name,
                        number(flow.path_efficiency, self.digits),
                        self.fn(flow.power, "power"),
                        self.fn(flow.motor_power, "motor_power"),
                        self.fn(flow.losses, "power"),
                        ", ".join(
                            f"{display.field_number(p, 'power', self.units, self.digits)} ({number(eta, self.digits)})"
                            for p, eta in zip(flow.stage_powers, flow.branch.stages, strict=True)
                        )
                        or "-",
                    ]
                    for depth, flow, _ in flows
                ),
                ("<", ">", ">", ">", ">", "<"),
                "Every branch: its powers, and what its power loses on the way from the motor (the shared stages' "
                "share included, so the branches' losses add up to the chain's)",
                "branches",
            )
        )
