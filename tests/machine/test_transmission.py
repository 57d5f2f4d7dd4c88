"""Drive-train reduction against the domain page's worked examples 3 (inertia part), 4 and 5."""

import pytest
from conftest import assert_published
from numpy.testing import assert_allclose

from flyopt.machine.transmission import motor_power, reduced_inertia, reduced_load_torque, series_efficiency


def test_domain_example4_series_efficiency_and_motor_power():
    """Belt 0.95, two gear pairs 0.97, conveyor 0.92: η = 0.8223; 5500 N at 1.2 m/s needs 8.026 kW."""
    eta = series_efficiency([0.95, 0.97, 0.97, 0.92])
    assert_published(eta, "0.8223")
    assert_published(motor_power([(5500 * 1.2, [0.95, 0.97, 0.97, 0.92])]) / 1000, "8.026")


def test_domain_example5_parallel_branches():
    """Belt 0.92 and two gear pairs 0.97 to each machine; A 5 kW at 0.8, B 1 kW at 0.5: 9.531 kW."""
    path = [0.92, 0.97, 0.97]
    power = motor_power([(5000, path + [0.8]), (1000, path + [0.5])])
    assert_published(power / 1000, "9.531")


def test_domain_example3_reduced_inertia_of_gears_and_masses():
    """Example 3's inertia: 0.003 + 0.06/2² + 1·0.1² + 5·0.0866² = 0.0655 kg m² (at ω1 = 1 rad/s)."""
    j = reduced_inertia(j_motor=0.003, shafts=[(0.06, 2.0)], masses=[(1.0, 0.1), (5.0, 0.0866)], omega_motor=1.0)
    assert_published(j, "0.0655")
    assert_allclose(j, 0.003 + 0.015 + 0.01 + 5 * 0.0866**2, rtol=1e-15)


def test_efficiency_convention_is_optional_and_explicit():
    plain = reduced_inertia(1.0, [(4.0, 2.0)])
    with_eta = reduced_inertia(1.0, [(4.0, 2.0)], efficiencies=[0.5])
    assert plain == 2.0 and with_eta == 3.0


def test_reduced_load_torque():
    assert reduced_load_torque(970.0, 10.0, 0.97) == pytest.approx(100.0, rel=1e-15)


@pytest.mark.parametrize("stages", [[1.2], [0.0], [-0.5]])
def test_bad_efficiency(stages):
    with pytest.raises(ValueError, match=r"\(0, 1\]"):
        series_efficiency(stages)


def test_masses_need_a_speed():
    with pytest.raises(ValueError, match="omega_motor"):
        reduced_inertia(0.0, masses=[(1.0, 1.0)])
