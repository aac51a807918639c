"""Numbers given from Python, checked and converted to SymPy (never parsed from text).

A value a user hands to the Python API (``Body3.at({m: 2})``, a radius, a height) is
taken as a Python or NumPy number, a :class:`fractions.Fraction` or a SymPy expression.
Numbers are converted by their type, so text never reaches ``sympify``; a string, a
complex number, NaN or an infinity is refused in one line naming the argument.

Examples
--------
>>> given_number(2, "mass")
2
>>> given_number("2", "mass")
Traceback (most recent call last):
...
rigidimpact.errors.InputError: mass: must be a number or a SymPy expression, not str '2'
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from fractions import Fraction
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError

__all__ = ["given_number", "given_values", "shown"]


def given_number(value: Any, where: str) -> sp.Expr:
    """`value` as SymPy: a real, finite number (converted by its type) or an expression,
    or InputError naming `where`.

    Examples
    --------
    >>> given_number(0.5, "radius"), given_number(Fraction(1, 3), "radius")
    (0.500000000000000, 1/3)
    >>> given_number(float("nan"), "radius")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: radius: must be finite, not nan
    """
    if isinstance(value, sp.Basic):
        converted = value
    elif isinstance(value, bool) or not isinstance(value, numbers.Number):
        raise InputError(where, "must be a number or a SymPy expression, not "
                         f"{type(value).__name__} {shown(value)}")
    elif isinstance(value, numbers.Integral):
        converted = sp.Integer(int(value))
    elif isinstance(value, Fraction):
        converted = sp.Rational(value.numerator, value.denominator)
    elif isinstance(value, numbers.Real):
        if not math.isfinite(float(value)):
            raise InputError(where, f"must be finite, not {float(value)}")
        converted = sp.Float(float(value))
    else:
        raise InputError(where, f"must be a real number, not {type(value).__name__} "
                         f"{shown(value)}")
    if not isinstance(converted, sp.Expr):
        raise InputError(where, "must be a number or a SymPy expression, not "
                         f"{type(converted).__name__} {shown(converted)}")
    if converted.is_number:
        if converted.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or converted.is_finite is False:
            raise InputError(where, f"must be finite, not {converted}")
        if converted.is_real is False:
            raise InputError(where, f"must be a real number, not {converted}")
    return converted


def given_values(values: Any, where: str = "values",
                 signs: bool = True) -> dict[sp.Basic, sp.Expr]:
    """A mapping of SymPy symbols to numbers (or expressions), each checked by
    :func:`given_number`; with `signs`, a symbol declared positive (a mass, a length)
    takes a positive number, one declared nonnegative one that is not negative (without,
    a limit such as a point foot's zero length is taken).

    Examples
    --------
    >>> m = sp.Symbol("m", positive=True)
    >>> given_values({m: 2})
    {m: 2}
    >>> given_values({m: -1})
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: values.m: must be positive (the symbol is declared positive), not -1
    """  # noqa: E501
    if not isinstance(values, Mapping):
        raise InputError(where, "must be a dict of SymPy symbols to numbers, not "
                         f"{type(values).__name__} {shown(values)}")
    checked = {}
    for key, value in values.items():
        if not isinstance(key, sp.Basic):
            raise InputError(where, "keys must be SymPy symbols (the ones the bodies were "
                             f"made with), not {type(key).__name__} {shown(key)}")
        field = f"{where}.{key}"
        number = given_number(value, field)
        if signs and number.is_number:
            if key.is_positive and not number.is_positive:
                raise InputError(field, "must be positive (the symbol is declared "
                                 f"positive), not {number}")
            if key.is_nonnegative and number.is_negative:
                raise InputError(field, "must not be negative (the symbol is declared "
                                 f"nonnegative), not {number}")
        checked[key] = number
    return checked


def shown(value: Any, width: int = 60) -> str:
    """`value`'s repr on one line, cut to `width` (it goes into a one-line message).

    Examples
    --------
    >>> shown(list(range(30)), 20)
    '[0, 1, 2, 3, 4, 5...'
    """
    text = " ".join(repr(value).split())
    return text if len(text) <= width else text[:width - 3] + "..."
