"""A seeded random search over a bar striking a floor through 2 to 4 rough contacts with
random rational normals, under every restitution law and both rules (the family of the
scenes that once hung or crashed): each scene must give an answer that the independent
oracle (:mod:`oracle`) confirms, or one line with exit status 2, in seconds.

``python tests/rough_search.py COUNT [SEED]`` prints each scene's time and outcome and
the distribution of times.
"""

from __future__ import annotations

import contextlib
import io
import json
import random
import sys
import time
import tomllib
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import oracle  # noqa: E402
from oracle import mp  # noqa: E402

LAWS = ("newton", "poisson", "energetic")


def _q(rng: random.Random, low: int, high: int, denominator: int = 8) -> str:
    return str(Fraction(rng.randint(low, high), denominator))


def random_scene(rng: random.Random) -> str:
    """One scene's TOML text: a bar (at the origin) and 2 to 4 rough contacts."""
    k = rng.randint(2, 4)
    law = rng.choice(LAWS)
    rule = rng.choice(("simultaneous", "sequential"))
    lines = ['title = "random rough contacts"', "[[bodies]]", 'name = "bar"',
             'shape = "rigid"', f'mass = "{_q(rng, 4, 16)}"',
             f'inertia = "{_q(rng, 2, 16)}"', 'position = ["0", "0"]',
             f'velocity = ["{_q(rng, -8, 8)}", "{_q(rng, -16, -2)}"]',
             f'spin = "{_q(rng, -12, 12)}"', "[[bodies]]", 'name = "floor"',
             'shape = "fixed"']
    for i in range(k):
        normal = ("0", "0")
        while normal == ("0", "0"):
            normal = (_q(rng, -8, 8), _q(rng, -8, 0))
        lines += ["[[contacts]]", f'name = "c{i}"', 'bodies = ["bar", "floor"]',
                  f'point = ["{_q(rng, -16, 16)}", "{_q(rng, -8, 2)}"]',
                  f'normal = ["{normal[0]}", "{normal[1]}"]',
                  f'restitution = "{_q(rng, 0, 4, 4)}"', f'law = "{law}"',
                  'tangential = "coulomb"', f'friction = "{_q(rng, 0, 6, 4)}"']
    lines += ["[impact]", f'rule = "{rule}"']
    if rule == "sequential":
        order = [f"c{i}" for i in range(k)]
        rng.shuffle(order)
        lines.append("order = [" + ", ".join(f'"{x}"' for x in order) + "]")
    return "\n".join(lines) + "\n"


def run_one(text: str, folder: Path) -> tuple[int, str, float, dict | None]:
    """The command line on one scene: (exit status, standard error, seconds, JSON)."""
    from rigidimpact.cli import main

    path = folder / "scene.toml"
    path.write_text(text, encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(["evaluate", str(path), "--json"])
    seconds = time.perf_counter() - start
    return status, err.getvalue(), seconds, json.loads(out.getvalue()) if status == 0 else None


def disagreement(text: str) -> list[str]:
    """What the package's exact answer breaks by the oracle (empty: confirmed)."""
    import rigidimpact as ri

    data = tomllib.loads(text)
    outcomes = ri.parse_scene(text).outcomes()
    [solution] = outcomes
    results = solution.results()
    bar, touches = oracle.from_scene(data)

    def at(key):
        return mp.mpf(str(sp_number(results[key])))

    u = [at("bar.vx"), at("bar.vy"), at("bar.omega")]
    impulses = {t.name: (at(f"{t.name}.normal_impulse"), at(f"{t.name}.tangential_impulse"))
                for t in touches}
    scale = max(abs(x) for x in bar.u) + 1
    if data["impact"]["rule"] == "sequential":
        expected, _ = oracle.sequential(bar, touches, data["impact"]["order"])
    elif len(solution.acted) == 1:  # one contact acts: its own exact (Routh) impact
        [name] = solution.acted
        touch = next(t for t in touches if t.name == name)
        expected = oracle.kick(bar, bar.u, touch, *oracle.routh(bar, bar.u, touch))
        others = [t for t in touches if t.name != name]
        late = [t.name for t in others
                if oracle.dot(t.rows()[0], u) < -t.e * min(oracle.dot(t.rows()[0], bar.u), 0)
                - mp.mpf(10) ** -30 * scale]
        if late:
            return [f"{', '.join(late)} left approaching"]
    else:
        return oracle.violations(bar, touches, u, impulses)
    gap = max(abs(a - b) for a, b in zip(expected, u, strict=True))
    return [] if gap < mp.mpf(10) ** -30 * scale else [f"velocities differ by {gap}"]


def sp_number(x):
    return x.evalf(60)


def search(count: int, seed: int, folder: Path, verbose: bool = False) -> list[dict]:
    """Every scene of the search: its seed index, status, seconds and any problem."""
    rng = random.Random(seed)
    rows = []
    for index in range(count):
        text = random_scene(rng)
        status, err, seconds, _ = run_one(text, folder)
        problem = []
        if status == 0:
            try:
                problem = disagreement(text)
            except AssertionError as error:  # the oracle itself cannot follow the impact
                problem = [f"oracle: {error}"]
        elif status != 2 or err.count("\n") != 1:
            problem = [f"exit {status}: {err.strip()}"]
        row = {"index": index, "status": status, "seconds": seconds, "problem": problem,
               "text": text, "error": err.strip()}
        rows.append(row)
        if verbose:
            print(f"{index:4d} exit {status} {seconds:6.2f} s {'; '.join(problem)} "
                  f"{err.strip()[:100]}", flush=True)
    return rows


if __name__ == "__main__":
    import tempfile

    count = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 31
    with tempfile.TemporaryDirectory() as tmp:
        rows = search(count, seed, Path(tmp), verbose=True)
    times = sorted(r["seconds"] for r in rows)
    answered = sum(r["status"] == 0 for r in rows)
    print(f"{len(rows)} scenes (seed {seed}): {answered} answered, "
          f"{sum(r['status'] == 2 for r in rows)} refused in one line, "
          f"{sum(bool(r['problem']) for r in rows)} with a problem")
    for q in (0.5, 0.9, 0.99, 1.0):
        print(f"  {int(q * 100)}th percentile of time: "
              f"{times[min(len(times) - 1, int(q * len(times)))]:.2f} s")
