"""Diagrams of a scene, its analysis and its design (matplotlib), one module per diagram family.

Each ``plot_*`` function draws on a given Axes (or a new figure) and returns
the Axes; :func:`save` writes a figure atomically (to a temporary file in the
same folder, then renamed), so a failed render leaves nothing half-written.
The backend is Agg unless the caller chose another one.

The plots draw computed results and never run a model: what a diagram needs
beyond the :class:`~flyopt.analysis.Analysis` (the speed over the cycle, a
simulation, a design, J_F at other δ) is computed by the caller and passed
in. A diagram that does not apply to the scene raises :class:`ValueError`;
one that would be empty because the machine needs no flywheel raises
:class:`NothingToDraw`.

One visual standard for every diagram: each axis carries its unit in the
system the caller chose (``units``: :data:`flyopt.report.display.SYSTEMS`,
engineering by default: mm, rpm, MPa, and a torque, energy, power or force
in N·m, J, W, N with the prefix the axis' largest value needs,
:func:`~flyopt.report.plots.standard.scale`), its labels ``digits``
significant figures (``--digits``), the legend sits outside
the data (below a figure the function made, right of an Axes it was
given), labels are placed where no curve and no other label is, and
titles are wrapped to the figure's width. The diagrams of one cycle share
their x axis: the cycle from 0 to Φ.

The modules: :mod:`~flyopt.report.plots.standard` (the visual standard),
:mod:`~flyopt.report.plots.output` (formats and the atomic save),
:mod:`~flyopt.report.plots.cycle` and :mod:`~flyopt.report.plots.labels`
(what the diagrams of the cycle share), one module per diagram
(:mod:`~flyopt.report.plots.turning_moment`, :mod:`~flyopt.report.plots.energy`,
:mod:`~flyopt.report.plots.inertia_delta`, :mod:`~flyopt.report.plots.cross_section`,
:mod:`~flyopt.report.plots.stress`, :mod:`~flyopt.report.plots.speed`,
:mod:`~flyopt.report.plots.energy_mass`) and :mod:`~flyopt.report.plots.results`
(sweeps and Pareto fronts). A diagram split into what it draws and how (:class:`Plot`:
:data:`TURNING_MOMENT`, :data:`ENERGY`, :data:`INERTIA_DELTA`,
:data:`SPEED`) has an exact digest of its data
(:mod:`~flyopt.report.plots.digest`): the same digest, the same figure. This package names the diagrams of a scene
(:data:`PLOTS`) and exposes every drawing function.
"""

from __future__ import annotations

from flyopt.report.plots.cross_section import plot_cross_section
from flyopt.report.plots.digest import Plot
from flyopt.report.plots.energy import ENERGY, plot_energy
from flyopt.report.plots.energy_mass import check_energy_mass, plot_energy_mass
from flyopt.report.plots.inertia_delta import INERTIA_DELTA, check_inertia_delta, plot_inertia_delta
from flyopt.report.plots.output import FORMATS, check_output, save
from flyopt.report.plots.results import (
    MAX_LINES,
    RESULT_PLOTS,
    pareto_objectives,
    plot_pareto,
    plot_sweep,
    varied_fields,
)
from flyopt.report.plots.speed import SPEED, plot_speed
from flyopt.report.plots.standard import DEFICIT, SURPLUS, NothingToDraw
from flyopt.report.plots.stress import plot_stress
from flyopt.report.plots.turning_moment import TURNING_MOMENT, plot_turning_moment

__all__ = [
    "DEFICIT",
    "ENERGY",
    "FORMATS",
    "INERTIA_DELTA",
    "MAX_LINES",
    "PLOTS",
    "RESULT_PLOTS",
    "SPEED",
    "SURPLUS",
    "TURNING_MOMENT",
    "NothingToDraw",
    "Plot",
    "check_energy_mass",
    "check_inertia_delta",
    "check_output",
    "pareto_objectives",
    "plot_cross_section",
    "plot_energy",
    "plot_energy_mass",
    "plot_inertia_delta",
    "plot_pareto",
    "plot_speed",
    "plot_stress",
    "plot_sweep",
    "plot_turning_moment",
    "save",
    "varied_fields",
]

#: The diagrams of a scene ``flyopt plot --what`` draws, with what each shows.
PLOTS = {
    "turning_moment": "driving and resisting torque over the cycle, areas shaded and labelled",
    "energy": "energy indicator diagram: the chain of ΔE with A_max marked",
    "inertia_delta": "required flywheel J_F against δ by the model that ran, the scene's δ marked",
    "cross_section": "dimensioned axial section of the chosen flywheel (hub, web or arms, rim)",
    "stress": "σ_r, σ_t and von Mises over the radius at ω_max, each part's allowable, the governing point",
    "speed": "ω(φ) over the cycle with the required flywheel, from the model that ran",
    "energy_mass": "energy–mass (Wittenbauer) diagram: ΔE against J_e with the two tangents "
    "(an inertia that varies with the angle)",
}
