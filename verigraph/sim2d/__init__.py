"""sim2d: pymunk tabletop (side view) and tangram (top view) worlds, renderer, generator.

    >>> from verigraph.graph.builtin_scenes import cup_on_book
    >>> world = world_for_graph(cup_on_book())
    >>> world.observe().sentences()
    ['book on desk', 'cup on book']
"""

from __future__ import annotations

from verigraph.graph.dictionary import load_dictionary
from verigraph.graph.model import SceneGraph
from verigraph.sim2d.degrade import Degradation, degrade
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.generator import FAMILIES, GeneratedScene, generate_scene
from verigraph.sim2d.render import encode_png, side_by_side
from verigraph.sim2d.tabletop import TabletopWorld
from verigraph.sim2d.tangram import TangramWorld
from verigraph.sim2d.world import SimWorld


def is_tangram(graph: SceneGraph) -> bool:
    """A graph of tangram pieces (every node has sides in the dictionary)."""
    d = load_dictionary(graph.dictionary)
    labels = [d.resolve(n.label) for n in graph.nodes]
    return bool(labels) and all(
        lab is not None and d.objects[lab].sides is not None for lab in labels)


def world_for_graph(graph: SceneGraph, seed: int = 0) -> SimWorld:
    """A simulated world whose `observe()` equals `graph` (tabletop or tangram).

    Raises MalformedGraphError for graphs that are not well formed and SimError for
    graphs the physics cannot realise (both VeriGraphError, with field and fix).
    """
    if is_tangram(graph):
        from verigraph.sim2d.tangram import build_tangram
        return build_tangram(graph)
    from verigraph.sim2d.layout import build_tabletop
    return build_tabletop(graph, seed)


__all__ = [
    "FAMILIES", "Degradation", "GeneratedScene", "SimError", "SimWorld", "TabletopWorld",
    "TangramWorld", "degrade", "encode_png", "generate_scene", "is_tangram", "side_by_side",
    "world_for_graph",
]
