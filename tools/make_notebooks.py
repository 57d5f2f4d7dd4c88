"""Write the notebooks of notebooks/ from the cells below (then execute them with nbmake or jupyter).

Keeping the source here makes the notebooks reviewable as Python; run
`python tools/make_notebooks.py` after editing, then
`python -m pytest --nbmake notebooks --overwrite` to store their outputs.
"""

from pathlib import Path

import nbformat as nbf

HERE = Path(__file__).resolve().parents[1] / "notebooks"


def notebook(cells):
    nb = nbf.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.cells = [nbf.v4.new_markdown_cell(text) if kind == "md" else nbf.v4.new_code_cell(text)
                for kind, text in cells]
    return nb


DESIGN_STUDY = [
    ("md", """# 01 · Design study: from a press's torque curve to a verified flywheel

A mechanical press (`problems/slider-crank-press.toml`): a crank drives a 400 kg ram through a
slider-crank at 120 strokes/min; the working force acts over the last 40° before bottom dead
centre. We want the lightest flywheel that keeps the speed fluctuation within δ = 0.15."""),
    ("code", """%matplotlib inline
from pathlib import Path
import flyopt
from flyopt.report import plots

ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
scene = flyopt.load(ROOT / "problems" / "slider-crank-press.toml")
analysis = flyopt.analyse(scene)
print(analysis.model, "-", analysis.model_reason)
print(f"A_max = {analysis.a_max:.1f} J, J_F = {analysis.j_required:.3f} kg·m² at the crankshaft")"""),
    ("md", """## The turning-moment diagram
The resisting torque includes the ram's working force reduced through the slider-crank's exact
kinematics; the driving torque is the constant that balances the cycle."""),
    ("code", "plots.plot_turning_moment(scene, analysis);"),
    ("md", """## Energy indicator and energy–mass diagrams
The ram makes the equivalent inertia vary with the angle, so flyopt sizes the flywheel with the
energy–mass (Wittenbauer) closed form: the tangents from the true origin have slopes ω_max²/2 and
ω_min²/2."""),
    ("code", "plots.plot_energy(scene, analysis);"),
    ("code", "plots.plot_energy_mass(scene, analysis);"),
    ("md", "How far would the textbook constant-inertia method be off?"),
    ("code", """import pandas as pd
pd.DataFrame(analysis.models)[["model", "exact", "j_required", "j_error", "achieved_delta"]]"""),
    ("md", """## The design
Every material × shaft combination is decided: a closed form proves the infeasible ones, and the
others are optimized, here by the exact closed form of the lightest rim (IPOPT takes the
structures it does not cover). Then the whole machine is simulated with the chosen flywheel."""),
    ("code", """solution = flyopt.solve(scene, verify_design=True)
best = solution.design.best
print(f"{best.material} on the {best.shaft} shaft: D_outer {best.d_outer:.3f} m, B {best.b*1000:.1f} mm, "
      f"mass {best.mass:.1f} kg, rim speed {best.rim_speed:.1f} m/s")
pd.DataFrame([c.to_dict() for c in solution.design.candidates])[
    ["material", "shaft", "feasible", "mass", "d_outer", "rim_speed", "binding"]]"""),
    ("code", """v = solution.verification
print(f"verification: achieved δ = {v.achieved_delta:.6f} (allowed {v.delta_allowed}), flagged: {v.flagged}")
assert not v.flagged"""),
    ("code", "plots.plot_cross_section(best);"),
    ("code", "plots.plot_speed(scene, analysis, analysis.speed_curve());"),
]

TRADE_OFF = [
    ("md", """# 02 · Material trade-off: cast iron, cast steel and a user material, across speeds

The punch press of `problems/punch-press.toml` (60 strokes/min; flywheel on the crankshaft, the
intermediate shaft or the motor shaft; envelope 1.2 m, width 0.2 m) with three materials: the
built-in cast iron (36 m/s rim limit, 7200 kg/m³) and cast steel (50 m/s, 7800 kg/m³), and the
scene's own ductile iron (14 MPa allowable hoop stress, so v_max = √(σ/ρ) = 44.4 m/s)."""),
    ("code", """%matplotlib inline
from pathlib import Path
import numpy as np
import matplotlib.pyplot as plt
import flyopt

ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
scene = flyopt.load(ROOT / "problems" / "punch-press.toml")
flyopt.material_tradeoff(scene)[["material", "shaft", "d_outer", "b", "rim_speed", "rim_speed_limit", "mass", "limit"]]"""),
    ("md", """At the nominal speed every material goes to the fast motor shaft and runs at its rim speed limit:
for a given inertia a larger diameter means less mass (J ∝ m D²), and the rim speed caps the
diameter. The material with the highest permissible speed therefore wins, even though it is the
densest: mass ∝ J/D² ∝ J ω²/v_max², so the lightest rim scales like 1/v_max² at fixed J.

Across crank speeds the picture changes where the envelope, not the rim speed, binds."""),
    ("code", """study = flyopt.sweep(scene, {"speed": "20:120:11rpm",
                              "material": ["cast_iron", "cast_steel", "ductile_iron"]})
fig, ax = plt.subplots(figsize=(8, 4.5), layout="constrained")
for material, part in study.groupby("material"):
    ax.plot(part["speed"] * 30 / np.pi, part["mass"], "o-", label=material)
ax.set(xlabel="crank speed [rpm]", ylabel="lightest flywheel [kg]", yscale="log",
       title="lightest flywheel by material (any shaft)")
ax.grid(True, which="both", alpha=0.3); ax.legend();"""),
    ("md", """Who wins depends on what binds. Give the materials illustrative prices (currency per kg; use
your supplier's) and compare the lightest and the cheapest design at each speed:"""),
    ("code", """import pandas as pd
prices = {"cast_iron": 1.0, "cast_steel": 1.6, "ductile_iron": 1.3}
study["cost"] = study["mass"] * study["material"].map(prices)
study["rpm"] = (study["speed"] * 30 / np.pi).round(1)
by = study.pivot(index="rpm", columns="material", values="mass")
lightest = study.loc[study.groupby("rpm")["mass"].idxmin()].set_index("rpm")
cheapest = study.loc[study.groupby("rpm")["cost"].idxmin()].set_index("rpm")
pd.DataFrame({"lightest": lightest["material"],
              "mass ratio iron/steel": (by["cast_iron"] / by["cast_steel"]).round(3),
              "cheapest": cheapest["material"], "what binds (cheapest)": cheapest["binding"]})"""),
    ("md", """Cast steel is the lightest at every speed, but not always the cheapest. What decides it is the
mass ratio against the price ratio (1.6 here):

- Where both materials run at their rim speed limit on the same shaft, the lightest rim scales
  like J ω²/v_max², so iron needs about (50/36)² ≈ 1.9 times steel's mass: more than steel's
  price premium, and steel is the cheaper design too.
- The other limits move the ratio away from 1.9: up where the width limit forces the slower iron
  rim to grow thicker, down where the envelope caps steel's diameter below its rim-speed diameter
  or the best shaft changes. Once the mass ratio drops below the price ratio, the cheaper
  material wins on cost.

The table shows both regimes along the speed range. The mass–cost Pareto front at a slow speed
shows the choice the engineer has there:"""),

    ("code", """priced = scene.replace(materials=tuple(
    m.__class__(m.name, m.density, m.max_rim_speed, m.allowable_stress, prices[m.name], m.source)
    for m in scene.material_library().values()), omega_mean=25 * np.pi / 30)
front = flyopt.pareto(priced, ("mass", "cost"))
front[["mass", "cost", "best_material", "best_shaft", "binding"]]"""),
]

SWEEP = [
    ("md", """# 03 · Parameter sweep: δ × speed, the mass surface and a Pareto front

How does the lightest flywheel of the shear press (`problems/shear-press.toml`) depend on the
allowed speed fluctuation δ and the motor speed? A 20 × 15 grid, 300 scenes × 2 materials, is
designed in a fraction of a second: the cycle is analysed once (A_max does not depend on δ or
speed for torques of the angle), and every combination is sized by the exact closed form where it
applies — checked against individual IPOPT solves."""),
    ("code", """%matplotlib inline
from pathlib import Path
import time
import numpy as np
import matplotlib.pyplot as plt
import flyopt

ROOT = Path.cwd() if (Path.cwd() / "problems").exists() else Path.cwd().parent
scene = flyopt.load(ROOT / "problems" / "shear-press.toml")
start = time.perf_counter()
grid = flyopt.sweep(scene, {"delta": "0.01:0.2:log20", "speed": "750:3000:15rpm"})
print(f"{len(grid)} points in {time.perf_counter() - start:.2f} s; methods: {grid['method'].value_counts().to_dict()}")
grid[["delta", "speed", "status", "best_material", "mass", "d_outer", "binding"]].head()"""),
    ("code", """delta = np.sort(grid["delta"].unique()); speed = np.sort(grid["speed"].unique())
mass = grid.pivot(index="speed", columns="delta", values="mass").loc[speed, delta].to_numpy()
fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
cs = ax.contourf(delta, speed * 30 / np.pi, mass, levels=np.geomspace(np.nanmin(mass), np.nanmax(mass), 15),
                 norm="log", cmap="viridis")
ax.contour(delta, speed * 30 / np.pi, mass, levels=cs.levels, colors="white", linewidths=0.4)
fig.colorbar(cs, label="lightest flywheel [kg]")
ax.set(xscale="log", xlabel="allowed δ", ylabel="motor speed [rpm]", title="shear press: mass surface");"""),
    ("md", """Mass falls like 1/δ (the hyperbola of J against δ) and, at a fixed envelope, like 1/n²: J_F = A_max/(ω²δ).
Check one point against an individual solve:"""),
    ("code", """from flyopt.studies.evaluate import point_scene

row = grid.iloc[57]
single = flyopt.solve(point_scene(scene, {"delta": row["delta"], "speed": row["speed"]}), design_method="ipopt")
print(f"sweep {row['mass']:.9g} kg, individual IPOPT solve {single.design.best.mass:.9g} kg")
assert abs(row["mass"] / single.design.best.mass - 1) < 1e-6"""),
    ("md", "And the trade-off between mass and outer diameter, by an ε-constraint on the envelope:"),
    ("code", """front = flyopt.pareto(scene, ("mass", "outer_diameter"), points=15)
from flyopt.report import plots
plots.plot_pareto(front, "outer_diameter", "mass");"""),
]

if __name__ == "__main__":
    HERE.mkdir(exist_ok=True)
    for name, cells in (("01-design-study.ipynb", DESIGN_STUDY), ("02-material-trade-off.ipynb", TRADE_OFF),
                        ("03-parameter-sweep.ipynb", SWEEP)):
        nbf.write(notebook(cells), HERE / name)
        print("wrote", HERE / name)
