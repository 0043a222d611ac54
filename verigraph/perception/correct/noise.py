"""Sensor noise and blur: measured cheaply; noise removed only when it is there, heavy
blur reported (it cannot be undone, and thin objects vanish or double under it).

A render is flat almost everywhere, so in a clean image nearly every pixel equals the
median of its neighbours; the median absolute difference is a direct estimate of the
noise level. Noisy images get a 3x3 median filter, which keeps edges (and therefore
outlines and thin objects) but removes the speckle that would otherwise break every
fill into hundreds of pieces. Clean images are left alone: a median would erase
one-pixel lines.
"""

from __future__ import annotations

import cv2
import numpy as np

SAMPLE_ROWS = 8  # every 8th band of rows is enough to measure the noise
NOISY = 3.0  # grey levels


def noise_level(image: np.ndarray) -> float:
    """Robust estimate of the pixel noise (grey levels, standard-deviation scale)."""
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    bands = np.ascontiguousarray(grey[: grey.shape[0] - grey.shape[0] % SAMPLE_ROWS]
                                 .reshape(-1, SAMPLE_ROWS, grey.shape[1])[:, :3]
                                 .reshape(-1, grey.shape[1]))
    diff = cv2.absdiff(bands, cv2.medianBlur(bands, 3))
    return float(np.median(diff)) * 1.4826 * 1.5


def denoise(image: np.ndarray) -> tuple[np.ndarray, bool]:
    """The image, median-filtered if it is noisy; and whether it was."""
    if noise_level(image) < NOISY:
        return image, False
    return np.asarray(cv2.medianBlur(image, 3)), True


SHARP_PERCENTILE = 99.7
SOFT = 420.0  # below this thin objects are checked by shape (Gaussian sigma 1: 290-360)
BLURRED = 240.0  # a sharp render measures about 570, Gaussian sigma 1 about 300-370


def sharpness(image: np.ndarray) -> float:
    """Edge strength in the direction where it is weakest: the 99.7th percentile of the
    absolute Sobel derivative along x, y and both diagonals, the smallest of the four.
    Outlines are the image's strongest edges; a shake smears those across its own
    direction only, which the weakest direction catches."""
    grey = cv2.medianBlur(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY), 3)
    # On 8-bit grey the derivatives are integers: 16-bit Sobel gives them exactly, at a
    # fraction of the float cost; every fourth pixel is plenty.
    gx = cv2.Sobel(grey, cv2.CV_16S, 1, 0)[::2, ::2].astype(np.float32).ravel()
    gy = cv2.Sobel(grey, cv2.CV_16S, 0, 1)[::2, ::2].astype(np.float32).ravel()
    return min(_percentile(d) for d in (gx, gy, (gx + gy) / np.float32(1.414),
                                        (gx - gy) / np.float32(1.414)))


def _percentile(values: np.ndarray) -> float:
    """SHARP_PERCENTILE of |values| by counting (Sobel values are integers below 1,100;
    a sort-based percentile of mostly-zero data is many times slower)."""
    counts = np.bincount(np.abs(values).astype(np.int64))
    rank = SHARP_PERCENTILE / 100 * (len(values) - 1)
    return float(np.searchsorted(np.cumsum(counts), rank, side="right"))


def blur_warning(level: float) -> str | None:
    """A warning when an image of this `sharpness` is too blurred to trust thin objects,
    else None."""
    if level >= BLURRED:
        return None
    return (f"the image is blurred (edge sharpness {level:.0f}; a sharp render shows about "
            "570): thin objects may be missed or doubled")
