"""Random inputs and the distributions of the outputs they drive.

A symbol of a derivation may be given a distribution (``uniform``, ``normal``,
``lognormal`` or ``discrete``; :func:`distribution` reads one from a scene's
``[random]`` table, its numbers through the scene's own expression parser). An output
that depends on one continuous random input and is monotone on finitely many pieces of
its support has an exact density by a change of variables: on each piece the output
``y = g(x)`` has an inverse ``x = h(y)``, and the density of y is the sum over the
pieces whose range holds y of ``f(h(y)) |h'(y)|``. :func:`pushforward` derives it with
SymPy, with its support and its mean (the integral of g against the input's density).
:func:`monte_carlo` draws the same quantity from a seeded generator and evaluates it with
the fused kernel of :mod:`rigidimpact.symbolic.numeric`, so the two can be set side by
side with the Monte Carlo's standard error.

Examples
--------
>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> out = pushforward(x**2, x, distribution({"uniform": ["0", "1"]}, "x"))
>>> out.support, out.mean
((0, 1), 1/3)
>>> sp.simplify(out.density - 1 / (2 * sp.sqrt(out.variable)))
0
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import sympy as sp
from sympy.simplify.fu import TR8

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.symbolic.drawn import DrawPlan, Sampler, stream
from rigidimpact.symbolic.expr import parse_expression
from rigidimpact.symbolic.numeric import fused

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["Distribution", "Pushforward", "RandomInputs", "distribution", "pushforward",
           "monte_carlo", "histogram", "random_table", "chunk_sizes", "chunk_sums",
           "combine", "stream", "draw_plan", "KINDS", "SAMPLES"]

KINDS = ("uniform", "normal", "lognormal", "discrete")
SAMPLES, MAX_SAMPLES = 1_000_000, 10**9  # the Monte Carlo beside each exact answer


@dataclass(frozen=True)
class Distribution:
    """A random input: `kind` (one of :data:`KINDS`) and its `parameters`: the ends of
    a uniform interval, the mean and standard deviation of a normal (of the logarithm
    for a log-normal), or for a discrete one its values, with `weights` (equal if
    none are given)."""

    kind: str
    parameters: tuple[sp.Expr, ...]
    weights: tuple[sp.Expr, ...] = ()

    def density(self, x: sp.Symbol) -> sp.Expr:
        """The probability density at x on the support (a continuous kind)."""
        if self.kind == "uniform":
            low, high = self.parameters
            return 1 / (high - low)
        if self.kind == "normal":
            mean, spread = self.parameters
            return sp.exp(-(x - mean) ** 2 / (2 * spread ** 2)) / (spread * sp.sqrt(2 * sp.pi))
        if self.kind == "lognormal":
            mean, spread = self.parameters
            return sp.exp(-(sp.log(x) - mean) ** 2 / (2 * spread ** 2)) / (
                x * spread * sp.sqrt(2 * sp.pi))
        raise InputError("random", "a discrete input has probabilities, not a density")

    @property
    def support(self) -> tuple[sp.Expr, sp.Expr]:
        """Where the input lies (its least and greatest values)."""
        if self.kind == "uniform":
            return self.parameters[0], self.parameters[1]
        if self.kind == "normal":
            return -sp.oo, sp.oo
        if self.kind == "lognormal":
            return sp.Integer(0), sp.oo
        return min(self.parameters, key=float), max(self.parameters, key=float)

    def sampler(self, name: str = "",
                values: Mapping[sp.Symbol, Any] | None = None) -> Sampler:
        """This law with its parameters at `values` as floats, for the draws
        (:class:`rigidimpact.symbolic.drawn.Sampler`)."""
        numbers = tuple(float(sp.sympify(p).subs(values or {})) for p in self.parameters)
        return Sampler(name, self.kind, numbers, tuple(float(w) for w in self.weights))

    def sample(self, rng: np.random.Generator, size: int,
               values: Mapping[sp.Symbol, Any] | None = None) -> np.ndarray:
        """`size` draws from `rng`, the parameters at `values`."""
        return self.sampler("", values).sample(rng, size)


def distribution(table: Any, name: str,
                 symbols: Mapping[str, sp.Symbol] | None = None) -> Distribution:
    """One entry of a ``[random]`` table, for the symbol `name`: ``{uniform = [a, b]}``,
    ``{normal = [mean, sd]}``, ``{lognormal = [mean, sd]}`` (of the logarithm) or
    ``{discrete = [v1, v2, ...], weights = [w1, w2, ...]}``; each number is text or a
    number, read by the scene's expression parser (it may name `symbols`)."""
    where = f"random.{name}"
    if not isinstance(table, dict) or not table:
        raise InputError(where, "a table such as { uniform = [\"0\", \"pi\"] }")
    kinds = [k for k in table if k in KINDS]
    unknown = [k for k in table if k not in KINDS and k != "weights"]
    if unknown or len(kinds) != 1:
        raise InputError(where, f"one of {', '.join(KINDS)} (and weights for discrete), "
                         f"not {', '.join(map(str, table))}")
    kind = kinds[0]
    raw = table[kind]
    if not isinstance(raw, list) or not raw:
        raise InputError(f"{where}.{kind}", "a list of numbers")
    parameters = tuple(parse_expression(v, f"{where}.{kind}", symbols or {}) for v in raw)
    if kind != "discrete" and len(parameters) != 2:
        raise InputError(f"{where}.{kind}", "two numbers: "
                         + ("its ends" if kind == "uniform" else "a mean and a spread"))
    weights: tuple[sp.Expr, ...] = ()
    if "weights" in table:
        if kind != "discrete" or not isinstance(table["weights"], list) or \
                len(table["weights"]) != len(parameters):
            raise InputError(f"{where}.weights", "one weight for each discrete value")
        weights = tuple(parse_expression(w, f"{where}.weights", {})
                        for w in table["weights"])
        if any(not w.is_number or w < 0 for w in weights) or not sum(weights) > 0:
            raise InputError(f"{where}.weights", "numbers, none negative, not all zero")
    if kind == "uniform" and all(p.is_number for p in parameters) and \
            not parameters[1] > parameters[0]:
        raise InputError(f"{where}.uniform", "the second end must be above the first")
    if kind in ("normal", "lognormal") and parameters[1].is_number and \
            not parameters[1] > 0:
        raise InputError(f"{where}.{kind}", "the spread must be positive")
    if kind == "discrete" and not all(p.is_number for p in parameters):
        raise InputError(f"{where}.discrete", "numbers")
    return Distribution(kind, parameters, weights)


@dataclass(frozen=True)
class RandomInputs:
    """A scene's ``[random]`` table: each random symbol's distribution, the outputs
    whose distributions are asked for (empty: every result driven by one random
    input), and the Monte Carlo's `samples` and `seed`."""

    inputs: Mapping[sp.Symbol, Distribution]
    outputs: tuple[str, ...] = ()
    samples: int = SAMPLES
    seed: int = 0
    samples_given: bool = False  # whether the table set `samples` (or the default holds)


def random_table(table: Mapping[str, Any], symbols: Mapping[str, sp.Symbol]
                 ) -> RandomInputs | None:
    """A scene's ``[random]`` table read: ``NAME = { uniform = [a, b] }`` (or normal,
    lognormal, discrete; see :func:`distribution`) for each random symbol, and the
    settings ``outputs = ["KEY", ...]``, ``samples = N`` and ``seed = S``. None when the
    table is empty."""
    if not table:
        return None
    inputs: dict[sp.Symbol, Distribution] = {}
    outputs: tuple[str, ...] = ()
    samples, seed = SAMPLES, 0
    for name, entry in table.items():
        if name == "outputs":
            if not isinstance(entry, list) or not all(isinstance(k, str) for k in entry):
                raise InputError("random.outputs", "a list of result keys such as "
                                 "[\"barbell.vy\"]")
            outputs = tuple(entry)
        elif name in ("samples", "seed"):
            low = 1 if name == "samples" else 0
            high = MAX_SAMPLES if name == "samples" else 2**63 - 1
            if isinstance(entry, bool) or not isinstance(entry, int) or \
                    not low <= entry <= high:
                raise InputError(f"random.{name}", f"a whole number from {low} to {high}, "
                                 f"not {entry!r}")
            samples, seed = (entry, seed) if name == "samples" else (samples, entry)
        elif name not in symbols:
            raise InputError(f"random.{name}", "not a symbol of the scene; declare it "
                             "under [symbols]")
        else:
            inputs[symbols[name]] = distribution(entry, name)
    if not inputs:
        raise InputError("random", "names no random symbol")
    return RandomInputs(inputs, outputs, samples, seed, "samples" in table)


@dataclass(frozen=True)
class Pushforward:
    """The exact distribution of an output `y = g(x)` of one random input: its
    `density` in the symbol `variable` on `support` (least, greatest), its `mean`, the
    `pieces` on which g is monotone (each as the input's interval), and `inverse`, the
    inverse on each piece."""

    variable: sp.Symbol
    density: sp.Expr
    support: tuple[sp.Expr, sp.Expr]
    mean: sp.Expr
    pieces: tuple[tuple[sp.Expr, sp.Expr], ...]
    inverse: tuple[sp.Expr, ...]
    rising: tuple[bool, ...]

    def probability_below(self, level: Any, input_density: sp.Expr,
                          x: sp.Symbol) -> sp.Expr:
        """P(y < level) for a level inside every piece's range, from the input's
        measure of the set where g < level: on each piece an interval ending at the
        inverse of the level."""
        total = sp.Integer(0)
        for (low, high), h, rising in zip(self.pieces, self.inverse, self.rising,
                                          strict=True):
            cut = h.subs(self.variable, level)
            total += sp.integrate(input_density, (x, low, cut) if rising else (x, cut, high))
        return sp.simplify(total)


def _sample_point(expr: sp.Expr, at: Mapping[sp.Symbol, Any]) -> float:
    return float(sp.N(expr.subs(at), 30))


def _rising(g: sp.Expr, x: sp.Symbol, low: sp.Expr, high: sp.Expr,
            at: Mapping[sp.Symbol, Any]) -> bool:
    """Whether g rises on the piece (low, high), judged at its middle."""
    return _sample_point(sp.diff(g, x).subs(x, (low + high) / 2), at) > 0


def pushforward(g: sp.Expr, x: sp.Symbol, input_distribution: Distribution,
                sample: Mapping[sp.Symbol, Any] | None = None,
                variable: sp.Symbol | None = None) -> Pushforward | None:
    """The exact distribution of ``y = g(x)`` for the continuous random input x, or
    None where it is not found in closed form (g not piecewise monotone in closed form,
    or an input that is not uniform on a finite interval, or g a Piecewise).

    The pieces are cut where g' vanishes inside the support (its numerator's factors
    that hold x, solved by SymPy). On each piece the inverse is the root of g = y that
    lies in the piece and the signs are judged at `sample`, values of the other
    symbols (for the barbell, e = 1/2): the answer holds wherever those signs do."""
    if input_distribution.kind != "uniform" or g.has(sp.Piecewise):
        return None  # a Piecewise (friction's courses, say): left to the Monte Carlo
    try:
        return _pushforward(g, x, input_distribution, sample, variable)
    except (NotImplementedError, ValueError, TypeError):
        return None  # what SymPy cannot solve or integrate: left to the Monte Carlo


def _pushforward(g: sp.Expr, x: sp.Symbol, input_distribution: Distribution,
                 sample: Mapping[sp.Symbol, Any] | None,
                 variable: sp.Symbol | None) -> Pushforward | None:
    y = variable or sp.Symbol("y", real=True)
    at = dict(sample or {})
    low, high = input_distribution.support
    f = input_distribution.density(x)
    slope = sp.factor(sp.together(sp.diff(g, x)))
    numerator = sp.numer(slope)
    cuts: set[sp.Expr] = set()
    for factor in sp.Mul.make_args(numerator):
        base = factor.base if factor.is_Pow else factor
        if not base.has(x):
            continue
        roots = sp.solveset(base, x, sp.Interval.open(low, high))
        if roots is sp.S.EmptySet:
            continue
        if not isinstance(roots, sp.FiniteSet):
            return None
        cuts |= set(roots)
    ends = sorted({low, high, *cuts}, key=lambda e: _sample_point(e, at))
    pieces = tuple(zip(ends[:-1], ends[1:], strict=True))
    density, inverses, images = sp.Integer(0), [], []
    candidates = sp.solve(sp.Eq(g, y), x)  # every inverse branch; each piece picks one
    for a, b in pieces:
        middle = (a + b) / 2
        level = g.subs(x, middle)
        h = None
        for candidate in candidates:
            try:
                value = _sample_point(candidate.subs(y, level), at)
            except (TypeError, ValueError):
                continue
            if abs(value - _sample_point(middle, at)) < 1e-9 * max(1.0, abs(value)):
                h = candidate
                break
        if h is None:
            return None
        inverses.append(h)
        image = sorted((sp.simplify(g.subs(x, a)), sp.simplify(g.subs(x, b))),
                       key=lambda e: _sample_point(e, at))
        images.append(tuple(image))
        part = sp.simplify(f.subs(x, h) * sp.Abs(sp.diff(h, y)))
        density += part if len(pieces) == 1 else sp.Piecewise(
            (part, (y > image[0]) & (y < image[1])), (0, True))
    least = min((i[0] for i in images), key=lambda e: _sample_point(e, at))
    greatest = max((i[1] for i in images), key=lambda e: _sample_point(e, at))
    mean = _mean(g, f, x, low, high)
    return Pushforward(y, _clean(density, y, least, greatest, at), (least, greatest),
                       mean, pieces, tuple(inverses),
                       tuple(_rising(g, x, a, b, at) for a, b in pieces))


def _mean(g: sp.Expr, f: sp.Expr, x: sp.Symbol, low: sp.Expr, high: sp.Expr) -> sp.Expr:
    """The integral of g against the density f over (low, high). Powers and products of
    sines and cosines are first written as sums of sines and cosines of multiple angles
    (``TR8``: cos^2 x = (1 + cos 2x)/2), on which SymPy's integral comes out in one term
    where the original's comes out as a difference of arctangents that it does not
    combine (the coin's mean, (1 + e)/sqrt(5) - 1); the original where that fails."""
    for form in (sp.together(TR8(g)), g):
        value = sp.integrate(form * f, (x, low, high))
        if not value.has(sp.Integral):
            break
    return sp.simplify(value)


def _clean(density: sp.Expr, y: sp.Symbol, least: sp.Expr, greatest: sp.Expr,
           at: Mapping[sp.Symbol, Any]) -> sp.Expr:
    """The density with |h'(y)| written without Abs where its sign is one across the
    support (judged at its middle), and its powers combined as if their bases were
    positive, which they are inside the support: kept only if it agrees with the
    density as derived at three points inside the support."""
    middle = (least + greatest) / 2

    def unsigned(arg: sp.Expr) -> sp.Expr:
        return arg if _sample_point(arg.subs(y, middle), at) >= 0 else -arg

    if density.has(sp.Abs):
        density = sp.simplify(density.replace(sp.Abs, unsigned))
    if density.has(sp.Piecewise):
        return density
    combined = sp.simplify(sp.powsimp(sp.powdenest(density, force=True), force=True))
    for share in (sp.Rational(1, 4), sp.Rational(1, 2), sp.Rational(3, 4)):
        point = {**at, y: (least + share * (greatest - least)).subs(at)}
        try:
            a, b = _sample_point(density, point), _sample_point(combined, point)
        except (TypeError, ValueError):
            return density
        if not abs(a - b) <= 1e-12 * max(1.0, abs(a)):
            return density
    return combined


def chunk_sizes(samples: int, chunk: int) -> list[int]:
    """The draws of each chunk: `chunk` each, the last one what is left."""
    return [min(chunk, samples - start) for start in range(0, samples, chunk)]


def draw_plan(g: sp.Expr, inputs: Mapping[sp.Symbol, Distribution],
              values: Mapping[sp.Symbol, Any]) -> DrawPlan:
    """How to draw g (:class:`rigidimpact.symbolic.drawn.DrawPlan`): its random `inputs`
    drawn in the order of their names, the other symbols at `values`, evaluated by the
    fused kernel (:func:`rigidimpact.symbolic.numeric.fused`: g in its stable form, its
    shared subexpressions once), whose source the plan carries."""
    fixed = {s: v for s, v in values.items() if s not in inputs}
    at = tuple(sorted(((s, sp.sympify(v)) for s, v in fixed.items()), key=lambda x: str(x[0])))
    kernel = _kernel(sp.sympify(g), at)
    return DrawPlan(kernel.source(), kernel.arguments,
                    tuple(inputs[s].sampler(s.name, fixed) for s in sorted(inputs, key=str)),
                    kernel.chunk)


@lru_cache(maxsize=32)
def _kernel(g: sp.Expr, at: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()) -> Any:
    """The fused kernel of g with the symbols in `at` given their values, built once a
    process."""
    return fused({"y": g.subs(dict(at))})


def chunk_sums(g: sp.Expr, inputs: Mapping[sp.Symbol, Distribution],
               values: Mapping[sp.Symbol, Any], seed: int, index: int,
               size: int) -> tuple[float, float, float]:
    """One chunk of a Monte Carlo: the sum, the sum of squares and the count below
    zero of `size` draws of g from chunk `index`'s own stream of the seed
    (:func:`stream`), so a chunk draws the same numbers in any process and any order
    (:meth:`rigidimpact.symbolic.drawn.DrawPlan.sums` of :func:`draw_plan`)."""
    return draw_plan(g, inputs, values).sums(seed, index, size)


def combine(sums: Sequence[tuple[float, float, float]], samples: int) -> dict[str, float]:
    """The Monte Carlo's mean, standard error and fraction below zero from its chunks'
    sums, added in the chunks' order (so the answer does not depend on where they ran)."""
    total = square = below = 0.0
    for part in sums:
        total += part[0]
        square += part[1]
        below += part[2]
    mean = total / samples
    spread = max(square / samples - mean * mean, 0.0) * samples / max(samples - 1, 1)
    return {"mean": mean, "standard_error": float(np.sqrt(spread / samples)),
            "below_zero": below / samples, "samples": float(samples)}


def monte_carlo(g: sp.Expr, inputs: Mapping[sp.Symbol, Distribution],
                values: Mapping[sp.Symbol, Any], samples: int, seed: int,
                chunk: int = 1_000_000) -> dict[str, float]:
    """The mean of g over `samples` seeded draws of its random `inputs` (the other
    symbols at `values`), with its standard error and the fraction below zero; drawn in
    chunks of `chunk`, each from its own stream of the seed (:func:`chunk_sums`), so the
    same seed and chunk give the same answer in one process or spread over workers
    (:func:`rigidimpact.analyses.distributions.monte_carlo_on_dask`)."""
    sizes = chunk_sizes(samples, chunk)
    plan = draw_plan(g, inputs, values)
    return combine([plan.sums(seed, k, size) for k, size in enumerate(sizes)], samples)


def histogram(g: sp.Expr, inputs: Mapping[sp.Symbol, Distribution],
              values: Mapping[sp.Symbol, Any], samples: int, seed: int,
              edges: np.ndarray, chunk: int = 1_000_000) -> np.ndarray:
    """The density of g estimated from `samples` seeded draws (as :func:`monte_carlo`
    draws them), in the bins between `edges`: counts over samples and bin width, a
    chunk at a time (ten million draws need no more memory than one chunk)."""
    counts = np.zeros(len(edges) - 1)
    sizes = chunk_sizes(samples, chunk)
    plan = draw_plan(g, inputs, values)
    for index, size in enumerate(sizes):
        out = plan.values(np.random.default_rng(stream(seed, index)), size)
        counts += np.histogram(out, bins=edges)[0]
    return counts / (samples * np.diff(edges))
