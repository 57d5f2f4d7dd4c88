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


def test_solve_still_refuses_in_one_line_placed_on_its_line(main_cli, write_scene):
    """solve (and every command) says the loader's first error alone, on the line check gives it."""
    path = write_scene(BROKEN)
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == ""
    assert len(err.splitlines()) == 1 and err.startswith(f"flyopt: error: {path}:3: machine.sped: unknown key")


def test_a_sound_structure_shows_the_loaders_error_on_its_line(main_cli, write_scene):
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    line = next(k for k, row in enumerate(text.splitlines(), 1) if row.startswith("delta"))
    path = write_scene(text.replace("\ndelta = 0.05\n", "\ndelta = 3\n", 1))
    status, out, err = main_cli("check", path)
    assert status == 2
    assert (
        err == f"{path}:{line}: machine.delta: must lie between 1e-06 and 2 (2 excluded), got 3; "
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


def test_a_press_delta_too_small_names_the_field_the_file_writes_on_its_line(main_cli, write_scene):
    """A [press] derives its δ from its slowdown. A slowdown that gives a δ too small to compute with is
    said of press.slowdown, on its line, by the one rule of every δ (it was said of machine.delta, a field
    the file does not write, without a line)."""
    text = (PROBLEMS / "press-from-process.toml").read_text(encoding="utf-8")
    path = write_scene(text.replace('flywheel_speed_min = "200 rpm"', "slowdown = 1e-300"))
    line = next(
        k for k, row in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if row.startswith("slowdown")
    )
    status, out, err = main_cli("check", path)
    assert status == 2 and len(err.splitlines()) == 1
    assert err.startswith(
        f"{path}:{line}: press.slowdown: 1e-300 gives δ = 2s/(2 − s) = 1e-300; δ must lie between 1e-06 and 2"
    ), err


def test_value_errors_in_different_sections_are_listed_at_once_each_on_its_line(main_cli, write_scene):
    """delta = -1, a material's negative density, a shaft's negative ratio and a title too long: four sections,
    four lines, in the order of the file (check listed the first alone, one run per mistake). The design's
    geometry 'blob' is not said while a shaft it would sit on is wrong (the design is read with its shafts);
    with the shafts sound it is."""
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    lines = text.splitlines()
    row = {key: next(k for k, r in enumerate(lines, 1) if r.startswith(key)) for key in ("delta", "speed_ratio")}
    broken = (
        text.replace("\ndelta = 0.05\n", "\ndelta = -1\n", 1)
        .replace("speed_ratio = 1.0", "speed_ratio = -3", 1)
        .replace('geometry = "rim"', 'geometry = "blob"', 1)
        .replace('title = "Shear press (worked example 2)"', 'title = "' + "t" * 201 + '"', 1)
    )
    broken += '\n[[material]]\nname = "lead"\ndensity = "-11340 kg/m^3"\nmax_rim_speed = "20 m/s"\n'
    path = write_scene(broken)
    status, out, err = main_cli("check", path)
    said = err.splitlines()
    assert status == 2 and out == ""
    assert [line.split(": ")[0] for line in said] == [
        f"{path}:{next(k for k, r in enumerate(lines, 1) if r.startswith('title'))}",
        f"{path}:{row['delta']}",
        f"{path}:{row['speed_ratio']}",
        f"{path}:{len(broken.splitlines()) - 1}",
    ], said
    assert (
        ": machine.delta: must lie between 1e-06 and 2" in said[1]
        and ": shaft[0].speed_ratio: must be positive" in said[2]
    )
    assert "material[0].density" in said[3] and "title: is 201 characters long" in said[0]
    assert not any("geometry" in line for line in said)
    # the shafts sound: the design is read, and its geometry said beside the delta
    path = write_scene(
        text.replace("\ndelta = 0.05\n", "\ndelta = -1\n", 1).replace('geometry = "rim"', 'geometry = "blob"')
    )
    status, _, err = main_cli("check", path)
    assert status == 2 and [line.split(": ")[1] for line in err.splitlines()] == ["machine.delta", "design.geometry"]
    # solve still stops at the first, in one line
    status, _, err = main_cli("solve", path)
    assert status == 2 and len(err.splitlines()) == 1 and "machine.delta" in err


def test_a_calculation_s_design_values_are_not_said_beside_its_refusal_of_the_design(main_cli, write_scene):
    """[operation] refuses a [design] table (give one of them): the design's own values are no error of such a
    scene, and fixing them would not be the fix; only the machine's δ is said beside the loader's error."""
    text = (
        '[machine]\nspeed = "300 rpm"\ndelta = -1\n\n[operation]\nenergy = "10 kJ"\nduration = "1 s"\n'
        'motor_power = "3 kW"\n\n[design]\nmax_outer_diameter = "-1 m"\n'
    )
    path = write_scene(text)
    status, _, err = main_cli("check", path)
    assert status == 2 and [line.split(": ")[1] for line in err.splitlines()] == ["machine.delta"], err


def test_errors_of_one_section_are_listed_each_on_its_line(main_cli, write_scene):
    """Was: one error a section. machine's speed and delta, two [[material]] tables and two [[shaft]]s each wrong
    on their own: six lines, each naming its field on its line; solve still says the first alone."""
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    broken = (
        text.replace("\ndelta = 0.05\n", "\ndelta = -1\n", 1)
        .replace('speed = "1500 rpm"', 'speed = "-1500 rpm"', 1)
        .replace("speed_ratio = 1.0", "speed_ratio = -3", 1)
    )
    assert broken.count("-") >= text.count("-") + 3  # each replacement took
    broken += (
        '\n[[shaft]]\nname = "spindle"\nspeed_ratio = 0\n'
        '\n[[material]]\nname = "lead"\ndensity = "-11340 kg/m^3"\nmax_rim_speed = "20 m/s"\n'
        '\n[[material]]\nname = "tin"\ndensity = "7300 kg/m^3"\nmax_rim_speed = "-20 m/s"\n'
    )
    path = write_scene(broken)
    status, out, err = main_cli("check", path)
    lines = broken.splitlines()

    def row(start):
        return next(k for k, r in enumerate(lines, 1) if r.startswith(start))

    said = {line.split(": ")[1]: int(line.split(": ")[0].rsplit(":", 1)[1]) for line in err.splitlines()}
    assert status == 2 and out == ""
    assert said == {
        "machine.speed": row('speed = "-1500 rpm"'),
        "machine.delta": row("delta = -1"),
        "shaft[0].speed_ratio": row("speed_ratio = -3"),
        "shaft[1].speed_ratio": row("speed_ratio = 0"),
        "material[0].density": row('density = "-11340'),
        "material[1].max_rim_speed": row('max_rim_speed = "-20'),
    }, err
    status, _, err = main_cli("solve", path)
    assert status == 2 and len(err.splitlines()) == 1


def test_the_design_of_a_scene_with_its_flywheel_is_not_said(main_cli, write_scene):
    """A [flywheel] that exists refuses a [design] before reading it (give one of them): the design's own values
    are no error of such a scene, and fixing them would not be the fix; only the machine's δ is said."""
    text = (
        '[machine]\nspeed = "100 rpm"\ndelta = -1\n\n[torque.driving]\nconstant = "100 N*m"\n'
        '[torque.resisting]\nconstant = "unknown"\n\n[flywheel]\ninertia = "10 kg*m^2"\n\n'
        '[design]\nmaterials = ["nope"]\n'
    )
    path = write_scene(text)
    status, _, err = main_cli("check", path)
    assert status == 2 and [line.split(": ")[1] for line in err.splitlines()] == ["machine.delta"], err


def test_a_scene_without_its_machine_speed_delta_or_torques_is_told_what_to_write_there(main_cli, write_scene):
    """A new user's file, built up from nothing by what flyopt says is missing: each refusal names the field and
    what to write there (they said "is missing" alone), and writing its example moves on to the next, until the
    scene is sound."""
    steps = [
        (
            "",
            [
                "flyopt: error: {path}: machine: is missing: give [machine] with the mean speed and the allowed δ "
                '(speed = "1500 rpm", delta = 0.05), or a [press] from its process data'
            ],
        ),
        (
            "[machine]\n",
            [
                '{path}:1: machine.speed: is missing: the reference shaft\'s mean speed, e.g. speed = "1500 rpm"',
                "{path}:1: machine.delta: is missing: the allowed coefficient of fluctuation of speed δ, "
                'e.g. delta = 0.05 or "5 %"',
            ],
        ),
        (
            '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n',
            [
                "flyopt: error: {path}: torque: is missing: give "
                "[torque.driving] and [torque.resisting], or [torque.net] "
                "with the net areas"
            ],
        ),
    ]
    for text, expected in steps:
        path = write_scene(text)
        for command in ("check", "solve"):
            status, out, err = main_cli(command, path)
            lines = err.splitlines()
            assert status == 2 and out == "", (command, err)
            wanted = [line.format(path=path) for line in expected]
            if command == "solve":  # one line, the first error on its line, as every command but check refuses
                wanted = [wanted[0].replace(f"{path}:1:", f"flyopt: error: {path}:1:")]
            assert len(lines) == len(wanted) and all(a.startswith(b) for a, b in zip(lines, wanted)), (command, err)
    path = write_scene('[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.net]\nareas = [1, -1]\n')
    status, out, err = main_cli("check", path)
    assert status == 0 and err == "", err


def test_a_missing_quantity_says_what_to_give(main_cli, write_scene):
    """A required quantity left out said "engine.bore: is missing" and no more (a new user deleting a line of the
    engine template): it says what kind of quantity goes there, with an example that reads."""
    scene = write_scene("")
    assert main_cli("new", "engine", "-o", scene, "--force")[0] == 0
    text = scene.read_text(encoding="utf-8")
    line = next(line for line in text.splitlines() if line.startswith("bore = "))
    scene.write_text(text.replace(line + "\n", ""), encoding="utf-8")
    status, _, err = main_cli("check", scene)
    assert status == 2 and "engine.bore: is missing: give a length (e.g. '0.8 m')" in err, err
    scene.write_text(text.replace(line, "bore = '0.8 m'"), encoding="utf-8")  # the example reads as a length
    status, _, err = main_cli("check", scene)
    assert "engine.bore" not in err, err


CELLS = """\
title = "a bad cell"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
unit = "N*m"
angle_unit = "deg"
points = [
  [0, 1600],
  [45, 1600],
  [90, 200],
  [180, "9000 m"],
  [360, 200],
]
[torque.driving]
constant = "unknown"
"""


def test_a_bad_cell_of_a_table_is_placed_on_its_row_by_check_and_by_solve(main_cli, write_scene, monkeypatch):
    """A cell's field names its column after the row ("points[3] torque"): it was placed on the table's first
    line (7), not on the row that writes it (12), by check and then by every command."""
    path = write_scene(CELLS)
    row = 1 + next(k for k, line in enumerate(CELLS.splitlines()) if "9000 m" in line)
    assert row == 12
    status, _, err = main_cli("check", path)
    assert status == 2 and err.startswith(f"{path}:{row}: torque.resisting.points[3] torque: "), err
    status, _, err = main_cli("solve", path)
    assert status == 2 and err.startswith(f"flyopt: error: {path}:{row}: torque.resisting.points[3] torque: "), err
    # the scene named as the user wrote it, "./scene.toml" (the loader names it "scene.toml"): placed too
    monkeypatch.chdir(path.parent)
    status, _, err = main_cli("solve", f"./{path.name}")
    assert status == 2 and err.startswith(f"flyopt: error: {path.name}:{row}: "), err


def test_a_refusal_of_a_scene_over_the_placing_limit_is_said_without_its_line(main_cli, write_scene, monkeypatch):
    """Placing scans the whole file in Python (about 1 s a MB): a scene over exits.PLACED_BYTES is refused at once,
    named as before; check still places it."""
    from flyopt.cli import exits

    path = write_scene(CELLS)
    monkeypatch.setattr(exits, "PLACED_BYTES", len(CELLS.encode()) - 1)
    status, _, err = main_cli("solve", path)
    assert status == 2 and err.startswith(f"flyopt: error: {path}: torque.resisting.points[3] torque: "), err
    status, _, err = main_cli("check", path)
    assert status == 2 and err.startswith(f"{path}:12: "), err
