"""The main job (`make run`): derive and verify the paper's results; write LaTeX, the PDF
where pdflatex exists, a verification table and the figures into one folder.

Run: python derivations/run_all.py --out build
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import section1_barbell  # noqa: E402
import section2_implications  # noqa: E402
import section3_two_bodies  # noqa: E402

import rigidimpact as ri  # noqa: E402
from rigidimpact import latex, plots, restrike  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="build", type=Path)
    out = parser.parse_args(argv).out
    out.mkdir(parents=True, exist_ok=True)

    for section in (section1_barbell, section2_implications, section3_two_bodies):
        section.main()
        print()

    checks = ri.run_checks()
    failed = [c for c in checks if c.status != "pass"]
    rows = ["| check | paper | status | seconds |", "|---|---|---|---|"]
    rows += [f"| {c.id} | {c.paper} | {c.status} | {c.seconds:.2f} |" for c in checks]
    (out / "verification.md").write_text("\n".join(rows) + "\n", encoding="utf-8")
    (out / "verification.json").write_text(json.dumps(
        [{"id": c.id, "paper": c.paper, "status": c.status, "detail": c.detail}
         for c in checks], indent=2) + "\n", encoding="utf-8")
    print(f"verification: {len(checks) - len(failed)} passed, {len(failed)} failed "
          f"-> {out / 'verification.md'}")

    derivations = [ri.derive(name) for name in ri.PROBLEMS]
    derivations += [ri.load_scene(p).derivation() for p in sorted(HERE.glob("*.toml"))]
    pdf = shutil.which("pdflatex") is not None
    written = latex.write_export(out / "latex", derivations, checks, pdf=pdf)
    print(f"LaTeX: {len(written)} files -> {out / 'latex'}"
          f"{'' if pdf else ' (no pdflatex here: no PDF)'}")

    figures = out / "figures"
    figures.mkdir(exist_ok=True)
    theta_c = float(restrike.critical_angle().theta_c)
    ten = math.radians(10.0)
    for name, make in (
        ("omega-vs-theta.png", plots.omega_vs_theta),
        ("energy-loss-vs-theta.png", plots.energy_loss_vs_theta),
        ("critical-angle.png", lambda: plots.critical_angle_graphical(theta_c)),
        ("restrike-map.png", lambda: plots.restrike_map(*restrike.restrike_map())),
        ("restrike-strobe.png", lambda: plots.strobe(
            restrike.strobe_frames(ten, 0.0, 1.0, 14),
            "e = 0, m = M, theta = 10 deg: from the impact to the re-strike by the B half")),
    ):
        make().savefig(figures / name)
        print(f"figure -> {figures / name}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
