"""Safe arithmetic expressions for torque curves, usable as numpy and CasADi.

A scene may give a torque as ``expression = "25000 + 3600*sin(phi)"``. The
text is parsed with :mod:`ast` into a syntax tree, and every node is checked
against a whitelist: numbers, the declared variables (``phi``; later
``omega``), the constants ``pi`` and ``e``, ``+ - * / **``, unary signs,
parentheses and the functions ``sin cos tan exp log sqrt abs min max``.
Nothing is ever evaluated by Python: the checked tree is turned into nested
closures that call numpy or CasADi, so attribute access, subscripts, keyword
arguments, strings, comprehensions and unknown names are rejected before any
arithmetic happens.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike

from flyopt.errors import ExpressionError, shorten
from flyopt.names import closest

MAX_LENGTH = 2000
"""Longest expression accepted [characters]: a torque curve, not a program."""

MAX_DEPTH = 200
"""Deepest nesting of operations accepted (``-(-(-phi))`` is 4, ``1+2+3`` is 3): the
compiled closures recurse once per level, and Python allows about 1000."""

CONSTANTS = {"pi": math.pi, "e": math.e}

# name -> (number of arguments, numpy implementation, casadi attribute name)
FUNCTIONS = {
    "sin": (1, np.sin, "sin"),
    "cos": (1, np.cos, "cos"),
    "tan": (1, np.tan, "tan"),
    "exp": (1, np.exp, "exp"),
    "log": (1, np.log, "log"),
    "sqrt": (1, np.sqrt, "sqrt"),
    "abs": (1, np.abs, "fabs"),
    "min": (2, np.minimum, "fmin"),
    "max": (2, np.maximum, "fmax"),
}

_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}
_UNARY = {ast.USub: lambda a: -a, ast.UAdd: lambda a: a}
_OTHER_OPERATORS = {
    ast.FloorDiv: "//",
    ast.Mod: "%",
    ast.BitXor: "^",
    ast.BitAnd: "&",
    ast.BitOr: "|",
    ast.MatMult: "@",
    ast.LShift: "<<",
    ast.RShift: ">>",
    ast.Invert: "~",
    ast.Not: "not",
}


_EPS = float(np.finfo(float).eps)


def _bound(node, values):
    """(value, error bound) of a checked expression tree under numpy (see Expression.error_bound)."""
    # numbers, constants and variables are exact: the expression means the floats it holds
    if isinstance(node, ast.Constant):
        return float(cast(float, node.value)), 0.0  # a number: checked by _compile
    if isinstance(node, ast.Name):
        if node.id in values:
            return np.asarray(values[node.id], dtype=float), 0.0
        return CONSTANTS[node.id], 0.0
    if isinstance(node, ast.UnaryOp):
        v, e = _bound(node.operand, values)
        return (-v if isinstance(node.op, ast.USub) else v), e
    if isinstance(node, ast.BinOp):
        (a, ea), (b, eb) = _bound(node.left, values), _bound(node.right, values)
        v = _BINARY[type(node.op)](a, b)
        if isinstance(node.op, (ast.Add, ast.Sub)):
            e = ea + eb
        elif isinstance(node.op, ast.Mult):
            e = np.abs(b) * ea + np.abs(a) * eb
        elif isinstance(node.op, ast.Div):
            e = (ea + np.abs(v) * eb) / np.abs(b)
        else:  # a ** b
            e = np.where(ea > 0, np.abs(b * a ** (b - 1)) * ea, 0.0) + np.where(
                eb > 0, np.abs(v * np.log(np.abs(a))) * eb, 0.0
            )
        return v, e + _EPS * np.abs(v)
    name = node.func.id
    args = [_bound(a, values) for a in node.args]
    if name in ("min", "max"):
        (a, ea), (b, eb) = args
        # the branch taken carries its error; where round-off could swap the branches, the larger
        first = (a <= b) if name == "min" else (a >= b)
        return FUNCTIONS[name][1](a, b), np.where(np.abs(a - b) <= ea + eb, np.maximum(ea, eb), np.where(first, ea, eb))
    ((x, ex),) = args
    v = FUNCTIONS[name][1](x)
    slope = {
        "sin": lambda: np.abs(np.cos(x)),
        "cos": lambda: np.abs(np.sin(x)),
        "tan": lambda: 1.0 / np.cos(x) ** 2,
        "exp": lambda: np.abs(v),
        "log": lambda: 1.0 / np.abs(x),
        "sqrt": lambda: 0.5 / np.abs(v),
        "abs": lambda: 1.0,
    }[name]()
    return v, np.where(ex > 0, slope * ex, 0.0) + (0.0 if name == "abs" else _EPS * np.abs(v))


def _depth(node):
    """How deep the operations of a syntax tree nest (counted without recursion)."""
    deepest, stack = 0, [(node, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node) if isinstance(child, ast.expr))
    return deepest


class Expression:
    """A parsed, whitelisted expression in a few named variables.

    Parameters
    ----------
    text : str
        The expression, e.g. ``"25000 + 3600*sin(phi)"``.
    variables : tuple of str
        The names the expression may use (default ``("phi",)``).

    Raises
    ------
    ExpressionError
        Syntax error, a name or function outside the whitelist, or a
        construct that is not plain arithmetic.

    Examples
    --------
    >>> f = Expression("1 + 2*sin(phi)")
    >>> float(f.numpy(phi=0.0))
    1.0
    """

    def __init__(self, text: str, variables: Sequence[str] = ("phi",)) -> None:
        if not isinstance(text, str):
            raise ExpressionError(f"an expression must be a string, got {shorten(text)}")
        if len(text) > MAX_LENGTH:
            raise ExpressionError(f"expression longer than {MAX_LENGTH} characters")
        self.text = text
        self.variables = tuple(variables)
        too_deep = (
            f"{shorten(text)}: operations nested more than {MAX_DEPTH} deep (a sum nests one level "
            "per term: give a long curve as a points table)"
        )
        try:
            tree = ast.parse(text.strip(), mode="eval")
        except SyntaxError as err:
            raise ExpressionError(f"cannot parse {shorten(text)}: {err.msg}") from None
        except (RecursionError, MemoryError):  # Python's own parser gives up
            raise ExpressionError(too_deep) from None
        if _depth(tree.body) > MAX_DEPTH:
            raise ExpressionError(too_deep)
        self.used: set[str] = set()
        self._kinks: list[Callable[..., Any]] = []
        self._build = self._compile(tree.body)
        self._tree = tree.body
        with np.errstate(all="ignore"):
            self._constant(tree.body)

    @property
    def depends_on(self) -> frozenset[str]:
        """The variables that actually occur in the expression (a frozenset)."""
        return frozenset(self.used)

    def numpy(self, **values: ArrayLike) -> Any:
        """Evaluate with numpy; variables are floats or arrays [SI]."""
        return self._evaluate(values, backend="numpy")

    def casadi(self, **values: Any) -> Any:
        """Build the CasADi expression; variables are SX/MX/DM symbols or numbers."""
        return self._evaluate(values, backend="casadi")

    def _evaluate(self, values: Mapping[str, Any], backend: str) -> Any:
        missing = [v for v in self.used if v not in values]
        if missing:
            raise ExpressionError(f"{shorten(self.text)} needs a value for {', '.join(sorted(missing))}")
        if backend == "casadi":
            import casadi as ca

            functions = {name: getattr(ca, attr) for name, (_, _, attr) in FUNCTIONS.items()}
        else:
            functions = {name: fn for name, (_, fn, _) in FUNCTIONS.items()}
        return self._build(values, functions)

    @property
    def has_kinks(self) -> bool:
        """True when ``abs``, ``min`` or ``max`` may make the expression kink."""
        return bool(self._kinks)

    def error_bound(self, **values: ArrayLike) -> Any:
        """A bound on the round-off of :meth:`numpy` at these values (same units).

        A running forward error bound: every operation adds half an ulp of
        its result (``eps |v|``) and passes on its operands' errors through
        its derivative (x ± y: e_x + e_y; x y: |y| e_x + |x| e_y; sin x:
        |cos x| e_x; ...). ``(1e6 + sin(phi)) - 1e6`` is known only to
        ~1e-10 however small it is; the cycle analysis asks its quadrature
        for no more than that.
        """
        return self.numpy_with_bound(**values)[1]

    def numpy_with_bound(self, **values: ArrayLike) -> tuple[Any, Any]:
        """(:meth:`numpy`, :meth:`error_bound`) from one pass over the tree."""
        with np.errstate(all="ignore"):
            return _bound(self._tree, values)

    @property
    def kink_count(self) -> int:
        """How many ``abs``, ``min`` and ``max`` calls the expression holds."""
        return len(self._kinks)

    def kink_argument(self, index: int, **values: ArrayLike) -> Any:
        """One quantity whose sign changes are kinks of the expression (numpy).

        ``abs(g)`` kinks where g changes sign, ``min(g, h)`` and ``max(g, h)``
        where g − h does. Calls are numbered as they are compiled: left to
        right, an inner call before the call that holds it.
        """
        functions = {name: fn for name, (_, fn, _) in FUNCTIONS.items()}
        return self._kinks[index](values, functions)

    def kink_arguments(self, **values: ArrayLike) -> list[Any]:
        """Every kink quantity (:meth:`kink_argument`), in their order."""
        return [self.kink_argument(k, **values) for k in range(len(self._kinks))]

    def __repr__(self) -> str:
        return f"Expression({self.text!r})"

    def __reduce__(self) -> tuple[type[Expression], tuple[str, tuple[str, ...]]]:
        """Pickle by text: the compiled closures are rebuilt (for worker processes)."""
        return (Expression, (self.text, self.variables))

    # -- compilation of the checked tree into closures -----------------------
    def _compile(self, node):
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ExpressionError(
                    f"{shorten(self.text)}: only numbers are allowed as constants, got {shorten(node.value)}"
                )
            try:
                number = float(node.value)
            except OverflowError:  # an integer beyond the floats
                number = math.inf
            if not math.isfinite(number):
                raise ExpressionError(f"{shorten(self.text)}: {shorten(node.value)} is not a finite number")
            return lambda values, fns: number
        if isinstance(node, ast.Name):
            name = node.id
            if name in self.variables:
                self.used.add(name)
                return lambda values, fns: values[name]
            if name in CONSTANTS:
                number = CONSTANTS[name]
                return lambda values, fns: number
            raise ExpressionError(f"{shorten(self.text)}: unknown name {shorten(name)}{self._hint(name)}")
        if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
            op = _BINARY[type(node.op)]
            left, right = self._compile(node.left), self._compile(node.right)
            return lambda values, fns: op(left(values, fns), right(values, fns))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
            unary: Any = _UNARY[type(node.op)]
            operand = self._compile(node.operand)
            return lambda values, fns: unary(operand(values, fns))
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name):
                raise ExpressionError(f"{shorten(self.text)}: only plain function calls are allowed")
            name = node.func.id
            if name not in FUNCTIONS:
                raise ExpressionError(
                    f"{shorten(self.text)}: unknown function {shorten(name)}{self._hint(name, functions=True)}"
                )
            if node.keywords:
                raise ExpressionError(f"{shorten(self.text)}: {name}() takes no keyword arguments")
            arity = FUNCTIONS[name][0]
            if len(node.args) != arity:
                raise ExpressionError(f"{shorten(self.text)}: {name}() takes {arity} argument(s), got {len(node.args)}")
            args = [self._compile(a) for a in node.args]
            if name == "abs":
                self._kinks.append(args[0])
            elif name in ("min", "max"):
                first, second = args
                self._kinks.append(lambda values, fns: first(values, fns) - second(values, fns))
            return lambda values, fns: fns[name](*(a(values, fns) for a in args))
        op = type(getattr(node, "op", None))
        what = f"the operator {_OTHER_OPERATORS[op]}" if op in _OTHER_OPERATORS else type(node).__name__
        hint = "; use ** for powers" if op is ast.BitXor else ""
        raise ExpressionError(
            f"{shorten(self.text)}: {what!s} is not allowed{hint} (numbers, "
            f"{', '.join(self.variables)}, pi, + - * / **, and "
            f"{' '.join(FUNCTIONS)} only)"
        )

    def _constant(self, node):
        """The value of a checked subtree that holds no variable (None if it holds one).

        Every such part must be a finite number: ``9**9**9**9``, ``1/0``,
        ``log(0)`` or ``(-8)**(1/3)`` is refused here, naming the part,
        rather than failing (or turning complex) when it is evaluated.
        IEEE arithmetic (numpy float64) gives inf or nan where Python's
        floats would raise.
        """
        if isinstance(node, ast.Constant):
            return np.float64(float(cast(float, node.value)))  # checked finite by _compile
        if isinstance(node, ast.Name):
            return None if node.id in self.variables else np.float64(CONSTANTS[node.id])
        if isinstance(node, ast.UnaryOp):
            operand = self._constant(node.operand)
            return None if operand is None else _UNARY[type(node.op)](operand)
        if isinstance(node, ast.BinOp):
            parts = [self._constant(node.left), self._constant(node.right)]
            function = _BINARY[type(node.op)]
        else:
            parts = [self._constant(a) for a in node.args]
            function = FUNCTIONS[node.func.id][1]
        if any(p is None for p in parts):
            return None
        value = np.float64(function(*parts))
        if not np.isfinite(value):
            raise ExpressionError(
                f"{shorten(self.text)}: {shorten(ast.unparse(node))} is {value} "
                "(it overflows or is undefined): every value must be a finite number"
            )
        return value

    def _hint(self, name, functions=False):
        pool = list(FUNCTIONS) if functions else [*self.variables, *CONSTANTS]
        close = closest(name, pool)
        allowed = ", ".join(pool)
        return f" (did you mean {shorten(close)}? allowed: {allowed})" if close else f" (allowed: {allowed})"
