"""Input types and conversions shared by several tools.

Actions arrive as JSON objects or as text (`move(cup, on, table)`); scenes as built-in
ids or graphs; dictionaries by built-in name or inline as the client's own labels
(never a path: that would let a remote client make the server read its files).
Every conversion error names the argument, the offending value and the fix.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Sequence
from typing import Annotated, Any

from pydantic import AfterValidator, BeforeValidator, Field, WithJsonSchema

from verigraph.actions.model import Action, AnyAction, DoneAction
from verigraph.actions.parser import parse_text_plan
from verigraph.errors import MalformedGraphError, PlanParseError
from verigraph.graph.behavior import BEHAVIOR
from verigraph.graph.builtin_scenes import BUILTIN_GOALS, BUILTIN_SCENES
from verigraph.graph.dictionary import (
    BUILTIN_DICTIONARIES,
    Dictionary,
    InlineDictionary,
    inline_or_name,
    load_dictionary,
    wrong_dictionary_advice,
)
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import GraphProblem
from verigraph.tools.errors import ToolArgumentError

EpisodeId = Annotated[str, Field(
    min_length=1, max_length=64, description="from load_scene",
    examples=["ep_Xq3v9f2PZxk7d1uQm0Cw8g"])]
RequestId = Annotated[str, Field(
    min_length=1, max_length=128, pattern=r"^[\x21-\x7e]+$",
    examples=["c3f1e2a0-step-4"])]
ActionText = Annotated[str, Field(
    min_length=1, max_length=2000,
    description="move(cup, on, table), move(cup, table), move(box, under, table), "
                "open(fridge), close(x), toggle_on(stove), toggle_off(x), "
                "align(piece, side, target, target_side) or done")]
ActionInput = Action | ActionText
SceneId = Annotated[str, Field(min_length=1, max_length=64,
                               description=f"{', '.join(BUILTIN_SCENES)}")]
DictionaryName = Annotated[
    Annotated[str, Field(min_length=1, max_length=32)] | InlineDictionary,
    BeforeValidator(inline_or_name), WithJsonSchema({"type": ["string", "object"]}),
    Field(description=f"{', '.join(BUILTIN_DICTIONARIES)}, all, or your own "
                      "{extends, objects: {label: {surface, container, capacity}}}")]
ImageData = Annotated[str, Field(
    min_length=1, max_length=17_000_000,
    description="base64 PNG/JPEG or a data: URL")]


MAX_GRAPH_NODES = 5000
MAX_GRAPH_EDGES = 20_000
# Node attributes are a colour and a few property overrides; an episode keeps them and
# returns them with every graph, so a large one would be paid for on every call.
MAX_NODE_ATTRS_BYTES = 4096
MAX_GRAPH_ATTRS_BYTES = 1024 * 1024


def check_attrs_size(nodes: Sequence[Any]) -> None:
    """ValueError naming the first node whose attrs (as JSON) are too large, or the total."""
    total = 0
    for i, node in enumerate(nodes):
        if not node.attrs:
            continue
        try:
            size = len(json.dumps(node.attrs, default=str))
        except (TypeError, ValueError, RecursionError):
            raise ValueError(f"nodes[{i}].attrs of '{str(node.id)[:64]}' is not plain JSON "
                             "data") from None
        if size > MAX_NODE_ATTRS_BYTES:
            raise ValueError(f"nodes[{i}].attrs of '{str(node.id)[:64]}' is {size} bytes as "
                             f"JSON; at most {MAX_NODE_ATTRS_BYTES} bytes per node are kept "
                             "(attrs hold a colour and property overrides, not data)")
        total += size
    if total > MAX_GRAPH_ATTRS_BYTES:
        raise ValueError(f"the nodes' attrs total {total} bytes; at most "
                         f"{MAX_GRAPH_ATTRS_BYTES} bytes per graph are kept")


def _check_counts(nodes: int, edges: int) -> None:
    if nodes > MAX_GRAPH_NODES or edges > MAX_GRAPH_EDGES:
        raise ValueError(f"the graph has {nodes} nodes and {edges} edges; at most "
                         f"{MAX_GRAPH_NODES} nodes and {MAX_GRAPH_EDGES} edges are accepted")


def counted_graph(value: Any) -> Any:
    """Refuse an oversized raw graph before its nodes and edges are validated one by one
    (300,000 nodes would take a second to validate only to be refused)."""
    if isinstance(value, dict):
        nodes, edges = value.get("nodes"), value.get("edges")
        _check_counts(len(nodes) if isinstance(nodes, list) else 0,
                      len(edges) if isinstance(edges, list) else 0)
    return value


def bounded_graph(graph: SceneGraph) -> SceneGraph:
    """A validated graph within the counts and the attrs' size, or a ValueError."""
    _check_counts(len(graph.nodes), len(graph.edges))
    check_attrs_size(graph.nodes)
    return graph


# A graph argument, refused by its counts before its items are validated one by one (a
# goal's graph: tools.goals.BoundedGoal).
BoundedGraph = Annotated[SceneGraph, BeforeValidator(counted_graph),
                         AfterValidator(bounded_graph)]


def parse_actions(items: Sequence[Any], *, field: str = "actions", indexed: bool = True
                  ) -> list[AnyAction]:
    """Models pass through; strings are parsed as text plans (one or more lines each)."""
    actions: list[AnyAction] = []
    for index, item in enumerate(items):
        where = f"{field}[{index}]" if indexed else field
        if not isinstance(item, str):
            actions.append(item)
            continue
        try:
            parsed = parse_text_plan(item)
        except PlanParseError as exc:
            raise ToolArgumentError(f"{exc.message}: {exc.text[:120]!r}", field=where,
                                    value=item[:120], fix=exc.fix) from None
        if not parsed:
            raise ToolArgumentError("no action in this text (only blanks or comments)",
                                    field=where, value=item[:120],
                                    fix="write an action such as move(cup, on, table) or done")
        actions.extend(parsed)
    return actions


def count_moves(actions: Sequence[AnyAction]) -> int:
    return sum(1 for a in actions if not isinstance(a, DoneAction))


def dictionary_for(name: str | InlineDictionary | None, *, field: str = "dictionary"
                   ) -> Dictionary:
    """A built-in dictionary (or the union for None/"all"), or the client's own inline
    one; paths are refused."""
    if isinstance(name, InlineDictionary):
        return name.build()
    if name is None or name == "all":
        return load_dictionary(None)
    if name not in (*BUILTIN_DICTIONARIES, BEHAVIOR):
        raise ToolArgumentError(
            f"'{name[:64]}' is not a built-in dictionary", field=field, value=name[:64],
            fix=f"use one of {', '.join(BUILTIN_DICTIONARIES)}, {BEHAVIOR} or all (dictionary "
                "files cannot be read through the tool interface)")
    return load_dictionary(name)


def builtin_scene(scene_id: str, *, field: str = "scene_id", with_goal: bool = True
                  ) -> tuple[SceneGraph, Goal | None]:
    """A built-in scene and its goal (None without one, or when `with_goal` is False:
    a caller with its own goal has no use for the built-in one)."""
    maker = BUILTIN_SCENES.get(scene_id)
    if maker is None:
        raise ToolArgumentError(f"no built-in scene '{scene_id[:64]}'", field=field,
                                value=scene_id[:64],
                                fix=f"use one of {', '.join(BUILTIN_SCENES)}, or pass a graph")
    return maker(), builtin_goal(scene_id) if with_goal else None


def builtin_goal(scene_id: str) -> Goal | None:
    """A built-in scene's goal, built alone (None for a scene without one)."""
    goal_maker = BUILTIN_GOALS.get(scene_id)
    return goal_maker() if goal_maker else None


@functools.cache
def builtin_state(scene_id: str) -> WorldState:
    """A built-in scene, checked and indexed once per process (built-in scenes are code,
    never edited); a caller that changes it works on a copy. An unknown id raises
    (and is not cached)."""
    return state_from_graph(builtin_scene(scene_id, with_goal=False)[0])


def problems_text(problems: Sequence[GraphProblem], prefix: str) -> str:
    """Every problem on its own line: field, message, fix."""
    return "\n".join(f"- {prefix}.{p.field}: {p.message} (fix: {p.fix})" for p in problems)


def state_from_graph(graph: SceneGraph, *, field: str = "graph", partial: bool = False
                     ) -> WorldState:
    """Index a graph after checking it; all well-formedness problems in one error."""
    dictionary = dictionary_for(graph.dictionary, field=f"{field}.dictionary")
    try:
        return WorldState.from_graph(graph, dictionary, partial=partial)
    except MalformedGraphError as exc:
        problems = with_dictionary_advice(graph, list(exc.problems))
        raise ToolArgumentError(
            f"the scene graph breaks {len(problems)} rule(s):\n"
            + problems_text(problems, field), field=field, value=None,
            fix="correct every listed problem and send the graph again") from None


def with_dictionary_advice(graph: SceneGraph, problems: list[GraphProblem],
                           chosen: str | InlineDictionary | None = None
                           ) -> list[GraphProblem]:
    """Unknown labels that another built-in dictionary knows become one problem on
    `dictionary` saying which one, instead of spelling suggestions per label.
    `chosen`: the dictionary the graph was checked against (default: the one it names)."""
    chosen = chosen or graph.dictionary
    unknown = [p for p in problems if p.rule == "unknown_label" and p.node is not None]
    if not unknown or not isinstance(chosen, str) or chosen not in BUILTIN_DICTIONARIES:
        return problems
    labels = {node.id: node.label for node in graph.nodes}
    found = wrong_dictionary_advice([labels[p.node] for p in unknown if p.node in labels],
                                    chosen, list(labels.values()))
    if found is None:
        return problems
    message, fix, covered = found
    moved = [p for p in unknown if p.node in labels and labels[p.node] in covered]
    merged = GraphProblem(rule="wrong_dictionary", node=None, field="dictionary",
                          message=message, fix=fix)
    return [merged, *(p for p in problems if p not in moved)]
