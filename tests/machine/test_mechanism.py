"""Reduction of a mechanism to the reference shaft, against published and independent references.

References used here:
- the domain page's worked example 3 (published figures, 3 significant digits);
- kinetic energy of a slider-crank from positions found by solving the loop
  closure numerically in 30-digit mpmath and differentiated by mpmath.diff
  (no hand-derived velocity formula involved);
- the textbook closed form of the zero-offset slider velocity;
- the work of a constant force over a cycle, −2 F × stroke, with the stroke
  found by maximizing the slider position numerically.
"""

import math

import casadi as ca
import mpmath
import numpy as np
import pytest
from conftest import assert_published
from numpy.testing import assert_allclose
from scipy import integrate, optimize

from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.torque import Constant
from flyopt.machine.kinematics import GearTrain, SliderCrank
from flyopt.machine.mechanism import Member, equivalent_inertia, equivalent_torque

TWO_PI = 2 * math.pi
ANGLES = np.array([0.0, 0.3, 1.0, math.pi / 2, 2.0, math.pi, 4.0, 5.5])

# A slider-crank with offset and every kind of member: crank (rotating, centre
# off the axis), connecting rod (general plane motion), slider (translation).
R, L, E = 0.12, 0.45, 0.03
CRANK_M, CRANK_J, CRANK_C = 4.0, 0.03, 0.05
ROD_M, ROD_J, ROD_C = 3.0, 0.06, 0.16
SLIDER_M = 7.0
J_C = 0.2


def slider_crank_members(sc):
    crank, rod, slider = sc.kinematics("crank", CRANK_C), sc.kinematics("rod", ROD_C), sc.kinematics("slider")
    return [
        Member("crank", CRANK_M, CRANK_J, crank.velocity_ratio, crank.angular_ratio),
        Member("rod", ROD_M, ROD_J, rod.velocity_ratio, rod.angular_ratio),
        Member("slider", SLIDER_M, 0.0, slider.velocity_ratio, slider.angular_ratio),
    ]


# -- independent reference: mpmath loop closure and numerical differentiation -----

DIGITS = 30


def mp_positions(phi):
    """Crank pin A, slider pin B (by solving |AB| = l numerically) and the rod angle."""
    r, l, e = mpmath.mpf(R), mpmath.mpf(L), mpmath.mpf(E)
    ax, ay = r * mpmath.cos(phi), r * mpmath.sin(phi)
    xb = mpmath.findroot(lambda x: (x - ax) ** 2 + (e - ay) ** 2 - l**2, ax + l)
    return (ax, ay), (xb, e), mpmath.atan2(e - ay, xb - ax)


def mp_kinetic_inertia(phi):
    """2 T/ω² = J_e, from positions differentiated numerically in 30 digits."""
    s = mpmath.mpf(ROD_C) / L

    def crank_centre(p):
        return mpmath.mpf(CRANK_C) * mpmath.cos(p), mpmath.mpf(CRANK_C) * mpmath.sin(p)

    def rod_centre(p):
        a, b, _ = mp_positions(p)
        return a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])

    def d(f, k):
        return mpmath.diff(lambda p: f(p)[k], phi)

    v_crank2 = d(crank_centre, 0) ** 2 + d(crank_centre, 1) ** 2
    v_rod2 = d(rod_centre, 0) ** 2 + d(rod_centre, 1) ** 2
    w_rod = mpmath.diff(lambda p: mp_positions(p)[2], phi)
    v_slider = mpmath.diff(lambda p: mp_positions(p)[1][0], phi)
    return J_C + CRANK_J + CRANK_M * v_crank2 + ROD_J * w_rod**2 + ROD_M * v_rod2 + SLIDER_M * v_slider**2


def test_domain_example3_reduced_inertia_and_torque():
    """Domain page example 3: J_e = 0.0655 kg m^2, M_e = 8.66 N m (resisting)."""
    gears = GearTrain.from_teeth([(20, 40)])
    members = [
        Member("shaft 1", 0.0, 0.003, 0.0, gears.angular_ratio(0)),
        Member("gear 2", 0.0, 0.06, 0.0, gears.angular_ratio(1)),
        Member("link", 1.0, 0.0, 0.1, 0.0),
        Member("slider", 5.0, 0.0, 0.0866, 0.0, force=100.0, force_sense="resisting"),
    ]
    j_e = equivalent_inertia(members)(0.0)
    m_e = equivalent_torque(members)(0.0)
    assert_published(j_e, "0.0655")
    assert_published(-m_e, "8.66")  # negative: it resists
    assert_published(equivalent_torque(members).resisting()(0.0), "8.66")
    assert equivalent_inertia(members).is_constant


def test_slider_crank_inertia_matches_mpmath_kinetic_energy():
    """J_e(φ) = 2T/ω² with T from loop-closure positions differentiated in 30-digit mpmath.

    Tolerance 1e-12: the analytic formulas in double precision against a
    30-digit reference; round-off of a few ulps times the terms' cancellation.
    """
    sc = SliderCrank(R, L, E)
    j_e = equivalent_inertia(slider_crank_members(sc), J_C)
    with mpmath.workdps(DIGITS):
        reference = [float(mp_kinetic_inertia(mpmath.mpf(float(p)))) for p in ANGLES]
    assert_allclose(j_e(ANGLES), reference, rtol=1e-12)


def test_slider_crank_inertia_derivative_matches_mpmath():
    """Exact dJ_e/dφ (CasADi AD) against mpmath.diff of the 30-digit J_e; 1e-10 (nested numerical diff)."""
    sc = SliderCrank(R, L, E)
    j_e = equivalent_inertia(slider_crank_members(sc), J_C)
    angles = ANGLES[[1, 2, 4, 6]]
    with mpmath.workdps(DIGITS):
        reference = [float(mpmath.diff(mp_kinetic_inertia, mpmath.mpf(float(p)))) for p in angles]
    assert_allclose(j_e.derivative(angles), reference, rtol=1e-10, atol=1e-14)


def test_slider_velocity_textbook_closed_form():
    """Zero offset: v_B/ω = −r sin φ (1 + λ cos φ / sqrt(1 − λ² sin² φ)), λ = r/l (exact textbook form).

    The rod's angular ratio is ω_rod/ω = −λ cos φ / sqrt(1 − λ² sin² φ). Tolerance 1e-13:
    two algebraically equal double-precision expressions.
    """
    sc = SliderCrank(R, L)
    lam = R / L
    root = np.sqrt(1 - lam**2 * np.sin(ANGLES) ** 2)
    assert_allclose(
        sc.slider_velocity_ratio(ANGLES),
        -R * np.sin(ANGLES) * (1 + lam * np.cos(ANGLES) / root),
        rtol=1e-13,
        atol=1e-16,
    )
    assert_allclose(sc.rod_angular_ratio(ANGLES), -lam * np.cos(ANGLES) / root, rtol=1e-13, atol=1e-16)
    assert sc.stroke() == pytest.approx(2 * R, rel=1e-15)


def test_slider_crank_loop_closure_and_stroke():
    """|AB| = l at every angle (1e-14); the closed-form stroke equals the numerically maximized span (1e-12)."""
    sc = SliderCrank(R, L, E)
    phi = np.linspace(0, TWO_PI, 101)
    xb = sc.slider_position(phi)
    assert_allclose(np.hypot(xb - R * np.cos(phi), E - R * np.sin(phi)), L, rtol=1e-14)
    hi = optimize.minimize_scalar(
        lambda p: -sc.slider_position(p), bounds=(-1, 1), method="bounded", options={"xatol": 1e-12}
    )
    lo = optimize.minimize_scalar(sc.slider_position, bounds=(2, 4.5), method="bounded", options={"xatol": 1e-12})
    # the extremes are flat, so the positions there are accurate to ~xatol² even though the angles are not
    assert_allclose(-hi.fun - lo.fun, sc.stroke(), rtol=1e-12)


def test_casadi_and_numpy_agree():
    """The same J_e and M_e through CasADi SX and through numpy (round-off only: 1e-14)."""
    sc = SliderCrank(R, L, E)
    members = slider_crank_members(sc)
    members[2] = Member(
        "slider",
        SLIDER_M,
        0.0,
        sc.slider_velocity_ratio,
        0.0,
        force=([0, 1, 1, TWO_PI], [0, 0, 500, 500]),
        force_sense="resisting",
    )
    j_e, m_e = equivalent_inertia(members, J_C), equivalent_torque(members)
    phi = ca.SX.sym("phi")
    f = ca.Function("f", [phi], [j_e.casadi(phi), m_e.casadi(phi)])
    angles = ANGLES[ANGLES != 1.0]  # away from the force step, where CasADi is right-continuous
    j_ca, m_ca = (np.asarray(v).ravel() for v in f(angles.reshape(1, -1)))
    assert_allclose(j_ca, j_e(angles), rtol=1e-14)
    assert_allclose(m_ca, m_e(angles), rtol=1e-14, atol=1e-12)


def test_constant_force_work_is_twice_the_stroke():
    """A constant resisting force F on the slider does −2 F × stroke per turn (quad to 1e-10)."""
    sc = SliderCrank(R, L, E)
    force = 1500.0
    m_e = equivalent_torque([Member("slider", SLIDER_M, 0.0, sc.slider_velocity_ratio, 0.0, force=force)])
    # |v| kinks at the dead centres; tell quad where
    dead = [optimize.brentq(sc.slider_velocity_ratio, a, b) for a, b in ((-0.5, 0.5), (2.5, 3.7))]
    points = sorted(d % TWO_PI for d in dead)
    work = integrate.quad(lambda p: m_e(p), 0, TWO_PI, points=points, epsabs=0, epsrel=1e-13, limit=200)[0]
    assert_allclose(work, -2 * force * sc.stroke(), rtol=1e-10)
    # and as the resisting curve of a cycle, the unknown constant driving torque balances it
    excess = ExcessWork(Constant(None), m_e.resisting(), TWO_PI)
    assert_allclose(excess.driving.value, 2 * force * sc.stroke() / TWO_PI, rtol=1e-10)


def test_axial_force_equals_resisting_force_that_opposes_motion():
    """An axial force −F sign(v) is the same as a resisting force F (same power at every angle)."""
    sc = SliderCrank(R, L, E)
    angles = ANGLES[np.abs(sc.slider_velocity_ratio(ANGLES)) > 1e-9]
    force = 800.0
    resisting = equivalent_torque([Member("s", 1.0, 0.0, sc.slider_velocity_ratio, 0.0, force=force)])
    signs = np.sign(sc.slider_velocity_ratio(angles))
    for phi, sign in zip(angles, signs):
        axial = equivalent_torque(
            [Member("s", 1.0, 0.0, sc.slider_velocity_ratio, 0.0, force=-force * sign, force_sense="axial")]
        )
        assert_allclose(axial(phi), resisting(phi), rtol=1e-15)
    driving = equivalent_torque(
        [Member("s", 1.0, 0.0, sc.slider_velocity_ratio, 0.0, force=force, force_sense="driving")]
    )
    assert_allclose(driving(angles), -resisting(angles), rtol=1e-15)


def test_torque_on_a_gear_and_force_table_limits():
    """A resisting moment T on a gear at ω_2/ω = 1/2 reduces to −T/2; a force table step has two limits."""
    gears = GearTrain([0.5, 0.25])
    assert gears.angular_ratio(2) == 0.125
    members = [
        Member("gear", 0.0, 0.1, 0.0, gears.angular_ratio(1), torque=40.0),
        Member("ram", 10.0, 0.0, 0.2, 0.0, force=([0, 1, 1, TWO_PI], [0, 0, 300, 300])),
    ]
    m_e = equivalent_torque(members)
    left, right = m_e.limits(np.array([1.0]))
    assert_allclose([left[0], right[0]], [-20.0, -20.0 - 60.0], rtol=1e-15)
    assert_allclose(m_e.breakpoints(), [0, 1, TWO_PI])
    assert_allclose(equivalent_inertia(members)(0.3), 0.1 * 0.25 + 10 * 0.04, rtol=1e-15)


def test_table_velocity_ratio_is_linear_between_points():
    """A tabulated velocity ratio interpolates linearly; J_e is quadratic between the points."""
    member = Member("m", 2.0, 0.0, ([0, 1, TWO_PI], [0.0, 0.1, 0.0]), 0.0)
    j_e = equivalent_inertia([member])
    assert_allclose(j_e([0.5, 1.0]), [2 * 0.05**2, 2 * 0.1**2], rtol=1e-15)
    assert_allclose(j_e.knots, [0, 1, TWO_PI])
    assert not j_e.is_constant


@pytest.mark.parametrize(
    "build, match",
    [
        (lambda: SliderCrank(0.2, 0.2), "cannot turn fully"),
        (lambda: SliderCrank(0.1, 0.3, 0.25), "cannot turn fully"),
        (lambda: SliderCrank(-0.1, 0.3), "crank length must be a positive"),
        (lambda: SliderCrank(0.1, 0.3).kinematics("piston"), "part 'piston' is not known"),
        (lambda: SliderCrank(0.1, 0.3).kinematics("rod", 0.5), "between the pins"),
        (lambda: Member("m", mass=-1.0), "mass must be a finite number >= 0"),
        (lambda: Member("m", inertia=math.nan), "inertia must be a finite number >= 0"),
        (lambda: Member("", mass=1.0), "non-empty name"),
        (lambda: Member("m", force=1.0, force_sense="pushing"), "force_sense 'pushing' is not known"),
        (lambda: equivalent_inertia([Member("a"), Member("a")]), "repeated: a"),
        (lambda: equivalent_inertia([Member("a", 1.0, 0.0, ([0, 1, 1, 2], [0, 0, 1, 1]))]), "cannot jump"),
        (lambda: equivalent_inertia([Member("a", 1.0, 0.0, ([0, 2, 1], [0, 1, 1]))]), "non-decreasing"),
        (lambda: equivalent_inertia([Member("a", 1.0, 0.0, "fast")]), "must be a number, a table"),
        (lambda: equivalent_inertia([Member("a")], j_constant=-1.0), "j_constant must be"),
        (
            lambda: equivalent_torque([Member("a", 1.0, 0.0, lambda p: (p, p), force=1.0, force_sense="axial")])(1.0),
            "needs a scalar",
        ),
        (lambda: GearTrain([0.5, 0.0]), "finite non-zero"),
        (lambda: GearTrain([0.5]).angular_ratio(3), "shafts 0..1"),
        (lambda: GearTrain.from_teeth([(20, 0)]), "tooth counts must be positive"),
    ],
)
def test_bad_input_raises_value_error(build, match):
    with pytest.raises(ValueError, match=match):
        build()
