"""The whitelisted expression parser: numpy and CasADi agree; nothing else gets through."""

import math

import casadi as ca
import numpy as np
import pytest
from numpy.testing import assert_allclose

from flyopt.errors import ExpressionError
from flyopt.expression import Expression

CASES = [
    ("25000 + 3600*sin(phi)", lambda p: 25000 + 3600 * np.sin(p)),
    ("-phi**2 / 3 + +2", lambda p: -p**2 / 3 + 2),
    ("sqrt(abs(cos(phi))) * exp(-phi) - log(2 + tan(phi/4))",
     lambda p: np.sqrt(np.abs(np.cos(p))) * np.exp(-p) - np.log(2 + np.tan(p / 4))),
    ("max(0, 1000*sin(phi)) + min(phi, pi) + e", lambda p: np.maximum(0, 1000 * np.sin(p)) + np.minimum(p, np.pi) + np.e),
    ("2**3**0.5", lambda p: 2 ** 3 ** 0.5 + 0 * p),
]


@pytest.mark.parametrize("text, reference", CASES)
def test_numpy_and_casadi_match_a_hand_written_reference(text, reference):
    expr = Expression(text)
    phi = np.linspace(0, 2 * math.pi, 37)
    assert_allclose(expr.numpy(phi=phi) + 0 * phi, reference(phi), rtol=1e-15, atol=1e-12)
    x = ca.SX.sym("phi")
    f = ca.Function("f", [x], [expr.casadi(phi=x)])
    assert_allclose(np.array(f(phi)).ravel(), reference(phi), rtol=1e-14, atol=1e-12)


def test_depends_on_and_extra_variables():
    assert Expression("1 + 2").depends_on == frozenset()
    expr = Expression("phi*omega", variables=("phi", "omega"))
    assert expr.depends_on == {"phi", "omega"}
    assert expr.numpy(phi=2.0, omega=3.0) == 6.0
    with pytest.raises(ExpressionError, match="needs a value for omega"):
        expr.numpy(phi=1.0)


REJECTED = [
    ("__import__('os').system('true')", "only plain function calls"),
    ("__import__('os')", "unknown function '__import__'"),
    ("phi.__class__", "Attribute is not allowed"),
    ("open('x')", "unknown function 'open'"),
    ("[1, 2][0]", "Subscript is not allowed"),
    ("[1, 2]", "List is not allowed"),
    ("phi if phi else 1", "IfExp is not allowed"),
    ("phi < 1", "Compare is not allowed"),
    ("phi // 2", r"// is not allowed"),
    ("phi ^ 2", r"\^ is not allowed; use \*\* for powers"),
    ("phi % 2", "% is not allowed"),
    ("'abc'", "only numbers"),
    ("True", "only numbers"),
    ("omega * 2", "unknown name 'omega'"),
    ("sine(phi)", "did you mean 'sin'"),
    ("sin(phi, 2)", r"sin\(\) takes 1 argument"),
    ("max(phi)", r"max\(\) takes 2 argument"),
    ("sin(x=phi)", "no keyword arguments"),
    ("lambda: 1", "Lambda is not allowed"),
    ("(1, 2)", "Tuple is not allowed"),
    ("1 +", "cannot parse"),
    ("x" * 3000, "longer than"),
    ("1e999", "not finite"),
]


@pytest.mark.parametrize("text, words", REJECTED)
def test_rejected(text, words):
    with pytest.raises(ExpressionError, match=words):
        Expression(text)


def test_not_a_string():
    with pytest.raises(ExpressionError, match="must be a string"):
        Expression(42)
