"""Planar geometry: the one copy of the cross product, omega x r and the contact frame.

Vectors are 2x1 SymPy matrices; the z axis points out of the plane, so a positive spin
turns counter-clockwise.

Examples
--------
>>> cross(sp.Matrix([1, 0]), sp.Matrix([0, 1]))
1
>>> spin_cross(1, sp.Matrix([1, 0])).T
Matrix([[0, 1]])
>>> frame_of(sp.Matrix([0, 1]))
Matrix([
[ 0, 1],
[-1, 0]])
"""

from __future__ import annotations

import sympy as sp

__all__ = ["cross", "spin_cross", "perp", "frame_of"]


def cross(a: sp.MatrixBase, b: sp.MatrixBase) -> sp.Expr:
    """The z component of ``a x b`` for planar vectors.

    Examples
    --------
    >>> cross(sp.Matrix([2, 0]), sp.Matrix([1, 3]))
    6
    """
    return a[0] * b[1] - a[1] * b[0]


def perp(r: sp.MatrixBase) -> sp.ImmutableMatrix:
    """``z_hat x r``: `r` turned by +90 degrees.

    Examples
    --------
    >>> perp(sp.Matrix([1, 2])).T
    Matrix([[-2, 1]])
    """
    return sp.ImmutableMatrix([-r[1], r[0]])


def spin_cross(omega: sp.Expr, r: sp.MatrixBase) -> sp.ImmutableMatrix:
    """``omega z_hat x r`` in the plane: the velocity that turning at `omega` gives the
    point at `r` from the axis.

    Examples
    --------
    >>> spin_cross(2, sp.Matrix([0, -1])).T
    Matrix([[2, 0]])
    """
    return sp.ImmutableMatrix([-omega * r[1], omega * r[0]])


def frame_of(unit_normal: sp.MatrixBase) -> sp.ImmutableMatrix:
    """The rotation taking scene coordinates to contact coordinates: its rows are the
    unit normal and the unit tangent (the normal turned by +90 degrees).

    Examples
    --------
    >>> frame_of(sp.Matrix([1, 0])) == sp.eye(2)
    True
    """
    t = perp(unit_normal)
    return sp.ImmutableMatrix([[unit_normal[0], unit_normal[1]], [t[0], t[1]]])
