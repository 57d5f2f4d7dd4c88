"""The mounting shaft with its wheel: the moments and torque along it with its utilisation, and a Campbell
diagram of its torsional modes against the orders of the cycle's net torque (docs/flywheel-design.md,
section 26)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from flyopt.design.combination import shaft_label
from flyopt.report import display
from flyopt.report.plots import standard
from flyopt.units import rpm_to_rad_s

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.design.shaft.cycle import ShaftReport
    from flyopt.machine.shaft_layout import ShaftLayout

__all__ = ["plot_shaft", "plot_campbell"]

#: Above this many orders the Campbell diagram draws their lines thin and light and their crossings small.
DENSE_ORDERS = 12


def _outline(ax: Axes, layout: ShaftLayout, units: str, top: float) -> None:
    """The shaft's steps as a profile under the curves, the bearings as triangles, the wheel as a bar."""
    x0 = 0.0
    scale = 0.12 * top / max(layout.diameters)
    for end, d in zip(layout.steps, layout.diameters):
        xs = standard.show(np.array([x0, end]), "length", units)
        ax.fill_between(xs, -scale * d / 2 - 0.2 * top, scale * d / 2 - 0.2 * top, color="0.85", lw=0.5, ec="0.5")
        x0 = end
    for b in layout.bearings:
        ax.plot(
            standard.show(b, "length", units), -0.2 * top - scale * max(layout.diameters) / 2, "^", color="0.3", ms=9
        )
    wx = standard.show(layout.wheel_at, "length", units)
    ax.plot([wx, wx], [-0.36 * top, -0.04 * top], color="tab:brown", lw=5, solid_capstyle="butt")


def plot_shaft(
    report: ShaftReport,
    layout: ShaftLayout,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """The bending moment amplitude M_a, the steady moment M_m and the torque along the shaft, with the plain
    section's fatigue utilisation on the right axis and the checked sections' utilisation marked.

    Parameters
    ----------
    report : ShaftReport
        The chosen wheel's shaft check (:func:`flyopt.design.shaft.cycle.report`).
    layout : ShaftLayout
        The shaft as described (its steps, bearings and wheel seat, drawn under the curves).
    units, digits
        The unit system (the moment axis takes its prefix from the moments and torque it draws,
        :func:`~flyopt.report.plots.standard.scale`) and the significant figures written.
    """
    ax, own = standard.axes(ax)
    c, diagram = report.check, report.check.diagram
    x = standard.show(diagram["x"], "length", units)
    moment = standard.scale(
        "torque", units, [diagram["moment_alternating"], diagram["moment_mean"], diagram["torque"]], digits
    )
    ma, mm, t = (
        moment.show(diagram["moment_alternating"]),
        moment.show(diagram["moment_mean"]),
        moment.show(diagram["torque"]),
    )
    ax.plot(x, ma, color="tab:blue", label="bending moment amplitude M_a (weight and pulls: fully reversed)")
    ax.plot(x, mm, color="tab:green", ls="--", label="steady bending M_m (permissible unbalance)")
    source = (
        "at the seat, the train's forced response" if c.torque_source == "forced response" else "the wheel exchanges"
    )
    ax.plot(x, t, color="tab:red", label=f"torque T_m + T_a {source}")
    top = float(max(np.max(ma), np.max(t), np.max(mm), 1e-12))
    _outline(ax, layout, units, top)
    ax.set_ylim(-0.45 * top, 1.15 * top)
    ax.set_xlabel(standard.axis_label("position along the shaft", "length", units))
    ax.set_ylabel(moment.axis_label("moment, torque"))
    ax.grid(alpha=0.3)
    right = ax.twinx()
    right.plot(x, diagram["utilisation"], color="black", lw=0.8, alpha=0.6, label="fatigue utilisation, plain section")
    for section in c.sections:
        use = report.check.limits[0].allowed / section.fatigue
        notched = section.kf > 1.0
        right.plot(standard.show(section.x, "length", units), use, "o" if notched else ".", color="black", ms=5)
        if notched:  # the keyseat and the shoulders, where K_f raises the utilisation above the plain line
            right.annotate(
                f"{section.name.split(' at ')[0]} {display.number(use, min(digits, 3))}",
                (standard.show(section.x, "length", units), use),
                textcoords="offset points",
                xytext=(4, 6),
                fontsize=standard.FONT - 1,
            )
    right.axhline(1.0, color="black", ls=":", lw=0.8)
    right.set_ylim(-0.45 * max(1.2, right.get_ylim()[1]), 1.15 * max(1.2, right.get_ylim()[1]))
    right.set_ylabel("fatigue utilisation n_required / n_f [-]")
    binding = c.binding
    standard.title(
        ax,
        own,
        f"The {shaft_label(report.shaft)} with the chosen wheel: moments and torque along it "
        "(dots: the sections checked; labelled: the notched ones)",
        f"binding: {binding.kind} {display.said_text(binding.where, units, digits)}, utilisation {display.number(binding.utilisation, display.UTILISATION_DIGITS)}",
    )
    handles = ax.get_legend_handles_labels()[0] + right.get_legend_handles_labels()[0]
    standard.legend(ax, own, handles=handles)
    return ax


def plot_campbell(
    report: ShaftReport,
    layout: ShaftLayout,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """Campbell diagram: the torsional modes [Hz] (horizontal: a torsional train has no gyroscopic term)
    against the order lines f = q n / 60 of the orders present, the running range shaded, the crossings marked.

    Raises
    ------
    ValueError
        When the shaft has no elastic torsional mode (no inertia on it besides the wheel) or no orders.
    """
    check = report.check.torsional
    if check is None or not check.critical:
        raise ValueError("the shaft has no elastic torsional mode (no inertia on it besides the wheel) or no orders")
    ax, own = standard.axes(ax)
    low, high = check.speed_range_rpm
    modes = np.asarray(check.modes.frequencies_hz, dtype=float)
    crossings = [c.speed_rpm for c in check.critical]
    n_top = 1.3 * max(high, min(max(crossings), 4.0 * high))
    rpm = np.linspace(0.0, n_top, 200)
    shown = standard.show(rpm_to_rad_s(rpm), "angular_speed", units)
    worst = next((lim for lim in report.check.limits if lim.kind == "torsional"), None)
    worst_order = None if worst is None else float(worst.where.split()[-1])
    labelled = set(np.sort(check.orders)[:4].tolist()) | ({worst_order} if worst_order is not None else set())
    placed: list[tuple[int, float]] = []  # (index along the speed axis, frequency) of each label drawn
    gap = 0.05 * 1.15 * modes.max()  # labels at the same speed (the right edge) at least this far apart
    many = len(check.orders) > DENSE_ORDERS  # a pulse's many orders: thin lines and small dots, or a grey wash
    for q in sorted(check.orders, key=lambda o: (float(o) != worst_order, -float(o))):
        f = q * rpm / 60.0
        nearest = worst_order is not None and math.isclose(float(q), worst_order, rel_tol=1e-5)  # :g in its words
        ax.plot(
            shown,
            f,
            color="tab:red" if nearest else "0.75" if many else "0.6",
            lw=0.9 if nearest else 0.35 if many else 0.7,
        )
        k = min(int(np.searchsorted(f, 1.15 * modes.max())), len(f) - 1)
        crowded = any(j == k and abs(f[k] - g) < gap for j, g in placed)
        if float(q) in labelled and not crowded:  # the lowest orders and the nearest; none over another
            placed.append((k, float(f[k])))
            ax.annotate(
                f"{q:.3g}",
                (shown[k], f[k]),
                textcoords="offset points",
                xytext=(-12, -2),
                fontsize=standard.FONT - 1,
                color="0.3",
            )
    for m, f_m in enumerate(modes, start=1):
        ax.axhline(f_m, color="tab:blue", lw=1.4, label=f"torsional mode {m}: {display.number(f_m, digits)} Hz")
    margin = layout.critical_margin
    ax.axvspan(
        standard.show(rpm_to_rad_s(low * (1.0 - margin)), "angular_speed", units),
        standard.show(rpm_to_rad_s(high * (1.0 + margin)), "angular_speed", units),
        color="tab:orange",
        alpha=0.12,
        label=f"the range widened by the margin, {100 * margin:.3g} %",
    )
    ax.axvspan(
        standard.show(rpm_to_rad_s(low), "angular_speed", units),
        standard.show(rpm_to_rad_s(high), "angular_speed", units),
        color="tab:orange",
        alpha=0.35,
        label="running range ω_m (1 ∓ δ/2)",
    )
    inside = [c for c in check.critical if c.speed_rpm <= n_top]
    for c in inside:
        colour = "tab:red" if report.check.binding.kind == "torsional" and c.in_range else "black"
        ax.plot(
            standard.show(rpm_to_rad_s(c.speed_rpm), "angular_speed", units),
            c.frequency_hz,
            "o",
            ms=2.2 if many else 4,
            color=colour,
        )
    if worst is not None:
        ax.plot(
            standard.show(rpm_to_rad_s(worst.value), "angular_speed", units),
            float(modes[int(worst.where.split()[1]) - 1]),
            "s",
            ms=9,
            mfc="none",
            color="tab:red",
            label=f"nearest: {worst.where}, {standard.q(rpm_to_rad_s(worst.value), 'angular_speed', units, digits)} "
            f"(utilisation {display.number(worst.utilisation, display.UTILISATION_DIGITS)})",
        )
    ax.set_xlim(0.0, shown[-1])
    ax.set_ylim(0.0, 1.25 * modes.max())
    ax.set_xlabel(standard.axis_label("speed of the shaft", "angular_speed", units))
    ax.set_ylabel("frequency [Hz]")
    ax.grid(alpha=0.3)
    standard.title(
        ax,
        own,
        f"Campbell diagram of the {shaft_label(report.shaft)}: torsional modes and the orders of the cycle's net torque",
        "grey: the order lines f = q n / 60 of the orders present (the lowest and the nearest labelled q); dots: their crossings with the modes",
    )
    standard.legend(ax, own)
    return ax
