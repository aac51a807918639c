"""Read the built site in headless Chromium as a reader would, from a server on 127.0.0.1
with every other host unreachable: for each page, whether its math is typeset (MathJax's
elements present, no raw $...$ left, none MathJax could not read), every image loaded
(natural width above zero) with an alternative text that says something (not a file's
name), every animation more than one frame (its GIF decoded by the browser), no script
error and no request to another host; whether the search finds "critical angle" with
its snippets typeset, not raw TeX; and a screenshot of each page under
build/docs/screens/.

Run: ``python docs/browse.py [SITE]`` (`make docs` runs it where Chromium is installed);
prints one line a page and exits 1 if any check fails. tests/test_site.py calls
:func:`browse`.
"""

from __future__ import annotations

import functools
import http.server
import json
import re
import shutil
import subprocess
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

SITE = Path(__file__).resolve().parents[1] / "build" / "docs"
PAGES = ["index.html", "getting-started.html", "guide/tutorial-paper.html",
         "guide/tutorial-scene.html", "guide/tutorial-3d.html", "guide/tutorial-walker.html",
         "guide/tutorial-random.html", "guide/mechanics.html", "guide/friction.html",
         "guide/random.html", "guide/three-dimensions.html",
         "notebooks/01-ball-meets-barbell.html", "gallery/index.html",
         "gallery/paper/restrike.html", "gallery/several-contacts/newtons-cradle.html",
         "performance.html", "paper-live.html", "guide/export-code.html"]
# every host but this machine resolves to nothing: a page that needs the network breaks
ISOLATED = "--host-resolver-rules=MAP * ~NOTFOUND , EXCLUDE 127.0.0.1"

PROBE = """<!DOCTYPE html><html><body><pre id="result">waiting</pre>
<iframe id="page" width="1280" height="2000"></iframe><script>
const errors = [];
const frame = document.getElementById("page");
frame.addEventListener("load", () => {
  const win = frame.contentWindow;
  win.addEventListener("error", (e) => errors.push(String(e.message || e)));
  setTimeout(async () => {
    const doc = frame.contentDocument;
    const images = Array.from(doc.images);
    const text = doc.body ? doc.body.innerText : "";
    const hits = Array.from(doc.querySelectorAll("#search-results li, ul.search li"));
    const frames = {};
    for (const image of images.filter((i) => /\\.gif$/i.test(i.src))) {
      try {
        const data = await (await fetch(image.src)).arrayBuffer();
        const decoder = new ImageDecoder({data: data, type: "image/gif"});
        await decoder.tracks.ready;
        frames[image.src.split("/").pop()] = decoder.tracks.selectedTrack.frameCount;
      } catch (e) { frames[image.src.split("/").pop()] = "undecoded: " + e; }
    }
    const foreign = performance.getEntriesByType("resource").concat(
        win.performance.getEntriesByType("resource")).map((r) => r.name)
      .filter((n) => !n.startsWith(location.origin) && !n.startsWith("data:"));
    // a wide formula or output must scroll in its own box, never spill or be clipped
    const column = doc.querySelector("article") || doc.body;
    const edge = column.getBoundingClientRect().right + 1;
    const cut = Array.from(doc.querySelectorAll('mjx-container[display="true"], pre'))
      .filter((el) => {
        const style = win.getComputedStyle(el);
        const scrolls = ["auto", "scroll"].includes(style.overflowX);
        const wide = el.scrollWidth > el.clientWidth + 1;
        return (wide && !scrolls) || el.getBoundingClientRect().right > edge;
      }).map((el) => (el.innerText || el.textContent).slice(0, 60));
    document.getElementById("result").textContent = JSON.stringify({
      typeset: doc.querySelectorAll("mjx-container").length,
      unreadable: doc.querySelectorAll("mjx-merror").length,
      raw_dollars: (text.match(/\\$[^$\\n]{1,80}\\$/g) || []).length,
      images: images.length,
      broken: images.filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.src),
      unsaid: images.filter((i) => !i.alt || /^[0-9a-f]{16,}|\\.(png|gif|svg)$/i.test(i.alt)
                            || /^sphx_glr/.test(i.alt)).map((i) => i.src.split("/").pop()),
      frames: frames, foreign: foreign, cut: cut,
      errors: errors, search_results: hits.length,
      raw_tex_in_snippets: hits.filter((h) => /\\\\\\(|\\\\\\[/.test(h.innerText)).length});
  }, 6000);
});
frame.src = decodeURIComponent(location.hash.slice(1));
</script></body></html>"""


@contextmanager
def serving(site: Path) -> Iterator[str]:
    """The site over HTTP on 127.0.0.1 (a free port) while the block runs."""
    handler = functools.partial(_Quiet, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args: object) -> None:  # no line a request
        pass


def chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


def _run(browser: str, *args: str) -> str:
    done = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu",
                           "--hide-scrollbars", ISOLATED, *args],
                          capture_output=True, text=True, timeout=120)
    return done.stdout


def browse(site: Path = SITE, pages: list[str] = PAGES) -> dict[str, dict]:
    """Each page's findings (see the module's text), and the search's, by page."""
    browser = chromium()
    if browser is None:
        raise RuntimeError("no Chromium: apt-get install chromium")
    (site / "screens").mkdir(exist_ok=True)
    (site / "screens" / "probe.html").write_text(PROBE)
    found: dict[str, dict] = {}
    with serving(site) as base:
        for page in [*pages, "search.html?q=critical+angle"]:
            if not (site / page.split("?")[0]).exists():
                found[page] = {"missing": True}
                continue
            for _ in range(6):  # on a busy machine the probe may not have finished yet
                dom = _run(browser, "--virtual-time-budget=60000", "--dump-dom",
                           f"{base}/screens/probe.html#{base}/{page}")
                match = re.search(r'<pre id="result">(.*?)</pre>', dom, re.S)
                text = match.group(1) if match else "{}"
                if text != "waiting":
                    break
            result = json.loads(text.replace("&quot;", '"').replace("&amp;", "&")) \
                if text.startswith("{") else {"failed": text[:200]}
            if not page.startswith("search"):
                shot = site / "screens" / (page.replace("/", "-").replace(".html", ".png"))
                _run(browser, f"--screenshot={shot}", "--window-size=1280,1600",
                     "--virtual-time-budget=15000", f"{base}/{page}")
                result["screenshot"] = str(shot.relative_to(site.parent.parent))
            found[page] = result
    return found


def problems(found: dict[str, dict]) -> list[str]:
    """What the findings show wrong, one line each."""
    wrong = []
    for page, r in found.items():
        if r.get("missing"):
            wrong.append(f"{page}: no such page in the site")
            continue
        if "failed" in r:
            wrong.append(f"{page}: the probe read nothing ({r['failed']})")
            continue
        if page.startswith("search"):
            if not r.get("search_results"):
                wrong.append("the search finds nothing for 'critical angle'")
            if r.get("raw_tex_in_snippets"):
                wrong.append(f"the search shows raw TeX in {r['raw_tex_in_snippets']} "
                             "snippets")
            continue
        if r["unreadable"] or r["raw_dollars"]:
            wrong.append(f"{page}: {r['unreadable']} formulas MathJax could not read, "
                         f"{r['raw_dollars']} left as raw $...$")
        if r["broken"]:
            wrong.append(f"{page}: images not loaded: {r['broken'][:3]}")
        if r["errors"]:
            wrong.append(f"{page}: script errors: {r['errors'][:3]}")
        if r.get("unsaid"):
            wrong.append(f"{page}: images whose alternative text says nothing: "
                         f"{r['unsaid'][:3]}")
        still = {name: n for name, n in r.get("frames", {}).items()
                 if not (isinstance(n, int) and n > 1)}
        if still:
            wrong.append(f"{page}: animations that do not move: {still}")
        if r.get("cut"):
            wrong.append(f"{page}: wide formulas or outputs cut off: {r['cut'][:2]}")
        if r.get("foreign"):
            wrong.append(f"{page}: requests to another host: {r['foreign'][:3]}")
    return wrong


def main(argv: list[str] | None = None) -> int:
    site = Path(argv[0]) if argv else SITE
    if chromium() is None:
        print("docs/browse.py: no Chromium (apt-get install chromium): the site was not "
              "read in a browser")
        return 0
    found = browse(site)
    for page, r in found.items():
        print(f"{page}: " + ", ".join(f"{k} {v}" for k, v in r.items()))
    wrong = problems(found)
    for line in wrong:
        print(f"docs/browse.py: {line}", file=sys.stderr)
    return 1 if wrong else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
