"""Tangram geometry from pixels: canonical side numbering and side-to-side contacts.

Sides are numbered as docs/design.md section 2 and `sim2d.tangram_geometry` define them:
clockwise as seen from above, starting at the canonical vertex (a triangle's right
angle; the parallelogram's acute vertex that starts a long side; any square vertex,
the square being symmetric). Image rows grow downwards, so pixel coordinates are first
turned into a y-up frame, where "clockwise" means a negative signed area. A detected
outline is then replaced by the piece's exact model placed by a least-squares fit,
which makes contact tests independent of pixel noise along the edges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from verigraph.sim2d.tangram_geometry import piece_model, sides_touch, signed_area

Vec = tuple[float, float]
MARGIN = 1.4
CLOSE = 1.7  # sides this much closer than the tolerance touch beyond doubt (a gap of a
# quarter unit hides under the outlines at the default scale: 3 px at 14 px per unit)


@dataclass(frozen=True, slots=True)
class PlacedPiece:
    """A piece's model vertices in the world-like frame (y up, world units)."""

    label: str
    vertices: tuple[Vec, ...]
    fit_error: float  # RMS distance of the detected corners from the fitted model, units
    flipped: bool = False


def to_world(points_px: np.ndarray, scale: float) -> np.ndarray:
    """Pixel (x, y-down) -> world-like (x, y-up) in world units."""
    out = np.asarray(points_px, dtype=np.float64) / scale
    out[:, 1] *= -1
    return out


def clockwise(points: np.ndarray) -> np.ndarray:
    """The same polygon listed clockwise in a y-up frame."""
    pts = [(float(x), float(y)) for x, y in points]
    return points if signed_area(pts) < 0 else points[::-1].copy()


def _angles(points: np.ndarray) -> np.ndarray:
    """Interior angle (radians) at each vertex of a convex polygon."""
    prev = np.roll(points, 1, axis=0) - points
    nxt = np.roll(points, -1, axis=0) - points
    cos = (prev * nxt).sum(axis=1) / (np.linalg.norm(prev, axis=1) *
                                        np.linalg.norm(nxt, axis=1) + 1e-12)
    return np.asarray(np.arccos(np.clip(cos, -1.0, 1.0)))


def canonical_start(label: str, points: np.ndarray) -> tuple[int, bool]:
    """Index of the canonical vertex in a clockwise polygon, and whether the piece looks
    mirrored (a parallelogram whose acute corners start short sides)."""
    angles = _angles(points)
    if len(points) == 3:
        return int(np.argmin(np.abs(angles - math.pi / 2))), False
    lengths = np.linalg.norm(np.roll(points, -1, axis=0) - points, axis=1)
    if label == "parallelogram":
        acute = sorted(np.argsort(angles)[:2].tolist())
        long_first = [i for i in acute if lengths[i] >= lengths[(i + 1) % 4]]
        if long_first:
            return long_first[0], False
        return acute[0], True
    # The square (or an unknown quadrilateral): the top-left-most corner, for stability.
    return int(np.argmin(points[:, 0] - points[:, 1])), False


def fit_model(label: str, corners: np.ndarray) -> PlacedPiece:
    """The piece's exact model, rotated and shifted onto clockwise corners (world units)
    that start at the canonical vertex."""
    model = np.array(piece_model(label), dtype=np.float64)
    if len(model) != len(corners):
        raise ValueError(f"{label} has {len(model)} corners, the outline {len(corners)}")
    mc = model - model.mean(axis=0)
    pc = corners - corners.mean(axis=0)
    dot = float((mc * pc).sum())
    cross = float((mc[:, 0] * pc[:, 1] - mc[:, 1] * pc[:, 0]).sum())
    theta = math.atan2(cross, dot)
    c, s = math.cos(theta), math.sin(theta)
    rotated = mc @ np.array([[c, s], [-s, c]])
    placed = rotated + corners.mean(axis=0)
    error = float(np.sqrt(((placed - corners) ** 2).sum(axis=1).mean()))
    return PlacedPiece(label=label, vertices=tuple((float(x), float(y)) for x, y in placed),
                       fit_error=error)


def contacts(a: PlacedPiece, b: PlacedPiece, *, max_angle: float, max_distance: float,
             min_overlap: float) -> list[tuple[int, int]]:
    """Every (side of a, side of b) that touch."""
    out = []
    na, nb = len(a.vertices), len(b.vertices)
    for i in range(na):
        for j in range(nb):
            if sides_touch((a.vertices[i], a.vertices[(i + 1) % na]),
                           (b.vertices[j], b.vertices[(j + 1) % nb]), max_angle=max_angle,
                           max_distance=max_distance, min_overlap=min_overlap):
                out.append((i, j))
    return out


def contact_share(a: PlacedPiece, b: PlacedPiece, sides: tuple[int, int]) -> float:
    """Share of the shorter of two facing sides that the other one covers, measured
    along side `sides[0]` of `a` (1.0: the shorter side lies wholly along the longer)."""
    i, j = sides
    p0, p1 = np.array(a.vertices[i]), np.array(a.vertices[(i + 1) % len(a.vertices)])
    q0, q1 = np.array(b.vertices[j]), np.array(b.vertices[(j + 1) % len(b.vertices)])
    lp, lq = float(np.linalg.norm(p1 - p0)), float(np.linalg.norm(q1 - q0))
    if min(lp, lq) < 1e-9:
        return 0.0
    direction = (p1 - p0) / lp
    t0, t1 = float((q0 - p0) @ direction), float((q1 - p0) @ direction)
    overlap = min(lp, max(t0, t1)) - max(0.0, min(t0, t1))
    return max(0.0, overlap) / min(lp, lq)


def borderline(a: PlacedPiece, b: PlacedPiece, sides: tuple[int, int], *, max_angle: float,
               max_distance: float, min_overlap: float) -> bool:
    """Whether a pair of sides touches under tolerances `MARGIN` times as wide as the
    given ones but not under narrower ones (offset `CLOSE` times smaller, angle and
    overlap `MARGIN` times stricter): a contact the measurement cannot settle."""
    i, j = sides
    p = (a.vertices[i], a.vertices[(i + 1) % len(a.vertices)])
    q = (b.vertices[j], b.vertices[(j + 1) % len(b.vertices)])
    loose = sides_touch(p, q, max_angle=MARGIN * max_angle,
                        max_distance=MARGIN * max_distance, min_overlap=min_overlap / MARGIN)
    tight = sides_touch(p, q, max_angle=max_angle / MARGIN,
                        max_distance=max_distance / CLOSE,
                        min_overlap=min(0.95, MARGIN * min_overlap))
    return loose and not tight
