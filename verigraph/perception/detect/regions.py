"""Connected regions of one colour class: the fragments objects are assembled from.

Every object is drawn as a filled outline, so after pixel classification an object is
one (or, when something covers part of it, a few) connected areas of its colour. A
fragment must keep some pixels after a one-pixel erosion: the thin rims that blur and
JPEG leave along outlines, and isolated noise pixels, have no such core.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import cv2
import numpy as np

from verigraph.perception.detect.colors import BACKGROUND, DARK, FIRST_OBJECT, ColourTable, purity

KERNEL3 = np.ones((3, 3), np.uint8)
CROSS3 = cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))
PURE = 8  # Lab distance of a pixel that shows its colour unmixed
PURE_PIXELS = 10
NEAR_PURE = 15  # median distance of a blurred, still recognisable thin part
BORDER_POCKET_SHARE = 0.01
THICK_CORE_SHARE = 0.5  # a thick region keeps half its pixels under a 1-px erosion


@dataclass(slots=True)
class Region:
    """Pixels of one colour class: a boolean mask cropped to its bounding box."""

    cls: int
    x0: int
    y0: int
    mask: np.ndarray
    area: int = field(init=False)
    _hull: np.ndarray | None = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.area = int(np.count_nonzero(self.mask))

    @property
    def x1(self) -> int:
        """One past the right-most column."""
        return self.x0 + self.mask.shape[1]

    @property
    def y1(self) -> int:
        """One past the bottom row."""
        return self.y0 + self.mask.shape[0]

    @property
    def width(self) -> int:
        return int(self.mask.shape[1])

    @property
    def height(self) -> int:
        return int(self.mask.shape[0])

    def centroid(self) -> tuple[float, float]:
        ys, xs = np.nonzero(self.mask)
        return float(xs.mean()) + self.x0, float(ys.mean()) + self.y0

    def points(self) -> np.ndarray:
        """Pixel coordinates (x, y) of the region, shape (n, 2), int32."""
        ys, xs = np.nonzero(self.mask)
        return np.stack([xs + self.x0, ys + self.y0], axis=1).astype(np.int32)

    def hull(self) -> np.ndarray:
        """Convex hull of the region's pixels (as `cv2.convexHull` of `points()` gives
        it), computed once. Only the left-most and right-most pixel of each row can be a
        hull vertex, so the hull is taken over those: the same polygon from a few hundred
        points instead of every pixel of a table."""
        if self._hull is None:
            m = self.mask
            rows = np.flatnonzero(m.any(axis=1))
            left = np.argmax(m[rows], axis=1)
            right = m.shape[1] - 1 - np.argmax(m[rows, ::-1], axis=1)
            xs = np.concatenate([left, right]) + self.x0
            ys = np.concatenate([rows, rows]) + self.y0
            self._hull = np.asarray(cv2.convexHull(np.stack([xs, ys], axis=1)
                                                   .astype(np.int32)))
        return self._hull

    def shifted(self, dx: int, dy: int) -> Region:
        """The same region with its box moved by (dx, dy) (crop -> image coordinates)."""
        return Region(self.cls, self.x0 + dx, self.y0 + dy, self.mask)

    def merged(self, other: Region) -> Region:
        """One region covering both (same class as self)."""
        x0, y0 = min(self.x0, other.x0), min(self.y0, other.y0)
        x1, y1 = max(self.x1, other.x1), max(self.y1, other.y1)
        mask = np.zeros((y1 - y0, x1 - x0), dtype=bool)
        for r in (self, other):
            mask[r.y0 - y0:r.y1 - y0, r.x0 - x0:r.x1 - x0] |= r.mask
        return Region(self.cls, x0, y0, mask)

    def union_box(self, other: Region) -> tuple[int, int]:
        """Width and height of the box around both regions."""
        return (max(self.x1, other.x1) - min(self.x0, other.x0),
                max(self.y1, other.y1) - min(self.y0, other.y0))


def core_area(mask: np.ndarray) -> int:
    """Pixels left after a one-pixel erosion (0 for lines at most two pixels thick)."""
    eroded = cv2.erode(mask.view(np.uint8), KERNEL3, borderType=cv2.BORDER_CONSTANT,
                       borderValue=0)
    return int(np.count_nonzero(eroded))


def _solid(piece: np.ndarray, pixels: np.ndarray, table: ColourTable, min_core: int,
           cls: int) -> bool:
    """A fragment, not a rim: thick enough, or thin but drawn in its own pure colour
    (a cup's wall at a small scale is thinner than the outline around it), or thin in a
    colour that no blurred edge of another colour imitates (blur takes the purity of a
    thin yellow wall, but nothing else turns yellow)."""
    if core_area(piece) >= min_core:
        return True
    if int(np.count_nonzero(purity(pixels[piece], table) < PURE)) >= PURE_PIXELS:
        return True
    if cls in table.confusable or int(np.count_nonzero(piece)) < 3 * min_core:
        return False
    # ... and still close to its colour on the whole (JPEG ringing makes thin streaks
    # of far-off colours that happen to fall in a class).
    return float(np.median(purity(pixels[piece], table))) < NEAR_PURE


def colour_fragments(image: np.ndarray, classes: np.ndarray, table: ColourTable, *,
                     min_core: int) -> list[Region]:
    """Connected regions of each object colour (bright colours are handled separately)."""
    objects = (classes >= FIRST_OBJECT).view(np.uint8)
    if table.bright:
        for c in table.bright:
            objects[classes == c] = 0
    n, labels, stats, _ = cv2.connectedComponentsWithStats(objects, connectivity=4)
    out: list[Region] = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if area < min(min_core, PURE_PIXELS):
            continue  # noise specks: too small for either test in _solid
        comp = labels[y:y + h, x:x + w] == i
        crop = classes[y:y + h, x:x + w]
        counts = np.bincount(crop[comp], minlength=len(table.names))
        present = [c for c in range(FIRST_OBJECT, len(counts)) if counts[c] >= min_core]
        pixels = image[y:y + h, x:x + w]
        if len(present) == 1 and counts[present[0]] == area:
            if _solid(comp, pixels, table, min_core, present[0]):
                out.append(Region(present[0], x, y, comp))
            continue
        for c in present:  # touching fills of different colours: split by colour
            sub = (comp & (crop == c)).view(np.uint8)
            m, sub_labels, sub_stats, _ = cv2.connectedComponentsWithStats(sub, connectivity=4)
            for j in range(1, m):
                sx, sy, sw, sh, _ = (int(v) for v in sub_stats[j])
                piece = sub_labels[sy:sy + sh, sx:sx + sw] == j
                if _solid(piece, pixels[sy:sy + sh, sx:sx + sw], table, min_core, c):
                    out.append(Region(c, x + sx, y + sy, piece))
    return [part for r in out for part in trimmed(r, min_core)]


def trimmed(region: Region, min_core: int) -> list[Region]:
    """A thick region without the one- and two-pixel slivers blur glues onto it (the
    brownish edge of an orange block joins the brown table it stands on)."""
    if core_area(region.mask) < THICK_CORE_SHARE * region.area:
        return [region]
    padded = np.pad(region.mask.view(np.uint8), 1)
    opened = cv2.morphologyEx(padded, cv2.MORPH_OPEN, KERNEL3)[1:-1, 1:-1]
    if np.count_nonzero(opened) == region.area:
        return [region]
    n, labels, stats, _ = cv2.connectedComponentsWithStats(opened, connectivity=4)
    parts = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if area >= min_core:
            parts.append(Region(region.cls, region.x0 + x, region.y0 + y,
                                labels[y:y + h, x:x + w] == i))
    return parts


def dark_blobs(classes: np.ndarray, cls: int, *, min_area: int, line_width: int = 5
               ) -> list[Region]:
    """Solid dark objects (a black stove): dark areas thicker than any outline."""
    dark = (classes == DARK).view(np.uint8)
    kernel = np.ones((line_width, line_width), np.uint8)
    core = cv2.erode(dark, kernel)
    n, labels, stats, _ = cv2.connectedComponentsWithStats(core, connectivity=4)
    out = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if area < min_area:
            continue
        pad = line_width
        x0, y0 = max(0, x - pad), max(0, y - pad)
        x1, y1 = min(dark.shape[1], x + w + pad), min(dark.shape[0], y + h + pad)
        blob = (labels[y0:y1, x0:x1] == i).view(np.uint8)
        grown = cv2.dilate(blob, kernel).astype(bool) & dark[y0:y1, x0:x1].astype(bool)
        out.append(Region(cls, x0, y0, grown))
    return out


def enclosed_bright(image: np.ndarray, classes: np.ndarray, table: ColourTable, *,
                    min_core: int) -> list[Region]:
    """Background-coloured areas cut off from the image border: candidates for white or
    silver objects, which per pixel look like the background (their class is decided
    later, by size and mean colour).

    Blur can open a one-pixel gap in the outline at a plate's thin tip, joining the
    plate to the background; a second pass on the mask opened by a 3x3 cross closes
    such leaks (at the cost of pockets thinner than three pixels, which the first pass
    keeps).
    """
    bright = (classes == BACKGROUND)
    for c in table.bright:
        bright |= classes == c
    mask = bright.view(np.uint8)
    out = _pockets(mask, image, classes, table, min_core)
    opened = cv2.morphologyEx(mask, cv2.MORPH_OPEN, CROSS3)
    for region in _pockets(opened, image, classes, table, min_core):
        if not any(_inside(region, r) for r in out):
            out.append(region)
    return out


def _inside(a: Region, b: Region) -> bool:
    return b.x0 <= a.x0 and b.y0 <= a.y0 and a.x1 <= b.x1 and a.y1 <= b.y1


def _pockets(mask: np.ndarray, image: np.ndarray, classes: np.ndarray, table: ColourTable,
             min_core: int) -> list[Region]:
    n, labels, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=4)
    h_img, w_img = mask.shape
    out = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if (x == 0 or y == 0 or x + w >= w_img or y + h >= h_img) and \
                area > BORDER_POCKET_SHARE * h_img * w_img:
            continue  # the background itself (an object cut by the frame is small)
        comp = labels[y:y + h, x:x + w] == i
        if area >= 2 * min_core or _pure_bright(comp, image[y:y + h, x:x + w],
                                                classes[y:y + h, x:x + w], table):
            out.append(Region(BACKGROUND, x, y, comp))
    return out


def _pure_bright(comp: np.ndarray, pixels: np.ndarray, classes: np.ndarray,
                 table: ColourTable) -> bool:
    """A thin enclosed area drawn in an unmixed bright object colour (a plate's edge)."""
    own = comp & np.isin(classes, list(table.bright))
    return int(np.count_nonzero(purity(pixels[own], table) < PURE)) >= PURE_PIXELS
