"""The relaxation's constraint Jacobian, formed apart from its dense rows, against CasADi's own, bit for bit.

flyopt.drive.relaxation hands IPOPT a Jacobian of the constraints that it
forms itself (the two rows that add a term of every interval differentiated in
two steps) because CasADi's own took a forward sweep per variable to build.
The NLP must be the same one: here CasADi builds its own Jacobian of the same
constraints, and the two are compared, entry for entry and bit for bit, at
random points, together with the relaxed optimum's figures.
"""

import casadi as ca
import numpy as np
import pytest

from flyopt.analysis import analyse
from flyopt.design import design_inputs
from flyopt.drive.relaxation import BUILDS, CatalogueFit, RelaxedWheel, relax
from flyopt.io.scene import load


def _relaxed():
    """press-drive's relaxation with its winning material, on a machine analysed afresh (built, not cached)."""
    scene = load("problems/press-drive.toml")
    analysis = analyse(scene)
    spec = scene.drive
    inputs = design_inputs(scene)
    steel = next(m for m in inputs.materials if m.name == "cast_steel")
    fit = CatalogueFit.of(spec.motors.motors)
    wheel = RelaxedWheel.of(steel, inputs.spec)
    return relax(
        analysis.machine, scene.omega_mean, scene.delta, scene.efficiency, fit, spec, wheel, analysis.driving_torque
    )


@pytest.fixture(scope="module")
def captured():
    seen = {}
    original = ca.nlpsol

    def nlpsol(name, plugin, nlp, opts):
        seen.update(nlp=nlp, opts=opts)
        return original(name, plugin, nlp, opts)

    ca.nlpsol = nlpsol
    try:
        count = BUILDS["count"]
        relaxed = _relaxed()
        assert BUILDS["count"] == count + 1
    finally:
        ca.nlpsol = original
    return seen, relaxed


def test_jacobian_is_casadis_own_bit_for_bit(captured):
    seen, _ = captured
    nlp, ours = seen["nlp"], seen["opts"]["jac_g"]
    theirs = ca.nlpsol("reference", "ipopt", nlp, {"print_time": False}).get_function("nlp_jac_g")
    rng = np.random.default_rng(26)
    n_x, n_p = nlp["x"].shape[0], nlp["p"].shape[0]
    for _ in range(5):
        x = 1 + 0.3 * rng.standard_normal(n_x)
        p = np.abs(1 + 0.3 * rng.standard_normal(n_p))
        g_a, jac_a = theirs(x, p)
        g_b, jac_b = ours(x, p)
        assert jac_a.sparsity() == jac_b.sparsity()
        assert np.array_equal(np.array(jac_a.nonzeros()), np.array(jac_b.nonzeros()))
        assert np.array_equal(np.array(g_a), np.array(g_b))


def test_dense_rows_are_there(captured):
    """The case the Jacobian is formed apart for: rows that touch (almost) every variable."""
    seen, _ = captured
    nlp = seen["nlp"]
    pattern = ca.jacobian_sparsity(nlp["g"], nlp["x"])
    per_row = np.diff(np.array(pattern.T.colind()))
    assert np.sum(per_row > 0.9 * nlp["x"].shape[0]) == 2


def test_same_optimum_as_casadis_own_jacobian(captured):
    """The relaxation solved again by an NLP with CasADi's own Jacobian: the same optimum, bit for bit."""
    seen, relaxed = captured
    opts = {k: v for k, v in seen["opts"].items() if k != "jac_g"}
    original = ca.nlpsol

    def nlpsol(name, plugin, nlp, options):  # the same NLP, CasADi's own Jacobian
        return original(name, plugin, nlp, opts)

    ca.nlpsol = nlpsol
    try:
        again = _relaxed()
    finally:
        ca.nlpsol = original
    assert again == relaxed
