"""Benchmark of ``flyopt app`` (issue 29): from an edit in the browser to updated numbers and diagrams.

The app is served by ``python -m flyopt app`` in a subprocess and driven by headless Debian chromium
through Playwright, as the browser tests drive it. Each edit selects ``machine.delta``'s value in the
editor of problems/shear-press.toml (an energy-model scene, solved on every edit) and types a new one
(the deltas cycle through values whose 1/δ is a whole number, so the card's "δ (1/n)" names the edit), or with
``--edit torque`` the resisting torque's points (their peak); the clock starts when the last key is sent and
stops when

* numbers: the answer card shows the new "δ (1/n)" (a torque edit: the card differs from before) and the
  status "designed";
* the diagram in view: before the edits the page is scrolled to the J_F–δ diagram (the third on the page; it
  changes with δ), which the page then draws first (flyopt.app.diagrams: the diagrams in view first); its SVG
  differs from before;
* all diagrams: the speed diagram's SVG (it draws ω_m(1 ± δ/2), so it changes with δ; the last on the page, out
  of view, so the last drawn) differs from before: every diagram of the edit has been drawn and sent by then.

The times are the browser's (performance.now()): from the edit's event in the page (the line replaced in one
input, as a paste or a single keystroke is) to the DOM changed (a MutationObserver) and to the frame after it.
They include Panel's debounce and the page's (flyopt.app.page.DEBOUNCE). Beside them, in
the same run, the server's share of the same texts in this process: :func:`flyopt.app.model.check`
(the loader), :func:`flyopt.app.model.numbers` (the report's one solve, its document without diagrams:
the card), :func:`flyopt.app.model.draw` and :func:`flyopt.app.model.figure_svg` (the diagrams).

Targets (issue 29): edit -> numbers <= 150 ms, edit -> diagrams <= 500 ms. Medians over the edits with
their ranges. ``--pin split`` (the default) puts the server on one CPU and the browser on another, as on an
engineer's machine; ``--pin same`` puts both on one (the runs before: the browser's layout and the server's
drawing then take turns on one core); ``--pin none`` leaves them to the OS. Writes
``benchmarks/results/app.md`` and ``app.csv``.

``--edit torque`` edits the resisting torque's peak instead of δ: every diagram then changes (a δ edit leaves
the turning-moment and energy diagrams as they were, and the page keeps them); it writes ``app_torque.md``.
``--edit envelope`` edits the wheel's envelope (max_outer_diameter): the cycle's three diagrams are kept, the
wheel's and the speed's drawn; it writes ``app_envelope.md``.

Usage::

    python benchmarks/bench_app.py [--edits 12] [--pin split|same|none] [--edit delta|torque|envelope]
"""

import argparse
import os
import platform
import socket
import statistics
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

from common import load_average, write_results

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from flyopt.app.page import DEBOUNCE  # noqa: E402 -- the page's own, after the path

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "problems" / "shear-press.toml"
DELTAS = ("0.04", "0.025", "0.02", "0.0125", "0.01", "0.05")
#: The peak resisting torques [N*m] a torque edit cycles through: each changes every diagram of the scene.
PEAKS = ("1500", "1700", "1450", "1650", "1550", "1600")
TORQUE = 'points = [["0 deg", "{peak} N*m"], ["45 deg", "{peak} N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]'


#: What each kind of edit replaces, and what of the page it leaves as it was.
EDITED = {
    "delta": "machine.delta's line",
    "torque": "the resisting torque's points (its peak)",
    "envelope": "design.max_outer_diameter's line (it binds the wheel)",
}
KEPT = {
    "delta": "a δ edit leaves the turning-moment and energy diagrams as they were",
    "torque": "a torque edit changes every diagram: none is kept",
    "envelope": "an envelope edit changes the wheel, not the cycle: the turning-moment, energy and J_F–δ "
    "diagrams are kept",
}
#: The diagrams each kind of edit is timed to, by the page's class (figure-KEY): "first" the diagram in view
#: (the J_F–δ, drawn first where it changes; an envelope edit keeps it), "last" the last diagram the edit changes
#: (the speed; an envelope edit leaves it the same to the byte, and its last changed diagram is the drawing).
WATCHED = {
    "delta": {"first": "inertia_delta", "last": "speed"},
    "torque": {"first": "inertia_delta", "last": "speed"},
    "envelope": {"last": "drawing"},
}
#: The envelopes an envelope edit cycles through [m]: each binds shear-press's wheel (its D is the envelope's).
ENVELOPES = ("0.58", "0.55", "0.57", "0.54", "0.56", "0.6")


def edit_lines(kind):
    """(line before, line after, what the card then shows or None: it changes) of each edit of ``kind``: δ's line
    (the turning-moment and energy diagrams stay as they were, the page keeps them) or the resisting torque's
    (every diagram changes)."""
    if kind == "delta":
        old = ["0.05", *DELTAS[:-1]]
        return [(f"delta = {a}", f"delta = {b}", f"{b} (1/{round(1 / float(b))})") for a, b in zip(old, DELTAS)]
    if kind == "envelope":
        old = ["0.6", *ENVELOPES[:-1]]
        line = 'max_outer_diameter = "{} m"'
        return [(line.format(a), line.format(b), None) for a, b in zip(old, ENVELOPES)]
    old = ["1600", *PEAKS[:-1]]
    return [(TORQUE.format(peak=a), TORQUE.format(peak=b), None) for a, b in zip(old, PEAKS)]


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


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until(condition, timeout=300.0, step=0.005, what="the page"):
    start = time.perf_counter()
    while not condition():
        if time.perf_counter() - start > timeout:
            raise TimeoutError(f"{what} did not update")
        time.sleep(step)
    return time.perf_counter()


#: In the page, before it loads: the time of the last edit (a key or an input event reaching the document).
MARK_EDITS = """
window.__flyoptEdit = 0;
for (const kind of ['keydown', 'input', 'beforeinput'])
  document.addEventListener(kind, () => { window.__flyoptEdit = performance.now(); }, true);
"""

#: In the page, before an edit: watch every shadow root for the card showing ``shown`` and for the first and
#: last diagrams' SVG differing from theirs before; the times are the browser's own (performance.now), taken
#: when the DOM changed (a MutationObserver) and at the next frame after it (painted), so nothing polls the
#: page while it works.
WATCH = """([shown, before, targets]) => {
  const deep = (root, sel) => {
    const found = root.querySelector(sel);
    if (found) return found;
    for (const el of root.querySelectorAll('*'))
      if (el.shadowRoot) { const inner = deep(el.shadowRoot, sel); if (inner) return inner; }
    return null;
  };
  const out = {};
  window.__flyoptDone = new Promise(resolve => {
    const seen = (name) => {
      out[name] = performance.now();
      requestAnimationFrame(() => {
        out[name + '_painted'] = performance.now();
        if (out.card_painted !== undefined && Object.keys(targets).every(name => out[name + '_painted'] !== undefined))
          resolve(out);
      });
    };
    const check = () => {
      if (out.card === undefined) {
        const card = deep(document, '.card');
        if (card && (shown ? card.innerText.includes(shown) : card.innerText !== before.card)
            && card.innerText.includes('designed')) {
          out.edit = window.__flyoptEdit;
          seen('card');
        }
      }
      for (const [name, sel] of Object.entries(targets)) {
        if (out[name] !== undefined) continue;
        const svg = deep(document, sel);
        if (svg && svg.innerHTML !== before[name]) seen(name);
      }
    };
    const observer = new MutationObserver(check);
    const observe = (root) => {
      observer.observe(root, {subtree: true, childList: true, characterData: true, attributes: true});
      for (const el of root.querySelectorAll('*')) if (el.shadowRoot) observe(el.shadowRoot);
    };
    observe(document);
  });
}"""


def browser_latencies(url, edits, cpus, kind):
    from playwright.sync_api import sync_playwright

    if cpus is not None:
        os.sched_setaffinity(0, cpus)  # Playwright's driver and the browser inherit it
    rows = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        page.add_init_script(MARK_EDITS)
        page.goto(url, timeout=300_000)
        page.wait_for_selector(".card >> text=designed", timeout=300_000)
        page.wait_for_selector(".figure-speed svg", timeout=300_000)
        page.wait_for_function("() => !document.body.innerText.includes('drawing the diagrams')", timeout=300_000)
        # the engineer looks at the J_F–δ diagram while editing δ: scrolled into view, the page told so
        page.locator(".figure-inertia_delta").first.scroll_into_view_if_needed()
        page.locator(".figure-inertia_delta").first.evaluate("(el) => el.scrollIntoView({block: 'start'})")
        time.sleep(1.0)
        lines = edit_lines(kind)
        for i in range(edits):
            old, new, shown = lines[i % len(lines)]
            targets = {name: f".figure-{key} svg" for name, key in WATCHED[kind].items()}
            before = {
                **{name: page.locator(selector).first.inner_html() for name, selector in targets.items()},
                "card": page.locator(".card").first.inner_text(),
            }
            editor = page.locator(".ace_editor").first
            editor.evaluate("(el, old) => { el.env.editor.find(old, {wrap: true}); }", old)
            page.evaluate(WATCH, [shown, before, targets])
            # one edit, as a paste or a single keystroke is: the selected line replaced through the editor's own
            # API (its change event is what Panel sends), the clock started there; typed keys would make the
            # browser scroll the page back to the editor, away from the diagram in view
            editor.evaluate(
                "(el, text) => { window.__flyoptEdit = performance.now(); el.env.editor.insert(text); }",
                new,
            )
            out = page.evaluate("() => window.__flyoptDone", [])
            row = {"edit": i, "kind": kind, "line": new}
            # where the J_F–δ diagram is after the edit (CSS pixels from the viewport's top; in view: 0 to 1000)
            row["in_view_top_px"] = page.locator(".figure-inertia_delta").first.evaluate(
                "(el) => el.getBoundingClientRect().top"
            )
            for name in ("card", *targets):
                row[f"{name}_ms"] = out[name] - out["edit"]
                row[f"{name}_painted_ms"] = out[f"{name}_painted"] - out["edit"]
            rows.append(row)
            time.sleep(0.3)  # the page settles (its last card without "drawing") before the next edit
        browser.close()
    return rows


def server_share(edits, kind):
    sys.path.insert(0, str(ROOT / "src"))
    from flyopt.app import model

    space = model.Workspace()
    text = SCENE.read_text(encoding="utf-8")
    model.solve(text, space).document.close()  # warm-up: imports, compiled models
    from flyopt.app.diagrams import Diagrams

    steps = {"check": [], "numbers": [], "draw": [], "svg": [], "speed": [], "in_view": [], "all": [], "kept": []}
    lines = edit_lines(kind)
    edited, shown = text, model.solve(text, space).figures  # what the page shows before the first edit
    for i in range(edits):
        old, new, _ = lines[i % len(lines)]
        if old not in edited:
            raise SystemExit(f"bench_app: {SCENE.name} has no line {old!r} to edit")
        edited = edited.replace(old, new)
        t0 = time.perf_counter()
        model.check(edited, space)
        t1 = time.perf_counter()
        answer = model.numbers(edited, space)
        t2 = time.perf_counter()
        document = model.draw(answer)
        t3 = time.perf_counter()
        speed = t3
        for block in model.figure_blocks(document):
            model.figure_svg(block)
            if block.key == "speed":
                speed = time.perf_counter()
        t4 = time.perf_counter()
        document.close()
        # as the page draws them: the diagram in view first (J_F–δ), then the rest from a second document
        answer = model.numbers(edited, space)
        t5 = time.perf_counter()
        diagrams = Diagrams(answer, {"inertia_delta": 1.0})
        diagrams.step()
        t6 = time.perf_counter()
        while diagrams.step() is not None:
            pass
        t7 = time.perf_counter()
        diagrams.document().close()
        # as the page draws them, keeping those it shows whose data the edit leaves as they were
        answer = model.numbers(edited, space)
        t8 = time.perf_counter()
        diagrams = Diagrams(answer, {"inertia_delta": 1.0}, shown)
        while diagrams.step() is not None:
            pass
        t9 = time.perf_counter()
        shown = diagrams.figures()
        diagrams.document().close()
        values = (
            t1 - t0,
            t2 - t1,
            t3 - t2,
            t4 - t3,
            speed - t1,
            t2 - t1 + t6 - t5,
            t2 - t1 + t7 - t5,
            t2 - t1 + t9 - t8,
        )
        for name, value in zip(steps, values):
            steps[name].append(1e3 * value)
    space.close()
    return steps


def summary(values):
    return f"{statistics.median(values):.0f} ms ({min(values):.0f}–{max(values):.0f})"


PINS = {
    # the server on one CPU, the browser and Playwright on another: as on an engineer's machine, where the
    # browser does not share a core with the server (the default)
    "split": ({0}, {1}),
    # both on one CPU (this benchmark's runs before): the browser's layout and the server's drawing take
    # turns on one core, a machine with one core
    "same": ({0}, {0}),
    "none": (None, None),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=12)
    parser.add_argument("--pin", choices=sorted(PINS), default="split")
    parser.add_argument("--edit", choices=sorted(EDITED), default="delta")
    args = parser.parse_args()
    available = os.sched_getaffinity(0) if hasattr(os, "sched_setaffinity") else set()
    server_cpus, browser_cpus = PINS[args.pin]
    if not available or not (server_cpus or set()) | (browser_cpus or set()) <= available:
        server_cpus = browser_cpus = None
    pinned = (
        "not pinned"
        if server_cpus is None
        else f"server pinned to CPU {min(server_cpus)}, browser and Playwright to CPU {min(browser_cpus)}"
        " (os.sched_setaffinity)"
    )
    load_before = load_average()
    port = free_port()
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    server = subprocess.Popen(
        [sys.executable, "-m", "flyopt", "app", "--port", str(port), "--no-browser"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        preexec_fn=None if server_cpus is None else (lambda: os.sched_setaffinity(0, server_cpus)),
    )
    url = f"http://127.0.0.1:{port}/"
    try:
        wait_until(lambda: _up(url), timeout=120)
        rows = browser_latencies(url, args.edits, browser_cpus, args.edit)
    finally:
        server.terminate()
        server.wait(10)
    load_after = load_average()
    if server_cpus is not None:
        os.sched_setaffinity(0, server_cpus)
    steps = server_share(args.edits, args.edit)
    numbers = [r["card_ms"] for r in rows]
    diagrams = [r["last_ms"] for r in rows]
    in_view = [r["first_ms"] for r in rows if "first_ms" in r]
    met_numbers = "met" if statistics.median(numbers) <= 150 else "NOT met"
    met_diagrams = "met" if statistics.median(diagrams) <= 500 else "NOT met"
    met_in_view = "met" if in_view and statistics.median(in_view) <= 500 else "NOT met"
    if in_view:
        in_view_row = (
            f"| the diagram in view (J_F–δ, scrolled to; drawn first) | {summary(in_view)} | "
            f"{summary([r['first_painted_ms'] for r in rows])} | (<= 500 ms) | {met_in_view} |"
        )
    else:
        in_view_row = "| the diagram in view (J_F–δ, scrolled to) | kept: the edit leaves it as it was | | | |"
    last = WATCHED[args.edit]["last"]
    text = f"""# flyopt app: edit to answer, in the browser

`python benchmarks/bench_app.py --edits {args.edits} --pin {args.pin} --edit {args.edit}`: problems/shear-press.toml (energy model,
solved on every edit), {EDITED[args.edit]} replaced {args.edits} times in headless chromium, each replacement one
edit (inserted at once through the editor's API, as a paste or a single keystroke is, the page scrolled to the J_F–δ
diagram); medians (min–max). The times are the browser's own
(`performance.now()`): from the edit's event in the page to the DOM showing the change (a MutationObserver; nothing
polls the page) and to the next frame after it (painted). They include Panel's 50 ms debounce and the page's ({1e3 * DEBOUNCE:.0f} ms).
{pinned}; Python {platform.python_version()}, {platform.platform()}, {os.cpu_count()} CPUs.
Host load average (1, 5, 15 min) before the run: {load_before}; after: {load_after}. The host is shared by
several engineers: absolute times are noisy, the ratios between the rows of the same run are what to compare.

| from an edit to | median (range) | painted: median (range) | target | |
| --- | --- | --- | --- | --- |
| updated numbers (card) | {summary(numbers)} | {summary([r["card_painted_ms"] for r in rows])} | <= 150 ms | {met_numbers} |
{in_view_row}
| updated diagrams, all of them ({last}, the last the edit changes) | {summary(diagrams)} | {summary([r["last_painted_ms"] for r in rows])} | <= 500 ms | {met_diagrams} |

The issue's target is the last row: every diagram of the edit updated. The row above it is the diagram the
engineer is looking at, which the page draws first; it does not replace the target.

The server's share, in this process after a warm-up ({"on the server's CPU" if server_cpus else "not pinned"}),
the same texts:

| step | median (range) |
| --- | --- |
| check (flyopt's loader on the text) | {summary(steps["check"])} |
| numbers: the report's one solve and its document without diagrams (the card) | {summary(steps["numbers"])} |
| the same solve's document with all its diagrams (made, not yet drawn) | {summary(steps["draw"])} |
| every diagram of that document drawn to SVG | {summary(steps["svg"])} |
| from the check's end to the speed diagram's SVG, all from one document | {summary(steps["speed"])} |
| as the page draws: from the check's end to the SVG of the diagram in view (a document making it alone) | {summary(steps["in_view"])} |
| as the page draws: from the check's end to the last SVG (the rest from a second document) | {summary(steps["all"])} |
| as the page draws, keeping the diagrams it shows whose data the edit leaves as they were: to the last SVG | {summary(steps["kept"])} |

The card is the first change sent once the numbers are solved (the report's document built without its
diagrams); the diagrams of the same solve are drawn after it, in their own worker, and each sent as soon as
it is drawn: those in view first (a document that makes their figures alone), then the others in the page's
order (a second document, without solving again), the speed diagram last; a diagram whose data the edit leaves
as they were (the digest of what it draws: flyopt.app.diagrams) is kept as the page shows it, not drawn
({KEPT[args.edit]}). An edit waits for the debounce, the check and the numbers for its card, and for every
diagram for the speed one, so the last row of this table is the server's floor under the last two rows of the
browser's table (the two rows above it: the same edit with every diagram drawn).
"""
    write_results(Path(__file__).parent / "results", "app" if args.edit == "delta" else f"app_{args.edit}", text, rows)
    print(text)


def _up(url):
    # a request that times out still makes the server build its session (a solve and every diagram): with a 1 s
    # timeout, a server pinned to one core built dozens before the browser's page, and the edits waited behind them
    try:
        urllib.request.urlopen(url, timeout=60).close()
        return True
    except OSError:
        return False


if __name__ == "__main__":
    main()
