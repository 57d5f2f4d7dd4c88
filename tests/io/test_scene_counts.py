"""How many items each list of a scene may hold: refused at load, in one line naming the list, before an item is
read, by check as by solve.

Before, nothing held them: a shaft of 5,000 steps ran the beam's check for over 5 minutes and 5.6 GB (killed),
6,000 [[shaft]] tables took 68 s, a million side loads 78 s and 5.2 GB, 2,000 materials 10 s (a scene file's
100 MB would hold 300,000), and each motor option, fixed ratio, member, cam segment or arm count is more work.
"""

import pytest
from conftest import PROBLEMS
from test_scene_bounds import refused_by_check_and_solve

import flyopt
from flyopt.io.design_section import MAX_ARM_COUNTS
from flyopt.io.drive import MAX_OPTIONS
from flyopt.io.material_section import MAX_MATERIALS
from flyopt.io.member_section import MAX_MEMBERS
from flyopt.io.shaft_section import MAX_SHAFTS, MAX_STEPS

SHAFT_SCENE = "punch-press-shaft.toml"
SEGMENTS = (
    'segments = [{ to = "120 mm", diameter = "60 mm" }, { to = "520 mm", diameter = "80 mm" }, '
    '{ to = "700 mm", diameter = "60 mm" }]'
)
LOADS = 'loads = [{ at = "660 mm", force = "12 kN", angle = "20 deg", description = "gear mesh force on the pinion" }]'


def _scene(tmp_path, problem, old, new, tail=""):
    text = (PROBLEMS / problem).read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "scene.toml"
    path.write_text(text.replace(old, new, 1) + tail, encoding="utf-8")
    return path


def _steps(n):
    """``n`` steps of 60 mm ending at 700 mm, the last through the bearings, wheel and pinion."""
    ends = [f'{{ to = "{k + 1} mm", diameter = "60 mm" }}' for k in range(n - 1)] + [
        '{ to = "700 mm", diameter = "60 mm" }'
    ]
    return f"segments = [{', '.join(ends)}]"


def _loads(n):
    return "loads = [" + ", ".join(f'{{ at = "{100 + k} mm", force = "10 N" }}' for k in range(n)) + "]"


def _shafts(n):
    return "".join(f'\n[[shaft]]\nname = "extra{k}"\nspeed_ratio = {2 + k / 100}\n' for k in range(n))


def _materials(n):
    return "".join(
        f'\n[[material]]\nname = "m{k}"\ndensity = "7100 kg/m^3"\ntensile_strength = "400 MPa"\nductile = false\n'
        for k in range(n)
    )


# (what is changed, the list's field, its limit, the scene with n items)
CASES = {
    "shafts": ("shaft", MAX_SHAFTS, lambda p, n: _scene(p, SHAFT_SCENE, "[design]", _shafts(n - 3) + "\n[design]")),
    "steps": ("shaft[1].segments", MAX_STEPS, lambda p, n: _scene(p, SHAFT_SCENE, SEGMENTS, _steps(n))),
    "loads": ("shaft[1].loads", MAX_STEPS, lambda p, n: _scene(p, SHAFT_SCENE, LOADS, _loads(n))),
    "materials": ("material", MAX_MATERIALS, lambda p, n: _scene(p, SHAFT_SCENE, "", "", _materials(n - 1))),
}


@pytest.mark.parametrize("case", CASES)
def test_a_list_over_its_limit_is_refused_and_one_at_it_loads(tmp_path, case):
    field, limit, scene = CASES[case]
    assert limit in (64, 256)
    refused_by_check_and_solve(scene(tmp_path, limit + 1), field, f"has {limit + 1} ")
    refused_by_check_and_solve(scene(tmp_path, limit + 1), field, f"(allowed: at most {limit})")
    loaded = flyopt.load(scene(tmp_path, limit))
    counts = {
        "shafts": len(loaded.shafts),
        "steps": len(loaded.shafts[1].layout.steps),
        "loads": len(loaded.shafts[1].layout.loads),
        "materials": len(loaded.materials),
    }
    assert counts[case] == limit


def _options(n):
    return "".join(
        f'\n[[motor_option]]\nname = "m{k}"\nrated_power = "{5 + k} kW"\nrated_speed = "1440 rpm"\n'
        f'synchronous_speed = "1500 rpm"\nrotor_inertia = "0.03 kg*m^2"\n'
        for k in range(n)
    )


@pytest.mark.parametrize(
    "problem, old, new, tail, field, what",
    [
        (
            "press-drive.toml",
            'motors = "iec_4pole"\n',
            "",
            _options(MAX_OPTIONS + 1),
            "motor_option",
            "[[motor_option]] tables",
        ),
        (
            "press-drive.toml",
            "ratio = [8, 25] ",
            f"ratios = [{', '.join(str(8 + k / 10) for k in range(MAX_OPTIONS + 1))}] ",
            "",
            "drive.ratios",
            "ratios",
        ),
        (
            "slider-crank-press.toml",
            "",
            "",
            "".join(f'\n[[member]]\nname = "extra{k}"\nmass = "1 kg"\n' for k in range(MAX_MEMBERS - 1)),
            "member",
            "[[member]] tables",
        ),
        (
            "textbook/seed000-calc7-gear-sine-mechanism-position.toml",
            '  {motion = "return", law = "simple_harmonic", angle = "180 deg"},\n',
            '  {motion = "return", law = "simple_harmonic", angle = "1 deg"},\n' * MAX_MEMBERS,
            "",
            "mechanism.segments",
            "segments",
        ),
        (
            SHAFT_SCENE,
            'geometry = "rim_web"',
            f'geometry = "rim_arms"\narms = [{", ".join(str(3 + k) for k in range(MAX_ARM_COUNTS + 1))}]',
            "",
            "design.arms",
            "arm counts",
        ),
    ],
    ids=["motor-options", "drive-ratios", "members", "cam-segments", "arm-counts"],
)
def test_each_other_list_over_its_limit_is_refused(tmp_path, problem, old, new, tail, field, what):
    limit = {"motor_option": MAX_OPTIONS, "drive.ratios": MAX_OPTIONS, "design.arms": MAX_ARM_COUNTS}.get(
        field, MAX_MEMBERS
    )
    # each scene above gives one more than the limit: press-drive none of its own motors, slider-crank-press
    # two members, the cam a rise before the copies of its return
    path = _scene(tmp_path, problem, old, new, tail)
    refused_by_check_and_solve(path, field, f"has {limit + 1} {what} (allowed: at most {limit}")


def _train_scene(tmp_path, pairs):
    """motor-press-drive-train with ``pairs`` more (inertia, shaft piece) pairs on the crankshaft before its crank:
    12 + 2 ``pairs`` elements, the crankshaft's inertia moved from the crank to the new inertias."""
    extra = "".join(
        f'  {{ name = "mass {k}", shaft = "crankshaft", inertia = "0.001 kg*m^2" }},\n'
        f'  {{ name = "piece {k}", length = "500 mm", diameter = "140 mm" }},\n'
        for k in range(pairs)
    )
    crank = '  { name = "crank", shaft = "crankshaft" },'
    return _scene(tmp_path, "motor-press-drive-train.toml", crank, extra + crank)


def test_a_train_of_more_elements_than_its_limit_is_refused_and_one_at_it_loads(tmp_path):
    """4,012 elements took `solve` 9.7 s and 410 MB, the torsional model growing with their square."""
    from flyopt.io.train_section import MAX_ELEMENTS

    assert MAX_ELEMENTS == 128
    pairs = (MAX_ELEMENTS - 12) // 2
    train = flyopt.load(_train_scene(tmp_path, pairs)).shafts[1].layout.train
    assert len(train) == MAX_ELEMENTS
    path = _train_scene(tmp_path, pairs + 1)
    refused_by_check_and_solve(path, "shaft[1].train", f"has {MAX_ELEMENTS + 2} elements (allowed: at most 128)")
