"""Every name a design can call binding has words for the text and the report (design.check.binding_label)."""

from __future__ import annotations

import itertools

import casadi as ca
import pytest
from conftest import ROOT, run_flyopt

from flyopt.design import castability, check, designer, wheel_nlp
from flyopt.names import Criterion, Geometry, Objective


def _row_names():
    """The constraint names of every wheel NLP structure, from the formulation the solver is built on."""
    names = set()
    rules = [None] + [p.rules for p in castability.processes().values()]
    for geo, bored, arms, crit, ductile, rule, disc_hub in itertools.product(
        (Geometry.RIM, Geometry.THIN_RIM, Geometry.DISC, Geometry.RIM_WEB, Geometry.RIM_ARMS),
        (False, True),
        (0, 6),
        (Criterion.RIM_SPEED, Criterion.STRESS),
        (True,),  # a brittle part writes sigma_r and sigma_t rows of the same name
        rules,
        (False, True),
    ):
        if (arms != 0) != (geo == Geometry.RIM_ARMS) or (disc_hub and geo != Geometry.DISC):
            continue
        if geo in (Geometry.RIM_WEB, Geometry.RIM_ARMS) and not bored:
            continue
        structure = wheel_nlp.WheelStructure(
            geo,
            crit,
            ductile,
            bored,
            arms,
            True,
            True,
            True,
            Objective.MASS,
            rule if geo in (Geometry.RIM_WEB, Geometry.RIM_ARMS, Geometry.DISC) else None,
            disc_hub,
        )
        n = len(wheel_nlp.variables_of(structure))
        x = ca.SX.sym("x", n)
        par = {name: ca.SX.sym(name) for name in wheel_nlp.PARAMETERS}
        allow = ca.SX.sym("allow", len(wheel_nlp.stressed_parts(structure)))
        names |= set(wheel_nlp.formulate(structure, x, par, allow).row_names)
    return names


@pytest.fixture(scope="module")
def every_name():
    rows = _row_names()
    bounds = set(designer._BOUND_NAMES.values()) | {"strength_table"}
    return rows | bounds | set(check.BINDING_NAMES)


def test_the_nlps_write_the_names_this_test_expects(every_name):
    """The enumeration reaches the part-named rows (else the test below would pass on too few names)."""
    assert {"stress_web", "stress_arms", "stress_disc", "castability_rim_web_ratio"} <= every_name
    assert any(n.startswith("castability_min_wall_") for n in every_name)


def test_every_binding_name_has_words(every_name):
    for name in sorted(every_name):
        label = check.binding_label(name)
        assert label != name or " " not in name and "_" not in name, name  # "inertia" is its own word
        assert "_" not in label.replace("D_m", ""), (name, label)


def test_part_rows_name_their_parts():
    assert check.binding_label("stress_web") == "web stress"
    assert check.binding_label("castability_rim_web_ratio") == "section ratio rim-web"
    assert check.binding_label("castability_min_wall_hub") == "hub cast wall"
    assert check.binding_label("hub_length_min") == "hub length min"


def test_the_text_and_the_report_say_the_words():
    """punch-press-wheel binds the section ratios and the hub's proportions (``--json`` keeps the names)."""
    text = run_flyopt("solve", str(ROOT / "problems/punch-press-wheel.toml")).stdout
    line = next(s for s in text.splitlines() if s.strip().startswith("binding"))
    assert "section ratio rim-web" in line and "hub length min" in line and "castability_" not in line
    assert "castability_" not in text.split("Every combination")[1].split("\n\n")[0]
