"""Labellers: the default colour/shape one, and OpenCLIP on a real (tiny) model.

The OpenCLIP tests load a real tiny model made here (tests/tiny_clip.py: a tiny
open_clip config trained on crops of rendered scenes, committed as a local-dir model
folder in tests/data/tiny_clip/) through the same code users run. Nothing is downloaded
(HF_HUB_OFFLINE=1). Without torch/open_clip these tests skip, except under CI=true,
where the `clip` extra is required and they fail.
"""

from __future__ import annotations

import contextlib
import json
import os
import time
from pathlib import Path
from typing import Any

import pytest

from tiny_clip import FAMILIES, build
from tiny_clip import FOLDER as TINY_CLIP
from verigraph.cli import main
from verigraph.errors import VeriGraphError
from verigraph.perception import perceive_image
from verigraph.perception.label.clip import ClipLabeller, ClipSource, make_labeller
from verigraph.perception.label.labelling import ColourShapeLabeller
from verigraph.perception.metrics import score_graph
from verigraph.sim2d.generator import generate_scene

TEST_SEEDS = range(600, 608)


def require_clip() -> tuple[Any, Any]:
    try:
        import open_clip
        import torch
    except ImportError as exc:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true requires the clip extra (pip install 'verigraph-mcp[clip]'): "
                        f"{exc.name} is missing")
        pytest.skip(f"the clip extra is not installed ({exc.name} missing)")
    return torch, open_clip


# -- the default labeller -------------------------------------------------------------
def test_default_labeller_tells_same_coloured_objects_apart_by_shape() -> None:
    """Under the union dictionary red is a block, a kettle or a mug: shape decides."""
    seen: dict[str, int] = {}
    for family, label in (("blocks", "block"), ("kitchen", "kettle"), ("tableware", "mug")):
        for seed in range(40):
            scene = generate_scene(family, seed)
            if not any(n.label == label and (n.attrs.get("color", "red") == "red")
                       for n in scene.graph.nodes):
                continue
            result = perceive_image(scene.world.render(640, 480))  # union dictionary
            red = [o for o in result.objects if o.colour == "red"]
            assert [o.label for o in red] == [label], (family, seed)
            seen[label] = seed
            break
    assert set(seen) == {"block", "kettle", "mug"}


def test_make_labeller_names() -> None:
    labeller, note = make_labeller("default")
    assert isinstance(labeller, ColourShapeLabeller) and note is None
    with pytest.raises(VeriGraphError, match="unknown labeller"):
        make_labeller("sift")


def test_clip_without_weights_falls_back_quickly_with_a_message(tmp_path: Path) -> None:
    """A tag that is not in the cache is never downloaded: the default labeller takes
    over at once and the message says why and how to fix it. (open_clip is imported
    first when installed: the clock times the lookup, not the import of torch.)"""
    with contextlib.suppress(ImportError):
        import open_clip  # noqa: F401
    start = time.perf_counter()
    labeller, note = make_labeller("clip", ClipSource("ViT-B-32", "openai",
                                                      cache_dir=str(tmp_path)))
    assert time.perf_counter() - start < 20
    assert isinstance(labeller, ColourShapeLabeller)
    assert note is not None and "colour/shape labeller" in note
    assert "not in the local cache" in note or "not installed" in note


@pytest.mark.parametrize("model,expected", [
    ("local-dir:/nonexistent/model", "no open_clip_config.json"),
    ("hf-hub:org/model", "fetched from the network"),
])
def test_clip_sources_that_are_not_local_are_refused(model: str, expected: str) -> None:
    labeller, note = make_labeller("clip", ClipSource(model))
    assert isinstance(labeller, ColourShapeLabeller)
    assert note is not None and (expected in note or "not installed" in note)


# -- OpenCLIP on a tiny model made here ------------------------------------------------
@pytest.fixture(scope="module")
def tiny_clip() -> Path:
    """The committed tiny CLIP folder (tests/tiny_clip.py says how it is made)."""
    require_clip()
    return TINY_CLIP


@pytest.mark.slow
def test_the_tiny_clip_recipe_still_gives_a_working_labeller(tmp_path: Path) -> None:
    """Rebuild the committed weights from their recipe (minutes of training): the new
    folder loads and labels unseen scenes as well as the committed one must."""
    require_clip()
    labeller, note = make_labeller("clip", ClipSource(f"local-dir:{build(tmp_path)}"))
    assert note is None and isinstance(labeller, ClipLabeller)
    assert_labels_unseen_scenes(labeller, "blocks")


@pytest.fixture(scope="module")
def clip_labeller(tiny_clip: Path) -> ClipLabeller:
    labeller, note = make_labeller("clip", ClipSource(f"local-dir:{tiny_clip}"))
    assert note is None, note
    assert isinstance(labeller, ClipLabeller)
    return labeller


def assert_labels_unseen_scenes(labeller: ClipLabeller, family: str) -> None:
    """Zero-shot over every (label, colour) of the dictionary: the labels (and the block
    colours, which CLIP picks too) of scenes it never saw. The tiny model is there to
    run the real loading and labelling code, not to be a good labeller, so the bar is
    set for it: nearly all objects right, most whole graphs right."""
    node_f1, exact = 0.0, 0
    for seed in TEST_SEEDS:
        scene = generate_scene(family, seed)
        result = perceive_image(scene.world.render(640, 480), dictionary=family,
                                labeller=labeller)
        assert result.labeller == "openclip"
        score = score_graph(result.graph, scene.graph, family)
        node_f1 += score.node_f1
        exact += score.exact
    assert node_f1 / len(TEST_SEEDS) >= 0.9
    assert exact >= len(TEST_SEEDS) // 2


@pytest.mark.parametrize("family", FAMILIES)
def test_clip_labels_unseen_scenes(clip_labeller: ClipLabeller, family: str) -> None:
    assert_labels_unseen_scenes(clip_labeller, family)


def test_clip_scores_are_probabilities(clip_labeller: ClipLabeller) -> None:
    result = perceive_image(generate_scene("kitchen", 600).world.render(640, 480),
                            dictionary="kitchen", labeller=clip_labeller)
    scores = [o.score for o in result.objects]
    assert scores and all(0.0 <= s <= 1.0 for s in scores) and max(scores) > 0.5


def test_clip_folder_given_as_a_plain_path(tiny_clip: Path) -> None:
    labeller, note = make_labeller("clip", ClipSource(str(tiny_clip)))
    assert note is None and isinstance(labeller, ClipLabeller)


def test_cli_with_the_clip_labeller(tiny_clip: Path, tmp_path: Path,
                                    capsys: pytest.CaptureFixture[str]) -> None:
    import cv2

    scene = generate_scene("tangram", 601)
    path = tmp_path / "t.png"
    path.write_bytes(cv2.imencode(".png", scene.world.render(640, 480))[1].tobytes())
    assert main(["perceive", str(path), "--json", "--labeller", "clip",
                 "--clip-model", f"local-dir:{tiny_clip}"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["labeller"] == "openclip" and data["view"] == "tangram"
    ids = [n["id"] for n in data["graph"]["nodes"]]
    assert len(ids) >= 5 and set(ids) <= set(scene.graph.node_ids())
    assert all(0.0 <= o["score"] <= 1.0 for o in data["objects"])


def test_cli_clip_fallback_warns(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import cv2

    path = tmp_path / "k.png"
    path.write_bytes(cv2.imencode(".png", generate_scene("kitchen", 1).world.render())[1]
                     .tobytes())
    assert main(["perceive", str(path), "--labeller", "clip",
                 "--clip-model", str(tmp_path / "missing")]) == 0
    captured = capsys.readouterr()
    assert "kitchen" in captured.out
    assert "warning: OpenCLIP labeller unavailable" in captured.err
