"""Read the built site in headless Chromium as a reader would, from a server on 127.0.0.1
with every other host unreachable: for each page, whether its math is typeset (MathJax's
elements present, no raw $...$ left), every image loaded (natural width above zero), no
script error; whether the search finds "critical angle"; and a screenshot of each page
under build/docs/screens/.

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
PAGES = ["index.html", "guide/friction.html", "notebooks/01-ball-meets-barbell.html",
         "gallery/index.html", "gallery/barbell.html"]
# every host but this machine resolves to nothing: a page that needs the network breaks
ISOLATED = "--host-resolver-rules=MAP * ~NOTFOUND , EXCLUDE 127.0.0.1"

PROBE = """<!DOCTYPE html><html><body><pre id="result">waiting</pre>
<iframe id="page" width="1280" height="2000"></iframe><script>
const errors = [];
const frame = document.getElementById("page");
frame.addEventListener("load", () => {
  const win = frame.contentWindow;
  win.addEventListener("error", (e) => errors.push(String(e.message || e)));
  setTimeout(() => {
    const doc = frame.contentDocument;
    const images = Array.from(doc.images);
    const text = doc.body ? doc.body.innerText : "";
    const found = doc.querySelectorAll("#search-results li, ul.search li").length;
    document.getElementById("result").textContent = JSON.stringify({
      typeset: doc.querySelectorAll("mjx-container").length,
      unreadable: doc.querySelectorAll("mjx-merror").length,
      raw_dollars: (text.match(/\\$[^$\\n]{1,80}\\$/g) || []).length,
      images: images.length,
      broken: images.filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.src),
      errors: errors, search_results: found});
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
            dom = _run(browser, "--virtual-time-budget=20000", "--dump-dom",
                       f"{base}/screens/probe.html#{base}/{page}")
            match = re.search(r'<pre id="result">(.*?)</pre>', dom, re.S)
            text = match.group(1) if match else "{}"
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
        if "failed" in r:
            wrong.append(f"{page}: the probe read nothing ({r['failed']})")
            continue
        if page.startswith("search"):
            if not r.get("search_results"):
                wrong.append("the search finds nothing for 'critical angle'")
            continue
        if r["unreadable"] or r["raw_dollars"]:
            wrong.append(f"{page}: {r['unreadable']} formulas MathJax could not read, "
                         f"{r['raw_dollars']} left as raw $...$")
        if r["broken"]:
            wrong.append(f"{page}: images not loaded: {r['broken'][:3]}")
        if r["errors"]:
            wrong.append(f"{page}: script errors: {r['errors'][:3]}")
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
