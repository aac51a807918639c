"""The guide's pictures, made by the build from the commands the pages show.

Each entry of :data:`PICTURES` names a file under ``docs/_generated/`` and the
``rigidimpact`` command (or a Python script under ``docs/figures/``) that writes it; a page
shows it as ``/_generated/NAME``. A picture is made again only when its command, the files
the command reads, or the package's source change (a key of their hashes is kept beside
it), so a rebuild with nothing changed makes none.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "_generated"

# name -> the command after `rigidimpact` (OUT stands for the file), or a script and its
# arguments; each page that shows a picture shows its command beside it
PICTURES: dict[str, list[str]] = {
    "gait.png": ["docs/figures/gait.py", "OUT"],
    "my-scene.png": ["simulate", "my-scene.toml", "--plot", "OUT"],
    "my-scene.gif": ["simulate", "my-scene.toml", "--animate", "OUT"],
    "random-barbell.png": ["derive", "derivations/random-barbell.toml", "--plot", "OUT"],
    "routh-rod-rough-floor.png": ["routh", "derivations/rod-rough-floor.toml", "--plot", "OUT"],
    "stun-shot.png": ["simulate", "derivations/stun-shot.toml", "--plot", "OUT"],
    "stun-shot.gif": ["simulate", "derivations/stun-shot.toml", "--animate", "OUT"],
    "draw-shot.png": ["simulate", "derivations/draw-shot.toml", "--plot", "OUT"],
    "draw-shot.gif": ["simulate", "derivations/draw-shot.toml", "--animate", "OUT"],
}
# files a command reads that are not in the repository: written from the page's own text
INPUTS: dict[str, str] = {"my-scene.toml": "docs/guide/tutorial-scene.md"}


def source_hash() -> str:
    """One hash of the package's source: a picture made by older code is made again."""
    digest = hashlib.sha256()
    for path in sorted((ROOT / "src" / "rigidimpact").rglob("*.py")):
        digest.update(path.read_bytes())
    return digest.hexdigest()


def _inputs(argv: list[str], scratch: Path) -> list[Path]:
    """The files `argv` reads, with pages' own scenes written into `scratch`."""
    found = []
    for word in argv:
        if word in INPUTS:
            found.append(scratch / word)
            (scratch / word).write_text(input_text(word))
        elif (ROOT / word).is_file():
            found.append(ROOT / word)
    return found


def block_after(text: str, marker: str, language: str = "toml") -> str:
    """The first ``language`` block of `text` after `marker`."""
    after = text.split(marker, 1)[1]
    return after.split(f"```{language}\n", 1)[1].split("```", 1)[0]


def input_text(name: str) -> str:
    """The file `name` of :data:`INPUTS` as its page gives it: the TOML block after the
    page's first mention of `name` in backquotes (where it asks the reader to save it)."""
    return block_after((ROOT / INPUTS[name]).read_text(), f"`{name}`")


def make_pictures(out: Path = OUT, names: list[str] | None = None) -> list[str]:
    """Make each picture whose key changed; the names made."""
    out.mkdir(exist_ok=True)
    scratch = out / "scratch"
    scratch.mkdir(exist_ok=True)
    keys_file = out / "keys.json"
    keys = json.loads(keys_file.read_text()) if keys_file.exists() else {}
    code = source_hash()
    made = []
    for name, argv in PICTURES.items():
        if names is not None and name not in names:
            continue
        digest = hashlib.sha256(json.dumps([argv, code]).encode())
        for path in _inputs(argv, scratch):
            digest.update(path.read_bytes())
        key = digest.hexdigest()
        target = out / name
        if keys.get(name) == key and target.exists():
            continue
        words = [str(target) if w == "OUT" else
                 str(scratch / w) if w in INPUTS else w for w in argv]
        command = ([sys.executable, *words] if words[0].endswith(".py") else
                   [sys.executable, "-m", "rigidimpact", *words])
        done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
        if done.returncode != 0 or not target.exists():
            raise RuntimeError(f"docs/_ext/pictures.py: {name}: {' '.join(argv)} failed:\n"
                               f"{done.stderr[-2000:]}")
        keys[name] = key
        keys_file.write_text(json.dumps(keys, indent=1, sort_keys=True))
        made.append(name)
    return made


def _on_init(app: Any) -> None:
    make_pictures()


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _on_init)
    return {"parallel_read_safe": True, "version": "1"}


if __name__ == "__main__":
    print(" ".join(make_pictures()) or "nothing to make")
