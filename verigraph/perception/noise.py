"""Sensor noise: measured cheaply, removed only when it is there.

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


def denoise(image: np.ndarray) -> np.ndarray:
    """The image, median-filtered if it is noisy."""
    if noise_level(image) < NOISY:
        return image
    return np.asarray(cv2.medianBlur(image, 3))
