"""The [power_chain] section: a motor driving machines through stages in series and branches in parallel.

In the efficiency chapters' terms (docs/flywheel-design.md, section 21): a trunk of stages from the
motor, then either the machine it drives (a series chain) or ``[[power_chain.branch]]`` tables, each
its own stages and, again, a machine or branches of its own (parallel and mixed set-ups). A machine
is given by the power it delivers: ``power``, or ``force`` with ``velocity``, or ``torque`` with
``speed``; its own efficiency is the last of its branch's stages.
"""

from __future__ import annotations

import math

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SPEED_RANGE, SPEED_WHY, Table, check_count, check_magnitude
from flyopt.io.shaft_section import read_stages
from flyopt.machine.transmission import PowerBranch

LOAD_KEYS = ("power", "force", "velocity", "torque", "speed")
KEYS = {"stages", "branch", "description", *LOAD_KEYS}
BRANCH_KEYS = {"name", *KEYS}
MAX_DEPTH = 8
"""Most levels of branches below the trunk: the set-ups the books draw have one or two."""
MAX_BRANCHES = 64
"""Most branches one split feeds."""
MAX_STAGES = 64
"""Most stages in series in one branch."""
MAX_NAME = 64
POWER_RANGE = (1e-3, 1e10)
POWER_WHY = "1 mW to 10 GW, beyond any machine a motor drives"
FORCE_RANGE = (1e-6, 1e10)
VELOCITY_RANGE = (1e-6, 1e4)
TORQUE_RANGE = (1e-6, 1e10)

#: How a machine's delivered power may be given: the keys, and the dimension of each.
LOADS = {
    "power": (("power", "power"),),
    "force": (("force", "force"), ("velocity", "speed")),
    "torque": (("torque", "torque"), ("speed", "angular_speed")),
}
_RANGES = {
    "power": (*POWER_RANGE, "W", POWER_WHY),
    "force": (*FORCE_RANGE, "N", "a force a machine takes"),
    "velocity": (*VELOCITY_RANGE, "m/s", "a machine's working speed"),
    "torque": (*TORQUE_RANGE, "N*m", "a torque a machine takes"),
    "speed": (*SPEED_RANGE, "rad/s", SPEED_WHY),
}


def read_power_chain(raw: object) -> PowerBranch:
    """[power_chain]: the trunk from the motor, with its machine or its branches (SI)."""
    return _branch(Table(raw, "power_chain", KEYS), "power_chain", "trunk", 0)


def _branch(table: Table, where: str, name: str, depth: int) -> PowerBranch:
    stages = read_stages(table.get("stages"), f"{where}.stages") if table.has("stages") else ()
    check_count(stages, f"{where}.stages", MAX_STAGES, "stages", "in series")
    power = _delivered(table, where)
    if not table.has("branch"):
        if power is None:
            raise SceneError(
                where,
                "gives neither the power its machine delivers (power, force with velocity, or torque with speed) "
                "nor the branches it splits into ([[...branch]])",
            )
        return PowerBranch(name, stages, (), power)
    if power is not None:
        raise SceneError(f"{where}.branch", "a branch ends either at a machine (its power) or in branches, not both")
    raw = table.get("branch")
    if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_BRANCHES:
        raise SceneError(
            f"{where}.branch", f"must be an array of 1 to {MAX_BRANCHES} tables, each a branch with its stages"
        )
    if depth >= MAX_DEPTH:
        raise SceneError(f"{where}.branch", f"nests branches more than {MAX_DEPTH} levels deep")
    branches, seen = [], set()
    for k, item in enumerate(raw):
        at = f"{where}.branch[{k}]"
        child = Table(item, at, BRANCH_KEYS)
        label = child.get("name", f"{k + 1}" if depth == 0 else f"{name}.{k + 1}")
        if not isinstance(label, str) or not label.strip() or len(label) > MAX_NAME:
            raise SceneError(f"{at}.name", f"must be a name of 1 to {MAX_NAME} characters, got {shorten(label)}")
        if label in seen:
            raise SceneError(f"{at}.name", f"branch {shorten(label)} is given twice in the same split")
        seen.add(label)
        branches.append(_branch(child, at, label, depth + 1))
    return PowerBranch(name, stages, tuple(branches), None)


def _delivered(table: Table, where: str) -> float | None:
    """The power a branch's machine delivers [W]: power, F v or T ω; None when the branch gives none of them."""
    given = [key for key in LOADS if table.has(key)]
    if len(given) > 1:
        raise SceneError(
            f"{where}.{given[1]}",
            f"give one of power, force with velocity and torque with speed, not {given[0]} and {given[1]}",
        )
    if not given:
        for key in ("velocity", "speed"):
            if table.has(key):
                other = "force" if key == "velocity" else "torque"
                raise SceneError(f"{where}.{other}", f"is missing ({key} is given: the power is {other} × {key})")
        return None
    for stray in ("velocity", "speed"):
        if table.has(stray) and stray not in (k for k, _ in LOADS[given[0]]):
            raise SceneError(
                f"{where}.{stray}", f"goes with {'force' if stray == 'velocity' else 'torque'}, not with {given[0]}"
            )
    power = 1.0
    for key, dimension in LOADS[given[0]]:
        if not table.has(key):
            raise SceneError(f"{where}.{key}", f"is missing (the power is {' × '.join(k for k, _ in LOADS[given[0]])})")
        value = table.quantity(key, dimension, required=True, own_range=True)
        if not (math.isfinite(value) and value > 0):
            raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table.raw(key))}")
        check_magnitude(value, f"{where}.{key}", table.raw(key), *_RANGES[key])
        power *= value
    check_magnitude(power, f"{where}.{given[0]}", table.raw(given[0]), *_RANGES["power"])
    return power
