"""Undo uneven lighting before colours are classified.

A brighter lamp or a shadow gradient multiplies every channel by a smooth gain, which
moves a grey counter towards a silver pot. The background and the floor have known
colours, so the gain is measured where they show (on a small thumbnail, so noise
averages out) and fitted as a plane `g(x, y) = a + b*x + c*y` with outliers dropped
(objects that happen to share the background's hue). Clipped pixels say nothing about
the gain and are left out. When too little background shows, nothing is corrected.

A grey counter is the background's colour at two thirds of the gain, and in a tightly
framed side view it can cover more of the image than the wall does; a plane through
its pixels would darken everything. So samples come from the areas that reach the
image border with a smoothly varying gain (the wall and the floor band) whenever
such areas exist; an object inside the frame is cut off from them by its outline.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

THUMB = 8  # thumbnail is 1/THUMB of the image in each direction
MIN_SAMPLES = 40
CHROMA_TOLERANCE = 0.04
RANSAC_TRIALS = 60
RANSAC_SUBSET = 600
INLIER_TOLERANCE = 0.015
CLIPPED = 248
NEUTRAL = 0.03  # gains this close to 1 everywhere are left alone
MIN_SPAN = 0.3  # share of the image samples must span for a slope in that direction
EXTRAPOLATION = 0.05  # gain margin beyond the measured range
SMOOTH_STEP = 0.05  # largest gain change within a 3x3 thumbnail window of one surface


@dataclass(frozen=True, slots=True)
class GainField:
    """g(x, y) = a + b * (x / w - 0.5) + c * (y / h - 0.5); identity when a=1, b=c=0."""

    a: float = 1.0
    b: float = 0.0
    c: float = 0.0
    samples: int = 0
    low: float = 0.0  # the field is clipped to the gains its samples showed, plus a margin:
    high: float = float("inf")  # a plane through the floor alone must not run off upwards

    @property
    def is_identity(self) -> bool:
        return abs(self.a - 1) + (abs(self.b) + abs(self.c)) / 2 < NEUTRAL

    def at(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Gain at image coordinates given as fractions of width and height."""
        return self.a + self.b * (u - 0.5) + self.c * (v - 0.5)

    def image(self, height: int, width: int) -> np.ndarray:
        """The gain at every pixel centre of a height x width image, float32."""
        u = (np.arange(width, dtype=np.float32) + 0.5) / width
        v = (np.arange(height, dtype=np.float32) + 0.5) / height
        field = np.asarray(self.at(u[None, :], v[:, None]), dtype=np.float32)
        return np.asarray(np.clip(field, self.low, self.high), dtype=np.float32)


def estimate_gain(image: np.ndarray, references: list[tuple[int, int, int]]) -> GainField:
    """Fit the gain plane from pixels that look like one of the reference colours."""
    h, w = image.shape[:2]
    size = (max(1, w // THUMB), max(1, h // THUMB))
    small = cv2.resize(image, size, interpolation=cv2.INTER_AREA).astype(np.float32)
    clipped = cv2.resize(clipped_pixels(image), size,
                         interpolation=cv2.INTER_AREA) > 0
    sh, sw = small.shape[:2]
    vv, uu = np.mgrid[0:sh, 0:sw].astype(np.float32)
    uu = (uu + 0.5) / sw - 0.5
    vv = (vv + 0.5) / sh - 0.5
    us, vs, gs = [], [], []
    for ref in references:
        ratio = small / np.array(ref, dtype=np.float32)
        gain = ratio.mean(axis=2)
        spread = np.abs(ratio - gain[:, :, None]).max(axis=2)
        ok = ~clipped & (spread < CHROMA_TOLERANCE * gain) & (gain > 0.4) & (gain < 1.8)
        ok = border_surfaces(ok, gain)
        us.append(uu[ok])
        vs.append(vv[ok])
        gs.append(gain[ok])
    u, v, g = np.concatenate(us), np.concatenate(vs), np.concatenate(gs)
    if len(g) < MIN_SAMPLES:
        return GainField(samples=int(len(g)))
    design = np.stack([np.ones(len(g)), u, v], axis=1)
    keep = _ransac_inliers(design, g, RANSAC_SUBSET)
    if keep.sum() < MIN_SAMPLES:
        return GainField(samples=int(keep.sum()))
    # A direction the samples barely span (the floor band alone spans no height) gets no
    # slope: extrapolating one would invent a gradient nothing measured.
    spans = [True, float(np.ptp(u[keep])) >= MIN_SPAN, float(np.ptp(v[keep])) >= MIN_SPAN]
    coef = np.zeros(3)
    fit, *_ = np.linalg.lstsq(design[keep][:, spans], g[keep], rcond=None)
    coef[np.array(spans)] = fit
    return GainField(float(coef[0]), float(coef[1]), float(coef[2]), int(keep.sum()),
                     low=float(g[keep].min()) - EXTRAPOLATION,
                     high=float(g[keep].max()) + EXTRAPOLATION)


def border_surfaces(ok: np.ndarray, gain: np.ndarray) -> np.ndarray:
    """The part of `ok` in smooth-gain areas that touch the image border; `ok` itself
    when no such area exists (a photo whose wall shows only between objects)."""
    gain = gain.astype(np.float32)
    k3 = np.ones((3, 3), np.uint8)
    smooth = cv2.subtract(cv2.dilate(gain, k3), cv2.erode(gain, k3)) < SMOOTH_STEP
    count, labels = cv2.connectedComponents((ok & smooth).view(np.uint8), connectivity=4)
    if count <= 1:
        return ok
    edge = np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]])
    touching = np.unique(edge[edge > 0])
    if len(touching) == 0:
        return ok
    return np.isin(labels, touching)


def _ransac_inliers(design: np.ndarray, g: np.ndarray, subset: int) -> np.ndarray:
    """Samples on the plane most samples agree with (objects that mimic the background's
    hue, such as a grey counter, form a smaller plane of their own and are dropped)."""
    rng = np.random.default_rng(0)
    scored = rng.choice(len(g), size=min(subset, len(g)), replace=False)
    trials = rng.integers(0, len(g), size=(RANSAC_TRIALS, 3))
    # Every trial's plane at once (batched solves, one product for all the scores).
    systems = design[trials]
    usable = np.abs(np.linalg.det(systems)) >= 1e-6
    if not usable.any():
        return np.zeros(len(g), dtype=bool)
    coefs = np.linalg.solve(systems[usable], g[trials[usable]][..., None])[..., 0]
    counts = np.count_nonzero(np.abs(design[scored] @ coefs.T - g[scored][:, None])
                              < INLIER_TOLERANCE, axis=0)
    best_coef = coefs[int(np.argmax(counts))]  # the first of the best, as a loop finds it
    return np.asarray(np.abs(design @ best_coef - g) < INLIER_TOLERANCE)


def correct(image: np.ndarray, gain: GainField) -> np.ndarray:
    """The image divided by the gain field (unchanged when the field is the identity)."""
    if gain.is_identity:
        return image
    inverse = 1.0 / np.clip(gain.image(*image.shape[:2]), 0.2, 5.0)
    out = cv2.multiply(image.astype(np.float32), cv2.merge([inverse, inverse, inverse]))
    result = np.clip(out, 0, 255).astype(np.uint8)
    # A clipped pixel only says "at least this bright": keep it as it is.
    clipped = clipped_pixels(image)
    return np.asarray(cv2.copyTo(image, clipped, result))


def clipped_pixels(image: np.ndarray) -> np.ndarray:
    """1 where any channel is at least CLIPPED, else 0 (uint8). One `cv2.inRange` pass
    is several times cheaper than the brightest channel per pixel."""
    limit = (CLIPPED - 1,) * 3
    return (cv2.inRange(image, (0, 0, 0), limit) == 0).view(np.uint8)
