"""Torsional vibration of a drive train (docs/flywheel-design.md, last section; issue 30, item 4).

A lumped model: inertias J_i [kg*m^2] at nodes, joined by shaft (or coupling)
stiffnesses k_e [N*m/rad], with optional viscous dampers. Gear and belt stages
are rigid and reflected to the reference shaft by their speed ratios
r = omega_member / omega_reference (same kinetic and potential energy):

    J_ref = J r^2,    k_ref = k r^2,    c_ref = c r^2,
    an applied torque T on a shaft of ratio r acts as T r on the reference,
    a reflected shaft torque T_ref is T_ref / r on the shaft itself.

The nodes and springs form any connected graph: a chain, or a branched tree
(a belt driving two shafts). Free vibration is the generalized symmetric
eigenproblem

    K phi = omega^2 M phi,    phi^T M phi = I   (mass-normalised),

solved by :func:`scipy.linalg.eigh`. A system with no spring to ground has one
rigid-body mode (the train turning as a whole): it is reported as 0 Hz and
kept apart from the elastic modes.

The forced steady state to the harmonic T e^{i Omega t} is

    (K - Omega^2 M + i Omega C) x = T,    twisting torque of spring e: (k_e + i Omega c_e)(x_a - x_b),

with C from the dampers, from Rayleigh's C = alpha M + beta K, or from modal
damping ratios zeta_m: C = M Phi diag(2 zeta_m omega_m) Phi^T M. A periodic
torque over a cycle is split into its orders q (harmonics per revolution of
the shaft it acts on) by :func:`torque_orders`; the order q of a shaft
turning at n [rpm] meets mode m at the critical speed n = 60 f_m / q.

References
----------
W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1,
Chapman & Hall, 1956 (lumped chains, orders and critical speeds).
M. I. Friswell et al., *Dynamics of Rotating Machines*, Cambridge University
Press, 2010, chapter 9 (torsional models, geared systems).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from flyopt.machine.transmission import reflected

# scipy.linalg is imported where a mode or a response is solved: a scene without a torsional chain
# (a report, a solve) never pays for its import (about 0.2 s)

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Inertia:
    """An inertia at a node of the model.

    Parameters
    ----------
    node : int
        The node it sits at (0, 1, ...); several inertias may share a node (the
        two wheels of a gear mesh or a belt, which turn together once reflected).
    inertia : float
        Its moment of inertia about its own axis [kg*m^2], > 0.
    ratio : float
        Speed ratio omega / omega_reference of the shaft it turns on, != 0 (1 on the reference shaft).
    damping : float
        An absolute viscous damper to the frame on it [N*m*s/rad], >= 0.
    """

    node: int
    inertia: float
    ratio: float = 1.0
    damping: float = 0.0


@dataclass(frozen=True)
class Spring:
    """A shaft or coupling joining two nodes (or a node and the frame).

    Parameters
    ----------
    a, b : int, int or None
        The nodes it joins; ``b`` None clamps ``a`` to the frame.
    stiffness : float
        Its torsional stiffness [N*m/rad], > 0.
    ratio : float
        Speed ratio omega / omega_reference of the shaft it is, != 0.
    damping : float
        Its internal viscous damping [N*m*s/rad], >= 0.
    """

    a: int
    b: int | None
    stiffness: float
    ratio: float = 1.0
    damping: float = 0.0


def _positive(name: str, values: Sequence[float] | np.ndarray) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim != 1:
        raise ValueError(f"{name} must be a one-dimensional sequence of numbers, got shape {array.shape}")
    bad = ~(np.isfinite(array) & (array > 0.0))
    if bad.any():
        index = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{name}[{index}] = {float(array[index])!r} must be a finite number > 0")
    return array


class TorsionalModel:
    """A lumped torsional model reflected to the reference shaft.

    Parameters
    ----------
    inertias : sequence of Inertia
        Every node 0..n-1 must carry at least one.
    springs : sequence of Spring
        The shafts and couplings; with the nodes they must form one connected system.

    Raises
    ------
    ValueError
        A non-positive or non-finite inertia or stiffness, a negative damping, a zero
        ratio, a spring to an unknown node or to its own node, a node with no inertia,
        or a system in more than one piece.
    """

    def __init__(self, inertias: Sequence[Inertia], springs: Sequence[Spring]) -> None:
        if not inertias:
            raise ValueError("a torsional model needs at least one inertia")
        self.inertias = tuple(inertias)
        self.springs = tuple(springs)
        nodes = [i.node for i in self.inertias]
        if any(isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 for n in nodes):
            raise ValueError(f"inertia nodes must be integers >= 0, got {nodes}")
        n = max(nodes) + 1
        missing = sorted(set(range(n)) - set(nodes))
        if missing:
            raise ValueError(f"node(s) {missing} carry no inertia: number the nodes 0..{n - 1} without gaps")
        for index, item in enumerate(self.inertias):
            _check_number(f"inertias[{index}].inertia", item.inertia, positive=True)
            _check_number(f"inertias[{index}].damping", item.damping, positive=False)
            _check_ratio(f"inertias[{index}].ratio", item.ratio)
        for index, spring in enumerate(self.springs):
            _check_number(f"springs[{index}].stiffness", spring.stiffness, positive=True)
            _check_number(f"springs[{index}].damping", spring.damping, positive=False)
            _check_ratio(f"springs[{index}].ratio", spring.ratio)
            ends = (spring.a,) if spring.b is None else (spring.a, spring.b)
            for end in ends:
                if isinstance(end, bool) or not isinstance(end, (int, np.integer)) or not 0 <= end < n:
                    raise ValueError(f"springs[{index}] joins node {end!r}, which is not one of 0..{n - 1}")
            if spring.a == spring.b:
                raise ValueError(f"springs[{index}] joins node {spring.a} to itself")
        self.size = n
        self._check_connected()
        self.grounded = any(spring.b is None for spring in self.springs)

    def _check_connected(self) -> None:
        parent = list(range(self.size))

        def root(i: int) -> int:
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for spring in self.springs:
            if spring.b is not None:
                parent[root(spring.a)] = root(spring.b)
        pieces = {root(i) for i in range(self.size)}
        if len(pieces) > 1:
            raise ValueError(
                f"the springs leave the model in {len(pieces)} separate pieces: join every node to the train"
            )

    @property
    def mass_matrix(self) -> np.ndarray:
        """M: the reflected inertias J r^2 on the diagonal [kg*m^2]."""
        m = np.zeros((self.size, self.size))
        for item in self.inertias:
            m[item.node, item.node] += reflected(item.inertia, item.ratio)
        return m

    @property
    def stiffness_matrix(self) -> np.ndarray:
        """K: the reflected stiffnesses k r^2 assembled over the springs [N*m/rad]."""
        return self._assemble([reflected(s.stiffness, s.ratio) for s in self.springs])

    @property
    def damping_matrix(self) -> np.ndarray:
        """C of the dampers: absolute ones c r^2 on the diagonal, spring ones c r^2 assembled [N*m*s/rad]."""
        c = self._assemble([reflected(s.damping, s.ratio) for s in self.springs])
        for item in self.inertias:
            c[item.node, item.node] += reflected(item.damping, item.ratio)
        return c

    def _assemble(self, values: Sequence[float]) -> np.ndarray:
        matrix = np.zeros((self.size, self.size))
        for spring, value in zip(self.springs, values, strict=True):
            matrix[spring.a, spring.a] += value
            if spring.b is not None:
                matrix[spring.b, spring.b] += value
                matrix[spring.a, spring.b] -= value
                matrix[spring.b, spring.a] -= value
        return matrix


def chain(
    inertias: Sequence[float] | np.ndarray,
    stiffnesses: Sequence[float] | np.ndarray,
    *,
    ratios: Sequence[float] | np.ndarray | None = None,
    absolute_damping: Sequence[float] | np.ndarray | None = None,
    shaft_damping: Sequence[float] | np.ndarray | None = None,
) -> TorsionalModel:
    """A free chain J_0 - k_0 - J_1 - k_1 - ... - J_{n-1}, all on one shaft unless ``ratios`` says otherwise.

    Parameters
    ----------
    inertias : sequence of float
        J_i [kg*m^2], n of them, each > 0.
    stiffnesses : sequence of float
        k_i [N*m/rad] of the shaft between node i and i+1, n - 1 of them, each > 0.
    ratios : sequence of float, optional
        The speed ratio of each node's shaft (n of them); the shaft between two nodes of
        different ratios is not allowed (put the gear stage inside a node: two wheels at one node).
    absolute_damping, shaft_damping : sequence of float, optional
        Dampers to the frame at each node (n) and in each shaft (n - 1) [N*m*s/rad].

    Raises
    ------
    ValueError
        Non-positive values or lengths that do not match.
    """
    j = _positive("inertias", inertias)
    if j.size == 0:
        raise ValueError("a torsional model needs at least one inertia")
    k = _positive("stiffnesses", stiffnesses)
    if len(k) != len(j) - 1:
        raise ValueError(f"a chain of {len(j)} inertias needs {len(j) - 1} stiffnesses, got {len(k)}")
    r = np.ones(len(j)) if ratios is None else np.asarray(ratios, dtype=float)
    c_abs = np.zeros(len(j)) if absolute_damping is None else np.asarray(absolute_damping, dtype=float)
    c_shaft = np.zeros(len(k)) if shaft_damping is None else np.asarray(shaft_damping, dtype=float)
    for name, values, expected in (
        ("ratios", r, len(j)),
        ("absolute_damping", c_abs, len(j)),
        ("shaft_damping", c_shaft, len(k)),
    ):
        if values.shape != (expected,):
            raise ValueError(f"{name} needs {expected} values (one per {'node' if expected == len(j) else 'shaft'})")
    for e in range(len(k)):
        if r[e] != r[e + 1]:
            raise ValueError(
                f"the shaft between nodes {e} and {e + 1} joins ratios {r[e]} and {r[e + 1]}: "
                "a gear or belt stage is rigid, build it with TorsionalModel (both wheels at one node)"
            )
    return TorsionalModel(
        [Inertia(i, float(j[i]), float(r[i]), float(c_abs[i])) for i in range(len(j))],
        [Spring(e, e + 1, float(k[e]), float(r[e]), float(c_shaft[e])) for e in range(len(k))],
    )


def shaft_compliance(shear_modulus: float, length: float, diameter: float) -> float:
    """1/k = l / (G J_p) = l / (G pi d^4 / 32) [rad/(N*m)] of a solid round shaft piece (Roark's Formulas for
    Stress and Strain, 7th ed., Table 10.1, case 1: theta = T l / (K G) with K = pi d^4 / 32 for a solid
    circle); pieces in series add their compliances."""
    for name, value in (("shear_modulus", shear_modulus), ("length", length), ("diameter", diameter)):
        _check_number(name, value, positive=True)
    return length / (shear_modulus * math.pi * diameter**4 / 32.0)


def shaft_stiffness(shear_modulus: float, length: float, diameter: float) -> float:
    """k = G pi d^4 / (32 l) [N*m/rad] of a solid round shaft piece: 1 / :func:`shaft_compliance`."""
    return 1.0 / shaft_compliance(shear_modulus, length, diameter)


def belt_stiffness(span_stiffness: float, radius: float) -> float:
    """k = 2 k_b r^2 [N*m/rad] of a belt drive on the shaft of the pulley of radius r [m].

    Both spans are pretensioned and stay taut: turning that pulley by theta against the other
    stretches one span by r theta and relieves the other by r theta, each span of stretch
    stiffness k_b [N/m] (E A / l of its belts in parallel), so the strain energy is
    2 (k_b (r theta)^2 / 2) and the torque 2 k_b r^2 theta. This is the discrete belt-drive model in
    which each span is an axial spring between the pulleys' rims (R. S. Beikmann, N. C. Perkins and
    A. G. Ulsoy, "Free vibration of serpentine belt drive systems", J. Vib. Acoust. 118 (1996)
    406-413), for two pulleys, the second one held. On the other pulley's shaft it is
    2 k_b r'^2 = k (r'/r)^2, the ratio-squared reflection of :func:`flyopt.machine.transmission.reflected`
    (r omega = r' omega': the belt speed).
    """
    _check_number("span_stiffness", span_stiffness, positive=True)
    _check_number("radius", radius, positive=True)
    return 2.0 * span_stiffness * radius**2


@dataclass(frozen=True)
class Modes:
    """The undamped modes of a torsional model.

    Attributes
    ----------
    omega : ndarray
        Elastic natural angular frequencies, ascending [rad/s].
    shapes : ndarray
        Mass-normalised elastic mode shapes in the reference coordinates, one column each
        (phi^T M phi = I), sign fixed so that each column's largest entry is positive.
    rigid_shapes : ndarray
        The rigid-body mode (0 Hz) of a free system, mass-normalised, one column; no column when grounded.
    """

    omega: np.ndarray
    shapes: np.ndarray
    rigid_shapes: np.ndarray

    @property
    def frequencies_hz(self) -> np.ndarray:
        """f_m = omega_m / 2 pi [Hz]."""
        return self.omega / TWO_PI

    @property
    def all_frequencies_hz(self) -> np.ndarray:
        """0 Hz for each rigid-body mode, then the elastic ones [Hz]."""
        return np.concatenate([np.zeros(self.rigid_shapes.shape[1]), self.frequencies_hz])


def modes(model: TorsionalModel) -> Modes:
    """The natural frequencies and mass-normalised mode shapes of ``model``.

    Solves K phi = omega^2 M phi by :func:`scipy.linalg.eigh`. A free system (no spring
    to the frame) has exactly one rigid-body mode: the lowest eigenpair, whose eigenvalue
    is round-off; it is kept apart as 0 Hz.

    Raises
    ------
    ValueError
        An elastic eigenvalue that is not positive (it cannot be for a valid model; it would
        mean the matrices are too ill-conditioned to trust).
    """
    m, k = model.mass_matrix, model.stiffness_matrix
    import scipy.linalg

    eigenvalues, vectors = scipy.linalg.eigh(k, m)
    rigid = 0 if model.grounded else 1
    elastic = eigenvalues[rigid:]
    if elastic.size and elastic[0] <= 0.0:
        raise ValueError(f"an elastic eigenvalue omega^2 = {elastic[0]:g} is not positive: ill-conditioned model")
    shapes = vectors[:, rigid:].copy()
    for column in range(shapes.shape[1]):
        if shapes[np.argmax(np.abs(shapes[:, column])), column] < 0.0:
            shapes[:, column] *= -1.0
    rigid_shapes = np.full((model.size, rigid), 1.0 / math.sqrt(np.trace(m)))
    return Modes(np.sqrt(elastic), shapes, rigid_shapes)


def rayleigh_damping(model: TorsionalModel, alpha: float, beta: float) -> np.ndarray:
    """C = alpha M + beta K [N*m*s/rad] (alpha [1/s], beta [s], both >= 0)."""
    _check_number("alpha", alpha, positive=False)
    _check_number("beta", beta, positive=False)
    return alpha * model.mass_matrix + beta * model.stiffness_matrix


def modal_damping(model: TorsionalModel, zeta: float | Sequence[float] | np.ndarray) -> np.ndarray:
    """C = M Phi diag(2 zeta_m omega_m) Phi^T M [N*m*s/rad]: each elastic mode m damped by its ratio zeta_m.

    ``zeta`` is one ratio for every elastic mode or one per elastic mode, each >= 0; the
    rigid-body mode stays undamped.
    """
    found = modes(model)
    z = np.asarray(zeta, dtype=float)
    if z.ndim == 0:
        z = np.full(found.omega.shape, float(z))
    elif z.shape != found.omega.shape:
        raise ValueError(f"zeta needs one ratio or {found.omega.size} (one per elastic mode), got {z.size}")
    if not np.all(np.isfinite(z) & (z >= 0.0)):
        raise ValueError(f"damping ratios must be finite and >= 0, got {z}")
    m = model.mass_matrix
    weighted = m @ found.shapes
    return weighted @ np.diag(2.0 * z * found.omega) @ weighted.T


def damped_eigenvalues(model: TorsionalModel, damping: np.ndarray | None = None) -> np.ndarray:
    """The eigenvalues lambda of M x'' + C x' + K x = 0 of the oscillating modes (Im > 0), by |lambda| [rad/s].

    |lambda| is the natural frequency and -Re(lambda)/|lambda| the damping ratio of
    each mode (for non-proportional C, |lambda| differs slightly from the undamped omega).
    The real eigenvalues are left out: the rigid-body mode (0, and -sum c / sum J when
    dampers hold it to the frame) and any overdamped mode. ``damping`` defaults to the
    model's dampers. LAPACK's real QZ returns real eigenvalues with an imaginary part of
    exactly 0, so the split is exact.
    """
    m, k = model.mass_matrix, model.stiffness_matrix
    c = model.damping_matrix if damping is None else _square(damping, model.size)
    n = model.size
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-k, -c]])
    b = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), m]])
    import scipy.linalg

    eigenvalues = scipy.linalg.eigvals(a, b)
    eigenvalues = eigenvalues[eigenvalues.imag > 0.0]
    return eigenvalues[np.argsort(np.abs(eigenvalues), kind="stable")]


@dataclass(frozen=True)
class TorqueOrders:
    """The Fourier series of a periodic torque by order: T(phi) = mean + sum_q Re(c_q e^{i q phi}).

    Attributes
    ----------
    mean : float
        The mean torque [N*m].
    orders : ndarray
        q, harmonics per revolution of the shaft (k / cycle_revolutions for k = 1, 2, ...).
    amplitudes : ndarray
        c_q, complex [N*m]: |c_q| the amplitude, arg c_q the phase.
    """

    mean: float
    orders: np.ndarray
    amplitudes: np.ndarray

    def torque(self, angle: np.ndarray | float) -> np.ndarray:
        """The series summed at shaft angles ``angle`` [rad] [N*m]."""
        phi = np.asarray(angle, dtype=float)
        return self.mean + np.real(np.exp(1j * np.multiply.outer(phi, self.orders)) @ self.amplitudes)


def torque_orders(
    angle: Sequence[float] | np.ndarray,
    torque: Sequence[float] | np.ndarray,
    *,
    cycle_revolutions: float = 1.0,
    max_order: float | None = None,
) -> TorqueOrders:
    """The orders of a periodic torque sampled over one cycle.

    Parameters
    ----------
    angle : sequence of float
        Equally spaced shaft angles [rad] over one cycle of 2 pi ``cycle_revolutions``,
        the last one either one step short of the cycle or its end (then its sample is
        dropped: it repeats the first).
    torque : sequence of float
        T at those angles [N*m] (e.g. flyopt's net torque M_d - M_r at the reference shaft).
    cycle_revolutions : float
        Shaft revolutions per cycle (2 for a four-stroke engine: half orders appear).
    max_order : float, optional
        Keep the orders up to this one; by default all that the sampling resolves.

    Notes
    -----
    With N samples T_j, c_k = (2/N) sum_j T_j e^{-2 pi i j k / N} (the discrete Fourier
    transform), exact for a torque whose orders stop below N / 2.
    """
    phi = np.asarray(angle, dtype=float)
    values = np.asarray(torque, dtype=float)
    if phi.ndim != 1 or phi.shape != values.shape:
        raise ValueError(f"angle and torque must be one-dimensional of one length, got {phi.shape} and {values.shape}")
    _check_number("cycle_revolutions", cycle_revolutions, positive=True)
    period = TWO_PI * cycle_revolutions
    if phi.size < 4 or not np.all(np.isfinite(phi)) or not np.all(np.isfinite(values)):
        raise ValueError("angle and torque need at least 4 finite samples")
    steps = np.diff(phi)
    step = steps.mean()
    if step <= 0.0 or np.max(np.abs(steps - step)) > 1e-9 * period:
        raise ValueError("angle must be equally spaced and increasing (resample the torque curve first)")
    span = phi[-1] - phi[0]
    if abs(span - period) <= 1e-9 * period:
        phi, values = phi[:-1], values[:-1]
    elif abs(span + step - period) > 1e-9 * period:
        raise ValueError(
            f"the samples span {span:.9g} rad: one cycle is {period:.9g} rad "
            "(cycle_revolutions turns), end one step short of it or on it"
        )
    n = values.size
    spectrum = np.fft.rfft(values) / n
    # phase relative to angle[0], so that T(phi) is the series at the given angles
    k = np.arange(spectrum.size)
    spectrum = spectrum * np.exp(-1j * k * TWO_PI * phi[0] / period)
    count = (n - 1) // 2  # the Nyquist term of an even N is not a resolved order
    orders = k[1 : count + 1] / cycle_revolutions
    amplitudes = 2.0 * spectrum[1 : count + 1]
    if max_order is not None:
        keep = orders <= max_order
        orders, amplitudes = orders[keep], amplitudes[keep]
    return TorqueOrders(float(spectrum[0].real), orders, amplitudes)


@dataclass(frozen=True)
class ForcedResponse:
    """The steady state of a torsional model to the orders of a torque at one speed.

    Attributes
    ----------
    orders : ndarray
        q of each harmonic.
    omega : ndarray
        Its angular frequency Omega_q [rad/s].
    angles : ndarray
        Complex angle amplitudes of each node, reference coordinates, [node, order] [rad].
    shaft_torques : ndarray
        Complex twisting torque amplitudes of each spring on its own shaft, [spring, order] [N*m].
    """

    orders: np.ndarray
    omega: np.ndarray
    angles: np.ndarray
    shaft_torques: np.ndarray

    @property
    def shaft_torque_bound(self) -> np.ndarray:
        """sum_q |T_e,q| per spring [N*m]: an upper bound of the alternating torque whatever the phases."""
        return np.abs(self.shaft_torques).sum(axis=1)


def harmonic_response(
    model: TorsionalModel,
    omega: float,
    torques: np.ndarray,
    damping: np.ndarray | None = None,
) -> np.ndarray:
    """Complex angle amplitudes x solving (K - Omega^2 M + i Omega C) x = T [rad, reference coordinates].

    ``torques`` are the reflected complex torque amplitudes at each node [N*m]; ``damping``
    defaults to the model's dampers.

    Raises
    ------
    ValueError
        A singular dynamic stiffness: an undamped system driven exactly at a natural frequency
        (or a free one at Omega = 0).
    """
    m, k = model.mass_matrix, model.stiffness_matrix
    c = model.damping_matrix if damping is None else _square(damping, model.size)
    t = np.asarray(torques, dtype=complex)
    if t.shape != (model.size,):
        raise ValueError(f"torques needs one amplitude per node ({model.size}), got shape {t.shape}")
    import scipy.linalg

    dynamic = k - omega**2 * m + 1j * omega * c
    with warnings.catch_warnings():
        # an exactly singular pivot is reported below, in a ValueError that says why
        warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
        lu = scipy.linalg.lu_factor(dynamic)
    diagonal = np.abs(np.diag(lu[0]))
    if diagonal.min() <= 1e-13 * diagonal.max():
        raise ValueError(f"Omega = {omega:g} rad/s is a natural frequency of the undamped system: add damping")
    return scipy.linalg.lu_solve(lu, t)


def shaft_torques(
    model: TorsionalModel, omega: float, angles: np.ndarray, damping: np.ndarray | None = None
) -> np.ndarray:
    """The complex twisting torque in each spring on its own shaft [N*m]: (k + i Omega c) r (x_a - x_b).

    Spring damping counts only when ``damping`` is None (the model's dampers are used); a
    Rayleigh or modal C has no element-by-element split, so the elastic torque k r (x_a - x_b) is given.
    """
    x = np.asarray(angles, dtype=complex)
    out = np.empty(len(model.springs), dtype=complex)
    for index, spring in enumerate(model.springs):
        twist = x[spring.a] - (0.0 if spring.b is None else x[spring.b])
        c = spring.damping if damping is None else 0.0
        out[index] = (spring.stiffness + 1j * omega * c) * spring.ratio * twist
    return out


def forced_response(
    model: TorsionalModel,
    excitation: TorqueOrders,
    node: int,
    speed_rpm: float,
    *,
    ratio: float = 1.0,
    damping: np.ndarray | None = None,
) -> ForcedResponse:
    """The response to the orders of a periodic torque at ``node``.

    Parameters
    ----------
    model : TorsionalModel
    excitation : TorqueOrders
        The torque's orders on the shaft it acts on (:func:`torque_orders`).
    node : int
        Where it acts.
    speed_rpm : float
        The speed n of the shaft it acts on [rpm], > 0: order q has Omega_q = q 2 pi n / 60.
    ratio : float
        Speed ratio of that shaft to the reference shaft (the torque reflects as T r, and the
        reference shaft turns at n / r).
    damping : ndarray, optional
        C [N*m*s/rad] (:func:`rayleigh_damping`, :func:`modal_damping`); the model's dampers by default.
    """
    if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or not 0 <= node < model.size:
        raise ValueError(f"node {node!r} is not one of 0..{model.size - 1}")
    _check_number("speed_rpm", speed_rpm, positive=True)
    _check_ratio("ratio", ratio)
    omega = excitation.orders * TWO_PI * speed_rpm / 60.0
    angles = np.empty((model.size, omega.size), dtype=complex)
    torques = np.empty((len(model.springs), omega.size), dtype=complex)
    for column, (frequency, amplitude) in enumerate(zip(omega, excitation.amplitudes, strict=True)):
        load = np.zeros(model.size, dtype=complex)
        load[node] = amplitude * ratio
        angles[:, column] = harmonic_response(model, float(frequency), load, damping)
        torques[:, column] = shaft_torques(model, float(frequency), angles[:, column], damping)
    return ForcedResponse(excitation.orders.copy(), omega, angles, torques)


def modal_spring_torque_orders(
    model: TorsionalModel,
    excitation: TorqueOrders,
    node: int,
    speed_rpm: float,
    spring: int,
    zeta: float,
    *,
    found: Modes | None = None,
) -> np.ndarray:
    """The complex twisting torque of one spring on its own shaft for every order, modal damping ζ [N*m].

    The steady state of :func:`forced_response` with C = :func:`modal_damping` (``model``, ζ), by modal
    superposition: with mass-normalised shapes phi_m the modal damping is diagonal, so

        T_q = c_q sum_m k r (phi_a,m - phi_b,m) phi_node,m / (omega_m^2 - Omega_q^2 + 2 i ζ omega_m Omega_q),

    exact (the rigid-body mode twists no spring), and a cycle's thousands of orders cost a product of two
    small arrays, where the shaft's fatigue check asks it for each design. ``found``: the model's modes,
    when the caller has them. An undamped system driven exactly at a natural frequency raises ValueError.
    """
    if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or not 0 <= node < model.size:
        raise ValueError(f"node {node!r} is not one of 0..{model.size - 1}")
    if not 0 <= spring < len(model.springs):
        raise ValueError(f"spring {spring!r} is not one of 0..{len(model.springs) - 1}")
    _check_number("speed_rpm", speed_rpm, positive=True)
    _check_number("zeta", zeta, positive=False)
    found = modes(model) if found is None else found
    chosen = model.springs[spring]
    twist = found.shapes[chosen.a] - (0.0 if chosen.b is None else found.shapes[chosen.b])
    gain = chosen.stiffness * chosen.ratio * twist * found.shapes[node]
    omega = np.asarray(excitation.orders, dtype=float) * TWO_PI * speed_rpm / 60.0
    w = found.omega
    denominator = w[None, :] ** 2 - omega[:, None] ** 2 + 2j * zeta * w[None, :] * omega[:, None]
    if np.any(denominator == 0.0):
        raise ValueError("an order meets a natural frequency of the undamped system: add damping")
    torques: np.ndarray = np.asarray(excitation.amplitudes, dtype=complex) * (gain[None, :] / denominator).sum(axis=1)
    return torques


@dataclass(frozen=True)
class CriticalSpeed:
    """Where order ``order`` of a shaft meets mode ``mode`` (1 = the first elastic mode).

    ``speed_rpm`` = 60 f / q; ``margin`` is its relative separation from the running range:
    (n_c - n_max)/n_max above it, (n_min - n_c)/n_min below it, 0 inside it (``in_range``).
    """

    mode: int
    order: float
    frequency_hz: float
    speed_rpm: float
    margin: float
    in_range: bool


def critical_speed(frequency_hz: float, order: float) -> float:
    """n_c = 60 f / q [rpm]: the shaft speed at which order q excites a mode of f [Hz]."""
    _check_number("frequency_hz", frequency_hz, positive=True)
    _check_number("order", order, positive=True)
    return 60.0 * frequency_hz / order


def critical_speeds(
    frequencies_hz: Sequence[float] | np.ndarray,
    orders: Sequence[float] | np.ndarray,
    speed_range_rpm: tuple[float, float],
) -> list[CriticalSpeed]:
    """Every (mode, order) critical speed with its margin against the running range [n_min, n_max] [rpm].

    ``frequencies_hz`` are the elastic modes' (rigid-body 0 Hz excluded); the list runs by mode, then order.
    """
    low, high = (float(v) for v in speed_range_rpm)
    _check_number("speed_range_rpm[0]", low, positive=True)
    if not high >= low:
        raise ValueError(f"speed_range_rpm must be (n_min, n_max) with n_max >= n_min, got {speed_range_rpm}")
    f = np.asarray(frequencies_hz, dtype=float).ravel()
    q = np.asarray(orders, dtype=float).ravel()
    if not (np.isfinite(f).all() and (f > 0.0).all() and np.isfinite(q).all() and (q > 0.0).all()):
        for frequency in f:  # the first bad entry, named as critical_speed names it
            for order in q:
                critical_speed(float(frequency), float(order))
    # n_c = 60 f / q (critical_speed) for every pair at once: the same operations on the same doubles
    speed = 60.0 * f[:, None] / q[None, :]
    above, below = speed > high, speed < low
    margin = np.where(above, (speed - high) / high, np.where(below, (low - speed) / low, 0.0))
    inside = ~(above | below)
    return [
        CriticalSpeed(
            mode + 1, float(q[k]), float(f[mode]), float(speed[mode, k]), float(margin[mode, k]), bool(inside[mode, k])
        )
        for mode in range(f.size)
        for k in range(q.size)
    ]


def _check_number(name: str, value: float, *, positive: bool) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a number, got {value!r}")
    if not math.isfinite(value) or (value <= 0.0 if positive else value < 0.0):
        raise ValueError(f"{name} = {float(value)!r} must be a finite number {'> 0' if positive else '>= 0'}")


def _check_ratio(name: str, value: float) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a number, got {value!r}")
    if not math.isfinite(value) or value == 0.0:
        raise ValueError(f"{name} = {float(value)!r} must be a finite, non-zero speed ratio")


def _square(matrix: np.ndarray, size: int) -> np.ndarray:
    array = np.asarray(matrix, dtype=float)
    if array.shape != (size, size):
        raise ValueError(f"a damping matrix must be {size} x {size}, got shape {array.shape}")
    return array
