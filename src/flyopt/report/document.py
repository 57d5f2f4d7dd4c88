"""The engineering report of one scene: what ``flyopt report`` writes as HTML or PDF.

The report is built once as a neutral :class:`Document` (sections of
paragraphs, facts, tables, equations, figures and code) by :func:`build`,
then rendered by :mod:`flyopt.report.html` or :mod:`flyopt.report.pdf`, so
that the two formats always say the same thing.

What it contains, for a colleague or a customer who was not there: a title
block (scene, file, date, flyopt version), the answer first (required J_F,
the chosen wheel, its mass and dimensions, the binding limits, the verified
δ), the scene file as given, the model chosen and why, every step of the
calculation in the order of docs/flywheel-design.md with its equation, the
numbers substituted and the section it comes from, every diagram, the design
with its parts, stress check, key, balance and sensitivities, the ranking of
every combination, the drive, the verification and the provenance.

Like the rest of :mod:`flyopt.report`, this module runs no model: every
number comes from the finished :class:`~flyopt.pipeline.Solution` and what
:class:`ReportInputs` carries beside it (the speed over the cycle, the stress
profile, the engine's textbook flywheel, gathered by ``flyopt.cli.report``).
The only arithmetic here is the substitution shown to the reader, and every
shown result is the solver's own value.

Units: the summary, the facts and the tables are in the unit system chosen
(:mod:`flyopt.report.display`); the equations are worked in coherent SI units
(rad/s, J, kg·m², m, Pa, W), so that each can be checked on a calculator, with
the result repeated in the chosen units where those differ.
"""

from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, field
from typing import Any

from flyopt.names import Geometry, Model
from flyopt.report import display
from flyopt.report.display import number

__all__ = [
    "Code",
    "Document",
    "Equation",
    "Facts",
    "Figure",
    "Paragraph",
    "Quantity",
    "ReportInputs",
    "Section",
    "Table",
    "build",
    "plain",
]

#: The domain notes every step cites.
NOTES = "docs/flywheel-design.md"


# --------------------------------------------------------------------------
# The document: what both renderers draw
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Quantity:
    """A number as the report shows it, and what it is.

    ``text`` is what the reader sees (in the report's unit system); ``name``
    is the quantity's JSON name (docs/nomenclature.md) or None; ``si`` its
    value in SI; the HTML carries ``name`` and ``si`` as data attributes so
    that the shown number can be checked against the solver's.
    """

    text: str
    name: str | None
    si: float | None
    dimension: str


#: A run of text: a string (with ``_{sub}`` and ``^{sup}`` markup) or a Quantity, or a tuple of them.
Text = "str | Quantity | tuple"


@dataclass(frozen=True)
class Paragraph:
    """A paragraph; ``kind`` "text", "note", "ok" or "warning" (a verdict the reader must not miss)."""

    text: object
    kind: str = "text"


@dataclass(frozen=True)
class Facts:
    """Label–value pairs (a two-column table without a header)."""

    rows: tuple
    name: str | None = None


@dataclass(frozen=True)
class Table:
    """A table: ``head`` (column titles), ``rows`` (cells of Text), ``align`` ("<" or ">" per column).

    ``total`` marks the last row as a total (drawn with a rule above it).
    """

    head: tuple
    rows: tuple
    align: tuple
    caption: str = ""
    name: str | None = None
    total: bool = False


@dataclass(frozen=True)
class Equation:
    """One step: the formula, the numbers substituted, the result, and where the formula comes from.

    ``lines[0]`` is the formula, ``lines[1:-1]`` the numbers substituted (SI),
    ``lines[-1]`` the result; ``key`` names the step (the HTML carries it).
    """

    key: str
    lines: tuple
    reference: str


@dataclass
class Figure:
    """A diagram: a matplotlib Figure, or why it is not drawn (``note``)."""

    key: str
    caption: str
    figure: Any = None  # a matplotlib Figure
    note: str = ""
    failed: bool = False


@dataclass(frozen=True)
class Code:
    """Text shown as given (the scene file)."""

    text: str
    caption: str = ""


@dataclass
class Section:
    """A numbered section (``level`` 1) or subsection (``level`` 2)."""

    number: str
    title: str
    blocks: list
    level: int = 1
    key: str = ""


@dataclass
class Document:
    """The whole report.

    Attributes
    ----------
    title : str
        The scene's title.
    title_block : tuple of (str, Text)
        Scene file, date, flyopt version, units, status.
    sections : list of Section
    units : str
        The unit system of the tables (:data:`flyopt.report.display.SYSTEMS`).
    status : str
        The solution's status ("designed", "not_needed", "infeasible", "analysed"),
        plus " flagged" when a verification flagged the design.
    failures : list of str
        Diagrams that could not be drawn because drawing raised (not a refusal
        for this scene): each ``"key: error"``.
    """

    title: str
    title_block: tuple
    sections: list
    units: str
    status: str
    failures: list = field(default_factory=list)

    def close(self):
        """Close the figures' matplotlib windows (memory) once rendered."""
        import matplotlib.pyplot as plt

        for section in self.sections:
            for block in section.blocks:
                if isinstance(block, Figure) and block.figure is not None:
                    plt.close(block.figure)


def plain(text):
    """A Text as plain characters (markup braces removed): for widths and for tests."""
    import re

    if isinstance(text, Quantity):
        return text.text
    if isinstance(text, tuple):
        return "".join(plain(t) for t in text)
    return re.sub(r"[_^]\{([^{}]*)\}", r"\1", str(text))


# --------------------------------------------------------------------------
# What the report is built from
# --------------------------------------------------------------------------


@dataclass
class ReportInputs:
    """Everything the report shows, computed before it is built (``flyopt.cli.report.collect``).

    Attributes
    ----------
    scene_file : str
        The scene file as given on the command line.
    scene_text : str
        Its contents, shown as given.
    scene_tables : tuple of str
        The top-level tables the file has ("press", "engine", "drive", ...).
    scene : Scene
        The scene as loaded (for a drive, the scene before the motor was chosen).
    solution : flyopt.pipeline.Solution
        ``solve(scene, verify_design=True)``.
    speed : object or None
        ω(φ) with the required flywheel (:meth:`flyopt.analysis.Analysis.speed_curve`).
    speed_note : str
        Why there is no ``speed``.
    energy_mass : Analysis or None
        The analysis by the energy–mass model, for its diagram, where it applies
        (the inertia varies and the torques depend on the angle only).
    tangents : dict or None
        The energy–mass model's tangent points: ``{"max": (phi, J_e, ΔE), "min": (...)}``
        [rad, kg*m^2, J], J_e and ΔE evaluated on the machine at those angles.
    j_machine : tuple or None
        (min, cycle mean, max) of the machine's J_e(φ) [kg*m^2].
    inertia_curve : tuple or None
        (δ, J_F) of the exact model at each δ, for the J_F(δ) diagram of a model other than
        the energy method (:func:`flyopt.delta_curve.inertia_curve`).
    inertia_note : str
        Why there is no ``inertia_curve`` where one was needed.
    stress : tuple or None
        ``(profile, beams, omega, material)`` of :func:`flyopt.pipeline.stress_profile`.
    stress_note : str
    textbook : object or None
        :func:`flyopt.sizing.textbook.textbook_requirement` of an [engine].
    provenance : tuple of (str, str)
        Versions, file hash, date, command line.
    """

    scene_file: str
    scene_text: str
    scene_tables: tuple
    scene: object
    solution: object
    speed: object = None
    speed_note: str = ""
    energy_mass: object = None
    tangents: dict | None = None
    j_machine: tuple | None = None
    inertia_curve: tuple | None = None
    inertia_note: str = ""
    stress: tuple | None = None
    stress_note: str = ""
    textbook: object = None
    provenance: tuple = ()


# --------------------------------------------------------------------------
# Building it
# --------------------------------------------------------------------------


def build(inputs: ReportInputs, units: str = display.DEFAULT, title_block: tuple = ()) -> Document:
    """The report of a solved scene, in a unit system.

    Parameters
    ----------
    inputs : ReportInputs
    units : {"engineering", "si", "imperial"}
        The units of the summary, facts and tables (equations stay SI).
    title_block : tuple of (str, str)
        Lines added to the title block (the date, the file's hash).

    Returns
    -------
    Document
        Its figures are open matplotlib Figures: render it, then :meth:`Document.close`.
    """
    display.check_system(units)
    return _Builder(inputs, units).document(title_block)


class _Builder:
    """Builds the sections in the order of the domain notes."""

    def __init__(self, inputs, units):
        self.inputs = inputs
        self.units = units
        self.solution = inputs.solution
        self.scene = inputs.solution.scene
        self.analysis = inputs.solution.analysis
        self.design = inputs.solution.design
        self.sections = []
        self.failures = []
        self._numbers = [0, 0]

    # -- numbers ---------------------------------------------------------------

    def q(self, value, dimension, name=None, digits=6):
        """A Quantity in the report's units, its unit after it ("-" where the value does not exist)."""
        if value is None or math.isnan(value):
            return Quantity("-", name, None, dimension)
        return Quantity(display.quantity_text(value, dimension, self.units, digits), name, float(value), dimension)

    def n(self, value, dimension, name=None, digits=6):
        """A Quantity in the report's units without its unit (a table cell: the unit is in the column's head)."""
        if value is None or math.isnan(value):
            return Quantity("-", name, None, dimension)
        return Quantity(
            number(display.show(float(value), dimension, self.units), digits), name, float(value), dimension
        )

    def head(self, title, dimension):
        """A column's head with the unit of its numbers, "mass [kg]"."""
        unit = display.label(dimension, self.units)
        return title if unit == "-" else f"{title} [{unit}]"

    @staticmethod
    def squared(text):
        """A number with its unit, squared: "(157.08 rad/s)²" (a bare number needs no brackets)."""
        return f"({text})²" if " " in text and not text.startswith("(") else f"{text}²"

    @staticmethod
    def si(value, dimension, digits=6, bracket=True):
        """A number with its SI unit, as an equation shows it; a negative one in brackets."""
        text = number(value, digits)
        unit = display.label(dimension, "si")
        text = text if unit == "-" else f"{text} {unit}"
        return f"({text})" if bracket and value is not None and value < 0 else text

    def result(self, value, dimension, digits=6):
        """An equation's result in SI, and in the report's units where those differ."""
        shown = self.si(value, dimension, digits, bracket=False)
        if display.label(dimension, self.units) != display.label(dimension, "si"):
            shown += f"   ({display.quantity_text(value, dimension, self.units, digits)})"
        return shown

    # -- structure -------------------------------------------------------------

    def section(self, title, key, level=1):
        if level == 1:
            self._numbers = [self._numbers[0] + 1, 0]
            label = str(self._numbers[0])
        else:
            self._numbers[1] += 1
            label = f"{self._numbers[0]}.{self._numbers[1]}"
        section = Section(label, title, [], level, key)
        self.sections.append(section)
        return section.blocks

    def figure(self, blocks, key, caption, draw, *args, **kwargs):
        """Draw a diagram with a function of :mod:`flyopt.report.plots` (``units=`` where it takes it)."""
        from flyopt.report import plots

        try:
            parameters = inspect.signature(draw).parameters
            if "units" in parameters:
                kwargs["units"] = self.units
            ax = draw(*args, **kwargs)
        except plots.NothingToDraw as said:
            blocks.append(Figure(key, caption, note=f"Not drawn: {said}."))
            return
        except ValueError as said:  # the diagram does not apply to this scene: said by the plot
            blocks.append(Figure(key, caption, note=f"Not drawn: {said}."))
            return
        except Exception as err:  # noqa: BLE001 -- a diagram that fails must not cost the whole report
            self.failures.append(f"{key}: {type(err).__name__}: {err}")
            blocks.append(
                Figure(
                    key, caption, note=f"This diagram could not be drawn ({type(err).__name__}: {err}).", failed=True
                )
            )
            return
        blocks.append(Figure(key, caption, figure=ax.figure))

    def document(self, extra):
        self.summary()
        self.scene_section()
        self.model_section()
        self.steps()
        self.design_section()
        self.ranking_section()
        self.drive_section()
        self.verification_section()
        self.provenance_section()
        status = self.solution.status
        if self.flagged():
            status += " flagged"
        head = (
            (("scene file", self.inputs.scene_file),)
            + tuple(extra)
            + (("units", f"{self.units}: {self.units_words()}; equations in SI"), ("status", self.status_words()))
        )
        return Document(self.analysis.title, head, self.sections, self.units, status, self.failures)

    def units_words(self):
        dims = ("length", "angular_speed", "torque", "energy", "stress", "power", "mass", "inertia")
        return ", ".join(dict.fromkeys(display.label(d, self.units) for d in dims))

    def flagged(self):
        v, check = self.solution.verification, self.solution.drive_check
        return bool((v is not None and v.flagged) or (check is not None and check.flagged))

    def status_words(self):
        status = self.solution.status
        words = {
            "designed": "designed",
            "not_needed": "no flywheel needed",
            "infeasible": "INFEASIBLE: no material and shaft can give the required flywheel",
            "analysed": "analysed (no design)",
        }.get(status, status)
        if self.flagged():
            words += "; VERIFICATION FLAGGED: the simulated δ exceeds the allowed one"
        elif self.solution.verification is not None or self.solution.drive_check is not None:
            words += "; verified"
        return words

    # -- 1. summary ------------------------------------------------------------

    def summary(self):
        a, d, best = self.analysis, self.design, self.best()
        blocks = self.section("Summary", "summary")
        blocks.append(
            Paragraph(self.answer(), "warning" if self.solution.status == "infeasible" or self.flagged() else "ok")
        )
        rows = [
            ("model", f"{a.model} ({self.model_description(a.model)})"),
            ("mean speed ω_{m}", self.q(a.omega_mean, "angular_speed", "omega_mean")),
            ("allowed δ", (self.q(a.delta, "dimensionless", "delta"), f" (1/{number(1 / a.delta, 4)})")),
            ("A_{max}", self.q(a.a_max, "energy", "a_max")),
        ]
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
                    (self.q(a.motor_power, "power", "motor_power"), f" (efficiency {number(a.efficiency, 4)})"),
                )
            )
        if best is not None:
            rows += [
                (
                    "chosen wheel",
                    f"{best.geometry} of {best.material} on the {best.shaft} shaft "
                    f"(speed ratio {number(best.speed_ratio)})",
                ),
                ("mass", self.q(best.mass, "mass", "mass")),
                ("outer diameter", self.q(best.d_outer, "length", "d_outer")),
                self.width_row(best),
                ("inertia on its shaft", self.q(best.j_flywheel, "inertia", "j_flywheel")),
                (
                    "rim speed",
                    (
                        self.q(best.rim_speed, "speed", "rim_speed"),
                        " (limit ",
                        self.q(best.rim_speed_limit, "speed", "rim_speed_limit"),
                        ")",
                    ),
                ),
                ("binding limits", ", ".join(best.binding) or "none"),
            ]
            if best.stress and (best.stress.get("where") or {}).get("part"):
                governing = self.governing(best)
                if governing is not None:
                    rows.append(
                        (
                            "governing stress",
                            (
                                self.q(governing["stress"], "stress", "stress"),
                                f" in the {governing['part']}, ",
                                f"{100 * governing['stress'] / governing['allowable']:.1f} % of its allowable"
                                if governing.get("allowable")
                                else "",
                            ),
                        )
                    )
        elif d is not None and d.status == "infeasible":
            rows.append(("design", "no feasible design: " + d.message))
        drive = self.solution.drive
        if drive is not None and drive.best is not None:
            m = drive.best.motor
            rows += [
                ("motor", (f"{m.name}: ", self.q(m.rated_power, "power", "rated_power"))),
                ("motor ratio", number(drive.best.motor_ratio)),
                ("motor + wheel mass", self.q(drive.best.total_mass, "mass", "total_mass")),
            ]
        v = self.solution.verification or (
            self.solution.drive_check.verification if self.solution.drive_check is not None else None
        )
        if v is not None:
            verdict = "FLAGGED" if self.flagged() else "ok"
            rows.append(
                (
                    "verified δ",
                    (
                        self.q(v.achieved_delta, "dimensionless", "achieved_delta"),
                        f" against the allowed {number(v.delta_allowed)}: {verdict}",
                    ),
                )
            )
        blocks.append(Facts(tuple(rows), "summary"))

    def answer(self):
        """The answer in one sentence."""
        a, best, status = self.analysis, self.best(), self.solution.status
        if status == "infeasible":
            return "No feasible design: " + (
                self.design.message if self.design is not None else self.solution.drive.message
            )
        if best is None:
            if self.solution.drive is not None and self.solution.drive.best is not None:
                return (
                    f"The drive needs no flywheel: the motor {self.solution.drive.best.motor.name} at ratio "
                    f"{number(self.solution.drive.best.motor_ratio)} holds δ = {number(a.delta)} by itself."
                )
            if not a.flywheel_needed:
                return (
                    f"No flywheel is needed: the machine's own inertia keeps δ within {number(a.delta)} "
                    f"(J_F would be {display.quantity_text(a.j_margin, 'inertia', self.units)})."
                )
            return f"The machine needs a flywheel of {display.quantity_text(a.j_required, 'inertia', self.units)}."
        v = self.solution.verification or (
            self.solution.drive_check.verification if self.solution.drive_check is not None else None
        )
        checked = (
            ""
            if v is None
            else (f"; simulated, it gives δ = {number(v.achieved_delta, 4)}" + (" (FLAGGED)" if self.flagged() else ""))
        )
        return (
            f"A {best.geometry} flywheel of {best.material} on the {best.shaft} shaft, "
            f"{display.quantity_text(best.mass, 'mass', self.units, 4)}, outer diameter "
            f"{display.quantity_text(best.d_outer, 'length', self.units, 4)}, keeps the speed fluctuation "
            f"within δ = {number(a.delta, 4)}{checked}."
        )

    def width_row(self, c):
        """The wheel's width and, for a rim, its radial thickness (a disc is the annulus with no hole, section 9)."""
        if c.geometry == Geometry.DISC:
            return (
                "axial width B",
                (
                    self.q(c.b, "length", "b"),
                    " (a disc: D_m = H = D/2, no hole)" if not c.d_inner else " (an annulus on its bore)",
                ),
            )
        return (
            "rim: radial thickness H × axial width B",
            (self.q(c.h, "length", "h"), " × ", self.q(c.b, "length", "b"), f" (H/B {number(c.hb_ratio, 4)})"),
        )

    def best(self):
        return self.design.best if self.design is not None else None

    @staticmethod
    def governing(candidate):
        where = (candidate.stress or {}).get("where") or {}
        for part in (candidate.stress or {}).get("parts", []):
            if part["part"] == where.get("part"):
                return part
        return None

    @staticmethod
    def model_description(model):
        from flyopt.sizing.choose import MODELS

        return MODELS.get(model, model)

    # -- 2. the scene ------------------------------------------------------------

    def scene_section(self):
        scene = self.scene
        blocks = self.section("The scene as given", "scene")
        rows = [
            ("title", scene.title),
            ("file", self.inputs.scene_file),
            ("cycle angle Φ", self.q(scene.cycle_angle, "angle", "cycle_angle")),
            ("mean speed (as given)", self.q(self.inputs.scene.omega_mean, "angular_speed")),
            ("allowed δ", number(scene.delta)),
            ("efficiency motor → reference shaft", number(scene.efficiency, 4)),
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
                number(s.speed_ratio),
                number(s.efficiency, 4),
                self.n(s.diameter, "length") if s.diameter else "-",
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
                ("H/B range", f"{number(spec.hb_ratio[0], 4)} to {number(spec.hb_ratio[1], 4)}"),
                ("envelope: outer diameter", self.limit(spec.max_outer_diameter)),
                ("envelope: width", self.limit(spec.max_width)),
            ]
            if spec.safety_factor is not None:
                brief.append(("safety factor", number(spec.safety_factor, 4)))
            if spec.min_wall is not None:
                brief.append(("thinnest section", self.q(spec.min_wall, "length")))
            materials = sorted({c.material for c in self.design.candidates})
            if materials:
                brief.append(("materials considered", ", ".join(materials)))
            blocks.append(Facts(tuple(brief), "brief"))
        blocks.append(Code(self.inputs.scene_text, f"{self.inputs.scene_file}, as given"))

    def limit(self, value):
        return "not set" if value is None or not math.isfinite(value) else self.q(value, "length")

    # -- 3. the model --------------------------------------------------------------

    def model_section(self):
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
                        self.n(m["j_required"], "inertia"),
                        "-" if m["j_error"] is None else f"{100 * m['j_error']:+.3g} %",
                        "-" if m["achieved_delta"] is None else number(m["achieved_delta"]),
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
                    else f", which really gives δ = {number(textbook['achieved_delta'])} instead of {number(a.delta)}"
                )
                blocks.append(
                    Paragraph(
                        (
                            "The textbook constant-inertia method (",
                            NOTES,
                            ", section 5) would ask for J_F = ",
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

    # -- 4. the steps ----------------------------------------------------------------

    def steps(self):
        a = self.analysis
        self.section("The calculation, step by step", "steps")
        self.sections[-1].blocks.append(
            Paragraph(
                f"Each step gives the formula, the numbers substituted and the section of {NOTES} (flyopt's engineering "
                "notes) it comes from. Equations are worked in coherent SI units (rad, rad/s, N·m, J, kg·m², m, Pa, W); "
                f"results are repeated in the report's units ({self.units})."
            )
        )
        self.step_speeds()
        self.step_reduction()
        if a.work_per_cycle is not None:
            self.step_work()
        self.step_a_max()
        self.step_requirement()
        self.step_shafts()

    def omega_given(self):
        """The mean speed the sizing took as given [rad/s] (a speed-dependent machine's is only a guess)."""
        machine = self.analysis.machine
        return machine.omega_mean if machine is not None else self.scene.omega_mean

    @staticmethod
    def eq(key, formula, numbers, result, section):
        """A worked step: the formula, "= " the numbers substituted, "= " the result, citing a section of the notes."""
        return Equation(key, (formula, f"= {numbers}", f"= {result}"), f"{NOTES}, section {section}")

    def step_speeds(self):
        a, si, res = self.analysis, self.si, self.result
        blocks = self.section("Speeds and the allowed fluctuation", "speeds", 2)
        w = self.omega_given()
        from flyopt.units import rad_s_to_rpm

        blocks.append(
            self.eq(
                "omega_mean", "ω_{m} = 2π n / 60", f"2π × {number(rad_s_to_rpm(w))} / 60", res(w, "angular_speed"), 2
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
        w = si(a.omega_mean, "angular_speed")
        blocks.append(
            self.eq(
                "omega_max",
                "ω_{max} = ω_{m} (1 + δ/2)",
                f"{w} × (1 + {number(a.delta)}/2)",
                res(a.omega_max, "angular_speed"),
                2,
            )
        )
        blocks.append(
            self.eq(
                "omega_min",
                "ω_{min} = ω_{m} (1 − δ/2)",
                f"{w} × (1 − {number(a.delta)}/2)",
                res(a.omega_min, "angular_speed"),
                2,
            )
        )

    def step_reduction(self):
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
                    number(s.speed_ratio),
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
        rows.append(("efficiency motor → reference shaft η", number(scene.efficiency, 4)))
        blocks.append(Facts(tuple(rows), "reduction"))

    def step_work(self):
        a, si, res = self.analysis, self.si, self.result
        blocks = self.section("Work balance and power", "work", 2)
        ind = a.indicator
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
                    self.q(net, "energy"),
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
                f"{si(a.power, 'power')} / {number(a.efficiency)}",
                res(a.motor_power, "power"),
                11,
            )
        )

    def step_a_max(self):
        a, scene = self.analysis, self.scene
        blocks = self.section("Energy indicator diagram and A_max", "a_max", 2)
        from flyopt.report import plots

        self.figure(
            blocks,
            "turning_moment",
            "Turning-moment diagram: the torques over the cycle, surplus and deficit areas between them",
            plots.plot_turning_moment,
            scene,
            a,
        )
        same = (a.angle_delta_e_max, a.angle_delta_e_min) == (a.angle_omega_max, a.angle_omega_min)
        top, bottom = ("ω_max", "ω_min") if same else ("ΔE max", "ΔE min")
        rows = []
        for e in a.energy_chain:
            mark = top if e["index"] == a.index_omega_max else bottom if e["index"] == a.index_omega_min else ""
            where = (
                self.n(e["angle"], "angle")
                if e["angle"] is not None
                else ("start" if e["index"] == 0 else f"after area {e['index']}")
            )
            rows.append([str(e["index"]), where, self.n(e["delta_e"], "energy", "delta_e"), mark])
        blocks.append(
            Table(
                ("point", self.head("angle φ", "angle"), self.head("ΔE", "energy"), ""),
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
        chain = [e["delta_e"] for e in a.energy_chain]
        blocks.append(
            self.eq(
                "a_max",
                "A_{max} = max ΔE − min ΔE",
                f"{self.si(max(chain), 'energy')} − {self.si(min(chain), 'energy')}",
                self.result(a.a_max, "energy"),
                4,
            )
        )
        self.figure(
            blocks,
            "energy",
            "Energy indicator diagram: the excess work ΔE from the cycle start, A_max its largest span",
            plots.plot_energy,
            scene,
            a,
        )

    def step_requirement(self):
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
                    f"{number(a.delta)}) − {si(a.j_constant, 'inertia')}",
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
                        f"{number(a.delta)}) − {si(j_mean, 'inertia')}",
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
                    (
                        "No flywheel is needed: the speed stays within δ however small the inertia, "
                        "the motor's slip alone holding it (the periodic solution down to a vanishing "
                        "inertia; ",
                        NOTES,
                        ", section 7).",
                    ),
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
                f"4 × {number(G_STANDARD)} m/s² × {si(a.j_required, 'inertia')}",
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
            self.figure(blocks, "inertia_delta", caption, plots.plot_inertia_delta, self.scene, a, **curve)
        if self.inputs.energy_mass is not None:
            self.figure(
                blocks,
                "energy_mass",
                "Energy–mass (Wittenbauer) diagram: ΔE against J_e, with the tangents of slope ω_max²/2 and ω_min²/2",
                plots.plot_energy_mass,
                self.scene,
                self.inputs.energy_mass,
            )

    def energy_mass_steps(self, blocks, textbook):
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
                f"max_{{φ}}[½ ω_{{min}}² J(φ) − ΔE(φ)], {at(number(math.degrees(phi_min)))}",
                f"½ × {sq(w_min)} × {si(j_min, 'inertia')} − {si(e_min, 'energy')}",
                self.si(upper, "energy", 10, bracket=False),
                6,
            )
        )
        blocks.append(
            self.eq(
                "em_lower",
                f"min_{{φ}}[½ ω_{{max}}² J(φ) − ΔE(φ)], {at(number(math.degrees(phi_max)))}",
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

    def off_words(self, textbook):
        a = self.analysis
        off = (textbook["j_required"] - a.j_margin) / a.j_margin
        gives = (
            ""
            if textbook["achieved_delta"] is None
            else f"; that flywheel would really give δ = {number(textbook['achieved_delta'])}"
        )
        return (f"The textbook step is {100 * off:+.3g} % off the exact J_F", gives, f" (allowed {number(a.delta)}).")

    def dynamic_steps(self, blocks, textbook):
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
        rows = [
            ("J_{F} of the periodic solution", self.q(a.j_margin, "inertia", "j_margin")),
            (
                "ω_{max}, ω_{min}",
                (
                    self.q(a.omega_max, "angular_speed", "omega_max"),
                    ", ",
                    self.q(a.omega_min, "angular_speed", "omega_min"),
                ),
            ),
        ]
        if detail is not None:
            rows.append(("what was held", detail.held))
            rows.append(
                (
                    "limit",
                    "δ reaches the allowed value"
                    if detail.limit == "delta"
                    else "stall: the smallest flywheel that still runs steadily",
                )
            )
            rows.append(("δ of the solution", number(detail.solution.delta)))
        blocks.append(Facts(tuple(rows), "dynamic"))
        if textbook is not None and textbook["j_required"] is not None and a.j_margin > 0:
            blocks.append(Paragraph(self.off_words(textbook), "note"))

    def engine_step(self, blocks):
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
                f"{number(a.delta)}) − {si(tb.j_machine_mean, 'inertia')}",
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

    def step_shafts(self):
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
                    f"{self.si(a.j_required, 'inertia')} / {number(s.speed_ratio)}²",
                    self.result(s.j_required, "inertia"),
                    8,
                )
            )
        rows = [
            [
                s.name,
                number(s.speed_ratio),
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

    # -- 5. the design ----------------------------------------------------------------

    def design_section(self):
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
            blocks.append(Paragraph(d.message, "ok"))
            return
        if best is None:
            blocks.append(Paragraph(f"No feasible design: {d.message}", "warning"))
            return
        material = self.scene.material_library().get(best.material)
        rows = [
            ("material / shaft", f"{best.material} on {best.shaft} (speed ratio {number(best.speed_ratio)})"),
            ("mass", (self.q(best.mass, "mass", "mass"), "" if best.cost is None else f" (cost {number(best.cost)})")),
            (
                "outer / mean / inner diameter",
                (
                    self.q(best.d_outer, "length", "d_outer"),
                    " / ",
                    self.q(best.d_mean, "length", "d_mean"),
                    " / ",
                    self.q(best.d_inner, "length", "d_inner"),
                ),
            ),
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
                    self.q(best.rim_speed, "speed", "rim_speed"),
                    " (limit ",
                    self.q(best.rim_speed_limit, "speed", "rim_speed_limit"),
                    ")",
                ),
            ),
            ("binding", ", ".join(best.binding) or "none"),
            ("solved by", self.solved_by(best)),
        ]
        if best.bore:
            rows.insert(3, ("bore", self.q(best.bore, "length", "bore")))
        blocks.append(Facts(tuple(rows), "design"))
        if not d.spec.has_envelope:
            blocks.append(
                Paragraph(
                    "No envelope (design.max_outer_diameter) is set, so only the rim speed limit bounds the diameter.",
                    "note",
                )
            )
        self.geometry_steps(blocks, best, material)
        self.parts(blocks, best)
        self.stress(blocks, best)
        self.hub_key_balance(blocks, best)
        from flyopt.report import plots

        self.figure(
            blocks, "cross_section", "Axial section of the chosen wheel, dimensioned", plots.plot_cross_section, best
        )
        if best.sensitivities:
            blocks.append(
                Table(
                    ("sensitivity of the mass",),
                    tuple([s["text"]] for s in best.sensitivities),
                    ("<",),
                    "How the mass moves with each limit (first order)",
                    "sensitivities",
                )
            )
        if best.notes:
            blocks.append(Table(("note",), tuple([n] for n in best.notes), ("<",), "Notes of the design", "notes"))

    @staticmethod
    def solved_by(candidate):
        from flyopt.report.text import solver_words

        return solver_words(candidate)

    def geometry_steps(self, blocks, c, material):
        """The wheel's mass and inertia (section 9) and its rim speed (section 10), numbers substituted."""
        si, res, sq = self.si, self.result, self.squared
        rho = getattr(material, "density", None)
        if c.geometry == Geometry.DISC and not c.d_inner and len(c.parts) <= 1 and rho:
            d = si(c.d_outer, "length")
            blocks.append(
                self.eq(
                    "disc_mass",
                    "m = π D² B ρ / 4",
                    f"π × {sq(d)} × {si(c.b, 'length')} × {si(rho, 'density')} / 4",
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
        elif c.geometry in ("rim", "thin_rim", "disc") and len(c.parts) <= 1 and rho:
            d_m, h = si(c.d_mean, "length"), si(c.h, "length")
            blocks.append(
                self.eq(
                    "rim_mass",
                    "m = π D_{m} H B ρ",
                    f"π × {d_m} × {h} × {si(c.b, 'length')} × {si(rho, 'density')}",
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
        elif c.parts:
            blocks.append(
                self.eq(
                    "parts_inertia",
                    "J = Σ J_{part}",
                    " + ".join(si(p["inertia"], "inertia") for p in c.parts),
                    res(c.j_flywheel, "inertia"),
                    9,
                )
            )
            blocks.append(
                self.eq(
                    "parts_mass",
                    "m = Σ m_{part}",
                    " + ".join(si(p["mass"], "mass") for p in c.parts),
                    res(c.mass, "mass"),
                    9,
                )
            )
        blocks.append(
            self.eq(
                "j_at_reference",
                "J_{F} = J' i²",
                f"{si(c.j_flywheel, 'inertia')} × {number(c.speed_ratio)}²",
                res(c.j_at_reference, "inertia"),
                8,
            )
        )
        blocks.append(
            self.eq(
                "rim_speed",
                "v = i ω_{max} D_{1} / 2",
                f"{number(c.speed_ratio)} × {si(self.design.omega, 'angular_speed')} × {si(c.d_outer, 'length')} / 2",
                res(c.rim_speed, "speed"),
                10,
            )
        )
        within = c.rim_speed <= c.rim_speed_limit * (1 + 1e-9)
        blocks.append(
            Paragraph(
                (
                    "The rim speed is ",
                    "within" if within else "BEYOND",
                    " the limit v_max = ",
                    self.q(c.rim_speed_limit, "speed", "rim_speed_limit"),
                    f" of {c.material} ({NOTES}, section 10).",
                ),
                "ok" if within else "warning",
            )
        )
        if rho and c.hoop_stress is not None:
            blocks.append(
                self.eq(
                    "hoop_stress",
                    "σ ≈ ρ v²",
                    f"{si(rho, 'density')} × {sq(si(c.rim_speed, 'speed'))}",
                    res(c.hoop_stress, "stress"),
                    10,
                )
            )
            if c.stress:
                blocks.append(
                    Paragraph(
                        f"ρv² is the thin ring's hoop stress at the outer diameter, the textbook's "
                        f"estimate; the stress check below takes every part exactly ({NOTES}, "
                        "section 13)."
                    )
                )

    def parts(self, blocks, c):
        if not c.parts:
            return
        n = self.n
        total_j = sum(p["inertia"] for p in c.parts)
        rows = [
            [
                p["name"],
                (n(p["r_inner"], "length"), " – ", n(p["r_outer"], "length")),
                n(p["thickness"], "length"),
                n(p["mass"], "mass"),
                n(p["inertia"], "inertia"),
                f"{100 * p['inertia'] / total_j:.1f} %" if total_j > 0 else "-",
            ]
            for p in c.parts
        ]
        rows.append(
            [
                "total",
                (
                    n(min(p["r_inner"] for p in c.parts), "length"),
                    " – ",
                    n(max(p["r_outer"] for p in c.parts), "length"),
                ),
                "",
                n(sum(p["mass"] for p in c.parts), "mass"),
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
        if c.n_arms and c.arm_major:
            blocks.append(
                Paragraph(
                    (
                        f"Arms: {c.n_arms} of elliptical section ",
                        self.q(c.arm_major, "length"),
                        " × ",
                        self.q(c.arm_minor, "length"),
                        " (major axis in the plane of rotation, minor axial).",
                    )
                )
            )

    def stress(self, blocks, c):
        if not c.stress:
            return
        from flyopt.report import plots

        s, n = c.stress, self.n
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
                    "-" if use is None else f"{100 * use:.1f} %",
                    n(p.get("strength"), "stress", digits=4),
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
                    self.q(s.get("hoop_max"), "stress", digits=4),
                    " / ",
                    self.q(s.get("radial_max"), "stress", digits=4),
                    " (von Mises ",
                    self.q(s.get("von_mises"), "stress", digits=4),
                    ")",
                ),
            )
        )
        if s.get("mean_hoop") is not None and math.isfinite(s["mean_hoop"]):
            facts.append(("mean hoop stress over the radial section", self.q(s["mean_hoop"], "stress", digits=4)))
        if c.strength_safety is not None and math.isfinite(c.strength_safety):
            facts.append(("safety on strength", number(c.strength_safety, 3)))
        if c.burst_speed is not None and math.isfinite(c.burst_speed):
            margin = "" if c.speed_margin is None else f" ({number(c.speed_margin, 3)} × ω_max)"
            facts.append(("burst speed on its shaft", (self.q(c.burst_speed, "angular_speed", "burst_speed"), margin)))
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
            )
        elif self.inputs.stress_note:
            blocks.append(Figure("stress", "Stresses over the radius", note=f"Not drawn: {self.inputs.stress_note}."))

    def hub_key_balance(self, blocks, c):
        """The permissible unbalance and the key, numbers substituted (section 13)."""
        si, res = self.si, self.result
        omega = self.design.omega * c.speed_ratio
        if c.unbalance_permissible is not None and math.isfinite(c.unbalance_permissible) and c.mass:
            from flyopt.design.balance import permissible_unbalance

            grade = inspect.signature(permissible_unbalance).parameters["grade"].default
            e_per = c.unbalance_permissible / c.mass
            blocks.append(
                Paragraph(
                    f"Permissible residual unbalance, ISO 21940-11 grade G{number(grade)} at the "
                    f"highest speed of the wheel's shaft ({NOTES}, section 13):"
                )
            )
            blocks.append(
                self.eq(
                    "e_per",
                    "e_{per} = G / Ω",
                    f"{number(grade * 1e-3)} m/s / {si(omega, 'angular_speed')}",
                    res(e_per, "length"),
                    13,
                )
            )
            blocks.append(
                self.eq(
                    "u_per",
                    "U_{per} = e_{per} m",
                    f"{si(e_per, 'length')} × {si(c.mass, 'mass')}",
                    res(c.unbalance_permissible, "unbalance"),
                    13,
                )
            )
        if not c.key:
            return
        k = c.key
        blocks.append(
            Paragraph(
                (
                    f"Key (DIN 6885-1 form A) {k['size']} on the ",
                    self.q(c.bore, "length"),
                    " bore, length ",
                    self.q(k["length"], "length"),
                    " (effective ",
                    self.q(k["effective_length"], "length"),
                    f"): {'OK' if k['ok'] else 'NOT OK'}, at the flywheel's peak torque ",
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
                            q(k["bearing_pressure"], "stress", digits=4),
                            " (allowable ",
                            q(k["allowable_pressure"], "stress", digits=4),
                            ")",
                        ),
                    ),
                    (
                        "shear",
                        (
                            q(k["shear"], "stress", digits=4),
                            " (allowable ",
                            q(k["allowable_shear"], "stress", digits=4),
                            ")",
                        ),
                    ),
                ),
                "key",
            )
        )

    # -- 6. ranking ---------------------------------------------------------------------

    def ranking_section(self):
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
            if c.feasible:
                rank += 1
                row = [
                    str(rank),
                    c.material,
                    c.shaft,
                    self.n(c.mass, "mass"),
                    self.n(c.d_outer, "length"),
                    self.n(c.h, "length"),
                    self.n(c.b, "length"),
                    self.n(c.rim_speed, "speed"),
                    ", ".join(c.binding),
                ]
            else:
                row = ["-", c.material, c.shaft, "cannot win" if c.pruned else "infeasible", "", "", "", "", ""]
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
        reasons = [c.reason for c in d.candidates if not c.feasible and not c.pruned]
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
        reasons = [c.reason for c in d.candidates if c.pruned]
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

    # -- 7. drive ---------------------------------------------------------------------------

    def drive_section(self):
        drive, check = self.solution.drive, self.solution.drive_check
        if drive is None:
            return
        blocks = self.section("The drive designed with the flywheel", "drive")
        blocks.append(
            Paragraph(
                f"The motor, its ratio and the flywheel's shaft designed together (objective: "
                f"{drive.objective}; {drive.note}; {NOTES}, section 14)."
            )
        )
        best = drive.best
        if best is None:
            blocks.append(Paragraph(f"INFEASIBLE: {drive.message}", "warning"))
        else:
            m = best.motor
            from flyopt.report.drive import limit_words

            rows: list[Any] = [
                (
                    "motor",
                    (
                        f"{m.name}: ",
                        self.q(m.rated_power, "power", "rated_power"),
                        " at ",
                        self.q(m.rated_speed, "angular_speed", "rated_speed"),
                        " (rated torque ",
                        self.q(m.rated_torque, "torque", "rated_torque"),
                        ", rotor ",
                        self.q(m.rotor_inertia, "inertia", "rotor_inertia"),
                        ")",
                    ),
                ),
                ("motor ratio", f"{number(best.motor_ratio)} (motor speed over crank speed)"),
                (
                    "flywheel",
                    (
                        self.q(best.j_flywheel, "inertia", "j_flywheel"),
                        " at the crank, set by ",
                        limit_words(best.limit),
                    ),
                ),
                (
                    "RMS torque",
                    (
                        self.q(best.rms_torque, "torque", "rms_torque"),
                        " of the rated ",
                        self.q(best.rated_torque, "torque"),
                        " (mean ",
                        self.q(best.mean_torque, "torque", "mean_torque"),
                        ")",
                    ),
                ),
                (
                    "start-up",
                    (self.q(best.startup_time, "time", "startup_time"), " from rest (Kloss curve, declutched)"),
                ),
                (
                    "masses",
                    (
                        "motor ",
                        self.q(best.motor_mass, "mass"),
                        " + wheel ",
                        self.q(best.wheel_mass, "mass"),
                        " = ",
                        self.q(best.total_mass, "mass", "total_mass"),
                    ),
                ),
            ]
            if best.flywheel_ratio is not None:
                rows.insert(3, ("flywheel shaft ratio", number(best.flywheel_ratio)))
            if best.cost is not None:
                rows.append(("cost", number(best.cost)))
            if drive.relaxation is not None:
                from flyopt.report.drive import relaxation_summary

                summary, moved = relaxation_summary(drive, self.units)
                rows.append(("relaxed optimum", summary))
                if moved:
                    rows.append(("binding limits", "; ".join(moved) + " (relaxed optimum, first order)"))
            blocks.append(Facts(tuple(rows), "drive"))
        rows = []
        for run in drive.runs:
            rows.append(
                [
                    run.motor.name,
                    self.n(run.motor.rated_power, "power"),
                    number(run.motor_ratio, 5),
                    self.n(run.j_flywheel, "inertia"),
                    run.limit or "-",
                    number(run.rms_torque / run.rated_torque, 4) if run.rms_torque else "-",
                    self.n(run.startup_time, "time"),
                    number(run.flywheel_ratio, 4),
                    self.n(run.wheel_mass, "mass"),
                    self.n(run.total_mass, "mass"),
                    ("best" if run is best else "ok") if run.feasible else run.reason,
                ]
            )
        blocks.append(
            Table(
                (
                    "motor",
                    self.head("rated power", "power"),
                    "motor ratio",
                    self.head("J_{F}", "inertia"),
                    "limit",
                    "RMS / rated torque",
                    self.head("start-up", "time"),
                    "flywheel ratio r",
                    self.head("wheel", "mass"),
                    self.head("total", "mass"),
                    "verdict",
                ),
                tuple(rows),
                ("<",) + (">",) * 9 + ("<",),
                "Every motor size solved",
                "drive_runs",
            )
        )
        if check is not None:
            v = check.verification
            verdict = "FLAGGED: " + "; ".join(check.notes) if check.flagged else "ok"
            blocks.append(
                Paragraph(
                    (
                        f"Drive verification (the machine simulated with the wheel as built): {verdict}. "
                        f"Achieved δ {number(v.achieved_delta)} against {number(v.delta_allowed)}; mean "
                        "speed ",
                        self.q(v.omega_mean, "angular_speed"),
                        "; RMS torque ",
                        self.q(check.rms_torque, "torque"),
                        " of ",
                        self.q(check.rated_torque, "torque"),
                        "; start-up ",
                        self.q(check.startup_time, "time"),
                        ".",
                    ),
                    "warning" if check.flagged else "ok",
                )
            )

    # -- 8. verification ---------------------------------------------------------------------

    def verification_section(self):
        v = self.solution.verification
        a = self.analysis
        blocks = self.section("Verification", "verification")
        if v is None and self.solution.drive_check is None:
            blocks.append(Paragraph("Nothing to verify: no flywheel was designed.", "note"))
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
                                f" against the allowed {number(v.delta_allowed)} (tolerance {number(v.tolerance, 3)})",
                            ),
                        ),
                        (
                            "speed range",
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
                            f"= {number(v.achieved_delta)}",
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
                    f" ({number(st.cycles, 4)} cycles) to ",
                    self.q(st.omega_target, "angular_speed"),
                    f"; {st.method}.",
                )
            else:
                text = f"Start-up from rest: not reached: {st.note}; {st.method}."
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
                "Speed over the cycle with the required flywheel"
                + (", and the simulation of the design over it" if simulation is not None else ""),
                plots.plot_speed,
                self.scene,
                a,
                self.inputs.speed,
                simulation,
            )

    # -- 9. provenance -------------------------------------------------------------------------

    def provenance_section(self):
        blocks = self.section("Provenance", "provenance")
        blocks.append(Facts(tuple(self.inputs.provenance), "provenance"))
