"""Tests of flyopt.design.closed_form, the vectorized closed-form designer.

Two references:

* flyopt.design.designer.design_flywheel (IPOPT on the cached NLP, with its own
  closed-form feasibility proof): on a few hundred random combinations of
  every covered structure, including infeasible ones, both must reach the
  same verdict and the same mass within 1e-6 (the issue's agreement).
* An independent reference written here from the physics, not from flyopt
  (neither flyopt.design.geometry nor flyopt.design.designer): a scan of the inertia of
  the widest admissible rim at the outer-diameter cap and scipy's brentq for
  its smallest root (free D_m), and the largest admissible H for a pinned
  annulus; mass within 1e-9 (both are exact to round-off).
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design import closed_form as batch
from flyopt.design.check import binding_names
from flyopt.design.closed_form import max_inertia_one as max_inertia
from flyopt.design.materials import Material, builtin_materials

RPM = math.pi / 30.0
CAST_STEEL = builtin_materials()["cast_steel"]


# --------------------------------------------------------------------------
# Independent references (physics only)
# --------------------------------------------------------------------------


def ref_free_rim(thin, rho, j, cap, hb_min, b_max=math.inf):
    """Lightest rim with D_m free, or None: D_outer = cap, H the smallest root of
    pi rho (cap - H) H B(H) k(H) / 4 = j with B(H) = min(H / hb_min, B_max)."""

    def inertia(h):
        d = cap - h
        b = np.minimum(h / hb_min, b_max)
        k = d * d if thin else d * d + h * h
        return math.pi * rho * d * h * b * k / 4.0

    grid = np.geomspace(1e-12 * cap, 0.5 * cap, 4000)
    values = inertia(grid)
    above = np.flatnonzero(values >= j)
    if above.size == 0:
        return None
    i = int(above[0])
    if i == 0:
        raise AssertionError("reference grid starts too high")
    h = brentq(lambda x: inertia(x) / j - 1.0, grid[i - 1], grid[i], xtol=1e-16, rtol=1e-15)
    d = cap - h
    k = d * d if thin else d * d + h * h
    return {"mass": 4.0 * j / k, "h": h, "b": float(min(h / hb_min, b_max))}


def ref_pinned_annulus(rho, j, d_mean, cap, hb_min, hb_max):
    """Lightest exact annulus of mean diameter d_mean: H as large as the room and
    H/B <= hb_max allow (bisection on H/B of the wheel giving exactly j)."""

    def hb_of(h):
        mass = 4.0 * j / (d_mean**2 + h**2)
        return h / (mass / (math.pi * rho * d_mean * h))

    if d_mean >= cap:
        return None
    h = min(cap - d_mean, d_mean)
    if hb_of(h) > hb_max:
        h = brentq(lambda x: hb_of(x) - hb_max, 1e-12 * d_mean, h, xtol=1e-16, rtol=1e-15)
    if hb_of(h) < hb_min * (1 - 1e-12):
        return None
    return {"mass": 4.0 * j / (d_mean**2 + h**2), "h": h}


# --------------------------------------------------------------------------
# Random combinations
# --------------------------------------------------------------------------


def random_combination(rng, geometry):
    """One material x shaft combination of a random scene (about a third infeasible)."""
    rho, v_max = float(rng.uniform(2000, 9000)), float(rng.uniform(20, 200))
    omega, ratio = float(10 ** rng.uniform(1, 3.5)), float(10 ** rng.uniform(-1, 1))
    j = float(10 ** rng.uniform(-3, 4))
    low = float(rng.uniform(1.0, 2.5))
    high = low if rng.random() < 0.2 else low + float(rng.uniform(0, 1))
    cap_speed = 2 * v_max / (omega * ratio)
    envelope = float(cap_speed * rng.uniform(0.3, 1.5)) if rng.random() < 0.5 else None
    cap = min(cap_speed, envelope or math.inf)
    j_shaft = j / ratio**2
    width = None
    if rng.random() < 0.5:  # near the width the wheel would take without a limit
        if geometry == "disc":
            free = 32 * j_shaft / (math.pi * rho * cap**4)
        else:
            free = math.sqrt(4 * low * j_shaft / (math.pi * rho * cap**3)) / low
        width = float(free * rng.uniform(0.3, 3.0))
    d_mean = float(cap * rng.uniform(0.2, 1.05)) if rng.random() < 0.3 else None
    spec = DesignSpec(
        geometry=geometry, hb_ratio=(low, high), max_outer_diameter=envelope, max_width=width, d_mean=d_mean
    )
    return j, omega, MountShaft("s", ratio), Material("m", rho, v_max), spec


def closed_form(j, omega, shaft, material, spec):
    def inf(x):
        return math.inf if x is None else x

    return batch.design_combinations(
        spec.geometry,
        j,
        omega,
        shaft.speed_ratio,
        material.density,
        material.max_rim_speed,
        spec.hb_ratio[0],
        spec.hb_ratio[1],
        inf(spec.max_outer_diameter),
        inf(spec.max_width),
        math.nan if spec.d_mean is None else spec.d_mean,
    )


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_closed_form_agrees_with_ipopt_on_random_combinations(seed):
    """300 random combinations (100 per seed) of every covered structure: thin_rim,
    rim and disc, D_m free and pinned, H/B range or collapsed, with and without
    envelope and width limit. Same feasibility verdict, mass within 1e-6, and the
    closed-form design satisfies every constraint."""
    rng = np.random.default_rng(seed)
    counts = {"feasible": 0, "infeasible": 0}
    for k in range(100):
        geometry = ("rim", "thin_rim", "disc")[k % 3]
        j, omega, shaft, material, spec = random_combination(rng, geometry)
        got = closed_form(j, omega, shaft, material, spec)
        ipopt = design_flywheel(j, omega, [shaft], [material], spec, method="ipopt").candidates[0]
        assert bool(got.feasible) == ipopt.feasible, (spec, ipopt.reason)
        if not ipopt.feasible:
            counts["infeasible"] += 1
            assert np.isnan(got.mass)
            continue
        counts["feasible"] += 1
        assert_allclose(float(got.mass), ipopt.mass, rtol=1e-6)
        # constraints, to round-off
        j_shaft = j / shaft.speed_ratio**2
        assert_allclose(float(got.j_flywheel), j_shaft, rtol=1e-12)
        assert float(got.d_outer) <= float(got.cap) * (1 + 1e-14)
        if spec.max_width is not None:
            assert float(got.b) <= spec.max_width * (1 + 1e-14)
        if geometry != "disc":
            assert spec.hb_ratio[0] * (1 - 1e-12) <= float(got.hb_ratio) <= spec.hb_ratio[1] * (1 + 1e-12)
            assert float(got.d_inner) >= 0.0
        if spec.d_mean is None or geometry == "thin_rim":
            # IPOPT's dimensions are well settled here: the same wheel and the same
            # active constraints (for a pinned annulus its mass is almost flat in H,
            # so IPOPT stops with H loose by ~1e-3 while the mass agrees to 1e-10)
            assert_allclose(float(got.d_outer), ipopt.dims.d_outer, rtol=1e-5)
            assert_allclose(float(got.b), ipopt.dims.b, rtol=1e-4)
            assert set(binding_names(got.binding)) == set(ipopt.limits.binding)
        else:
            assert float(got.mass) <= ipopt.mass * (1 + 1e-9)  # the exact vertex is no heavier
    assert counts["feasible"] >= 40 and counts["infeasible"] >= 15, counts


def test_max_inertia_is_bitwise_the_same_as_the_scalar_form():
    """The screening must decide exactly as the designer does, also at the edge of
    feasibility: the same J_max to the last bit on 3000 random inputs."""
    rng = np.random.default_rng(5)
    for k in range(3000):
        geometry = ("rim", "thin_rim", "disc")[k % 3]
        rho, cap = float(rng.uniform(2000, 9000)), float(10 ** rng.uniform(-2, 1))
        low = float(rng.uniform(1, 2.5))
        high = low + float(rng.uniform(0, 1)) * (rng.random() < 0.8)
        width = float(cap * 10 ** rng.uniform(-3, 0)) if rng.random() < 0.5 else math.inf
        d_mean = float(cap * rng.uniform(0.1, 1.2)) if rng.random() < 0.3 else None
        expected = max_inertia(geometry, rho, cap, (low, high), width, d_mean)[0]
        got = batch.max_inertia(geometry, rho, cap, low, high, width, math.nan if d_mean is None else d_mean)
        assert float(got) == expected, (geometry, rho, cap, low, high, width, d_mean)


@pytest.mark.parametrize("geometry", ["rim", "thin_rim"])
@pytest.mark.parametrize("factor", [1 - 1e-9, 1.0, 1 + 1e-9])
def test_edge_of_feasibility_decided_like_optimize(geometry, factor):
    """J a hair below, at and above the largest a rim under the cap can give."""
    omega = 1500 * RPM
    cap = 2 * CAST_STEEL.max_rim_speed / omega
    j_max = max_inertia(geometry, CAST_STEEL.density, cap, (1.5, 2.0))[0]
    j = j_max * factor
    got = batch.design_combinations(geometry, j, omega, 1.0, CAST_STEEL.density, CAST_STEEL.max_rim_speed, 1.5, 2.0)
    ipopt = design_flywheel(
        j, omega, [MountShaft("m", 1.0)], [CAST_STEEL], DesignSpec(geometry=geometry), method="ipopt"
    ).candidates[0]
    assert bool(got.feasible) == ipopt.feasible == (factor <= 1.0)
    if factor < 1.0:
        # near the fold of J(H) the mass is sqrt-sensitive to J; 1e-6 still holds
        assert_allclose(float(got.mass), ipopt.mass, rtol=1e-6)
    elif factor == 1.0:
        # at the fold the only wheel is the peak of J(H): H = 2C/5 (thin rim, m = 4 J /
        # (3C/5)^2) or H = C/2 (annulus, m = 4 J / (C^2/2)). The closed form finds it to
        # ~sqrt(eps) in H, 1e-8 in mass; IPOPT stops ~3e-6 away in mass here
        exact = 4 * j / (0.6 * cap) ** 2 if geometry == "thin_rim" else 8 * j / cap**2
        assert_allclose(float(got.mass), exact, rtol=1e-7)
        assert_allclose(ipopt.mass, exact, rtol=1e-5)


@pytest.mark.parametrize("thin", [True, False])
@pytest.mark.parametrize("with_width", [False, True])
def test_free_rim_matches_independent_root_search(thin, with_width):
    """D_m free: 200 random combinations against the scan + brentq reference,
    mass within 1e-9 and H within 1e-7 (both exact to round-off; H is less well
    conditioned than the mass where J(H) is flat)."""
    rng = np.random.default_rng(100 + 2 * thin + with_width)
    n = 200
    rho = rng.uniform(2000, 9000, n)
    cap = 10 ** rng.uniform(-1.5, 0.5, n)
    j = 10 ** rng.uniform(-3, 3, n)
    a = rng.uniform(1.0, 2.5, n)
    c = a + rng.uniform(0, 1, n)
    width = (
        np.sqrt(4 * a * j / (np.pi * rho * cap**3)) / a * rng.uniform(0.5, 2, n) if with_width else np.full(n, np.inf)
    )
    got = batch.lightest("thin_rim" if thin else "rim", j, rho, cap, a, c, width)
    seen = 0
    for k in range(n):
        ref = ref_free_rim(thin, rho[k], j[k], cap[k], a[k], width[k])
        # the reference ignores H/B <= hb_max; it binds only when hb_max B_max < H
        if ref is not None and ref["h"] > c[k] * width[k]:
            ref = None
        assert bool(got.feasible[k]) == (ref is not None), k
        if ref is not None:
            seen += 1
            assert_allclose(got.mass[k], ref["mass"], rtol=1e-9)
            assert_allclose(got.h[k], ref["h"], rtol=1e-7)
            assert_allclose(got.b[k], ref["b"], rtol=1e-7)
            # the scalar twin (design_flywheel's ranking path) against the same reference
            d, h, b = batch.lightest_one("thin_rim" if thin else "rim", j[k], rho[k], cap[k], a[k], c[k], width[k])
            k_ref = d * d if thin else d * d + h * h
            assert_allclose(4.0 * j[k] / k_ref, ref["mass"], rtol=1e-9)
            assert_allclose((d + h, h, b), (cap[k], ref["h"], ref["b"]), rtol=1e-7)
    assert seen >= 50


def test_pinned_annulus_matches_independent_reference():
    """D_m pinned, exact annulus: H = min(room, the H where H/B reaches hb_max)."""
    rng = np.random.default_rng(8)
    j, omega = 1.0183, 1500 * RPM
    cap = 2 * CAST_STEEL.max_rim_speed / omega
    d_means = cap * rng.uniform(0.05, 1.05, 100)
    a = rng.uniform(1.0, 2.0, 100)
    c = a + rng.uniform(0.0, 2.0, 100)
    got = batch.lightest("rim", j, CAST_STEEL.density, cap, a, c, np.inf, d_means)
    for k in range(100):
        ref = ref_pinned_annulus(CAST_STEEL.density, j, d_means[k], cap, a[k], c[k])
        assert bool(got.feasible[k]) == (ref is not None)
        if ref is not None:
            assert_allclose(got.mass[k], ref["mass"], rtol=1e-12)
            assert_allclose(got.h[k], ref["h"], rtol=1e-9)
            d, h, _ = batch.lightest_one("rim", j, CAST_STEEL.density, cap, a[k], c[k], np.inf, d_means[k])
            assert_allclose((d, 4.0 * j / (d * d + h * h)), (d_means[k], ref["mass"]), rtol=1e-12)
            assert_allclose(h, ref["h"], rtol=1e-9)


def test_domain_example6_rim_sizing_pinned_thin_rim():
    """Domain notes, worked example 6: J = 76 kg m^2, D_m = 0.8 m, cast steel,
    H/B = 2: m = 4 J / D_m^2 = 475 kg exactly, B = 0.110 m, H = 0.220 m (three
    figures as published)."""
    got = batch.lightest("thin_rim", 76.0, CAST_STEEL.density, 2.0, 2.0, 2.0, np.inf, 0.8)
    assert_allclose(got.mass, 475.0, rtol=1e-14)
    assert_allclose(got.b, 0.110, rtol=5e-3)
    assert_allclose(got.h, 0.220, rtol=5e-3)
    d, h, b = batch.lightest_one("thin_rim", 76.0, CAST_STEEL.density, 2.0, 2.0, 2.0, np.inf, 0.8)
    assert_allclose(math.pi * CAST_STEEL.density * d * h * b, 475.0, rtol=1e-14)
    assert_allclose((b, h), (0.110, 0.220), rtol=5e-3)


def test_disc_closed_form():
    """Disc: D at the cap, B = 32 J / (pi rho D^4), m = 8 J / D^2; infeasible when
    that B exceeds the width limit; a pinned D above the cap does not fit."""
    j, omega = 2.0, 1000 * RPM
    d = 2 * CAST_STEEL.max_rim_speed / omega
    rho = CAST_STEEL.density
    b = 32 * j / (math.pi * rho * d**4)
    got = batch.design_combinations(
        "disc",
        [j, j, j, j],
        omega,
        1.0,
        rho,
        CAST_STEEL.max_rim_speed,
        1.5,
        2.0,
        math.inf,
        [math.inf, 0.5 * b, math.inf, math.inf],
        [math.nan, math.nan, 1.01 * d, 0.5 * d],
    )
    assert got.feasible.tolist() == [True, False, False, True]
    assert_allclose(got.d_outer[0], d, rtol=1e-15)
    assert_allclose(got.b[0], b, rtol=1e-14)
    assert_allclose(got.mass[0], 8 * j / d**2, rtol=1e-14)
    assert got.d_inner[0] == 0.0
    assert_allclose(got.mass[3], 8 * j / (0.5 * d) ** 2, rtol=1e-14)
    assert binding_names(got.binding[0]) == ("inertia", "rim_speed")
    assert_allclose(batch.lightest_one("disc", j, rho, d, 1.5, 2.0), (d / 2, d / 2, b), rtol=1e-14)
    assert_allclose(
        batch.lightest_one("disc", j, rho, d, 1.5, 2.0, math.inf, 0.5 * d)[2],
        32 * j / (math.pi * rho * (0.5 * d) ** 4),
        rtol=1e-14,
    )


def test_covers_only_mass_and_cost():
    for geometry in ("rim", "thin_rim", "disc"):
        assert batch.covers(geometry, "mass") and batch.covers(geometry, "cost", pinned=True)
        assert not batch.covers(geometry, "outer_diameter")


@pytest.mark.parametrize("thin", [True, False])
def test_newton_stops_when_its_step_is_an_ulp(thin, monkeypatch):
    """Away from the fold of J_line (J' <= 0.9 J_max) Newton converges quadratically:
    both the vectorized and the scalar root take at most 8 steps. (A last step of an
    ulp used to land on the bracket's edge and start a bisection of ~40 more.)"""
    rng = np.random.default_rng(5)
    n = 400
    rho, a, c = 7200.0, 1.5, 2.0
    cap = 10 ** rng.uniform(-1, 1, n)
    width = np.where(rng.random(n) < 0.6, np.inf, cap * 10 ** rng.uniform(-2, 0, n))
    geometry = "thin_rim" if thin else "rim"
    j_max = batch.max_inertia(geometry, rho, cap, a, c, width)
    j = j_max * 10 ** rng.uniform(-6, math.log10(0.9), n)
    monkeypatch.setattr(batch, "_NEWTON_MAX_ITER", 8)
    got = batch.lightest(geometry, j, rho, cap, a, c, width)
    assert got.feasible.all()
    for k in range(n):
        d, h, b = batch.lightest_one(geometry, j[k], rho, cap[k], a, c, width[k])
        assert_allclose(h, got.h[k], rtol=1e-13)
