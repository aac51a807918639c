"""The documentation site as a reader gets it: built by `make docs` (which CI runs before
these tests), read offline, its math typeset by MathJax in a real browser (headless
Chromium), every shipped scene in the gallery, every notebook rendered with its figures.

Where the site or Chromium is missing these tests skip, unless RIGIDIMPACT_SITE=1 (CI):
then a missing site or browser is a failure, not a skip.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "build" / "docs"
REQUIRED = os.environ.get("RIGIDIMPACT_SITE") == "1"


def _need(condition: bool, why: str) -> None:
    if not condition:
        if REQUIRED:
            pytest.fail(why)
        pytest.skip(why)


@pytest.fixture(scope="module")
def site() -> Path:
    _need((SITE / "index.html").exists(), "no site: run make docs first")
    return SITE


def _browser() -> str:
    found = shutil.which("chromium") or shutil.which("chromium-browser")
    _need(found is not None, "no Chromium (apt-get install chromium)")
    return found  # type: ignore[return-value]


def _rendered(page: Path) -> str:
    """The page's DOM after its scripts ran (MathJax typesets on load)."""
    run = subprocess.run([_browser(), "--headless", "--no-sandbox", "--disable-gpu",
                          "--virtual-time-budget=15000", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout


def _gallery_page(site: Path, stem: str) -> Path:
    found = list((site / "gallery").glob(f"*/{stem}.html"))
    assert len(found) == 1, (stem, found)
    return found[0]


def test_every_shipped_scene_has_a_gallery_page_with_its_figure(site):
    scenes = sorted(p.stem for p in (ROOT / "derivations").glob("*.toml"))
    assert scenes
    index = (site / "gallery" / "index.html").read_text()
    for stem in scenes:
        page = _gallery_page(site, stem).read_text()
        assert "The equations solved" in page, stem
        assert "The scene file" in page, stem
        assert re.search(rf'<img alt="[^"]{{20,}}" [^>]*src="[^"]*sphx_glr_{re.escape(stem)}_001'
                         r'\.png"', page), stem
        # its thumbnail in the grid, saying what it shows
        assert re.search(rf'<img alt="[^"]{{20,}}" src="[^"]*sphx_glr_{re.escape(stem)}_thumb',
                         index), stem


def test_the_scenes_that_move_are_animated_in_the_gallery(site):
    import PIL.Image

    moving = ["restrike", "newtons-cradle", "superball-under-table", "stun-shot",
              "double-pendulum-wall"]
    for stem in moving:
        page = _gallery_page(site, stem)
        gifs = re.findall(r'src="([^"]+\.gif)"', page.read_text())
        assert gifs, stem
        with PIL.Image.open(page.parent / gifs[0]) as animation:
            assert animation.n_frames > 10, stem


def test_every_notebook_is_rendered_with_its_stored_figures(site):
    for notebook in sorted((ROOT / "notebooks").glob("*.ipynb")):
        page = site / "notebooks" / f"{notebook.stem}.html"
        assert page.exists(), notebook.name
        stored = notebook.read_text().count('"image/png"')
        shown = len(re.findall(r'<img [^>]*src="[^"]*_images/', page.read_text()))
        assert shown >= min(stored, 1), (notebook.name, stored, shown)


def test_the_site_reads_offline(site):
    # no script, style sheet or image is fetched from the network
    for page in site.rglob("*.html"):
        text = page.read_text()
        remote = re.findall(r'<(?:script|link|img)[^>]*(?:src|href)="(https?:[^"]+)"', text)
        assert not remote, (page.relative_to(site), remote[:3])
        for local in re.findall(r'<(?:script|img)[^>]*src="([^"#?]+)', text):
            assert (page.parent / local).exists(), (page.relative_to(site), local)


@pytest.mark.parametrize("page, formulas", [
    ("index.html", False), ("gallery/paper/barbell.html", True),
    ("gallery/supports-and-friction/rod-rough-floor.html", True),
    ("notebooks/01-ball-meets-barbell.html", True),
    ("notebooks/05-two-bodies.html", True),
    ("notebooks/16-random-restitution.html", True), ("guide/friction.html", False),
    ("api.html", False)])
def test_math_is_typeset_in_a_real_browser(site, page, formulas):
    dom = _rendered(site / page)
    assert (dom.count("<mjx-container") > 0) == formulas, page
    assert "<mjx-merror" not in dom, page  # a formula MathJax could not read
    assert "rigidimpact" in dom


def test_the_site_says_which_version_it_was_built_from(site):
    import rigidimpact

    assert f"rigidimpact {rigidimpact.__version__}" in (site / "index.html").read_text()


def test_a_reader_in_chromium_finds_the_math_the_figures_and_the_search(site):
    # served from 127.0.0.1 with every other host unreachable: the front page, each
    # tutorial, guide pages, a notebook, the gallery's grid and scene pages typeset their
    # math, load every image (each saying what it shows), animate every GIF, cut no wide
    # formula, raise no script error and ask no other host; the search finds "critical
    # angle" with its snippets typeset; each page's screenshot is saved under
    # build/docs/screens/
    import sys

    _browser()
    sys.path.insert(0, str(ROOT / "docs"))
    try:
        import browse
    finally:
        sys.path.remove(str(ROOT / "docs"))
    found = browse.browse(site)
    assert browse.problems(found) == []
    assert found["notebooks/01-ball-meets-barbell.html"]["typeset"] > 0
    assert found["gallery/paper/restrike.html"]["typeset"] > 0
    assert found["gallery/paper/restrike.html"]["frames"]  # its animation was decoded
    assert found["index.html"]["images"] > 0
    for page, result in found.items():
        if "screenshot" in result:
            assert (ROOT / result["screenshot"]).stat().st_size > 10_000, page
