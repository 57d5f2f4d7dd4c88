"""A scene that is one calculation ([operation], [position], [electric_drive], [power_chain]) has no cycle: ``solve``,
``check`` and ``report`` answer it; every other command refuses it in one line naming its section, exit 2 (a plot of
an [electric_drive] once failed with a traceback)."""

from pathlib import Path

import pytest
from conftest import run_flyopt, unplaced

TEXTBOOK = Path(__file__).resolve().parents[1] / "problems" / "textbook"
SCENES = {
    "operation": "khurmi-16-21.toml",
    "position": "khurmi-15-crank-forces.toml",
    "electric_drive": "seed-004-lathe-drive.toml",
    "power_chain": "seed-001-5-8-parallel-machines.toml",
}
#: The calculations that need machine.speed (a power chain is given by its machines' powers).
NEEDS_SPEED = ("electric_drive", "operation", "position")


#: Every form of calculation: the [position] of a mechanism's equivalents beside that of a crank's forces (the
#: members' loads of a position scene are no cycle's torques: a sweep once reduced them as one, with a traceback).
FORMS = [*SCENES.items(), ("position", "seed000-calc6-guide-bar-position.toml")]


@pytest.mark.parametrize(("section", "scene"), FORMS)
@pytest.mark.parametrize(
    "command",
    [
        ["plot", "--what", "speed", "-o", "{out}.png"],
        ["sweep", "--vary", "speed=100:200:2", "-o", "{out}.csv"],
    ],
)
def test_every_other_command_refuses_a_calculation_in_one_line(section, scene, command, tmp_path):
    out = tmp_path / "out"
    args = [a.format(out=out) for a in command]
    run = run_flyopt(args[0], TEXTBOOK / scene, *args[1:])
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and f"{section}: is one calculation" in lines[0] and "Traceback" not in run.stderr
    assert not list(tmp_path.iterdir())


#: Each calculation's key answers as the report shows them in engineering units (4 digits, the default since
#: issue 29; 6 before), each the book's published answer to its rounding (the comments of the scene):
#: {section: [answers]}.
ANSWERS = {
    "operation": ["257.6 rpm", "18 at most"],  # Khurmi 16.21: ω₂ ≈ 257.6 rpm, 18 rivets a minute
    "position": ["68.72 kN", "19.28 kN", "14.49 kN·m"],  # Khurmi ch. 15: F_L 68.72 kN, F_I 19.28, T 14.49 kN·m
    "electric_drive": ["3.796 kW", "5.207 kW", "4.769 N·m²"],  # seed 004 ex. 2: 3.796 kW, 5.207 kW, 4.769 N·m²
    "power_chain": ["7.22 kW", "2.31 kW", "9.531 kW"],  # seed 001 ex. 5-8: P_dA 7220.2, P_dB 2310.5, 9530.7 W
}


# the PDF of each in the slow run; a calculation report's PDF is in the default run in
# tests/report/test_calculation_report.py (hostile names in both formats)
@pytest.mark.parametrize("suffix", [".html", pytest.param(".pdf", marks=pytest.mark.slow)])
@pytest.mark.parametrize("section", sorted(SCENES))
def test_report_writes_a_calculation_with_its_answers(section, suffix, tmp_path):
    """``flyopt report`` of a calculation writes the report (exit 0) and its text holds the book's answers."""
    out = tmp_path / f"out{suffix}"
    run = run_flyopt("report", TEXTBOOK / SCENES[section], "-o", out)
    assert run.returncode == 0, run.stderr
    assert out.is_file() and run.stderr == ""
    if suffix == ".pdf":
        from pypdf import PdfReader

        text = " ".join(" ".join(page.extract_text() or "" for page in PdfReader(str(out)).pages).split())
    else:
        text = out.read_text(encoding="utf-8")
    for answer in ANSWERS[section]:
        assert answer in text, (section, answer)
    assert ("CALCULATION REPORT" if suffix == ".pdf" else "Calculation report") in text  # not a design report


@pytest.mark.parametrize("section", sorted(SCENES))
def test_solve_and_check_answer_it(section):
    for verb in ("solve", "check"):
        run = run_flyopt(verb, TEXTBOOK / SCENES[section])
        assert run.returncode == 0, run.stderr


@pytest.mark.parametrize("section", NEEDS_SPEED)
def test_a_calculation_that_needs_the_speed_refuses_a_scene_without_it(section, tmp_path):
    """machine.speed may be left out of a calculation's scene only where the calculation needs no speed."""
    text = (TEXTBOOK / SCENES[section]).read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if not line.startswith("speed =")]
    assert len(lines) == len(text.splitlines()) - 1  # the scene gave exactly one machine.speed
    scene = tmp_path / "no-speed.toml"
    scene.write_text("\n".join(lines), encoding="utf-8")
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 2, run.stderr
    assert unplaced(run.stderr, scene).strip().splitlines() == [
        f"flyopt: error: {scene}: machine.speed: is missing (the [{section}] calculation needs it)"
    ]


def test_a_power_chain_needs_no_machine_and_takes_one_given():
    """[power_chain] stands without [machine]; a machine.speed given beside it changes nothing."""
    import flyopt
    from flyopt.io.scene import from_dict
    from flyopt.pipeline import solve_calculation

    chain = {"stages": [0.9], "power": "1 kW"}
    alone = solve_calculation(from_dict({"power_chain": chain}))
    given = solve_calculation(from_dict({"machine": {"speed": "100 rpm"}, "power_chain": chain}))
    assert alone.motor_power == given.motor_power == 1000 / 0.9
    assert set(SCENES) == set(flyopt.names.CALCULATIONS)
