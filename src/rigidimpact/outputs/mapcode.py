"""The impact map of a sympy.physics.mechanics system as C: the speeds after from the
state before, for a controller (a walker's heel strike) or a loop over many states.

The map is the one :class:`~rigidimpact.mechanics.kernel.MapKernel` evaluates with
NumPy, every contact acting (smooth or sticking contacts under Newton's law):

    W P = -(1 + E) J u-,   u+ = u- + M^-1 J^T P,   W = J M^-1 J^T,

with the entries of M(q) and J(q) printed by SymPy's C printer (common subexpressions
shared) and the two small systems solved in C by Gaussian elimination with partial
pivoting. As in the kernel, a state where a contact would pull (a negative normal
impulse), the impact would create kinetic energy, or M or W is singular gets NaN
speeds: the function returns 0 there, 1 where the speeds are the impact's.

Examples
--------
>>> import sympy as sp, sympy.physics.mechanics as me
>>> from rigidimpact.mechanics import contact, impact
>>> q, u = me.dynamicsymbols("q u")
>>> N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
>>> A.orient_axis(N, N.z, q); A.set_ang_vel(N, u * N.z)
>>> O = me.Point("O"); O.set_vel(N, 0)
>>> bob = O.locatenew("bob", -A.y); _ = bob.v2pt_theory(O, N, A)
>>> kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
>>> _ = kane.kanes_equations([me.Particle("P", bob, 3)], [])
>>> text = impact_map_code(impact(kane, [contact(bob, N.x, restitution=sp.Rational(1, 2))],
...                                   frame=N))
>>> print(text[text.index("int impact_map("):].splitlines()[0])
int impact_map(const double *q, const double *u, double *after) {
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.printing.c import C99CodePrinter

from rigidimpact.mechanics.kernel import SINGULAR, TOLERANCE, map_rows

__all__ = ["impact_map_code", "map_matrices"]


def map_matrices(system: Any, values: dict | None = None) -> tuple[sp.Matrix, sp.Matrix,
                                                                    list[float], list[int]]:
    """M(q) and the contact rows J(q) of a SystemImpact with numbers put in, each row's
    restitution and which rows are normal rows: what the kernel's map is made of (its
    one assembly, :func:`~rigidimpact.mechanics.kernel.map_rows`)."""
    M, J, _, normal, restitution = map_rows(system, values)
    return M, J, [float(e) for e in restitution], normal


def impact_map_code(system: Any, values: dict | None = None, name: str = "impact_map") -> str:
    """C source of the impact map of a :class:`~rigidimpact.mechanics.impact.SystemImpact`
    (`values`: its constants, as for ``kernel``): ``int NAME(q, u, after)`` for one
    state and ``long NAME_many(count, q, u, after)`` over `count` states stored row by
    row, returning how many states are the impact's."""
    M, J, restitution, normal = map_matrices(system, values)
    n, k = M.shape[0], J.shape[0]
    q = list(system.q)
    plain = [sp.Symbol(f"q_{i}") for i in range(len(q))]
    swap = dict(zip(q, plain, strict=True))
    flat = [x.xreplace(swap) for x in (*M, *J)]
    temps, reduced = sp.cse(flat, symbols=sp.numbered_symbols("cse"), order="none")
    printer = C99CodePrinter({"strict": True})
    unpack = [f"    const double q_{i} = q[{i}];" for i in range(len(q))]
    shared = [f"    const double {t} = {printer.doprint(x)};" for t, x in temps]
    entries = [f"    M[{i}] = {printer.doprint(x)};" for i, x in enumerate(reduced[:n * n])]
    entries += [f"    J[{i}] = {printer.doprint(x)};" for i, x in enumerate(reduced[n * n:])]
    e = ", ".join(repr(x) for x in restitution)
    normals = ", ".join(str(i) for i in normal)
    speeds = ", ".join(f'"{s}"' for s in map(str, system.u))
    return f"""/*
 * The impact map of a sympy.physics.mechanics system, every contact acting: the speeds
 * after ({speeds}) from the coordinates q and the speeds before, written by rigidimpact
 * (rigidimpact.outputs.mapcode.impact_map_code) with SymPy's C printer.
 *   W P = -(1 + E) J u,   after = u + M^-1 J^T P,   W = J M^-1 J^T
 * Build: gcc -O2 -shared -fPIC -o {name}.so {name}.c -lm  (or link it into a program)
 * NAME returns 1 where the speeds are the impact's; 0 (and NaN speeds) where a contact
 * would pull, kinetic energy would be created, or M or W is singular.
 */
#include <math.h>
#include <string.h>

#define N_SPEEDS {n}
#define N_ROWS {k}
static const double restitution[N_ROWS] = {{{e}}};
static const int normal_rows[] = {{{normals}}};

/* solve A X = B in place (A: size x size, B: size x columns, row by row) by Gaussian
 * elimination with partial pivoting; 0 where A is singular to `tiny` of its scale */
static int solve(int size, double *A, int columns, double *B, double tiny) {{
    for (int c = 0; c < size; c++) {{
        int p = c;
        for (int r = c + 1; r < size; r++) if (fabs(A[r * size + c]) > fabs(A[p * size + c])) p = r;
        if (!(fabs(A[p * size + c]) > tiny)) return 0;
        if (p != c) {{
            for (int j = 0; j < size; j++) {{
                double t = A[c * size + j];
                A[c * size + j] = A[p * size + j];
                A[p * size + j] = t;
            }}
            for (int j = 0; j < columns; j++) {{
                double t = B[c * columns + j];
                B[c * columns + j] = B[p * columns + j];
                B[p * columns + j] = t;
            }}
        }}
        for (int r = c + 1; r < size; r++) {{
            const double f = A[r * size + c] / A[c * size + c];
            for (int j = c; j < size; j++) A[r * size + j] -= f * A[c * size + j];
            for (int j = 0; j < columns; j++) B[r * columns + j] -= f * B[c * columns + j];
        }}
    }}
    for (int c = size - 1; c >= 0; c--)
        for (int j = 0; j < columns; j++) {{
            double s = B[c * columns + j];
            for (int r = c + 1; r < size; r++) s -= A[c * size + r] * B[r * columns + j];
            B[c * columns + j] = s / A[c * size + c];
        }}
    return 1;
}}

int {name}(const double *q, const double *u, double *after) {{
    double M[N_SPEEDS * N_SPEEDS], J[N_ROWS * N_SPEEDS];
{chr(10).join(unpack + shared + entries)}
    double Mc[N_SPEEDS * N_SPEEDS], A[N_SPEEDS * N_ROWS], W[N_ROWS * N_ROWS], P[N_ROWS];
    double scale = 0.0;
    memcpy(Mc, M, sizeof M);
    for (int i = 0; i < N_SPEEDS * N_SPEEDS; i++) scale = fmax(scale, fabs(M[i]));
    for (int i = 0; i < N_SPEEDS; i++)
        for (int r = 0; r < N_ROWS; r++) A[i * N_ROWS + r] = J[r * N_SPEEDS + i];
    int ok = solve(N_SPEEDS, Mc, N_ROWS, A, 1e-300 + 1e-14 * scale);  /* A = M^-1 J^T */
    double diagonal = 1.0;
    for (int r = 0; r < N_ROWS && ok; r++) {{
        double before = 0.0;
        for (int i = 0; i < N_SPEEDS; i++) before += J[r * N_SPEEDS + i] * u[i];
        P[r] = -(1.0 + restitution[r]) * before;
        for (int c = 0; c < N_ROWS; c++) {{
            double s = 0.0;
            for (int i = 0; i < N_SPEEDS; i++) s += J[r * N_SPEEDS + i] * A[i * N_ROWS + c];
            W[r * N_ROWS + c] = s;
        }}
        diagonal *= W[r * N_ROWS + r];
    }}
    double Wc[N_ROWS * N_ROWS];
    memcpy(Wc, W, sizeof W);
    ok = ok && solve(N_ROWS, Wc, 1, P, 1e-300);
    if (ok) {{  /* W's rows independent: det W above {SINGULAR!r} x its diagonal's product */
        double det = 1.0;
        for (int r = 0; r < N_ROWS; r++) det *= Wc[r * N_ROWS + r];
        ok = fabs(det) > {SINGULAR!r} * diagonal;
    }}
    double largest = 0.0;
    for (int r = 0; r < N_ROWS && ok; r++) largest = fmax(largest, fabs(P[r]));
    for (unsigned j = 0; j < sizeof normal_rows / sizeof normal_rows[0] && ok; j++)
        if (P[normal_rows[j]] < -{TOLERANCE!r} * largest) ok = 0;  /* a contact would pull */
    double energy = 0.0, energy_after = 0.0;
    for (int i = 0; i < N_SPEEDS && ok; i++) {{
        double s = u[i];
        for (int r = 0; r < N_ROWS; r++) s += A[i * N_ROWS + r] * P[r];
        after[i] = s;
    }}
    for (int i = 0; i < N_SPEEDS && ok; i++)
        for (int j = 0; j < N_SPEEDS; j++) {{
            energy += u[i] * M[i * N_SPEEDS + j] * u[j];
            energy_after += after[i] * M[i * N_SPEEDS + j] * after[j];
        }}
    if (ok && energy_after > energy * (1.0 + {TOLERANCE!r})) ok = 0;  /* energy created */
    if (!ok) for (int i = 0; i < N_SPEEDS; i++) after[i] = NAN;
    return ok;
}}

long {name}_many(long count, const double *q, const double *u, double *after) {{
    long honoured = 0;
    for (long s = 0; s < count; s++)
        honoured += {name}(q + s * {len(q)}, u + s * N_SPEEDS, after + s * N_SPEEDS);
    return honoured;
}}
"""
