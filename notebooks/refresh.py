"""Re-execute notebooks in place (`make notebooks`), keeping them free of run-to-run noise.

Each notebook runs top to bottom in a fresh kernel from its own folder; timing metadata is
not recorded, so a refresh that changes nothing leaves no diff.

Run: python notebooks/refresh.py notebooks/*.ipynb
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient


def refresh(path: Path) -> float:
    """Execute one notebook in place; return the seconds it took."""
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
    start = time.perf_counter()
    NotebookClient(nb, timeout=120, kernel_name="python3", record_timing=False,
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = _coalesced(cell.outputs)
    nbformat.write(nb, path)
    return time.perf_counter() - start


def _coalesced(outputs: list) -> list:
    """Join consecutive pieces of one stream: how the kernel splits them depends on timing."""
    joined: list = []
    for output in outputs:
        if (output.output_type == "stream" and joined and joined[-1].output_type == "stream"
                and joined[-1].name == output.name):
            joined[-1].text += output.text
        else:
            joined.append(output)
    return joined


def main(paths: list[str]) -> int:
    for name in paths:
        print(f"{name}: {refresh(Path(name)):.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
