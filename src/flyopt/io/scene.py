"""Scene files: one machine to regulate, read from TOML and checked field by field.

A scene says how fast the reference shaft turns, the allowed coefficient of
speed fluctuation δ, the torques over one cycle (two curves, or the signed net
areas between them), and the shafts a flywheel may sit on. Every value may
carry a unit ("1500 rpm", "100 N*m/mm"); plain numbers are SI. Everything that
is wrong is reported as a :class:`~flyopt.errors.SceneError` naming the field.

See README.md for the format with an example, and problems/ for scenes.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.angle_tables import ANGLE_TOLERANCE
from flyopt.io.design_section import read_design
from flyopt.io.engine_section import read_engine
from flyopt.io.fields import MAX_LINE_LENGTH, Table, check_delta, check_line, cycle_of, mean_speed
from flyopt.io.input_files import recording_inputs
from flyopt.io.material_section import MAX_MATERIALS, read_material, read_materials
from flyopt.io.member_section import read_mechanism, read_members, with_engine
from flyopt.io.shaft_section import (
    MAX_SHAFTS,
    check_designed_seats,
    check_shaft_materials,
    read_efficiency,
    read_shaft,
    read_shafts,
    reference_efficiency,
)
from flyopt.io.toml_file import read_toml
from flyopt.io.torque_section import NetAreas, read_torques
from flyopt.machine.transmission import PowerBranch, Shaft, inertia_at_reference
from flyopt.names import CALCULATIONS
from flyopt.units import inertia_from_gd2

if TYPE_CHECKING:
    from flyopt.cycle.torque import MotorTorque, TorqueCurve
    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec
    from flyopt.io.drive import DriveSpec
    from flyopt.machine.crank_forces import CrankPosition
    from flyopt.machine.electric_drive import ElectricDrive
    from flyopt.machine.engine import Engine
    from flyopt.machine.equivalents import MechanismPosition
    from flyopt.machine.flywheel import ExistingFlywheel
    from flyopt.machine.kinematics import GearTrain, SliderCrank
    from flyopt.machine.linkages import Linkage
    from flyopt.machine.mechanism import Member
    from flyopt.sizing.operation import Operation


MAX_TITLE_LENGTH = MAX_LINE_LENGTH
"""Longest scene title [characters]: it heads every report, plot and table."""


@dataclass(frozen=True)
class Scene:
    """A machine to regulate, in SI units.

    Attributes
    ----------
    title : str
    omega_mean : float
        Mean speed ω_m of the reference shaft [rad/s]; NaN only in a
        calculation that needs no speed (machine.speed left out).
    delta : float
        Allowed coefficient of speed fluctuation δ [-].
    j_constant : float
        Constant part J_c of the equivalent inertia at the reference shaft
        [kg*m^2]: machine.inertia (or gd2) plus the inertia on every
        [[shaft]] by the ratio-squared transfer (:func:`constant_inertia`).
    cycle_angle : float
        Angle Φ of one cycle of the reference shaft [rad].
    efficiency : float
        Efficiency from the motor to the reference shaft [-].
    driving, resisting : torque curve or None
        Equivalent torques at the reference shaft (None when ``net`` is
        given; ``Constant(0.0)`` for a curve left out when [[member]] loads
        are given).
    net : NetAreas or None
    shafts : tuple of Shaft
    design : DesignSpec
        Geometry, H/B range, envelope and objective of the flywheel design.
    design_materials, design_shafts : tuple of str or None
        Materials and shafts the design may choose from (None: all).
    materials : tuple of Material
        The scene's own materials.
    members : tuple of flyopt.machine.mechanism.Member
        Members whose kinetic energy and loads are reduced to the reference
        shaft (J_e(φ) = J_c + Σ ..., their forces join the resisting torque).
    mechanism : SliderCrank, GearTrain, Linkage (guide-bar, four-bar, cam) or None
    engine : flyopt.machine.engine.Engine or None
        The [engine]: its pistons and rods are the first of ``members``.
    flywheel : flyopt.machine.flywheel.ExistingFlywheel or None
        The [flywheel] that exists: analysed, not designed. ``delta`` may then
        be None (the δ it reaches is found instead; :attr:`allowed_delta`).
    operation : flyopt.sizing.operation.Operation or None
        The [operation]: one load that comes once, acting on the [flywheel];
        the scene then has no torques (``driving``, ``resisting``, ``net`` None).
    position : flyopt.machine.crank_forces.CrankPosition, flyopt.machine.equivalents.MechanismPosition or None
        The [position]: a slider-crank engine at one crank angle, for its forces there; or, beside
        [[member]]s, a mechanism at one position, for its equivalents there; no torques either.
    electric_drive : flyopt.machine.electric_drive.ElectricDrive or None
        The [electric_drive]: a motor, its reduction stages and its load, reduced to the
        motor shaft (machine.speed is the motor's); no torques either.
    power_chain : flyopt.machine.transmission.PowerBranch or None
        The [power_chain]: a motor driving machines through stages in series and
        branches in parallel (the trunk); no speed needed, no torques either.
    source : str or None
        File the scene came from.
    shown_as : str or None
        The file's name in outputs (a report's provenance, a table's metadata, a drawing's title block) where
        it is not ``source``: the app's scenes are files in its server's private folder. None: ``source``.
    inputs : tuple of (str, str)
        The data files the scene read (a ``points_file``, a member's ``force_file``, ...), each as (the field
        that names it, its absolute path, made so when read): no output may replace one (:func:`flyopt.outputs.files.check_not_scene`).
    """

    title: str
    omega_mean: float
    delta: float | None  # None only with a [flywheel] that exists: the δ it reaches is the answer
    j_constant: float = 0.0
    cycle_angle: float = 2 * math.pi
    efficiency: float = 1.0
    driving: TorqueCurve | MotorTorque | None = None
    resisting: TorqueCurve | MotorTorque | None = None
    net: NetAreas | None = None
    shafts: tuple[Shaft, ...] = (Shaft("reference", 1.0),)
    design: DesignSpec | None = None  # the loader always gives one (the defaults when the scene has no [design])
    design_materials: tuple[str, ...] | None = None  # names the design may use; None: every known material
    design_shafts: tuple[str, ...] | None = None  # names of [[shaft]] the design may use; None: all
    materials: tuple[Material, ...] = ()  # user materials ([[material]]), extending the built-in ones
    members: tuple[Member, ...] = ()  # the [[member]]: J_e(φ) and member loads
    mechanism: SliderCrank | GearTrain | Linkage | None = None  # [mechanism]
    drive: DriveSpec | None = None  # [drive]: the motor and ratio designed with the wheel
    engine: Engine | None = None  # [engine]; its members lead ``members``
    flywheel: ExistingFlywheel | None = None  # [flywheel]: a wheel that exists, analysed instead of designed
    operation: Operation | None = None  # [operation]: one load, not a cycle (with a [flywheel]; no torques)
    position: CrankPosition | MechanismPosition | None = (
        None  # [position]: a crank's forces or a mechanism's equivalents
    )
    electric_drive: ElectricDrive | None = None  # [electric_drive]: a drive reduced to its motor shaft (no torques)
    power_chain: PowerBranch | None = None  # [power_chain]: the trunk of a motor's stages and branches (no torques)
    source: str | None = field(default=None, compare=False)
    shown_as: str | None = field(default=None, compare=False)
    inputs: tuple[tuple[str, str], ...] = field(default=(), compare=False)

    @property
    def calculation(self) -> str | None:
        """The section that makes this scene one calculation rather than a cycle (:data:`flyopt.names.CALCULATIONS`:
        "operation", "position", "electric_drive" or "power_chain"), or None for a cycle."""
        return next((name for name in CALCULATIONS if getattr(self, name) is not None), None)

    def require_cycle(self) -> None:
        """Refuse, in words naming its section, a scene that is one calculation where a cycle is needed."""
        if self.calculation is not None:
            raise SceneError(
                self.calculation,
                "is one calculation, not a cycle: flyopt solve, check and report answer it, nothing else",
            ).with_source(self.source)

    @property
    def allowed_delta(self) -> float:
        """machine.delta, where a computation needs it (a scene with a [flywheel] may leave it out)."""
        self.require_cycle()
        if self.delta is None:
            raise SceneError(
                "machine.delta", "is needed here (only the analysis of a [flywheel] that exists can do without it)"
            ).with_source(self.source)
        return self.delta

    def material_library(self) -> dict[str, Material]:
        """Built-in materials extended or overridden by the scene's own."""
        from flyopt.design.materials import material_library

        return material_library(self.materials)

    def replace(self, **changes: Any) -> Scene:
        """A copy with some fields changed (for studies and tests)."""
        return replace(self, **changes)


def load(path: str | os.PathLike[str], data: Mapping[str, Any] | None = None) -> Scene:
    """Read and check a scene file.

    Parameters
    ----------
    path : str or Path
        A TOML scene file.
    data : dict, optional
        The file's contents as :func:`read_toml` gave them (read once by a
        caller that also needs them); default: read the file.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        The file cannot be read, is not valid TOML, or a field is wrong; the
        message names the file and the field.
    """
    path = Path(path)
    if data is None:
        data = read_toml(path)
    try:
        return from_dict(data, source=str(path))
    except SceneError as err:
        raise err.with_source(str(path)) from None


def from_dict(data: Mapping[str, Any], source: str | None = None) -> Scene:
    """Build a scene from a dictionary shaped like a scene file.

    Parameters
    ----------
    data : dict
        As ``tomllib`` (or :func:`read_toml`) reads a scene file.
    source : str, optional
        The file the scene came from: a ``points_file`` (or a member's
        ``force_file``, ...) is relative to its folder; without one, to the
        working directory.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        A field is missing, unknown or wrong.
    """
    with recording_inputs() as read:
        scene = _from_dict(data, source)
    return replace(scene, inputs=tuple(read)) if read else scene


def _from_dict(data: Mapping[str, Any], source: str | None) -> Scene:
    files = Path(source).parent if source else Path()  # a points_file is relative to the scene file
    if isinstance(data, dict) and ("energy" in data or "strokes" in data):  # the courses' energy terms
        from flyopt.io.energy_form import scene_data as energy_scene_data

        data = energy_scene_data(data)
    if (
        isinstance(data, dict) and "press" in data
    ):  # a press from its process data (docs/flywheel-design.md, section 11)
        from flyopt.io.press import scene_data

        data = scene_data(data)
    top = Table(
        data,
        "",
        {
            "title",
            "description",
            "machine",
            "torque",
            "shaft",
            "design",
            "material",
            "mechanism",
            "member",
            "sweep",
            "drive",
            "motor_option",
            "engine",
            "flywheel",
            "operation",
            "position",
            "electric_drive",
            "power_chain",
        },
    )  # [sweep] is read by flyopt.studies.sweep.load_sweep
    once = any(top.has(k) for k in CALCULATIONS)  # one calculation, not a cycle: no δ to hold
    existing = top.has("flywheel")
    machine, omega, delta, j_c, cycle = _machine(top, once, existing)
    engine = read_engine(top.get("engine"), files) if top.has("engine") else None
    if engine is not None:
        if machine.has("cycle") and abs(cycle - engine.cycle_angle) > ANGLE_TOLERANCE * engine.cycle_angle:
            raise SceneError(
                "machine.cycle",
                f"is {math.degrees(cycle):.6g} deg, but the cycle of a {engine.cycle} "
                f"engine is {math.degrees(engine.cycle_angle):.6g} deg (leave machine.cycle out: "
                "[engine] cycle sets it)",
            )
        cycle = engine.cycle_angle

    raw_shafts, drive_shaft = _drive_flywheel_shaft(top)
    shafts = read_shafts(raw_shafts)
    others = [s for s in shafts if s.name != drive_shaft]  # the drive's flywheel shaft: no inertia, no efficiency
    j_c = constant_inertia(j_c, others)
    efficiency = (
        read_efficiency(machine.get("efficiency"), "machine.efficiency")
        if machine.has("efficiency")
        else reference_efficiency(others)
    )

    mechanism = read_mechanism(top.get("mechanism"))
    members = read_members(top.get("member"), mechanism, cycle, files)
    if engine is not None:
        members = with_engine(engine, mechanism, members)
    member_loads = any(m.force is not None or m.torque is not None for m in members)
    for needs_speed in ("operation", "electric_drive"):  # a [position] needs it only for a crank's forces
        if top.has(needs_speed) and math.isnan(omega):
            raise SceneError("machine.speed", f"is missing (the [{needs_speed}] calculation needs it)")
    operation = _operation(top) if top.has("operation") else None
    position = _position(top, omega, cycle, mechanism, members) if top.has("position") else None
    electric = _electric_drive(top, omega) if top.has("electric_drive") else None
    chain = _power_chain(top) if top.has("power_chain") else None
    if once:  # one calculation: no torques
        driving = resisting = net = None
    else:
        driving, resisting, net = read_torques(
            top.get("torque", {}) if member_loads else _table(top, "torque"),
            cycle,
            shafts,
            efficiency,
            member_loads,
            files,
        )
    if engine is not None and net is not None:
        raise SceneError(
            "torque.net",
            "an [engine] needs torque curves, not net areas: its gas torque is a curve "
            'over the crank angle (give [torque.resisting], e.g. constant = "unknown")',
        )
    if members and net is not None:
        raise SceneError(
            "member",
            "members need the torque curves ([torque.driving] and [torque.resisting]), "
            "not net areas: their inertia varies with the angle",
        )
    materials = read_materials(top.get("material"))
    if any(s.layout is not None for s in shafts):
        from flyopt.design.materials import material_library

        check_shaft_materials(shafts, material_library(materials))
    design, design_materials, design_shafts = read_design(top.get("design", {}), shafts, materials)
    check_designed_seats(shafts, design.bore)
    drive = None
    if top.has("drive") or top.has("motor_option"):
        from flyopt.design.materials import design_material_names, material_library
        from flyopt.io.drive import drive_spec

        library = material_library(materials)
        from flyopt.design.inputs import single_design_only

        single_design_only(design, "the drive's co-design ([drive])")
        drive = drive_spec(
            top.get("drive"),
            top.get("motor_option"),
            shafts,
            materials={n: library[n] for n in design_material_names(library, design_materials)},
        )
        # a described shaft other than the drive's flywheel shaft would carry no wheel (_drive_flywheel_shaft
        # has read that one, at the ratio the drive designs)
        described = next((k for k, s in enumerate(shafts) if s.layout is not None and s.name != drive_shaft), None)
        if described is not None:
            from flyopt.drive.codesign import FLYWHEEL_SHAFT

            raise SceneError(
                f"shaft[{described}]",
                f"is described as a part (segments, bearings, wheel_at), but [drive] puts the flywheel on its own "
                f"flywheel shaft at the ratio it designs: describe that shaft as [[shaft]] name = "
                f'"{FLYWHEEL_SHAFT}" (no speed_ratio), or give this shaft\'s speed_ratio, diameter and inertia only',
            )
    flywheel = None
    if existing:
        from flyopt.io.flywheel_section import read_flywheel

        for other in ("drive", "motor_option", "design"):
            if top.has(other):
                raise SceneError(
                    "flywheel",
                    f"gives the flywheel, and [{other}] asks to design one: give one of them "
                    "(a [flywheel] that exists is analysed, not designed)",
                )
        flywheel = read_flywheel(top.get("flywheel"), shafts)
        if flywheel.angles and net is not None:
            raise SceneError(
                "flywheel.angles",
                "asks the acceleration at angles, and net areas give no torque over the angle: give the torque curves",
            )
        for k, angle in enumerate(flywheel.angles):
            if not 0.0 <= angle <= cycle * (1.0 + ANGLE_TOLERANCE):
                raise SceneError(
                    f"flywheel.angles[{k}]",
                    f"{math.degrees(angle):.6g} deg is outside the cycle, 0 to {math.degrees(cycle):.6g} deg",
                )
    title = _title(top)
    return Scene(
        title=title or (Path(source).stem if source else "scene"),
        omega_mean=omega,
        delta=delta,
        j_constant=j_c,
        cycle_angle=cycle,
        efficiency=efficiency,
        driving=driving,
        resisting=resisting,
        net=net,
        shafts=shafts,
        design=design,
        design_materials=design_materials,
        design_shafts=design_shafts,
        materials=materials,
        members=members,
        mechanism=mechanism,
        drive=drive,
        engine=engine,
        flywheel=flywheel,
        operation=operation,
        position=position,
        electric_drive=electric,
        power_chain=chain,
        source=source,
    )


def _machine(top: Table, once: bool, existing: bool) -> tuple[Table, float, float | None, float, float]:
    """The [machine] table and its scalars: (the table, ω_m [rad/s], δ or None, J_c [kg*m^2], the cycle [rad]).
    ``once``: the scene is one calculation (no machine needed); ``existing``: it gives a [flywheel] (no δ).
    Each scalar is read by a function of its own, which ``flyopt check`` calls alone (:func:`section_errors`)."""
    machine = _machine_table(top, once)
    omega = _mean_speed(machine, required=not once)
    delta = _delta(machine, required=not (existing or once))
    return machine, omega, delta, _constant_inertia(machine), cycle_of(machine)


def _machine_table(top: Table, once: bool) -> Table:
    """[machine], with none but its own keys (one calculation may leave it out)."""
    return Table(
        top.get("machine", {}) if once else _table(top, "machine"),
        "machine",
        {"speed", "delta", "inertia", "gd2", "cycle", "efficiency", "description"},
    )


#: What a scene that leaves out [machine], [torque] or the machine's speed or δ is told: what to write there.
MISSING = {
    "machine": (
        'is missing: give [machine] with the mean speed and the allowed δ (speed = "1500 rpm", delta = 0.05), or a '
        "[press] from its process data (flyopt new KIND writes a template)"
    ),
    "torque": (
        "is missing: give [torque.driving] and [torque.resisting], or [torque.net] with the net areas, or the cycle "
        "by an [engine], a [press] or [[member]] loads"
    ),
    "machine.speed": 'is missing: the reference shaft\'s mean speed, e.g. speed = "1500 rpm"',
    "machine.delta": 'is missing: the allowed coefficient of fluctuation of speed δ, e.g. delta = 0.05 or "5 %"',
}


def _table(top: Table, key: str) -> Any:
    """The scene's table ``key``, which it must give (:data:`MISSING` says what to write)."""
    _required(top, key)
    return top.get(key)


def _required(table: Table, key: str) -> None:
    """Refuse a scene without ``key`` of ``table``, saying what to write (:data:`MISSING`)."""
    if not table.has(key):
        where = f"{table.where}.{key}" if table.where else key
        raise SceneError(where, MISSING[where])


def _delta(machine: Table, required: bool) -> float | None:
    """machine.delta, the allowed coefficient of fluctuation (None where the scene needs none and gives none)."""
    if required:
        _required(machine, "delta")
    delta = machine.quantity("delta", "dimensionless", required=required, own_range=True)
    if delta is not None:
        _check_delta(delta, machine)
    return delta


def _constant_inertia(machine: Table) -> float:
    """J_c [kg*m^2]: machine.inertia, or machine.gd2 as an inertia, not both; 0 where neither is given."""
    if machine.has("inertia") and machine.has("gd2"):
        raise SceneError("machine.gd2", "give either machine.inertia or machine.gd2, not both")
    j_c = machine.quantity("inertia", "inertia", default=0.0)
    if machine.has("gd2"):
        j_c = inertia_from_gd2(machine.quantity("gd2", "flywheel_moment", required=True))
    if j_c < 0:
        raise SceneError("machine.inertia" if machine.has("inertia") else "machine.gd2", "must not be negative")
    return j_c


def section_errors(data: Mapping[str, Any]) -> list[SceneError]:
    """The value errors of a scene's parts that are read on their own, each part read alone: each of [machine]'s
    scalars (speed, delta, the constant inertia, the cycle, the efficiency), each [[material]] table, each
    [[shaft]] table (their trains once every shaft reads), the title, and [design] where the shafts and
    materials it names read without error. At most one error a part (its first, as the loader meets it); what
    depends on another section (the torques on the cycle and the shafts, a mechanism's members, a drive) is left
    to the loader, which stops at the first error of the whole scene (:func:`from_dict`). ``flyopt check`` lists
    these beside that one, so that independent errors are said at once; none is a consequence of another.

    A scene in the courses' energy terms or a press's process data (rewritten into a scene by the loader) is not
    probed: its sections are not the file's."""
    if not isinstance(data, Mapping) or any(k in data for k in ("energy", "strokes", "press")):
        return []
    errors: list[SceneError] = []

    def attempt(read: Any, *args: Any) -> Any:
        try:
            return read(*args)
        except SceneError as err:
            errors.append(err)
            return None

    def each(raw: Any, read_one: Any, read_all: Any, limit: int) -> Any:
        """A list of tables read table by table, then (none wrong) as the loader reads it: its tuple, or None.
        A list of more than ``limit`` tables is the loader's one error (its count), not one per table."""
        if isinstance(raw, list) and len(raw) <= limit:
            seen: set[str] = set()
            failed = len(errors)
            for k, item in enumerate(raw):
                attempt(read_one, item, k, seen)
            if len(errors) > failed:
                return None
        return attempt(read_all, raw)

    try:
        top = Table(data, "", set(data))
    except SceneError:
        return []
    once, existing = any(top.has(k) for k in CALCULATIONS), top.has("flywheel")
    machine = attempt(_machine_table, top, once)
    if machine is not None:
        attempt(_mean_speed, machine, not once)
        attempt(_delta, machine, not (existing or once))
        attempt(_constant_inertia, machine)
        attempt(cycle_of, machine)
        if machine.has("efficiency"):
            attempt(read_efficiency, machine.get("efficiency"), "machine.efficiency")
    materials = each(top.get("material"), read_material, read_materials, MAX_MATERIALS)
    shafts = None
    if not (isinstance(data.get("drive"), Mapping) or "motor_option" in data):  # a drive reads its own shaft
        shafts = each(data.get("shaft"), read_shaft, read_shafts, MAX_SHAFTS)
    attempt(_title, top)
    # one calculation, and a [flywheel] that exists, refuse a [design] before reading it: its values are no
    # error of such a scene
    if (
        shafts is not None
        and materials is not None
        and not (once or existing)
        and isinstance(data.get("design", {}), Mapping)
    ):
        attempt(read_design, top.get("design", {}), shafts, materials)
    return errors


def _title(top: Table) -> str:
    """The scene's title ("" where it gives none): a string of at most :data:`MAX_TITLE_LENGTH` characters."""
    title = top.get("title", "")
    if not isinstance(title, str):
        raise SceneError("title", f"must be a string, got {shorten(title)}")
    check_line(title, "title", "a longer text belongs in description")
    return title


def _mean_speed(machine: Table, required: bool) -> float:
    """machine.speed [rad/s] (:func:`flyopt.io.fields.mean_speed`), saying what to write where it is needed and
    missing (:data:`MISSING`).

    Only a calculation that needs no speed (``required`` False) may leave it
    out; its scene's ``omega_mean`` is then NaN, which no calculation reads
    and every cycle computation refuses first (:attr:`Scene.calculation`).
    """
    if required:
        _required(machine, "speed")
    return mean_speed(machine, required)


def _electric_drive(top: Table, omega: float) -> ElectricDrive:
    """[electric_drive], the motor at machine.speed, with none of the sections that describe something else."""
    from flyopt.io.electric_drive_section import read_electric_drive

    _alone(top, "electric_drive", "an electric drive reduced to its motor shaft")
    return read_electric_drive(top.get("electric_drive"), omega)


def _power_chain(top: Table) -> PowerBranch:
    """[power_chain], with none of the sections that describe something else (it needs no machine.speed)."""
    from flyopt.io.power_chain_section import read_power_chain

    _alone(top, "power_chain", "a power chain from one motor")
    return read_power_chain(top.get("power_chain"))


#: The sections that describe a cycle, a design or a wheel, which a calculation's scene does not have.
_CYCLE_SECTIONS = ("torque", "press", "engine", "member", "mechanism", "design", "drive", "motor_option", "sweep")


def _alone(top: Table, key: str, what: str, allowed: tuple[str, ...] = ()) -> None:
    """Refuse a calculation's section beside a cycle's, a design's or another calculation's."""
    for other in (*_CYCLE_SECTIONS, "flywheel", *CALCULATIONS):
        if other != key and other not in allowed and top.has(other):
            raise SceneError(key, f"is {what}, and [{other}] describes something else: give one of them")


def _position(
    top: Table,
    omega: float,
    cycle: float,
    mechanism: SliderCrank | GearTrain | Linkage | None,
    members: tuple[Member, ...],
) -> CrankPosition | MechanismPosition:
    """[position]: beside [[member]]s (and their [mechanism]) the equivalents of a mechanism at one position;
    alone, a slider-crank engine's forces at one crank angle (which need machine.speed). Neither has the
    sections that describe a cycle, a design or a flywheel."""
    from flyopt.io.position_section import read_mechanism_position, read_position

    if top.has("member") or top.has("mechanism"):
        _alone(top, "position", "one position of a mechanism", allowed=("member", "mechanism"))
        if not members:
            raise SceneError(
                "position", "reduces the [[member]]s of a mechanism: give them (a [mechanism] alone has none)"
            )
        return read_mechanism_position(top.get("position"), cycle, mechanism, members)
    _alone(top, "position", "one crank position of a slider-crank engine")
    if math.isnan(omega):
        raise SceneError("machine.speed", "is missing (the [position] calculation needs it)")
    return read_position(top.get("position"))


def _operation(top: Table) -> Operation:
    """[operation], with the flywheel it acts on and none of the sections that describe a cycle."""
    from flyopt.io.operation_section import read_operation

    _alone(top, "operation", "one operation, not a cycle", allowed=("flywheel",))
    if not top.has("flywheel"):
        raise SceneError(
            "operation", "acts on a flywheel that exists: give [flywheel] (inertia, or mass with radius_of_gyration)"
        )
    return read_operation(top.get("operation"))


def _check_delta(delta: float, machine: Table) -> None:
    """Refuse a machine.delta outside :data:`~flyopt.io.fields.DELTA_RANGE`."""
    check_delta(
        delta, "machine.delta", machine.raw("delta"), "typical values are 1/5 (crushers) to 1/300 (AC generators)"
    )


#: Keys the drive's flywheel shaft may not give: the drive designs its ratio, and an inertia or an
#: efficiency on it would take that ratio (its inertia at the crank J r², the efficiency at ratio 1).
DRIVE_SHAFT_REFUSED = ("speed_ratio", "inertia", "gd2", "efficiency", "train")


def _drive_flywheel_shaft(top: Table) -> tuple[object, str | None]:
    """(the [[shaft]] tables to read, the name of the drive's flywheel shaft when the scene describes it).

    With a [drive], a [[shaft]] named ``"flywheel"`` (:data:`flyopt.drive.codesign.FLYWHEEL_SHAFT`, the
    name the drive gives the shaft it puts its wheel on, as ``press.flywheel_speed`` does) is that shaft,
    and it must give ``segments``, which describe it as a part (docs/flywheel-design.md, sections 14 and 26). Its speed
    ratio is the drive's to design, so it gives none (nor the keys :data:`DRIVE_SHAFT_REFUSED` names); it
    is read at ratio 1, a stand-in the drive replaces by each ratio it designs (and which neither the
    machine's inertia nor its efficiency reads).
    """
    raw = top.get("shaft")
    if not top.has("drive") or not isinstance(raw, list):
        return raw, None
    from flyopt.drive.codesign import FLYWHEEL_SHAFT
    from flyopt.io.shaft_section import DESIGNED

    for k, item in enumerate(raw):
        if not (isinstance(item, dict) and item.get("name") == FLYWHEEL_SHAFT):
            continue
        for key in DRIVE_SHAFT_REFUSED:
            if key in item:
                raise SceneError(
                    f"shaft[{k}].{key}",
                    f"is given on the drive's flywheel shaft ({FLYWHEEL_SHAFT!r}), whose speed ratio [drive] "
                    "designs: leave it out (its inertia, efficiency and train would change with the ratio)",
                )
        if "segments" not in item:
            raise SceneError(
                f"shaft[{k}].segments",
                f"is missing: beside a [drive], a [[shaft]] named {FLYWHEEL_SHAFT!r} is the drive's flywheel shaft, "
                "described as a part by its segments (or give this shaft another name)",
            )
        segments = item["segments"]
        if isinstance(segments, list) and any(isinstance(g, dict) and g.get("diameter") == DESIGNED for g in segments):
            raise SceneError(
                f"shaft[{k}].segments",
                f'a "design" diameter on the drive\'s flywheel shaft ({FLYWHEEL_SHAFT!r}) is not supported: '
                "[drive] designs the wheel on the seat the segments give; give the seat's diameter",
            )
        stand_in = {**item, "speed_ratio": 1.0}
        return [stand_in if j == k else other for j, other in enumerate(raw)], FLYWHEEL_SHAFT
    return raw, None


def constant_inertia(j_machine: float, shafts: Iterable[Shaft]) -> float:
    """J_c at the reference shaft: the machine's own plus the inertia on each shaft [kg*m^2].

    J_c = J_machine + Σ_k J_k i_k², i_k = ω_k/ω the shaft's speed ratio: the
    same kinetic energy at every speed (docs/flywheel-design.md, sections 3
    and 8; the reduction of GD² to one shaft of the electric-drive texts, in
    flyopt's speed-ratio convention), no efficiency applied.

    Parameters
    ----------
    j_machine : float
        machine.inertia (or gd2) [kg*m^2], already at the reference shaft.
    shafts : iterable of Shaft

    Returns
    -------
    float
    """
    return j_machine + math.fsum(inertia_at_reference(s.inertia, s.speed_ratio) for s in shafts)
