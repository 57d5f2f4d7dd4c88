"""One rule for a material's safe rim speed, on every path (issue 24).

The case of the issue: a material given by its strength with its own safety
factor 5, designed with ``[design] safety_factor = 2`` under the textbook
rim-speed criterion. The design's own factor wins over the material's
(``Material.allowable``, ``DesignSpec.safety_factor``), so the limit is the
thin-ring hoop stress at R_m / 2:

    sigma = rho v^2  (docs/flywheel-design.md, section 10)  =>  v_max = sqrt(R_m / (S rho)),

131.76 m/s for R_m 250 MPa, rho 7200 kg/m^3, S = 2 (the material's own
factor 5 would give 83.33 m/s). Before the one rule, ``solve``, ``sweep``,
``tradeoff`` and ``pareto`` used 83.33 m/s and the drive's relaxation too.
Every path must give the same limit, and the design the limit implies: the
lightest rim of a rim-speed design sits at the cap D = 2 v_max / omega_max.
"""

import math

import pytest
from numpy.testing import assert_allclose

import flyopt
from flyopt.report.display import DEFAULT
from flyopt.report.text import design_report, formatters
from flyopt.studies.pareto import pareto
from flyopt.studies.tradeoff import material_tradeoff

R_M = 250e6  # [Pa] tensile strength of the user's grey iron
RHO = 7200.0  # [kg/m^3]
MATERIAL_FACTOR = 5.0
DESIGN_FACTOR = 2.0
#: sigma = rho v^2 at the design's allowable R_m / S (the design's factor wins)
V_DESIGN = math.sqrt(R_M / DESIGN_FACTOR / RHO)
V_MATERIAL = math.sqrt(R_M / MATERIAL_FACTOR / RHO)
#: Two computations of the same closed form or of IPOPT's optimum at an active bound: round-off only.
RTOL = 1e-12
RTOL_IPOPT = 1e-8


def _scene(design_factor=DESIGN_FACTOR, materials=("strong_iron",)):
    """Worked example 1 (A_max 1600 J, 1500 rpm, delta 0.02) with the issue's material."""
    design = {"criterion": "rim_speed", "geometry": "rim", "materials": list(materials)}
    if design_factor is not None:
        design["safety_factor"] = design_factor
    return flyopt.from_dict(
        {
            "title": "rim speed rule",
            "machine": {"speed": "1500 rpm", "delta": 0.02},
            "torque": {"net": {"areas": ["1500 J", "-1000 J", "400 J", "-1000 J", "100 J"]}},
            "design": design,
            "material": [
                {
                    "name": "strong_iron",
                    "density": f"{RHO} kg/m^3",
                    "tensile_strength": f"{R_M / 1e6} MPa",
                    "ductile": False,
                    "safety_factor": MATERIAL_FACTOR,
                    "elastic_modulus": "100 GPa",
                    "poisson_ratio": 0.26,
                }
            ],
        }
    )


SCENE = _scene()


def _omega_max(scene):
    return scene.omega_mean * (1.0 + scene.delta / 2.0)


def test_the_numbers_of_the_issue():
    assert_allclose([V_DESIGN, V_MATERIAL], [131.762, 83.333], rtol=1e-5)


@pytest.mark.parametrize("method", ["auto", "ipopt"])
def test_solve_takes_the_designs_factor(method):
    best = flyopt.solve(SCENE, design_method=method).design.best
    assert best.material == "strong_iron"
    assert_allclose(best.limits.rim_speed_limit, V_DESIGN, rtol=RTOL)
    assert "rim_speed" in best.limits.binding
    rtol = RTOL if method == "auto" else RTOL_IPOPT
    assert_allclose(best.stresses.rim_speed, V_DESIGN, rtol=rtol)
    assert_allclose(best.dims.d_outer, 2.0 * V_DESIGN / _omega_max(SCENE), rtol=rtol)


def test_without_a_design_factor_the_materials_own_applies():
    best = flyopt.solve(_scene(design_factor=None)).design.best
    assert_allclose(best.limits.rim_speed_limit, V_MATERIAL, rtol=RTOL)
    assert_allclose(best.dims.d_outer, 2.0 * V_MATERIAL / _omega_max(SCENE), rtol=RTOL)


def test_a_textbook_speed_limit_is_not_changed_by_the_designs_factor():
    """Cast iron's 36 m/s is a speed, not a strength: no factor divides it."""
    result = flyopt.solve(_scene(materials=("cast_iron", "strong_iron"))).design
    limits = {c.material: c.limits.rim_speed_limit for c in result.candidates}
    assert limits["cast_iron"] == 36.0
    assert_allclose(limits["strong_iron"], V_DESIGN, rtol=RTOL)


@pytest.mark.parametrize("method", ["auto", "ipopt"])
def test_sweep_takes_the_designs_factor(method):
    deltas = [0.01, 0.02, 0.05]
    frame = flyopt.sweep(SCENE, {"delta": deltas}, workers=1, method=method)
    assert list(frame["status"]) == ["designed"] * len(deltas)
    assert_allclose(frame["rim_speed_limit"], V_DESIGN, rtol=RTOL)
    rtol = RTOL if method == "auto" else RTOL_IPOPT
    for row in frame.to_dict("records"):
        scene = SCENE.replace(delta=row["delta"])
        assert_allclose(row["d_outer"], 2.0 * V_DESIGN / _omega_max(scene), rtol=rtol)
        assert_allclose(row["mass"], flyopt.solve(scene).design.best.mass, rtol=rtol)


def test_sweep_of_the_density_keeps_the_rule():
    """The design's factor over a swept density: v_max = sqrt(R_m / (S rho)) at each point's rho."""
    densities = [7000.0, 7400.0]
    frame = flyopt.sweep(SCENE, {"material.strong_iron.density": densities}, workers=1)
    expected = [math.sqrt(R_M / DESIGN_FACTOR / rho) for rho in frame["material.strong_iron.density"]]
    assert sorted(frame["material.strong_iron.density"]) == densities
    assert_allclose(frame["rim_speed_limit"], expected, rtol=RTOL)


def test_tradeoff_takes_the_designs_factor():
    row = material_tradeoff(SCENE).set_index("material").loc["strong_iron"]
    assert row["status"] == "designed"
    assert_allclose([row["rim_speed_limit"], row["rim_speed"]], [V_DESIGN, V_DESIGN], rtol=RTOL)
    assert_allclose(row["d_outer"], 2.0 * V_DESIGN / _omega_max(SCENE), rtol=RTOL)


def test_pareto_takes_the_designs_factor():
    """The lightest end of the mass / outer diameter front is the wheel at its rim-speed cap."""
    front = pareto(SCENE, "mass,outer_diameter", points=4)
    assert_allclose(front["rim_speed_limit"], V_DESIGN, rtol=RTOL)
    cap = 2.0 * V_DESIGN / _omega_max(SCENE)
    assert front["outer_diameter"].max() <= cap * (1 + 1e-9)
    assert_allclose(front["outer_diameter"].iloc[-1], cap, rtol=RTOL_IPOPT)
    assert_allclose(front["mass"].iloc[-1], flyopt.solve(SCENE).design.best.mass, rtol=RTOL_IPOPT)


def test_the_drive_relaxation_takes_the_designs_factor():
    from flyopt.drive.relaxation import RelaxedWheel

    material = SCENE.material_library()["strong_iron"]
    wheel = RelaxedWheel.of(material, SCENE.design)
    assert_allclose(wheel.v_max, V_DESIGN, rtol=RTOL)
    assert_allclose(wheel.problem.max_rim_speed, V_DESIGN, rtol=RTOL)


def test_the_report_states_the_designs_limit():
    result = flyopt.solve(SCENE).design
    q, _n = formatters(DEFAULT)
    text = "\n".join(design_report(result))
    assert f"(limit {q(V_DESIGN, 'rim_speed_limit')})" in text
    assert q(V_DESIGN, "rim_speed_limit") != q(V_MATERIAL, "rim_speed_limit")
