"""A small valid scene, and that scene with one line changed: what the scene-reading tests start from."""

VALID = """
title = "t"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
points = [["0 deg", "1600 N*m"], ["45 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]
[torque.driving]
constant = "unknown"
[[shaft]]
name = "main"
speed_ratio = 1.0
"""


def scene_text(old=None, new=None, extra=""):
    text = VALID if old is None else VALID.replace(old, new)
    if old is not None and old not in VALID:
        raise ValueError(f"test bug: {old!r} is not in the base scene")
    return text + extra
