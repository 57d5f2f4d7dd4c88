"""The described shafts of a scene checked with each designed wheel over the cycle that sized it (issue 30, item 5).

:func:`shaft_context` gathers, once per scene, what every check needs from the
analysis: the cycle's speeds, the net torque M_d - M_r and the machine's J_e at
the reference shaft (:meth:`flyopt.machine.reduce.Machine.net_torque_grid`, the
samples the flywheel's peak torque is found on), the net torque's orders
(:func:`flyopt.design.shaft.torsional.net_torque_orders`) and each described
shaft's material (:func:`flyopt.design.materials.get_material`).
:func:`check_candidate` runs :func:`flyopt.design.shaft.check.check_shaft` on one
designed wheel; :func:`acceptor` turns it into the designer's post-check
(``design_flywheel(accept=...)``): a wheel its shaft cannot carry, or one that puts a
critical speed in the running range, makes that combination infeasible with the
limits in numbers; :func:`mass_sensitivity` is d(utilisation)/d(m) of the binding limit.
:func:`key_torque_on` is the torque the wheel's key carries where the shaft's train is modelled, the one the
post-check checks the key at and the design sizes the hub at (:func:`keyed_shafts` puts it on the designer's
shafts; :func:`rekeyed` is the short fixed point where a wheel's own inertia puts more on it).
"""

from __future__ import annotations

import dataclasses
import math
import weakref
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from flyopt.design.combination import combination_label
from flyopt.design.shaft.check import KeySeat, ShaftCheck, ShaftLimit, check_shaft
from flyopt.design.shaft.train import key_torque, shaft_train
from flyopt.machine.drive_train import TrainSpring
from flyopt.machine.torsion import TorqueOrders
from flyopt.machine.transmission import inertia_on_shaft
from flyopt.said import join, said
from flyopt.units import rad_s_to_rpm

if TYPE_CHECKING:
    from flyopt.analysis import Analysis
    from flyopt.design.materials import Material
    from flyopt.design.result import Candidate, DesignResult
    from flyopt.design.spec import MountShaft
    from flyopt.machine.reduce import Machine
    from flyopt.machine.shaft_layout import ShaftLayout
    from flyopt.machine.transmission import Shaft

__all__ = [
    "ShaftContext",
    "ShaftReport",
    "shaft_context",
    "machine_context",
    "at_ratio",
    "check_candidate",
    "acceptor",
    "mass_sensitivity",
    "seat_of",
    "key_of",
    "layout_of",
    "torque_curve",
    "excitation_on",
    "key_torque_on",
    "keyed_shafts",
    "rekeyed",
]

#: Relative step of the central difference of a limit's utilisation in the wheel's mass.
MASS_STEP = 1e-3

#: The words of a candidate's reason that say its shaft refused it (:func:`reject_reason`).
REFUSED = "the shaft cannot carry this"


@dataclass
class ShaftContext:
    """What the shaft checks of one scene need from its analysis (SI, at the reference shaft)."""

    omega_mean: float
    delta: float
    shafts: dict[str, Shaft]
    materials: dict[str, Material]
    j_machine: np.ndarray | None  # J_e at the samples [kg*m^2]; None: net areas (no curves)
    net_torque: np.ndarray | None  # M_d - M_r at the same samples [N*m]
    orders: TorqueOrders | None
    train_materials: dict[str, Material] = field(default_factory=dict)  # the materials a train's pieces name
    # each designed seat's choice, (shaft, material, arms) -> flyopt.design.shaft.seat_nlp.SeatChoice
    seats: dict[tuple[str, str, int | None], Any] = field(default_factory=dict, repr=False)
    _cache: dict[tuple[Any, ...], ShaftCheck] = field(default_factory=dict, repr=False)
    _keyed: dict[tuple[Any, ...], float | None] = field(default_factory=dict, repr=False)  # key_torque_on's


@dataclass(frozen=True)
class ShaftReport:
    """A described shaft's checks with the chosen wheel, and the binding limit's sensitivity to its mass."""

    shaft: str
    material: str
    check: ShaftCheck
    sensitivity: float  # d(utilisation of the binding limit)/d(wheel mass) [1/kg]
    material_name: str = ""  # the material's name for people (Material.display_name); the JSON keeps its key
    layout: ShaftLayout | None = None  # the shaft checked (a designed seat at its diameter)
    seat_diameter: float | None = None  # the designed seat diameter [m]; None: the scene gives it
    seat_series: str | None = None  # the ISO 3 series it was chosen from
    seat_continuous: float | None = None  # the NLP's continuous seat d* [m] (nan: the NLP gave none)
    seat_set_by: str | None = None  # which limit set the seat, in words
    seat_sensitivity: float | None = None  # d(mass)/d(required factor) of the NLP's binding row [kg] (nan: none)
    seat_choice: Any = field(default=None, repr=False, compare=False)  # its flyopt.design.shaft.seat_nlp.SeatChoice

    def to_dict(self) -> dict[str, Any]:
        """The report for ``--json`` (SI); a designed seat adds ``seat_diameter`` [m], ``seat_series``, the NLP's
        ``seat_diameter_continuous`` [m], ``seat_set_by`` and ``seat_dmass_dfactor`` [kg] (null where none)."""
        seat = (
            {}
            if self.seat_diameter is None
            else {"seat_diameter": self.seat_diameter, "seat_series": self.seat_series, **self._seat_nlp()}
        )
        return {
            "shaft": self.shaft,
            "material": self.material,
            **seat,
            **self.check.to_dict(),
            "dutilisation_dmass": self.sensitivity,
        }

    def _seat_nlp(self) -> dict[str, Any]:
        """The NLP's part of a designed seat (absent where the report has none)."""
        if self.seat_set_by is None:
            return {}

        def finite(x: float | None) -> float | None:
            return x if x is not None and math.isfinite(x) else None

        return {
            "seat_diameter_continuous": finite(self.seat_continuous),
            "seat_set_by": self.seat_set_by,
            "seat_dmass_dfactor": finite(self.seat_sensitivity),
        }


#: The context of each live analysis and its shafts (id(analysis) -> (weak reference, shafts, context)): the design
#: and the report of one solve read one context, so the report finds the seat choices the design recorded.
_CONTEXTS: dict[int, tuple[Any, tuple[Any, ...], ShaftContext | None]] = {}


def _forget(key: int) -> Callable[[Any], None]:
    """The callback that drops a dead analysis's context."""

    def drop(_: Any) -> None:
        _CONTEXTS.pop(key, None)

    return drop


def shaft_context(analysis: Analysis, shafts: Iterable[Shaft], library: Mapping[str, Material]) -> ShaftContext | None:
    """The context of the scene's described shafts; None when it describes none. One per analysis and shafts
    while the analysis lives (its checks and designed seats shared by the design and its report)."""
    shafts = tuple(shafts)
    held = _CONTEXTS.get(id(analysis))
    if held is not None and held[0]() is analysis and held[1] == shafts:
        return held[2]
    ctx = machine_context(analysis.machine, analysis.omega_mean, analysis.delta, shafts, library)
    try:
        ref = weakref.ref(analysis, _forget(id(analysis)))
    except TypeError:  # not weakly referable: not kept
        return ctx
    _CONTEXTS[id(analysis)] = (ref, shafts, ctx)
    return ctx


def machine_context(
    machine: Machine | None,
    omega_mean: float,
    delta: float,
    shafts: Iterable[Shaft],
    library: Mapping[str, Material],
) -> ShaftContext | None:
    """The context of the described ``shafts`` on a reduced ``machine`` (None: net areas) running at
    ``omega_mean`` [rad/s] with ``delta``; None when no shaft is described. :func:`shaft_context` of an
    analysis, and the drive's co-design of each motor's machine (:mod:`flyopt.drive.codesign`), call it."""
    from flyopt.design.materials import get_material

    described = {s.name: s for s in shafts if s.layout is not None}
    if not described:
        return None
    materials = {name: get_material(s.layout.material, library) for name, s in described.items() if s.layout}
    j_machine = net = None
    orders = None
    if machine is not None:
        from flyopt.design.shaft.torsional import net_torque_orders

        phi, before, after = machine.net_torque_grid()
        net = np.concatenate([before, after])
        j = machine.j_machine(phi) if machine.variable_inertia else np.full(phi.shape, float(machine.j_machine))
        j_machine = np.concatenate([j, j])
        balanced = machine.angle_only()
        orders = net_torque_orders(balanced.driving, balanced.resisting, machine.cycle_angle)
    pieces = {
        e.material: get_material(e.material, library)
        for s in described.values()
        if s.layout is not None
        for e in s.layout.train
        if isinstance(e, TrainSpring) and e.kind == "piece"
    }
    return ShaftContext(omega_mean, delta, described, materials, j_machine, net, orders, pieces)


def at_ratio(ctx: ShaftContext, name: str, ratio: float) -> ShaftContext:
    """The context with shaft ``name`` turning at ``ratio`` [-] (the drive's flywheel shaft, whose ratio the
    co-design chooses); the checks already made are shared (their key holds the ratio). The shaft's ``loads``
    (a belt pull, a mesh force) stay as given at every ratio, though the torque through that pulley scales with
    1/ratio: the scene states them for the drive as built (docs/flywheel-design.md, section 14)."""
    shafts = {**ctx.shafts, name: dataclasses.replace(ctx.shafts[name], speed_ratio=float(ratio))}
    return dataclasses.replace(ctx, shafts=shafts, _cache=ctx._cache, _keyed=ctx._keyed)


def _wheel(candidate: Candidate) -> tuple[float, float, float]:
    dims = candidate.dims
    width = 0.0 if dims is None else max(dims.b, dims.l_hub or 0.0)
    return float(candidate.mass or 0.0), float(candidate.j_flywheel or 0.0), width


def seat_of(ctx: ShaftContext, candidate: Candidate) -> float | None:
    """The designed seat diameter the candidate's wheel was designed on [m] (its bore), or None where the
    candidate's shaft gives its seat (docs/flywheel-design.md, section 26)."""
    shaft = ctx.shafts.get(candidate.shaft)
    if shaft is None or shaft.layout is None or not shaft.layout.designs_seat:
        return None
    if not candidate.bore:
        raise ValueError(
            f"shaft {candidate.shaft!r} designs its seat, and the wheel was designed without a bore: design it "
            "on a seat diameter (flyopt.design.shaft.diameter)"
        )
    return float(candidate.bore)


def layout_of(ctx: ShaftContext, name: str, seat: float | None = None) -> ShaftLayout:
    """The described shaft ``name`` with its designed steps at ``seat`` [m] (as given where it designs none)."""
    layout = ctx.shafts[name].layout
    if layout is None:
        raise ValueError(f"shaft {name!r} is not described")
    if layout.designs_seat and seat is None:
        raise ValueError(f"shaft {name!r} designs its seat: its checks need the seat diameter")
    return layout.with_seat(seat) if seat is not None else layout


def torque_curve(ctx: ShaftContext, name: str, inertia: float) -> np.ndarray:
    """The torque a wheel of ``inertia`` [kg*m^2] on shaft ``name`` exchanges with it over the cycle [N*m]
    (:func:`flyopt.sizing.peak_torque.flywheel_torque_curve`; a zero where the cycle gives net areas only)."""
    from flyopt.sizing.peak_torque import flywheel_torque_curve

    r = ctx.shafts[name].speed_ratio
    if ctx.net_torque is not None and ctx.j_machine is not None and inertia > 0.0:
        j_ref = inertia * r * r
        curve: np.ndarray = flywheel_torque_curve(j_ref, ctx.j_machine + j_ref, ctx.net_torque, r)
        return curve
    return np.zeros(1)


def key_of(candidate: Candidate) -> KeySeat | None:
    """The key the candidate's wheel was designed with (its seat, its standard length, the allowables the design
    checked it against: the key's shear always, the hub's bearing pressure where its material gives one), or None
    where the design checked none (no bore, no hub, no torque)."""
    found = None if candidate.parts is None else candidate.parts.key
    if not found or not candidate.bore or found.get("allowable_shear") is None:
        return None
    pressure = found.get("allowable_pressure")
    return KeySeat(
        float(candidate.bore),
        float(found["length"]),
        None if pressure is None else float(pressure),
        float(found["allowable_shear"]),
    )


def checked_at(
    ctx: ShaftContext,
    name: str,
    mass: float,
    inertia: float,
    width: float,
    seat: float | None = None,
    key: KeySeat | None = None,
) -> ShaftCheck:
    shaft = ctx.shafts[name]
    cached = (name, shaft.speed_ratio, ctx.omega_mean, mass, inertia, width, seat, key)
    if cached in ctx._cache:
        return ctx._cache[cached]
    layout = layout_of(ctx, name, seat)
    r = shaft.speed_ratio
    torque = torque_curve(ctx, name, inertia)
    excitation = excitation_on(ctx, name)
    check = check_shaft(
        layout,
        ctx.materials[name],
        wheel_mass=mass,
        wheel_inertia=inertia,
        wheel_width=width,
        omega_mean=ctx.omega_mean * r,
        delta=ctx.delta,
        torque_curve=torque,
        excitation=excitation,
        other_inertia=shaft.inertia,
        speed_ratio=r,
        materials=ctx.train_materials,
        key=key,
    )
    ctx._cache[cached] = check
    return check


def excitation_on(ctx: ShaftContext, name: str) -> TorqueOrders | None:
    """The net torque's orders per revolution of shaft ``name`` (order q of the reference is q / r there, its torque
    c_q / r); None where the cycle gives net areas only."""
    if ctx.orders is None:
        return None
    r = ctx.shafts[name].speed_ratio
    o = ctx.orders
    return TorqueOrders(o.mean / r, o.orders / r, o.amplitudes / r)


def key_torque_on(ctx: ShaftContext, name: str, inertia: float, seat: float | None = None) -> float | None:
    """The peak torque [N*m] the key of a wheel of ``inertia`` [kg*m^2] on shaft ``name`` (its seat at ``seat`` [m]
    where the shaft designs it) carries by its train's forced response, J_w theta''_w: the torque the post-check
    checks the key at (:attr:`flyopt.design.shaft.check.ShaftCheck.key_torque`, the same train built by the same
    :func:`flyopt.design.shaft.train.shaft_train` and the same :func:`flyopt.design.shaft.train.key_torque`),
    and so the one the design sizes the hub's length and checks the key at (:func:`keyed_shafts`). None where the
    post-check adds no key limit (net areas, no train, the wheel at the crank end): the design keeps the rigid
    body's peak torque there (docs/flywheel-design.md, section 26)."""
    shaft = ctx.shafts[name]
    excitation = excitation_on(ctx, name)
    if excitation is None or not inertia > 0.0:
        return None
    layout = layout_of(ctx, name, seat)
    r = shaft.speed_ratio
    cached = (name, r, ctx.omega_mean, inertia, seat)
    if cached in ctx._keyed:
        return ctx._keyed[cached]
    built = shaft_train(
        layout,
        ctx.materials[name],
        wheel_inertia=inertia,
        speed_ratio=r,
        other_inertia=shaft.inertia,
        materials=ctx.train_materials,
    )
    found = (
        None if built is None else key_torque(built, excitation, rad_s_to_rpm(ctx.omega_mean * r), layout.damping_ratio)
    )
    peak = None if found is None else found.peak
    ctx._keyed[cached] = peak
    return peak


def keyed_shafts(ctx: ShaftContext | None, shafts: Sequence[MountShaft], j_required: float) -> tuple[MountShaft, ...]:
    """``shafts`` with each described one carrying its key's torque (:func:`key_torque_on`) at the inertia the design
    must supply there, J_F / r^2 (``j_required`` at the reference shaft, already times the rim's share), and at its
    seat: the torque its wheel's arms, hub length and key are designed at in place of the rigid body's
    (:attr:`flyopt.design.spec.MountShaft.torque`). A shaft that designs its seat is keyed at the seat it is given
    (the walk of :mod:`flyopt.design.shaft.diameter` gives each seat it tries), and left as it is without one; so is
    a shaft whose train gives no key torque, one not described and one that already carries its torque."""
    if ctx is None:
        return tuple(shafts)
    out = []
    for s in shafts:
        described = ctx.shafts.get(s.name)
        layout = None if described is None else described.layout
        if layout is None or s.torque is not None or (layout.designs_seat and not s.diameter):
            out.append(s)
            continue
        at = ctx if described.speed_ratio == s.speed_ratio else at_ratio(ctx, s.name, s.speed_ratio)  # type: ignore[union-attr]
        seat = s.diameter if layout.designs_seat else None
        torque = key_torque_on(at, s.name, inertia_on_shaft(j_required, s.speed_ratio), seat)
        out.append(dataclasses.replace(s, torque=torque) if torque is not None and torque > 0.0 else s)
    return tuple(out)


def rekeyed(ctx: ShaftContext, result: DesignResult, shafts: Sequence[MountShaft]) -> tuple[MountShaft, ...] | None:
    """The shafts to design again on, or None: the short fixed point of the key's torque.

    The design sizes a keyed shaft's hub at its key's torque for the inertia it must supply (:func:`keyed_shafts`);
    the post-check checks the key at the torque of the wheel designed, whose inertia can be larger (a rounded
    wheel's), and the train's key torque grows with it (the wheel's share of the train's inertia). Where the
    post-check refused a wheel for its key alone at a torque above the one its shaft was designed at, that shaft is
    returned carrying the largest such torque (each refused wheel's own, :func:`key_torque_on` at its inertia), to
    design again at: the wheels then designed have hubs long enough for the torque their post-check found.
    """
    torques: dict[str, float] = {}
    for c in result.candidates:
        if c.feasible or c.mass is None or REFUSED not in (c.reason or ""):
            continue
        shaft = next((s for s in shafts if s.name == c.shaft and s.torque is not None), None)
        check = None if shaft is None else check_candidate(ctx, c)
        if shaft is None or check is None or not check.failed():
            continue
        if all(lim.kind == "key" for lim in check.failed()) and check.key_torque > cast(float, shaft.torque):
            torques[c.shaft] = max(torques.get(c.shaft, 0.0), check.key_torque)
    if not torques:
        return None
    return tuple(dataclasses.replace(s, torque=torques[s.name]) if s.name in torques else s for s in shafts)


def check_candidate(ctx: ShaftContext, candidate: Candidate) -> ShaftCheck | None:
    """The checks of the candidate's shaft with its wheel; None when that shaft is not described."""
    if candidate.shaft not in ctx.shafts or candidate.mass is None:
        return None
    return checked_at(ctx, candidate.shaft, *_wheel(candidate), seat_of(ctx, candidate), key_of(candidate))


def mass_sensitivity(ctx: ShaftContext, candidate: Candidate, limit: ShaftLimit) -> float:
    """d(utilisation)/d(m) [1/kg] of ``limit``: the wheel scaled in mass and inertia together, central difference."""
    mass, inertia, width = _wheel(candidate)
    h = MASS_STEP * mass
    values = []
    for sign in (1.0, -1.0):
        scale = 1.0 + sign * MASS_STEP
        check = checked_at(
            ctx, candidate.shaft, mass * scale, inertia * scale, width, seat_of(ctx, candidate), key_of(candidate)
        )
        same = [lim for lim in check.limits if lim.kind == limit.kind and lim.where == limit.where]
        values.append(same[0].utilisation if same else math.nan)
    return (values[0] - values[1]) / (2.0 * h)


def reject_reason(candidate: Candidate, check: ShaftCheck, names: Mapping[str, str] | None = None) -> str | None:
    """The sentence that makes a combination infeasible, or None when its shaft holds.

    ``names``: material key -> its name for people (:attr:`flyopt.design.materials.Material.display_name`),
    the name the sentence gives the wheel's material (its key where the map has none).
    """
    failed = check.failed()
    if not failed:
        return None
    material = (names or {}).get(candidate.material, candidate.material)
    what = join("; ", [lim.describe() for lim in failed])
    mass = cast(float, candidate.mass)  # a designed candidate's: the check ran on its wheel
    return (
        f"{combination_label(material, candidate.shaft, candidate.n_arms)}: {REFUSED} "
        + said("{mass} wheel: ", mass=(mass, "mass", f"{mass:.4g} kg"))
        + what
    )


def acceptor(ctx: ShaftContext, names: Mapping[str, str] | None = None) -> Callable[[Candidate], str | None]:
    """The designer's post-check (``design_flywheel(accept=...)``) of the scene's described shafts; its reasons name
    the wheel's material by ``names`` (material key -> name for people, :func:`reject_reason`)."""

    def accept(candidate: Candidate) -> str | None:
        check = check_candidate(ctx, candidate)
        return None if check is None else reject_reason(candidate, check, names)

    return accept


def report(ctx: ShaftContext, candidate: Candidate) -> ShaftReport | None:
    """The chosen wheel's shaft report (None when its shaft is not described)."""
    check = check_candidate(ctx, candidate)
    if check is None:
        return None
    material = ctx.materials[candidate.shaft]
    sensitivity = mass_sensitivity(ctx, candidate, check.binding)
    seat = seat_of(ctx, candidate)
    layout = layout_of(ctx, candidate.shaft, seat)
    series = None if seat is None else ctx.shafts[candidate.shaft].layout.diameter_series  # type: ignore[union-attr]
    choice = ctx.seats.get((candidate.shaft, candidate.material, candidate.n_arms)) if seat is not None else None
    nlp: dict[str, Any] = {}
    if choice is not None and choice.set_by:
        optimum = choice.optimum
        nlp = {
            "seat_continuous": math.nan if optimum is None else optimum.diameter,
            "seat_set_by": choice.set_by,
            "seat_sensitivity": choice.sensitivity(layout.safety_factor),
            "seat_choice": choice,
        }
    return ShaftReport(
        candidate.shaft, material.name, check, sensitivity, material.display_name, layout, seat, series, **nlp
    )
