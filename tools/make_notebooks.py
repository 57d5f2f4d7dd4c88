"""Write the notebooks of notebooks/ from the cells below (then execute them with nbmake).

Keeping the source here makes the notebooks reviewable as Python; run
`python tools/make_notebooks.py` after editing, then
`python -m pytest --nbmake notebooks --overwrite` to store their outputs.

Each notebook states its question, tells the engineering story cell by cell
and ends with conclusions built from the computed values (a final cell that
writes them as Markdown), so that they cannot go stale; a number typed in the
text is checked by an assert in the notebook. Only the public API is used:
what ``flyopt`` exports (``to_units``, ``read_results``, a design's
``to_frame``), the plots of ``flyopt.report.plots`` and the display units of
``flyopt.report.display``.
"""

import sys
from pathlib import Path

import nbformat as nbf

HERE = Path(__file__).resolve().parents[1] / "notebooks"


def notebook(cells):
    nb = nbf.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.cells = [nbf.v4.new_markdown_cell(text) if kind == "md" else nbf.v4.new_code_cell(text) for kind, text in cells]
    return nb


#: Every notebook's table helpers: flyopt.to_units (the engineer's units of flyopt.report.display, each
#: quantity's dimension from flyopt's one table of output fields), so that no printed number goes without its unit.
UNITS_HELPER = '''
import pandas as pd
from flyopt.report import display

SYSTEM = "engineering"     # what people read: mm, rpm, kN·m, kJ, MPa (flyopt.report.display)
pd.set_option("display.float_format", "{:.4g}".format)     # four significant digits in every table


def in_units(frame):
    """The table in the engineer's units, each quantity's unit in its column's name (flyopt.to_units)."""
    return flyopt.to_units(frame, SYSTEM, labels=True)


def text(value, dimension, digits=4, system=SYSTEM):
    """A number with its unit, e.g. "616.9 mm"."""
    return display.quantity_text(value, dimension, system, digits)
'''.strip()


DESIGN_STUDY = [
    (
        "md",
        """# 01 · Design study: the lightest flywheel for a slider-crank press

**The question.** A mechanical press (`problems/slider-crank-press.toml`): an electric motor drives
the crankshaft through a 12 : 1 reduction, and the crank drives a 400 kg ram through a slider-crank
at 120 strokes/min. The working force acts near the end of the down-stroke. *What is the
lightest flywheel that keeps the speed fluctuation within the allowed δ = 0.15, on which shaft should
it sit, and does the machine with that flywheel really run within δ?*

**The way there** (each step cites the project's engineering notes, `docs/flywheel-design.md`):

1. reduce the press to the crankshaft and balance the work of one cycle (sections 3 and 4);
2. read A_max from the energy indicator diagram (section 4);
3. size the flywheel with the model that is exact for this machine (sections 5 and 6);
4. design a rim on every material × shaft and choose the lightest (sections 8–10);
5. check the winner with the textbook's closed forms, and simulate the machine with it (section 7);
6. conclude.""",
    ),
    (
        "code",
        """%matplotlib inline
from pathlib import Path
import math
import numpy as np
import flyopt
from flyopt.report import plots

"""
        + UNITS_HELPER
        + """


ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
scene = flyopt.load(ROOT / "problems" / "slider-crank-press.toml")

# the question's figures are the scene's
assert scene.delta == 0.15 and math.isclose(display.show(scene.omega_mean, "angular_speed"), 120)
assert {m.name: m.mass for m in scene.members}["ram"] == 400
assert {s.name: s.speed_ratio for s in scene.shafts}["motor"] == 12
print(scene.title)
print(f"mean crank speed {text(scene.omega_mean, 'angular_speed')}, allowed δ {scene.delta}, "
      f"constant inertia J_c {text(scene.j_constant, 'inertia')} at the crankshaft")
in_units(pd.DataFrame([{"shaft": s.name, "speed_ratio": s.speed_ratio, "efficiency": s.efficiency}
                       for s in scene.shafts]).set_index("shaft"))""",
    ),
    (
        "md",
        """## 1. Analyse the cycle

The ram's mass makes the equivalent inertia J_e(φ) vary with the crank angle (section 3), so the
textbook constant-inertia formula J_F = A_max/(ω_m² δ) − J_c (section 5) is only an approximation.
flyopt chooses the cheapest model that is exact for the scene and says why:""",
    ),
    (
        "code",
        """analysis = flyopt.analyse(scene, extras=("models", "speed"))  # the comparison of models, ω(φ): read below
print(f"model: {analysis.model} — {analysis.model_reason}")
print(f"driving torque M_d = {text(analysis.driving_torque, 'torque')} (from the work balance, section 4)")
print(f"power {text(analysis.power, 'power')} at the crank, {text(analysis.motor_power, 'power')} at the motor")
print(f"A_max = {text(analysis.a_max, 'energy')}, J_F = {text(analysis.j_required, 'inertia')} at the crankshaft")""",
    ),
    (
        "md",
        """## 2. The turning-moment diagram

The resisting torque is the friction plus the ram's working force reduced through the slider-crank's
exact kinematics (section 3); the driving torque is the constant that balances the cycle. The shaded
areas are the surplus (green) and deficit (red) of work between the crossings. The marks show where
the *speed* is highest and lowest with the required flywheel: ω_max sits at the start of the working
stroke, where the surplus ends, but ω_min does not sit where the deficit ends — see below the
diagram.""",
    ),
    ("code", "plots.plot_turning_moment(scene, analysis);"),
    (
        "code",
        """angles = pd.DataFrame(
    {"angle": [analysis.angle_delta_e_max, analysis.angle_delta_e_min,
               analysis.angle_omega_max, analysis.angle_omega_min]},
    index=["ΔE largest (end of the surplus)", "ΔE smallest (end of the deficit)",
           "ω largest (this model)", "ω smallest (this model)"])
assert analysis.angle_omega_max == analysis.angle_delta_e_max                      # as the text says
assert abs(analysis.angle_omega_min - analysis.angle_delta_e_min) > math.radians(10)
in_units(angles)""",
    ),
    (
        "md",
        """With a constant inertia the speed would be extreme where the excess work ΔE is (section 4). Here
the kinetic energy is E = ½ J_e(φ) ω², and J_e(φ) grows while the ram speeds up on its return stroke.
After the working stroke the surplus refills E only slowly, and the speed keeps falling as long as
J_e grows faster, relatively, than E: ω is lowest where J_e′/J_e = E′/E, late in the return stroke and
not at the end of the deficit. Section 6 says the same graphically: the speed extremes are the
tangent points of the energy–mass diagram, not the extremes of ΔE.

## 3. Energy indicator and energy–mass diagrams

The energy indicator diagram chains the areas head to tail; A_max is its largest vertical span
(section 4):""",
    ),
    ("code", "plots.plot_energy(scene, analysis);"),
    (
        "md",
        """Wittenbauer's energy–mass diagram plots ΔE against J_e over the cycle. The flywheel J_F moves the
true origin to (−J_F, −E_0); from there the tangents to the curve have slopes ω_max²/2 and
ω_min²/2 (section 6). This closed form is exact for a variable inertia and torques of the angle:""",
    ),
    ("code", "plots.plot_energy_mass(scene, analysis);"),
    (
        "md",
        """How far off would the textbook constant-inertia method be? flyopt sizes the flywheel by every
applicable model and simulates the δ each one really gives (section 5 with the cycle mean of J_e in
place of J_c):""",
    ),
    (
        "code",
        """models = pd.DataFrame(analysis.models).set_index("model")
table = in_units(models[["exact", "j_required", "achieved_delta"]])
table["J_F off by [%]"] = 100 * models["j_error"]
table""",
    ),
    (
        "md",
        """## 4. The design

Every material × shaft combination gets the lightest rim within the envelope, the H/B range and the
rim speed limit of its material (sections 9 and 10): an exact closed form where one exists
(IPOPT takes the structures it does not cover), and a closed form proves the combinations that cannot
give the inertia infeasible. On a shaft that turns i times faster than the crank the flywheel needs
only J_F/i² (section 8).""",
    ),
    (
        "code",
        """solution = flyopt.solve(scene, verify_design=True)
solution      # its answer card: the answer of the text report (flyopt solve), as a table""",
    ),
    (
        "code",
        """best = solution.design.best
candidates = solution.design.to_frame()      # the ranking: every material × shaft, SI, units in attrs
in_units(candidates[["material", "shaft", "speed_ratio", "feasible", "mass", "d_outer", "d_inner",
                     "b", "h", "rim_speed", "binding"]])""",
    ),
    (
        "md",
        """The motor shaft wins by far. Before trusting it, check the winner with the textbook's closed forms,
written here independently of flyopt's code: the inertia on its shaft (section 8), the exact annulus
J = m (D_1² + D_2²)/8 and m = ρ π (D_1² − D_2²) B/4 (section 9), and the rim speed
v = i ω_max D_1/2 with ω_max = ω_m (1 + δ/2) (section 10):""",
    ),
    (
        "code",
        """rho = scene.material_library()[best.material].density
omega_max = scene.omega_mean * (1 + scene.delta / 2)
checks = pd.DataFrame({
    "flyopt": [best.limits.j_required_on_shaft, best.j_flywheel, best.mass, best.stresses.rim_speed],
    "closed form": [analysis.j_required / best.speed_ratio**2,
                    best.mass * (best.dims.d_outer**2 + best.dims.d_inner**2) / 8,
                    rho * math.pi * (best.dims.d_outer**2 - best.dims.d_inner**2) * best.dims.b / 4,
                    best.speed_ratio * omega_max * best.dims.d_outer / 2]},
    index=["J' = J_F/i² [kg·m²]", "J = m (D_1² + D_2²)/8 [kg·m²]", "m = ρπ(D_1² − D_2²)B/4 [kg]",
           "v = i ω_max D_1/2 [m/s]"])
checks["relative difference [-]"] = checks["flyopt"] / checks["closed form"] - 1
assert (checks["relative difference [-]"].abs() < 1e-12).all()
checks""",
    ),
    (
        "md",
        """The section of the winner. Note what it is: the *rim alone* (the scene's geometry is `rim`), a
thin ring at the rim speed limit. The hub and the arms or web it needs, and the belt and gears that
now carry the flywheel's fluctuating torque between motor and crank (section 8), are not in this
mass; `geometry = "rim_web"` or `"rim_arms"` designs the whole wheel (section 13).""",
    ),
    ("code", "plots.plot_cross_section(best);"),
    (
        "md",
        """## 5. Verification: simulate the machine with the flywheel

The energy–mass method is exact for this machine, so the periodic solution of the equation of motion
d(½ J_e ω²)/dφ = M_d − M_r (section 7), integrated with the chosen flywheel, must give the allowed δ.
The simulation is drawn over the model's speed curve:""",
    ),
    (
        "code",
        """v = solution.verification
print(f"{v.method}: achieved δ = {v.achieved_delta:.6f} (allowed {v.delta_allowed}, tolerance {v.tolerance:.1e})")
assert not v.flagged
plots.plot_speed(scene, analysis, analysis.speed_curve(), simulation=v.solution);""",
    ),
    ("md", "## Conclusions"),
    (
        "code",
        """from IPython.display import Markdown

energy = models.loc["energy"]
crank = candidates[(candidates["shaft"] == "crankshaft") & candidates["feasible"]].sort_values("mass").iloc[0]
assert best.shaft == "motor" and best.speed_ratio == 12 and "rim_speed" in best.limits.binding
Markdown(f\"\"\"
- **The model.** The ram makes J_e(φ) vary, so flyopt sized the flywheel with the exact
  `{analysis.model}` model: A_max = {text(analysis.a_max, "energy")} and J_F =
  {text(analysis.j_required, "inertia")} at the crankshaft. The textbook constant-inertia method would
  ask for {text(energy.j_required, "inertia")} ({100 * energy.j_error:+.1f} %), a flywheel that gives
  δ = {energy.achieved_delta:.4f} instead of {scene.delta}: safe, but not the lightest.
- **Where the speed dips.** ω_max is at {text(analysis.angle_omega_max, "angle")}, where the surplus
  ends, but ω_min is at {text(analysis.angle_omega_min, "angle")}, not at the end of the deficit
  ({text(analysis.angle_delta_e_min, "angle")}): with a variable inertia the speed extremes are the
  tangent points of the energy–mass diagram.
- **The lightest flywheel** is a {best.material.replace("_", " ")} rim on the {best.shaft} shaft:
  {text(best.mass, "mass")}, D_outer {text(best.dims.d_outer, "length")}, B {text(best.dims.b, "length")} ×
  H {text(best.dims.h, "length")}, at its rim speed limit of {text(best.stresses.rim_speed, "speed")}. The motor shaft
  turns {best.speed_ratio:g} times faster than the crank, so it needs only J_F/{best.speed_ratio**2:g} =
  {text(best.limits.j_required_on_shaft, "inertia")}; the lightest rim on the crankshaft weighs
  {text(crank["mass"], "mass")} ({crank["mass"] / best.mass:.0f} times as much) at the
  {text(crank["d_outer"], "length")} envelope.
- **Checked.** Its inertia, mass and rim speed agree with the textbook closed forms to
  {checks["relative difference [-]"].abs().max():.1e}, and the simulated machine runs at
  δ = {v.achieved_delta:.6f} against the allowed {v.delta_allowed}.
- **Before building it.** This is the rim alone; the hub, arms or web, and the belt and gears that carry
  the flywheel's torque on the motor side, come next (a `rim_web` or `rim_arms` design, section 13).
  A wheel on the crankshaft spares the transmission that torque, at {crank["mass"] / best.mass:.0f}
  times the mass.
\"\"\")""",
    ),
]

TRADE_OFF = [
    (
        "md",
        """# 02 · Material trade-off: which material, on which shaft, for the punch press

**The question.** The punch press of `problems/punch-press.toml` runs at 60 strokes/min. Its flywheel
may sit on the crankshaft, on the intermediate shaft (6 × crank speed) or on the motor shaft
(24 ×), within a 1.2 m envelope and 0.2 m width. Three materials are offered: the built-in cast iron
and cast steel, and the scene's own ductile iron. *Which material gives the lightest flywheel and
which the cheapest, on which shaft, and how does the answer change with the crank speed?*

**The way there:** the materials' limits (section 10 of `docs/flywheel-design.md`); the best design of
each material at the nominal speed (sections 8–10); a sweep over the crank speed; illustrative prices
and the lightest against the cheapest; the mass–cost Pareto front where they disagree; conclusions.""",
    ),
    (
        "code",
        """%matplotlib inline
from dataclasses import replace
from pathlib import Path
import math
import numpy as np
import matplotlib.pyplot as plt
from matplotlib import ticker
import flyopt

"""
        + UNITS_HELPER
        + """


ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
scene = flyopt.load(ROOT / "problems" / "punch-press.toml")
shafts = {s.name: s.speed_ratio for s in scene.shafts}
assert math.isclose(display.show(scene.omega_mean, "angular_speed"), 60)
assert shafts == {"crankshaft": 1, "intermediate": 6, "motor": 24}
assert scene.design.max_outer_diameter == 1.2 and scene.design.max_width == 0.2
print(f"{scene.title}: δ = {scene.delta}, A_max does not depend on the material")""",
    ),
    (
        "md",
        """## 1. The materials

A rotating thin ring carries the hoop stress σ ≈ ρ v², so each material has a safe rim speed
(section 10): cast iron 36 m/s and cast steel 50 m/s by the textbook, and the ductile iron's from its
allowable stress, v_max = √(σ/ρ). Checked here against that formula:""",
    ),
    (
        "code",
        """library = scene.material_library()
names = list(scene.design_materials)
materials = pd.DataFrame({"density": [library[n].density for n in names],
                          "rim_speed_limit": [library[n].max_rim_speed for n in names],
                          "allowable_stress": [library[n].allowable_stress for n in names]}, index=names)
ductile = library["ductile_iron"]
assert library["cast_iron"].max_rim_speed == 36 and library["cast_steel"].max_rim_speed == 50      # section 10
assert materials["density"].idxmax() == materials["rim_speed_limit"].idxmax() == "cast_steel"   # densest and fastest
assert math.isclose(ductile.max_rim_speed, math.sqrt(ductile.allowable_stress / ductile.density), rel_tol=1e-12)
in_units(materials)""",
    ),
    (
        "md",
        """## 2. At the nominal speed

The best design of each material, any shaft:""",
    ),
    (
        "code",
        """nominal = flyopt.material_tradeoff(scene)
in_units(nominal[["material", "shaft", "mass", "d_outer", "d_mean", "b", "h", "rim_speed", "rim_speed_limit",
                  "binding"]])""",
    ),
    (
        "md",
        """Every material goes to the fast motor shaft and runs at its rim speed limit. For a given inertia a
larger diameter means less mass (J ∝ m D², section 9), and the rim speed caps the diameter at
D = 2 v_max/(i ω_max). For a thin ring that gives m = 4J/D² = J i² ω_max²/v_max² = J_F ω_max²/v_max²:
the lightest rim scales like 1/v_max², whatever the shaft beyond the one where the rim speed first
binds (section 14). The material with the highest permissible speed wins although it is the densest.

A real rim is not thin: the H/B range fixes its width against its thickness, and a smaller wheel must
be thicker. Its inner diameter falls, and an annulus with a small bore stores less per kilogram
(J = m (D_1² + D_2²)/8). So the slower materials lose more than (v_steel/v)² suggests:""",
    ),
    (
        "code",
        """by_material = nominal.set_index("material")
d_inner = by_material["d_mean"] - by_material["h"]                  # D_2 = D_m − H (section 9)
ratios = pd.DataFrame({
    "D_2/D_1 [-]": d_inner / by_material["d_outer"],
    "thin-ring mass ratio to steel (v_steel/v)² [-]":
        (by_material.loc["cast_steel", "rim_speed_limit"] / by_material["rim_speed_limit"])**2,
    "mass ratio to steel [-]": by_material["mass"] / by_material.loc["cast_steel", "mass"]})
assert (ratios["mass ratio to steel [-]"] >= ratios["thin-ring mass ratio to steel (v_steel/v)² [-]"] - 1e-12).all()
ratios""",
    ),
    (
        "md",
        """## 3. Across crank speeds

The crank speed moves every shaft's speed with it (the ratios are fixed). Sweep it from 20 to 120 rpm in
steps of 5 rpm for each material; at each point the design chooses the material's best shaft:""",
    ),
    (
        "code",
        """import tempfile
folder = tempfile.TemporaryDirectory()                # removed when the kernel stops
STUDY = Path(folder.name) / "speeds.parquet"          # the sweep's file, as `flyopt sweep -o` writes it
flyopt.sweep(scene, {"speed": "20:120:21rpm", "material": names}, workers=1, output=STUDY)
study = flyopt.read_results(STUDY)                     # in SI, as computed; the crank speed back in rpm, as given:
given = flyopt.read_results(STUDY, columns=["speed"], units="input")
assert given.attrs["flyopt"]["units"]["speed"] == "rpm" and (study["status"] == "designed").all()
rpm = given.attrs["flyopt"]["units"]["speed"]
study["rpm"] = given["speed"].round(9)
assert np.allclose(np.sort(study["rpm"].unique()), np.arange(20, 121, 5))

fig, ax = plt.subplots(figsize=(9, 4.8), layout="constrained")
markers = {"motor": "o", "intermediate": "s", "crankshaft": "^"}
for k, material in enumerate(names):
    part = study[study["material"] == material]
    ax.plot(part["rpm"], part["mass"], "-", color=f"C{k}", lw=1.2, label=material.replace("_", " "))
    for shaft, points in part.groupby("best_shaft"):
        ax.plot(points["rpm"], points["mass"], markers[shaft], color=f"C{k}", ms=5,
                mfc=f"C{k}" if shaft == "motor" else "white")
for shaft in sorted(set(study["best_shaft"]), key=list(markers).index):
    ax.plot([], [], markers[shaft], color="gray", mfc="gray" if shaft == "motor" else "white",
            label=f"on the {shaft} shaft")
ax.set_ylim(0, 1.05 * study["mass"].max())
ax.set(xlabel=f"crank speed [{rpm}]", ylabel="lightest flywheel [kg]",
       title="Punch press: the lightest flywheel of each material against the crank speed")
ax.grid(True, alpha=0.3)
ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=9);""",
    ),
    (
        "md",
        """Three regimes show:

- **At the slowest speeds the envelope binds** on the motor shaft: every material fills the 1.2 m
  envelope below its rim speed limit, and the masses are nearly equal (at a fixed diameter the density
  hardly matters: m ≈ 8J/(D_1² + D_2²)).
- **Then the rim speed binds on the motor shaft.** The diameter falls like 1/ω and J_F like 1/ω², so a
  thin ring would keep its mass; the real rim grows thicker and heavier as it shrinks (as at the
  nominal speed above).
- **At higher speeds the intermediate shaft takes over**: its rim, four times slower, is large again.
  The slowest material moves first, since its rim on the motor shaft is the smallest and thickest.

A rim sees only its own shaft: its speed and the inertia J_F/i² it must carry there (section 8). On the
intermediate shaft at a crank speed n it meets exactly what it meets on the motor shaft at n/4, the same
shaft speed and the same J'. The table below gives the speed at which each material leaves the motor
shaft; the checks under it hold the text to the numbers:""",
    ),
    (
        "code",
        """lowest = study[study["rpm"] == study["rpm"].min()]
assert (lowest["best_shaft"] == "motor").all() and lowest["binding"].str.contains("max_outer_diameter").all()
assert lowest["mass"].max() / lowest["mass"].min() - 1 < 0.01
switch = study[study["best_shaft"] != "motor"].groupby("material")["speed"].min().reindex(names)
assert list(switch.sort_values().index) == sorted(names, key=lambda n: library[n].max_rim_speed)

ratio = shafts["motor"] / shafts["intermediate"]
by_point = study.set_index(["material", "rpm"])
pairs = [(m, n) for m, n in by_point.index
         if by_point.loc[(m, n), "best_shaft"] == "intermediate" and (m, round(n / ratio, 9)) in by_point.index
         and by_point.loc[(m, round(n / ratio, 9)), "best_shaft"] == "motor"]
for m, n in pairs:
    assert math.isclose(by_point.loc[(m, n), "mass"], by_point.loc[(m, round(n / ratio, 9)), "mass"], rel_tol=1e-9)
print(f"{len(pairs)} designs on the intermediate shaft equal the motor shaft's at a {ratio:g} times slower crank")
in_units(switch.rename("speed").to_frame())""",
    ),
    (
        "md",
        """## 4. Lightest or cheapest?

Give the materials illustrative prices (currency per kilogram; use your supplier's) and let flyopt
price every design: the scene's materials, each with its cost, through `Scene.replace`.""",
    ),
    (
        "code",
        """prices = {"cast_iron": 1.0, "cast_steel": 1.6, "ductile_iron": 1.3}
priced = scene.replace(materials=tuple(replace(library[name], cost=price) for name, price in prices.items()))
costed = flyopt.sweep(priced, {"speed": "20:120:21rpm", "material": names}, workers=1)
costed["rpm"] = flyopt.to_units(costed, "input")["speed"].round(9)      # the speed as the sweep was given it
assert np.allclose(costed["mass"], study["mass"], rtol=1e-12)                          # prices change no design
assert np.allclose(costed["cost"], costed["mass"] * costed["material"].map(prices), rtol=1e-12)   # a rim's cost
mass = costed.pivot(index="rpm", columns="material", values="mass")
cost = costed.pivot(index="rpm", columns="material", values="cost")
cheapest = cost.idxmin(axis=1)
choice = pd.DataFrame({
    "lightest": mass.idxmin(axis=1), "cheapest": cheapest,
    "cheapest's shaft": [costed.set_index(["rpm", "material"]).loc[(n, m), "best_shaft"] for n, m in cheapest.items()],
    "cast_iron/cast_steel mass [-]": mass["cast_iron"] / mass["cast_steel"],
    "ductile_iron/cast_steel mass [-]": mass["ductile_iron"] / mass["cast_steel"],
    **{f"cost {m} [currency]": cost[m] for m in names}})
choice.index.name = f"crank speed [{rpm}]"
choice""",
    ),
    (
        "md",
        """Cast steel is the lightest at every speed of the sweep, but not the cheapest everywhere. A design's
cost is its price times its mass, so a cheaper material beats steel wherever its mass ratio to steel is
below steel's price ratio to it: 1.6 for cast iron, 1.6/1.3 ≈ 1.23 for ductile iron here.

- Where iron and steel both run at their rim speed limit on the same shaft, iron needs at least
  (50/36)² ≈ 1.93 times steel's mass (more where its rim is thicker): more than the price ratio, so steel
  is the cheaper design too.
- Where the envelope binds both (equal diameters), or where the slower material has already moved to
  the intermediate shaft and is large again while steel is still on the motor shaft, the mass ratio
  falls below the price ratio and the cheaper material wins on cost.""",
    ),
    (
        "code",
        """iron, steel = (costed[costed["material"] == m].set_index("rpm") for m in ("cast_iron", "cast_steel"))
both_rim = (iron["binding"].str.contains("rim_speed") & steel["binding"].str.contains("rim_speed")
            & (iron["best_shaft"] == steel["best_shaft"]))
thin_ratio = (library["cast_steel"].max_rim_speed / library["cast_iron"].max_rim_speed)**2
assert (iron["mass"][both_rim] / steel["mass"][both_rim] >= thin_ratio - 1e-12).all()
assert (choice.loc[both_rim[both_rim].index, "cheapest"] != "cast_iron").all()
assert prices["cast_steel"] / prices["cast_iron"] == 1.6 and round(prices["cast_steel"] / prices["ductile_iron"], 2) == 1.23
print(f"{both_rim.sum()} speeds with iron and steel at their rim speed limits on one shaft: "
      f"iron/steel mass {(iron['mass'] / steel['mass'])[both_rim].min():.3f} or more (≥ {thin_ratio:.3f})")""",
    ),
    (
        "md",
        """Where the lightest and the cheapest disagree, the engineer chooses. At 25 rpm, the mass–cost Pareto
front over all materials and shafts shows the choice:""",
    ),
    (
        "code",
        """slow = priced.replace(omega_mean=25 / display.show(1.0, "angular_speed"))
front = flyopt.pareto(slow, ("mass", "cost"))
assert front.attrs["objectives"] == ["mass", "cost"]
in_units(front[["best_material", "best_shaft", "mass", "cost", "d_outer", "b", "h", "binding"]])""",
    ),
    ("md", "## Conclusions"),
    (
        "code",
        """from IPython.display import Markdown

winner = nominal.iloc[0]
assert winner["material"] == "cast_steel" and (choice["lightest"] == "cast_steel").all()
cost_wins = choice[choice["cheapest"] != "cast_steel"]
steel_band = choice.index[choice["cheapest"] == "cast_steel"]
assert list(steel_band) == list(choice.index[(choice.index >= steel_band.min()) & (choice.index <= steel_band.max())])
iron_ratio = choice["cast_iron/cast_steel mass [-]"]
cheapest_front, lightest_front = front.iloc[front["cost"].argmin()], front.iloc[front["mass"].argmin()]
def name(material):
    return material.replace("_", " ")
Markdown(f\"\"\"
- **At {text(scene.omega_mean, "angular_speed")}** every material is lightest on the motor shaft at its rim
  speed limit, and cast steel wins: {text(winner["mass"], "mass")}, D_outer {text(winner["d_outer"], "length")},
  against {", ".join(f"{name(m)} {text(r['mass'], 'mass')}" for m, r in by_material.iloc[1:].iterrows())}.
  Iron needs {ratios.loc["cast_iron", "mass ratio to steel [-]"]:.2f} times steel's mass, more than the
  thin ring's (50/36)² = {thin_ratio:.2f}, because its smaller rim must be thicker
  (D_2/D_1 = {ratios.loc["cast_iron", "D_2/D_1 [-]"]:.2f} against {ratios.loc["cast_steel", "D_2/D_1 [-]"]:.2f}).
- **Across {study["rpm"].min():g}–{study["rpm"].max():g} {rpm}** cast steel stays the lightest at every
  speed; the iron/steel mass ratio runs from {iron_ratio.min():.3f} (the envelope binds both) to
  {iron_ratio.max():.2f}. Each material leaves the motor shaft for the intermediate shaft once its rim
  on the motor shaft has grown too thick, the slowest first:
  {", ".join(f"{name(m)} at {text(s, 'angular_speed')}" for m, s in switch.sort_values().items())}.
- **With the prices** ({", ".join(f"{name(m)} {p:g}" for m, p in prices.items())} per kg) steel is the
  cheapest only from {steel_band.min():g} to {steel_band.max():g} {rpm};
  at {", ".join(f"{n:g}" for n in cost_wins.index)} {rpm} the cheapest is
  {" or ".join(name(m) for m in sorted(set(cost_wins["cheapest"])))}, where its mass ratio to steel is below
  steel's price ratio to it.
- **At 25 {rpm}** the mass–cost Pareto front holds
  {"; ".join(f"{name(r['best_material'])} on the {r['best_shaft']} shaft, {text(r['mass'], 'mass')} for {r['cost']:.1f}" for _, r in front.iterrows())}
  (currency). The lightest design saves {100 * (1 - lightest_front["mass"] / cheapest_front["mass"]):.0f} % of
  the cheapest's mass for {100 * (lightest_front["cost"] / cheapest_front["cost"] - 1):.0f} % more money.
\"\"\")""",
    ),
]

SWEEP = [
    (
        "md",
        """# 03 · Parameter sweep: how δ and the motor speed set the shear press's flywheel

**The question.** The shear press of worked example 2 (`problems/shear-press.toml`;
`docs/flywheel-design.md`, section 12) carries its flywheel on the motor shaft, within a 600 mm
envelope. *How does the lightest flywheel depend on the allowed speed fluctuation δ and on the motor
speed? Where does a faster motor stop paying off, and what does a smaller envelope cost?*

**The way there:** a grid of δ × speed, sized at every point (section 5) and designed (sections 9 and
10); the mass surface and the two regimes it shows; the trend along each axis; a few points checked
by individual solves of their own scene files; the mass–envelope Pareto front; conclusions.""",
    ),
    (
        "code",
        """%matplotlib inline
from pathlib import Path
import math
import time
import tomllib
import numpy as np
import matplotlib.pyplot as plt
from matplotlib import colors, ticker
import flyopt

"""
        + UNITS_HELPER
        + """


ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
SCENE = ROOT / "problems" / "shear-press.toml"
scene = flyopt.load(SCENE)
assert scene.design.max_outer_diameter == 0.6 and [s.name for s in scene.shafts] == ["motor"]
rpm = display.label("angular_speed")
plain = ticker.FuncFormatter(lambda value, _: f"{value:g}")     # 0.05, not 5×10⁻²""",
    ),
    (
        "md",
        """## 1. The grid

Twenty values of δ from 0.01 to 0.2 (log-spaced) × sixteen motor speeds from 750 to 3000 rpm. The
shear's torques depend on the angle alone, so A_max is the same at every point and J_F = A_max/(ω_m² δ)
(section 5): the cycle is analysed once and every point is designed by the exact closed form of the
lightest rim. Checked here against section 5 at every point:""",
    ),
    (
        "code",
        """start = time.perf_counter()
grid = flyopt.sweep(scene, {"delta": "0.01:0.2:log20", "speed": "750:3000:16rpm"}, workers=1)
seconds = time.perf_counter() - start
assert grid["delta"].nunique() == 20 and grid["speed"].nunique() == 16
assert np.allclose([grid["delta"].min(), grid["delta"].max()], [0.01, 0.2], rtol=1e-12)
assert np.allclose(display.show(np.array([grid["speed"].min(), grid["speed"].max()]), "angular_speed"), [750, 3000])
a_max = grid["a_max"].iloc[0]
assert np.allclose(grid["a_max"], a_max, rtol=1e-12)
j_section5 = a_max / (grid["speed"]**2 * grid["delta"]) - scene.j_constant
assert np.allclose(grid["j_required"], j_section5, rtol=1e-12)
print(f"{len(grid)} points × {grid['n_combinations'].iloc[0]} material–shaft combinations in {seconds:.2f} s; "
      f"A_max = {text(a_max, 'energy')} at every point")
print(grid["status"].value_counts().to_dict(), "— best material:", grid["best_material"].dropna().unique().tolist())
in_units(grid[["delta", "speed", "status", "best_material", "j_required", "mass", "d_outer", "d_inner",
               "rim_speed", "binding"]].iloc[::53])""",
    ),
    (
        "md",
        """## 2. The mass surface

Read it with section 10 in mind. The rim's outer diameter is capped twice: by the 600 mm envelope, and
by the rim speed limit at the highest speed of the cycle, D_1 = 2 v_max/ω_max with
ω_max = ω_m (1 + δ/2). The dashed line is where the two caps meet,
n* = 60/(2π) · 2 v_max/(D_env (1 + δ/2)). Crosses mark points where no rim can give the inertia.""",
    ),
    (
        "code",
        """delta = np.sort(grid["delta"].unique())
speed = np.sort(grid["speed"].unique())
mass = grid.pivot(index="speed", columns="delta", values="mass").loc[speed, delta].to_numpy()
n = display.show(speed, "angular_speed")
nice = np.array([1, 1.5, 2, 3, 5, 7])[None, :] * 10.0 ** np.arange(-1, 5)[:, None]
nice = np.sort(nice.ravel())
levels = nice[(nice >= nice[nice <= np.nanmin(mass)].max()) & (nice <= nice[nice >= np.nanmax(mass)].min())]

steel = grid["best_material"].dropna().unique()
assert list(steel) == ["cast_steel"]
v_max = scene.material_library()["cast_steel"].max_rim_speed
d_env = scene.design.max_outer_diameter
def n_star(d):
    \"\"\"The speed at which the rim speed limit is reached at the envelope (section 10) [rad/s].\"\"\"
    return 2 * v_max / (d_env * (1 + d / 2))

fig, ax = plt.subplots(figsize=(9, 5.2), layout="constrained")
cs = ax.contourf(delta, n, mass, levels=levels, norm=colors.LogNorm(levels[0], levels[-1]), cmap="viridis")
ax.contour(delta, n, mass, levels=levels, colors="white", linewidths=0.5)
labelled = [v for v in levels if round(v / 10 ** math.floor(math.log10(v)), 6) in (1, 2, 5)]   # 1, 2, 5 × 10^k
bar = fig.colorbar(cs, ax=ax, ticks=labelled, format=plain)
bar.ax.minorticks_off()
bar.set_label("lightest flywheel [kg]")
curve = np.geomspace(delta[0], delta[-1], 60)
ax.plot(curve, display.show(n_star(curve), "angular_speed"), "--", color="black", lw=1.2,
        label=f"n*: the rim speed limit ({text(v_max, 'speed')}) reached at the {text(d_env, 'length')} envelope")
bad = grid[grid["status"] != "designed"]
ax.plot(bad["delta"], display.show(bad["speed"], "angular_speed"), "x", color="red", ms=8, mew=2, clip_on=False,
        label=f"no rim can give the inertia ({len(bad)} points)")
ax.set_xscale("log")
ax.xaxis.set_major_locator(ticker.FixedLocator([0.01, 0.02, 0.05, 0.1, 0.2]))
ax.xaxis.set_major_formatter(plain)
ax.xaxis.set_minor_formatter(ticker.NullFormatter())
ax.set(xlabel="allowed speed fluctuation δ [-]", ylabel=f"motor speed [{rpm}]",
       title="Shear press: the lightest flywheel over δ and the motor speed")
ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=1, fontsize=9, frameon=False);""",
    ),
    (
        "md",
        """Below the dashed line the contours slope down to the right: the envelope binds, and a faster motor
needs less mass. Above it they lean the other way: the rim speed binds, and a faster motor makes the
flywheel heavier, not lighter. That the line really separates the two limits is checked point by
point:""",
    ),
    (
        "code",
        """designed = grid[grid["status"] == "designed"]
below = designed["speed"] < n_star(designed["delta"])
binds = designed["binding"].str.split(",")
envelope_bound = binds.apply(lambda b: "max_outer_diameter" in b)
rim_bound = binds.apply(lambda b: "rim_speed" in b)
assert (envelope_bound == below).all() and (rim_bound == ~below).all()
print(f"{below.sum()} designed points below n*, all bound by the envelope; "
      f"{(~below).sum()} above it, all bound by the rim speed")""",
    ),
    (
        "md",
        """## 3. Along each axis

Slices of the surface at three values of δ. Where the envelope binds, the diameter is fixed and
J_F ∝ 1/(n² δ) sets the mass. Where the rim speed binds, a thin ring would keep a constant mass
(m = J_F ω_max²/v_max², section 14); the real rim must grow thicker as its diameter shrinks with the
speed, stores less per kilogram, and gets *heavier* — until at small δ no rim inside the shrinking
diameter can hold the energy at all.""",
    ),
    (
        "code",
        """fig, ax = plt.subplots(figsize=(9, 4.6), layout="constrained")
for k, j in enumerate((0, len(delta) // 2, len(delta) - 1)):
    missing = int(np.isnan(mass[:, j]).sum())
    ax.plot(n, mass[:, j], "o-", ms=4, color=f"C{k}",
            label=f"δ = {delta[j]:.3g}" + (f" ({missing} speeds without a design)" if missing else ""))
    ax.axvline(display.show(n_star(delta[j]), "angular_speed"), color=f"C{k}", ls=":", lw=1)
ax.plot([], [], ":", color="gray", label="n* of each δ")
ax.set_yscale("log")
ax.yaxis.set_major_locator(ticker.FixedLocator([2, 5, 10, 20, 50, 100, 200, 500]))
ax.yaxis.set_major_formatter(plain)
ax.yaxis.set_minor_formatter(ticker.NullFormatter())
ax.set(xlabel=f"motor speed [{rpm}]", ylabel="lightest flywheel [kg]",
       title="Shear press: the lightest flywheel against the motor speed")
ax.grid(True, alpha=0.3)
ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=9);""",
    ),
    (
        "md",
        """How fast does the mass move? The local exponents p of m ∝ x^p, from neighbouring grid points, over
each regime. A thin rim at a fixed diameter would give p = −2 in speed and −1 in δ. A real rim does
better than that as J_F falls at the envelope: it gets thinner, its inner diameter grows, and each
kilogram sits further out.""",
    ),
    (
        "code",
        """log_m, log_n, log_d = np.log(mass), np.log(speed), np.log(delta)
in_speed = np.diff(log_m, axis=0) / np.diff(log_n)[:, None]       # between neighbouring speeds
in_delta = np.diff(log_m, axis=1) / np.diff(log_d)[None, :]       # between neighbouring δ
above = speed[:, None] >= n_star(delta)[None, :]
both_above = above[1:] & above[:-1]
both_below = ~above[1:] & ~above[:-1]
exponents = pd.DataFrame({
    "mass against speed, p [-]": [np.nanmin(in_speed[both_below]), np.nanmax(in_speed[both_below]),
                                  np.nanmin(in_speed[both_above]), np.nanmax(in_speed[both_above])],
    "mass against δ, p [-]": [np.nanmin(in_delta[~above[:, 1:] & ~above[:, :-1]]),
                              np.nanmax(in_delta[~above[:, 1:] & ~above[:, :-1]]),
                              np.nanmin(in_delta[above[:, 1:] & above[:, :-1]]),
                              np.nanmax(in_delta[above[:, 1:] & above[:, :-1]])]},
    index=["envelope binds: least", "envelope binds: most", "rim speed binds: least", "rim speed binds: most"])
steepest = np.unravel_index(np.nanargmax(np.where(both_above, in_speed, np.nan)), in_speed.shape)
assert delta[steepest[1]] <= np.median(delta)           # the steepest rise is at small δ
exponents""",
    ),
    (
        "md",
        """## 4. Checked against individual solves

Three points of the grid, each written into its own copy of the scene file (the file's δ and speed
replaced, read by the scene parser) and solved on its own with IPOPT instead of the closed form: one
where the envelope binds, one where the rim speed binds, and one the sweep found infeasible.""",
    ),
    (
        "code",
        """data = tomllib.loads(SCENE.read_text(encoding="utf-8"))
picks = {"envelope binds": designed[below].index[len(designed[below]) // 2],
         "rim speed binds": designed[~below].index[len(designed[~below]) // 2],
         "infeasible": bad.index[0]}
rows = []
for case, i in picks.items():
    point = grid.loc[i]
    data["machine"]["delta"], data["machine"]["speed"] = float(point["delta"]), float(point["speed"])
    single = flyopt.solve(flyopt.from_dict(data, source=f"{SCENE.name} at point {i}"), design_method="ipopt")
    mass_single = single.design.best.mass if single.design.best is not None else math.nan
    rows.append({"case": case, "delta": point["delta"], "speed": point["speed"], "status": point["status"],
                 "individual status": single.design.status, "mass": point["mass"],
                 "mass, individual [kg]": mass_single})
checks = pd.DataFrame(rows).set_index("case")
checks["relative difference [-]"] = checks["mass"] / checks["mass, individual [kg]"] - 1
assert (checks["status"] == checks["individual status"]).all()
assert (checks["relative difference [-]"].dropna().abs() < 1e-6).all()
print("the individual solve of the infeasible point:", single.design.message)
in_units(checks.drop(columns=["mass, individual [kg]", "relative difference [-]"])).join(
    checks[["mass, individual [kg]", "relative difference [-]"]])""",
    ),
    (
        "md",
        """## 5. What the envelope costs

At the scene's own point, the mass–diameter trade-off by an ε-constraint on the outer diameter: each
point is the lightest design whose outer diameter is at most ε. A larger envelope would help only up
to the rim speed's cap on the diameter (section 10), drawn dashed.""",
    ),
    (
        "code",
        """front = flyopt.pareto(scene, ("mass", "outer_diameter"), points=15)
assert front.attrs["objectives"] == ["mass", "outer_diameter"]
d_rim = 2 * v_max / (scene.omega_mean * (1 + scene.delta / 2))   # the rim speed's cap at this point
fig, ax = plt.subplots(figsize=(8, 4.6), layout="constrained")
x = display.show(front["outer_diameter"], "length")
ax.step(x, front["mass"], where="post", color="C3", lw=1.2)
ax.plot(x, front["mass"], "o", color="C3", ms=5, label=f"Pareto front ({len(front)} designs)")
ax.axvline(display.show(d_rim, "length"), color="black", ls="--", lw=1,
           label=f"rim speed cap {text(d_rim, 'length')}")
ax.annotate("a full disc", (x.iloc[0], front["mass"].iloc[0]), xytext=(3, 5), textcoords="offset points",
            fontsize=9, va="bottom")
ax.set_ylim(0, 1.12 * front["mass"].max())
ax.set(xlabel=f"outer diameter [{display.label('length')}]", ylabel="flywheel mass [kg]",
       title=f"Shear press at {text(scene.omega_mean, 'angular_speed')}, δ = {scene.delta}: mass against diameter")
ax.grid(True, alpha=0.3)
ax.legend(loc="upper right", fontsize=9)
in_units(front[["outer_diameter", "mass", "d_inner", "b", "h", "rim_speed", "binding"]]).round(3)""",
    ),
    ("md", "## Conclusions"),
    (
        "code",
        """from IPython.display import Markdown

# the lightest flywheel of each δ is at the grid's first speed above n* (as the conclusions say)
first_above = np.array([speed[speed >= n_star(d)].min() for d in delta])
assert np.array_equal(speed[np.nanargmin(mass, axis=0)], first_above)
nominal = front.iloc[-1]
smallest = front.iloc[0]
assert "inner_diameter" in smallest["binding"] and smallest["d_inner"] < 1e-9     # a full disc
envelope_bad = bad[bad["speed"] < n_star(bad["delta"])]
rim_bad = bad[bad["speed"] >= n_star(bad["delta"])]
half_mass = front[front["mass"] <= 2 * nominal["mass"]].iloc[0]
n_min_mass = {f"{delta[j]:.3g}": display.show(speed[np.nanargmin(mass[:, j])], "angular_speed")
              for j in (0, len(delta) // 2, len(delta) - 1)}
Markdown(f\"\"\"
- **The cycle fixes A_max = {text(a_max, "energy")}**; δ and the speed only scale J_F = A_max/(ω_m² δ), which
  flyopt's {len(grid)} points follow to 1e-12. The best material is cast steel at every designed point:
  above n\\\\* by its higher rim speed limit; below it, at the same diameter, its thinner rim (it is denser)
  keeps its mass further out.
- **Two regimes, split by n\\\\* = 2 v_max/(D_env (1 + δ/2))**, {text(n_star(delta[-1]), "angular_speed")} to
  {text(n_star(delta[0]), "angular_speed")} over this δ range: below it the {text(d_env, "length")} envelope binds
  ({below.sum()} points) and the mass falls with the speed (exponents {exponents.iloc[0, 0]:.2f} to
  {exponents.iloc[1, 0]:.2f}); above it the rim speed binds ({(~below).sum()} points) and the mass *rises* with
  the speed (exponents {exponents.iloc[2, 0]:.2f} to {exponents.iloc[3, 0]:.2f}), as the rim shrinks and
  thickens; the steepest at small δ, where the rim nears a full disc. A faster motor stops paying off at n\\\\*: at every δ of the grid the lightest flywheel is at the
  first grid speed above n\\\\* ({", ".join(f"{v:g} {rpm} for δ = {k}" for k, v in n_min_mass.items())}).
- **Along δ** the mass follows the 1/δ hyperbola of section 2 closely, δ^p with p from
  {exponents.iloc[:, 1].min():.2f} to {exponents.iloc[:, 1].max():.2f} over the grid: halving δ about doubles the
  flywheel, whatever the speed.
- **Limits:** {len(bad)} points have no design: {len(envelope_bad)} below n\\\\*
  (δ ≤ {envelope_bad["delta"].max():.3g}, {display.show(envelope_bad["speed"].max(), "angular_speed"):g} {rpm} and below), where even the
  fullest rim in the envelope cannot hold the energy, and {len(rim_bad)} above it (δ ≤ {rim_bad["delta"].max():.3g},
  {display.show(rim_bad["speed"].min(), "angular_speed"):g} {rpm} and above), where the rim speed caps the diameter.
- **Checked:** individual IPOPT solves of rewritten scene files agree to
  {checks["relative difference [-]"].abs().max():.1e} and confirm the infeasible point.
- **The envelope:** at the scene's {text(scene.omega_mean, "angular_speed")} and δ = {scene.delta} the
  {text(nominal["outer_diameter"], "length")} envelope gives {text(nominal["mass"], "mass")}. The smallest wheel
  within twice that mass is {text(half_mass["outer_diameter"], "length")} across ({text(half_mass["mass"], "mass")}), and
  the smallest of all a full disc of {text(smallest["outer_diameter"], "length")} and {text(smallest["mass"], "mass")}.
  A larger envelope could give at most {text(d_rim, "length")} before the rim speed caps the wheel.
\"\"\")""",
    ),
]

NOTEBOOKS = (
    ("01-design-study.ipynb", DESIGN_STUDY),
    ("02-material-trade-off.ipynb", TRADE_OFF),
    ("03-parameter-sweep.ipynb", SWEEP),
)

if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE
    out.mkdir(exist_ok=True)
    for name, cells in NOTEBOOKS:
        nbf.write(notebook(cells), out / name)
        print("wrote", out / name)
