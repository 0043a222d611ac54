"""Plausibility of a perceived side view against what the dictionary says is possible,
checked before the graph is returned.

A reading the world cannot produce is a misreading (most often something in front of
the scene that looks like an object), so it is never returned as fact:

- a piece of furniture (a fixed surface) standing on another object is not emitted at
  all (`furniture_on_objects`): furniture stands on the floor, so the region is
  something else, reported as an area in front of the scene (what it touches is named);
- an object standing on nothing (no supporter under it, not on the floor), an object
  wider than the surface it stands on (by the dictionary, unless it stands on end; or by
  its outline, 1.3 times; a thing in a container may stick out of it, as a knife in a
  cup or a board in a pot does, as the simulator draws them), and a region running into the image
  border (it goes on outside the picture, or it is something hanging into it; for
  furniture only the top border counts, since a crop or a tilted camera often cuts its
  sides or legs off, while its top is always inside the picture) are emitted but
  uncertain, each with the reason (`plausibility_doubts`), so the result is a proposal;
- an object that meets the wall without its outline along a stretch of its edge
  (`unoutlined_doubts`): every object is seen with its edge (the drawn outline),
  so a straight cut into the wall's colour is something of the wall's colour in front
  of it (a white pole on a white wall shows only where it crosses objects), which may
  have split it in two or hidden what it carries. It is emitted but uncertain. The
  floor never shows the wall's colour either: where it does (`wall_on_floor`), a thing
  of the wall's colour stands in front, and the objects above it are doubted.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.model import SceneGraph
from verigraph.perception.detect import colors
from verigraph.perception.detect.tabletop import Detection
from verigraph.perception.relate.confidence import edge_name
from verigraph.perception.result import Uncertain

IMPLAUSIBLE = 0.3  # confidence of a reading the dictionary says cannot be
BORDER_SLACK = 1  # px from the frame that count as running into it
WIDER = 1.3  # a carried object's outline this much wider than its carrier's is implausible
WIDER_PIXELS = 3  # ... and by at least this many pixels (outlines vary)


def furniture_on_objects(detections: Sequence[Detection],
                         supports: dict[str, tuple[str, str]]) -> list[int]:
    """Indices of fixed detections (furniture) that rest on or in another detection."""
    return [i for i, d in enumerate(detections) if d.model.fixed and d.id in supports]


def plausibility_doubts(graph: SceneGraph, detections: Sequence[Detection],
                        d: Dictionary, shape: tuple[int, int]) -> list[Uncertain]:
    """Uncertain items (nodes and their edges) for readings the dictionary or the frame
    make implausible: an object on nothing, an object wider than its carrier, a region
    running into the image border."""
    h, w = shape
    by_id = {det.id: det for det in detections}
    rests = {e.source: e for e in graph.edges}
    out: list[Uncertain] = []

    def doubt(obj: str, reason: str) -> None:
        out.append(Uncertain(item=obj, confidence=IMPLAUSIBLE, reason=reason))
        for e in graph.edges:
            if obj in (e.source, e.target):
                out.append(Uncertain(item=edge_name(e.source, e.relation, e.target),
                                     confidence=IMPLAUSIBLE, reason=f"{obj} is doubtful"))

    for det in detections:
        r = det.region
        sides = [name for name, hit in (
            ("left", r.x0 <= BORDER_SLACK), ("top", r.y0 <= BORDER_SLACK),
            ("right", r.x1 >= w - BORDER_SLACK), ("bottom", r.y1 >= h - BORDER_SLACK))
            if hit]
        if det.model.fixed:
            # Furniture is large: the frame cutting its sides or legs off is ordinary
            # (a crop, a tilted camera), but it never reaches the top of the picture.
            sides = [side for side in sides if side == "top"]
        if sides:
            doubt(det.id, f"it runs into the image's {' and '.join(sides)} border: it may "
                  "go on outside the picture, or be something in front of the scene")
            continue
        if det.model.fixed:
            continue
        edge = rests.get(det.id)
        if edge is None:
            doubt(det.id, "it stands on nothing: what it rests on is not seen (hidden "
                  "or missed), or it is not what it looks like")
            continue
        carrier = by_id.get(edge.target)
        if carrier is None or carrier.model.fixed or edge.relation == "in":
            continue  # a thing in a container may stick out of it (a board in a pot)
        own = d.objects.get(det.label)
        base = d.objects.get(carrier.label)
        # A long thin thing may stand on end in a narrow container (a knife in a cup):
        # the dictionary's width counts only for an object lying as drawn.
        lying = r.height < r.width
        wider_by_dictionary = (lying and own is not None and base is not None
                               and own.width is not None and base.width is not None
                               and own.width > base.width)
        cw = carrier.region.width
        if wider_by_dictionary or (r.width > WIDER * cw and r.width - cw >= WIDER_PIXELS):
            doubt(det.id, f"it is wider than {carrier.id}, which carries it ({r.width} px "
                  f"against {cw} px; a {det.label} is "
                  + (f"wider than a {carrier.label}" if wider_by_dictionary else
                     f"not wider than a {carrier.label} by the dictionary")
                  + "): the reading is unlikely")
    return out


OUTLINE_DARK = 110  # brightest channel of an outline pixel, blurred or scaled down
UNOUTLINED = 12  # px of an object's edge meeting the wall with no outline: a cut


def unoutlined_doubts(graph: SceneGraph, detections: Sequence[Detection],
                      image: np.ndarray, wall: np.ndarray) -> list[Uncertain]:
    """Uncertain items for objects whose edge meets the wall (`wall`: bool, its
    pixels) with no outline (`OUTLINE_DARK`) along at least `UNOUTLINED` connected px:
    something of the wall's colour stands in front and cuts them."""
    h, w = wall.shape
    dark = (colors.brightest(image) <= OUTLINE_DARK).view(np.uint8)
    near_dark = cv2.dilate(dark, np.ones((5, 5), np.uint8)).astype(bool)
    near_wall = cv2.dilate(wall.view(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)
    out: list[Uncertain] = []
    for det in detections:
        r = det.region
        if r.area < 4 * UNOUTLINED:
            continue
        y0, y1, x0, x1 = r.y0, r.y0 + r.mask.shape[0], r.x0, r.x0 + r.mask.shape[1]
        mask = r.mask.view(np.uint8)
        inner = cv2.erode(mask, np.ones((3, 3), np.uint8), borderType=cv2.BORDER_CONSTANT,
                          borderValue=0)
        edge = (mask & ~inner.astype(bool).view(np.uint8)).astype(bool)
        cut = edge & near_wall[y0:y1, x0:x1] & ~near_dark[y0:y1, x0:x1]
        if np.count_nonzero(cut) < UNOUTLINED:
            continue
        n, _, stats, _ = cv2.connectedComponentsWithStats(cut.view(np.uint8), connectivity=8)
        longest = int(stats[1:n, cv2.CC_STAT_AREA].max()) if n > 1 else 0
        if longest < UNOUTLINED:
            continue
        reason = (f"{longest} px of its edge meet the wall with no outline: something of "
                  "the wall's colour may stand in front of it, cutting it or hiding what "
                  "it carries")
        out.append(Uncertain(item=det.id, confidence=IMPLAUSIBLE, reason=reason))
        for e in graph.edges:
            if det.id in (e.source, e.target):
                out.append(Uncertain(item=edge_name(e.source, e.relation, e.target),
                                     confidence=IMPLAUSIBLE, reason=f"{det.id} is doubtful"))
    return out


WALL_ON_FLOOR = 3  # rows below the floor line before wall-coloured pixels count there
WALL_DOWN = 0.9  # share of a floor-band column in the wall's colour that counts
WALL_BAND = 6  # fewest rows of floor band the check needs
WALL_RUN = 0.25  # widest run of such columns, as a share of the width (a bar, no wedge)


def wall_on_floor(graph: SceneGraph, detections: Sequence[Detection], wall: np.ndarray,
                  floor_row: int | None) -> tuple[list[str], list[Uncertain]]:
    """(warnings, uncertain items) for wall-coloured columns inside the floor band
    (away from the image's sides): something of the wall's colour stands in front
    there, and every object over those columns may be cut by it."""
    h, w = wall.shape
    if floor_row is None or floor_row + WALL_ON_FLOOR + WALL_BAND >= h - 1:
        return [], []  # no floor band tall enough to tell a bar from a tilted edge
    band = wall[floor_row + WALL_ON_FLOOR:h - 1]
    if not band.size:
        return [], []
    # A thing in front covers the floor band from its top to the picture's bottom; a
    # slightly rolled floor line only lets the wall into the band's top rows.
    flags = np.concatenate(([0], (band.mean(axis=0) >= WALL_DOWN).view(np.int8), [0]))
    steps = np.flatnonzero(np.diff(flags))
    # Runs with floor on both sides: a rolled camera's corners reach in from the sides.
    runs = [(a, b) for a, b in zip(steps[::2].tolist(), steps[1::2].tolist(), strict=True)
            if a > 2 and b < w - 2 and 2 <= b - a <= WALL_RUN * w]
    if not runs:
        return [], []
    x0, x1 = min(a for a, _ in runs), max(b for _, b in runs)
    hit = [det for det in detections if det.region.x0 < x1 + 2 and det.region.x1 > x0 - 2]
    warning = (f"the floor shows the wall's colour at columns {x0}-{x1}: something of the "
               "wall's colour stands in front of the scene there"
               + (f"; it may cut or hide {', '.join(d.id for d in hit)}" if hit else "")
               + ": confirm the graph")
    out: list[Uncertain] = []
    for det in hit:
        out.append(Uncertain(item=det.id, confidence=IMPLAUSIBLE, reason=f"something of "
                             f"the wall's colour stands in front at columns {x0}-{x1}"))
        for e in graph.edges:
            if det.id in (e.source, e.target):
                out.append(Uncertain(item=edge_name(e.source, e.relation, e.target),
                                     confidence=IMPLAUSIBLE, reason=f"{det.id} is doubtful"))
    return [warning], out
