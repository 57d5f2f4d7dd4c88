"""More mechanisms for the reduction: the guide-bar (slotted lever), the four-bar linkage and the cam.

Like :class:`flyopt.machine.kinematics.SliderCrank`, each mechanism is given
by its closed-form position analysis, differentiated by hand: the velocity
ratios v_S/ω [m/rad] and ω_i/ω [-] of its parts and their exact slopes
d/dφ, on numpy arrays **or** CasADi symbols (one definition serves the
numpy analysis and the CasADi models). A part becomes a
:class:`flyopt.machine.mechanism.Member` through :meth:`Linkage.kinematics`,
so its equivalent torque and inertia go through the same models as the
slider-crank's (docs/flywheel-design.md, "More mechanisms").

Every mechanism's input (its crank, or the cam's shaft) turns at
``speed_ratio`` times the reference shaft (a gear pair between them: ω_crank/ω
= z_ref/z_crank), with its own angle ψ = speed_ratio·φ − phase; a ratio
with respect to φ is speed_ratio times the ratio with respect to ψ, its
slope speed_ratio² times.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from typing import Any

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from flyopt.errors import shorten
from flyopt.machine.kinematics import ClosedFormRatio, Kinematics, StateCache, is_casadi

TWO_PI = 2.0 * math.pi


def _lib(x: Any) -> Any:
    return ca if is_casadi(x) else np


def _atan2(lib: Any, y: Any, x: Any) -> Any:
    return ca.atan2(y, x) if lib is ca else np.arctan2(y, x)


def _positive(name: str, value: object, what: str) -> float:
    if isinstance(value, bool) or not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise ValueError(f"{what} {name} must be a positive finite number [m], got {shorten(value)}")
    return float(value)


def _finite(name: str, value: object, what: str) -> float:
    if isinstance(value, bool) or not (isinstance(value, (int, float)) and math.isfinite(value)):
        raise ValueError(f"{what} {name} must be a finite number, got {shorten(value)}")
    return float(value)


class Linkage(ABC):
    """What the guide-bar, the four-bar and the cam share: the input's angle and the ratios' chain rule.

    Parameters
    ----------
    speed_ratio : float
        ω_input/ω of the mechanism's input shaft against the reference shaft
        [-] (default 1: the input is the reference shaft).
    phase : float
        ψ = speed_ratio·φ − phase [rad] (default 0).
    """

    what = "mechanism"
    parts: tuple[str, ...] = ()

    def __init__(self, speed_ratio: float = 1.0, phase: float = 0.0) -> None:
        k = _finite("speed_ratio", speed_ratio, self.what)
        if k == 0:
            raise ValueError(f"{self.what} speed_ratio must not be zero")
        self.speed_ratio = k
        self.phase = _finite("phase", phase, self.what)

    @property
    def period(self) -> float:
        """Angle of the reference shaft over which the mechanism repeats, 2π/|speed_ratio| [rad]."""
        return TWO_PI / abs(self.speed_ratio)

    def own_angle(self, phi: Any) -> Any:
        """The input's own angle ψ = speed_ratio·φ − phase [rad]."""
        return self.speed_ratio * phi - self.phase

    @abstractmethod
    def _ratio(self, kind: str, psi: Any, lib: Any, centre: float) -> Any:
        """A ratio with respect to ψ (scalar or pair)."""

    @abstractmethod
    def _slope(self, kind: str, psi: NDArray[np.float64], centre: float) -> Any:
        """d/dψ of :meth:`_ratio` (numpy)."""

    def ratio(self, kind: str, phi: Any, centre: float = 0.0) -> Any:
        """A velocity ratio with respect to φ: speed_ratio × the ratio with respect to ψ."""
        k = self.speed_ratio
        out = self._ratio(kind, self.own_angle(phi), _lib(phi), centre)
        return (k * out[0], k * out[1]) if isinstance(out, tuple) else k * out

    @abstractmethod
    def _part(self, part: str, centre: float | None) -> Kinematics:
        """The velocity ratios of one named part."""

    def kinematics(self, part: str, centre: float | None = None) -> Kinematics:
        """Velocity ratios of one part, for a :class:`flyopt.machine.mechanism.Member`.

        Parameters
        ----------
        part : str
            One of the mechanism's :attr:`parts`.
        centre : float, optional
            Where the part's centre of mass lies [m] (see each mechanism).
        """
        if part not in self.parts:
            allowed = ", ".join(repr(p) for p in self.parts)
            raise ValueError(f"{self.what} part {shorten(part)} is not known (allowed: {allowed})")
        return self._part(part, centre)

    def _crank(self, centre: float) -> Kinematics:
        """A part turning with the input shaft, its centre at ``centre`` from the axis."""
        k = abs(self.speed_ratio)
        return Kinematics(velocity_ratio=abs(centre) * k, angular_ratio=self.speed_ratio)


class LinkageRatio(ClosedFormRatio):
    """One velocity ratio of a :class:`Linkage` as a function of φ, with its exact slope.

    Parameters
    ----------
    mechanism : Linkage
    kind : str
        Which ratio (each mechanism names its own).
    centre : float
        The point's distance along its link [m], where the ratio is a point's.
    """

    def __init__(self, mechanism: Linkage, kind: str, centre: float = 0.0) -> None:
        self.mechanism, self.kind, self.centre = mechanism, kind, float(centre)

    def __repr__(self) -> str:
        return f"LinkageRatio({self.mechanism!r}, {self.kind!r}, {self.centre!r})"

    def __call__(self, phi: Any) -> Any:
        return self.mechanism.ratio(self.kind, phi, self.centre)

    def numpy(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The ratio on a numpy array (``cache`` unused: each ratio is computed on its own)."""
        return self.mechanism.ratio(self.kind, np.asarray(phi, dtype=float), self.centre)

    def slope(
        self, phi: NDArray[np.float64], cache: StateCache | None = None
    ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
        """d/dφ of the ratio: speed_ratio² × the closed-form d/dψ."""
        m = self.mechanism
        k2 = m.speed_ratio**2
        out = m._slope(self.kind, m.own_angle(np.asarray(phi, dtype=float)), self.centre)
        return (k2 * out[0], k2 * out[1]) if isinstance(out, tuple) else k2 * out


def _limits_and_return(angles: list[float]) -> tuple[tuple[float, ...], float]:
    """Sorted crank angles of the two limit positions in [0, 2π) and the time ratio K = long arc / short arc."""
    a, b = sorted(x % TWO_PI for x in angles)
    arc = b - a
    return (a, b), max(arc, TWO_PI - arc) / min(arc, TWO_PI - arc)


class GuideBar(Linkage):
    """The guide-bar (slotted lever, coulisse): a crank whose pin slides in a lever pivoted at a fixed point.

    The crank AB turns about A at the origin; the lever turns about C at
    (−d, 0), the crank's pin B (with its block) sliding along it. The crank
    angle ψ is measured from the direction C→A, counter-clockwise. With
    d > r the lever swings (the quick-return mechanism of shapers); with
    d < r it turns fully (the rotating guide-bar).

    Parameters
    ----------
    crank : float
        r = |AB| [m].
    frame : float
        d = |AC|, the distance between the crank's and the lever's pivots [m].
    lever : float, optional
        Length of the lever |CD| [m]; at least d + r, so that the pin stays
        in the slot.
    speed_ratio, phase : float
        See :class:`Linkage`.

    Raises
    ------
    ValueError
        For non-positive lengths, d = r (the pin then passes through the
        lever's pivot, where the lever's angle is undefined), or a lever
        shorter than d + r.

    Notes
    -----
    With s = sin ψ, c = cos ψ and q = |CB|² = d² + r² + 2dr c:

        lever angle β = atan2(r s, d + r c),
        ω_lever/ω_crank = g = r (r + d c)/q,          g' = r d s (r² − d²)/q²,
        pin B: (−r s, r c),                            slope (−r c, −r s),
        lever point at e from C: e g (−sin β, cos β),  slope e g' (−sin β, cos β) − e g² (cos β, sin β).

    The lever stands still (g = 0) where the crank is perpendicular to it,
    cos ψ = −r/d: the limit positions, whose crank angles split the turn
    into the working and the return stroke, K = (180° + θ)/(180° − θ)
    with the lever's swing θ = 2 arcsin(r/d).
    """

    what = "guide-bar"
    parts = ("crank", "block", "lever")

    def __init__(
        self, crank: float, frame: float, lever: float | None = None, speed_ratio: float = 1.0, phase: float = 0.0
    ) -> None:
        super().__init__(speed_ratio, phase)
        self.crank = _positive("crank", crank, self.what)
        self.frame = _positive("frame", frame, self.what)
        if self.frame == self.crank:
            raise ValueError(
                f"guide-bar with crank = frame = {self.crank!r} m: the pin passes through the lever's pivot "
                f"(at crank angle 180°), where the lever's angle is undefined"
            )
        self.lever = None if lever is None else _positive("lever", lever, self.what)
        if self.lever is not None and self.lever < self.crank + self.frame:
            raise ValueError(
                f"guide-bar lever {self.lever!r} m is shorter than frame + crank = {self.crank + self.frame!r} m: "
                f"the pin would leave the slot"
            )

    def __repr__(self) -> str:
        return (
            f"GuideBar(crank={self.crank!r}, frame={self.frame!r}, lever={self.lever!r}, "
            f"speed_ratio={self.speed_ratio!r}, phase={self.phase!r})"
        )

    @property
    def swings(self) -> bool:
        """Whether the lever swings (d > r, the quick-return mechanism) rather than turns fully."""
        return self.frame > self.crank

    def lever_angle(self, phi: Any) -> Any:
        """β, the lever's angle C→B from +x [rad]."""
        lib = _lib(phi)
        psi = self.own_angle(phi)
        return _atan2(lib, self.crank * lib.sin(psi), self.frame + self.crank * lib.cos(psi))

    def slot_position(self, phi: Any) -> Any:
        """|CB|, the pin's distance from the lever's pivot [m]."""
        lib = _lib(phi)
        r, d = self.crank, self.frame
        return lib.sqrt(d * d + r * r + 2 * d * r * lib.cos(self.own_angle(phi)))

    def lever_angular_ratio(self, phi: Any) -> Any:
        """ω_lever/ω [-]."""
        return self.ratio("lever_angular", phi)

    def limit_positions(self) -> tuple[tuple[float, ...], float]:
        """The crank's own angles ψ where the lever stands still [rad], and the time ratio K.

        Returns ``((), 1.0)`` for a rotating guide-bar (d < r).
        """
        if not self.swings:
            return (), 1.0
        psi = math.acos(-self.crank / self.frame)
        return _limits_and_return([psi, -psi])

    def _g(self, psi: Any, lib: Any) -> tuple[Any, Any, Any]:
        r, d = self.crank, self.frame
        c = lib.cos(psi)
        q = d * d + r * r + 2 * d * r * c
        return r * (r + d * c) / q, q, c

    def _ratio(self, kind: str, psi: Any, lib: Any, centre: float) -> Any:
        r = self.crank
        if kind == "block":
            return -r * lib.sin(psi), r * lib.cos(psi)
        g, q, c = self._g(psi, lib)
        if kind == "lever_angular":
            return g
        root = lib.sqrt(q)  # lever point: e g (−sin β, cos β)
        return -centre * g * r * lib.sin(psi) / root, centre * g * (self.frame + r * c) / root

    def _slope(self, kind: str, psi: NDArray[np.float64], centre: float) -> Any:
        r, d = self.crank, self.frame
        s = np.sin(psi)
        if kind == "block":
            return -r * np.cos(psi), -r * s
        g, q, c = self._g(psi, np)
        dg = r * d * s * (r * r - d * d) / (q * q)
        if kind == "lever_angular":
            return dg
        root = np.sqrt(q)
        sin_b, cos_b = r * s / root, (d + r * c) / root
        return -centre * (dg * sin_b + g * g * cos_b), centre * (dg * cos_b - g * g * sin_b)

    def _part(self, part: str, centre: float | None) -> Kinematics:
        if part == "crank":
            return self._crank(0.5 * self.crank if centre is None else float(centre))
        if part == "block":
            return Kinematics(LinkageRatio(self, "block"), LinkageRatio(self, "lever_angular"))
        if centre is None:
            if self.lever is None:
                raise ValueError("guide-bar lever: give its centre (from the pivot C) or the lever's length")
            centre = 0.5 * self.lever
        return Kinematics(LinkageRatio(self, "lever_point", float(centre)), LinkageRatio(self, "lever_angular"))


FOUR_BAR_BRANCHES = ("open", "crossed")
"""The two assembly branches of a four-bar: "open" has C clockwise of B seen from D (for a crank above the
frame, coupler and rocker do not cross), "crossed" the mirror image about the diagonal BD."""


class FourBar(Linkage):
    """The four-bar linkage driven by its crank: a crank-rocker (or a double crank).

    The crank AB turns about A at the origin, the rocker DC about D at
    (d, 0); the coupler BC joins them. ψ is the crank's angle from A→D,
    counter-clockwise.

    Parameters
    ----------
    crank, coupler, rocker, frame : float
        a = |AB|, b = |BC|, c = |DC|, d = |AD| [m].
    branch : {"open", "crossed"}
        The assembly branch (:data:`FOUR_BAR_BRANCHES`).
    speed_ratio, phase : float
        See :class:`Linkage`.

    Raises
    ------
    ValueError
        When the four lengths cannot close a loop at any angle, or the crank
        cannot turn fully (the diagonal f = |BD|, from |d − a| to d + a,
        must stay strictly between |b − c| and b + c; equality is a dead
        point where the branch is undefined).

    Notes
    -----
    With f² = a² + d² − 2ad cos ψ, δ = atan2(a sin ψ, a cos ψ − d) (the
    direction D→B) and γ = acos((c² + f² − b²)/(2cf)), the rocker's angle
    is θ4 = δ ∓ γ (open: −, crossed: +) and the coupler's θ3 the direction
    B→C. The loop a e^{iψ} + b e^{iθ3} = d + c e^{iθ4}, differentiated:

        k3 = ω3/ω = a sin(θ4 − ψ)/(b sin(θ3 − θ4)),
        k4 = ω4/ω = a sin(θ3 − ψ)/(c sin(θ3 − θ4)),

    and their slopes by the quotient rule (θ3' = k3, θ4' = k4).
    """

    what = "four-bar"
    parts = ("crank", "coupler", "rocker")

    def __init__(
        self,
        crank: float,
        coupler: float,
        rocker: float,
        frame: float,
        branch: str = "open",
        speed_ratio: float = 1.0,
        phase: float = 0.0,
    ) -> None:
        super().__init__(speed_ratio, phase)
        a, b, c, d = (
            _positive(n, v, self.what)
            for n, v in (("crank", crank), ("coupler", coupler), ("rocker", rocker), ("frame", frame))
        )
        if branch not in FOUR_BAR_BRANCHES:
            raise ValueError(f"four-bar branch {shorten(branch)} is not known (allowed: 'open', 'crossed')")
        lengths = (a, b, c, d)
        if 2 * max(lengths) >= sum(lengths):
            raise ValueError(
                f"four-bar {a!r}, {b!r}, {c!r}, {d!r} m cannot be assembled: its longest link must be shorter "
                f"than the other three together"
            )
        low, high = abs(d - a), d + a
        margin = 1e-12 * sum(lengths)  # equal within rounding is the dead point, refused
        if not (abs(b - c) + margin < low and high + margin < b + c):
            raise ValueError(
                f"four-bar crank {a:.6g} m cannot turn fully: the diagonal |BD| runs from {low:.6g} to {high:.6g} m, "
                f"but coupler {b:.6g} m and rocker {c:.6g} m close the loop only for |BD| strictly between "
                f"{abs(b - c):.6g} and {b + c:.6g} m (Grashof, with the crank or the frame the shortest link)"
            )
        self.crank, self.coupler, self.rocker, self.frame, self.branch = a, b, c, d, branch

    def __repr__(self) -> str:
        return (
            f"FourBar(crank={self.crank!r}, coupler={self.coupler!r}, rocker={self.rocker!r}, frame={self.frame!r}, "
            f"branch={self.branch!r}, speed_ratio={self.speed_ratio!r}, phase={self.phase!r})"
        )

    @property
    def rocks(self) -> bool:
        """Whether the output rocks (crank-rocker, the crank the shortest) rather than turns (double crank)."""
        return self.crank < self.frame

    def _angles(self, psi: Any, lib: Any) -> tuple[Any, Any]:
        """θ3 (coupler B→C) and θ4 (rocker D→C) at the crank's own angle [rad]."""
        a, b, c, d = self.crank, self.coupler, self.rocker, self.frame
        bx, by = a * lib.cos(psi), a * lib.sin(psi)
        f2 = a * a + d * d - 2 * a * d * lib.cos(psi)
        delta = _atan2(lib, by, bx - d)
        gamma = (
            lib.arccos((c * c + f2 - b * b) / (2 * c * lib.sqrt(f2)))
            if lib is np
            else ca.acos((c * c + f2 - b * b) / (2 * c * ca.sqrt(f2)))
        )
        theta4 = delta - gamma if self.branch == "open" else delta + gamma
        theta3 = _atan2(lib, c * lib.sin(theta4) - by, d + c * lib.cos(theta4) - bx)
        return theta3, theta4

    def coupler_angle(self, phi: Any) -> Any:
        """θ3, the coupler's direction B→C [rad]."""
        return self._angles(self.own_angle(phi), _lib(phi))[0]

    def rocker_angle(self, phi: Any) -> Any:
        """θ4, the rocker's direction D→C [rad]."""
        return self._angles(self.own_angle(phi), _lib(phi))[1]

    def transmission_angle(self, phi: Any) -> Any:
        """The angle between coupler and rocker, in [0, π] [rad] (90° transmits best)."""
        lib = _lib(phi)
        t3, t4 = self._angles(self.own_angle(phi), lib)
        return lib.arccos(lib.cos(t3 - t4)) if lib is np else ca.acos(ca.cos(t3 - t4))

    def rocker_angular_ratio(self, phi: Any) -> Any:
        """ω_rocker/ω [-]."""
        return self.ratio("rocker_angular", phi)

    def coupler_angular_ratio(self, phi: Any) -> Any:
        """ω_coupler/ω [-]."""
        return self.ratio("coupler_angular", phi)

    def limit_positions(self) -> tuple[tuple[float, ...], float]:
        """The crank's own angles ψ where the rocker stands still (crank and coupler in line) [rad], and K.

        Returns ``((), 1.0)`` for a double crank.
        """
        if not self.rocks:
            return (), 1.0
        a, b, c, d = self.crank, self.coupler, self.rocker, self.frame
        found = []
        for reach, turn in ((b + a, 0.0), (b - a, math.pi)):
            # C at |AC| = reach and |DC| = c; the crank points along A→C (extended) or against it (folded)
            at_a = math.acos((reach * reach + d * d - c * c) / (2 * reach * d))
            for sign in (1.0, -1.0):
                cx, cy = reach * math.cos(sign * at_a), reach * math.sin(sign * at_a)
                psi = sign * at_a + turn
                t4 = float(self._angles(np.array(psi), np)[1])
                if math.hypot(d + c * math.cos(t4) - cx, c * math.sin(t4) - cy) < 1e-9 * (a + b + c + d):
                    found.append(psi)
                    break
        return _limits_and_return(found)

    def _k(self, psi: Any, lib: Any) -> tuple[Any, Any, Any, Any]:
        t3, t4 = self._angles(psi, lib)
        den = lib.sin(t3 - t4)
        k3 = self.crank * lib.sin(t4 - psi) / (self.coupler * den)
        k4 = self.crank * lib.sin(t3 - psi) / (self.rocker * den)
        return t3, t4, k3, k4

    def _ratio(self, kind: str, psi: Any, lib: Any, centre: float) -> Any:
        t3, t4, k3, k4 = self._k(psi, lib)
        if kind == "coupler_angular":
            return k3
        if kind == "rocker_angular":
            return k4
        if kind == "rocker_point":
            return -centre * k4 * lib.sin(t4), centre * k4 * lib.cos(t4)
        a = self.crank  # coupler point at e from B along B→C
        return -a * lib.sin(psi) - centre * k3 * lib.sin(t3), a * lib.cos(psi) + centre * k3 * lib.cos(t3)

    def _slopes(self, psi: NDArray[np.float64]) -> tuple[Any, ...]:
        a, b, c = self.crank, self.coupler, self.rocker
        t3, t4, k3, k4 = self._k(psi, np)
        den, dden = np.sin(t3 - t4), np.cos(t3 - t4) * (k3 - k4)
        n3, dn3 = a * np.sin(t4 - psi), a * np.cos(t4 - psi) * (k4 - 1)
        n4, dn4 = a * np.sin(t3 - psi), a * np.cos(t3 - psi) * (k3 - 1)
        dk3 = (dn3 * den - n3 * dden) / (b * den * den)
        dk4 = (dn4 * den - n4 * dden) / (c * den * den)
        return t3, t4, k3, k4, dk3, dk4

    def _slope(self, kind: str, psi: NDArray[np.float64], centre: float) -> Any:
        t3, t4, k3, k4, dk3, dk4 = self._slopes(psi)
        if kind == "coupler_angular":
            return dk3
        if kind == "rocker_angular":
            return dk4
        e = centre
        if kind == "rocker_point":
            return -e * (dk4 * np.sin(t4) + k4 * k4 * np.cos(t4)), e * (dk4 * np.cos(t4) - k4 * k4 * np.sin(t4))
        a = self.crank
        return (
            -a * np.cos(psi) - e * (dk3 * np.sin(t3) + k3 * k3 * np.cos(t3)),
            -a * np.sin(psi) + e * (dk3 * np.cos(t3) - k3 * k3 * np.sin(t3)),
        )

    def _part(self, part: str, centre: float | None) -> Kinematics:
        if part == "crank":
            return self._crank(0.5 * self.crank if centre is None else float(centre))
        if part == "coupler":
            e = 0.5 * self.coupler if centre is None else float(centre)
            if not 0 <= e <= self.coupler:
                raise ValueError(f"coupler centre of mass must lie between its pins, 0..{self.coupler!r} m, got {e!r}")
            return Kinematics(LinkageRatio(self, "coupler_point", e), LinkageRatio(self, "coupler_angular"))
        e = 0.5 * self.rocker if centre is None else float(centre)
        return Kinematics(LinkageRatio(self, "rocker_point", e), LinkageRatio(self, "rocker_angular"))


#: Follower motion laws: name -> (f(x), f'(x), f''(x)) on the segment's fraction x in [0, 1], f(0) = 0, f(1) = 1.
CAM_LAWS = ("uniform_velocity", "simple_harmonic", "cycloidal", "polynomial_345")

CAM_MOTIONS = ("rise", "dwell", "return")


def _law(name: str, x: Any, lib: Any) -> tuple[Any, Any, Any]:
    """f, f' and f'' of a motion law at the fraction ``x`` (numpy or CasADi)."""
    pi = math.pi
    if name == "uniform_velocity":
        return x, 1.0 + 0.0 * x, 0.0 * x
    if name == "simple_harmonic":
        return 0.5 * (1 - lib.cos(pi * x)), 0.5 * pi * lib.sin(pi * x), 0.5 * pi * pi * lib.cos(pi * x)
    if name == "cycloidal":
        return (
            x - lib.sin(2 * pi * x) / (2 * pi),
            1 - lib.cos(2 * pi * x),
            2 * pi * lib.sin(2 * pi * x),
        )
    x2 = x * x
    return (
        x2 * x * (10 - 15 * x + 6 * x2),
        30 * x2 * (1 - 2 * x + x2),
        60 * x * (1 - 3 * x + 2 * x2),
    )


class Cam(Linkage):
    """A cam with a translating follower moving by named laws, segment after segment.

    Parameters
    ----------
    segments : sequence of (motion, law, angle, lift)
        One turn of the cam from ψ = 0: ``motion`` is "rise", "dwell" or
        "return"; ``law`` one of :data:`CAM_LAWS` (None for a dwell);
        ``angle`` the cam angle the segment takes [rad]; ``lift`` the
        follower's travel in it [m] (unused for a dwell). The angles must
        add up to one turn, and the rises and the returns to the same lift.
    speed_ratio, phase : float
        See :class:`Linkage`.

    Notes
    -----
    On a segment from ψ_k of angle β with x = (ψ − ψ_k)/β, the follower is
    at s = s_k ± h f(x) (+ rise, − return), so ds/dψ = ± h f'(x)/β and
    d²s/dψ² = ± h f''(x)/β². For a translating follower (knife-edge, roller
    or flat, in line or offset) the velocity ratio of the follower is
    ds/dψ whatever the cam's profile, since the profile is made to give
    s(ψ). Laws: uniform velocity f = x (the velocity jumps at the ends: the
    book's rigid impact); simple harmonic (1 − cos πx)/2; cycloidal
    x − sin(2πx)/2π; 3-4-5 polynomial 10x³ − 15x⁴ + 6x⁵.
    """

    what = "cam"
    parts = ("cam", "follower")

    def __init__(
        self,
        segments: Sequence[tuple[str, str | None, float, float]],
        speed_ratio: float = 1.0,
        phase: float = 0.0,
    ) -> None:
        super().__init__(speed_ratio, phase)
        if not segments:
            raise ValueError("cam needs at least one segment")
        rows = []
        start, level, top = 0.0, 0.0, 0.0
        for k, (motion, law, angle, lift) in enumerate(segments):
            if motion not in CAM_MOTIONS:
                raise ValueError(
                    f"cam segment {k}: motion {shorten(motion)} is not known (allowed: rise, dwell, return)"
                )
            beta = _positive("angle", angle, f"cam segment {k}")
            if motion == "dwell":
                rows.append((start, beta, level, 0.0, "uniform_velocity"))
            else:
                if law not in CAM_LAWS:
                    raise ValueError(
                        f"cam segment {k}: law {shorten(law)} is not known (allowed: {', '.join(CAM_LAWS)})"
                    )
                h = _positive("lift", lift, f"cam segment {k}")
                signed = h if motion == "rise" else -h
                rows.append((start, beta, level, signed, law))
                level += signed
                if level < -1e-12 * h:
                    raise ValueError(f"cam segment {k}: the return takes the follower below where it started")
                top = max(top, level)
            start += beta
        if abs(start - TWO_PI) > 1e-9:
            raise ValueError(f"cam segments cover {math.degrees(start)!r} deg; they must add up to one turn, 360 deg")
        if abs(level) > 1e-9 * max(top, 1e-300):
            raise ValueError(
                f"cam: the follower ends {level!r} m from where it started; the rises and returns must balance"
            )
        self.segments = tuple(rows)
        self.stroke = top

    def __repr__(self) -> str:
        return f"Cam(segments={self.segments!r}, speed_ratio={self.speed_ratio!r}, phase={self.phase!r})"

    def _pieces(self, psi: Any, lib: Any, order: int) -> Any:
        """s (order 0), ds/dψ (1) or d²s/dψ² (2) of the follower, piecewise over the segments."""
        turn = psi - TWO_PI * lib.floor(psi / TWO_PI)
        out = 0.0 * turn
        for start, beta, level, signed, law in self.segments:  # a later segment overrides from its start
            x = (turn - start) / beta
            f = _law(law, x, lib)[order]
            value = (level if order == 0 else 0.0) + signed * f / beta**order
            inside = turn >= start
            out = ca.if_else(inside, value, out) if lib is ca else np.where(inside, value, out)
        return out

    def follower_position(self, phi: Any) -> Any:
        """s, the follower's lift from its lowest position [m]."""
        return self._pieces(self.own_angle(phi), _lib(phi), 0)

    def follower_velocity_ratio(self, phi: Any) -> Any:
        """v_follower/ω [m/rad], signed (+ away from the cam's axis)."""
        return self.ratio("follower", phi)

    def _ratio(self, kind: str, psi: Any, lib: Any, centre: float) -> Any:
        return self._pieces(psi, lib, 1)

    def _slope(self, kind: str, psi: NDArray[np.float64], centre: float) -> Any:
        return self._pieces(psi, np, 2)

    def _part(self, part: str, centre: float | None) -> Kinematics:
        if part == "cam":
            return self._crank(0.0 if centre is None else float(centre))
        return Kinematics(LinkageRatio(self, "follower"), 0.0)
