"""A name's control and bidirectional-override characters reach no reader raw (issue 25, item 10).

A scene's title or a shaft's name is the user's text: NUL, BEL, ESC (which
starts a terminal sequence) and U+202E (which reverses what follows) were
copied raw into the text report, the HTML page and the PDF. Each renderer now
writes them as their escapes; what shows is what the file holds.
"""

import unicodedata

import pytest

from flyopt.report.characters import visible

HOSTILE = "a\x00b\x07c\x1bd\u202eevil\u2066\u200b\ue000"
ACTING = ("\x00", "\x07", "\x1b", "\u202e", "\u2066", "\u200b", "\ue000")


def acting(text):
    """The characters of ``text`` that act rather than show (but line break and tab)."""
    return sorted({c for c in text if c not in "\n\t" and unicodedata.category(c) in ("Cc", "Cf", "Co", "Cs", "Cn")})


def test_every_acting_character_is_its_escape():
    assert visible(HOSTILE) == "a\\x00b\\x07c\\x1bd\\u202eevil\\u2066\\u200b\\ue000"


@pytest.mark.parametrize(
    "text", ["plain text", "ΔE = 0.84 kJ, ω 1,500 rpm", "🔥 flywheel ☃", "two\nlines\tand a tab", ""]
)
def test_what_shows_is_kept(text):
    assert visible(text) == text


def test_characters_seen_to_show_let_no_acting_one_through():
    """visible remembers the characters it found showing (a text of them only is returned at once): a text of
    those same characters and one acting character still has that one escaped, wherever it stands."""
    shown = "ΔE ω δ · ² é"
    assert visible(shown) == shown
    for where in range(len(shown) + 1):
        text = shown[:where] + "\u202e" + shown[where:]
        assert visible(text) == shown[:where] + "\\u202e" + shown[where:]
    assert visible(shown + "\n\t") == shown + "\n\t"


def test_an_escape_is_left_as_it_is():
    assert visible(visible(HOSTILE)) == visible(HOSTILE)


def test_the_text_report_shows_the_title_and_names_escaped():
    from flyopt.report.text import table

    lines = table(["shaft", "ratio"], [[HOSTILE, "1"], ["crank", "2"]])
    assert not acting("\n".join(lines))
    assert lines[2].startswith(visible(HOSTILE))
    assert len({len(line) for line in lines[:3]}) == 1  # the columns still line up


def test_solve_prints_no_acting_character(main_cli, write_scene):
    scene = write_scene(
        'title = "a\\u200bb\\u2066c\\ue000d\\u202eevil"\n'
        '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n'
        '[torque.resisting]\npoints = [["0 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]\n'
        '[torque.driving]\nconstant = "unknown"\n'
    )
    status, out, err = main_cli("solve", scene)
    assert status == 0, err
    assert not acting(out)
    assert out.startswith("a\\u200bb\\u2066c\\ue000d\\u202eevil")  # control characters: refused at load
