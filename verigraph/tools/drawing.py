"""A picture of a scene graph, for episodes that have no simulator to render.

Support edges are drawn as a side view: each object sits above what supports it, so a
stack looks like a stack. Tangram contacts (no supports) are laid out on a circle.
Layout is networkx; drawing is OpenCV; the result is a BGR image, PNG-encoded by the
caller. Deterministic: the same graph always gives the same pixels.
"""

from __future__ import annotations

import hashlib
from collections.abc import Collection

import cv2
import networkx as nx
import numpy as np

from verigraph.graph.model import Edge, SceneGraph

NAMED_COLORS: dict[str, tuple[int, int, int]] = {  # BGR
    "white": (245, 245, 245), "black": (40, 40, 40), "gray": (160, 160, 160),
    "grey": (160, 160, 160), "darkgray": (100, 100, 100), "silver": (200, 200, 200),
    "steel": (180, 175, 170), "red": (60, 60, 220), "green": (80, 170, 80),
    "blue": (200, 120, 50), "yellow": (60, 210, 230), "orange": (40, 150, 245),
    "purple": (160, 70, 140), "pink": (180, 150, 240), "brown": (50, 90, 140),
    "walnut": (45, 75, 110), "tan": (120, 170, 210), "cyan": (210, 200, 60),
}
SIDE_LABEL_AT = 0.3  # a side number's place along a touches line, from its own piece
EDGE_COLORS = {"on": (70, 70, 70), "in": (180, 100, 30), "touches": (60, 150, 60)}
HIGHLIGHT_COLOR = (0, 140, 255)  # BGR orange: edges the step added
OUTLINE_COLOR = (30, 30, 220)  # BGR red: objects that block a refused step
FONT = cv2.FONT_HERSHEY_SIMPLEX


def layout(graph: SceneGraph) -> dict[str, tuple[float, float]]:
    """Node positions in [0, 1]^2 (x to the right, y upwards)."""
    ids = graph.node_ids()
    if not ids:
        return {}
    support = nx.DiGraph()
    support.add_nodes_from(ids)
    support.add_edges_from((e.target, e.source) for e in graph.edges
                           if e.relation != "touches" and e.source in support
                           and e.target in support)
    if support.number_of_edges() == 0 and any(e.relation == "touches" for e in graph.edges):
        circle = nx.circular_layout(sorted(ids))
        return {n: ((float(p[0]) + 1) / 2, (float(p[1]) + 1) / 2) for n, p in circle.items()}
    if not nx.is_directed_acyclic_graph(support):  # malformed input: fall back to a row
        return {n: ((i + 0.5) / len(ids), 0.5) for i, n in enumerate(sorted(ids))}
    slots: dict[str, float] = {}
    depth: dict[str, int] = {}
    next_slot = 0.0
    roots = sorted((n for n in ids if support.in_degree(n) == 0),
                   key=lambda n: (support.out_degree(n) == 0, n))
    for root in roots:
        depth[root] = 0
        for parent, child in nx.bfs_edges(support, root):
            depth.setdefault(child, depth[parent] + 1)
        for node in nx.dfs_postorder_nodes(support, root):
            if node in slots:
                continue
            children = [c for c in sorted(support.successors(node)) if c in slots]
            if children:
                slots[node] = sum(slots[c] for c in children) / len(children)
            else:
                slots[node] = next_slot
                next_slot += 1.0
    width = max(next_slot, 1.0)
    levels = max(depth.values(), default=0) + 1
    return {n: ((slots[n] + 0.5) / width, (depth.get(n, 0) + 0.5) / levels) for n in ids}


def node_color(label: str, attrs: dict[str, object], default: str | None = None
               ) -> tuple[int, int, int]:
    """The node's `color` attribute, else the dictionary's colour, else one from its label."""
    name = str(attrs.get("color", default or "")).lower()
    if name in NAMED_COLORS:
        return NAMED_COLORS[name]
    digest = hashlib.sha256(label.encode()).digest()
    return (150 + digest[0] % 90, 150 + digest[1] % 90, 150 + digest[2] % 90)


DRAWING_SIZE = (640, 480)


def draw_graph(graph: SceneGraph, width: int | None = None, height: int | None = None,
               title: str | None = None, colors: dict[str, str] | None = None, *,
               highlight: Collection[Edge] = (), outline: Collection[str] = ()
               ) -> np.ndarray:
    """BGR uint8 picture of `graph`: labelled boxes, relation arrows, optional title.
    A side not given is DRAWING_SIZE's.

    `colors` maps node ids to colour names (e.g. from the dictionary) used when a node
    has no `color` attribute of its own. `highlight` edges (those a step added) are drawn
    thick and orange; `outline` objects (those blocking a refused step) get a thick red
    frame, so a picture alone shows what changed and what is in the way.
    """
    highlighted = {(e.source, e.relation, e.target) for e in highlight}
    colors = colors or {}
    width, height = width or DRAWING_SIZE[0], height or DRAWING_SIZE[1]
    image = np.full((height, width, 3), 255, dtype=np.uint8)
    top = 30 if title else 8
    if title:
        cv2.putText(image, title[:90], (8, 20), FONT, 0.5, (30, 30, 30), 1, cv2.LINE_AA)
    positions = layout(graph)
    if not positions:
        cv2.putText(image, "(empty scene graph)", (8, height // 2), FONT, 0.6, (90, 90, 90), 1,
                    cv2.LINE_AA)
        return image
    box_w = int(min(130, max(60, width / (len(positions) + 1))))
    box_h = 34
    margin_x, margin_y = box_w // 2 + 6, box_h // 2 + 6
    centers = {n: (int(margin_x + x * (width - 2 * margin_x)),
                   int(height - margin_y - y * (height - top - 2 * margin_y)))
               for n, (x, y) in positions.items()}
    for edge in graph.edges:
        if edge.source not in centers or edge.target not in centers:
            continue
        _draw_edge(image, centers[edge.source], centers[edge.target], edge.relation, box_h,
                   edge.source_side, edge.target_side,
                   (edge.source, edge.relation, edge.target) in highlighted)
    for node in graph.nodes:
        if node.id in centers:
            _draw_node(image, centers[node.id], box_w, box_h, node.id, node.label,
                       node_color(node.label, node.attrs, colors.get(node.id)))
            if node.id in outline:
                x, y = centers[node.id]
                cv2.rectangle(image, (x - box_w // 2 - 4, y - box_h // 2 - 4),
                              (x + box_w // 2 + 4, y + box_h // 2 + 4), OUTLINE_COLOR, 3,
                              cv2.LINE_AA)
    return image


def _draw_edge(image: np.ndarray, src: tuple[int, int], dst: tuple[int, int], relation: str,
               box_h: int, source_side: int | None, target_side: int | None,
               highlighted: bool = False) -> None:
    color = HIGHLIGHT_COLOR if highlighted else EDGE_COLORS.get(relation, (120, 60, 160))
    thickness = 4 if highlighted else 2
    if relation == "touches":
        # Each piece's side number at that piece's end of the line, so no reader has to
        # guess which number belongs to which piece.
        cv2.line(image, src, dst, color, thickness, cv2.LINE_AA)
        for near, far, side in ((src, dst, source_side), (dst, src, target_side)):
            at = (int(near[0] + SIDE_LABEL_AT * (far[0] - near[0])) + 4,
                  int(near[1] + SIDE_LABEL_AT * (far[1] - near[1])))
            cv2.putText(image, f"side {side or 0}", at, FONT, 0.42, color, 1, cv2.LINE_AA)
        return
    start = (src[0], src[1] + box_h // 2)
    end = (dst[0], dst[1] - box_h // 2)
    cv2.arrowedLine(image, start, end, color, thickness, cv2.LINE_AA, tipLength=0.12)
    mid = ((src[0] + dst[0]) // 2 + 4, (src[1] + dst[1]) // 2)
    cv2.putText(image, relation, mid, FONT, 0.42, color, 1, cv2.LINE_AA)


def _draw_node(image: np.ndarray, center: tuple[int, int], box_w: int, box_h: int,
               node_id: str, label: str, fill: tuple[int, int, int]) -> None:
    x0, y0 = center[0] - box_w // 2, center[1] - box_h // 2
    x1, y1 = x0 + box_w, y0 + box_h
    cv2.rectangle(image, (x0, y0), (x1, y1), fill, -1)
    cv2.rectangle(image, (x0, y0), (x1, y1), (40, 40, 40), 1, cv2.LINE_AA)
    ink = (20, 20, 20) if sum(fill) > 330 else (245, 245, 245)
    lines = [node_id] if label == node_id else [node_id, f"({label})"]
    first_baseline = center[1] + 5 - 7 * (len(lines) - 1)
    for row, text in enumerate(lines):
        scale = 0.4
        (tw, _), _ = cv2.getTextSize(text, FONT, scale, 1)
        while tw > box_w - 6 and len(text) > 4:
            text = text[:-2] + "~"
            (tw, _), _ = cv2.getTextSize(text, FONT, scale, 1)
        origin = (center[0] - tw // 2, first_baseline + row * 14)
        cv2.putText(image, text, origin, FONT, scale, ink, 1, cv2.LINE_AA)


def render_caption(view: str, *, simulated: bool, photo: bool) -> str:
    """What render_scene's image is, for a reader that cannot tell a diagram from a photo.

    Only a simulated episode has a picture of its own; a graph-only episode gets this
    module's diagram, and the caption says how to get a picture instead.
    """
    what = "the goal" if view == "goal" else "the current scene"
    if simulated:
        return f"the 2D simulator's picture of {what}"
    if photo:
        return "the photo the episode was loaded from (it does not change as actions run)"
    return (f"a DIAGRAM of {what}'s graph (boxes and support edges; a touches line shows "
            "each piece's side number at that piece's end), not a picture: this "
            "episode has no simulator; load the scene with simulate=true for the simulator's "
            "picture")
