"""Detections -> scene graph: ids by the generator's conventions, attrs, edges.

Ids follow what the rest of VeriGraph writes, so a perceived reference image names the
same objects as the episode it is a goal for: the label (`cup`), `label_2` for a second
one (numbered left to right), and `<colour>_<label>` for objects whose colour is their
identity (blocks: `red_block`, with `attrs.color`).
"""

from __future__ import annotations

from collections.abc import Sequence

from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.perception.detect.tabletop import Detection


def assign_ids(detections: Sequence[Detection]) -> None:
    """Give every detection a unique id (in place)."""
    order = sorted(range(len(detections)), key=lambda i: (detections[i].region.x0,
                                                          detections[i].region.y0))
    seen: dict[str, int] = {}
    for i in order:
        d = detections[i]
        base = d.label if d.model.own_colour else f"{d.colour}_{d.label}"
        seen[base] = seen.get(base, 0) + 1
        d.id = base if seen[base] == 1 else f"{base}_{seen[base]}"


def node_for(d: Detection) -> Node:
    attrs: dict[str, object] = {} if d.model.own_colour else {"color": d.colour}
    return Node(id=d.id, label=d.label, attrs=attrs)


def tabletop_graph(detections: Sequence[Detection], supports: dict[str, tuple[str, str]],
                   dictionary_name: str | None) -> SceneGraph:
    """The scene graph of a side view (edges: object relation supporter, by id)."""
    nodes = [node_for(d) for d in detections]
    edges = [Edge(source=obj, relation=rel, target=target)
             for obj, (rel, target) in supports.items()]
    return SceneGraph(nodes=nodes, edges=edges, dictionary=dictionary_name).canonical()
