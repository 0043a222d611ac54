"""`verigraph render` and `verigraph demo`."""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import pytest

from verigraph.cli import main
from verigraph.graph.builtin_scenes import kitchen_pan


def read(path: Path) -> tuple[int, int]:
    image = cv2.imread(str(path))
    assert image is not None, path
    return image.shape[1], image.shape[0]


@pytest.mark.parametrize("scene", ["kitchen:7", "blocks:3:5", "tangram:2", "cup_on_book"])
def test_render_writes_a_png_of_the_scene(scene: str, tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "scene.png"
    assert main(["render", "--scene", scene, "--out", str(out), "--width", "320",
                 "--height", "200"]) == 0
    assert read(out) == (320, 200)
    printed = capsys.readouterr().out
    assert scene in printed and (" on " in printed or "touches" in printed)


def test_render_goal_labels_and_degradations(tmp_path: Path) -> None:
    clean, noisy = tmp_path / "clean.png", tmp_path / "noisy.png"
    assert main(["render", "--scene", "tableware:4", "--goal", "--labels", "--out",
                 str(clean)]) == 0
    assert main(["render", "--scene", "tableware:4", "--goal", "--labels", "--out",
                 str(noisy), "--noise", "10", "--blur", "1", "--lighting", "0.5",
                 "--jpeg", "40"]) == 0
    a, b = cv2.imread(str(clean)), cv2.imread(str(noisy))
    assert a is not None and b is not None
    assert a.shape == b.shape
    height, width = a.shape[:2]
    assert width >= 640 and width > 2 * height  # the default frame takes the scene's shape
    assert abs(a.astype(int) - b.astype(int)).mean() > 1


def test_render_a_scene_file(tmp_path: Path) -> None:
    scene = tmp_path / "kitchen.json"
    scene.write_text(json.dumps(kitchen_pan().model_dump()))
    out = tmp_path / "k.png"
    assert main(["render", "--scene", str(scene), "--out", str(out), "--width", "640",
                 "--height", "480"]) == 0
    assert read(out) == (640, 480)
    assert main(["render", "--scene", str(scene), "--out", str(out), "--width", "900"]) == 0
    width, height = read(out)
    default = tmp_path / "default.png"
    assert main(["render", "--scene", str(scene), "--out", str(default)]) == 0
    dw, dh = read(default)
    assert width == 900 and abs(height / width - dh / dw) < 0.01  # one side: same shape


@pytest.mark.parametrize("flag", ["--width", "--height"])
def test_render_size_out_of_range_names_the_field(flag: str, tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["render", "--scene", "cup_on_book", "--out", str(tmp_path / "x.png"), flag,
                 "5"]) == 2
    err = capsys.readouterr().err
    assert flag.strip("-") in err and "16..4000" in err
    assert not (tmp_path / "x.png").exists()


def test_render_bad_scene_id_is_bad_input(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["render", "--scene", "garden:1", "--out", str(tmp_path / "x.png")]) == 2
    assert "unknown scene family" in capsys.readouterr().err
    assert main(["render", "--scene", "nowhere", "--out", str(tmp_path / "x.png")]) == 2
    assert "FAMILY:SEED" in capsys.readouterr().err
    assert main(["render", "--scene", "three_blocks", "--goal", "--out",
                 str(tmp_path / "x.png")]) == 2  # its goal is a predicate, not a graph


@pytest.mark.parametrize("scene", ["cup_on_book", "kitchen_pan"])
def test_demo_catches_the_mistake_and_reaches_the_goal(scene: str, tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    out = tmp_path / "demo"
    assert main(["demo", "--scene", scene, "--out", str(out), "--width", "320",
                 "--height", "240"]) == 0
    printed = capsys.readouterr().out
    assert "FAIL" in printed and "object_not_clear" in printed and "Suggestion:" in printed
    assert "Verdict: SUCCESS" in printed
    steps = sorted(p.name for p in out.glob("step_*.png"))
    assert steps[0] == "step_0_start.png" and len(steps) >= 3
    assert read(out / "unverified_mistake.png") == (320, 240)
    width, height = read(out / "start_vs_goal.png")
    assert width > 640 and height > 240
    if scene == "cup_on_book":
        assert "fell over: cup" in printed
