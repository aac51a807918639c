"""The documentation site: `make docs` builds it into build/docs (warnings are errors).

Sphinx with MyST (Markdown pages, the README's own syntax) and myst-nb (the notebooks,
rendered from their stored outputs: nbval already re-executes them in `make test`);
autodoc with napoleon for the API reference (the docstrings are in NumPy's style); the
gallery is written from derivations/*.toml by docs/_ext/gallery.py at each build; MathJax
is served from the site itself (sphinx-mathjax-offline), so the site reads offline.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import rigidimpact  # noqa: E402

project = "rigidimpact"
author = "the rigidimpact authors"
copyright = "2026, the rigidimpact authors"  # noqa: A001 - Sphinx's name
release = version = rigidimpact.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.viewcode",
    "sphinx-mathjax-offline",  # its module name has hyphens
    "gallery",  # writes the gallery's examples, before sphinx-gallery reads them
    "sphinx_gallery.gen_gallery",
    "pictures",
    "live_pages",  # the live pages (rigidimpact export --to html), copied to live/
]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb", ".rst": "restructuredtext"}
# the gallery's notebooks are downloads, not pages
exclude_patterns = ["_build", "**/.ipynb_checkpoints", "_generated", "_gallery_src",
                    "gallery/**.ipynb", "gallery/**.py"]
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
nb_execution_mode = "off"  # the stored outputs; nbval runs the notebooks
nb_render_markdown_format = "myst"
autodoc_member_order = "bysource"
autodoc_typehints = "none"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
# ref.python: a field named alike in two classes (Contact.law, Equation.law) is ambiguous
# config.cache: the gallery's image scraper is a function, which Sphinx cannot pickle
suppress_warnings = ["config.cache", "myst.header", "mystnb.unknown_mime_type",
                     "misc.highlighting_failure", "ref.python"]

import gallery  # noqa: E402 - docs/_ext, on the path above

sphinx_gallery_conf = {
    "examples_dirs": "_gallery_src",
    "gallery_dirs": "gallery",
    "filename_pattern": r"\.py$",  # every example runs
    "subsection_order": [f"_gallery_src/{folder}" for folder, *_ in gallery.TOPICS],
    "within_subsection_order": gallery.TopicOrder,
    "image_scrapers": (gallery.scraper,),
    "remove_config_comments": True,
    "download_all_examples": False,
    "min_reported_time": 10**9,  # no running times on the pages
    "write_computation_times": False,
    "show_signature": False,
    "abort_on_example_error": True,
}

html_theme = "furo"
html_title = f"rigidimpact {release}"
html_static_path = ["_static"]
html_extra_path = ["_live"]  # the live pages, written by docs/_ext/live_pages.py
(HERE / "_live").mkdir(exist_ok=True)  # filled at builder-inited, checked before it
html_js_files = ["search-math.js"]  # the search's snippets typeset, not raw TeX
html_css_files = ["wide.css"]  # wide formulas and outputs scroll, never cut off
# notebook 02's slider is shown as its stored picture: no widget script from the network
nb_ipywidgets_js: dict[str, dict[str, str]] = {}
