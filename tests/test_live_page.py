"""The live page in a real browser: headless Chromium, served from 127.0.0.1 with every
other host unreachable. Its sliders are set to seeded values, the numbers it computes
(with the JavaScript export, in the page) are read back and compared with Python's
``evaluate`` to 1e-12; the barbell's critical angle, found in the page, with
:func:`rigidimpact.critical_angle`; no script error, no request to another host; a
screenshot of each page under build/live/.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import agreement, export_reference, seeded_points
from rigidimpact.outputs.code import program_of
from rigidimpact.outputs.live import write_live

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "build" / "live"

PROBE = """<!DOCTYPE html><html><body><pre id="result">waiting</pre>
<iframe id="page" width="1280" height="1800"></iframe><script>
const ask = JSON.parse(decodeURIComponent(location.hash.slice(1)));
const frame = document.getElementById("page");
frame.addEventListener("load", () => {
  const win = frame.contentWindow, doc = frame.contentDocument;
  const errors = [];
  win.addEventListener("error", (e) => errors.push(String(e.message || e)));
  setTimeout(() => {
    const first = doc.querySelector("[data-key]");
    const rows = ask.points.map((point) => {
      for (const [name, x] of Object.entries(point)) {
        const input = doc.getElementById("value-" + name);
        input.value = x;
        input.dispatchEvent(new win.Event("input"));
      }
      const row = {};
      for (const el of doc.querySelectorAll("[data-key]")) {
        row[el.dataset.key] = el.dataset.value;
      }
      const strike = doc.getElementById("restrike");
      row.__critical = strike.dataset.critical || "";
      row.__refused = doc.getElementById("refused").textContent;
      return row;
    });
    const foreign = performance.getEntriesByType("resource").concat(
        win.performance.getEntriesByType("resource")).map((r) => r.name)
      .filter((n) => !n.startsWith(location.origin) && !n.startsWith("data:"));
    document.getElementById("result").textContent = JSON.stringify({
      rows: rows, errors: errors, foreign: foreign, started: first ? first.dataset.value : null,
      math: doc.querySelectorAll("math").length,
      sliders: doc.querySelectorAll("input[type=range]").length,
      drawn: doc.querySelectorAll("#after circle").length});
  }, 1500);
});
frame.src = ask.page;
</script></body></html>"""


def _browse():
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        pytest.skip("no Chromium here (Debian: apt-get install chromium); CI installs it")
    sys.path.insert(0, str(ROOT / "docs"))
    try:
        import browse
    finally:
        sys.path.remove(str(ROOT / "docs"))
    return browser, browse


def read_page(target: str, points: list[dict], folder: Path, shot: str) -> dict:
    """The page of `target` with each point set in turn: what it shows, as JSON."""
    browser, browse = _browse()
    name = "page.html"
    write_live(target, folder / name)
    (folder / "probe.html").write_text(PROBE)
    with browse.serving(folder) as base:
        ask = json.dumps({"page": f"{base}/{name}",
                          "points": [{k: repr(v) for k, v in p.items()} for p in points]})
        done = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu",
                               browse.ISOLATED, "--enable-logging=stderr", "--v=0",
                               "--virtual-time-budget=60000", "--dump-dom",
                               f"{base}/probe.html#{ask}"],
                              capture_output=True, text=True, timeout=300)
        SHOTS.mkdir(parents=True, exist_ok=True)
        subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu",
                        browse.ISOLATED, f"--screenshot={SHOTS / shot}",
                        "--window-size=1280,1500", "--virtual-time-budget=5000",
                        f"{base}/{name}"], capture_output=True, timeout=120)
    match = re.search(r'<pre id="result">(.*?)</pre>', done.stdout, re.S)
    assert match and match.group(1) != "waiting", done.stderr[-2000:]
    found = json.loads(match.group(1).replace("&quot;", '"').replace("&amp;", "&")
                       .replace("&lt;", "<").replace("&gt;", ">"))
    found["console"] = [line for line in done.stderr.splitlines()
                        if "CONSOLE" in line and "Uncaught" in line]
    return found


def _agrees(target: str, count: int, folder: Path, shot: str) -> tuple[dict, list]:
    program = program_of(target)
    points = seeded_points(program, count, 7, export_reference(target))
    found = read_page(target, [p for p, _, _ in points], folder, shot)
    assert found["errors"] == [] and found["console"] == [] and found["foreign"] == []
    assert found["sliders"] == len(program.names) and found["math"] >= len(program.outputs)
    for key in program.outputs:
        scale = max(abs(n[key]) for _, n, _ in points)
        for (point, numbers, _), row in zip(points, found["rows"], strict=True):
            assert row["__refused"] == ""
            shown = float(row[key]) if row[key] not in ("NaN", "") else math.nan
            assert agreement(shown, numbers[key], scale) <= 1e-12, (key, point, row[key])
    return found, points


def test_the_barbell_page_agrees_with_python_and_finds_the_critical_angle(tmp_path):
    from rigidimpact.analyses.restrike import critical_angle

    found, _ = _agrees("barbell", 12, tmp_path, "barbell.png")
    assert found["drawn"] > 0  # the bodies are drawn
    # the critical angle found in the page, at e = 0 (the paper's) and at e = 1/10, m/M = 4
    # (a window that opens above 0), against the certified one
    cases = [({"e": 0.0, "m": 1.0, "M": 1.0}, ("0", 1)), ({"e": 0.1, "m": 4.0, "M": 1.0},
                                                         ("0.1", 4))]
    base = {"L": 0.5, "theta": 0.3, "v_ix": 1.0}
    page = read_page("barbell", [base | v for v, _ in cases], tmp_path, "barbell-critical.png")
    for row, (_, (e, ratio)) in zip(page["rows"], cases, strict=True):
        wanted = float(critical_angle(e, ratio).theta_c)
        assert abs(float(row["__critical"]) - wanted) < 1e-9, (row["__critical"], wanted)


@pytest.mark.parametrize("target", ["derivations/rod-rough-floor.toml", "sticking"])
def test_a_scene_page_agrees_with_python(target, tmp_path):
    path = target if "/" not in target else str(ROOT / target)
    _agrees(path, 8, tmp_path, Path(target).stem + ".png")
