"""Which view an image is (side-view tabletop or top-view tangram), which family it shows.

With a named dictionary the answer is in the dictionary (tangram pieces have sides).
With the union of the built-ins, the picture decides: a tabletop render has a floor
band under a tinted background, a tangram render a neutral white table seen from above.
"""

from __future__ import annotations

from collections.abc import Iterable

import cv2
import numpy as np

from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, Dictionary, builtin_dictionary
from verigraph.perception.config import ViewKind
from verigraph.sim2d import palette

FAMILY_ORDER = ("blocks", "kitchen", "tableware")
BOTTOM_SHARE = 0.02
FLOOR_SHARE = 0.5


def _looks_like(small: np.ndarray, colour: tuple[int, int, int]) -> np.ndarray:
    ratio = small / np.array(colour, dtype=np.float32)
    gain = ratio.mean(axis=2)
    spread = np.abs(ratio - gain[:, :, None]).max(axis=2)
    return np.asarray((spread < 0.04 * gain) & (gain > 0.5) & (gain < 1.6))


def _tint(colour: tuple[int, int, int]) -> float:
    """Blue over red of a BGR colour: 1.06 for the tabletop wall, 1.0 for the tangram
    table; lighting scales both channels alike and keeps it."""
    return colour[0] / max(colour[2], 1)


def choose_view(image: np.ndarray, dictionary: Dictionary, requested: ViewKind) -> str:
    """'tabletop' or 'tangram'."""
    if requested != "auto":
        return requested
    sided = [p.sides is not None for p in dictionary.objects.values()]
    if sided and all(sided):
        return "tangram"
    if not any(sided):
        return "tabletop"
    h, w = image.shape[:2]
    small = cv2.resize(image, (max(1, w // 4), max(1, h // 4)),
                       interpolation=cv2.INTER_AREA).astype(np.float32)
    bottom = small[-max(1, int(small.shape[0] * BOTTOM_SHARE)):]
    if _looks_like(bottom, palette.FLOOR).mean() > FLOOR_SHARE:
        return "tabletop"
    bright = small.mean(axis=2) > 150
    tint = small[:, :, 0] / np.maximum(small[:, :, 2], 1.0)
    tinted = np.count_nonzero(bright & (np.abs(tint - _tint(palette.BACKGROUND)) < 0.02))
    neutral = np.count_nonzero(bright & (np.abs(tint - _tint(palette.TANGRAM_BACKGROUND))
                                         < 0.02))
    return "tabletop" if tinted > neutral else "tangram"


def family_of(labels: Iterable[str], dictionary: Dictionary) -> str | None:
    """The built-in dictionary that holds every label (the given one if it is built in)."""
    if dictionary.name in BUILTIN_DICTIONARIES:
        return dictionary.name
    wanted = set(labels)
    if not wanted:
        return None
    for name in FAMILY_ORDER + ("tangram",):
        if wanted <= set(builtin_dictionary(name).objects):
            return name
    return None
