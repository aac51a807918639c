"""A scene's numbers: the values every simulation needs, and its expressions as floats.

Examples
--------
>>> import sympy as sp
>>> as_float(sp.sqrt(2) / 2, {})
0.7071067811865476
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import Scene

__all__ = ["scene_values", "as_float", "as_array"]


def scene_values(scene: Scene) -> dict[sp.Symbol, sp.Expr]:
    """The scene's ``[values]``, after checking that every symbol the bodies use has one.

    Raises
    ------
    InputError
        Naming the symbols without a value.
    """
    needed = set()
    for body in scene.bodies:
        for x in (body.mass, body.inertia, *body.position, *body.velocity, body.spin,
                  *(v for _, v in body.dimensions)):
            needed |= x.free_symbols
        if body.pivot is not None:
            needed |= sp.Tuple(*body.pivot).free_symbols
    needed |= sp.sympify(scene.contact.restitution).free_symbols
    for x in scene.contact.normal:
        needed |= sp.sympify(x).free_symbols
    missing = sorted(s.name for s in needed if s not in scene.values)
    if missing:
        raise InputError("values", f"simulate needs numbers for: {', '.join(missing)}")
    return dict(scene.values)


def as_float(x: Any, values: Mapping[sp.Symbol, sp.Expr]) -> float:
    """An expression at the values, evaluated to 30 digits and rounded once to float64."""
    return float(sp.sympify(x).subs(values).evalf(30))


def as_array(v: Iterable[Any], values: Mapping[sp.Symbol, sp.Expr]) -> np.ndarray:
    """A vector of expressions at the values, as a float64 array."""
    return np.array([as_float(c, values) for c in v], dtype=float)
