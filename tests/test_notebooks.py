"""The notebooks: stored executed, and nbval really catches a changed result."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = Path(__file__).resolve().parent.parent / "notebooks"
STORY = ["01-ball-meets-barbell", "02-energy-lost", "03-restrike", "04-clay-ball",
         "05-two-bodies", "06-discs", "07-spring-rod", "08-accuracy-and-time",
         "09-hard-cases", "10-supports", "11-friction", "12-several-contacts",
         "15-three-dimensions", "16-random-restitution", "17-after-the-impact-in-3d"]


@pytest.mark.parametrize("name", STORY)
def test_each_notebook_is_stored_executed_with_title_and_figure(name):
    nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    assert nb.cells[0].cell_type == "markdown" and nb.cells[0].source.startswith("# ")
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert all(c.execution_count is not None for c in code)
    assert not any(o.output_type == "error" for c in code for o in c.outputs)
    assert any("image/png" in o.get("data", {}) for c in code for o in c.outputs)


def test_nbval_fails_when_a_stored_result_differs(tmp_path):
    """A formula that changed would print a different result: nbval must catch it."""
    nb = nbformat.read(NOTEBOOKS / "02-energy-lost.ipynb", as_version=4)
    cell = next(c for c in nb.cells if c.cell_type == "code" and "Delta K / K_i" in c.source)
    stream = next(o for o in cell.outputs if o.output_type == "stream")
    assert "2*M*(1 - e)*(e + 1)" in stream.text
    stream.text = stream.text.replace("2*M*(1 - e)*(e + 1)", "2*M*(1 - e)*(e + 2)")
    copy = tmp_path / "changed.ipynb"
    nbformat.write(nb, copy)
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                             "--nbval", "--nbval-current-env", str(copy), "-o",
                             "addopts=", "-o", "testpaths="],
                            capture_output=True, text=True, cwd=NOTEBOOKS.parent, timeout=300)
    assert result.returncode == 1, result.stdout[-2000:]
    assert "1 failed" in result.stdout


def test_the_bench_notebook_reads_a_committed_run():
    report = json.loads((NOTEBOOKS / "data" / "bench.json").read_text())
    assert {"rows", "throughput", "auto_choice"} <= set(report)


def _imported_modules(name: str) -> set[str]:
    import ast

    nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    found = set()
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        for node in ast.walk(ast.parse(cell.source)):
            if isinstance(node, ast.Import):
                found |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module:
                found.add(node.module.split(".")[0])
    return found


@pytest.mark.parametrize("name", STORY)
def test_each_notebook_needs_only_the_package_and_its_notebook_extra(name):
    # a user installs `rigidimpact[notebooks]` and Jupyter: nothing from the developers'
    # extra may be imported (notebook 02's slider once needed ipywidgets from it)
    import tomllib

    project = tomllib.loads((NOTEBOOKS.parent / "pyproject.toml").read_text())["project"]
    installed = [d.split("==")[0] for d in
                 project["dependencies"] + project["optional-dependencies"]["notebooks"]]
    modules = {"ipykernel": {"ipykernel", "IPython"}}  # ipykernel brings IPython
    allowed = {"rigidimpact"} | set(sys.stdlib_module_names)
    for dist in installed:
        allowed |= modules.get(dist, {dist})
    assert _imported_modules(name) <= allowed
