"""Lateral critical speeds (flyopt.design.shaft.lateral) against closed forms, and the FE's convergence.

References: the first bending frequency of a uniform simply supported beam, omega_1 = (pi/l)^2
sqrt(EI/(rho A)) (e.g. Rao, *Mechanical Vibrations*, Euler-Bernoulli beam, pinned-pinned);
Jeffcott's rotor omega = sqrt(k/m), k = 48 EI/l^3 at mid-span; Shigley's Mechanical Engineering
Design, 9th ed., section 7-6: Rayleigh's Eq. (7-23) (an upper bound) and Dunkerley's Eq. (7-32)
(a lower bound); the gyroscopic 2-DOF disc model derived below.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from flyopt.design.shaft.beam import SteppedShaft
from flyopt.design.shaft.lateral import (
    Disc,
    critical_speeds,
    dunkerley_speed,
    jeffcott_speed,
    natural_frequencies,
    rayleigh_speed,
    rotor_model,
    running_margin,
    whirl_frequencies,
)

E, RHO, D = 207e9, 7850.0, 0.05
I_ = math.pi * D**4 / 64
A_ = math.pi * D**2 / 4


def test_fe_converges_to_the_uniform_beam_at_the_fourth_power_of_the_element():
    """Pinned-pinned uniform beam: the Hermite element with consistent mass converges as h^4.

    Meshes of 2, 4, 8, 16, 32 elements: each halving of h divides the error by 2^4 (observed order
    within 0.1 of 4 once in the asymptotic range), and the finest mesh is within 1e-7.
    """
    length = 1.2
    exact = (math.pi / length) ** 2 * math.sqrt(E * I_ / (RHO * A_))
    shaft = SteppedShaft((length,), (D,), E, (0.0, length), density=RHO)
    errors = []
    for n in (2, 4, 8, 16, 32):
        errors.append(abs(natural_frequencies(rotor_model(shaft, elements=n))[0] - exact) / exact)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.diff(errors) < 0)
    assert_allclose(orders[1:], 4.0, atol=0.1)
    assert errors[-1] < 1e-7


def test_massless_shaft_with_a_central_disc_is_jeffcott():
    """Central disc on a massless uniform shaft: omega = sqrt(48 E I / (m l^3)), whatever the mesh;
    its diametral and polar inertias do not enter (the disc does not tilt in the symmetric mode),
    nor the speed: the forward and backward first whirl stay at Jeffcott's omega."""
    length, mass = 0.9, 40.0
    exact = math.sqrt(48 * E * I_ / (mass * length**3))
    shaft = SteppedShaft((length,), (D,), E, (0.0, length), density=RHO)
    disc = Disc(length / 2, mass, 0.4, 0.8)
    for n in (1, 3, 7):
        model = rotor_model(shaft, [disc], elements=n, shaft_mass=False)
        assert_allclose(natural_frequencies(model)[0], exact, rtol=1e-12)
        whirl = whirl_frequencies(model, [0.0, 300.0, 900.0])
        assert_allclose(whirl.forward[:, 0], exact, rtol=1e-10)
        assert_allclose(whirl.backward[:, 0], exact, rtol=1e-10)
    assert_allclose(jeffcott_speed(shaft, length / 2, mass), exact, rtol=1e-12)
    assert_allclose(rayleigh_speed(shaft, [length / 2], [mass]), exact, rtol=1e-12)
    assert_allclose(dunkerley_speed(shaft, [length / 2], [mass]), exact, rtol=1e-12)


def test_spring_bearings_soften_jeffcott():
    """Equal springs k_b: 1/k = l^3/(48 E I) + 1/(2 k_b) at mid-span."""
    length, mass, k_b = 0.9, 40.0, 5e7
    k = 1.0 / (length**3 / (48 * E * I_) + 1.0 / (2 * k_b))
    shaft = SteppedShaft((length,), (D,), E, (0.0, length), bearing_stiffness=(k_b, k_b))
    model = rotor_model(shaft, [Disc(length / 2, mass)], elements=2, shaft_mass=False)
    assert_allclose(natural_frequencies(model)[0], math.sqrt(k / mass), rtol=1e-12)
    assert_allclose(jeffcott_speed(shaft, length / 2, mass), math.sqrt(k / mass), rtol=1e-12)


def test_two_masses_fe_exact_and_rayleigh_dunkerley_bound_it():
    """Two point masses on a massless stepped shaft: the FE equals the flexibility closed form
    det(Delta M - I/omega^2) = 0 (Delta from the integrated elastic line), and
    Dunkerley <= omega_1 <= Rayleigh."""
    from flyopt.design.shaft.beam import influence_coefficient

    shaft = SteppedShaft((0.3, 0.8, 1.0), (0.04, 0.06, 0.04), E, (0.05, 0.95))
    x, m = [0.35, 0.7], [30.0, 20.0]
    delta = np.array([[influence_coefficient(shaft, a, b) for b in x] for a in x])
    inverse_squares = np.linalg.eigvals(delta @ np.diag(m))
    exact = np.sort(1.0 / np.sqrt(np.real(inverse_squares)))
    model = rotor_model(shaft, [Disc(x[0], m[0]), Disc(x[1], m[1])], elements=2, shaft_mass=False)
    assert_allclose(natural_frequencies(model)[:2], exact, rtol=1e-10)
    assert dunkerley_speed(shaft, x, m) < exact[0] < rayleigh_speed(shaft, x, m)
    assert rayleigh_speed(shaft, x, m) < 1.01 * exact[0]


def _overhung_disc_closed_form(span, overhang, mass, i_d, i_p, speed):
    """The 2-DOF disc model of an overhung disc on a massless shaft (derived here).

    The disc sits at the tip of an overhang a beyond the second of two rigid bearings a span l apart.
    Its deflection w and slope phi (complex coordinates, w = u + i v) under a tip force F and moment M
    follow from the elastic line (Shigley Table A-9, overhanging cases):

        w = F a^2 (l + a)/(3 E I) + M a (2 l + 3 a)/(6 E I),    phi = F a (2 l + 3 a)/(6 E I) + M (l + 3 a)/(3 E I),

    (a cantilever is the limit l -> 0: a^3/3, a^2/2, a over E I). The stiffness K = inverse of that
    flexibility. The disc's equations, with its angular momentum I_p Omega about the axis:

        m w'' + k11 w + k12 phi = 0,    I_d phi'' - i Omega I_p phi' + k21 w + k22 phi = 0.

    With w, phi ~ e^{i omega t} (omega > 0 forward whirl, omega < 0 backward):

        (k11 - m omega^2)(k22 - I_d omega^2 + I_p Omega omega) - k12^2 = 0,

    a quartic m I_d omega^4 - m I_p Omega omega^3 - (k11 I_d + m k22) omega^2 + k11 I_p Omega omega
    + (k11 k22 - k12^2) = 0: two positive roots (forward) and two negative (backward).
    """
    ei = E * I_
    flexibility = np.array(
        [
            [overhang**2 * (span + overhang) / (3 * ei), overhang * (2 * span + 3 * overhang) / (6 * ei)],
            [overhang * (2 * span + 3 * overhang) / (6 * ei), (span + 3 * overhang) / (3 * ei)],
        ]
    )
    (k11, k12), (_, k22) = np.linalg.inv(flexibility)
    roots = np.roots(
        [mass * i_d, -mass * i_p * speed, -(k11 * i_d + mass * k22), k11 * i_p * speed, k11 * k22 - k12**2]
    )
    roots = np.sort(roots.real)
    return roots[roots > 0], -roots[roots < 0][::-1], (k11, k12, k22)


def test_gyroscopic_splitting_of_an_overhung_disc():
    span, overhang, mass = 0.5, 0.2, 60.0
    radius = 0.25
    i_d, i_p = mass * radius**2 / 4, mass * radius**2 / 2  # a thin disc
    shaft = SteppedShaft((span + overhang,), (D,), E, (0.0, span))
    model = rotor_model(shaft, [Disc(span + overhang, mass, i_d, i_p)], elements=3, shaft_mass=False)
    speeds = np.array([0.0, 100.0, 400.0, 1500.0])
    whirl = whirl_frequencies(model, speeds, modes=2)
    for i, speed in enumerate(speeds):
        forward, backward, _ = _overhung_disc_closed_form(span, overhang, mass, i_d, i_p, speed)
        assert_allclose(whirl.forward[i], forward, rtol=1e-9)
        assert_allclose(whirl.backward[i], backward, rtol=1e-9)
    # gyroscopic stiffening: forward whirl rises with speed, backward falls
    assert np.all(np.diff(whirl.forward[:, 0]) > 0) and np.all(np.diff(whirl.backward[:, 0]) < 0)


def test_critical_speeds_where_whirl_meets_the_first_order():
    """omega = +-Omega in the quartic: m (I_d -+ I_p) Omega^4 - (k11 (I_d -+ I_p) + m k22) Omega^2 + det K = 0.

    A thin disc (I_p = 2 I_d) has I_d - I_p < 0: one forward critical speed (the quadratic in
    Omega^2 has one positive root), two backward ones."""
    span, overhang, mass, radius = 0.5, 0.2, 60.0, 0.25
    i_d, i_p = mass * radius**2 / 4, mass * radius**2 / 2
    shaft = SteppedShaft((span + overhang,), (D,), E, (0.0, span))
    model = rotor_model(shaft, [Disc(span + overhang, mass, i_d, i_p)], elements=3, shaft_mass=False)
    _, _, (k11, k12, k22) = _overhung_disc_closed_form(span, overhang, mass, i_d, i_p, 0.0)
    for whirl, j in (("forward", i_d - i_p), ("backward", i_d + i_p)):
        squares = np.roots([mass * j, -(k11 * j + mass * k22), k11 * k22 - k12**2])
        expected = np.sort(np.sqrt(squares[squares > 0].real))
        assert_allclose(critical_speeds(model, whirl=whirl), expected, rtol=1e-10)
    assert critical_speeds(model).size == 1 and critical_speeds(model, whirl="backward").size == 2
    # and the whirl line crosses 1x there
    speed = critical_speeds(model)[0]
    assert_allclose(whirl_frequencies(model, [speed]).forward[0, 0], speed, rtol=1e-9)


def test_running_margin_against_the_speed_range():
    rpm = 2 * math.pi / 60
    assert running_margin(1200 * rpm, (900.0, 1500.0)) == 0.0
    assert_allclose(running_margin(1800 * rpm, (900.0, 1500.0)), 0.2, rtol=1e-12)
    assert_allclose(running_margin(600 * rpm, (900.0, 1500.0)), 1 / 3, rtol=1e-12)


def test_bad_input_is_refused():
    shaft = SteppedShaft((1.0,), (D,), E, (0.0, 1.0))
    with pytest.raises(ValueError, match="mass"):
        Disc(0.5, 0.0)
    with pytest.raises(ValueError, match="on the shaft"):
        rotor_model(shaft, [Disc(1.5, 10.0)])
    with pytest.raises(ValueError, match="whirl"):
        critical_speeds(rotor_model(shaft), whirl="sideways")
    with pytest.raises(ValueError, match="critical_speed"):
        running_margin(-1.0, (900.0, 1500.0))
