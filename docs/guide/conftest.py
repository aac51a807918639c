"""The guide's pages run as a reader runs them: from a folder of their own that holds the
shipped scenes under ``derivations/``, so the files a page writes (figures, animations,
scenes of one's own) land there and not in the clone."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def page_block(page: str, name: str, language: str = "toml") -> str:
    """The first ``language`` block after the line that names `name` on the guide's
    `page`: a file the page asks the reader to save."""
    text = (ROOT / "docs" / "guide" / page).read_text()
    after = text.split(f"`{name}`", 1)[1]
    return after.split(f"```{language}\n", 1)[1].split("```", 1)[0]


@pytest.fixture(autouse=True)
def _the_files_pages_ask_to_save(doctest_namespace):
    doctest_namespace["SCENE"] = page_block("tutorial-scene.md", "my-scene.toml")


@pytest.fixture(autouse=True)
def _in_a_folder_of_its_own(tmp_path: Path):
    (tmp_path / "derivations").symlink_to(ROOT / "derivations")
    before = Path.cwd()
    os.chdir(tmp_path)
    try:
        yield
    finally:
        os.chdir(before)
