"""Power through stages in series and branches in parallel ([power_chain], issue 27 item 8).

References: the published answers of ../shared/seeds/001 (exercises 5-7 and 5-8) and 004 (example 2)
at the books' rounding; each written again by hand from the books' formulas (P_d = P_r / (η_1 η_2 ⋯),
added over the branches), and the energy balance stage by stage (the motor's power less every
stage's loss P_in (1 − η) is what the machines deliver), which flyopt does not compute.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import jsonschema
import pytest
from conftest import assert_published, run_flyopt

import flyopt
from flyopt.errors import SceneError
from flyopt.io.scene import from_dict
from flyopt.machine.transmission import BranchFlow, PowerBranch, power_flow
from flyopt.outputs.documents import calculation_document, json_text, schema
from flyopt.pipeline import solve_calculation

TEXTBOOK = Path(__file__).resolve().parent.parent / "problems" / "textbook"


def _solve(name):
    return solve_calculation(flyopt.load(TEXTBOOK / name))


def _stage_losses(branch: BranchFlow) -> float:
    """Σ P_in (1 − η) over every stage of the tree: the energy balance, stage by stage."""
    own = sum(p * (1 - eta) for p, eta in zip(branch.stage_powers, branch.branch.stages))
    return own + sum(_stage_losses(b) for b in branch.branches)


def test_seed_001_5_7_conveyor_at_the_books_rounding_and_exactly():
    flow = _solve("seed-001-5-7-conveyor.toml")
    assert_published(flow.efficiency, "0.82")  # the book's η = η1 η2² η3 = 0.82
    # the book divides by η rounded to 0.82 first: 5500 × 1.2 / 0.82 = 8048.8 W
    assert_published(5500 * 1.2 / round(flow.efficiency, 2), "8048.8")
    # η to four digits, 0.8223, gives 8026.3 W; the exact product 0.8223466 gives 8025.8 W
    assert_published(5500 * 1.2 / round(flow.efficiency, 4), "8026.3")
    assert_published(flow.motor_power, "8025.8")
    # by hand: F v / (η1 η2 η2 η3)
    assert flow.motor_power == pytest.approx(5500 * 1.2 / (0.95 * 0.97 * 0.97 * 0.92), rel=1e-14)
    assert flow.delivered == pytest.approx(6600.0, rel=1e-15)
    assert flow.losses == pytest.approx(_stage_losses(flow.trunk), rel=1e-13)
    assert flow.trunk.branches == () and flow.trunk.power == pytest.approx(6600.0, rel=1e-15)


def test_seed_001_5_8_two_machines_in_parallel():
    flow = _solve("seed-001-5-8-parallel-machines.toml")
    a, b = flow.trunk.branches
    assert (a.branch.name, b.branch.name) == ("A", "B")
    assert_published(a.stage_powers[-1], "6250")  # P_rA = P_A / η_A, entering machine A
    assert_published(b.stage_powers[-1], "2000")  # P_rB
    assert_published(a.motor_power, "7220.2")  # P_dA = P_rA / (η2 η1²)
    assert_published(b.motor_power, "2310.5")  # P_dB
    assert_published(flow.motor_power, "9530.7")  # P_d = P_dA + P_dB
    # by hand, the book's way
    path = 0.92 * 0.97 * 0.97
    assert a.motor_power == pytest.approx(5000 / 0.8 / path, rel=1e-14)
    assert b.motor_power == pytest.approx(1000 / 0.5 / path, rel=1e-14)
    assert flow.motor_power == pytest.approx(a.motor_power + b.motor_power, rel=1e-15)
    assert flow.efficiency == pytest.approx(6000 / (6250 / path + 2000 / path), rel=1e-14)
    # the energy balance: what every stage loses, from the powers entering them
    assert flow.losses == pytest.approx(_stage_losses(flow.trunk), rel=1e-13)
    assert a.losses + b.losses == pytest.approx(flow.losses, rel=1e-14)
    # the trunk ends where the branches start: what they draw there
    assert flow.trunk.power == pytest.approx(a.stage_powers[0] + b.stage_powers[0], rel=1e-15)


def test_seed_004_lathe_cutting_and_motor_power():
    flow = _solve("seed-004-lathe-power.toml")
    assert_published(flow.delivered / 1e3, "3.796")  # (1) P = T 2π n / 60
    assert_published(flow.motor_power / 1e3, "5.207")  # (2) P / 0.9³
    assert flow.delivered == pytest.approx(150 * 1450 / 6 * math.pi / 30, rel=1e-14)
    # the same number as the [electric_drive] scene of the same exercise
    drive = _solve("seed-004-lathe-drive.toml")
    assert flow.motor_power == pytest.approx(drive.motor_power, rel=1e-13)


def test_a_mixed_chain_nested_branches():
    """混联: a trunk splitting into a machine and a branch that splits again, by hand and by the balance."""
    tree = PowerBranch(
        "trunk",
        (0.95,),
        (
            PowerBranch("A", (0.9,), power=3000.0),
            PowerBranch(
                "B",
                (0.98, 0.96),
                (PowerBranch("B1", (0.8,), power=1000.0), PowerBranch("B2", (0.7, 0.5), power=500.0)),
            ),
        ),
    )
    flow = power_flow(tree)
    b1 = 1000 / 0.8
    b2 = 500 / 0.5 / 0.7
    b = (b1 + b2) / 0.96 / 0.98
    motor = (3000 / 0.9 + b) / 0.95
    assert flow.motor_power == pytest.approx(motor, rel=1e-14)
    a_flow, b_flow = flow.trunk.branches
    assert b_flow.stage_powers[0] == pytest.approx(b, rel=1e-14)
    assert b_flow.branches[1].path_efficiency == pytest.approx(0.95 * 0.98 * 0.96 * 0.7 * 0.5, rel=1e-15)
    assert b_flow.motor_power == pytest.approx(b / 0.95, rel=1e-14)
    assert flow.losses == pytest.approx(_stage_losses(flow.trunk), rel=1e-13)
    assert flow.efficiency == pytest.approx(4500 / motor, rel=1e-14)


def test_the_json_is_its_own_kind_and_meets_the_schema():
    flow = _solve("seed-001-5-8-parallel-machines.toml")
    document = json.loads(json_text(calculation_document("power_chain", "t", "s.toml", flow.to_dict())))
    assert [e.message for e in jsonschema.Draft202012Validator(schema()).iter_errors(document)] == []
    assert document["units"]["motor_power"] == "W" and document["units"]["efficiency"] == "1"
    assert [b["name"] for b in document["trunk"]["branches"]] == ["A", "B"]
    assert document["trunk"]["branches"][0]["stages"][1] == {"efficiency": 0.8, "power": 6250.0}


def test_solve_prints_the_motor_power_and_each_branch():
    run = run_flyopt("solve", str(TEXTBOOK / "seed-001-5-8-parallel-machines.toml"))
    assert run.returncode == 0, run.stderr
    # 9,530.65 W, η 0.629548, 6,443.3 W: to four figures (issue 29; six before)
    assert "motor power P_in    9.531 kW" in run.stdout
    assert "overall efficiency  0.6295 (Σ P_out / P_in)" in run.stdout
    assert "  A: 6.443 →(0.97)→ 6.25 →(0.8)→ 5 kW" in run.stdout


LEAF = {"stages": [0.97, 0.8], "power": "5 kW"}


def _deep(levels):
    branch = LEAF
    for _ in range(levels):
        branch = {"branch": [branch]}
    return branch


@pytest.mark.parametrize(
    ("section", "field", "words"),
    [
        ({"stages": [1.2], "power": "1 kW"}, "power_chain.stages[0]", "(0, 1]"),
        ({"stages": [0.9, 0], "power": "1 kW"}, "power_chain.stages[1]", "(0, 1]"),
        ({"stages": 1.5, "power": "1 kW"}, "power_chain.stages", "(0, 1]"),
        ({"stages": [], "power": "1 kW"}, "power_chain.stages", "non-empty"),
        ({"stages": [0.9], "power": "-1 kW"}, "power_chain.power", "positive"),
        ({"stages": [0.9], "power": "0 W"}, "power_chain.power", "positive"),
        ({"stages": [0.9], "power": "1e12 W"}, "power_chain.power", "out of range"),
        ({"stages": [0.9], "force": "1e15 N", "velocity": "1 m/s"}, "power_chain.force", "out of range"),
        ({"stages": [0.9], "force": "1e9 N", "velocity": "1e3 m/s"}, "power_chain.force", "out of range"),
        ({"stages": [0.9], "power": "1 kW", "force": "1 kN"}, "power_chain.force", "not power and force"),
        ({"stages": [0.9], "power": "1 kW", "torque": "1 N*m"}, "power_chain.torque", "not power and torque"),
        ({"stages": [0.9], "force": "1 kN"}, "power_chain.velocity", "is missing"),
        ({"stages": [0.9], "velocity": "1 m/s"}, "power_chain.force", "is missing"),
        ({"stages": [0.9], "torque": "1 N*m", "velocity": "1 m/s"}, "power_chain.velocity", "goes with force"),
        ({"stages": [0.9], "power": "1 kW", "speed": "100 rpm"}, "power_chain.speed", "goes with torque"),
        ({"stages": [0.9]}, "power_chain", "neither"),
        ({"stages": [0.9], "branch": []}, "power_chain.branch", "array of 1 to"),
        ({"stages": [0.9], "branch": [{}]}, "power_chain.branch[0]", "neither"),
        ({"power": "1 kW", "branch": [LEAF]}, "power_chain.branch", "not both"),
        ({"branch": [{**LEAF, "name": "A"}, {**LEAF, "name": "A"}]}, "power_chain.branch[1].name", "twice"),
        ({"branch": [{**LEAF, "stages": [0.9, 1.01]}]}, "power_chain.branch[0].stages[1]", "(0, 1]"),
        ({"branch": [{**LEAF, "ratio": 2}]}, "power_chain.branch[0].ratio", "unknown key"),
        ({"branch": [{**LEAF, "name": ""}]}, "power_chain.branch[0].name", "1 to"),
        (_deep(9), "power_chain" + ".branch[0]" * 8 + ".branch", "more than 8 levels"),
    ],
)
def test_bad_chain_is_refused_naming_the_field(section, field, words):
    with pytest.raises(SceneError) as err:
        from_dict({"power_chain": section})
    assert err.value.field == field and words in str(err.value), str(err.value)


def test_eight_levels_of_branches_are_read():
    flow = power_flow(from_dict({"power_chain": _deep(8)}).power_chain)
    assert flow.motor_power == pytest.approx(5000 / 0.8 / 0.97, rel=1e-15)


def test_a_chain_beside_a_cycle_or_a_flywheel_is_refused():
    for other in ({"torque": {"net": {"areas": ["1 J", "-1 J"]}}}, {"flywheel": {"inertia": "1 kg*m^2"}}):
        with pytest.raises(SceneError) as err:
            from_dict({"power_chain": LEAF, **other})
        assert err.value.field == "power_chain" and f"[{next(iter(other))}]" in str(err.value)


def test_a_bad_scene_is_refused_in_one_line_exit_2(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text('[power_chain]\nstages = [0.9, 1.2]\npower = "1 kW"\n', encoding="utf-8")
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 2
    assert run.stderr.strip().splitlines() == [
        f"flyopt: error: {scene}:2: power_chain.stages[1]: must lie in (0, 1], got 1.2"
    ]


def test_the_model_refuses_what_the_reader_would():
    with pytest.raises(ValueError, match="either a power or branches"):
        power_flow(PowerBranch("x", (0.9,)))
    with pytest.raises(ValueError, match="positive"):
        power_flow(PowerBranch("x", (0.9,), power=-1.0))
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        power_flow(PowerBranch("x", (1.5,), power=1.0))
