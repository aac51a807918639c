"""Numbers from exact results: float64 NumPy kernels and mpmath at a chosen precision.

Before compiling, each expression is put in a form that float64 evaluates stably; the
rewrites and why each is there:

* one fraction, cancelled and factored (``tidy``): a difference of two nearly equal
  quotients, such as v_fx = v_ix - 2M V_x / m when m << M, becomes one numerator in
  which the cancellation, if any, is exact in the data;
* ``1 - e**2`` as ``(1 - e)(1 + e)`` (``factor``): 1 - e is exact in float64 for e
  near 1 (Sterbenz), 1 - e*e is not;
* ``1 - sin(x)**2`` back to ``cos(x)**2`` (and the reverse): the subtraction loses
  every digit near x = 90 degrees (or 0), the square does not;
* the kinetic energy lost from the work of the impulse (see ``Solution.energy_lost``),
  never as K_i - K_f, which cancels as e -> 1.

Examples
--------
>>> from rigidimpact.paper.problems import derive
>>> k = Kernel.from_expr(derive("barbell").results["V_x"])
>>> k.arguments
('M', 'e', 'm', 'theta', 'v_ix')
>>> float(k(M=1.0, e=1.0, m=2.0, theta=0.0, v_ix=1.0))
1.0
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import mpmath
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.symbolic.drawn import compiled
from rigidimpact.symbolic.given import given_number, shown
from rigidimpact.symbolic.rewrite import tidy

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["stable_form", "magnitude", "Kernel", "kernels", "evaluate", "Fused", "fused",
           "BACKENDS", "CHUNK", "has_numba"]


def _reverse_pythagoras(expr: sp.Expr) -> sp.Expr:
    """``a - a sin(x)^2 -> a cos(x)^2`` and ``a - a cos(x)^2 -> a sin(x)^2`` in any sum."""

    def fix(node: sp.Add) -> sp.Expr:
        squares = [p for p in node.atoms(sp.Pow)
                   if p.exp == 2 and isinstance(p.base, (sp.sin, sp.cos))]
        for power in sorted(squares, key=sp.default_sort_key):
            coeff = node.coeff(power)
            if coeff == 0 or coeff.has(power.base):
                continue
            rest = sp.expand(node - coeff * power)
            remainder = sp.expand(rest + coeff)
            if len(sp.Add.make_args(remainder)) < len(sp.Add.make_args(rest)):
                other = sp.cos if isinstance(power.base, sp.sin) else sp.sin
                return -coeff * other(power.base.args[0]) ** 2 + remainder
        return node

    return expr.replace(lambda n: isinstance(n, sp.Add), fix)


def stable_form(expr: sp.Expr) -> sp.Expr:
    """The expression rewritten for stable float64 evaluation (see the module notes).

    Examples
    --------
    >>> e = sp.Symbol("e", nonnegative=True)
    >>> stable_form(1 - e**2)
    (1 - e)*(e + 1)
    >>> x = sp.Symbol("x", real=True)
    >>> stable_form(3 - 3 * sp.sin(x)**2)
    3*cos(x)**2
    """
    return _reverse_pythagoras(tidy(expr))


def magnitude(expr: sp.Expr) -> sp.Expr:
    """The expression with every sum's terms replaced by their absolute values.

    Float64 evaluation of a sum errs by about one rounding of the sum of the terms'
    magnitudes, so ``magnitude(x) / |x|`` is the condition number that multiplies the
    rounding error; where nothing cancels, ``magnitude(x) == |x|``. For the paper's
    v_fx it is ``|v_ix| (m(1 + sin^2) + 2Me) / (2M + m(1 + sin^2))``.

    Examples
    --------
    >>> a, b = sp.symbols("a b", positive=True)
    >>> magnitude((a - b) / (a + b))  # a - b may cancel: its scale is a + b
    1
    >>> magnitude(a - 2 * b).subs({a: 2, b: 1})  # the value is 0, the scale 4
    4
    """
    def absolute_terms(node: sp.Basic) -> sp.Basic:
        return sp.Add(*(sp.Abs(t) for t in node.args), evaluate=False)

    numerator, denominator = sp.fraction(sp.factor(expr))
    numerator = numerator.replace(lambda n: isinstance(n, sp.Add), absolute_terms)
    return sp.Abs(numerator) / sp.Abs(denominator)


@dataclass(frozen=True)
class Kernel:
    """An exact expression compiled for float64 (vectorised) and for mpmath.

    Call it with keyword arguments (NumPy arrays broadcast); ``.mp(dps=50, **values)``
    evaluates the same stable form with mpmath at `dps` digits, and ``.reference``
    evaluates the *exact* expression with mpmath (for checking the float path).
    """

    expr: sp.Expr
    stable: sp.Expr
    arguments: tuple[str, ...]
    size: sp.Expr  # magnitude(expr): the scale float64 errors are measured against

    @classmethod
    def from_expr(cls, expr: sp.Expr) -> Kernel:
        if not isinstance(expr, sp.Basic):  # a Python number; text is refused, not parsed
            expr = given_number(expr, "expr")
        arguments = tuple(sorted(s.name for s in expr.free_symbols))
        return cls(expr, stable_form(expr), arguments, magnitude(expr))

    def _symbols(self, expr: sp.Expr) -> list[sp.Symbol]:
        by_name = {s.name: s for s in expr.free_symbols}
        return [by_name.get(n, sp.Symbol(n)) for n in self.arguments]

    @property
    def _float(self):
        return _compiled(self.stable, tuple(self._symbols(self.stable)), "numpy")

    def __call__(self, **values: Any) -> Any:
        arrays = [_real_array(n, values[n]) for n in self._given(values)]
        try:
            np.broadcast_shapes(*(a.shape for a in arrays))
        except ValueError:
            raise InputError("values", "the arrays do not broadcast together: " + ", ".join(
                f"{n} {a.shape}" for n, a in zip(self.arguments, arrays, strict=True))
            ) from None
        return self._float(*arrays)

    def mp(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """The stable form in mpmath at `dps` significant digits."""
        fn = _compiled(self.stable, tuple(self._symbols(self.stable)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(_mp_number(n, values[n]) for n in self._given(values)))

    def reference(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """The exact (unrewritten) expression at `dps` digits, inputs taken exactly."""
        fn = _compiled(self.expr, tuple(self._symbols(self.expr)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(_mp_number(n, values[n]) for n in self._given(values)))

    def scale(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """``magnitude`` of the exact expression at the inputs (see :func:`magnitude`)."""
        fn = _compiled(self.size, tuple(self._symbols(self.expr)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(_mp_number(n, values[n]) for n in self._given(values)))

    def _given(self, values: Mapping[str, Any]) -> tuple[str, ...]:
        """The arguments, in order, each given a value (or InputError naming those not)."""
        missing = [n for n in self.arguments if n not in values]
        if missing:
            raise InputError("values", f"the kernel needs a number for {', '.join(missing)}"
                             f" (its arguments: {', '.join(self.arguments)})")
        return self.arguments


def _real_array(name: str, value: Any) -> np.ndarray:
    """`value` as a float64 array, or InputError naming it: text, complex numbers and
    objects are refused (NumPy would parse a string of digits)."""
    array = np.asarray(value)
    if array.dtype.kind in "iuf":
        return array.astype(np.float64, copy=False)
    if array.dtype.kind == "O" and not any(isinstance(x, (str, bytes, bool))
                                           for x in array.flat):
        try:  # SymPy or mpmath numbers
            return array.astype(np.float64)
        except (TypeError, ValueError):
            pass
    raise InputError(name, "must be real numbers (a number or an array of them), not "
                     f"{type(value).__name__} {shown(value, 40)}")



def _mp_number(name: str, value: Any) -> Any:
    """`value` as an mpmath number taken exactly (an mpf kept), or InputError naming it:
    text is refused, not parsed."""
    if isinstance(value, mpmath.mpf):
        return value
    if isinstance(value, sp.Basic):
        number = given_number(value, name)
        if not number.is_number:
            raise InputError(name, f"must be a number, not {number}")
        return mpmath.mpf(number)
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer,
                                                         np.floating)):
        raise InputError(name, f"must be a real number, not {type(value).__name__} "
                         f"{value!r}")
    return mpmath.mpf(value)


_CACHE: dict[tuple, Any] = {}


def _compiled(expr: sp.Expr, symbols: tuple[sp.Symbol, ...], module: str):
    key = (expr, symbols, module)
    if key not in _CACHE:
        # the generated code sees only fresh dummies: a scene's symbol named like one of
        # its own names (mpf, sin, select) would otherwise shadow it
        dummies = [sp.Dummy(f"x{k}") for k in range(len(symbols))]
        safe = expr.xreplace(dict(zip(symbols, dummies, strict=True)))
        _CACHE[key] = sp.lambdify(dummies, safe, module)
    return _CACHE[key]


def kernels(results: Mapping[str, sp.Expr]) -> dict[str, Kernel]:
    """A kernel per result.

    Examples
    --------
    >>> from rigidimpact.paper.problems import derive
    >>> sorted(kernels(derive("discs").results))[:2]
    ['V_1fx', 'V_1fy']
    """
    return {key: Kernel.from_expr(expr) for key, expr in results.items()}


BACKENDS = ("numpy", "numba")


def has_numba() -> bool:
    """Whether the optional ``numba`` backend is installed."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True

# computed by NumPy's vectorised routines before the numba loop (which would call libm)
TRANSCENDENTAL = (sp.sin, sp.cos, sp.tan, sp.exp, sp.log, sp.asin, sp.acos, sp.atan,
                  sp.sinh, sp.cosh, sp.tanh)
CHUNK = 1 << 13  # parameter sets per pass: the temporaries of one pass stay in cache
NUMBA_CHUNK = 1 << 18  # per worker thread: the hand-over (slicing, dispatch) paid rarely


@dataclass(frozen=True)
class Fused:
    """All results of a derivation compiled together: one float64 kernel.

    The results are put in their stable forms (:func:`stable_form`, as for
    :class:`Kernel`) and their common subexpressions are computed once (``sympy.cse``): a
    sine shared by four results is taken once per parameter set. The work goes chunk by
    chunk (`chunk` sets at a time), so the temporaries stay in cache and the memory used
    beyond the results is bounded. The ``numpy`` backend runs whole-chunk array code; the
    ``numba`` backend (an optional extra) takes NumPy's vectorised sines (and other
    transcendental functions) for each chunk, does the rest in one compiled loop that
    releases the GIL, and spreads the chunks over the cores.

    Call it with keyword arguments (arrays broadcast): it returns ``{key: array}``.
    :meth:`sweep` evaluates over a grid (the product of 1-D ranges) without ever
    building the grid, writing into arrays you give (memory-mapped files, say).

    Examples
    --------
    >>> from rigidimpact.paper.problems import derive
    >>> kernel = fused(derive("barbell").results)
    >>> kernel.arguments
    ('L', 'M', 'e', 'm', 'theta', 'v_ix')
    >>> out = kernel(M=1.0, L=1.0, e=1.0, m=2.0, theta=np.zeros(3), v_ix=1.0)
    >>> out["V_x"].tolist()
    [1.0, 1.0, 1.0]
    """

    keys: tuple[str, ...]
    arguments: tuple[str, ...]
    stable: tuple[sp.Expr, ...]
    backend: str = "numpy"
    chunk: int = CHUNK

    def source(self, scalars: tuple[bool, ...] | None = None) -> str:
        """The generated Python source (`scalars`: which arguments are single numbers,
        for the numba loop)."""
        scalars = scalars or (False,) * len(self.arguments)
        return _fused_source(self.stable, self.arguments, self.backend, scalars)

    def _function(self, scalars: tuple[bool, ...]):
        scalars = scalars if self.backend == "numba" else (False,) * len(self.arguments)
        key = (self.stable, self.arguments, self.backend, scalars)
        if key not in _CACHE:
            function = _fused_function(self.source(scalars), self.backend)
            if self.backend == "numba":  # with the count of scratch arrays `pre` takes
                pre = function[0]
                function = (*function, pre.__code__.co_argcount - len(self.arguments))
            _CACHE[key] = function
        return _CACHE[key]

    def _run(self, inputs: list, outputs: list[np.ndarray]) -> None:
        """One chunk: `inputs` are 1-D arrays of the chunk's length or single floats."""
        scalars = tuple(not isinstance(a, np.ndarray) for a in inputs)
        function = self._function(scalars)
        if self.backend == "numba":
            pre, loop, spare = function
            size = outputs[0].shape[0]
            loop(*inputs, *pre(*inputs, *(s[:size] for s in _scratch(spare, size))),
                 *outputs)
            return
        for out, value in zip(outputs, function(*inputs), strict=True):
            out[...] = value

    def _chunks(self, total: int, work, progress) -> None:
        """``work(start, stop)`` over every chunk: in order (NumPy), or spread over the
        cores (numba: its loop releases the GIL, as do NumPy's functions)."""
        starts = range(0, total, self.chunk)
        if self.backend != "numba" or total <= self.chunk:
            for start in starts:
                stop = min(start + self.chunk, total)
                work(start, stop)
                if progress is not None:
                    progress(stop, total)
            return
        def job(start: int) -> int:
            stop = min(start + self.chunk, total)
            work(start, stop)
            return stop

        for stop in _pool().map(job, starts):  # in order, so the progress only grows
            if progress is not None:
                progress(stop, total)

    def __call__(self, progress=None, **values: Any) -> dict[str, np.ndarray]:
        """Every result over the broadcast inputs; `progress(done, total)` is called
        after each chunk when given."""
        flat, shape = self._inputs(values)
        outputs = {k: np.empty(shape) for k in self.keys}
        self._fill(flat, shape, outputs, progress)
        return outputs

    def into(self, outputs: Mapping[str, np.ndarray], progress=None, **values: Any) -> None:
        """Like calling the kernel, but writing into `outputs` (one C-contiguous float64
        array of the broadcast shape per key), so repeated evaluations reuse their memory
        instead of having the system hand out (and zero) fresh pages each time.

        Examples
        --------
        >>> from rigidimpact.paper.problems import derive
        >>> kernel = fused({"V_x": derive("barbell").results["V_x"]})
        >>> buffer = {"V_x": np.empty(2)}
        >>> kernel.into(buffer, M=1.0, L=1.0, e=1.0, m=2.0, theta=np.zeros(2), v_ix=1.0)
        >>> buffer["V_x"].tolist()
        [1.0, 1.0]
        """
        flat, shape = self._inputs(values)
        for key in self.keys:
            target = outputs.get(key)
            if not (isinstance(target, np.ndarray) and target.shape == shape
                    and target.dtype == np.float64 and target.flags.c_contiguous
                    and target.flags.writeable):
                raise InputError(f"outputs.{key}", "must be a writable C-contiguous float64 "
                                 f"array of shape {shape}")
        self._fill(flat, shape, outputs, progress)

    def _inputs(self, values: Mapping[str, Any]) -> tuple[list, tuple[int, ...]]:
        """The arguments broadcast together and flattened (single numbers kept single)."""
        missing = [n for n in self.arguments if n not in values]
        if missing:
            raise InputError(missing[0], "a value is needed for every argument")
        given = [np.asarray(values[n], dtype=np.float64) for n in self.arguments]
        try:
            shape = np.broadcast_shapes(*(a.shape for a in given)) if given else ()
        except ValueError:
            raise InputError("values", "the arrays do not broadcast together: "
                             + ", ".join(f"{n} {a.shape}" for n, a in
                                         zip(self.arguments, given, strict=True))) from None
        # a single number stays one: a float for the numba loop, a NumPy scalar for the
        # NumPy code (whose arithmetic, unlike Python's, obeys np.errstate)
        single = float if self.backend == "numba" else np.float64
        flat = [single(a.reshape(-1)[0]) if a.size == 1 else
                np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1) for a in given]
        return flat, shape

    def _fill(self, flat: list, shape: tuple[int, ...], outputs: Mapping[str, np.ndarray],
              progress) -> None:
        total = int(np.prod(shape))
        targets = [outputs[k].reshape(-1) for k in self.keys]

        def work(start: int, stop: int) -> None:
            self._run([a if not isinstance(a, np.ndarray) else a[start:stop] for a in flat],
                      [t[start:stop] for t in targets])

        self._chunks(total, work, progress)

    def sweep(self, grid: Mapping[str, np.ndarray], fixed: Mapping[str, float],
              outputs: Mapping[str, np.ndarray], progress=None) -> None:
        """Every result over the product of the 1-D ranges in `grid` (the last varies
        fastest), the other arguments `fixed`, written into `outputs` (flat arrays of the
        grid's size, one per key): only the chunks at work have their inputs in memory."""
        names = list(grid)
        axes = [np.asarray(grid[n], dtype=np.float64) for n in names]
        shape = tuple(len(a) for a in axes)
        total = int(np.prod(shape))
        targets = [np.asarray(outputs[k]) for k in self.keys]

        def work(start: int, stop: int) -> None:
            coordinates = np.unravel_index(np.arange(start, stop), shape)
            chunk = {n: a[c] for n, a, c in zip(names, axes, coordinates, strict=True)}
            inputs = [chunk[n] if n in chunk else float(fixed[n]) for n in self.arguments]
            self._run(inputs, [t[start:stop] for t in targets])

        self._chunks(total, work, progress)


_POOL: list = []
_LOCAL = threading.local()


def _scratch(count: int, size: int) -> list[np.ndarray]:
    """`count` arrays of at least `size` floats, kept by the calling thread: the sines of
    chunk after chunk go into the same (cached) memory."""
    kept: tuple[np.ndarray, ...] = getattr(_LOCAL, "arrays", ())
    if len(kept) < count or (count and kept[0].shape[0] < size):
        kept = _LOCAL.arrays = tuple(np.empty(size) for _ in range(count))
    return list(kept[:count])


def _pool():
    """Worker threads for the numba backend, one per core numba would use."""
    if not _POOL:
        from concurrent.futures import ThreadPoolExecutor

        import numba

        _POOL.append(ThreadPoolExecutor(max_workers=numba.get_num_threads()))
    return _POOL[0]


def fused(results: Mapping[str, sp.Expr], backend: str = "numpy",
          chunk: int | None = None) -> Fused:
    """One fused kernel for all of `results` (see :class:`Fused`); `chunk` defaults to
    the backend's (8192 sets for NumPy, 262144 per worker thread for numba).

    Raises
    ------
    InputError
        An unknown backend, or ``numba`` when it is not installed.
    """
    if backend not in BACKENDS:
        raise InputError("--backend", f"must be one of {', '.join(BACKENDS)}, got "
                         f"{backend!r}")
    if backend == "numba" and not has_numba():
        raise InputError("--backend", "numba is not installed: pip install -e '.[fast]'")
    chunk = chunk or (NUMBA_CHUNK if backend == "numba" else CHUNK)
    keys = tuple(results)
    exprs = tuple(stable_form(sp.sympify(results[k])) for k in keys)
    names = sorted({s.name for e in exprs for s in e.free_symbols})
    return Fused(keys, tuple(names), exprs, backend, chunk)


def _fused_source(stable: tuple[sp.Expr, ...], arguments: tuple[str, ...],
                  backend: str, scalars: tuple[bool, ...]) -> str:
    """Python source of the fused kernel: shared subexpressions first, then results."""
    from sympy.printing.numpy import NumPyPrinter
    from sympy.printing.pycode import PythonCodePrinter

    dummies = {s: sp.Symbol(f"a{arguments.index(s.name)}")
               for e in stable for s in e.free_symbols}
    exprs = [e.xreplace(dummies) for e in stable]
    args = [f"a{k}" for k in range(len(arguments))]
    found: list[sp.Expr] = []
    if backend == "numba":  # NumPy's vectorised sines first, then one compiled loop
        found = sorted({a for e in exprs for a in e.atoms(*TRANSCENDENTAL)
                        if not a.args[0].has(*TRANSCENDENTAL)}, key=sp.default_sort_key)
        exprs = [e.xreplace({a: sp.Symbol(f"f{k}") for k, a in enumerate(found)})
                 for e in exprs]
    shared, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("t"))
    numpy_printer = NumPyPrinter({"fully_qualified_modules": True})
    if backend == "numpy":
        lines = [f"def kernel({', '.join(args)}):"]
        lines += [f"    {t} = {numpy_printer.doprint(v)}" for t, v in shared]
        lines += [f"    return ({', '.join(numpy_printer.doprint(r) for r in reduced)},)"]
        return "\n".join(lines) + "\n"
    scalar_of = dict(zip(args, scalars, strict=True))
    loose = [all(scalar_of[s.name] for s in a.free_symbols) for a in found]
    printer = PythonCodePrinter({"fully_qualified_modules": True})
    outs = [f"out{k}" for k in range(len(exprs))]
    inputs = [a + "_" for a in args] + [f"f{k}_" for k in range(len(found))]
    # an array-valued function goes into scratch memory the caller keeps (s0, s1, ...)
    scratch = [f"s{k}" for k in range(loose.count(False))]
    spare = iter(scratch)
    values = [numpy_printer.doprint(a) for a in found]  # each a ufunc call: numpy.f(...)
    values = [v if single else v[:-1] + f", out={next(spare)})"
              for v, single in zip(values, loose, strict=True)]
    lines = [f"def pre({', '.join(args + scratch)}):",
             "    return (" + "".join(f"{v}, " for v in values) + ")",
             "", "",
             f"def kernel({', '.join(inputs + outs)}):",
             f"    for i in range({outs[0]}.shape[0]):"]
    lines += [f"        {a} = {a}_" + ("" if scalar else "[i]")
              for a, scalar in zip(args, scalars, strict=True)]
    lines += [f"        f{k} = f{k}_" + ("" if scalar else "[i]") for k, scalar in enumerate(loose)]
    lines += [f"        {t} = {printer.doprint(v)}" for t, v in shared]
    lines += [f"        out{k}[i] = {printer.doprint(r)}" for k, r in enumerate(reduced)]
    return "\n".join(lines) + "\n"


def _fused_function(source: str, backend: str):
    """Compile generated source (:func:`rigidimpact.symbolic.drawn.compiled`: our own
    printer's output from exact expressions, never text from a user's file)."""
    return compiled(source, backend)


FALLBACK_DIGITS = 40  # where float64 cannot hold a result or a step toward it
_FLOAT_MAX = sys.float_info.max
_FLOAT_TINY = sys.float_info.min


def _float_point(kernel: Kernel, args: Mapping[str, Any]) -> float | None:
    """The float64 kernel at one point, or None where float64 overflows, underflows or
    divides by zero on the way (the answer would be wrong, not merely inexact)."""
    try:
        with np.errstate(over="raise", under="raise", invalid="raise", divide="raise"):
            value = float(kernel(**{n: float(v) for n, v in args.items()}))
    except (OverflowError, FloatingPointError, ZeroDivisionError):
        return None
    return value if np.isfinite(value) else None


def _fused_point(results: Mapping[str, sp.Expr], values: Mapping[str, Any]) -> dict | None:
    """Every result at one point through one fused kernel, or None where float64
    overflows, underflows or divides by zero on the way (then each result is redone)."""
    key = ("point", tuple(results.items()))
    if key not in _CACHE:
        _CACHE[key] = fused(results)
    kernel = _CACHE[key]
    try:
        with np.errstate(over="raise", under="raise", invalid="raise", divide="raise"):
            found = kernel(**{n: float(values[n]) for n in kernel.arguments})
    except (OverflowError, FloatingPointError, ZeroDivisionError):
        return None
    numbers = {k: float(v) for k, v in found.items()}
    return numbers if all(np.isfinite(v) for v in numbers.values()) else None


def _mp_point(kernel: Kernel, key: str, args: Mapping[str, Any], dps: int) -> mpmath.mpf:
    """The stable form in mpmath; refuse a result that is undefined at these values."""
    with mpmath.workdps(dps + 10):
        exact = {n: mpmath.mpf(sp.N(v, dps + 10)) if isinstance(v, sp.Basic) else v
                 for n, v in args.items()}
    try:
        value = kernel.mp(dps, **exact)
    except (ZeroDivisionError, OverflowError, ValueError):
        value = mpmath.nan
    if not mpmath.isfinite(value):
        raise InputError(key, "undefined at these values (a division by zero or an "
                         "infinite result); the geometry or data are degenerate")
    return value


def _exact_number(key: str, expr: sp.Expr, dps: int | None) -> Any:
    """An exact number at `dps` digits (mpmath), or as float64 when it fits."""
    value = sp.N(expr, (dps or FALLBACK_DIGITS) + 10)
    if not value.is_real or not value.is_finite:
        raise InputError(key, "undefined at these values (a division by zero or an "
                         "infinite result); the geometry or data are degenerate")
    if dps:
        with mpmath.workdps(dps):
            return mpmath.mpf(value._to_mpmath(mpmath.mp.prec))
    precise = mpmath.mpf(value._to_mpmath(200))
    fits = precise == 0 or _FLOAT_TINY <= abs(precise) <= _FLOAT_MAX
    return float(precise) if fits else precise


def evaluate(results: Mapping[str, sp.Expr], values: Mapping[str, Any],
             dps: int | None = None) -> dict[str, Any]:
    """Evaluate every result at `values` (name -> number): float64, or mpmath at `dps`.

    The float64 path never returns NaN or an infinity: where float64 would overflow or
    underflow on the way, the result is computed with mpmath at 40 digits instead, and
    returned as a float when it fits in float64 (else as the mpmath number). A result
    that is undefined at the values raises :class:`InputError`. This is the unchecked
    core: :meth:`rigidimpact.paper.problems.Derivation.evaluate` checks the values first.

    Examples
    --------
    >>> from rigidimpact.paper.problems import derive
    >>> evaluate(derive("discs").results, {"V_1ix": 1.0, "V_2ix": 0.0, "V_1iy": 0.0,
    ...                                    "V_2iy": 0.0, "e": 1.0})["V_2fx"]
    1.0
    >>> big = {"V_1ix": sp.Integer(10)**100, "V_2ix": 0, "V_1iy": 0, "V_2iy": 0, "e": 1}
    >>> evaluate({"square": derive("discs").results["V_2fx"]**4}, big)["square"]
    mpf('1.0e+400')
    """
    out: dict[str, Any] = {}
    # a result with no symbols left is a number already: evaluated from its exact form
    # at the precision asked (its integers may be far past what float64 holds)
    constants = {key: expr for key, expr in results.items()
                 if isinstance(expr, sp.Basic) and not expr.free_symbols}
    for key, expr in constants.items():
        out[key] = _exact_number(key, expr, dps)
    order = list(results)
    results = {key: expr for key, expr in results.items() if key not in constants}
    if not dps and results:  # every result at once through the fused kernel, when
        together = _fused_point(results, values)  # float64 suffices
        if together is not None:
            out.update(together)
            results = {}
    for key, kernel in kernels(results).items():
        args = {n: values[n] for n in kernel.arguments}
        if dps:
            out[key] = _mp_point(kernel, key, args, dps)
            continue
        value = _float_point(kernel, args)
        if value is None:
            precise = _mp_point(kernel, key, args, FALLBACK_DIGITS)
            fits = precise == 0 or _FLOAT_TINY <= abs(precise) <= _FLOAT_MAX
            value = float(precise) if fits else precise
        out[key] = value
    return {key: out[key] for key in order}
