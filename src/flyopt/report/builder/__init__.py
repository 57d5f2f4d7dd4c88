"""The engineering report of one scene: what ``flyopt report`` writes as HTML or PDF, built section by section.

A scene that is one calculation rather than a cycle has its own, shorter
report (:mod:`~flyopt.report.builder.calculation`): :func:`build` takes its
:class:`CalculationInputs` as well.

The report is built once as a neutral :class:`~flyopt.report.document.Document`
by :func:`build`, one module per section (:mod:`~flyopt.report.builder.summary`,
:mod:`~flyopt.report.builder.scene`, :mod:`~flyopt.report.builder.steps` and
:mod:`~flyopt.report.builder.requirement`, :mod:`~flyopt.report.builder.design`,
:mod:`~flyopt.report.builder.ranking`, :mod:`~flyopt.report.builder.drive`,
:mod:`~flyopt.report.builder.verification`) on the tools of
:mod:`~flyopt.report.builder.base`, then rendered by :mod:`flyopt.report.html` or
:mod:`flyopt.report.pdf`, so that the two formats always say the same thing.

What it contains, for a colleague or a customer who was not there: a title
block (scene, file, date, flyopt version), the answer first (required J_F,
the chosen wheel, its mass and dimensions, the binding limits, the verified
δ), the scene file as given, the model chosen and why, every step of the
calculation in the order of docs/flywheel-design.md with its equation, the
numbers substituted and the section it comes from, every diagram, the design
with its parts, stress check, key, balance and sensitivities, the ranking of
every combination, the drive, the verification and the provenance.

Like the rest of :mod:`flyopt.report`, this package runs no model: every
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

from flyopt.report.builder.calculation import CalculationInputs
from flyopt.report.builder.inputs import ReportInputs
from flyopt.report.builder.report import build

__all__ = ["CalculationInputs", "ReportInputs", "build"]
