"""The units of every number flyopt writes.

:data:`QUANTITIES` gives the dimension of every number flyopt writes,
:data:`INPUTS` that of a sweep's inputs (the fields of
:data:`flyopt.io.sweep_spec.FIELDS`); :func:`unit_of` turns a name into
its SI unit through :data:`flyopt.units.DIMENSIONS`. This is the one
table behind the ``units`` map of ``flyopt solve --json``, the units of
the columns of sweep, Pareto and trade-off files, and the unit labels of
the printed tables. A name means one quantity wherever it appears
(``mass`` is kg in ``design``, in ``parts[]`` and in a sweep's column;
docs/nomenclature.md lists the names with their meaning).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from flyopt.units import DIMENSIONS

__all__ = [
    "COUNTS",
    "INPUTS",
    "MATERIAL_INPUTS",
    "MISSING",
    "OUTPUT_DIMENSIONS",
    "QUANTITIES",
    "SHAFT_INPUTS",
    "UNIT_SET_BY",
    "dimension_of",
    "document_units",
    "has_unit",
    "table_units",
    "unit_of",
]


#: Dimensions of outputs that no input has, with their SI unit (the others are
#: :data:`flyopt.units.DIMENSIONS`'). Money is a plain number: a material's cost is read
#: per kilogram (``"2.1 1/kg"``, dimension ``cost_per_mass``), so a wheel's cost is
#: ``dimensionless``, in the currency the scene's prices are given in.
OUTPUT_DIMENSIONS = {
    "time": "s",
    "unbalance": "kg*m",
    "angular_acceleration": "rad/s**2",
    "frequency": "1/s",
    "acceleration": "m/s**2",
    "per_mass": "1/kg",
}

#: The columns of a sweep's inputs: the fields of :data:`flyopt.io.sweep_spec.FIELDS` (which
#: reads their values in these dimensions) and their dimension, None for a name. sweep_spec
#: imports flyopt.outputs.results (for its output_format), which imports this module, so the table cannot be read from there;
#: tests/outputs/test_results.py checks that the two agree, field by field.
INPUTS = {
    "delta": "dimensionless",
    "speed": "angular_speed",
    "inertia": "inertia",
    "torque.scale": "dimensionless",
    "design.max_outer_diameter": "length",
    "design.max_width": "length",
    "design.d_mean": "length",
    "design.hb_ratio": "dimensionless",
    "design.hb_min": "dimensionless",
    "design.hb_max": "dimensionless",
    "design.geometry": None,
    "design.objective": None,
    "material": None,
    "shaft": None,
}
#: Columns ``material.NAME.FIELD`` and ``shaft.NAME.FIELD`` of a sweep: FIELD and its dimension.
MATERIAL_INPUTS = {"density": "density", "max_rim_speed": "speed", "cost": "cost_per_mass"}
SHAFT_INPUTS = {"speed_ratio": "dimensionless"}

#: The dimension of every other number flyopt writes: the JSON of ``flyopt solve`` and the
#: columns of sweep, Pareto and trade-off tables (a name of :data:`INPUTS` that the JSON also
#: holds, ``delta`` or a part's ``inertia``, has that entry's dimension). Sections of
#: docs/flywheel-design.md.
QUANTITIES = {
    # the cycle, sections 2-5: energy indicator diagram, A_max, J_F
    "a_max": "energy",
    "delta_e": "energy",
    "work_per_cycle": "energy",
    "angle": "angle",
    "cycle_angle": "angle",
    "angle_omega_max": "angle",
    "angle_omega_min": "angle",
    "angle_delta_e_max": "angle",
    "angle_delta_e_min": "angle",
    "driving_torque": "torque",
    "resisting_torque": "torque",
    "omega": "angular_speed",
    "omega_mean": "angular_speed",
    "omega_max": "angular_speed",
    "omega_min": "angular_speed",
    "omega_target": "angular_speed",
    "j_constant": "inertia",
    "j_margin": "inertia",
    "j_required": "inertia",
    "gd2_required": "flywheel_moment",
    "achieved_delta": "dimensionless",
    # a flywheel that exists ([flywheel]): what it leaves of the speed, and what it is
    "energy_swing": "energy",
    "acceleration_max": "angular_acceleration",
    "angular_acceleration": "angular_acceleration",  # a [flywheel]'s dω/dt at one of its angles
    "angles": "angle",
    "acceleration_min": "angular_acceleration",
    "angle_acceleration_max": "angle",
    "angle_acceleration_min": "angle",
    "j_machine": "inertia",
    "margin": "dimensionless",
    "radius_of_gyration": "length",
    # one operation ([operation])
    "omega_before": "angular_speed",
    "omega_after": "angular_speed",
    "energy_from_motor": "energy",
    "energy_from_flywheel": "energy",
    "speed_drop": "dimensionless",
    "recovery_time": "time",
    "shortest_interval": "time",
    "operation_rate": "frequency",
    "energy": "energy",
    "duration": "time",
    # one crank position ([position])
    "crank": "length",
    "rod": "length",
    "pressure": "stress",
    "reciprocating_mass": "mass",
    "obliquity": "angle",
    "displacement": "length",
    "velocity": "speed",
    "acceleration": "acceleration",
    "gas_force": "force",
    "inertia_force": "force",
    "weight": "force",
    "piston_effort": "force",
    "rod_force": "force",
    "thrust": "force",
    "tangential_force": "force",
    "radial_force": "force",
    "turning_moment": "torque",
    # a mechanism's equivalents at one position ([position] beside [[member]]s): ratios in m/rad (rad is 1)
    "input_angle": "angle",
    "velocity_ratio": "length",
    "angular_ratio": "dimensionless",
    "inertia_share": "inertia",
    "torque_share": "torque",
    "equivalent_inertia": "inertia",
    "equivalent_moment": "torque",
    "equivalent_force": "force",
    "equivalent_mass": "mass",
    # an electric drive reduced to its motor shaft ([electric_drive]): the texts' GD² in N·m²
    "shaft_speeds": "angular_speed",
    "load_speed": "angular_speed",
    "motor_speed": "angular_speed",
    "total_ratio": "dimensionless",
    "ratio": "dimensionless",
    "load_power": "power",
    "load_torque": "torque",
    "load_torque_at_motor": "torque",
    "gd2": "flywheel_moment",
    "motor_gd2": "flywheel_moment",
    "gd2_total": "flywheel_moment",
    "gd2_with_losses": "flywheel_moment",
    "inertia_total": "inertia",
    "inertia_with_losses": "inertia",
    "accelerating_torque": "torque",
    "motor_torque": "torque",
    "motor_acceleration": "angular_acceleration",
    # a power chain ([power_chain]): what each branch loses, and its stages' product from the motor
    "losses": "power",
    "path_efficiency": "dimensionless",
    "delta_allowed": "dimensionless",
    "j_error": "dimensionless",
    "tolerance": "dimensionless",
    # power and efficiency, section 11; transfer to a shaft, section 8; start-up, section 7
    "power": "power",
    "motor_power": "power",
    "efficiency": "dimensionless",
    "speed_ratio": "dimensionless",
    "best_speed_ratio": "dimensionless",
    "time": "time",
    "cycles": "dimensionless",
    "solve_time": "time",
    # the wheel, sections 9, 10 and 13
    "d_mean": "length",
    "d_outer": "length",
    "d_inner": "length",
    "h": "length",
    "b": "length",
    "outer_diameter": "length",
    "d_outer_limit": "length",
    "d_outer_needed": "length",
    "max_outer_diameter": "length",
    "max_width": "length",
    "bore": "length",
    "t_web": "length",
    "d_hub": "length",
    "l_hub": "length",
    "arm_major": "length",
    "arm_minor": "length",
    "r_inner": "length",
    "r_outer": "length",
    "thickness": "length",
    "casting_size": "length",  # castability: the outer diameter the process's minimum wall is read at
    "process_min_wall": "length",
    "min_wall": "length",
    "thinnest_wall": "length",
    "section_ratio": "dimensionless",
    "radius": "length",
    "wall": "length",
    "hb_ratio": "dimensionless",
    "mass": "mass",
    "dmass": "mass",  # a sensitivity's change of mass over its step
    "cost": "dimensionless",
    "density": "density",
    "j_flywheel": "inertia",
    "j_at_reference": "inertia",
    "j_max": "inertia",
    "j_required_on_shaft": "inertia",
    "rim_speed": "speed",
    "rim_speed_limit": "speed",
    "rim_share": "dimensionless",
    "hoop_stress": "stress",
    "allowable_stress": "stress",
    "allowable": "stress",
    "strength": "stress",
    "stress": "stress",
    "max_principal": "stress",
    "von_mises": "stress",
    "hoop_max": "stress",
    "radial_max": "stress",
    "mean_hoop": "stress",
    "safety_factor": "dimensionless",
    "strength_safety": "dimensionless",
    "burst_speed": "angular_speed",
    "speed_margin": "dimensionless",
    "unbalance_permissible": "unbalance",
    # the FE check of the best design (design.fem, flyopt.design.fem), section 13
    "peak": "stress",
    "model_peak": "stress",
    "model_stress": "stress",
    "fem_peak": "stress",
    "lame": "stress",
    "model_radius": "length",
    "fillet": "length",
    "von_mises_at": "length",
    "max_principal_at": "length",
    "fem_at": "length",
    "difference": "dimensionless",
    "utilisation": "dimensionless",
    "factor": "dimensionless",
    "size": "dimensionless",
    # the hub's key (DIN 6885-1), section 13
    "length": "length",
    "effective_length": "length",
    "t1": "length",
    "t2": "length",
    "torque": "torque",
    "bearing_pressure": "stress",
    "shear": "stress",
    "allowable_pressure": "stress",
    "allowable_shear": "stress",
    # the drive designed with the flywheel, sections 7, 8 and 14: the motor, its ratio, its heating
    "motor_ratio": "dimensionless",
    "flywheel_ratio": "dimensionless",
    "breakdown_ratio": "dimensionless",
    "rated_power": "power",
    "rated_speed": "angular_speed",
    "synchronous_speed": "angular_speed",
    "rotor_inertia": "inertia",
    "j_delta": "inertia",
    "rms_torque": "torque",
    "mean_torque": "torque",
    "rated_torque": "torque",
    "startup_time": "time",
    "motor_mass": "mass",
    "wheel_mass": "mass",
    "total_mass": "mass",
    "price": "dimensionless",
    # the mounting shaft checked with its wheel, section 26
    "seat_diameter": "length",  # a designed seat's diameter (step diameter = "design")
    "seat_diameter_continuous": "length",  # the NLP's continuous seat d* before rounding up to the series
    "seat_dmass_dfactor": "mass",  # d(wheel and designed steps' mass)/d(required factor of the NLP's binding row)
    "fatigue_factor": "dimensionless",
    "fatigue_factor_allowed": "dimensionless",
    "yield_factor": "dimensionless",
    "yield_factor_allowed": "dimensionless",
    "slope": "angle",
    "slope_allowed": "angle",
    "deflection": "length",
    "deflection_allowed": "length",
    "critical_speed": "angular_speed",
    "critical_speed_allowed": "angular_speed",
    "key_stress": "stress",  # the designed key's governing stress at the train's peak torque on the wheel
    "key_stress_allowed": "stress",
    "key_torque": "torque",  # that peak torque, J_wheel theta''_wheel
    "unbalance_force": "force",
    "torque_mean": "torque",
    "torque_alternating": "torque",
    "torque_alternating_rigid": "torque",
    "lateral_critical_speed": "angular_speed",
    "speed_range": "angular_speed",
    "torsional_modes": "angular_speed",
    "dutilisation_dmass": "per_mass",
    # the drive train's torsional model (drive_train), section 26
    "natural_frequency": "angular_speed",
    "mode_shape": "dimensionless",
    "damping_ratio": "dimensionless",
    "orders": "dimensionless",
    "order": "dimensionless",
    "largest_order": "dimensionless",
    "torsional_stiffness": "torsional_stiffness",
    "torque_largest_order": "torque",
}

#: Numbers whose unit is set by another field, so that a table or document has no single
#: unit for them where that field varies (their ``units`` entry is then null).
UNIT_SET_BY = {
    "objective": "the unit of the quantity the design's objective names "
    "(mass: kg, outer_diameter: m, cost: 1; a drive's mass is motor plus wheel)",
    "objective_bound": "the unit of the design's objective, as for objective",
    "epsilon": "the unit of the Pareto front's second objective",
    "dmass_dlimit": "kg per the unit given in the same entry's 'unit'",
    "step": "the unit given in the same entry's 'unit' (a sensitivity's step)",
    "dobjective_dlimit": "the drive objective's unit (kg for mass, 1 for cost) per the unit given in the same "
    "entry's 'unit'",
}

#: Whole numbers that count or index: no unit.
COUNTS = frozenset(
    {
        "index",
        "index_omega_max",
        "index_omega_min",
        "iterations",
        "n_arms",
        "point",
        "seed",
        "n_combinations",
        "n_feasible",
        "elements",
        "nodes",
        "rounds",
        "mode",
        "wheel_node",
        "load_node",
    }
)

#: The convention for values that do not exist, as each file states it.
MISSING = (
    "null where a value does not exist (nothing designed, no limit binding, no IPOPT "
    "iterations, no price); an empty cell in CSV, which pandas reads as NaN. A limit "
    "that is not set is +inf in tables (inf in CSV) and null in JSON"
)


def dimension_of(name: str) -> str | None:
    """The dimension of a numeric field, or None (text, counts, unknown names)."""
    if name in INPUTS:
        return INPUTS[name]
    parts = name.split(".")
    if len(parts) == 3 and parts[0] == "material":
        return MATERIAL_INPUTS.get(parts[2])
    if len(parts) == 3 and parts[0] == "shaft":
        return SHAFT_INPUTS.get(parts[2])
    return QUANTITIES.get(name)


def _si(dimension: str) -> str:
    if dimension in OUTPUT_DIMENSIONS:
        return OUTPUT_DIMENSIONS[dimension]
    return DIMENSIONS[dimension][1] or "1"


def has_unit(name: str) -> bool:
    """Whether ``name`` is a quantity: a unit of its own, or one set by another field."""
    return name in UNIT_SET_BY or dimension_of(name) is not None


def unit_of(name: str, objective: str | None = None, front: str | None = None) -> str | None:
    """The SI unit of a field, as pint writes it ("kg", "kg*m**2", "rad/s"; "1": dimensionless).

    Parameters
    ----------
    name : str
        A JSON field or a table column: ``mass``, ``shafts``' ``omega``,
        ``design.max_width``, ``material.cast_iron.density`` ...
    objective : str, optional
        The objective the ``objective`` values are of (``mass``,
        ``outer_diameter``, ``cost``).
    front : str, optional
        The second objective of a Pareto front, the unit of ``epsilon``.

    Returns
    -------
    str or None
        None for text, counts and names that are no quantity, and for a
        field of :data:`UNIT_SET_BY` whose unit is not fixed by the arguments.
    """
    if name in ("objective", "objective_bound"):
        return unit_of(objective) if objective else None
    if name == "epsilon":
        return unit_of(front) if front else None
    dimension = dimension_of(name)
    return None if dimension is None else _si(dimension)


def table_units(
    columns: Iterable[object], objective: str | None = None, front: str | None = None
) -> dict[str, str | None]:
    """The ``units`` map of a table: every quantity column and its unit (null: no single unit)."""
    return {str(c): unit_of(str(c), objective, front) for c in columns if has_unit(str(c))}


def document_units(document: Mapping[str, Any], objective: str | None = None) -> dict[str, str | None]:
    """The ``units`` map of a JSON document: every numeric field that occurs in it, and its unit.

    A field counts where it holds a number, a list of numbers or null (a
    value that may be a number elsewhere); text, booleans, counts and
    objects do not.

    Parameters
    ----------
    document : dict
        Plain JSON data.
    objective : str, optional
        The objective the document's ``objective`` values are of.

    Returns
    -------
    dict
        Field name to unit, sorted by name.
    """
    found: set[str | None] = set()

    def visit(key: str | None, value: object) -> None:
        if isinstance(value, dict):
            for k, v in value.items():
                visit(k, v)
        elif isinstance(value, list):
            if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
                found.add(key)
            for v in value:
                if isinstance(v, (dict, list)):
                    visit(key, v)
        elif value is None or (isinstance(value, (int, float)) and not isinstance(value, bool)):
            found.add(key)

    visit(None, document)
    return {name: unit_of(name, objective) for name in sorted(n for n in found if n and has_unit(n))}
