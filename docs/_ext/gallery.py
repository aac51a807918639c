"""The gallery: one page for each shipped scene in derivations/, written by the build.

Each page shows the scene's figure (what `rigidimpact simulate SCENE --plot` draws: the
bodies at the impact with their velocities after, or the run's trajectories), the
equations it solves and its results typeset from the derivation itself (what
`rigidimpact derive SCENE --format latex` prints), and the scene file. Nothing on these
pages is written by hand: change a scene and the next build shows it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "derivations"
OUT = Path(__file__).resolve().parents[1] / "gallery"


def _plain(text: str) -> str:
    """`text` shown as written (a product's * is not emphasis)."""
    return "".join("\\" + c if c in "*_`[]<>" else c for c in text)


def _latex_blocks(derivation: Any) -> list[str]:
    from rigidimpact.outputs.latex import equation_latex, to_latex

    lines = ["## The equations solved", ""]
    for eq in derivation.equations:
        lines += [f"{eq.label}:", "", "$$", equation_latex(eq), "$$", ""]
    outcomes = list(getattr(derivation, "outcomes", ()) or ())
    if outcomes:
        for outcome in outcomes:
            lines += [f"## {outcome.label}", ""]
            for key, value in outcome.results().items():
                lines += [f"- `{key}` $= {to_latex(value)}$"]
            for warning in outcome.warnings:
                lines += [f"- warning: {warning}"]
            lines.append("")
    else:
        lines += ["## Results", ""]
        for key, value in derivation.results.items():
            lines += [f"- `{key}` $= {to_latex(value)}$"]
        lines.append("")
    return lines


def _figure(path: Path, target: Path) -> str | None:
    """Draw the scene's run to `target`; None, or why there is no figure."""
    from rigidimpact.errors import InputError
    from rigidimpact.figures import plot_outcome, plot_space
    from rigidimpact.scenes.scene import Scene
    from rigidimpact.scenes.space import load_any
    from rigidimpact.simulate import run
    from rigidimpact.simulate.space import run_space

    scene = load_any(str(path))
    if not isinstance(scene, Scene):
        if scene.simulate.get("until", "separation") == "separation" and \
                "impacts" not in scene.simulate:
            return "a 3-D scene whose run ends at the impact (nothing moves to draw)"
        plot_space(scene, run_space(scene), target)
        return None
    try:
        plot_outcome(scene, run(scene), target)
    except InputError as refusal:
        return str(refusal)
    return None


def write_gallery(scenes: Path = SCENES, out: Path = OUT) -> list[str]:
    """Write gallery/<scene>.md (and its .png) for every scene file, and the index."""
    from rigidimpact.scenes.space import load_any

    out.mkdir(exist_ok=True)
    pages = []
    for path in sorted(scenes.glob("*.toml")):
        derivation = load_any(str(path)).derivation()
        why = _figure(path, out / f"{path.stem}.png")
        title = derivation.title
        text = [f"# {title}", "", f"`derivations/{path.name}`: "
                f"`rigidimpact derive derivations/{path.name}` prints this derivation, "
                f"`rigidimpact simulate derivations/{path.name} --plot FIGURE.png` draws "
                "the figure.", ""]
        text += [f"![{title}]({path.stem}.png)", ""] if why is None else \
            [f"(No figure: {why}.)", ""]
        text += ["## Setup", ""] + [f"- {_plain(line)}" for line in derivation.setup] + [""]
        text += _latex_blocks(derivation)
        text += ["## The scene file", "", "```toml", path.read_text().rstrip(), "```", ""]
        (out / f"{path.stem}.md").write_text("\n".join(text))
        pages.append((path.stem, title))
    index = ["# Gallery", "",
             "Every scene shipped in `derivations/`, drawn and derived by the build that "
             "made this site.", "", "```{toctree}", ":maxdepth: 1", ""]
    index += [stem for stem, _ in pages] + ["```", ""]
    (out / "index.md").write_text("\n".join(index))
    return [stem for stem, _ in pages]


def _on_init(app: Any) -> None:
    write_gallery()


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _on_init)
    return {"parallel_read_safe": True, "version": "1"}


if __name__ == "__main__":
    print(" ".join(write_gallery()))
