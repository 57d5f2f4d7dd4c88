"""What every section of the report is written with: its numbers in the reader's units and in SI, its numbered sections, its figures and equations, and the facts of the solution several sections state."""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable, Collection, Sequence
from typing import TYPE_CHECKING, Any, cast

from flyopt.names import Geometry, Model
from flyopt.report import display
from flyopt.report.display import number
from flyopt.report.document import Equation, Figure, Paragraph, Quantity, Section
from flyopt.report.method import NOTES

if TYPE_CHECKING:
    from flyopt.design.result import BookRim, Design
    from flyopt.pipeline import Solution
    from flyopt.report.builder.inputs import ReportInputs
    from flyopt.report.plots.digest import Plot


#: The note of a figure a document of numbers only leaves undrawn (:class:`BuilderBase`, ``figures=False``).
NOT_DRAWN = "Not drawn in this document: it holds the numbers only."


class BuilderBase:
    """The state of a report being built and the tools every section is written with."""

    def __init__(
        self,
        inputs: ReportInputs,
        units: str,
        digits: int = display.DEFAULT_DIGITS,
        figures: bool | Collection[str] = True,
        digests: bool | Collection[str] = False,
        read: dict[str, Any] | None = None,
    ) -> None:
        self.inputs = inputs
        self.units = units
        self.digits = digits  # significant figures of every number shown (--digits)
        # False: the figures' blocks hold their captions only (the app's card first); keys: those figures alone
        # (the app's diagram in view first)
        self.figures = figures if isinstance(figures, bool) else frozenset(figures)
        # the digests of the figures it does not draw (True: all, or those of these keys), where they have one
        self.digests = digests if isinstance(digests, bool) else frozenset(digests)
        # a split diagram's data by figure key, read once for the documents of one solve (the caller's, kept)
        self.read: dict[str, Any] = {} if read is None else read
        self.solution = cast("Solution", inputs.solution)
        self.scene = self.solution.scene
        self.analysis = self.solution.analysis
        self.design = self.solution.design
        self.sections: list[Section] = []
        self.failures: list[str] = []
        self._numbers = [0, 0]

    @property
    def worked(self) -> int:
        """The significant figures of a worked equation's numbers (:func:`flyopt.report.display.worked_digits`)."""
        return display.worked_digits(self.digits)

    def q(self, value: float | None, dimension: str, name: str | None = None, digits: int | None = None) -> Quantity:
        """A Quantity in the report's units, its unit after it ("-" where the value does not exist); ``digits``
        the report's unless given."""
        if value is None or math.isnan(value):
            return Quantity("-", name, None, dimension)
        text = display.quantity_text(value, dimension, self.units, digits or self.digits)
        return Quantity(text, name, float(value), dimension)

    def n(
        self,
        value: float | None,
        dimension: str,
        name: str | None = None,
        digits: int | None = None,
        among: Sequence[float | None] | None = None,
    ) -> Quantity:
        """A Quantity in the report's units without its unit (a table cell: the unit is in the column's head,
        :meth:`head` given the same ``among``, the column's SI values, which choose its one unit)."""
        if value is None or math.isnan(value):
            return Quantity("-", name, None, dimension)
        magnitude = None if among is None else display.largest(among)  # none: the head's unit without values
        factor = display.unit(dimension, self.units, magnitude, digits or self.digits)[1]
        scale = None if magnitude is None else magnitude / factor
        return Quantity(number(float(value) / factor, digits or self.digits, scale), name, float(value), dimension)

    def head(self, title: str, dimension: str, among: Sequence[float | None] | None = None) -> str:
        """A column's head with the unit of its numbers, "mass [kg]" (``among``: the column, as :meth:`n`)."""
        magnitude = None if among is None else display.largest(among)
        unit = display.unit(dimension, self.units, magnitude, self.digits)[0]
        return title if unit == "-" else f"{title} [{unit}]"

    @staticmethod
    def squared(text: str) -> str:
        """A number with its unit, squared: "(157.08 rad/s)²" (a bare number needs no brackets)."""
        return f"({text})²" if " " in text and not text.startswith("(") else f"{text}²"

    def si(self, value: float | None, dimension: str, digits: int | None = None, bracket: bool = True) -> str:
        """A number with its SI unit, as an equation shows it (the report's figures and its guard figures,
        :func:`flyopt.report.display.worked_digits`, unless ``digits``); a negative one in brackets."""
        text = number(value, digits or display.worked_digits(self.digits))
        unit = display.label(dimension, "si")
        text = text if unit == "-" else f"{text} {unit}"
        return f"({text})" if bracket and value is not None and value < 0 else text

    def result(self, value: float | None, dimension: str, digits: int | None = None) -> str:
        """An equation's result in SI (to the equation's figures), and in the report's units where those differ."""
        shown = self.si(value, dimension, digits, bracket=False)
        digits = digits or self.digits
        magnitude = None if value is None else abs(value)
        if display.unit(dimension, self.units, magnitude, digits)[0] != display.label(dimension, "si"):
            shown += f"   ({display.quantity_text(value, dimension, self.units, digits)})"
        return shown

    def section(self, title: str, key: str, level: int = 1) -> list[Any]:
        """Open a numbered section (level 1) or subsection (level 2): its list of blocks, to fill."""
        if level == 1:
            self._numbers = [self._numbers[0] + 1, 0]
            label = str(self._numbers[0])
        else:
            self._numbers[1] += 1
            label = f"{self._numbers[0]}.{self._numbers[1]}"
        section = Section(label, title, [], level, key)
        self.sections.append(section)
        return section.blocks

    def figure(
        self, blocks: list[Any], key: str, caption: str, draw: Callable[..., Any] | Plot, *args: Any, **kwargs: Any
    ) -> None:
        """Draw a diagram with a function of :mod:`flyopt.report.plots` (``units=`` and ``digits=`` where it takes
        them: the report's), or with a :class:`~flyopt.report.plots.digest.Plot`: its data read off ``args``,
        their digest kept on the block (:attr:`~flyopt.report.document.Figure.digest`), then drawn from them.

        A builder made with ``figures=False`` draws nothing: the block holds the key and caption only, the
        note saying so (a document of numbers, for the app's answer card before its diagrams), and, made with
        ``digests=True``, a Plot's digest (what the app compares with the diagram it shows); one made with a
        collection of keys draws the figures of those keys alone (the app's diagram in view, first). A Plot's
        data are read once for the builders given the same ``read`` (the documents of one solve).
        """
        from flyopt.report import plots
        from flyopt.report.plots.standard import figure_of

        wanted = self.figures is True or (not isinstance(self.figures, bool) and key in self.figures)
        digesting = self.digests is True or (not isinstance(self.digests, bool) and key in self.digests)
        if not wanted and not (digesting and isinstance(draw, plots.Plot)):
            blocks.append(Figure(key, caption, note=NOT_DRAWN))
            return
        if self.solution.drive_failed:  # the analysis is the scene without its drive: no machine to draw
            from flyopt.report.text import NO_MACHINE

            blocks.append(Figure(key, caption, note=f"Not drawn: {NO_MACHINE} (the drive's section says why)."))
            return
        digest, unread = "", None
        call: Callable[..., Any] = draw if not isinstance(draw, plots.Plot) else draw.draw
        if isinstance(draw, plots.Plot):
            plot = draw
            try:
                data = self.read[key] if key in self.read else plot.data(*args, **kwargs)
            except Exception as err:  # noqa: BLE001 -- said below, as the diagram's own call would say it
                if not wanted:
                    blocks.append(Figure(key, caption, note=NOT_DRAWN))
                    return
                unread = err
            else:
                self.read[key] = data
                try:
                    digest = plot.digest(data, self.units, self.digits)
                except TypeError:  # data it cannot digest: drawn at every edit, never kept
                    digest = ""
                if not wanted:
                    blocks.append(Figure(key, caption, note=NOT_DRAWN, digest=digest))
                    return
                args, kwargs = (data,), {}
        try:
            if unread is not None:
                raise unread
            parameters = inspect.signature(call).parameters
            if "units" in parameters:
                kwargs["units"] = self.units
            if "digits" in parameters:
                kwargs["digits"] = self.digits
            ax = call(*args, **kwargs)
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
        blocks.append(Figure(key, caption, figure=figure_of(ax), digest=digest))

    @staticmethod
    def eq(key: str, formula: str, numbers: str, result: str, section: str | int) -> Equation:
        """A worked step: the formula, "= " the numbers substituted, "= " the result, citing a section of the notes."""
        return Equation(key, (formula, f"= {numbers}", f"= {result}"), f"{NOTES}, section {section}")

    def units_words(self) -> str:
        """The units of the report's system and its figures, in a line ("mm, rpm, N·m, J, ... (N·m, J, W with the
        prefix each value needs); 4 significant figures")."""
        dims = ("length", "angular_speed", "torque", "energy", "stress", "power", "mass", "inertia")
        prefixed = display.PREFIXED.get(self.units, {})
        words = ", ".join(dict.fromkeys(prefixed.get(d) or display.label(d, self.units) for d in dims))
        chosen = [prefixed[d] for d in dims if d in prefixed]
        if chosen:
            words += f" ({', '.join(chosen)} with the prefix each value needs)"
        return f"{words}; {self.digits} significant figures"

    def flagged(self) -> bool:
        """Whether a verification (of the design or of the drive) flagged the solution."""
        v, check = self.solution.verification, self.solution.drive_check
        return bool((v is not None and v.flagged) or (check is not None and check.flagged))

    def document_status(self) -> str:
        """The solution's status as the document carries it: "flagged" after it where a verification flagged it."""
        return self.solution.status + (" flagged" if self.flagged() else "")

    def status_words(self) -> str:
        """The solution's status as the title block says it."""
        status = self.solution.status
        words = {
            "designed": "designed",
            "not_needed": "no flywheel needed",
            "infeasible": "INFEASIBLE: no material and shaft can give the required flywheel",
            "analysed": "analysed (no design)",
            "checked": "the flywheel given, checked",
            "insufficient": "INSUFFICIENT: the flywheel given misses the allowed δ",
        }.get(status, status)
        if self.solution.drive_failed:
            words = "INFEASIBLE: no motor size drives the machine within the limits"
        if self.flagged():
            words += "; VERIFICATION FLAGGED: the simulated δ exceeds the allowed one"
        elif self.solution.verification is not None or self.solution.drive_check is not None:
            words += "; verified"
        return words

    def best(self) -> Design | None:
        """The chosen wheel, or None."""
        return self.design.best if self.design is not None else None

    @staticmethod
    def governing(candidate: Design) -> dict[str, Any] | None:
        """The stress check of the part where the governing stress is, or None."""
        where = (candidate.stresses.stress or {}).get("where") or {}
        for part in (candidate.stresses.stress or {}).get("parts", []):
            if part["part"] == where.get("part"):
                return part
        return None

    @staticmethod
    def model_description(model: str) -> str:
        """What a sizing model is, in words."""
        from flyopt.sizing.choose import MODELS

        return MODELS.get(Model(model), model) if model in MODELS else model

    def material_name(self, key: str) -> str:
        """A material's name for people (the design's; the key with spaces where there is no design)."""
        return self.design.material_name(key) if self.design is not None else key.replace("_", " ")

    def diameter_row(self, c: Design) -> tuple[str, tuple[Any, ...]]:
        """The wheel's diameters: a rim's outer, mean and inner; a disc's outer and its bore (it has no rim)."""
        if c.geometry == Geometry.DISC:
            if c.bore:
                return (
                    "outer diameter / bore",
                    (self.q(c.dims.d_outer, "length", "d_outer"), " / ", self.q(c.bore, "length", "bore")),
                )
            return ("outer diameter", (self.q(c.dims.d_outer, "length", "d_outer"),))
        return (
            "outer / mean / inner diameter",
            (
                self.q(c.dims.d_outer, "length", "d_outer"),
                " / ",
                self.q(c.dims.d_mean, "length", "d_mean"),
                " / ",
                self.q(c.dims.d_inner, "length", "d_inner"),
            ),
        )

    def width_row(self, c: Design) -> tuple[str, tuple[Any, ...]]:
        """The wheel's width and, for a rim, its radial thickness (a disc is the annulus with no hole, section 9)."""
        if c.geometry == Geometry.DISC:
            return (
                "axial width B",
                (
                    self.q(c.dims.b, "length", "b"),
                    " (a solid disc)"
                    if not c.dims.d_inner
                    else " (on its hub, see the parts)"
                    if c.dims.d_hub
                    else " (an annulus on its bore)",
                ),
            )
        return (
            "rim: radial thickness H × axial width B",
            (
                self.q(c.dims.h, "length", "h"),
                " × ",
                self.q(c.dims.b, "length", "b"),
                f" (H/B {number(c.dims.hb_ratio, self.digits)})",
            ),
        )

    def limit(self, value: float | None) -> Quantity | str:
        """A length limit, or "not set"."""
        return "not set" if value is None or not math.isfinite(value) else self.q(value, "length")

    def omega_given(self) -> float:
        """The mean speed the sizing took as given [rad/s] (a speed-dependent machine's is only a guess)."""
        machine = self.analysis.machine
        return machine.omega_mean if machine is not None else self.scene.omega_mean

    def off_words(self, textbook: dict[str, Any]) -> tuple[str, str, str]:
        """How far the textbook flywheel is from the exact J_F, in words."""
        a = self.analysis
        off = (textbook["j_required"] - a.j_margin) / a.j_margin
        gives = (
            ""
            if textbook["achieved_delta"] is None
            else f"; that flywheel would really give δ = {number(textbook['achieved_delta'], self.digits)}"
        )
        return (
            f"The textbook step is {100 * off:+.3g} % off the exact J_F",
            gives,
            f" (allowed {number(a.delta, self.digits)}).",
        )

    @staticmethod
    def solved_by(candidate: Design) -> str:
        """How the candidate's sizing problem was solved, in words."""
        from flyopt.report.text import solver_words

        return solver_words(candidate)

    def book_rim_verdict(self, book: BookRim) -> Paragraph:
        """The courses' rim (criterion mean_rim_speed) beside what it really sees at ω_max, in a warning."""

        def over(stress: float | None) -> str:
            excess = book.excess(stress)
            if excess is None:
                return ""
            return f", {display.share(abs(excess))} {'over' if excess > 1e-9 else 'within'} the allowable"

        text: list[Any] = [
            "Criterion mean_rim_speed, the courses' convention, sized this rim: at the mean diameter and the mean "
            "speed it runs at v_m = ",
            self.q(book.mean_rim_speed, "speed", "rim_speed"),
            ", where ρ v_m² = ",
            self.q(book.book_stress, "stress", "hoop_stress"),
            " is the allowable. But the stress peaks at the top speed ω_max: at the outer diameter the thin ring's "
            "ρv² is ",
            self.q(book.outer_hoop_stress, "stress", "hoop_stress"),
            over(book.outer_hoop_stress),
        ]
        if book.largest_stress is not None:
            text += [
                ", and Lamé's stress at the bore ",
                self.q(book.largest_stress, "stress", "hoop_stress"),
                over(book.largest_stress),
            ]
        text.append(f" ({NOTES}, section 20). flyopt's default criterion (rim_speed) keeps the rim within it.")
        if book.rim_share < 1.0:
            text.append(
                f" The rim gives {book.rim_share:.4g} of the required inertia (design.rim_share); the arms and hub, "
                "not designed here, must give the rest."
            )
        excess = book.excess(book.largest_stress if book.largest_stress is not None else book.outer_hoop_stress)
        return Paragraph(tuple(text), "warning" if excess is not None and excess > 1e-9 else "note")
