"""The textbook's mechanism exercises (problems/textbook/) against their published answers, and the scene's refusals.

Seed 000 (陆宁, 机械设计基础总复习题及解答, ch. 7), calculations 6 (a guide-bar),
7 (gears and a sine mechanism) and 8 (gears and an eccentric cam, answered in
symbols). Calculations 6 and 7 ask for the equivalents at one position, which
their scenes' [position] gives (no speed, no δ); the velocity ratios are
checked against finite differences of the positions, written here from the
geometry. Where the book's figure differs from flyopt's in the last digit,
the test shows that it comes from the book rounding an intermediate ratio.
"""

import json
import math

import jsonschema
import numpy as np
import pytest
from conftest import PROBLEMS, assert_published, names_field, unplaced
from scipy import optimize

import flyopt
from flyopt.errors import SceneError
from flyopt.machine.equivalents import MechanismPosition, equivalents_at
from flyopt.machine.linkages import Cam
from flyopt.machine.mechanism import Member, equivalent_inertia, equivalent_torque
from flyopt.outputs.documents import schema
from flyopt.pipeline import solve_position

TEXTBOOK = PROBLEMS / "textbook"
CALC6 = TEXTBOOK / "seed000-calc6-guide-bar-position.toml"
CALC7 = TEXTBOOK / "seed000-calc7-gear-sine-mechanism-position.toml"
STEP = 1e-6  # of the central differences [rad]


def _rate(position, at):
    """d/dψ of a point (x, y) or an angle at ``at``, by central differences of the position itself."""
    ahead, behind = np.asarray(position(at + STEP)), np.asarray(position(at - STEP))
    return (ahead - behind) / (2 * STEP)


def test_seed000_calc6_guide_bar_at_one_position():
    scene = flyopt.load(CALC6)
    assert math.isnan(scene.omega_mean) and scene.delta is None  # no speed, no δ: the book gives none
    result = solve_position(scene)
    psi = math.radians(44)
    assert result.angle == pytest.approx(psi, rel=1e-15) and result.input_angle == pytest.approx(psi, rel=1e-15)
    rows = {m.name: m for m in result.members}
    w31 = rows["guide-bar 3"].angular_ratio  # ω3/ω1
    assert_published(1 / w31, "3.23")
    assert_published(rows["guide-bar 3"].velocity_ratio / w31, "0.275")  # v_S3/ω3
    assert_published(rows["block 2"].angular_ratio / w31, "1")  # ω2/ω3
    assert rows["block 2"].velocity_ratio == pytest.approx(0.15, rel=1e-12)  # v_S2/ω3 = l_AB ω1/ω3 = 0.4845

    # independently: A at the origin, C at (−0.3, 0), B = r(cos ψ, sin ψ), the lever C→B; differences of positions
    r, d, e = 0.15, 0.3, 0.275

    def lever(x):
        return math.atan2(r * math.sin(x), d + r * math.cos(x))

    def s3(x):
        b = lever(x)
        return (-d + e * math.cos(b), e * math.sin(b))

    def pin(x):
        return (r * math.cos(x), r * math.sin(x))

    w3 = float(_rate(lever, psi))
    v_s3 = float(np.hypot(*_rate(s3, psi)))
    v_s2 = float(np.hypot(*_rate(pin, psi)))
    assert w31 == pytest.approx(w3, rel=1e-8)
    assert rows["guide-bar 3"].velocity_ratio == pytest.approx(v_s3, rel=1e-8)
    assert rows["block 2"].velocity_ratio == pytest.approx(v_s2, rel=1e-8)
    j_crank = 0.05 + 3 * v_s2**2 + 0.002 * w3**2 + 10 * v_s3**2 + 0.2 * w3**2
    assert result.equivalent_inertia == pytest.approx(j_crank, rel=1e-8)
    assert result.equivalent_moment == pytest.approx(300.0, rel=1e-15) and result.sense == "driving"

    # (1) M1 reduced to the guide-bar, and to a force at D (l_CD = 0.55 m)
    reduced = result.reduced
    assert reduced.member == "guide-bar 3" and reduced.turns and reduced.radius == pytest.approx(0.55)
    assert reduced.equivalent_moment == pytest.approx(300 / w3, rel=1e-8)
    assert_published(reduced.equivalent_moment, "969")
    assert_published(reduced.equivalent_force, "1762")  # the book's 1764 N is 300 × 5.88,
    assert_published(300 * 5.88, "1764")  # but its own ω1/v_D = 3.23/0.55 = 5.873 rounds to 5.87
    assert_published(3.23 / 0.55, "5.87")
    assert reduced.equivalent_force == pytest.approx(reduced.equivalent_moment / 0.55, rel=1e-15)

    # (2) the equivalent inertia at C: J_e at the crank × (ω1/ω3)²
    assert reduced.equivalent_inertia == pytest.approx(j_crank / w3**2, rel=1e-8)
    assert_published(reduced.equivalent_inertia, "2.184")
    # the book's 2.186 takes v_S2/ω3 rounded to 0.485 (from 0.15 × 3.23 = 0.4845)
    book = 0.2 + 10 * 0.275**2 + 0.002 * 1**2 + 3 * 0.485**2 + 0.05 * 3.23**2
    assert_published(book, "2.186")
    assert_published(book - 3 * 0.485**2 + 3 * 0.4845**2, "2.184")  # the book's sum with 0.4845 unrounded
    by_member_c = 0.2 + 10 * (v_s3 / w3) ** 2 + 0.002 + 3 * (v_s2 / w3) ** 2 + 0.05 / w3**2  # the book's sum, exact
    assert reduced.equivalent_inertia == pytest.approx(by_member_c, rel=1e-8)


def test_seed000_calc6_the_angle_is_where_the_book_reads_3_23():
    """The seed has no figure: 44° is the crank angle on the working stroke where ω1/ω3 = 3.23, the book's."""
    bar = flyopt.load(CALC6).mechanism
    psi = optimize.brentq(lambda p: float(bar.lever_angular_ratio(p)) - 1 / 3.23, 0.01, 2.0, xtol=1e-15)
    assert math.degrees(psi) == pytest.approx(44.0, abs=0.1)


def test_seed000_calc6_the_figure_at_45_degrees_would_read_3_24():
    """Had the figure drawn the crank at 45°, the velocity diagram should have given ω1/ω3 = 3.243."""
    bar = flyopt.load(CALC6).mechanism
    r, d, psi = 0.15, 0.3, math.radians(45)
    by_hand = (d * d + r * r + 2 * d * r * math.cos(psi)) / (r * (r + d * math.cos(psi)))
    assert 1 / float(bar.lever_angular_ratio(psi)) == pytest.approx(by_hand, rel=1e-14)
    assert_published(by_hand, "3.243")


def test_seed000_calc7_gears_and_sine_mechanism_at_one_position():
    scene = flyopt.load(CALC7)
    assert math.isnan(scene.omega_mean) and scene.delta is None
    result = solve_position(scene)
    # φ2 = 60° as the book gives it (input_angle): O1, turning twice as fast, is at 120°
    assert result.position.input_angle == pytest.approx(math.radians(60), rel=1e-15)
    assert result.angle == pytest.approx(math.radians(120), rel=1e-15)
    assert result.input_angle == pytest.approx(math.radians(60), rel=1e-15)
    rows = {m.name: m for m in result.members}
    assert_published(rows["gear 2 and crank O2A"].angular_ratio, "0.5")
    assert_published(rows["block 3"].velocity_ratio, "0.1")  # v_S3/ω1
    v4 = rows["bar 4"].velocity_ratio
    assert_published(v4, "0.0866")  # v4/ω1
    assert_published(v4 / 0.5, "0.173")  # v4/ω2
    assert rows["bar 4"].angular_ratio == 0.0

    # independently: A = r (cos φ2, sin φ2) with φ2 = φ1/2, the bar follows A's x; differences of positions in φ1
    r, phi1 = 0.2, math.radians(120)

    def a(x):
        return (r * math.cos(x / 2), r * math.sin(x / 2))

    v_a = float(np.hypot(*_rate(a, phi1)))
    v_bar = float(_rate(lambda x: a(x)[0], phi1))
    assert rows["block 3"].velocity_ratio == pytest.approx(v_a, rel=1e-8)
    assert v4 == pytest.approx(abs(v_bar), rel=1e-8)
    assert result.equivalent_moment == pytest.approx(-100 * abs(v_bar), rel=1e-8)
    assert result.sense == "resisting"  # against ω1, as the book says
    assert_published(-result.equivalent_moment, "8.66")
    j_e = 0.003 + 0.06 * 0.5**2 + 1 * v_a**2 + 5 * v_bar**2
    assert result.equivalent_inertia == pytest.approx(j_e, rel=1e-8)
    # exactly 0.003 + 0.06/4 + 1 × 0.1² + 5 × (0.1 sin 60°)² = 0.0655; the book's 0.065 squares 0.0866 (rounded)
    assert result.equivalent_inertia == pytest.approx(0.0655, rel=1e-12)
    book = 0.003 + 0.06 * 0.5**2 + 1 * 0.1**2 + 5 * 0.0866**2
    assert_published(book, "0.065")
    assert book == pytest.approx(0.0654978, abs=1e-9)


def test_seed000_calc7_reduced_to_the_bar_gives_back_its_force():
    """Reduced to bar 4, which only translates, the equivalent force is F4 itself (resisting) and the
    equivalent mass J_e (ω1/v4)²."""
    scene = flyopt.load(CALC7)
    result = solve_position(scene.replace(position=MechanismPosition(scene.position.angle, reduce_to="bar 4")))
    reduced = result.reduced
    assert not reduced.turns and reduced.equivalent_inertia is None and reduced.equivalent_moment is None
    assert reduced.equivalent_force == pytest.approx(-100.0, rel=1e-14)
    assert reduced.equivalent_mass == pytest.approx(0.0655 / (0.1 * math.sin(math.radians(60))) ** 2, rel=1e-12)


@pytest.mark.parametrize("path", [CALC6, CALC7])
def test_the_position_scenes_solve_check_and_meet_the_schema(main_cli, path):
    status, out, err = main_cli("solve", path, "--json")
    assert status == 0, err
    document = json.loads(out)
    assert document["kind"] == "position" and document["form"] == "equivalents"
    assert [e.message for e in jsonschema.Draft202012Validator(schema()).iter_errors(document)] == []
    assert document["units"]["equivalent_inertia"] == "kg*m**2" and document["units"]["velocity_ratio"] == "m"
    status, out, err = main_cli("solve", path)
    assert status == 0 and "equivalent inertia J_e" in out and "equivalent moment M_e" in out
    status, out, err = main_cli("check", path)
    assert status == 0, err


def test_a_speed_given_changes_nothing(write_scene):
    """The equivalents at a position need no speed; one given (machine.speed) is not used."""
    text = CALC6.read_text(encoding="utf-8").replace("[mechanism]", '[machine]\nspeed = "60 rpm"\n\n[mechanism]', 1)
    with_speed = solve_position(flyopt.load(write_scene(text)))
    assert with_speed.to_dict() == solve_position(flyopt.load(CALC6)).to_dict()


def test_a_member_turning_backwards_is_reduced_with_the_power_and_the_energy():
    """M_k ω_k = M_e ω and J_k ω_k² = J_e ω² with ω_k = −ω/2: the reduced moment is positive (driving) and twice M_e."""
    members = [
        Member("gear 1", inertia=0.01, angular_ratio=1.0, torque=10.0, force_sense="driving"),
        Member("gear 2", inertia=0.2, angular_ratio=-0.5),
    ]
    result = equivalents_at(MechanismPosition(None, reduce_to="gear 2", force_at=0.1), members, j_constant=0.02)
    assert result.equivalent_inertia == pytest.approx(0.01 + 0.2 / 4 + 0.02, rel=1e-15)
    assert result.equivalent_moment == 10.0 and result.sense == "driving"
    assert result.reduced.equivalent_moment == pytest.approx(20.0, rel=1e-15)
    assert result.reduced.equivalent_inertia == pytest.approx(4 * result.equivalent_inertia, rel=1e-15)
    assert result.reduced.equivalent_force == pytest.approx(200.0, rel=1e-15)
    assert result.reduced.equivalent_mass == pytest.approx(400 * result.equivalent_inertia, rel=1e-15)


def test_a_mechanism_that_cannot_be_assembled_at_the_angle_is_refused():
    """Ratios that are not finite at the angle (a mechanism that does not close there) name position.angle."""
    members = [Member("link", mass=1.0, velocity_ratio=lambda phi: np.sqrt(np.cos(phi) - 2.0), angular_ratio=1.0)]
    with pytest.raises(SceneError) as err, np.errstate(invalid="ignore"):
        equivalents_at(MechanismPosition(0.5), members)
    assert err.value.field == "position.angle" and "cannot be assembled" in str(err.value)


def test_seed000_calc8_gears_and_eccentric_cam_in_symbols():
    """Calculation 8 answers in symbols: with gear 2 and the cam as the equivalent member, where v4 = e ω2,
    J_e = J2 + J1 (z2/z1)² + J3 + m3 e² + m4 e² and M_e = M1 z2/z1 − Q e (numbers of our own)."""
    z1, z2, j1, j2, j3, m3, m4, e, m1, q = 20, 50, 0.01, 0.3, 0.02, 4.0, 2.0, 0.03, 15.0, 200.0
    # an eccentric disc under a flat translating follower: s = e (1 − cos ψ), simple harmonic 180/180, lift 2e
    cam = Cam([("rise", "simple_harmonic", math.pi, 2 * e), ("return", "simple_harmonic", math.pi, 2 * e)])
    disc, follower = cam.kinematics("cam", e), cam.kinematics("follower")
    members = [
        Member("gear 1", 0.0, j1, 0.0, z2 / z1, torque=m1, force_sense="driving"),
        Member("gear 2", 0.0, j2, 0.0, 1.0),
        Member("cam 3", m3, j3, disc.velocity_ratio, disc.angular_ratio),
        Member("follower 4", m4, 0.0, follower.velocity_ratio, follower.angular_ratio, force=q),
    ]
    at = np.array(math.pi / 2)  # P34 at S3: the follower moves at e ω2
    assert float(cam.follower_velocity_ratio(at)) == pytest.approx(e, rel=1e-14)
    j_e = j2 + j1 * (z2 / z1) ** 2 + j3 + m3 * e**2 + m4 * e**2
    assert float(equivalent_inertia(members)(at)) == pytest.approx(j_e, rel=1e-14)
    assert float(equivalent_torque(members)(at)) == pytest.approx(m1 * z2 / z1 - q * e, rel=1e-14)


DESIGN = '\n[design]\ngeometry = "disc"\nmax_outer_diameter = "0.5 m"\n'


def _cycle_scene(path, speed, sections):
    """A position scene made a cycle with inputs of our own (a speed, a δ, the balancing load, a design)."""
    text = path.read_text(encoding="utf-8").split("[position]")[0]
    machine = f'[machine]\nspeed = "{speed}"\ndelta = 0.05\n'
    if "[machine]\n" in text:
        return text.replace("[machine]\n", machine, 1) + sections + DESIGN
    return text.replace("[mechanism]", machine + "\n[mechanism]", 1) + sections + DESIGN


@pytest.mark.parametrize(
    "path, speed, load",
    [(CALC6, "60 rpm", "[torque.resisting]"), (CALC7, "300 rpm", "[torque.driving]")],
)
def test_the_books_mechanisms_in_a_cycle_design_a_flywheel(main_cli, write_scene, path, speed, load):
    """The same mechanisms through the cycle's models (J_e(φ) varies): a speed, δ and a balancing load of our own."""
    scene = write_scene(_cycle_scene(path, speed, f'{load}\nconstant = "unknown"\n'))
    status, out, err = main_cli("solve", scene, "--json")
    assert status == 0, err
    assert '"kind": "solve"' in out
    status, out, err = main_cli("solve", scene)
    assert status == 0 and "energy_mass" in out


SCENE = """
[machine]
speed = "60 rpm"
delta = 0.05
{cycle}
[mechanism]
{mechanism}
[[member]]
name = "part"
part = "{part}"
mass = "3 kg"
force = "50 N"
[torque.driving]
constant = "unknown"
[design]
geometry = "disc"
"""

GUIDE = 'kind = "guide_bar"\ncrank = "150 mm"\nframe = "300 mm"\nlever = "550 mm"'
FOUR = 'kind = "four_bar"\ncrank = "100 mm"\ncoupler = "350 mm"\nrocker = "300 mm"\nframe = "400 mm"'
CAM = (
    'kind = "cam"\nlift = "20 mm"\nsegments = [{motion = "rise", law = "cycloidal", angle = "150 deg"},'
    ' {motion = "dwell", angle = "30 deg"}, {motion = "return", law = "polynomial_345", angle = "120 deg"},'
    ' {motion = "dwell", angle = "60 deg"}]'
)


@pytest.mark.parametrize(
    "mechanism, part, cycle, field, words",
    [
        (FOUR.replace('"400 mm"', '"900 mm"'), "rocker", "", "mechanism", "cannot be assembled"),
        (FOUR.replace('"100 mm"', '"320 mm"'), "rocker", "", "mechanism", "cannot turn fully"),
        (FOUR + '\nbranch = "upper"', "rocker", "", "mechanism.branch", "'upper' is not known"),
        (FOUR + '\nlength = "1 m"', "rocker", "", "mechanism.length", "unknown key"),
        (GUIDE.replace('"300 mm"', '"150 mm"'), "lever", "", "mechanism", "passes through the lever's pivot"),
        (GUIDE.replace('"550 mm"', '"400 mm"'), "lever", "", "mechanism", "leave the slot"),
        (GUIDE, "rod", "", "member[0].part", "'rod' is not known"),
        (GUIDE + "\nspeed_ratio = 0.75", "lever", "", "mechanism.speed_ratio", "does not divide machine.cycle"),
        (GUIDE + "\nspeed_ratio = 0.5", "lever", 'cycle = "720 deg"', None, None),
        (CAM.replace('"60 deg"', '"50 deg"'), "follower", "", "mechanism", "one turn"),
        (CAM.replace('"cycloidal"', '"parabolic"'), "follower", "", "mechanism.segments[0].law", "'parabolic'"),
        (
            CAM.replace('"dwell", angle = "30 deg"', '"dwell", law = "cycloidal", angle = "30 deg"'),
            "follower",
            "",
            "mechanism.segments[1].law",
            "a dwell has no law",
        ),
        (CAM.replace('lift = "20 mm"\n', ""), "follower", "", "mechanism.segments[0].lift", "is missing"),
        (CAM.replace('"rise"', '"up"'), "follower", "", "mechanism.segments[0].motion", "'up' is not known"),
    ],
)
def test_bad_mechanism_scenes_are_refused_in_one_line(main_cli, write_scene, mechanism, part, cycle, field, words):
    path = write_scene(SCENE.format(mechanism=mechanism, part=part, cycle=cycle))
    status, out, err = main_cli("solve", path)
    if field is None:
        assert status == 0, err
        return
    assert status != 0
    line = err.strip()
    assert "\n" not in line
    assert f"{path}: {field}: " in unplaced(line, path) and words in line


FOUR_BAR_MOTOR = """
[machine]
speed = "60 rpm"
delta = 0.05
[mechanism]
kind = "four_bar"
crank = "100 mm"
coupler = "350 mm"
rocker = "300 mm"
frame = "400 mm"
[[member]]
name = "rocker"
part = "rocker"
mass = "20 kg"
inertia = "0.5 kg*m^2"
torque = "300 N*m"
[[member]]
name = "coupler"
part = "coupler"
mass = "8 kg"
inertia = "0.1 kg*m^2"
[torque.driving]
motor = { kind = "induction", rated_power = "7.5 kW", rated_speed = "1420 rpm", synchronous_speed = "1500 rpm" }
[[shaft]]
name = "motor"
speed_ratio = 24.0
[design]
geometry = "disc"
max_outer_diameter = "0.6 m"
"""


@pytest.mark.slow  # 5-8 s; the dynamic model with a motor runs in the default run on motor-press and slider-crank
def test_a_four_bar_driven_by_a_motor_goes_through_the_dynamic_model(main_cli, write_scene):
    """A speed-dependent motor torque: the periodic solution (CasADi) of a machine with a four-bar's J_e(φ)."""
    # --no-design: the wheel's design and its δ-sensitivity would solve the periodic model twice more (20 s of
    # a test that is about the model; the design of a dynamic scene is tested on motor-press)
    status, out, err = main_cli("solve", write_scene(FOUR_BAR_MOTOR), "--no-design")
    assert status == 0, err
    assert "model: dynamic" in out and "dynamic (exact)" in out


POSITION = """
{machine}
[mechanism]
{mechanism}
[[member]]
name = "crank"
part = "crank"
mass = "5 kg"
torque = "300 N*m"
force_sense = "driving"
[[member]]
name = "block"
part = "block"
mass = "3 kg"
[[member]]
name = "lever"
part = "lever"
mass = "10 kg"
inertia = "0.2 kg*m^2"
[position]
{position}
{extra}
"""


@pytest.mark.parametrize(
    "position, field, words, changes",
    [
        ('angle = "400 deg"', "position.angle", "must lie within the cycle, 0 to 360 deg", {}),
        ('angle = "-10 deg"', "position.angle", "must lie within the cycle", {}),
        ('angle = "1e400 deg"', "position.angle", "", {}),
        ('angle = "44 deg"\nreduce_to = "lever 9"', "position.reduce_to", "'lever 9' is not a [[member]]", {}),
        ('angle = "44 deg"\nreduce_to = 3', "position.reduce_to", "must be the name of a [[member]]", {}),
        ('angle = "44 deg"\nforce_at = "550 mm"', "position.force_at", "needs reduce_to", {}),
        ('angle = "44 deg"\nreduce_to = "lever"\nforce_at = "-1 m"', "position.force_at", "must be positive", {}),
        ('angle = "44 deg"\nreduce_to = "lever"\nforce_at = "1e9 km"', "position.force_at", "out of range", {}),
        ('angle = "44 deg"\ninput_angle = "44 deg"', "position.input_angle", "not both", {}),
        ('input_angle = "400 deg"', "position.input_angle", "within one turn", {}),
        ("", "position.angle", "is missing: the members' ratios or loads vary with the angle", {}),
        ('angle = "44 deg"\ncrank = "0.3 m"', "position.crank", "belongs to the forces of a slider-crank engine", {}),
        ('angle = "44 deg"\nspeed = "1 rpm"', "position.speed", "unknown key", {}),
        ('angle = "120 deg"\nreduce_to = "lever"', "position.reduce_to", "'lever' stands still at this position", {}),
        (
            'angle = "120 deg"\nreduce_to = "block"\nforce_at = "0.1 m"',
            "position.force_at",
            "'block' does not turn at this position",
            {},
        ),
        (
            'angle = "44 deg"',
            "position",
            "[torque] describes something else",
            {"extra": "[torque.driving]\nconstant = 1"},
        ),
        ('angle = "44 deg"', "position", "[design] describes something else", {"extra": '[design]\ngeometry = "disc"'}),
        ('angle = "44 deg"', "position", "[flywheel] describes something else", {"extra": "[flywheel]\ninertia = 1"}),
        (
            'angle = "44 deg"',
            "mechanism",
            "cannot turn fully",
            {"mechanism": FOUR.replace('"100 mm"', '"320 mm"')},
        ),
        ('input_angle = "60 deg"', "position.input_angle", "a gear train has no input angle", {"mechanism": "gear"}),
        (
            'input_angle = "300 deg"',
            "mechanism.speed_ratio",
            "does not divide machine.cycle",
            {"mechanism": GUIDE + "\nspeed_ratio = 0.5"},
        ),
    ],
)
def test_bad_positions_are_refused_in_one_line(main_cli, write_scene, position, field, words, changes):
    mechanism = changes.get("mechanism", GUIDE)
    text = POSITION.format(
        machine=changes.get("machine", ""), mechanism=mechanism, position=position, extra=changes.get("extra", "")
    )
    if mechanism == "gear":  # a gear train: shafts, no input angle
        text = text.replace("[mechanism]\ngear", '[mechanism]\nkind = "gear_train"\nratios = [0.5]')
        text = text.replace('part = "crank"', "part = 0").replace('part = "block"', "part = 1")
        text = text.replace('part = "lever"', "part = 1")
    if mechanism.startswith('kind = "four_bar"'):
        text = text.replace('part = "block"', 'part = "coupler"').replace('part = "lever"', 'part = "rocker"')
    path = write_scene(text)
    for verb in ("solve", "check"):
        status, out, err = main_cli(verb, path)
        assert status == 2, (verb, out, err)
        lines = err.strip().splitlines()
        assert len(lines) == 1 and names_field(lines[0], path, field) and words in lines[0], lines


def test_the_mechanism_alone_has_nothing_to_reduce(main_cli, write_scene):
    path = write_scene(f'[mechanism]\n{GUIDE}\n[position]\nangle = "44 deg"\n')
    status, out, err = main_cli("solve", path)
    assert status == 2 and f"{path}: position: reduces the [[member]]s of a mechanism: give them" in unplaced(err, path)


def test_a_gear_train_needs_no_angle(main_cli, write_scene):
    """Constant ratios and loads: the equivalents are those at any angle, and the scene need not invent one."""
    text = """
[mechanism]
kind = "gear_train"
ratios = [-0.25]
[[member]]
name = "pinion"
part = 0
inertia = "0.01 kg*m^2"
[[member]]
name = "wheel"
part = 1
inertia = "0.8 kg*m^2"
torque = "400 N*m"
[position]
reduce_to = "wheel"
"""
    status, out, err = main_cli("solve", write_scene(text), "--json")
    assert status == 0, err
    document = json.loads(out)
    assert document["angle"] == 0.0 and document["input_angle"] is None
    assert document["equivalent_inertia"] == pytest.approx(0.01 + 0.8 / 16, rel=1e-15)
    assert document["equivalent_moment"] == pytest.approx(-100.0, rel=1e-15) and document["sense"] == "resisting"
    assert document["reduced"]["equivalent_moment"] == pytest.approx(-400.0, rel=1e-15)
    assert document["reduced"]["equivalent_inertia"] == pytest.approx(16 * 0.01 + 0.8, rel=1e-15)


def test_an_input_angle_beyond_the_cycle_is_refused():
    """Members given their own ratios need not repeat with the mechanism: ψ = 300° of a crank at half the
    speed is φ = 600°, beyond a cycle of 360°."""
    from flyopt.io.position_section import read_mechanism_position
    from flyopt.machine.linkages import GuideBar

    members = [Member("lever", mass=1.0, velocity_ratio=([0.0, 2 * math.pi], [0.1, 0.2]))]
    with pytest.raises(SceneError) as err:
        read_mechanism_position({"input_angle": "300 deg"}, 2 * math.pi, GuideBar(0.15, 0.3, speed_ratio=0.5), members)
    assert err.value.field == "position.input_angle"
    assert "puts the reference shaft at 600 deg, outside the cycle, 0 to 360 deg" in str(err.value)


def test_a_cycle_is_not_solved_from_a_position_scene():
    """The refusals of plot and sweep are tests/test_calculation_scenes.py's; the API refuses it the same way."""
    with pytest.raises(SceneError) as raised:
        flyopt.solve(flyopt.load(CALC6))
    assert raised.value.field == "position"


def test_the_two_forms_of_position_agree_on_a_slider_crank():
    """Khurmi ch. 15's gas force on the piston at 60°: the crank's forces give the turning moment F_T r, the
    equivalents the moment of the same force on the slider member, F v/ω (no inertia force: no speed)."""
    from flyopt.machine.crank_forces import CrankPosition, crank_forces
    from flyopt.machine.kinematics import SliderCrank

    theta, r, l, gas = math.radians(60), 0.3, 1.2, 0.35e6 * math.pi * 0.5**2 / 4
    forces = crank_forces(CrankPosition(theta, r, l, 0.0, gas_force=gas), 26.0)
    slider = SliderCrank(r, l).kinematics("slider")  # φ = 0: the slider farthest from the crank, θ = 0
    piston = Member("piston", 0.0, 0.0, slider.velocity_ratio, slider.angular_ratio, force=-gas, force_sense="axial")
    result = equivalents_at(MechanismPosition(theta), [piston])  # the gas force acts towards the crank: −x
    assert result.equivalent_moment == pytest.approx(forces.turning_moment, rel=1e-12)
    assert result.sense == "driving"


def test_the_position_is_the_cycles_reduction_at_that_angle(write_scene):
    """One path: J_e at the position is the cycle's J_e(φ) of the same mechanism and members (reduce)."""
    from flyopt.machine.reduce import reduce

    for path, speed, load in ((CALC6, "60 rpm", "[torque.resisting]"), (CALC7, "300 rpm", "[torque.driving]")):
        at_position = solve_position(flyopt.load(path))
        machine = reduce(flyopt.load(write_scene(_cycle_scene(path, speed, f'{load}\nconstant = "unknown"\n'))))
        cycle_j = float(machine.j_machine(np.array([at_position.angle]))[0])
        assert at_position.equivalent_inertia == cycle_j


@pytest.mark.parametrize("speed_ratio, phase", [(1.0, 0.0), (0.5, 0.0), (-2.0, 0.3), (3.0, -1.0)])
def test_the_input_angle_is_the_mechanisms_own_angle(speed_ratio, phase):
    from flyopt.machine.equivalents import input_angle, reference_angle
    from flyopt.machine.linkages import GuideBar

    bar = GuideBar(0.15, 0.3, speed_ratio=speed_ratio, phase=phase)
    for psi in np.linspace(-2 * math.pi, 2 * math.pi, 17):
        phi = reference_angle(bar, float(psi))
        assert 0 <= phi < bar.period
        turns = (float(bar.own_angle(phi)) - psi) / (2 * math.pi)
        assert turns == pytest.approx(round(turns), abs=1e-12)
        back = input_angle(bar, phi)
        assert 0 <= back < 2 * math.pi
        assert abs((back - psi + math.pi) % (2 * math.pi) - math.pi) < 1e-12  # the same angle on the circle
