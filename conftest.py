"""Shared by every test, doctest and notebook check: figures do not outlive their test,
and the guide's pages run as a reader runs them."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pictures  # docs/_ext (pytest's pythonpath): the files the guide asks to save
import pytest

ROOT = Path(__file__).resolve().parent
GUIDE = ROOT / "docs" / "guide"


@pytest.fixture(autouse=True)
def _close_figures():
    """pyplot keeps every figure until it is closed; close them after each test."""
    yield
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        pyplot.close("all")


@pytest.fixture(autouse=True)
def _guide_in_a_folder_of_its_own(request: pytest.FixtureRequest):
    """A page of the guide runs from a folder of its own that holds the shipped scenes
    under ``derivations/``, so the files it writes (figures, animations, scenes of one's
    own) land there and not in the clone. (Here rather than in a conftest.py of the
    guide's folder: a second module named conftest would shadow the tests' own, which
    their modules import by that name.)"""
    if GUIDE not in Path(request.node.path).parents:
        yield
        return
    folder = request.getfixturevalue("tmp_path")
    (folder / "derivations").symlink_to(ROOT / "derivations")
    before = Path.cwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(before)


@pytest.fixture(autouse=True)
def _the_files_guide_pages_ask_to_save(request: pytest.FixtureRequest):
    """The scene a tutorial asks the reader to save, as ``SCENE`` in its doctests."""
    if GUIDE in Path(request.node.path).parents:
        namespace = request.getfixturevalue("doctest_namespace")
        namespace["SCENE"] = pictures.input_text("my-scene.toml")
    yield
