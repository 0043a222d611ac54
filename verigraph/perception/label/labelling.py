"""Labellers: which dictionary object a detected region is.

A labeller sees the image, the region, the colour class the segmentation found and
every object model of the dictionary; it returns the model it believes and a score in
[0, 1]. The default needs no weights: colour narrows the candidates (a kitchen has one
red thing) and shape decides between the rest (a red block is square and solid, a red
mug is hollow, a red kettle is tall and tapered). The OpenCLIP labeller
(`verigraph.perception.label.clip`) implements the same protocol from pixels alone.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import cv2
import numpy as np

from verigraph.perception.detect.colors import lab
from verigraph.perception.detect.regions import Region
from verigraph.perception.label.catalogue import ObjectModel
from verigraph.sim2d import palette

OUTLINE_INSET = 3.0  # a fill is about one outline width smaller than the shape
HOLLOW_SOLIDITY = 0.8


@dataclass(frozen=True, slots=True)
class Shape:
    """Measurements of a region that do not depend on its colour."""

    long_side: float
    short_side: float
    solidity: float

    @classmethod
    def of(cls, region: Region) -> Shape:
        if region.area < 3:
            return cls(float(region.width), float(region.height), 1.0)
        hull = region.hull()
        (_, _), (w, h), _ = cv2.minAreaRect(hull)  # the hull's rectangle is the region's
        hull_area = max(float(cv2.contourArea(hull)), 1.0)
        return cls(max(w, h) + 1 + OUTLINE_INSET, min(w, h) + 1 + OUTLINE_INSET,
                   min(1.0, region.area / (hull_area + 0.5 * cv2.arcLength(hull, True))))


class Labeller(Protocol):
    """Chooses the dictionary object each region shows."""

    name: str

    def label(self, image: np.ndarray, regions: Sequence[Region], colours: Sequence[str],
              models: Sequence[ObjectModel], scale: float) -> list[tuple[ObjectModel, float]]:
        """For each region (with the colour class segmentation gave it), the best model
        and a confidence in [0, 1]. All regions of an image come in one call, so a
        network labeller can batch them."""
        ...


def shape_error(shape: Shape, model: ObjectModel, scale: float) -> float:
    """How badly a region's size and hollowness fit an object model (0 = perfectly)."""
    error = 0.0
    if not model.fixed and scale > 0:
        error += abs(math.log(shape.long_side / (model.long_side * scale)))
        error += abs(math.log(shape.short_side / max(model.short_side * scale, 1.0)))
    hollow = shape.solidity < HOLLOW_SOLIDITY
    if model.container != hollow and not model.fixed:
        error += 1.0
    return error


class ColourShapeLabeller:
    """The default labeller: colour and shape weigh alike.

    Candidates are the movable models whose palette colour lies within `COLOUR_MARGIN`
    (CIELab) of the region's own mean colour, the segmentation's colour class among
    them; each costs its colour distance in units of `COLOUR_UNIT` plus its shape
    error, so a lid whose teal a camera has turned towards steel is still a lid by its
    outline rather than a knife by its colour. Furniture (fixed models) is labelled by
    colour. The confidence is the margin between the best and the second-best cost.
    """

    name = "colour-shape"

    def label(self, image: np.ndarray, regions: Sequence[Region], colours: Sequence[str],
              models: Sequence[ObjectModel], scale: float) -> list[tuple[ObjectModel, float]]:
        return [self.choose(image, r, c, models, scale)
                for r, c in zip(regions, colours, strict=True)]

    def choose(self, image: np.ndarray, region: Region, colour: str,
               models: Sequence[ObjectModel], scale: float) -> tuple[ObjectModel, float]:
        own = [m for m in models if m.colour == colour]
        if not own:
            raise LookupError(f"no object of colour {colour}")
        if any(m.fixed for m in own):
            candidates, colour_cost = own, dict.fromkeys(range(len(own)), 0.0)
        else:
            candidates, colour_cost = _near_colours(image, region, colour, models)
        if len(candidates) == 1:
            return candidates[0], 1.0
        shape = Shape.of(region)
        costs = sorted((colour_cost[i] + shape_error(shape, m, scale), i)
                       for i, m in enumerate(candidates))
        (best, i), (second, _) = costs[0], costs[1]
        return candidates[i], float(min(1.0, max(0.0, second - best)))


COLOUR_MARGIN = 14.0  # CIELab distance beyond the nearest colour still considered
COLOUR_UNIT = 10.0  # CIELab distance that costs as much as a shape error of 1
OWN_CLEAR = 10.0  # a core colour this close to its class colour leaves no doubt
MAX_PIXELS = 2000


def _palette_lab(colour: str) -> np.ndarray:
    return lab(np.array([palette.COLORS.get(colour, palette.FALLBACK)], dtype=np.uint8))[0]


def _near_colours(image: np.ndarray, region: Region, colour: str,
                  models: Sequence[ObjectModel]) -> tuple[list[ObjectModel], dict[int, float]]:
    """Movable models whose colour is close to the region's core colour (its own class
    always among them), with their colour costs. The core colour is the median of the
    quarter of its pixels nearest its class colour (thin parts are mostly outline
    blend); when that is plainly its class colour, the class alone is the candidate."""
    movable = [m for m in models if not m.fixed]
    own = [m for m in movable if m.colour == colour]
    if region.area == 0:
        return own, dict.fromkeys(range(len(own)), 0.0)
    # Every k-th pixel of the region, gathered from their positions (not all of them).
    where = np.flatnonzero(region.mask)[:: max(1, region.area // MAX_PIXELS)]
    rows, cols = np.divmod(where, region.width)
    pixel_lab = lab(image[region.y0 + rows, region.x0 + cols])
    own_lab = _palette_lab(colour)
    to_own = np.linalg.norm(pixel_lab - own_lab, axis=1)
    core = np.median(pixel_lab[to_own <= np.percentile(to_own, 25)], axis=0)
    if float(np.linalg.norm(core - own_lab)) < OWN_CLEAR:
        return own, dict.fromkeys(range(len(own)), 0.0)
    dist = [float(np.linalg.norm(_palette_lab(m.colour) - core)) for m in movable]
    nearest = min(dist)
    chosen = [(m, d) for m, d in zip(movable, dist, strict=True)
              if m.colour == colour or d <= nearest + COLOUR_MARGIN]
    return [m for m, _ in chosen], {i: d / COLOUR_UNIT for i, (_, d) in enumerate(chosen)}
