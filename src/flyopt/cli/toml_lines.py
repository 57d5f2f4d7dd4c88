"""Where a field stands in a TOML file: the line of each key path, for ``flyopt check``.

``tomllib`` gives the values but no positions, so :func:`key_lines` reads the
text once more, as a small scanner of TOML's structure (headers, keys, arrays,
inline tables, the four kinds of string, comments) that keeps the line where
each key, array-of-tables entry and array element begins. It runs only on a
file ``tomllib`` has already read, and only to place an error: its paths are
spelled as the loader names fields (``member[1].force[3]``, zero-based
indices), and :func:`line_of` falls back to the nearest enclosing field that
has a line.
"""

from __future__ import annotations

import re

__all__ = ["key_lines", "line_of", "set_value"]

_BARE = re.compile(r"[A-Za-z0-9_-]+")
_INDEX = re.compile(r"\[\d+\]$")
#: A cell of a table's row, named by its column after the row's index ("points[3] torque").
_CELL = re.compile(r"\] [A-Za-z_ ]+$")


class _Scanner:
    """One pass over the text; ``lines`` maps a key path to its 1-based line."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0
        self.line = 1
        self.lines: dict[str, int] = {}
        #: Where each key's value is written, (start, end) offsets in the text (keys of tables, not of inline ones).
        self.spans: dict[str, tuple[int, int]] = {}
        #: Where each table's header line ends (an offset), for a key added to it.
        self.headers: dict[str, int] = {}
        self.array_tables: dict[str, int] = {}  # path of an [[array]] -> index of its last entry

    # -- characters -------------------------------------------------------
    def peek(self, n: int = 1) -> str:
        return self.text[self.pos : self.pos + n]

    def advance(self, n: int = 1) -> None:
        self.line += self.text.count("\n", self.pos, self.pos + n)
        self.pos += n

    def skip_blank(self, newlines: bool) -> None:
        """Skip spaces and comments, and newlines too when ``newlines``."""
        while self.pos < len(self.text):
            c = self.text[self.pos]
            if c in " \t\r" or (newlines and c == "\n"):
                self.advance()
            elif c == "#":
                end = self.text.find("\n", self.pos)
                self.advance((len(self.text) if end < 0 else end) - self.pos)
            else:
                return

    def skip_string(self) -> str:
        """Skip a string starting here; return its value when it is a one-line string (for a quoted key)."""
        for quote in ('"""', "'''"):
            if self.peek(3) == quote:
                self.advance(3)
                end = self.text.find(quote, self.pos)
                while end >= 0 and quote == '"""' and _escaped(self.text, end):
                    end = self.text.find(quote, end + 1)
                end = len(self.text) if end < 0 else end
                while self.text[end + 3 : end + 4] == quote[0]:  # up to two quotes may close the content
                    end += 1
                self.advance(end + 3 - self.pos)
                return ""
        quote = self.text[self.pos]
        start = self.pos + 1
        end = start
        while end < len(self.text) and self.text[end] != quote and self.text[end] != "\n":
            end += 2 if quote == '"' and self.text[end] == "\\" else 1
        value = self.text[start:end]
        self.advance(min(end + 1, len(self.text)) - self.pos)
        return value

    # -- structure --------------------------------------------------------
    def key(self) -> list[str]:
        """A (dotted) key: its parts, unquoted."""
        parts = []
        while True:
            self.skip_blank(newlines=False)
            if self.peek() in ('"', "'"):
                parts.append(self.skip_string())
            else:
                match = _BARE.match(self.text, self.pos)
                if not match:
                    return parts
                parts.append(match.group())
                self.advance(match.end() - self.pos)
            self.skip_blank(newlines=False)
            if self.peek() != ".":
                return parts
            self.advance()

    def resolve(self, parts: list[str]) -> str:
        """The path of a header's key, each array of tables on the way at its last entry."""
        path = ""
        for part in parts:
            path = f"{path}.{part}" if path else part
            self.lines.setdefault(path, self.line)  # [a.b] makes a here, unless it was made before
            if path in self.array_tables:
                path = f"{path}[{self.array_tables[path]}]"
        return path

    def value(self, path: str) -> None:
        """Skip one value, noting the line of each element and inline key below ``path``."""
        c = self.peek()
        if c in ('"', "'"):
            self.skip_string()
        elif c == "[":
            self.advance()
            index = 0
            while self.pos < len(self.text):
                self.skip_blank(newlines=True)
                if self.peek() in ("]", ""):
                    break
                self.lines.setdefault(f"{path}[{index}]", self.line)
                before = self.pos
                self.value(f"{path}[{index}]")
                self.skip_blank(newlines=True)
                if self.peek() == ",":
                    self.advance()
                    index += 1
                elif self.pos == before:  # not TOML (a stray "}"): stop here rather than loop
                    return
            self.advance()
        elif c == "{":
            self.advance()
            while self.pos < len(self.text):
                self.skip_blank(newlines=False)
                if self.peek() in ("}", ""):
                    break
                line = self.line
                parts = self.key()
                if not parts or self.peek() != "=":
                    break
                self.advance()
                self.skip_blank(newlines=False)
                inner = ".".join((path, *parts))
                self.lines.setdefault(inner, line)
                before = self.pos
                self.value(inner)
                self.skip_blank(newlines=False)
                if self.peek() == ",":
                    self.advance()
                elif self.pos == before:  # not TOML: stop here rather than loop
                    return
            self.advance()
        else:  # a number, boolean or date: up to its end
            while self.pos < len(self.text) and self.text[self.pos] not in ",]}\n#":
                self.advance()

    def run(self) -> dict[str, int]:
        table = ""
        while True:
            self.skip_blank(newlines=True)
            if self.pos >= len(self.text):
                return self.lines
            line = self.line
            if self.peek(2) == "[[":
                self.advance(2)
                parts = self.key()
                name = self.resolve(parts[:-1])
                name = f"{name}.{parts[-1]}" if name else parts[-1] if parts else ""
                self.array_tables[name] = self.array_tables.get(name, -1) + 1
                table = f"{name}[{self.array_tables[name]}]"
                self.lines.setdefault(name, line)
                self.lines.setdefault(table, line)
                self.skip_to_line_end()
                self.headers.setdefault(table, self.pos)
            elif self.peek() == "[":
                self.advance()
                table = self.resolve(self.key())
                self.lines.setdefault(table, line)
                self.skip_to_line_end()
                self.headers.setdefault(table, self.pos)
            else:
                parts = self.key()
                if not parts or self.peek() != "=":  # not TOML: nothing more to place
                    return self.lines
                self.advance()
                self.skip_blank(newlines=False)
                path = ".".join((table, *parts)) if table else ".".join(parts)
                for k in range(1, len(parts)):  # a dotted key makes its tables here
                    self.lines.setdefault(".".join((table, *parts[:k])) if table else ".".join(parts[:k]), line)
                self.lines.setdefault(path, line)
                start = self.pos
                self.value(path)
                end = min(self.pos, len(self.text))
                while end > start and self.text[end - 1] in " \t\r":  # a number's scan stops at the comment
                    end -= 1
                self.spans.setdefault(path, (start, end))

    def skip_to_line_end(self) -> None:
        end = self.text.find("\n", self.pos)
        self.advance((len(self.text) if end < 0 else end) - self.pos)


def _escaped(text: str, at: int) -> bool:
    """Whether the character at ``at`` follows an odd number of backslashes."""
    count = 0
    while at - count - 1 >= 0 and text[at - count - 1] == "\\":
        count += 1
    return count % 2 == 1


def key_lines(text: str) -> dict[str, int]:
    """The 1-based line of every key path in a TOML text.

    Parameters
    ----------
    text : str
        A TOML document (one ``tomllib`` reads; on anything else the result
        stops where the text stops being TOML).

    Returns
    -------
    dict of str to int
        ``"machine.speed"``, ``"member[1]"`` (the line of the second
        ``[[member]]``), ``"member[1].force[3]"`` (the line where the fourth
        element of that array begins), ``"torque.driving.motor.kind"`` (a key
        of an inline table), each to the line where it is written. A table
        made implicitly (``[a.b]`` makes ``a``) has the line that made it.
        A byte-order mark before the first line is read past, as the loader reads past it.
    """
    return _Scanner(text.removeprefix("\ufeff")).run()


def line_of(lines: dict[str, int], field: str) -> int | None:
    """The line of ``field`` (a loader's field path), or of the nearest enclosing field that has one.

    Parameters
    ----------
    lines : dict of str to int
        :func:`key_lines` of the file.
    field : str
        ``"machine.delta"``, ``"member[0].force[7]"``, ... A field the file
        does not write (a key that is missing) takes the line of the table
        that should hold it.

    Returns
    -------
    int or None
        None when not even the first part of the path is in the file.
    """
    field = _CELL.sub("]", field)  # "points[3] torque": a cell of row 3, on the row's line
    while field:
        if field in lines:
            return lines[field]
        if _INDEX.search(field):
            field = _INDEX.sub("", field)
        elif "." in field:
            field = field.rsplit(".", 1)[0]
        else:
            return None
    return None


def set_value(text: str, path: str, literal: str) -> str:
    """``text`` with the key ``path`` ("machine.delta", "shaft[1].speed_ratio") given the TOML value ``literal``.

    The value is replaced where it is written, the rest of the text (comments, order, layout) kept; a key
    not written is added after its table's header (a table not written is added at the end, ``[table]``;
    an entry of an array of tables must exist). Used by ``flyopt app``'s form, so that a field set there
    reads in the editor as if typed.

    Raises
    ------
    KeyError
        ``path`` is in an entry of an array of tables the text does not have, or under an inline table.
    """
    scanner = _Scanner(text)
    scanner.run()
    if path in scanner.spans:
        start, end = scanner.spans[path]
        return text[:start] + literal + text[end:]
    table, _, key = path.rpartition(".")
    if any(span == table or table.startswith(span + ".") for span in scanner.spans):
        raise KeyError(f"{path}: under a key written inline, not a table")
    line = f"{_key(key)} = {literal}\n"
    dotted = [span for span in scanner.spans if table and span.startswith(table + ".")]
    if table and table not in scanner.headers and dotted:  # a table made by dotted keys: one more beside them
        end = max(scanner.spans[span][1] for span in dotted)
        owner = max(
            ((at, name) for name, at in scanner.headers.items() if at <= end and path.startswith(name + ".")),
            default=(0, ""),
        )[1]
        relative = path[len(owner) + 1 :] if owner else path
        if "[" in relative:
            raise KeyError(f"{path}: the text has no such entry of an array of tables")
        parts = relative.split(".")
        eol = text.find("\n", end)
        eol = len(text) if eol < 0 else eol
        return text[:eol] + "\n" + ".".join(_key(p) for p in parts) + f" = {literal}" + text[eol:]
    if not table:
        first = min(scanner.headers.values(), default=len(text))
        head = text[:first].rfind("\n", 0, max(first - 1, 0)) + 1 if scanner.headers else len(text)
        return _joined(text[:head], line) + text[head:]
    if table in scanner.headers:
        at = scanner.headers[table]
        return text[:at] + "\n" + line.rstrip("\n") + text[at:]
    if _INDEX.search(table) or "[" in table:
        raise KeyError(f"{path}: the text has no such entry of an array of tables")
    return _joined(text, f"\n[{table}]\n{line}")


def _key(key: str) -> str:
    return key if _BARE.fullmatch(key) else '"' + key.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _joined(text: str, more: str) -> str:
    return text + ("" if not text or text.endswith("\n") else "\n") + more
