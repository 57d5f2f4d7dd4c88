"""flyopt.outputs.quantities: the ``units`` map of every document and table (issue 15, part 3).

It is checked against two independent sources: the dimensions that the engineering relations
of docs/flywheel-design.md give each quantity (pint's dimensional analysis of
J_F = A_max/(omega_m^2 delta), v = omega D/2, sigma = rho v^2 ...), and the unit column of
docs/nomenclature.md.
"""

import re

import pytest
from conftest import ROOT, unit_registry

from flyopt.outputs import quantities
from flyopt.outputs.quantities import COUNTS, QUANTITIES, UNIT_SET_BY, unit_of

# --------------------------------------------------------------------------
# Units
# --------------------------------------------------------------------------


def _q(unit):
    return unit_registry().Quantity(1.0, unit)


#: Relations of docs/flywheel-design.md between quantities: the unit of the name on the left
#: must have the dimension of the expression on the right, written with the units of other names
#: (pint's dimensional analysis; rad is a plain number, as in SI).
RELATIONS = {
    # section 5: J_F = A_max / (omega_m^2 delta); J_F is what j_margin clips and J_c adds to
    "j_required": "a_max / omega_mean**2 / delta",
    "j_margin": "j_required",
    "j_constant": "j_required",
    # section 4: the work of a torque over the cycle angle; the excess work delta E; an angle
    # is a work over a torque
    "angle": "a_max / driving_torque",
    "work_per_cycle": "driving_torque * cycle_angle",
    "delta_e": "a_max",
    "a_max": "driving_torque * angle",
    "resisting_torque": "driving_torque",
    # section 2: omega_m (1 +- delta/2); delta = (omega_max - omega_min)/omega_m
    "omega_max": "omega_mean * (1 + delta)",
    "omega_min": "omega_mean",
    "omega": "omega_mean",
    "omega_target": "omega_mean",
    "achieved_delta": "omega_max / omega_mean",
    "delta_allowed": "delta",
    "tolerance": "delta",
    "j_error": "j_required / j_required",
    # a flywheel that exists: J dω/dt = M_d - M_r, the energy swing ½ J (ω_max² - ω_min²), J = m k²
    "acceleration_max": "driving_torque / j_required",
    "acceleration_min": "acceleration_max",
    "angle_acceleration_max": "angle",
    "angle_acceleration_min": "angle",
    "energy_swing": "j_required * omega_max**2",
    "j_machine": "j_required",
    "radius_of_gyration": "(j_required / mass)**0.5",
    "margin": "j_required / j_required",
    # one operation: ω₂² = ω₁² − 2 ΔE / J, t_r = ΔE / P, the rate P / E
    "omega_before": "omega_mean",
    "omega_after": "omega_mean",
    "energy_from_motor": "a_max",
    "energy_from_flywheel": "j_required * omega_before**2",
    "energy": "a_max",
    "speed_drop": "omega_after / omega_before",
    "recovery_time": "energy_from_flywheel / power",
    "shortest_interval": "recovery_time",
    "duration": "recovery_time",
    "operation_rate": "power / energy",
    # one crank position: F_L = p π d²/4, F_I = m a, T = F_T r, v = ω r (...)
    "crank": "r_outer",
    "rod": "crank",
    "pressure": "stress",
    "reciprocating_mass": "mass",
    "obliquity": "angle",
    "displacement": "crank",
    "velocity": "omega * crank",
    "acceleration": "omega**2 * crank",
    "gas_force": "pressure * bore**2",
    "inertia_force": "reciprocating_mass * acceleration",
    "weight": "inertia_force",
    "piston_effort": "gas_force",
    "rod_force": "gas_force",
    "thrust": "gas_force",
    "tangential_force": "gas_force",
    "radial_force": "gas_force",
    "turning_moment": "tangential_force * crank",
    # a mechanism's equivalents at one position: J_e = Σ J (ω_k/ω)² + m (v_S/ω)², M_e = Σ F v/ω, P = M/r, m = J/r²
    "input_angle": "angle",
    "velocity_ratio": "crank / angle",
    "angular_ratio": "omega / omega_mean",
    "inertia_share": "mass * velocity_ratio**2",
    "torque_share": "gas_force * velocity_ratio",
    "equivalent_inertia": "inertia_share",
    "equivalent_moment": "torque_share",
    "equivalent_force": "equivalent_moment / crank",
    "equivalent_mass": "equivalent_inertia / crank**2",
    # an electric drive: T_L' = T_L/(j η), P = T ω, GD² = 4 g J, T_a = J dω/dt
    "shaft_speeds": "omega_mean",
    "load_speed": "omega_mean",
    "motor_speed": "omega_mean",
    "total_ratio": "speed_ratio",
    "ratio": "speed_ratio",
    "load_torque": "driving_torque",
    "load_torque_at_motor": "load_torque / total_ratio",
    "load_power": "load_torque * load_speed",
    "gd2": "gd2_required",
    "motor_gd2": "gd2",
    "gd2_total": "gd2",
    "gd2_with_losses": "gd2",
    "inertia_total": "gd2 / (meter / second**2)",
    "inertia_with_losses": "inertia_total",
    "motor_acceleration": "omega_mean / time",
    "angular_acceleration": "omega_mean / time",  # dω/dt of a [flywheel] at one of its angles
    "angles": "angle",
    "accelerating_torque": "inertia_total * motor_acceleration",
    "motor_torque": "accelerating_torque",
    # a power chain: P_in - P_out, and the stages' product from the motor
    "losses": "motor_power - load_power",
    "path_efficiency": "efficiency",
    "rim_share": "efficiency",  # a share of J_F, as an efficiency is one of power
    # angles of the cycle
    "cycle_angle": "angle",
    "angle_omega_max": "angle",
    "angle_omega_min": "angle",
    "angle_delta_e_max": "angle",
    "angle_delta_e_min": "angle",
    # section 3: GD^2 = 4 g J (g in m/s^2)
    "gd2_required": "j_required * meter / second**2",
    # section 11: P = M_d omega_m, P_motor = P / eta
    "power": "driving_torque * omega_mean",
    "motor_power": "power / efficiency",
    # section 8: J' = J_F / i^2, omega' = i omega
    "j_required_on_shaft": "j_required / speed_ratio**2",
    "j_at_reference": "j_flywheel * speed_ratio**2",
    "speed_ratio": "omega / omega_mean",
    "best_speed_ratio": "speed_ratio",
    # section 9: J = m D_m^2 / 4, H/B, D_1 = D_m + H
    "j_flywheel": "mass * d_mean**2",
    "j_max": "j_flywheel",
    "hb_ratio": "h / b",
    "d_outer": "d_mean + h",
    "d_inner": "d_mean - h",
    "d_mean": "h",
    "b": "h",
    "outer_diameter": "d_outer",
    "d_outer_limit": "d_outer",
    "d_outer_needed": "d_outer",
    "max_outer_diameter": "d_outer",
    "max_width": "b",
    # section 10: v = omega' D_1 / 2, sigma = rho v^2 (rho = m / volume), safety factor
    "rim_speed": "omega_max * d_outer",
    "rim_speed_limit": "rim_speed",
    "hoop_stress": "mass / d_outer**3 * rim_speed**2",
    "allowable_stress": "hoop_stress",
    "safety_factor": "allowable_stress / hoop_stress",
    # section 13: parts, stresses, burst, balance (U = e m), the key (p = 2 T / (d t2 l), tau = 2 T / (d b l))
    "inertia": "mass * r_outer**2",
    "r_outer": "d_outer",
    "r_inner": "d_inner",
    "thickness": "b",
    # section 23: castability, walls and the size they are read at
    "casting_size": "d_outer",
    "process_min_wall": "b",
    "min_wall": "b",
    "thinnest_wall": "b",
    "section_ratio": "hb_ratio",
    "bore": "d_inner",
    "t_web": "b",
    "d_hub": "d_outer",
    "l_hub": "b",
    "arm_major": "b",
    "arm_minor": "b",
    "radius": "r_outer",
    "wall": "b",
    "stress": "hoop_stress",
    "allowable": "stress",
    "strength": "stress",
    "max_principal": "stress",
    "von_mises": "stress",
    "hoop_max": "stress",
    "radial_max": "stress",
    "mean_hoop": "stress",
    "strength_safety": "strength / stress",
    # the FE check (design.fem): stresses of the same body, where they are, and their ratios
    "peak": "stress",
    "model_peak": "stress",
    "model_stress": "stress",
    "fem_peak": "stress",
    "lame": "stress",
    "model_radius": "radius",
    "fillet": "radius",
    "von_mises_at": "radius",
    "max_principal_at": "radius",
    "fem_at": "radius",
    "difference": "peak / model_peak",
    "utilisation": "peak / allowable",
    "factor": "fem_peak / lame",
    "size": "fillet / fillet",
    "burst_speed": "omega_max",
    "speed_margin": "burst_speed / omega_max",
    "unbalance_permissible": "mass * d_outer",
    "torque": "driving_torque",
    "length": "l_hub",
    "effective_length": "length",
    "t1": "h",
    "t2": "h",
    "bearing_pressure": "torque / (bore * t2 * effective_length)",
    "shear": "torque / (bore * b * effective_length)",
    "allowable_pressure": "bearing_pressure",
    "allowable_shear": "shear",
    # section 11 and money: a cost is mass times a price per kg (the sweep field material.NAME.cost)
    "efficiency": "power / power",
    "cost": "mass * material.x.cost",
    # section 7: cycles turned in the run-up, omega t / Phi; wall-clock times
    "time": "cycle_angle / omega_target",
    "cycles": "omega_target * time / cycle_angle",
    "solve_time": "time",
    # section 9: m = J / (D_m^2 / 4); section 11: omega_m = P / M_d
    "mass": "j_flywheel / d_mean**2",
    "omega_mean": "power / driving_torque",
    # section 9: m = rho pi D_m H B
    "density": "mass / (d_mean * h * b)",
    "driving_torque": "work_per_cycle / cycle_angle",
    "h": "d_outer - d_inner",
    # section 14, the drive: ratios of speeds, M_n = P_n / omega_n, inertias, the run-up, masses, price
    "motor_ratio": "omega / omega_mean",
    "flywheel_ratio": "omega / omega_mean",
    "breakdown_ratio": "torque / rated_torque",
    "rated_torque": "rated_power / rated_speed",
    "rms_torque": "rated_torque",
    "mean_torque": "rated_torque",
    "rated_power": "power",
    "rated_speed": "omega_mean",
    "synchronous_speed": "omega_mean",
    "rotor_inertia": "j_required",
    "j_delta": "j_required",
    "startup_time": "time",
    "motor_mass": "mass",
    "wheel_mass": "mass",
    "dmass": "mass",  # a sensitivity's change of mass over its step
    "total_mass": "motor_mass + wheel_mass",
    "price": "cost",
    # section 26, the mounting shaft: factors of safety are stress ratios; slope = deflection / length;
    # an unbalance force is U_per omega^2; a critical speed and the running range are speeds; a torsional
    # mode is sqrt(k / J); the sensitivity of a utilisation to a mass is 1 / kg
    "fatigue_factor": "allowable_stress / stress",
    "fatigue_factor_allowed": "fatigue_factor",
    "yield_factor": "allowable_stress / stress",
    "yield_factor_allowed": "yield_factor",
    "slope": "deflection / length",
    "slope_allowed": "slope",
    "deflection": "d_outer - d_inner",
    "deflection_allowed": "deflection",
    "seat_diameter": "bore",  # a designed seat is the wheel's bore
    "seat_diameter_continuous": "bore",  # the NLP's seat before it is rounded up to the series
    "seat_dmass_dfactor": "mass / utilisation",  # d(m)/d(n), n a factor of safety (dimensionless)
    "unbalance_force": "unbalance_permissible * omega_max**2",
    "torque_mean": "driving_torque",
    "torque_alternating": "driving_torque",
    "torque_alternating_rigid": "driving_torque",
    "key_torque": "driving_torque",
    "key_stress": "bearing_pressure",
    "key_stress_allowed": "bearing_pressure",
    "critical_speed": "omega_max",
    "critical_speed_allowed": "critical_speed",
    # the drive train: a natural frequency is sqrt(k / J); shapes, damping ratios and orders are ratios;
    # a torsional stiffness is a torque per radian
    "natural_frequency": "(torque / j_flywheel)**0.5",
    "mode_shape": "j_required / j_required",
    "damping_ratio": "j_required / j_required",
    "orders": "omega_max / omega_mean",
    "order": "omega_max / omega_mean",
    "largest_order": "omega_max / omega_mean",
    "torsional_stiffness": "driving_torque",
    "torque_largest_order": "driving_torque",
    "lateral_critical_speed": "critical_speed",
    "speed_range": "omega_mean",
    "torsional_modes": "(torque / j_flywheel)**0.5",
    "dutilisation_dmass": "utilisation / mass",
}


def _value(expression):
    names = set(re.findall(r"[a-z_][a-z_0-9.]*", expression)) - {"meter", "second"}
    scope = {"meter": unit_registry().meter, "second": unit_registry().second}
    text = expression
    for k, name in enumerate(sorted(names, key=len, reverse=True)):
        text = re.sub(rf"(?<![a-z_0-9.]){re.escape(name)}(?![a-z_0-9.])", f"_v{k}", text)
        unit = "radian" if name == "angle" else unit_of(name)
        assert unit is not None, f"{name} has no unit"
        scope[f"_v{k}"] = _q(unit)
    return eval(text, {"__builtins__": {}}, scope)  # noqa: S307 - expressions of this file


@pytest.mark.parametrize("name", sorted(RELATIONS))
def test_units_agree_with_the_relations_of_the_engineering_notes(name):
    unit = unit_of(name)
    assert unit is not None
    assert _q(unit).dimensionality == _value(RELATIONS[name]).dimensionality, (name, unit, RELATIONS[name])


def test_every_quantity_is_in_a_relation_and_every_unit_is_coherent_si():
    """No unit escapes the dimensional check, and each is SI without a prefix (1 of it is 1 in
    base units): "mm" or "MPa" would pass the dimension and still be wrong."""
    assert set(QUANTITIES) <= set(RELATIONS)
    names = set(QUANTITIES) | {
        "delta",
        "speed",
        "inertia",
        "design.max_outer_diameter",
        "design.max_width",
        "design.d_mean",
        "material.x.density",
        "material.x.max_rim_speed",
        "material.x.cost",
        "shaft.x.speed_ratio",
        "torque.scale",
    }
    for name in names:
        unit = unit_of(name)
        assert _q(unit).to_base_units().magnitude == pytest.approx(1.0, rel=1e-15), (name, unit)


def test_the_sweep_inputs_have_the_dimensions_their_values_are_read_in():
    """quantities.INPUTS against the sweep grammar itself (flyopt.io.sweep_spec), field by field:
    a new sweep field, or one read in another dimension, fails here."""
    from flyopt.io import sweep_spec

    assert set(quantities.INPUTS) == set(sweep_spec.FIELDS)
    for name, field in sweep_spec.FIELDS.items():
        assert quantities.INPUTS[name] == (field.dimension if field.kind == "number" else None), name
    for table, mine in (
        (sweep_spec._MATERIAL_FIELDS, quantities.MATERIAL_INPUTS),
        (sweep_spec._SHAFT_FIELDS, quantities.SHAFT_INPUTS),
    ):
        assert {k: f.dimension for k, f in table.items()} == mine
    assert not set(quantities.INPUTS) & set(QUANTITIES)  # one entry per name
    assert unit_of("material.cast_iron.density") == "kg/m**3" and unit_of("shaft.motor.speed_ratio") == "1"


def test_units_set_by_another_field():
    assert unit_of("objective", objective="mass") == "kg"
    assert unit_of("objective", objective="outer_diameter") == "m"
    assert unit_of("objective", objective="cost") == "1"
    assert unit_of("objective") is None and unit_of("dmass_dlimit") is None
    assert unit_of("epsilon", front="outer_diameter") == "m" and unit_of("epsilon", front="delta") == "1"
    assert unit_of("objective_bound", objective="mass") == "kg" and unit_of("objective_bound") is None
    assert unit_of("dobjective_dlimit") is None
    assert unit_of("step") is None  # a sensitivity's step, in its entry's unit
    assert set(UNIT_SET_BY) == {"objective", "objective_bound", "epsilon", "dmass_dlimit", "dobjective_dlimit", "step"}
    assert unit_of("status") is None and unit_of("iterations") is None and unit_of("design.geometry") is None


_NOMENCLATURE_UNITS = {"kg·m²": "kg*m**2", "N·m": "N*m", "N·m²": "N*m**2", "–": "1"}


def test_units_agree_with_the_nomenclature():
    """docs/nomenclature.md, written as documentation, gives each JSON name its SI unit: every
    row with one unit and JSON names agrees with the units map (56 names when written)."""
    checked = 0
    for line in (ROOT / "docs" / "nomenclature.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("| ") or len(cells) < 3 or cells[0] in ("symbol", "---"):
            continue
        names, unit = cells[1], cells[2]
        if any(ch in unit for ch in ",; ") or unit in ("—", "bool", ""):
            continue
        unit = _NOMENCLATURE_UNITS.get(unit, unit)
        for segment in names.split(";"):
            if "(" in segment:  # code or scene names, not JSON
                continue
            for path in re.findall(r"`([^`]+)`", segment):
                field = [p for p in re.split(r"\.|\[\]", path) if p][-1]
                if field in COUNTS:
                    continue
                mine = unit_of(field)
                assert mine is not None, path
                assert _q(unit).to(mine).magnitude == pytest.approx(1.0, rel=1e-15), (path, unit, mine)
                checked += 1
    assert checked >= 50


def test_a_shaft_limit_is_shown_in_the_dimension_its_json_field_has():
    """A shaft limit's words (:meth:`ShaftLimit.describe`) and its ``--json`` field are one quantity: its value in
    SI (a critical speed's rpm as rad/s, by :meth:`ShaftLimit.si`, the one conversion the JSON, the text and the
    report read) in the dimension QUANTITIES gives the field."""
    import math

    from flyopt.design.shaft.check import DIMENSIONS, JSON_NAMES, ShaftLimit

    assert DIMENSIONS.keys() == JSON_NAMES.keys()
    for kind, name in JSON_NAMES.items():
        assert QUANTITIES[name] == QUANTITIES[f"{name}_allowed"] == DIMENSIONS[kind], kind
    limit = ShaftLimit("lateral", "first forward whirl", 3000.0, 1650.0, 0.9, "rpm")
    said = limit.describe()
    assert said.values["value"][:2] == (3000.0 * math.pi / 30.0, "angular_speed")
    assert limit.to_dict()["critical_speed"] == said.values["value"][0] == limit.si(3000.0)
    assert ShaftLimit("slope", "at bearing A", 1e-3, 2e-3, 0.5, "rad").si(1e-3) == 1e-3
