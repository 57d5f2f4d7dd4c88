"""Sentences that keep their quantities: what the design layer says in words, shown in the reader's units.

A reason ("the envelope caps the outer diameter at 1.2 m, where ...") or a limit's place ("at bearing A
(60 mm)") is written by the design layer in SI or engineering units, and that string is what the JSON, the
goldens and every caller read. A :class:`Said` *is* that string, and keeps beside it a template with a named
placeholder for each number and the number itself (SI, with its dimension): a text or a report in another
unit system fills the template in its units (:func:`flyopt.report.display.said_text`) instead of printing
metres and kg·m² among inches and lb·ft² (issue 29: units that drift within one output).

Sentences are joined with ``+`` (a plain string on either side is taken as words, its braces escaped) or
:func:`join`; an f-string or ``str.join`` gives a plain string, the quantities lost.

This module imports nothing from flyopt, so every stage may use it.
"""

from __future__ import annotations

import functools
import string
from collections.abc import Iterable, Mapping
from typing import Any

__all__ = ["Said", "said", "join", "counted", "indefinite", "removeprefix", "said_by", "template", "quantities"]

#: One quantity of a sentence: (value in SI, dimension as flyopt.report.display names it, the text as written).
Quantity = tuple[float, str, str]


class Said(str):
    """A sentence as written (the ``str``), with its template and quantities (see the module's text).

    Made by :func:`said`; ``template`` holds ``{name}`` for each quantity and ``{{``/``}}`` for a brace of the
    words, ``values`` maps each name to its :data:`Quantity` (SI value, dimension, text as written).
    """

    template: str
    values: Mapping[str, Quantity]

    def __add__(self, other: object) -> Any:
        if not isinstance(other, str):
            return NotImplemented
        return _joined((self, other))

    def __radd__(self, other: object) -> Any:
        if not isinstance(other, str):
            return NotImplemented
        return _joined((other, self))


def said(words: str, **quantities: Quantity) -> Said:
    """The sentence ``words`` with each ``{name}`` filled by its quantity's text as written.

    Parameters
    ----------
    words : str
        The template: ``{name}`` for each quantity (no format spec), ``{{`` and ``}}`` for braces.
    **quantities : (float, str, str)
        Each placeholder's (value in SI, dimension, the text the sentence has always had there: "1.2 m").

    Returns
    -------
    Said
        ``str`` of it is ``words`` filled with the texts as written.
    """
    named = _names(words)
    if named != quantities.keys():
        raise ValueError(f"said: the placeholders {sorted(named)} and the quantities {sorted(quantities)} differ")
    values = {k: (float(q[0]), str(q[1]), str(q[2])) for k, q in quantities.items()}
    return _made(words.format(**{k: q[2] for k, q in values.items()}), words, values)


def _made(text: str, words: str, values: Mapping[str, Quantity]) -> Said:
    """The Said of ``text`` (``words`` filled with ``values``' texts as written: the caller's word for it)."""
    out = Said(text)
    out.template = words
    out.values = values
    return out


def join(separator: str, parts: Iterable[str]) -> str:
    """``separator.join(parts)``, a :class:`Said` where any part is one (its quantities kept)."""
    parts = list(parts)
    if not any(isinstance(p, Said) for p in parts):
        return separator.join(parts)
    spaced: list[str] = []
    for k, part in enumerate(parts):
        if k:
            spaced.append(separator)
        spaced.append(part)
    return _joined(spaced)


def counted(count: int, noun: str) -> str:
    """A count and its noun, singular for one: "1 point", "2 points", "0 points", "1,200 designs" (thousands
    grouped, as :func:`flyopt.report.display.number` groups them). For nouns whose plural takes an s."""
    return f"{count:,} {noun}{'' if count == 1 else 's'}"


def indefinite(text: str, capital: bool = False) -> str:
    """``text`` after its indefinite article, by its first letter: "an EN-GJS-400-18 …", "a cast iron …" ("an"
    before a, e, i and o; a u is read "you", as in "a unit", and takes "a")."""
    article = "an" if text[:1].lower() in ("a", "e", "i", "o") else "a"
    return f"{article.capitalize() if capital else article} {text}"


def removeprefix(text: str, head: str) -> str:
    """``text.removeprefix(head)``, a :class:`Said` kept with its quantities where ``head`` holds none (a
    combination's label and its colon)."""
    if isinstance(text, Said) and text.template.startswith(template(head)):
        return said(text.template[len(template(head)) :], **text.values)
    return text.removeprefix(head)


def said_by(err: BaseException) -> str:
    """An exception's message as the sentence it was raised with: a :class:`Said` given as its one argument
    keeps its quantities, which ``str(err)`` would drop; else ``str(err)``."""
    words = str(err)
    given = err.args[0] if len(err.args) == 1 else None
    return given if isinstance(given, Said) and given == words else words


def template(text: str) -> str:
    """The template of a sentence: its own, or the words of a plain string with their braces escaped."""
    return text.template if isinstance(text, Said) else _escaped(text)


def quantities(text: str) -> Mapping[str, Quantity]:
    """The quantities of a sentence by placeholder ({} for a plain string)."""
    return text.values if isinstance(text, Said) else {}


def _escaped(words: str) -> str:
    return words.replace("{", "{{").replace("}", "}}")


@functools.lru_cache(maxsize=1024)  # a template is most often a constant of its module: read once
def _names(words: str) -> frozenset[str]:
    """The placeholders of a template (a format spec or conversion is refused: the reader's units format it)."""
    found = set()
    for _, name, spec, conversion in string.Formatter().parse(words):
        if name is None:
            continue
        if not name.isidentifier() or spec or conversion:
            raise ValueError(f"said: the placeholder {{{name}}} must be a bare name, without a format")
        found.add(name)
    return frozenset(found)


def _joined(parts: Iterable[str]) -> Said:
    """The parts as one sentence, a placeholder renamed where an earlier part holds the same name (the string
    is the parts' strings end to end: nothing is formatted again)."""
    text: list[str] = []
    words: list[str] = []
    values: dict[str, Quantity] = {}
    for part in parts:
        text.append(part)
        if not isinstance(part, Said):
            words.append(_escaped(part))
            continue
        if values.keys().isdisjoint(part.values):
            words.append(part.template)
            values.update(part.values)
            continue
        renamed: dict[str, str] = {}
        for name, quantity in part.values.items():
            new, k = name, 1
            while new in values:
                k += 1
                new = f"{name}_{k}"
            renamed[name] = new
            values[new] = quantity
        words.append(
            "".join(
                _escaped(literal) + ("" if name is None else "{" + renamed[name] + "}")
                for literal, name, _, _ in string.Formatter().parse(part.template)
            )
        )
    return _made("".join(text), "".join(words), values)
