"""Built-in perception as the tools use it: a graph, and whether it may be taken as fact.

Perception reports warnings and uncertain items; a graph that comes with any of them
is a proposal, not a perceived fact. The tools then return it with one
`perception_uncertain` problem per reason (so it is not accepted) and the agent
confirms or corrects it with `submit_scene_graph`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import GraphProblem
from verigraph.perception import perceive_image

CONFIRM = ("look at the image (get_scene_image) and send the graph as you see it, this "
           "proposal corrected where needed, with submit_scene_graph")


@dataclass(slots=True)
class Perceived:
    """A perceived graph and the reasons to doubt it (empty: take it as perceived)."""

    graph: SceneGraph
    doubts: list[GraphProblem] = field(default_factory=list)

    @property
    def confident(self) -> bool:
        return not self.doubts


def perceive(image: np.ndarray, dictionary: Dictionary) -> Perceived:
    """Run built-in perception; its warnings and uncertain items become doubts."""
    result = perceive_image(image, dictionary=dictionary)
    doubts = [GraphProblem(rule="perception_uncertain", node=None, field="image",
                           message=w, fix=CONFIRM) for w in result.warnings]
    doubts += [GraphProblem(rule="perception_uncertain",
                            node=u.item if " " not in u.item else None, field="image",
                            message=f"{u.item}: confidence {u.confidence:.2f}, {u.reason}",
                            fix=CONFIRM) for u in result.uncertain]
    return Perceived(result.graph, doubts)
