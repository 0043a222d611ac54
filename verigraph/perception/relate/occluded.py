"""What an occluder does to the graph: the objects it touches are named, made uncertain
(with their edges), and the graph becomes a proposal, never an accepted wrong graph.

Part of an object behind a band may still be inferred: when the object shows on both
sides of the band (its extent is bounded), or its contact with what it rests on shows,
and that supporter is visible on both sides of the band (or is not hidden at all), the
edge between them is what the picture shows around the band. Such objects are doubted
less, and the reason says the hidden part can be inferred; the rest say it cannot.
An object whose bottom meets the occluder (what is right under it is hidden) and that
does not show on both sides of it is never inferred: its supporter is read through the
hidden part (a lid seen resting on a counter may stand in a pan behind a pole).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence

import numpy as np

from verigraph.graph.model import Edge, SceneGraph
from verigraph.perception.detect.occlusion import Occluder, occluded_by, split_by
from verigraph.perception.detect.regions import Region
from verigraph.perception.result import Blocked, Uncertain

INFERRED = 0.45  # confidence of an occluded object whose hidden part can be inferred
HIDDEN = 0.2  # ... and of one whose hidden part cannot
HIDDEN_REASON = "partly hidden by"  # how every occlusion doubt's reason starts
UNDER = 9  # px under an object's bottom where what it rests on is looked for


def occlusion_doubts(graph: SceneGraph, ids: Sequence[str], regions: Sequence[Region],
                     occluders: Sequence[Occluder], shape: tuple[int, int], *,
                     edge_name: Callable[[Edge], str], supports: bool = True,
                     completed: Collection[str] = ()
                     ) -> tuple[list[str], list[Uncertain], list[str]]:
    """(warnings, uncertain items, occluded ids) for the occluders found in an image.

    `supports`: edges are `source rests on/in target` (tabletop); tangram contacts have
    no supporter, so only the shape's completion is judged. `completed`: objects whose
    hidden part was read from what shows of them and their known shape (tangram
    pieces): inferred, still uncertain."""
    warnings: list[str] = []
    doubts: dict[str, Uncertain] = {}
    rests_on = {e.source: e for e in graph.edges} if supports else {}
    index = {obj: i for i, obj in enumerate(ids)}
    touched = occluded_by(occluders, regions, shape)
    hidden_ids = {ids[i] for hits in touched for i in hits}
    for occ, hits in zip(occluders, touched, strict=True):
        names = [ids[i] for i in hits]
        warnings.append(
            f"something in front hides part of the scene: {occ.describe()}; "
            + (f"it touches {', '.join(names)}" if names else "it touches no detected object")
            + "; what it hides, and any object wholly behind it, is not seen: confirm the "
            "graph")
        for i in hits:
            obj = ids[i]
            edge = rests_on.get(obj)
            both_sides = split_by(regions[i], occ)
            if edge is not None:
                j = index.get(edge.target)
                support_seen = j is None or edge.target not in hidden_ids or \
                    split_by(regions[j], occ)
                through = not both_sides and rests_behind(regions[i], occ, shape)
                inferable = support_seen and not through
                why = (f"'{edge_name(edge)}' can be inferred: {edge.target} is visible on "
                       "both sides of it" if inferable else
                       f"'{edge_name(edge)}' is read through the hidden part (what is "
                       "right under it is behind the occluder) and cannot be inferred"
                       if through else
                       f"what it rests on behind it cannot be inferred ({edge.target} is "
                       "hidden there too)")
            elif obj in completed:
                inferable = True
                why = ("its hidden sides were read from its visible sides and its known "
                       "shape")
            else:
                inferable = both_sides
                why = ("its shape can be completed: it shows on both sides" if inferable
                       else "its hidden part cannot be inferred")
            value = INFERRED if inferable else HIDDEN
            reason = f"{HIDDEN_REASON} {occ.describe()}; {why}"
            if obj not in doubts or doubts[obj].confidence > value:
                doubts[obj] = Uncertain(item=obj, confidence=value, reason=reason)
    uncertain = list(doubts.values())
    for edge in graph.edges:
        low = [doubts[end] for end in (edge.source, edge.target) if end in doubts]
        if low:
            worst = min(low, key=lambda u: u.confidence)
            uncertain.append(Uncertain(item=edge_name(edge), confidence=worst.confidence,
                                       reason=f"{worst.item} is partly hidden"))
    return warnings, uncertain, sorted(doubts)


def merge_doubts(confidence: dict[str, float], uncertain: list[Uncertain],
                 extra: Sequence[Uncertain]) -> None:
    """Add occlusion doubts to a result's confidence and uncertain items (in place):
    an item keeps the lower confidence and every reason."""
    for doubt in extra:
        confidence[doubt.item] = min(confidence.get(doubt.item, 1.0), doubt.confidence)
        uncertain.append(doubt)


def blocked_views(occluders: Sequence[Occluder], ids: Sequence[str],
                  regions: Sequence[Region], shape: tuple[int, int]) -> list[Blocked]:
    """Each occluder's kind and box with the ids of the objects it touches."""
    touched = occluded_by(occluders, regions, shape)
    return [Blocked(kind=occ.kind, box=occ.box, touches=[ids[i] for i in hits])
            for occ, hits in zip(occluders, touched, strict=True)]


def rests_behind(region: Region, occ: Occluder, shape: tuple[int, int]) -> bool:
    """Whether what lies right under the region's bottom (within `UNDER` px of its
    lowest pixel, column by column) is covered by the occluder."""
    mask = occ.full_mask(shape, 1)
    h = shape[0]
    has = region.mask.any(axis=0)
    cols = np.nonzero(has)[0]
    if len(cols) == 0:
        return False
    rows = region.mask.shape[0]
    lowest = region.y0 + rows - 1 - np.argmax(region.mask[::-1, cols], axis=0)
    xs = region.x0 + cols
    for step in range(1, UNDER + 1):
        ys = lowest + step
        ok = ys < h
        if np.any(mask[ys[ok], xs[ok]]):
            return True
    return False
