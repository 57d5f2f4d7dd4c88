"""Tests of flyopt.design.geometry: rim and disc mass, inertia, rim speed."""

import math

import casadi as ca
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from flyopt.design import geometry


def test_domain_example6_rim_sizing_textbook():
    """Domain notes, worked example 6: J = 76 kg m^2, D_m = 0.8 m gives m = 475 kg;
    cast steel (7800 kg/m^3) with H/B = 2 gives B = 0.110 m, H = 0.220 m.

    The mass is exact (4 J / D_m^2 = 475); B and H are published to three
    figures, hence rtol 5e-3 (half a unit in the last published digit).
    """
    mass = 475.0
    assert_allclose(geometry.thin_rim_inertia(mass, 0.8), 76.0, rtol=1e-15)
    # m = pi D_m H B rho with H = 2 B  ->  B = sqrt(m / (2 pi D_m rho))
    b = math.sqrt(mass / (2.0 * math.pi * 0.8 * 7800.0))
    assert_allclose(b, 0.110, rtol=5e-3)
    assert_allclose(2.0 * b, 0.220, rtol=5e-3)
    assert_allclose(geometry.rim_mass(0.8, 2.0 * b, b, 7800.0), mass, rtol=1e-14)


@pytest.mark.parametrize(
    "d_mean, h, b, density",
    [
        (0.8, 0.22, 0.11, 7800.0),
        (2.0, 0.05, 0.5, 7200.0),
        (0.1, 0.099, 0.01, 2700.0),  # almost a disc
    ],
)
def test_rim_inertia_equals_integral_of_r2_dm(d_mean, h, b, density):
    """Exact annulus against the defining integral J = int r^2 rho B 2 pi r dr,
    evaluated by adaptive quadrature (rtol 1e-12: quad is asked for 1e-13)."""
    r_in, r_out = (d_mean - h) / 2.0, (d_mean + h) / 2.0
    j_quad, _ = quad(lambda r: r * r * density * b * 2.0 * math.pi * r, r_in, r_out, epsabs=0.0, epsrel=1e-13)
    m_quad, _ = quad(lambda r: density * b * 2.0 * math.pi * r, r_in, r_out, epsabs=0.0, epsrel=1e-13)
    mass = geometry.rim_mass(d_mean, h, b, density)
    assert_allclose(mass, m_quad, rtol=1e-12)
    assert_allclose(geometry.rim_inertia(mass, d_mean, h), j_quad, rtol=1e-12)


def test_thin_rim_is_low_by_m_h2_over_4():
    """Domain notes section 9: the thin-rim value is slightly low (errs safe)."""
    mass, d_mean, h = 100.0, 1.0, 0.1
    exact = geometry.rim_inertia(mass, d_mean, h)
    thin = geometry.thin_rim_inertia(mass, d_mean)
    assert thin < exact
    assert_allclose(exact - thin, mass * h * h / 4.0, rtol=1e-12)


def test_disc_is_an_annulus_without_hole():
    """J = m D^2/8 and m = pi D^2 B rho/4 are the annulus with D_m = H = D/2."""
    d, b, rho = 0.6, 0.05, 7800.0
    assert_allclose(geometry.disc_mass(d, b, rho), geometry.rim_mass(d / 2, d / 2, b, rho), rtol=1e-15)
    mass = geometry.disc_mass(d, b, rho)
    assert_allclose(geometry.disc_inertia(mass, d), geometry.rim_inertia(mass, d / 2, d / 2), rtol=1e-15)
    # against the integral over the full disc
    j_quad, _ = quad(lambda r: r**3 * rho * b * 2.0 * math.pi, 0.0, d / 2.0, epsrel=1e-13)
    assert_allclose(geometry.disc_inertia(mass, d), j_quad, rtol=1e-12)


def test_rim_speed_and_its_diameter_cap_are_inverse():
    """Domain notes section 10: v = omega D_1 / 2; cast iron at 1500 rpm."""
    omega = 1500.0 * math.pi / 30.0
    cap = geometry.outer_diameter_for_rim_speed(36.0, omega)
    assert_allclose(cap, 72.0 / omega, rtol=1e-15)
    assert_allclose(geometry.rim_speed(omega, cap), 36.0, rtol=1e-15)
    assert_allclose(geometry.hoop_stress(7200.0, 36.0), 7200.0 * 36.0**2, rtol=1e-15)
    assert geometry.outer_diameter(0.8, 0.2) == pytest.approx(1.0, rel=1e-15)
    assert geometry.inner_diameter(0.8, 0.2) == pytest.approx(0.6, rel=1e-15)


FORMULAS = [
    (geometry.rim_mass, 4),
    (geometry.rim_inertia, 3),
    (geometry.thin_rim_inertia, 2),
    (geometry.disc_mass, 3),
    (geometry.disc_inertia, 2),
    (geometry.outer_diameter, 2),
    (geometry.inner_diameter, 2),
    (geometry.rim_speed, 2),
    (geometry.outer_diameter_for_rim_speed, 2),
    (geometry.hoop_stress, 2),
]


@pytest.mark.parametrize("formula, nargs", FORMULAS, ids=[f.__name__ for f, _ in FORMULAS])
def test_formulas_work_on_floats_arrays_and_casadi(formula, nargs):
    """Same numbers from floats, numpy arrays and CasADi SX (exact arithmetic
    on the same operations: rtol 1e-14)."""
    rng = np.random.default_rng(7)
    values = rng.uniform(0.1, 2.0, size=(nargs, 5))
    from_floats = np.array([formula(*column) for column in values.T])
    assert_allclose(formula(*values), from_floats, rtol=1e-14)
    symbols = [ca.SX.sym(f"a{i}") for i in range(nargs)]
    expression = formula(*symbols)
    assert isinstance(expression, ca.SX)
    function = ca.Function("f", symbols, [expression])
    from_casadi = np.array([float(function(*column)) for column in values.T])
    assert_allclose(from_casadi, from_floats, rtol=1e-14)


def test_geometry_names():
    assert set(geometry.BARE) == {"thin_rim", "rim", "disc"}
    assert set(geometry.WHEELS) == {"rim_web", "rim_arms"}
    assert set(geometry.GEOMETRIES) == set(geometry.BARE) | set(geometry.WHEELS)
