"""flyopt check lists every error of a scene, each on its TOML line (issue 29); solve still stops at the first."""

from conftest import PROBLEMS

BROKEN = """\
title = "three mistakes"
[machine]
sped = "1500 rpm"
delta = true

[torque.net]
areas = [1, -1]

[[material]]
density = "7200 kg/m^3"
"""


def test_check_lists_every_structural_error_with_its_line(main_cli, write_scene):
    path = write_scene(BROKEN)
    status, out, err = main_cli("check", path)
    assert status == 2 and out == ""
    assert err.splitlines() == [
        f"{path}:3: machine.sped: unknown key; did you mean 'speed'? "
        "(allowed here: cycle, delta, description, efficiency, gd2, inertia, speed)",
        f"{path}:4: machine.delta: must be a number or a string with its unit (e.g. '1500 rpm'), got boolean",
        f"{path}:9: material[0].name: is missing",
    ]


def test_solve_still_refuses_in_one_line(main_cli, write_scene):
    path = write_scene(BROKEN)
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == ""
    assert len(err.splitlines()) == 1 and err.startswith(f"flyopt: error: {path}: machine.sped: unknown key")


def test_a_sound_structure_shows_the_loaders_error_on_its_line(main_cli, write_scene):
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    line = next(k for k, row in enumerate(text.splitlines(), 1) if row.startswith("delta"))
    path = write_scene(text.replace("\ndelta = 0.05\n", "\ndelta = 3\n", 1))
    status, out, err = main_cli("check", path)
    assert status == 2
    assert (
        err == f"{path}:{line}: machine.delta: must lie between 0 and 2 (exclusive), got 3; "
        "typical values are 1/5 (crushers) to 1/300 (AC generators)\n"
    )


def test_a_good_scene_is_still_ok(main_cli):
    status, out, err = main_cli("check", PROBLEMS / "shear-press.toml")
    assert status == 0 and out.startswith(f"{PROBLEMS / 'shear-press.toml'}: ok") and err == ""


def test_a_flood_of_errors_is_cut_to_the_first_hundred_and_counted(main_cli, write_scene):
    from flyopt.cli.scene import MAX_LISTED

    keys = "".join(f"bad_{k} = 1\n" for k in range(MAX_LISTED + 20))
    path = write_scene("[machine]\n" + keys)
    status, out, err = main_cli("check", path)
    lines = err.splitlines()
    assert status == 2 and len(lines) == MAX_LISTED + 1
    assert lines[0].startswith(f"{path}:2: machine.bad_0: unknown key")
    assert lines[-1] == f"{path}:{MAX_LISTED + 2}: 20 more errors after these"


def test_a_field_the_file_does_not_write_is_said_without_a_line(main_cli, write_scene):
    """A [press] derives machine.delta from its slowdown: no line of the file writes it."""
    text = (PROBLEMS / "press-from-process.toml").read_text(encoding="utf-8")
    path = write_scene(text.replace('flywheel_speed_min = "200 rpm"', "slowdown = 1e-300"))
    status, out, err = main_cli("check", path)
    assert status == 2 and len(err.splitlines()) == 1
    assert err.startswith(f"flyopt: error: {path}: machine.delta: 1e-300 is out of range"), err
