"""Reading a PDF back as a reader sees it, for the report's layout tests: where each run of text stands.

pypdf (the test extra) walks each page's content stream and calls back on every operator
(``visitor_operand_before``, with the current transformation matrix it tracks through ``q``/``Q``/``cm``),
into each form XObject a ``Do`` shows (a form's text is placed by the matrix in force at its ``Do``, which
pypdf does not pass into the form: it is applied here);
the text state (text and line matrices, font, size, leading, rise, character and word spacing, horizontal
scaling) is followed here as PDF 32000-1, section 9.4 defines it, and each shown string's box is its
advance (the file's own ``/Widths`` of the embedded font) by the font's ascent and descent (its
``/FontDescriptor``), raised by the rise, in page coordinates [pt]. Nothing is taken from reportlab, which
wrote the file.
"""

from __future__ import annotations

from dataclasses import dataclass

_IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)


@dataclass(frozen=True)
class Box:
    """A run of text on a page: its box [pt] (x0, y0, x1, y1) and its characters (as the font codes them)."""

    page: int
    x0: float
    y0: float
    x1: float
    y1: float
    codes: bytes

    def overlap(self, other: Box) -> tuple[float, float]:
        """How far the two boxes overlap across and up [pt] (negative: apart)."""
        return (min(self.x1, other.x1) - max(self.x0, other.x0), min(self.y1, other.y1) - max(self.y0, other.y0))


def _times(a, b):
    """The product a·b of two PDF matrices (a b c d e f)."""
    return (
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
        a[4] * b[0] + a[5] * b[2] + b[4],
        a[4] * b[1] + a[5] * b[3] + b[5],
    )


def text_boxes(page, number: int = 0) -> list[Box]:
    """Every shown run of text on a pypdf page that has a visible character, as a :class:`Box`."""
    resources = page["/Resources"]
    found: list[Box] = []
    # the forms being read, innermost last: [operations of the form still to come, matrix at its Do, its fonts]
    forms: list[list] = []
    state = {"font": None, "size": 0.0, "leading": 0.0, "tc": 0.0, "tw": 0.0, "rise": 0.0, "scale": 1.0}
    matrices = {"tm": _IDENTITY, "lm": _IDENTITY}

    def next_line(tx, ty):
        matrices["lm"] = _times((1.0, 0.0, 0.0, 1.0, tx, ty), matrices["lm"])
        matrices["tm"] = matrices["lm"]

    def show(items, cm):
        font, size = state["font"], state["size"]
        widths, first = font["/Widths"], int(font.get("/FirstChar", 0))
        descriptor = font["/FontDescriptor"]
        ascent, descent = float(descriptor["/Ascent"]) / 1000 * size, float(descriptor["/Descent"]) / 1000 * size
        advance, codes = 0.0, b""
        for item in items:
            if not isinstance(item, (str, bytes)):  # a TJ adjustment, in thousandths of the size
                advance -= float(item) / 1000 * size * state["scale"]
                continue
            data = item.original_bytes if hasattr(item, "original_bytes") else bytes(item)
            for code in data:
                space = state["tw"] if code == 32 else 0.0
                advance += (float(widths[code - first]) / 1000 * size + state["tc"] + space) * state["scale"]
            codes += data
        if codes.strip(b" "):
            m = _times(matrices["tm"], cm)
            low, high = state["rise"] + descent, state["rise"] + ascent
            corners = [
                (x * m[0] + y * m[2] + m[4], x * m[1] + y * m[3] + m[5]) for x in (0, advance) for y in (low, high)
            ]
            xs, ys = [c[0] for c in corners], [c[1] for c in corners]
            found.append(Box(number, min(xs), min(ys), max(xs), max(ys), codes))
        matrices["tm"] = _times((1.0, 0.0, 0.0, 1.0, advance, 0.0), matrices["tm"])

    def visit(op, args, cm, tm):
        fonts = (forms[-1][2] if forms else resources).get("/Font", {})
        if forms:  # an operation of the form on top: placed by the matrix at its Do
            cm = _times(cm, forms[-1][1])
            forms[-1][0] -= 1
            if forms[-1][0] == 0:
                forms.pop()
        if op == b"Do":
            shown = (forms[-1][2] if forms else resources).get("/XObject", {})[args[0]].get_object()
            if shown["/Subtype"] == "/Form":
                from pypdf.generic import ContentStream

                if tuple(float(v) for v in shown.get("/Matrix", _IDENTITY)) != _IDENTITY:
                    raise NotImplementedError("a form with its own /Matrix")
                operations = len(ContentStream(shown, page.pdf).operations)
                if operations:
                    forms.append([operations, cm, shown.get("/Resources", resources)])
        elif op == b"BT":
            matrices["tm"] = matrices["lm"] = _IDENTITY
        elif op == b"Tm":
            matrices["tm"] = matrices["lm"] = tuple(float(a) for a in args)
        elif op == b"Td":
            next_line(float(args[0]), float(args[1]))
        elif op == b"TD":
            state["leading"] = -float(args[1])
            next_line(float(args[0]), float(args[1]))
        elif op == b"T*":
            next_line(0.0, -state["leading"])
        elif op == b"Tf":
            state["font"], state["size"] = fonts[args[0]].get_object(), float(args[1])
        elif op in (b"TL", b"Tc", b"Tw", b"Ts"):
            state[{b"TL": "leading", b"Tc": "tc", b"Tw": "tw", b"Ts": "rise"}[op]] = float(args[0])
        elif op == b"Tz":
            state["scale"] = float(args[0]) / 100
        elif op == b"Tj":
            show([args[0]], cm)
        elif op == b"TJ":
            show(list(args[0]), cm)
        elif op == b"'":
            next_line(0.0, -state["leading"])
            show([args[0]], cm)
        elif op == b'"':
            state["tw"], state["tc"] = float(args[0]), float(args[1])
            next_line(0.0, -state["leading"])
            show([args[2]], cm)

    page.extract_text(visitor_operand_before=visit)
    return found


def collisions(path, tolerance: float = 0.1) -> list[tuple[Box, Box, float, float]]:
    """Every pair of text boxes on a page of the PDF at ``path`` that overlap by more than ``tolerance`` [pt]
    both across and up (two runs of one line meet edge to edge: that is not an overlap)."""
    from pypdf import PdfReader

    hits = []
    for number, page in enumerate(PdfReader(str(path)).pages, start=1):
        boxes = sorted(text_boxes(page, number), key=lambda b: b.x0)
        for k, a in enumerate(boxes):
            for b in boxes[k + 1 :]:
                if b.x0 >= a.x1 - tolerance:
                    break
                across, up = a.overlap(b)
                if across > tolerance and up > tolerance:
                    hits.append((a, b, across, up))
    return hits


def assert_vector_diagrams(path, words=("crank angle", "stress [MPa]", "radius r [mm]", "von Mises")) -> None:
    """The PDF's diagrams are vectors with their words as text (issue 26): no page holds an image, and words
    only a diagram writes (the turning-moment and stress diagrams' axis labels, a legend entry) are text."""
    from pypdf import PdfReader

    reader = PdfReader(str(path))
    assert all(not page.images for page in reader.pages), "a diagram was rasterised"
    assert b"/Subtype /Image" not in path.read_bytes()
    text = " ".join(" ".join(page.extract_text() or "" for page in reader.pages).split())
    for word in words:
        assert word in text, word
