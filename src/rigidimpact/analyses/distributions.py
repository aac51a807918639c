"""The distributions of a scene's outputs under its ``[random]`` inputs: the exact
density, support and mean where an output is monotone in pieces of one continuous
random input (a change of variables, :func:`rigidimpact.symbolic.distributions.pushforward`),
and beside it a seeded Monte Carlo with its standard error, each timed (what accuracy
costs in time). ``derive`` prints them and ``derive --json`` adds them under
``"distributions"``.
"""

from __future__ import annotations

import contextlib
import random
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.outputs.workers import dask_client, gathered, guided, local_or_here
from rigidimpact.scenes.space import load_any
from rigidimpact.symbolic.distributions import (
    Distribution,
    chunk_sizes,
    combine,
    draw_plan,
    histogram,
    monte_carlo,
    pushforward,
    stream,
)
from rigidimpact.symbolic.drawn import plan_run

__all__ = ["distributions", "scene_distributions", "monte_carlo_on_dask", "point_monte_carlo",
           "point_chunk", "distributions_json", "distributions_text"]

CHUNK = 1_000_000  # draws a chunk (a worker takes a run of them)
# a scene with no closed form (several contacts, joints, the compliant rule) is solved
# once a draw: 1000 draws by default, at most a million, 64 a task
POINT_SAMPLES, MAX_POINT_SAMPLES, POINT_CHUNK = 1000, 10**6, 64

Progress = Callable[[int, int], None]  # told (tasks done, tasks) as a Dask task ends


def monte_carlo_on_dask(g: sp.Expr, inputs: dict[sp.Symbol, Distribution],
                        values: dict[sp.Symbol, Any], samples: int, seed: int,
                        chunk: int = CHUNK, workers: int | None = None,
                        scheduler: str | None = None, processes: bool = True,
                        progress: Progress | None = None,
                        client: Any = None) -> dict[str, float]:
    """:func:`rigidimpact.symbolic.distributions.monte_carlo` spread over Dask workers:
    one task a chunk, each drawing from its own stream of the seed, their sums added
    in the chunks' order, so the answer equals the one-process answer for the same
    seed and chunk, whatever the number of workers. On `client` where one is given (a
    command's several outputs share one cluster); else with no `scheduler` a local
    cluster of `workers` processes (default: one a core) is started and closed, and
    with one (``tcp://host:8786``) its cluster is used. `progress(done, total)` is told
    as each task ends."""
    if client is None:
        with dask_client(workers, scheduler, processes) as opened:
            return monte_carlo_on_dask(g, inputs, values, samples, seed, chunk,
                                       progress=progress, client=opened)
    return _gathered(client, _sent(client, g, inputs, values, samples, seed, chunk),
                     samples, progress)[0]


def _sent(client: Any, g: sp.Expr, inputs: dict[sp.Symbol, Distribution],
          values: dict[sp.Symbol, Any], samples: int, seed: int,
          chunk: int) -> list[Any]:
    """The futures of :func:`monte_carlo_on_dask`'s tasks, sent to `client`'s workers
    and not waited for."""
    sizes = chunk_sizes(samples, chunk)
    # runs of consecutive chunks, shrinking as the work ends (the plan sent once a run,
    # not once a chunk), each chunk still its own stream: the sums are the one-process
    # sums, in the chunks' order
    count = len(client.scheduler_info().get("workers", {})) or 1
    runs = guided(len(sizes), count)
    # the plan (the kernel's source, the samplers' numbers) is made here, so a worker
    # draws with NumPy alone: it imports neither SymPy nor the rest of this package
    plan = draw_plan(g, inputs, values)
    return [client.submit(plan_run, plan, seed, start, sizes[start:stop], pure=False)
            for start, stop in runs]


def _gathered(client: Any, futures: list[Any], samples: int,
              progress: Progress | None) -> tuple[dict[str, float], int]:
    """The Monte Carlo's answer once the tasks of :func:`_sent` are done, and how many
    workers drew it."""
    runs, drew = gathered(client, futures, progress)
    return combine([part for run in runs for part in run], samples), drew


def point_chunk(scene: Any, keys: Sequence[str], inputs: Mapping[sp.Symbol, Distribution],
                seed: int, index: int, size: int
                ) -> tuple[dict[str, tuple[float, float, float]], int, str | None]:
    """One chunk of a Monte Carlo of a scene solved with numbers: `size` draws of its
    random `inputs` from chunk `index`'s own stream of the seed (as
    a closed form's chunks draw them), each set solved
    by the scene's rule at its [values] otherwise. For each key the sum, the sum of
    squares and the count below zero; with the number of draws whose answer came with a
    warning (kinetic energy created, a contact that would pull) and the first such."""
    rng = np.random.default_rng(stream(seed, index))
    fixed = {s: v for s, v in scene.values.items() if s not in inputs}
    order = sorted(inputs, key=str)
    drawn = [inputs[s].sample(rng, size, fixed) for s in order]
    base = {s.name: v for s, v in fixed.items()}
    sources = {n: f"values.{n}" for n in base} | {s.name: f"random.{s.name}" for s in order}
    sums = {k: [0.0, 0.0, 0.0] for k in keys}
    warned, first = 0, None
    for j in range(size):
        values = base | {s.name: float(x[j]) for s, x in zip(order, drawn, strict=True)}
        answer = scene.evaluate(values, sources, None)
        if answer.warnings:
            warned += 1
            first = first or answer.warnings[0]
        for key in keys:
            value = float(answer.numbers[key])
            part = sums[key]
            part[0] += value
            part[1] += value * value
            part[2] += value < 0
    return {k: (v[0], v[1], v[2]) for k, v in sums.items()}, warned, first


def point_monte_carlo(scene: Any, keys: Sequence[str], samples: int, seed: int,
                      workers: int | None = None, scheduler: str | None = None,
                      processes: bool = True, progress: Progress | None = None,
                      chunk: int = POINT_CHUNK) -> dict[str, dict[str, Any]]:
    """The Monte Carlo of `keys` for a scene with no closed form: `samples` draws of its
    [random] inputs, each solved with numbers by its rule (:func:`point_chunk`, `chunk`
    draws a task), in this process or on Dask workers; the same numbers either way for
    the same seed. For each key its mean, standard error, fraction below zero and
    samples, and ``warned``: the draws whose answer came with a warning, and the
    first warning. `progress(done, total)` is told as each Dask task ends."""
    return _point_monte_carlo(scene, keys, samples, seed, workers, scheduler, processes,
                              progress, chunk)[0]


def _point_monte_carlo(scene: Any, keys: Sequence[str], samples: int, seed: int,
                       workers: int | None, scheduler: str | None, processes: bool,
                       progress: Progress | None, chunk: int
                       ) -> tuple[dict[str, dict[str, Any]], int]:
    """:func:`point_monte_carlo`'s answer and how many Dask workers drew it (0: this
    process did)."""
    table = scene.random
    inputs = dict(table.inputs)
    sizes = chunk_sizes(samples, chunk)
    jobs = [(k, size) for k, size in enumerate(sizes)]
    workers, note = local_or_here(samples, "solves", workers, scheduler)
    drew = 0
    if workers is None and scheduler is None:
        parts = [point_chunk(scene, keys, inputs, seed, k, size)
                 for k, size in jobs]
    else:
        with dask_client(workers, scheduler, processes) as client:
            sent = client.scatter(scene, broadcast=True)  # once a worker, not once a task
            futures = [client.submit(point_chunk, sent, list(keys), inputs, seed, k, size,
                                     pure=False) for k, size in jobs]
            parts, drew = gathered(client, futures, progress)
    warned = sum(p[1] for p in parts)
    first = next((p[2] for p in parts if p[2]), None)
    return {key: {**combine([p[0][key] for p in parts], samples), "seed": seed,
                  "warned": warned, **({"warning": first} if first else {}),
                  **({"workers": note} if note else {})}
            for key in keys}, drew


def _point_distributions(scene: Any, results: Mapping[str, Any], workers: int | None,
                         scheduler: str | None, progress: Progress | None
                         ) -> dict[str, dict[str, Any]]:
    """:func:`scene_distributions` for a scene solved with numbers (several contacts,
    joints): its outputs have no closed form, so each is a Monte Carlo of solves."""
    table = scene.random
    samples = table.samples if table.samples_given else POINT_SAMPLES
    if samples > MAX_POINT_SAMPLES:
        raise InputError("random.samples", f"{samples} draws, each a solve of its own: "
                         f"past the budget of {MAX_POINT_SAMPLES} for a scene without a "
                         "closed form")
    keys = list(table.outputs or results)
    begin = time.perf_counter()
    found, drew = _point_monte_carlo(scene, keys, samples, table.seed, workers,
                                     scheduler, True, progress, POINT_CHUNK)
    seconds = time.perf_counter() - begin
    drivers = [str(s) for s in sorted(table.inputs, key=str)]
    return {key: {"random": drivers, "solved": "a solve a draw (no closed form)",
                  "monte_carlo": {**{k: v for k, v in found[key].items()
                                     if k != "workers"}, "workers": drew},
                  "monte_carlo_seconds": seconds,
                  **({"workers": found[key]["workers"]} if "workers" in found[key]
                     else {})}
            for key in keys}


def _exact(g: sp.Expr, x: sp.Symbol, law: Distribution, values: Mapping[sp.Symbol, Any]
           ) -> dict[str, Any] | None:
    """The closed form of g's distribution (:func:`pushforward`): ``variable``,
    ``density``, ``support``, ``mean``, and ``below_zero`` where 0 lies inside the
    support at `values`; None where it is not found."""
    exact = pushforward(g, x, law, values, sp.Symbol("y", real=True))
    if exact is None:
        return None
    found: dict[str, Any] = {"variable": exact.variable, "density": exact.density,
                             "support": exact.support, "mean": exact.mean}
    low, high = (float(sp.N(e.subs(values))) for e in exact.support)
    if low < 0 < high:
        found["below_zero"] = exact.probability_below(0, law.density(x), x)
    return found


# the closed form is sought where the output is a ratio of polynomials of degree at most
# MAX_DEGREE in one of these forms of its random input: SymPy's inverse is then a
# quadratic's root and its integrals are of a known kind, so whether a density is given
# depends on the output's form alone (never on a clock)
MAX_DEGREE = 2


def closed_form_refusal(g: sp.Expr, x: sp.Symbol) -> str | None:
    """Why the closed form of g's distribution over x is not sought, or None when it is:
    g must be a ratio of polynomials of degree at most 2 in x, cos x, sin x or tan x
    (one of them, the others absent).

    Examples
    --------
    >>> x, e = sp.symbols("x e", positive=True)
    >>> closed_form_refusal((e - sp.cos(x)**2) / (1 + sp.cos(x)**2), x) is None
    True
    >>> closed_form_refusal(sp.sqrt(1 + x**2), x)
    'not a ratio of polynomials of degree at most 2 in x, cos(x), sin(x) or tan(x)'
    """
    k = sp.Dummy("k")
    for kernel in (x, sp.cos(x), sp.sin(x), sp.tan(x)):
        h = sp.together(g.xreplace({kernel: k}) if kernel != x else g.subs(x, k))
        if h.has(x):
            continue
        numerator, denominator = sp.fraction(h)
        try:
            degrees = [sp.Poly(part, k).degree() for part in (numerator, denominator)]
        except sp.PolynomialError:
            continue
        if max(degrees) <= MAX_DEGREE:
            return None
    return (f"not a ratio of polynomials of degree at most {MAX_DEGREE} in {x}, cos({x}), "
            f"sin({x}) or tan({x})")


def _refusal(g: sp.Expr, x: sp.Symbol, law: Distribution) -> str | None:
    """Why no closed form of g's distribution is sought, as ``derive`` says it (the
    change of variables is made for a uniform input, on an output of the form
    :func:`closed_form_refusal` accepts), or None when it is."""
    if law.kind != "uniform":
        return f"{x} is {law.kind}, and the closed form is derived for a uniform input only"
    refusal = closed_form_refusal(g, x)
    return None if refusal is None else f"the output is {refusal}"


def _points(symbols: Sequence[sp.Symbol], roles: Sequence[Any], count: int = 3
            ) -> list[dict[sp.Symbol, sp.Rational]]:
    """`count` seeded rational points of `symbols` inside the ranges their roles allow
    (a restitution coefficient in (0, 1)), or (0, 2) for a positive symbol and (-2, 2)
    otherwise."""
    rng = random.Random(47)
    spans = {}
    for s in symbols:
        low, high = (0, 2) if s.is_positive or s.is_nonnegative else (-2, 2)
        for role in roles:
            if role.expr == s:
                low = role.low if role.low is not None else low
                high = role.high if role.high is not None else low + 2
        spans[s] = (sp.Rational(low), sp.Rational(high))
    return [{s: a + (b - a) * sp.Rational(rng.randint(1, 99), 100)
             for s, (a, b) in spans.items()} for _ in range(count)]


def _exact_for_every(g: sp.Expr, x: sp.Symbol, law: Distribution,
                     values: Mapping[sp.Symbol, Any], free: Sequence[sp.Symbol],
                     roles: Sequence[Any]) -> dict[str, Any] | None:
    """:func:`_exact` where some symbols of g have no number: the signs the closed form
    is judged by are judged at three seeded points of their allowed ranges, and the
    answer is kept only where the same formulas come out at each (``symbolic_in``)."""
    found = []
    for point in _points(free, roles):
        exact = _exact(g, x, law, {**values, **point})
        if exact is None:
            return None
        found.append(exact)
    keys = ("density", "support", "mean")
    if any(f[k] != found[0][k] for f in found[1:] for k in keys):
        return None
    first = {k: found[0][k] for k in ("variable", *keys)}
    chances = [f.get("below_zero") for f in found]
    if chances[0] is not None and all(c == chances[0] for c in chances):
        first["below_zero"] = chances[0]  # 0 inside the support at every point
    return {**first, "symbolic_in": [str(s) for s in free]}


def scene_distributions(scene: Any, results: dict[str, sp.Expr], workers: int | None = None,
                        scheduler: str | None = None,
                        progress: Progress | None = None) -> dict[str, dict[str, Any]]:
    """Each asked output's distribution (the ``[random]`` table's `outputs`, or every
    result driven by exactly one random input): ``random`` (its random symbols), and
    where found in closed form ``variable``, ``density``, ``support`` and ``mean`` (SymPy
    expressions), ``below_zero`` (P(output < 0), where 0 lies inside the support at the
    scene's [values]); always ``monte_carlo`` (mean, standard_error, below_zero,
    samples, seed, and ``workers``: how many Dask workers drew it, 0 where this process
    did) at the scene's [values], and the seconds each took. With `workers`
    asked for draws too few to repay starting them
    (:func:`rigidimpact.outputs.workers.local_or_here`), each drawn output's
    ``workers`` says they were not started and the draws were made here."""
    table = scene.random
    inputs = dict(table.inputs)
    unknown = [k for k in table.outputs if k not in results]
    if unknown:
        raise InputError("random.outputs", f"no result {unknown[0]!r}; the results are "
                         f"{', '.join(results)}")
    if len(scene.contacts) > 1 or scene.joints:
        return _point_distributions(scene, results, workers, scheduler, progress)
    keys = table.outputs or tuple(k for k, v in results.items()
                                  if len(v.free_symbols & set(inputs)) == 1)
    values = {s: v for s, v in scene.values.items() if s not in inputs}
    # the outputs drawn (a random input in them, every other number given): local
    # workers only where all their draws together repay the workers' start, and then
    # one cluster for them all
    drawn_keys = [k for k in keys if results[k].free_symbols & set(inputs)
                  and not results[k].free_symbols - set(inputs) - set(values)]
    workers, note = local_or_here(table.samples * len(drawn_keys), "draws", workers,
                                  scheduler)
    with contextlib.ExitStack() as stack:
        found = _each_distribution(scene, results, keys, inputs, values, workers,
                                   scheduler, progress, stack)
    if note:
        for entry in found.values():
            if "monte_carlo" in entry:
                entry["workers"] = note
    return found


def distributions(scene: Any, workers: int | None = None, scheduler: str | None = None
                  ) -> dict[str, dict[str, Any]]:
    """The distribution of each random output of a scene, as ``rigidimpact derive
    SCENE`` prints it: the exact density, support, mean and chance of a negative value
    where a closed form exists, and a seeded Monte Carlo at the scene's ``[values]``.

    Parameters
    ----------
    scene : Scene, str or Path
        A scene with a ``[random]`` table, or the path of its TOML file.
    workers : int, optional
        Draw the Monte Carlo on this many local Dask worker processes, as ``derive
        --workers N`` does. Where the draws are too few to repay starting them (fewer
        than 10^8 draws of a closed form, 200 solves of a scene without one), they are
        made in this process instead and each drawn output's ``"workers"`` says so.
        The numbers are the same either way.
    scheduler : str, optional
        The address of a running Dask scheduler (``tcp://host:8786``), as ``derive
        --scheduler`` uses: its workers draw.

    Returns
    -------
    dict
        For each output (the ``[random]`` table's ``outputs``, or else every result
        that one random input drives), a dict with:

        - ``random``: the names of the random inputs it depends on;
        - where a closed form was found, ``variable`` (the output's symbol, y),
          ``density`` (in y), ``support`` (its least and greatest values), ``mean``
          and, where 0 lies inside the support at ``[values]``, ``below_zero``
          (the chance that the output is negative), each a SymPy expression in the
          scene's symbols;
        - ``monte_carlo``: the draws' ``mean``, ``standard_error``, ``below_zero``
          (the fraction of draws below zero), ``samples``, ``seed`` and ``workers``
          (how many Dask workers drew them; 0 where this process did);
        - ``no_closed_form`` where none was sought, saying why;
        - ``exact_seconds`` and ``monte_carlo_seconds``: what each took.

    Raises
    ------
    InputError
        When the scene has no ``[random]`` table, or an output it names is not one of
        its results.

    Examples
    --------
    >>> import rigidimpact as ri
    >>> found = ri.distributions("derivations/random-barbell.toml")  # doctest: +SKIP
    >>> found["barbell.vy"]["mean"]  # doctest: +SKIP
    sqrt(2)*e/2 - 1 + sqrt(2)/2
    """
    if isinstance(scene, (str, Path)):
        scene = load_any(scene)
    if getattr(scene, "random", None) is None:
        raise InputError("random", f"the scene {scene.name!r} has no [random] table: "
                         "give a symbol a distribution there, such as theta = "
                         "{ uniform = [\"0\", \"pi/2\"] }")
    return scene_distributions(scene, dict(scene.derivation().results), workers, scheduler)


def _each_distribution(scene: Any, results: dict[str, sp.Expr], keys: Sequence[str],
                       inputs: Mapping[sp.Symbol, Distribution],
                       values: Mapping[sp.Symbol, Any], workers: int | None,
                       scheduler: str | None, progress: Progress | None,
                       stack: contextlib.ExitStack) -> dict[str, dict[str, Any]]:
    """:func:`scene_distributions`' outputs: where workers are asked for, a Dask cluster
    opened into `stack` and every output's draws sent to it first, then the closed
    forms derived here while the workers draw, then the draws' sums gathered; in one
    process, the closed forms and then the draws. A Monte Carlo's seconds on workers run
    from the sending of its tasks to their sums."""
    table = scene.random
    found: dict[str, dict[str, Any]] = {}
    every = {}
    for key in keys:
        g = results[key]
        drivers = sorted(g.free_symbols & set(inputs), key=str)
        if drivers:
            every[key] = (g, drivers, sorted(g.free_symbols - set(inputs) - set(values),
                                             key=str))
    # on workers, every output's draws are sent first and its closed form is derived
    # here while they are drawn (this process would otherwise leave a core idle)
    sent: dict[str, tuple[float, list[Any]]] = {}
    client = None
    if workers is not None or scheduler is not None:
        for key, (g, drivers, missing) in every.items():
            if missing:
                continue
            if client is None:
                client = stack.enter_context(dask_client(workers, scheduler))
            sent[key] = (time.perf_counter(),
                         _sent(client, g, {s: inputs[s] for s in drivers}, dict(values),
                               table.samples, table.seed, CHUNK))
    for key, (g, drivers, missing) in every.items():
        entry: dict[str, Any] = {"random": [str(s) for s in drivers]}
        if len(drivers) == 1 and inputs[drivers[0]].kind != "discrete":
            refusal = _refusal(g, drivers[0], inputs[drivers[0]])
            if refusal is not None:
                entry["no_closed_form"] = refusal
            else:
                begin = time.perf_counter()
                exact = (_exact_for_every(g, drivers[0], inputs[drivers[0]], values,
                                          missing, scene.roles) if missing
                         else _exact(g, drivers[0], inputs[drivers[0]], values))
                entry["exact_seconds"] = time.perf_counter() - begin
                if exact is not None:
                    entry.update(exact)
        elif len(drivers) > 1:
            entry["no_closed_form"] = (f"the output is driven by {len(drivers)} random "
                                       f"inputs ({', '.join(map(str, drivers))}): a closed "
                                       "form is derived for one")
        else:
            entry["no_closed_form"] = (f"{drivers[0]} is discrete: its distribution is the "
                                       "Monte Carlo's, value by value")
        if missing:  # the closed form alone: the draws need every other number
            if "density" not in entry:
                raise InputError("values", f"{key} needs a number for {missing[0]} under "
                                 "[values] (its Monte Carlo, and the signs its closed "
                                 "form is judged by)")
            entry["monte_carlo_missing"] = str(missing[0])
            found[key] = entry
            continue
        found[key] = entry
    for key, entry in found.items():
        if "monte_carlo_missing" in entry:
            continue
        g, drivers, _ = every[key]
        if key in sent:  # from the sending of its tasks to their sums
            begin, futures = sent[key]
            stats, drew = _gathered(client, futures, table.samples, progress)
        else:
            begin = time.perf_counter()
            stats, drew = monte_carlo(g, {s: inputs[s] for s in drivers}, values,
                                      table.samples, table.seed, CHUNK), 0
        entry["monte_carlo"] = {**stats, "seed": table.seed, "workers": drew}
        entry["monte_carlo_seconds"] = time.perf_counter() - begin
    return found


def distributions_json(found: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """:func:`scene_distributions`' answer for JSON: expressions as SymPy strings, the
    seconds rounded."""
    out: dict[str, Any] = {}
    for key, entry in found.items():
        row: dict[str, Any] = {"random": entry["random"]}
        for name in ("variable", "density", "mean", "below_zero", "solved"):
            if name in entry:
                row[name] = str(entry[name])
        if "support" in entry:
            row["support"] = [str(x) for x in entry["support"]]
        for name in ("symbolic_in", "no_closed_form", "monte_carlo_missing", "workers"):
            if name in entry:
                row[name] = entry[name]
        if "monte_carlo" in entry:
            row["monte_carlo"] = entry["monte_carlo"]
            row["monte_carlo_seconds"] = round(entry["monte_carlo_seconds"], 4)
        if "exact_seconds" in entry:
            row["exact_seconds"] = round(entry["exact_seconds"], 4)
        out[key] = row
    return out


def distributions_text(table: Any, values: Any, found: dict[str, dict[str, Any]]
                       ) -> list[str]:
    """:func:`scene_distributions`' answer as the lines ``derive`` prints, the closed
    forms' numbers at the scene's `values`."""
    laws = "; ".join(f"{s} {law.kind} on {list(law.parameters)}" if law.kind == "uniform"
                     else f"{s} {law.kind} {list(law.parameters)}"
                     for s, law in table.inputs.items())
    samples = next((int(e["monte_carlo"]["samples"]) for e in found.values()
                    if "monte_carlo" in e), table.samples)
    lines = [f"Distributions (random: {laws}; Monte Carlo at [values], {samples} "
             f"samples, seed {table.seed}):"]
    note = next((e["workers"] for e in found.values() if "workers" in e), None)
    if note:
        lines.append(f"  ({note})")
    for key, entry in found.items():
        lines.append(f"  {key}:")
        if "density" in entry:
            y = entry["variable"]
            low, high = entry["support"]
            lines += [f"      density at {y}: {entry['density']}",
                      f"      for {low} < {y} < {high}"]
            if "symbolic_in" in entry:
                lines += [f"      mean: {entry['mean']}  ({entry['exact_seconds']:.2f} s)",
                          f"      (for {', '.join(entry['symbolic_in'])} anywhere in "
                          "the range allowed: the same formulas at three seeded points "
                          "of it)"]
            else:
                at = float(sp.N(entry["mean"].subs(dict(values))))
                lines.append(f"      mean: {entry['mean']}  (= {at:.10g} at [values]; "
                             f"{entry['exact_seconds']:.2f} s)")
            if "below_zero" in entry and "symbolic_in" in entry:
                lines.append(f"      P({key} < 0) = {entry['below_zero']}")
            elif "below_zero" in entry:
                chance = float(sp.N(entry["below_zero"].subs(dict(values))))
                lines.append(f"      P({key} < 0) = {entry['below_zero']}  "
                             f"(= {chance:.10g})")
        elif "no_closed_form" in entry:
            lines.append(f"      no closed form sought: {entry['no_closed_form']}")
        elif "exact_seconds" in entry:
            lines.append("      no closed form found (not monotone in pieces in closed "
                         "form)")
        elif "solved" in entry:
            lines.append(f"      no closed form: {entry['solved']}")
        if "monte_carlo" not in entry:
            lines.append(f"      no Monte Carlo: the draws need a number for "
                         f"{entry['monte_carlo_missing']} under [values]")
            continue
        mc = entry["monte_carlo"]
        lines.append(f"      Monte Carlo: mean {mc['mean']:.10g} +- "
                     f"{mc['standard_error']:.2g} (standard error), P(< 0) "
                     f"{mc['below_zero']:.6g}; {entry['monte_carlo_seconds']:.2f} s"
                     + (f" on {mc['workers']} Dask worker" + "s" * (mc["workers"] > 1)
                        if mc.get("workers") else ""))
        if mc.get("warned"):
            lines.append(f"      warning: at {mc['warned']} of {int(mc['samples'])} draws: "
                         f"{mc['warning']}")
    return lines


def distribution_curves(scene: Any, results: Mapping[str, sp.Expr],
                        found: Mapping[str, Mapping[str, Any]], samples: int = 10**6,
                        bins: int = 60) -> list[tuple[str, Any, Any, Any, Any]]:
    """What :func:`rigidimpact.outputs.plots.random_outputs` draws for each output of
    `found` (:func:`scene_distributions`) driven by one random input, at the scene's
    [values]: its histogram from `samples` seeded draws (the table's seed) and, where
    found in closed form, its exact density between the ends of its support (else the
    histogram alone, between the draws' own ends)."""
    table = scene.random
    inputs = dict(table.inputs)
    values = {s: v for s, v in scene.values.items() if s not in inputs}
    curves = []
    for key, entry in found.items():
        g = results[key]
        drivers = g.free_symbols & set(inputs)
        if len(drivers) != 1 or g.free_symbols - drivers - set(values):
            continue  # two random inputs, or a symbol without a value: nothing to draw
        count = min(samples, table.samples)
        if "density" in entry:
            low, high = (float(sp.N(e.subs(values))) for e in entry["support"])
        else:
            sample = draw_plan(g, inputs, values).values(np.random.default_rng(table.seed),
                                                         min(count, 10**5))
            low, high = float(np.min(sample)), float(np.max(sample))
        if not low < high:
            continue  # one value: a point, no density
        edges = np.linspace(low, high, bins + 1)
        sampled = histogram(g, inputs, values, count, table.seed, edges)
        points = density = None
        if "density" in entry:
            points = np.linspace(low, high, 801)[1:-1]
            exact = sp.lambdify(entry["variable"], entry["density"].subs(values), "numpy")
            density = np.broadcast_to(np.asarray(exact(points), dtype=float), points.shape)
        curves.append((key, edges, sampled, points, density))
    return curves
