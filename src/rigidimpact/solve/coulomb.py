"""Coulomb friction at many contacts acting together, in floating point: the
simultaneous rule's conditions (Newton's law at the velocity level, each contact's
friction inside its cone with no slip after, or on the cone's edge against the slip)
as Alart and Curnier's function, solved by a damped semismooth Newton method, one
sparse factorisation a step (:func:`coulomb_newton`); in the plane the cone is an
interval, in space a disc. Its answer's residual (:func:`coulomb_residual`), and where
other impulses give the same motion, the least-norm ones (:func:`least_norm_rough`).

The exact methods of :mod:`rigidimpact.solve.lcp` (Lemke's tableau, confirmation in
the rationals) take a rough set where its numbers are rational and it is small enough;
this module takes the rest, and gives them their first guess.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rigidimpact.lazy import deferred
from rigidimpact.solve.lcp import NoSolution, pivoting, proximal

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["coulomb_newton", "coulomb_residual", "least_norm_rough", "START_ROUNDS"]


def _bound(mu: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The cone's radius mu P_n (infinite for a pushing contact that sticks, zero for a
    released one)."""
    with np.errstate(invalid="ignore"):
        return np.where(normal > 0, mu * normal, 0.0)


def _disc(sigma: np.ndarray, radius: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each contact's row of `sigma` (its tangential components) projected on the disc
    (in the plane: the interval) of its `radius`, and each row's length."""
    size = np.sqrt((sigma ** 2).sum(axis=1))
    with np.errstate(invalid="ignore", divide="ignore"):
        shrink = np.where(size > radius, radius / np.where(size > 0, size, 1.0), 1.0)
    return sigma * shrink[:, None], size


def _alart_curnier(W: Any, b: np.ndarray, mu: np.ndarray, rho: np.ndarray,
                   lam: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Alart and Curnier's function of the impulses (n normal parts, then each
    contact's tangential components in turn), zero exactly where they solve the
    frictional problem, with the two projections' arguments (the tangential ones one
    row a contact) and the projected normal impulses."""
    n = len(mu)
    g = b + W @ lam
    sn = lam[:n] - rho[:n] * g[:n]
    normal = np.maximum(sn, 0.0)
    st = (lam[n:] - rho[n:] * g[n:]).reshape(n, -1)
    projected, _ = _disc(st, _bound(mu, normal))
    return (np.concatenate([lam[:n] - normal, lam[n:] - projected.ravel()]), sn, st,
            normal)


def coulomb_residual(W: Any, b: np.ndarray, mu: np.ndarray, lam: np.ndarray) -> float:
    """The largest violation of the frictional problem's conditions at the impulses
    `lam` (see :func:`coulomb_newton`), relative to the largest closing speed: a push,
    a normal velocity below its target, the normal complementarity, the cone, a slip
    inside it and a friction not on the cone's edge against the slip."""
    n = len(mu)
    g = b + W @ lam
    ln, gn = lam[:n], g[:n]
    lt, gt = lam[n:].reshape(n, -1), g[n:].reshape(n, -1)
    big = max(1.0, float(np.abs(lam).max()))
    scale = max(float(np.abs(b).max()), 1e-300)
    friction, slip = np.sqrt((lt ** 2).sum(axis=1)), np.sqrt((gt ** 2).sum(axis=1))
    with np.errstate(invalid="ignore"):
        room = np.where(np.isfinite(mu), mu * ln - friction, np.inf)
    inside = room > 1e-9 * big
    sliding = ~inside & (slip > 1e-9 * scale) & np.isfinite(mu)
    against = lt + (np.where(sliding, np.where(np.isfinite(mu), mu, 0.0) * ln, 0.0)
                    / np.where(slip > 0, slip, 1.0)
                    )[:, None] * gt
    worst = max(0.0, -float(ln.min()), -float(gn.min()), float(np.abs(ln * gn).max()),
                -float(room.min()), float(np.where(inside, slip, 0.0).max()),
                float(np.abs(np.where(sliding[:, None], against, 0.0)).max()))
    return worst / scale


START_ROUNDS = 100  # the proximal point method's rounds for a start (not an answer)


def _smooth_start(W: Any, q: np.ndarray) -> np.ndarray:
    """The normal impulses of the smooth problem (every mu zero), the first stage's
    start: block principal pivoting, or where W is singular a few rounds of the proximal
    point method (a start need not be the answer); zeros where neither ends."""
    from scipy.sparse.linalg import splu

    W = W.tocsc()
    try:
        pivots = np.abs(splu(W, permc_spec="MMD_AT_PLUS_A").U.diagonal())
        singular = bool(pivots.min() < 1e-11 * pivots.max())
    except RuntimeError:  # exactly singular
        singular = True
    try:
        if singular:
            return proximal(W, q, 1e-2 * float(W.diagonal().max()), max_rounds=START_ROUNDS)[0]
        return pivoting(W, q)[0]
    except (NoSolution, RuntimeError):
        return np.zeros(len(q))


def coulomb_newton(W: Any, b: np.ndarray, mu: np.ndarray, stages: int = 4,
                   tolerance: float = 1e-14, max_steps: int = 400,
                   passing: float = 1e-6, accepted: float = 1e-11
                   ) -> tuple[np.ndarray, int]:
    """Coulomb friction at many contacts acting together, in floating point: impulses
    ``lam`` (n normal parts, then each contact's tangential components in turn: one in
    the plane, two in space) with velocities ``g = b + W lam`` (normal ones less their
    targets, then the slips) such that every normal impulse pushes, its normal velocity
    is at least its target and one of the two is zero, and every tangential impulse is
    inside the circular cone ``|lam_t| <= mu lam_n`` with no slip, or on its edge
    against the slip (in space, pointing straight against it). ``mu`` may be ``inf`` (a
    contact that sticks) or 0 (a smooth one).

    The conditions are Alart and Curnier's function ``Phi(lam) = 0`` (Alart and Curnier,
    Comput. Methods Appl. Mech. Eng. 92, 1991, the form Siconos solves), found by a
    semismooth Newton method whose steps are damped as Levenberg and Marquardt's: each
    solves ``(G + eps E) d = -Phi`` with G the function's generalized Jacobian and E
    the proximal term, one sparse factorisation a step; eps falls after a full step
    and grows after a failed line search. A singular W (more contact conditions than the
    bodies' freedoms) is what the damping is for; the impulses are then not unique, and
    it ends at one set of them, reached from zero (not the least-norm one). With
    friction the function has stationary points that are not solutions; the cone is
    opened in `stages` (mu times 0, 1/stages, ..., 1), each stage from the last's
    impulses, which here leads past them (a stage before the last ends at the residual
    `passing`: it is only a start). The last stage runs to `tolerance` (relative to the
    largest ``|b|``) or its steps' end. Returns
    ``(lam, steps)``; raises :class:`NoSolution` if it ends above `accepted`."""
    import scipy.sparse as sps
    from scipy.sparse.linalg import splu

    n = len(mu)
    W = sps.csr_matrix(W)
    d = (len(b) - n) // n if n else 1  # tangential components a contact: 1 or 2
    if not n or (b[:n] >= 0).all() and not np.abs(b[n:]).any():
        return np.zeros(len(b)), 0
    diagonal = W.diagonal()
    rho = 1.0 / np.maximum(diagonal, 1e-300 * max(1.0, float(diagonal.max())))
    rn, rt = rho[:n], rho[n:]
    Wn, Wt = W[:n], W[n:]
    size = n + n * d
    En = sps.eye(n, size, format="csr")
    Et = sps.eye(n * d, size, k=n, format="csr")
    scale = max(float(np.abs(b).max()), 1e-300)
    top = float(diagonal.max())
    lam = np.zeros(size)
    lam[:n] = _smooth_start(W[:n][:, :n], b[:n])
    finite = np.isfinite(mu)
    # each contact's d x d block, row by row: the (row, column) of its entries
    block_rows = np.repeat(np.arange(n * d), d)
    block_columns = (np.arange(n * d).reshape(n, d)[:, None, :]
                     .repeat(d, axis=1).reshape(-1))

    def descend(cone: np.ndarray, lam: np.ndarray, enough: float, limit: int
                ) -> tuple[np.ndarray, float, int]:
        """Damped Newton steps on the problem of the cone `cone` from `lam`, until the
        residual is below `enough`, the damping stalls or `limit` steps are taken."""
        Phi, sn, st, normal = _alart_curnier(W, b, cone, rho, lam)
        merit, eps, steps = float(Phi @ Phi), 1e-2 * top, 0
        for _ in range(limit):
            if np.sqrt(merit) < enough or eps > 1e8 * top:
                break
            steps += 1
            closed = sn > 0
            radius = _bound(cone, normal)
            length = np.sqrt((st ** 2).sum(axis=1))
            stick = length <= radius
            slip = ~stick
            damped_n, damped_t = Wn + eps * En, Wt + eps * Et
            Gn = sps.diags(np.where(closed, rn, 0.0)) @ damped_n + sps.diags(
                (~closed).astype(float)) @ En
            grows = sps.diags(closed.astype(float)) @ (En - sps.diags(rn) @ damped_n)
            # outside the disc the projection is radius sigma/|sigma|: its derivative
            # is radius/|sigma| (I - s s^T) in sigma (zero in the plane) and s in radius
            with np.errstate(invalid="ignore", divide="ignore"):
                unit = st / np.where(length > 0, length, 1.0)[:, None]
                ratio = np.where(slip & (length > 0), radius / np.where(
                    length > 0, length, 1.0), 0.0)
            ratio = np.where(np.isfinite(ratio), ratio, 0.0)
            blocks = ratio[:, None, None] * (np.eye(d)[None] - unit[:, :, None]
                                             * unit[:, None, :])
            turn = sps.csr_matrix((blocks.reshape(-1), (block_rows, block_columns)),
                                  shape=(n * d, n * d))
            along = np.where((slip & finite & closed)[:, None],
                             unit * np.where(finite, cone, 0.0)[:, None], 0.0)
            lift = sps.csr_matrix((along.reshape(-1), (np.arange(n * d),
                                                       np.repeat(np.arange(n), d))),
                                  shape=(n * d, n))
            inside = np.repeat(stick, d)
            Gt = (sps.diags(np.where(inside, rt, 0.0)) @ damped_t
                  + sps.diags((~inside).astype(float)) @ Et
                  - turn @ sps.diags((~inside).astype(float)) @ (Et - sps.diags(rt)
                                                                 @ damped_t)
                  - lift @ grows)
            # a released contact's rows are the identity's: its step is -Phi there, and
            # only the others' block is factorised
            known = np.concatenate([~closed, np.repeat(~closed & slip, d)])
            step = np.where(known, -Phi, 0.0)
            rest = np.flatnonzero(~known)
            if len(rest):
                G = sps.vstack([Gn, Gt]).tocsr()
                block = G[rest]
                try:
                    step[rest] = splu(block[:, rest].tocsc()).solve(-Phi[rest] - block @ step)
                except RuntimeError:  # singular even damped: damp more
                    eps *= 8
                    continue
            scaled = 1.0
            for _ in range(8):  # a backtracking line search on |Phi|^2
                trial = _alart_curnier(W, b, cone, rho, lam + scaled * step)
                value = float(trial[0] @ trial[0])
                if value <= (1 - 1e-4 * scaled) * merit:
                    break
                scaled /= 2
            if value <= (1 - 1e-4 * scaled) * merit:
                lam = lam + scaled * step
                Phi, sn, st, normal = trial
                merit = value
                if scaled == 1.0:
                    eps = max(eps / 4, 1e-12 * top)
            else:
                eps *= 8
        return lam, merit, steps

    # the cone opened in stages, each from the last's impulses; a stage that stalls
    # short of its residual is approached again through the stage halfway to it
    fractions = [k / stages for k in range(stages + 1)]
    reached, used, merit = 0.0, 0, float("inf")
    while fractions:
        fraction = fractions[0]
        last = fraction == 1.0
        cone = np.where(finite, np.where(finite, mu, 0.0) * fraction, np.inf)  # inf * 0: nan
        enough = (tolerance if last else passing) * scale
        tried, merit, steps = descend(cone, lam, enough,
                                      max_steps if last else max_steps // 4)
        used += steps
        if np.sqrt(merit) < (accepted if last else passing) * scale or \
                fraction - reached < 1.0 / 64 or used > 4 * max_steps:
            lam, reached = tried, fraction
            fractions.pop(0)
        else:
            fractions.insert(0, (reached + fraction) / 2)
    if not np.sqrt(merit) < accepted * scale:
        raise NoSolution(f"the semismooth Newton method stopped at a residual of "
                         f"{np.sqrt(merit) / scale:.1e} after {used} steps")
    return lam, used


def least_norm_rough(J: Any, mass: np.ndarray, change: np.ndarray, lam: np.ndarray,
                     mu: np.ndarray, slip: np.ndarray) -> np.ndarray | None:
    """Of the impulses that give the same velocity `change` (``M du = J^T lam``, J's n
    normal rows then its n tangential ones, M diagonal: `mass`) with each contact in
    the state it has in `lam`, the least-norm ones, or None where they break a law.

    A released contact has none; a sliding one (its slip after not zero) has one, its
    normal impulse, with its friction on the cone's edge against the slip; a sticking
    one (no slip after) its normal and tangential impulses. The least-norm solution of
    that consistent linear system is LSMR's from zero (Fong and Saunders 2011), each
    sliding contact's column scaled so that its unknown's size is its impulse's; it is
    returned only if every normal impulse pushes and every sticking one stays inside
    its cone, to 1e-12 of the largest impulse, and it gives `change` to 1e-12."""
    import scipy.sparse as sps
    from scipy.sparse.linalg import lsmr

    n = len(mu)
    J = sps.csr_matrix(J)
    big = max(1.0, float(np.abs(lam).max()))
    still = np.abs(slip) <= 1e-12 * max(1.0, float(np.abs(slip).max()))
    columns, where = [], []
    for i in np.flatnonzero(lam[:n] > 1e-12 * big):
        if mu[i] == 0:  # smooth: its normal impulse only
            columns.append(J[i])
            where.append((i, 0.0, 1.0))
        elif still[i]:
            columns += [J[i], J[n + i]]
            where += [(i, 0.0, 1.0), (n + i, 0.0, 1.0)]
        else:  # sliding: friction on the cone's edge, P_t = side mu P_n
            side = float(np.sign(lam[n + i])) * float(mu[i])
            size = float(np.hypot(1.0, side))
            columns.append((J[i] + side * J[n + i]) / size)
            where.append((i, side, size))
    if not columns:
        return None
    A = sps.vstack(columns).T.tocsr()
    target = mass * change
    x = lsmr(A, target, atol=1e-16, btol=1e-16, maxiter=20 * A.shape[1])[0]
    if np.abs(A @ x - target).max() > 1e-12 * max(1.0, float(np.abs(target).max())):
        return None
    out = np.zeros(2 * n)
    for value, (k, side, size) in zip(x, where, strict=True):
        if k < n and side:  # a sliding contact's one unknown
            out[k], out[n + k] = value / size, side * value / size
        else:
            out[k] = value
    room = mu * out[:n] - np.abs(out[n:])
    tolerance = 1e-12 * big
    if (out[:n] < -tolerance).any() or (np.isfinite(mu) & (room < -tolerance)).any():
        return None
    return out
