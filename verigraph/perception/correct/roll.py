"""Camera roll: measured on the floor line and undone before supports are read.

Supports are read by scanning straight down from an object's bottom, and the floor band
is found row by row; both assume the floor line is horizontal. A camera rolled by a
few degrees tilts it, so the floor's top edge is measured (per column, the top of the
floor run that reaches the bottom border), a line is fitted robustly (the median of
slopes between column pairs, then least squares on the columns that agree), and the
image is turned back about its centre. Angles under `MIN_DEGREES` are left alone: the
downward scan and the floor band tolerate them (measured: exact graphs at 2 degrees),
while a turn costs sharpness and smears furniture cut by the frame into the corners
it uncovers (a stove at the edge came back as two). Beyond `MAX_DEGREES` the fit is
not trusted.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from verigraph.perception.detect.colors import FLOOR

MIN_DEGREES = 3.0
MAX_DEGREES = 12.0
MIN_COLUMNS = 0.3  # share of the columns that must show the floor's edge
AGREE = 2.0  # px from the robust line that a column may be and still count


def floor_edge(classes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(columns, top row of the floor run from the bottom border) where there is one."""
    floor = classes == FLOOR
    h = floor.shape[0]
    # Length of the run of floor pixels that ends at the bottom border, per column.
    not_floor = ~floor[::-1]
    run = np.where(not_floor.any(axis=0), np.argmax(not_floor, axis=0), h)
    cols = np.flatnonzero((run >= 2) & (run < 0.6 * h))
    return cols, (h - run[cols]).astype(np.float64)


def estimate_roll(classes: np.ndarray) -> float | None:
    """Degrees the floor line is turned (positive: it rises to the right), or None."""
    cols, rows = floor_edge(classes)
    if len(cols) < MIN_COLUMNS * classes.shape[1]:
        return None
    rng = np.random.default_rng(0)
    i, j = rng.integers(0, len(cols), size=(2, 400))
    ok = np.abs(cols[i] - cols[j]) > 0.2 * classes.shape[1]
    if ok.sum() < 20:
        return None
    slope = float(np.median((rows[j][ok] - rows[i][ok]) / (cols[j][ok] - cols[i][ok])))
    offset = float(np.median(rows - slope * cols))
    agree = np.abs(rows - (offset + slope * cols)) < AGREE
    if agree.sum() < MIN_COLUMNS * classes.shape[1]:
        return None
    slope, _ = np.polyfit(cols[agree], rows[agree], 1)
    degrees = -math.degrees(math.atan(float(slope)))
    return degrees if abs(degrees) <= MAX_DEGREES else None


def unroll(image: np.ndarray, degrees: float) -> np.ndarray:
    """The image turned by -degrees about its centre (the floor line level again)."""
    h, w = image.shape[:2]
    m = cv2.getRotationMatrix2D((w / 2.0, h / 2.0), -degrees, 1.0)
    return np.asarray(cv2.warpAffine(image, m, (w, h), flags=cv2.INTER_LINEAR,
                                     borderMode=cv2.BORDER_REPLICATE))
