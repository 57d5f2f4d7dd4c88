"""The terminal flyopt writes to: a console that cannot show a character gets it spelled in ASCII.

flyopt's reports write the engineer's symbols (ω, δ, kg·m², 1,462 – 1,538 rpm).
A terminal whose encoding lacks them (``LC_ALL=C``, ``PYTHONIOENCODING=ascii``,
a Windows code page) made every report end in "'ascii' codec can't encode
character" and exit 1. :func:`fit_streams` lets stdout and stderr write such a
character in the words a plain-text engineering document uses (``omega``,
``delta``, ``kg*m^2``), and any other as its code point (``\\u2202``); a UTF-8
console is left as it is.
"""

from __future__ import annotations

import codecs
import sys

__all__ = ["ASCII_SPELLING", "fit_streams"]

#: How a character flyopt writes is spelled where the console cannot show it.
ASCII_SPELLING = {
    "·": "*",
    "×": "x",
    "−": "-",
    "–": "-",
    "—": "-",
    "…": "...",
    "⋯": "...",
    "²": "^2",
    "³": "^3",
    "⁴": "^4",
    "⁻": "^-",
    "±": "+/-",
    "≈": "~",
    "≤": "<=",
    "≥": ">=",
    "≠": "!=",
    "→": "->",
    "°": " deg",
    "µ": "u",
    "√": "sqrt",
    "½": "1/2",
    "′": "'",
    "ω": "omega",
    "Ω": "Omega",
    "δ": "delta",
    "Δ": "Delta",
    "φ": "phi",
    "Φ": "Phi",
    "η": "eta",
    "θ": "theta",
    "π": "pi",
    "ψ": "psi",
    "ρ": "rho",
    "σ": "sigma",
    "Σ": "Sum",
    "τ": "tau",
    "ε": "epsilon",
    "β": "beta",
    "α": "alpha",
    "λ": "lambda",
    "ζ": "zeta",
    "γ": "gamma",
    "ν": "nu",
    "₀": "0",
    "₁": "1",
    "₂": "2",
    "Ø": "dia. ",
    "é": "e",
}

_HANDLER = "flyopt.ascii"


def _spell(error: UnicodeError) -> tuple[str, int]:
    if not isinstance(error, UnicodeEncodeError):
        raise error
    text = error.object[error.start : error.end]
    return "".join(ASCII_SPELLING.get(c, _escape(c)) for c in text), error.end


def _escape(character: str) -> str:
    """Python's escape of a character: ``\\u2202``, ``\\U0001f600`` beyond the 16-bit plane."""
    code = ord(character)
    return f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}"


codecs.register_error(_HANDLER, _spell)


def fit_streams() -> None:
    """Let stdout and stderr spell in ASCII what their encoding cannot write (see the module's note)."""
    for stream in (sys.stdout, sys.stderr):
        encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
        if encoding.startswith("utf") or not hasattr(stream, "reconfigure"):
            continue
        stream.reconfigure(errors=_HANDLER)
