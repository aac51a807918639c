"""A closed form's draws made with NumPy alone: the plan a Monte Carlo's chunks follow
(its fused kernel's source, its samplers with their numbers), made once from the
SymPy expression in the command's own process and sent to Dask workers as it is, so a
worker imports neither SymPy nor the rest of the package to draw. The one process and
every worker draw through the same :class:`DrawPlan`, so their sums agree to the bit.

Examples
--------
>>> import numpy as np
>>> plan = DrawPlan("def kernel(a0):\\n    return (2*a0,)\\n", ("x",),
...                 (Sampler("x", "uniform", (0.0, 1.0)),))
>>> values = plan.values(np.random.default_rng(0), 3)
>>> bool(np.array_equal(values, 2 * np.random.default_rng(0).uniform(0.0, 1.0, 3)))
True
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rigidimpact.lazy import deferred

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")  # imported at the first draw, not with the scene parser

__all__ = ["DrawPlan", "Sampler", "compiled", "plan_run", "stream"]

_COMPILED: dict[tuple[str, str], Any] = {}


def compiled(source: str, backend: str = "numpy") -> Any:
    """The function of generated kernel source (this package's own printer's output from
    exact expressions, never text from a user's file), compiled once a process: NumPy's
    ``kernel``, or numba's ``(pre, kernel)``."""
    key = (source, backend)
    if key not in _COMPILED:
        import math

        import numpy  # the module itself, not this module's stand-in: numba types it

        namespace: dict[str, Any] = {"numpy": numpy, "math": math}
        exec(compile(source, "<rigidimpact fused kernel>", "exec"), namespace)  # noqa: S102
        if backend == "numba":
            import numba

            # NumPy's error model: a division by zero gives inf or nan as in the NumPy
            # backend (not a ZeroDivisionError), and with no check in it the loop
            # vectorises
            _COMPILED[key] = (namespace["pre"], numba.njit(
                nogil=True, error_model="numpy")(namespace["kernel"]))
        else:
            _COMPILED[key] = namespace["kernel"]
    return _COMPILED[key]


def stream(seed: int, index: int) -> np.random.SeedSequence:
    """Chunk `index`'s own stream of the seed: the `index`-th child of
    ``numpy.random.SeedSequence(seed)`` (what ``spawn`` would give it, made without
    making the children before it).

    Examples
    --------
    >>> a = stream(2011, 5).generate_state(4)
    >>> b = np.random.SeedSequence(2011).spawn(8)[5].generate_state(4)
    >>> bool((a == b).all())
    True
    """
    return np.random.SeedSequence(seed, spawn_key=(index,))


@dataclass(frozen=True)
class Sampler:
    """One random input's law with its numbers (``uniform``: low and high; ``normal``
    and ``lognormal``: mean and standard deviation; ``discrete``: the values, with their
    `weights` or equally likely)."""

    name: str
    kind: str
    numbers: tuple[float, ...]
    weights: tuple[float, ...] = ()

    def sample(self, rng: np.random.Generator, size: int) -> np.ndarray:
        """`size` draws from `rng`."""
        a = self.numbers
        if self.kind == "uniform":
            return rng.uniform(a[0], a[1], size)
        if self.kind == "normal":
            return rng.normal(a[0], a[1], size)
        if self.kind == "lognormal":
            return rng.lognormal(a[0], a[1], size)
        weights = np.array(list(self.weights) or [1.0] * len(a))
        return rng.choice(np.array(a), size=size, p=weights / weights.sum())


@dataclass(frozen=True)
class DrawPlan:
    """How to draw a closed form: the NumPy `source` of its fused kernel (one result,
    the other numbers already in it), the kernel's `arguments` by name, the `samplers`
    in the order their inputs are drawn (by name), and the `chunk` of sets the kernel
    takes at a time (as :class:`rigidimpact.symbolic.numeric.Fused` runs it)."""

    source: str
    arguments: tuple[str, ...]
    samplers: tuple[Sampler, ...]
    chunk: int = 8192

    def values(self, rng: np.random.Generator, size: int) -> np.ndarray:
        """`size` values of the closed form, its inputs drawn from `rng` in turn."""
        drawn = {s.name: s.sample(rng, size) for s in self.samplers}
        kernel = compiled(self.source)
        inputs = [np.asarray(drawn[n], dtype=np.float64) for n in self.arguments]
        out = np.empty((size,) if inputs else ())
        flat = out.reshape(-1)
        for start in range(0, flat.shape[0], self.chunk):
            stop = min(start + self.chunk, flat.shape[0])
            (flat[start:stop],) = kernel(*(a[start:stop] for a in inputs))
        return np.broadcast_to(out, (size,))

    def sums(self, seed: int, index: int, size: int) -> tuple[float, float, float]:
        """One chunk of a Monte Carlo: the sum, the sum of squares and the count below
        zero of `size` values drawn from chunk `index`'s own stream of the seed
        (:func:`stream`), so a chunk draws the same numbers in any process and any
        order: the numbers :meth:`values` draws from that stream.

        The values are made and summed a block of :attr:`chunk` at a time, each sum
        NumPy's sum of its blocks' sums, so no array of the chunk's size is made where
        one input is drawn: a sampler's draws made a block at a time are the numbers it
        draws at once, from the same stream. (Several inputs are each drawn whole, in
        turn, as :meth:`values` draws them.) The chunk's arrays of 8 MB were each mapped
        afresh by the system and their pages zeroed: blocks that stay in the processor's
        cache took the dropped barbell's chunk in 0.66 to 0.77 of the time."""
        rng = np.random.default_rng(stream(seed, index))
        kernel = compiled(self.source)
        whole = ({s.name: s.sample(rng, size) for s in self.samplers}
                 if len(self.samplers) > 1 else {})
        starts = range(0, size, self.chunk)
        parts = np.empty((3, len(starts)))
        for j, start in enumerate(starts):
            stop = min(start + self.chunk, size)
            drawn = ({n: a[start:stop] for n, a in whole.items()} if whole else
                     {s.name: s.sample(rng, stop - start) for s in self.samplers})
            (out,) = kernel(*(np.asarray(drawn[n], dtype=np.float64)
                              for n in self.arguments))
            # a closed form that draws nothing: one value for every draw
            out = np.broadcast_to(out, (stop - start,))
            parts[0, j] = out.sum()
            parts[1, j] = (out * out).sum()
            parts[2, j] = np.count_nonzero(out < 0)
        return float(parts[0].sum()), float(parts[1].sum()), float(parts[2].sum())


def plan_run(plan: DrawPlan, seed: int, start: int,
             sizes: Sequence[int]) -> list[tuple[float, float, float]]:
    """The sums of chunks start, start + 1, ... (one :meth:`DrawPlan.sums` each): a Dask
    worker's task."""
    return [plan.sums(seed, start + k, size) for k, size in enumerate(sizes)]
