"""The Python examples of docs/scenes.md run as written (README.md's are doctests)."""

from __future__ import annotations

import math
import re
from pathlib import Path

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


TUTORIAL = DOCS.parent / "guide" / "tutorial-scene.md"


def _block_after(text: str, marker: str, language: str) -> str:
    return text.split(marker, 1)[1].split(f"```{language}\n", 1)[1].split("```", 1)[0]


def test_your_own_scene_prints_on_the_command_line_what_its_page_shows(tmp_path, capsys,
                                                                        monkeypatch):
    from rigidimpact.cli import main

    text = TUTORIAL.read_text()
    (tmp_path / "my-scene.toml").write_text(_block_after(text, "`my-scene.toml`", "toml"))
    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "my-scene.toml", "--exact"]) == 0
    shown = _block_after(text, "rigidimpact evaluate my-scene.toml --exact", "text")
    assert capsys.readouterr().out.strip() == shown.strip()


def test_your_own_scene_restrikes_when_the_hand_derivation_says(tmp_path):
    # by hand (the page): J = (1 + e) v / (1/m + 1/M + d^2 / (M l^2 / 12)) = 4/5, so the
    # puck keeps 1/5, the rod's centre 2/5 and its spin 6/5; seen from the rod's centre
    # the puck is at (-t/5, -1/4) and the rod points along (-sin 6t/5, cos 6t/5): they
    # meet where 0.25 sin(1.2 t) + 0.2 t cos(1.2 t) = 0 (first positive root)
    import mpmath

    import rigidimpact as ri

    text = TUTORIAL.read_text()
    (tmp_path / "s.toml").write_text(_block_after(text, "`my-scene.toml`", "toml"))
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


# guide pages whose shell commands run here as the page shows them, each compared with
# the output block that follows it
COMMAND_PAGES = ["guide/tutorial-random.md", "guide/random.md", "guide/friction.md"]
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


def _appears_in(shown: str, printed: str) -> bool:
    """Whether the page's output block is what was printed: its runs of lines between
    lines of ``...`` (lines left out) appear in the output in order, the seconds each
    step took aside."""
    printed = SECONDS.sub("#.## s", printed)
    at = 0
    for run in re.split(r"^\.\.\.\n", SECONDS.sub("#.## s", shown), flags=re.M):
        if not run.strip():
            continue
        at = printed.find(run, at)
        if at < 0:
            return False
        at += len(run)
    return True


def test_the_pages_that_show_commands_show_some():
    for name in COMMAND_PAGES:
        assert _shown_commands(DOCS.parent / name), name


@pytest.mark.parametrize(("name", "argv", "shown"), [
    pytest.param(name, argv, shown, id=f"{name}: rigidimpact {' '.join(argv)}")
    for name in COMMAND_PAGES for argv, shown in _shown_commands(DOCS.parent / name)])
def test_a_guide_pages_command_prints_what_the_page_shows(name, argv, shown, tmp_path,
                                                          monkeypatch, capsys):
    """Run from a folder of its own holding the shipped scenes under derivations/, as
    the guide's doctests run; what a terminal shows is the standard error's warnings
    and then the standard output."""
    from rigidimpact.cli import main

    (tmp_path / "derivations").symlink_to(DOCS.parents[1] / "derivations")
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 0, (name, argv)
    printed = capsys.readouterr()
    if shown is not None:
        assert _appears_in(shown, printed.err + printed.out), (name, argv, printed.out)


def test_the_random_tutorial_shows_the_shipped_scene_whole():
    page = (DOCS.parent / "guide" / "tutorial-random.md").read_text(encoding="utf-8")
    (toml,) = re.findall(r"```toml\n(.*?)```", page, re.S)
    assert toml == (DOCS.parents[1] / "derivations" / "random-barbell.toml").read_text()


# --- the shell sessions of the guide's pages: each command prints what its page shows ---

GUIDE = DOCS.parent / "guide"
SESSIONS = [GUIDE / "tutorial-3d.md", GUIDE / "three-dimensions.md", DOCS.parent / "three-d.md"]


def _sessions(page: Path) -> list[tuple[str, str]]:
    """Each ```sh block followed at once by a ```text block: (the command, its output)."""
    return re.findall(r"```sh\n(rigidimpact [^\n]*)\n```\n\n```text\n(.*?)```",
                      page.read_text(encoding="utf-8"), re.S)


def _shows(printed: str, shown: str) -> bool:
    """Whether `printed` holds every line `shown` holds, in order, a line "..." standing
    for any run of lines left out (and the shown lines after it starting anywhere)."""
    lines = printed.splitlines()
    at = 0
    skip = False
    for line in shown.splitlines():
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


@pytest.fixture
def _in_a_reader_folder(tmp_path, monkeypatch):
    """A folder of its own holding the shipped scenes, as the guide's pages run."""
    (tmp_path / "derivations").symlink_to(DOCS.parents[1] / "derivations")
    monkeypatch.chdir(tmp_path)


@pytest.mark.parametrize("page", SESSIONS, ids=lambda p: p.name)
def test_a_pages_shell_sessions_print_what_it_shows(page, capsys, _in_a_reader_folder):
    import shlex

    from rigidimpact.cli import main

    sessions = _sessions(page)
    assert sessions, page.name
    for command, shown in sessions:
        assert main(shlex.split(command)[1:]) == 0, command
        printed = capsys.readouterr().out
        assert _shows(printed, shown), (command, printed)


def test_the_shown_output_may_leave_lines_out_but_not_change_them():
    assert _shows("a\nb\nc\nd\n", "a\n...\nc\n...\n")
    assert _shows("a\nb\nc\n", "a\nb\nc\n")
    assert not _shows("a\nb\nc\n", "a\nb\n")  # the end is shown or marked left out
    assert not _shows("a\nb\nc\n", "a\nc\n")
    assert not _shows("a\nb\nc\n", "a\n...\nx\n")


def test_the_3d_tutorial_shows_the_shipped_scene_as_it_is():
    text = (GUIDE / "tutorial-3d.md").read_text(encoding="utf-8")
    scene = (DOCS.parents[1] / "derivations" / "draw-shot.toml").read_text(encoding="utf-8")
    blocks = re.findall(r"```toml\n(.*?)```", text, re.S)
    assert len(blocks) >= 5
    for block in blocks:
        assert block in scene, block


def _pictures() -> dict[str, list[str]]:
    import importlib.util

    path = DOCS.parent / "_ext" / "pictures.py"
    spec = importlib.util.spec_from_file_location("pictures", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.PICTURES


@pytest.mark.parametrize("page", SESSIONS, ids=lambda p: p.name)
def test_each_picture_a_page_shows_is_made_by_the_command_it_shows(page):
    # the build makes /_generated/NAME from PICTURES[NAME]: the command the page shows
    # just before the picture, with its file named NAME
    import shlex

    pictures = _pictures()
    text = page.read_text(encoding="utf-8")
    shown = re.findall(r"```sh\n(rigidimpact [^\n]*)\n```\n\n!\[[^\]]+\]\(/_generated/([^)]+)\)",
                       text)
    assert len(shown) == text.count("](/_generated/"), page.name
    for command, name in shown:
        argv = [("OUT" if word == name else word) for word in shlex.split(command)[1:]]
        assert pictures.get(name) == argv, (name, command)
