"""Tangram pieces partly hidden by something in front: the piece's exact shape placed
over what shows of it.

A bar across a figure cuts a piece into parts, or cuts a corner off it; the outline of
what shows is not the piece's, and a polygon fitted to it is wrong. But the piece's
shape and the picture's scale are known, and whatever part of it is not seen lies
under the occluder. So the model is placed where it covers every visible pixel of the
piece's colour (within `OUTLINE_SLACK`) and shows nothing else where the picture is
seen: all of its area that is not the piece's colour must be hidden (deeper than
`SHOWN_INSET`; `ACCEPT`). Placements are proposed by the piece's visible sides: each
straight stretch of the visible outline that runs clear of the occluder is part of one
side of the model, with one of its two ends at that side's corner (the other end may
be where the side goes under the occluder). The best few placements are then refined
onto the visible sides (a least-squares fit of their lines, with the drawn outline's
share) and judged again. The best is settled only when what shows pins it down: no
other refined placement, placed differently, explains what shows about as well
(judged more finely), and three of its sides show; otherwise it is kept but not
settled (too little of the piece shows to say where the rest lies). A piece with no
visible side, or with no placement that explains what shows, is left to the ordinary
fit (and doubted for the occluder).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.sim2d.tangram_geometry import piece_model

CLEAR = 3  # px: a visible side runs at least this far from the occluder
MIN_SIDE = 0.3  # world units: shortest visible stretch taken for a side
OUTLINE_SLACK = 1  # px around the model that the piece's visible pixels may reach
SHOWN_INSET = 4  # px inside the model before a visible pixel of another colour counts (a
# piece drawn early loses part of its fill to the outlines of later ones) ...
FITTED_INSET = 2  # ... and when two placements fitted to the visible sides are compared
ACCEPT = 0.05  # largest unexplained pixels (missed plus shown), as a share of the piece
ON_SIDE = 5.0  # px from a side of the placed model within which outline points are its
CORNER_GAP = 3.0  # px from a side's ends where the drawn outline rounds the corner
REFINE_STEPS = 4  # Gauss-Newton steps of the fit onto the visible sides
MIN_SIDE_POINTS = 4  # hull points along a side before it counts as seen
MAX_OFFSET = 3.0  # px: the most the drawn fill's sides lie in or out of the model's
REFINED = 6  # best rough placements refined onto the visible sides ...
ROUGH = 4.0  # ... among those within this many times the accepted error
AMBIGUOUS = 0.025  # another placement this close in error (share of the piece) ...
SAME = 0.5  # ... with a corner this far (world units) from the best's: not settled
SEEN_SIDES = 3  # sides a settled completion shows ...
SEEN_POINTS = 6  # ... each along at least this many px of its visible hull ...
ON_EDGE = 3.0  # ... lying within this many px of it
SHIFT = 4  # bits of sub-pixel precision when a polygon is drawn


@dataclass(frozen=True, slots=True)
class Completion:
    """A piece's outline completed under an occluder: its corners in pixels (as an
    unoccluded piece's outline gives them), and whether what shows settles them (no
    other placement explains it about as well)."""

    corners: np.ndarray
    settled: bool


def complete_piece(label: str, visible: np.ndarray, hidden: np.ndarray, scale: float,
                   inset: float = 0.0) -> Completion | None:
    """The outline of the piece `label` completed over its `visible` pixels (bool, the
    image's shape) where the rest of it lies under `hidden` (bool, what occluders
    cover), at `scale` pixels per world unit; None when no placement explains what
    shows.
    `inset`: how far (px) the drawn fill's sides lie outside the model's at this scale
    (negative: inside) in pieces seen whole (`drawn_offset`), taken where what shows
    of this piece cannot tell."""
    if scale <= 0 or not visible.any():
        return None
    model = np.array(piece_model(label), dtype=np.float64)
    reach = int(np.ceil(np.abs(model).max() * 2 * scale)) + 4
    ys, xs = np.nonzero(visible)
    h, w = visible.shape
    x0, y0 = max(0, int(xs.min()) - reach), max(0, int(ys.min()) - reach)
    x1, y1 = min(w, int(xs.max()) + reach + 1), min(h, int(ys.max()) + reach + 1)
    seen = visible[y0:y1, x0:x1]
    cover = hidden[y0:y1, x0:x1].view(np.uint8)
    near = cv2.dilate(cover, np.ones((2 * CLEAR + 1, 2 * CLEAR + 1), np.uint8)).astype(bool)
    hull = _hull(seen)
    if hull is None:
        return None
    sides = _clear_sides(hull, near, MIN_SIDE * scale)
    if not sides:
        return None
    area = abs(_signed_area(model)) * scale * scale
    allowed = seen | cover.astype(bool)  # where the model may lie: the piece or the hidden
    rough = sorted((_cost(corners, seen, allowed, SHOWN_INSET), k, corners)
                   for k, corners in enumerate(c for p, q in sides
                                               for c in _placements(model, p, q, scale)))
    pts = _clear_points(hull, near)
    fitted = [_refine(corners, pts, inset) for cost, _, corners in rough[:REFINED]
              if cost <= ROUGH * ACCEPT * area]
    judged = sorted((_cost(corners, seen, allowed, SHOWN_INSET), k, corners)
                    for k, corners in enumerate(fitted))
    if not judged or judged[0][0] > ACCEPT * area:
        return None
    best = judged[0][2]
    # Rivals are told apart more finely: what shows near their corners counts too.
    least = _cost(best, seen, allowed, FITTED_INSET)
    rival = any(_apart(best, other) > SAME * scale
                and _cost(other, seen, allowed, FITTED_INSET) <= least + AMBIGUOUS * area
                for _, _, other in judged[1:])
    # Settled only where what shows pins it down: three of its sides seen along a few
    # px each (two sides leave how far the third lies to the outline's share; slivers
    # at two corners of a small triangle fit more than one placement).
    sure = not rival and _sides_seen(best, pts) >= SEEN_SIDES
    return Completion(np.asarray(best + np.array([x0, y0], np.float64)), sure)


def _apart(a: np.ndarray, b: np.ndarray) -> float:
    """How far the corners of one polygon lie from the nearest of another's, at most."""
    return float(np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2).min(axis=1).max())


def _hull(mask: np.ndarray) -> np.ndarray | None:
    """Convex hull of a mask's pixel centres, shape (n, 2), in the frame where pixel i
    spans i to i + 1 (as `tangram.piece_outline` gives corners), with a negative signed area
    in these (y-down) coordinates: clockwise as OpenCV counts with y up."""
    ys, xs = np.nonzero(mask)
    if len(xs) < 3:
        return None
    pts = np.stack([xs, ys], axis=1).astype(np.float32)
    hull = cv2.convexHull(pts, clockwise=True).reshape(-1, 2).astype(np.float64) + 0.5
    return hull if len(hull) >= 3 else None


def _along(hull: np.ndarray) -> np.ndarray:
    """Points every pixel or so along a closed polygon's sides."""
    out = []
    for k in range(len(hull)):
        p, q = hull[k], hull[(k + 1) % len(hull)]
        n = max(1, int(np.ceil(np.linalg.norm(q - p))))
        out.append(p + np.linspace(0.0, 1.0, n, endpoint=False)[:, None] * (q - p))
    return np.concatenate(out)


def _clear_sides(hull: np.ndarray, near: np.ndarray, shortest: float
                 ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Stretches (start, end) of the hull's edges, at least `shortest` px long, that
    run clear of the occluder (`near`: within `CLEAR` px of it): parts of the piece's
    own sides (an edge the occluder crosses shows on either side of it)."""
    h, w = near.shape
    out = []
    for k in range(len(hull)):
        p, q = hull[k], hull[(k + 1) % len(hull)]
        length = float(np.linalg.norm(q - p))
        if length < shortest:
            continue
        t = np.linspace(0.0, 1.0, max(2, int(np.ceil(length)) + 1))
        pts = np.round(p + t[:, None] * (q - p) - 0.5).astype(int)
        clear = ~near[np.clip(pts[:, 1], 0, h - 1), np.clip(pts[:, 0], 0, w - 1)]
        steps = np.flatnonzero(np.diff(np.concatenate(([0], clear.view(np.int8), [0]))))
        for a, b in zip(steps[::2].tolist(), steps[1::2].tolist(), strict=True):
            start, end = p + t[a] * (q - p), p + t[b - 1] * (q - p)
            if float(np.linalg.norm(end - start)) >= shortest:
                out.append((start, end))
    return out


def _placements(model: np.ndarray, p: np.ndarray, q: np.ndarray, scale: float
                ) -> list[np.ndarray]:
    """The model's corners (px, y down) placed so that one of its sides runs along the
    visible stretch p -> q of the hull (`_hull`), its start at p or its end at q, for
    every side the stretch fits in; in the model's own corner order."""
    pts = model * scale
    pts[:, 1] *= -1  # y down: the model's signed area turns positive ...
    pts = pts[::-1]  # ... so it is reversed to run as the hull does (negative)
    n = len(pts)
    seen = q - p
    length = float(np.linalg.norm(seen))
    angle = math.atan2(seen[1], seen[0])
    out = []
    for j in range(n):
        a, b = pts[j], pts[(j + 1) % n]
        side = b - a
        if float(np.linalg.norm(side)) < 0.9 * length:
            continue  # a side cannot show longer than it is
        turn = angle - math.atan2(side[1], side[0])
        c, s = math.cos(turn), math.sin(turn)
        turned = pts @ np.array([[c, s], [-s, c]])
        for anchor, at in ((turned[j], p), (turned[(j + 1) % n], q)):
            out.append((turned - anchor + at)[::-1].copy())  # back to the model's order
    return out


def _cost(corners: np.ndarray, seen: np.ndarray, allowed: np.ndarray, inset: int
          ) -> float:
    """Pixels a placement leaves unexplained: visible pixels of the piece outside it
    (beyond `OUTLINE_SLACK`) and pixels inside it (deeper than `inset`) that show
    something else."""
    shape = seen.shape
    poly = np.zeros(shape, np.uint8)
    cv2.fillConvexPoly(poly, np.round((corners - 0.5) * (1 << SHIFT)).astype(np.int32), 1,
                       cv2.LINE_8, SHIFT)
    grown = cv2.dilate(poly, np.ones((2 * OUTLINE_SLACK + 1,) * 2, np.uint8)).astype(bool)
    inner = cv2.erode(poly, np.ones((2 * inset + 1,) * 2, np.uint8),
                      borderType=cv2.BORDER_CONSTANT, borderValue=0).astype(bool)
    return float(np.count_nonzero(seen & ~grown) + np.count_nonzero(inner & ~allowed))


def _refine(corners: np.ndarray, pts: np.ndarray, inset: float) -> np.ndarray:
    """The outline of the piece's drawn fill: the placement turned and shifted onto the
    piece's visible sides, and its sides moved in or out alike by the drawn outline's
    share (the fill lies inside the outline; an unoccluded piece's outline shows the
    same). Fitted by least squares of the distances to the side lines of the points of
    the visible part's convex hull (where the outlines of pieces drawn later have not
    bitten into its fill; `pts`, clear of the occluder: `_clear_points`) that lie along
    a side (within `ON_SIDE` px, clear of the corners, which the drawn outline rounds),
    in a few Gauss-Newton steps. The offset is fitted only where the visible sides
    settle it (three sides, or two parallel ones); otherwise it is `inset`, and a shift
    the visible sides do not settle stays. The corners returned are where the moved sides meet."""
    offset = inset
    for _ in range(REFINE_STEPS):
        normals, lines, chosen = _side_points(corners, pts, offset)
        if len(chosen) < 2:
            break
        centre = corners.mean(axis=0)
        across = np.stack([-normals[:, 1], normals[:, 0]], axis=1)
        residual = (normals * chosen).sum(axis=1) - lines
        columns = [(across * (chosen - centre)).sum(axis=1), -normals[:, 0], -normals[:, 1]]
        free = _settles_offset(np.unique(np.round(normals, 6), axis=0))
        if free:
            columns.append(-np.ones(len(chosen)))
        step, *_ = np.linalg.lstsq(np.column_stack(columns), -residual, rcond=None)
        c, s = math.cos(float(step[0])), math.sin(float(step[0]))
        corners = (corners - centre) @ np.array([[c, s], [-s, c]]) + centre + step[1:3]
        if free:
            offset = float(np.clip(offset + step[3], -MAX_OFFSET, MAX_OFFSET))
    return _moved_out(corners, offset)


def _clear_points(hull: np.ndarray, near: np.ndarray) -> np.ndarray:
    """Points every pixel or so along the hull's sides that lie clear of the occluder
    (`near`)."""
    pts = _along(hull)
    h, w = near.shape
    ix = np.clip(pts[:, 0].astype(int), 0, w - 1)
    iy = np.clip(pts[:, 1].astype(int), 0, h - 1)
    return np.asarray(pts[~near[iy, ix]])


def _sides_seen(corners: np.ndarray, pts: np.ndarray) -> int:
    """How many sides of an outline the visible hull points `pts` show along at least
    `SEEN_POINTS` px (within `ON_EDGE` px of the side, clear of its corners)."""
    return sum(int(np.count_nonzero(on) >= SEEN_POINTS)
               for _, _, on in _near_sides(corners, pts, ON_EDGE))


def _near_sides(corners: np.ndarray, pts: np.ndarray, reach: float, offset: float = 0.0
                ) -> Iterator[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """For each side of a convex outline longer than `2 * CORNER_GAP`, moved out by
    `offset` px: its unit outward normal, its first corner (unmoved), and which of the
    points `pts` lie within `reach` px of it, at least `CORNER_GAP` px from its ends."""
    n = len(corners)
    normals = _outward(corners)
    for j in range(n):
        a, b = corners[j], corners[(j + 1) % n]
        length = float(np.linalg.norm(b - a))
        if length <= 2 * CORNER_GAP:
            continue
        t = (pts - a) @ ((b - a) / length)
        d = (pts - a) @ normals[j] - offset
        yield normals[j], a, (np.abs(d) <= reach) & (t >= CORNER_GAP) & (t <= length - CORNER_GAP)


def _settles_offset(normals: np.ndarray) -> bool:
    """Whether sides with these outward normals fix how far they all lie out (beside
    the shift): (0, 0, 1) is a combination of the rows (normal, 1), as with three sides
    of a triangle or two opposite sides of a square, not with two sides at a corner."""
    if len(normals) < 2:
        return False
    rows = np.column_stack([normals, np.ones(len(normals))])
    target = np.array([0.0, 0.0, 1.0])
    weights, *_ = np.linalg.lstsq(rows.T, target, rcond=None)
    return bool(np.linalg.norm(rows.T @ weights - target) < 1e-6)


def _outward(corners: np.ndarray) -> np.ndarray:
    """Unit outward normals of a convex polygon's sides (side j from corner j)."""
    along = np.roll(corners, -1, axis=0) - corners
    along /= np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-9)
    sign = 1.0 if _signed_area(corners) > 0 else -1.0
    return np.asarray(sign * np.stack([along[:, 1], -along[:, 0]], axis=1))


def _moved_out(corners: np.ndarray, offset: float) -> np.ndarray:
    """A convex polygon with every side moved `offset` px outwards (inwards when
    negative): each corner moves along the sum of its two sides' normals."""
    if offset == 0.0:
        return corners
    normals = _outward(corners)
    before = np.roll(normals, 1, axis=0)  # the side ending at each corner
    dot = (normals * before).sum(axis=1, keepdims=True)
    return np.asarray(corners + offset * (normals + before) / (1.0 + dot))


def _side_points(corners: np.ndarray, pts: np.ndarray, offset: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the outline points `pts` that lie along a side of the placed model moved
    out by `offset` (within `ON_SIDE` px of it, at least `CORNER_GAP` px from its
    ends): each one's side as its unit outward normal and line (normal . x = line on
    the moved side), and the points."""
    normals, lines, chosen = [], [], []
    for normal, a, keep in _near_sides(corners, pts, ON_SIDE, offset):
        count = int(keep.sum())
        if count < MIN_SIDE_POINTS:
            continue
        normals.append(np.repeat(normal[None], count, axis=0))
        lines.append(np.full(count, float(normal @ a) + offset))
        chosen.append(pts[keep])
    if not chosen:
        return np.zeros((0, 2)), np.zeros(0), np.zeros((0, 2))
    return np.concatenate(normals), np.concatenate(lines), np.concatenate(chosen)


def drawn_offset(pieces: list[tuple[np.ndarray, np.ndarray, tuple[int, int]]]) -> float:
    """How far (px) the drawn fills' sides (their convex hulls') lie outside their
    fitted models' (negative: inside), the median over pieces seen whole: each given
    as its model's corners (pixels), its region's mask and the mask's top-left corner.
    0 with none."""
    found = []
    for corners, mask, (x0, y0) in pieces:
        hull = _hull(mask)
        if hull is None:
            continue
        normals, lines, chosen = _side_points(corners, _along(hull) + np.array([x0, y0]),
                                              0.0)
        if len(chosen):
            found.append(float(np.median((normals * chosen).sum(axis=1) - lines)))
    return float(np.median(found)) if found else 0.0


def _signed_area(pts: np.ndarray) -> float:
    x, y = pts[:, 0], pts[:, 1]
    return 0.5 * float((x * np.roll(y, -1) - np.roll(x, -1) * y).sum())
