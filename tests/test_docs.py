"""The Python examples of docs/scenes.md run as written (README.md's are doctests)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pictures  # docs/_ext (pytest's pythonpath): the pictures the build makes
import pytest
import sympy as sp

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


GUIDE = DOCS.parent / "guide"
TUTORIAL = GUIDE / "tutorial-scene.md"
# the pages whose `rigidimpact` commands run here as the page shows them, each compared
# with the output block that follows it
COMMAND_PAGES = [GUIDE / "tutorial-scene.md", GUIDE / "tutorial-random.md",
                 GUIDE / "several-contacts.md",
                 GUIDE / "tutorial-3d.md", GUIDE / "random.md", GUIDE / "friction.md",
                 GUIDE / "three-dimensions.md", DOCS.parent / "three-d.md",
                 GUIDE / "export-code.md"]
SECONDS = re.compile(r"\b\d+\.\d+ s\b")  # what a run took: differs from run to run


def _shown_commands(page: Path) -> list[tuple[list[str], str | None]]:
    """Each `rigidimpact ...` command of the page's ```sh blocks, as its arguments, with
    the ```text block right after its block (for the block's last command) or None."""
    import shlex

    found: list[tuple[list[str], str | None]] = []
    pattern = re.compile(r"```sh\n(.*?)```\n(?:\n?```text\n(.*?)```)?", re.S)
    for block, shown in pattern.findall(page.read_text(encoding="utf-8")):
        words = [shlex.split(line, comments=True) for line in block.splitlines()]
        commands = [w[1:] for w in words if w and w[0].endswith("rigidimpact")]
        found += [(argv, shown if k == len(commands) - 1 and shown else None)
                  for k, argv in enumerate(commands)]
    return found


def _shows(printed: str, shown: str) -> bool:
    """Whether `printed` holds every line `shown` holds, in order, from its first line to
    its last, a line "..." standing for any run of lines left out (and the shown lines
    after it starting anywhere); the seconds a step took are not compared."""
    lines = SECONDS.sub("#.## s", printed).splitlines()
    at = 0
    skip = False
    for line in SECONDS.sub("#.## s", shown).splitlines():
        if line == "...":
            skip = True
            continue
        if skip:
            if line not in lines[at:]:
                return False
            at = lines.index(line, at)
        elif at >= len(lines) or lines[at] != line:
            return False
        at += 1
        skip = False
    return skip or at == len(lines)


def test_the_guide_teaches_without_a_diary():
    # the user guide names no file of the sources or the tests (the architecture page
    # may), no date and no medians of timed runs: measured figures are on the
    # performance page, written by the benchmark (a cited paper's year is no date)
    for page in sorted(GUIDE.glob("*.md")):
        if page.name == "architecture.md":
            continue
        text = page.read_text(encoding="utf-8")
        for pattern in (r"\b(?:tests|src)/\w", r"\b20\d\d-\d\d-\d\d\b", r"\bmedian"):
            found = re.search(pattern, text)
            assert found is None, (page.name, found.group(0) if found else None)


def test_the_pages_that_show_commands_show_some_with_their_output():
    for page in COMMAND_PAGES:
        commands = _shown_commands(page)
        assert any(shown for _, shown in commands), page.name


@pytest.mark.parametrize(("page", "argv", "shown"), [
    pytest.param(page, argv, shown, id=f"{page.name}: rigidimpact {' '.join(argv)}")
    for page in COMMAND_PAGES for argv, shown in _shown_commands(page)])
def test_a_pages_command_prints_what_the_page_shows(page, argv, shown, capsys,
                                                    reader_folder):
    """What a terminal shows: the standard error's warnings, then the standard output."""
    from rigidimpact.cli import main

    assert main(argv) == 0, (page.name, argv)
    printed = capsys.readouterr()
    if shown is not None:
        assert _shows(printed.err + printed.out, shown), (page.name, argv, printed.out)


def test_the_shown_output_may_leave_lines_out_but_not_change_them():
    assert _shows("a\nb\nc\nd\n", "a\n...\nc\n...\n")
    assert _shows("a\nb\nc\n", "a\nb\nc\n")
    assert _shows("took 0.12 s\n", "took 3.40 s\n")  # the seconds aside
    assert not _shows("a\nb\nc\n", "a\nb\n")  # the end is shown or marked left out
    assert not _shows("a\nb\nc\n", "a\nc\n")
    assert not _shows("a\nb\nc\n", "a\n...\nx\n")


PICTURE_PAGES = sorted(p for p in [*GUIDE.glob("*.md"), DOCS.parent / "three-d.md"]
                       if "](/_generated/" in p.read_text(encoding="utf-8"))


@pytest.mark.parametrize("page", PICTURE_PAGES, ids=lambda p: p.name)
def test_each_picture_a_page_shows_is_made_by_the_command_it_shows(page):
    # the build makes /_generated/NAME from PICTURES[NAME]: the command the page shows
    # just before the picture, with its file named NAME
    import shlex

    text = page.read_text(encoding="utf-8")
    shown = re.findall(r"```sh\n((?:rigidimpact|python) [^\n]*)\n```\n\n!\[[^\]]+\]"
                       r"\(/_generated/([^)]+)\)", text)
    assert len(shown) == text.count("](/_generated/"), page.name
    for command, name in shown:
        argv = [("OUT" if word == name else word) for word in shlex.split(command)[1:]]
        assert pictures.PICTURES.get(name) == argv, (name, command)


def test_your_own_scene_restrikes_when_the_hand_derivation_says(tmp_path):
    # by hand (the page): J = (1 + e) v / (1/m + 1/M + d^2 / (M l^2 / 12)) = 4/5, so the
    # puck keeps 1/5, the rod's centre 2/5 and its spin 6/5; seen from the rod's centre
    # the puck is at (-t/5, -1/4) and the rod points along (-sin 6t/5, cos 6t/5): they
    # meet where 0.25 sin(1.2 t) + 0.2 t cos(1.2 t) = 0 (first positive root)
    import mpmath

    import rigidimpact as ri

    (tmp_path / "s.toml").write_text(pictures.input_text("my-scene.toml"))
    scene = ri.load_any(str(tmp_path / "s.toml"))
    exact = scene.derivation().evaluate(scene.values, exact=True).exact
    assert [exact[k] for k in ("puck.vx", "rod.vx", "rod.omega", "impulse")] == \
        [sp.Rational(1, 5), sp.Rational(2, 5), sp.Rational(6, 5), sp.Rational(4, 5)]
    root = mpmath.findroot(lambda t: 0.25 * mpmath.sin(1.2 * t) + 0.2 * t * mpmath.cos(1.2 * t),
                           1.8)
    grid = [k / 1000 for k in range(1, 1812)]  # no earlier root: the sign stays
    assert all(0.25 * math.sin(1.2 * t) + 0.2 * t * math.cos(1.2 * t) > 0 for t in grid)
    events = ri.run(scene).events
    assert [e["kind"] for e in events] == ["impact", "restrike", "end"]
    assert events[1]["t"] == pytest.approx(float(root), rel=1e-12)


def test_the_random_tutorial_shows_the_shipped_scene_whole():
    page = (DOCS.parent / "guide" / "tutorial-random.md").read_text(encoding="utf-8")
    (toml,) = re.findall(r"```toml\n(.*?)```", page, re.S)
    assert toml == (DOCS.parents[1] / "derivations" / "random-barbell.toml").read_text()


def test_the_3d_tutorial_shows_the_shipped_scene_as_it_is():
    text = (GUIDE / "tutorial-3d.md").read_text(encoding="utf-8")
    scene = (DOCS.parents[1] / "derivations" / "draw-shot.toml").read_text(encoding="utf-8")
    blocks = re.findall(r"```toml\n(.*?)```", text, re.S)
    assert len(blocks) >= 5
    for block in blocks:
        assert block in scene, block
