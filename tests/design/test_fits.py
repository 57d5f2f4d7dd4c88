"""ISO 286 tolerances (flyopt.design.fits) against the standard's own formula and printed examples."""

import math

import pytest

from flyopt.design.fits import hole_tolerance, it_grade

#: ISO 286-1's nominal size steps [mm] up to 500 mm.
STEPS = (0, 3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500)


def test_every_row_above_3_mm_is_the_standards_formula_rounded():
    # ISO 286-1: IT7 = 16 i, IT9 = 40 i, i = 0.45 D^(1/3) + 0.001 D [um] at the step's geometric mean D;
    # the printed values are rounded by the standard's rules, within 5 % of the formula
    for d_over, d_up_to in zip(STEPS[1:], STEPS[2:]):
        d = math.sqrt(d_over * d_up_to)
        i = 0.45 * d ** (1 / 3) + 0.001 * d
        for grade, factor in (("IT7", 16), ("IT9", 40)):
            printed = it_grade(d_up_to * 1e-3, grade) * 1e6
            assert printed == it_grade(d_over * 1.0001e-3, grade) * 1e6  # one value over the whole step
            assert printed == pytest.approx(factor * i, rel=0.05), (d_over, grade)


def test_h7_of_a_55_mm_bore_and_js9_of_a_16_mm_keyway():
    # ISO 286-2: 55 H7 = 55 +0.030/0; 16 JS9 = 16 +-0.0215 (IT9 = 43 um over 10 up to 18 mm)
    bore = hole_tolerance(0.055, "H7")
    assert (bore.upper, bore.lower, bore.fit) == (pytest.approx(30e-6, rel=1e-12), 0.0, "H7")
    width = hole_tolerance(0.016, "JS9")
    assert width.upper == pytest.approx(21.5e-6, rel=1e-12) and width.lower == -width.upper


@pytest.mark.parametrize(("size", "it7_um"), [(0.003, 10), (0.0030001, 12), (0.050, 25), (0.0500001, 30), (0.5, 63)])
def test_a_size_on_a_step_takes_the_lower_row(size, it7_um):
    # "above ... up to and including"
    assert it_grade(size, "IT7") == pytest.approx(it7_um * 1e-6, rel=1e-12)


@pytest.mark.parametrize(("size", "fit"), [(0.6, "H7"), (0.0, "H7"), (0.05, "H8")])
def test_beyond_the_table_or_an_unknown_class_is_refused(size, fit):
    with pytest.raises(ValueError):
        hole_tolerance(size, fit)
