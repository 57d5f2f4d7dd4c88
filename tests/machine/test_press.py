"""Presses and shears from their process data ([press], issue 14 part 2).

A [press] table is rewritten into an ordinary scene (flyopt.io.press) and
then runs through flyopt's one analysis. The references here are the
textbook's published figures (Khurmi's punching press), closed forms written
out in the tests (the work of a force table, the energy indicator of a ramp
load, ½ F_max t of punching), an integration of the equation of motion in
time by scipy, and a second, hand-written scene with the same torques.
"""

import copy
import math
import re

import numpy as np
import pytest
from conftest import PROBLEMS, assert_published, names_field
from numpy.testing import assert_allclose
from scipy.integrate import quad, solve_ivp
from test_input_failures import assert_refused, cli  # noqa: F401 (cli is a fixture)

import flyopt
from flyopt.analysis import EXTRAS

RPM = 2 * math.pi / 60

KHURMI = """
title = "Khurmi punching press"
[press]
strokes_per_minute = 12
energy_per_stroke = "15 kJ"
working_time = 2
flywheel_speed = "225 rpm"
slowdown = {slowdown!r}
"""


def khurmi(write_scene, slowdown=1 / 9, extra=""):
    """Khurmi's press as a scene with the issue's keys (slowdown = 1/9 is 225 -> 200 rpm exactly)."""
    return flyopt.load(write_scene(KHURMI.format(slowdown=slowdown) + extra))


def flywheel(analysis):
    return next(s for s in analysis.shafts if s.name == "flywheel")


# -- Khurmi's punching press ---------------------------------------------------


def test_khurmi_punching_press_720_holes_an_hour():
    """Khurmi's punching press (R.S. Khurmi & J.K. Gupta, the flywheel examples: the
    punching press of 720 holes an hour): 15 kN·m a hole, 2 s a punch, the flywheel from
    225 down to 200 rpm, radius of gyration 0.5 m. Published: motor 3 kW, flywheel 618 kg.

    By hand: 720 holes an hour is 12 a minute, a period of 5 s. The motor supplies the
    15 kJ evenly over the 5 s, 15 x 2/5 = 6 kJ during the 2 s punch, so the flywheel
    supplies 15 - 6 = 9 kJ. With w1 = 225 rpm = 23.562 rad/s and w2 = 200 rpm =
    20.944 rad/s: J = 9000 / (1/2 (w1^2 - w2^2)) = 9000 / 58.258 = 154.48 kg·m^2, and
    m = J/k^2 = 154.48/0.25 = 617.9 kg, printed 618 kg. Motor: 15 kJ / 5 s = 3 kW.

    problems/press-from-process.toml runs through flyopt's ordinary analysis and design.
    """
    scene = flyopt.load(PROBLEMS / "press-from-process.toml")
    solution = flyopt.solve(scene)
    result = solution.analysis
    w1, w2 = 225 * RPM, 200 * RPM
    j_khurmi = 9000 / (0.5 * (w1**2 - w2**2))  # the textbook's J, in floats
    assert_allclose(result.a_max, 15000 * (1 - 2 / 5), rtol=1e-13)  # the flywheel's 9 kJ
    assert_allclose(flywheel(result).j_required, j_khurmi, rtol=1e-12)
    assert_published(flywheel(result).j_required / 0.5**2, "618")
    assert_allclose(result.power, 15000 / 5, rtol=1e-13)
    assert_allclose(result.motor_power, 15000 / 5, rtol=1e-13)  # no efficiency given: 1
    assert_published(result.power / 1000, "3")
    # the thin rim of mean diameter 2k = 1 m is m = J/k^2: the textbook's mass through the design
    assert solution.design.best.shaft == "flywheel"
    assert_allclose(solution.design.best.mass, j_khurmi / 0.5**2, rtol=1e-9)
    assert_published(solution.design.best.mass, "618")


def test_the_report_states_khurmis_3_kw_motor():
    """The text report's mean driving power and motor power lines say 3 kW."""
    from flyopt.report.text import analysis_report

    text = analysis_report(flyopt.analyse(flyopt.load(PROBLEMS / "press-from-process.toml"), extras=EXTRAS))
    lines = text.splitlines()
    assert re.search(r"^  mean driving power +3 kW$", text, re.M), lines
    assert re.search(r"^  motor power +3 kW \(efficiency 1\)$", text, re.M), lines


def test_the_issues_slowdown_gives_khurmis_press(write_scene):
    """The issue's form, slowdown = (w_top - w_bottom)/w_top: 1/9 is Khurmi's 225 -> 200 rpm,
    the same J as the problem scene's flywheel_speed_min = "200 rpm" (to round-off).

    The issue writes the slowdown rounded, 0.111: then w_bottom = 225 x 0.889 = 200.025 rpm
    and 1 - (1 - s)^2 = 0.209679 instead of 17/81 = 0.209877, so J and m are 1.00094 times
    Khurmi's: 618.5 kg, which no longer rounds to the printed 618. The test checks that value
    against the closed form J = A_max / (1/2 w1^2 (1 - (1 - s)^2)), not against 618.
    """
    exact = flyopt.analyse(khurmi(write_scene))
    problem = flyopt.analyse(flyopt.load(PROBLEMS / "press-from-process.toml"))
    assert_allclose(flywheel(exact).j_required, flywheel(problem).j_required, rtol=1e-13)
    assert_published(flywheel(exact).j_required / 0.25, "618")
    rounded = flyopt.analyse(khurmi(write_scene, 0.111))
    w1 = 225 * RPM
    j = 9000 / (0.5 * w1**2 * (1 - (1 - 0.111) ** 2))
    assert_allclose(flywheel(rounded).j_required, j, rtol=1e-12)
    assert_published(flywheel(rounded).j_required / 0.25, "618.5")


# -- the slowdown, delta and the flywheel shaft ---------------------------------------


@pytest.mark.parametrize("slowdown", [0.02, 1 / 9, 0.25, 0.6, 0.95])
def test_the_solved_cycle_reproduces_the_flywheels_top_and_bottom_speed(write_scene, slowdown):
    """ω_max and ω_min of the analysis (section 2's ω_m (1 ± δ/2)) on the flywheel shaft are
    the top speed, 225 rpm, and 225 (1 - s) rpm: δ = 2s/(2 - s) and the speed ratio of the mean
    speeds are right for any slowdown. Their ratio gives s back; their angles are the start
    and the end of the working stroke."""
    result = flyopt.analyse(khurmi(write_scene, slowdown))
    ratio = flywheel(result).speed_ratio
    assert_allclose(result.omega_max * ratio, 225 * RPM, rtol=1e-14)
    assert_allclose(result.omega_min * ratio, 225 * (1 - slowdown) * RPM, rtol=1e-13)
    assert_allclose(1 - result.omega_min / result.omega_max, slowdown, rtol=1e-13)
    assert_allclose(result.omega_mean, 12 * RPM, rtol=1e-15)
    assert result.angle_omega_max in (0.0, 2 * math.pi)
    assert_allclose(result.angle_omega_min, 2 * math.pi * 2 / 5, rtol=1e-14)


@pytest.mark.parametrize("slowdown", [1 / 9, 0.5])
def test_a_simulation_in_time_slows_the_flywheel_from_225_to_its_bottom_speed(write_scene, slowdown):
    """The equation of motion J dω/dt = M_d - M_r(φ), dφ/dt = ω, integrated in time by scipy
    (RK45 at rtol 1e-12) with flyopt's J_F and torques written here (M_d = E/2π, M_r = E/θ_w
    over the working angle): started at the top speed at the start of the working stroke,
    the flywheel shaft turns at 225 (1 - s) rpm when the working stroke ends and at 225 rpm
    again after one turn. Agreement to 1e-9 (the integrator's tolerance)."""
    result = flyopt.analyse(khurmi(write_scene, slowdown))
    ratio, j = flywheel(result).speed_ratio, result.j_required
    energy, theta = 15000.0, 2 * math.pi * 2 / 5
    driving = energy / (2 * math.pi)

    def run(load, start, angle):
        """Integrate with a constant load [N*m] from ``start`` (t, φ, ω) until φ reaches ``angle``;
        each piece is smooth, so the integrator never steps across the load's step."""

        def reached(t, y):
            return y[0] - angle

        reached.terminal = True
        t0, phi, omega = start
        sol = solve_ivp(
            lambda t, y: [y[1], (driving - load) / j],
            (t0, t0 + 100),
            [phi, omega],
            events=reached,
            rtol=1e-12,
            atol=1e-14,
            max_step=0.01,
        )
        return sol.t_events[0][0], *sol.y_events[0][0]

    top = 225 * RPM / ratio
    stroke_end = run(energy / theta, (0.0, 0.0, top), theta)
    turn_end = run(0.0, stroke_end, 2 * math.pi)
    assert_allclose(stroke_end[2] * ratio, 225 * (1 - slowdown) * RPM, rtol=1e-9)
    assert_allclose(turn_end[2] * ratio, 225 * RPM, rtol=1e-9)


def test_delta_and_the_bottom_speed_are_the_slowdown_given_otherwise(write_scene):
    """delta = 2/17 and flywheel_speed_min = "200 rpm" are slowdown = 1/9 (δ = 2s/(2 - s))."""
    base = flyopt.analyse(khurmi(write_scene))
    for line in ("delta = 0.11764705882352941", 'flywheel_speed_min = "200 rpm"'):
        text = KHURMI.format(slowdown=0.1).replace("slowdown = 0.1", line)
        other = flyopt.analyse(flyopt.load(write_scene(text, name="other.toml")))
        assert_allclose(other.delta, 2 / 17, rtol=1e-15)
        assert_allclose(flywheel(other).j_required, flywheel(base).j_required, rtol=1e-13)
        assert_allclose(flywheel(other).speed_ratio, 212.5 / 12, rtol=1e-14)


def test_the_conversions_of_the_physics_module():
    """δ = 2s/(2 - s) and back; the mean speed of a top speed; the punching energy."""
    from flyopt.machine import press

    for s in (0.01, 0.1, 1 / 9, 0.5, 0.99):
        delta = press.delta_from_slowdown(s)
        omega_max, omega_min = 1 + delta / 2, 1 - delta / 2  # section 2, ω_m = 1
        assert_allclose((omega_max - omega_min) / omega_max, s, rtol=1e-14)
        assert_allclose(press.slowdown_from_delta(delta), s, rtol=1e-14)
        assert_allclose(press.mean_from_top_speed(10.0, delta), 10 * (1 - s / 2), rtol=1e-14)
    assert_allclose(press.delta_from_slowdown(1 / 9), 2 / 17, rtol=1e-15)
    assert_allclose(press.working_angle(2.0, 5.0), math.radians(144), rtol=1e-15)


# -- the rate and the working stroke, in their other forms ----------------------------


def _same_cycle(a, b):
    for name in ("omega_mean", "delta", "a_max", "work_per_cycle", "power", "j_required"):
        assert_allclose(getattr(b, name), getattr(a, name), rtol=1e-13, err_msg=name)
    assert_allclose(flywheel(b).speed_ratio, flywheel(a).speed_ratio, rtol=1e-13)


@pytest.mark.parametrize(
    "old, new",
    [
        ("strokes_per_minute = 12", 'stroke_period = "5 s"'),
        ("strokes_per_minute = 12", "stroke_period = 5"),
        ("strokes_per_minute = 12", 'stroke_period = "5000 ms"'),
        ("working_time = 2", 'working_time = "2 s"'),
        ("working_time = 2", 'working_time = "2000 ms"'),
        ("working_time = 2", 'working_angle = "144 deg"'),
        ("working_time = 2", "working_angle = 2.5132741228718345"),
        ('energy_per_stroke = "15 kJ"', 'energy_per_stroke = "15 kN*m"'),
    ],
)
def test_each_form_of_the_rate_and_the_working_stroke_gives_the_same_cycle(write_scene, old, new):
    """5 s a stroke is 12 strokes a minute; 2 s of 5 s is 144 deg of the crank."""
    base = flyopt.analyse(khurmi(write_scene))
    text = KHURMI.format(slowdown=1 / 9)
    assert old in text
    _same_cycle(base, flyopt.analyse(flyopt.load(write_scene(text.replace(old, new), name="other.toml"))))


def test_the_press_writes_the_scene_a_user_would_write_by_hand(write_scene):
    """The same press written out by hand, [machine] and [torque] (the working stroke from 0 to
    144 deg) and the flywheel's [[shaft]] at 212.5/12: the same analysis, field by field."""
    hand = """
title = "Khurmi punching press"
[machine]
speed = "12 rpm"
delta = 0.11764705882352941
[torque.driving]
constant = "unknown"
[torque.resisting]
points = [["0 deg", "5968.310365946075 N*m"], ["144 deg", "5968.310365946075 N*m"], ["144 deg", "0 N*m"],
          ["360 deg", "0 N*m"]]
[[shaft]]
name = "crankshaft"
speed_ratio = 1
[[shaft]]
name = "flywheel"
speed_ratio = 17.708333333333332
"""
    assert_allclose(15000 / math.radians(144), 5968.310365946075, rtol=1e-15)
    press = flyopt.analyse(khurmi(write_scene))
    by_hand = flyopt.analyse(flyopt.load(write_scene(hand, name="hand.toml")))
    _same_cycle(by_hand, press)
    assert [s.name for s in press.shafts] == ["crankshaft", "flywheel"]


# -- the energy sources against closed forms -------------------------------------------

RAMP = """
[press]
strokes_per_minute = 30
working_angle = "{angle} deg"
force = [[0, 0], [{stroke}, {force}]]
position_unit = "mm"
force_unit = "kN"
delta = 0.1
"""


@pytest.mark.parametrize("angle, stroke, force", [(60, 20, 600), (120, 5, 2000), (10, 100, 50)])
def test_a_force_ramp_gives_its_work_and_the_energy_indicator_of_its_closed_form(write_scene, angle, stroke, force):
    """A force rising linearly from 0 to F over the stroke s: work E = F s/2. With the positions
    uniform over θ_w, M_r rises linearly to M_p = F s/θ_w (= 2E/θ_w), M_d = E/2π. ΔE climbs to
    M_d φ*/2 at the crossing φ* = θ_w M_d/M_p = θ_w²/(4π), and falls to E θ_w/2π - E at the end of
    the working stroke: A_max = M_d φ*/2 + E (1 - θ_w/2π). Closed forms written out here."""
    result = flyopt.analyse(flyopt.load(write_scene(RAMP.format(angle=angle, stroke=stroke, force=force))))
    energy = 0.5 * force * 1e3 * stroke * 1e-3
    theta = math.radians(angle)
    m_d = energy / (2 * math.pi)
    crossing = theta**2 / (4 * math.pi)
    a_max = 0.5 * m_d * crossing + energy * (1 - theta / (2 * math.pi))
    assert_allclose(result.work_per_cycle, energy, rtol=1e-13)
    assert_allclose(result.a_max, a_max, rtol=1e-12)
    assert_allclose(result.angle_delta_e_max, crossing, rtol=1e-12)
    assert_allclose(result.angle_delta_e_min, theta, rtol=1e-13)
    assert_allclose(result.power, energy * 30 / 60, rtol=1e-13)


def test_a_force_table_with_steps_does_the_work_of_its_integral(write_scene):
    """A measured-looking table (a step up at contact, a peak, a step down at breakthrough),
    plain numbers and strings with units mixed: the work per cycle is ∫F dx by scipy's quad of
    the interpolated table (to 1e-10), and the load ends at the working angle."""
    rows = [["0 mm", "0 kN"], ["0 mm", "120 kN"], [4, 300], [9, 420], ["12 mm", "0.39 MN"], [12, 0], [15, 0]]
    text = (
        '[press]\nstrokes_per_minute = 20\nworking_angle = "90 deg"\nslowdown = 0.15\n'
        'position_unit = "mm"\nforce_unit = "kN"\nforce = ' + repr(rows).replace("'", '"') + "\n"
    )
    result = flyopt.analyse(flyopt.load(write_scene(text)))
    x = np.array([0, 0, 4, 9, 12, 12, 15]) * 1e-3
    f = np.array([0, 120, 300, 420, 390, 0, 0]) * 1e3
    pieces = [
        quad(lambda t, k=k: np.interp(t, x[k : k + 2], f[k : k + 2]), x[k], x[k + 1], epsabs=0, epsrel=1e-13)[0]
        for k in range(len(x) - 1)
        if x[k + 1] > x[k]
    ]
    assert_allclose(result.work_per_cycle, sum(pieces), rtol=1e-10)
    chain = [e["angle"] for e in result.energy_chain]
    assert max(chain[:-1]) <= math.radians(90) * (1 + 1e-12)  # nothing happens after the working stroke


def test_punching_energy_is_half_the_largest_force_times_the_thickness(write_scene):
    """Punching (Khurmi & Gupta, Theory of Machines, "Flywheel in punching press"):
    F_max = τ π d t and E = ½ F_max t. Published (a GATE question with a worked answer,
    https://byjus.com/question-answer/a-hole-of-50-mm-diameter-is-to-be-punched-on-a-2-mm-thick):
    a 50 mm hole in a 2 mm sheet, τ = 3.1 kN/mm², penetration half the thickness: 973.89 J.
    By hand: F = 3100 N/mm² x π x 50 mm x 2 mm = 973,894 N; E = ½ x 973,894 N x 0.002 m = 973.89 J.
    A cut_length of π d is the same hole."""
    text = (
        '[press]\nstrokes_per_minute = 24\nworking_angle = "36 deg"\ndelta = 0.1\n'
        '[press.punching]\nthickness = "2 mm"\nshear_strength = "3.1 kN/mm^2"\nhole_diameter = "50 mm"\n'
    )
    result = flyopt.analyse(flyopt.load(write_scene(text)))
    assert_published(result.work_per_cycle, "973.89")
    assert_allclose(result.work_per_cycle, 0.5 * 3.1e9 * math.pi * 0.05 * 0.002 * 0.002, rtol=1e-13)
    cut = text.replace('hole_diameter = "50 mm"', f"cut_length = {math.pi * 0.05!r}")
    assert_allclose(
        flyopt.analyse(flyopt.load(write_scene(cut, name="cut.toml"))).work_per_cycle, result.work_per_cycle, rtol=1e-15
    )


def test_a_punching_press_with_an_efficiency_takes_its_motor_power_through_it(write_scene):
    """Khurmi's punching machine of 24 strokes a minute (30 mm holes in 20 mm plate, τ = 350 MPa,
    the punch during 1/10 of a turn, mechanical efficiency 76 %, flywheel at 9 times the crank):
    E = ½ (350 x π x 30 x 20) N x 0.020 m = 6,597.3 J a stroke, mean power E x 24/60 = 2,638.9 W,
    motor 2,638.9/0.76 = 3,472 W; the flywheel gives up E (1 - 1/10) = 5,937.6 J. Closed forms
    written out here (the inputs are the textbook's; its answers are not quoted)."""
    text = (
        '[press]\nstrokes_per_minute = 24\nworking_angle = "36 deg"\ndelta = 0.1\n'
        '[press.punching]\nthickness = "20 mm"\nshear_strength = "350 MPa"\nhole_diameter = "30 mm"\n'
        '[machine]\nefficiency = "76 %"\n'
    )
    result = flyopt.analyse(flyopt.load(write_scene(text)))
    energy = 0.5 * 350e6 * math.pi * 0.030 * 0.020 * 0.020
    assert_allclose(result.work_per_cycle, energy, rtol=1e-13)
    assert_allclose(result.power, energy * 24 / 60, rtol=1e-13)
    assert_allclose(result.motor_power, energy * 24 / 60 / 0.76, rtol=1e-13)
    assert_allclose(result.a_max, energy * 0.9, rtol=1e-13)


@pytest.mark.parametrize("working_time", [0.5, 2.0, 4.5])
def test_the_flywheel_supplies_the_energy_the_motor_does_not_during_the_working_stroke(write_scene, working_time):
    """A_max = E (1 - t_w/T): the motor gives E t_w/T while the press works (Khurmi's 9 kJ of 15)."""
    text = KHURMI.format(slowdown=1 / 9).replace("working_time = 2", f"working_time = {working_time}")
    result = flyopt.analyse(flyopt.load(write_scene(text)))
    assert_allclose(result.a_max, 15000 * (1 - working_time / 5), rtol=1e-13)


# -- what the scene keeps, adds and leaves alone ----------------------------------------


def test_the_users_own_tables_are_kept_and_the_input_is_not_changed():
    from flyopt.io.press import scene_data
    from flyopt.io.scene import from_dict

    data = {
        "title": "p",
        "press": {
            "strokes_per_minute": 12,
            "energy_per_stroke": "15 kJ",
            "working_time": 2,
            "slowdown": 0.1,
            "flywheel_speed": "225 rpm",
        },
        "machine": {"inertia": "2 kg*m^2", "efficiency": 0.9},
        "shaft": [{"name": "main", "speed_ratio": 1, "efficiency": 0.9}],
        "design": {"geometry": "disc"},
        "material": [{"name": "x", "density": 7000, "max_rim_speed": 30}],
    }
    before = copy.deepcopy(data)
    out = scene_data(data)
    assert data == before
    assert "press" not in out
    assert out["machine"]["inertia"] == "2 kg*m^2" and out["machine"]["efficiency"] == 0.9
    assert [s["name"] for s in out["shaft"]] == ["main", "flywheel"]
    assert out["design"] == {"geometry": "disc", "shafts": ["flywheel"]}
    assert out["material"] == before["material"]
    assert out["torque"]["driving"] == {"constant": "unknown"}
    scene = from_dict(out)
    assert scene.j_constant == 2.0 and scene.efficiency == 0.9 and scene.design_shafts == ("flywheel",)


def test_a_scene_that_names_its_design_shafts_keeps_them(write_scene):
    text = KHURMI.format(slowdown=0.1) + '[[shaft]]\nname = "motor"\nspeed_ratio = 120\n[design]\nshafts = ["motor"]\n'
    scene = flyopt.load(write_scene(text))
    assert scene.design_shafts == ("motor",)
    assert [s.name for s in scene.shafts] == ["motor", "flywheel"]


def test_without_a_flywheel_speed_the_flywheel_may_sit_on_any_shaft(write_scene):
    text = KHURMI.format(slowdown=0.1).replace('flywheel_speed = "225 rpm"\n', "")
    scene = flyopt.load(write_scene(text))
    assert [s.name for s in scene.shafts] == ["reference"] and scene.design_shafts is None
    assert_allclose(scene.delta, 2 * 0.1 / 1.9, rtol=1e-15)


def test_a_motor_the_user_gives_drives_the_press(write_scene):
    """[torque.driving] is the user's: a motor on the flywheel shaft drives, the press's load resists."""
    from flyopt.cycle.torque import MotorTorque, PiecewiseLinear

    text = KHURMI.format(slowdown=0.1) + (
        '[torque.driving]\nmotor = { kind = "induction", rated_power = "4 kW", '
        'rated_speed = "1440 rpm", synchronous_speed = "1500 rpm" }\n'
    )
    scene = flyopt.load(write_scene(text))
    assert isinstance(scene.driving, MotorTorque) and isinstance(scene.resisting, PiecewiseLinear)


# -- bad values: exit 2, one line naming the file and press.<field> ------------------------

GOOD = """title = "press"
[press]
strokes_per_minute = 12
energy_per_stroke = "15 kJ"
working_time = "2 s"
slowdown = 0.1
flywheel_speed = "225 rpm"
"""
FORCE = GOOD.replace(
    'energy_per_stroke = "15 kJ"', 'force = [[0, 0], [20, 600]]\nposition_unit = "mm"\nforce_unit = "kN"'
)
PUNCH = GOOD.replace('energy_per_stroke = "15 kJ"', "") + (
    '[press.punching]\nthickness = "20 mm"\nshear_strength = "350 MPa"\nhole_diameter = "30 mm"\n'
)

BAD = [
    # the rate
    (GOOD, "strokes_per_minute = 12", "strokes_per_minute = 0", "press.strokes_per_minute", "positive"),
    (GOOD, "strokes_per_minute = 12", "strokes_per_minute = -12", "press.strokes_per_minute", "positive"),
    (GOOD, "strokes_per_minute = 12", 'strokes_per_minute = "12 rpm"', "press.strokes_per_minute", "plain number"),
    (
        GOOD,
        "strokes_per_minute = 12",
        'strokes_per_minute = 12\nstroke_period = "5 s"',
        "press.stroke_period",
        "exactly one of strokes_per_minute, strokes_per_hour, stroke_period",
    ),
    (GOOD, "strokes_per_minute = 12\n", "", "press.strokes_per_minute", "exactly one of"),
    (GOOD, "strokes_per_minute = 12", 'stroke_period = "0 s"', "press.stroke_period", "positive"),
    (GOOD, "strokes_per_minute = 12", 'stroke_period = "5 m"', "press.stroke_period", "expected a time"),
    (GOOD, "strokes_per_minute = 12", 'stroke_period = "5 s) * (1 m"', "press.stroke_period", "time"),
    (GOOD, "strokes_per_minute = 12", "stroke_period = true", "press.stroke_period", "expected a time"),
    # the working stroke
    (
        GOOD,
        'working_time = "2 s"',
        'working_time = "5 s"',
        "press.working_time",
        r"shorter than the stroke period \(5 s\)",
    ),
    (GOOD, 'working_time = "2 s"', 'working_time = "6 s"', "press.working_time", "shorter than"),
    (GOOD, 'working_time = "2 s"', "working_time = 0", "press.working_time", "positive"),
    (GOOD, 'working_time = "2 s"', 'working_time = "2 kg"', "press.working_time", "expected a time"),
    (GOOD, 'working_time = "2 s"', 'working_angle = "360 deg"', "press.working_angle", "between 1e-06 rad and 360 deg"),
    (GOOD, 'working_time = "2 s"', 'working_angle = "-10 deg"', "press.working_angle", "between 1e-06 rad and 360 deg"),
    (GOOD, 'working_time = "2 s"', 'working_angle = "60 s"', "press.working_angle", "wrong dimension"),
    (
        GOOD,
        'working_time = "2 s"',
        'working_time = "2 s"\nworking_angle = "60 deg"',
        "press.working_angle",
        "exactly one of working_time, working_angle",
    ),
    (GOOD, 'working_time = "2 s"\n', "", "press.working_time", "exactly one of"),
    # the fluctuation
    (GOOD, "slowdown = 0.1", "slowdown = 1", "press.slowdown", "between 0 and 1"),
    (GOOD, "slowdown = 0.1", "slowdown = 1.5", "press.slowdown", "between 0 and 1"),
    (GOOD, "slowdown = 0.1", "slowdown = 0", "press.slowdown", "between 0 and 1"),
    (GOOD, "slowdown = 0.1", 'slowdown = "100 %"', "press.slowdown", "between 0 and 1"),
    (GOOD, "slowdown = 0.1", "delta = 2", "press.delta", "between 1e-06 and 2"),
    (GOOD, "slowdown = 0.1", "delta = -0.1", "press.delta", "between 1e-06 and 2"),
    # a δ too small to compute with is the press's field's, not machine.delta's (the press gives no [machine])
    (GOOD, "slowdown = 0.1", "delta = 1e-9", "press.delta", "between 1e-06 and 2"),
    (
        GOOD,
        "slowdown = 0.1",
        "slowdown = 1e-9",
        "press.slowdown",
        r"gives δ = 2s/\(2 − s\) = 1e-09; δ must lie between 1e-06",
    ),
    (
        GOOD,
        "slowdown = 0.1",
        'flywheel_speed_min = "224.9999999 rpm"',
        "press.flywheel_speed_min",
        r"gives δ = .* = 4.444e-10; δ must lie between 1e-06 and 2",
    ),
    (GOOD, "slowdown = 0.1", "slowdown = 0.1\ndelta = 0.1", "press.delta", "exactly one of slowdown, delta"),
    (GOOD, "slowdown = 0.1\n", "", "press.slowdown", "exactly one of"),
    (GOOD, "slowdown = 0.1", 'flywheel_speed_min = "230 rpm"', "press.flywheel_speed_min", "below flywheel_speed"),
    (GOOD, "slowdown = 0.1", 'flywheel_speed_min = "0 rpm"', "press.flywheel_speed_min", "positive"),
    (
        GOOD.replace('flywheel_speed = "225 rpm"\n', ""),
        "slowdown = 0.1",
        'flywheel_speed_min = "200 rpm"',
        "press.flywheel_speed_min",
        "needs press.flywheel_speed",
    ),
    # the flywheel shaft
    (GOOD, 'flywheel_speed = "225 rpm"', 'flywheel_speed = "0 rpm"', "press.flywheel_speed", "positive"),
    (GOOD, 'flywheel_speed = "225 rpm"', 'flywheel_speed = "-225 rpm"', "press.flywheel_speed", "positive"),
    (GOOD, 'flywheel_speed = "225 rpm"', 'flywheel_speed = "225 m"', "press.flywheel_speed", "wrong dimension"),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[[shaft]]\nname = "flywheel"\nspeed_ratio = 2',
        "press.flywheel_speed",
        "shaft\\[0\\] is named 'flywheel' too",
    ),
    # the energy
    (GOOD, 'energy_per_stroke = "15 kJ"', 'energy_per_stroke = "0 J"', "press.energy_per_stroke", "positive"),
    (GOOD, 'energy_per_stroke = "15 kJ"', 'energy_per_stroke = "-15 kJ"', "press.energy_per_stroke", "positive"),
    (GOOD, 'energy_per_stroke = "15 kJ"', 'energy_per_stroke = "15 kW"', "press.energy_per_stroke", "wrong dimension"),
    (GOOD, 'energy_per_stroke = "15 kJ"\n', "", "press.energy_per_stroke", "exactly one of"),
    (
        GOOD,
        'energy_per_stroke = "15 kJ"',
        'energy_per_stroke = "15 kJ"\nforce = [[0, 0], [1, 1]]',
        "press.force",
        "exactly one of energy_per_stroke, force, punching",
    ),
    (
        GOOD,
        'energy_per_stroke = "15 kJ"',
        'energy_per_stroke = "15 kJ"\nforce_unit = "kN"',
        "press.force_unit",
        "belongs to press.force",
    ),
    (FORCE, "force = [[0, 0], [20, 600]]", "force = [[0, 0]]", "press.force", "at least two"),
    (FORCE, "force = [[0, 0], [20, 600]]", "force = [[0, 0], [20]]", "press.force[1]", "pair"),
    (
        FORCE,
        "force = [[0, 0], [20, 600]]",
        "force = [[0, 0], [20, 600], [10, 0]]",
        "press.force[2]",
        "must not decrease",
    ),
    (
        FORCE,
        "force = [[0, 0], [20, 600]]",
        "force = [[0, 0], [20, 600], [20, 300], [20, 0]]",
        "press.force[3]",
        "three points at one position",
    ),
    (FORCE, "force = [[0, 0], [20, 600]]", "force = [[0, 0], [20, -600]]", "press.force[1]", "not be negative"),
    (FORCE, "force = [[0, 0], [20, 600]]", "force = [[0, 0], [20, 0]]", "press.force", "does no work"),
    (FORCE, "force = [[0, 0], [20, 600]]", "force = [[5, 0], [5, 600]]", "press.force", "no length"),
    (
        FORCE,
        "force = [[0, 0], [20, 600]]",
        'force = [[0, 0], ["20 mm", "600 N*m"]]',
        "press.force[1] force",
        "wrong dimension",
    ),
    (FORCE, 'force_unit = "kN"', 'force_unit = "kJ"', "press.force_unit", "wrong dimension"),
    # a unit alone: "1 " + "kN*2" was twice the force, "1 " + "-1 kN" a negative kilonewton
    (FORCE, 'force_unit = "kN"', 'force_unit = "kN*2"', "press.force_unit", "no part of a unit"),
    (FORCE, 'position_unit = "mm"', 'position_unit = "-1 mm"', "press.position_unit", "no part of a unit"),
    (FORCE, 'position_unit = "mm"', "position_unit = 0.001", "press.position_unit", "unit string"),
    (PUNCH, 'thickness = "20 mm"\n', "", "press.punching.thickness", "is missing"),
    (PUNCH, 'shear_strength = "350 MPa"', 'shear_strength = "-350 MPa"', "press.punching.shear_strength", "positive"),
    (
        PUNCH,
        'hole_diameter = "30 mm"',
        'hole_diameter = "30 mm"\ncut_length = "94 mm"',
        "press.punching.cut_length",
        "exactly one of hole_diameter, cut_length",
    ),
    (
        PUNCH,
        'hole_diameter = "30 mm"',
        'hole_diamter = "30 mm"',
        "press.punching.hole_diamter",
        "did you mean 'hole_diameter'",
    ),
    # the table and conflicts with the scene's own
    (GOOD, "slowdown = 0.1", "slowdown = 0.1\nstroke_rate = 12", "press.stroke_rate", "unknown key"),
    (GOOD, "[press]\nstrokes_per_minute", "press = 5\n[pres]\nstrokes_per_minute", "press", "must be a table"),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[machine]\nspeed = "12 rpm"',
        "press.strokes_per_minute",
        "machine.speed is given too",
    ),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[machine]\ndelta = 0.1',
        "press.slowdown",
        "machine.delta is given too",
    ),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[machine]\ncycle = "720 deg"',
        "press.strokes_per_minute",
        "machine.cycle is given too",
    ),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[torque.resisting]\nconstant = "100 N*m"',
        "press.energy_per_stroke",
        "torque.resisting is given too",
    ),
    (
        GOOD,
        'flywheel_speed = "225 rpm"',
        'flywheel_speed = "225 rpm"\n[torque.net]\nareas = [1, -1]',
        "press.energy_per_stroke",
        "torque.net is given too",
    ),
]


@pytest.mark.parametrize("base, old, new, field, match", BAD, ids=[f"{k}-{case[3]}" for k, case in enumerate(BAD)])
def test_a_bad_press_value_is_refused_in_one_line(tmp_path, cli, base, old, new, field, match):
    assert old in base, "test bug: the snippet is not in the scene"
    path = tmp_path / "press.toml"
    path.write_text(base.replace(old, new, 1))
    run = cli("check", path)
    if new.startswith("press = 5\n[pres]"):  # two errors, and check lists each on its line (issue 29)
        lines = run.stderr.splitlines()
        assert run.returncode == 2 and len(lines) == 2, run.stderr
        assert names_field(lines[0], path, field) and match in lines[0], lines
        assert names_field(lines[1], path, "pres") and "unknown key; did you mean 'press'?" in lines[1], lines
        return
    assert_refused(run, path, field, match)


@pytest.mark.parametrize(
    "base, old, new, field, match",
    [case for case in BAD if case[2] in ("slowdown = 1", 'working_time = "5 s"', "force = [[0, 0], [20, 0]]")],
)
def test_solve_refuses_a_bad_press_value_as_check_does(tmp_path, cli, base, old, new, field, match):
    path = tmp_path / "press.toml"
    path.write_text(base.replace(old, new, 1))
    assert_refused(cli("solve", path), path, field, match)


@pytest.mark.parametrize("text", [GOOD, FORCE, PUNCH])
def test_the_good_press_scenes_check(tmp_path, cli, text):
    path = tmp_path / "press.toml"
    path.write_text(text)
    result = cli("check", path)
    assert result.returncode == 0, result.stderr


def test_a_long_force_table_read_without_tomllib_gives_the_work_of_its_rows(write_scene):
    """A force table of 400 plain-number rows is read by flyopt's fast table reader (an
    InlineRows, not a list): the same cycle as the table handed over as a list, and the work
    of its trapezoids summed here by numpy."""
    from flyopt.io.press import scene_data
    from flyopt.io.scene import from_dict
    from flyopt.io.toml_file import InlineRows, read_toml

    x = np.linspace(0.0, 30.0, 400)  # mm
    f = 500.0 * np.sin(np.pi * x / 30.0) ** 2  # kN
    rows = ", ".join(f"[{a!r}, {b!r}]" for a, b in zip(x.tolist(), f.tolist()))
    path = write_scene(
        '[press]\nstrokes_per_minute = 20\nworking_angle = "100 deg"\nslowdown = 0.1\n'
        f'position_unit = "mm"\nforce_unit = "kN"\nforce = [{rows}]\n'
    )
    data = read_toml(path)
    assert isinstance(data["press"]["force"], InlineRows)
    fast = flyopt.analyse(from_dict(scene_data(data)))
    listed = dict(data, press=dict(data["press"], force=[[a, b] for a, b in zip(x.tolist(), f.tolist())]))
    slow = flyopt.analyse(from_dict(scene_data(listed)))
    work = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))  # kN*mm = J
    assert_allclose(fast.work_per_cycle, work, rtol=1e-12)
    assert_allclose(slow.a_max, fast.a_max, rtol=1e-15)
