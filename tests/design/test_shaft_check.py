"""The described shaft checked with its wheel over the cycle (flyopt.design.shaft.check), against closed forms.

References, independent of the code under test:

- a simply supported uniform shaft under a central force F (R. G. Budynas and J. K. Nisbett, *Shigley's
  Mechanical Engineering Design*, 9th ed., Table A-9, case 6): M = F l / 4 at the centre,
  slope F l^2 / (16 E I) at the supports, deflection F l^3 / (48 E I) at the centre;
- Jeffcott's rotor: a disc of mass m at the middle of a massless shaft, omega_c^2 = 48 E I / (m l^3);
- two inertias on a shaft of stiffness k = G pi d^4 / (32 l): omega^2 = k (J_1 + J_2) / (J_1 J_2);
- ISO 21940-11: the permissible residual unbalance of grade G is e_per = G / omega, so the force at
  omega is m e_per omega^2 = m G omega;
- the DE-Goodman factor of safety at the keyseat (Shigley Eq. (7-7)) worked by hand below with the
  book's Table 7-1 (end-mill keyseat: K_t 2.14, K_ts 3.0, r/d 0.02), Eqs. (6-8), (6-19), (6-20),
  (6-32), (6-34), (6-35) and Table 6-2 (machined: a 4.51 MPa, b -0.265).
"""

import math

import numpy as np
import pytest

from flyopt.design.materials import make_material
from flyopt.design.shaft.check import check_shaft, separation_utilisation
from flyopt.machine.shaft_layout import ShaftLayout, SideLoad

E, NU, SUT, SY = 207e9, 0.3, 700e6, 500e6
D, L = 0.05, 1.0
MASS, J, OTHER = 80.0, 4.0, 1.5
G_GRADE = 6.3e-3
OMEGA, DELTA = 50.0, 0.1


def steel(density=1e-6):
    """A steel whose shaft is (nearly) massless: the closed forms' massless shaft."""
    return make_material(
        "test_steel",
        density,
        elastic_modulus=E,
        poisson_ratio=NU,
        tensile_strength=SUT,
        yield_strength=SY,
        ductile=True,
        safety_factor=2.0,
    )


def layout(**changes):
    base = {
        "steps": (L,),
        "diameters": (D,),
        "bearings": (0.0, L),
        "wheel_at": L / 2,
        "torque_at": 0.9 * L,
        "material": "test_steel",
        "max_deflection": 1e-3,
    }
    return ShaftLayout(**{**base, **changes})


def run(shape=None, torque=(-300.0, 100.0, 500.0), **kwargs):
    return check_shaft(
        shape or layout(),
        steel(),
        wheel_mass=MASS,
        wheel_inertia=J,
        omega_mean=OMEGA,
        delta=DELTA,
        torque_curve=np.array(torque),
        other_inertia=OTHER,
        excitation=kwargs.pop("excitation", None),
        **kwargs,
    )


def limit(check, kind, where=None):
    return next(lim for lim in check.limits if lim.kind == kind and (where is None or where in lim.where))


@pytest.fixture(scope="module")
def central():
    return run()


def test_a_central_wheel_bends_and_tilts_the_shaft_as_table_a9_says(central):
    ei = E * math.pi * D**4 / 64
    weight = MASS * 9.80665
    unbalance = MASS * G_GRADE * OMEGA * (1 + DELTA / 2)  # ISO 21940-11: m (G / omega) omega^2 at omega_max
    assert central.weight == pytest.approx(weight, rel=1e-12)
    assert central.unbalance == pytest.approx(unbalance, rel=1e-12)
    seat = central.sections[0]
    assert seat.name == "keyseat at the wheel seat"
    assert seat.ma == pytest.approx(weight * L / 4, rel=1e-12)  # the weight: fully reversed in the turning shaft
    assert seat.mm == pytest.approx(unbalance * L / 4, rel=1e-12)  # the unbalance turns with it: steady
    # slopes and deflection: the stationary and the turning loads added in magnitude
    slope = (weight + unbalance) * L**2 / (16 * ei)
    assert limit(central, "slope", "bearing A").value == pytest.approx(slope, rel=1e-10)
    assert limit(central, "slope", "bearing B").value == pytest.approx(slope, rel=1e-10)
    assert limit(central, "deflection").value == pytest.approx((weight + unbalance) * L**3 / (48 * ei), rel=1e-10)


def test_the_cycles_torque_is_split_into_its_midrange_and_alternating_parts(central):
    assert central.torque_mean == pytest.approx(100.0) and central.torque_alternating == pytest.approx(400.0)
    seat = central.sections[0]
    assert (seat.tm, seat.ta) == (pytest.approx(100.0), pytest.approx(400.0))
    # a bearing outside the length between the seat and torque_at carries no torque
    bearing = next(s for s in central.sections if s.name.startswith("bearing at 0"))
    assert (bearing.tm, bearing.ta) == (0.0, 0.0)


def test_the_keyseat_fatigue_factor_is_shigleys_de_goodman_worked_by_hand(central):
    seat = central.sections[0]
    sut_kpsi = SUT / 6.894757293168361e6
    root_a = 0.246 - 3.08e-3 * sut_kpsi + 1.51e-5 * sut_kpsi**2 - 2.67e-8 * sut_kpsi**3  # (6-35a) [in^0.5]
    root_as = 0.190 - 2.51e-3 * sut_kpsi + 1.35e-5 * sut_kpsi**2 - 2.67e-8 * sut_kpsi**3  # (6-35b)
    r_in = 0.02 * D / 0.0254
    kf = 1 + (2.14 - 1) / (1 + root_a / math.sqrt(r_in))  # (6-32), (6-34)
    kfs = 1 + (3.0 - 1) / (1 + root_as / math.sqrt(r_in))
    # (6-18) with (6-8), (6-19) and (6-20) in its exact form (d/7.62 mm)^-0.107 (the book rounds it to 1.24 d^-0.107)
    se = 4.51 * 700.0**-0.265 * (D * 1e3 / 7.62) ** -0.107 * 0.5 * SUT
    a = math.sqrt(4 * (kf * seat.ma) ** 2 + 3 * (kfs * 400.0) ** 2)
    b = math.sqrt(4 * (kf * seat.mm) ** 2 + 3 * (kfs * 100.0) ** 2)
    n = math.pi * D**3 / (16 * (a / se + b / SUT))  # (7-7)
    assert (seat.kf, seat.kfs) == (pytest.approx(kf, rel=1e-12), pytest.approx(kfs, rel=1e-12))
    assert seat.fatigue == pytest.approx(n, rel=1e-10)
    s_max = math.sqrt(
        (32 * kf * (seat.ma + seat.mm) / (math.pi * D**3)) ** 2 + 3 * (16 * kfs * 500.0 / (math.pi * D**3)) ** 2
    )  # (7-15)
    assert seat.yield_ == pytest.approx(SY / s_max, rel=1e-10)


def test_the_lateral_critical_speed_is_jeffcotts_for_a_central_wheel_on_a_massless_shaft(central):
    ei = E * math.pi * D**4 / 64
    assert central.lateral_speed == pytest.approx(math.sqrt(48 * ei / (MASS * L**3)), rel=1e-6)


def test_the_torsional_mode_is_the_two_inertia_closed_form(central):
    k = E / (2 * (1 + NU)) * math.pi * D**4 / 32 / (0.4 * L)
    from flyopt.machine.torsion import TorqueOrders

    excitation = TorqueOrders(0.0, np.array([1.0, 2.0, 3.0]), np.array([100.0, 50.0, 1.0]))
    found = run(excitation=excitation).torsional
    omega = math.sqrt(k * (J + OTHER) / (J * OTHER))
    assert found.modes.frequencies_hz[0] == pytest.approx(omega / (2 * math.pi), rel=1e-10)
    assert list(found.orders) == [1.0, 2.0]  # order 3 is under 5 % of the largest


def test_a_critical_speed_inside_the_running_range_or_its_margin_binds():
    band = (95.0, 105.0)
    assert separation_utilisation(100.0, band, 0.2) > 1.0  # inside the range
    assert separation_utilisation(105.0 * 1.3, band, 0.2) == pytest.approx(1.2 / 1.3)
    assert separation_utilisation(95.0 * 0.7, band, 0.2) == pytest.approx(0.7 / 0.8)
    assert separation_utilisation(105.0 * 1.1, band, 0.2) > 1.0  # above the range, within the margin


def test_a_heavy_wheel_on_a_thin_shaft_fails_and_a_side_pull_adds_as_a_vector():
    thin = run(layout(diameters=(0.02,)))
    assert not thin.holds
    assert {lim.kind for lim in thin.failed()} >= {"fatigue", "slope"}
    # a horizontal pull beside the weight: the bending amplitude at the seat is the vector sum
    pull = 2000.0
    sideways = run(layout(loads=(SideLoad(L / 2, pull, math.pi / 2),)))
    assert sideways.sections[0].ma == pytest.approx(math.hypot(MASS * 9.80665, pull) * L / 4, rel=1e-12)
