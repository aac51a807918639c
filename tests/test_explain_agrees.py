"""`simulate --explain` says what the run will do, refusals included."""

from __future__ import annotations

from pathlib import Path

from rigidimpact.cli import main

ROOT = Path(__file__).resolve().parents[1]


def test_explain_says_the_refusal_the_run_then_gives(tmp_path, capsys):
    # a disc striking a rod, followed for a time: the next-contact search follows a point,
    # so the run refuses, and --explain says so first (it promised the search before)
    text = (ROOT / "derivations" / "disc-rod.toml").read_text() + "\n[simulate]\nuntil = 2\n"
    scene = tmp_path / "disc-rod-run.toml"
    scene.write_text(text)
    assert main(["simulate", str(scene), "--explain"]) == 0
    explained = capsys.readouterr().out
    refused = [line for line in explained.splitlines() if line.startswith("refused: ")]
    assert len(refused) == 1 and "needs one particle" in refused[0]
    assert main(["simulate", str(scene)]) == 2
    error = capsys.readouterr().err.strip()
    assert error == f"rigidimpact: error: simulate.until: {refused[0][len('refused: '):]}"


def test_explain_of_a_run_it_can_follow_says_no_refusal(capsys):
    assert main(["simulate", str(ROOT / "derivations" / "restrike.toml"), "--explain"]) == 0
    assert "refused" not in capsys.readouterr().out
