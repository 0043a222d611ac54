"""OpenCLIP zero-shot labeller: each detected crop against the dictionary's names.

The paper labelled tangram colours with OpenCLIP; here any detection can be labelled
this way. A crop is compared with one text prompt per (label, colour) the dictionary
allows ("a photo of a red block"), and the best prompt names the object.

Weights never come from the network. A model is loaded from
- a folder (`local-dir:/path` or just `/path`) holding `open_clip_config.json` and a
  checkpoint, as `open_clip` saves them;
- a checkpoint file together with an architecture name (`ViT-B-32` + `/path/w.pt`);
- an architecture and a pretrained tag (`ViT-B-32` + `openai`) only if those weights
  are already in the user's cache (`~/.cache/huggingface`, `~/.cache/clip`).
Anything else raises `ClipUnavailable`, and `make_labeller` falls back to the
colour/shape labeller with a message saying how to get the model. torch and open_clip
are the optional extra `clip` (see `verigraph.extras`).
"""

from __future__ import annotations

import logging
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from verigraph.errors import VeriGraphError
from verigraph.extras import EXTRAS, missing
from verigraph.perception.detect.regions import Region
from verigraph.perception.label.catalogue import ObjectModel
from verigraph.perception.label.labelling import ColourShapeLabeller, Labeller

log = logging.getLogger("verigraph.perception")

PROMPT = "a photo of a {colour} {name}"
CROP_MARGIN = 0.15
GROUND = 128  # grey behind a cropped object
DEFAULT_MODEL = "ViT-B-32"
DEFAULT_TAG = "openai"
INSTALL_FIX = (f"{EXTRAS['clip'].install}, then give a local model folder "
               "(--clip-model local-dir:/path) or a tag whose weights are in your cache")


class ClipUnavailable(VeriGraphError):
    """OpenCLIP cannot be used here: not installed, or no weights on this machine."""


@dataclass(frozen=True, slots=True)
class ClipSource:
    """Where a model comes from: an architecture or folder, and weights (tag or file)."""

    model: str = DEFAULT_MODEL
    pretrained: str | None = DEFAULT_TAG
    cache_dir: str | None = None


def _modules() -> tuple[Any, Any]:
    absent = missing("clip")
    if absent:
        raise ClipUnavailable(f"OpenCLIP is not installed ({absent[0]} is missing)",
                              field="labeller", value="clip", fix=INSTALL_FIX)
    try:
        import open_clip
        import torch
    except ImportError as exc:
        raise ClipUnavailable(f"OpenCLIP is not installed ({exc.name} is missing)",
                              field="labeller", value="clip", fix=INSTALL_FIX) from None
    return torch, open_clip


def cached_weights(open_clip: Any, model: str, tag: str, cache_dir: str | None) -> str:
    """The local file of a pretrained tag, if a previous download left it in the cache."""
    cfg = open_clip.get_pretrained_cfg(model, tag)
    if not cfg:
        raise ClipUnavailable(f"open_clip knows no pretrained tag '{tag}' for {model}",
                              field="pretrained", value=tag,
                              fix=f"use one of {open_clip.list_pretrained_tags_by_model(model)}"
                                  " or a checkpoint file")
    if cfg.get("file"):
        return str(cfg["file"])
    hub = cfg.get("hf_hub", "")
    if hub:
        from huggingface_hub import try_to_load_from_cache

        repo, filename = os.path.split(hub.rstrip("/")) if not hub.endswith("/") else (
            hub.rstrip("/"), "")
        names = [filename] if filename else ["open_clip_model.safetensors",
                                             "open_clip_pytorch_model.bin"]
        if filename.endswith((".bin", ".pth")):
            names.insert(0, filename[:-4] + ".safetensors")
        for name in names:
            found = try_to_load_from_cache(repo_id=repo, filename=name, cache_dir=cache_dir)
            if isinstance(found, str):
                return found
    url = cfg.get("url", "")
    if url:
        path = Path(cache_dir or os.path.expanduser("~/.cache/clip")) / os.path.basename(url)
        if path.is_file():
            return str(path)
    raise ClipUnavailable(f"the weights for {model}/{tag} are not in the local cache, and "
                          "VeriGraph never downloads them", field="pretrained", value=tag,
                          fix="copy the checkpoint to this machine and pass its path, or a "
                              "local-dir: model folder")


def load_model(source: ClipSource) -> tuple[Any, Any, Any]:
    """(model, preprocess, tokenizer) for a source, from local files only."""
    torch, open_clip = _modules()
    name = source.model
    if not name.startswith(("local-dir:", "hf-hub:")) and Path(name).is_dir():
        name = f"local-dir:{name}"
    if name.startswith("hf-hub:"):
        raise ClipUnavailable("hf-hub: models are fetched from the network", field="model",
                              value=name, fix="download the folder once and use local-dir:")
    kwargs: dict[str, Any] = {}
    if name.startswith("local-dir:"):
        folder = Path(name.removeprefix("local-dir:"))
        if not (folder / "open_clip_config.json").is_file():
            raise ClipUnavailable(f"{folder} holds no open_clip_config.json", field="model",
                                  value=str(folder), fix="point at a folder saved by open_clip")
    elif source.pretrained and Path(source.pretrained).is_file():
        kwargs["pretrained"] = source.pretrained
    elif source.pretrained:
        cfg = open_clip.get_pretrained_cfg(name, source.pretrained)
        kwargs["pretrained"] = cached_weights(open_clip, name, source.pretrained,
                                              source.cache_dir)
        for key, arg in (("mean", "image_mean"), ("std", "image_std"),
                         ("interpolation", "image_interpolation"),
                         ("resize_mode", "image_resize_mode")):
            if cfg.get(key) is not None:
                kwargs[arg] = cfg[key]
    else:
        raise ClipUnavailable(f"no weights given for {name}", field="pretrained", value=None,
                              fix="give a pretrained tag in your cache or a checkpoint file")
    try:
        model, _, preprocess = open_clip.create_model_and_transforms(name, device="cpu",
                                                                     **kwargs)
        tokenizer = open_clip.get_tokenizer(name)
    except (RuntimeError, ValueError, OSError) as exc:
        raise ClipUnavailable(f"open_clip could not load {name}: {exc}", field="model",
                              value=name, fix=INSTALL_FIX) from None
    model.eval()
    torch.set_grad_enabled(False)
    return model, preprocess, tokenizer


def crop(image: np.ndarray, box: tuple[int, int, int, int],
         margin: float = CROP_MARGIN) -> np.ndarray:
    """RGB crop around a box (x0, y0, x1, y1) with some context, as CLIP expects."""
    h, w = image.shape[:2]
    bx0, by0, bx1, by1 = box
    pad = int(round(margin * max(bx1 - bx0, by1 - by0))) + 2
    x0, y0 = max(0, bx0 - pad), max(0, by0 - pad)
    x1, y1 = min(w, bx1 + pad), min(h, by1 + pad)
    return np.asarray(cv2.cvtColor(image[y0:y1, x0:x1], cv2.COLOR_BGR2RGB))


def object_crop(image: np.ndarray, region: Region, margin: float = CROP_MARGIN) -> np.ndarray:
    """RGB crop of one detected object on a plain grey ground: neighbours that share the
    bounding box (a tangram piece's box holds parts of three others) are blanked, so the
    crop shows the object and its outline only."""
    h, w = image.shape[:2]
    pad = int(round(margin * max(region.width, region.height))) + 2
    x0, y0 = max(0, region.x0 - pad), max(0, region.y0 - pad)
    x1, y1 = min(w, region.x1 + pad), min(h, region.y1 + pad)
    mask = np.zeros((y1 - y0, x1 - x0), np.uint8)
    mask[region.y0 - y0:region.y1 - y0, region.x0 - x0:region.x1 - x0] = region.mask
    mask = cv2.dilate(mask, np.ones((5, 5), np.uint8))  # keep the outline
    out = np.full((y1 - y0, x1 - x0, 3), GROUND, np.uint8)
    out[mask.astype(bool)] = image[y0:y1, x0:x1][mask.astype(bool)]
    return np.asarray(cv2.cvtColor(out, cv2.COLOR_BGR2RGB))


def prompt_text(label: str, colour: str, template: str = PROMPT) -> str:
    """The text a crop is compared with: "a photo of a red block"."""
    return template.format(colour=colour, name=label.replace("_", " "))


def prompt_for(model: ObjectModel, template: str = PROMPT) -> str:
    return prompt_text(model.label, model.colour, template)


class ClipLabeller:
    """Zero-shot labelling of detected crops with an OpenCLIP model."""

    name = "openclip"

    def __init__(self, source: ClipSource | None = None, *, template: str = PROMPT) -> None:
        self.source = source or ClipSource()
        self.template = template
        self.model, self.preprocess, self.tokenizer = load_model(self.source)
        self._texts: dict[tuple[str, ...], Any] = {}

    def _text_features(self, prompts: tuple[str, ...]) -> Any:
        if prompts not in self._texts:
            features = self.model.encode_text(self.tokenizer(list(prompts)))
            self._texts[prompts] = features / features.norm(dim=-1, keepdim=True)
        return self._texts[prompts]

    def image_features(self, crops: Sequence[np.ndarray]) -> Any:
        """Normalised image embeddings of RGB crops."""
        torch, _ = _modules()
        from PIL import Image

        batch = torch.stack([self.preprocess(Image.fromarray(c)) for c in crops])
        features = self.model.encode_image(batch)
        return features / features.norm(dim=-1, keepdim=True)

    def label(self, image: np.ndarray, regions: Sequence[Region], colours: Sequence[str],
              models: Sequence[ObjectModel], scale: float) -> list[tuple[ObjectModel, float]]:
        if not regions:
            return []
        prompts = tuple(prompt_for(m, self.template) for m in models)
        texts = self._text_features(prompts)
        images = self.image_features([object_crop(image, r) for r in regions])
        probs = (100.0 * images @ texts.T).softmax(dim=-1).numpy()
        best = probs.argmax(axis=1)
        return [(models[int(b)], float(probs[i, b])) for i, b in enumerate(best)]


def make_labeller(name: str = "default", source: ClipSource | None = None
                  ) -> tuple[Labeller, str | None]:
    """A labeller by name, and a message when the requested one could not be used.

    'clip' falls back to the colour/shape labeller when OpenCLIP or its weights are
    missing, so perception keeps working; the message says what was missing and how to
    fix it.
    """
    if name in ("default", "colour-shape", "color-shape"):
        return ColourShapeLabeller(), None
    if name not in ("clip", "openclip"):
        raise VeriGraphError(f"unknown labeller '{name}'", field="labeller", value=name,
                             fix="use default or clip")
    try:
        return ClipLabeller(source), None
    except ClipUnavailable as exc:
        message = f"OpenCLIP labeller unavailable, using the colour/shape labeller: {exc}"
        log.warning("%s", message)
        return ColourShapeLabeller(), message
