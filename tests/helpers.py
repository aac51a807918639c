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
