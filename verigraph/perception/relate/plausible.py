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
  uncertain, each with the reason (`plausibility_doubts`), so the result is a proposal.
"""

from __future__ import annotations

from collections.abc import Sequence

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.model import SceneGraph
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
