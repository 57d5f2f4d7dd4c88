"""The vectorized variable-inertia analysis against independent references.

What is pinned here, and against what:

- J_e(φ) and dJ_e/dφ evaluated in numpy (closed-form slopes of the slider-crank
  ratios, a table's slope) against complex-step differentiation of the value
  formulas and against CasADi's algorithmic differentiation of the same J_e;
- the vectorized Brent method against scipy.optimize.brentq, zero for zero;
- the batched Gauss–Kronrod quadrature: each piece the same number as the
  one-piece adaptive quadrature, and ΔE at every knot of slider-crank-press
  and engine-members against mpmath (30 digits) and scipy.integrate.quad
  (epsrel 2e-14) of a textbook model of the scene written here from the
  scene file (no flyopt curve involved);
- the energy–mass extremes (J_F, E_0, the angles of ω_max and ω_min, A_max)
  against a dense grid of the textbook derivative refined by Brent's method,
  with values from scipy.integrate.quad;
- the forward use (the δ of the constant-inertia flywheel) against a
  time-free reference: E_0 by bisection on the same textbook model.

Speed is not asserted here (timing belongs to benchmarks, not to tests).
"""

import math

import casadi as ca
import mpmath
import numpy as np
import pytest
import tomllib
from conftest import PROBLEMS
from numpy.testing import assert_allclose, assert_array_equal
from scipy import integrate, optimize

from flyopt.analysis import analyse
from flyopt.cycle import numerics
from flyopt.cycle.difference import segments
from flyopt.cycle.expression import Expression
from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.numerics import brentq_many
from flyopt.cycle.torque import Constant, ExpressionTorque
from flyopt.io.scene import load
from flyopt.machine.kinematics import GearTrain, SliderCrank, SliderCrankRatio
from flyopt.machine.mechanism import Member, equivalent_inertia
from flyopt.machine.reduce import reduce
from flyopt.sizing import energy_mass
from flyopt.sizing._numerics import Inertia

EPS = np.finfo(float).eps
DEG = math.pi / 180


# -- a textbook model of a slider-crank scene, written from the scene file ---------


class Textbook:
    """J_e(φ) and M_d − M_r of a zero-offset slider-crank scene, from the textbook formulas.

    v_B/ω = −r sin φ (1 + λ cos φ / √(1 − λ² sin² φ)),  ω_rod/ω = −λ cos φ / √(1 − λ² sin² φ);
    a rod point at s = c/l from the crank pin moves at ((1 − s)(−r sin φ) + s v_B, (1 − s) r cos φ).
    Works on floats, complex numbers (for complex-step derivatives) and mpmath numbers.
    """

    def __init__(self, path):
        data = tomllib.loads(path.read_text())
        mech = data["mechanism"]
        assert mech["kind"] == "slider_crank" and "offset" not in mech
        self.r, self.l = _si(mech["crank"]), _si(mech["rod"])
        machine = data["machine"]
        self.j_c = _si(machine["inertia"])
        self.cycle = _si(machine.get("cycle", "360 deg"))
        self.omega = _si(machine["speed"])
        self.delta = float(machine["delta"])
        self.slider_mass = self.rod_mass = self.rod_inertia = 0.0
        self.rod_s = 0.5
        for member in data["member"]:
            if member["part"] == "slider":
                self.slider_mass = _si(member["mass"])
                unit = {"kN": 1e3, "N": 1.0}[member["unit"]]
                table = np.array(member["force"], dtype=float)
                self.force_angles, self.force_values = table[:, 0] * DEG, table[:, 1] * unit
                self.sense = member["force_sense"]
            elif member["part"] == "rod":
                self.rod_mass, self.rod_inertia = _si(member["mass"]), _si(member["inertia"])
                self.rod_s = _si(member["centre"]) / self.l
        driving, resisting = data["torque"]["driving"]["constant"], data["torque"]["resisting"]["constant"]
        self.unknown = "driving" if driving == "unknown" else "resisting"
        self.known = _si(resisting if self.unknown == "driving" else driving)
        # the knots: the force table's angles (steps included once)
        self.knots = np.unique(np.concatenate((self.force_angles, [0.0, self.cycle])))
        w = sum(quad(self._load, a, b) for a, b in zip(self.knots[:-1], self.knots[1:]))
        # the unknown constant balances the cycle: M_r = known − load (driving unknown), M_d = known + load
        self.balance = self.known - w / self.cycle if self.unknown == "driving" else self.known + w / self.cycle
        self.work = sum(
            integrate.quad(lambda p: abs(self.net(p)), a, b, epsabs=1e-9, epsrel=1e-12, limit=200)[0]
            for a, b in zip(self.knots[:-1], self.knots[1:])
        )

    @staticmethod
    def _lib(phi):
        if isinstance(phi, (mpmath.mpf, mpmath.mpc)):
            return mpmath
        return np if isinstance(phi, (np.ndarray, complex, np.complexfloating)) else math

    def ratios(self, phi):
        lib = self._lib(phi)
        r, lam = self.r, self.r / self.l
        root = lib.sqrt(1 - lam**2 * lib.sin(phi) ** 2)
        v_b = -r * lib.sin(phi) * (1 + lam * lib.cos(phi) / root)
        w_rod = -lam * lib.cos(phi) / root
        s = self.rod_s
        return v_b, w_rod, ((1 - s) * (-r * lib.sin(phi)) + s * v_b, (1 - s) * r * lib.cos(phi))

    def inertia(self, phi):
        v_b, w_rod, (vx, vy) = self.ratios(phi)
        return self.j_c + self.slider_mass * v_b**2 + self.rod_mass * (vx**2 + vy**2) + self.rod_inertia * w_rod**2

    def inertia_slope(self, phi):
        """dJ_e/dφ by the complex step, Im J(φ + i h)/h (no subtraction: exact to round-off)."""
        h = 1e-30
        return np.imag(self.inertia(np.asarray(phi, dtype=float) + 1j * h)) / h

    def force(self, phi, piece):
        """The force table on piece ``piece`` (between knots), linear there [N]."""
        a, b = self.knots[piece], self.knots[piece + 1]
        x, y = self.force_angles, self.force_values
        # the table's values just right of a and just left of b
        k_a = np.flatnonzero(x == a)[-1] if np.any(x == a) else None
        k_b = np.flatnonzero(x == b)[0] if np.any(x == b) else None
        fa = y[k_a] if k_a is not None else np.interp(a, x, y)
        fb = y[k_b] if k_b is not None else np.interp(b, x, y)
        return fa + (fb - fa) * (phi - a) / (b - a)

    def _load(self, phi, piece=None):
        """Power ratio of the member force, F v_B (axial) or −F |v_B| (resisting) [N*m]."""
        if piece is None:
            piece = min(max(int(np.searchsorted(self.knots, phi, side="right")) - 1, 0), len(self.knots) - 2)
        v_b = self.ratios(phi)[0]
        f = self.force(phi, piece)
        return f * v_b if self.sense == "axial" else -f * abs(v_b)

    def net(self, phi, piece=None):
        """M_d − M_r on a piece [N*m]."""
        load = self._load(phi, piece)
        if self.unknown == "driving":  # M_r = known − load (a resisting force), M_d = balance
            return self.balance - (self.known - load)
        return self.known + load - self.balance

    def delta_e_at_knots(self):
        parts = [quad(self.net, a, b, (k,)) for k, (a, b) in enumerate(zip(self.knots[:-1], self.knots[1:]))]
        return np.concatenate(([0.0], np.cumsum(parts)))


def quad(f, a, b, args=(), floor=1e-9):
    """scipy.integrate.quad to 2e-14 relative or ``floor`` [J] absolute, whichever is larger
    (a floor far below the 1e-12 of the cycle work the tests ask for; without it QUADPACK
    reports round-off where an integral is near zero)."""
    return integrate.quad(f, a, b, args=args, epsabs=floor, epsrel=2e-14, limit=200)[0]


def _si(text):
    value, unit = str(text).split()
    return float(value) * {"m": 1.0, "kg": 1.0, "kg*m^2": 1.0, "N*m": 1.0, "deg": DEG, "rpm": 2 * math.pi / 60}[unit]


SLIDER_CRANK, ENGINE = PROBLEMS / "slider-crank-press.toml", PROBLEMS / "engine-members.toml"


@pytest.fixture(scope="module", params=[SLIDER_CRANK, ENGINE], ids=["slider-crank-press", "engine-members"])
def scene(request):
    path = request.param
    return path, Textbook(path), reduce(load(path))


# -- J_e and its derivative on arrays --------------------------------------------------


def test_inertia_and_slope_on_arrays_match_the_textbook_and_complex_step(scene):
    """The scene's J_e from the members (numpy, shared trigonometry) against the textbook J_e
    (1e-14), and its closed-form dJ_e/dφ against the complex step of the textbook J_e (1e-12
    of its largest value)."""
    _, book, machine = scene
    phi = np.linspace(0.0, book.cycle, 2001)
    j, dj = machine.j_machine.value_and_derivative(phi)
    assert_allclose(j, book.inertia(phi), rtol=1e-14)
    reference = book.inertia_slope(phi)
    assert np.max(np.abs(dj - reference)) <= 1e-12 * np.max(np.abs(reference))
    assert_array_equal(machine.j_machine.derivative(phi), dj)
    assert_array_equal(machine.j_machine(phi), j)


def test_numpy_slope_matches_casadi_ad_with_offset_tables_and_gears():
    """An offset slider-crank (every ratio kind), a table ratio and a gear: the numpy dJ_e/dφ
    against CasADi's algorithmic differentiation of the symbolic J_e (1e-13), at points off
    the table's knots."""
    sc = SliderCrank(0.11, 0.4, 0.025)
    crank, rod, slider = sc.kinematics("crank", -0.03), sc.kinematics("rod", 0.12), sc.kinematics("slider")
    table = (np.array([0.0, 1.0, 2.5, 4.0, 2 * math.pi]), np.array([0.1, 0.3, -0.2, 0.05, 0.1]))
    gears = GearTrain([0.5, 0.25])
    members = [
        Member("crank", 3.0, 0.02, crank.velocity_ratio, crank.angular_ratio),
        Member("rod", 2.0, 0.05, rod.velocity_ratio, rod.angular_ratio),
        Member("slider", 6.0, 0.0, slider.velocity_ratio, slider.angular_ratio),
        Member("follower", 1.5, 0.01, table, table),
        Member("gear", 0.0, 0.4, 0.0, gears.angular_ratio(2)),
        Member("slider, given as the method", 1.0, 0.0, sc.slider_velocity_ratio, 0.0),
    ]
    j_e = equivalent_inertia(members, 0.3)
    assert j_e.has_numpy_derivative
    phi = np.linspace(0.0, 2 * math.pi, 1001)
    phi = phi[np.min(np.abs(phi[:, None] - table[0][None, :]), axis=1) > 1e-6]
    x = ca.SX.sym("x")
    expr = j_e.casadi(x)
    f = ca.Function("f", [x], [expr, ca.jacobian(expr, x)]).map(len(phi))
    j_ad, dj_ad = (np.asarray(v).ravel() for v in f(phi.reshape(1, -1)))
    j, dj = j_e.value_and_derivative(phi)
    assert_allclose(j, j_ad, rtol=1e-14)
    assert np.max(np.abs(dj - dj_ad)) <= 1e-13 * np.max(np.abs(dj_ad))


@pytest.mark.parametrize("kind, fraction", [("slider", 0.0), ("rod_angular", 0.0), ("rod_point", 0.3)])
def test_slider_crank_ratio_slopes_against_complex_step(kind, fraction):
    """Each closed-form slope of an offset slider-crank's ratios against the complex step of
    the ratio's own value formula (1e-13 of the largest slope)."""
    ratio = SliderCrankRatio(SliderCrank(0.12, 0.45, 0.03), kind, fraction)
    phi = np.linspace(0.0, 2 * math.pi, 721)
    h = 1e-30
    step = ratio(phi + 1j * h)
    slope = ratio.slope(phi)
    for s, v in zip(slope if isinstance(slope, tuple) else (slope,), step if isinstance(step, tuple) else (step,)):
        reference = np.imag(v) / h
        assert np.max(np.abs(s - reference)) <= 1e-13 * np.max(np.abs(reference))
    value = ratio.numpy(phi)
    direct = ratio(phi)
    pairs = zip(value, direct) if isinstance(value, tuple) else [(value, direct)]
    for a, b in pairs:
        assert_array_equal(a, b)  # the shared-trigonometry value is the method's, operation for operation


def test_inertia_wrapper_numpy_and_casadi_paths_agree():
    """Inertia evaluates an EquivalentInertia in numpy and keeps the CasADi function (built on
    first use) for the models that need it: both give the same J and dJ/dφ (1e-14)."""
    machine = reduce(load(SLIDER_CRANK))
    inertia = Inertia(machine.j_machine)
    phi = np.linspace(0.0, 2 * math.pi, 301)
    j_np, dj_np = inertia(phi), inertia.derivative(phi)
    j_ca, dj_ca = (np.asarray(v).ravel() for v in inertia.function.map(len(phi))(phi.reshape(1, -1)))
    assert_allclose(j_np, j_ca, rtol=1e-14)
    assert np.max(np.abs(dj_np - dj_ca)) <= 1e-14 * np.max(np.abs(dj_ca))
    assert not inertia.is_constant
    assert float(inertia(0.0)) == j_np[0]
    assert Inertia(2.5).is_constant and float(Inertia(2.5).derivative(1.0)) == 0.0
    with pytest.raises(ValueError, match="must accept a CasADi symbol"):
        Inertia(lambda phi: 1.0 if phi > 0 else 2.0)
    with pytest.raises(ValueError, match="finite number >= 0"):
        Inertia(-1.0)


# -- vectorized Brent --------------------------------------------------------------------


@pytest.mark.parametrize("n", [12, 1000])
def test_brentq_many_is_scipy_brentq_zero_for_zero(n):
    """Brent's method run on many brackets at once gives bit for bit what scipy.optimize.brentq
    gives on each (the same algorithm, operation for operation): with a few brackets (their
    state in Python floats) and with many (in numpy arrays)."""
    rng = np.random.default_rng(12)
    c, d, p = rng.uniform(0.1, 30, n), rng.uniform(-1, 1, n), rng.integers(1, 9, n)

    def f(x, i):
        return np.sin(c[i] * x) - 0.3 * d[i] + 0.01 * (x - 1.0) ** p[i]

    a, b = np.full(n, -0.5), np.full(n, 1.5)
    fa, fb = f(a, np.arange(n)), f(b, np.arange(n))
    idx = np.flatnonzero(fa * fb < 0)
    assert len(idx) > 0.3 * n
    roots = brentq_many(lambda x, k: f(x, idx[k]), a[idx], b[idx], fa[idx], fb[idx], xtol=1e-15, rtol=4 * EPS)
    for j, i in enumerate(idx):
        expected = optimize.brentq(
            lambda x: float(f(np.array([x]), np.array([i]))[0]), -0.5, 1.5, xtol=1e-15, rtol=4 * EPS
        )
        assert roots[j] == expected


def test_brentq_many_refuses_a_bracket_without_a_sign_change():
    with pytest.raises(ValueError, match="different signs"):
        brentq_many(lambda x, i: x, np.array([1.0]), np.array([2.0]), np.array([1.0]), np.array([2.0]), 1e-15)


# -- the quadrature of all pieces at once ------------------------------------------------


def test_batched_quadrature_is_the_one_piece_quadrature_piece_for_piece():
    """Pieces that the first round settles and pieces that need halving (a sharp peak, an
    oscillation), mixed: each integral is the number the one-piece adaptive quadrature gives,
    bit for bit, and within 1e-12 of mpmath at 30 digits."""
    fs = [lambda x: np.exp(np.sin(5 * x)), lambda x: 1.0 / (1e-4 + (x - 1.234) ** 2), lambda x: np.cos(40 * x) + 2]
    mp_fs = [
        lambda x: mpmath.exp(mpmath.sin(5 * x)),
        lambda x: 1 / (mpmath.mpf("1e-4") + (x - 1.234) ** 2),
        lambda x: mpmath.cos(40 * x) + 2,
    ]
    a = np.array([0.0, 0.5, 1.0, 2.0, 0.0, 0.3])
    b = np.array([0.4, 3.0, 1.1, 2.0, 6.0, 0.30001])
    which = np.array([0, 1, 0, 0, 2, 2])

    def f(phi, i):
        out = np.empty(len(phi))
        for k in range(3):
            sel = which[i] == k
            out[sel] = fs[k](phi[sel])
        return out

    batched = numerics.quad_many(f, a, b, scale=1.0)
    single = np.array([numerics.quad(fs[w], lo, hi, scale=1.0) for w, lo, hi in zip(which, a, b)])
    assert_array_equal(batched, single)
    mpmath.mp.dps = 30
    for w, lo, hi, got in zip(which, a, b, batched):
        ref = float(mpmath.quad(mp_fs[w], [lo, 1.234, hi] if lo < 1.234 < hi else [lo, hi]))
        assert abs(got - ref) <= 1e-12 * max(abs(ref), 1e-300) or (lo == hi and got == 0.0)


def test_delta_e_at_knots_against_mpmath_slider_crank():
    """ΔE at every knot of slider-crank-press (the batched quadrature of all pieces) against
    mpmath at 30 digits of the textbook net torque: 1e-12 of the cycle work."""
    book = Textbook(SLIDER_CRANK)
    machine = reduce(load(SLIDER_CRANK))
    ew = machine.angle_only()
    assert_allclose(ew.knots, book.knots, rtol=1e-15)
    mpmath.mp.dps = 30
    parts = [
        mpmath.quad(lambda p, k=k: book.net(p, k), [mpmath.mpf(a), mpmath.mpf(b)])
        for k, (a, b) in enumerate(zip(book.knots[:-1], book.knots[1:]))
    ]
    reference = np.array([0.0] + [float(v) for v in np.cumsum(parts)])
    got = ew(book.knots)
    assert np.max(np.abs(got - reference)) <= 1e-12 * book.work


def test_delta_e_at_knots_and_between_against_quad_engine():
    """ΔE of engine-members at its 145 knots and at 300 angles between them (each a batched
    quadrature from its knot) against scipy.integrate.quad (epsrel 2e-14) of the textbook
    net torque: 1e-12 of the cycle work."""
    book = Textbook(ENGINE)
    machine = reduce(load(ENGINE))
    ew = machine.angle_only()
    at_knots = book.delta_e_at_knots()
    assert np.max(np.abs(ew(book.knots) - at_knots)) <= 1e-12 * book.work
    phi = np.sort(np.random.default_rng(3).uniform(0.0, book.cycle, 300))
    k = np.clip(np.searchsorted(book.knots, phi, side="right") - 1, 0, len(book.knots) - 2)
    reference = np.array([at_knots[j] + quad(book.net, book.knots[j], p, (j,)) for j, p in zip(k, phi)])
    assert np.max(np.abs(ew(phi) - reference)) <= 1e-12 * book.work


def test_events_see_a_step_at_a_knot_from_the_piece_itself():
    """The ram force steps at 140°: the piece before it ends with its own (left) value, so the
    event scan finds no zero of M_d − M_r a few ulps before the knot (it found one there,
    after 41 Brent steps, when it sampled the next piece's value at the knot)."""
    machine = reduce(load(SLIDER_CRANK))
    ew = machine.angle_only()
    angle, sign, _ = segments(ew.driving, ew.resisting, machine.cycle_angle).events()
    knot = 140 * DEG
    assert not np.any((angle > knot - 1e-9) & (angle < knot))
    assert np.any(angle == knot)


# -- the energy–mass extremes ------------------------------------------------------------


@pytest.mark.parametrize("frequency, rule", [(3, 4), (300, 4), (1000, 8), (2000, 8)])
def test_grid_delta_e_rule_is_checked(frequency, rule):
    """ΔE on the energy–mass grid for M_d = 1000 + 400 sin(nφ) against its closed form
    400 (1 − cos nφ)/n (less the balancing constant's excess over 1000 times φ), to 1e-14 of
    the work scale: up to n = 300 the 4-point Gauss–Legendre
    rule passes its check against the adaptive quadrature; at n = 1000 it is 6e-12 off, the
    check says so, and the grid takes the 8-point rule; at n = 2000 the adaptive quadrature
    from the cycle start cannot give a reference, and the grid takes the 8-point rule too."""
    driving = ExpressionTorque(Expression(f"1000 + 400*sin({frequency}*phi)"), 1.0, "test")
    ew = ExcessWork(driving, Constant(None), 2 * math.pi)
    sc = SliderCrank(0.1, 0.4)
    slider = sc.kinematics("slider")
    j_e = equivalent_inertia([Member("slider", 5.0, 0.0, slider.velocity_ratio, slider.angular_ratio)], 0.5)
    grid = energy_mass._grid(ew, j_e)
    assert grid.rule == rule
    # the balancing constant is the adaptive quadrature's (its work, 6283 J, to 1e-13: at n = 2000
    # it is 2.5e-11 N*m above 1000); the closed form takes it as it is
    exact = 400 * (1 - np.cos(frequency * grid.x)) / frequency - (ew.resisting.value - 1000) * grid.x
    scale = 400 * 2 * math.pi
    assert np.max(np.abs(grid.delta_e - exact)) <= 1e-14 * scale
    gl4 = grid._composite(energy_mass._GL4_NODES, energy_mass._GL4_WEIGHTS)
    off = np.max(np.abs(gl4 - exact)) / scale
    assert (off > 1e-13) == (rule == 8)  # the check is not idle: at n = 300 the 4-point rule is off


def _reference_extreme(book, c, find_max, at_knots):
    """Extreme over φ of c J(φ) − ΔE(φ): the textbook derivative c J' − M on a grid of 20 000 points
    per cycle in each piece, every sign change refined by scipy's Brent, the knots as candidates;
    values with ΔE from the knots plus scipy.integrate.quad."""
    s = 1.0 if find_max else -1.0
    candidates = []
    for k, (a, b) in enumerate(zip(book.knots[:-1], book.knots[1:])):
        n = max(int(20000 * (b - a) / book.cycle), 50)
        x = np.linspace(a, b, n + 1)[1:-1]

        def g(p, k=k):
            return c * book.inertia_slope(np.atleast_1d(p)) - book.net(np.atleast_1d(p), k)

        gx = g(x)
        for i in np.flatnonzero(np.sign(gx[:-1]) * np.sign(gx[1:]) < 0):
            root = optimize.brentq(lambda p: float(g(p)[0]), x[i], x[i + 1], xtol=1e-15, rtol=4 * EPS)
            candidates.append((root, k))
        candidates.append((a, k))
    candidates.append((book.knots[-1], len(book.knots) - 2))
    best = None
    for p, k in candidates:
        de = at_knots[k] + (quad(book.net, book.knots[k], p, (k,)) if p > book.knots[k] else 0.0)
        v = c * float(book.inertia(p)) - de
        if best is None or s * v > s * best[1]:
            best = (p, v)
    return best


def test_energy_mass_extremes_against_a_dense_grid_and_brent(scene):
    """J_F, E_0, the angles of ω_max and ω_min and A_max of the energy–mass closed form
    (docs/flywheel-design.md, section 6) against the textbook reference: J_F and E_0 to
    1e-10, the angles to 1e-9, A_max to 1e-11."""
    path, book, machine = scene
    result = analyse(load(path)).requirement.detail
    w_max, w_min = book.omega * (1 + book.delta / 2), book.omega * (1 - book.delta / 2)
    at_knots = book.delta_e_at_knots()
    upper = _reference_extreme(book, 0.5 * w_min**2, True, at_knots)
    lower = _reference_extreme(book, 0.5 * w_max**2, False, at_knots)
    j_required = (upper[1] - lower[1]) / (0.5 * (w_max**2 - w_min**2))
    e0 = lower[1] + 0.5 * w_max**2 * j_required
    assert_allclose(result.j_required, j_required, rtol=1e-10)
    assert_allclose(result.e0, e0, rtol=1e-10)
    assert_allclose([result.phi_omega_max, result.phi_omega_min], [lower[0], upper[0]], rtol=1e-9)
    de_max = -_reference_extreme(book, 0.0, False, at_knots)[1]
    de_min = -_reference_extreme(book, 0.0, True, at_knots)[1]
    assert abs(result.a_max - (de_max - de_min)) <= 1e-11 * book.work


def test_mean_inertia_against_quad(scene):
    """The cycle mean of J_e (adaptive Gauss–Kronrod on panels) against scipy.integrate.quad of the
    textbook J_e (epsrel 2e-14): 1e-13."""
    path, book, machine = scene
    result = energy_mass.energy_mass_requirement(machine.angle_only(), machine.j_machine, book.omega, book.delta)
    mean = integrate.quad(book.inertia, 0.0, book.cycle, epsabs=0, epsrel=2e-14, limit=400)[0] / book.cycle
    assert_allclose(result.j_machine_mean, mean, rtol=1e-13)


def test_forward_use_against_bisection_on_the_textbook(scene):
    """The δ of the constant-inertia flywheel (Newton on E_0 with the envelope derivative) against
    E_0 found by bisection to the last bit on the textbook model, its ω extremes from a dense grid
    refined by scipy's bounded minimizer: δ to 1e-9."""
    path, book, machine = scene
    result = energy_mass.energy_mass_requirement(machine.angle_only(), machine.j_machine, book.omega, book.delta)
    j_f = result.j_constant_inertia
    # ΔE on a grid with every knot: exact at the knots, cumulative Simpson inside each piece
    # (only to find where the extremes are; their values come from quad below)
    at_knots = book.delta_e_at_knots()
    phi, de = [], []
    for k, (a, b) in enumerate(zip(book.knots[:-1], book.knots[1:])):
        x = np.linspace(a, b, max(int(40000 * (b - a) / book.cycle), 8) + 1)
        phi.append(x[:-1])
        de.append(at_knots[k] + integrate.cumulative_simpson(book.net(x, k), x=x, initial=0.0)[:-1])
    phi, de = np.concatenate(phi + [book.knots[-1:]]), np.concatenate(de + [at_knots[-1:]])
    j_tot = j_f + book.inertia(phi)

    def extremes(e0):
        v = (e0 + de) / j_tot
        out = []
        for sign in (1, -1):
            i = int(np.argmax(sign * v))
            lo, hi = phi[max(i - 1, 0)], phi[min(i + 1, len(phi) - 1)]

            def neg(p):
                j = min(max(int(np.searchsorted(book.knots, p, side="right")) - 1, 0), len(book.knots) - 2)
                d = at_knots[j] + quad(book.net, book.knots[j], p, (j,))
                return -sign * (e0 + d) / (j_f + book.inertia(p))

            res = optimize.minimize_scalar(neg, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
            out.append(max(sign * v[i], -res.fun) * sign)
        return out

    def mismatch(e0):
        hi, lo = extremes(e0)
        return (math.sqrt(2 * hi) + math.sqrt(2 * max(lo, 0.0))) / (2 * book.omega) - 1

    guess = 0.5 * book.omega**2 * float(np.mean(j_tot)) - float(np.mean(de))
    a, b = 0.9 * guess, 1.1 * guess
    assert mismatch(a) < 0 < mismatch(b)
    e0 = optimize.brentq(mismatch, a, b, xtol=1e-13 * guess, rtol=4 * EPS)
    hi, lo = extremes(e0)
    w_hi, w_lo = math.sqrt(2 * hi), math.sqrt(2 * lo)
    assert_allclose(result.delta_constant_inertia, (w_hi - w_lo) / (0.5 * (w_hi + w_lo)), rtol=1e-9)
    assert (
        result.delta_constant_inertia
        == energy_mass.achieved_speed(machine.angle_only(), machine.j_machine, book.omega, j_f).delta
    )


def test_forward_use_refuses_a_flywheel_too_small_to_keep_the_speed():
    """With J_F far below the requirement the speed of slider-crank-press would reach zero:
    a ValueError, as before (the check at the lowest E_0 now runs where Newton comes down to it)."""
    machine = reduce(load(SLIDER_CRANK))
    with pytest.raises(ValueError, match="cannot keep the mean speed"):
        energy_mass.achieved_speed(machine.angle_only(), machine.j_machine, 0.05, 0.0)


def test_analysis_caches_do_not_travel_with_a_pickled_scene():
    """The pieces and evaluations the cycle analysis keeps on a scene's curves (arrays, and
    functions that do not pickle) are left behind when the scene is pickled to a worker: the
    pickle is the size it was before the analysis, up to the few bytes of an empty cache."""
    import pickle

    scene = load(PROBLEMS / "four-stroke-engine.toml")
    before = len(pickle.dumps(scene))
    analyse(scene)
    assert scene.driving.__dict__["_analysis_kept"]  # the analysis did keep pieces on it
    after = pickle.dumps(scene)
    assert len(after) <= before + 200
    assert pickle.loads(after).driving.__dict__["_analysis_kept"] == {}
