"""Confidence per node and edge of a perceived tabletop graph, and the uncertain items.

A node's confidence is the labeller's (how clearly colour and shape chose its label)
times how well its pixels show that colour after correction (a region far from its
palette colour may be something else altogether); an edge is as sure as the less sure
of its two ends. Items under `CONFIDENT` are listed as uncertain, with the reason.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from verigraph.graph.model import SceneGraph
from verigraph.perception.detect.colors import ColourTable, purity
from verigraph.perception.detect.tabletop import Detection
from verigraph.perception.label.labelling import Shape, shape_error
from verigraph.perception.result import CONFIDENT, Uncertain, add_edge_confidence

PURE_DISTANCE = 10.0  # median palette distance of a region that shows its colour plainly
DOUBT_RANGE = 20.0  # distance over which colour confidence falls from 1 to 0
SHAPE_SLACK = 0.35  # shape error (labelling.shape_error) of a cleanly drawn object
SHAPE_RANGE = 0.5  # shape error over which shape confidence falls from 1 to 0
SOFT_SCALE = 6.5  # px per world unit from which thin parts are checked in a soft picture
UPRIGHT = 4.0  # height over width of a region standing on end (a long thin model)
FLOOR_REACH = 1.0  # world units furniture's bottom may end above the floor line


def edge_name(source: str, relation: str, target: str) -> str:
    return f"{source} {relation} {target}"


def colour_confidence(image: np.ndarray, det: Detection, table: ColourTable) -> float:
    """1 when the region's pixels sit on its palette colour, falling to 0 far from it."""
    cls = table.index(det.colour)
    r = det.region
    if cls is None or table.names[r.cls] != det.colour:
        # Labelled by shape across colours (or a bright object): the labeller's score
        # already weighed the colour.
        return 1.0
    pixels = image[r.y0:r.y1, r.x0:r.x1][r.mask]
    if len(pixels) == 0:
        return 0.0
    distance = float(np.median(purity(pixels.reshape(-1, 3), table)))
    return float(np.clip(1.0 - (distance - PURE_DISTANCE) / DOUBT_RANGE, 0.0, 1.0))


def shape_confidence(det: Detection, scale: float, soft: bool = False) -> float:
    """For objects whose colour is per instance (blocks: any colour, one shape), 1 when
    the region has the model's size and hollowness, falling to 0 well past what a clean
    render shows (a blurred rim of a red block that passes for a thin maroon block has
    half a block's height). Objects with a class colour are confirmed by it; their thin
    parts (a knife, a spoon) vary too much in outline at small scales to add anything,
    except in a soft picture (`soft`), where blur mixes a wall and its outline into a
    sliver of another object's colour (a blue bowl's wall into a steel knife), and the
    scale is large enough (`SOFT_SCALE`) for a thin part's outline to be measured."""
    soft = soft and scale >= SOFT_SCALE
    if det.model.fixed or (det.model.own_colour and not soft) or scale <= 0:
        return 1.0
    error = shape_error(Shape.of(det.region), det.model, scale)
    return float(np.clip(1.0 - (error - SHAPE_SLACK) / SHAPE_RANGE, 0.0, 1.0))


def floor_confidence(det: Detection, floor_row: int | None, scale: float) -> float:
    """Furniture stands on the floor: 1 when its bottom reaches the floor line, 0 when it
    ends a world unit or more above it (a grey blob over a grey counter that passes for
    a second counter)."""
    if not det.model.fixed or floor_row is None or scale <= 0:
        return 1.0
    return 0.0 if det.region.y1 < floor_row - (FLOOR_REACH * scale + 2) else 1.0


def upright_doubts(graph: SceneGraph, detections: Sequence[Detection]) -> list[Uncertain]:
    """Thin objects standing on end `on` a surface: physics lays a knife, a fork or a
    spoon down unless a container's walls hold it, so such a sliver is more likely a
    blurred edge than the object (they stand `in` cups and pots)."""
    rests = {e.source: e for e in graph.edges}
    out = []
    for det in detections:
        edge = rests.get(det.id)
        r = det.region
        if det.model.fixed or edge is None or edge.relation != "on":
            continue
        if r.height >= UPRIGHT * max(r.width, 1) and det.model.width >= UPRIGHT * det.model.height:
            out.append(Uncertain(item=det.id, confidence=0.3, reason=(
                f"it stands on end on {edge.target}, which a {det.label} cannot do outside "
                "a container; it may be a blurred edge")))
            out.append(Uncertain(item=edge_name(edge.source, edge.relation, edge.target),
                                 confidence=0.3, reason=f"{det.id} is doubtful"))
    return out


def graph_confidence(graph: SceneGraph, detections: Sequence[Detection], image: np.ndarray,
                     table: ColourTable, scale: float, *, floor_row: int | None = None,
                     soft: bool = False) -> tuple[dict[str, float], list[Uncertain]]:
    """Confidence of every node id and edge, and the items below `CONFIDENT`."""
    confidence: dict[str, float] = {}
    uncertain: list[Uncertain] = []
    for det in detections:
        colour = round(colour_confidence(image, det, table), 3)
        shape = round(shape_confidence(det, scale, soft), 3)
        standing = floor_confidence(det, floor_row, scale)
        value = min(round(det.score, 3), colour, shape, standing)
        confidence[det.id] = value
        if value < CONFIDENT:
            if standing == value:
                why = f"it does not stand on the floor, as a {det.label} does"
            elif shape == value:
                why = f"its outline does not have a {det.label}'s size or form"
            elif colour == value:
                why = "its colour is far from the dictionary's " + det.colour
            else:
                why = (f"its shape and colour fit {det.label} only a little better than "
                       "another object")
            uncertain.append(Uncertain(item=det.id, confidence=value, reason=why))
    add_edge_confidence(graph, confidence, uncertain,
                        lambda e: edge_name(e.source, e.relation, e.target), "objects")
    return confidence, uncertain
