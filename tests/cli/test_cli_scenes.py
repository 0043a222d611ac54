"""`--scene` means the same in `validate` as in `agent`: a file or a built-in scene id."""

from __future__ import annotations

from pathlib import Path

import pytest

from verigraph.cli import main
from verigraph.cli.scenes import scene_argument
from verigraph.errors import VeriGraphError

pytestmark = pytest.mark.fast

EXAMPLES = Path(__file__).parents[2] / "examples" / "scenes"


def plan(tmp_path: Path, text: str) -> str:
    path = tmp_path / "plan.txt"
    path.write_text(text)
    return str(path)


def test_validate_accepts_a_builtin_scene_and_checks_its_goal(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    good = plan(tmp_path, "move(cup, desk)\nmove(book, shelf)\n")
    assert main(["validate", "--scene", "cup_on_book", "--plan", good]) == 0
    assert "goal reached" in capsys.readouterr().out
    half = plan(tmp_path, "move(cup, desk)\n")
    assert main(["validate", "--scene", "cup_on_book", "--plan", half]) == 1
    assert "goal not reached" in capsys.readouterr().out
    # an explicit --goal replaces the built-in one
    assert main(["validate", "--scene", "cup_on_book", "--plan", half,
                 "--goal", "single_stack"]) == 1


def test_validate_names_the_accepted_forms(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "--scene", "cup_on_boo", "--plan", plan(tmp_path, "done\n")]) == 2
    err = capsys.readouterr().err
    assert "--scene" in err and "cup_on_book" in err and ".json/.yaml" in err


def test_files_still_win_and_the_agent_reads_the_same_forms() -> None:
    from_file = scene_argument(str(EXAMPLES / "cup_on_book.json"))
    assert from_file.graph is not None and from_file.builtin is None
    assert scene_argument("three_blocks").builtin == "three_blocks"
    assert scene_argument("blocks:3:4").generator == {"family": "blocks", "seed": 3,
                                                      "n_objects": 4}
    with pytest.raises(VeriGraphError):
        scene_argument("blocks:3", generator=False)
