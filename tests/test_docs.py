"""The Python examples of docs/scenes.md run as written (README.md's are doctests)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs" / "scenes.md"
BLOCKS = [b for b in re.findall(r"```python\n(.*?)```", DOCS.read_text(), re.S)
          if b.startswith("import rigidimpact as ri")]


def test_the_scene_guide_has_python_examples():
    assert BLOCKS


@pytest.mark.parametrize("block", BLOCKS)
def test_a_python_example_of_the_scene_guide_runs(block):
    exec(compile(block, str(DOCS), "exec"), {})  # noqa: S102 - our own documentation


START = DOCS.parent / "getting-started.md"


def test_the_getting_started_page_runs_as_written():
    import rigidimpact as ri

    text = START.read_text()
    (python,) = re.findall(r"```python\n(.*?)```", text, re.S)
    exec(compile(python, str(START), "exec"), {})  # noqa: S102 - our own documentation
    (toml,) = re.findall(r"```toml\n(.*?)```", text, re.S)
    (solution,) = ri.parse_scene(toml).outcomes()
    assert solution.results()["rod.vy"] is not None


def test_the_notebooks_use_only_what_a_user_may_use():
    # a notebook is a user's first program: it imports the package's public names (and
    # its outputs, analyses and paper modules), never the internals of its core
    import json

    internal = re.compile(r"^\s*(from|import)\s+rigidimpact\.(laws|solve|model|symbolic)\b",
                          re.M)
    for notebook in sorted((DOCS.parents[1] / "notebooks").glob("*.ipynb")):
        cells = json.loads(notebook.read_text())["cells"]
        code = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
        assert not internal.search(code), (notebook.name, internal.search(code).group(0))
        # and shows at least one typeset result among its stored outputs
        typeset = [o for c in cells if c["cell_type"] == "code" for o in c["outputs"]
                   if "text/latex" in o.get("data", {})]
        assert typeset, f"{notebook.name} shows no typeset result"


def test_the_sphere_example_of_the_3d_guide_runs(capsys):
    page = DOCS.parent / "three-d.md"
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", page.read_text(), re.S)
                if "rigidimpact.simulate.sphere" in b]
    exec(compile(block, str(page), "exec"), {})  # noqa: S102 - our own documentation
    printed = capsys.readouterr().out.splitlines()
    assert printed[-1] == "1"  # the landing time the page states


def test_the_readme_is_a_front_door():
    """At most 120 lines; no benchmark history (medians, runs in turn, dates) and no paths
    into the sources or the tests; every link into the site resolves; the worked
    example's printed lines are what derive barbell prints."""
    import subprocess
    import sys

    root = DOCS.parents[1]
    text = (root / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 120
    for words in ("median", "in turn", "src/", "tests/", "2026", "2025"):
        assert words not in text, words
    for link in re.findall(r"\]\((docs/[^)#]+)\)", text):
        assert (root / link).exists(), link
    shown = re.search(r"```\n(With f = .*?)```", text, re.S).group(1)
    printed = subprocess.run([sys.executable, "-m", "rigidimpact", "derive", "barbell"],
                             capture_output=True, text=True, check=True).stdout
    assert shown in printed
