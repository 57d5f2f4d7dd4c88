"""Inertia already on the shafts ([[shaft]] inertia or gd2) counts towards J_c by the ratio-squared transfer.

References used here:
- the domain page's worked example 3 (docs/flywheel-design.md, section 12:
  J_S1 = 0.003 kg·m² on shaft 1, gear 2 of 0.06 kg·m² at ω2/ω1 = 1/2, a 1 kg
  member at v/ω = 0.1 m and a 5 kg slider at 0.0866 m with 100 N:
  J_e = 0.0655 kg·m², M_e = 8.66 N·m), written as a scene with the two
  shafts' inertia on [[shaft]];
- Budynas & Nisbett, *Shigley's Mechanical Engineering Design*, ch. 16
  (flywheels), the inertia of a gear reducer reflected to the motor: armature
  I_M = 10, pinion I_P = 1, gear I_G = n⁴ I_P and load I_L = 100 on the output
  shaft, n = 10: I_e = 10 + 1 + 10² (1) + 100/10² = 112 (the book's inertia
  unit; the transfer is linear, so the same numbers in kg·m² give 112 kg·m²);
- the shear press of example 2 (A_max in closed form, J_F = A_max/(ω_m² δ) − J_c);
- the kinetic energy of every shaft written out: ½ J_c ω² = Σ ½ J_k (i_k ω)².
"""

import math

import numpy as np
import pytest
from conftest import PROBLEMS, assert_published
from numpy.testing import assert_allclose

import flyopt
from flyopt.machine.reduce import reduce

EXAMPLE3 = """
[machine]
speed = "100 rpm"
delta = 0.05
[torque.driving]
constant = "unknown"
[[shaft]]
name = "shaft 1"
speed_ratio = 1.0
inertia = "0.003 kg*m^2"
[[shaft]]
name = "gear 2"
speed_ratio = 0.5           # z1/z2 = 20/40
inertia = "0.06 kg*m^2"
[[member]]
name = "link"
mass = "1 kg"
velocity_ratio = 0.1
[[member]]
name = "slider"
mass = "5 kg"
velocity_ratio = 0.0866
force = "100 N"
force_sense = "resisting"
"""


def test_domain_example3_with_the_shafts_inertia_on_the_shafts(write_scene):
    """Example 3: J_e = 0.0655 kg·m² and M_e = 8.66 N·m (resisting), the gears' inertia given on [[shaft]]."""
    scene = flyopt.load(write_scene(EXAMPLE3))
    assert_allclose(scene.j_constant, 0.003 + 0.06 * 0.5**2, rtol=1e-15)
    machine = reduce(scene)
    assert not machine.variable_inertia
    assert_published(machine.j_machine, "0.0655")
    assert_published(float(machine.resisting(np.array([0.3]))[0]), "8.66")


@pytest.mark.parametrize("form", ["inertia", "gd2"])
def test_shigley_gear_reducer_reflected_to_the_motor(write_scene, form):
    """Shigley's gear reducer, n = 10: I_e = I_M + I_P + n² I_P + I_L/n² = 112, given as inertia or as GD².

    GD² = 4 g J with g = 9.81 m/s² (flyopt's electric-drive convention,
    flyopt.units.G_STANDARD); the GD² strings are written from J in the test.
    """
    n, i_m, i_p, i_l = 10.0, 10.0, 1.0, 100.0
    i_g = n**4 * i_p

    def value(j):
        return f'inertia = "{j!r} kg*m^2"' if form == "inertia" else f'gd2 = "{4 * 9.81 * j!r} N*m^2"'

    text = f"""
[machine]
speed = "1500 rpm"
delta = 0.02
[torque.net]
areas = ["1500 J", "-1500 J"]
[[shaft]]
name = "motor"
speed_ratio = 1.0
{value(i_m + i_p)}
[[shaft]]
name = "output"
speed_ratio = {1 / n!r}
{value(i_g + i_l)}
"""
    scene = flyopt.load(write_scene(text))
    assert_allclose(scene.j_constant, 112.0, rtol=1e-14)
    assert_published(scene.j_constant, "112")


def test_the_shafts_inertia_holds_the_kinetic_energy_of_every_shaft(write_scene):
    """½ J_c ω² = ½ J_machine ω² + Σ_k ½ J_k (i_k ω)² for random shafts and ratios (1e-14)."""
    rng = np.random.default_rng(11)
    omega = 1500 * math.pi / 30
    for _ in range(5):
        count = int(rng.integers(1, 6))
        ratios, inertias = rng.uniform(0.05, 8.0, count).tolist(), rng.uniform(0.0, 3.0, count).tolist()
        j_machine = float(rng.uniform(0, 2))
        shafts = "".join(
            f'[[shaft]]\nname = "s{k}"\nspeed_ratio = {ratios[k]!r}\ninertia = "{inertias[k]!r} kg*m^2"\n'
            for k in range(count)
        )
        text = (
            f'[machine]\nspeed = "1500 rpm"\ndelta = 0.02\ninertia = "{j_machine!r} kg*m^2"\n'
            f'[torque.net]\nareas = ["100 J", "-100 J"]\n{shafts}'
        )
        scene = flyopt.load(write_scene(text))
        energy = 0.5 * j_machine * omega**2 + math.fsum(0.5 * j * (i * omega) ** 2 for j, i in zip(inertias, ratios))
        assert_allclose(0.5 * scene.j_constant * omega**2, energy, rtol=1e-14)


def test_shear_press_flywheel_shrinks_by_the_inertia_already_on_the_shafts(write_scene):
    """Example 2 with a motor rotor (0.3 kg·m²) and a pulley on a shaft at a quarter of the speed (2 kg·m²).

    A_max in closed form: the resisting torque exceeds M_d = 462.5 N·m from 0
    to the crossing on its falling segment, (1137.5/1400) π/4 after π/4, so
    A_max = 1137.5 π/4 (1 + 1137.5/2800) = 1256.33 J (published); then
    J_F = A_max/(ω_m² δ) − (0.3 + 2 × 0.25²) (1e-12).
    """
    text = (PROBLEMS / "shear-press.toml").read_text()
    motor = 'name = "motor"\nspeed_ratio = 1.0\n'
    assert text.count(motor) == 1 and "inertia" not in text
    text = text.replace(motor, motor + 'inertia = "0.3 kg*m^2"\n')
    text += '\n[[shaft]]\nname = "main"\nspeed_ratio = 0.25\ninertia = "2 kg*m^2"\n'
    result = flyopt.analyse(flyopt.load(write_scene(text)))
    a_max = 1137.5 * math.pi / 4 * (1 + 1137.5 / 2800)
    assert_published(a_max, "1256.33")
    omega = 1500 * math.pi / 30
    j_c = 0.3 + 2.0 * 0.25**2
    assert_allclose(result.j_constant, j_c, rtol=1e-15)
    assert_allclose(result.a_max, a_max, rtol=1e-12)
    assert_allclose(result.j_required, a_max / (omega**2 * 0.05) - j_c, rtol=1e-12)
    main = next(s for s in result.shafts if s.name == "main")
    assert_allclose(main.j_required, result.j_required / 0.25**2, rtol=1e-15)


@pytest.mark.parametrize(
    "new, field, match",
    [
        ('inertia = "-0.06 kg*m^2"', "shaft[1].inertia", ">= 0"),
        ('inertia = "0.06 kg*m^2"\ngd2 = "2 N*m^2"', "shaft[1].gd2", "either inertia or gd2"),
        ('inertia = "0.06 kg"', "shaft[1].inertia", "wrong dimension"),
        ('gd2 = "0.06 kg*m^2"', "shaft[1].gd2", "wrong dimension"),
        ('gd2 = "-2 N*m^2"', "shaft[1].gd2", ">= 0"),
        ('inertia = "inf kg*m^2"', "shaft[1].inertia", "must be finite"),
        ("inertia = true", "shaft[1].inertia", "moment of inertia"),
    ],
)
def test_bad_shaft_inertia_exits_2_with_one_line(main_cli, write_scene, new, field, match):
    import re

    text = EXAMPLE3.replace('inertia = "0.06 kg*m^2"', new)
    assert text != EXAMPLE3
    path = write_scene(text)
    for command in ("check", "solve"):
        status, out, err = main_cli(command, path)
        lines = err.splitlines()
        assert status == 2 and out == "" and len(lines) == 1, (status, err[-2000:])
        assert str(path) in lines[0] and f"{field}:" in lines[0], lines[0]
        assert re.search(match, lines[0]), lines[0]


def test_a_sweep_of_the_ratio_of_a_shaft_with_inertia_is_refused(tmp_path, main_cli):
    """Its ratio would move J_c (J i²) while the sweep holds J_c: refused in one line; a bare shaft's ratio is not.
    (``flyopt check`` run in this process, as tests/conftest.py's ``main_cli`` runs it: the command's exit status
    and its stderr, without a new interpreter's start-up for each of the three.)"""
    from pathlib import Path

    base = Path("problems/four-cylinder-engine.toml").read_text()
    for shaft, refused in (("fan", True), ("crankshaft", True)):
        path = tmp_path / f"{shaft}.toml"
        path.write_text(base + f'\n[sweep.vary]\n"shaft.{shaft}.speed_ratio" = "1:2:3"\n')
        status, _, err = main_cli("check", path)
        assert (status == 2) == refused, err
        lines = err.strip().splitlines()
        assert len(lines) == 1 and "Traceback" not in err
        assert f"shaft {shaft!r} carries inertia" in lines[0] and str(path) in lines[0]
    bare = tmp_path / "bare.toml"
    bare.write_text(
        Path("problems/punch-press.toml").read_text() + '\n[sweep.vary]\n"shaft.intermediate.speed_ratio" = "4:8:3"\n'
    )
    status, _, err = main_cli("check", bare)
    assert status == 0, err
