"""The drive train of a described shaft as a lumped torsional model, and its forced response (issue 30, item 4).

:func:`train_model` builds the scene's train (:mod:`flyopt.machine.drive_train`, from the motor to
the crank) with the designed wheel at its place into a :class:`flyopt.machine.torsion.TorsionalModel`
seen from the described shaft (every element reflected by (r_element / r_shaft)^2 there, by
:mod:`flyopt.machine.torsion`, the one place the reflection is decided). A shaft without a ``train``
has the two-inertia train of :func:`default_train`: the wheel, the shaft's own steps from its seat
to ``torque_at``, and the shaft's own ``inertia`` there - so the old two-inertia check is exactly a
special case of the chain. :func:`train_response` is the forced response at the mean speed to the
orders of the cycle's net torque, entering at the last inertia (the crank end), with modal damping
(docs/flywheel-design.md, section 26). :func:`seat_torque` is the one place the shaft's alternating
torque at the wheel seat is decided where the train is modelled: the forced response's torque there, its
orders synthesised in time (the fatigue check's T_m and T_a).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.machine.drive_train import TrainInertia, TrainSpring
from flyopt.machine.torsion import (
    Inertia,
    Spring,
    TorqueOrders,
    TorsionalModel,
    belt_stiffness,
    forced_response,
    modal_damping,
    modal_spring_torque_orders,
    shaft_compliance,
    shaft_stiffness,
)
from flyopt.machine.torsion import modes as torsion_modes
from flyopt.units import rpm_to_rad_s

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.machine.shaft_layout import ShaftLayout
    from flyopt.machine.torsion import Modes

__all__ = [
    "STEEL_POISSON",
    "TrainModel",
    "TrainResponse",
    "SeatTorque",
    "seat_torque",
    "KeyTorque",
    "key_torque",
    "shaft_train",
    "wheel_torque_orders",
    "default_train",
    "shear_modulus",
    "span_stiffness",
    "train_model",
    "train_response",
]

#: The tolerance of the extreme's bounded search, as a share of a sample step (:func:`_extreme`).
EXTREME_XATOL = 1e-4

#: Poisson's ratio of a steel when the material gives none (G = E / (2 (1 + nu))).
STEEL_POISSON = 0.3


def shear_modulus(material: Material) -> float:
    """G = E / (2 (1 + nu)) [Pa] of an isotropic material (nu of a steel, 0.3, when it gives none)."""
    nu = material.poisson_ratio if material.poisson_ratio is not None else STEEL_POISSON
    return float(material.elastic_modulus or 0.0) / (2.0 * (1.0 + nu))


def span_stiffness(layout: ShaftLayout, g: float, start: float, end: float) -> float:
    """k = 1 / sum l_i / k_i [N*m/rad] of the shaft's steps between ``start`` and ``end`` [m] (each step's piece
    in series, l_i / (G pi d_i^4 / 32), :func:`flyopt.machine.torsion.shaft_compliance`)."""
    low, high = sorted((start, end))
    if high - low <= 0.0:
        raise ValueError("a span of the shaft needs two different positions: no length of shaft twists between them")
    compliance, begin = 0.0, 0.0
    for step_end, d in zip(layout.steps, layout.diameters):
        overlap = min(step_end, high) - max(begin, low)
        if overlap > 0.0:
            compliance += shaft_compliance(g, overlap, d)
        begin = step_end
    return 1.0 / compliance


def default_train(layout: ShaftLayout, shaft: str, ratio: float, inertia: float) -> tuple[Any, ...]:
    """The two-inertia train of a shaft that gives no ``train``: the wheel, its steps from the seat to
    ``torque_at``, and the shaft's own ``inertia`` at ``torque_at``; empty when that inertia is 0 (no elastic mode)."""
    if not inertia > 0.0:
        return ()
    return (
        TrainInertia("flywheel", shaft, ratio, None),
        TrainSpring("shaft, seat to torque_at", "span", shaft, ratio, start=layout.wheel_at, end=layout.torque_at),
        TrainInertia("inertia at torque_at", shaft, ratio, inertia),
    )


@dataclass(frozen=True)
class TrainModel:
    """A train built for one wheel, seen from the described shaft.

    Attributes
    ----------
    model : TorsionalModel
    nodes : tuple of str
        Each node's name (the inertias turning together there, joined by " + ").
    springs : tuple of (str, str, float)
        Each elastic element's name, kind and stiffness on its own shaft [N*m/rad].
    wheel_node, load_node : int
        The wheel's node and the last one, where the cycle's net torque enters.
    wheel : Inertia or None
        The wheel's own inertia in the model (its J on its shaft and that shaft's ratio to the described one):
        what its key carries, J_wheel theta''_wheel (:func:`key_torque`); None where the train has no wheel.
    """

    model: TorsionalModel
    nodes: tuple[str, ...]
    springs: tuple[tuple[str, str, float], ...]
    wheel_node: int
    load_node: int
    wheel: Inertia | None = None


def train_model(
    train: tuple[Any, ...],
    layout: ShaftLayout,
    material: Material,
    *,
    wheel_inertia: float,
    speed_ratio: float = 1.0,
    materials: Mapping[str, Material] | None = None,
) -> TrainModel:
    """The train's model with a wheel of ``wheel_inertia`` [kg*m^2] at its place.

    ``speed_ratio`` is the described shaft's omega / omega_reference: each element's ratio is taken
    relative to it. ``material`` is the shaft's own (its spans, and pieces that name no other);
    ``materials`` resolves a piece's other material by name.
    """
    inertias: list[Inertia] = []
    springs: list[Spring] = []
    names: list[list[str]] = []
    spring_rows: list[tuple[str, str, float]] = []
    node, joined, wheel = -1, False, -1
    wheel_item: Inertia | None = None
    for element in train:
        if isinstance(element, TrainInertia):
            if not joined:
                node += 1
                names.append([])
            j = wheel_inertia if element.inertia is None else element.inertia
            if element.inertia is None:
                wheel = node
            inertias.append(Inertia(node, float(j), element.ratio / speed_ratio))
            if element.inertia is None:
                wheel_item = inertias[-1]
            names[node].append(element.name)
            joined = True  # a next inertia without a spring between turns with this one
            continue
        joined = False
        k = _stiffness(element, layout, material, materials)
        springs.append(Spring(node, node + 1, k, element.ratio / speed_ratio))
        spring_rows.append((element.name, element.kind, k))
    return TrainModel(
        TorsionalModel(inertias, springs),
        tuple(" + ".join(n) for n in names),
        tuple(spring_rows),
        wheel,
        node,
        wheel_item,
    )


def _stiffness(
    element: TrainSpring, layout: ShaftLayout, material: Material, materials: Mapping[str, Material] | None
) -> float:
    """k [N*m/rad] of an elastic element on its own shaft."""
    if element.kind == "stiffness":
        return element.stiffness
    if element.kind == "belt":
        return belt_stiffness(element.stiffness, element.radius)
    if element.kind == "span":
        return span_stiffness(layout, shear_modulus(material), element.start, element.end)
    if element.material in ("", layout.material):
        piece = material
    elif materials is not None and element.material in materials:
        piece = materials[element.material]
    else:
        raise ValueError(f"the shaft piece {element.name!r} is of {element.material!r}, which materials does not give")
    return shaft_stiffness(shear_modulus(piece), element.length, element.diameter)


@dataclass(frozen=True)
class TrainResponse:
    """The train's modes and its forced response at the mean speed (SI, the described shaft's coordinates).

    Attributes
    ----------
    built : TrainModel
    modes : Modes
    shapes : ndarray
        Each elastic mode's shape scaled to a largest |entry| of 1, [node, mode].
    orders : ndarray
        The orders of the excitation used (those present).
    speed_rpm : float
        The described shaft's mean speed [rpm].
    damping_ratio : float
    shaft_torques : ndarray
        |T_e,q| of each elastic element on its own shaft [N*m], [element, order].
    """

    built: TrainModel
    modes: Modes
    shapes: np.ndarray
    orders: np.ndarray
    speed_rpm: float
    damping_ratio: float
    shaft_torques: np.ndarray

    @property
    def torque_bound(self) -> np.ndarray:
        """sum_q |T_e,q| per element [N*m]: the alternating torque whatever the phases, at most."""
        return self.shaft_torques.sum(axis=1)

    def to_dict(self) -> dict[str, Any]:
        """The train for ``--json`` (SI)."""
        nodes = list(self.built.nodes)
        elements = []
        for e, (name, kind, k) in enumerate(self.built.springs):
            row = self.shaft_torques[e]
            top = int(np.argmax(row)) if row.size else -1
            elements.append(
                {
                    "name": name,
                    "kind": kind,
                    "torsional_stiffness": k,
                    "torque_alternating": float(self.torque_bound[e]),
                    "largest_order": float(self.orders[top]) if top >= 0 else None,
                    "torque_largest_order": float(row[top]) if top >= 0 else 0.0,
                }
            )
        return {
            "node_names": nodes,
            "wheel_node": self.built.wheel_node,
            "load_node": self.built.load_node,
            "modes": [
                {"natural_frequency": float(w), "mode_shape": [float(v) for v in self.shapes[:, m]]}
                for m, w in enumerate(self.modes.omega)
            ],
            "speed": rpm_to_rad_s(self.speed_rpm),
            "damping_ratio": self.damping_ratio,
            "orders": [float(q) for q in self.orders],
            "springs": elements,
        }


def train_response(
    built: TrainModel,
    modes: Modes,
    excitation: TorqueOrders,
    orders: np.ndarray,
    speed_rpm: float,
    damping_ratio: float,
) -> TrainResponse:
    """The forced response at ``speed_rpm`` of the described shaft to the ``orders`` of ``excitation`` (in its
    coordinates, per its revolution) entering at the last node, each elastic mode damped by ``damping_ratio``."""
    shapes = modes.shapes / np.max(np.abs(modes.shapes), axis=0, keepdims=True)
    keep = np.isin(excitation.orders, orders)
    present = TorqueOrders(excitation.mean, excitation.orders[keep], excitation.amplitudes[keep])
    if present.orders.size == 0:
        torques = np.zeros((len(built.springs), 0))
    else:
        c = modal_damping(built.model, damping_ratio)
        found = forced_response(built.model, present, built.load_node, speed_rpm, damping=c)
        torques = np.abs(found.shaft_torques)
    return TrainResponse(built, modes, shapes, present.orders, speed_rpm, damping_ratio, torques)


@dataclass(frozen=True)
class SeatTorque:
    """The torque the shaft carries from the wheel's seat toward the crank, by the forced response (SI).

    Attributes
    ----------
    curve : ndarray
        T(theta) over one cycle, equally spaced [N*m], the sign of the rigid-body torque the wheel exchanges.
    mean, alternating : float
        Its midrange (T_max + T_min)/2 and half range (T_max - T_min)/2 [N*m].
    element : str
        The train's elastic element it is the torque of (the first after the wheel, toward the crank).
    speed_rpm, damping_ratio : float
        The shaft's speed the orders are taken at [rpm] and the modal damping ratio.
    """

    curve: np.ndarray
    mean: float
    alternating: float
    element: str
    speed_rpm: float
    damping_ratio: float


def seat_torque(
    built: TrainModel,
    excitation: TorqueOrders,
    speed_rpm: float,
    damping_ratio: float,
    found: Modes | None = None,
) -> SeatTorque | None:
    """The torque at the wheel's seat by the forced response at ``speed_rpm``, every order synthesised in time.

    The cycle's net torque (``excitation``, per revolution of the described shaft) enters at the last node;
    the seat's torque is the twisting torque of the first elastic element after the wheel (toward the
    crank, where that torque enters): on a shaft with no ``train`` the span from the seat to ``torque_at``.
    Every order of the excitation is kept (the rigid-body T_a reads the whole curve, so dropping the small
    ones could only lower it), each damped by the modal ``damping_ratio``, and the orders are superposed
    with their phases over one cycle (an inverse FFT on 4096 or more points); T_m and T_a are that curve's midrange and half range
    (Shigley's definitions, docs/flywheel-design.md, section 26, for the reason over a sum of amplitudes).
    The mean torque enters quasi-statically: the share J_wheel side / J_total of the excitation's mean. As
    Omega -> 0 each order's torque tends to the rigid-body share of the SECTION, sum J[: wheel + 1] / J (every
    inertia on the wheel's side, the motor and pulleys upstream included: the torque that accelerates them all),
    not the wheel's J_F/J (its key's, :func:`key_torque`). So for a smooth load a stiff train gives that share of
    the net torque. A discontinuous load (a punch's torque step) is resolved only up to the highest order: where
    a mode lies below it, the orders above roll off and the step rings the mode (each extreme beyond its level by
    up to the step's jump, dynamic load factor 2 undamped); where the response is quasi-static up to the
    truncation (a stiff train), the truncated series overshoots each jump by Gibbs' 8.95 % of it, which flyopt
    keeps (on the safe side; docs/flywheel-design.md, section 26). None where no elastic element follows the wheel (the wheel at the crank
    end) or the orders are not the harmonics of one cycle. ``found``: the train's modes, when the caller
    has them (:func:`flyopt.machine.torsion.modal_spring_torque_orders` superposes them).
    """
    wheel = built.wheel_node
    model = built.model
    after = [e for e, spring in enumerate(model.springs) if spring.a == wheel and spring.b == wheel + 1]
    k = _harmonics(excitation)
    if not after or k is None:
        return None
    e = after[0]
    spring = model.springs[e]
    # the spring's torque on its own shaft, on the described shaft (x ratio), with the rigid body's sign
    # (the spring holds the wheel side back: k (x_a - x_b) = -J_side alpha)
    torques = modal_spring_torque_orders(model, excitation, built.load_node, speed_rpm, e, damping_ratio, found=found)
    amplitudes = -torques * spring.ratio
    inertia = np.diag(model.mass_matrix)
    share = float(inertia[: wheel + 1].sum() / inertia.sum())
    t_mean = share * excitation.mean
    curve, t_max, t_min = _synthesised(amplitudes, k, t_mean)
    return SeatTorque(
        curve,
        0.5 * (t_max + t_min),
        0.5 * (t_max - t_min),
        built.springs[e][0],
        float(speed_rpm),
        float(damping_ratio),
    )


def wheel_torque_orders(
    built: TrainModel,
    excitation: TorqueOrders,
    speed_rpm: float,
    damping_ratio: float,
    found: Modes | None = None,
) -> np.ndarray:
    """The complex torque J_wheel theta''_wheel the wheel's key carries, per order of ``excitation`` [N*m], on
    the wheel's shaft (docs/flywheel-design.md, section 26).

    The wheel node's own equation of motion: the key drives the wheel alone (not the other inertias turning
    with it at its node), so it carries J_w theta''_w = -J_w (q Omega)^2 Theta_w,q of each order. Theta_w,q by
    modal superposition with the modal ``damping_ratio`` (the steady state of
    :func:`flyopt.machine.torsion.forced_response` with :func:`flyopt.machine.torsion.modal_damping`), the
    rigid-body mode included:

        -Omega^2 Theta_w,q = c_q [phi0_w phi0_L + sum_m -Omega^2 phi_w,m phi_L,m / (omega_m^2 - Omega^2 + 2 i zeta omega_m Omega)]

    (L the load node where the net torque enters). As Omega -> 0 it tends to the rigid body's J_w / J c_q (the
    torque the design sized the key for); near a mode it is amplified like the seat's torque.
    """
    wheel = built.wheel
    if wheel is None:
        raise ValueError("the train has no wheel: its key carries no torque")
    found = torsion_modes(built.model) if found is None else found
    node, load = built.wheel_node, built.load_node
    omega = np.asarray(excitation.orders, dtype=float) * 2.0 * math.pi * speed_rpm / 60.0
    w = found.omega
    rigid = float((found.rigid_shapes[node] * found.rigid_shapes[load]).sum())
    gain = found.shapes[node] * found.shapes[load]
    denominator = w[None, :] ** 2 - omega[:, None] ** 2 + 2j * damping_ratio * w[None, :] * omega[:, None]
    if np.any(denominator == 0.0):
        raise ValueError("an order meets a natural frequency of the undamped system: add damping")
    accel = rigid - omega**2 * (gain[None, :] / denominator).sum(axis=1)  # -Omega^2 Theta_w / c_q
    # the torque on the wheel's own shaft: J theta''_own = J r theta''_node (r its ratio to the described shaft)
    torques: np.ndarray = wheel.inertia * wheel.ratio * np.asarray(excitation.amplitudes, dtype=complex) * accel
    return torques


@dataclass(frozen=True)
class KeyTorque:
    """The torque the wheel's key carries by the forced response, J_wheel theta''_wheel (SI).

    Attributes
    ----------
    curve : ndarray
        Over one cycle, equally spaced [N*m].
    peak : float
        max |T| over the cycle [N*m] (the extremes refined between samples, :func:`_extreme`).
    speed_rpm, damping_ratio : float
    """

    curve: np.ndarray
    peak: float
    speed_rpm: float
    damping_ratio: float


def key_torque(
    built: TrainModel,
    excitation: TorqueOrders,
    speed_rpm: float,
    damping_ratio: float,
    found: Modes | None = None,
) -> KeyTorque | None:
    """The key's torque J_wheel theta''_wheel by the forced response at ``speed_rpm``, every order synthesised
    in time as :func:`seat_torque` does (:func:`_synthesised`), and its peak |T|. The mean net torque enters
    quasi-statically, the rigid body's share J_w / J of it (nil over a balanced cycle). None where the train has
    no wheel, no elastic element follows the wheel toward the crank (the wheel at the crank end: the seat's torque
    is then the rigid body's, :func:`seat_torque` gives none), or the orders are not the harmonics of one cycle.

    The one torque a wheel's key is designed at (:func:`flyopt.design.shaft.cycle.key_torque_on`, the design's hub
    length and key check) and checked at (the post-check's limit "key"), docs/flywheel-design.md, section 26;
    where it gives None both use the rigid body's peak torque.
    """
    k = _harmonics(excitation)
    if k is None or built.wheel is None:
        return None
    wheel_node = built.wheel_node
    if not any(spring.a == wheel_node and spring.b == wheel_node + 1 for spring in built.model.springs):
        return None
    amplitudes = wheel_torque_orders(built, excitation, speed_rpm, damping_ratio, found)
    inertia = np.diag(built.model.mass_matrix)
    wheel = built.wheel
    mean = wheel.inertia * wheel.ratio * float(excitation.mean) / float(inertia.sum())
    curve, t_max, t_min = _synthesised(amplitudes, k, mean)
    return KeyTorque(curve, max(abs(t_max), abs(t_min)), float(speed_rpm), float(damping_ratio))


def shaft_train(
    layout: ShaftLayout,
    material: Material,
    *,
    wheel_inertia: float,
    speed_ratio: float = 1.0,
    other_inertia: float = 0.0,
    materials: Mapping[str, Material] | None = None,
) -> TrainModel | None:
    """The train of a described shaft with a wheel of ``wheel_inertia`` [kg*m^2] at its place: the layout's own
    ``train``, else the two-inertia one ``other_inertia`` makes (:func:`default_train`); None where there is none
    (no train and no inertia on the shaft: no elastic mode). The one way the post-check
    (:func:`flyopt.design.shaft.check.check_shaft`) and the design (:func:`key_torque`) build it."""
    train = layout.train or default_train(layout, "", speed_ratio, other_inertia)
    if not train:
        return None
    return train_model(
        train, layout, material, wheel_inertia=wheel_inertia, speed_ratio=speed_ratio, materials=materials
    )


def _harmonics(excitation: TorqueOrders) -> np.ndarray | None:
    """The excitation's orders as integer harmonics k of one cycle (orders / orders[0]), increasing; None where
    they are not the harmonics of one cycle (or there are none)."""
    orders = np.asarray(excitation.orders, dtype=float)
    if orders.size == 0:
        return None
    harmonic = orders / orders[0]
    k = np.rint(harmonic).astype(int)
    if np.any(np.abs(harmonic - k) > 1e-9) or np.any(np.diff(k) <= 0):
        return None
    return k


def _synthesised(amplitudes: np.ndarray, k: np.ndarray, mean: float) -> tuple[np.ndarray, float, float]:
    """(curve, T_max, T_min) of mean + sum_k Re(A_k e^{i k t}) over one cycle: the orders superposed with their
    phases by an inverse FFT on 4096 or more points, its extremes refined by :func:`_extreme`. The one synthesis
    of the seat's torque (:func:`seat_torque`) and the key's (:func:`key_torque`)."""
    n = max(4096, 1 << int(8 * k[-1]).bit_length())  # a power of two, 8+ points a period of the highest order
    spectrum = np.zeros(n // 2 + 1, dtype=complex)
    spectrum[k] = amplitudes * (n / 2.0)
    curve = mean + np.fft.irfft(spectrum, n)
    t_max, t_min = _extreme(amplitudes, k, curve, 1.0), _extreme(amplitudes, k, curve, -1.0)
    return curve, mean + t_max, mean + t_min


def _extreme(amplitudes: np.ndarray, harmonics: np.ndarray, curve: np.ndarray, sign: float) -> float:
    """The largest (``sign`` 1) or smallest (-1) value of sum_k Re(A_k e^{i k t}) over a period: the sampled
    extreme of ``curve`` (its samples, the mean included) refined between its neighbours by a bounded search on
    the series summed directly (the samples alone miss a ringing peak by up to 1 - cos(pi / points a period)).

    The search stops within :data:`EXTREME_XATOL` of a sample step in t (Brent's test adds sqrt(eps) |t|, up to
    1e-7 rad, which it cannot go below): with 8 or more samples a period of the highest order, the phase of any
    order is then off by at most 2 pi 1e-4 / 8, and the extreme's value by (8e-5)^2 / 2 = 3e-9 of its amplitude.
    """
    from flyopt.cycle.minimize import bounded_minimum

    n = curve.size
    j = int(np.argmax(sign * curve))
    step = 2.0 * math.pi / n

    def minus(t: float) -> float:
        return -sign * float(np.real(np.exp(1j * harmonics * t) @ amplitudes))

    sampled = minus(j * step)
    found = bounded_minimum(minus, (j - 1) * step, (j + 1) * step, xatol=EXTREME_XATOL * step)
    if not found.converged or not math.isfinite(found.fun):
        return -sign * sampled  # the search did not converge: the sample stands (it is a value of the series)
    return -sign * min(found.fun, sampled)
