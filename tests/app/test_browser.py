"""The app in a real browser (headless Debian chromium through Playwright): edit, see the error, fix, download."""

from __future__ import annotations

import io
import json
import os
import re
from pathlib import Path

import pytest
from conftest import run_flyopt

from tests.app.app_server import served

pytestmark = [pytest.mark.browser, pytest.mark.usefixtures("close_figures")]  # no figure outlives a test

CHROMIUM = "/usr/bin/chromium"
ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """The app served as a user runs it, its temporary directory its own (TMPDIR): stopped by SIGTERM at the
    end, it must leave no session's private folder there (tests/app/test_server.py says why), and nothing the
    pages did (tabs closed while the server still sent them diagrams among it) a traceback in its terminal."""
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    temporary = tmp_path_factory.mktemp("app-tmp")
    stderr: list[str] = []
    with served(temporary, stderr) as (url, _):
        yield url
    assert list(temporary.glob("flyopt-app-*")) == [], "the stopped server left its sessions' folders"
    assert "Traceback" not in stderr[0] and "Task was destroyed" not in stderr[0], stderr[0][-3000:]


@pytest.fixture(scope="module")
def browser():
    if not os.path.exists(CHROMIUM):
        # only on a machine without Debian's chromium (Playwright cannot download its own here); .ci/run installs
        # it, so in CI these tests always run
        pytest.skip(f"{CHROMIUM} is absent (apt-get install -y chromium; .ci/run installs it)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="the app-test extra (playwright) is not installed")
    with sync_api.sync_playwright() as p:
        launched = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield launched
        launched.close()


ROOT = Path(__file__).resolve().parents[2]
SHOTS = os.environ.get("FLYOPT_APP_SHOTS")  # a folder for screenshots of each stage, when set


def shot(page, name):
    if SHOTS:
        page.screenshot(path=str(Path(SHOTS) / f"app-{name}.png"), full_page=True)


def replace_line(page, old, new):
    """Select ``old`` in the editor (Ace's own find) and type ``new`` over it with the keyboard, as a user would."""
    page.locator(".ace_editor").first.evaluate(
        "(el, old) => { const ed = el.env.editor; ed.focus(); ed.find(old, {wrap: true}); }", old
    )
    page.keyboard.type(new)


def model_text():
    return (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")


def solve_json(path):
    """``flyopt solve PATH --json``, the command line's answer the page must equal (run in this process, as
    tests/conftest.py's run_flyopt runs it: the app's server is the other process)."""
    solved = run_flyopt("solve", path, "--json")
    assert solved.returncode == 0, solved.stderr
    return json.loads(solved.stdout)


def card(page):
    return page.locator(".card").first


def test_edit_break_fix_and_download(server, browser, tmp_path):
    from pypdf import PdfReader

    from flyopt.app import model

    page = browser.new_page(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.wait_for_selector(".figure-turning_moment svg", timeout=60_000)
    shot(page, "1-loaded")
    # the diagrams' texts are text, set in the font the server sends (not one the browser happens to have)
    loaded = page.evaluate(
        "() => document.fonts.ready.then(() => [...document.fonts].filter(f => f.status === 'loaded').map(f => f.family))"
    )
    assert any(f.strip("\"'") == model.page_font()[0] for f in loaded), loaded
    assert page.locator(".figure-turning_moment svg text").count() > 10
    json_doc = solve_json(ROOT / "problems" / "shear-press.toml")
    from flyopt.report import display

    mass = display.quantity_text(json_doc["design"]["mass"], "mass", "engineering")
    assert mass in card(page).inner_text()
    # the card stays in view while the diagrams are scrolled through, to the last of them (it scrolled away)
    last = page.locator(".figure-speed svg").first
    last.wait_for(timeout=60_000)
    last.scroll_into_view_if_needed()
    status, diagram = card(page).locator(".status").first.bounding_box(), last.bounding_box()
    assert 0 <= status["y"] and status["y"] + status["height"] <= 1000, status
    assert diagram["y"] < 1000 and diagram["y"] + diagram["height"] > 0, diagram
    assert not (diagram["x"] < status["x"] + status["width"] and status["x"] < diagram["x"] + diagram["width"])

    replace_line(page, "delta = 0.05", "delta = -1")
    # the card of the last keystroke's text: typing over a selection sends the text without the line first (Ace
    # removes, then inserts), whose card, "machine.delta (line 9): is missing", a loaded host can show for a moment
    page.wait_for_selector(".card >> text=between 1e-06 and 2", timeout=30_000)
    text = card(page).inner_text()
    assert "line 11" in text and "between 1e-06 and 2" in text
    shot(page, "2-error")

    replace_line(page, "delta = -1", "delta = 0.025")
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.wait_for_selector(".card >> text=0.025 (1/40)", timeout=120_000)
    shot(page, "3-fixed")
    fixed = tmp_path / "fixed.toml"
    fixed.write_text(model_text().replace("delta = 0.05", "delta = 0.025"), encoding="utf-8")
    mass = display.quantity_text(solve_json(fixed)["design"]["mass"], "mass", "engineering")
    assert mass in card(page).inner_text()
    assert page.locator(".figure-energy svg").count() == 1

    with page.expect_download() as download:
        page.get_by_text("Report (HTML)").click()
    html = Path(download.value.path()).read_text(encoding="utf-8")
    assert "<title>" in html and "Shear press" in html
    with page.expect_download() as download:
        page.get_by_text("Report (PDF)").click()
    reader = PdfReader(io.BytesIO(Path(download.value.path()).read_bytes()))
    assert "Shear press" in reader.pages[0].extract_text()

    # a text over the websocket's limit closes the connection: the page says so (it said nothing and went on
    # showing its last answer as if current), and the server writes no traceback (the fixture's check)
    editor = page.locator(".ace_editor").first
    editor.evaluate("el => el.env.editor.setValue(el.env.editor.getValue() + '#' + 'x'.repeat(5000000))")
    page.wait_for_selector("text=The connection to flyopt was lost", timeout=60_000)
    page.close()


def test_the_server_sends_the_diagrams_font_and_no_other_file(server):
    """The font's route serves that one file, as it is; any other name there is not found."""
    import urllib.error
    import urllib.request

    from flyopt.app import model

    _family, file = model.page_font()
    with urllib.request.urlopen(f"{server.rstrip('/')}/{model.FONT_ROUTE}/{file.name}", timeout=30) as answer:
        assert answer.read() == file.read_bytes()
    others = [p.name for p in file.parent.iterdir() if p.is_file() and p != file][:2] + ["..%2F..%2Fmatplotlibrc"]
    for name in others:
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(f"{server.rstrip('/')}/{model.FONT_ROUTE}/{name}", timeout=30)
        refused.value.close()  # the error is the response: its socket closed here
        assert refused.value.code == 404, name


@pytest.mark.slow  # the default run's five minutes; the form's writes and the pasted rows' answer are checked
# without a browser in test_form.py (a typed δ, the book's 1.256 kJ from pasted rows)
def test_the_form_writes_into_the_scene_and_a_pasted_table_solves(server, browser):
    """δ set in the form reads in the editor as if typed and the card follows; the shear press's table pasted
    from a spreadsheet in degrees and N*m gives the book's A_max (1.256 kJ, docs/flywheel-design.md example 2)."""
    page = browser.new_page(viewport={"width": 1400, "height": 1100})
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.get_by_text("Form", exact=True).click()
    delta = page.get_by_label("allowed δ (e.g. 0.05 or 5 %)")
    assert delta.input_value() == "0.05"
    delta.fill("0.025")
    delta.press("Enter")
    page.wait_for_selector(".card >> text=0.025 (1/40)", timeout=60_000)
    # the book's four rows with collinear rows between (the same curve), over 5,000 characters: the paste box
    # kept Panel's default 5,000 and dropped the rest silently, cutting the table short
    rows = [(0.5 * k, 1600) for k in range(91)] + [(90 + 0.5 * k, 200) for k in range(541)]
    pasted = "angle\ttorque\n" + "\n".join(f"{a:g}\t{t}" for a, t in rows)
    assert len(pasted) > 5_500 and rows[90] == (45, 1600) and rows[91] == (90, 200) and rows[-1] == (360, 200)
    page.get_by_placeholder("0\t1600").fill(pasted)
    page.get_by_role("button", name="Use the pasted rows").click()
    editor = page.locator(".ace_editor").first
    for _ in range(600):  # the editor's own text (in its shadow root: polled through the locator)
        if "angle_unit" in editor.evaluate("el => el.env.editor.getValue()"):
            break
        page.wait_for_timeout(50)
    page.wait_for_selector(".card >> text=designed", timeout=60_000)
    page.wait_for_selector(".card >> text=1.256 kJ", timeout=60_000)
    text = editor.evaluate("el => el.env.editor.getValue()")
    assert "delta = 0.025" in text and 'angle_unit = "deg"' in text and "[45.0, 1600.0]" in text
    assert "[359.5, 200.0]" in text and "[360.0, 200.0]" in text  # the last rows too
    assert text.count("# ") == model_text().count("# ")  # the comments kept
    shot(page, "4-form")
    page.close()


def tradeoff_json(path):
    """``flyopt tradeoff PATH --json``'s rows, the command line's trade-off the materials tab must equal (run in
    this process, as solve_json)."""
    done = run_flyopt("tradeoff", path, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)["rows"]


@pytest.mark.slow  # 11-17 s; the tabs' logic is checked against the command line in test_tabs.py by default
def test_tick_two_materials_and_run_a_sweep_to_the_end(server, browser, tmp_path):
    from playwright.sync_api import expect

    from flyopt import read_results
    from flyopt.report import display

    page = browser.new_page(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)

    page.get_by_text("Compare materials", exact=True).click()
    page.wait_for_selector(".tradeoff .tabulator-row", timeout=60_000)  # the scene's own two, ticked at first

    def tick(name):
        cell = page.locator('.tabulator-cell[tabulator-field="material"]', has_text=re.compile(f"^{name}$"))
        page.locator(".library .tabulator-row").filter(has=cell).locator("input[type=checkbox]").click()

    for name in ("cast iron", "cast steel"):  # untick both: nothing to compare
        tick(name)
    page.wait_for_selector("text=Tick at least one material", timeout=30_000)
    for name in ("cast steel", "cast iron"):
        tick(name)
    rows = page.locator(".tradeoff .tabulator-row")
    page.wait_for_selector(".tradeoff .tabulator-row >> text=cast iron", timeout=60_000)
    page.wait_for_selector(".tradeoff .tabulator-row >> text=cast steel", timeout=60_000)
    assert rows.count() == 2
    texts = [rows.nth(i).inner_text() for i in range(rows.count())]
    cli = {r["material"]: r for r in tradeoff_json(ROOT / "problems" / "shear-press.toml")}
    for text, name in zip(texts, ("cast_steel", "cast_iron")):  # lightest first, as flyopt tradeoff ranks them
        assert name.replace("_", " ") in text
        assert display.number(cli[name]["mass"]) in text
    page.wait_for_selector(".tradeoff-chart svg", timeout=60_000)
    shot(page, "5-materials")

    page.get_by_text("Sweeps", exact=True).click()
    page.wait_for_selector(".sweep-spec >> text=5 points", timeout=30_000)
    parquet = page.get_by_role("button", name="Parquet", exact=True)
    expect(parquet).to_be_disabled()  # no sweep yet: nothing to give (a click failed silently)
    page.get_by_text("Run the sweep").click()
    page.wait_for_selector(".sweep-status >> text=done: 5 points", timeout=120_000)
    assert page.locator(".sweep-bar progress").get_attribute("value") == "100"
    expect(page.locator(".sweep-table .tabulator-row")).to_have_count(5, timeout=30_000)
    page.wait_for_selector(".sweep-plot svg", timeout=30_000)
    shot(page, "6-sweep")
    expect(parquet).to_be_enabled()
    with page.expect_download() as download:
        page.get_by_text("Parquet", exact=True).click()
    saved = tmp_path / "sweep.parquet"
    download.value.save_as(saved)
    frame = read_results(saved)
    assert len(frame) == 5 and (frame["status"] == "designed").all()
    page.close()


@pytest.mark.slow
def test_a_scene_material_s_markup_is_shown_as_text_in_the_library(server, browser):
    """A [[material]]'s name and source are the user's strings: the library table shows them, never runs them."""
    evil = (
        model_text() + '\n[[material]]\nname = "evil_<b>x</b>"\ndensity = "7000 kg/m^3"\nmax_rim_speed = "40 m/s"\n'
        'source = "<img src=q onerror=\\"window.pwned=1\\"> <b>bold</b>"\n'
    )
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.locator(".ace_editor").first.evaluate("(el, text) => el.env.editor.setValue(text, -1)", evil)
    page.wait_for_timeout(1000)
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.get_by_text("Compare materials", exact=True).click()
    row = page.locator(".library .tabulator-row").filter(has_text="evil")
    row.first.wait_for(timeout=60_000)
    assert "<img src=q" in row.first.inner_text() and "<b>x</b>" in row.first.inner_text()
    assert page.locator(".library img").count() == 0 and page.locator(".library b").count() == 0
    assert page.evaluate("window.pwned") is None
    page.close()


def speed_of(path):
    """The speed over the cycle of the scene's solve, (φ [deg], ω [rpm]): the curve the speed diagram draws, from
    the analysis, not from the figure or its read-outs."""
    import numpy as np

    import flyopt

    curve = flyopt.solve(flyopt.load(path), extras=("speed",)).analysis.speed_curve()
    return np.degrees(np.asarray(curve.phi, dtype=float)), np.asarray(curve.omega, dtype=float) * 30.0 / np.pi


@pytest.mark.slow  # the page's load; the read-outs' numbers are checked without a browser in test_plots_readout.py
def test_hovering_the_speed_diagram_reads_the_curve_at_the_pointer(server, browser):
    import numpy as np

    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    figure = page.locator(".figure-speed svg").first
    figure.wait_for(timeout=60_000)
    figure.scroll_into_view_if_needed()
    phi, omega = speed_of(ROOT / "problems" / "shear-press.toml")
    tip = page.locator(".figure-speed .readout").first
    box = figure.bounding_box()
    for fraction in (0.3, 0.55, 0.8):  # across the axes, which span most of the figure's width
        page.mouse.move(box["x"] + fraction * box["width"], box["y"] + 0.5 * box["height"])
        tip.wait_for(state="visible", timeout=10_000)
        lines = tip.inner_text().splitlines()
        at = re.fullmatch(r"φ = ([0-9.,]+) deg", lines[0])
        shown = re.fullmatch(r"ω = ([0-9.,]+) rpm", lines[1])
        assert at and shown, lines
        x, y = float(at.group(1).replace(",", "")), float(shown.group(1).replace(",", ""))
        # four significant figures: ω within half its last digit of the curve at φ (φ itself within half of its
        # last digit: the curve's change over that is allowed too)
        true = np.interp(x, phi, omega)
        spread = abs(np.interp(x + 0.05, phi, omega) - np.interp(x - 0.05, phi, omega))
        assert abs(y - true) <= 0.5 + spread, (lines, true)
        assert page.locator(".figure-speed .readout-guide line").count() == 1
    shot(page, "7-hover")
    page.mouse.move(5, 5)  # off the diagram: the read-out goes
    tip.wait_for(state="hidden", timeout=10_000)
    page.close()


@pytest.mark.slow  # the page's load and a front of 15 designs; the loaded text is checked without a browser too
def test_clicking_a_pareto_point_loads_its_design_into_the_editor(server, browser):
    from flyopt.app import materials
    from flyopt.io.scene import load
    from flyopt.report import display

    scene = load(ROOT / "problems" / "shear-press.toml")
    front = materials.pareto_front(scene, ["cast_iron", "cast_steel"], materials.OBJECTIVES[0])
    index = len(front) // 2
    row = front.iloc[index]
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(server, timeout=120_000)  # a loaded host loads the page slowly
    page.wait_for_selector(".card >> text=designed", timeout=120_000)
    page.get_by_text("Compare materials", exact=True).click()
    page.wait_for_selector(".tradeoff .tabulator-row", timeout=60_000)
    page.get_by_text("Draw the front", exact=True).click()
    page.wait_for_selector(".figure-pareto svg", timeout=120_000)
    links = page.locator(".figure-pareto a")  # one a point, in the front's order (every point here is drawn)
    assert links.count() == len(front)
    assert links.nth(index).get_attribute("xlink:href").endswith(materials.PICK.format(index).lstrip("#"))
    mass = display.quantity_text(float(row["mass"]), "mass", "engineering")
    # under the pointer, the point says what a click loads: its material and its objectives
    links.nth(index).scroll_into_view_if_needed()
    dot = links.nth(index).locator("use").bounding_box()
    page.mouse.move(dot["x"] + dot["width"] / 2, dot["y"] + dot["height"] / 2)
    tip = page.locator(".figure-pareto .readout").first
    tip.wait_for(state="visible", timeout=10_000)
    lines = tip.inner_text().splitlines()
    assert lines[0] == f"material = {materials.display_names(scene)[row['best_material']]}", lines
    assert lines[2] == f"mass = {mass}", lines
    shot(page, "8-pareto-hover")
    links.nth(index).click(force=True)
    # the Design tab's answer card (the Compare tab's card of the point, also a .card, shows this mass at once;
    # the answer card shows the last answer while the point's scene is solved, then the point's)
    answer = page.locator(".card.flyopt-answer").first
    answer.locator("td[data-name=mass]", has_text=mass).wait_for(timeout=120_000)
    text = page.locator(".ace_editor").first.evaluate("el => el.env.editor.getValue()")
    assert f'materials = ["{row["best_material"]}"]' in text
    assert f'max_outer_diameter = "{row["design.max_outer_diameter"] * 1000:.10g} mm"' in text
    assert display.quantity_text(float(row["d_outer"]), "length", "engineering") in answer.inner_text()
    shot(page, "9-pareto-loaded")
    page.close()


@pytest.mark.slow  # 10 s with its own server; the rule is checked without a browser in test_address.py by default
def test_another_site_s_page_cannot_make_the_browser_build_sessions(browser, tmp_path):
    """An outside audit: every request for the page built a whole session (its widgets, its private folder),
    so any page the user visited could make the browser build them by the dozen (``<img src=...>``, an iframe,
    a fetch). Now only a page the user opens builds one (flyopt.app.address.refused_request)."""
    import threading
    from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

    temporary = tmp_path / "tmp"
    temporary.mkdir()
    with served(temporary) as (url, _):
        body = "".join(f'<img src="{url}?{k}">' for k in range(5)) + f'<iframe src="{url}"></iframe>'
        body += f"<script>fetch('{url}', {{mode: 'no-cors'}}).finally(() => document.title = 'fetched')</script>"

        class Elsewhere(BaseHTTPRequestHandler):
            def do_GET(self):  # noqa: N802 (http.server's name)
                self.send_response(200)
                self.send_header("Content-Type", "text/html")
                self.end_headers()
                self.wfile.write(body.encode())

            def log_message(self, *args):
                pass

        # another site on this machine: localhost is not 127.0.0.1 (Chromium's local-network checks block a
        # public page's requests to the loopback on their own; Firefox's do not)
        elsewhere = ThreadingHTTPServer(("127.0.0.1", 0), Elsewhere)
        threading.Thread(target=elsewhere.serve_forever, daemon=True).start()

        def sessions():  # one private folder a session
            return len(list(temporary.glob("flyopt-app-*")))

        try:
            page = browser.new_page()
            assert sessions() == 1  # the served() helper's own first request: a script's, without Sec-Fetch-*
            asked = []

            def ended(request):
                if request.url.split("?")[0] == url:
                    asked.append((request.url, request.failure))

            page.on("requestfinished", ended)
            page.on("requestfailed", ended)
            page.goto(f"http://localhost:{elsewhere.server_address[1]}/")
            page.wait_for_function("document.title == 'fetched'", timeout=60_000)
            page.wait_for_function("Array.from(document.images).every(i => i.complete)", timeout=60_000)
            for _ in range(600):
                if len(asked) >= 7:
                    break
                page.wait_for_timeout(50)
            # each reached the server (the browser then blocked an image's HTML from the page: ORB), none was
            # stopped by Chromium's own local-network checks
            assert len(asked) == 7 and not any("LOCAL_NETWORK" in str(failure) for _, failure in asked), asked
            assert sessions() == 1
        finally:
            elsewhere.shutdown()
            elsewhere.server_close()
        page.goto(url, timeout=120_000)  # the user opens it: a session, as before
        page.wait_for_selector(".card >> text=designed", timeout=120_000)
        assert sessions() == 2
        page.close()
