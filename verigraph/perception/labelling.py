"""Labellers: which dictionary object a detected region is.

A labeller sees the image, the region, the colour class the segmentation found and
every object model of the dictionary; it returns the model it believes and a score in
[0, 1]. The default needs no weights: colour narrows the candidates (a kitchen has one
red thing) and shape decides between the rest (a red block is square and solid, a red
mug is hollow, a red kettle is tall and tapered). The OpenCLIP labeller
(`verigraph.perception.clip`) implements the same protocol from pixels alone.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import cv2
import numpy as np

from verigraph.perception.catalogue import ObjectModel
from verigraph.perception.regions import Region

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
        pts = region.points()
        if len(pts) < 3:
            return cls(float(region.width), float(region.height), 1.0)
        (_, _), (w, h), _ = cv2.minAreaRect(pts)
        hull = cv2.convexHull(pts)
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
    """The default labeller: colour class first, then size and hollowness."""

    name = "colour-shape"

    def label(self, image: np.ndarray, regions: Sequence[Region], colours: Sequence[str],
              models: Sequence[ObjectModel], scale: float) -> list[tuple[ObjectModel, float]]:
        return [self.choose(image, r, c, models, scale)
                for r, c in zip(regions, colours, strict=True)]

    def choose(self, image: np.ndarray, region: Region, colour: str,
               models: Sequence[ObjectModel], scale: float) -> tuple[ObjectModel, float]:
        candidates = [m for m in models if m.colour == colour]
        if not candidates:
            raise LookupError(f"no object of colour {colour}")
        if len(candidates) == 1:
            return candidates[0], 1.0
        shape = Shape.of(region)
        scored = sorted(candidates, key=lambda m: shape_error(shape, m, scale))
        best, second = shape_error(shape, scored[0], scale), shape_error(shape, scored[1], scale)
        return scored[0], float(min(1.0, max(0.0, second - best)))
