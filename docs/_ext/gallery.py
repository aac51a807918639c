"""The gallery: one example for each shipped scene in derivations/, grouped by topic.

sphinx-gallery makes the gallery: it runs each example's Python once, keeps the pictures
and animations it wrote, makes the grid of thumbnails (one section a topic) and gives
each example a page with its code and pictures, downloadable as a script or a notebook.
It was chosen over hand-written HTML or a grid of myst-nb glue cells because it does all
of that itself, and because it runs an example again only when the example's text
changed, which is what makes a rebuild with nothing changed fast.

This module writes those examples at each build, before sphinx-gallery reads them: for a
scene, a short script (load it, run it, draw it, animate it where it moves) whose text
also holds the scene's setup, its equations and results typeset from the derivation, and
the scene file. A key of the package's source is part of each example's text, so new code
makes new pictures. A small image scraper hands sphinx-gallery the PNG and GIF files an
example wrote, each with an alternative text that says what it shows.
"""

from __future__ import annotations

import shutil
import textwrap
from pathlib import Path
from typing import Any

from pictures import source_hash  # docs/_ext, on Sphinx's path

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "derivations"
SOURCE = ROOT / "docs" / "_gallery_src"  # the examples written here (not kept in git)

# the topics, in the gallery's order: (folder, heading, one sentence, scenes)
TOPICS: list[tuple[str, str, str, list[str]]] = [
    ("paper", "The paper",
     "Mungan's ball and barbell: the bounce, the clay ball, the re-strike, and the same "
     "blow through a compliant contact or a springy rod.",
     ["barbell", "sticking", "restrike", "discs", "compliant", "spring-rod"]),
    ("supports-and-friction", "Supports and friction",
     "Hinges, pendulums and walls; rough contacts under Coulomb's law.",
     ["ballistic-pendulum", "swinging-pendulum", "hinged-rod", "bar-wall", "disc-rod",
      "rod-rough-floor", "sphere-oblique-flat"]),
    ("several-contacts", "Several contacts",
     "Impacts at two or more points at once, under the simultaneous and sequential rules.",
     ["newtons-cradle", "two-ball-drop", "rod-lands-flat", "rod-slides-flat",
      "rocking-block"]),
    ("linkages-and-walkers", "Linkages and walkers",
     "Jointed bodies and sympy.physics.mechanics systems: chains, pendulums, a heel strike.",
     ["hinged-chain", "swinging-rods", "double-pendulum-wall", "double-pendulum-wall-rough",
      "compass-gait-heel-strike"]),
    ("three-dimensions", "Three dimensions and billiards",
     "Bodies with spin in space: balls on a table and against cushions, a box on a corner.",
     ["stun-shot", "draw-shot", "superball-under-table", "spinning-ball-bounces",
      "spinning-ball-floor", "cushion-rebound", "box-corner-floor"]),
    ("random-inputs", "Random inputs",
     "An output's exact distribution when an input is random, beside its Monte Carlo.",
     ["random-barbell", "random-rod", "random-coin"]),
]

# alternative texts, by example and by the file it wrote, read by the scraper
ALT: dict[tuple[str, str], str] = {}


def _rst_text(text: str) -> str:
    """`text` shown as written in reST (a product's * is not emphasis)."""
    return "".join("\\" + c if c in "*_`|\\" else c for c in text)


def _comment(lines: list[str]) -> list[str]:
    """reST lines as a sphinx-gallery text block between code blocks."""
    return ["# %%"] + [("# " + line).rstrip() for line in lines]


def _math_lines(derivation: Any) -> list[str]:
    """The equations solved and the results, typeset."""
    from rigidimpact.outputs.latex import equation_latex, to_latex

    lines = ["The equations solved", "--------------------", ""]
    for eq in derivation.equations:
        lines += [f"{_rst_text(eq.label)}:", "", ".. math::", "",
                  f"   {equation_latex(eq)}", ""]
    outcomes = list(getattr(derivation, "outcomes", ()) or ())
    groups = [(o.label, o.results(), list(o.warnings)) for o in outcomes] or \
        [("Results", dict(derivation.results), list(derivation.warnings))]
    for label, results, warnings in groups:
        lines += [_rst_text(label), "-" * len(label), ""]
        for key, value in results.items():
            lines += [f"- ``{key}`` :math:`= {to_latex(value)}`"]
        lines += [f"- warning: {_rst_text(w)}" for w in warnings]
        lines.append("")
    return lines


def _what_is_drawn(scene: Any, moves: bool, spatial: bool) -> str:
    if spatial:
        return "the path of each ball's centre, seen from above and from the side"
    if moves:
        return "the paths of the bodies' points after the impact"
    return "the bodies at the impact, each with its velocity after"


def example(stem: str, source_key: str) -> tuple[str, dict[str, str]]:
    """The example's text for scene `stem`, and the alternative texts of its files."""
    from rigidimpact.scenes.space import SpaceScene, load_any
    from rigidimpact.simulate.planner import goes_past_impact

    path = SCENES / f"{stem}.toml"
    scene = load_any(str(path))
    derivation = scene.derivation()
    title = derivation.title or stem
    spatial = isinstance(scene, SpaceScene)
    moves = goes_past_impact(scene.simulate)
    random = bool(getattr(scene, "random", None))
    alt = {f"{stem}.png": f"{title}: {_what_is_drawn(scene, moves, spatial)}."}
    setup = [f"- {_rst_text(line)}" for line in derivation.setup]
    head = [title, "=" * len(title), ""] + setup + [
        "", f"The scene is ``derivations/{stem}.toml``, shown in full at the foot of the "
        "page. The same from the command line: ``rigidimpact derive`` prints the "
        "derivation, ``rigidimpact simulate --plot`` (and ``--animate``) draw the run.", ""]
    if derivation.symbols:  # a closed form over its symbols: a live page (live_pages.py)
        head += [f"`The live page <../../live/scene-{stem}.html>`_: a slider for each "
                 "symbol, every output computed in the browser (``rigidimpact export "
                 "--to html``).", ""]
    # the key, a reST comment (not shown), makes new code run the example again
    code = ['"""', *head, f".. made by the package source {source_key[:16]}", '"""', "",
            *_comment(["Load the scene, run it as its ``[simulate]`` table asks, and draw "
                       "the run:"]), "",
            "import rigidimpact as ri", "",
            f'scene = ri.load_any("{stem}.toml")', "outcome = ri.run(scene)",
            f'ri.draw(scene, outcome, "{stem}.png")', ""]
    if moves:
        alt[f"{stem}.gif"] = f"Animation: {title}, {_what_is_drawn(scene, True, spatial)}."
        code += [*_comment(["The motion after the impact:"]), "",
                 f'ri.animate(scene, outcome, "{stem}.gif")', ""]
    if random:
        alt[f"{stem}-density.png"] = (f"{title}: the exact density of each random output "
                                      "over the histogram of a seeded Monte Carlo.")
        code += [*_comment(["Each random output's exact density over the histogram of "
                            "its Monte Carlo, as ``rigidimpact derive --plot`` draws it:"]),
                 "", f'ri.draw_distributions(scene, "{stem}-density.png")', ""]
    scene_text = textwrap.indent(path.read_text().rstrip(), "   ")
    code += _comment(_math_lines(derivation) + [
        "The scene file", "--------------", "", ".. code-block:: toml", "",
        *scene_text.splitlines()])
    return "\n".join(code) + "\n", alt


def write_examples(source: Path = SOURCE) -> list[str]:
    """Write every scene's example under `source`, one folder a topic; a scene in no
    topic, or a topic's scene that is not shipped, is an error (the gallery shows every
    scene once)."""
    shipped = {p.stem for p in SCENES.glob("*.toml")}
    listed = [stem for *_, stems in TOPICS for stem in stems]
    missing = sorted(shipped - set(listed))
    if missing:
        raise RuntimeError(f"docs/_ext/gallery.py: scenes in no gallery topic: {missing}")
    key = source_hash()
    source.mkdir(exist_ok=True)
    (source / "README.txt").write_text(
        "Gallery\n=======\n\nEvery scene shipped in ``derivations/``, run, drawn and derived "
        "by the build that made this site. Each page shows the scene's picture, its motion "
        "where it moves, the Python that made them, the equations and results typeset, "
        "and the scene file.\n")
    written = []
    for folder, heading, sentence, stems in TOPICS:
        where = source / folder
        where.mkdir(exist_ok=True)
        (where / "README.txt").write_text(f"{heading}\n{'-' * len(heading)}\n\n{sentence}\n")
        for stem in stems:
            if stem not in shipped:
                raise RuntimeError(f"docs/_ext/gallery.py: no scene derivations/{stem}.toml")
            text, alt = example(stem, key)
            script = where / f"{stem}.py"
            if not script.exists() or script.read_text() != text:
                script.write_text(text)
            shutil.copyfile(SCENES / f"{stem}.toml", where / f"{stem}.toml")
            ALT.update({(stem, name): words for name, words in alt.items()})
            written.append(stem)
    return written


def scraper(block: Any, block_vars: dict, gallery_conf: dict) -> str:
    """The PNG and GIF files the block wrote in the example's folder, moved to
    sphinx-gallery's image folder, as reST images with their alternative texts."""
    example_file = Path(block_vars["src_file"])
    folder = example_file.parent
    stem = example_file.stem
    seen = block_vars.setdefault("rigidimpact_seen", set())
    iterator = block_vars["image_path_iterator"]
    lines = []
    for made in sorted(folder.glob(f"{stem}*.png")) + sorted(folder.glob(f"{stem}*.gif")):
        if made.name in seen:
            continue
        seen.add(made.name)
        target = Path(next(iterator)).with_suffix(made.suffix)
        shutil.move(str(made), str(target))
        relative = target.relative_to(Path(gallery_conf["src_dir"])).as_posix()
        alt = ALT.get((stem, made.name), f"{stem}: {made.name}")
        lines += [f".. image:: /{relative}", f"   :alt: {alt}",
                  "   :class: sphx-glr-single-img", ""]
    return "\n".join(["", *lines]) if lines else ""


class TopicOrder:
    """sphinx-gallery's order within a topic: the order of :data:`TOPICS`."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir
        self.rank = {f"{stem}.py": k for *_, stems in TOPICS for k, stem in enumerate(stems)}

    def __call__(self, filename: str) -> int:
        return self.rank.get(Path(filename).name, len(self.rank))

    def __repr__(self) -> str:  # Sphinx compares the configuration by its text
        return "TopicOrder"


def _on_init(app: Any) -> None:
    write_examples()


def say_thumbnails(gallery: Path) -> int:
    """Give each thumbnail in sphinx-gallery's index an alternative text (it leaves them
    empty): what the scene's picture shows. Returns how many it gave."""
    index = gallery / "index.rst"
    if not index.exists():
        return 0
    text = index.read_text()
    given = 0
    for (stem, name), words in ALT.items():
        if name != f"{stem}.png":
            continue
        thumb = f"images/thumb/sphx_glr_{stem}_thumb.png\n    :alt:"
        if thumb + "\n" in text:
            text = text.replace(thumb + "\n", f"{thumb} {words}\n")
            given += 1
    index.write_text(text)
    return given


def _after_gallery(app: Any) -> None:
    say_thumbnails(Path(app.srcdir) / "gallery")


def setup(app: Any) -> dict[str, Any]:
    # connected before sphinx-gallery's own handler, so the examples exist when it reads,
    # and after it, to say what each thumbnail shows
    app.connect("builder-inited", _on_init, priority=400)
    app.connect("builder-inited", _after_gallery, priority=600)
    return {"parallel_read_safe": True, "version": "2"}


if __name__ == "__main__":
    print(" ".join(write_examples()))
