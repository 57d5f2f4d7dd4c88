"""The speed-against-error run: its sections, in order, and the loop that runs them."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable

from flyopt.bench.cycle import section_cycle
from flyopt.bench.design import section_design
from flyopt.bench.geometry import section_geometry
from flyopt.bench.inertia import section_required_inertia
from flyopt.bench.timing import Config, Row
from flyopt.bench.wheel import section_wheel

__all__ = ["SECTIONS", "run"]

SECTIONS: dict[str, Callable[[Config], list[Row]]] = {
    "cycle": section_cycle,
    "design": section_design,
    "geometry": section_geometry,
    "required_inertia": section_required_inertia,
    "wheel": section_wheel,
}
"""Sections of the speed-against-error run, in order: name -> function(config) -> list of Row."""


def run(
    config: Config, sections: Iterable[str] | None = None, progress: Callable[[str], object] | None = None
) -> list[Row]:
    """Run the named sections (default all); return their rows in order."""
    rows = []
    for name in sections or SECTIONS:
        if name not in SECTIONS:
            raise ValueError(f"section {name!r} not recognised; allowed are {list(SECTIONS)}")
        start = time.perf_counter()
        rows += SECTIONS[name](config)
        if progress:
            progress(f"section {name}: {time.perf_counter() - start:.1f} s")
    return rows
