"""Labellers: the default colour/shape one, and OpenCLIP on a real (tiny) model.

The OpenCLIP tests build their model: a tiny open_clip config trained for a few seconds
on crops of rendered scenes, saved as a local-dir model folder the way open_clip saves
models, then loaded and used through the same code users run. Nothing is downloaded
(HF_HUB_OFFLINE=1). Without torch/open_clip these tests skip, except under CI=true,
where the `clip` extra is required and they fail.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from verigraph.cli import main
from verigraph.errors import VeriGraphError
from verigraph.perception import perceive_image
from verigraph.perception.label.clip import (
    PROMPT,
    ClipLabeller,
    ClipSource,
    make_labeller,
    object_crop,
    prompt_text,
)
from verigraph.perception.label.labelling import ColourShapeLabeller
from verigraph.perception.metrics import score_graph
from verigraph.sim2d.generator import generate_scene

TRAIN_SEEDS = range(2000, 2030)
TEST_SEEDS = range(600, 608)
FAMILIES = ("kitchen", "blocks", "tangram")
TINY_CONFIG = {
    "embed_dim": 32,
    "vision_cfg": {"image_size": 32, "layers": 2, "width": 64, "patch_size": 8,
                   "head_width": 32},
    "text_cfg": {"context_length": 12, "vocab_size": 49408, "width": 64, "heads": 2,
                 "layers": 2},
}
PREPROCESS = {"mean": [0.5, 0.5, 0.5], "std": [0.25, 0.25, 0.25], "size": 32,
              "interpolation": "bicubic", "resize_mode": "squash"}


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
    over at once and the message says why and how to fix it."""
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


# -- OpenCLIP on a tiny model trained here ---------------------------------------------
class RecordingLabeller(ColourShapeLabeller):
    """The default labeller, keeping the crops it was shown and the labels it gave: the
    very regions the pipeline hands any labeller, cut out as ClipLabeller cuts them."""

    def __init__(self) -> None:
        self.seen: list[tuple[np.ndarray, str]] = []

    def label(self, image: np.ndarray, regions: Any, colours: Any, models: Any,
              scale: float) -> Any:
        chosen = super().label(image, regions, colours, models, scale)
        self.seen += [(object_crop(image, r), prompt_text(m.label, m.colour, PROMPT))
                      for r, (m, _) in zip(regions, chosen, strict=True)]
        return chosen


def training_crops() -> tuple[list[np.ndarray], list[str]]:
    """Crops of correctly perceived objects, each with its prompt."""
    crops, texts = [], []
    # Scenes of twelve blocks show every block colour, so every prompt is trained.
    runs = [(f, seed, None) for f in FAMILIES for seed in TRAIN_SEEDS] + [
        ("blocks", seed, 12) for seed in TRAIN_SEEDS[:10]]
    for family, seed, n_objects in runs:
        scene = generate_scene(family, seed, n_objects)
        recorder = RecordingLabeller()
        result = perceive_image(scene.world.render(640, 480), dictionary=family,
                                labeller=recorder)
        if score_graph(result.graph, scene.graph, family).exact:
            crops += [c for c, _ in recorder.seen]
            texts += [t for _, t in recorder.seen]
    return crops, texts


@pytest.fixture(scope="module")
def tiny_clip(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Train a tiny CLIP on rendered crops and save it as a local-dir model folder."""
    torch, open_clip = require_clip()
    from open_clip.transform import image_transform
    from PIL import Image
    from safetensors.torch import save_file

    torch.manual_seed(0)
    crops, texts = training_crops()
    prompts = sorted(set(texts))
    model = open_clip.CLIP(**TINY_CONFIG)
    transform = image_transform(PREPROCESS["size"], is_train=False, mean=PREPROCESS["mean"],
                                std=PREPROCESS["std"], resize_mode=PREPROCESS["resize_mode"])
    images = torch.stack([transform(Image.fromarray(c)) for c in crops])
    targets = torch.tensor([prompts.index(t) for t in texts])
    tokens = open_clip.get_tokenizer("ViT-B-32", context_length=12)(prompts)
    optimiser = torch.optim.AdamW(model.parameters(), lr=2e-3, weight_decay=0.01)
    for _ in range(400):
        batch = torch.randint(0, len(images), (96,))
        img = model.encode_image(images[batch])
        txt = model.encode_text(tokens)
        logits = model.logit_scale.exp() * (img / img.norm(dim=-1, keepdim=True)) @ (
            txt / txt.norm(dim=-1, keepdim=True)).T
        loss = torch.nn.functional.cross_entropy(logits, targets[batch])
        optimiser.zero_grad()
        loss.backward()
        optimiser.step()
    folder = tmp_path_factory.mktemp("tiny_clip")
    save_file({k: v.contiguous() for k, v in model.state_dict().items()},
              str(folder / "open_clip_model.safetensors"))
    (folder / "open_clip_config.json").write_text(json.dumps(
        {"model_cfg": TINY_CONFIG, "preprocess_cfg": PREPROCESS}))
    return folder


@pytest.fixture(scope="module")
def clip_labeller(tiny_clip: Path) -> ClipLabeller:
    labeller, note = make_labeller("clip", ClipSource(f"local-dir:{tiny_clip}"))
    assert note is None, note
    assert isinstance(labeller, ClipLabeller)
    return labeller


@pytest.mark.parametrize("family", FAMILIES)
def test_clip_labels_unseen_scenes(clip_labeller: ClipLabeller, family: str) -> None:
    """Zero-shot over every (label, colour) of the dictionary: the labels (and the block
    colours, which CLIP picks too) of scenes it never saw. The tiny model is there to
    run the real loading and labelling code, not to be a good labeller, so the bar is
    set for it: nearly all objects right, most whole graphs right."""
    node_f1, exact = 0.0, 0
    for seed in TEST_SEEDS:
        scene = generate_scene(family, seed)
        result = perceive_image(scene.world.render(640, 480), dictionary=family,
                                labeller=clip_labeller)
        assert result.labeller == "openclip"
        score = score_graph(result.graph, scene.graph, family)
        node_f1 += score.node_f1
        exact += score.exact
    assert node_f1 / len(TEST_SEEDS) >= 0.9
    assert exact >= len(TEST_SEEDS) // 2


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
