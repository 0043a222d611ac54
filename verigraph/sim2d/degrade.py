"""Image degradations for perception tests and benchmarks: sensor noise, blur, uneven
lighting, JPEG, and what a real camera adds (colour casts, tone curves, another wall
colour, roll, tilt, zoom, framing, shake, an occluder).

Seeded: the same image, settings and seed always give the same degraded image. The
order is that of a camera: the scene (wall colour, occluder in front), the light
(white balance, lighting gradient), the optics (pose, framing, blur), the sensor (tone
curve, hue error, noise), then compression.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import cv2
import numpy as np

from verigraph.sim2d import degrade_ops as ops
from verigraph.sim2d import palette

Colour = tuple[int, int, int]


@dataclass(frozen=True, slots=True)
class Degradation:
    """How much to spoil a render; all default values leave it untouched.

    noise: standard deviation of Gaussian pixel noise (0-255 scale);
    blur: Gaussian blur sigma in pixels; lighting: 0-1, strength of a global gain
    change plus a linear brightness gradient; jpeg: JPEG quality 1-100 (None = none);
    hue: degrees every hue is turned by; gamma: tone-curve exponent (1 = none);
    white_balance: per-channel gains (B, G, R); wall: BGR the background is repainted;
    rotation: camera roll in degrees; scale: zoom factor of the whole image;
    crop: up to this share of each side cut off (never into the objects);
    perspective: corner displacement as a share of the frame (camera tilt);
    motion_blur: shake length in pixels; motion_angle: its direction in degrees
    (None = drawn from the seed); occlusion: width of a grey bar in front of the scene
    as a share of the image width; occlusion_angle: the bar's tilt from vertical in
    degrees (90 = a horizontal bar); occlusion_at: where it crosses the content box,
    0-1 (None = drawn from the seed); blob: radius of a grey blob in front of the
    scene as a share of the content box's height; pole: width of a plain bar hanging
    from the top edge in front of the scene (no outline), as a share of the image width;
    pole_length: how far down it reaches, as a share of the image height (1 = to the
    bottom edge); pole_colour: its BGR (None = the grey 118, 118, 118); pole_at: where it
    crosses the content box, 0-1 (None = drawn from the seed).
    """

    noise: float = 0.0
    blur: float = 0.0
    lighting: float = 0.0
    jpeg: int | None = None
    hue: float = 0.0
    gamma: float = 1.0
    white_balance: tuple[float, float, float] = (1.0, 1.0, 1.0)
    wall: Colour | None = None
    rotation: float = 0.0
    scale: float = 1.0
    crop: float = 0.0
    perspective: float = 0.0
    motion_blur: int = 0
    occlusion: float = 0.0
    motion_angle: float | None = None
    occlusion_angle: float = 0.0
    occlusion_at: float | None = None
    blob: float = 0.0
    pole: float = 0.0
    pole_length: float = 1.0
    pole_colour: Colour | None = None
    pole_at: float | None = None

    @property
    def active(self) -> bool:
        return any(getattr(self, f.name) != f.default for f in fields(self))


def _background(image: np.ndarray) -> Colour:
    """The background colour the render was drawn on (side-view wall or tangram table)."""
    counts = [cv2.countNonZero(cv2.inRange(image, np.array(c, np.uint8), np.array(c, np.uint8)))
              for c in (palette.BACKGROUND, palette.TANGRAM_BACKGROUND)]
    return palette.BACKGROUND if counts[0] >= counts[1] else palette.TANGRAM_BACKGROUND


def degrade(image: np.ndarray, spec: Degradation, seed: int = 0) -> np.ndarray:
    """A degraded copy of a BGR uint8 image."""
    if not spec.active:
        return image.copy()
    rng = np.random.default_rng(seed)
    background = _background(image)
    keep = ops.content_box(image, [background, palette.FLOOR])
    out = image
    if spec.wall is not None:
        out = ops.recolour(out, background, spec.wall)
    if spec.occlusion > 0 and spec.occlusion_angle == 0.0 and spec.occlusion_at is None:
        out = ops.occlude(out, spec.occlusion, keep, rng)
    elif spec.occlusion > 0:
        out = ops.occlude_bar(out, spec.occlusion, keep, rng, degrees=spec.occlusion_angle,
                              at=spec.occlusion_at)
    if spec.blob > 0:
        out = ops.occlude_blob(out, spec.blob, keep, rng)
    if spec.pole > 0:
        out = ops.occlude_pole(out, spec.pole, spec.pole_length, keep, rng,
                               colour=spec.pole_colour or (118, 118, 118), at=spec.pole_at)
    if spec.white_balance != (1.0, 1.0, 1.0):
        out = ops.white_balance(out, spec.white_balance)
    if spec.lighting > 0:
        out = _lighting(out, spec.lighting, rng)
    if spec.crop > 0:
        out = ops.crop_randomly(out, spec.crop, keep, rng)
    if spec.rotation:
        out = ops.rotate(out, spec.rotation, 1.0)
    if spec.scale != 1.0:
        out = ops.rescale(out, spec.scale)
    if spec.perspective > 0:
        out = ops.perspective(out, spec.perspective, rng)
    if spec.motion_blur > 1:
        angle = float(rng.uniform(0, 180))  # drawn either way: same seed, same stream
        out = ops.motion_blur(out, spec.motion_blur,
                              angle if spec.motion_angle is None else spec.motion_angle)
    if spec.gamma != 1.0:
        out = ops.gamma(out, spec.gamma)
    if spec.hue:
        out = ops.hue_shift(out, spec.hue)
    return _sensor(out, spec, rng)


def _lighting(image: np.ndarray, strength: float, rng: np.random.Generator) -> np.ndarray:
    out = image.astype(np.float32)
    h, w = out.shape[:2]
    angle = rng.uniform(0, 2 * np.pi)
    xs = (np.arange(w, dtype=np.float32) / w - 0.5) * np.float32(np.cos(angle))
    ys = (np.arange(h, dtype=np.float32) / h - 0.5) * np.float32(np.sin(angle))
    gain = 1.0 + strength * (rng.uniform(-0.3, 0.3) + 0.6 * (ys[:, None] + xs[None, :]))
    out *= gain.astype(np.float32)[:, :, None]
    return np.clip(out, 0, 255).astype(np.uint8)


def _sensor(image: np.ndarray, spec: Degradation, rng: np.random.Generator) -> np.ndarray:
    out = image.astype(np.float32)
    if spec.blur > 0:
        out = np.asarray(cv2.GaussianBlur(out, (0, 0), sigmaX=spec.blur), dtype=np.float32)
    if spec.noise > 0:
        out += rng.standard_normal(size=out.shape, dtype=np.float32) * np.float32(spec.noise)
    result = np.clip(out, 0, 255).astype(np.uint8)
    if spec.jpeg is not None:
        quality = int(min(100, max(1, spec.jpeg)))
        ok, buf = cv2.imencode(".jpg", result, [cv2.IMWRITE_JPEG_QUALITY, quality])
        decoded = cv2.imdecode(buf, cv2.IMREAD_COLOR) if ok else None
        if decoded is not None:
            result = np.asarray(decoded, dtype=np.uint8)
    return result
