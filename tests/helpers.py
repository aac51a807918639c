"""Helpers the command-line tests share: a scene written to a file, a refusal checked."""

from __future__ import annotations

import json

from rigidimpact.cli import main
from rigidimpact.laws.contact import Contact


def refused(capsys, argv, needle=""):
    """main(argv) ends in exit 2 with exactly one line naming `needle`."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("rigidimpact: error: "), err
    assert needle in err, err
    return err


def evaluated(capsys, argv) -> dict:
    """main(argv + --json) succeeds; its JSON."""
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def scene_file(tmp_path, text: str, name: str = "scene.toml") -> str:
    """The scene text written to `name` in `tmp_path`; its path."""
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def touching(name: str, first: str, second: str, point, normal, restitution,
             law: str = "newton", friction=None) -> Contact:
    """One contact of several, stated in the order a test reads best: its name, the two
    bodies, where and along which normal, e, the restitution law and Coulomb's mu (None:
    smooth)."""
    return Contact(normal, restitution, "smooth" if friction is None else "coulomb", law,
                   name, friction, bodies=(first, second), point=point)


def hinged_rod_struck_twice(law: str = "newton", impact: str = "") -> str:
    """Two balls strike a rod hinged at its top (mass 8, length 1.2, inertia 0.96): one
    at its lower end (mass 2 at 5, e = 4/5), one 0.3 above it (mass 1 at 3, e = 1/2)."""
    return f"""
[[bodies]]
name = "low"
shape = "particle"
mass = "2"
position = ["0", "0"]
velocity = ["5", "0"]
[[bodies]]
name = "high"
shape = "particle"
mass = "1"
position = ["0", "3/10"]
velocity = ["3", "0"]
[[bodies]]
name = "rod"
shape = "rigid"
mass = "8"
inertia = "24/25"
position = ["0", "3/5"]
pivot = ["0", "6/5"]
[[contacts]]
name = "a"
bodies = ["low", "rod"]
point = ["0", "0"]
restitution = "4/5"
law = "{law}"
[[contacts]]
name = "b"
bodies = ["high", "rod"]
point = ["0", "3/10"]
restitution = "1/2"
law = "{law}"
{impact}"""


# ---- the code export and the live page (tests/test_export_code.py) ---------------------

def export_reference(target: str):
    """evaluate's numbers for `target` at given values, as ``rigidimpact evaluate`` gives
    them: a function of {name: float} (each read as the decimal its repr writes), which
    raises InputError where evaluate refuses the values. One derivation for all points."""
    import functools

    from rigidimpact.paper.problems import PROBLEMS, derive
    from rigidimpact.scenes.scene import Scene
    from rigidimpact.scenes.space import load_any

    defaults: dict = {}
    if target in PROBLEMS:
        ask = derive(target).evaluate
    else:
        scene = load_any(target)
        defaults = {s.name: v for s, v in scene.values.items()}  # as evaluate starts
        if isinstance(scene, Scene) and len(scene.contacts) == 1 and not scene.joints:
            ask = scene.derivation().evaluate  # what Scene.evaluate does, derived once
        else:
            ask = functools.partial(scene.evaluate, sources={})

    def at(point: dict) -> tuple[dict, str | None]:
        found = ask(defaults | {k: repr(float(v)) for k, v in point.items()})
        return dict(found.numbers), found.regime
    return at


def seeded_points(program, count: int, seed: int, reference) -> list[tuple[dict, dict, str]]:
    """`count` points drawn uniformly in the live page's slider ranges that evaluate
    accepts, each with evaluate's numbers and regime there."""
    import random

    from rigidimpact.errors import InputError
    from rigidimpact.outputs.live import slider_ranges

    ranges = slider_ranges(program)
    rng = random.Random(seed)
    found = []
    for _ in range(20 * count):
        point = {n: rng.uniform(*ranges[n]) for n in program.names}
        try:
            numbers, regime = reference(point)
        except InputError:
            continue
        found.append((point, numbers, regime))
        if len(found) == count or not program.names:
            break
    return found


OCTAVE_EXIT = "error: ignoring const execution_exception& while preparing to exit\n"


def run_export(lang: str, text: str, sets: list[dict], folder) -> list[dict]:
    """The exported file compiled (where the language compiles) and run once with every
    set of values (separated by --): each set's printed `key = value` lines as a dict."""
    import subprocess

    from rigidimpact.outputs.code import BUILD, SUFFIX

    build = BUILD[lang]
    src = folder / f"program{SUFFIX[lang]}"
    exe = folder / "program"
    src.write_text(text)
    if "compile" in build:
        command = [x.format(src=src, exe=exe) for x in build["compile"]]
        done = subprocess.run(command, capture_output=True, text=True, cwd=folder)
        assert done.returncode == 0, done.stderr[-3000:]
    args = []
    for i, point in enumerate(sets):
        args += (["--"] if i else []) + [f"{k}={v!r}" for k, v in point.items()]
    command = [x.format(src=src, exe=exe) for x in build["run"]] + args
    done = subprocess.run(command, capture_output=True, text=True, cwd=folder, timeout=600)
    # Debian's Octave 7.3 may say this at every exit, whatever the script did
    said = done.stderr.replace(OCTAVE_EXIT, "") if lang == "octave" else done.stderr
    assert done.returncode == 0 and not said.strip(), done.stderr[-3000:]
    blocks = done.stdout.strip("\n").split("\n\n")
    rows = []
    for block in blocks:
        row = {}
        for line in block.splitlines():
            key, _, value = line.partition(" = ")
            value = value.strip()
            try:
                row[key.strip()] = float(value)
            except ValueError:
                row[key.strip()] = value
        rows.append(row)
    return rows


def agreement(found: float, wanted: float, scale: float) -> float:
    """The error of `found`, relative to `wanted` (to the output's scale over the points
    where `wanted` is below it by twelve orders: a zero computed as 1e-17 agrees)."""
    import math

    if math.isnan(wanted) or math.isnan(found):
        return 0.0 if math.isnan(wanted) and math.isnan(found) else math.inf
    return abs(found - wanted) / max(abs(wanted), 1e-12 * scale, 1e-300)
