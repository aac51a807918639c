"""The compass gait walked ten steps from a little off its period-one gait: the stance
leg's angle against its rate, closing onto the limit cycle, each heel strike a jump.

Run: ``python docs/figures/gait.py FILE.png`` (the docs' build runs it).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "derivations"))
import compass_gait  # noqa: E402

import rigidimpact as ri  # noqa: E402


def main(target: str) -> None:
    kane, _, solution = compass_gait.heel_strike()
    found = compass_gait.gait(solution, kane)
    flow_kane, *_ = compass_gait.legs(floating=False)
    rhs = ri.mechanics.flow_of(flow_kane, compass_gait.VALUES)
    _, _, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    after = sp.lambdify([st, sw, w_st, w_sw], list(solution.speeds_after.xreplace(
        {ux: 0, uy: 0}).xreplace(compass_gait.VALUES)), "numpy", cse=True)
    biped = ri.mechanics.Hybrid(
        rhs, gap=lambda x: np.cos(x[0]) - np.cos(x[1]),
        jump=lambda x: np.array([x[1], x[0], after(*x)[3], after(*x)[2]]),
        guard=lambda x: x[1] > 0.05, fallen=lambda x: abs(x[0]) > 1.2)
    walk = biped.simulate(found.state + np.array([0.0, 0.0, 0.05, 0.0]), impacts=10)
    slope = float(compass_gait.VALUES[compass_gait.gamma])
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    for k, states in enumerate(walk.states):
        ax.plot(states[0] - slope, states[2], color="C0", lw=0.9,
                label="a step (stance leg)" if k == 0 else None)
    ax.plot([found.state[0] - slope], [found.state[2]], "o", color="C3",
            label="the gait just after heel strike")
    ax.set_xlabel("stance angle from the vertical (rad)")
    ax.set_ylabel("stance rate (rad/s)")
    ax.set_title("Compass gait: ten steps from a little off the gait onto its limit cycle")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    fig.tight_layout()
    fig.savefig(target)


if __name__ == "__main__":
    main(sys.argv[1])
