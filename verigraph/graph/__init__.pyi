"""Scene graphs, the dictionary D, relations R, goals and graph diffs."""

from .dictionary import BUILTIN_DICTIONARIES as BUILTIN_DICTIONARIES
from .dictionary import Dictionary as Dictionary
from .dictionary import ObjectProperties as ObjectProperties
from .dictionary import builtin_dictionary as builtin_dictionary
from .dictionary import load_dictionary as load_dictionary
from .dictionary import union_dictionary as union_dictionary
from .goal import Goal as Goal
from .goal import GraphDiff as GraphDiff
from .goal import check_goal as check_goal
from .goal import diff as diff
from .io import load_goal as load_goal
from .io import load_scene as load_scene
from .io import save_graph as save_graph
from .model import Edge as Edge
from .model import Node as Node
from .model import SceneGraph as SceneGraph
from .state import WorldState as WorldState
from .wellformed import GraphProblem as GraphProblem
from .wellformed import check_well_formed as check_well_formed

__all__ = [
    "BUILTIN_DICTIONARIES",
    "Dictionary",
    "Edge",
    "Goal",
    "GraphDiff",
    "GraphProblem",
    "Node",
    "ObjectProperties",
    "SceneGraph",
    "WorldState",
    "builtin_dictionary",
    "check_goal",
    "check_well_formed",
    "diff",
    "load_dictionary",
    "load_goal",
    "load_scene",
    "save_graph",
    "union_dictionary",
]
