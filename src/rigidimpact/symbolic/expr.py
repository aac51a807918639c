"""A bounded, safe parser for the expressions of a scene file.

Scene text is read with Python's :mod:`ast` and walked by a whitelist: numbers, declared
symbols, ``+ - * / **`` (``^`` means power, as a physicist writes it), parentheses,
``sin cos tan sqrt`` and ``pi``, with an optional trailing ``deg``. The walker builds
SymPy objects itself, so text from a file never reaches ``eval``, ``sympify`` or
``parse_expr``. Three bounds keep every input cheap:

* the text is ASCII and at most ``MAX_EXPRESSION`` characters (no look-alike Unicode
  digits or letters, which Python would silently normalise);
* number literals are read exactly from their digits (``0.1`` is 1/10, not the nearest
  double) and must lie in [1e-100, 1e100] (or be zero);
* every intermediate result is bounded too, not only the literals: a numerator or
  denominator of more than ``MAX_DIGITS`` digits, or a power whose exponent exceeds
  ``MAX_POWER``, is refused, so ``((9**16)**16)**16`` stops at its second power.

Every problem is an :class:`~rigidimpact.errors.InputError` naming the field.

Examples
--------
>>> from rigidimpact.symbolic.notation import SYMBOLS
>>> parse_expression("2*M + m*(1 + sin(theta)^2)", "demo", SYMBOLS)
2*M + m*(sin(theta)**2 + 1)
>>> parse_expression("30 deg", "demo")
pi/6
>>> parse_expression("0.1", "demo")
1/10
>>> parse_expression("__import__('os')", "demo")
Traceback (most recent call last):
...
rigidimpact.errors.InputError: demo: unknown function '__import__'; use sin, cos, tan or sqrt
"""

from __future__ import annotations

import ast
import math
import re
from collections.abc import Mapping
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError

__all__ = ["parse_expression", "check_size", "MAX_EXPRESSION", "MAX_DIGITS", "MAX_POWER",
           "MAX_DEPTH", "FUNCTIONS", "CONSTANTS"]

MAX_EXPRESSION = 400
MAX_DIGITS = 101  # numerator or denominator: 1e100 and 1e-100 fit, 1e101 does not
MAX_POWER = 16
MAX_DEPTH = 40  # nesting of operations and parentheses
FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sqrt": sp.sqrt}
CONSTANTS = {"pi": sp.pi}
_LITERAL = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_LIMIT = 10**MAX_DIGITS
_OPERATORS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**"}


def check_size(expr: sp.Expr, where: str) -> sp.Expr:
    """Refuse an expression holding a number or a power larger than the tool supports.

    Examples
    --------
    >>> check_size(sp.Integer(10)**100, "x")
    10000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000
    >>> check_size(sp.Integer(10)**101, "x")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: x: a number beyond what the tool supports (numbers from 1e-100 to 1e100, at most 101 digits)
    """  # noqa: E501
    for number in expr.atoms(sp.Rational):
        if abs(number.p) >= _LIMIT or number.q >= _LIMIT:
            raise InputError(where, f"a number beyond what the tool supports (numbers from "
                             f"1e-100 to 1e100, at most {MAX_DIGITS} digits)")
    for power in expr.atoms(sp.Pow):
        exponent = power.exp
        if exponent.is_number and abs(exponent) > MAX_POWER:
            raise InputError(where, f"a power beyond what the tool supports (exponents of "
                             f"size at most {MAX_POWER})")
    return expr


def _literal(text: str, where: str) -> sp.Rational:
    """A number literal read exactly from its digits, within the supported range."""
    if not _LITERAL.fullmatch(text):
        raise InputError(where, f"not a plain decimal number: {text!r}")
    mantissa, _, exponent = text.lower().partition("e")
    if exponent and abs(int(exponent)) > 400:  # before building a huge integer
        raise InputError(where, f"{text} is beyond what the tool supports (1e-100 to 1e100)")
    value = sp.Rational(mantissa) * sp.Rational(10) ** int(exponent or 0)
    if value != 0 and not sp.Rational(1, 10**100) <= value <= sp.Rational(10**100):
        raise InputError(where, f"{text} is beyond what the tool supports (1e-100 to 1e100)")
    return check_size(value, where)


class _Walker:
    """Builds a SymPy expression from a whitelisted syntax tree, bounding every step."""

    def __init__(self, text: str, where: str, symbols: Mapping[str, sp.Symbol]) -> None:
        self.text, self.where, self.symbols = text, where, symbols

    def fail(self, message: str) -> InputError:
        return InputError(self.where, message)

    def build(self, node: ast.AST) -> sp.Expr:
        if isinstance(node, ast.Constant):
            return self.constant(node)
        if isinstance(node, ast.Name):
            return self.name(node.id)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            operand = self.build(node.operand)
            return operand if isinstance(node.op, ast.UAdd) else -operand
        if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
            return self.binary(node)
        if isinstance(node, ast.Call):
            return self.call(node)
        raise self.fail(f"{self.shown(node)!r} is not allowed; expressions use numbers, "
                        "symbols, + - * / ** ^, parentheses, sin cos tan sqrt and pi")

    def shown(self, node: ast.AST) -> str:
        return ast.get_source_segment(self.text, node) or type(node).__name__

    def constant(self, node: ast.Constant) -> sp.Expr:
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise self.fail(f"{self.shown(node)!r} is not a number")
        return _literal(self.shown(node), self.where)

    def name(self, text: str) -> sp.Expr:
        if text in CONSTANTS:
            return CONSTANTS[text]
        if text in self.symbols:
            return self.symbols[text]
        if text in FUNCTIONS:
            raise self.fail(f"{text} is a function: write {text}(x)")
        raise self.fail(f"unknown symbol {text!r}; declare it under [symbols]")

    def binary(self, node: ast.BinOp) -> sp.Expr:
        left, right = self.build(node.left), self.build(node.right)
        op = _OPERATORS[type(node.op)]
        if op == "/" and right.is_zero:
            raise self.fail("division by zero")
        if op == "**":
            return self.power(left, right)
        result = {"+": sp.Add, "-": lambda a, b: a - b, "*": sp.Mul,
                  "/": lambda a, b: a / b}[op](left, right)
        return check_size(result, self.where)

    def power(self, base: sp.Expr, exponent: sp.Expr) -> sp.Expr:
        if exponent.free_symbols or not exponent.is_number or not exponent.is_real:
            raise self.fail("an exponent must be a number")
        if abs(exponent) > MAX_POWER:
            raise self.fail(f"a power beyond what the tool supports (exponents of size at "
                            f"most {MAX_POWER})")
        if base.is_zero and exponent.is_nonpositive:
            raise self.fail("zero to a non-positive power")
        if base.is_Rational and exponent.is_Rational:  # bound the size before computing it
            digits = max(len(str(abs(base.p))), len(str(base.q)))
            if digits * abs(exponent) > 2 * MAX_DIGITS:
                raise self.fail(f"a number beyond what the tool supports (numbers from "
                                f"1e-100 to 1e100, at most {MAX_DIGITS} digits)")
        return check_size(base**exponent, self.where)

    def call(self, node: ast.Call) -> sp.Expr:
        function = node.func.id if isinstance(node.func, ast.Name) else None
        if function not in FUNCTIONS:
            raise self.fail(f"unknown function {function or self.shown(node.func)!r}; use "
                            "sin, cos, tan or sqrt")
        if node.keywords or len(node.args) != 1:
            raise self.fail(f"{function} takes one argument")
        argument = self.build(node.args[0])
        if function == "tan" and (argument / sp.pi - sp.Rational(1, 2)).is_integer:
            raise self.fail(f"tan({argument}) is infinite")
        return check_size(FUNCTIONS[function](argument), self.where)


def _number(value: int | float, where: str) -> sp.Expr:
    """An exact number from a TOML integer or float (a float from its shortest repr)."""
    if isinstance(value, int):
        if abs(value) >= _LIMIT:
            raise InputError(where, f"{value} is beyond what the tool supports (1e-100 to "
                             "1e100)")
        return sp.Integer(value)
    if not math.isfinite(value):
        raise InputError(where, f"must be finite, got {value}")
    return -_literal(repr(-value), where) if value < 0 else _literal(repr(value), where)


def _depth(text: str) -> int:
    """How deeply the text nests: parentheses, and unary signs and powers, which chain."""
    depth = deepest = 0
    for char in text:
        depth += (char == "(") - (char == ")")
        deepest = max(deepest, depth)
    return deepest + text.count("**") + len(re.findall(r"[-+]\s*[-+(]", text))


def parse_expression(value: Any, where: str,
                     symbols: Mapping[str, sp.Symbol] | None = None) -> sp.Expr:
    """An exact SymPy expression from a scene value (a TOML number or string).

    Parameters
    ----------
    value : str, int or float
        The value as read from TOML (a float is read from its shortest repr, exactly).
    where : str
        The field, for messages.
    symbols : mapping, optional
        The names that may appear (none by default: numbers only).

    Raises
    ------
    InputError
        For anything outside the grammar or the bounds, naming `where`.

    Examples
    --------
    >>> parse_expression(0.25, "x")
    1/4
    >>> parse_expression("1e7", "x")
    10000000
    >>> parse_expression("2^3^2", "x")  # right-associative, as in mathematics
    512
    >>> parse_expression("1e-300", "x")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: x: 1e-300 is beyond what the tool supports (1e-100 to 1e100)
    """
    symbols = {} if symbols is None else symbols
    # a scene repeats its values ("0", "1/2") thousands of times: each text is read once
    # per set of names (a failure is not kept, so its message names each field)
    key = (value, type(value), tuple(symbols.items()))
    try:
        return _READ[key]
    except (KeyError, TypeError):
        pass
    expr = _parse(value, where, symbols)
    if len(_READ) > 4096:
        _READ.clear()
    _READ[key] = expr
    return expr


_READ: dict[tuple, sp.Expr] = {}


def _parse(value: Any, where: str, symbols: Mapping[str, sp.Symbol]) -> sp.Expr:
    if isinstance(value, bool):
        raise InputError(where, "expected a number or expression, not true/false")
    if isinstance(value, (int, float)):
        return _number(value, where)
    if not isinstance(value, str):
        raise InputError(where, f"expected a number or expression, got {type(value).__name__}")
    if len(value) > MAX_EXPRESSION:
        raise InputError(where, f"expression longer than {MAX_EXPRESSION} characters")
    if not value.isascii() or not value.isprintable():
        bad = next(c for c in value if not c.isascii() or not c.isprintable())
        raise InputError(where, f"unexpected character {bad!r}: expressions are plain ASCII")
    text = value.strip()
    degrees = re.fullmatch(r"(.*?)\s*deg", text, re.DOTALL)
    if degrees:
        text = degrees.group(1)
    if not text:
        raise InputError(where, "empty expression")
    if text.lower().lstrip("+-") in ("nan", "inf", "infinity"):
        raise InputError(where, f"must be finite, got {value!r}")
    text = text.replace("^", "**")  # before parsing: Python's ^ binds looser than +
    try:
        tree = ast.parse(text, mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        raise InputError(where, f"cannot read {value!r} as an expression") from None
    if _depth(text) > MAX_DEPTH:
        raise InputError(where, "expression nested too deeply")
    expr = _Walker(text, where, symbols).build(tree.body)
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        raise InputError(where, f"must be finite, got {expr}")
    if expr.is_real is False:
        raise InputError(where, f"must be real, got {expr}")
    return expr * sp.pi / 180 if degrees else expr
