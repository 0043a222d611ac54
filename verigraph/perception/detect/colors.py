"""Colour classes: which colours an image may contain, and a fast pixel classifier for them.

Perception reads the same colour table the renderer draws with (`sim2d.palette`), so a
change of a dictionary colour needs no change here. Classification is a lookup in a
32x32x32 table built once per palette: every pixel costs one index, whatever the metric.
The metric is CIELab distance with a weight on lightness; the tangram view lowers that
weight because its pieces differ in hue while uneven lighting changes their lightness.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import cv2
import numpy as np

from verigraph.sim2d import palette

UNKNOWN, BACKGROUND, FLOOR, DARK, MIXED = 0, 1, 2, 3, 4
FIRST_OBJECT = 5
BINS = 32
SHIFT = 3  # 256 / BINS levels per bin

# Colours whose lightness sits near the background's: told apart from it by enclosure.
BRIGHT_DELTA_E = 20.0
CONFUSABLE_DELTA_E = 12.0
SLOPE = 20  # grey levels to a darker and to a brighter neighbour


@dataclass(frozen=True, slots=True)
class ColourTable:
    """The classes an image is classified into: index -> colour name and BGR.

    Indices 0-4 are fixed (unknown, background, floor, dark outline, mixed: an edge
    pixel that only looked like an object colour); object colours follow. `bright`
    lists object classes too close to the background to separate per pixel;
    `confusable` those that an outline blurred into a neighbour also produces (grey
    from black and the background, brown from orange and black).
    """

    names: tuple[str, ...]
    bgr: tuple[tuple[int, int, int], ...]
    lightness_weight: float
    unknown_distance: float
    bright: frozenset[int]
    confusable: frozenset[int]

    def index(self, name: str) -> int | None:
        return self.names.index(name) if name in self.names else None

    @property
    def object_classes(self) -> range:
        return range(FIRST_OBJECT, len(self.names))


@cache
def colour_table(colours: tuple[str, ...], *, tangram: bool) -> ColourTable:
    """The classes for a view (tabletop or tangram) and a set of object colours."""
    background = palette.TANGRAM_BACKGROUND if tangram else palette.BACKGROUND
    names = ("unknown", "background", "floor", "dark", "mixed") + colours
    bgr = ((128, 128, 128), background, palette.FLOOR, palette.OUTLINE, (128, 128, 128)
           ) + tuple(palette.COLORS[c] for c in colours)
    colours_lab = lab(np.array(bgr, dtype=np.uint8))
    bright = frozenset(i for i in range(FIRST_OBJECT, len(names))
                       if float(np.linalg.norm(colours_lab[i] - colours_lab[BACKGROUND]))
                       < BRIGHT_DELTA_E)
    return ColourTable(names=names, bgr=bgr, lightness_weight=0.35 if tangram else 1.0,
                       unknown_distance=40.0 if tangram else 28.0, bright=bright,
                       confusable=_confusable(bgr))


def _confusable(bgr: tuple[tuple[int, int, int], ...]) -> frozenset[int]:
    """Object classes that a mix of another colour with the outline comes close to."""
    colours = np.array(bgr, dtype=np.float32)
    dark = colours[DARK]
    shares = np.linspace(0.25, 0.85, 13, dtype=np.float32)
    out = set()
    for i in range(FIRST_OBJECT, len(bgr)):
        others = [j for j in range(1, len(bgr)) if j not in (i, DARK, MIXED)]
        mixes = (shares[None, :, None] * colours[others][:, None, :]
                 + (1 - shares[None, :, None]) * dark).reshape(-1, 3)
        mix_lab = lab(np.clip(mixes, 0, 255).astype(np.uint8))
        own = lab(np.array([bgr[i]], dtype=np.uint8))[0]
        if float(np.min(np.linalg.norm(mix_lab - own, axis=1))) < CONFUSABLE_DELTA_E:
            out.add(i)
    return frozenset(out)


def lab(bgr: np.ndarray) -> np.ndarray:
    """CIELab (L in 0-100) of uint8 BGR colours, shape (n, 3) -> (n, 3) float32."""
    scaled = bgr.reshape(1, -1, 3).astype(np.float32) / 255.0
    return np.asarray(cv2.cvtColor(scaled, cv2.COLOR_BGR2Lab), dtype=np.float32).reshape(-1, 3)


def brightest(image: np.ndarray) -> np.ndarray:
    """Each pixel's brightest channel, (h, w) uint8 of a uint8 (h, w, 3) image; taken
    by OpenCV (numpy's max over the last axis costs several ms on a 640x480 image)."""
    if image.ndim == 2:
        return image
    b, g, r = cv2.split(np.ascontiguousarray(image))
    return np.asarray(cv2.max(cv2.max(b, g), r))


@cache
def lookup_table(table: ColourTable) -> np.ndarray:
    """Class index for every quantised BGR colour: shape (BINS**3,), uint8."""
    return _tables(table)[0]


@cache
def distance_table(table: ColourTable) -> np.ndarray:
    """Distance (weighted Lab, clipped to 255) from every quantised colour to its class."""
    return _tables(table)[1]


@cache
def _tables(table: ColourTable) -> tuple[np.ndarray, np.ndarray]:
    levels = np.arange(BINS, dtype=np.int32) * (256 // BINS) + (256 // BINS) // 2
    b, g, r = np.meshgrid(levels, levels, levels, indexing="ij")
    grid = np.stack([b, g, r], axis=-1).reshape(-1, 3).astype(np.uint8)
    weight = np.array([table.lightness_weight, 1.0, 1.0], dtype=np.float32)
    grid_lab = lab(grid) * weight
    classes = lab(np.array(table.bgr[1:], dtype=np.uint8)) * weight
    dist = np.linalg.norm(grid_lab[:, None, :] - classes[None, :, :], axis=2)
    dist[:, MIXED - 1] = np.inf  # assigned by structure (edges), never by colour
    best = np.argmin(dist, axis=1)
    out = (best + 1).astype(np.uint8)
    out[dist[np.arange(len(best)), best] > table.unknown_distance] = UNKNOWN
    out[(dist[:, DARK - 1] <= table.unknown_distance) & (grid.max(axis=1) < 60)] = DARK
    nearest = np.clip(dist[np.arange(len(best)), best], 0, 255).astype(np.uint8)
    return out, nearest


def colour_index(image: np.ndarray) -> np.ndarray:
    """Quantised colour per pixel: the index into the lookup tables. Works on uint8
    BGR of any shape (..., 3); the channels are split into planes first, which makes
    the shifts contiguous (three times faster than on interleaved channels)."""
    if image.size == 0:
        return np.zeros(image.shape[:-1], dtype=np.uint16)
    b, g, r = (np.asarray(p, dtype=np.uint8)
               for p in cv2.split((image >> SHIFT).reshape(-1, 1, 3)))
    out = b.astype(np.uint16) << 10
    out |= g.astype(np.uint16) << 5
    out |= r
    return out.reshape(image.shape[:-1])


def classify(image: np.ndarray, table: ColourTable) -> np.ndarray:
    """Class index per pixel (uint8, same height and width as the BGR image)."""
    return np.asarray(np.take(lookup_table(table), colour_index(image)))


def refine_edges(image: np.ndarray, classes: np.ndarray, table: ColourTable) -> None:
    """Reclassify object-colour pixels on a slope as MIXED (in place).

    A blurred outline between a dark line and a brighter fill passes through every
    shade in between, so a pixel with clearly darker and clearly brighter neighbours is
    a mixture, whatever colour it resembles (the edge of an orange block looks like the
    brown table, the edge of anything like a grey counter). A real grey counter is flat
    inside, and a thin knife is the brightest thing between its outlines.
    """
    objects = set(table.object_classes) - table.bright
    if not objects:
        return
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    k3 = np.ones((3, 3), np.uint8)
    brighter = cv2.subtract(cv2.dilate(grey, k3), grey) > SLOPE
    darker = cv2.subtract(grey, cv2.erode(grey, k3)) > SLOPE
    mixed = brighter & darker & np.isin(classes, list(objects))
    classes[mixed] = MIXED


def purity(pixels: np.ndarray, table: ColourTable) -> np.ndarray:
    """Distance of BGR pixels (any shape (..., 3)) to the colour of their class."""
    return np.asarray(distance_table(table)[colour_index(pixels)])
