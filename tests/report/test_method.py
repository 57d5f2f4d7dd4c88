"""The report is self-contained (issue 29): the sections of the notes it cites are its Appendix A, and no
text sends the reader to docs/flywheel-design.md or any file of the repository.

The appendix must be the notes themselves, not a copy that can drift: the file the package ships is
byte for byte docs/flywheel-design.md, and every formula line of every section of the notes, found here
with this test's own reading of the markdown, is in that section's appendix text.
"""

import re

import pytest
from conftest import ROOT

from flyopt.report.document import Document, Equation, Paragraph, Section, plain
from flyopt.report.method import appendix, notes_sections, with_appendix

DOC = ROOT / "docs" / "flywheel-design.md"

#: A file of the repository, as a reader would meet it: a folder of the repository, a source/data name, or a
#: module of the source by its dotted name (its floors, tests/test_floors.py).
_FILE = re.compile(
    r"\b(?:docs|tests|benchmarks|problems|src|notebooks|tools)/|\b\w[\w-]*\.(?:py|md|toml|csv|json)\b"
    r"|\bflyopt\.(?:pipeline|report|design|machine|cycle|sizing|analysis|drive|io|outputs|studies|cli)\."
)


def test_the_package_ships_the_notes_themselves():
    from importlib import resources

    shipped = resources.files("flyopt").joinpath("data", "flywheel-design.md").read_bytes()
    assert shipped == DOC.read_bytes()


#: The notes' text for developers, which no report carries: between these comments (docs/flywheel-design.md's top).
_FOR_DEVELOPERS = re.compile(r"<!-- implementation -->(.*?)<!-- /implementation -->", re.S)


def _doc_sections():
    """The notes' numbered sections as this test reads them, less their text for developers: number -> (title,
    lines)."""
    sections, current = {}, None
    for line in _FOR_DEVELOPERS.sub("", DOC.read_text(encoding="utf-8")).split("\n"):
        heading = re.match(r"## (\d+)\. (.+)", line)
        if heading:
            current = heading.group(1)
            sections[current] = (heading.group(2).strip(), [])
        elif current:
            sections[current][1].append(line)
    return sections


def _text(sections):
    out = []
    for section in sections:
        out.append(section.title)
        for block in section.blocks:
            if isinstance(block, Paragraph):
                out.append(plain(block.text))
            elif hasattr(block, "rows"):
                out += [plain(c) for row in block.rows for c in row] + [plain(c) for c in block.head]
            elif hasattr(block, "text"):
                out.append(block.text)
    return " ".join(" ".join(out).split())


def test_every_section_of_the_notes_is_read_and_each_formula_reaches_its_appendix():
    doc = _doc_sections()
    assert list(notes_sections()) == list(doc) and len(doc) >= 25
    checked = 0
    for number, (title, lines) in doc.items():
        made = appendix([number])
        # the notes' title, less a parenthesis that names the project's tracker ("(issue 30, item 4: ...)") and code marks
        shown = re.sub(r"\s*\([^()]*issue[^()]*\)", "", title).replace("`", "")
        assert made[1].number == f"A.{number}" and made[1].title == shown
        text = _text(made)
        assert not _FILE.search(text), (number, _FILE.search(text).group(0))
        fenced = False
        for line in lines:
            fenced ^= line.startswith("```")
            words = line.lstrip("> ").strip()
            # a formula line: an equation, not inside a code block, not naming a file or a section (rewritten)
            if fenced or " = " not in words or _FILE.search(words) or re.search(r"sections? \d|\(|\)|\||`", words):
                continue
            words = re.sub(r"^(?:[-*]|\d+\.) ", "", words).replace("*", "")
            assert " ".join(words.split()) in text, (number, words)
            checked += 1
    assert checked > 50


def test_a_citation_becomes_the_appendix_number_and_the_sections_cited_are_appended():
    document = Document(
        "t",
        (),
        [
            Section(
                "1",
                "Steps",
                [
                    Paragraph("Reduced to one shaft (docs/flywheel-design.md, sections 3 and 14)."),
                    Equation("j", ("J_{F} = A / (ω² δ)", "= 1", "= 1"), "docs/flywheel-design.md, section 5"),
                    Paragraph("The calculations (docs/flywheel-design.md, sections 16–18)."),
                ],
            )
        ],
        "engineering",
        "designed",
    )
    done = with_appendix(document)
    blocks = done.sections[0].blocks
    assert plain(blocks[0].text) == "Reduced to one shaft (Appendices A.3 and A.14)."
    assert blocks[1].reference == "Appendix A.5"
    assert plain(blocks[2].text) == "The calculations (Appendices A.16 to A.18)."
    numbers = [s.number for s in done.sections if s.level == 2 and s.number.count(".") == 1]
    assert numbers == ["A.3", "A.5", "A.14", "A.16", "A.17", "A.18"]
    assert done.sections[1].number == "A" and done.sections[1].level == 1
    parts = [s.title for s in done.sections if s.number.startswith("A.14.")]
    assert parts[0] == "Engines from indicator data"  # a part of a section (### in the notes) is A.14.1
    # a reference inside the appendix names the appendix where it holds that section, else the notes' number
    said = _text([s for s in done.sections if s.number == "A.3"])
    assert "section 14" not in said.replace("section 14 of flyopt's notes", "")


def test_a_citation_written_across_the_pieces_of_a_paragraph_is_one_citation():
    """A paragraph built of pieces, its citation across three of them ("(", the notes, ", section 5)"), cites by
    the one rule: "(Appendix A.5)", the section appended, its number as it is. It read "(Appendix A, section
    5)", the pieces rewritten one by one."""
    from flyopt.report.document import Quantity

    j = Quantity("863.2 kg·m²", "j_required", 863.2, "inertia")
    text = ("The textbook method (", "docs/flywheel-design.md", ", section 5) would ask for J_F = ", j, ".")
    done = with_appendix(Document("t", (), [Section("1", "Model", [Paragraph(text)])], "engineering", "designed"))
    said = done.sections[0].blocks[0].text
    assert plain(said) == "The textbook method (Appendix A.5) would ask for J_F = 863.2 kg·m²."
    assert j in said and [s.number for s in done.sections if s.number.count(".") == 1] == ["A.5"]


@pytest.mark.parametrize("scene", ["motor-press", "slider-crank-press"])
def test_a_reports_model_section_cites_the_constant_inertia_method_as_the_appendix(scene):
    """The model section's "textbook constant-inertia method (...) would ask for J_F = ..." cites Appendix A.5 as
    every other citation does; no text of the report says "Appendix A, section"."""
    from conftest import PROBLEMS

    from flyopt.cli.report import collect
    from flyopt.report.builder import build

    document = build(collect(str(PROBLEMS / f"{scene}.toml")), figures=False)
    try:
        texts = [
            plain(block.text)
            for section in document.sections
            for block in section.blocks
            if isinstance(block, Paragraph)
        ]
    finally:
        document.close()
    method = [t for t in texts if t.startswith("The textbook constant-inertia method")]
    assert len(method) == 1 and method[0].startswith("The textbook constant-inertia method (Appendix A.5) would"), (
        method
    )
    assert not [t for t in texts if re.search(r"Appendix A, ?sections?", t)]


def test_the_notes_for_developers_reach_no_appendix():
    """What the notes mark for developers (where the code lives, how it is tested and timed) is in no appendix: each
    marked span's every clause of some length, as this test reads the markdown, is absent from its section's
    appendix, while the text around it is there."""
    text = DOC.read_text(encoding="utf-8")
    first = text.index("\n## 1. ")  # the page's introduction shows the convention, in code
    spans = [span for span in _FOR_DEVELOPERS.finditer(text) if span.start() > first]
    assert len(spans) >= 10
    checked = 0
    for span in spans:
        number = re.findall(r"^## (\d+)\.", text[: span.start()], flags=re.M)[-1]
        said = _text(appendix([number]))
        words = " ".join(re.sub(r"[`*>]|^\s*- ", "", span.group(1), flags=re.M).split())
        for clause in re.split(r"[;:()]|(?<=\.) ", words):
            clause = clause.strip(" .,")
            if len(clause) >= 25:
                assert clause not in said, (number, clause)
                checked += 1
    assert checked >= 20
    # the words around a span stay: the finite-element check still says what it solves
    assert "The finite-element check solves the wheel as an axisymmetric linear-elastic body" in _text(appendix(["13"]))


@pytest.mark.parametrize(
    "line, shown",
    [
        ("J_F = A / (ω² δ) (section 5).", "J_F = A / (ω² δ) (A.5)."),
        ("as in section 7, the same.", "as in section 7 of flyopt's notes, the same."),
        ("The scenes (`problems/a.toml`, `b.toml`) reproduce it.", "The scenes reproduce it."),
        ("Checked. problems/x.toml is such a disc: 5 kg. It holds.", "Checked. It holds."),
        ("Names as in [the nomenclature](nomenclature.md).", "Names as in the nomenclature."),
        # a ";" inside a parenthesis does not cut its sentence: the parenthesis goes with the sentence that names a file
        ("Khurmi 16.22 (327 kg; flyopt 326.59 kg) are in `problems/textbook/`. It holds.", "It holds."),
        ("**Arms** (Khurmi & Gupta, *Machine Design*, ch. 22).", "Arms (Khurmi & Gupta, Machine Design, ch. 22)."),
    ],
)
def test_a_line_of_the_notes_as_the_reader_gets_it(line, shown):
    from flyopt.report.method import readable

    assert readable(line, {"5"}) == shown
