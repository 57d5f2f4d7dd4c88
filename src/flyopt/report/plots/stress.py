"""The stresses over the radius at ω_max: σ_r, σ_t and von Mises, each part's span and allowable."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.design.result import Design
from flyopt.report import display
from flyopt.report.plots import readout, standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from flyopt.design.result import Candidate

#: Colours of the stress curves.
_STRESS_COLOURS = {"sr": "tab:blue", "st": "tab:red", "vm": "black"}
#: Shades of the parts' spans, inner to outer.
_PART_SHADES = ("#eef1f6", "#f8f4ea")


def plot_stress(
    candidate: Candidate,
    profile: Sequence[tuple[str, npt.ArrayLike, npt.ArrayLike, npt.ArrayLike, npt.ArrayLike]],
    beams: Sequence[tuple[str, float, float, float]] = (),
    omega: float | None = None,
    ductile: bool = True,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
    material: str | None = None,
) -> Axes:
    """sigma_r, sigma_t and von Mises over the radius at omega_max, each part's span and allowable.

    Parameters
    ----------
    candidate : flyopt.design.result.Candidate
        A feasible design with its ``parts`` and ``stress`` (the check the
        design carries: each part's governing stress and allowable).
    profile : list of (part, r, sr, st, vm)
        The stresses of the disc parts over their radii [m, Pa], from
        :func:`flyopt.design.strength.profile` at the same speed.
    beams : list of (part, r, sr, st)
        The parts of a ``rim_arms`` wheel the texts treat as beams: the arms'
        root stress (a radial stress at the hub) and the rim's combined hoop
        and bending stress (at its mean radius) [m, Pa].
    omega : float or None
        The speed the stresses are at, on the wheel's shaft [rad/s] (for the title).
    ductile : bool
        Whether the governing stress is von Mises (True) or the largest
        principal stress (False).
    ax : matplotlib Axes, optional
    units : {"engineering", "si", "imperial"}
        Stress and radius in the system's units (MPa over mm by default).
    material : str, optional
        The material's name for people in the title (default: its key with spaces).

    Returns
    -------
    matplotlib Axes
        Lines labelled "σ_r", "σ_t" and "von Mises" (the first part's; the
        others' carry a leading underscore), stress over radius in ``units``.
    """
    display.check_system(units)
    c = candidate
    if not isinstance(c, Design) or not c.parts.items:
        raise ValueError(f"{c.material} on {c.shaft} is not a design: no stresses to draw")
    if not c.stresses.stress:
        raise ValueError(
            f"the design of {c.material} carries no stresses (its notes: {'; '.join(c.provenance.notes) or 'none'})"
        )
    ax, own = standard.axes(ax, figsize=(9, 5.6))
    mm, mpa = 1.0 / standard.unit("length", units)[1], 1.0 / standard.unit("stress", units)[1]
    r_unit, s_unit = standard.unit("length", units)[0], standard.unit("stress", units)[0]
    checked = {p["part"]: p for p in c.stresses.stress.get("parts", [])}
    spans = {p["name"]: (p["r_inner"], p["r_outer"]) for p in c.parts.items}
    # the parts' spans, shaded and named at the top
    for k, p in enumerate(c.parts.items):
        r0, r1 = p["r_inner"] * mm, p["r_outer"] * mm
        ax.axvspan(r0, r1, color=_PART_SHADES[k % 2], lw=0, zorder=0)
        ax.axvline(r0, color="gray", lw=0.5, zorder=1)
        narrow = (r1 - r0) < 0.06 * c.dims.d_outer / 2 * mm
        ax.text(
            0.5 * (r0 + r1),
            0.985,
            p["name"],
            transform=ax.get_xaxis_transform(),
            ha="center",
            va="top",
            fontsize=8,
            color="dimgray",
            rotation=90 if narrow else 0,
        )
    # the curves of the disc parts
    names = {"sr": "σ_r", "st": "σ_t", "vm": "von Mises"}
    stress_scale = standard.scale("stress", units, digits=digits)
    readout.abscissa(ax, "r", standard.scale("length", units, digits=digits))
    for k, (_part, r, sr, st, vm) in enumerate(profile):
        for key, values, style in (("sr", sr, "-"), ("st", st, "-"), ("vm", vm, "--")):
            (line,) = ax.plot(
                np.asarray(r) * mm,
                np.asarray(values) * mpa,
                style,
                color=_STRESS_COLOURS[key],
                lw=1.5,
                label=names[key] if k == 0 else f"_{names[key]}",
            )
            readout.curve(line, names[key], stress_scale)
    # each part's allowable over its span
    allowables = [
        (name, checked[name]["allowable"])
        for name in spans
        if name in checked and _finite_positive(checked[name].get("allowable"))
    ]
    same = len({a for _n, a in allowables}) == 1
    for k, (name, allowable) in enumerate(allowables):
        label = (
            (f"allowable {standard.q(allowable, 'stress', units, digits)}" if same else "allowable of each part")
            if k == 0
            else "_allowable"
        )
        ax.hlines(
            allowable * mpa,
            spans[name][0] * mm,
            spans[name][1] * mm,
            colors=standard.DEFICIT,
            linestyles=":",
            lw=1.8,
            label=label,
        )
        if not same:
            ax.annotate(
                display.number(allowable * mpa, digits),
                (0.5 * (spans[name][0] + spans[name][1]) * mm, allowable * mpa),
                xytext=(0, 2),
                textcoords="offset points",
                ha="center",
                va="bottom",
                fontsize=7,
                color=standard.DEFICIT,
            )
    # the beams of an arms wheel
    beam_words = {"arms": ("arm root (pull + bending)", "^"), "rim": ("rim (hoop + bending)", "s")}
    for part, r, sr, st in beams:
        value = sr if part == "arms" else st
        words, marker = beam_words.get(part, (part, "o"))
        ax.plot(
            [r * mm],
            [value * mpa],
            marker,
            color="tab:purple",
            ms=8,
            zorder=4,
            label=f"{words}: {standard.q(value, 'stress', units, digits)}",
        )
        at = r / (c.dims.d_outer / 2)  # near an end of the axis the label turns inwards
        ha, dx = ("left", -4) if at < 0.15 else ("right", 4) if at > 0.85 else ("center", 0)
        ax.annotate(
            f"{words}\n{standard.q(value, 'stress', units, digits)}",
            (r * mm, value * mpa),
            xytext=(dx, -12),
            textcoords="offset points",
            ha=ha,
            va="top",
            fontsize=8,
            color="tab:purple",
        )
    # the governing point
    where = c.stresses.stress.get("where") or {}
    governing = checked.get(where.get("part"))
    if governing is not None:
        measure = "von Mises" if ductile else "largest principal"
        utilisation = governing["stress"] / governing["allowable"] if governing.get("allowable") else math.nan
        x, y = governing["radius"] * mm, governing["stress"] * mpa
        ax.plot(
            [x],
            [y],
            "o",
            ms=11,
            mfc="none",
            mec="black",
            mew=1.5,
            zorder=5,
            label=f"governing: {governing['part']}, {measure} {standard.q(governing['stress'], 'stress', units, digits)} at "
            f"r = {standard.q(governing['radius'], 'length', units, digits)} ({display.share_of_allowable(utilisation)})",
        )
    ax.axhline(0, color="black", lw=0.6)
    top = max([a for _n, a in allowables] + [governing["stress"] if governing else 0.0]) * mpa
    r_in, r_out = min(spans.values())[0] * mm, c.dims.d_outer / 2 * mm
    # from the axis, unless the wheel is a ring far from it (a bare rim): then its own span
    left = 0.0 if r_in < 0.4 * r_out else r_in - 0.08 * (r_out - r_in)
    ax.set_xlim(left, r_out + 0.03 * (r_out - left))
    low = min([0.0] + [float(np.min(np.minimum(sr, st))) * mpa for _p, _r, sr, st, _v in profile])
    ax.set_ylim(low - 0.05 * top, 1.25 * top if top > 0 else 1.0)
    speed = f" = {standard.q(omega, 'angular_speed', units, digits)}" if omega else ""
    ax.set(xlabel=f"radius r [{r_unit}]", ylabel=f"stress [{s_unit}]")
    name = material or c.material.replace("_", " ")
    standard.title(ax, own, f"{name} {c.geometry} on {c.shaft}", f"stresses over the radius at ω_max{speed}")
    ax.grid(True, alpha=0.3)
    standard.legend(ax, own)
    return ax


def _finite_positive(value: float | None) -> bool:
    return value is not None and math.isfinite(value) and value > 0
