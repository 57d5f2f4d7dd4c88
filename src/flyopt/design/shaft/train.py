"""The drive train of a described shaft as a lumped torsional model, and its forced response (issue 30, item 4).

:func:`train_model` builds the scene's train (:mod:`flyopt.machine.drive_train`, from the motor to
the crank) with the designed wheel at its place into a :class:`flyopt.machine.torsion.TorsionalModel`
seen from the described shaft (every element reflected by (r_element / r_shaft)^2 there, by
:mod:`flyopt.machine.torsion`, the one place the reflection is decided). A shaft without a ``train``
has the two-inertia train of :func:`default_train`: the wheel, the shaft's own steps from its seat
to ``torque_at``, and the shaft's own ``inertia`` there - so the old two-inertia check is exactly a
special case of the chain. :func:`train_response` is the forced response at the mean speed to the
orders of the cycle's net torque, entering at the last inertia (the crank end), with modal damping
(docs/flywheel-design.md, section 26).
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
    shaft_compliance,
    shaft_stiffness,
)

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.machine.shaft_layout import ShaftLayout
    from flyopt.machine.torsion import Modes

__all__ = [
    "STEEL_POISSON",
    "TrainModel",
    "TrainResponse",
    "default_train",
    "shear_modulus",
    "span_stiffness",
    "train_model",
    "train_response",
]

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
    """

    model: TorsionalModel
    nodes: tuple[str, ...]
    springs: tuple[tuple[str, str, float], ...]
    wheel_node: int
    load_node: int


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
    for element in train:
        if isinstance(element, TrainInertia):
            if not joined:
                node += 1
                names.append([])
            j = wheel_inertia if element.inertia is None else element.inertia
            if element.inertia is None:
                wheel = node
            inertias.append(Inertia(node, float(j), element.ratio / speed_ratio))
            names[node].append(element.name)
            joined = True  # a next inertia without a spring between turns with this one
            continue
        joined = False
        k = _stiffness(element, layout, material, materials)
        springs.append(Spring(node, node + 1, k, element.ratio / speed_ratio))
        spring_rows.append((element.name, element.kind, k))
    return TrainModel(
        TorsionalModel(inertias, springs), tuple(" + ".join(n) for n in names), tuple(spring_rows), wheel, node
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
            "speed": self.speed_rpm * math.pi / 30.0,
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
