"""Every scene in problems/ runs, and the domain page's worked examples give their published figures."""

import math

import pytest
from conftest import PROBLEMS, assert_published
from numpy.testing import assert_allclose

import flyopt
from flyopt.analysis import EXTRAS

SCENES = sorted(PROBLEMS.glob("*.toml"))


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_every_problem_scene_analyses(path):
    result = flyopt.analyse(flyopt.load(path))
    assert result.a_max >= 0 and math.isfinite(result.j_required)
    assert result.to_dict()["shafts"]


def test_domain_example1():
    r = flyopt.analyse(flyopt.load(PROBLEMS / "example1-net-areas.toml"))
    assert [e["delta_e"] for e in r.energy_chain] == [0, 1500, 500, 900, -100, 0]
    assert (r.index_omega_max, r.index_omega_min) == (1, 4)
    assert r.a_max == 1600
    assert_published(r.j_required, "3.2423")


def test_domain_example2():
    r = flyopt.analyse(flyopt.load(PROBLEMS / "shear-press.toml"))
    assert_allclose(r.driving_torque, 462.5, rtol=1e-15)  # W_r/Φ: exact up to rounding
    assert_published(r.a_max, "1256.33")
    assert_published(r.j_required, "1.0183")
    assert_published(r.power / 1000, "72.65")


def test_domain_example4_conveyor_needs_no_flywheel():
    r = flyopt.analyse(flyopt.load(PROBLEMS / "conveyor.toml"))
    assert_published(r.efficiency, "0.8223")
    assert_published(r.motor_power / 1000, "8.026")
    assert r.flywheel_needed is False and r.j_required == 0.0 and r.a_max == 0.0


def test_indicator_drawing_areas():
    """Chain in mm²: 0, 580, 260, 650, 130, 320, −70, 190, 0 at 1 J/mm²: A_max = 720 J."""
    r = flyopt.analyse(flyopt.load(PROBLEMS / "indicator-drawing.toml"))
    assert_allclose(r.a_max, 720.0, rtol=1e-13)
    omega = 600 * 2 * math.pi / 60
    assert_allclose(r.j_required, 720 / (omega**2 * 0.01) - 2.0, rtol=1e-13)


def test_compressor_closed_form():
    r = flyopt.analyse(flyopt.load(PROBLEMS / "compressor.toml"))
    assert_allclose(r.a_max, 350.0, rtol=1e-12)
    motor = next(s for s in r.shafts if s.name == "motor")
    assert_allclose(motor.j_required, r.j_required / 2.45**2, rtol=1e-15)
    assert_allclose(r.motor_power, 400 * r.omega_mean / 0.95, rtol=1e-12)


def test_four_stroke_engine_cycle_is_two_turns():
    r = flyopt.analyse(flyopt.load(PROBLEMS / "four-stroke-engine.toml"))
    assert r.cycle_angle == pytest.approx(4 * math.pi)
    # ω_min just after firing TDC (360 deg), ω_max late in the expansion stroke
    assert 360 < math.degrees(r.angle_omega_min) < 380
    assert 380 < math.degrees(r.angle_omega_max) < 540
    assert r.flywheel_needed


def test_no_flywheel_when_own_inertia_suffices(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(
        '[machine]\nspeed = "1500 rpm"\ndelta = 0.02\ninertia = "4 kg*m^2"\n'
        '[torque.net]\nareas = ["1500 J", "-1000 J", "400 J", "-1000 J", "100 J"]\n'
    )
    r = flyopt.analyse(flyopt.load(path))
    assert r.flywheel_needed is False and r.j_required == 0.0
    assert_allclose(r.j_margin, 3.2423 - 4, rtol=5e-4)


def test_speed_and_energy_extremes_are_named_apart_where_they_differ():
    """slider-crank-press (variable inertia): ΔE is lowest at 177.4°, the speed at 264.9°.

    The JSON names both: ``angle_delta_e_*`` are the energy chain's extremes,
    ``angle_omega_*`` where the speed is extreme for the model that ran.
    """
    r = flyopt.analyse(flyopt.load(PROBLEMS / "slider-crank-press.toml"))
    chain = {e["index"]: e for e in r.energy_chain}
    assert r.angle_delta_e_max == chain[r.index_omega_max]["angle"]
    assert r.angle_delta_e_min == chain[r.index_omega_min]["angle"]
    assert chain[r.index_omega_min]["delta_e"] == min(e["delta_e"] for e in r.energy_chain)
    assert f"{math.degrees(r.angle_delta_e_min):.1f}" == "177.4"
    assert f"{math.degrees(r.angle_omega_min):.1f}" == "264.9"
    # the constant-inertia energy model: the two are the same angles
    e = flyopt.analyse(flyopt.load(PROBLEMS / "shear-press.toml"))
    assert (e.angle_omega_max, e.angle_omega_min) == (e.angle_delta_e_max, e.angle_delta_e_min)


def test_text_report_labels_the_energy_chain_by_what_it_is():
    """The chain's extremes are marked ΔE where they are not the speed's extremes (they were
    labelled ω_min at 177.4° while the speed is lowest at 264.9°)."""
    from flyopt.report.text import analysis_report

    text = analysis_report(flyopt.analyse(flyopt.load(PROBLEMS / "slider-crank-press.toml"), extras=EXTRAS))
    assert "ΔE min" in text and "ω_min" not in text.split("Energy indicator diagram")[1].split("\n\n")[0]
    assert "264.9" in text and "177.4" in text  # 264.885 and 177.366 deg to four figures
    plain = analysis_report(flyopt.analyse(flyopt.load(PROBLEMS / "shear-press.toml"), extras=EXTRAS))
    assert "ω_min" in plain.split("Energy indicator diagram")[1] and "ΔE min" not in plain
