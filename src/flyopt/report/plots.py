"""Diagrams of a scene, its analysis and its design (matplotlib).

Each ``plot_*`` function draws on a given Axes (or a new figure) and returns
the Axes; :func:`save` writes a figure atomically (to a temporary file in the
same folder, then renamed), so a failed render leaves nothing half-written.
The backend is Agg unless the caller chose another one.

The plots draw computed results and never run a model: what a diagram needs
beyond the :class:`~flyopt.analysis.Analysis` (the speed over the cycle, a
simulation, a design) is computed by the caller and passed in. A diagram that
cannot be drawn for this scene raises :class:`ValueError`; one that would be
empty because the machine needs no flywheel raises :class:`NothingToDraw`.
"""

import math
import os
import tempfile
from pathlib import Path

import numpy as np

from flyopt.cycle.indicator import ExcessWork
from flyopt.errors import SceneError
from flyopt.units import rad_s_to_rpm

SURPLUS, DEFICIT = "#2e8b57", "#c0392b"
PLOTS = {
    "turning_moment": "driving and resisting torque over the cycle, areas shaded and labelled",
    "energy": "energy indicator diagram: the chain of ΔE with A_max marked",
    "inertia_delta": "required flywheel J against δ (the hyperbola), the scene's δ marked",
    "cross_section": "dimensioned cross-section of the chosen flywheel",
    "speed": "ω(φ) over the cycle with the required flywheel, from the model that ran",
    "energy_mass": "energy–mass (Wittenbauer) diagram: ΔE against J_e with the two tangents",
}
#: Image formats :func:`save` writes, by the suffix of the file.
FORMATS = ("png", "svg", "pdf")


class NothingToDraw(Exception):
    """The diagram would be empty for this machine (no flywheel is needed): not an error."""


def check_output(path):
    """Check the file a diagram will go to, before anything is computed.

    Parameters
    ----------
    path : str or Path
        The output file; its suffix picks the format (:data:`FORMATS`).

    Raises
    ------
    SceneError
        Field ``-o/--output``: an unsupported suffix, or a folder that does
        not exist (flyopt does not create folders the user did not ask for).
    """
    path = Path(path)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise SceneError("-o/--output", f"{str(path)!r} must end in .png, .svg or .pdf "
                         f"(the suffix picks the format)")
    folder = path.parent
    if not folder.is_dir():
        raise SceneError("-o/--output", f"the folder {str(folder)!r} does not exist")


def _pyplot():
    import matplotlib

    if "MPLBACKEND" not in os.environ and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _axes(ax, figsize=(8, 4.5)):
    if ax is not None:
        return ax
    plt = _pyplot()
    return plt.figure(figsize=figsize, layout="constrained").add_subplot()


def _excess_work(scene, analysis):
    """ΔE of the torques as the analysis saw them (members' loads joined, a motor at its mean)."""
    if analysis.machine is not None:
        return analysis.machine.angle_only()
    return ExcessWork(scene.driving, scene.resisting, scene.cycle_angle)


def _curve_samples(curve, cycle_angle, n=2000):
    """Angles and values that draw a torque curve exactly (tables at their points)."""
    from flyopt.machine.torque import Constant, PiecewiseLinear

    if isinstance(curve, PiecewiseLinear):
        return curve.angles, curve.values
    if isinstance(curve, Constant):
        return np.array([0.0, cycle_angle]), np.array([curve.value, curve.value])
    phi = np.linspace(0.0, cycle_angle, n)
    return phi, curve(phi)


def plot_turning_moment(scene, analysis, ax=None):
    """Turning-moment diagram: M_d and M_r over the cycle, surplus and deficit shaded.

    Each area between crossings is labelled with its energy [J]; the angles of
    ω_max and ω_min are marked. Net-area scenes have no curves: their areas are
    drawn as a bar chart instead.
    """
    ax = _axes(ax)
    ind = analysis.indicator
    if scene.net is not None:
        areas = ind.areas
        ax.bar(np.arange(1, len(areas) + 1), areas, color=[SURPLUS if a > 0 else DEFICIT for a in areas])
        ax.axhline(0, color="black", lw=0.8)
        ax.set(xlabel="area (in order over the cycle)", ylabel="energy [J]",
               title=f"{analysis.title}: net areas between the torque curves")
        return ax
    ew = _excess_work(scene, analysis)
    grid = np.union1d(np.linspace(0, scene.cycle_angle, 3000), ind.chain_angle)
    grid = np.union1d(grid, ew.knots)
    d = _curve_samples(ew.driving, scene.cycle_angle)
    r = _curve_samples(ew.resisting, scene.cycle_angle)
    md = np.interp(grid, *d) if not hasattr(ew.driving, "expression") else ew.driving(grid)
    mr = np.interp(grid, *r) if not hasattr(ew.resisting, "expression") else ew.resisting(grid)
    deg = np.degrees(grid)
    ax.fill_between(deg, md, mr, where=md >= mr, color=SURPLUS, alpha=0.3, interpolate=True, lw=0)
    ax.fill_between(deg, md, mr, where=md < mr, color=DEFICIT, alpha=0.3, interpolate=True, lw=0)
    ax.plot(np.degrees(d[0]), d[1], color="tab:blue", lw=1.8, label="driving M_d")
    ax.plot(np.degrees(r[0]), r[1], color="black", lw=1.8, label="resisting M_r")
    span = max(np.ptp(np.concatenate([md, mr])), 1e-12)
    for left, right, area in zip(ind.chain_angle[:-1], ind.chain_angle[1:], ind.areas):
        if right - left < 0.02 * scene.cycle_angle and abs(area) < 0.05 * max(ind.a_max, 1e-300):
            continue
        mid = 0.5 * (left + right)
        y = 0.5 * (np.interp(mid, grid, md) + np.interp(mid, grid, mr))
        ax.annotate(f"{area:+.4g} J", (math.degrees(mid), y), ha="center", va="center", fontsize=8,
                    color=SURPLUS if area > 0 else DEFICIT)
    for angle, label in ((analysis.angle_omega_max, "ω_max"), (analysis.angle_omega_min, "ω_min")):
        ax.axvline(math.degrees(angle), color="gray", ls="--", lw=0.8)
        ax.text(math.degrees(angle), 0.97, f" {label}", transform=ax.get_xaxis_transform(), ha="left", va="top",
                fontsize=8, color="gray")
    ax.set(xlabel="crank angle φ [deg]", ylabel="torque [N·m]", xlim=(0, math.degrees(scene.cycle_angle)),
           title=f"{analysis.title}: turning-moment diagram (A_max = {analysis.a_max:.5g} J)")
    ax.margins(y=0.08 if span else 0.5)
    ax.legend(loc="best", fontsize=8)
    return ax


def plot_energy(scene, analysis, ax=None):
    """Energy indicator diagram: ΔE from the cycle start, the chain points and A_max."""
    ax = _axes(ax)
    ind = analysis.indicator
    chain = ind.chain_delta_e
    if ind.chain_angle is None:
        x = np.arange(len(chain))
        ax.plot(x, chain, "o-", color="tab:blue")
        ax.set_xlabel("end of area")
        where_max, where_min = x[ind.index_max], x[ind.index_min]
    else:
        ew = _excess_work(scene, analysis)
        phi = np.union1d(np.linspace(0, scene.cycle_angle, 1500), ind.chain_angle)
        ax.plot(np.degrees(phi), ew(phi), color="tab:blue", lw=1.5, label="ΔE(φ)")
        ax.plot(np.degrees(ind.chain_angle), chain, "o", color="black", ms=4, label="crossings")
        ax.set_xlabel("crank angle φ [deg]")
        where_max, where_min = np.degrees(ind.chain_angle[[ind.index_max, ind.index_min]])
    hi, lo = chain[ind.index_max], chain[ind.index_min]
    ax.axhline(hi, color=SURPLUS, ls=":", lw=1)
    ax.axhline(lo, color=DEFICIT, ls=":", lw=1)
    x_arrow = 0.5 * (where_max + where_min)
    ax.annotate("", (x_arrow, hi), (x_arrow, lo), arrowprops={"arrowstyle": "<->", "color": "gray"})
    ax.annotate(f"A_max = {ind.a_max:.5g} J", (x_arrow, 0.5 * (hi + lo)), ha="left", va="center", fontsize=9)
    ax.set(ylabel="excess work ΔE [J]", title=f"{analysis.title}: energy indicator diagram")
    return ax


def plot_inertia_delta(scene, analysis, ax=None):
    """J_F against δ: J_F = A_max/(ω_m² δ) − J_c, an equilateral hyperbola, the scene's δ marked.

    J_F is positive only below δ* = A_max/(ω_m² J_c), where the machine's own
    inertia stops sufficing; the δ axis reaches down to δ*/20 when the scene's
    δ lies above it, and δ* is marked.

    Raises
    ------
    NothingToDraw
        A_max = 0: no flywheel is needed for any δ.
    """
    if analysis.a_max <= 0:
        raise NothingToDraw("no flywheel is needed for any δ (A_max = 0 J, so J_F(δ) = 0): nothing to draw")
    ax = _axes(ax)
    omega2 = analysis.omega_mean**2
    delta_free = analysis.a_max / (omega2 * analysis.j_constant) if analysis.j_constant > 0 else math.inf
    lo, hi = min(analysis.delta, delta_free) / 20, min(1.9, analysis.delta * 20)
    delta = np.geomspace(lo, hi, 200)
    j = analysis.a_max / (omega2 * delta) - analysis.j_constant
    ax.plot(delta, np.where(j > 0, j, np.nan), color="tab:blue", label="J_F(δ)")
    if delta_free < hi:
        ax.axvline(delta_free, color="gray", ls="--", lw=0.8,
                   label=f"δ* = {delta_free:.4g}: J_F = 0 above (J_c suffices)")
    if analysis.flywheel_needed:
        ax.plot([analysis.delta], [analysis.j_required], "o", color=DEFICIT,
                label=f"δ = {analysis.delta:.4g}: J_F = {analysis.j_required:.4g} kg·m²")
    ax.set(xscale="log", yscale="log", xlabel="coefficient of speed fluctuation δ",
           ylabel="required flywheel J_F [kg·m²]", title=f"{analysis.title}: J grows like 1/δ")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_cross_section(candidate, ax=None):
    """Dimensioned axial cross-section of a designed rim or disc (half above the axis, mirrored)."""
    from matplotlib.patches import Rectangle

    ax = _axes(ax, figsize=(6, 6))
    c = candidate
    r_out, r_in, b = c.d_outer / 2, c.d_inner / 2, c.b
    for sign in (1, -1):
        low, high = (r_in, r_out) if sign > 0 else (-r_out, -r_in)
        ax.add_patch(Rectangle((-b / 2, low), b, high - low, facecolor="#b0b7c3", edgecolor="black", hatch="//"))
    ax.axhline(0, color="black", ls="-.", lw=0.8)
    pad = 0.12 * r_out
    x_dim = b / 2 + pad

    def dim(x, y0, y1, text):
        ax.annotate("", (x, y0), (x, y1), arrowprops={"arrowstyle": "<->", "lw": 0.8})
        ax.text(x + 0.03 * r_out, 0.5 * (y0 + y1), text, rotation=90, ha="left", va="center", fontsize=8,
                backgroundcolor="white")

    dim(x_dim, -r_out, r_out, f"D_outer {c.d_outer * 1000:.4g} mm")
    if r_in > 0:
        dim(x_dim + pad, -r_in, r_in, f"D_inner {c.d_inner * 1000:.4g} mm")
    ax.annotate("", (-b / 2, r_out + pad / 2), (b / 2, r_out + pad / 2), arrowprops={"arrowstyle": "<->", "lw": 0.8})
    ax.annotate(f"B {b * 1000:.4g} mm", (0, r_out + pad / 2), ha="center", va="bottom", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlim(-b / 2 - 2 * pad, b / 2 + 4 * pad)
    ax.set_ylim(-r_out - pad, r_out + 1.5 * pad)
    ax.set(xlabel="axial [m]", ylabel="radial [m]",
           title=f"{c.material} {c.geometry} on {c.shaft}: {c.mass:.4g} kg, v = {c.rim_speed:.3g} m/s")
    return ax


def plot_speed(scene, analysis, speed=None, simulation=None, ax=None):
    """ω(φ) over the cycle with the required flywheel, from the model that ran.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    speed : SpeedFluctuation or PeriodicSolution, optional
        The model's speed over the cycle: ``phi`` [rad] and ``omega`` [rad/s].
        Energy models: ω² = 2 (E_0 + ΔE)/J_e with E_0 such that
        (ω_max + ω_min)/2 = ω_m (docs/flywheel-design.md, section 6, forward
        use: :func:`flyopt.sizing.energy_mass.achieved_speed`); the dynamic
        model: its periodic solution, which the analysis carries (the default).
    simulation : PeriodicSolution, optional
        The periodic simulation of the machine with that flywheel (the
        verification's), drawn over it: ``phi``, ``omega`` and ``delta``.
    ax : matplotlib Axes, optional

    Raises
    ------
    ValueError
        A net-area scene: it has no angles; or no ``speed`` for an analysis
        whose result does not carry one (the energy models).
    """
    if scene.net is not None:
        raise ValueError("a net-area scene has no angles: ω(φ) cannot be drawn")
    if speed is None:
        if analysis.requirement is None or analysis.requirement.model != "dynamic":
            raise ValueError(f"the {analysis.model} model's result carries no ω(φ): pass speed "
                             f"(flyopt.sizing.energy_mass.achieved_speed with J_F)")
        speed = analysis.requirement.detail.solution
    ax = _axes(ax)
    omega = np.asarray(speed.omega)
    ax.plot(np.degrees(speed.phi), rad_s_to_rpm(omega), color="tab:blue", label=f"model: {analysis.model}")
    if simulation is not None:
        ax.plot(np.degrees(simulation.phi), rad_s_to_rpm(simulation.omega), color=DEFICIT, ls="--", lw=1,
                label=f"simulation (δ = {simulation.delta:.6g})")
    for value, label in ((omega.max(), "ω_max"), (omega.min(), "ω_min")):
        ax.axhline(rad_s_to_rpm(value), color="gray", ls=":", lw=0.8)
        ax.annotate(label, (0, rad_s_to_rpm(value)), fontsize=8, va="bottom")
    ax.set(xlabel="crank angle φ [deg]", ylabel="speed [rpm]", xlim=(0, math.degrees(scene.cycle_angle)),
           title=f"{analysis.title}: speed over the cycle (δ = {analysis.delta:.4g})")
    ax.legend(fontsize=8)
    return ax


def plot_energy_mass(scene, analysis, ax=None):
    """Wittenbauer's energy–mass diagram: ΔE against J_e over the cycle, with the two tangents.

    From the true origin (−J_F, −E_0) the lines of slope ω_max²/2 and ω_min²/2
    touch the curve where the speed is highest and lowest (docs/flywheel-design.md, section 6).

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        Sized by the energy–mass model (``analyse(scene, model="energy_mass")``):
        ``analysis.requirement.detail`` is its EnergyMassRequirement
        (``j_required``, ``e0``, ``omega_max``, ``omega_min``).
    ax : matplotlib Axes, optional

    Raises
    ------
    ValueError
        Torques that depend on speed, or net areas; or an analysis by another model.
    NothingToDraw
        A_max = 0 with a constant inertia: the curve is one point.
    """
    check_energy_mass(analysis)
    if analysis.requirement is None or analysis.requirement.model != "energy_mass":
        raise ValueError(f"the energy–mass diagram draws the energy–mass model's result, and this "
                         f"analysis ran the {analysis.model} model: analyse with model='energy_mass'")
    machine = analysis.machine
    if analysis.a_max <= 0 and not machine.variable_inertia:
        raise NothingToDraw("no flywheel is needed and the diagram is one point (A_max = 0 J, constant "
                            "inertia): nothing to draw")
    ax = _axes(ax, figsize=(7, 5.5))
    em = analysis.requirement.detail
    ew = machine.angle_only()
    phi = np.union1d(np.linspace(0, scene.cycle_angle, 1500), ew.knots)
    j = np.broadcast_to(machine.j_machine(phi) if machine.variable_inertia else machine.j_machine, phi.shape)
    de = ew(phi)
    ax.plot(j, de, color="tab:blue", lw=1.5, label="(J_e(φ), ΔE(φ))")
    j_f = max(em.j_required, 0.0)
    x0, y0 = -j_f, -em.e0
    xs = np.array([x0, j.max() + 0.05 * (j.max() - x0)])
    for w, colour, label in ((em.omega_max, SURPLUS, "ω_max²/2"), (em.omega_min, DEFICIT, "ω_min²/2")):
        ax.plot(xs, y0 + 0.5 * w**2 * (xs - x0), color=colour, lw=1, ls="--", label=f"slope {label}")
    ax.plot([x0], [y0], "ko")
    ax.annotate(f"origin (−J_F, −E_0), J_F = {j_f:.4g} kg·m²", (x0, y0), fontsize=8, xytext=(5, 5),
                textcoords="offset points")
    span_x = j.max() - j.min()
    ax.set_xlim(j.min() - 0.5 * max(span_x, 1e-9), j.max() + 0.5 * max(span_x, 1e-9))
    span_y = de.max() - de.min()
    ax.set_ylim(de.min() - 0.3 * max(span_y, 1e-9), de.max() + 0.3 * max(span_y, 1e-9))
    if x0 < j.min() - 0.5 * max(span_x, 1e-9):
        ax.text(0.01, 0.01, f"tangents meet at (−J_F, −E_0) = ({x0:.4g} kg·m², {y0:.4g} J), off the plot",
                transform=ax.transAxes, fontsize=8, color="gray")
    ax.set(xlabel="equivalent inertia J_e [kg·m²]", ylabel="excess work ΔE [J]",
           title=f"{analysis.title}: energy–mass diagram")
    ax.legend(fontsize=8)
    return ax


def check_energy_mass(analysis):
    """Raise ValueError unless the energy–mass diagram can be drawn: torques of the angle only, as curves."""
    if analysis.machine is None or analysis.machine.speed_dependent:
        raise ValueError("the energy–mass diagram needs torques of the angle only given as curves")


RESULT_PLOTS = {
    "sweep": "a result of a sweep against a varied field, one line per group (--by)",
    "pareto": "a Pareto front: the non-dominated designs of two objectives",
}


def _label(column):
    units = {"mass": "kg", "d_outer": "m", "outer_diameter": "m", "d_mean": "m", "b": "m", "h": "m",
             "speed": "rad/s", "j_required": "kg·m²", "rim_speed": "m/s", "delta": "-", "cost": "currency"}
    unit = units.get(column)
    return f"{column} [{unit}]" if unit else column


def _column(frame, name):
    """The column a user names: itself, or the result of that name (``material`` is ``best_material``)."""
    for column in (name, f"best_{name}"):
        if column in frame.columns:
            return column
    raise ValueError(f"the results have no column {name!r} (columns: {', '.join(frame.columns)})")


def pareto_objectives(frame):
    """The two objectives of a front written by ``flyopt pareto``, or None.

    A front has an ``epsilon`` column (the constraint value of each point)
    and its two objectives as its first two columns, mass first.

    Returns
    -------
    tuple of str or None
        ``("mass", "outer_diameter")`` and so on; None for other results (a sweep).
    """
    columns = list(frame.columns)
    if "epsilon" not in columns or len(columns) < 3 or columns[0] != "mass":
        return None
    return tuple(columns[:2])


def plot_sweep(frame, x, y="mass", by=None, ax=None):
    """A sweep's result ``y`` against a varied field ``x``, one line per value of ``by``.

    Points that are not designed (infeasible, failed, not needed) are left out of
    the lines and counted in the legend. A field spanning more than a decade is
    drawn on a log axis. A name that is not a column may name a result:
    ``material`` and ``shaft`` are the winner's, ``best_material`` and
    ``best_shaft``, when the sweep did not vary them.
    """
    x, y = _column(frame, x), _column(frame, y)
    by = _column(frame, by) if by else None
    ax = _axes(ax)
    groups = frame.groupby(by, sort=True) if by else [(None, frame)]
    for key, part in groups:
        part = part.sort_values(x)
        ok = part["status"] == "designed" if "status" in part.columns else np.ones(len(part), bool)
        label = f"{by} = {key}" if by else y
        missing = int((~ok).sum())
        if missing:
            label += f" ({missing} not designed)"
        ax.plot(part[x][ok], part[y][ok], "o-", ms=3, lw=1.2, label=label)
    values = frame[x].to_numpy()
    positive = values[values > 0] if np.issubdtype(values.dtype, np.number) else values[:0]
    if positive.size and positive.max() / positive.min() > 10:
        ax.set_xscale("log")
    ax.set(xlabel=_label(x), ylabel=_label(y), title=f"sweep: {y} against {x}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_pareto(frame, x, y, ax=None):
    """The Pareto front of two objectives (both minimized), non-dominated points joined."""
    x, y = _column(frame, x), _column(frame, y)
    ax = _axes(ax)
    data = frame[[x, y]].dropna().to_numpy(dtype=float)
    order = np.lexsort((data[:, 1], data[:, 0]))
    data = data[order]
    front = data[np.concatenate(([True], data[1:, 1] < np.minimum.accumulate(data[:, 1])[:-1]))]
    ax.plot(data[:, 0], data[:, 1], "o", color="lightgray", ms=4, label="designs")
    ax.step(front[:, 0], front[:, 1], where="post", color=DEFICIT, lw=1.2)
    ax.plot(front[:, 0], front[:, 1], "o", color=DEFICIT, ms=5, label=f"Pareto front ({len(front)})")
    ax.set(xlabel=_label(x), ylabel=_label(y), title=f"Pareto front: {y} against {x}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def save(ax, path):
    """Write the Axes' figure to ``path`` (png, svg or pdf by suffix), atomically.

    Raises
    ------
    SceneError
        See :func:`check_output`.
    OSError
        The folder cannot be written; the error names ``path``.
    """
    check_output(path)
    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    fig = ax.figure
    try:
        handle, tmp = tempfile.mkstemp(suffix=path.suffix, dir=path.parent)
    except OSError as err:
        _pyplot().close(fig)
        raise OSError(err.errno, err.strerror, str(path)) from err
    os.close(handle)
    try:
        fig.savefig(tmp, format=suffix, dpi=150)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
        _pyplot().close(fig)
    return path
