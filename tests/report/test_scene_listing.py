"""The scene file as the report lists it: whole where it is a scene an engineer writes, cut where it would run to
scores of pages, and never a line wider or taller than the page.

Before: one comment line of 13,000 characters stopped the PDF with reportlab's LayoutError (its one wrapped row
taller than a page, exit 1 and a traceback); 5,000 comment lines made a 76-page PDF in 16 s and 8 MB of them took
minutes; and the listing's last characters ran into the block's right padding, onto its border.
"""

import re

import pytest
from conftest import PROBLEMS
from pdf_reading import collisions, text_boxes

from flyopt.report.document import MAX_LISTED_CHARACTERS, MAX_LISTED_LINES, Code, listing


@pytest.mark.parametrize("path", sorted(PROBLEMS.rglob("*.toml")), ids=lambda p: p.stem)
def test_every_shipped_scene_is_listed_whole(path):
    text = path.read_text(encoding="utf-8")
    code = listing(text, "c")
    assert (code.text, code.note) == (text, "")


def test_a_listing_stops_after_its_lines_and_counts_what_it_left():
    lines = [f"# line {k}" for k in range(1, 5001)]
    code = listing("\n".join(lines) + "\n", "c")
    assert code.text == "\n".join(lines[:MAX_LISTED_LINES]) + "\n"
    left = "\n".join(lines[MAX_LISTED_LINES:])
    assert code.note.startswith(f"Not listed: lines 2,001 to 5,000 ({len(left):,} characters);")
    one_more = listing("\n".join(lines[: MAX_LISTED_LINES + 1]), "c")
    assert one_more.note.startswith(f"Not listed: line 2,001 ({len(lines[MAX_LISTED_LINES])} characters);")
    exactly = "\n".join(lines[:MAX_LISTED_LINES]) + "\n"
    assert listing(exactly, "c") == Code(exactly, "c")
    # blank lines past the limit are no more text, however many: left out without a note
    assert listing(exactly + "\n" * 20_000 + " \t\n", "c") == Code(exactly, "c")


def test_a_listing_stops_inside_a_line_longer_than_its_characters():
    text = "#" + "x" * (MAX_LISTED_CHARACTERS + 49_999) + "\na = 1\nb = 2\n"
    code = listing(text, "c")
    assert code.text == text[:MAX_LISTED_CHARACTERS] + "\n"
    assert code.note.startswith(
        f"Not listed: the rest of line 1, from its character {MAX_LISTED_CHARACTERS + 1:,}, and lines 2 to 3 "
        f"({50_000 + 12:,} characters);"
    )


def _scene(tmp_path, head):
    scene = tmp_path / "s.toml"
    scene.write_text(head + (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8"), encoding="utf-8")
    return scene


def test_a_line_longer_than_a_page_is_broken_over_rows_inside_the_block(main_cli, tmp_path):
    from pypdf import PdfReader
    from reportlab.lib.pagesizes import A4
    from reportlab.lib.units import mm

    long = "# " + "".join(f"{k % 10}" for k in range(13_000))
    status, _, err = main_cli("report", _scene(tmp_path, long + "\n"), "-o", tmp_path / "r.pdf", "-q")
    assert (status, err) == (0, "")
    reader = PdfReader(str(tmp_path / "r.pdf"))
    text = "".join(page.extract_text() for page in reader.pages)
    # every character of the line, in order, the rows after the first marked as its continuation
    pieces = re.findall(r"(?:^# |↪ )([0-9]+)$", text, flags=re.M)
    assert "".join(pieces) == long[2:]
    right = A4[0] - 16 * mm - 5  # the block's edge is the page margin, its right padding 6 pt
    # the listing's full rows, and lines of the text (a table's number or a page number may end at the margin)
    rows = [b for k, page in enumerate(reader.pages) for b in text_boxes(page, k + 1) if b.x1 - b.x0 > 400]
    assert len(rows) > 13_000 / 130 and max(b.x1 for b in rows) <= right
    assert not collisions(tmp_path / "r.pdf")


def test_a_scene_of_thousands_of_lines_is_listed_to_its_limit_in_both_formats(main_cli, tmp_path):
    from pypdf import PdfReader

    head = "".join(f"# note {k}\n" for k in range(1, 5001))
    scene = _scene(tmp_path, head)
    total = scene.read_text(encoding="utf-8").rstrip("\n").count("\n") + 1
    said = f"Not listed: lines 2,001 to {total:,} ("
    for suffix in ("html", "pdf"):
        status, _, err = main_cli("report", scene, "-o", tmp_path / f"r.{suffix}", "-q")
        assert (status, err) == (0, "")
    html = (tmp_path / "r.html").read_text(encoding="utf-8")
    assert said in html and "# note 2000\n" in html and "# note 2001\n" not in html
    text = "\n".join(page.extract_text() for page in PdfReader(str(tmp_path / "r.pdf")).pages)
    assert said in " ".join(text.split())
    assert re.search(r"^# note 2000$", text, re.M) and not re.search(r"^# note 2001$", text, re.M)
