"""The one check of a design against its constraints, and the one rule for what binds.

Every design flyopt reports, by IPOPT or by the closed form, for one scene
or for a sweep of a million points, passes through these two functions:
:func:`violations` (is every constraint met, to :data:`VERIFY_RTOL`?) and
:func:`binding_mask` (which constraints are active, to :data:`ACTIVE_RTOL`?).
Both take numpy arrays or plain floats, so the scalar ranking and the
vectorized sweep cannot disagree.

Limits that are not set are ``inf`` (see :mod:`flyopt.design.spec`), which
never binds and is never violated.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 8-10.
"""

from __future__ import annotations

from typing import SupportsInt

import numpy as np
from numpy.typing import NDArray

from flyopt.names import Geometry

#: One design (a float) or many (an array), by the same operators.
FloatOrArray = float | NDArray[np.float64]

__all__ = [
    "BINDING_NAMES",
    "BINDING_BITS",
    "ACTIVE_RTOL",
    "VERIFY_RTOL",
    "binding_label",
    "binding_mask",
    "binding_names",
    "violations",
]

#: Names that ``Candidate.binding`` may contain, in the order reports list them.
BINDING_NAMES = {
    "inertia": "the wheel gives exactly the required inertia",
    "rim_speed": "the outer diameter is at the material's rim speed limit",
    "max_outer_diameter": "the outer diameter is at the scene's envelope",
    "max_width": "the axial width is at the scene's limit",
    "hb_min": "H/B is at the lower end of its range",
    "hb_max": "H/B is at the upper end of its range",
    "inner_diameter": "the inner diameter has shrunk to zero (the rim became a disc)",
}
#: What the limits of a whole wheel (flyopt.design.wheel_nlp) mean when they bind.
WHEEL_BINDING_NAMES = {
    "max_width_hub": "the hub's length is at the scene's width limit",
    "hb_ratio": "H/B is at an end of its range",
    "rim_clears_hub": "the rim sits on the hub (no room left for a web or arms)",
    "bore_clear": "the disc's outer diameter is down to its bore",
    "d_mean": "the mean diameter is pinned",
    "web_below_rim": "the web is as thick as the rim is wide",
    "web_below_hub": "the web is as thick as the hub is long",
    "arms_fit_hub": "the arms fill the hub's circumference",
    "arm_within_rim": "the arms' axial minor axis equals the rim width",
    "arm_within_hub": "the arms' axial minor axis equals the hub length",
    "hub_wall": "the hub's wall is at min_wall",
    "stress_rim": "the rim's stress is at its allowable",
    "stress_web": "the web's stress is at its allowable",
    "stress_hub": "the hub's stress is at its allowable",
    "stress_arms": "the arms' stress is at their allowable",
    "stress_disc": "the disc's stress is at its allowable",
    "min_wall": "a section is at the thinnest the process makes (min_wall)",
    "strength_table": "a section is at the thickest its material's strength-by-thickness table covers",
    "hub_diameter_min": "the hub diameter is at the smallest the textbook proportions allow",
    "hub_diameter_max": "the hub diameter is at the largest the textbook proportions allow",
    "hub_length_min": "the hub length is at its minimum (the proportions, or the key's length at the peak torque)",
    "hub_length_max": "the hub length is at the largest the textbook proportions allow",
    "disc_clears_hub": "the disc's outer diameter is down to its hub",
    "disc_below_hub": "the hub is as long as the disc is wide",
    "castability_min_wall_PART": "a part's wall is at the casting process's minimum for the wheel's size",
    "castability_A_B_ratio": "the section ratio of two joined parts is at the process's limit",
}
#: Short words for each binding name, for the text's and the report's tables (``--json`` keeps the names).
_LABELS = {
    "inertia": "inertia",
    "rim_speed": "rim speed",
    "mean_rim_speed": "mean rim speed (the courses' criterion)",
    "max_outer_diameter": "envelope",
    "max_width": "width limit",
    "hb_min": "H/B min",
    "hb_max": "H/B max",
    "inner_diameter": "no bore left",
    "max_width_hub": "width limit (hub)",
    "hb_ratio": "H/B range",
    "rim_clears_hub": "rim on hub",
    "bore_clear": "disc down to bore",
    "d_mean": "D_m pinned",
    "web_below_rim": "web = rim width",
    "web_below_hub": "web = hub length",
    "arms_fit_hub": "arms fill hub",
    "arm_within_rim": "arm = rim width",
    "arm_within_hub": "arm = hub length",
    "hub_wall": "hub wall",
    "min_wall": "min wall",
    "strength_table": "strength table end",
    "hub_diameter_min": "hub diameter min",
    "hub_diameter_max": "hub diameter max",
    "hub_length_min": "hub length min",
    "hub_length_max": "hub length max",
    "disc_clears_hub": "disc down to hub",
    "disc_below_hub": "hub length = disc width",
}
#: Bits of a binding mask, in the order of :data:`BINDING_NAMES`.
BINDING_BITS = {name: 1 << k for k, name in enumerate(BINDING_NAMES)}
_BITS = tuple(BINDING_BITS.values())
#: Relative tolerance for calling a constraint binding.
ACTIVE_RTOL = 1e-6
#: Relative tolerance when checking a solved design against its constraints.
VERIFY_RTOL = 1e-6


def binding_mask(
    geometry_name: str,
    j_wheel: FloatOrArray,
    j_shaft: FloatOrArray,
    d_outer: FloatOrArray,
    d_inner: FloatOrArray,
    b: FloatOrArray,
    hb: FloatOrArray,
    cap_speed: FloatOrArray,
    envelope: FloatOrArray,
    max_width: FloatOrArray,
    hb_min: FloatOrArray,
    hb_max: FloatOrArray,
) -> int | NDArray[np.int64]:
    """Bit mask of the active constraints of designed wheels (see :func:`binding_names`).

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
    j_wheel, j_shaft : float or ndarray
        Inertia the wheel gives and the inertia needed, on its shaft [kg*m^2].
    d_outer, d_inner, b : float or ndarray
        Outer and inner diameter (may be slightly negative from round-off) and width [m].
    hb : float or ndarray
        H/B [-].
    cap_speed, envelope, max_width : float or ndarray
        Outer-diameter cap of the rim speed, the envelope and the width limit [m]
        (``inf`` where not set).
    hb_min, hb_max : float or ndarray
        The H/B range [-].

    Returns
    -------
    int or ndarray of int64
        OR of :data:`BINDING_BITS` of the constraints within :data:`ACTIVE_RTOL` of their limit.
    """
    rtol = ACTIVE_RTOL
    # plain operators: the same rule for floats (one design, no numpy overhead) and for arrays;
    # in the order of BINDING_NAMES (the last three for rims only)
    flags = [
        j_wheel <= j_shaft * (1.0 + rtol),
        d_outer >= cap_speed * (1.0 - rtol),
        d_outer >= envelope * (1.0 - rtol),
        b >= max_width * (1.0 - rtol),
    ]
    if geometry_name != Geometry.DISC:
        flags += [hb <= hb_min * (1.0 + rtol), hb >= hb_max * (1.0 - rtol), d_inner <= d_outer * rtol]
    if set(map(type, flags)) == {bool} or not any(isinstance(flag, np.ndarray) for flag in flags):  # one design
        bits = 0
        for bit, flag in zip(_BITS, flags):
            if flag:
                bits |= bit
        return bits
    mask = np.zeros(np.shape(d_outer), dtype=np.int64)
    for bit, flag in zip(_BITS, flags):
        mask |= np.where(flag, bit, 0)
    return mask


_NAMES_OF_MASK: dict[int, tuple[str, ...]] = {}


def binding_label(name: str) -> str:
    """The short words for a binding name of :data:`BINDING_NAMES` or :data:`WHEEL_BINDING_NAMES`.

    A part's rows carry the part's name: ``stress_web`` is "web stress",
    ``castability_min_wall_rim`` "rim cast wall", ``castability_rim_web_ratio``
    "section ratio rim-web". A name without words (none, tests/design/test_check.py
    holds every name the NLPs write) is given as it is.
    """
    label = _LABELS.get(name)
    if label is not None:
        return label
    if name.startswith("stress_"):
        return f"{name[len('stress_') :]} stress"
    if name.startswith("castability_min_wall_"):
        return f"{name[len('castability_min_wall_') :]} cast wall"
    if name.startswith("castability_") and name.endswith("_ratio"):
        return f"section ratio {name[len('castability_') : -len('_ratio')].replace('_', '-')}"
    return name


def binding_names(mask: SupportsInt) -> tuple[str, ...]:
    """The constraint names of a binding bit mask, in :data:`BINDING_NAMES` order.

    Returns
    -------
    tuple of str
    """
    mask = int(mask)
    names = _NAMES_OF_MASK.get(mask)
    if names is None:
        names = tuple(name for name, bit in BINDING_BITS.items() if mask & bit)
        _NAMES_OF_MASK[mask] = names
    return names


def violations(
    geometry_name: str,
    j_wheel: float,
    j_shaft: float,
    d_outer: float,
    d_inner: float,
    b: float,
    hb: float,
    cap: float,
    max_width: float,
    hb_min: float,
    hb_max: float,
) -> list[str]:
    """The constraints one design violates by more than :data:`VERIFY_RTOL`, in words.

    Parameters are those of :func:`binding_mask` for one design (plain floats),
    with ``cap`` = min(cap_speed, envelope) [m].

    Returns
    -------
    list of str
        Empty when every constraint holds.
    """
    tol = VERIFY_RTOL
    found = []
    if j_wheel < j_shaft * (1.0 - tol):
        found.append(f"inertia {j_wheel:.9g} < {j_shaft:.9g} kg·m²")
    if d_outer > cap * (1.0 + tol):
        found.append(f"outer diameter {d_outer:.9g} > cap {cap:.9g} m")
    if b > max_width * (1.0 + tol):
        found.append(f"width {b:.9g} > {max_width:.9g} m")
    if geometry_name != Geometry.DISC:
        if not hb_min * (1.0 - tol) <= hb <= hb_max * (1.0 + tol):
            found.append(f"H/B {hb:.9g} outside [{hb_min}, {hb_max}]")
        if d_inner < -tol * d_outer:
            found.append(f"inner diameter {d_inner:.9g} m < 0")
    return found
