"""Write the site's Performance page from what `make bench` just measured.

Reads the bench's own outputs (``bench.md`` and ``accuracy-vs-time.png`` from
``rigidimpact bench --out DIR``, and the JSON of
``derivations/beside_pinocchio.py --kernel N --json`` when given) and writes
``docs/performance.md`` and ``docs/images/accuracy-vs-time.png``: each table and figure
under the command that measured it. Nothing on that page is typed by hand.

Run: ``python tools/performance_page.py BENCH_DIR COMMAND [PINOCCHIO_JSON PINOCCHIO_COMMAND]``
(`make bench` does).
"""

from __future__ import annotations

import json
import platform
import shutil
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def _machine() -> str:
    import os

    return f"{os.cpu_count()} cores, Python {platform.python_version()}, NumPy {np.__version__}"


def pinocchio_lines(found: list[dict], command: str) -> list[str]:
    """The impact maps beside Pinocchio, per state, as a table (with the map exported as
    C, compiled and called in a loop, where the run measured it)."""
    in_c = all("C per state" in row for row in found)
    lines = ["## Impact maps beside Pinocchio", "",
             f"Measured by `{command}`: the compiled map over many states at once against "
             "Pinocchio's `impulseDynamics` called once a state from Python"
             + ("; and the same map exported as C (`impact_map_code`), compiled with "
                "`gcc -O2` and called in a loop over the states, from a shared library"
                if in_c else "") + ".", "",
             "| system | rigidimpact's kernel, per state (s) | "
             + ("the map in C, per state (s) | " if in_c else "")
             + "Pinocchio, per state (s) | largest difference |",
             "|---|---|---|---|" + ("---|" if in_c else "")]
    for row in found:
        gap = max(row["largest difference"], row.get("C against pinocchio", 0.0))
        lines.append(f"| {row['system']} ({row['states']:,} states) | "
                     f"{row['kernel per state']:.3g} | "
                     + (f"{row['C per state']:.3g} | " if in_c else "")
                     + f"{row['pinocchio per state']:.3g} | {gap:.2g} |")
    return lines + [""]


def write(bench_dir: Path, command: str, pinocchio: Path | None = None,
          pinocchio_command: str = "") -> Path:
    images = ROOT / "docs" / "images"
    images.mkdir(exist_ok=True)
    shutil.copyfile(bench_dir / "accuracy-vs-time.png", images / "accuracy-vs-time.png")
    body = (bench_dir / "bench.md").read_text().strip()
    lines = ["# Performance", "",
             "What accuracy costs in time, and what each method costs beside its peers. "
             "Every figure on this page was measured by the command shown with it, on "
             f"one machine ({_machine()}), and written here by the benchmark itself: "
             "`make bench` runs them all again and rewrites this page, so run it to "
             "measure yours. Ratios measured side by side travel between machines better "
             "than seconds do.", "",
             "## Accuracy against time", "",
             f"Measured by `{command}`.", "",
             "![Error against time for each method on the collision, the re-strike and the "
             "compliant integration: each method's settings as points, log axes, the front "
             "of the best trade-offs marked](images/accuracy-vs-time.png)", "",
             body, ""]
    if pinocchio is not None and pinocchio.exists():
        lines += pinocchio_lines(json.loads(pinocchio.read_text()), pinocchio_command)
    lines += ["## Several contacts at scale", "",
              "The rules over thousands of contacts are measured by "
              "`rigidimpact bench --family contacts`: [the measured run](bench-contacts.md).",
              ""]
    page = ROOT / "docs" / "performance.md"
    page.write_text("\n".join(lines))
    return page


if __name__ == "__main__":
    args = sys.argv[1:]
    print(write(Path(args[0]), args[1], Path(args[2]) if len(args) > 2 else None,
                args[3] if len(args) > 3 else ""))
