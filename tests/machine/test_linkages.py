"""The guide-bar, the four-bar and the cam (flyopt.machine.linkages) against independent references.

References used here:
- positions found by solving the loop-closure equations numerically
  (scipy.optimize.fsolve from a nearby guess), differentiated by central
  finite differences: no hand-derived formula involved;
- the closed-form positions of the mechanisms, differentiated by central
  finite differences (the ratios and their slopes are hand-derived);
- the kinetic energy of the members from finite-difference velocities of
  their positions (J_e = 2T/ω²);
- the work of a constant moment or force over a cycle from the extreme
  positions (found by scipy.optimize), not from the ratios;
- the textbook's peak-velocity factors of the follower laws and the classical
  time ratio K = (180° + θ)/(180° − θ) of the quick-return mechanisms.
"""

import math

import casadi as ca
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy import integrate, optimize

from flyopt.errors import SceneError
from flyopt.machine.linkages import Cam, FourBar, GuideBar, LinkageRatio
from flyopt.machine.mechanism import Member, equivalent_inertia, equivalent_torque

TWO_PI = 2 * math.pi
ANGLES = np.array([0.05, 0.3, 1.0, math.pi / 2, 2.0, 3.0, 4.0, 5.5, 6.2])
H = 1e-6  # central differences: error ~ h² f''' ~ 1e-12, rounding ~ 1e-16/h ~ 1e-10


def deriv(f, x, h=H):
    a, b = f(x + h), f(x - h)
    if isinstance(a, tuple):
        return tuple((p - q) / (2 * h) for p, q in zip(a, b, strict=True))
    return (a - b) / (2 * h)


def stack(v):
    return np.column_stack(v) if isinstance(v, tuple) else np.asarray(v)[:, None]


GUIDE_BARS = [GuideBar(0.15, 0.3, 0.55), GuideBar(0.3, 0.15, 0.6), GuideBar(0.1, 0.25, 0.4, speed_ratio=0.5, phase=0.3)]
FOUR_BARS = [
    FourBar(0.1, 0.35, 0.3, 0.4),
    FourBar(0.1, 0.35, 0.3, 0.4, "crossed"),
    FourBar(0.4, 0.5, 0.45, 0.15),  # double crank (the frame the shortest)
    FourBar(0.05, 0.2, 0.12, 0.18, speed_ratio=-2.0, phase=1.0),
]
CAM = Cam(
    [
        ("rise", "cycloidal", math.radians(100), 0.02),
        ("dwell", None, math.radians(40), 0.0),
        ("return", "polynomial_345", math.radians(80), 0.012),
        ("return", "simple_harmonic", math.radians(70), 0.008),
        ("dwell", None, math.radians(20), 0.0),
        ("rise", "uniform_velocity", math.radians(30), 0.005),
        ("return", "simple_harmonic", math.radians(20), 0.005),
    ],
    speed_ratio=1.5,
    phase=0.2,
)

RATIOS = (
    [(m, k, c) for m in GUIDE_BARS for k, c in (("block", 0), ("lever_angular", 0), ("lever_point", 0.27))]
    + [
        (m, k, c)
        for m in FOUR_BARS
        for k, c in (("coupler_angular", 0), ("rocker_angular", 0), ("rocker_point", 0.1), ("coupler_point", 0.13))
    ]
    + [(CAM, "follower", 0)]
)


# -- independent positions: loop closure solved by scipy --------------------------


def guide_bar_solve(m, phi, guess):
    """Lever angle β and slot position s with B = C + s (cos β, sin β) (fsolve on the loop)."""
    psi = m.speed_ratio * phi - m.phase
    bx, by = m.crank * math.cos(psi), m.crank * math.sin(psi)

    def loop(x):
        beta, s = x
        return [-m.frame + s * math.cos(beta) - bx, s * math.sin(beta) - by]

    sol = optimize.fsolve(loop, guess, xtol=1e-13)
    assert np.abs(loop(sol)).max() < 1e-15
    return sol


def four_bar_solve(m, phi, guess):
    """θ3 and θ4 from a e^{iψ} + b e^{iθ3} = d + c e^{iθ4} (fsolve from a guess on the branch)."""
    psi = m.speed_ratio * phi - m.phase
    a, b, c, d = m.crank, m.coupler, m.rocker, m.frame

    def loop(x):
        t3, t4 = x
        return [
            a * math.cos(psi) + b * math.cos(t3) - d - c * math.cos(t4),
            a * math.sin(psi) + b * math.sin(t3) - c * math.sin(t4),
        ]

    sol = optimize.fsolve(loop, guess, xtol=1e-13)
    assert np.abs(loop(sol)).max() < 1e-15
    return sol


@pytest.mark.parametrize("m", GUIDE_BARS, ids=repr)
def test_guide_bar_ratios_against_a_numerical_loop_solve(m):
    h = 1e-5
    for phi in ANGLES:
        guess = [float(m.lever_angle(phi)) + 0.05, float(m.slot_position(phi)) * 1.05]
        beta_plus = guide_bar_solve(m, phi + h, guess)[0]
        beta_minus = guide_bar_solve(m, phi - h, guess)[0]
        beta, s = guide_bar_solve(m, phi, guess)
        assert_allclose(m.lever_angle(phi), beta, atol=1e-12)
        assert_allclose(m.slot_position(phi), s, atol=1e-12)
        assert_allclose(m.lever_angular_ratio(phi), (beta_plus - beta_minus) / (2 * h), atol=1e-8)


@pytest.mark.parametrize("m", FOUR_BARS, ids=repr)
def test_four_bar_ratios_against_a_numerical_loop_solve(m):
    h = 1e-5
    for phi in ANGLES:
        guess = [float(m.coupler_angle(phi)) + 0.03, float(m.rocker_angle(phi)) - 0.03]
        plus, minus = four_bar_solve(m, phi + h, guess), four_bar_solve(m, phi - h, guess)
        t3, t4 = four_bar_solve(m, phi, guess)
        assert_allclose(np.cos(m.coupler_angle(phi) - t3), 1.0, atol=1e-13)
        assert_allclose(np.cos(m.rocker_angle(phi) - t4), 1.0, atol=1e-13)
        assert_allclose(m.coupler_angular_ratio(phi), (plus[0] - minus[0]) / (2 * h), atol=1e-8)
        assert_allclose(m.rocker_angular_ratio(phi), (plus[1] - minus[1]) / (2 * h), atol=1e-8)


def test_four_bar_branches_are_the_named_ones():
    """Open: C clockwise of B seen from D (cross product D→B × D→C < 0); crossed: the mirror image."""
    for branch, sign in (("open", -1), ("crossed", 1)):
        m = FourBar(0.1, 0.35, 0.3, 0.4, branch)
        for phi in ANGLES:
            t4 = m.rocker_angle(phi)
            bx, by = 0.1 * math.cos(phi) - 0.4, 0.1 * math.sin(phi)
            cx, cy = 0.3 * math.cos(t4), 0.3 * math.sin(t4)
            assert np.sign(bx * cy - by * cx) == sign
    # the open crank-rocker with the crank up has its coupler and rocker uncrossed: C above the frame
    m = FourBar(1.0, 3.0, 3.0, 3.0)
    assert m.rocker_angle(math.pi / 2) == pytest.approx(math.radians(103.37), abs=1e-4)


def test_cam_positions_and_ratios_against_independent_integration():
    """s(ψ) integrates the velocity ratio (scipy quad, across the segments), and returns after one turn."""
    period = CAM.period
    assert CAM.follower_position(CAM.phase / CAM.speed_ratio) == pytest.approx(0.0, abs=1e-15)
    assert CAM.follower_position(CAM.phase / CAM.speed_ratio + period) == pytest.approx(0.0, abs=1e-12)
    start = CAM.phase / CAM.speed_ratio
    edges = start + np.cumsum([0.0] + [row[1] for row in CAM.segments]) / CAM.speed_ratio
    for phi in np.linspace(start, start + period, 37)[1:]:
        pieces = [e for e in edges if e < phi]
        total = sum(
            integrate.quad(lambda x: float(CAM.follower_velocity_ratio(x)), lo, min(hi, phi), epsabs=1e-14)[0]
            for lo, hi in zip(pieces, list(pieces[1:]) + [phi], strict=True)
        )
        assert float(CAM.follower_position(phi)) == pytest.approx(total, abs=1e-12)
    assert CAM.stroke == pytest.approx(0.02)


@pytest.mark.parametrize(
    "law, peak",
    [("uniform_velocity", 1.0), ("simple_harmonic", math.pi / 2), ("cycloidal", 2.0), ("polynomial_345", 15 / 8)],
)
def test_cam_laws_have_the_textbook_peak_velocity(law, peak):
    """v_max = C_v h ω / β: 1 (uniform), π/2 (harmonic), 2 (cycloidal), 15/8 (3-4-5)."""
    h, beta = 0.03, math.radians(120)
    cam = Cam(
        [
            ("rise", law, beta, h),
            ("dwell", None, math.radians(60), 0.0),
            ("return", law, beta, h),
            ("dwell", None, math.radians(60), 0.0),
        ]
    )
    phi = np.linspace(0, beta, 20001)
    assert float(np.max(cam.follower_velocity_ratio(phi))) == pytest.approx(peak * h / beta, rel=1e-7)
    assert float(cam.follower_position(beta / 2)) == pytest.approx(h / 2, rel=1e-12)  # all four are symmetric


@pytest.mark.parametrize("m, kind, centre", RATIOS, ids=lambda x: x if isinstance(x, str) else None)
def test_ratios_against_finite_differences_and_casadi(m, kind, centre):
    ratio = LinkageRatio(m, kind, centre)
    value, slope = stack(ratio.numpy(ANGLES)), stack(ratio.slope(ANGLES))
    assert_allclose(slope, stack(deriv(ratio.numpy, ANGLES)), atol=1e-8 * max(1.0, np.abs(slope).max()))
    x = ca.SX.sym("x")
    out = ratio(x)
    f = ca.Function("f", [x], [ca.vertcat(*out) if isinstance(out, tuple) else out])
    assert_allclose(np.array([np.asarray(f(p)).ravel() for p in ANGLES]), value, rtol=1e-14, atol=1e-16)


@pytest.mark.parametrize("m", GUIDE_BARS + FOUR_BARS, ids=repr)
def test_point_ratios_against_finite_differences_of_positions(m):
    """The velocity ratio of a lever, rocker or coupler point is d/dφ of its closed-form position."""
    if isinstance(m, GuideBar):
        e = 0.27

        def point(phi):
            beta = m.lever_angle(phi)
            return -m.frame + e * np.cos(beta), e * np.sin(beta)

        kind = "lever_point"
    else:
        e = 0.13

        def point(phi):
            psi = m.speed_ratio * phi - m.phase
            t3 = m.coupler_angle(phi)
            return m.crank * np.cos(psi) + e * np.cos(t3), m.crank * np.sin(psi) + e * np.sin(t3)

        kind = "coupler_point"
    assert_allclose(stack(LinkageRatio(m, kind, e).numpy(ANGLES)), stack(deriv(point, ANGLES)), atol=1e-9)


# -- the reduction: kinetic energy and work ---------------------------------------


def four_bar_members(m):
    crank, coupler, rocker = m.kinematics("crank", 0.02), m.kinematics("coupler", 0.15), m.kinematics("rocker", 0.1)
    return [
        Member("crank", 2.0, 0.004, crank.velocity_ratio, crank.angular_ratio),
        Member("coupler", 3.0, 0.03, coupler.velocity_ratio, coupler.angular_ratio),
        Member("rocker", 2.5, 0.02, rocker.velocity_ratio, rocker.angular_ratio, torque=40.0),
    ]


def five_point(f, x, h=1e-3):
    """f'(x) by the five-point stencil (error ~ h⁴ f⁽⁵⁾/30, rounding ~ 1e-16/h)."""
    return (f(x - 2 * h) - 8 * f(x - h) + 8 * f(x + h) - f(x + 2 * h)) / (12 * h)


def four_bar_energy(m, phi):
    """2T/ω² of the members of :func:`four_bar_members`, velocities from differences of positions."""

    def psi(p):
        return m.speed_ratio * p - m.phase

    def turned(angle):  # an angle relative to its value at phi: differences without the ±π wrap
        return lambda p: np.angle(np.exp(1j * (angle(p) - angle(phi))))

    points = [
        (2.0, lambda p: 0.02 * np.cos(psi(p)), lambda p: 0.02 * np.sin(psi(p))),
        (
            3.0,
            lambda p: m.crank * np.cos(psi(p)) + 0.15 * np.cos(m.coupler_angle(p)),
            lambda p: m.crank * np.sin(psi(p)) + 0.15 * np.sin(m.coupler_angle(p)),
        ),
        (2.5, lambda p: m.frame + 0.1 * np.cos(m.rocker_angle(p)), lambda p: 0.1 * np.sin(m.rocker_angle(p))),
    ]
    total = 0.004 * five_point(psi, phi) ** 2
    total = total + 0.03 * five_point(turned(m.coupler_angle), phi) ** 2
    total = total + 0.02 * five_point(turned(m.rocker_angle), phi) ** 2
    for mass, x, y in points:
        total = total + mass * (five_point(x, phi) ** 2 + five_point(y, phi) ** 2)
    return total


@pytest.mark.parametrize("m", FOUR_BARS, ids=repr)
def test_four_bar_inertia_is_the_kinetic_energy_and_its_slope(m):
    j = equivalent_inertia(four_bar_members(m), 0.1)
    assert j.has_numpy_derivative
    assert_allclose(j(ANGLES), 0.1 + four_bar_energy(m, ANGLES), rtol=1e-8)
    value, slope = j.value_and_derivative(ANGLES)
    assert_allclose(value, j(ANGLES), rtol=1e-15)
    reference = five_point(lambda p: four_bar_energy(m, p), ANGLES)
    assert_allclose(slope, reference, atol=1e-8 * np.abs(value).max())
    x = ca.SX.sym("x")
    casadi_slope = ca.Function("d", [x], [j.casadi_derivative(x)])
    assert_allclose([float(casadi_slope(p)) for p in ANGLES], slope, rtol=1e-10, atol=1e-13)


def test_four_bar_torque_work_is_the_rocker_swing():
    """A resisting moment T on the rocker takes 2 T × (its swing) per crank turn, the swing from the positions."""
    m = FOUR_BARS[0]
    grid = np.linspace(0, TWO_PI, 721)
    angle = np.unwrap(m.rocker_angle(grid))
    assert np.ptp(angle) < math.pi  # it rocks: no wrap-around in the extremes below

    def extreme(sign):
        k = int(np.argmax(sign * angle))
        best = optimize.minimize_scalar(
            lambda p: -sign * float(np.unwrap([angle[k], float(m.rocker_angle(p))])[1]),
            bounds=(grid[max(k - 2, 0)], grid[min(k + 2, 720)]),
            method="bounded",
            options={"xatol": 1e-12},
        )
        return -sign * best.fun

    low, high = extreme(-1.0), extreme(1.0)
    torque = equivalent_torque(four_bar_members(m))
    work = integrate.quad(lambda p: float(torque(np.array(p))), 0, TWO_PI, limit=200, epsabs=1e-11)[0]
    assert work == pytest.approx(-2 * 40.0 * (high - low), rel=1e-9)


def test_guide_bar_torque_work_and_limit_positions():
    """The lever swings 2 arcsin(r/d); a resisting moment on it takes 2 T × the swing; K = (180+θ)/(180−θ)."""
    m = GuideBar(0.15, 0.3, 0.55)
    swing = 2 * math.asin(0.15 / 0.3)
    (first, second), k = m.limit_positions()
    assert_allclose(m.lever_angular_ratio(np.array([first, second])), 0.0, atol=1e-15)
    extremes = sorted(float(m.lever_angle(p)) for p in (first, second))
    assert extremes[1] - extremes[0] == pytest.approx(swing, rel=1e-14)
    best = optimize.minimize_scalar(
        lambda p: -float(m.lever_angle(p)), bounds=(1.0, 3.0), method="bounded", options={"xatol": 1e-12}
    )
    assert -best.fun == pytest.approx(swing / 2, abs=1e-12) and best.x == pytest.approx(first, abs=1e-5)
    assert k == pytest.approx((math.pi + swing) / (math.pi - swing), rel=1e-14)
    lever = m.kinematics("lever")
    member = Member("lever", 10.0, 0.2, lever.velocity_ratio, lever.angular_ratio, torque=50.0)
    work = integrate.quad(
        lambda p: float(equivalent_torque([member])(np.array(p))),
        0,
        TWO_PI,
        limit=200,
        epsabs=1e-11,
        points=[first, second],
    )[0]
    assert work == pytest.approx(-2 * 50.0 * swing, rel=1e-9)
    assert GuideBar(0.3, 0.15).limit_positions() == ((), 1.0)


def test_four_bar_limit_positions_and_the_classical_time_ratio():
    """Crank and coupler in line: the rocker stands still; θ between them from the triangles (cosine rule)."""
    a, b, c, d = 0.1, 0.35, 0.3, 0.4
    for branch in ("open", "crossed"):
        m = FourBar(a, b, c, d, branch)
        angles, k = m.limit_positions()
        assert len(angles) == 2
        assert_allclose(m.rocker_angular_ratio(np.array(angles)), 0.0, atol=1e-12)
        theta = math.acos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d)) - math.acos(
            ((b + a) ** 2 + d * d - c * c) / (2 * (b + a) * d)
        )
        assert k == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-12)
    assert FourBar(0.4, 0.5, 0.45, 0.15).limit_positions() == ((), 1.0)


def test_cam_force_work_is_twice_the_lift():
    """A resisting force F on the follower takes F × (the path up and down) = 2 F h per turn of the cam."""
    follower = CAM.kinematics("follower")
    member = Member("follower", 2.0, 0.0, follower.velocity_ratio, follower.angular_ratio, force=30.0)
    torque = equivalent_torque([member])
    start = CAM.phase / CAM.speed_ratio
    edges = start + np.cumsum([0.0] + [row[1] for row in CAM.segments]) / CAM.speed_ratio
    work = sum(
        integrate.quad(lambda p: float(torque(np.array(p))), lo, hi, epsabs=1e-13)[0]
        for lo, hi in zip(edges[:-1], edges[1:], strict=True)
    )
    assert work == pytest.approx(-2 * 30.0 * 0.025, rel=1e-10)
    j = equivalent_inertia([member])
    assert_allclose(j(ANGLES), 2.0 * deriv(CAM.follower_position, ANGLES) ** 2, rtol=1e-7, atol=1e-16)


# -- refusals ---------------------------------------------------------------------


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda: FourBar(0.1, 0.2, 0.3, 0.7), "cannot be assembled"),
        (lambda: FourBar(0.3, 0.35, 0.3, 0.4), "cannot turn fully"),  # Grashof fails
        (lambda: FourBar(0.3, 0.2, 0.4, 0.35), "cannot turn fully"),  # Grashof, but the coupler is the shortest
        (lambda: FourBar(0.1, 0.3, 0.25, 0.15), "cannot turn fully"),  # s + l = p + q: the change point
        (lambda: FourBar(0.2, 0.3, 0.4, 0.3), "cannot turn fully"),  # the same, equal only within rounding
        (lambda: FourBar(0.1, 0.35, 0.3, 0.4, "mirror"), "branch 'mirror' is not known"),
        (lambda: GuideBar(0.2, 0.2), "passes through the lever's pivot"),
        (lambda: GuideBar(0.15, 0.3, 0.4), "the pin would leave the slot"),
        (lambda: GuideBar(-0.15, 0.3), "crank must be a positive"),
        (lambda: Cam([("rise", "cycloidal", math.pi, 0.01)]), "add up to one turn"),
        (lambda: Cam([("rise", "cycloidal", math.pi, 0.01), ("return", "cycloidal", math.pi, 0.02)]), "below"),
        (lambda: Cam([("rise", "cycloidal", math.pi, 0.02), ("return", "cycloidal", math.pi, 0.01)]), "balance"),
        (lambda: Cam([("rise", "parabolic", math.pi, 0.01), ("dwell", None, math.pi, 0)]), "law 'parabolic'"),
        (lambda: GuideBar(0.15, 0.3, speed_ratio=0.0), "speed_ratio must not be zero"),
    ],
)
def test_refusals(make, words):
    with pytest.raises(ValueError, match=None) as info:
        make()
    assert words in str(info.value)
    assert not isinstance(info.value, SceneError)


def test_part_names_and_centres():
    with pytest.raises(ValueError, match="part 'rod' is not known"):
        GuideBar(0.15, 0.3).kinematics("rod")
    with pytest.raises(ValueError, match="give its centre"):
        GuideBar(0.15, 0.3).kinematics("lever")
    with pytest.raises(ValueError, match="between its pins"):
        FourBar(0.1, 0.35, 0.3, 0.4).kinematics("coupler", 0.5)
