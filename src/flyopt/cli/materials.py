"""``flyopt materials [--units SYSTEM] [--digits N] [--json]``: the built-in material library, as a table or JSON.

Every material of ``flyopt/data/materials.toml``
(:func:`flyopt.design.materials.builtin_materials`), with its density,
strengths, safe rim speed, ductility and source: what a scene may name in
``[design] materials`` without defining it.
"""

from __future__ import annotations

import argparse
import re
from typing import TYPE_CHECKING, Any

from flyopt.cli.exits import EXIT_OK
from flyopt.report import display

if TYPE_CHECKING:
    from flyopt.design.materials import Material

__all__ = ["library_rows", "material_row", "add_materials_arguments", "run_materials"]


#: The columns of the table: (key, heading, dimension or None for text).
COLUMNS = (
    ("name", "name", None),
    ("display_name", "display name", None),
    ("density", "density", "density"),
    ("tensile_strength", "R_m", "stress"),
    ("yield_strength", "R_p0.2", "stress"),
    ("rim_speed_limit", "v_max", "speed"),
    ("ductile", "ductile", None),
    ("default", "default", None),
    ("source", "source", None),
)


def library_rows() -> list[dict[str, Any]]:
    """One row per built-in material, values in SI: what ``flyopt materials --json`` prints.

    ``rim_speed_limit`` [m/s] is the material's own safe rim speed (given, or
    derived from its allowable stress or its strengths and own safety factor);
    None for a material given by strengths without a factor: its limit then
    follows from the design's safety factor. ``default`` says whether a design
    uses it when the scene names no materials. Strengths from a table by
    thickness are its weakest row.
    """
    from flyopt.design.materials import builtin_materials

    defaults = builtin_materials(default_only=True)
    return [material_row(m, m.name in defaults) for m in builtin_materials(default_only=False).values()]


def material_row(material: Material, default: bool) -> dict[str, Any]:
    """One material's row of :func:`library_rows` (SI), ``default`` whether a design uses it by default; the
    app's library (:mod:`flyopt.app.materials`) writes a scene's own materials by it too."""
    return {
        "name": material.name,
        "display_name": material.display_name,
        "density": material.density,
        "tensile_strength": material.tensile_strength,
        "yield_strength": material.yield_strength,
        "rim_speed_limit": material.max_rim_speed,
        "ductile": material.ductile,
        "default": default,
        "source": " ".join(material.source.split()),
    }


def add_materials_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt materials``; the handler is :func:`run_materials`."""
    from flyopt.cli.scene import add_digits_argument, units_help

    parser.add_argument("--units", choices=display.SYSTEMS, default=display.DEFAULT, help=units_help("the table"))
    add_digits_argument(parser, "the table")
    parser.add_argument(
        "--json", action="store_true", help="print one JSON object, all numbers in SI whatever --units says"
    )
    parser.set_defaults(run=run_materials)


def run_materials(args: argparse.Namespace) -> int:
    """``flyopt materials``: the library as a table in the user's units, or as JSON (SI)."""
    rows = library_rows()
    if args.json:
        from flyopt.outputs.documents import json_text

        units = {key: display.unit(dimension, "si")[0] for key, _, dimension in COLUMNS if dimension}
        print(json_text({"materials": rows, "units": units}))
        return EXIT_OK
    print(_table(rows, args.units, args.digits))
    return EXIT_OK


def _cell(value: Any, dimension: str | None, system: str, digits: int = display.DEFAULT_DIGITS) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if dimension is None:
        return str(value)
    return display.number(display.show(float(value), dimension, system), digits)


def _table(rows: list[dict[str, Any]], system: str, digits: int = display.DEFAULT_DIGITS) -> str:
    """The rows as aligned columns, headings with units; a source cut to its first clause."""
    headings = [
        heading if dimension is None else f"{heading} [{display.label(dimension, system)}]"
        for _, heading, dimension in COLUMNS
    ]
    cells = []
    for row in rows:
        line = [_cell(row[key], dimension, system, digits) for key, _, dimension in COLUMNS]
        source = re.split(r"[;.](?:\s|$)", line[-1], maxsplit=1)[0]
        line[-1] = source if len(source) <= 60 else source[:59] + "…"
        cells.append(line)
    widths = [max(len(text) for text in column) for column in zip(headings, *cells)]
    numeric = [dimension is not None for _, _, dimension in COLUMNS]

    def format_line(texts: list[str]) -> str:
        parts = [t.rjust(w) if right else t.ljust(w) for t, w, right in zip(texts, widths, numeric)]
        return "  ".join(parts).rstrip()

    notes = [
        "",
        "R_m, R_p0.2: tensile and yield strength (a table by thickness: its weakest row); v_max: the safe rim speed",
        "('-': from the design's safety factor); default: used when a scene names no materials.",
        "Full sources: flyopt materials --json. A scene's [[material]] adds or replaces one (docs/scene-schema.md).",
    ]
    return "\n".join([format_line(headings), *(format_line(line) for line in cells), *notes])
