"""Readable text reports of an analysis (and, later, of a design)."""

import math

from flyopt.units import rad_s_to_rpm


def number(value, digits=6):
    """A number with ``digits`` significant digits, no exponent for everyday sizes."""
    if value is None:
        return "-"
    if not math.isfinite(value):
        return str(value)            # inf, -inf, nan: say so rather than fail
    if value == 0:
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    if -4 <= magnitude < 9:
        decimals = max(digits - 1 - magnitude, 0)
        return f"{value:,.{decimals}f}".rstrip("0").rstrip(".") if decimals else f"{value:,.0f}"
    return f"{value:.{digits - 1}e}"


def power(watts):
    return "-" if watts is None else (f"{number(watts / 1000)} kW" if abs(watts) >= 1000 else f"{number(watts)} W")


def table(header, rows, align=None):
    """Fixed-width table: a header row, a rule, then the rows."""
    cells = [header] + [[str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    align = align or ["<"] + [">"] * (len(header) - 1)
    lines = ["  ".join(f"{c:{a}{w}}" for c, a, w in zip(r, align, widths)).rstrip() for r in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return lines


def analysis_report(result, source=None):
    """The report of ``flyopt solve`` for the cycle analysis, as text."""
    r = result
    deg = math.degrees
    lines = [f"{r.title}" + (f"  ({source})" if source else ""), f"model: {r.model}: {r.model_reason}", ""]
    facts = [
        ("mean speed", f"{number(r.omega_mean)} rad/s ({number(rad_s_to_rpm(r.omega_mean))} rpm)"),
        ("allowed δ", f"{number(r.delta)} (1/{number(1 / r.delta, 4)})"),
        ("speed range", f"{number(r.omega_min)} to {number(r.omega_max)} rad/s"),
        ("cycle", f"{number(deg(r.cycle_angle))} deg"),
    ]
    if r.work_per_cycle is not None:
        facts += [
            ("driving torque (mean)", f"{number(r.driving_torque)} N·m"),
            ("resisting torque (mean)", f"{number(r.resisting_torque)} N·m"),
            ("work per cycle", f"{number(r.work_per_cycle)} J"),
            ("mean driving power", power(r.power)),
            ("motor power", f"{power(r.motor_power)} (efficiency {number(r.efficiency, 4)})"),
        ]
    facts.append(("A_max", f"{number(r.a_max)} J"))
    if r.angle_omega_max is not None:
        facts.append(("ω_max / ω_min at", f"{number(deg(r.angle_omega_max))} / {number(deg(r.angle_omega_min))} deg"))
        if (r.angle_delta_e_max, r.angle_delta_e_min) != (r.angle_omega_max, r.angle_omega_min):
            facts.append(("ΔE max / min at", f"{number(deg(r.angle_delta_e_max))} / "
                          f"{number(deg(r.angle_delta_e_min))} deg (where the speed is extreme differs: "
                          f"the inertia varies or a torque depends on speed)"))
    else:
        facts.append(("ω_max / ω_min at", f"the end of area {r.index_omega_max} / area {r.index_omega_min}"))
    if r.j_constant:
        facts.append(("machine's own J_c", f"{number(r.j_constant)} kg·m²"))
    if r.flywheel_needed:
        facts.append(("required flywheel J_F", f"{number(r.j_required)} kg·m² (GD² {number(r.gd2_required)} N·m²) "
                                                "at the reference shaft"))
    else:
        facts.append(("required flywheel", f"none: the machine's own inertia suffices "
                                            f"(J_F would be {number(r.j_margin)} kg·m²)"))
    width = max(len(k) for k, _ in facts)
    lines += [f"  {k:<{width}}  {v}" for k, v in facts]

    if r.startup is not None:
        st = r.startup
        facts_text = (f"{number(st.time)} s ({number(st.cycles, 4)} cycles) to {number(st.omega_target)} rad/s"
                      if st.time is not None else f"not reached: {st.note}")
        lines.append(f"  {'start-up':<{width}}  {facts_text}; {st.method}")
    if len(r.models) > 1 or (r.models and not r.models[0]["exact"]):
        lines += ["", "Models (J_F each asks for, and the δ it really gives by the exact model):"]
        rows = []
        for m in r.models:
            rows.append([m["model"] + (" (exact)" if m["exact"] else ""), number(m["j_required"]),
                         "-" if m["j_error"] is None else f"{100 * m['j_error']:+.3g} %",
                         number(m["achieved_delta"]), m["note"]])
        lines += ["  " + line for line in table(["model", "J_F [kg·m²]", "vs exact", "achieved δ", "note"], rows,
                                                ["<", ">", ">", ">", "<"])]
    lines += ["", "Energy indicator diagram (excess work from the cycle start):"]
    rows = []
    for e in r.energy_chain:
        same = (r.angle_delta_e_max, r.angle_delta_e_min) == (r.angle_omega_max, r.angle_omega_min)
        top, bottom = ("ω_max", "ω_min") if same else ("ΔE max", "ΔE min")
        mark = top if e["index"] == r.index_omega_max else bottom if e["index"] == r.index_omega_min else ""
        where = number(deg(e["angle"])) if e["angle"] is not None else \
            ("start" if e["index"] == 0 else f"after area {e['index']}")
        rows.append([where, number(e["delta_e"]), mark])
    head = ["angle [deg]" if r.angle_omega_max is not None else "point", "ΔE [J]", ""]
    lines += ["  " + line for line in table(head, rows, ["<", ">", "<"])]

    lines += ["", "Flywheel needed on each shaft (same kinetic energy, J' = J (ω/ω')²):"]
    rows = [[s.name, number(s.speed_ratio), number(rad_s_to_rpm(s.omega)), number(s.j_required),
             number(s.gd2_required)] for s in r.shafts]
    lines += ["  " + line for line in table(["shaft", "speed ratio", "speed [rpm]", "J [kg·m²]", "GD² [N·m²]"], rows)]
    return "\n".join(lines)


def _solved_by(candidate):
    """How a design was found, in words: the exact closed form or IPOPT with its status."""
    if candidate.solver_status == "closed_form":
        return "the exact closed form of the lightest wheel, checked against every constraint"
    return (f"IPOPT ({candidate.solver_status}, {candidate.iterations} iterations), checked against every "
            f"constraint")


def design_report(result, spec=None):
    """The design part of the ``flyopt solve`` report: the winner and the ranking of every combination."""
    lines = ["", f"Flywheel design ({result.spec.geometry}, objective: {result.spec.objective}):"]
    if result.status == "not_needed":
        return lines + [f"  {result.message}"]
    best = result.best
    if best is not None:
        facts = [
            ("material / shaft", f"{best.material} on {best.shaft} (speed ratio {number(best.speed_ratio)})"),
            ("mass", f"{number(best.mass)} kg" + (f" (cost {number(best.cost)})" if best.cost is not None else "")),
            ("outer / mean / inner diameter", f"{number(best.d_outer)} / {number(best.d_mean)} / "
                                              f"{number(best.d_inner)} m"),
            ("rim H x B", f"{number(best.h)} x {number(best.b)} m (H/B {number(best.hb_ratio, 4)})"),
            ("inertia", f"{number(best.j_flywheel)} kg·m² on its shaft = {number(best.j_at_reference)} kg·m² "
                        "at the reference shaft"),
            ("rim speed", f"{number(best.rim_speed)} m/s (limit {number(best.rim_speed_limit)} m/s), "
                          f"hoop stress ρv² {number(best.hoop_stress / 1e6)} MPa"
             + (f", safety factor {number(best.safety_factor, 3)}" if best.safety_factor else "")),
            ("binding", ", ".join(best.binding) or "none"),
            ("solved by", _solved_by(best)),
        ]
        width = max(len(k) for k, _ in facts)
        lines += [f"  {k:<{width}}  {v}" for k, v in facts]
        if not result.spec.has_envelope:
            lines.append("  note: no envelope (design.max_outer_diameter) is set, so only the rim speed limit "
                         "bounds the diameter")
    else:
        lines.append("  no feasible design: no material and shaft can give the required inertia")
    rows = []
    for k, c in enumerate(result.candidates, 1):
        if c.feasible:
            rows.append([str(k), c.material, c.shaft, number(c.mass), number(c.d_outer), number(c.h), number(c.b),
                         number(c.rim_speed), ", ".join(c.binding)])
        else:
            rows.append(["-", c.material, c.shaft, "infeasible", "", "", "", "", ""])
    lines += ["", "Every combination (ranked):"]
    lines += ["  " + line for line in table(["rank", "material", "shaft", "mass [kg]", "D_outer [m]", "H [m]", "B [m]",
                                             "v [m/s]", "binding"], rows, ["<", "<", "<", ">", ">", ">", ">", ">", "<"])]
    reasons = [c.reason for c in result.candidates if not c.feasible]
    if reasons:
        lines += ["", "Why the infeasible ones fail:"] + [f"  - {r}" for r in reasons]
    return lines


def verification_report(v):
    """The verification part of the ``flyopt solve --verify`` report."""
    verdict = "FLAGGED: the design misses the allowed δ" if v.flagged else "ok"
    return ["", f"Verification ({v.method}): {verdict}",
            f"  achieved δ {number(v.achieved_delta)} against the allowed {number(v.delta_allowed)} "
            f"(tolerance {number(v.tolerance, 3)}); ω {number(v.omega_min)} to {number(v.omega_max)} rad/s, "
            f"mean {number(v.omega_mean)}; flywheel {number(v.j_flywheel)} kg·m² at the reference shaft"]
