"""What the tabletop detector could not account for: furniture cut in two by something
in front of it, and areas no detected object explains.

A bar, an arm or an unknown object in front of a table splits its fill into two
regions. Two fills of one furniture colour whose tops lie on one line, with no wall
between them, are one piece of furniture seen around an occluder: they are joined and
the occlusion is reported. Whatever is left unexplained (not wall, not floor, not a
detected object or its outline) is an area the graph says nothing about, so the graph
may miss what is there or behind it; such areas make the result a proposal.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from verigraph.perception.colors import BACKGROUND, FLOOR
from verigraph.perception.regions import Region

TOP_TOLERANCE = 3  # px between the tops of two parts of one piece of furniture
MAX_GAP_SHARE = 0.5  # of the narrower part's width
WALL_IN_GAP = 0.2  # share of wall pixels in the gap that says "two pieces, not one"
FLOOR_TILT = 0.06  # rise of the floor's edge across the image (about 3.5 degrees)
OUTLINE_REACH = 3  # px around a detection that its outline and blur may cover


def join_occluded(parts: list[Region], classes: np.ndarray) -> tuple[list[Region], list[str]]:
    """Furniture parts of one colour split by an occluder, joined; with a note each."""
    notes: list[str] = []
    parts = sorted(parts, key=lambda r: r.x0)
    out: list[Region] = []
    for part in parts:
        if out and _same_piece(out[-1], part, classes):
            left = out[-1]
            notes.append(f"something in front hides columns {left.x1}-{part.x0} of a piece "
                         "of furniture; its two visible parts were joined")
            out[-1] = left.merged(part)
        else:
            out.append(part)
    return out, notes


def _same_piece(left: Region, right: Region, classes: np.ndarray) -> bool:
    gap = right.x0 - left.x1
    if gap <= 0 or abs(left.y0 - right.y0) > TOP_TOLERANCE:
        return False
    if gap > MAX_GAP_SHARE * min(left.width, right.width):
        return False
    top = max(left.y0, right.y0)
    band = classes[top:top + max(3, min(left.height, right.height) // 4), left.x1:right.x0]
    return band.size > 0 and float(np.mean(band == BACKGROUND)) < WALL_IN_GAP


def unexplained_areas(classes: np.ndarray, regions: Sequence[Region], floor_row: int | None,
                      min_area: int) -> tuple[list[tuple[int, int, int, int]], float]:
    """Boxes (x0, y0, x1, y1) of areas that are neither wall, floor nor a detected
    object (with its outline), each at least `min_area` pixels after a 1-px erosion;
    and the share of the scene (what is not wall or floor) that is explained."""
    explained = _open_wall(classes, regions, floor_row)
    if floor_row is not None:
        explained[floor_row:, :] = 1
        # A slightly rolled camera tilts the floor's edge above the floor row.
        near = max(0, floor_row - int(FLOOR_TILT * classes.shape[1]))
        explained[near:floor_row][classes[near:floor_row] == FLOOR] = 1
    objects = np.zeros_like(explained)
    for r in regions:
        objects[r.y0:r.y1, r.x0:r.x1] |= r.mask.view(np.uint8)
    reach = 2 * OUTLINE_REACH + 1
    objects = cv2.dilate(objects, np.ones((reach, reach), np.uint8))
    rest = ((explained | objects) == 0).view(np.uint8)
    rest = cv2.erode(rest, np.ones((3, 3), np.uint8))
    scene = max(1, int(np.count_nonzero(explained == 0)))
    left = int(np.count_nonzero(rest))
    share = 1.0 - min(1.0, left / scene)
    if left < min_area:  # no area can be large enough: skip the labelling
        return [], share
    x, y, w, h = cv2.boundingRect(rest)  # label only the box the leftovers lie in
    n, _, stats, _ = cv2.connectedComponentsWithStats(rest[y:y + h, x:x + w], connectivity=4)
    return [(int(x + bx), int(y + by), int(x + bx + bw), int(y + by + bh))
            for bx, by, bw, bh, area in stats[1:n] if area >= min_area], share


def _open_wall(classes: np.ndarray, regions: Sequence[Region], floor_row: int | None
               ) -> np.ndarray:
    """Wall-coloured pixels that are the wall: connected to the image border or the
    floor, or inside a detected object's convex hull (a cup's cavity, the wall between
    a table's legs). A wall-coloured pocket elsewhere is something white or silver
    that no detection accounts for (a plate a colour cast turned the wall's colour)."""
    wall = (classes == BACKGROUND).view(np.uint8)
    n, labels = cv2.connectedComponents(wall, connectivity=4)
    if n <= 1:
        return wall.copy()
    edge = [labels[0], labels[-1], labels[:, 0], labels[:, -1]]
    if floor_row is not None and floor_row > 0:
        edge.append(labels[floor_row - 1])
    is_open = np.zeros(n, dtype=np.uint8)  # a lookup per label is far cheaper than isin
    is_open[np.concatenate(edge)] = 1
    is_open[0] = 0
    out = np.take(is_open, labels)
    hulls = np.zeros_like(out)
    for r in regions:
        if r.area >= 3:
            cv2.fillConvexPoly(hulls, r.hull(), 1)
    return np.asarray(out | (hulls & wall))
