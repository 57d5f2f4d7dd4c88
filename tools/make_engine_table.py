"""Generate the gas-torque table of problems/four-stroke-engine.toml.

A single-cylinder four-stroke engine, bore 100 mm, stroke 120 mm (crank
r = 60 mm), connecting rod l = 240 mm (λ = r/l = 0.25), compression ratio 9.
Gauge gas pressure over 720° of crank angle from an idealised cycle:
intake at -0.1 bar, polytropic compression (n = 1.3) from 1 bar abs at BDC,
combustion raising the pressure to 55 bar abs over 0-15° after TDC,
polytropic expansion (n = 1.3) to BDC, exhaust at +0.15 bar.
Torque = p A r (sin θ + λ sin 2θ / (2 sqrt(1 - λ² sin²θ))) [N*m].
Run: python tools/make_engine_table.py  (prints the TOML points of the torque),
     python tools/make_engine_table.py --force  (the gas force on the piston
     along the slider axis, +x pointing away from the crank, for a [[member]]).
"""

import math

BORE, R, L, CR, N = 0.100, 0.060, 0.240, 9.0, 1.3
LAM = R / L
AREA = math.pi * BORE**2 / 4
P_ATM = 1.0e5


def volume_fraction(theta):
    """Cylinder volume over clearance volume at crank angle theta [rad], TDC = 0."""
    x = R * (1 - math.cos(theta)) + L * (1 - math.sqrt(1 - (LAM * math.sin(theta)) ** 2))
    stroke_volume = 2 * R
    clearance = stroke_volume / (CR - 1)
    return (clearance + x) / clearance


def pressure(deg):
    """Absolute cylinder pressure [Pa] at crank angle deg (0 = TDC of intake)."""
    th = math.radians(deg)
    if deg < 180:
        return 0.9e5
    if deg < 360:
        return 1.0e5 * (volume_fraction(math.radians(180)) / volume_fraction(th)) ** N
    if deg < 540:
        p_top = 1.0e5 * CR**N
        p_peak = 55e5
        if deg < 375:
            return p_top + (p_peak - p_top) * (deg - 360) / 15
        return p_peak * (volume_fraction(math.radians(375)) / volume_fraction(th)) ** N
    return 1.15e5


def torque(deg):
    th = math.radians(deg)
    s = math.sin(th)
    return (pressure(deg) - P_ATM) * AREA * R * (s + LAM * math.sin(2 * th) / (2 * math.sqrt(1 - (LAM * s) ** 2)))


def force(deg):
    """Gas force on the piston along +x (away from the crank) [N]: the gas pushes it towards the crank."""
    return -(pressure(deg) - P_ATM) * AREA


if __name__ == "__main__":
    import sys

    value = force if "--force" in sys.argv else torque
    rows = [f"[{d}, {value(d):.1f}]" for d in range(0, 721, 5)]
    for k in range(0, len(rows), 6):
        print("  " + ", ".join(rows[k : k + 6]) + ",")
