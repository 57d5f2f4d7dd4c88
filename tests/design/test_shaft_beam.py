"""A stepped shaft's elastic line (flyopt.design.shaft.beam) against closed forms and the beam FE.

Closed forms: Shigley's Mechanical Engineering Design, 9th ed., Table A-9, case 6 (simple supports,
intermediate load: y = F b x (x^2 + b^2 - l^2) / (6 E I l) for x <= a, theta_A = F b (b^2 - l^2)/(6 E I l)
for a force F along -y written as -F) and case 10 (simple supports, overhanging load: the tip
deflection F a^2 (l + a)/(3 E I), between the supports y = F a x (l^2 - x^2)/(6 E I l) opposite to
the load). Second method: the finite-element stiffness of flyopt.design.shaft.lateral (cubic
Hermite elements, whose nodal values are exact for point loads at nodes) solved statically.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flyopt.design.shaft.beam import SteppedShaft, elastic_line, elastic_lines, influence_coefficient, reactions
from flyopt.design.shaft.lateral import rotor_model

E, D = 207e9, 0.06
I_ = math.pi * D**4 / 64


def test_simply_supported_point_load_matches_the_closed_form():
    length, a, force = 0.8, 0.3, 5000.0
    b = length - a
    shaft = SteppedShaft((length,), (D,), E, (0.0, length))
    x = np.linspace(0.0, a, 11)
    line = elastic_line(shaft, [a], [-force], at=x)
    assert_allclose(line.deflection, -force * b * x * (length**2 - b**2 - x**2) / (6 * E * I_ * length), rtol=1e-12)
    assert_allclose(line.slope[0], -force * b * (length**2 - b**2) / (6 * E * I_ * length), rtol=1e-12)
    assert_allclose(line.deflection[-1], -force * a**2 * b**2 / (3 * E * I_ * length), rtol=1e-12)
    assert_allclose(line.moment[-1], force * a * b / length, rtol=1e-12)  # sagging, F a b / l
    assert_allclose(line.reactions, (force * b / length, force * a / length), rtol=1e-14)


def test_overhung_load_matches_the_closed_form():
    span, overhang, force = 0.6, 0.25, 3000.0
    shaft = SteppedShaft((span + overhang,), (D,), E, (0.0, span))
    x = np.linspace(0.0, span, 7)
    line = elastic_line(shaft, [span + overhang], [-force], at=np.append(x, span + overhang))
    assert_allclose(
        line.deflection[:-1], force * overhang * x * (span**2 - x**2) / (6 * E * I_ * span), rtol=1e-12, atol=1e-18
    )
    assert_allclose(line.deflection[-1], -force * overhang**2 * (span + overhang) / (3 * E * I_), rtol=1e-12)
    # tip slope, F a (2 l + 3 a) / (6 E I), from the same case
    assert_allclose(line.slope[-1], -force * overhang * (2 * span + 3 * overhang) / (6 * E * I_), rtol=1e-12)


def test_several_load_cases_at_once_each_match_their_closed_form():
    """elastic_lines: three cases on the same two points (a zero force where a case has none), each against
    Shigley's case 6 (a load between the supports) or case 10 (an overhanging load), superposed by hand."""
    span, overhang, a = 0.6, 0.25, 0.2
    shaft = SteppedShaft((span + overhang,), (D,), E, (0.0, span))
    positions = np.array([a, span + overhang])
    forces = np.array([[-4000.0, 0.0], [0.0, -1500.0], [-4000.0, -1500.0]])
    x = np.linspace(0.0, a, 5)  # left of the intermediate load, where case 6's first formula holds

    def between(force):  # case 6 at x <= a
        b = span - a
        return -force * b * x * (span**2 - b**2 - x**2) / (6 * E * I_ * span)

    def hanging(force):  # case 10 between the supports
        return force * overhang * x * (span**2 - x**2) / (6 * E * I_ * span)

    expected = (between(4000.0), hanging(1500.0), between(4000.0) + hanging(1500.0))
    lines = elastic_lines(shaft, positions, forces, at=x)
    assert len(lines) == 3
    for line, want, row in zip(lines, expected, forces):
        assert_allclose(line.deflection, want, rtol=1e-12, atol=1e-18)
        assert_allclose(line.reactions, reactions(shaft, positions, row), rtol=1e-14, atol=1e-9)


def _fe_static(shaft, positions, forces):
    """Deflections and slopes at the FE nodes, K y = F (a second, independent method)."""
    model = rotor_model(shaft, elements=4, shaft_mass=False, extra_nodes=positions)
    full = np.zeros(2 * model.nodes.size)
    for x, f in zip(positions, forces):
        full[2 * int(np.argmin(np.abs(model.nodes - x)))] += f
    y = np.zeros_like(full)
    y[model.free] = np.linalg.solve(model.stiffness, full[model.free])
    return model.nodes, y[0::2], y[1::2]


@pytest.mark.parametrize("stiffness", [(None, None), (4e8, 9e8)])
def test_stepped_shaft_matches_the_finite_element_solution(stiffness):
    """Three steps, a wheel between the bearings and a pull on the overhang, rigid or spring bearings."""
    shaft = SteppedShaft((0.2, 0.7, 0.95), (0.05, 0.08, 0.045), E, (0.1, 0.75), bearing_stiffness=stiffness)
    positions, forces = [0.45, 0.95], [-8000.0, 2500.0]
    nodes, y, theta = _fe_static(shaft, positions, forces)
    line = elastic_line(shaft, positions, forces, at=nodes)
    scale = np.max(np.abs(y))
    assert_allclose(line.deflection, y, rtol=0, atol=1e-11 * scale)
    assert_allclose(line.slope, theta, rtol=0, atol=1e-11 * np.max(np.abs(theta)))


def test_influence_coefficients_are_reciprocal():
    """Maxwell: delta_ij = delta_ji on a stepped shaft with spring bearings."""
    shaft = SteppedShaft((0.3, 0.9, 1.1), (0.05, 0.09, 0.05), E, (0.05, 1.0), bearing_stiffness=(2e8, 5e8))
    assert_allclose(influence_coefficient(shaft, 0.4, 1.1), influence_coefficient(shaft, 1.1, 0.4), rtol=1e-12)


def test_spring_bearings_add_their_compliance():
    """A central force on a uniform shaft: 1/k = l^3/(48 E I) + (1/k_A + 1/k_B)/4."""
    length, k_a, k_b = 1.0, 3e8, 6e8
    shaft = SteppedShaft((length,), (D,), E, (0.0, length), bearing_stiffness=(k_a, k_b))
    expected = length**3 / (48 * E * I_) + (1 / k_a + 1 / k_b) / 4
    assert_allclose(influence_coefficient(shaft, 0.5), expected, rtol=1e-12)


def test_reactions_balance_the_loads():
    shaft = SteppedShaft((1.0,), (D,), E, (0.2, 0.8))
    r_a, r_b = reactions(shaft, [0.1, 0.5, 1.0], [100.0, -300.0, 50.0])
    assert_allclose(r_a + r_b, 150.0, rtol=1e-14)
    assert_allclose(r_b * 0.6 + 100.0 * -0.1 - 300.0 * 0.3 + 50.0 * 0.8, 0.0, atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(steps=(0.5, 0.4), diameters=(0.05, 0.05), elastic_modulus=E, bearings=(0, 0.4)), "increase"),
        (dict(steps=(0.5,), diameters=(0.05, 0.04), elastic_modulus=E, bearings=(0, 0.5)), "as many"),
        (dict(steps=(0.5,), diameters=(-0.05,), elastic_modulus=E, bearings=(0, 0.5)), "diameters"),
        (dict(steps=(0.5,), diameters=(0.05,), elastic_modulus=E, bearings=(0.3, 0.2)), "bearings"),
        (dict(steps=(0.5,), diameters=(0.05,), elastic_modulus=E, bearings=(0, 0.6)), "bearings"),
    ],
)
def test_bad_shafts_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SteppedShaft(**kwargs)


def test_loads_off_the_shaft_are_refused():
    shaft = SteppedShaft((0.5,), (0.05,), E, (0.0, 0.5))
    with pytest.raises(ValueError, match="on the shaft"):
        elastic_line(shaft, [0.7], [1.0])
