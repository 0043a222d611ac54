"""Scene graphs, the dictionary D, relations R, goals and graph diffs."""

from verigraph.graph.dictionary import (
    BUILTIN_DICTIONARIES,
    Dictionary,
    ObjectProperties,
    builtin_dictionary,
    load_dictionary,
    union_dictionary,
)
from verigraph.graph.goal import Goal, GraphDiff, check_goal, diff
from verigraph.graph.io import load_goal, load_scene, save_graph
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import GraphProblem, check_well_formed

__all__ = [
    "BUILTIN_DICTIONARIES", "Dictionary", "Edge", "Goal", "GraphDiff", "GraphProblem", "Node",
    "ObjectProperties", "SceneGraph", "WorldState", "builtin_dictionary", "check_goal",
    "check_well_formed", "diff", "load_dictionary", "load_goal", "load_scene", "save_graph",
    "union_dictionary",
]
