"""Fatigue and first-cycle yield of a shaft section, by Shigley's method (issue 30, item 2).

One published method, implemented whole: R. G. Budynas and J. K. Nisbett,
*Shigley's Mechanical Engineering Design*, 9th ed., McGraw-Hill, 2011,
chapter 6 (endurance limit and Marin factors, notch sensitivity) and
chapter 7, section 7-4 (the distortion-energy shaft equations). The tables
are data, in ``flyopt/data/shaft.toml``, each row with its table and page.

The endurance limit of the part, Eq. (6-18) (k_f, the miscellaneous factor,
is left to the stress-concentration factor K_f as the book does for shafts):

    S_e = k_a k_b k_c k_d k_e S'_e,     S'_e = 0.5 S_ut (S_ut <= 1400 MPa), else 700 MPa   (6-8)
    k_a = a S_ut^b (Table 6-2),  k_b (6-20),  k_c (6-26),  k_d (6-27),  k_e = 1 - 0.08 z_a (6-29)

The fatigue stress-concentration factor, Eqs. (6-32), (6-34), (6-35):

    K_f = 1 + q (K_t - 1),   q = 1 / (1 + sqrt(a) / sqrt(r)),   sqrt(a) = polynomial in S_ut [kpsi]

and with A = sqrt(4 (K_f M_a)^2 + 3 (K_fs T_a)^2), B = sqrt(4 (K_f M_m)^2 + 3 (K_fs T_m)^2),
the shaft equations (7-7) to (7-14) give the factor of safety n at a diameter d
or the diameter d for a factor n; (7-15) and (7-16) check yielding in the
first cycle against the largest von Mises stress.

Everything is SI at the boundary: strengths and stresses [Pa], lengths [m],
moments [N*m], temperatures [degC]. The book's fits are in kpsi and inches or
MPa and millimetres; ``fit="si"`` (the default) uses its MPa column, ``fit="us"``
its kpsi column (they are separate fits and differ in the third digit, so a
worked example in kpsi is reproduced with ``fit="us"``). Functions take
numbers or numpy arrays and broadcast.
"""

from __future__ import annotations

import functools
import math
from importlib import resources
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from flyopt._toml import tomllib
from flyopt.errors import shorten
from flyopt.names import choice
from flyopt.validate import finite_array, positive

if TYPE_CHECKING:
    from flyopt.design.materials import Material

__all__ = [
    "CRITERIA",
    "FINISHES",
    "LOADINGS",
    "EnduranceLimit",
    "KPSI",
    "INCH",
    "specimen_endurance_limit",
    "surface_factor",
    "size_factor",
    "loading_factor",
    "temperature_factor",
    "reliability_factor",
    "endurance_limit",
    "neuber_root_a",
    "notch_sensitivity",
    "fatigue_concentration",
    "von_mises_amplitudes",
    "fatigue_safety_factor",
    "fatigue_diameter",
    "max_von_mises",
    "yield_safety_factor",
    "shaft_strengths",
    "sensitivity_of",
    "de_terms",
    "von_mises_peak",
    "size_exponent",
]

#: One kpsi in pascals (1000 lbf/in^2, lbf = 4.4482216152605 N, in = 0.0254 m).
KPSI = 4.4482216152605e3 / 0.0254**2
#: One inch in metres.
INCH = 0.0254
MPA = 1.0e6
MM = 1.0e-3

#: The fatigue criteria of section 7-4: DE-Goodman (7-7, 7-8), DE-Gerber (7-9, 7-10),
#: DE-ASME elliptic (7-11, 7-12), DE-Soderberg (7-13, 7-14).
CRITERIA = ("goodman", "gerber", "asme_elliptic", "soderberg")
#: The surface finishes of Table 6-2.
FINISHES = ("ground", "machined", "hot_rolled", "as_forged")
#: The loadings of Eq. (6-26).
LOADINGS = ("bending", "axial", "torsion")
_FITS = ("si", "us")

Real = Any  # a float or a numpy array of floats (the functions broadcast)


@functools.lru_cache(maxsize=1)
def _data() -> dict[str, Any]:
    text = resources.files("flyopt").joinpath("data", "shaft.toml").read_text(encoding="utf-8")
    data: dict[str, Any] = tomllib.loads(text)
    return data


def _outside(values: Any, outside: Any) -> str:
    """The first of ``values`` that ``outside`` marks, as a message quotes it (a number, not numpy's
    ``array(1.e-06)``)."""
    return f"{float(np.ravel(values)[np.flatnonzero(np.ravel(outside))[0]]):g}"


def _array(value: Real, field: str, *, positive: bool = True) -> np.ndarray:
    array: np.ndarray = finite_array(value, field)
    if positive and np.any(array <= 0.0):
        raise ValueError(f"{field} must be > 0, got {shorten(value)}")
    return array


def _moment(value: Real, field: str) -> np.ndarray:
    return np.abs(_array(value, field, positive=False))


def _out(array: np.ndarray) -> Real:
    return float(array) if array.ndim == 0 else array


def specimen_endurance_limit(sut: Real, *, fit: str = "si") -> Real:
    """The rotating-beam endurance limit S'_e [Pa] of a steel, Shigley 9th ed. Eq. (6-8).

    S'_e = 0.5 S_ut up to S_ut = 1400 MPa (200 kpsi), 700 MPa (100 kpsi) above.

    Parameters
    ----------
    sut : float or array
        Ultimate tensile strength S_ut [Pa].
    fit : {"si", "us"}
        The book's MPa or kpsi form (1400/700 MPa against 200/100 kpsi).
    """
    sut = _array(sut, "sut [Pa]")
    row = _data()["specimen_endurance"]
    unit = MPA if choice(fit, _FITS, "fit") == "si" else KPSI
    suffix = "mpa" if fit == "si" else "kpsi"
    knee, limit = row[f"knee_{suffix}"] * unit, row[f"limit_{suffix}"] * unit
    return _out(np.where(sut <= knee, row["ratio"] * sut, limit))


def surface_factor(sut: Real, finish: str, *, fit: str = "si") -> Real:
    """Marin surface factor k_a = a S_ut^b, Shigley 9th ed. Eq. (6-19) and Table 6-2 (p. 288).

    Parameters
    ----------
    sut : float or array
        Ultimate tensile strength S_ut [Pa].
    finish : {"ground", "machined", "hot_rolled", "as_forged"}
        ``machined`` is the table's "machined or cold-drawn".
    fit : {"si", "us"}
        The table's MPa column (a for S_ut in MPa) or kpsi column.
    """
    sut = _array(sut, "sut [Pa]")
    row = _data()["surface"][choice(finish, FINISHES, "finish")]
    if choice(fit, _FITS, "fit") == "si":
        return _out(row["a_mpa"] * (sut / MPA) ** row["b"])
    return _out(row["a_kpsi"] * (sut / KPSI) ** row["b"])


def size_factor(diameter: Real, *, loading: str = "bending", fit: str = "si") -> Real:
    """Marin size factor k_b of a rotating round shaft, Shigley 9th ed. Eqs. (6-20), (6-21).

    k_b = (d/7.62 mm)^-0.107 = 1.24 d^-0.107 for 2.79 <= d <= 51 mm, 1.51 d^-0.157
    for 51 < d <= 254 mm (d in mm; ``fit="us"``: 0.879 d^-0.107 and 0.91 d^-0.157,
    d in inches, 0.11 to 10 in); 1 for axial loading.

    Parameters
    ----------
    diameter : float or array
        Shaft diameter d [m] at the section.
    loading : {"bending", "torsion", "axial"}
    fit : {"si", "us"}

    Raises
    ------
    ValueError
        If d is outside the range of the fit (the book gives no size factor there).
    """
    diameter = _array(diameter, "diameter [m]")
    if choice(loading, LOADINGS, "loading") == "axial":
        return _out(np.ones_like(diameter))
    rows, unit = (_data()["size"]["mm"], MM) if choice(fit, _FITS, "fit") == "si" else (_data()["size"]["inch"], INCH)
    d = diameter / unit
    low, high = rows[0][0], rows[-1][1]
    if np.any(d < low) or np.any(d > high):
        raise ValueError(
            f"diameter [m] must lie within Shigley's Eq. (6-20), {low * unit:g} to {high * unit:g} m, got "
            f"{_outside(diameter, (d < low) | (d > high))}"
        )
    first, second = rows
    # The first row's printed coefficient is (d/0.3)^-0.107 or (d/7.62)^-0.107 written out;
    # use the exact quotient form so that 0.3 in and 7.62 mm give the same k_b.
    base = 0.3 if unit == INCH else 7.62
    return _out(np.where(d <= first[1], (d / base) ** first[3], second[2] * d ** second[3]))


def size_exponent(diameter: float) -> float:
    """The exponent of Eq. (6-20)'s branch that holds ``diameter`` [m] (SI fit): k_b is c d^e on each branch, so
    k_b(d) = k_b(d_0) (d/d_0)^e near d_0, which the seat's NLP writes with its d."""
    first, second = _data()["size"]["mm"]
    return float(first[3] if diameter / MM <= first[1] else second[3])


def loading_factor(loading: str) -> float:
    """Marin load factor k_c, Shigley 9th ed. Eq. (6-26): 1 bending, 0.85 axial, 0.59 torsion."""
    return float(_data()["loading"][choice(loading, LOADINGS, "loading")])


def temperature_factor(temperature: Real) -> Real:
    """Marin temperature factor k_d, Shigley 9th ed. Eq. (6-27) (p. 291).

    k_d = 0.975 + 0.432e-3 T_F - 0.115e-5 T_F^2 + 0.104e-8 T_F^3 - 0.595e-12 T_F^4,
    T_F the temperature in degrees Fahrenheit, 70 <= T_F <= 1000.

    Parameters
    ----------
    temperature : float or array
        Operating temperature [degC] (21.1 to 537.8 degC).
    """
    fahrenheit = _array(temperature, "temperature [degC]", positive=False) * 1.8 + 32.0
    row = _data()["temperature"]
    if np.any(fahrenheit < row["min_fahrenheit"] - 1e-9) or np.any(fahrenheit > row["max_fahrenheit"] + 1e-9):
        raise ValueError(
            f"temperature [degC] must lie within Shigley's Eq. (6-27), 70 to 1000 degF, got "
            f"{_outside(np.asarray(temperature, dtype=float), (fahrenheit < row['min_fahrenheit'] - 1e-9) | (fahrenheit > row['max_fahrenheit'] + 1e-9))}"
        )
    return _out(np.polynomial.polynomial.polyval(fahrenheit, row["coefficients"]))


def reliability_factor(reliability: Real) -> Real:
    """Marin reliability factor k_e = 1 - 0.08 z_a, Shigley 9th ed. Eq. (6-29) and Table 6-5.

    z_a is the standard normal variate of the reliability R (Table A-10); an 8 %
    standard deviation of the endurance limit. Table 6-5's rows are reproduced to
    their printed three digits (tests/design/test_shaft_strength.py).

    Parameters
    ----------
    reliability : float or array
        R, 0.5 <= R < 1.
    """
    from scipy.special import ndtri

    value = _array(reliability, "reliability")
    if np.any(value < 0.5) or np.any(value >= 1.0):
        raise ValueError(f"reliability must lie in [0.5, 1), got {shorten(reliability)}")
    return _out(1.0 - _data()["reliability"]["standard_deviation"] * ndtri(value))


class EnduranceLimit(NamedTuple):
    """S_e [Pa] of a shaft section and the factors it is made of (Shigley 9th ed. Eq. (6-18))."""

    se: Real
    se_prime: Real
    ka: Real
    kb: Real
    kc: float
    kd: Real
    ke: Real


def endurance_limit(
    sut: Real,
    diameter: Real,
    finish: str,
    *,
    loading: str = "bending",
    temperature: Real | None = None,
    reliability: Real = 0.5,
    se_prime: Real | None = None,
    fit: str = "si",
) -> EnduranceLimit:
    """The fully corrected endurance limit S_e = k_a k_b k_c k_d k_e S'_e, Shigley 9th ed. Eq. (6-18).

    Parameters
    ----------
    sut : float or array
        Ultimate tensile strength [Pa].
    diameter : float or array
        Section diameter [m] (for k_b).
    finish : str
        Surface finish (Table 6-2).
    loading : str
        ``bending`` (the rotating shaft's case; the DE shaft equations fold
        torsion in through the von Mises stress, so k_c = 1 there).
    temperature : float or array, optional
        [degC]; omitted: room temperature, k_d = 1.
    reliability : float or array
        Default 0.5 (k_e = 1).
    se_prime : float or array, optional
        A tested rotating-beam endurance limit [Pa]; omitted: Eq. (6-8).
    fit : {"si", "us"}
    """
    sp = specimen_endurance_limit(sut, fit=fit) if se_prime is None else _out(_array(se_prime, "se_prime [Pa]"))
    ka = surface_factor(sut, finish, fit=fit)
    kb = size_factor(diameter, loading=loading, fit=fit)
    kc = loading_factor(loading)
    kd = 1.0 if temperature is None else temperature_factor(temperature)
    ke = reliability_factor(reliability)
    return EnduranceLimit(ka * kb * kc * kd * ke * sp, sp, ka, kb, kc, kd, ke)


def neuber_root_a(sut: Real, loading: str = "bending") -> Real:
    """The Neuber constant sqrt(a) [sqrt(m)] of a steel, Shigley 9th ed. Eq. (6-35a, b) (p. 296).

    sqrt(a) [sqrt(in)] = 0.246 - 3.08e-3 S + 1.51e-5 S^2 - 2.67e-8 S^3 (bending or axial),
    0.190 - 2.51e-3 S + 1.35e-5 S^2 - 2.67e-8 S^3 (torsion), S = S_ut in kpsi, 50 to 250 kpsi.
    """
    sut = _array(sut, "sut [Pa]")
    row = _data()["neuber"]
    kind = "torsion" if choice(loading, LOADINGS, "loading") == "torsion" else "bending"
    s = sut / KPSI
    if np.any(s < row["min_kpsi"] - 1e-9) or np.any(s > row["max_kpsi"] + 1e-9):
        raise ValueError(
            f"sut [Pa] must lie within Shigley's Eq. (6-35), 50 to 250 kpsi, got "
            f"{_outside(sut, (s < row['min_kpsi'] - 1e-9) | (s > row['max_kpsi'] + 1e-9))}"
        )
    return _out(np.polynomial.polynomial.polyval(s, row[kind]) * math.sqrt(INCH))


def notch_sensitivity(radius: Real, sut: Real, loading: str = "bending") -> Real:
    """Notch sensitivity q = 1 / (1 + sqrt(a)/sqrt(r)) of a steel, Shigley 9th ed. Eq. (6-34).

    Parameters
    ----------
    radius : float or array
        Notch (fillet, keyseat bottom) radius r [m].
    sut : float or array
        [Pa], 50 to 250 kpsi (Eq. (6-35)).
    loading : {"bending", "axial", "torsion"}
    """
    radius = _array(radius, "radius [m]")
    return _out(sensitivity_of(neuber_root_a(sut, loading), radius))


def sensitivity_of(root_a: Any, radius: Any, sqrt: Any = np.sqrt) -> Any:
    """q = 1 / (1 + sqrt(a)/sqrt(r)), Eq. (6-34), of a Neuber constant [sqrt(m)] and a radius [m]: plain arithmetic,
    so that the NLP of a designed seat (:mod:`flyopt.design.shaft.seat_nlp`) writes it on its symbols (``sqrt``:
    theirs) by the same expression the check evaluates."""
    return 1.0 / (1.0 + root_a / sqrt(radius))


def fatigue_concentration(kt: Real, q: Real) -> Real:
    """K_f = 1 + q (K_t - 1), Shigley 9th ed. Eq. (6-32) (K_fs likewise with K_ts and q_shear)."""
    kt = _array(kt, "kt")
    q = _array(q, "q", positive=False)
    if np.any(kt < 1.0) or np.any(q < 0.0) or np.any(q > 1.0):
        raise ValueError(f"kt must be >= 1 and q within [0, 1], got kt={shorten(kt)}, q={shorten(q)}")
    return _out(1.0 + q * (kt - 1.0))


def _ab(ma: Real, ta: Real, mm: Real, tm: Real, kf: Real, kfs: Real) -> tuple[np.ndarray, np.ndarray]:
    kf, kfs = _array(kf, "kf"), _array(kfs, "kfs")
    ma, ta, mm, tm = (
        _moment(v, f) for v, f in ((ma, "ma [N*m]"), (ta, "ta [N*m]"), (mm, "mm [N*m]"), (tm, "tm [N*m]"))
    )
    return de_terms(ma, ta, mm, tm, kf, kfs)


def de_terms(ma: Any, ta: Any, mm: Any, tm: Any, kf: Any, kfs: Any, sqrt: Any = np.sqrt) -> tuple[Any, Any]:
    """A = [4(K_f M_a)^2 + 3(K_fs T_a)^2]^(1/2) and B likewise with M_m, T_m (Shigley 9th ed. section 7-4), on
    magnitudes already checked: plain arithmetic, so the seat's NLP writes them on its symbols (``sqrt``: theirs)."""
    a = sqrt(4.0 * (kf * ma) ** 2 + 3.0 * (kfs * ta) ** 2)
    b = sqrt(4.0 * (kf * mm) ** 2 + 3.0 * (kfs * tm) ** 2)
    return a, b


def von_mises_amplitudes(
    diameter: Real, ma: Real, ta: Real, mm: Real, tm: Real, kf: Real = 1.0, kfs: Real = 1.0
) -> tuple[Real, Real]:
    """Alternating and midrange von Mises stresses sigma'_a, sigma'_m [Pa], Shigley 9th ed. Eqs. (7-5), (7-6).

    sigma'_a = [(32 K_f M_a / (pi d^3))^2 + 3 (16 K_fs T_a / (pi d^3))^2]^(1/2) = 16 A / (pi d^3),
    sigma'_m likewise with M_m, T_m (= 16 B / (pi d^3)).
    """
    d = _array(diameter, "diameter [m]")
    a, b = _ab(ma, ta, mm, tm, kf, kfs)
    z = 16.0 / (math.pi * d**3)
    return _out(z * a), _out(z * b)


def _criterion_sum(criterion: str, a: Any, b: Any, se: Any, sut: Any, sy: Any) -> Any:
    """The bracket of the criterion: 1/n = 16 S / (pi d^3), d^3 = 16 n S / pi, with S [N*m/Pa = m^3]. Plain
    arithmetic for DE-Goodman and DE-Soderberg (the seat's NLP writes it on its symbols)."""
    if criterion == "goodman":
        return a / se + b / sut
    if criterion == "soderberg":
        return a / se + b / sy
    if criterion == "gerber":
        # (7-9): 1/n = 8A/(pi d^3 S_e) {1 + [1 + (2 B S_e/(A S_ut))^2]^(1/2)}; with A factored
        # into the root, (A + [A^2 + (2 B S_e/S_ut)^2]^(1/2)) / (2 S_e): the same, and finite at A = 0.
        return (a + np.sqrt(a**2 + (2.0 * b * se / sut) ** 2)) / (2.0 * se)
    # asme_elliptic (7-11): [4(K_f M_a/S_e)^2 + 3(K_fs T_a/S_e)^2 + 4(K_f M_m/S_y)^2 + 3(K_fs T_m/S_y)^2]^(1/2)
    return np.sqrt((a / se) ** 2 + (b / sy) ** 2)


def _strengths(se: Real, sut: Real, sy: Real, criterion: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    se_, sut_ = _array(se, "se [Pa]"), _array(sut, "sut [Pa]")
    needs_sy = criterion in ("soderberg", "asme_elliptic")
    if sy is None:
        if needs_sy:
            raise ValueError(f"sy [Pa] is needed by the {criterion} criterion")
        sy_ = np.asarray(np.nan)
    else:
        sy_ = _array(sy, "sy [Pa]")
    return se_, sut_, sy_


def fatigue_safety_factor(
    diameter: Real,
    ma: Real,
    ta: Real,
    mm: Real,
    tm: Real,
    *,
    kf: Real,
    kfs: Real,
    se: Real,
    sut: Real,
    sy: Real | None = None,
    criterion: str = "goodman",
) -> Real:
    """Fatigue factor of safety n of a round shaft section, Shigley 9th ed. Eqs. (7-7), (7-9), (7-11), (7-13).

    DE-Goodman (7-7):  1/n = 16/(pi d^3) [A/S_e + B/S_ut]
    DE-Gerber (7-9):   1/n = 8A/(pi d^3 S_e) {1 + [1 + (2 B S_e/(A S_ut))^2]^(1/2)}
    DE-ASME elliptic (7-11): 1/n = 16/(pi d^3) [4(K_f M_a/S_e)^2 + 3(K_fs T_a/S_e)^2 + 4(K_f M_m/S_y)^2
                             + 3(K_fs T_m/S_y)^2]^(1/2)
    DE-Soderberg (7-13): 1/n = 16/(pi d^3) [A/S_e + B/S_y]

    with A = [4(K_f M_a)^2 + 3(K_fs T_a)^2]^(1/2), B = [4(K_f M_m)^2 + 3(K_fs T_m)^2]^(1/2).

    Parameters
    ----------
    diameter : float or array
        d [m].
    ma, ta, mm, tm : float or array
        Alternating and midrange bending moment and torque [N*m] (their magnitudes).
    kf, kfs : float or array
        Fatigue stress-concentration factors in bending and torsion.
    se, sut : float or array
        Fully corrected endurance limit and ultimate strength [Pa].
    sy : float or array, optional
        Yield strength [Pa] (ASME elliptic and Soderberg).
    criterion : {"goodman", "gerber", "asme_elliptic", "soderberg"}

    Returns
    -------
    float or array
        n; ``inf`` for a section with no load.
    """
    criterion = choice(criterion, CRITERIA, "criterion")
    d = _array(diameter, "diameter [m]")
    a, b = _ab(ma, ta, mm, tm, kf, kfs)
    s = _criterion_sum(criterion, a, b, *_strengths(se, sut, sy, criterion))
    with np.errstate(divide="ignore"):
        return _out(math.pi * d**3 / (16.0 * s))


def fatigue_diameter(
    n: Real,
    ma: Real,
    ta: Real,
    mm: Real,
    tm: Real,
    *,
    kf: Real,
    kfs: Real,
    se: Real,
    sut: Real,
    sy: Real | None = None,
    criterion: str = "goodman",
) -> Real:
    """The diameter d [m] that gives the fatigue factor n, Shigley 9th ed. Eqs. (7-8), (7-10), (7-12), (7-14).

    d = (16 n S / pi)^(1/3) with the bracket S of :func:`fatigue_safety_factor`'s
    criterion (for DE-Gerber, (7-10): d = (8 n A/(pi S_e) {1 + [1 + (2 B S_e/(A S_ut))^2]^(1/2)})^(1/3)).
    S_e is held fixed: where k_b depends on d, iterate (the book's Example 7-2 does so by hand).
    """
    criterion = choice(criterion, CRITERIA, "criterion")
    n_ = _array(n, "n")
    a, b = _ab(ma, ta, mm, tm, kf, kfs)
    s = _criterion_sum(criterion, a, b, *_strengths(se, sut, sy, criterion))
    return _out(np.cbrt(16.0 * n_ * s / math.pi))


def max_von_mises(diameter: Real, ma: Real, ta: Real, mm: Real, tm: Real, kf: Real = 1.0, kfs: Real = 1.0) -> Real:
    """The largest von Mises stress of the cycle sigma'_max [Pa], Shigley 9th ed. Eq. (7-15).

    sigma'_max = [(32 K_f (M_m + M_a)/(pi d^3))^2 + 3 (16 K_fs (T_m + T_a)/(pi d^3))^2]^(1/2)
    """
    d = _array(diameter, "diameter [m]")
    kf, kfs = _array(kf, "kf"), _array(kfs, "kfs")
    m = _moment(mm, "mm [N*m]") + _moment(ma, "ma [N*m]")
    t = _moment(tm, "tm [N*m]") + _moment(ta, "ta [N*m]")
    return _out(von_mises_peak(d, m, t, kf, kfs))


def von_mises_peak(d: Any, m: Any, t: Any, kf: Any, kfs: Any, sqrt: Any = np.sqrt) -> Any:
    """sigma'_max of Eq. (7-15) from M = M_m + M_a and T = T_m + T_a (magnitudes): plain arithmetic, so the seat's
    NLP writes it on its symbols (``sqrt``: theirs)."""
    return sqrt((32.0 * kf * m / (math.pi * d**3)) ** 2 + 3.0 * (16.0 * kfs * t / (math.pi * d**3)) ** 2)


def yield_safety_factor(
    diameter: Real, ma: Real, ta: Real, mm: Real, tm: Real, *, sy: Real, kf: Real = 1.0, kfs: Real = 1.0
) -> Real:
    """First-cycle yield factor n_y = S_y / sigma'_max, Shigley 9th ed. Eq. (7-16) (the Langer line's check)."""
    sy_ = _array(sy, "sy [Pa]")
    with np.errstate(divide="ignore"):
        return _out(sy_ / np.asarray(max_von_mises(diameter, ma, ta, mm, tm, kf, kfs)))


def shaft_strengths(material: Material, diameter: float) -> tuple[float, float]:
    """(S_ut, S_y) [Pa] of a round shaft of ``material`` and ``diameter`` [m].

    Through :meth:`Material.strength` (the one place a material's strength at a
    section is decided), read at the thickness t = d. The strength tables are
    by flat thickness; EN 10083-1/-3 print each ruling-section row for a round
    and a flat side by side (d <= 16 mm with t <= 8, d <= 40 with t <= 20,
    d <= 100 with t <= 60, d <= 160 with t <= 100, d <= 250 with t <= 160:
    materials.toml's 42CrMo4+QT source), a round always at least as thick as
    its flat, so a round read at t = d falls in its own row or a thicker,
    weaker one: on the safe side (up to one row low), since the data keeps no
    column for rounds.

    Raises
    ------
    ValueError
        If the material gives no tensile or no yield strength (the fatigue
        method needs both), or the section is beyond its strength table.
    """
    sut, sy = material.strength(positive(diameter, "diameter [m]"))
    if sut is None or sy is None:
        raise ValueError(
            f"material {material.name!r}: a shaft's fatigue check needs its tensile and yield strengths "
            f"(tensile_strength and yield_strength, or a strength_by_thickness table with both)"
        )
    return sut, sy
