"""Something in front of the scene, and what the detector could not account for: bands
and blobs in front (`find_occluders`, both views), objects split by them, furniture cut
in two, and areas no detected object explains.

A band is found before any object is read, by its geometry alone: a flat area that
meets the frame with both ends (an arm reaching in) and is at least twice as long as
wide. A pole is a plain bar reaching in from the top edge or a side (a pole, a cable,
an arm link), square to it or tilted, found by following from that edge inwards a run
of one colour that the scenery there does not have, with its width unchanged, along a
straight line, for at least twice its width from a side and 1.25 times from the top
(`find_poles`); its colour does not matter (it may be any object's), only its
geometry. Their pixels, the end of a tilted bar and the part of one that leaves the
picture through another edge included, are then read as no object, and parts of one
colour facing each other across them are one object (`join_across`).

A bar, an arm or an unknown object in front of a table splits its fill into two
regions. Two fills of one furniture colour whose tops lie on one line, with no wall
between them, are one piece of furniture seen around an occluder: they are joined and
the occlusion is reported. Whatever is left unexplained (not wall, not floor, not a
detected object or its outline) is an area the graph says nothing about, so the graph
may miss what is there or behind it; such areas make the result a proposal.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.perception.detect import colors
from verigraph.perception.detect.colors import BACKGROUND, FLOOR, UNKNOWN
from verigraph.perception.detect.regions import Region

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
    # Pieces of furniture stand side by side; a part inside another's box of the same
    # colour is that piece seen around something in front of it (a hand on a counter).
    for small_index in sorted(range(len(out)), key=lambda i: out[i].area):
        small = out[small_index]
        if small.area == 0:
            continue
        host = next((i for i, r in enumerate(out) if i != small_index
                     and r.area > small.area and _within(small, r)), None)
        if host is not None:
            big = out[host]
            notes.append(f"something in front splits a piece of furniture (box {big.x0}, "
                         f"{big.y0}, {big.x1}, {big.y1}); its visible parts were joined")
            out[host] = big.merged(small)
            out[small_index] = Region(small.cls, small.x0, small.y0,
                                      np.zeros((0, 0), bool))
    out = [r for r in out if r.mask.size]
    return out, notes


def _within(inner: Region, outer: Region, slack: int = 2) -> bool:
    return (outer.x0 - slack <= inner.x0 and outer.y0 - slack <= inner.y0
            and inner.x1 <= outer.x1 + slack and inner.y1 <= outer.y1 + slack)


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
                      min_area: int, hidden: np.ndarray | None = None
                      ) -> tuple[list[Region], float]:
    """Areas (their pixels, as regions of class UNKNOWN) that are neither wall, floor
    nor a detected object (with its outline), each at least `min_area` pixels after a
    1-px erosion; and the share of the scene (what is not wall or floor) that is
    explained. What a band in front covers (`hidden`) is neither: it is not counted."""
    explained = _open_wall(classes, regions, floor_row)
    if hidden is not None:
        explained[hidden] = 1
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
    n, labels, stats, _ = cv2.connectedComponentsWithStats(rest[y:y + h, x:x + w],
                                                           connectivity=4)
    return [Region(UNKNOWN, int(x + bx), int(y + by), labels[by:by + bh, bx:bx + bw] == i)
            for i, (bx, by, bw, bh, area) in enumerate(stats[1:n].tolist(), start=1)
            if area >= min_area], share


def area_occluders(areas: Sequence[Region], image: np.ndarray) -> list[Occluder]:
    """Unexplained areas that look like something in front: flat (one colour, as an
    occluder is; a failure of colour correction leaves wall-sized areas instead) and
    at most `AREA_SHARE` of the image."""
    h, w = image.shape[:2]
    step = _step(image)
    out = []
    for r in areas:
        if r.area > AREA_SHARE * h * w:
            continue
        flat = step[r.y0:r.y1, r.x0:r.x1][r.mask] <= FLAT_STEP
        if flat.size and float(np.mean(flat)) >= AREA_FLAT:
            out.append(Occluder("area", (r.x0, r.y0, r.x1, r.y1), r.mask.copy()))
    return out


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


FLAT_STEP = 14  # grey levels: largest colour step between neighbours inside a flat area
BAND_REACH = 0.6  # a band spans at least this share of the frame along its length
BAND_THIN = 0.5  # ... and is at most this share of its length wide
BAND_FILL = 0.75  # share of its bounding rectangle a band's flat area fills
BLOB_SHARE = 0.004  # smallest blob, as a share of the image
BLOB_SOLIDITY = 0.85  # area over convex-hull area of a blob (an irregular ellipse)
BLOB_FOREIGN = 45.0  # BGR distance from every palette colour that marks a foreign blob
AREA_SHARE = 0.25  # largest unexplained area taken for something in front
AREA_FLAT = 0.7  # share of its pixels an occluding area shows flat
TOUCH = 6  # px between an occluder and an object it hides part of
BORDER = 2  # px from the frame that count as reaching it
HIDING = ("band", "pole")  # occluders proven to be in front by their geometry
POLE_TOP_ROWS = 2  # rows at the top edge a pole is seen in (a crop keeps 2 px of wall)
POLE_OFF_WALL = 10  # largest channel difference from the wall that is still wall
POLE_MATCH = 28  # largest channel difference from the pole's colour along it ...
POLE_MATCH_SHARE = 0.5  # ... and at most this share of its difference from the wall
POLE_ROW_SHARE = 0.8  # share of a row's inner columns in the pole's colour
POLE_MIN_LENGTH = 0.06  # shortest pole, as a share of the image height
POLE_ASPECT = 2.0  # ... and at least this many times as long as wide (as a band) ...
POLE_TOP_ASPECT = 1.25  # ... or this many from the top edge, where the scene never shows
POLE_MAX_WIDTH = 0.25  # widest pole, as a share of the image width
POLE_APART = 0.6  # share of its rows in which a pole's sides differ from it
POLE_EDGES = ("top", "left", "right")  # edges a bar is looked for at
POLE_SCENERY = 30  # largest channel difference from a scenery colour along the edge
OUTLINE_DARK = 110  # brightest channel of an outline pixel (drawn 25, 25, 25; warped,
# blurred or scaled down it mixes with its neighbours) ...
OUTLINE_STEP = 40  # ... at least this much darker than the run's own colour ...
OUTLINE_MIN = 40  # ... and a run too dark to leave that room is not judged
OUTLINED = 0.5  # share of its rows in which a scene object cut by the frame shows them
POLE_REFERENCE = 0.3  # running-medoid window along an edge, as a share of its length
POLE_PASSES = 3  # times the scenery is found again with the runs found taken out
POLE_CORE = 10  # channel difference from its median colour of most of a bar's run where
# two sceneries meet
MEDIAN_SAMPLES = 31  # samples per window of the running medoid along an edge
POLE_DRIFT = 3  # px a bar's run is looked for beyond where its line puts it
POLE_TILT = 0.7  # largest drift of a bar's centre per row (35 degrees from square)


@dataclass(frozen=True, slots=True)
class Occluder:
    """Something in front of the scene: a straight band crossing the frame (an arm, a
    pole), a bar hanging from the top edge, a blob of a colour no object has (a hand),
    or an area no detected object explains (it may hide part of what it borders), with
    its pixels."""

    kind: str  # "band", "pole", "blob" or "area"
    box: tuple[int, int, int, int]  # x0, y0, x1, y1 (exclusive)
    mask: np.ndarray  # bool, the box's size
    edge: str = "top"  # the edge a pole reaches in from

    def describe(self) -> str:
        x0, y0, x1, y1 = self.box
        what = {"band": "a band across the picture", "blob": "a blob",
                "pole": "a bar hanging from the top edge" if self.edge == "top" else
                f"a bar reaching in from the {self.edge} edge",
                "area": "an area no detected object explains"}[self.kind]
        return f"{what} (box {x0}, {y0}, {x1}, {y1})"

    def full_mask(self, shape: tuple[int, int], grow: int = 0) -> np.ndarray:
        """The occluder's pixels in an image of `shape`, grown by `grow` px."""
        out: np.ndarray = np.zeros(shape, np.uint8)
        x0, y0, x1, y1 = self.box
        out[y0:y1, x0:x1] = self.mask.view(np.uint8)
        if grow:
            out = cv2.dilate(out, np.ones((2 * grow + 1, 2 * grow + 1), np.uint8))
        return out.astype(bool)


def find_occluders(image: np.ndarray, scenery: Sequence[tuple[int, int, int]],
                   object_colours: Sequence[tuple[int, int, int]]) -> list[Occluder]:
    """Flat areas in front of the scene: straight bands that run from one side of the
    frame to the other (no object of a scene does: objects stand inside the frame, and
    the floor band meets three sides), and compact blobs whose colour is far from the
    scenery (`scenery`: wall, floor, table) and from every colour the dictionary's
    objects are drawn in (`object_colours`). Colour does not matter for a band: an arm
    may be any colour, and its reach across the frame gives it away. A blob of an object
    colour is not found here; the detector's unexplained areas catch it."""
    h, w = image.shape[:2]
    step = _step(image)
    flat = (step <= FLAT_STEP).view(np.uint8)
    n, labels, stats, _ = cv2.connectedComponentsWithStats(flat, connectivity=4)
    foreign = np.array(list(scenery) + list(object_colours), dtype=np.float32).reshape(-1, 3)
    out: list[Occluder] = []
    for i in range(1, n):
        x, y, bw, bh, area = (int(v) for v in stats[i])
        if area < BLOB_SHARE * h * w / 4:
            continue
        touches = sum((x <= BORDER, y <= BORDER, x + bw >= w - BORDER, y + bh >= h - BORDER))
        # A band meets two sides of the frame, or three when it runs out at a corner.
        if touches in (1, 4) or (touches >= 2 and bw < BAND_REACH * w
                                                 and bh < BAND_REACH * h):
            continue  # the wall, the floor, the table; or a thing standing at the border
        comp = labels[y:y + bh, x:x + bw] == i
        kind = _band_or_blob(comp, area, x, y, (h, w), image, foreign)
        if kind is not None:
            # The flat interior, grown by 2 px over the occluder's own edges and outline.
            gx0, gy0 = max(0, x - 2), max(0, y - 2)
            gx1, gy1 = min(w, x + bw + 2), min(h, y + bh + 2)
            full: np.ndarray = np.zeros((y + bh + 2 - gy0, x + bw + 2 - gx0), np.uint8)
            full[y - gy0:y - gy0 + bh, x - gx0:x - gx0 + bw] = comp.view(np.uint8)
            full = cv2.dilate(full, np.ones((5, 5), np.uint8))[:gy1 - gy0, :gx1 - gx0]
            out.append(Occluder(kind, (gx0, gy0, gx1, gy1), full.astype(bool)))
    return out + find_poles(image, [o for o in out if o.kind == "band"], scenery)


def find_poles(image: np.ndarray, bands: Sequence[Occluder] = (),
               scenery: Sequence[tuple[int, int, int]] = ()) -> list[Occluder]:
    """Plain bars reaching into the picture from its top, left or right edge in front
    of the scene (a pole, a cable, an arm link), of any colour and length, square to
    the edge or tilted (`POLE_TILT`).

    The rows and columns at the edges of a picture show the scenery only (the wall, the
    floor, the tangram table): objects stand inside the frame. Each edge is turned to
    the top (`_edge_view`) and searched as the top edge is: a run of pixels that
    differs from the scenery along the edge (its running medoid, `POLE_REFERENCE`) in
    the `POLE_TOP_ROWS` outermost rows is followed inwards as long as its inner pixels
    keep its colour (`POLE_MATCH`, or half its difference from the scenery when that is
    less; `POLE_ROW_SHARE`; one row's gap is bridged), its centre allowed to drift row
    by row along a straight line (a tilted bar). It is a bar when it runs at least
    `POLE_ASPECT` times its width in (`POLE_TOP_ASPECT` from the top edge, where the
    scene never shows; both measured along the bar's axis) and `POLE_MIN_LENGTH` of
    the picture, and its sides differ from it along most of that length (`POLE_APART`;
    a same-coloured object it crosses joins it there, a thing merely reaching the edge
    does not keep its width). Its mask covers the run and 2 px around it (the
    anti-aliased sides), its end past the last row followed, and the rest of a bar
    that leaves through another edge (`_bar_end`). A run already inside a band crossing
    the frame is that band. Only where the edge shows the scenery (`scenery`, and the
    colours of the picture's top and bottom rows; `POLE_SCENERY`) around the run is it
    a bar (at a side: the wall before it, the wall or the floor after it): a camera
    rolled or tilted far enough cuts furniture and what stands on it off at a side, and
    that stretch of the edge (an object, its outline) is the scene, not something in
    front. A bar of the scenery's own colour does not show at the edge and is not
    found here."""
    h, w = image.shape[:2]
    if min(h, w) < 4 * POLE_TOP_ROWS or min(h, w) < 8:
        return []
    covered = hidden_mask(list(bands), (h, w))
    rows = np.concatenate([image[:POLE_TOP_ROWS], image[-POLE_TOP_ROWS:]]).reshape(-1, 3)
    known = np.array([*scenery, np.median(image[:POLE_TOP_ROWS].reshape(-1, 3), axis=0),
                      np.median(rows[len(rows) // 2:], axis=0)], np.int16).reshape(-1, 3)
    out: list[Occluder] = []
    for edge in POLE_EDGES:
        view = _edge_view(image, edge)
        taken = None if covered is None else _edge_view(covered, edge)
        # At a side the wall must show before a bar (above it) and the wall or the
        # floor after it: where a rolled or tilted camera cuts furniture off, the edge
        # shows the furniture's outline and the floor on its other side too, but the
        # scene's objects never stand with the floor above them.
        near = known if edge == "top" else known[[*([0] if scenery else []), -2]]
        aspect = POLE_TOP_ASPECT if edge == "top" else POLE_ASPECT
        for mask in _bars_from_top(view, taken, near, known, aspect):
            full = _edge_back(mask, edge)
            ys, xs = np.nonzero(full)
            x0, y0, x1, y1 = int(xs.min()), int(ys.min()), int(xs.max()) + 1, int(ys.max()) + 1
            out.append(Occluder("pole", (x0, y0, x1, y1), full[y0:y1, x0:x1].copy(), edge))
    return out


def _edge_view(image: np.ndarray, edge: str) -> np.ndarray:
    """The picture turned so that `edge` is its top row (a view, not a copy)."""
    if edge == "left":
        return image.swapaxes(0, 1)
    if edge == "right":
        return image[:, ::-1].swapaxes(0, 1)
    return image


def _edge_back(mask: np.ndarray, edge: str) -> np.ndarray:
    """A mask of `_edge_view(..., edge)` in the picture's own orientation."""
    if edge == "left":
        return np.ascontiguousarray(mask.T)
    if edge == "right":
        return np.ascontiguousarray(mask.T[:, ::-1])
    return mask


def _bars_from_top(img: np.ndarray, taken: np.ndarray | None, known: np.ndarray,
                   below: np.ndarray, aspect: float) -> list[np.ndarray]:
    """Masks (the view's shape) of the bars hanging from the top row of a view, where
    the edge shows one of the `known` scenery colours before the run and under half of
    it, and one of the `below` colours after it (a side bar may enter right above the
    floor), and that run at least `aspect` times their width in (both measured in the
    bar's own frame: a tilted bar's run along the edge is wider than the bar). A run
    must differ from the pixels right beside it, and where it lies between two
    sceneries (the wall and the floor) most of it must show one colour (`POLE_CORE`):
    a soft or restored floor edge passes through a range of colours and rings."""
    h, w = img.shape[:2]
    top = img[:POLE_TOP_ROWS].astype(np.int16)
    whole: np.ndarray | None = None  # the whole view in int16, made once it is needed
    line = np.median(top, axis=0)
    window = max(9, int(POLE_REFERENCE * w))
    before, after = _scenery_around(line, window)
    off = _differs(top, before) & _differs(top, after)
    filled = off
    for _ in range(POLE_PASSES):
        if not filled.any():
            break
        # A run wider than half the window pulls the scenery towards its colour: the
        # scenery of the line with the runs found (and their anti-aliased sides)
        # taken out does not.
        before, after = _scenery_around(_fill_runs(line, _grown(filled, 2)), window)
        off = _differs(top, before) & _differs(top, after)
        if not (off & ~filled).any():
            break
        filled = filled | off
    if taken is not None:
        off &= ~taken[:POLE_TOP_ROWS].any(axis=0)

    def scenic(colours: np.ndarray, at: np.ndarray) -> np.ndarray:
        return np.asarray((np.abs(at[:, None, :] - colours[None]).max(axis=2)
                           <= POLE_SCENERY).any(axis=1))

    edges = np.flatnonzero(np.diff(np.concatenate(([0], off.view(np.int8), [0]))))
    out: list[np.ndarray] = []
    for a, b in zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True):
        width = b - a
        if width < 2 or width > POLE_MAX_WIDTH * w or a <= 2 * BORDER or b >= w - 2 * BORDER:
            continue  # a run into a corner is the scenery changing (the floor), no bar
        past = np.median(line[b + 1:b + 4], axis=0)[None]  # beyond its anti-aliased end
        if not (scenic(known, before[max(0, a - 3):a]).all()
                and scenic(below, after[b:b + 3]).all()
                and (scenic(known, before[a:b]) | scenic(known, after[a:b])).mean() >= 0.5
                and scenic(known, np.median(line[a - 4:a - 1], axis=0)[None]).all()
                and scenic(below, past).all()):
            continue  # the edge cuts an object of the scene there
        if not scenic(known, past).all() and _seam_beside(line, a, b):
            continue  # furniture standing on the floor, cut by the frame: it is outlined
        if np.abs(before[max(0, a - 1)] - after[min(w - 1, b)]).max() > POLE_OFF_WALL:
            # Between two sceneries (the wall above the floor) a soft or restored edge
            # of the floor passes through a range of colours; a bar shows one colour
            # across most of its run (all but its anti-aliased ends).
            stretch = top[:, a:b]
            alike = np.abs(stretch - np.median(stretch.reshape(-1, 3), axis=0)).max(axis=2)
            if (alike <= POLE_CORE).sum(axis=1).min() < 2 or (alike <= POLE_CORE).mean() < 0.5:
                continue
        inner = (a + 1, b - 1) if width >= 4 else (a, b)
        colour = np.median(top[:, inner[0]:inner[1]].reshape(-1, 3),
                           axis=0).astype(np.int16)
        # A thing in front differs from what lies right beside it (past an anti-aliased
        # pixel), not only from the scenery along the edge: a ringing trough along a
        # restored floor line differs from the floor's medoid, not from the floor next
        # to it.
        if min(int(np.abs(line[max(0, a - 2)] - colour).max()),
               int(np.abs(line[min(w - 1, b + 1)] - colour).max())) <= POLE_OFF_WALL:
            continue
        wall = np.concatenate([before[a:b], after[a:b]])
        # A bar nearly the scenery's colour (white on the wall) is followed more tightly.
        match = min(POLE_MATCH,
                    POLE_MATCH_SHARE * float(np.abs(wall - colour).max(axis=1).min()))
        # Its solid core: the pixels of its colour across it at the edge, less one (a
        # tilted bar drifts by a fraction of a pixel a row before its line is known).
        solid = int((np.abs(top[:, a:b] - colour).max(axis=2) <= match).sum(axis=1).min())
        if solid < 2:
            continue  # a speck of noise along the edge, no bar
        if whole is None:
            whole = img.astype(np.int16)
        run = _follow(whole, colour, match, (a + b - 1) / 2, max(2, solid - 1), width)
        end = len(run.centres)
        # Along its axis a bar tilted by slope s runs end * sqrt(1 + s^2) rows in, and
        # it is width / sqrt(1 + s^2) wide.
        if end * (1 + run.slope ** 2) < aspect * width or end < POLE_MIN_LENGTH * h:
            continue
        rows = np.arange(end)
        centres = run.centres
        lefts = np.round(centres - width / 2 - 1.5).astype(int)
        rights = np.round(centres + width / 2 + 0.5).astype(int)
        apart = np.zeros(end, bool)
        seen = np.zeros(end, bool)
        for cols in (lefts, rights):
            ok = (cols >= 0) & (cols < w)
            seen |= ok
            apart[ok] |= np.abs(whole[rows[ok], cols[ok]] - colour).max(axis=1) > match
        if seen.any() and float(np.mean(apart[seen])) < POLE_APART:
            continue
        if _outlined(whole, centres, width, colour):
            continue  # an object of the scene cut by the frame: it is drawn outlined
        mask = np.zeros((h, w), bool)
        for r in range(min(h, end + 2)):
            c = centres[min(r, end - 1)]
            mask[r, max(0, int(np.floor(c - width / 2 - 2))):
                 min(w, int(np.ceil(c + width / 2 + 2)))] = True
        mask |= _bar_end(whole, colour, match, run, width)
        out.append(mask)
    return out


def _scenery_around(line: np.ndarray, window: int) -> tuple[np.ndarray, np.ndarray]:
    """The scenery just before and just after each place of an edge's row of colours:
    the running medoid of the `window` ending just before it and of the one starting
    just after it. A run is off the scenery where it differs from both: at a step of
    the scenery (the wall meeting the floor) every place matches the side it belongs
    to, and a bar right beside the step differs from both sides."""
    centred = _running_medoid(line, window)
    reach = (window | 1) // 2 + 1
    padded = np.pad(centred, ((reach, reach), (0, 0)), mode="edge")
    return padded[:len(line)], padded[2 * reach:]


def _seam_beside(line: np.ndarray, a: int, b: int) -> bool:
    """Whether a run `a:b` of an edge's row of colours may have a dark seam (an object's
    drawn outline, `OUTLINE_DARK` and `OUTLINE_STEP` darker than the run) at either end,
    between it and the scenery: an object of the scene cut by the frame. A run too dark
    to tell its outline from its own anti-aliased ends may (it is not taken)."""
    colour = np.median(line[a:b], axis=0)
    limit = min(OUTLINE_DARK, int(colour.max()) - OUTLINE_STEP)
    if limit < OUTLINE_MIN:
        return True
    ends = np.concatenate([line[max(0, a - 2):a + 1], line[b - 1:b + 2]])
    return bool((ends.max(axis=1) <= limit).any())


def _differs(top: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Columns of the edge rows `top` off the `reference` colours in every row."""
    return np.asarray((np.abs(top - reference).max(axis=2) > POLE_OFF_WALL).all(axis=0))


def _grown(flags: np.ndarray, by: int) -> np.ndarray:
    """A row of flags, each set one grown by `by` places either way."""
    kernel = np.ones(2 * by + 1, np.int32)
    return np.asarray(np.convolve(flags.view(np.int8).astype(np.int32), kernel,
                                  mode="same") > 0)


@dataclass(frozen=True, slots=True)
class _Run:
    """A bar followed from the top row of a view: its centre per row, the straight
    line fitted through them (x = base + slope * row), and whether it ended by leaving
    the view through a side (`exits`) rather than by losing its colour."""

    centres: np.ndarray
    slope: float
    base: float
    exits: bool


def _bar_end(img: np.ndarray, colour: np.ndarray, match: float, run: _Run,
             width: int) -> np.ndarray:
    """The pixels of a bar past its last row followed (a mask of the view's shape):
    those of its colour between its two sides (its line, `width` wide) where its end
    is cut square to a tilted bar (the end spans `width * s / (1 + s^2)` rows), or, for
    a bar leaving the view through a side, up to where it has left, grown by 2 px over
    its anti-aliased sides. What the bar covers there is no object, however it is
    cut."""
    h, w = img.shape[:2]
    out = np.zeros((h, w), bool)
    start = len(run.centres)
    slope = run.slope
    stop = h if run.exits else min(h, start + 2 + int(np.ceil(
        width * abs(slope) / (1 + slope * slope))))
    misses = 0
    for r in range(start, stop):
        c = run.base + slope * r
        lo, hi = max(0, int(np.floor(c - width / 2 - 1))), min(w, int(np.ceil(c + width / 2 + 1)))
        if lo >= hi:
            break  # wholly out of the view
        hits = np.abs(img[r, lo:hi] - colour).max(axis=1) <= match
        if not hits.any():
            misses += 1
            if misses >= 2:
                break
            continue
        misses = 0
        out[r, lo:hi] = hits
    if out.any():
        out = cv2.dilate(out.view(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)
    return out


def _follow(img: np.ndarray, colour: np.ndarray, match: float, centre: float,
            inner: int, width: int) -> _Run:
    """A run of `colour` (`width` px wide, its `inner` px solid) that starts at
    `centre` in the top row and goes on along a straight line, followed row by row; it
    ends at two rows in a row off its colour (the last rows off it are dropped) or
    where its solid core reaches a side of the view."""
    h, w = img.shape[:2]
    half = inner / 2
    reach = int(np.ceil(width / 2)) + POLE_DRIFT
    centres: list[float] = []
    fit: list[tuple[int, float]] = []  # rows whose run kept the bar's width
    misses = 0
    exits = False
    slope, base = 0.0, centre
    sums = (0.0, 0.0, 0.0, 0.0, 0.0)  # n, sum r, sum x, sum r^2, sum r x
    for r in range(h):
        guess = base + slope * r
        if guess - half < 0 or guess + half > w:
            exits = True
            break
        # Re-centre on the run nearest the line when it still has the bar's width (not
        # where it crosses an object of its colour), then refit the line through them.
        s0, s1 = max(0, int(guess) - reach), min(w, int(guess) + reach + 1)
        hits = np.abs(img[r, s0:s1] - colour).max(axis=1) <= match
        at = int(guess) - s0
        near = [i for i in (at, at + 1, at - 1, at + 2, at - 2) if 0 <= i < len(hits)
                and hits[i]]
        if near:
            left = right = near[0]
            while left > 0 and hits[left - 1]:
                left -= 1
            while right < len(hits) - 1 and hits[right + 1]:
                right += 1
            run = right - left + 1
            if left > 0 and right < len(hits) - 1 and inner - 1 <= run <= width + 2:
                guess = s0 + (left + right) / 2
                fit.append((r, guess))
                sums = (sums[0] + 1, sums[1] + r, sums[2] + guess, sums[3] + r * r,
                        sums[4] + r * guess)
        lo = int(np.floor(guess - half + 0.5))
        row = np.abs(img[r, max(0, lo):lo + inner] - colour).max(axis=1) <= match
        good = r < POLE_TOP_ROWS or (row.size > 0 and float(row.mean()) >= POLE_ROW_SHARE)
        centres.append(guess)
        if not good:
            misses += 1
            if misses >= 2:
                break
            continue
        misses = 0
        if len(fit) >= 4:  # least squares through the centres so far
            n, sy, sx, syy, sxy = sums
            slope = (n * sxy - sy * sx) / max(n * syy - sy * sy, 1e-9)
            slope = min(POLE_TILT, max(-POLE_TILT, slope))
            base = (sx - slope * sy) / n
        elif fit:  # too few rows for a line yet: follow the last centre
            base = fit[-1][1]
    while misses and centres:
        centres.pop()
        misses -= 1
    return _Run(np.array(centres, float), slope, base, exits)


def _outlined(img: np.ndarray, centres: np.ndarray, width: int, colour: np.ndarray) -> bool:
    """Whether a run shows a thin dark seam (`OUTLINE_DARK`, with no dark beyond it)
    just inside or outside both its sides along most of its length (`OUTLINED`): the
    outline every object of the scene is drawn with, which a thing in front of the
    camera does not have."""
    limit = min(OUTLINE_DARK, int(colour.max()) - OUTLINE_STEP)
    if limit < OUTLINE_MIN:
        return False  # a dark bar: its own sides look like an outline
    h, w = img.shape[:2]
    n = len(centres)
    if n == 0:
        return False
    rows = np.arange(n)[:, None]
    lo = np.round(centres - width / 2).astype(int)[:, None]
    hi = np.round(centres + width / 2).astype(int)[:, None]

    def dark(cols: np.ndarray) -> np.ndarray:
        inside = (cols >= 0) & (cols < w)
        pixels = img[np.broadcast_to(rows, cols.shape), np.clip(cols, 0, w - 1)]
        return (pixels.max(axis=2) <= limit) & inside

    left = dark(lo + np.arange(-2, 4)).any(axis=1)
    right = dark(hi + np.arange(-4, 2)).any(axis=1)
    # A seam, not a dark thing the run lies on (a black stove it crosses).
    beyond = dark(np.hstack([lo - 5, hi + 4])).any(axis=1)
    both = int(np.count_nonzero(left & right & ~beyond))
    return both >= OUTLINED * max(1, len(centres))


def _fill_runs(line: np.ndarray, off: np.ndarray) -> np.ndarray:
    """The line with each run of `off` pixels given the colour just before it (just
    after it for a run at the start)."""
    out = line.copy()
    idx = np.where(~off, np.arange(len(off)), -1)
    before = np.maximum.accumulate(idx)
    after = np.where(~off, np.arange(len(off)), len(off))[::-1]
    after = np.minimum.accumulate(after)[::-1]
    if (~off).any():
        source = np.where(before >= 0, before, after)
        out[off] = line[source[off]]
    return out


def _running_medoid(line: np.ndarray, window: int) -> np.ndarray:
    """The scenery along a row of colours: at each place, the medoid of the colours in
    a `window` around it (the sampled colour nearest all the others, summing channel
    differences), which keeps the scenery's steps (wall to floor) and drops narrow runs
    (a bar). A medoid is a colour the window shows: a per-channel median there would
    mix the channels of a bar and the floor next to it into a colour neither has. A
    window of one colour (within `POLE_OFF_WALL` per channel, most of an edge) takes
    its per-channel median, the same colour for less work. Each window is sampled at
    about `MEDIAN_SAMPLES` points, and the medoid is taken every sampling interval (a
    step of the scenery is placed within one interval, 1/31 of the window; the cost
    stays linear in the edge's length)."""
    window |= 1
    pad = window // 2
    step = max(1, window // MEDIAN_SAMPLES)
    padded = np.pad(line, ((pad, pad), (0, 0)), mode="edge").astype(np.float32)
    windows = np.lib.stride_tricks.sliding_window_view(padded, window, axis=0)
    at = np.ascontiguousarray(windows[::step, :, ::step])  # windows, channels, samples
    out = np.median(at, axis=2)
    mixed = np.flatnonzero((at.max(axis=2) - at.min(axis=2)).max(axis=1) > POLE_OFF_WALL)
    if len(mixed):
        # Window k samples grid points k .. k + m - 1 of the line taken every `step`
        # places, so one table of distances between grid points (prefix-summed along
        # its rows) gives every sample's summed distance to its window in one lookup
        # (an edge's colours are medians of two rows, halves: the sums are exact).
        samples = at.shape[2]
        grid = padded[::step][:len(at) + samples - 1].astype(np.float64)
        apart = sum(np.abs(grid[:, None, c] - grid[None, :, c]) for c in range(3))
        summed = np.zeros((len(grid), len(grid) + 1))
        np.cumsum(apart, axis=1, out=summed[:, 1:])
        rows = mixed[:, None] + np.arange(samples)[None, :]
        spread = summed[rows, (mixed + samples)[:, None]] - summed[rows, mixed[:, None]]
        out[mixed] = grid[mixed + np.argmin(spread, axis=1)]
    return np.asarray(np.repeat(out, step, axis=0)[:len(line)], dtype=np.int16)


def _step(image: np.ndarray) -> np.ndarray:
    """Largest colour step to a 3x3 neighbour, per pixel (the channels' morphological
    gradients, their maximum taken by OpenCV: numpy's max over the last axis costs more
    than the rest of the search)."""
    return colors.brightest(cv2.morphologyEx(image, cv2.MORPH_GRADIENT,
                                             np.ones((3, 3), np.uint8)))


def _band_or_blob(comp: np.ndarray, area: int, x: int, y: int, shape: tuple[int, int],
                  image: np.ndarray, foreign: np.ndarray) -> str | None:
    """"band", "blob" or None for a flat component (`comp`: its pixels in its box at
    (x, y), `area` of them)."""
    h, w = shape
    bh, bw = comp.shape
    touches = (x <= BORDER, y <= BORDER, x + bw >= w - BORDER, y + bh >= h - BORDER)
    if sum(touches) in (2, 3) and (bw >= BAND_REACH * w or bh >= BAND_REACH * h):
        # Its two ends meet the frame, not a long side (a floor cut in two by a bar
        # meets the frame along its bottom; the wall meets it along three sides).
        on_frame = _frame_pixels(comp, touches)
        # (the test below needs on_frame <= 3 width + 4 <= 1.5 length + 4, so the
        # rectangle is not fitted to a component that cannot pass: the wall)
        (_, _), (rw, rh), _ = cv2.minAreaRect(_outline(comp)) if on_frame <= 1.5 * float(
            np.hypot(bw, bh)) + 4 else ((0.0, 0.0), (0.0, 0.0), 0.0)
        length, width = max(rw, rh), min(rw, rh)
        if length > 0 and width <= BAND_THIN * length and \
                area >= BAND_FILL * length * width and on_frame <= 3 * width + 4:
            return "band"
    if not any(touches) and area >= BLOB_SHARE * h * w and len(foreign):
        colour = np.asarray(cv2.mean(image[y:y + bh, x:x + bw], comp.view(np.uint8))[:3],
                            dtype=np.float32)
        if float(np.min(np.linalg.norm(foreign - colour, axis=1))) >= BLOB_FOREIGN:
            hull = cv2.convexHull(_outline(comp))
            if area >= BLOB_SOLIDITY * max(float(cv2.contourArea(hull)), 1.0):
                return "blob"
    return None


def _outline(comp: np.ndarray) -> np.ndarray:
    """The pixels of a component's outer boundary, (n, 1, 2) int32 (x, y): every corner
    of its convex hull, so its hull and its smallest rectangle are those of all its
    pixels, found from far fewer points."""
    contours, _ = cv2.findContours(comp.view(np.uint8), cv2.RETR_EXTERNAL,
                                   cv2.CHAIN_APPROX_SIMPLE)
    return np.concatenate(contours)


def _frame_pixels(comp: np.ndarray, touches: tuple[bool, bool, bool, bool]) -> int:
    """Pixels of a component (its box at the frame where `touches`) along the frame."""
    left, top, right, bottom = touches
    return int(sum(np.count_nonzero(edge) for edge, on in (
        (comp[:, 0], left), (comp[0], top), (comp[:, -1], right), (comp[-1], bottom)) if on))


def occluded_by(occluders: Sequence[Occluder], regions: Sequence[Region],
                shape: tuple[int, int]) -> list[list[int]]:
    """For each occluder, the indices of the regions it touches (hides part of)."""
    out: list[list[int]] = []
    for occ in occluders:
        near = occ.full_mask(shape, TOUCH)
        out.append([i for i, r in enumerate(regions) if _touches(r, near)])
    return out


def split_by(region: Region, occ: Occluder) -> bool:
    """Whether a band crosses the region: its visible pixels lie on both sides of the
    band, so its extent behind the band is bounded."""
    if occ.kind not in HIDING or not np.any(occ.mask):
        return False
    side, _ = _sides(region, _line(occ))
    return bool(np.any(side > 0) and np.any(side < 0))


def hidden_mask(occluders: Sequence[Occluder], shape: tuple[int, int]) -> np.ndarray | None:
    """Every band's and pole's pixels (bool), or None when there is none. Only they
    hide: their reach across the frame (or down from its top edge) proves them to be in
    front; a blob is known by its colour alone, which a strong colour cast can give an
    object too, so it is reported but nothing is read around it."""
    bands = [occ for occ in occluders if occ.kind in HIDING]
    if not bands:
        return None
    out = np.zeros(shape, bool)
    for occ in bands:
        out |= occ.full_mask(shape)
    return out


def _line(occ: Occluder) -> tuple[float, float, float, float]:
    """(cx, cy, vx, vy): the band's centre line."""
    ys, xs = np.nonzero(occ.mask)
    pts = np.column_stack([xs + occ.box[0], ys + occ.box[1]]).astype(np.float32)
    vx, vy, cx, cy = (float(v) for v in cv2.fitLine(pts, cv2.DIST_L2, 0, 0.01, 0.01).ravel())
    return cx, cy, vx, vy


def _sides(region: Region, line: tuple[float, float, float, float]
           ) -> tuple[np.ndarray, np.ndarray]:
    """Signed distance across the line, and position along it, of a region's pixels."""
    cx, cy, vx, vy = line
    ys, xs = np.nonzero(region.mask)
    dx, dy = xs + region.x0 - cx, ys + region.y0 - cy
    return dx * vy - dy * vx, dx * vx + dy * vy


def join_across(parts: list[Region], occluders: Sequence[Occluder], shape: tuple[int, int]
                ) -> tuple[list[Region], list[str]]:
    """Parts of one colour on the two sides of a band that hides what joins them (they
    face each other across it), joined into one region; with a note each."""
    notes: list[str] = []
    bands = [o for o in occluders if o.kind in HIDING]
    if not bands or len(parts) < 2:
        return parts, notes
    out = list(parts)
    for occ in bands:
        near = occ.full_mask(shape, TOUCH)
        line = _line(occ)
        i = 0
        while i < len(out):
            merged = False
            for j in range(i + 1, len(out)):
                a, b = out[i], out[j]
                if not (_touches(a, near) and _touches(b, near)):
                    continue
                sa, pa = _sides(a, line)
                sb, pb = _sides(b, line)
                opposite = (np.median(sa) > 0) != (np.median(sb) > 0)
                overlap = min(pa.max(), pb.max()) - max(pa.min(), pb.min())
                if opposite and overlap > 0:
                    out[i] = a.merged(b)
                    del out[j]
                    notes.append(f"{occ.describe()} hides the middle of an object; its "
                                 "parts on both sides were joined")
                    merged = True
                    break
            if not merged:
                i += 1
    return out, notes


def _touches(region: Region, near: np.ndarray) -> bool:
    return bool(np.any(near[region.y0:region.y1, region.x0:region.x1] & region.mask))
