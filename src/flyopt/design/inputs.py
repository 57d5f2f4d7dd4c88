"""The one translation from a scene to what the designer needs.

``flyopt solve``, the sweep, the Pareto fronts and the material trade-off all
take the materials, the mounting shafts and the design specification of a
scene from :func:`design_inputs`, so a scene means the same design problem
wherever it is used. A sweep point is first made a scene of its own
(:func:`flyopt.studies.points.point_scene`), or, vectorized, its columns
override exactly these defaults.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from flyopt.design.spec import DesignSpec, MountShaft

if TYPE_CHECKING:  # annotations only
    from flyopt.design.materials import Material
    from flyopt.io.scene import Scene

__all__ = ["DesignInputs", "design_inputs", "builds_whole", "one_design"]


@dataclass(frozen=True)
class DesignInputs:
    """The design problem of a scene, apart from the inertia and the speed.

    Attributes
    ----------
    materials : tuple of flyopt.design.materials.Material
        The materials to consider, in the scene's order (default: the scene's own and the
        built-in defaults, :func:`flyopt.design.materials.default_materials`).
    shafts : tuple of MountShaft
        The shafts the wheel may sit on, in the scene's order (default: every [[shaft]]).
    spec : DesignSpec
        Geometry, limits and objective.
    """

    materials: tuple[Material, ...]
    shafts: tuple[MountShaft, ...]
    spec: DesignSpec


def design_inputs(scene: Scene) -> DesignInputs:
    """The materials, mounting shafts and design specification of a scene.

    Parameters
    ----------
    scene : flyopt.io.scene.Scene

    Returns
    -------
    DesignInputs
    """
    from flyopt.design.materials import design_material_names

    library = scene.material_library()
    materials = tuple(library[name] for name in design_material_names(library, scene.design_materials))
    allowed = scene.design_shafts
    shafts = tuple(
        MountShaft(s.name, s.speed_ratio, s.diameter) for s in scene.shafts if allowed is None or s.name in allowed
    )
    spec = scene.design if scene.design is not None else DesignSpec()
    _check_own_materials(scene, materials, spec)
    return DesignInputs(materials=materials, shafts=shafts, spec=spec)


def builds_whole(inputs: DesignInputs) -> bool:
    """Whether a design problem has a combination flyopt designs as a whole wheel (a web or arms and a hub, a
    bore, or any wheel under the stress criterion), not as the textbook's bare rim or disc
    (:meth:`flyopt.design.spec.DesignSpec.textbook`)."""
    from flyopt.design.wheel_design import bore_of

    return any(not inputs.spec.textbook(bore_of(inputs.spec, s)) for s in inputs.shafts)


def one_design(inputs: DesignInputs) -> DesignInputs:
    """The design problem of one design (``flyopt solve``, ``report``, ``export``): a wheel flyopt designs whole
    (:func:`builds_whole`) is rounded to whole millimetres (:data:`flyopt.design.spec.DEFAULT_ROUND_TO`)
    unless the scene gives its own step or ``round_to = false``; where no wheel near the optimum on that
    grid meets every limit, the continuous optimum stays the design and the reason is given
    (``round_strict`` False), where a step the scene gave makes the design infeasible. Sweeps, Pareto fronts, the trade-off and the
    drive's co-design compare continuous designs and do not come here. A textbook design stays as the books
    make it."""
    import dataclasses

    from flyopt.design.spec import DEFAULT_ROUND_TO

    if inputs.spec.round_to is not None or not builds_whole(inputs):
        return inputs
    spec = dataclasses.replace(inputs.spec, round_to=DEFAULT_ROUND_TO, round_strict=False)
    return dataclasses.replace(inputs, spec=spec)


def _check_own_materials(scene: Scene, materials: tuple[Material, ...], spec: DesignSpec) -> None:
    """Refuse a ``[[material]]`` of the scene that the design cannot use for want of a field the scene
    could have given: its Poisson's ratio under the stress criterion or for a web or arms. A
    shipped material without one is a material that cannot make such a wheel (its combinations
    say so); a material the user wrote for this design lacks a field (SceneError, as ``check`` says)."""
    from flyopt.design.wheel_design import missing_poisson
    from flyopt.errors import SceneError

    own = {m.name for m in scene.materials}
    for material in materials:
        if material.name in own and missing_poisson(material, spec):
            raise SceneError(
                f"material.{material.name}.poisson_ratio",
                f"missing: the {spec.criterion} criterion and the stress of a {spec.geometry} need it "
                "(e.g. 0.26 for grey cast iron, 0.3 for steel)",
                scene.source,
            )


def seat_given_only(scene: Scene, what: str) -> None:
    """Refuse a described shaft whose seat diameter is left to the design (``diameter = "design"``,
    docs/flywheel-design.md, section 26) where ``what`` designs wheels without the shaft's search.

    Only :func:`flyopt.pipeline.solve` (``flyopt solve``, ``report``) walks the seat through its series
    with the shaft's post-check; a sweep, a Pareto front or a material trade-off designs its wheels on the
    shafts as given, and a designed seat gives no bore to design the hub and key on.

    Raises
    ------
    SceneError
        Naming the designed step's ``diameter`` and what to give instead.
    """
    from flyopt.errors import SceneError

    for k, shaft in enumerate(scene.shafts):
        layout = shaft.layout
        if layout is not None and layout.designs_seat:
            raise SceneError(
                f"shaft[{k}].segments[{layout.designed[0]}].diameter",
                f'"design" leaves the seat of shaft {shaft.name!r} to flyopt solve and report, which choose it with '
                f"the shaft's checks; {what} designs its wheels on a given seat: give the diameter (the one solve "
                "chooses, for one)",
            ).with_source(scene.source)


def wheel_alone_only(scene: Scene, what: str) -> None:
    """Refuse a scene whose answer is not a wheel designed alone where ``what`` designs wheels alone: a
    ``[flywheel]`` that exists (analysed by ``flyopt solve``, not designed) and a ``[drive]`` (the motor, its ratio
    and the wheel designed together by ``flyopt solve``). A sweep, a front and a trade-off of either designed a
    wheel as if the scene gave neither: press-drive's sweep found every point infeasible at the crank, where solve
    designs its motor, ratio and wheel.

    Raises
    ------
    SceneError
        Naming the section and what answers it.
    """
    from flyopt.errors import SceneError

    scene.require_cycle()  # a calculation is refused as one first (it may give a [flywheel] too)
    if scene.flywheel is not None:
        raise SceneError(
            "flywheel",
            f"gives a flywheel that exists, which flyopt solve, check and report analyse; {what} designs flywheels: "
            "remove [flywheel] to design one",
        ).with_source(scene.source)
    if scene.drive is not None:
        raise SceneError(
            "drive",
            f"designs the motor, its ratio and the wheel together (flyopt solve, report), where {what} designs the "
            "wheel alone: compare the drives by flyopt pareto --objectives mass,motor_power, or design the wheel "
            "alone without [drive]",
        ).with_source(scene.source)


def single_design_only(spec: DesignSpec, what: str, source: str | None = None) -> None:
    """Refuse the courses' rim convention where ``what`` designs by flyopt's own criteria only.

    Criterion ``mean_rim_speed``, a given ``rim_speed``, a ``rim_share`` below 1 and rounding
    (``round_to``) act in :func:`flyopt.design.design_flywheel` only, on one bare
    rim through :func:`flyopt.design.design_flywheel` (``flyopt solve``,
    ``report``, ``tradeoff``); sweeps, Pareto fronts and the drive's
    co-design size their wheels by other paths, which know only
    ``rim_speed`` and ``stress`` and the whole J_F.

    Raises
    ------
    SceneError
        Naming the field and what ``what`` allows (and ``source``, the scene's file, when given).
    """
    from flyopt.errors import SceneError

    if spec.by_mean_rim_speed:
        raise SceneError(
            "design.criterion",
            f"'mean_rim_speed' (the courses' convention) sizes one rim at a time; {what} uses 'rim_speed' or 'stress'",
        ).with_source(source)
    if spec.rim_speed is not None:
        raise SceneError(
            "design.rim_speed",
            f"pins one rim's mean diameter at the mean speed (solve, report, tradeoff); {what} does not know it: "
            "give d_mean (2 v / omega'_m) instead",
        ).with_source(source)
    if spec.round_to:
        raise SceneError(
            "design.round_to",
            f"rounds one winning wheel (solve, report); {what} reports continuous designs: leave it out",
        ).with_source(source)
    if spec.rim_share < 1.0:
        raise SceneError(
            "design.rim_share",
            f"is the courses' share of one rim (solve, report, tradeoff); {what} designs the whole flywheel: leave it out",
        ).with_source(source)
