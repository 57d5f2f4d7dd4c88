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
    lines += engine_report(r)
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


def engine_report(result):
    """For an [engine]: the textbook's flywheel beside the exact one, and by how much it is off.

    The textbook's method (flyopt.machine.engine.textbook_requirement) takes
    the crank effort at the mean speed (gas torque plus the inertia torque
    −½ J_e' ω_m²) as a torque curve on a constant inertia; the exact model
    keeps J_e(φ) varying (docs/flywheel-design.md, sections 5 and 6). The
    difference is (J_textbook − J_exact)/J_exact. No lines for a machine that
    is not an engine, or whose inertia is constant (no moving masses: the
    two methods are one).
    """
    machine = result.machine
    if machine is None or not machine.variable_inertia:
        return []
    from flyopt.machine.engine import engine_of, textbook_requirement   # CasADi: loaded with the members

    engine = engine_of(machine)
    if engine is None:
        return []
    deg = math.degrees
    textbook = textbook_requirement(machine, result.omega_mean, result.delta)
    exact = next((m for m in result.models if m["exact"]), None)
    angles = ", ".join(number(deg(a), 4) for a in engine.firing_angles)
    found = f"A_max {number(textbook.a_max)} J, J_F {number(textbook.j_required)} kg·m²"
    if exact is None or exact["j_required"] is None:
        found += "; the exact model gave no J_F to compare with"
    elif exact["j_required"] > 0:
        off = (textbook.j_required - exact["j_required"]) / exact["j_required"]
        found += f", {100 * off:+.3g} % against the exact J_F {number(exact['j_required'])} kg·m² ({exact['model']})"
    else:
        found += (f"; the exact model ({exact['model']}) needs no flywheel (J_F would be "
                  f"{number(exact['j_required'])} kg·m²)")
    return ["", f"Engine: {engine.cylinder_count} cylinder{'s' if engine.cylinder_count > 1 else ''}, "
                f"{engine.cycle}, cycles starting at {angles} deg",
            f"  textbook method (the crank effort at the mean speed, gas torque − ½ J_e′(φ) ω_m², on the constant "
            f"mean J_e {number(textbook.j_machine_mean)} kg·m²):",
            f"    {found}"]


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
        lines += wheel_report(best, result.omega * best.speed_ratio)
    else:
        lines.append("  no feasible design: no material and shaft can give the required inertia")
    rows = []
    for k, c in enumerate(result.candidates, 1):
        if c.feasible:
            rows.append([str(k), c.material, c.shaft, number(c.mass), number(c.d_outer), number(c.h), number(c.b),
                         number(c.rim_speed), ", ".join(c.binding)])
        else:
            rows.append(["-", c.material, c.shaft, "infeasible", "", "", "", "", ""])
    head = ["rank", "material", "shaft", "mass [kg]", "D_outer [m]", "H [m]", "B [m]", "v [m/s]", "binding"]
    align = ["<", "<", "<", ">", ">", ">", ">", ">", "<"]
    if any(c.n_arms for c in result.candidates):   # one combination per arm count: say which
        for row, c in zip(rows, result.candidates):
            row.insert(3, str(c.n_arms or "-"))
        head.insert(3, "arms")
        align.insert(3, ">")
    lines += ["", "Every combination (ranked):"]
    lines += ["  " + line for line in table(head, rows, align)]
    reasons = [c.reason for c in result.candidates if not c.feasible]
    if reasons:
        lines += ["", "Why the infeasible ones fail:"] + [f"  - {r}" for r in reasons]
    return lines


def _finite(value):
    """Whether a reported value exists: not None and a finite number."""
    return value is not None and math.isfinite(value)


def _mm(metres, digits=4):
    return number(None if metres is None else metres * 1e3, digits)


def _mpa(pascals, digits=4):
    return number(pascals / 1e6, digits) if _finite(pascals) else "-"


def wheel_report(candidate, omega):
    """The whole wheel of a design: its parts, stress check, burst speed, balance, key, sensitivities, notes.

    Parameters
    ----------
    candidate : flyopt.design.result.Candidate
        A feasible design.
    omega : float
        omega_max on the wheel's own shaft [rad/s] (the speed the stresses were checked at).

    Returns
    -------
    list of str
        Report lines; a block appears only where the design carries its data
        (a textbook rim has parts and stresses, but no key).
    """
    c = candidate
    lines = []
    if c.parts:
        total_j = sum(p["inertia"] for p in c.parts)
        rows = [[p["name"], f"{_mm(p['r_inner'])} – {_mm(p['r_outer'])}", _mm(p["thickness"]), number(p["mass"]),
                 number(p["inertia"]), f"{100 * p['inertia'] / total_j:.1f} %" if total_j > 0 else "-"]
                for p in c.parts]
        rows.append(["total", f"{_mm(min(p['r_inner'] for p in c.parts))} – "
                              f"{_mm(max(p['r_outer'] for p in c.parts))}", "",
                     number(sum(p["mass"] for p in c.parts)), number(total_j), "100.0 %" if total_j > 0 else "-"])
        head = ["part", "r_inner – r_outer [mm]", "thickness [mm]", "mass [kg]", "inertia [kg·m²]", "share of J"]
        lines += ["", "Parts of the wheel (thickness: axial):"]
        body = table(head, rows, ["<", ">", ">", ">", ">", ">"])
        body.insert(len(body) - 1, "  ".join("-" * len(cell) for cell in body[1].split("  ")))
        lines += ["  " + line for line in body]
        if c.n_arms and c.arm_major:
            lines.append(f"  arms: {c.n_arms} of elliptical section {_mm(c.arm_major)} x {_mm(c.arm_minor)} mm "
                         "(major axis in the plane of rotation, minor axial)")
    if c.stress:
        s = c.stress
        lines += ["", f"Stress check at ω_max = {number(omega)} rad/s ({number(rad_s_to_rpm(omega))} rpm) on its shaft:"]
        rows = []
        for p in s.get("parts", []):
            utilisation = p["stress"] / p["allowable"] if _finite(p["allowable"]) and p["allowable"] > 0 else None
            rows.append([p["part"], _mpa(p["stress"]), _mm(p["radius"]), _mpa(p["allowable"]),
                         "-" if utilisation is None else f"{100 * utilisation:.1f} %",
                         _mpa(p.get("strength")), _mm(p.get("wall"))])
        head = ["part", "stress [MPa]", "at r [mm]", "allowable [MPa]", "utilisation", "strength [MPa]",
                "at wall [mm]"]
        lines += ["  " + line for line in table(head, rows)]
        lines.append("  (stress: von Mises if ductile, largest principal if brittle; strength: yield if ductile, "
                     "tensile if brittle, at the part's wall)")
        where = s.get("where") or {}
        facts = []
        if where:
            facts.append(("governing", f"{where['part']} at r = {_mm(where['radius'])} mm"))
        facts.append(("largest σ_t / σ_r", f"{_mpa(s.get('hoop_max'))} / {_mpa(s.get('radial_max'))} MPa "
                                           f"(von Mises {_mpa(s.get('von_mises'))} MPa)"))
        if _finite(s.get("mean_hoop")):
            facts.append(("mean hoop stress", f"{_mpa(s['mean_hoop'])} MPa over the radial section"))
        if _finite(c.strength_safety):
            facts.append(("safety on strength", number(c.strength_safety, 3)))
        if _finite(c.burst_speed):
            margin = f" ({number(c.speed_margin, 3)} x ω_max)" if _finite(c.speed_margin) else ""
            facts.append(("burst speed", f"{number(rad_s_to_rpm(c.burst_speed))} rpm on its shaft{margin}"))
        width = max(len(k) for k, _ in facts)
        lines += [f"  {k:<{width}}  {v}" for k, v in facts]
    if _finite(c.unbalance_permissible):
        lines += ["", f"Permissible unbalance (ISO 21940-11, G6.3 at ω_max): {number(c.unbalance_permissible * 1e6)} g·mm"
                      + (f" (e_per {number(c.unbalance_permissible / c.mass * 1e6, 4)} µm)" if c.mass else "")]
    if c.key:
        k = c.key
        verdict = "OK" if k["ok"] else "NOT OK"
        lines += ["", f"Key (DIN 6885-1 form A) on a {_mm(c.bore)} mm bore: {k['size']}, length {_mm(k['length'])} mm "
                      f"(effective {_mm(k['effective_length'])} mm): {verdict}",
                  f"  at the peak torque {number(k['torque'])} N·m: bearing pressure {_mpa(k['bearing_pressure'])} MPa "
                  f"(allowable {_mpa(k['allowable_pressure'])} MPa), shear {_mpa(k['shear'])} MPa "
                  f"(allowable {_mpa(k['allowable_shear'])} MPa)"]
    if c.sensitivities:
        lines += ["", "Sensitivities of the mass:"]
        lines += [f"  - {s['text']}" for s in c.sensitivities]
    if c.notes:
        lines += ["", "Notes:"] + [f"  - {n}" for n in c.notes]
    return lines


def verification_report(v):
    """The verification part of the ``flyopt solve --verify`` report."""
    verdict = "FLAGGED: the design misses the allowed δ" if v.flagged else "ok"
    return ["", f"Verification ({v.method}): {verdict}",
            f"  achieved δ {number(v.achieved_delta)} against the allowed {number(v.delta_allowed)} "
            f"(tolerance {number(v.tolerance, 3)}); ω {number(v.omega_min)} to {number(v.omega_max)} rad/s, "
            f"mean {number(v.omega_mean)}; flywheel {number(v.j_flywheel)} kg·m² at the reference shaft"]
