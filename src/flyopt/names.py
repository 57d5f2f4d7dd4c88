"""The closed vocabularies of flyopt, one enum each, and the one rule that hints at a misspelt name.

Every closed set of names a scene, a function or the command line accepts is
listed here once: the sizing models, the geometries, the design objectives,
the strength criteria, the design methods, the stress measures and the
induction-motor models. Each member *is* its string (``Model.ENERGY ==
"energy"``, ``json.dumps(Model.ENERGY) == '"energy"'``, ``f"{Model.ENERGY}"
== "energy"``), so a value read from a scene file compares equal to the
member and the outputs stay what they were. The descriptions of each name
stay with the physics that gives them meaning (``design.geometry.GEOMETRIES``,
``design.spec.OBJECTIVES``, ``sizing.choose.MODELS``, ...), keyed by these
members.

Open sets that come from data (material names, hub rules, motor catalogues)
have their registry in their data file; they share :func:`closest`.

This module imports nothing from flyopt but :mod:`flyopt.errors`, so every
stage may use it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from enum import Enum

from flyopt.errors import shorten

__all__ = [
    "Name",
    "Model",
    "Geometry",
    "Objective",
    "Criterion",
    "Method",
    "StressMeasure",
    "MotorModel",
    "CUTOFF",
    "closest",
    "hint",
    "choice",
    "unknown",
]

CUTOFF = 0.6
"""Least similarity (difflib's ratio, 0–1) of a name offered as "did you mean"."""


class Name(str, Enum):
    """A name of a closed vocabulary that is, in every use, its string.

    ``str`` and ``format`` give the value (as ``enum.StrEnum`` of Python
    3.11, which 3.10 lacks), ``repr`` the value's repr (messages quote names
    as the user wrote them), and the hash is the string's, so a member finds
    its string's entry in a dictionary and the reverse.
    """

    __str__ = str.__str__
    __format__ = str.__format__  # type: ignore[assignment]  # str's format is Enum's in signature; its stub differs
    __hash__ = str.__hash__

    def __repr__(self) -> str:
        return str.__repr__(self.value)

    @classmethod
    def values(cls) -> tuple[str, ...]:
        """The plain strings of the vocabulary, in their order of definition."""
        return tuple(member.value for member in cls)


class Model(Name):
    """The sizing models, from the cheapest (``sizing.choose``)."""

    ENERGY = "energy"
    ENERGY_MASS = "energy_mass"
    DYNAMIC = "dynamic"


class Geometry(Name):
    """The flywheel geometries (``design.geometry``): three bare models, then two whole wheels."""

    THIN_RIM = "thin_rim"
    RIM = "rim"
    DISC = "disc"
    RIM_WEB = "rim_web"
    RIM_ARMS = "rim_arms"


class Objective(Name):
    """What a design minimizes (``design.spec.OBJECTIVES``)."""

    MASS = "mass"
    OUTER_DIAMETER = "outer_diameter"
    COST = "cost"


class Criterion(Name):
    """What limits a wheel's size (``design.spec.CRITERIA``)."""

    RIM_SPEED = "rim_speed"
    STRESS = "stress"
    MEAN_RIM_SPEED = "mean_rim_speed"


class Method(Name):
    """How a combination is designed (``design.designer.design_flywheel``)."""

    AUTO = "auto"
    IPOPT = "ipopt"
    CLOSED_FORM = "closed_form"


class StressMeasure(Name):
    """The stress measures ``design.stress.max_stress_per_step`` maximises."""

    VON_MISES = "von_mises"
    LARGEST_PRINCIPAL = "largest_principal"
    RADIAL = "radial"
    HOOP = "hoop"


class MotorModel(Name):
    """The torque–speed models of an induction motor (``machine.motor``)."""

    LINEAR = "linear"
    KLOSS = "kloss"


def closest(name: object, allowed: Iterable[object]) -> str | None:
    """The allowed name closest to ``name``, or None when none is close.

    The one rule behind every "did you mean" of flyopt: difflib's ratio of
    at least :data:`CUTOFF`, the best one only.

    Parameters
    ----------
    name : object
        What the user wrote (its ``str`` is compared).
    allowed : iterable of str
        The names it should have been one of.

    Returns
    -------
    str or None
        The plain string of the closest allowed name.
    """
    close = difflib.get_close_matches(str(name), [str(a) for a in allowed], n=1, cutoff=CUTOFF)
    return close[0] if close else None


def hint(name: object, allowed: Iterable[object]) -> str:
    """``"; did you mean 'x'?"`` for the closest allowed name, or ``""`` when none is close."""
    close = closest(name, allowed)
    return f"; did you mean {shorten(close)}?" if close is not None else ""


def choice(value: object, allowed: Iterable[object], field: str) -> str:
    """``value`` when it is one of ``allowed``; else a ValueError of one line.

    The message names the field, quotes the value, offers the closest name
    and lists what is allowed:
    ``geometry 'rimm' is not known; did you mean 'rim'? (allowed: thin_rim, rim, disc, rim_web, rim_arms)``.

    Parameters
    ----------
    value : object
        What the user gave.
    allowed : iterable of str
        The vocabulary (an enum class of this module, or any names).
    field : str
        The field's name as the user knows it.

    Returns
    -------
    object
        ``value`` unchanged.

    Raises
    ------
    ValueError
    """
    names = [str(a) for a in allowed]
    if isinstance(value, str) and value in names:
        return value
    raise ValueError(f"{field} {unknown(value, names)}")


def unknown(value: object, allowed: Iterable[object]) -> str:
    """The words for a name not in ``allowed``: ``'rimm' is not known; did you mean 'rim'? (allowed: ...)``.

    The scene loader puts them after the field's path (a SceneError);
    :func:`choice` after the field's name.
    """
    names = [str(a) for a in allowed]
    return f"{shorten(value)} is not known{hint(value, names)} (allowed: {', '.join(names)})"


#: The sections of a scene that are one calculation rather than a cycle ([operation], [position],
#: [electric_drive], [power_chain]): each stands alone in its scene (flyopt.io.scene), flyopt.pipeline.solve_calculation
#: answers it, and its JSON document is of that kind.
CALCULATIONS = ("operation", "position", "electric_drive", "power_chain")
