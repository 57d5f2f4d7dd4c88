"""The engineering report of one scene built as one :class:`~flyopt.report.document.Document`, its sections in the order of the domain notes."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from flyopt.report import display
from flyopt.report.builder.calculation import CalculationInputs, build_calculation
from flyopt.report.builder.design import DesignSection
from flyopt.report.builder.drive import DriveSection
from flyopt.report.builder.existing import ExistingFlywheelSection
from flyopt.report.builder.inputs import ReportInputs
from flyopt.report.builder.ranking import Ranking
from flyopt.report.builder.scene import SceneAndModel
from flyopt.report.builder.shaft import ShaftSection
from flyopt.report.builder.steps import Steps
from flyopt.report.builder.summary import Summary
from flyopt.report.builder.verification import VerificationAndProvenance
from flyopt.report.document import Document
from flyopt.report.method import citing, with_appendix
from flyopt.report.plots import standard


def build(
    inputs: ReportInputs | CalculationInputs,
    units: str = display.DEFAULT,
    title_block: tuple[tuple[str, Any], ...] = (),
    digits: int = display.DEFAULT_DIGITS,
    figures: bool | Collection[str] = True,
    digests: bool | Collection[str] = False,
    read: dict[str, Any] | None = None,
) -> Document:
    """The report of a solved scene, or of a scene that is one calculation, in a unit system.

    Parameters
    ----------
    inputs : ReportInputs or CalculationInputs
        A cycle's solution, or one calculation's answer (its report:
        :func:`flyopt.report.builder.calculation.build_calculation`).
    units : {"engineering", "si", "imperial"}
        The units of the summary, facts and tables (equations stay SI).
    title_block : tuple of (str, str)
        Lines added to the title block (the date, the file's hash).
    digits : int
        Significant figures of every number shown, tables and equations alike
        (:func:`flyopt.report.display.check_digits`).
    figures : bool or collection of str
        False: no diagram is drawn, each figure's block holds its caption only (a document of the
        numbers, built in a few milliseconds: the app's answer card before its diagrams); figure keys
        ("speed"): those diagrams alone are drawn, the others' blocks hold their captions only (the
        app's diagram in view, drawn first). A calculation's report draws its figures either way.
    digests : bool or collection of str
        Give the figures it does not draw (all, or those of these keys) the digest of what they would draw,
        where they have one
        (:class:`flyopt.report.plots.digest.Plot`; a drawn figure has it either way): the app keeps a diagram it
        shows whose digest an edit leaves as it was.
    read : dict, optional
        The split diagrams' data by figure key, read by the first document built with it and kept there for
        the next of the same solve (the app's documents of one answer: its digests, then its diagrams).

    Returns
    -------
    Document
        Its figures are open matplotlib Figures: render it, then :meth:`Document.close`.
    """
    display.check_system(units)
    display.check_digits(digits)
    # its figures made without the collector's full scans (issue 26), citing the notes as its text does
    with standard.collector_paused(), citing() as cited:
        if isinstance(inputs, CalculationInputs):
            document = build_calculation(inputs, units, title_block, digits)
        else:
            document = Builder(inputs, units, digits, figures, digests, read).document(title_block)
    return with_appendix(document, cited)


class Builder(
    Summary,
    SceneAndModel,
    Steps,
    ExistingFlywheelSection,
    DesignSection,
    ShaftSection,
    Ranking,
    DriveSection,
    VerificationAndProvenance,
):
    """Builds the sections in the order of the domain notes."""

    def document(self, extra: tuple[tuple[str, Any], ...]) -> Document:
        """Every section in order, and the title block with ``extra`` lines."""
        self.summary()
        self.scene_section()
        self.model_section()
        self.steps()
        self.existing_flywheel_section()
        self.design_section()
        self.shaft_section()
        self.ranking_section()
        self.drive_section()
        self.verification_section()
        self.provenance_section()
        status = self.document_status()
        head = (
            (("scene file", self.inputs.scene_file),)
            + tuple(extra)
            + (("units", f"{self.units}: {self.units_words()}; equations in SI"), ("status", self.status_words()))
        )
        return Document(self.analysis.title, head, self.sections, self.units, status, self.failures)
