"""One material x mounting shaft combination, as the designer decides it.

The designer (:func:`flyopt.design.designer.design_flywheel`) builds one
:class:`Combination` per material and shaft: the speed of that shaft, the
inertia required there (J_F / r^2), the caps on the outer diameter, the
shaft seat and the peak torque there. The textbook NLP
(:mod:`flyopt.design.nlp`) and the whole-wheel design
(:mod:`flyopt.design.wheel_design`) read it; its :attr:`Combination.label`
names it in every message.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from flyopt.design.materials import Material
from flyopt.design.spec import DesignSpec, MountShaft

__all__ = ["Combination", "combination_label", "shaft_label", "wheel_words"]


@dataclass
class Combination:
    """A material on a mounting shaft, with what the design of its wheel needs (SI)."""

    material: Material
    shaft: MountShaft
    omega: float  # speed of the carrying shaft [rad/s]
    j_shaft: float  # required inertia on that shaft [kg*m^2]
    j_reference: float
    cap_speed: float  # outer-diameter cap of the rim speed [m]
    cap: float  # min(cap_speed, envelope) [m]
    j_max: float = 0.0
    bore: float = 0.0  # the shaft seat [m], 0: none
    torque: float = 0.0  # peak torque on this shaft [N*m], 0: unknown
    n_arms: int = 0  # a rim_arms wheel's arm count
    v_max: float = math.nan  # the material's safe rim speed [m/s] (nan: none, under the stress criterion)
    d_mean: float | None = None  # pinned mean diameter [m]: the spec's, or the courses' rim convention's
    cap_mean: float = math.inf  # the courses' cap on D_m: 2 v_max / omega'_mean [m] (criterion mean_rim_speed)

    def stress_factors(self, spec: DesignSpec) -> dict[str, float]:
        """This combination's factors on its parts' modelled stresses (the FE acceptance's): part -> factor."""
        return spec.stress_factors_for(self.material.name, self.shaft.name, self.n_arms)

    @property
    def label(self) -> str:
        """The combination in words, e.g. ``"grey cast iron on the crank shaft with 6 arms"``."""
        return combination_label(self.material.display_name, self.shaft.name, self.n_arms)


def combination_label(material: str, shaft: str, n_arms: int | None = 0) -> str:
    """A combination in words, the one way every message names one: ``material`` is the material's name for
    people (:attr:`flyopt.design.materials.Material.display_name`, never its library key), ``shaft`` the
    mounting shaft's name, ``n_arms`` a rim_arms wheel's arm count (0 or None: no arms)."""
    arms = f" with {n_arms} arms" if n_arms else ""
    return f"{material} on the {shaft_label(shaft)}{arms}"


def wheel_words(geometry: str, n_arms: int | None = None) -> str:
    """A wheel's geometry in words, the one way the answers name it: "disc", "wheel with a web", "wheel on 6
    arms", "rim" (a rim or a thin rim)."""
    if geometry == "disc":
        return "disc"
    if geometry == "rim_web":
        return "wheel with a web"
    if geometry == "rim_arms":
        return f"wheel on {n_arms} arms" if n_arms else "wheel on arms"
    return "rim"


def shaft_label(name: str) -> str:
    """A shaft's name as a phrase: ``"crank"`` becomes ``"crank shaft"``; ``"output shaft"`` stays."""
    return name if name.lower().endswith("shaft") else f"{name} shaft"
