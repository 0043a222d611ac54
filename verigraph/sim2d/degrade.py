"""Image degradations for perception tests: sensor noise, blur, uneven lighting, JPEG.

Seeded: the same image, settings and seed always give the same degraded image.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np


@dataclass(frozen=True, slots=True)
class Degradation:
    """How much to spoil a render; all zero (the default) leaves it untouched.

    noise: standard deviation of Gaussian pixel noise (0-255 scale);
    blur: Gaussian blur sigma in pixels; lighting: 0-1, strength of a global gain
    change plus a linear brightness gradient; jpeg: JPEG quality 1-100 (None = none).
    """

    noise: float = 0.0
    blur: float = 0.0
    lighting: float = 0.0
    jpeg: int | None = None

    @property
    def active(self) -> bool:
        return bool(self.noise or self.blur or self.lighting or self.jpeg is not None)


def degrade(image: np.ndarray, spec: Degradation, seed: int = 0) -> np.ndarray:
    """A degraded copy of a BGR uint8 image."""
    if not spec.active:
        return image.copy()
    rng = np.random.default_rng(seed)
    out = image.astype(np.float32)
    if spec.lighting > 0:
        h, w = out.shape[:2]
        angle = rng.uniform(0, 2 * np.pi)
        xs = (np.arange(w, dtype=np.float32) / w - 0.5) * np.float32(np.cos(angle))
        ys = (np.arange(h, dtype=np.float32) / h - 0.5) * np.float32(np.sin(angle))
        gain = 1.0 + spec.lighting * (rng.uniform(-0.3, 0.3) + 0.6 * (ys[:, None] + xs[None, :]))
        out *= gain.astype(np.float32)[:, :, None]
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
