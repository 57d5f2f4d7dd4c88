"""What the report is built from, computed before it is built."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene
    from flyopt.sizing.energy_mass import SpeedFluctuation
    from flyopt.sizing.periodic import PeriodicSolution
    from flyopt.sizing.textbook import TextbookRequirement


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
    scene_tables: tuple[str, ...]
    scene: Scene
    solution: object  # flyopt.pipeline.Solution (typed so once flyopt.cli.report drops its cast of it)
    speed: SpeedFluctuation | PeriodicSolution | None = None
    speed_note: str = ""
    energy_mass: Analysis | None = None
    tangents: dict[str, tuple[float, float, float]] | None = None
    j_machine: tuple[float, float, float] | None = None
    inertia_curve: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None
    inertia_note: str = ""
    stress: tuple[Any, ...] | None = None
    stress_note: str = ""
    textbook: TextbookRequirement | None = None
    provenance: tuple[tuple[str, str], ...] = ()
