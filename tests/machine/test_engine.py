"""Engines from indicator data ([engine]), against published figures and independent computations.

References used here:
- Khurmi & Gupta, *Theory of Machines*, the turning-moment example of a
  horizontal engine (r = 0.3 m, l = 1.2 m, bore 0.5 m, 250 kg reciprocating,
  250 rpm, 0.35 N/mm² at 60° from the inner dead centre): 14.49 kN·m;
- the exact piston motion differentiated in 40-digit mpmath (mpmath.diff of
  the position x = r cos ψ + sqrt(l² − r² sin² ψ), no velocity formula);
- the cylinder's kinematics in numpy by complex-step differentiation of the
  positions (exact to round-off, no hand-derived velocity formula), the
  pressure by numpy.interp of the table as written in the scene file, and
  the cycle integrated by 10-point Gauss–Legendre on panels of at most 1°
  between the table's rows (the integrand is smooth there): the work
  ∮(p − p_crankcase) dV, the excess work ΔE(φ), Wittenbauer's closed form,
  the forward use with flyopt's flywheel, and the textbook's method;
- the sum over cylinders written out: a multi-cylinder engine against one
  cylinder at φ − θ_i.
"""

import math

import mpmath
import numpy as np
import pytest
import tomllib
from conftest import PROBLEMS, assert_published
from numpy.testing import assert_allclose
from scipy import optimize

import flyopt
from flyopt.analysis import EXTRAS
from flyopt.cycle.torque import PiecewiseLinear
from flyopt.machine.engine import Engine, engine_of, phase_table
from flyopt.machine.reduce import reduce
from flyopt.sizing.textbook import textbook_requirement

BAR = 1e5
FOUR_CYLINDER = PROBLEMS / "four-cylinder-engine.toml"


# -- Khurmi's turning moment ---------------------------------------------------------------

KHURMI = """
[machine]
speed = "250 rpm"
delta = 0.01
[engine]
cycle = "2-stroke"
cylinders = 1
bore = "0.5 m"
stroke = "0.6 m"
rod = "1.2 m"
reciprocating_mass = "250 kg"
pressure = [["0 deg", "0.35 N/mm^2"], ["360 deg", "0.35 N/mm^2"]]   # net of the back pressure
crankcase_pressure = "0 Pa"
[torque.resisting]
constant = "unknown"
"""


def test_khurmi_turning_moment_and_the_series_truncation(write_scene):
    """Khurmi & Gupta, *Theory of Machines*, turning moment of a horizontal engine: 14.49 kN·m.

    By hand, n = l/r = 4, ω = 2π 250/60 = 26.18 rad/s, θ = 60°:
    F_L = 0.35e6 π/4 0.5² = 68,722 N;
    F_I = m ω² r (cos θ + cos 2θ/n) = 250 × 685.4 × 0.3 × (0.5 − 0.125) = 19,277 N;
    F_P = F_L − F_I = 49,446 N;
    T = F_P r (sin θ + sin 2θ / (2 sqrt(n² − sin² θ))) = 49,446 × 0.3 × (0.8660 + 0.1109) = 14,491 N·m.

    The book's inertia force is the two-term series; flyopt's inertia torque
    is exact, −½ J_e'(φ) ω² = −m a_B (v_B/ω), so it differs from the book by
    the truncation of the series alone: the exact inertia force is
    m ω² (−x''(θ)) = 19,282.3 N (40-digit mpmath), 5.7 N more than the
    series, which moves T by −1.68 N·m. Tolerances: the textbook formula to
    its printed rounding; flyopt against mpmath to 1e-9 (the double-
    precision closed form against 40 digits, a few ulps of cancellation).
    """
    engine = flyopt.load(write_scene(KHURMI)).engine
    r, _l, m, n, bore, p = 0.3, 1.2, 250.0, 4.0, 0.5, 0.35e6  # l = 1.2 m enters through the scene
    omega = 250 * 2 * math.pi / 60
    theta = math.radians(60)
    f_gas = p * math.pi / 4 * bore**2
    f_series = m * omega**2 * r * (math.cos(theta) + math.cos(2 * theta) / n)
    t_textbook = (
        (f_gas - f_series) * r * (math.sin(theta) + math.sin(2 * theta) / (2 * math.sqrt(n * n - math.sin(theta) ** 2)))
    )
    assert_published(t_textbook / 1000, "14.49")

    mpmath.mp.dps = 40
    rr, ll, mm, ww = mpmath.mpf("0.3"), mpmath.mpf("1.2"), mpmath.mpf(250), mpmath.mpf(250) * 2 * mpmath.pi / 60
    fg = mpmath.mpf("0.35e6") * mpmath.pi / 4 * mpmath.mpf("0.5") ** 2
    th = mpmath.pi / 3

    def x(t):
        return rr * mpmath.cos(t) + mpmath.sqrt(ll**2 - (rr * mpmath.sin(t)) ** 2)

    x1, x2 = mpmath.diff(x, th), mpmath.diff(x, th, 2)
    # along +x (away from the crank): gas −F_L, d'Alembert force −m ω² x''; torque = force × dx/dθ
    t_exact = float((-fg - mm * ww**2 * x2) * x1)

    t_flyopt = float(engine.crank_effort(np.array([theta]), omega)[0])
    assert_allclose(t_flyopt, t_exact, rtol=1e-9)
    assert_allclose(t_flyopt - t_textbook, t_exact - t_textbook, atol=1e-9 * t_exact)
    assert -1.7 < t_exact - t_textbook < -1.6  # the series' truncation, as the docstring says
    # the gas torque alone and the inertia torque alone, each against its exact value
    assert_allclose(float(engine.gas_torque(np.array([theta]))[0]), float(-fg * x1), rtol=1e-12)
    assert_allclose(float(engine.inertia_torque(np.array([theta]), omega)[0]), float(-mm * ww**2 * x2 * x1), rtol=1e-9)


# -- independent kinematics of a cylinder (complex step) ---------------------------------------

STEP = 1e-30


def complex_step(f, psi):
    """df/dψ of a function analytic in ψ, exact to round-off: Im f(ψ + ih)/h."""
    return f(psi + 1j * STEP).imag / STEP


def cylinder_ratios(r, l, centre, psi):
    """v_piston/ω, |v_rod centre/ω|² and ω_rod/ω at the cylinder's own angle ψ, from positions only."""

    def x_piston(t):
        return r * np.cos(t) + np.sqrt(l * l - (r * np.sin(t)) ** 2)

    s = centre / l

    def rod_x(t):
        return (1 - s) * r * np.cos(t) + s * x_piston(t)

    def rod_y(t):
        return (1 - s) * r * np.sin(t)

    def beta(t):
        return -np.arcsin(r * np.sin(t) / l)

    return (
        complex_step(x_piston, psi),
        complex_step(rod_x, psi) ** 2 + complex_step(rod_y, psi) ** 2,
        complex_step(beta, psi),
    )


class Reference:
    """An engine's cycle computed in the test from the scene file's own numbers (no flyopt)."""

    def __init__(self, path):
        data = tomllib.loads(path.read_text())
        e = data["engine"]
        mm = {"83 mm": 0.083, "92 mm": 0.092, "145 mm": 0.145, "35 mm": 0.035}
        self.bore, stroke, self.l = mm[e["bore"]], mm[e["stroke"]], mm[e["rod"]]
        self.r = stroke / 2
        self.m_p = float(e["reciprocating_mass"].split()[0])
        self.m_r = float(e["rod_mass"].split()[0])
        self.c_r = mm[e["rod_centre"]]
        self.j_r = float(e["rod_inertia"].split()[0])
        self.p_cc = float(e["crankcase_pressure"].split()[0]) * BAR
        rows = np.array(e["pressure"], dtype=float)
        self.table_deg, self.table_p = rows[:, 0], rows[:, 1] * BAR
        self.cycle = 4 * math.pi
        self.theta = np.radians(e["firing_angles"])
        self.area = math.pi * self.bore**2 / 4
        m = data["machine"]
        self.omega = float(m["speed"].split()[0]) * 2 * math.pi / 60
        self.delta = float(m["delta"])
        g = 9.81
        shafts = {s["name"]: s for s in data["shaft"]}
        self.j_c = (
            float(shafts["crankshaft"]["inertia"].split()[0])
            + float(shafts["generator"]["gd2"].split()[0]) / (4 * g)
            + float(shafts["fan"]["inertia"].split()[0]) * shafts["fan"]["speed_ratio"] ** 2
        )
        self._panels()

    def pressure(self, psi_cycle, side):
        """Absolute pressure at the cycle angle (0..Φ); at a step the row before (left) or after (right)."""
        x, y = np.radians(self.table_deg), self.table_p
        if side == "right":  # np.interp takes the last of equal abscissae from the right
            return np.interp(psi_cycle, x, y)
        return -np.interp(-psi_cycle, -x[::-1], -y[::-1])

    def torque(self, phi, side="right"):
        """Gas torque Σ_i −(p − p_cc) A v_piston/ω at the cylinders' own angles [N*m]."""
        total = np.zeros_like(phi)
        for theta in self.theta:
            psi = phi - theta
            v = cylinder_ratios(self.r, self.l, self.c_r, psi)[0]
            p = self.pressure(np.mod(psi, self.cycle), side)
            total += -(p - self.p_cc) * self.area * v
        return total

    def inertia(self, phi):
        """J(φ) = J_c + Σ_i [m_p v_p² + m_r |v_r|² + J_r ω_r²] [kg*m^2]."""
        total = np.full_like(phi, self.j_c)
        for theta in self.theta:
            v, v_rod2, w_rod = cylinder_ratios(self.r, self.l, self.c_r, phi - theta)
            total += self.m_p * v * v + self.m_r * v_rod2 + self.j_r * w_rod * w_rod
        return total

    def _panels(self):
        """Breakpoints of every cylinder's pressure, split into panels of at most 1°."""
        knots = [0.0, self.cycle]
        for theta in self.theta:
            knots += list(np.mod(np.radians(self.table_deg) + theta, self.cycle))
        knots = np.unique(knots)
        edges = [knots[0]]
        for a, b in zip(knots[:-1], knots[1:]):
            count = max(1, math.ceil((b - a) / math.radians(1.0)))
            edges += list(a + (b - a) * np.arange(1, count + 1) / count)
        self.x = np.array(edges)
        nodes, weights = np.polynomial.legendre.leggauss(10)
        self._nodes, self._weights = 0.5 * (nodes + 1), 0.5 * weights
        h = np.diff(self.x)
        at = self.x[:-1, None] + h[:, None] * self._nodes
        work = (self.torque(at.ravel()).reshape(at.shape) * self._weights).sum(axis=1) * h
        self.work = math.fsum(work)
        self.mean_torque = self.work / self.cycle
        self.delta_e = np.concatenate(([0.0], np.cumsum(work - self.mean_torque * h)))
        self.j_mean = (
            math.fsum((self.inertia(at.ravel()).reshape(at.shape) * self._weights).sum(axis=1) * h) / self.cycle
        )

    def excess(self, phi):
        """ΔE(φ) = ∫_0^φ (M − M_mean) dφ: the panel's start plus Gauss–Legendre from there."""
        k = int(np.clip(np.searchsorted(self.x, phi, side="right") - 1, 0, len(self.x) - 2))
        a = self.x[k]
        at = a + (phi - a) * self._nodes
        return self.delta_e[k] + (phi - a) * float(((self.torque(at) - self.mean_torque) * self._weights).sum())

    def extreme(self, f, largest):
        """max or min over the cycle of f(φ) (given ΔE on the panel edges): the panels' edges, then
        Brent's bounded search around the best ones."""
        s = 1.0 if largest else -1.0
        values = s * f(self.x, self.delta_e)
        best = float(values.max())
        for k in np.argsort(values)[-6:]:
            lo, hi = self.x[max(k - 1, 0)], self.x[min(k + 1, len(self.x) - 1)]
            for a, b in ((lo, self.x[k]), (self.x[k], hi)):
                if b > a:
                    res = optimize.minimize_scalar(
                        lambda t: -s * f(np.array([t]), np.array([self.excess(t)]))[0],
                        bounds=(a, b),
                        method="bounded",
                        options={"xatol": 1e-13},
                    )
                    best = max(best, -res.fun)
        return s * best


@pytest.fixture(scope="module")
def four():
    scene = flyopt.load(FOUR_CYLINDER)
    return scene, flyopt.analyse(scene, extras=EXTRAS), Reference(FOUR_CYLINDER)  # the text report reads them


def test_the_reference_kinematics_are_those_of_mpmath():
    """The test's complex-step velocity ratio against 30-digit mpmath.diff of the position (1e-13)."""
    r, l = 0.046, 0.145
    mpmath.mp.dps = 30
    for psi in (0.3, 1.7, 4.0):
        exact = mpmath.diff(lambda t: r * mpmath.cos(t) + mpmath.sqrt(l**2 - (r * mpmath.sin(t)) ** 2), psi)
        assert_allclose(cylinder_ratios(r, l, 0.0, np.array([psi]))[0][0], float(exact), rtol=1e-13)


@pytest.mark.slow  # 7 s; the engine scenes' goldens and test_engine's closed forms run by default
def test_four_stroke_cycle_against_an_independent_integration(four):
    """The problem's four-cylinder engine over its 720° cycle, every figure against the test's own integration.

    Work per cycle = 4 ∮(p − p_cc) dV > 0 (the indicated work), the mean
    torque, A_max, the machine's J_c (the shafts' inertia moved to the
    crankshaft) and its cycle-mean J_e, and the exact flywheel by
    Wittenbauer's closed form (docs/flywheel-design.md, section 6) with ΔE
    and J_e(φ) of the test. Then the forward use: with flyopt's J_F the
    speed computed by the test, ω = sqrt(2 (E_0 + ΔE)/(J_F + J)), E_0 such
    that (ω_max + ω_min)/2 = ω_m, fluctuates by exactly the scene's δ.
    Tolerances: 1e-12 for the integrals and 1e-11 for J_F and δ (measured:
    2e-16, 2e-15, 0 and 4e-14; both sides integrate exactly to round-off, and
    the test's extremes are found by bounded Brent to 1e-13 rad, where the
    functions are flat).
    """
    scene, result, ref = four
    assert result.model == "energy_mass"
    assert_allclose(scene.j_constant, ref.j_c, rtol=1e-14)
    assert ref.work > 0
    assert_allclose(result.work_per_cycle, ref.work, rtol=1e-12)
    assert_allclose(result.resisting_torque, ref.mean_torque, rtol=1e-12)
    a_max = ref.extreme(lambda x, de: de, True) - ref.extreme(lambda x, de: de, False)
    assert_allclose(result.a_max, a_max, rtol=1e-12)
    assert_allclose(result.machine.j_mean(), ref.j_mean, rtol=1e-12)

    w, d = ref.omega, ref.delta
    w_max, w_min = w * (1 + d / 2), w * (1 - d / 2)
    upper = ref.extreme(lambda x, de: 0.5 * w_min**2 * ref.inertia(x) - de, True)
    lower = ref.extreme(lambda x, de: 0.5 * w_max**2 * ref.inertia(x) - de, False)
    j_f = (upper - lower) / (0.5 * (w_max**2 - w_min**2))
    assert_allclose(result.j_required, j_f, rtol=1e-11)

    def fluctuation(e0):
        hi = ref.extreme(lambda x, de: (e0 + de) / (result.j_required + ref.inertia(x)), True)
        lo = ref.extreme(lambda x, de: (e0 + de) / (result.j_required + ref.inertia(x)), False)
        return math.sqrt(2 * hi), math.sqrt(2 * lo)

    e_guess = 0.5 * w**2 * (result.j_required + ref.j_mean)
    e0 = optimize.brentq(lambda e: sum(fluctuation(e)) / 2 - w, 0.9 * e_guess, 1.1 * e_guess, xtol=1e-12)
    high, low = fluctuation(e0)
    assert_allclose((high - low) / w, d, rtol=1e-11)


def test_textbook_method_against_an_independent_computation(four):
    """The textbook's flywheel (crank effort at ω_m on the constant mean J_e) and how far it is off.

    The inertia torque −½ J_e' ω_m² integrates to −½ ω_m² (J_e(φ) − J_e(0)), so
    the test's ΔE of the crank effort is ΔE(φ) − ½ ω_m² (J(φ) − J(0)) with no
    derivative taken; J_F = A_max/(ω_m² δ) − mean J_e (1e-11; measured 1e-14
    on A_max, 4e-14 on J_F). The report's
    line gives it and its difference from the exact J_F in percent, which
    the test recomputes from its own two flywheels.
    """
    from flyopt.report.text import analysis_report

    scene, result, ref = four
    w, d = ref.omega, ref.delta
    j0 = float(ref.inertia(np.array([0.0]))[0])

    def effort(x, de):
        return de - 0.5 * w**2 * (ref.inertia(x) - j0)

    a_max = ref.extreme(effort, True) - ref.extreme(effort, False)
    textbook = textbook_requirement(result.machine)
    assert_allclose(textbook.a_max, a_max, rtol=1e-11)
    assert_allclose(textbook.j_machine_mean, ref.j_mean, rtol=1e-12)
    assert_allclose(textbook.j_required, a_max / (w**2 * d) - ref.j_mean, rtol=1e-11)

    w_max, w_min = w * (1 + d / 2), w * (1 - d / 2)
    upper = ref.extreme(lambda x, de: 0.5 * w_min**2 * ref.inertia(x) - de, True)
    lower = ref.extreme(lambda x, de: 0.5 * w_max**2 * ref.inertia(x) - de, False)
    exact = (upper - lower) / (0.5 * (w_max**2 - w_min**2))
    off = (a_max / (w**2 * d) - ref.j_mean - exact) / exact
    assert abs(off) > 1e-3  # the methods really differ here (3000 rpm: large inertia forces)
    text = analysis_report(result)
    assert f"{100 * off:+.3g} %" in text
    assert "Engine: 4 cylinders, 4-stroke, cycles starting at 0, 180, 540, 360 deg" in text
    assert engine_of(result.machine) is scene.engine


def test_inertia_of_the_cylinders_against_mpmath(four):
    """J_e(φ) and the inertia torque −½ J_e'(φ) ω² of the problem's engine, phases and rods included.

    Reference: J(φ) of the test's complex-step ratios (1e-13), and its
    derivative by 30-digit mpmath.diff of the kinetic energy written from
    positions (1e-9), at angles spread over the cycle.
    """
    scene, result, ref = four
    engine = scene.engine
    phi = np.array([0.1, 1.3, 2.9, 4.4, 6.0, 7.7, 9.9, 12.3])
    assert_allclose(engine.inertia(phi) + ref.j_c, ref.inertia(phi), rtol=1e-13)
    mpmath.mp.dps = 30
    r, l, s = mpmath.mpf(ref.r), mpmath.mpf(ref.l), mpmath.mpf(ref.c_r) / mpmath.mpf(ref.l)

    def kinetic(t):
        total = 0
        for theta in ref.theta:

            def positions(u):
                psi = u - mpmath.mpf(theta)
                xb = r * mpmath.cos(psi) + mpmath.sqrt(l**2 - (r * mpmath.sin(psi)) ** 2)
                return (
                    xb,
                    (1 - s) * r * mpmath.cos(psi) + s * xb,
                    (1 - s) * r * mpmath.sin(psi),
                    -mpmath.asin(r * mpmath.sin(psi) / l),
                )

            v = [mpmath.diff(lambda u, k=k: positions(u)[k], t) for k in range(4)]
            total += ref.m_p * v[0] ** 2 + ref.m_r * (v[1] ** 2 + v[2] ** 2) + ref.j_r * v[3] ** 2
        return total

    for t in phi[:4]:
        slope = mpmath.diff(kinetic, mpmath.mpf(t))
        assert_allclose(
            float(engine.inertia_torque(np.array([t]), ref.omega)[0]), float(-0.5 * ref.omega**2 * slope), rtol=1e-9
        )


# -- many cylinders are one cylinder, shifted ---------------------------------------------------


def _engine(firing, cycle="4-stroke", mass=0.65, rod_mass=0.45, pressure=None):
    if pressure is None:
        deg = [0, 180, 180, 300, 360, 375, 450, 540, 540, 720]
        bar = [0.9, 0.9, 1.0, 3.5, 20.0, 60.0, 9.0, 3.8, 1.15, 1.15]
        if cycle == "2-stroke":
            deg, bar = [0, 15, 100, 140, 140, 220, 300, 360], [20.0, 55.0, 6.0, 3.0, 1.1, 1.2, 8.0, 20.0]
        pressure = PiecewiseLinear(np.radians(deg), np.array(bar) * BAR)
    return Engine(
        cycle,
        tuple(np.radians(firing)),
        0.083,
        0.092,
        0.145,
        mass,
        pressure,
        1.0e5,
        rod_mass,
        0.035 if rod_mass else 0.0,
        0.0012 if rod_mass else 0.0,
    )


@pytest.mark.parametrize(
    "cycle, firing",
    [
        ("4-stroke", [0, 180, 540, 360]),
        ("4-stroke", [0, 90, 270, 450, 630, 500]),  # uneven, six cylinders
        ("2-stroke", [0, 120, 240]),
        ("2-stroke", [0, 0]),  # two cylinders in step
    ],
)
def test_multicylinder_engine_is_the_sum_of_its_cylinders_shifted(cycle, firing):
    """Gas torque, J_e and crank effort of n cylinders = Σ_i one cylinder at (φ − θ_i) mod Φ, to 1e-12.

    The tolerance is relative to the largest value over the angles: the two
    sides round differently (a shifted table against a shifted angle).
    """
    many, one = _engine(firing, cycle), _engine([0], cycle)
    cycle_angle = many.cycle_angle
    phi = np.random.default_rng(7).uniform(0, cycle_angle, 2000)
    omega = 3000 * math.pi / 30
    for what in ("gas_torque", "inertia", "crank_effort"):
        args = (omega,) if what == "crank_effort" else ()
        got = getattr(many, what)(phi, *args)
        expected = sum(getattr(one, what)(np.mod(phi - theta, cycle_angle), *args) for theta in many.firing_angles)
        assert_allclose(got, expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))


def test_phase_table_is_the_table_at_the_shifted_angle():
    """phase_table(f, s)(φ) = f((φ − s) mod Φ) on both sides of every step, for shifts on and off the rows."""
    cycle = 4 * math.pi
    rng = np.random.default_rng(3)
    angles = np.sort(np.concatenate(([0.0, cycle], rng.uniform(0, cycle, 20))))
    angles = np.sort(np.concatenate((angles, angles[[5, 12]])))  # two steps
    table = PiecewiseLinear(angles, rng.uniform(-5, 5, len(angles)))
    for shift in (0.0, 1.0, cycle - angles[5], cycle - angles[-2], math.pi, cycle - 1e-9):
        x, y = phase_table(table, shift, cycle)
        assert x[0] == 0.0 and x[-1] == cycle and np.all(np.diff(x) >= 0)
        shifted = PiecewiseLinear(x, y)
        phi = rng.uniform(0, cycle, 500)
        assert_allclose(shifted.limits(phi)[1], table.limits(np.mod(phi - shift, cycle))[1], rtol=0, atol=1e-12)


def test_engine_without_moving_masses_is_its_gas_torque_alone(write_scene):
    """Reciprocating masses and rods of zero mass: the inertia is J_c, the energy model is exact, and the
    net torque is the test's gas torque less its mean (1e-12); A_max and J_F from the test's integration."""
    text = FOUR_CYLINDER.read_text()
    for old, new in (
        ('"0.65 kg"', '"0 kg"'),
        ('rod_mass = "0.45 kg"', "# no rod"),
        ('rod_centre = "35 mm"', "#"),
        ('rod_inertia = "0.0012 kg*m^2"', "#"),
    ):
        assert old in text
        text = text.replace(old, new)
    scene = flyopt.load(write_scene(text))
    result = flyopt.analyse(scene)
    ref = Reference(FOUR_CYLINDER)
    ref.m_p = ref.m_r = ref.j_r = 0.0
    assert result.model == "energy" and not result.machine.variable_inertia
    assert result.machine.j_machine == pytest.approx(ref.j_c, rel=1e-14)
    phi = np.random.default_rng(5).uniform(0, 4 * math.pi, 1000)
    balanced = result.machine.angle_only()
    net = balanced.net_torque(phi)
    expected = ref.torque(phi) - ref.mean_torque
    assert_allclose(net, expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))
    a_max = ref.extreme(lambda x, de: de, True) - ref.extreme(lambda x, de: de, False)
    assert_allclose(result.a_max, a_max, rtol=1e-12)  # measured 2e-15
    assert_allclose(result.j_required, a_max / (ref.omega**2 * ref.delta) - ref.j_c, rtol=1e-12)
    # with no moving masses the textbook's method is the energy method, and the report has no engine block
    assert_allclose(textbook_requirement(result.machine).j_required, result.j_required, rtol=1e-12)
    from flyopt.analysis import complete
    from flyopt.report.text import analysis_report

    assert "Engine:" not in analysis_report(complete(result))  # the report reads what the solve computed


def test_engine_scene_reads_into_members_and_the_machine(four):
    """The [engine] is members of the scene (pistons with the gas force, rods), and the machine's driving
    torque is the engine's gas torque (the resisting torque is the unknown constant)."""
    scene, result, ref = four
    names = [m.name for m in scene.members]
    assert names == [f"cylinder {k} {part}" for k in (1, 2, 3, 4) for part in ("piston", "rod")]
    assert scene.cycle_angle == 4 * math.pi
    machine = reduce(scene)
    phi = np.linspace(0.05, 12.5, 300)
    assert_allclose(machine.driving(phi), scene.engine.gas_torque(phi), rtol=0, atol=1e-9)
    assert_allclose(scene.engine.gas_torque(phi), ref.torque(phi), rtol=0, atol=1e-12 * np.max(np.abs(ref.torque(phi))))


def test_pressure_from_a_csv_file_equals_the_inline_table(write_scene, tmp_path):
    """pressure_file with a header and the engine's units gives the same engine as the inline table."""
    data = tomllib.loads(FOUR_CYLINDER.read_text())
    rows = data["engine"]["pressure"]
    (tmp_path / "indicator.csv").write_text("angle,pressure\n" + "".join(f"{a},{p}\n" for a, p in rows))
    text = FOUR_CYLINDER.read_text()
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    path = write_scene(text[:start] + 'pressure_file = "indicator.csv"\n' + text[end:])
    inline, from_file = flyopt.load(FOUR_CYLINDER).engine, flyopt.load(path).engine
    assert_allclose(from_file.pressure.angles, inline.pressure.angles, rtol=0, atol=0)
    assert_allclose(from_file.pressure.values, inline.pressure.values, rtol=0, atol=0)


def test_plain_pascals_are_read_as_the_same_table_in_bar(write_scene, tmp_path):
    """A table of plain numbers is pascals (no pressure_unit): the same indicator diagram written in Pa, inline
    and from a CSV file, gives the engine the table in bar gives (the refusal of a unit left out does not touch
    it); its largest, 6 MPa, is far above the crankcase's 1 bar."""
    data = tomllib.loads(FOUR_CYLINDER.read_text())
    rows = [(a, round(p * 1e5, 6)) for a, p in data["engine"]["pressure"]]
    (tmp_path / "indicator.csv").write_text("angle,pressure\n" + "".join(f"{a},{p}\n" for a, p in rows))
    text = FOUR_CYLINDER.read_text().replace('pressure_unit = "bar"\n', "")
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    inline = write_scene(text[:start] + f"pressure = {[list(r) for r in rows]}\n" + text[end:], "inline.toml")
    from_file = write_scene(text[:start] + 'pressure_file = "indicator.csv"\n' + text[end:], "file.toml")
    reference = flyopt.load(FOUR_CYLINDER).engine.pressure
    for path in (inline, from_file):
        pressure = flyopt.load(path).engine.pressure
        assert_allclose(pressure.values, reference.values, rtol=1e-15, atol=0)


def test_a_csv_indicator_diagram_in_bar_without_its_unit_is_refused(main_cli, write_scene, tmp_path):
    """A CSV file's numbers are plain: in bar without pressure_unit they are pascals, refused on one line."""
    data = tomllib.loads(FOUR_CYLINDER.read_text())
    (tmp_path / "p.csv").write_text("angle,pressure\n" + "".join(f"{a},{p}\n" for a, p in data["engine"]["pressure"]))
    text = FOUR_CYLINDER.read_text().replace('pressure_unit = "bar"\n', "")
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    path = write_scene(text[:start] + 'pressure_file = "p.csv"\n' + text[end:])
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == "" and len(err.splitlines()) == 1, err
    assert "engine.pressure_file: " in err and "the largest, 60 Pa, does not rise above" in err, err


def test_default_firing_angles_are_evenly_spaced(write_scene):
    text = FOUR_CYLINDER.read_text().replace("firing_angles = [0, 180, 540, 360]\n", "")
    engine = flyopt.load(write_scene(text)).engine
    assert_allclose(np.degrees(engine.firing_angles), [0, 180, 360, 540], rtol=0, atol=1e-12)


# -- bad values: exit 2, one line naming the file and the field --------------------------------


@pytest.mark.parametrize(
    "old, new, field, match",
    [
        ('rod = "145 mm"', 'rod = "40 mm"', "engine.rod", "not longer than the crank radius, stroke/2 = 46 mm"),
        ('rod = "145 mm"', 'rod = "46 mm"', "engine.rod", "not longer than the crank radius"),
        ("[180, 1.000]", "[180, -1.000]", "engine.pressure[7]", "absolute pressures, which cannot be negative"),
        ("[0, 180, 540, 360]", "[0, 180, 720, 360]", "engine.firing_angles[2]", r"outside the cycle.*720 deg"),
        ("[0, 180, 540, 360]", "[-10, 180, 540, 360]", "engine.firing_angles[0]", "outside the cycle"),
        ("[0, 180, 540, 360]", "[0, 180, 540]", "engine.firing_angles", "a list of 4 angles"),
        ('cycle = "4-stroke"', 'cycle = "3-stroke"', "engine.cycle", "did you mean"),
        ('cycle = "4-stroke"', 'cycle = "four-stroke"', "engine.cycle", "allowed: '4-stroke'"),
        ("cylinders = 4", "cylinders = 0", "engine.cylinders", "from 1 to 64"),
        ("cylinders = 4", "cylinders = 4.0", "engine.cylinders", "whole number"),
        ("cylinders = 4", "cylinders = 1000000000", "engine.cylinders", "from 1 to 64"),
        ('bore = "83 mm"', 'bore = "-83 mm"', "engine.bore", "positive length"),
        ('bore = "83 mm"', 'bore = "83 kg"', "engine.bore", "wrong dimension"),
        ('stroke = "92 mm"', 'stroke = "0 mm"', "engine.stroke", "positive length"),
        ('reciprocating_mass = "0.65 kg"', 'reciprocating_mass = "-0.65 kg"', "engine.reciprocating_mass", ">= 0"),
        ('reciprocating_mass = "0.65 kg"', "", "engine.reciprocating_mass", "is missing"),
        ('rod_centre = "35 mm"', 'rod_centre = "150 mm"', "engine.rod_centre", "not between the pins"),
        ('rod_centre = "35 mm"', "", "engine.rod_centre", "come together"),
        ('rod_mass = "0.45 kg"', "", "engine.rod_centre", "give rod_mass with it"),
        ('rod_inertia = "0.0012 kg*m^2"', 'rod_inertia = "-1 kg*m^2"', "engine.rod_inertia", ">= 0"),
        ('crankcase_pressure = "1 bar"', 'crankcase_pressure = "-1 bar"', "engine.crankcase_pressure", ">= 0"),
        ('pressure_unit = "bar"', 'pressure_unit = "m"', "engine.pressure_unit", "wrong dimension"),
        ("[690, 1.150], [720, 1.150],", "[690, 1.150],", "engine.pressure", "does not close"),
        ('pressure_unit = "bar"', 'pressure_unit = "bar"\npressure_file = "p.csv"', "engine.pressure", "given both"),
        # the unit left out: bar read as pascals (below the crankcase's 1 bar), or with a crankcase of none
        (
            'pressure_unit = "bar"\n',
            "",
            "engine.pressure",
            r"largest, 60 Pa, does not rise above the crankcase's 100000 Pa, .*: give pressure_unit, "
            r'e\.g\. "bar" or "MPa"$',  # not "Pa if pascals are meant": a cylinder that never pushes is no engine
        ),
        (
            'crankcase_pressure = "1 bar"\nangle_unit = "deg"\npressure_unit = "bar"\n',
            'crankcase_pressure = "0 bar"\nangle_unit = "deg"\n',
            "engine.pressure",
            r"largest, 60 Pa, is below 1000 Pa.*give pressure_unit",
        ),
        ('cycle = "4-stroke"', 'cycle = "4-stroke"\nstrokes = 4', "engine.strokes", "unknown key"),
        ("delta = 0.005", 'delta = 0.005\ncycle = "360 deg"', "machine.cycle", "leave machine.cycle out"),
        (
            "[torque.resisting]",
            '[mechanism]\nkind = "slider_crank"\ncrank = "46 mm"\nrod = "145 mm"\n[torque.resisting]',
            "mechanism",
            "brings its own slider-cranks",
        ),
        (
            "[torque.resisting]",
            '[[member]]\nname = "cylinder 1 piston"\nmass = "1 kg"\n[torque.resisting]',
            "member[0].name",
            "name of a member of the",
        ),
        (
            '[torque.resisting]\nconstant = "unknown"',
            '[torque.net]\nareas = ["10 J", "-10 J"]',
            "torque.net",
            "an \\[engine\\] needs torque curves",
        ),
    ],
)
def test_bad_engine_values_exit_2_with_one_line(main_cli, write_scene, old, new, field, match):
    import re

    text = FOUR_CYLINDER.read_text()
    assert old in text
    path = write_scene(text.replace(old, new, 1))
    for command in ("check", "solve"):
        status, out, err = main_cli(command, path)
        lines = err.splitlines()
        assert status == 2 and out == "" and len(lines) == 1, (status, err[-2000:])
        assert str(path) in lines[0] and f"{field}:" in lines[0], lines[0]
        assert re.search(match, lines[0]), lines[0]
        assert "Traceback" not in err


def test_negative_pressure_in_a_csv_file_names_its_line(main_cli, write_scene, tmp_path):
    (tmp_path / "p.csv").write_text("angle,pressure\n0,1\n# a comment\n360,-0.5\n720,1\n")
    text = FOUR_CYLINDER.read_text()
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    path = write_scene(text[:start] + 'pressure_file = "p.csv"\n' + text[end:])
    status, out, err = main_cli("check", path)
    assert status == 2 and len(err.splitlines()) == 1
    assert "engine.pressure_file: " in err and "p.csv line 4: the pressure -0.5 bar is below 0" in err, err


def test_phased_cylinders_are_the_same_in_casadi_and_numpy():
    """J_e, dJ_e/dφ, the gas torque and the inertia torque of phased cylinders: CasADi against numpy (1e-12).

    The periodic (dynamic) model and the numpy analysis must see one engine."""
    import casadi as ca

    from flyopt.machine.engine import InertiaTorque
    from flyopt.machine.mechanism import equivalent_inertia, equivalent_torque

    engine = _engine([0, 90, 270, 450, 630, 500])
    phi = ca.SX.sym("phi")
    inertia, torque = equivalent_inertia(engine.members), equivalent_torque(engine.members)
    inertia_torque = InertiaTorque(inertia, 300.0)
    f = ca.Function(
        "f",
        [phi],
        [inertia.casadi(phi), inertia.casadi_derivative(phi), torque.casadi(phi), inertia_torque.casadi(phi)],
    )
    angles = np.random.default_rng(2).uniform(0, engine.cycle_angle, 50)
    got = np.array([[float(v) for v in f(a)] for a in angles])
    expected = np.column_stack([inertia(angles), inertia.derivative(angles), torque(angles), inertia_torque(angles)])
    for k in range(4):
        assert_allclose(got[:, k], expected[:, k], rtol=0, atol=1e-12 * np.max(np.abs(expected[:, k])))


def test_the_plain_pressure_floor_is_the_plain_stress_bands_top():
    """With no crankcase pressure, a plain table is refused up to (not including) the top of units.PLAIN_SLIPS'
    stress band, as a plain stress is: 1 kPa is read as written."""
    from flyopt.errors import SceneError
    from flyopt.io.engine_section import _check_plain_pressures
    from flyopt.units import PLAIN_SLIPS

    top = PLAIN_SLIPS["stress"][1]
    _check_plain_pressures(top, 0.0, "engine.pressure")
    with pytest.raises(SceneError, match="is below 1000 Pa"):
        _check_plain_pressures(0.999 * top, 0.0, "engine.pressure")


def test_a_table_in_bar_with_one_cell_given_its_unit_is_refused_on_that_line(main_cli, write_scene):
    """Without pressure_unit, "60 bar" written on the peak alone left the other cells, written in bar, to be
    read as pascals: a cylinder at vacuum but for one point, accepted. The largest plain cell is named."""
    text = FOUR_CYLINDER.read_text().replace('pressure_unit = "bar"\n', "")
    assert "[375, 60.000]" in text
    path = write_scene(text.replace("[375, 60.000]", '[375, "60 bar"]'))
    for command in ("check", "solve"):
        status, out, err = main_cli(command, path)
        assert status == 2 and out == "" and len(err.splitlines()) == 1, err
        assert "engine.pressure[22]: the pressure 51.297 is a plain number beside cells that carry their unit" in err
        assert "51.297 Pa" in err and 'give each cell its unit, or give pressure_unit (e.g. "bar")' in err, err


def test_plain_pascals_beside_cells_with_their_unit_are_read_as_written(write_scene):
    """The rule refuses only plain cells no cylinder pressure can be: the table in bar with its low cells
    written as plain pascals and the rest with their unit is the table in bar."""
    data = tomllib.loads(FOUR_CYLINDER.read_text())
    rows = [[a, round(p * 1e5, 6) if p < 2 else f"{p} bar"] for a, p in data["engine"]["pressure"]]
    assert any(isinstance(p, float) for _, p in rows) and any(isinstance(p, str) for _, p in rows)
    text = FOUR_CYLINDER.read_text().replace('pressure_unit = "bar"\n', "")
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    body = ", ".join(f'[{a}, "{p}"]' if isinstance(p, str) else f"[{a}, {p}]" for a, p in rows)
    path = write_scene(text[:start] + f"pressure = [{body}]\n" + text[end:])
    reference = flyopt.load(FOUR_CYLINDER).engine.pressure
    assert_allclose(flyopt.load(path).engine.pressure.values, reference.values, rtol=1e-15, atol=0)


def _mixed(write_scene, cells, name):
    """four-cylinder-engine with its indicator table written as ``cells`` (one TOML cell per row) and no
    pressure_unit."""
    text = FOUR_CYLINDER.read_text().replace('pressure_unit = "bar"\n', "")
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    angles = [a for a, _ in tomllib.loads(FOUR_CYLINDER.read_text())["engine"]["pressure"]]
    body = ", ".join(f"[{a}, {c}]" for a, c in zip(angles, cells))
    return write_scene(text[:start] + f"pressure = [{body}]\n" + text[end:], name)


def test_a_table_in_kpa_with_its_peak_alone_in_kpa_is_refused_at_the_jump(main_cli, write_scene):
    """The same slip in kPa: the plain cells (kPa meant) are pascals of 90-5130 Pa, over 1 kPa, but the peak's
    neighbours are a thousandth of it; no cylinder pressure changes 300-fold between two points (the table's own
    largest step is 3.3-fold)."""
    pressures = [p for _, p in tomllib.loads(FOUR_CYLINDER.read_text())["engine"]["pressure"]]
    cells = [f'"{p * 100:g} kPa"' if p == 60 else f"{p * 100:g}" for p in pressures]
    status, out, err = main_cli("check", _mixed(write_scene, cells, "kpa.toml"))
    assert status == 2 and out == "" and len(err.splitlines()) == 1, err
    assert "engine.pressure[20]: the pressure 4665.1 is a plain number" in err, err
    assert "the point beside it, '6000 kPa', differs from it 1.29e+03-fold" in err, err


def test_plain_zeros_beside_cells_with_their_unit_are_zeros_in_any_unit(write_scene):
    """A plain 0 is 0 in every unit: beside cells in bar it is read (as "0 bar" is), not taken for a slip."""
    pressures = [p for _, p in tomllib.loads(FOUR_CYLINDER.read_text())["engine"]["pressure"]]
    cells = ["0" if k == 0 else f'"{p} bar"' for k, p in enumerate(pressures)]
    values = flyopt.load(_mixed(write_scene, cells, "zero.toml")).engine.pressure.values
    reference = flyopt.load(FOUR_CYLINDER).engine.pressure.values
    assert values[0] == 0.0 and np.array_equal(values[1:], reference[1:])
