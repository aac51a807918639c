"""The simultaneous rule with Coulomb friction in floating point: many contacts, 3-D
contacts (two tangents each), or numbers out of the rationals. The velocity-level
conditions of :func:`rigidimpact.solve.rules.simultaneous.simultaneous` are solved for
Coulomb's circular cone by a damped semismooth Newton method on Alart and Curnier's
function, or for its inscribed pyramid (``facets``) by Lemke's method; where one contact
acts alone, its own impact is the answer (:func:`one_acting`), as under every rule. The
answer comes back in 17-digit floats for the certificate to check at 50 digits.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.solve.coulomb import coulomb_newton, coulomb_residual, least_norm_rough
from rigidimpact.solve.lcp import NoSolution, lemke_float
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.rules.base import alone_outcome, own_step
from rigidimpact.solve.solution import Solution

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["frictional_newton", "frictional_pyramid", "float_problem", "one_acting",
           "STATE"]

# each contact's state at the velocity level, as its course says it
STATE = {"off": "released", "on": "acts", "stick": "sticks", "slide+": "slides",
         "slide-": "slides", "mixed": "differs between the solutions"}


def float_problem(problem: ImpulseRows, rows: sp.Matrix, v_n: sp.Matrix, v_t: sp.Matrix,
                  mu: Sequence[Any], target: Sequence[sp.Expr], tangential: Sequence[Any]
                  ) -> tuple[Any, Any, Any, np.ndarray, np.ndarray, np.ndarray]:
    """The frictional problem in float64: J (normal rows, then tangential) and M^-1 as
    SciPy sparse matrices, W, the velocities b before (normal ones less their targets,
    then the slips), each contact's cone (inf: it sticks; 0: smooth) and u before."""
    import scipy.sparse as sps

    n = len(problem.contacts)
    entries = rows.row_list()
    J = sps.csr_matrix(([float(x) for _, _, x in entries],
                        ([i for i, _, _ in entries], [j for _, j, _ in entries])),
                       shape=rows.shape)
    if problem.dense:
        Minv = sps.csr_matrix(np.array(problem.M_inverse.evalf(), dtype=float))
    else:
        Minv = sps.diags([float(x) for x in problem.inverse_inertia]).tocsr()
    W = (J @ Minv @ J.T).tocsr()
    b = np.array([float(v_n[i] - target[i]) for i in range(n)]
                 + [float(x) for x in v_t])
    cone = np.array([np.inf if m is None and law.grips else
                     0.0 if m is None or not law.grips else float(m)
                     for m, law in zip(mu, tangential, strict=True)])
    return J, Minv, W, b, cone, np.array([float(x) for x in problem.u_before])


def frictional_newton(problem: ImpulseRows, rows: sp.Matrix, v_n: sp.Matrix,
                      v_t: sp.Matrix, mu: Sequence[Any], target: Sequence[sp.Expr],
                      tangential: Sequence[Any]) -> Solution:
    """Many frictional contacts, or numbers out of the rationals (sqrt(3) in a hexagonal
    cluster): the same conditions as :func:`_frictional_lcp`, in floating point, by a
    damped semismooth Newton method on Alart and Curnier's function
    (:func:`rigidimpact.solve.coulomb.coulomb_newton`), one sparse factorisation a step. The
    answer is in floats with its residual in a note, and the certificate checks it at
    50 digits like every answer; where the method stops short it refuses in one line."""
    n = len(problem.contacts)
    if rows.free_symbols or problem.M_inverse.free_symbols or any(
            sp.sympify(x).free_symbols for x in (*v_n, *v_t, *target)):
        raise InputError("contacts", f"{n} frictional contacts acting together are "
                         "solved for numbers; these hold symbols")
    J, Minv, W, b, cone, u0 = float_problem(problem, rows, v_n, v_t, mu, target, tangential)
    try:
        lam, steps = coulomb_newton(W, b, cone)
    except NoSolution as exc:
        raise InputError("impact.rule", f"{n} frictional contacts acting together: {exc}, "
                         "so no answer is given; try the sequential rule") from None
    u = u0 + Minv @ (J.T @ lam)
    error = coulomb_residual(W, b, cone, lam)
    t = problem.tangents  # one tangent a contact in the plane, two in space
    slip = (J @ u)[n:].reshape(n, t)
    friction = lam[n:].reshape(n, t)
    big = max(1.0, float(np.abs(lam).max()))
    on = lam[:n] > 1e-12 * big
    with np.errstate(invalid="ignore"):  # a sticking law's cone is infinite
        reach = np.where(np.isfinite(cone), cone * lam[:n], np.inf)
    inside = np.linalg.norm(friction, axis=1) < reach - 1e-9 * big
    acting = [i for i in range(n) if on[i]]
    if len(acting) == 1 and tangential[acting[0]].solved_by_regimes:
        return one_acting(problem, acting[0], list(target))  # its own answer, any rule
    states = ["off" if not on[i] else "on" if not tangential[i].grips else
              "stick" if inside[i] or not np.isfinite(cone[i]) else
              "slide+" if slip[i, 0] > 0 else "slide-" for i in range(n)]

    shared = ""
    if not problem.dense:  # the least-norm impulses with this motion, if others fit it
        least = least_norm_rough(J, 1.0 / Minv.diagonal(), u - u0, lam, cone, slip.ravel())
        if least is not None and np.abs(least - lam).max() > 1e-9 * big:
            lam, shared = least, (
                "; other impulses give the same motion after (more contact conditions "
                "than the bodies' freedoms): shown are the least-norm ones with these "
                "contact states")
            u = u0 + Minv @ (J.T @ lam)
            error = max(error, coulomb_residual(W, b, cone, lam))

    note = (f"{n} frictional contacts: solved in floating point by a damped semismooth "
            f"Newton method on Alart and Curnier's function ({(1 + t) * n} unknowns, "
            f"{steps} steps{', the circular cone' if t == 2 else ''}), residual "
            f"{error:.1e} of the largest closing speed; it gives one answer, and with "
            "friction others may exist" + shared)
    return _in_floats(problem, u, lam, on, states, note, "newton")


def _in_floats(problem: ImpulseRows, u: np.ndarray, lam: np.ndarray, on: np.ndarray,
               states: Sequence[str], note: str, method: str) -> Solution:
    """The rule's outcome from impulses found in floating point (`lam`: the normal
    ones, then each contact's one or two tangential ones; `on`: which push), each
    number a 17-digit Float, for the certificate to check at 50 digits."""
    n, t = len(problem.contacts), problem.tangents

    def number(x: float) -> sp.Float:
        return sp.Float(float(x), 17)

    friction = lam[n:].reshape(n, t)
    normal = sp.Matrix([number(x) if on[i] else sp.Integer(0)
                        for i, x in enumerate(lam[:n])])
    along = sp.Matrix([number(friction[i, 0]) if on[i] else sp.Integer(0)
                       for i in range(n)])
    more: dict[str, Any] = {"tangent_impulses": {
        c.name: (along[i], number(friction[i, 1]) if on[i] else sp.Integer(0))
        for i, c in enumerate(problem.contacts)}} if t == 2 else {}
    return problem.outcome("simultaneous", (), sp.Matrix([number(x) for x in u]),
                           problem.named(normal), tuple(c.name for i, c in
                                                        enumerate(problem.contacts)
                                                        if on[i]),
                           tangential=problem.named(along),
                           courses=tuple(f"{c.name}: {STATE[s]}" for c, s in
                                         zip(problem.contacts, states, strict=True)),
                           notes=(note,), method=method, **more)


def frictional_pyramid(problem: ImpulseRows, rows: sp.Matrix, v_n: sp.Matrix,
                       v_t: sp.Matrix, mu: Sequence[Any], target: Sequence[sp.Expr],
                       tangential: Sequence[Any]) -> Solution:
    """The same conditions as :func:`frictional_newton` with each contact's cone
    replaced by the inscribed pyramid of ``problem.facets`` edges ``d_j`` in its tangent
    plane (along t1, then every 360/facets degrees; one tangent has the two edges + and
    -): Stewart and Trinkle's formulation. Each contact's unknowns are its normal
    impulse p, an impulse p_j >= 0 along each edge and a slack s (the slip speed after
    as the pyramid sees it)::

        w_p = v_n+ - target >= 0     with p
        w_j = s + d_j . v_t+ >= 0    with p_j
        w_s = mu p - sum_j p_j >= 0  with s

    solved by Lemke's method in floating point; the certificate checks the answer as it
    checks every other. The pyramid is an accuracy choice: exact where the slip after is
    along an edge, otherwise its friction is short of the cone's by up to
    1 - cos(180/facets degrees)."""
    n, t, m = len(problem.contacts), problem.tangents, problem.facets or 2
    stuck = [c.name for c, law, c_mu in zip(problem.contacts, tangential, mu, strict=True)
             if c_mu is None and law.grips]
    if stuck:
        raise InputError(f"{stuck[0]}.tangential", "a sticking contact has no cone to make "
                         "a pyramid of: use coulomb with a friction coefficient, or no "
                         "facets")
    J, Minv, W, b, cone, u0 = float_problem(problem, rows, v_n, v_t, mu, target, tangential)
    W = W.toarray()
    if t == 1:
        D = np.array([[1.0], [-1.0]])
    else:
        angles = np.arange(m) * 2 * np.pi / m
        D = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        D[np.abs(D) < 1e-15] = 0.0
    e = len(D)  # edges a contact
    size = n * (e + 2)
    B = np.zeros((n + n * t, size))  # the impulse (normal ones, then tangential) = B z
    for i in range(n):
        B[i, i] = 1.0
        B[n + i * t:n + (i + 1) * t, n + i * e:n + (i + 1) * e] = D.T
    WB = W @ B
    M, q = np.zeros((size, size)), np.zeros(size)
    for i in range(n):
        M[i], q[i] = WB[i], b[i]
        across = slice(n + i * t, n + (i + 1) * t)
        for j in range(e):
            r = n + i * e + j
            M[r] = D[j] @ WB[across]
            M[r, n + n * e + i] = 1.0
            q[r] = D[j] @ b[across]
        last = n + n * e + i
        M[last, i] = cone[i]
        M[last, n + i * e:n + (i + 1) * e] = -1.0
    z = lemke_float(M, q)
    if z is None:  # with friction the matrix is not copositive-plus: no proof of none
        raise InputError("impact.rule", f"Coulomb's cone as a pyramid of {m} edges: "
                         "Lemke's method ended on a ray, which with friction says neither "
                         "that an answer exists nor that none does; leave out facets (the "
                         "circular cone itself), or try the sequential rule")
    lam = B @ z
    u = u0 + Minv @ (J.T @ lam)
    big = max(1.0, float(np.abs(lam).max()), float(np.abs(u0).max()))
    on = lam[:n] > 1e-12 * big
    if on.sum() == 1 and tangential[int(np.argmax(on))].solved_by_regimes:
        return one_acting(problem, int(np.argmax(on)), list(target))  # its own answer
    slip = (J @ u)[n:].reshape(n, t)
    still = np.linalg.norm(slip, axis=1) <= 1e-9 * big
    states = ["off" if not on[i] else "on" if cone[i] == 0 else "stick" if still[i] else
              "slide+" if slip[i, 0] > 0 else "slide-" for i in range(n)]

    note = (f"{n} contacts act together (the simultaneous rule, Newton's law at the "
            f"velocity level), Coulomb's cone as a pyramid of {m} edges (an accuracy "
            "choice: exact where a slip is along an edge), solved by Lemke's method in "
            "floating point; it gives one answer, and with friction or more contacts than "
            "freedoms others may exist")
    return _in_floats(problem, u, lam, on, states, note, "pyramid")


def one_acting(problem: ImpulseRows, k: int, target: list[sp.Expr]) -> Solution:
    """Only contact k acts: its frictional impact alone by Routh's method (the answer
    for one contact under every rule), if that leaves every other contact opening
    at least as fast as its law asks; otherwise one line saying so."""
    P, course, u, _, _ = own_step(problem, k, problem.u_before)
    after = problem.closings(u)
    blocked = [t.name for i, t in enumerate(problem.contacts)
               if i != k and after[i] < target[i]]
    name = problem.contacts[k].name
    if blocked:
        raise InputError("impact.rule", f"only {name} acts at the velocity level, but "
                         f"its exact (Routh) impulse leaves {', '.join(blocked)} "
                         "closing: the simultaneous rule has no consistent answer here; "
                         "try the sequential rule")
    return alone_outcome(problem, k, "simultaneous", P, course, u, courses=tuple(
        f"{t.name}: {course}" if i == k else f"{t.name}: {STATE['off']}"
        for i, t in enumerate(problem.contacts)))
