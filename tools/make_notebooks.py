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
from flyopt import plots

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
Every material × shaft combination is decided: a closed form proves the infeasible ones, IPOPT
optimizes the others. Then the whole machine is simulated with the chosen flywheel."""),
    ("code", """solution = flyopt.solve(scene, verify_design=True)
best = solution.design.best
print(f"{best.material} on the {best.shaft} shaft: D_outer {best.d_outer:.3f} m, B {best.b*1000:.1f} mm, "
      f"mass {best.mass:.1f} kg, rim speed {best.rim_speed:.1f} m/s")
pd.DataFrame([c.to_dict() for c in solution.design.candidates])[
    ["material", "shaft", "feasible", "mass", "d_outer", "rim_speed", "binding"]]"""),
    ("code", """v = solution.verification
print(f"verification: achieved δ = {v['achieved_delta']:.6f} (allowed {v['delta_allowed']}), flagged: {v['flagged']}")
assert not v["flagged"]"""),
    ("code", "plots.plot_cross_section(best);"),
    ("code", "plots.plot_speed(scene, analysis);"),
]

if __name__ == "__main__":
    HERE.mkdir(exist_ok=True)
    for name, cells in (("01-design-study.ipynb", DESIGN_STUDY),):
        nbf.write(notebook(cells), HERE / name)
        print("wrote", HERE / name)
