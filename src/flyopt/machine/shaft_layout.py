"""A mounting shaft described as a part: its steps, bearings, wheel seat, material and other loads (issue 30).

Plain data in SI, read from a scene's ``[[shaft]]`` (:mod:`flyopt.io.shaft_section`)
and checked with the wheel designed for it by :func:`flyopt.design.shaft.check.check_shaft`
(docs/flywheel-design.md, section 26). The shaft is the line 0 <= x <= L of solid
round steps on two bearings; x is measured from one end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from flyopt.machine.drive_train import TrainInertia, TrainSpring

__all__ = ["SideLoad", "ShaftLayout"]


@dataclass(frozen=True)
class SideLoad:
    """A transverse force on the shaft other than the wheel's (a belt's or a gear's pull).

    Attributes
    ----------
    position : float
        x [m] along the shaft.
    force : float
        Its magnitude [N], >= 0.
    angle : float
        Its direction in the plane normal to the axis [rad], from the weight's (straight down),
        turning towards the horizontal: 0 pulls down with the weight, pi/2 pulls sideways, pi lifts.
    """

    position: float
    force: float
    angle: float = 0.0


@dataclass(frozen=True)
class ShaftLayout:
    """The geometry, material and loads of a shaft described as a part (SI).

    Attributes
    ----------
    steps : tuple of float
        The step ends x_1 < ... < x_n = L [m] (the shaft starts at x = 0).
    diameters : tuple of float
        d_j [m] of the step ending at ``steps[j]``.
    bearings : (float, float)
        x_A < x_B [m].
    wheel_at : float
        The wheel seat's centre [m] (between the bearings, or overhung beyond one); a keyway is cut there.
    torque_at : float
        Where the torque the wheel exchanges enters or leaves the shaft [m] (the crank, a pulley,
        a coupling): the length between it and the seat carries that torque and twists.
    material : str
        The shaft's material, a name of the material library or of the scene's [[material]]s.
    finish : str
        Surface finish of Shigley's Table 6-2 (ground, machined, hot_rolled, as_forged).
    fillet : float or None
        Fillet radius of the shoulders [m]; None: sharp (Shigley's Table 7-1, r/d = 0.02).
    loads : tuple of SideLoad
        Other transverse loads (belt or gear pulls).
    balance_grade : float or None
        ISO 21940-11 balance quality grade G = e omega [m/s]; None: the flywheel's grade
        (:data:`flyopt.design.balance.BALANCE_GRADE`, G 6.3), the one the wheel's own balance uses.
    safety_factor : float
        The factor of safety the fatigue and first-cycle yield checks require [-].
    max_slope : float
        The largest slope allowed at a bearing [rad].
    max_deflection : float or None
        The largest deflection allowed at the wheel [m]; None: reported, not limited.
    critical_margin : float
        The separation a lateral critical speed must keep from the running range, as a share of
        its nearer end [-].
    train : tuple of TrainInertia and TrainSpring
        The drive train's torsional elements in order from the motor to the crank
        (:mod:`flyopt.machine.drive_train`); empty: the wheel and the shaft's own inertia at
        ``torque_at``, joined by the shaft between them (the two-inertia train).
    damping_ratio : float
        The modal damping ratio of every elastic torsional mode in the forced response [-].
    designed : tuple of int
        The steps whose diameter the design chooses (``diameter = "design"``; the wheel seat's step among
        them): each takes the one designed seat diameter d, their ``diameters`` entries are nan until
        :meth:`with_seat` gives it. Empty: every diameter is given (docs/flywheel-design.md, section 26).
    diameter_series : str
        The ISO 3 preferred-number series d is chosen from (:data:`flyopt.design.preferred.SERIES`).
    """

    steps: tuple[float, ...]
    diameters: tuple[float, ...]
    bearings: tuple[float, float]
    wheel_at: float
    torque_at: float
    material: str
    finish: str = "machined"
    fillet: float | None = None
    loads: tuple[SideLoad, ...] = ()
    balance_grade: float | None = None
    safety_factor: float = 1.5
    max_slope: float = 1.0e-3
    max_deflection: float | None = None
    critical_margin: float = 0.2
    train: tuple[TrainInertia | TrainSpring, ...] = ()
    damping_ratio: float = 0.02
    designed: tuple[int, ...] = ()
    diameter_series: str = "R40"

    @property
    def length(self) -> float:
        """L [m]."""
        return self.steps[-1]

    def diameter_at(self, x: float) -> float:
        """d [m] of the step holding x (at a step end, the step that ends there)."""
        for end, d in zip(self.steps, self.diameters):
            if x <= end:
                return d
        return self.diameters[-1]

    @property
    def designs_seat(self) -> bool:
        """Whether the design chooses the seat diameter (some steps are ``"design"``)."""
        return bool(self.designed)

    def with_seat(self, d: float) -> ShaftLayout:
        """This shaft with its designed steps at diameter ``d`` [m] (itself when none is designed)."""
        if not self.designed:
            return self
        if not (math.isfinite(d) and d > 0.0):
            raise ValueError(f"a designed seat diameter must be positive and finite, got {d!r} m")
        diameters = tuple(d if j in self.designed else dj for j, dj in enumerate(self.diameters))
        return replace(self, diameters=diameters, designed=())

    @property
    def overhung(self) -> bool:
        """Whether the wheel sits beyond a bearing."""
        return not self.bearings[0] <= self.wheel_at <= self.bearings[1]
