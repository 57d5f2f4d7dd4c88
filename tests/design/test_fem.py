"""The axisymmetric FE check (flyopt.design.fem): the closed forms first, then the whole wheels' junctions.

References are independent of the FE model: the plane-stress closed forms of a rotating disc
(Timoshenko & Goodier, art. 32; flyopt.design.stress holds them) and the figures the issue prints,
the hoop-force balance of a ring (the mean hoop stress of a thin rim is rho v^2), and, for the
junction factors of the shipped wheels, the same model on a finer mesh (convergence shown).
"""

import dataclasses
import json
import math
import sys

import pytest
from conftest import PROBLEMS, assert_published

import flyopt
from flyopt.design import fem, stress
from flyopt.report.text import fem_verdict

#: The issue's disc: steel, R = 0.5 m, 3000 rpm.
RHO, NU, R, BORE_RADIUS = 7850.0, 0.3, 0.5, 0.05
OMEGA = 3000.0 * 2.0 * math.pi / 60.0

#: The disc's thickness: thin, so that the plane-stress closed forms hold (the axisymmetric body's
#: departure from plane stress goes as (t/R)^2, 1.6e-5 here).
THICKNESS = 0.002

#: The closed forms to 1e-3 relative (the issue's requirement).
CLOSED_FORM_RTOL = 1e-3

#: A finer mesh (size factor halved) changes each junction factor of a shipped wheel by less than this,
#: relatively. Measured from "normal" (0.5) to "fine" (0.25): 1.8 % (four-cylinder-engine's 5 mm hub-disc
#: fillet on a 280 mm wheel, the default high), 0.9 % (the arms variant), 0.4 % (punch-press-wheel).
JUNCTION_RTOL = 0.02
#: The last of three halvings ("fine" to "finer", 0.125) moves each factor by less than this (slow test).
#: Measured: 1.1 % (punch-press-wheel on arms: a 1.5 mm hub-arms fillet), 0.85 % (press-arms-wheel), 0.21 %
#: (the engine disc).
SETTLED_RTOL = 0.015
#: The default mesh's factor against the finest's. Measured: 2.0 % (the engine disc: 1.388 against 1.361).
DEFAULT_RTOL = 0.025


def _disc(bore_radius, size):
    return fem.solve_section(fem.Section((bore_radius, R), (THICKNESS,), ("disc",)), RHO, NU, OMEGA, size=size)


def _closed_forms():
    return {
        "centre": stress.solid_disc_centre_stress(R, RHO, NU, OMEGA),
        "bore_hoop": stress.annulus_bore_hoop_stress(BORE_RADIUS, R, RHO, NU, OMEGA),
        "radial_max": stress.annulus_max_radial_stress(BORE_RADIUS, R, RHO, NU, OMEGA),
    }


def _fe_values(size):
    solid, bored = _disc(0.0, size), _disc(BORE_RADIUS, size)
    return {
        "centre": float(solid.radial.max()),
        "bore_hoop": float(bored.hoop.max()),
        "radial_max": float(bored.radial.max()),
    }


def test_closed_forms_as_the_issue_prints_them():
    """79.90 MPa at the centre of the solid disc; 160.13 MPa hoop at the 0.05 m bore, 64.72 MPa radial maximum
    (the closed forms round to the issue's figures): the FE on the default mesh to 1e-3 of them (measured
    7e-6, 7e-6 and 1.1e-4; the bore's 160.13506 MPa prints as 160.14, 6.5e-6 above the closed form's 160.13402)."""
    exact, mine = _closed_forms(), _fe_values(fem.MESH_SIZES["normal"])
    assert_published(exact["centre"] / 1e6, "79.90")
    assert_published(exact["bore_hoop"] / 1e6, "160.13")
    assert_published(exact["radial_max"] / 1e6, "64.72")
    for name in exact:
        assert abs(mine[name] / exact[name] - 1.0) <= CLOSED_FORM_RTOL, (name, mine[name], exact[name])
    # the solid disc's centre is equibiaxial
    solid = _disc(0.0, fem.MESH_SIZES["normal"])
    assert abs(solid.hoop.max() / exact["centre"] - 1.0) <= CLOSED_FORM_RTOL


def test_closed_forms_converge_as_the_mesh_is_refined():
    """Halving the element size twice: every error falls each time, and the finest is within 1e-3
    (measured 2e-4, 3e-4 and 1e-3 at size 0.25)."""
    exact = _closed_forms()
    errors = {name: [] for name in exact}
    for size in (1.0, 0.5, 0.25):
        mine = _fe_values(size)
        for name in exact:
            errors[name].append(abs(mine[name] / exact[name] - 1.0))
    for name, e in errors.items():
        assert e[0] > e[1] > e[2], (name, e)
        assert e[2] <= CLOSED_FORM_RTOL / 3.0, (name, e)


def test_mean_hoop_of_a_thin_rim_is_rho_v_squared():
    """A thin free rim (H/D_m = 1 %): the FE's mean hoop stress over the section is rho v_m^2 to the
    thin-ring error (H/D_m)^2/3 (the exact balance gives rho omega^2 (a^2 + a b + b^2)/3), plus 1e-6."""
    a, b = 0.495, 0.505
    ring = fem.solve_section(fem.Section((a, b), (0.05,), ("rim",)), RHO, NU, OMEGA, size=fem.MESH_SIZES["normal"])
    v_mean = OMEGA * (a + b) / 2.0
    thin_ring = stress.thin_ring_hoop_stress(RHO, v_mean)
    assert abs(ring.mean_hoop() / thin_ring - 1.0) <= ((b - a) / (a + b)) ** 2 / 3.0 + 1e-6
    exact = RHO * OMEGA**2 * (a * a + a * b + b * b) / 3.0
    assert abs(ring.mean_hoop() / exact - 1.0) <= 1e-6


# ------------------------------------------------------------------------------------- whole wheels


def _designed(text=None):
    scene = flyopt.load(PROBLEMS / "punch-press-wheel.toml") if text is None else text
    design = flyopt.solve(scene).design
    assert design.status == "designed"
    best = design.best
    return best, scene.material_library()[best.material], design.omega * best.speed_ratio


@pytest.fixture(scope="module")
def web_wheel():
    """punch-press-wheel's design: hub, web, rim (the shipped whole wheel)."""
    return _designed()


@pytest.fixture(scope="module")
def arms_wheel(tmp_path_factory):
    """The same scene with arms (no shipped scene has rim_arms: this one stands in)."""
    path = tmp_path_factory.mktemp("arms") / "arms.toml"
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    path.write_text(text.replace('geometry = "rim_web"', 'geometry = "rim_arms"'), encoding="utf-8")
    return _designed(flyopt.load(path))


@pytest.fixture(scope="module")
def shipped_arms_wheel():
    """problems/press-arms-wheel.toml's design: the shipped wheel on arms."""
    return _designed(flyopt.load(PROBLEMS / "press-arms-wheel.toml"))


@pytest.fixture(scope="module")
def disc_on_hub():
    """problems/four-cylinder-engine.toml's design: the engine's disc on its keyed hub (design.disc_hub)."""
    return _designed(flyopt.load(PROBLEMS / "four-cylinder-engine.toml"))


SHIPPED = ["web_wheel", "arms_wheel", "shipped_arms_wheel", "disc_on_hub"]


@pytest.mark.parametrize(
    # the web wheel and the disc by default; the two arms wheels in the slow run, with the three-mesh test below
    "wheel",
    [w if w in ("web_wheel", "disc_on_hub") else pytest.param(w, marks=pytest.mark.slow) for w in SHIPPED],
)
def test_junction_factors_on_a_finer_mesh(wheel, request):
    """Each junction's factor on the default mesh and on one twice as fine differ by less than JUNCTION_RTOL."""
    design, material, omega = request.getfixturevalue(wheel)
    normal = fem.fem_check(design, material, omega, mesh="normal")
    fine = fem.fem_check(design, material, omega, mesh="fine")
    assert fine.elements > 1.5 * normal.elements
    assert normal.junctions and [j.name for j in normal.junctions] == [j.name for j in fine.junctions]
    for mine, finer in zip(normal.junctions, fine.junctions):
        assert abs(mine.factor / finer.factor - 1.0) <= JUNCTION_RTOL, (mine.name, mine.factor, finer.factor)
        assert mine.factor > 0.9, mine  # a junction never relieves the Lamé stress by much


@pytest.mark.slow
@pytest.mark.parametrize("wheel", SHIPPED)
def test_junction_factors_converge(wheel, request):
    """Three meshes, each twice as fine: the last halving moves each factor by less than SETTLED_RTOL, and
    the default mesh's factor is within DEFAULT_RTOL of the finest's. The factors do not settle
    monotonically (the peak is sampled in the fillet: 1.366, 1.363, 1.356 on punch-press-wheel's hub-web):
    they are known to about 1 %, which the report's three significant figures of a factor overstate by one."""
    design, material, omega = request.getfixturevalue(wheel)
    checks = [fem.fem_check(design, material, omega, mesh=mesh) for mesh in ("normal", "fine", "finer")]
    assert all(b.elements > 1.5 * a.elements for a, b in zip(checks, checks[1:])), [c.elements for c in checks]
    for default, fine, finest in zip(*(c.junctions for c in checks)):
        assert abs(fine.factor / finest.factor - 1.0) <= SETTLED_RTOL, (default.name, fine.factor, finest.factor)
        assert abs(default.factor / finest.factor - 1.0) <= DEFAULT_RTOL, (default.name, default.factor, finest)


def test_web_wheel_check_reads_the_design(web_wheel):
    """punch-press-wheel: hub, web and rim with their peaks; the 11 mm web meets the 66 mm hub in a
    default 5.5 mm fillet (said so) and the 13 mm rim in one the 1 mm step leaves room for (half the
    step: 0.5 mm), a mild corner (castability keeps the rim and web sections within 1.3)."""
    design, material, omega = web_wheel
    check = fem.fem_check(design, material, omega)
    assert [p.part for p in check.parts] == ["hub", "web", "rim"]
    assert [j.name for j in check.junctions] == ["hub-web", "web-rim"]
    hub_web, web_rim = check.junctions
    assert hub_web.fillet == pytest.approx(design.dims.t_web * fem.DEFAULT_FILLET_RATIO)
    step = (design.dims.b - design.dims.t_web) / 2.0  # the rim stands this far proud of the web, each side
    assert step > 0.0
    assert web_rim.fillet == pytest.approx(min(design.dims.t_web * fem.DEFAULT_FILLET_RATIO, step / 2.0))
    assert 1.0 < hub_web.factor < 3.0
    assert 1.0 < web_rim.factor < 1.5  # a shallow step: a mild concentration
    assert any("fillets not given" in note for note in check.notes)
    assert check.measure == "von_mises"  # a ductile iron
    # the junction peak sits in the fillet: within one fillet radius of it
    r_k, z_thin = hub_web.radius, design.dims.t_web / 2.0
    assert math.hypot(hub_web.fem_at[0] - r_k, hub_web.fem_at[1] - z_thin) <= 2.0 * hub_web.fillet
    # the FE's mean hoop stress of the section against the Lamé step model's (same load, same section)
    assert check.mean_hoop == pytest.approx(design.stresses.stress["mean_hoop"], rel=0.01)
    data = json.loads(json.dumps(check.to_dict()))
    assert data["junctions"][0]["name"] == "hub-web" and data["mesh"]["elements"] == check.elements
    assert data["difference"] == pytest.approx(check.peak / check.model_peak - 1.0)


def test_arms_wheel_is_said_to_be_an_equivalent_web(arms_wheel):
    design, material, omega = arms_wheel
    check = fem.fem_check(design, material, omega)
    assert [p.part for p in check.parts] == ["hub", "arms", "rim"]
    assert any("equivalent axisymmetric web" in note for note in check.notes)
    sec = fem.section(design)
    area = stress.arm_section_area(design.dims.arm_major, design.dims.arm_minor)
    web_mass = math.pi * sec.thicknesses[1] * (sec.radii[2] ** 2 - sec.radii[1] ** 2)
    arms_mass = design.n_arms * area * (sec.radii[2] - sec.radii[1])
    assert web_mass == pytest.approx(arms_mass, rel=1e-12)


def test_a_given_fillet_is_used(web_wheel):
    design, material, omega = web_wheel
    check = fem.fem_check(design, material, omega, fillet=0.002)
    assert check.junctions[0].fillet == 0.002
    assert not any("fillets not given" in note for note in check.notes)


def test_bad_mesh_is_refused(web_wheel):
    design, material, omega = web_wheel
    with pytest.raises(ValueError, match="mesh 'medium' not known: one of coarse, normal"):
        fem.fem_check(design, material, omega, mesh="medium")
    with pytest.raises(ValueError, match="must be > 0"):
        fem.fem_check(design, material, omega, mesh=0.0)


def test_missing_extra_is_refused_in_one_line(web_wheel, monkeypatch):
    design, material, omega = web_wheel
    monkeypatch.setitem(sys.modules, "skfem", None)
    with pytest.raises(ImportError, match=r"needs scikit-fem, a dependency of flyopt: pip install scikit-fem"):
        fem.fem_check(design, material, omega)


# --------------------------------------------------------------------- [design] fem_check = true


@pytest.fixture(scope="module")
def checked_solution(tmp_path_factory):
    """punch-press-wheel with ``fem_check = true``, solved once."""
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    assert "\n[design]\n" in text
    path = tmp_path_factory.mktemp("fem") / "checked.toml"
    path.write_text(text.replace("\n[design]\n", "\n[design]\nfem_check = true\n"), encoding="utf-8")
    return path, flyopt.solve(flyopt.load(path))


def test_solve_runs_the_check_on_the_best_design(checked_solution, web_wheel):
    """The scene key makes the solve check its best design, as fem_check itself does; without it, no check."""
    _, solution = checked_solution
    design, material, omega = web_wheel
    check = solution.design.fem
    assert check is not None and solution.design.spec.fem_check
    # within its allowables at the first design: accepted as it is, with no factor
    assert check.rounds == 1 and check.stress_factors == () and check.accepted_by == "fem"
    assert check.to_dict() == dataclasses.replace(fem.fem_check(design, material, omega), accepted_by="fem").to_dict()
    # without the key a whole wheel's solve reports the check and accepts nothing by it
    reported = flyopt.solve(flyopt.load(PROBLEMS / "punch-press-wheel.toml")).design.fem
    assert reported is not None and reported.accepted_by is None and reported.rounds == 1
    assert "accepted" not in fem_verdict(reported)


def test_solve_json_and_text_carry_the_check(checked_solution):
    import jsonschema

    from flyopt.outputs.documents import json_text, schema, solution_document
    from flyopt.outputs.quantities import has_unit
    from flyopt.report.text import design_report

    path, solution = checked_solution
    document = json.loads(json_text(solution_document(solution, str(path))))
    jsonschema.Draft202012Validator(schema()).validate(document)
    fem_json = document["design"]["fem"]
    assert fem_json["junctions"][0]["name"] == "hub-web"
    for name in ("peak", "fem_peak", "lame", "factor", "fem_at", "fillet", "utilisation", "difference"):
        assert has_unit(name) and name in document["units"], name
    text = "\n".join(design_report(solution.design))
    assert "FEM check" in text and "junction factors" in text and "hub-web 1.3" in text
    assert "the two models: FE peak" in text and "% above" in text
    assert "fillets not given by the design" in text


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
def test_the_report_shows_the_check_beside_the_lame_model(checked_solution, tmp_path):
    """The HTML report carries the check as the text does: the parts' peaks, the junctions and the difference."""
    import subprocess

    path, solution = checked_solution
    out = tmp_path / "checked.html"
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "report", str(path), "-o", str(out)], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    html = out.read_text(encoding="utf-8")
    assert "The second opinion: an axisymmetric FE model" in html and "Stress concentration at the junctions" in html
    check = solution.design.fem
    assert f"the FE is {100 * abs(check.difference):.1f} % above" in html
    assert f"{check.junctions[0].factor:.3f}" in html


def test_fem_check_key_must_be_a_boolean(write_scene):
    from flyopt.errors import SceneError

    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    path = write_scene(text.replace("\n[design]\n", '\n[design]\nfem_check = "yes"\n'))
    with pytest.raises(SceneError, match="design.fem_check.*must be true or false"):
        flyopt.load(path)


def test_the_rounded_wheel_is_the_one_checked(tmp_path):
    """With round_to, the check is of the wheel reported (rounded), not of the continuous optimum."""
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    path = tmp_path / "rounded.toml"
    path.write_text(text.replace("\n[design]\n", '\n[design]\nfem_check = true\nround_to = "1 mm"\n'), encoding="utf-8")
    scene = flyopt.load(path)
    result = flyopt.solve(scene).design
    best = result.best
    assert result.continuous is not None and best.dims.d_outer != result.continuous.dims.d_outer
    material = scene.material_library()[best.material]
    again = fem.fem_check(best, material, result.omega * best.speed_ratio)
    assert result.fem.to_dict() == dataclasses.replace(again, accepted_by="fem").to_dict()


# ------------------------------------------------ accepted against the larger of the FE and the model


def _derated_scene(tmp_path, safety_factor, materials='["gjs_keyed"]', fem_check=True, process=None, edits=()):
    """punch-press-wheel on one material at a safety factor where the stress binds (process: the
    castability process named in [design], None: the material's; edits: (old, new) texts replaced)."""
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    old_materials = 'materials = ["en_gjl_250", "en_gjs_400_18", "gjs_keyed"]'
    assert old_materials in text and "safety_factor = 5\n" in text
    text = text.replace(old_materials, f"materials = {materials}").replace(
        "safety_factor = 5\n", f"safety_factor = {safety_factor}\n"
    )
    if fem_check:
        text = text.replace("\n[design]\n", "\n[design]\nfem_check = true\n")
    if process is not None:
        text = text.replace("\n[design]\n", f'\n[design]\nprocess = "{process}"\n')
    path = tmp_path / f"derated-{safety_factor}-{fem_check}-{process}.toml"
    path.write_text(text, encoding="utf-8")
    return flyopt.load(path)


@pytest.mark.slow  # 3 s: repeated FE solves; the FE check itself is tested by default
def test_a_wheel_the_fe_rejects_is_designed_again_until_the_fe_accepts_it(tmp_path):
    """At a safety factor of 20 the web's Lamé stress is within its allowable but the FE peak at the hub-web
    junction is 12.7 % over it: the acceptance divides the web's allowable by the concentration the FE found
    and designs again, until the FE peak is within. The accepted wheel is heavier, its web's model stress
    times the factor is within the material's allowable, and a finer mesh agrees that it is within.
    Without castability (process "none"): ductile iron's section ratio makes a web thick enough that the FE
    accepts it at this factor, and the loop is tested on the wheel where one part alone is over."""
    first = flyopt.solve(_derated_scene(tmp_path, 20, fem_check=False, process="none")).design
    scene = _derated_scene(tmp_path, 20, process="none")
    material = scene.material_library()["gjs_keyed"]
    plain = fem.fem_check(first.best, material, first.omega * first.best.speed_ratio)
    web = next(p for p in plain.parts if p.part == "web")
    assert web.utilisation > 1.05 and web.model_stress < web.allowable  # the model alone accepts it, the FE not
    result = flyopt.solve(scene).design
    check, best = result.fem, result.best
    assert check.accepted_by == "fem" and check.rounds >= 2
    factors = dict(check.stress_factors)
    assert set(factors) == {"web"} and factors["web"] > web.ratio > 1.0
    assert best.mass > first.best.mass * 1.02
    # the design's own allowable of the web is the material's divided by the factor: the model times it within
    allowable = material.allowable(safety_factor=20)
    model_web = next(p for p in best.stresses.stress["parts"] if p["part"] == "web")
    assert model_web["allowable"] == pytest.approx(allowable / factors["web"], rel=1e-12)
    assert model_web["stress"] * factors["web"] <= allowable * (1.0 + 1e-9)
    # the FE peaks, on this mesh and on a finer one, are within the material's allowable
    for mesh, slack in (("normal", fem.ACCEPT_RTOL), ("fine", 1e-2)):
        again = fem.fem_check(best, material, result.omega * best.speed_ratio, mesh=mesh, stress_factors=factors)
        assert all(p.utilisation <= 1.0 + slack for p in again.parts), (mesh, [p.utilisation for p in again.parts])
    text = fem_verdict(check)
    assert "accepted against the larger" in text and f"web's divided by {factors['web']:.3f}" in text


def test_a_combination_the_fe_rejects_gives_way_to_one_it_accepts(tmp_path):
    """At a safety factor of 40 the lightest wheel (on the motor shaft) has a hub 57 % over its allowable by
    FE; with the FE's concentration on it, the intermediate shaft's wheel is lighter, and the FE accepts it
    as it is: the accepted design carries no factor of its own. The intermediate seat is 80 mm here: on the
    scene's 70 mm one no key of at most 1.5 d carries the wheel's torque at the hub's 90 MPa."""
    seat = (('diameter = "70 mm"', 'diameter = "80 mm"'),)
    first = flyopt.solve(_derated_scene(tmp_path, 40, fem_check=False, edits=seat)).design
    result = flyopt.solve(_derated_scene(tmp_path, 40, edits=seat)).design
    assert first.best.shaft == "motor" and result.best.shaft != "motor"
    assert result.fem.rounds >= 2 and result.fem.stress_factors == ()
    assert result.fem.within_allowable
    motor = [f for f in result.spec.stress_factors if f.shaft == "motor"]
    assert motor and all(f.factor > 1.0 for f in motor)


@pytest.mark.parametrize(
    "line, words",
    [
        ('disc_hub = "yes"', "design.disc_hub: must be true or false"),
        ("disc_hub = true", 'design.disc_hub: is for geometry = "disc"'),
    ],
)
def test_disc_hub_is_a_boolean_of_discs_refused_in_one_line(main_cli, tmp_path, line, words):
    """A disc_hub that is not a boolean, or on a web wheel (which has its hub anyway): exit 2, one line."""
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    assert "\n[design]\n" in text
    path = tmp_path / "scene.toml"
    path.write_text(text.replace("\n[design]\n", f"\n[design]\n{line}\n"), encoding="utf-8")
    status, stdout, stderr = main_cli("solve", path)
    assert status == 2 and stdout == "" and words in stderr and len(stderr.strip().splitlines()) == 1, stderr


@pytest.mark.parametrize(
    "section",
    [
        fem.Section((0.0, R), (THICKNESS,), ("disc",)),  # solid: quadrature points come close to the axis
        fem.Section((0.04, 0.07, 0.36, 0.42), (0.09, 0.025, 0.12), ("hub", "web", "rim")),  # steps and fillets
    ],
    ids=["solid-disc", "hub-web-rim"],
)
def test_the_stiffness_is_the_one_skfems_generic_assembly_gives(section):
    """fem.stiffness_matrix (every element at once, by einsum) against scikit-fem's own assembly of the
    axisymmetric elasticity integrand, written here from the textbook (eps_rr = du_r/dr, eps_tt = u_r/r,
    eps_zz = du_z/dz, gamma_rz = du_r/dz + du_z/dr; sigma = lam tr(eps) I + 2 mu eps; dV ~ r dA; u[0] is u_r)."""
    import skfem

    points, triangles = fem.section_mesh(section, fem.MESH_SIZES["normal"])
    basis = skfem.Basis(skfem.MeshTri(points, triangles), skfem.ElementVector(skfem.ElementTriP2()), intorder=4)
    e_modulus, nu = 1.7e11, 0.27
    lam, mu = e_modulus * nu / ((1 + nu) * (1 - 2 * nu)), e_modulus / (2 * (1 + nu))

    @skfem.BilinearForm
    def textbook(u, v, w):
        r = w.x[0]
        e_u = (u.grad[0, 0], u[0] / r, u.grad[1, 1], u.grad[0, 1] + u.grad[1, 0])
        e_v = (v.grad[0, 0], v[0] / r, v.grad[1, 1], v.grad[0, 1] + v.grad[1, 0])
        trace = e_u[0] + e_u[1] + e_u[2]
        return (sum((lam * trace + 2 * mu * e_u[k]) * e_v[k] for k in range(3)) + mu * e_u[3] * e_v[3]) * r

    expected = textbook.assemble(basis)
    found = fem.stiffness_matrix(basis, lam, mu)
    difference = abs(found - expected).max()
    assert difference <= 1e-13 * abs(expected).max(), difference
    assert found.shape == (basis.N, basis.N)
    # and not a matrix that merely resembles it: symmetric, as the integrand is
    assert abs(found - found.T).max() <= 1e-13 * abs(expected).max()
