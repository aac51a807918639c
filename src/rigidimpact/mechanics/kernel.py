"""The impact map of a mechanics system as one NumPy kernel over many states.

Where every contact acts (each normal row ends at ``-e`` times its approach, each
sticking contact's tangent rows at zero), the map from the speeds before to the speeds
after is linear at each configuration q:

    W P = -(1 + E) J u-,   u+ = u- + M^-1 J^T P,   W = J M^-1 J^T,

with M(q) the mass matrix and J(q) the contact rows. This module evaluates M and J for a
whole array of states at once (one expression tree, its common parts computed once) and
solves the small systems in one batched call, so that a state costs microseconds. It is
the map a robotics library's impulse dynamics computes (Pinocchio's
``impulseDynamics``); it does not ask which contacts act. So each state is checked: where
a contact would pull (a negative normal impulse) or the impact would create kinetic
energy, the map is not the impact; where the contacts' rows depend on each other (W
singular) the impulses are not fixed; the speeds after there are NaN, counted in the
result's warnings (``SystemImpact.solve()`` finds which contacts act at such a state).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy as sp
import sympy.physics.mechanics as me

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.symbolic.given import given_values, shown

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["MapKernel", "MapNumbers"]

# relative to the state's own scale: a normal impulse below -TOLERANCE x its largest
# impulse pulls; kinetic energy above (1 + TOLERANCE) x before is created
TOLERANCE = 1e-9
# W's rows depend on each other where det W < SINGULAR x the product of its diagonal
SINGULAR = 1e-10


@dataclass(frozen=True)
class MapNumbers:
    """The map at N states: `speeds_after` (N, speeds), NaN where the map is not the
    impact; `impulses` (N, rows); `honoured` (N,) where every contact pushes and no
    energy is created; `warnings` say how many states fail and why."""

    speeds_after: Any
    impulses: Any
    honoured: Any
    warnings: tuple[str, ...]


@dataclass(frozen=True)
class MapKernel:
    """The impact map, every contact acting, compiled for arrays of states; see the
    module's text. Call it with q (N, len(q)) and u (N, len(u)), or one state each.

    `rows` names the contact rows (``tip.n``, ``heel.t``), `speeds` the speeds."""

    speeds: tuple[str, ...]
    rows: tuple[str, ...]
    normal: tuple[int, ...]  # which rows are normal rows
    restitution: tuple[float, ...]  # e of each row's contact; 0 for a tangent row
    entries: Any  # f(*q) -> the entries of M (row by row), then of J (NumPy)
    coordinates: int = 0  # how many q a state has

    @classmethod
    def of(cls, system: Any, values: dict | None = None) -> MapKernel:
        """The kernel of a :class:`~rigidimpact.mechanics.impact.SystemImpact`; see its
        ``kernel``."""
        M, J, names, normal, restitution = map_rows(system, values)
        return cls.build(system.q, system.u, M, J, names, normal, restitution)

    @classmethod
    def build(cls, q: Sequence[Any], u: Sequence[Any], M: sp.MatrixBase,
              J: sp.MatrixBase, rows: Sequence[str], normal: Sequence[int],
              restitution: Sequence[float]) -> MapKernel:
        """The kernel of M(q) and J(q), whose only symbols are q's (numbers put in)."""
        stand_ins = [sp.Dummy(f"q{k}") for k in range(len(q))]
        swap = dict(zip(q, stand_ins, strict=True))
        flat = [x.xreplace(swap) for x in (*M, *J)]
        entries = sp.lambdify(stand_ins, flat, "numpy", cse=True)
        return cls(tuple(str(s) for s in u), tuple(rows), tuple(normal),
                   tuple(float(e) for e in restitution), entries, len(q))

    def __call__(self, q: Any, u: Any) -> MapNumbers:
        n, k = len(self.speeds), len(self.rows)
        q, u = _states("q", q, self.coordinates), _states("u", u, n)
        if q.shape[0] != u.shape[0]:
            raise InputError("u", f"must have a row for each state of q: q has {q.shape[0]}"
                             f" states, u {u.shape[0]}")
        states = q.shape[0]
        values = [np.broadcast_to(np.asarray(x, dtype=float), (states,))
                  for x in self.entries(*q.T)]
        table = np.stack(values, axis=1)
        M = table[:, :n * n].reshape(states, n, n)
        J = table[:, n * n:].reshape(states, k, n)
        before = (J @ u[..., None])[..., 0]
        e = np.asarray(self.restitution)
        right = (-(1 + e) * before)[..., None]
        try:
            A = np.linalg.solve(M, np.swapaxes(J, 1, 2))  # M^-1 J^T
            W = J @ A
            P = np.linalg.solve(W, right)[..., 0]
        except np.linalg.LinAlgError:  # singular somewhere: state by state, NaN there
            A, P = _one_by_one(M, J, right)
            W = J @ np.nan_to_num(A)
        after = u + (A @ P[..., None])[..., 0]
        # W is symmetric positive semidefinite: det W / (the product of its diagonal),
        # in [0, 1], is near 0 where its rows depend on each other (rounding keeps a
        # singular W from being exactly so, and its impulses are then not fixed)
        diagonal = np.prod(np.diagonal(W, axis1=1, axis2=2), axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            independent = np.linalg.det(W) > SINGULAR * diagonal
        singular = ~(np.isfinite(P).all(axis=1) & independent)
        scale = np.abs(P).max(axis=1, initial=0.0)
        pulls = (P[:, list(self.normal)] < -TOLERANCE * scale[:, None]).any(axis=1)
        energy = np.einsum("si,sij,sj->s", u, M, u)
        gains = np.einsum("si,sij,sj->s", after, M, after) > energy * (1 + TOLERANCE)
        honoured = ~(pulls | gains | singular) & np.isfinite(after).all(axis=1)
        warnings = []
        if singular.any():
            warnings.append(f"at {int(singular.sum())} of {states} states M or W = J M^-1 "
                            "J^T is singular (the contacts' rows depend on each other): "
                            "the impulses are not fixed there; solve() takes such a state")
        if pulls.any():
            warnings.append(f"at {int(pulls.sum())} of {states} states a contact would "
                            "pull (a negative normal impulse): every contact acting is "
                            "not the impact there; solve() finds which act")
        if gains.any():
            warnings.append(f"at {int(gains.sum())} of {states} states the map creates "
                            "kinetic energy")
        return MapNumbers(np.where(honoured[:, None], after, np.nan), P, honoured,
                          tuple(warnings))


def _states(name: str, value: Any, width: int) -> np.ndarray:
    """`value` as an array of states (N, width), one state (width,) as one row, or
    InputError naming it: another shape, text, complex numbers or objects."""
    array = np.asarray(value)
    if array.dtype.kind not in "iuf":
        raise InputError(name, f"must be real numbers, an array (states, {width}), not "
                         f"{type(value).__name__} {shown(value, 40)}")
    array = np.atleast_2d(array.astype(float, copy=False))
    if array.ndim != 2 or array.shape[1] != width:
        raise InputError(name, f"must be an array (states, {width}) or one state of "
                         f"{width}, not one of shape {np.shape(value)}")
    with np.errstate(over="ignore", invalid="ignore"):  # one pass: a sum of huge finite
        total = array.sum()  # numbers may overflow, then each state is looked at
    if not np.isfinite(total):  # the state named only where one is bad
        bad = np.flatnonzero(~np.isfinite(array).all(axis=1))
        if bad.size:
            raise InputError(name, f"must be finite: state {int(bad[0])} holds NaN or an "
                             "infinity")
    return array


def _one_by_one(M: Any, J: Any, right: Any) -> tuple[Any, Any]:
    """M^-1 J^T and the impulses state by state, NaN where M or W is singular."""
    states, n, k = J.shape[0], J.shape[2], J.shape[1]
    A, P = np.full((states, n, k), np.nan), np.full((states, k), np.nan)
    for s in range(states):
        try:
            A[s] = np.linalg.solve(M[s], J[s].T)
            P[s] = np.linalg.solve(J[s] @ A[s], right[s])[:, 0]
        except np.linalg.LinAlgError:
            continue
    return A, P


def map_rows(system: Any, values: dict | None = None
             ) -> tuple[sp.Matrix, sp.Matrix, list[str], list[int], list[Any]]:
    """What an impact map of every contact acting is made of: M(q) and the contact rows
    J(q) with numbers put in for the constants (`values`), each row's name, which rows
    are normal rows, and each row's restitution (the law's own target, v+ = -e v-; 0 for
    a tangent row). Each contact's laws are asked, not named: a law at the velocity
    level, linear in the closing speed, with a tangential law of linear conditions
    (smooth: a normal row; sticking: its tangent rows too); the rest is refused in one
    line (``solve()`` takes it). The one assembly of the NumPy kernel and its C
    export."""
    if system.fold is not None:
        raise InputError("system", "the impact map takes a system without dependent "
                         "speeds; solve() takes a nonholonomic one")
    put = given_values({} if values is None else values, signs=False)
    blocks: list[sp.MatrixBase] = []
    names: list[str] = []
    normal: list[int] = []
    restitution: list[Any] = []
    kinds: tuple[str, ...]
    for i, c in enumerate(system.contacts):
        first, second = c.laws.laws
        if first.together != "velocity" or second.solved_by_regimes:
            raise InputError(f"{c.name}.laws", "the impact map takes smooth or sticking "
                             "contacts under a restitution law at the velocity level, every "
                             "contact acting; solve() takes the rest")
        if not second.grips:
            block, kinds = system.J[2 * i:2 * i + 1, :], ("n",)
        elif system.J_plane is not None:
            block, kinds = system.J_plane[3 * i:3 * i + 3, :], ("n", "t1", "t2")
        else:
            block, kinds = system.J[2 * i:2 * i + 2, :], ("n", "t")
        # the law's own target, v+ = leaving(v-) = -k v- (a law at the velocity level is
        # linear in the closing speed: checked at two speeds)
        one, two = (sp.sympify(first.leaving(sp.Integer(x))).xreplace(put)
                    for x in (-1, -2))
        e = sp.nsimplify(one) if one.is_number else one
        if not e.is_number or not 0 <= e <= 1:
            raise InputError(f"{c.name}.restitution", "must be a number in [0, 1] "
                             f"(values may give it), not {e}")
        if sp.simplify(two - 2 * one) != 0:
            raise InputError(f"{c.name}.laws", "the impact map takes a restitution law "
                             "linear in the closing speed; solve() takes the rest")
        for k, kind in enumerate(kinds):
            normal += [len(names)] if kind == "n" else []
            names.append(f"{c.name}.{kind}")
            restitution.append(e if kind == "n" else 0)
            blocks.append(block.row(k))
    M, J = system.M.xreplace(put), sp.Matrix.vstack(*blocks).xreplace(put)
    time = me.dynamicsymbols._t
    left = (M.free_symbols | J.free_symbols) - set(system.q) - {time}
    left = {s for s in left if not any(s in qi.free_symbols for qi in system.q
                                       if not qi.is_Symbol)}
    if left:
        raise InputError("values", "the map needs a number for "
                         + ", ".join(sorted(map(str, left))))
    return M, J, names, normal, restitution
