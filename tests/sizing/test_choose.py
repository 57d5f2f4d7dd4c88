"""Model choice: the cheapest exact model runs, the others agree where they apply and are off where not."""

import json
import math

import pytest
from conftest import PROBLEMS
from numpy.testing import assert_allclose

import flyopt
from flyopt.cli.main import main
from flyopt.errors import SceneError


def models_of(analysis):
    return {m["model"]: m for m in analysis.models}


@pytest.mark.parametrize(
    "scene, expected",
    [
        ("shear-press", "energy"),
        ("compressor", "energy"),
        ("slider-crank-press", "energy_mass"),
        ("motor-press", "dynamic"),
        ("example1-net-areas", "energy"),
    ],
)
def test_the_cheapest_exact_model_is_chosen(scene, expected):
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / f"{scene}.toml"))
    assert analysis.model == expected
    assert analysis.model_reason


@pytest.mark.parametrize("scene", ["shear-press", "compressor"])
@pytest.mark.parametrize("forced", ["energy_mass", "dynamic"])
def test_all_models_agree_where_the_cheap_one_is_exact(scene, forced):
    """Constant inertia, angle-only torques: energy, energy–mass and the periodic solution agree to 1e-8."""
    s = flyopt.load(PROBLEMS / f"{scene}.toml")
    energy = flyopt.analyse(s)
    other = flyopt.analyse(s, model=forced)
    assert other.model == forced and f"the exact model for this scene is {energy.model}" in other.model_reason
    assert_allclose(other.j_required, energy.j_required, rtol=1e-8)


def test_cheaper_model_is_off_on_a_variable_inertia_press():
    """The slider-crank press: J_e varies, so the constant-inertia method misses δ."""
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "slider-crank-press.toml"), extras=("models",))
    rows = models_of(analysis)
    exact, cheap = rows["energy_mass"], rows["energy"]
    assert exact["exact"] and not cheap["exact"]
    assert abs(cheap["j_error"]) > 0.01  # > 1 % off in J_F
    assert abs(cheap["achieved_delta"] - analysis.delta) > 1e-3 * analysis.delta  # and δ is not what was asked
    assert_allclose(exact["achieved_delta"], analysis.delta, rtol=1e-12)


def test_cheaper_models_are_off_on_a_speed_dependent_press():
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "motor-press.toml"), extras=("models", "startup"))
    rows = models_of(analysis)
    assert analysis.model == "dynamic" and "energy_mass" not in rows  # constant J: energy_mass adds nothing
    assert abs(rows["energy"]["j_error"]) > 1e-3
    assert abs(rows["energy"]["achieved_delta"] - analysis.delta) > 1e-4 * analysis.delta
    # the mean speed follows from the motor's torque-speed balance, below synchronous/24
    assert analysis.omega_mean < 1500 * 2 * math.pi / 60 / 24
    assert analysis.startup.time > 0 and analysis.startup.note == ""


def test_verification_reproduces_delta_of_the_exact_method():
    """Periodic simulation with the designed flywheel: δ within 1e-6 relative of the allowed one."""
    solution = flyopt.solve(flyopt.load(PROBLEMS / "slider-crank-press.toml"), verify_design=True)
    v = solution.verification
    assert v.flagged is False
    # the designed flywheel gives at least J_F, so δ is at most the allowed one, and equal within the
    # design's own 1e-9 excess of inertia
    assert_allclose(v.achieved_delta, solution.analysis.delta, rtol=1e-6)
    assert v.achieved_delta <= solution.analysis.delta * (1 + 1e-6)


@pytest.mark.slow
def test_engine_members_verification():
    """The member-based engine (720°, variable J_e): simulation and energy–mass agree to 1e-6 in δ."""
    solution = flyopt.solve(flyopt.load(PROBLEMS / "engine-members.toml"), design_flywheel=False, verify_design=True)
    assert solution.analysis.model == "energy_mass"
    assert_allclose(solution.verification.achieved_delta, solution.analysis.delta, rtol=1e-6)


def test_forcing_a_cheap_model_says_it_is_not_exact(capsys):
    assert main(["solve", str(PROBLEMS / "slider-crank-press.toml"), "--model", "energy", "--json", "--no-design"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "energy"
    assert "the exact model for this scene is energy_mass" in data["model_reason"]


@pytest.mark.parametrize("scene", ["slider-crank-press", "motor-press"])
def test_verification_flags_a_flywheel_that_is_too_small(scene):
    """A flywheel 20 % below J_F misses δ and is flagged; at J_F it passes (by the exact simulation)."""
    import dataclasses

    from flyopt.pipeline import verify

    s = flyopt.load(PROBLEMS / f"{scene}.toml")
    analysis = flyopt.analyse(s)
    ok = verify(s, analysis)
    small = verify(s, dataclasses.replace(analysis, j_margin=0.8 * analysis.j_margin))
    assert ok.flagged is False and ok.achieved_delta <= analysis.delta * (1 + 1e-6)
    assert small.flagged is True and small.achieved_delta > 1.05 * analysis.delta


def test_flagged_verification_exits_4(monkeypatch, capsys):
    from flyopt import pipeline

    real = pipeline.verify

    def too_small(scene, analysis, design_result=None):
        import dataclasses

        return real(scene, dataclasses.replace(analysis, j_margin=0.5 * analysis.j_margin))

    monkeypatch.setattr(pipeline, "verify", too_small)
    assert main(["solve", str(PROBLEMS / "shear-press.toml"), "--verify", "--no-design"]) == 4
    assert "FLAGGED" in capsys.readouterr().out


def test_net_area_scene_refuses_other_models():
    with pytest.raises(SceneError, match="only the energy model applies"):
        flyopt.analyse(flyopt.load(PROBLEMS / "example1-net-areas.toml"), model="dynamic")


MECHANISM = """
[machine]
speed = "120 rpm"
delta = 0.1
[mechanism]
kind = "slider_crank"
crank = "0.08 m"
rod = "0.45 m"
[torque.driving]
constant = "unknown"
[torque.resisting]
constant = "100 N*m"
"""

BAD = [
    ('[[member]]\nname = "ram"\npart = "piston"\nmass = 10\n', "member[0].part", "'piston' is not known"),
    ('[[member]]\nname = "ram"\npart = "slider"\nvelocity_ratio = 0.1\n', "member[0].part", "not both"),
    ('[[member]]\nname = "ram"\nmass = "-1 kg"\n', "member[0].mass", "must not be negative"),
    ('[[member]]\nname = "ram"\npart = "slider"\nforce_sense = "pushing"\n', "member[0].force_sense", "not known"),
    ('[[member]]\nname = "ram"\npart = "slider"\nforce = "10 m"\n', "member[0].force", "wrong dimension"),
    ('[[member]]\nname = "ram"\npart = "rod"\ncentre = "0.9 m"\n', "member[0].part", "between the pins"),
]


@pytest.mark.parametrize("extra, field, words", BAD)
def test_bad_members(tmp_path, extra, field, words):
    path = tmp_path / "m.toml"
    path.write_text(MECHANISM + extra)
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ") and words in str(info.value)


@pytest.mark.parametrize(
    "mechanism, field, words",
    [
        ('kind = "slider_crank"\ncrank = "0.5 m"\nrod = "0.4 m"', "mechanism", "cannot turn fully"),
        ('kind = "geneva"', "mechanism.kind", "'geneva' is not known"),
    ],
)
def test_bad_mechanism(tmp_path, mechanism, field, words):
    text = MECHANISM.replace('kind = "slider_crank"\ncrank = "0.08 m"\nrod = "0.45 m"', mechanism)
    path = tmp_path / "m.toml"
    path.write_text(text)
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ") and words in str(info.value)


MOTOR = """
[machine]
speed = "60 rpm"
delta = 0.1
[torque.driving]
motor = { MOTOR }
[torque.resisting]
constant = "100 N*m"
[[shaft]]
name = "motor"
speed_ratio = 24.0
"""


@pytest.mark.parametrize(
    "motor, field, words",
    [
        ('kind = "stepper"', "torque.driving.motor.kind", "'stepper' is not known"),
        (
            'kind = "induction", rated_power = "5 kW", rated_speed = "1500 rpm", synchronous_speed = "1440 rpm"',
            "torque.driving.motor",
            "must be below its synchronous speed",
        ),
        (
            'kind = "induction", rated_power = "5 kW", rated_speed = "1440 rpm", synchronous_speed = "1500 rpm", '
            'shaft = "gearbox"',
            "torque.driving.motor.shaft",
            "no [[shaft]] is named 'gearbox'",
        ),
        (
            'kind = "induction", rated_power = "5 kW", rated_speed = "1440 rpm", synchronous_speed = "1500 rpm", '
            'model = "exact"',
            "torque.driving.motor.model",
            "not known",
        ),
        ('kind = "dc", no_load_speed = "1500 rpm"', "torque.driving.motor.rated_power", "is missing"),
    ],
)
def test_bad_motor(tmp_path, motor, field, words):
    path = tmp_path / "m.toml"
    path.write_text(MOTOR.replace("MOTOR", motor))
    with pytest.raises(SceneError) as info:
        flyopt.load(path)
    assert str(info.value).startswith(f"{path}: {field}: ") and words in str(info.value)


def test_speed_dependent_expression_runs_the_dynamic_model(tmp_path):
    """A load that grows with speed (fan-like) on a constant-inertia machine: the dynamic model runs,
    and as the speed term vanishes the result tends to the energy method's."""
    base = (
        '[machine]\nspeed = "600 rpm"\ndelta = 0.05\ninertia = "0.5 kg*m^2"\n'
        '[torque.driving]\nconstant = "unknown"\n[torque.resisting]\nexpression = "{expr}"\nunit = "N*m"\n'
    )
    results = {}
    for k, expr in (("speed", "300 + 200*sin(phi) + 0.01*omega**2"), ("none", "300 + 200*sin(phi) + 0*omega")):
        path = tmp_path / f"{k}.toml"
        path.write_text(base.format(expr=expr))
        results[k] = flyopt.analyse(flyopt.load(path))
    assert results["speed"].model == "dynamic" and results["none"].model == "dynamic"
    plain = tmp_path / "plain.toml"
    plain.write_text(base.format(expr="300 + 200*sin(phi)"))
    energy = flyopt.analyse(flyopt.load(plain))
    assert energy.model == "energy"
    assert_allclose(results["none"].j_required, energy.j_required, rtol=1e-8)


def test_the_chosen_model_is_solved_once(monkeypatch):
    """The comparison of models reuses the chosen model's requirement instead of solving
    the periodic dynamic problem a second time, with the same rows as a comparison that
    solves every model itself."""
    from flyopt.sizing import choose

    scene = flyopt.load(PROBLEMS / "motor-press.toml")
    calls = []
    solve = choose.requirement

    def counted(machine, model, indicator=None, **options):
        calls.append(model)
        return solve(machine, model, indicator, **options)

    monkeypatch.setattr(choose, "requirement", counted)
    analysis = flyopt.analyse(scene, extras=("models",))
    assert analysis.model == choose.DYNAMIC and calls.count(choose.DYNAMIC) == 1
    fresh = choose.compare(analysis.machine, analysis.model, analysis.indicator)
    assert [row["model"] for row in fresh] == [row["model"] for row in analysis.models]
    for ours, theirs in zip(analysis.models, fresh):
        assert_allclose(ours["j_required"], theirs["j_required"], rtol=1e-12)
        assert_allclose(ours["achieved_delta"], theirs["achieved_delta"], rtol=1e-9)
    with pytest.raises(ValueError, match="not of the chosen"):
        choose.compare(analysis.machine, choose.ENERGY, analysis.indicator, known=analysis.requirement)
