"""The live pages: at each build, ``rigidimpact export --to html`` of the paper's three
problems and of every gallery scene with a closed form (one with symbols), written into
docs/_live/live/, which Sphinx copies to the site's live/ folder (html_extra_path). Each
is one self-contained file: the site's pages link to it or show it in a frame.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "_live"
PAPER = ["barbell", "sticking", "restrike"]  # "The paper, live": built-in or scene


def pages() -> dict[str, str]:
    """Each live page's file name and what it is made from (a built-in name or a scene)."""
    from gallery import TOPICS  # docs/_ext, on Sphinx's path

    from rigidimpact.outputs.code import program_of

    found = {"barbell.html": "barbell", "sticking.html": "sticking"}
    for _, _, _, stems in TOPICS:
        for stem in stems:
            scene = str(ROOT / "derivations" / f"{stem}.toml")
            if program_of(scene).names:  # a closed form over the scene's symbols
                found[f"scene-{stem}.html"] = scene
    return found


def write(app: Any = None) -> None:
    from rigidimpact.outputs.live import write_live

    folder = OUT / "live"
    folder.mkdir(parents=True, exist_ok=True)
    for name, target in pages().items():
        write_live(target, folder / name)


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", write)
    return {"parallel_read_safe": True}
