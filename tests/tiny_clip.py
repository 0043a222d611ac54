"""The tiny OpenCLIP model the labeller tests load, and the recipe that rebuilt it.

The weights in tests/data/tiny_clip/ are generated, not downloaded: `python
tests/tiny_clip.py` trains a tiny open_clip config for a few hundred steps on crops of
rendered scenes the default labeller read correctly, and saves it as a local-dir model
folder (open_clip_config.json + open_clip_model.safetensors) the way open_clip saves
models. Training takes minutes on two busy cores, so the suite loads the committed
folder and only the slow tier (`pytest -m slow`) rebuilds it to check that the recipe
still gives a working labeller. The weights are stored as float16, and token-embedding
rows no prompt uses are zeroed (they never reach an output), which keeps the file small
in git.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

FOLDER = Path(__file__).parent / "data" / "tiny_clip"
TRAIN_SEEDS = range(2000, 2030)
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


def training_crops() -> tuple[list[np.ndarray], list[str]]:
    """Crops of correctly perceived objects, each with its prompt."""
    from verigraph.perception import perceive_image
    from verigraph.perception.label.clip import PROMPT, object_crop, prompt_text
    from verigraph.perception.label.labelling import ColourShapeLabeller
    from verigraph.perception.metrics import score_graph
    from verigraph.sim2d.generator import generate_scene

    class RecordingLabeller(ColourShapeLabeller):
        """The default labeller, keeping the crops it was shown and the labels it gave:
        the very regions the pipeline hands any labeller, cut as ClipLabeller cuts them."""

        def __init__(self) -> None:
            self.seen: list[tuple[np.ndarray, str]] = []

        def label(self, image: np.ndarray, regions: Any, colours: Any, models: Any,
                  scale: float) -> Any:
            chosen = super().label(image, regions, colours, models, scale)
            self.seen += [(object_crop(image, r), prompt_text(m.label, m.colour, PROMPT))
                          for r, (m, _) in zip(regions, chosen, strict=True)]
            return chosen

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


def build(folder: Path, steps: int = 400) -> Path:
    """Train the tiny CLIP (seeded) and save it into `folder` as a local-dir model."""
    import open_clip
    import torch
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
    for _ in range(steps):
        batch = torch.randint(0, len(images), (96,))
        img = model.encode_image(images[batch])
        txt = model.encode_text(tokens)
        logits = model.logit_scale.exp() * (img / img.norm(dim=-1, keepdim=True)) @ (
            txt / txt.norm(dim=-1, keepdim=True)).T
        loss = torch.nn.functional.cross_entropy(logits, targets[batch])
        optimiser.zero_grad()
        loss.backward()
        optimiser.step()
    state = {k: v.detach().clone() for k, v in model.state_dict().items()}
    used = torch.zeros(TINY_CONFIG["text_cfg"]["vocab_size"], dtype=torch.bool)
    used[tokens.flatten()] = True
    state["token_embedding.weight"][~used] = 0.0
    folder.mkdir(parents=True, exist_ok=True)
    save_file({k: v.to(torch.float16).contiguous() for k, v in state.items()},
              str(folder / "open_clip_model.safetensors"))
    (folder / "open_clip_config.json").write_text(json.dumps(
        {"model_cfg": TINY_CONFIG, "preprocess_cfg": PREPROCESS}, indent=1) + "\n")
    return folder


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    print(build(Path(sys.argv[1]) if len(sys.argv) > 1 else FOLDER))
