"""The manufacturing drawing (flyopt.outputs.drawing, flyopt.report.drawing) and ``flyopt export``.

The DXF is read back with ezdxf: every DIMENSION entity's measurement is the
Design's own dimension (read from the Design, not from the drawing), the
layers and the title block are there. SVG and PDF are written, non-empty,
and carry the same texts. Refusals: one line, exit status, nothing written.
"""

from __future__ import annotations

import datetime
import hashlib
import math

import pytest

from flyopt._toml import tomllib
from tests.conftest import PROBLEMS

ezdxf = pytest.importorskip("ezdxf")  # the cad extra: the test extra installs it, so CI runs these

DATE = datetime.date(2026, 11, 28)


def _scene(name, geometry=None):
    import flyopt

    path = PROBLEMS / f"{name}.toml"
    if geometry is None:
        return flyopt.load(path)
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data["design"]["geometry"] = geometry
    return flyopt.from_dict(data)


#: A rim-and-web wheel, an arms wheel (the same press with arms), an engine's disc on its keyed hub, a bare rim.
CASES = {
    "rim_web": ("punch-press-wheel", None),
    "rim_arms": ("punch-press-wheel", "rim_arms"),
    "disc": ("four-cylinder-engine", None),
    "rim": ("punch-press", None),
}


@pytest.fixture(scope="module")
def drawn():
    """{case: (Drawing, Design)}, each scene solved once."""
    from flyopt.report.drawing import drawing_of_scene

    return {case: drawing_of_scene(_scene(*args), DATE) for case, args in CASES.items()}


#: castability.toml read by the test itself: the fillet ratio, each process's smallest fillet, the chamfer table.
FINISH = tomllib.loads(
    __import__("importlib.resources").resources.files("flyopt").joinpath("data", "castability.toml").read_text("utf-8")
)


def fillets_expected(design):
    """The fillet radius at each junction [mm], from the Design's dimensions and the data file's rule:
    r = ratio x the thinner part (ratio 0.5, the cited range's), at least the process's smallest,
    at most half the thinner part's length and a quarter of the thickness step."""
    d = design.dims
    process = design.limits.castability["process"] if design.limits.castability else None
    ratio = FINISH["fillet"]["ratio"]
    smallest = FINISH["process"].get(process, {}).get("min_fillet", 0.0)

    def rule(t_a, t_b, length):
        if math.isclose(t_a, t_b, rel_tol=1e-6):
            return 0.0
        return 1e3 * min(max(ratio * min(t_a, t_b), smallest), length / 2.0, abs(t_a - t_b) / 4.0)

    if design.geometry == "rim_web":
        out = {"fillet_rim": rule(d.t_web, d.b, d.d_inner / 2 - d.d_hub / 2)}
        out["fillet_hub"] = rule(d.t_web, d.l_hub, d.d_inner / 2 - d.d_hub / 2)
    elif design.geometry == "rim_arms":
        out = {"fillet_rim": rule(d.arm_minor, d.b, d.d_inner / 2 - d.d_hub / 2)}
        out["fillet_hub"] = rule(d.arm_minor, d.l_hub, d.d_inner / 2 - d.d_hub / 2)
    else:
        out = {}
    return {name: r for name, r in out.items() if r > 0}


def chamfers_expected(design):
    """The 45-degree chamfer of each machined edge [mm]: the table's C for the edge's diameter, at most a
    tenth of the shorter face, rounded down to a row (castability.toml [chamfer], read here)."""
    d = design.dims
    rows = FINISH["chamfer"]["table"]
    cap = FINISH["chamfer"]["face_fraction"]

    def size(diameter, face):
        by_size = next((c for top, c in rows if diameter <= top), rows[-1][1])
        return 1e3 * max([c for _, c in rows if c <= min(by_size, cap * face) + 1e-12] or [rows[0][1]])

    if design.geometry == "disc":  # the disc's radial extent: from its hub (design.disc_hub) or its bore
        inner = d.d_hub / 2 if d.d_hub else (design.bore or 0) / 2
        out = {"chamfer_rim": size(d.d_outer, min(d.b, d.d_outer / 2 - inner))}
    else:
        out = {"chamfer_rim": size(d.d_outer, min(d.b, d.d_outer / 2 - d.d_inner / 2))}
    if design.bore and d.d_hub:  # a hub: web and arms wheels, and the engine's disc on its hub
        wall = min(d.d_hub / 2 - design.bore / 2, d.l_hub)
        out |= {"chamfer_hub": size(d.d_hub, wall), "chamfer_bore": size(design.bore, wall)}
    return out


def expected(design):
    """What each dimension must measure [mm], from the Design's own fields."""
    d, key = design.dims, design.parts.key
    out = {"d_outer": d.d_outer, "b": d.b}
    if design.geometry in ("rim_web", "rim_arms", "rim", "thin_rim"):
        out["d_inner"] = d.d_inner
    if design.geometry == "rim_web":
        out["t_web"] = d.t_web
    if design.geometry in ("rim_web", "rim_arms", "disc") and design.bore and d.d_hub:  # a disc on its hub too
        out |= {"d_hub": d.d_hub, "l_hub": d.l_hub}
    if design.geometry == "rim_arms":
        out |= {"arm_major": d.arm_major, "arm_minor": d.arm_minor}
    if design.bore:
        out["bore"] = design.bore
    if design.bore and key:
        out |= {"key_width": key["b"], "key_depth": design.bore + key["t2"]}
    return {name: value * 1e3 for name, value in out.items()} | fillets_expected(design)


def test_the_cases_are_the_geometries_they_claim(drawn):
    for case, (_drawing, design) in drawn.items():
        assert design.geometry == case
    assert drawn["rim_web"][1].bore and drawn["rim_web"][1].parts.key  # a keyed bore to draw
    assert drawn["rim_arms"][1].n_arms


@pytest.mark.parametrize("case", CASES)
def test_dxf_dimensions_are_the_designs(drawn, case, tmp_path):
    from flyopt.outputs.drawing import XDATA_APP, write_dxf

    drawing, design = drawn[case]
    path = tmp_path / "wheel.dxf"
    write_dxf(drawing, path)
    doc = ezdxf.readfile(path)
    assert doc.audit().has_errors is False
    assert doc.header["$INSUNITS"] == 4  # millimetres
    measured = {}
    for dim in doc.modelspace().query("DIMENSION"):
        assert dim.dxf.layer == "DIMENSIONS"
        name = dim.get_xdata(XDATA_APP)[0].value
        assert name not in measured, name
        # a detail's dimension measures its enlarged drawing; DIMLFAC gives the true size
        measured[name] = dim.get_measurement() * dim.override().get("dimlfac", 1.0)
        assert dim.dxf.dimtype & 0x0F in ((4,) if name.startswith("fillet") else (0, 3))  # linear, diameter, radius
    want = expected(design)
    assert measured.keys() == want.keys()
    for name, value in want.items():
        assert measured[name] == pytest.approx(value, rel=1e-9), name


def _outline(doc, design):
    """The section's outline in a DXF read back: its polylines' points and its arcs, each on layer OUTLINE
    (the seen bore edge behind the keyway, a thin line, left out)."""
    msp = doc.modelspace()
    polylines = [
        ([tuple(p) for p in e.get_points("xy")], e.closed)
        for e in msp.query("LWPOLYLINE[layer=='OUTLINE']")
        if e.dxf.get("lineweight", -1) != 25 and _in_section([tuple(p) for p in e.get_points("xy")], design)
    ]
    arcs = [a for a in msp.query("ARC[layer=='OUTLINE']") if _in_section([(a.dxf.center.x, a.dxf.center.y)], design)]
    return polylines, arcs


@pytest.mark.parametrize("case", ["rim_web", "rim_arms"])
def test_dxf_fillets_are_arcs_of_the_rules_radius_at_each_junction(drawn, case, tmp_path):
    """Section A-A: at each junction, on both sides and in both halves, an ARC on layer OUTLINE of the
    radius the rule gives (computed here from the design's dimensions and the data file), centred one
    radius off both faces it joins; its radius dimension in the detail says the same."""
    from flyopt.outputs.drawing import write_dxf

    drawing, design = drawn[case]
    path = tmp_path / "wheel.dxf"
    write_dxf(drawing, path)
    doc = ezdxf.readfile(path)
    _polylines, arcs = _outline(doc, design)
    d = design.dims
    thin = 1e3 * (d.t_web if case == "rim_web" else d.arm_minor)
    want = fillets_expected(design)
    assert want["fillet_hub"] == pytest.approx(5.5 if case == "rim_web" else 8.75, rel=1e-9)  # 0.5 x 11; 0.5 x 17.5
    corners = {"fillet_hub": (1e3 * d.d_hub / 2, 1), "fillet_rim": (1e3 * d.d_inner / 2, -1)}
    for name, radius in want.items():
        r_corner, away = corners[name]
        for sx in (1, -1):
            for sy in (1, -1):
                centre = (sx * (thin / 2 + radius), sy * (r_corner + away * radius))
                found = [a for a in arcs if math.dist((a.dxf.center.x, a.dxf.center.y), centre) < 1e-6]
                assert len(found) == 1, (name, sx, sy)
                assert found[0].dxf.radius == pytest.approx(radius, rel=1e-9)
                assert (found[0].dxf.end_angle - found[0].dxf.start_angle) % 360 == pytest.approx(90.0)
    radii = {
        dim.get_xdata("FLYOPT")[0].value: dim.get_measurement() * dim.override().get("dimlfac", 1.0)
        for dim in doc.modelspace().query("DIMENSION")
        if dim.dxf.dimtype & 0x0F == 4
    }
    assert radii == pytest.approx(want, rel=1e-9)


def test_the_fe_check_rounds_its_junctions_as_the_drawing_does(drawn):
    """One rule: the FE's section of the web wheel has the drawing's fillets at the same junctions."""
    from flyopt.design import fem

    _drawing, design = drawn["rim_web"]
    sec = fem.section(design)
    by_radius = {round(r * 1e3, 6): f * 1e3 for _k, r, _z, f, _side in sec.junctions()}
    want = fillets_expected(design)
    assert by_radius == pytest.approx(
        {
            round(design.dims.d_hub * 500, 6): want["fillet_hub"],
            round(design.dims.d_inner * 500, 6): want["fillet_rim"],
        },
        rel=1e-9,
    )


@pytest.mark.parametrize("case", ["rim_web", "disc", "rim"])
def test_dxf_section_outline_is_closed_and_chamfered(drawn, case, tmp_path):
    """The cut faces' outlines read back from the DXF close (every end of a polyline or arc meets another's,
    or the polyline is closed), and each machined edge carries a 45-degree chamfer of the table's size: a
    segment from (x_face, r -+ c) to (x_face - c, r) (or its mirror) in the outline, and a leader saying it."""
    from flyopt.outputs.drawing import write_dxf

    drawing, design = drawn[case]
    path = tmp_path / "wheel.dxf"
    write_dxf(drawing, path)
    doc = ezdxf.readfile(path)
    polylines, arcs = _outline(doc, design)
    ends = []
    for points, closed in polylines:
        if not closed:
            ends += [points[0], points[-1]]
    for arc in arcs:
        ends += [(arc.start_point.x, arc.start_point.y), (arc.end_point.x, arc.end_point.y)]
    for end in ends:
        assert sum(math.dist(end, other) < 1e-6 for other in ends) == 2, end  # itself and one other
    segments = [(a, b) for points, closed in polylines for a, b in zip(points, points[1:] + points[:1] * closed)]
    want = chamfers_expected(design)
    d = design.dims
    r_o, half = d.d_outer * 500, d.b * 500
    edges = {"chamfer_rim": [(sx * half, sy * r_o) for sx in (1, -1) for sy in (1, -1)]}
    if "chamfer_hub" in want:
        edges["chamfer_hub"] = [(sx * d.l_hub * 500, sy * d.d_hub * 500) for sx in (1, -1) for sy in (1, -1)]
        edges["chamfer_bore"] = [(sx * d.l_hub * 500, -design.bore * 500) for sx in (1, -1)]  # the keyway's half: none
    for name, corners in edges.items():
        c = want[name]
        inward = 1.0 if name == "chamfer_bore" else -1.0  # the end face runs from the bore away from the axis
        for x, y in corners:
            ends_at = {((x - math.copysign(c, x)), y), (x, y + inward * math.copysign(c, y))}
            assert any(
                {(round(a[0], 6), round(a[1], 6)), (round(b[0], 6), round(b[1], 6))}
                == {(round(p[0], 6), round(p[1], 6)) for p in ends_at}
                for a, b in segments
            ), (name, x, y, c)
    said = {
        leader.get_xdata("FLYOPT")[0].value: leader.get_xdata("FLYOPT")[1].value
        for leader in doc.modelspace().query("LEADER")
    }
    assert said == pytest.approx(want, rel=1e-12)
    assert all(leader.dxf.layer == "DIMENSIONS" for leader in doc.modelspace().query("LEADER"))


def test_chamfers_follow_the_table_by_hand():
    """castability.chamfer_size against the table read by hand: the punch-press wheel's 657 mm rim (13 mm
    wide, 25 mm deep) gets GB/T 6403.4's C10 for 630-800 mm, cut to a tenth of 13 mm: 1.3, down to the row
    1.0; its 55 mm bore in a hub of 16.5 mm wall: C2 for 50-80 mm, cut to 1.65, down to 1.6."""
    from flyopt.design import castability

    assert castability.chamfer_size(0.657, 0.013) == pytest.approx(0.001, rel=1e-12)
    assert castability.chamfer_size(0.055, 0.0165) == pytest.approx(0.0016, rel=1e-12)
    assert castability.chamfer_size(0.055, 1.0) == pytest.approx(0.002, rel=1e-12)  # the table alone
    assert castability.chamfer_size(5.0, 1.0) == pytest.approx(0.025, rel=1e-12)  # beyond the table: its last row


def test_the_notes_give_the_finish(drawn):
    """The notes name the fillet radii, the chamfers, the cast faces' draft of the process, the machined
    faces' texture and the sharp STEP solid; the old 'not given' note is gone."""
    drawing, design = drawn["rim_web"]
    notes = " ".join(t.text for t in drawing.texts if t.layer == "TITLE")
    draft = FINISH["process"][design.limits.castability["process"]]["draft"]
    assert 1.0 <= draft <= 2.0  # the foundry guides' range
    for words in (
        "Fillets R0.5, R5.5",
        "at least R3",
        "Chamfers 1 × 45°, 1.6 × 45°",
        f"Draft {draft:g}°",
        "Ra 3.2 µm",
        "bore Ra 1.6 µm",
        "sharp edges",
    ):
        assert words in notes, words
    assert "not given by this design" not in notes
    texts = {t.text for t in drawing.texts}
    assert {"DETAIL B  1:1", "DETAIL C  1:1"} <= texts


def test_dxf_layers_hatches_and_the_bores_tolerance(drawn, tmp_path):
    from flyopt.design.fits import hole_tolerance
    from flyopt.outputs.drawing import LAYERS, write_dxf

    drawing, design = drawn["rim_web"]
    path = tmp_path / "wheel.dxf"
    write_dxf(drawing, path)
    doc = ezdxf.readfile(path)
    assert set(LAYERS) <= {layer.dxf.name for layer in doc.layers}
    msp = doc.modelspace()
    used = {e.dxf.layer for e in msp}
    assert set(LAYERS) <= used  # every layer holds something
    hatches = [h for h in msp.query("HATCH") if _in_section(h.paths[0].vertices, design)]
    assert len(hatches) == 2 and all(h.dxf.layer == "HATCH" for h in msp.query("HATCH"))  # the section's two halves
    bore = next(d for d in msp.query("DIMENSION") if d.get_xdata("FLYOPT")[0].value == "bore")
    style = bore.override()
    h7 = hole_tolerance(design.bore, "H7")
    # ISO 286: 55 H7 is 55.000 ... 55.030
    assert style.get("dimtol") == 1 and style.get("dimtp") == pytest.approx(h7.upper * 1e3, rel=1e-12)
    assert style.get("dimtm") == 0 and h7.upper == pytest.approx(30e-6, rel=1e-12)


def test_dxf_title_block_says_what_and_whence(drawn, tmp_path):
    from flyopt.outputs.drawing import write_dxf

    drawing, design = drawn["rim_web"]
    path = tmp_path / "wheel.dxf"
    write_dxf(drawing, path)
    texts = " ".join(t.dxf.text for t in ezdxf.readfile(path).modelspace().query("TEXT[layer=='TITLE']"))
    sha = hashlib.sha256((PROBLEMS / "punch-press-wheel.toml").read_bytes()).hexdigest()
    import flyopt

    for words in (
        "Flywheel, rim, web and hub",
        f"Material: {flyopt.load(PROBLEMS / 'punch-press-wheel.toml').material_library()[design.material].display_name}",
        f"Mass: {design.mass:.2f} kg",
        f"J about the axis: {design.j_flywheel:.4g} kg·m²",
        "G 6.3",
        f"U_per = {design.stresses.unbalance_permissible * 1e6:.0f} g·mm",
        "Scale: 1:5",
        "Date: 2026-11-28",
        f"flyopt {flyopt.__version__}",
        "dimensions in mm",
        "punch-press-wheel.toml",
        sha,
    ):
        assert words in texts, words


def _in_section(points, design):
    """Whether points [mm] lie in section A-A (centred on x = 0, the axis on y = 0), not in a detail."""
    d = design.dims
    half = 0.5e3 * max(d.b, d.l_hub or 0.0, d.t_web or 0.0) + 1e-6
    return all(abs(p[0]) <= half and abs(p[1]) <= d.d_outer * 500 + 1e-6 for p in points)


def test_the_part_names_are_words(drawn):
    for case, words in (
        ("rim_web", {"Rim", "Web", "Hub", "Bore (shaft seat)"}),
        ("rim_arms", {"Rim", "Hub"}),
        ("disc", {"Disc"}),
    ):
        texts = {t.text for t in drawn[case][0].texts}
        assert words <= texts, case
        assert not any(code in " ".join(texts) for code in ("l_hub", "t_web", "d_hub", "arm_major"))
    assert any(t.text.startswith("Keyway DIN 6885-1, key 16 x 10") for t in drawn["rim_web"][0].texts)
    assert any(t.text.startswith("Arm, 8 off") for t in drawn["rim_arms"][0].texts)


@pytest.mark.parametrize("case", ["rim_web", "rim_arms"])
def test_the_keyway_is_cut_in_the_section(drawn, case):
    # the upper half's cut face starts at the keyway's bottom, bore/2 + t2; the lower half's at the bore;
    # an arms wheel's rim (a face of its own) is not cut
    drawing, design = drawn[case]
    r_bore, t2 = design.bore * 500, design.parts.key["t2"] * 1e3
    cut = [h for h in drawing.hatches if _in_section(h.boundary, design)]  # not the details' enlarged copies
    lows = sorted({min(y for _x, y in h.boundary) for h in cut if min(y for _x, y in h.boundary) > 0})
    highs = sorted({max(y for _x, y in h.boundary) for h in cut if max(y for _x, y in h.boundary) < 0})
    if case == "rim_web":
        assert lows == [pytest.approx(r_bore + t2, rel=1e-12)]
        assert highs == [pytest.approx(-r_bore, rel=1e-12)]
    else:  # the hub, the rim (and the revolved arm section, below the axis, ending at its ellipse's top)
        r_i = design.dims.d_inner * 500
        assert lows == [pytest.approx(r_bore + t2, rel=1e-12), pytest.approx(r_i, rel=1e-12)]
        assert highs[0] == pytest.approx(-r_i, rel=1e-12) and highs[-1] == pytest.approx(-r_bore, rel=1e-12)


def test_dimension_texts_do_not_overlap(drawn):
    """No two dimension texts share ground on the sheet (boxes from the description's estimate)."""
    for case, (drawing, _design) in drawn.items():
        boxes = []
        for dim in drawing.dimensions:
            w = 0.75 * 2.5 * len(dim.text) / drawing.scale
            h = 2.5 / drawing.scale
            if dim.vertical:
                w, h = h, w
            x, y = dim.text_at
            if dim.kind in ("diameter", "radius", "chamfer"):  # left-aligned from its point
                x += w / 2
            boxes.append((dim.name, x - w / 2, x + w / 2, y - h / 2, y + h / 2))
        for i, a in enumerate(boxes):
            for b in boxes[i + 1 :]:
                apart = a[2] <= b[1] or b[2] <= a[1] or a[4] <= b[3] or b[4] <= a[3]
                assert apart, (case, a[0], b[0])


@pytest.mark.parametrize("kind", ["svg", "pdf"])
def test_svg_and_pdf_are_written_with_the_same_texts(drawn, tmp_path, kind):
    from flyopt.report.drawing import write_drawing

    drawing, design = drawn["rim_web"]
    path = tmp_path / f"wheel.{kind}"
    write_drawing(drawing, path, kind)
    data = path.read_bytes()
    assert len(data) > 10_000
    if kind == "svg":
        text = data.decode("utf-8")
    else:
        import pypdf

        assert data.startswith(b"%PDF")
        text = pypdf.PdfReader(path).pages[0].extract_text()
    for dim in drawing.dimensions:
        assert dim.text.split(" ")[0].lstrip("Ø") in text, dim.name
    assert "Flywheel, rim, web and hub" in text and drawing.title["sha256"] in text.replace("\n", "")


def test_export_from_python_writes_each_format(tmp_path):
    from flyopt.report.drawing import export

    for suffix in ("dxf", "svg", "pdf"):
        out = tmp_path / f"wheel.{suffix}"
        drawing = export(PROBLEMS / "four-cylinder-engine.toml", out, date=DATE)
        assert out.stat().st_size > 1000 and drawing.scale == 0.5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wheel.dxf", "wheel.pdf", "wheel.svg"]


# --------------------------------------------------------------------------
# flyopt export: refusals
# --------------------------------------------------------------------------


def test_export_command_writes_a_dxf(main_cli, tmp_path):
    out = tmp_path / "wheel.dxf"
    status, stdout, stderr = main_cli("export", PROBLEMS / "punch-press-wheel.toml", "-o", out)
    assert (status, stderr) == (0, "") and f"wrote {out}" in stdout
    # the nine of the views, the two fillets' radii in the details; the three chamfers by leader
    msp = ezdxf.readfile(out).modelspace()
    assert len(msp.query("DIMENSION")) == 11 and len(msp.query("LEADER")) == 3


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("wheel.png", "must end in .dxf, .svg, .pdf or .step/.stp"),
        ("no-such-folder/wheel.dxf", "does not exist"),
    ],
)
def test_export_refuses_in_one_line_and_writes_nothing(main_cli, tmp_path, name, words):
    status, stdout, stderr = main_cli("export", PROBLEMS / "punch-press-wheel.toml", "-o", tmp_path / name)
    assert status == 2 and stderr.count("\n") == 1 and words in stderr and stdout == ""
    assert list(tmp_path.iterdir()) == []


def test_export_onto_its_own_scene_file_is_refused_and_the_scene_kept(main_cli, tmp_path):
    scene = tmp_path / "wheel.dxf"  # a scene file may have any name: the drawing must not overwrite it
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    scene.write_text(text, encoding="utf-8")
    status, stdout, stderr = main_cli("export", scene, "-o", scene)
    assert status == 2 and stderr.count("\n") == 1 and stdout == "", stderr
    assert "-o/--output" in stderr and "is the scene file itself" in stderr and "the drawing" in stderr, stderr
    assert [p.name for p in tmp_path.iterdir()] == ["wheel.dxf"] and scene.read_text(encoding="utf-8") == text


def test_export_without_ezdxf_names_the_extra(main_cli, tmp_path, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "ezdxf", None)  # import ezdxf raises ImportError
    status, _out, stderr = main_cli("export", PROBLEMS / "punch-press-wheel.toml", "-o", tmp_path / "w.dxf")
    assert status == 2 and stderr.count("\n") == 1 and "pip install 'flyopt[cad]'" in stderr
    assert list(tmp_path.iterdir()) == []
    # the other formats need no extra
    assert main_cli("export", PROBLEMS / "four-cylinder-engine.toml", "-o", tmp_path / "w.svg")[0] == 0


def test_export_of_a_machine_that_needs_no_flywheel_is_refused(main_cli, tmp_path):
    status, _out, stderr = main_cli("export", PROBLEMS / "conveyor.toml", "-o", tmp_path / "w.pdf")
    assert status == 2 and "no flywheel is needed" in stderr and stderr.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_export_of_an_infeasible_wheel_is_refused(main_cli, write_scene, tmp_path):
    text = (PROBLEMS / "punch-press-wheel.toml").read_text(encoding="utf-8")
    text = text.replace('max_outer_diameter = "1.2 m"', 'max_outer_diameter = "0.1 m"')
    scene = write_scene(text)
    out = tmp_path / "out"
    out.mkdir()
    status, _out, stderr = main_cli("export", scene, "-o", out / "w.pdf")
    assert status == 3 and "no flywheel to draw" in stderr and stderr.count("\n") == 1
    assert list(out.iterdir()) == []


def test_a_drawing_of_what_is_not_a_design_is_refused(drawn):
    import dataclasses

    from flyopt.design.result import Candidate
    from flyopt.outputs.drawing import drawing_of

    design = drawn["disc"][1]
    fields = {f.name: getattr(design, f.name) for f in dataclasses.fields(Candidate)}
    with pytest.raises(ValueError, match="not a design"):
        drawing_of(Candidate(**{**fields, "feasible": False}))
    assert math.isfinite(design.mass)


@pytest.mark.slow  # 5 s: every drawing format of two scenes; one name per material is tested by default in the text
def test_a_grade_is_named_by_its_designation_everywhere(tmp_path, main_cli):
    """One name per material (issue 29): press-arms-wheel's en_gjl_250 is EN-GJL-250 (EN 1561's designation)
    in the text, the report, the messages and the drawing's title block; the JSON keeps the scene's key."""
    import json

    from flyopt.report.drawing import export

    scene = PROBLEMS / "press-arms-wheel.toml"
    status, text, _ = main_cli("solve", scene)  # the command line in this process: no interpreter to start
    assert status == 0 and "EN-GJL-250 on intermediate" in text and "en_gjl_250" not in text
    data = json.loads(main_cli("solve", scene, "--json")[1])
    assert data["design"]["material"] == "en_gjl_250" and data["design"]["message"].startswith("EN-GJL-250 on the")
    drawing = export(scene, tmp_path / "arms.svg")
    assert drawing.title["material"] == "EN-GJL-250"


def test_a_wheel_of_a_scenes_own_material_is_drawn_saying_its_process_is_not_known(main_cli, tmp_path):
    """khurmi-16-14-book-rim designs its rim of a material the scene defines ("book_cast_iron"), whose casting
    process flyopt does not know: `flyopt export` stopped with a traceback (exit 1) and the report's drawing
    said "could not be drawn (TypeError ...)", the note's other wording formatted with the draft it has not.
    The drawing is written and its note says why it has no draft."""
    out = tmp_path / "rim.svg"
    scene = PROBLEMS / "textbook" / "khurmi-16-14-book-rim.toml"
    status, stdout, stderr = main_cli("export", scene, "-o", out)
    assert (status, stderr) == (0, "") and f"wrote {out}" in stdout
    svg = out.read_text(encoding="utf-8")
    assert "the process is not known" in " ".join(svg.split())
    status, _, stderr = main_cli("report", scene, "-o", tmp_path / "r.html")
    assert status == 0 and stderr == "", stderr  # no diagram failed (it warned "diagram drawing: TypeError")
    assert "could not be drawn" not in (tmp_path / "r.html").read_text(encoding="utf-8")


def test_a_scene_that_gives_its_flywheel_has_no_design_to_draw(main_cli, tmp_path):
    """khurmi-16-1 gives its flywheel ([flywheel], by its inertia) and asks what δ it leaves: export said "no
    flywheel to draw (no drive and wheel meet the limits)", exit 3, as if a design had failed."""
    status, stdout, stderr = main_cli("export", PROBLEMS / "textbook" / "khurmi-16-1.toml", "-o", tmp_path / "x.svg")
    assert status == 2 and stdout == "" and stderr.count("\n") == 1
    assert "gives its flywheel ([flywheel]) and designs none: nothing to draw" in stderr
    assert list(tmp_path.iterdir()) == []
