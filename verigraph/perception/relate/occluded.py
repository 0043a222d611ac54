"""What an occluder does to the graph: the objects it touches are named, made uncertain
(with their edges), and the graph becomes a proposal, never an accepted wrong graph.

Part of an object behind a band may still be inferred: when the object shows on both
sides of the band (its extent is bounded), or its contact with what it rests on shows,
and that supporter is visible on both sides of the band (or is not hidden at all), the
edge between them is what the picture shows around the band. Such objects are doubted
less, and the reason says the hidden part can be inferred; the rest say it cannot.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from verigraph.graph.model import Edge, SceneGraph
from verigraph.perception.detect.occlusion import Occluder, occluded_by, split_by
from verigraph.perception.detect.regions import Region
from verigraph.perception.result import Uncertain

INFERRED = 0.45  # confidence of an occluded object whose hidden part can be inferred
HIDDEN = 0.2  # ... and of one whose hidden part cannot
HIDDEN_REASON = "partly hidden by"  # how every occlusion doubt's reason starts


def occlusion_doubts(graph: SceneGraph, ids: Sequence[str], regions: Sequence[Region],
                     occluders: Sequence[Occluder], shape: tuple[int, int], *,
                     edge_name: Callable[[Edge], str], supports: bool = True
                     ) -> tuple[list[str], list[Uncertain], list[str]]:
    """(warnings, uncertain items, occluded ids) for the occluders found in an image.

    `supports`: edges are `source rests on/in target` (tabletop); tangram contacts have
    no supporter, so only the shape's completion is judged."""
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
                inferable = support_seen
                why = (f"'{edge_name(edge)}' can be inferred: {edge.target} is visible on "
                       "both sides of it" if inferable else
                       f"what it rests on behind it cannot be inferred ({edge.target} is "
                       "hidden there too)")
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
