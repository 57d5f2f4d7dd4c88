"""A second stress opinion: the wheel as an axisymmetric linear-elastic body of revolution, by finite elements.

flyopt's stresses come from one model (plane-stress Lamé discs joined at
steps, :mod:`flyopt.design.stress`, and the texts' arm formulas). That model
has no junctions: a step in thickness is a jump in a one-dimensional stress
field, where a real wheel concentrates stress in the fillet. This module
meshes the wheel's axial section (the half above its mid-plane) and solves
the axisymmetric elasticity problem under the centrifugal load rho omega^2 r,
then reports each part's peak von Mises and largest principal stress, where
they are, and the concentration factor at each junction: the FE peak near the
junction over the Lamé step model's stress there.

The model
---------
* Unknowns u_r(r, z), u_z(r, z); strains eps_rr = du_r/dr, eps_tt = u_r/r
  (the hoop strain), eps_zz = du_z/dz, gamma_rz = du_r/dz + du_z/dr;
  isotropic Hooke's law in three dimensions (lambda, mu from E, nu).
* Weak form with the r-weighted integrals (the 2 pi cancels):
  integral of eps(v) : sigma(u) r dA = integral of rho omega^2 r v_r r dA.
* Boundary conditions: u_z = 0 on the mid-plane z = 0 (symmetry), u_r = 0 on
  the axis r = 0 of a solid wheel; every other face is free.
* Quadratic triangles (P2, six nodes) on a Delaunay triangulation of a graded
  point set: a tensor grid in (r, z) through every step's radius and
  half-thickness, dense near each junction, the bore and the fillets, coarse
  far from them (:func:`section_mesh`). Stresses are evaluated at each
  triangle's six nodes from its own displacement field (not averaged), so
  that a peak on a free edge (the bore, a fillet) is seen where it is.
* Stresses do not depend on E (a body loaded by its own inertia, with no
  imposed displacement); E is used only to scale the displacements.

Fillets. A design carries no fillet radius; at a re-entrant corner (a thick
part meeting a thinner one) the elastic stress is singular, and a FE "peak"
there would only measure the mesh. Every such corner is rounded with the
fillet the manufacturing drawing gives it
(:func:`flyopt.design.castability.fillet_radius`: :data:`DEFAULT_FILLET_RATIO`
x the thinner section's thickness, at least the process's smallest fillet,
limited by the room; the numbers and their sources in
``flyopt/data/castability.toml``), unless the caller gives one; the check says
which it used. The factor depends on it (roughly 1 + c sqrt(t / r_f)).

Arms. A ``rim_arms`` wheel is not a body of revolution: its arms are treated
as an equivalent axisymmetric web of the same mass, t = n A / (pi (r_h + r_i)),
and said so. The equivalent web carries hoop stress that real arms cannot,
so for an arms wheel the FE check is of the web wheel of equal mass; the
texts' arm and rim-bending model stays the one the design is judged by.

The closed forms first (tests/design/test_fem.py): a thin steel disc
(rho = 7850 kg/m^3, nu = 0.3, R = 0.5 m, 3000 rpm, 2 mm thick) gives 79.90 MPa
at the centre solid, 160.13 MPa hoop at a 0.05 m bore and 64.72 MPa radial
maximum, to 1e-3, converging as the mesh is refined.

scikit-fem is a dependency of flyopt (pure Python on numpy and scipy), imported
here only when a check runs.

References
----------
.. [1] S. Timoshenko and J. N. Goodier, Theory of Elasticity, 3rd ed.,
   art. 32 (rotating discs) and chapter 14 (axisymmetric bodies).
.. [2] O. C. Zienkiewicz and R. L. Taylor, The Finite Element Method, vol. 1,
   chapter on axisymmetric stress analysis.
.. [3] T. Gustafsson and G. D. McBain, scikit-fem: A Python package for
   finite element assembly, JOSS 5(52), 2369 (2020).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from flyopt.design import castability, stress, wheel
from flyopt.names import Geometry
from flyopt.said import said

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.design.result import Design, DesignResult
    from flyopt.design.spec import StressFactor

__all__ = [
    "DEFAULT_FILLET_RATIO",
    "MESH_SIZES",
    "Section",
    "FemField",
    "PartPeak",
    "JunctionFactor",
    "FemCheck",
    "section",
    "section_mesh",
    "solve_section",
    "stiffness_matrix",
    "strains",
    "hooke",
    "fem_check",
    "check_result",
    "accept",
    "judged_parts",
    "MAX_ACCEPT_ROUNDS",
]

#: Default fillet radius at a re-entrant junction, over the thinner section's (full) thickness: the drawing's
#: (castability.toml, [fillet]; :func:`flyopt.design.castability.fillet_radius` is the rule).
DEFAULT_FILLET_RATIO = castability.FILLET_RATIO

#: Named mesh sizes: the factor on every element size (smaller: finer).
MESH_SIZES = {"coarse": 1.0, "normal": 0.5, "fine": 0.25, "finer": 0.125}

#: Growth of the element size away from a point of refinement, per unit distance [-].
GROWTH = 0.25

#: Two steps whose thicknesses differ by less than this, relatively, are one section (no corner, no fillet):
#: the NLP's solution of an equal-thickness web and rim differs in the eighth digit.
SAME_THICKNESS = castability.SAME_THICKNESS

#: The junction zone: points within this many (fillet radius + thinner thickness) of the corner.
ZONE = 1.5


def _skfem():
    """scikit-fem, or an ImportError naming the extra."""
    try:
        import skfem  # type: ignore[import-untyped]  # scikit-fem ships no stubs
    except ImportError as err:
        raise ImportError("the FEM check needs scikit-fem, a dependency of flyopt: pip install scikit-fem") from err
    return skfem


@dataclass(frozen=True)
class Section:
    """The axial section of a wheel as steps of constant thickness, symmetric about its mid-plane (SI).

    Attributes
    ----------
    radii : tuple of float
        Edge radii r_0 < ... < r_N [m] (r_0 = 0: a solid centre).
    thicknesses : tuple of float
        Full axial thickness of each step [m].
    names : tuple of str
        The part each step belongs to.
    fillets : tuple of float
        Fillet radius at each inner edge r_1 .. r_{N-1} [m] (0 where the two steps are as thick).
    notes : tuple of str
        How the section was made (equivalent web, default fillets).
    """

    radii: tuple[float, ...]
    thicknesses: tuple[float, ...]
    names: tuple[str, ...]
    fillets: tuple[float, ...] = ()
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if len(self.radii) != len(self.thicknesses) + 1 or len(self.names) != len(self.thicknesses):
            raise ValueError("a section needs N + 1 radii, N thicknesses and N names")
        if any(b <= a for a, b in zip(self.radii, self.radii[1:])) or self.radii[0] < 0:
            raise ValueError(f"section radii must rise from r_0 >= 0: {self.radii}")
        if any(t <= 0 for t in self.thicknesses):
            raise ValueError(f"section thicknesses must be positive: {self.thicknesses}")
        if not self.fillets:
            object.__setattr__(self, "fillets", tuple(0.0 for _ in self.radii[1:-1]))
        if len(self.fillets) != len(self.radii) - 2:
            raise ValueError("a section needs one fillet radius per inner edge")

    @property
    def solid(self) -> bool:
        """No bore: the section reaches the axis."""
        return self.radii[0] == 0.0

    def junctions(self) -> list[tuple[int, float, float, float, int]]:
        """(edge index k, radius, thinner half-thickness, fillet radius, +1 / -1: thicker side inward / outward)
        of every inner edge where the thickness steps."""
        out = []
        for k in range(1, len(self.radii) - 1):
            inner, outer = self.thicknesses[k - 1], self.thicknesses[k]
            if not math.isclose(inner, outer, rel_tol=SAME_THICKNESS):
                out.append((k, self.radii[k], min(inner, outer) / 2.0, self.fillets[k - 1], 1 if inner > outer else -1))
        return out


def section(design: Design, fillet: float | None = None) -> Section:
    """The axial section of a designed wheel (:class:`Section`), with fillets at its re-entrant junctions.

    Parameters
    ----------
    design : flyopt.design.result.Design
    fillet : float or None
        Fillet radius at every junction where the thickness steps [m]; None:
        the drawing's fillet (:func:`flyopt.design.castability.fillet_radius`
        for the wheel's process: :data:`DEFAULT_FILLET_RATIO` x the thinner
        section's thickness, at least the process's smallest fillet; the
        design gives none).

    Returns
    -------
    Section
        rim_arms: hub, an equivalent axisymmetric web of the arms' mass, rim.
    """
    dims = design.dims.wheel(design.n_arms, design.bore)
    notes: list[str] = []
    if design.geometry == Geometry.RIM_ARMS:
        r_h, r_i, r_o = dims.d_hub / 2.0, dims.d_inner / 2.0, dims.d_outer / 2.0
        area = stress.arm_section_area(dims.arm_major, wheel.ARM_MINOR_RATIO * dims.arm_major)
        t_eq = dims.n_arms * area / (math.pi * (r_h + r_i))
        radii = [dims.bore / 2.0, r_h, r_i, r_o]
        thicknesses = [dims.l_hub, t_eq, dims.b]
        names = ["hub", "arms", "rim"]
        notes.append(
            said(
                f"the {dims.n_arms} arms as an equivalent axisymmetric web of their mass, t = n A / (pi (r_h + r_i)) = "
                "{t}: it carries hoop stress real arms cannot, so the arms' and rim's stresses are "
                "those of the web wheel of equal mass",
                t=(t_eq, "length", f"{t_eq * 1e3:.3g} mm"),
            )
        )
    else:
        radii, thicknesses, _, names = wheel.steps(design.geometry, dims)
    radii = [float(r) for r in radii]
    thicknesses = [float(t) for t in thicknesses]
    finish = castability.finishing(castability.process_of_design(design))
    if fillet is not None:  # the caller's radius, at every junction, within the same room
        finish = finish._replace(fillet_ratio=0.0, min_fillet=fillet)
    fillets = []
    for k in range(1, len(radii) - 1):
        if math.isclose(thicknesses[k - 1], thicknesses[k], rel_tol=SAME_THICKNESS):
            fillets.append(0.0)
            continue
        # the fillet runs a radius along the thin part's face and up the thick part's: it must fit in the thin
        # part's length (shared with a fillet at its other end) and in the step's height
        k_thin = k if thicknesses[k - 1] > thicknesses[k] else k - 1
        fillets.append(
            castability.fillet_radius(
                finish,
                thicknesses[k - 1],
                thicknesses[k],
                radii[k_thin + 1] - radii[k_thin],
                # the arms' equivalent web is no wall of the casting: no foundry minimum on it (a given radius holds)
                cast_wall=fillet is not None or names[k_thin] != "arms",
            )
        )
    if fillet is None and any(fillets):
        notes.append(
            f"fillets not given by the design: r_f = {DEFAULT_FILLET_RATIO:g} x the thinner section at each junction "
            "(each junction's radius is given with its factor)"
        )
    return Section(tuple(radii), tuple(thicknesses), tuple(names), tuple(fillets), tuple(notes))


# ----------------------------------------------------------------------------------------------- mesh


def _graded(fixed: list[float], foci: list[tuple[float, float]], h_far: float) -> NDArray[np.float64]:
    """1-D nodes through every fixed point, sized h(x) = min(h_far, h_f + GROWTH |x - f|) over the foci (x_f, h_f)."""
    ordered = sorted(fixed)
    merge = 1e-6 * (ordered[-1] - ordered[0])  # fixed points this close are one (an NLP's 4.00000005 mm and 4 mm)
    fixed = [ordered[0]]
    for x in ordered[1:]:
        if x - fixed[-1] > merge:
            fixed.append(x)
    f_x = np.array([f for f, _ in foci]) if foci else np.zeros(0)
    f_h = np.array([h for _, h in foci]) if foci else np.zeros(0)

    def size(x):
        if not foci:
            return h_far
        return min(h_far, float(np.min(f_h + GROWTH * np.abs(x - f_x))))

    nodes = [fixed[0]]
    for a, b in zip(fixed, fixed[1:]):
        march = [a]
        while True:
            x = march[-1] + size(march[-1])
            if x >= b - 0.5 * size(march[-1]):
                break
            march.append(x)
        pts = np.array(march[1:] + [b])
        # the marched points end short of b: stretch them to end at b
        last = march[-1] + size(march[-1]) if len(march) > 1 else b
        span = max(last - a, b - a) if len(march) > 1 else b - a
        nodes.extend(a + (pts[:-1] - a) * (b - a) / span)
        nodes.append(b)
    return np.array(sorted(set(nodes)))


def _fillet_centres(sec: Section) -> list[tuple[float, float, float, int, float]]:
    """(centre r, centre z, radius, side, corner r) of every fillet (side +1: thick part inward)."""
    out = []
    for _, r_k, z_thin, rho_f, side in sec.junctions():
        if rho_f > 0:
            out.append((r_k + side * rho_f, z_thin + rho_f, rho_f, side, r_k))
    return out


def _inside(sec: Section, r: NDArray[np.float64], z: NDArray[np.float64], tol: float) -> NDArray[np.bool_]:
    """Whether points lie in the section (its steps and its fillets), to a tolerance [m]."""
    radii = np.array(sec.radii)
    half = np.array(sec.thicknesses) / 2.0
    k = np.clip(np.searchsorted(radii, r, side="right") - 1, 0, len(half) - 1)
    inside = (r >= radii[0] - tol) & (r <= radii[-1] + tol) & (z >= -tol) & (z <= half[k] + tol)
    # a point on an edge belongs to the thicker step
    on_edge = np.isclose(r[:, None], radii[None, 1:-1], atol=tol)
    for j in range(len(radii) - 2):
        inside |= on_edge[:, j] & (z <= max(half[j], half[j + 1]) + tol)
    for c_r, c_z, rho_f, _, r_k in _fillet_centres(sec):
        lo, hi = sorted((r_k, c_r))
        in_square = (r >= lo - tol) & (r <= hi + tol) & (z >= c_z - rho_f - tol) & (z <= c_z + tol)
        inside |= in_square & (np.hypot(r - c_r, z - c_z) >= rho_f - tol)
    return inside


def section_mesh(sec: Section, size: float = 1.0) -> tuple[NDArray[np.float64], NDArray[np.int_]]:
    """Points and triangles of the half section z >= 0, graded toward the junctions, fillets and bore.

    Parameters
    ----------
    sec : Section
    size : float
        Factor on every element size (:data:`MESH_SIZES`).

    Returns
    -------
    points : (2, n) array
        (r, z) [m].
    triangles : (3, m) array
        Vertex indices, counter-clockwise.
    """
    from scipy.spatial import Delaunay

    radii, half = list(sec.radii), [t / 2.0 for t in sec.thicknesses]
    length = radii[-1] - radii[0]
    thin = min(half)
    fillets = _fillet_centres(sec)
    # far from every focus: a 40th of the radial extent, but no finer than a 160th of the outer radius (a
    # compact section, a bare rim, needs no finer mesh than a disc of its size)
    base = max(length, radii[-1] / 4.0) / 40.0
    h_far_r = size * base
    h_far_z = size * min(max(half) / 4.0, base)
    r_fixed, z_fixed = list(radii), [0.0, *half]
    r_foci = [(radii[0], size * max(min(length, radii[0] or length) / 100.0, thin / 4.0))]
    r_foci.append((radii[-1], size * max(length / 100.0, thin / 4.0)))
    z_foci = [(h, size * min(h, thin) / 3.0) for h in half]
    near = size * thin / 3.0
    for c_r, c_z, rho_f, _, r_k in fillets:
        near = min(near, size * rho_f / 4.0)
        h_f = size * rho_f / 4.0
        r_fixed += [r_k, c_r]
        z_fixed.append(c_z)
        r_foci += [(r_k, h_f), (c_r, h_f)]
        z_foci += [(c_z - rho_f, h_f), (c_z, h_f)]
    for r_k in radii[1:-1]:
        r_foci.append((r_k, size * thin / 3.0))
    r_nodes = _graded(r_fixed, r_foci, h_far_r)
    z_nodes = _graded(z_fixed, z_foci, h_far_z)
    rr, zz = (a.ravel() for a in np.meshgrid(r_nodes, z_nodes))
    tol = 1e-9 * length
    keep = _inside(sec, rr, zz, tol)
    points = [np.vstack([rr[keep], zz[keep]])]
    for c_r, c_z, rho_f, side, _ in fillets:
        # drop grid points that crowd the arc, then put points on it
        d = np.hypot(points[0][0] - c_r, points[0][1] - c_z)
        lo, hi = sorted((c_r - side * rho_f, c_r))
        crowd = (d > rho_f + tol) & (d < rho_f + 0.5 * near) & (points[0][0] >= lo - tol) & (points[0][0] <= hi + tol)
        crowd &= points[0][1] <= c_z + tol
        points[0] = points[0][:, ~crowd]
        n = max(4, math.ceil(0.5 * math.pi * rho_f / near))
        phi = np.linspace(0.0, 0.5 * math.pi, n + 1)[1:-1]  # the ends are grid points
        points.append(np.vstack([c_r - side * rho_f * np.cos(phi), c_z - rho_f * np.sin(phi)]))
    p = np.hstack(points)
    tri = Delaunay(p.T).simplices.T
    centroid = p[:, tri].mean(axis=1)
    area = 0.5 * (
        (p[0, tri[1]] - p[0, tri[0]]) * (p[1, tri[2]] - p[1, tri[0]])
        - (p[0, tri[2]] - p[0, tri[0]]) * (p[1, tri[1]] - p[1, tri[0]])
    )
    good = _inside(sec, centroid[0], centroid[1], -tol) & (np.abs(area) > 1e-12 * length**2)
    tri, area = tri[:, good], area[good]
    flip = area < 0
    tri[1, flip], tri[2, flip] = tri[2, flip], tri[1, flip].copy()
    used = np.unique(tri)
    index = np.full(p.shape[1], -1)
    index[used] = np.arange(used.size)
    return np.ascontiguousarray(p[:, used]), np.ascontiguousarray(index[tri])


# --------------------------------------------------------------------------------------------- solve


@dataclass(frozen=True)
class FemField:
    """The stresses of a solved section, at each triangle's six nodes (element by element, not averaged) [Pa].

    Arrays of shape (elements, 6); ``r``, ``z`` [m]; ``part`` the step index of each element.
    """

    r: NDArray[np.float64]
    z: NDArray[np.float64]
    radial: NDArray[np.float64]
    hoop: NDArray[np.float64]
    axial: NDArray[np.float64]
    shear: NDArray[np.float64]
    part: NDArray[np.int_]
    hoop_force: NDArray[np.float64]  # integral of sigma_t dA over each element [N]
    element_area: NDArray[np.float64]  # [m^2]
    nodes: int
    elements: int

    @property
    def von_mises(self) -> NDArray[np.float64]:
        """The von Mises stress of the three-dimensional state [Pa]."""
        sr, st, sz, tau = self.radial, self.hoop, self.axial, self.shear
        return np.sqrt(0.5 * ((sr - st) ** 2 + (st - sz) ** 2 + (sz - sr) ** 2) + 3.0 * tau**2)

    @property
    def max_principal(self) -> NDArray[np.float64]:
        """The largest principal stress [Pa]: sigma_t, or the larger in-plane principal of (sigma_r, sigma_z, tau)."""
        mean = 0.5 * (self.radial + self.axial)
        in_plane = mean + np.sqrt((0.5 * (self.radial - self.axial)) ** 2 + self.shear**2)
        return np.maximum(self.hoop, in_plane)

    def mean_hoop(self, part: int | None = None) -> float:
        """Mean hoop stress over the radial section (of one step, or all) [Pa]."""
        mask = np.ones(self.part.shape, bool) if part is None else self.part == part
        return float(self.hoop_force[mask].sum() / self.element_area[mask].sum())


def strains(u: Any, r: Any) -> tuple[Any, Any, Any, Any]:
    """The axisymmetric strains (radial, hoop, axial, engineering shear) of a displacement field ``u`` (an
    skfem field of (u_r, u_z): its values and gradients in (r, z)) at radii ``r``."""
    return u.grad[0, 0], u[0] / r, u.grad[1, 1], u.grad[0, 1] + u.grad[1, 0]


def hooke(lam: float, mu: float, err: Any, ett: Any, ezz: Any, grz: Any) -> tuple[Any, Any, Any, Any]:
    """Isotropic Hooke's law of the axisymmetric strains (:func:`strains`), by Lame's lam and mu: the radial,
    hoop and axial stresses and the shear stress tau_rz."""
    trace = err + ett + ezz
    return lam * trace + 2 * mu * err, lam * trace + 2 * mu * ett, lam * trace + 2 * mu * ezz, mu * grz


def stiffness_matrix(basis: Any, lam: float, mu: float) -> Any:
    """The axisymmetric stiffness matrix of an skfem vector basis: the integral over the section of
    eps(v) . sigma(u) r dA (:func:`strains`, :func:`hooke`), every element's at once.

    The same matrix as skfem's ``BilinearForm`` of that integrand (``tests/design/test_fem.py`` holds them
    equal to round-off), in about half its time: the form's kernel runs once per pair of an element's twelve
    basis functions (144 passes over every element), where here each function's strains and stresses are
    formed once and the element matrices are one ``einsum``. It holds every function's strains and stresses
    at every quadrature point at once: about twice the form's peak memory (some 50 MB for 4,000 elements,
    235 MB for 18,000).

    Returns
    -------
    scipy.sparse.csr_matrix
    """
    from scipy.sparse import coo_matrix

    r = np.asarray(basis.global_coordinates()[0])  # (elements, quadrature points)
    eps = np.array([strains(basis.basis[i][0], r) for i in range(basis.Nbfun)])  # (functions, 4, el., q.)
    stress_of = np.stack(hooke(lam, mu, *np.moveaxis(eps, 1, 0)), axis=1)  # (functions, 4, el., q.)
    local = np.einsum("iaeq,jaeq,eq->eij", eps, stress_of, basis.dx * r, optimize=True)
    dofs = basis.element_dofs.T  # (elements, functions)
    rows = np.broadcast_to(dofs[:, :, None], local.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], local.shape).ravel()
    return coo_matrix((local.ravel(), (rows, cols)), shape=(basis.N, basis.N)).tocsr()


def solve_section(
    sec: Section, density: float, poisson: float, omega: float, *, size: float = 1.0, elastic_modulus: float = 1.0
) -> FemField:
    """Solve the axisymmetric elasticity problem of a spinning section (see the module notes).

    Parameters
    ----------
    sec : Section
    density, poisson : float
        rho [kg/m^3], nu [-].
    omega : float
        Speed [rad/s].
    size : float
        Factor on every element size (:data:`MESH_SIZES`).
    elastic_modulus : float
        E [Pa]; the stresses do not depend on it.

    Returns
    -------
    FemField
    """
    skfem = _skfem()
    from scipy.sparse.linalg import splu

    points, triangles = section_mesh(sec, size)
    mesh = skfem.MeshTri(points, triangles)
    element = skfem.ElementVector(skfem.ElementTriP2())
    basis = skfem.Basis(mesh, element, intorder=4)
    lam = elastic_modulus * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
    mu = elastic_modulus / (2.0 * (1.0 + poisson))

    @skfem.LinearForm
    def load(v, w):
        r = w.x[0]
        return density * omega**2 * r * v[0] * r

    a = stiffness_matrix(basis, lam, mu)
    b = load.assemble(basis)
    tol = 1e-9 * (sec.radii[-1] - sec.radii[0])
    fixed = [basis.get_dofs(lambda x: np.abs(x[1]) < tol).all(["u^2"])]
    if sec.solid:
        fixed.append(basis.get_dofs(lambda x: np.abs(x[0]) < tol).all(["u^1"]))
    d = np.unique(np.concatenate(fixed))
    free = np.setdiff1d(np.arange(basis.N), d)
    u = np.zeros(basis.N)
    # the stiffness is symmetric positive definite: SuperLU in its symmetric mode (a minimum-degree ordering of
    # A + A^T, a diagonal pivot wherever it is at least a tenth of its column's largest) factors it in some 60 %
    # of the time of its default (COLAMD, partial pivoting: spsolve), to the same residual (punch-press-wheel's
    # 17,000 unknowns: 73 against 125 ms, the displacements 6e-12 apart)
    factor = splu(
        a[free][:, free].tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.1, options={"SymmetricMode": True}
    )
    u[free] = factor.solve(b[free])

    # stresses at each element's six nodes, from its own field
    at_nodes = skfem.Basis(mesh, element, quadrature=(skfem.ElementTriP2().doflocs.T, np.full(6, 1.0 / 12.0)))
    field_ = at_nodes.interpolate(u)
    x = at_nodes.global_coordinates()
    r, z = x[0], x[1]
    on_axis = r < tol
    err, ett, ezz, grz = strains(field_, np.where(on_axis, 1.0, r))
    ett = np.where(on_axis, err, ett)  # u_r / r -> du_r/dr on the axis
    radial, hoop, axial, shear = hooke(lam, mu, err, ett, ezz, grz)
    # the hoop force of each element, by its quadrature
    hoop_q = hooke(lam, mu, *strains(basis.interpolate(u), basis.global_coordinates()[0]))[1]
    weights = basis.dx
    centroid_r = points[0, triangles].mean(axis=0)
    part = np.clip(np.searchsorted(np.array(sec.radii), centroid_r, side="right") - 1, 0, len(sec.thicknesses) - 1)
    return FemField(
        r=r,
        z=z,
        radial=radial,
        hoop=hoop,
        axial=axial,
        shear=shear,
        part=part,
        hoop_force=(hoop_q * weights).sum(axis=1),
        element_area=weights.sum(axis=1),
        nodes=int(basis.N // 2),
        elements=int(triangles.shape[1]),
    )


# --------------------------------------------------------------------------------------------- check


@dataclass(frozen=True)
class PartPeak:
    """One part's peak stresses by the FE model, beside the Lamé/arm model's governing stress [Pa], (r, z) [m]."""

    part: str
    von_mises: float
    von_mises_at: tuple[float, float]
    max_principal: float
    max_principal_at: tuple[float, float]
    model_stress: float | None  # the design's (Lamé/arm) governing stress of the part
    model_radius: float | None
    ratio: float | None  # FE governing peak / model_stress
    allowable: float | None = None  # the part's allowable stress (the design's) [Pa]
    utilisation: float | None = None  # FE governing peak / allowable

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready plain Python."""
        return {
            "part": self.part,
            "von_mises": self.von_mises,
            "von_mises_at": list(self.von_mises_at),
            "max_principal": self.max_principal,
            "max_principal_at": list(self.max_principal_at),
            "model_stress": self.model_stress,
            "model_radius": self.model_radius,
            "ratio": self.ratio,
            "allowable": self.allowable,
            "utilisation": self.utilisation,
        }


@dataclass(frozen=True)
class JunctionFactor:
    """The stress concentration at one junction: FE peak near it over the Lamé step model's stress there."""

    name: str  # "hub-web", ...
    radius: float  # [m]
    fillet: float  # [m]; 0: the two parts are as thick (no corner)
    fem_peak: float  # the governing measure's FE peak in the junction zone [Pa]
    fem_at: tuple[float, float]  # (r, z) [m]
    lame: float  # the larger of the two steps' governing stress at the junction radius (Lamé) [Pa]
    factor: float  # fem_peak / lame

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready plain Python."""
        return {
            "name": self.name,
            "radius": self.radius,
            "fillet": self.fillet,
            "fem_peak": self.fem_peak,
            "fem_at": list(self.fem_at),
            "lame": self.lame,
            "factor": self.factor,
        }


@dataclass(frozen=True)
class FemCheck:
    """The axisymmetric FE check of a designed wheel at one speed (SI).

    Attributes
    ----------
    omega : float
        The speed checked, on the wheel's shaft [rad/s].
    measure : str
        "von_mises" (ductile) or "max_principal" (brittle): what the factors and ratios compare.
    parts : tuple of PartPeak
    junctions : tuple of JunctionFactor
    peak : float
        The largest governing FE stress of the wheel [Pa]; ``model_peak`` the model's.
    mean_hoop : float
        Mean hoop stress of the radial section by FE [Pa].
    size : float
        Mesh size factor; ``elements``, ``nodes`` its count.
    notes : tuple of str
    """

    omega: float
    measure: str
    parts: tuple[PartPeak, ...]
    junctions: tuple[JunctionFactor, ...]
    peak: float
    model_peak: float | None
    mean_hoop: float
    size: float
    elements: int
    nodes: int
    notes: tuple[str, ...] = field(default=())
    accepted_by: str | None = None  # "fem" where the design was accepted against the larger of FE and model
    stress_factors: tuple[tuple[str, float], ...] = ()  # the factors the accepted design's allowables carry
    rounds: int = 1  # designs the acceptance made (1: the first was within its allowables)

    @property
    def within_allowable(self) -> bool | None:
        """Whether every part's FE peak is within its allowable stress (None: no allowable known)."""
        known = [p.utilisation for p in self.parts if p.utilisation is not None]
        return None if not known else max(known) <= 1.0

    @property
    def difference(self) -> float | None:
        """How far the FE peak lies from the model's, as a fraction (0.3: the FE peak is 30 % higher)."""
        return None if not self.model_peak else self.peak / self.model_peak - 1.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready plain Python."""
        return {
            "omega": self.omega,
            "measure": self.measure,
            "peak": self.peak,
            "model_peak": self.model_peak,
            "difference": self.difference,
            "within_allowable": self.within_allowable,
            "mean_hoop": self.mean_hoop,
            "parts": [p.to_dict() for p in self.parts],
            "junctions": [j.to_dict() for j in self.junctions],
            "mesh": {"size": self.size, "elements": self.elements, "nodes": self.nodes},
            "notes": list(self.notes),
            "accepted_by": self.accepted_by,
            "stress_factors": [{"part": part, "factor": value} for part, value in self.stress_factors],
            "rounds": self.rounds,
        }


def _argmax(values: NDArray[np.float64], mask: NDArray[np.bool_], r, z) -> tuple[float, tuple[float, float]]:
    """The largest value under a mask and its (r, z)."""
    masked = np.where(mask, values, -np.inf)
    i = np.unravel_index(int(np.argmax(masked)), values.shape)
    return float(masked[i]), (float(r[i]), float(z[i]))


def _mesh_size(mesh: str | float) -> float:
    if isinstance(mesh, str):
        if mesh not in MESH_SIZES:
            raise ValueError(f"mesh {mesh!r} not known: one of {', '.join(MESH_SIZES)} or a size factor > 0")
        return MESH_SIZES[mesh]
    if not mesh > 0:
        raise ValueError(f"mesh size factor {mesh!r} must be > 0")
    return float(mesh)


def fem_check(
    design: Design,
    material: Material,
    omega: float,
    *,
    mesh: str | float = "normal",
    fillet: float | None = None,
    stress_factors: Mapping[str, float] | None = None,
) -> FemCheck:
    """The axisymmetric FE check of a designed wheel under its own centrifugal load.

    Parameters
    ----------
    design : flyopt.design.result.Design
    material : flyopt.design.materials.Material
        The design's material (density, Poisson's ratio; ductile or brittle).
    omega : float
        Speed of the wheel's shaft [rad/s]: the design's omega_max on its shaft.
    mesh : str or float
        "coarse", "normal", "fine", "finer" or a factor on every element size.
    fillet : float or None
        Fillet radius at the junctions [m]; None: :data:`DEFAULT_FILLET_RATIO` x the thinner section.
    stress_factors : mapping or None
        The factors the design's allowables were divided by (:attr:`flyopt.design.spec.DesignSpec.stress_factors`):
        the FE peaks are judged against the material's own allowable, the design's times its factor.

    Returns
    -------
    FemCheck

    Raises
    ------
    ImportError
        Without scikit-fem (a dependency of flyopt, missing from this environment).
    ValueError
        A material without Poisson's ratio; an unknown mesh.
    """
    size = _mesh_size(mesh)
    if material.poisson_ratio is None:
        raise ValueError(f"material {material.name}: the FEM check needs its poisson_ratio [-], and none is given")
    rho, nu = material.density, material.poisson_ratio
    sec = section(design, fillet)
    result = solve_section(sec, rho, nu, omega, size=size, elastic_modulus=material.elastic_modulus or 1.0)
    measure = "von_mises" if material.ductile else "max_principal"
    governing = result.von_mises if material.ductile else result.max_principal
    model = {p["part"]: p for p in (design.stresses.stress or {}).get("parts", ())}
    factors = dict(stress_factors or {})
    element_part = np.broadcast_to(result.part[:, None], result.r.shape)
    parts = []
    for k, name in enumerate(sec.names):
        mask = element_part == k
        vm, vm_at = _argmax(result.von_mises, mask, result.r, result.z)
        mp, mp_at = _argmax(result.max_principal, mask, result.r, result.z)
        theirs = model.get(name)
        model_stress = None if theirs is None else float(theirs["stress"])
        allowable = (
            None
            if theirs is None or not theirs.get("allowable")
            else float(theirs["allowable"]) * factors.get(name, 1.0)
        )
        mine = vm if material.ductile else mp
        parts.append(
            PartPeak(
                name,
                vm,
                vm_at,
                mp,
                mp_at,
                model_stress,
                None if theirs is None else float(theirs["radius"]),
                mine / model_stress if model_stress else None,
                allowable,
                None if allowable is None else mine / allowable,
            )
        )
    # the Lamé step model of the same section, at each junction (flyopt.design.stress: one path for it)
    coefficients = stress.disc_coefficients(list(sec.radii), list(sec.thicknesses), rho, nu, omega, solid=sec.solid)

    def lame(k, r):
        sr, st = (float(v) for v in stress.disc_stresses(coefficients[k], rho, nu, omega, r))
        return float(stress.von_mises(sr, st)) if material.ductile else max(sr, st)

    junctions = []
    fillets = {j[0]: j[3] for j in sec.junctions()}
    for k in range(1, len(sec.radii) - 1):
        r_k = sec.radii[k]
        thin = min(sec.thicknesses[k - 1], sec.thicknesses[k])
        rho_f = fillets.get(k, 0.0)
        reach = ZONE * (rho_f + thin)
        mask = np.abs(result.r - r_k) <= reach
        peak, at = _argmax(governing, mask, result.r, result.z)
        reference = max(lame(k - 1, r_k), lame(k, r_k))
        junctions.append(
            JunctionFactor(f"{sec.names[k - 1]}-{sec.names[k]}", r_k, rho_f, peak, at, reference, peak / reference)
        )
    peak = float(governing.max())
    model_peak = max((p.model_stress for p in parts if p.model_stress is not None), default=None)
    return FemCheck(
        omega=omega,
        measure=measure,
        parts=tuple(parts),
        junctions=tuple(junctions),
        peak=peak,
        model_peak=model_peak,
        mean_hoop=result.mean_hoop(),
        size=size,
        elements=result.elements,
        nodes=result.nodes,
        notes=sec.notes,
    )


def check_result(result: DesignResult, materials: Sequence[Material], *, mesh: str | float = "normal") -> DesignResult:
    """The design result with its best design's FE check (``result.fem``), reported beside the Lamé/arm model.

    Parameters
    ----------
    result : flyopt.design.result.DesignResult
    materials : sequence of Material
        The materials the design chose among (the best design's is looked up by name).
    mesh : str or float
        As :func:`fem_check`.

    Returns
    -------
    DesignResult
        ``result`` itself where there is no design, ``fem_check`` is false, or the best design's material
        gives no Poisson's ratio (no stress model, so nothing to compare: a whole wheel's design needs one).

    Notes
    -----
    The check reports; it does not re-design (that is :func:`accept`, ``fem_check = true``). A design
    whose FE peak exceeds an allowable stress is still the design, and the check says so
    (:attr:`FemCheck.within_allowable`).
    """
    best = result.best
    if result.spec.fem_check is False or best is None:
        return result
    material = next(m for m in materials if m.name == best.material)
    if material.poisson_ratio is None:
        return result
    check = fem_check(best, material, result.omega * best.speed_ratio, mesh=mesh)
    return dataclasses.replace(result, fem=check)


#: Designs the FE acceptance makes at most before it gives up (the first included).
MAX_ACCEPT_ROUNDS = 6

#: A part's FE peak is within its allowable up to this relative excess (the FE's own accuracy on the
#: "normal" mesh: tests/design/test_fem.py reproduces the closed forms to 1e-3).
ACCEPT_RTOL = 1e-3

#: Margin a new factor carries above the concentration found, so that the next design lands inside.
ACCEPT_MARGIN = 2e-3


def judged_parts(design: Design) -> tuple[str, ...]:
    """The parts the FE acceptance judges: every part of a body of revolution; of an arms wheel only its hub
    (its arms and rim are judged by the texts' beams, which the FE's equivalent web cannot represent)."""
    names = tuple(p["part"] for p in (design.stresses.stress or {}).get("parts", ()))
    return ("hub",) if design.geometry == Geometry.RIM_ARMS and "hub" in names else names


def accept(
    result: DesignResult,
    materials: Sequence[Material],
    redesign: Callable[[tuple[StressFactor, ...]], DesignResult],
    *,
    mesh: str | float = "normal",
) -> DesignResult:
    """The design accepted against the larger of the FE peak and the Lamé/arm model (``[design] fem_check``).

    The best design is checked by FE (:func:`fem_check`). Where a judged part's FE peak exceeds the
    material's allowable (by more than :data:`ACCEPT_RTOL`), the concentration the FE found in that part
    (FE peak / the model's stress, and at least a step above the factor it had) becomes that part's factor
    for that combination (material, shaft, arm count), and every combination is designed again
    (``redesign``) with the part's allowable divided by its factor: the model's stress times the
    concentration, the larger of the two opinions, stays within the allowable. The new best is checked in turn: a combination the FE has not
    checked carries no factor and is checked when it wins. So the design reported is within its allowables
    by both models, and no combination the FE accepted is lighter. At most :data:`MAX_ACCEPT_ROUNDS` designs.

    Parameters
    ----------
    result : flyopt.design.result.DesignResult
        The first design (its spec's ``stress_factors`` none).
    materials : sequence of Material
    redesign : callable
        The same design with the given stress factors.
    mesh : str or float
        As :func:`fem_check`.

    Returns
    -------
    DesignResult
        The accepted design with its FE check (``fem.accepted_by == "fem"``, ``fem.stress_factors`` its own
        combination's); a result without a design (no wheel meets the limits with the factors) as the
        designer gives it.

    Raises
    ------
    flyopt.errors.SolverFailed
        The FE peaks did not come within the allowables in :data:`MAX_ACCEPT_ROUNDS` designs.
    """
    from flyopt.design.spec import StressFactor
    from flyopt.errors import SolverFailed

    factors = {(f.material, f.shaft, f.n_arms, f.part): f.factor for f in result.spec.stress_factors}
    over: dict[str, tuple[float, float | None]] = {}
    for rounds in range(1, MAX_ACCEPT_ROUNDS + 1):
        best = result.best
        if best is None:
            return result
        material = next(m for m in materials if m.name == best.material)
        combo = (best.material, best.shaft, best.n_arms or 0)
        own = result.spec.stress_factors_for(*combo)
        check = fem_check(best, material, result.omega * best.speed_ratio, mesh=mesh, stress_factors=own)
        judged = judged_parts(best)
        over = {
            p.part: (p.utilisation, p.ratio)
            for p in check.parts
            if p.part in judged and p.utilisation is not None and p.utilisation > 1.0 + ACCEPT_RTOL
        }
        if not over:
            accepted = dataclasses.replace(
                check, accepted_by="fem", stress_factors=tuple(sorted(own.items())), rounds=rounds
            )
            return dataclasses.replace(result, fem=accepted)
        for part, (_excess, ratio) in over.items():
            key = (*combo, part)
            # the concentration FE / model on this wheel, and at least a step above the factor that let it over
            factors[key] = max(factors.get(key, 1.0), ratio or 1.0) * (1.0 + ACCEPT_MARGIN)
        result = redesign(tuple(StressFactor(*key, value) for key, value in sorted(factors.items())))
    worst = ", ".join(f"{part} {excess:.4g} x its allowable" for part, (excess, _ratio) in sorted(over.items()))
    raise SolverFailed(
        f"the FE check did not accept the wheel in {MAX_ACCEPT_ROUNDS} designs: its FE peaks still exceed the "
        f"allowables ({worst}); no design is reported"
    )
