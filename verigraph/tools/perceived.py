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
    # perception's confidence per node id and per edge ('source relation target')
    confidence: dict[str, float] = field(default_factory=dict)

    @property
    def confident(self) -> bool:
        return not self.doubts


USER_LABELS = "user_labels_not_perceived"


def perceive_photo(image: np.ndarray, dictionary: Dictionary) -> Perceived:
    """Run built-in perception; its warnings and uncertain items become doubts.

    Built-in perception knows the built-in families only: with a dictionary of the
    client's own labels it does not guess, it says so (the client's vision model reads
    the image with the scene-graph prompt and answers with submit_scene_graph)."""
    if dictionary.user_labels:
        shown = ", ".join(dictionary.user_labels[:8])
        return Perceived(SceneGraph(dictionary=dictionary.reference()), [GraphProblem(
            rule=USER_LABELS, node=None, field="dictionary",
            message=f"built-in perception knows only the built-in dictionaries and cannot "
                    f"see your labels ({shown})",
            fix="read the image with your own vision model using the scene-graph prompt "
                "(get_scene_image returns it with the image) and send the graph with "
                "submit_scene_graph")])
    result = perceive_image(image, dictionary=dictionary)
    doubts = [GraphProblem(rule="perception_uncertain", node=None, field="image",
                           message=w, fix=CONFIRM) for w in result.warnings]
    doubts += [GraphProblem(rule="perception_uncertain",
                            node=u.item if " " not in u.item else None, field="image",
                            message=f"{u.item}: confidence {u.confidence:.2f}, {u.reason}",
                            fix=CONFIRM) for u in result.uncertain]
    return Perceived(result.graph, doubts, dict(result.confidence))
