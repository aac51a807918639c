"""`pip check`, with the one conflict the Makefile makes on purpose said in one line.

pooltool 0.6.0 pins a development build of panda3d that no registry serves, so `make
pooltool` installs it without its pins and a released panda3d beside it; and it asks for
an llvmlite older than the one numba 0.68 needs and a rich older than the one pinned in
constraints.txt. pip then reports those three pins as broken. Any other broken
requirement is an error: its lines are printed and the exit status is 1.
"""

from __future__ import annotations

import subprocess
import sys

KNOWN = ("pooltool-billiards 0.6.0 has requirement panda3d",
         "pooltool-billiards 0.6.0 has requirement llvmlite",
         "pooltool-billiards 0.6.0 has requirement rich")


def main() -> int:
    found = subprocess.run([sys.executable, "-m", "pip", "check"], capture_output=True,
                           text=True)
    lines = [line for line in found.stdout.splitlines()
             if line.strip() and not line.startswith("No broken requirements")]
    known = [line for line in lines if line.startswith(KNOWN)]
    other = [line for line in lines if line not in known]
    if known:
        print("pip check: pooltool 0.6.0's pins of a development panda3d and of older "
              "llvmlite and rich are not met on purpose (a released panda3d, numba's "
              "llvmlite and the pinned rich are installed; see the Makefile)")
    if other:
        print("pip check: broken requirements:", *other, sep="\n  ", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
