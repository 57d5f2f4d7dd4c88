"""Kinematics of the mechanisms a machine is built from: velocity ratios over the crank angle.

The reduction to the reference shaft (:mod:`flyopt.machine.mechanism`) needs
only the velocity *ratios* v_S/ω [m/rad] and ω_i/ω [-] of each member. They
are constant for gear trains (:class:`GearTrain`) and vary with φ for
linkages; the slider-crank (:class:`SliderCrank`) is given by its analytic
kinematics (closed-form positions differentiated by hand, not finite
differences, with the exact slopes in :class:`SliderCrankRatio`). Every
kinematic function accepts a numpy array **or** a CasADi SX/MX symbol and
returns the same kind, so one definition serves the numpy analysis and the
CasADi models.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from flyopt.errors import shorten

#: A mechanism's trigonometry in one numpy evaluation (:meth:`SliderCrank._state`), shared by its members:
#: id(mechanism) -> (the angles it was computed at, (sin φ, cos φ, u, w)).
StateCache = dict[
    int, tuple[object, tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]]
]


def is_casadi(x: object) -> bool:
    """Whether ``x`` is a CasADi value (SX, MX or DM) rather than a number or a numpy array."""
    return isinstance(x, (ca.SX, ca.MX, ca.DM))


def _lib(x: Any) -> Any:
    """numpy or casadi, whichever matches ``x``."""
    return ca if is_casadi(x) else np


@dataclass(frozen=True)
class Kinematics:
    """Velocity ratios of one member of a mechanism.

    Attributes
    ----------
    velocity_ratio : callable
        φ ↦ v_S/ω of the member's centre of mass [m/rad]; returns a scalar
        (signed, along a fixed axis) or a pair (v_x/ω, v_y/ω).
    angular_ratio : callable
        φ ↦ ω_member/ω [-].
    """

    velocity_ratio: Any  # a number, or a function of φ (numpy or CasADi) giving a scalar or a pair
    angular_ratio: Any  # a number, or a function of φ


class SliderCrank:
    """Slider-crank (crank OA, rod AB, slider B) driven by the reference crank.

    The crank turns about O at the origin; the crank angle φ [rad] is measured
    from the slider axis, positive counter-clockwise. The slider moves along
    the line y = ``offset`` on the side x > 0, so φ = 0 is (for zero offset)
    the outer dead centre.

    Parameters
    ----------
    crank : float
        Crank radius r = |OA| [m].
    rod : float
        Connecting-rod length l = |AB| [m]; must exceed r + |offset| so that
        the crank turns fully.
    offset : float
        Distance e of the slider axis from O [m] (positive: the axis lies on
        the side y > 0).
    phase : float
        Angle of the reference shaft at which this crank points along the
        slider axis [rad] (default 0): the crank's own angle is
        ψ = φ − phase, and every formula below is written in ψ. A
        multi-cylinder engine is one slider-crank per cylinder, each phased
        by its firing angle (flyopt.machine.engine). Derivatives with
        respect to φ and ψ are the same.

    Raises
    ------
    ValueError
        For non-positive or non-finite lengths, l <= r + |e|, or a
        non-finite phase.

    Notes
    -----
    With u = r sin ψ − e and w = sqrt(l² − u²) (ψ = φ for phase 0):

        x_B = r cos ψ + w,
        v_B/ω = dx_B/dφ = −r sin ψ − u r cos ψ / w,
        rod angle β = atan2(−u, w)  (direction of A→B),
        ω_rod/ω = dβ/dφ = −r cos ψ / w.

    A point of the rod at the fraction s = |AP|/l from the crank pin moves at
    ((1 − s)(−r sin ψ) + s v_B/ω, (1 − s) r cos ψ) times ω.

    References
    ----------
    .. [1] Shigley, J. E., Uicker, J. J., *Theory of Machines and Mechanisms*,
       slider-crank position and velocity analysis (loop-closure equations).
    """

    def __init__(self, crank: float, rod: float, offset: float = 0.0, phase: float = 0.0) -> None:
        for name, value in (("crank", crank), ("rod", rod)):
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"slider-crank {name} length must be a positive finite number [m], got {value!r}")
        if not (isinstance(offset, (int, float)) and math.isfinite(offset)):
            raise ValueError(f"slider-crank offset must be a finite number [m], got {offset!r}")
        if rod <= crank + abs(offset):
            raise ValueError(
                f"slider-crank with crank {crank!r} m, rod {rod!r} m and offset {offset!r} m cannot turn fully: "
                f"the rod must be longer than crank + |offset| = {crank + abs(offset)!r} m"
            )
        if not (isinstance(phase, (int, float)) and math.isfinite(phase)):
            raise ValueError(f"slider-crank phase must be a finite angle [rad], got {phase!r}")
        self.crank = float(crank)
        self.rod = float(rod)
        self.offset = float(offset)
        self.phase = float(phase)

    def __repr__(self) -> str:
        phase = f", phase={self.phase!r}" if self.phase else ""
        return f"SliderCrank(crank={self.crank!r}, rod={self.rod!r}, offset={self.offset!r}{phase})"

    def _own(self, phi):
        """The crank's own angle ψ = φ − phase (φ itself, untouched, for phase 0)."""
        return phi - self.phase if self.phase else phi

    def _uw(self, psi):
        """u and w at the crank's own angle ψ (see Notes)."""
        lib = _lib(psi)
        u = self.crank * lib.sin(psi) - self.offset
        return u, lib.sqrt(self.rod**2 - u * u)

    def _state(self, phi, cache=None):
        """sin φ, cos φ, u and w on a numpy array, computed once per evaluation.

        ``cache`` (a dict, or None) is shared by the members of one
        evaluation of J_e or M_e, so that a mechanism's trigonometry is done
        once however many of its parts are members. The values are those of
        the methods below, operation for operation.
        """
        key = id(self)
        if cache is not None and key in cache and cache[key][0] is phi:
            return cache[key][1]
        psi = self._own(phi)
        s, c = np.sin(psi), np.cos(psi)
        u = self.crank * s - self.offset
        state = (s, c, u, np.sqrt(self.rod**2 - u * u))
        if cache is not None:
            cache[key] = (phi, state)
        return state

    def slider_position(self, phi: Any) -> Any:
        """Slider position x_B along its axis [m]."""
        lib = _lib(phi)
        psi = self._own(phi)
        return self.crank * lib.cos(psi) + self._uw(psi)[1]

    def stroke(self) -> float:
        """Slider stroke, x_B max − x_B min [m] (closed form, valid with offset)."""
        r, l, e = self.crank, self.rod, self.offset
        return math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e)

    def slider_velocity_ratio(self, phi: Any) -> Any:
        """v_B/ω of the slider [m/rad], signed along +x."""
        lib = _lib(phi)
        psi = self._own(phi)
        u, w = self._uw(psi)
        return -self.crank * lib.sin(psi) - u * self.crank * lib.cos(psi) / w

    def rod_angle(self, phi: Any) -> Any:
        """Angle β of the rod, direction crank pin → slider, from +x [rad]."""
        lib = _lib(phi)
        u, w = self._uw(self._own(phi))
        return lib.arctan2(-u, w) if lib is np else ca.atan2(-u, w)

    def rod_angular_ratio(self, phi: Any) -> Any:
        """ω_rod/ω [-] (signed, counter-clockwise positive)."""
        lib = _lib(phi)
        psi = self._own(phi)
        return -self.crank * lib.cos(psi) / self._uw(psi)[1]

    def rod_point_velocity_ratio(self, phi: Any, fraction: float) -> tuple[Any, Any]:
        """Velocity ratio of a point of the rod, (v_x/ω, v_y/ω) [m/rad].

        Parameters
        ----------
        phi : array or casadi symbol
            Crank angle [rad].
        fraction : float
            s = |AP|/l: 0 at the crank pin, 1 at the slider pin.
        """
        lib = _lib(phi)
        s = float(fraction)
        psi = self._own(phi)
        vx = (1 - s) * (-self.crank * lib.sin(psi)) + s * self.slider_velocity_ratio(phi)
        vy = (1 - s) * self.crank * lib.cos(psi)
        return vx, vy

    def kinematics(self, part: str, centre: float | None = None) -> Kinematics:
        """Velocity ratios of one part of the mechanism, for a :class:`flyopt.machine.mechanism.Member`.

        Parameters
        ----------
        part : {"crank", "rod", "slider"}
        centre : float, optional
            Position of the part's centre of mass [m]: for the crank, its
            distance from O along OA (negative: behind O, e.g. a
            counterweight; default r/2); for the rod, its distance from the
            crank pin A along AB (default l/2); unused for the slider.

        Returns
        -------
        Kinematics
        """
        if part == "crank":
            c = 0.5 * self.crank if centre is None else float(centre)
            return Kinematics(velocity_ratio=abs(c), angular_ratio=1.0)
        if part == "rod":
            c = 0.5 * self.rod if centre is None else float(centre)
            if not 0 <= c <= self.rod:
                raise ValueError(f"rod centre of mass must lie between the pins, 0..{self.rod!r} m, got {c!r}")
            s = c / self.rod
            return Kinematics(
                velocity_ratio=SliderCrankRatio(self, "rod_point", s),
                angular_ratio=SliderCrankRatio(self, "rod_angular"),
            )
        if part == "slider":
            return Kinematics(velocity_ratio=SliderCrankRatio(self, "slider"), angular_ratio=0.0)
        raise ValueError(f"slider-crank part {shorten(part)} is not known (allowed: 'crank', 'rod', 'slider')")


class ClosedFormRatio(ABC):
    """A velocity ratio of a linkage given in closed form, with its exact slope.

    Callable on a numpy array or a CasADi symbol (returning the same kind);
    :meth:`numpy` and :meth:`slope` give the ratio and its derivative with
    respect to φ on numpy arrays without CasADi. The reduction
    (:mod:`flyopt.machine.mechanism`) recognises this class and takes
    dJ_e/dφ from :meth:`slope`. Subclasses: :class:`SliderCrankRatio` and
    :class:`flyopt.machine.linkages.LinkageRatio`.
    """

    @abstractmethod
    def __call__(self, phi: Any) -> Any:
        """The ratio on a numpy array or a CasADi symbol."""

    @abstractmethod
    def numpy(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The ratio on a numpy array [m/rad] or [-]."""

    @abstractmethod
    def slope(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """d/dφ of the ratio on a numpy array [m/rad²] or [1/rad]."""


class SliderCrankRatio(ClosedFormRatio):
    """One velocity ratio of a :class:`SliderCrank` as a function of φ, with its exact derivative.

    Callable like the mechanism's methods (numpy arrays or CasADi symbols);
    for numpy it also gives the derivative with respect to φ by the
    hand-differentiated closed form, so that J_e(φ) and dJ_e/dφ are
    evaluated on arrays without CasADi.

    Parameters
    ----------
    mechanism : SliderCrank
    kind : {"slider", "rod_angular", "rod_point"}
        v_B/ω of the slider [m/rad], ω_rod/ω [-], or the velocity ratio
        (v_x/ω, v_y/ω) of a point of the rod [m/rad].
    fraction : float
        For "rod_point": s = |AP|/l.

    Notes
    -----
    With s = sin φ, c = cos φ, u = r s − e, w = sqrt(l² − u²), so that
    u' = r c and w' = −u r c / w (:class:`SliderCrank`):

        (v_B/ω)'   = −r c − r² c²/w + u r s/w − u² r² c²/w³,
        (ω_rod/ω)' = r s/w − u r² c²/w³,
        rod point: ((1 − s_f)(−r c) + s_f (v_B/ω)',  −(1 − s_f) r s).
    """

    def __init__(self, mechanism: SliderCrank, kind: str, fraction: float = 0.0) -> None:
        if kind not in ("slider", "rod_angular", "rod_point"):
            raise ValueError(f"slider-crank ratio {shorten(kind)} is not known")
        self.mechanism, self.kind, self.fraction = mechanism, kind, float(fraction)

    def __repr__(self) -> str:
        extra = f", {self.fraction!r}" if self.kind == "rod_point" else ""
        return f"SliderCrankRatio({self.mechanism!r}, {self.kind!r}{extra})"

    def __call__(self, phi: Any) -> Any:
        sc = self.mechanism
        if self.kind == "slider":
            return sc.slider_velocity_ratio(phi)
        if self.kind == "rod_angular":
            return sc.rod_angular_ratio(phi)
        return sc.rod_point_velocity_ratio(phi, self.fraction)

    def numpy(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The ratio on a numpy array (the same operations as calling it) [m/rad] or [-]."""
        sc = self.mechanism
        s, c, u, w = sc._state(phi, cache)
        r = sc.crank
        if self.kind == "rod_angular":
            return -r * c / w
        slider = -r * s - u * r * c / w
        if self.kind == "slider":
            return slider
        f = self.fraction
        return (1 - f) * (-r * s) + f * slider, (1 - f) * r * c

    def slope(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """d/dφ of the ratio on a numpy array [m/rad²] or [1/rad] (see Notes)."""
        sc = self.mechanism
        s, c, u, w = sc._state(phi, cache)
        r = sc.crank
        rc2_w3 = (r * c) ** 2 / (w * w * w)
        if self.kind == "rod_angular":
            return r * s / w - u * rc2_w3
        slider = -r * c - (r * c) ** 2 / w + u * r * s / w - u * u * rc2_w3
        if self.kind == "slider":
            return slider
        f = self.fraction
        return (1 - f) * (-r * c) + f * slider, -(1 - f) * r * s


def known_ratio(function: object) -> SliderCrankRatio | None:
    """A SliderCrank's own ratio method, given bound, as a :class:`SliderCrankRatio` (else None)."""
    owner = getattr(function, "__self__", None)
    if isinstance(owner, SliderCrank):
        name = getattr(function, "__name__", "")
        if name == "slider_velocity_ratio":
            return SliderCrankRatio(owner, "slider")
        if name == "rod_angular_ratio":
            return SliderCrankRatio(owner, "rod_angular")
    return None


class GearTrain:
    """A train of gear (or belt) stages with constant speed ratios.

    Parameters
    ----------
    ratios : sequence of float
        Speed ratio of each stage, ω_out/ω_in [-], from the reference shaft
        outwards. Shaft 0 is the reference shaft; shaft k turns at
        ratios[0]·…·ratios[k−1] times its speed.

    Notes
    -----
    For a pair of gears with z_in and z_out teeth, ω_out/ω_in = z_in/z_out
    (the sense of rotation does not enter the inertia; a torque on a gear
    uses the "driving"/"resisting" sense of :class:`flyopt.machine.mechanism.Member`).
    """

    def __init__(self, ratios: Iterable[float]) -> None:
        ratios = [float(r) for r in ratios]
        for r in ratios:
            if not (math.isfinite(r) and r != 0):
                raise ValueError(f"a gear stage ratio must be a finite non-zero number, got {r!r}")
        self.ratios = tuple(ratios)

    @classmethod
    def from_teeth(cls, pairs: Iterable[tuple[float, float]]) -> GearTrain:
        """Gear train from tooth counts ``[(z_in, z_out), ...]`` per stage."""
        stages = []
        for pair in pairs:
            z_in, z_out = pair
            if not (z_in > 0 and z_out > 0):
                raise ValueError(f"tooth counts must be positive, got {pair!r}")
            stages.append(z_in / z_out)
        return cls(stages)

    def angular_ratio(self, shaft: int) -> float:
        """ω_shaft/ω of shaft ``shaft`` (0 = reference) [-]."""
        if not 0 <= shaft <= len(self.ratios):
            raise ValueError(f"gear train has shafts 0..{len(self.ratios)}, got {shaft!r}")
        return math.prod(self.ratios[:shaft])

    def kinematics(self, shaft: int) -> Kinematics:
        """Velocity ratios of a gear on shaft ``shaft`` (centre on the axis)."""
        return Kinematics(velocity_ratio=0.0, angular_ratio=self.angular_ratio(shaft))
