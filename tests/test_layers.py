"""The package's modules import one another one way: no circles, and no project imports
hidden inside functions (outside the command line, which loads lazily for start-up)."""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "rigidimpact"


def _module(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> tuple[set[str], list[int]]:
    """The project modules a file imports at its top, and the lines of any import of the
    project made inside a function or class."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top: set[str] = set()
    inner: list[int] = []
    for node in ast.walk(tree):
        if not isinstance(node, (ast.Import, ast.ImportFrom)):
            continue
        names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
            [node.module or ""] + [f"{node.module}.{a.name}" for a in node.names]
        project = [n for n in names if n.startswith("rigidimpact")]
        if not project:
            continue
        if node.col_offset > 0:
            inner.append(node.lineno)
        else:
            top |= set(project)
    return top, inner


def _graph() -> dict[str, set[str]]:
    modules = {_module(p): p for p in PACKAGE.rglob("*.py")}
    graph = {}
    for name, path in modules.items():
        if name == "rigidimpact":  # the package's own names, loaded on first use
            continue
        top, _ = _imports(path)
        graph[name] = {m for m in top if m in modules and m not in (name, "rigidimpact")}
    return graph


def test_no_import_circles():
    graph = _graph()
    state: dict[str, int] = {}
    path: list[str] = []

    def visit(node: str) -> None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                raise AssertionError("import circle: " + " -> ".join(
                    path[path.index(nxt):] + [nxt]))
            if nxt not in state:
                visit(nxt)
        path.pop()
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node)


def test_no_project_imports_inside_functions():
    hidden = {}
    for path in PACKAGE.rglob("*.py"):
        if path.name == "__init__.py" or path.parent.name == "cli":
            continue  # the command line loads lazily, for start-up
        _, inner = _imports(path)
        if inner:
            hidden[str(path.relative_to(SRC))] = inner
    assert hidden == {}


def test_the_checker_sees_a_circle(tmp_path, monkeypatch):
    # the test above can fail: two modules that import each other are caught
    package = tmp_path / "rigidimpact"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("from rigidimpact import b\n")
    (package / "b.py").write_text("from rigidimpact.a import x\n")
    monkeypatch.setattr(__import__(__name__), "SRC", tmp_path)
    monkeypatch.setattr(__import__(__name__), "PACKAGE", package)
    try:
        test_no_import_circles()
    except AssertionError as exc:
        assert "rigidimpact.a -> rigidimpact.b -> rigidimpact.a" in str(exc)
    else:
        raise AssertionError("the circle was not seen")
