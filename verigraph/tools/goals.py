"""Goals: the set_goal tool, the goal arguments of the stateless tools, and the check
every goal passes before it is stored. A stateless check (validate_plan, solve, the
viewer's plan view) reads its scene's state and its goal once, together
(`stateless_source`), and hands both to the core.

A goal graph must be well formed and name only objects of the scene; goal edges may be
given as text (`cup on table; spoon in pot`), nodes taken from the episode; a goal formula
(BDDL, text starting with `(`) must parse and name only the scene's objects and known
kinds; an image goal
is read by built-in perception and its objects matched to the episode's ids; words alone
are translated by the rule-based translator into a proposal the client confirms. An
invalid goal changes nothing, and neither does a proposal.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass, field
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, model_validator

from verigraph.errors import GoalError
from verigraph.graph.dictionary import STATE_ROLES, STATE_WORDS
from verigraph.graph.formula import FORMULA_EXAMPLE, parse_formula
from verigraph.graph.formula_eval import check_names, facts_of, meanings_in
from verigraph.graph.goal import (
    PREDICATES,
    Goal,
    GraphDiff,
    check_goal,
    goal_kind_problems,
    looks_like_formula,
)
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.translator import read_instruction
from verigraph.graph.wellformed import check_well_formed, label_readings, readings_line
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.fields import (
    BoundedGraph,
    EpisodeId,
    ImageData,
    bounded_graph,
    builtin_goal,
    builtin_state,
    counted_graph,
    dictionary_for,
    problems_text,
    state_from_graph,
)
from verigraph.tools.images import decode_base64_image
from verigraph.tools.perceived import Perceived, perceive_photo
from verigraph.tools.request import (
    WORLD_LIMITS,
    is_narrower,
    keep_asked_goal,
    keep_asked_words,
    left_out,
)
from verigraph.tools.store import LiveEpisode
from verigraph.tools.texts import goal_edges_text, goal_line

Instruction = Field(default=None, max_length=4000,
                    description="the task in words (shown, not checked)")
MAX_GOAL_EDGES_CHARS = 20_000
# Below this, a perceived object's or edge's confidence is named in set_goal's text.
NOTED_CONFIDENCE = 0.9
# set_goal's text lists at most this many photo-object matches (the rest are counted).
MAX_LISTED_MATCHES = 40
# An unknown id in a goal edge is compared with at most this many scene ids.
MAX_NEAR_CANDIDATES = 400


def check_goal_against(goal: Goal, state: WorldState | None, *, field: str) -> None:
    """A goal graph must be well formed and name only objects of the scene; a formula
    must name only the scene's objects and known kinds."""
    if goal.formula is not None and state is not None:
        check_formula_against(goal.formula, state, field=f"{field}.formula")
    if goal.graph is None:
        return
    dictionary = state.dictionary if state is not None else dictionary_for(goal.graph.dictionary)
    problems = check_well_formed(goal.graph, dictionary, partial=goal.partial)
    if problems:
        raise ToolArgumentError(
            f"the goal graph breaks {len(problems)} rule(s):\n"
            + problems_text(problems, f"{field}.graph"), field=f"{field}.graph", value=None,
            fix="correct every listed problem and send the goal again")
    if state is None:
        return
    goal_ids = set(goal.graph.node_ids())
    unknown = sorted(goal_ids - set(state.objects))
    if unknown:
        raise ToolArgumentError(
            f"the goal names objects that are not in the scene: {', '.join(unknown)}",
            field=f"{field}.graph.nodes", value=unknown[0],
            fix=f"use ids from the scene: {', '.join(sorted(state.objects))}")
    changed = goal_kind_problems(goal.graph, state)
    if changed:
        raise ToolArgumentError(
            f"the goal gives {len(changed)} object(s) another kind than the scene's:\n"
            + problems_text(changed, f"{field}.graph"), field=f"{field}.graph.nodes",
            value=changed[0].node, fix=changed[0].fix)
    absent = sorted(set(state.objects) - goal_ids)
    if absent and not goal.partial:
        raise ToolArgumentError(
            f"a full goal must list every object of the scene; missing: {', '.join(absent)}",
            field=f"{field}.graph.nodes", value=absent[0],
            fix="add the missing objects with their goal supports, or set partial=true to "
                "require only the listed edges")


def check_formula_against(text: str, state: WorldState, *, field: str) -> None:
    """The formula parses and names only the scene's objects and known kinds."""
    try:
        check_names(parse_formula(text), facts_of(state))
    except GoalError as exc:
        raise ToolArgumentError(exc.message, field=field, value=exc.value,
                                fix=exc.fix) from None


def goal_from_formula(text: str, state: WorldState | None, *, field: str = "formula",
                      partial: bool = True) -> Goal:
    """A formula's text as a goal, checked against the scene when there is one."""
    try:
        parse_formula(text.strip())
    except GoalError as exc:
        raise ToolArgumentError(exc.message, field=field, value=exc.value,
                                fix=exc.fix) from None
    goal = Goal(formula=text.strip(), partial=partial)
    if state is not None:
        check_formula_against(goal.formula or "", state, field=field)
    return goal


class SetGoalInput(BaseModel):
    """A goal graph, a predicate, a reference image, or just an instruction."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    graph: BoundedGraph | None = Field(default=None, description="goal scene graph")
    edges: str | None = Field(default=None, max_length=MAX_GOAL_EDGES_CHARS,
                              description="goal edges as text; 'x not on y' makes "
                                          "them a formula")
    formula: str | None = Field(default=None, max_length=MAX_GOAL_EDGES_CHARS,
                                description=f"BDDL, e.g. {FORMULA_EXAMPLE}")
    partial: bool | None = Field(default=None, description="only the listed edges must "
                                 "hold (default: true for edges)")
    predicate: Literal["single_stack"] | None = Field(
        default=None, description="single_stack: every movable object in one tower")
    image: ImageData | None = Field(default=None, description="goal picture (built-in "
                                                              "perception)")
    instruction: str | None = Field(default=None, max_length=4000,
                                    description="words; alone: a proposal (placements, "
                                                "states like 'stove on', 'no cup on any "
                                                "plate')")

    @model_validator(mode="after")
    def _something(self) -> SetGoalInput:
        if not any(v is not None for v in (self.graph, self.edges, self.formula,
                                           self.predicate, self.image, self.instruction)):
            raise ValueError("give a goal: graph, edges, formula, predicate, image or "
                             "instruction")
        if sum(v is not None for v in (self.graph, self.edges, self.formula, self.image)) > 1:
            raise ValueError("give only one of graph, edges, formula and image")
        return self


class GoalOutput(BaseModel):
    """The episode's goal after set_goal and how far the current graph is from it."""

    episode_id: str
    goal: Goal | None
    instruction: str | None
    checkable: bool = Field(description="false when only an instruction was given")
    goal_satisfied: bool | None
    goal_diff: GraphDiff | None
    accepted: bool = Field(default=True, description="false: `proposal` is not set yet")
    proposal: Goal | None = None
    notes: list[str] = Field(default_factory=list)
    # How the goal graph's labels were read, as load_scene reports them (`box read as
    # block (synonym, blocks dictionary)`).
    label_readings: list[str] = Field(default_factory=list)

    def summary(self) -> str:
        notes = [f"- {n}" for n in self.notes]
        if self.label_readings:
            notes.append(readings_line(self.label_readings))
        if not self.accepted:
            return "\n".join(self._proposal_lines() + notes)
        if not self.checkable:
            return "\n".join([
                "instruction recorded; it is not checkable by itself: give goal edges "
                "(edges='cup on table; spoon in pot'), a goal graph or a predicate ("
                + ", ".join(PREDICATES) + ") to verify it", *notes])
        assert self.goal is not None
        head = "goal set"
        if self.goal_diff is None:
            head += "; it will be checked once the scene graph is submitted"
        else:
            head += f"; {self.goal_diff.summary()}"
        return "\n".join([head, goal_line(self.goal) or "",
                          *meanings_in(self.goal.formula or ""), *notes])

    def _proposal_lines(self) -> list[str]:
        kept = (f"the episode keeps its goal: {goal_line(self.goal)}" if self.goal is not None
                else "the episode has no goal yet")
        if self.proposal is None:
            return ["goal PROPOSAL: nothing to propose (accepted: false, nothing set); "
                    f"{kept}; it is not checkable: give goal edges (edges='cup on table; "
                    "spoon in pot') or a predicate (" + ", ".join(PREDICATES) + ")"]
        return [f"goal PROPOSAL (accepted: false, nothing set; {kept}):",
                f"proposed {goal_line(self.proposal)}",
                "to accept it, call set_goal with "
                f"{accepting_arguments(self.episode_id, self.proposal)} (corrected where "
                "needed)"]


def accepting_arguments(episode_id: str, proposal: Goal) -> str:
    """`episode_id="ep_1", edges="cup on table; stove on", partial=true`: the set_goal
    arguments that store exactly `proposal` (partial spelled out: edges default to
    partial, and a full proposal needs partial=false); a formula proposal's
    `formula='(forall ...)'`."""
    if proposal.formula is not None:
        return f"episode_id=\"{episode_id}\", formula='{proposal.formula_text()}'"
    return (f"episode_id=\"{episode_id}\", edges=\"{goal_edges_text(proposal)}\", "
            f"partial={'true' if proposal.partial else 'false'}")


@dataclass
class _Reading:
    """A goal as set_goal read it: the goal, whether to store it, and what to tell."""

    goal: Goal | None
    accepted: bool = True
    notes: list[str] = field(default_factory=list)


# `source relation target`, words apart by spaces or a comma and spaces, `move(...)` around
# them allowed. Possessive runs (`*+`, `++`) and a separator read one way: each run of
# spaces is read once (the backtracking form was quadratic in a long run of spaces).
_SEP = r"(?:\s*+,\s++|\s++)"
_EDGE_TEXT = re.compile(rf"\s*+(?:move\s*+\()?+\s*+([\w.-]++){_SEP}([a-z_]++){_SEP}([\w.-]++)"
                        r"\s*+\)?+\s*+")
# A goal state: `fridge closed`, `stove on` (the words of STATE_WORDS).
_STATE_TEXT = re.compile(r"\s*+([\w.-]++)\s++(open|closed|on|off)\s*+")
_STATE_OF_WORD = {word: (key, value) for key, words in STATE_WORDS.items()
                  for value, word in ((False, words[0]), (True, words[1]))}


# `cup_1 not on plate_a`: an item that asks for an edge NOT to hold.
_NOT_EDGE_TEXT = re.compile(r"\s*+([\w.-]++)\s++not\s++([a-z_]++)\s++([\w.-]++)\s*+")


def negated_edges_formula(text: str) -> str | None:
    """Goal edges with `x not on y` items, as the formula they mean: `(and (on plate_b
    tray) (not (on cup_1 plate_a)))` (a graph goal cannot say "not"); None when no item
    is negated or an item is not an edge, a negated edge or a state (goal_from_edges
    then reports it)."""
    items = [i for i in re.split(r"[;\n]", text) if i.strip()]
    parts: list[str] = []
    negated = False
    for item in items:
        if (m := _NOT_EDGE_TEXT.fullmatch(item)) is not None:
            source, relation, target = m.groups()
            parts.append(f"(not ({relation} {source} {target}))")
            negated = True
        elif (m := _EDGE_TEXT.fullmatch(item)) is not None:
            source, relation, target = m.groups()
            parts.append(f"({relation} {source} {target})")
        elif (m := _STATE_TEXT.fullmatch(item)) is not None:
            obj, word = m.groups()
            key, value = _STATE_OF_WORD[word]
            parts.append(f"({key} {obj})" if value else f"(not ({key} {obj}))")
        else:
            return None
    if not negated:
        return None
    return parts[0] if len(parts) == 1 else f"(and {' '.join(parts)})"


def goal_from_edges(text: str, state: WorldState | None, *, field: str = "edges",
                    partial: bool = True) -> Goal:
    """`cup on table; spoon in pot` (or one per line, or move(...) forms) as a goal;
    `fridge closed`, `stove on` ask for a state.

    The nodes come from the scene, so a goal names only what must hold. Partial (only
    these edges must hold) unless `partial` is False: then the listed edges are the
    whole goal graph. Every bad item is reported at once, each with the fix.
    """
    if state is None:
        raise ToolArgumentError("the episode has no scene graph yet, so goal edges cannot "
                                "name its objects", field=field, value=text[:80],
                                fix="submit the scene graph first (submit_scene_graph)")
    items = [i for i in re.split(r"[;\n]", text) if i.strip()]
    if len(items) == 1 and "," in items[0] and "(" not in items[0]:
        items = [i for i in items[0].split(",") if i.strip()]
    edges: list[Edge] = []
    problems: list[str] = []
    relations = state.move_relations
    states: dict[str, dict[str, bool]] = {}
    for item in items:
        wanted = _STATE_TEXT.fullmatch(item)
        if wanted is not None:
            obj, word = wanted.groups()
            key, value = _STATE_OF_WORD[word]
            role = STATE_ROLES[key]
            info = state.objects.get(obj)
            if info is None:
                problems.append(f"'{item.strip()[:60]}': no object {obj} in the scene")
            elif not getattr(info.props, role):
                problems.append(f"'{item.strip()[:60]}': {obj} ({info.label}) is not {role}")
            else:
                states.setdefault(obj, {})[key] = value
            continue
        m = _EDGE_TEXT.fullmatch(item)
        if m is None:
            problems.append(f"'{item.strip()[:60]}' is not 'source relation target'")
            continue
        source, relation, target = m.groups()
        unknown = [n for n in (source, target) if n not in state.objects]
        if unknown:
            problems.append(f"'{item.strip()[:60]}': no object {', '.join(unknown)} in the "
                            "scene")
        elif relation not in relations:
            problems.append(f"'{item.strip()[:60]}': relation '{relation}' is not one of "
                            f"{', '.join(relations)}")
        else:
            edges.append(Edge(source=source, relation=relation, target=target))
    if problems or not (edges or states):
        raise ToolArgumentError(
            "goal edges: " + ("; ".join(problems[:10]) or "no edge given"), field=field,
            value=text[:80], fix="write one 'source relation target' (or 'source not "
                                 "relation target') per item, separated by ';', with ids from "
                                 "the scene: "
                                 f"{', '.join(sorted(state.objects)[:20])}")
    # The scene's nodes (as `state.to_graph().stateless_nodes()` has them, in id order),
    # read off the state itself: the scene's edges are not needed.
    nodes = [Node.model_validate({"id": o.id, "label": o.label, "attrs": o.attrs,
                                  **({"state": states[o.id]} if o.id in states else {})})
             for o in sorted(state.objects.values(), key=lambda o: o.id)]
    return Goal(graph=SceneGraph(nodes=nodes, edges=edges,
                                 dictionary=state.dictionary.reference()), partial=partial)


def _counted_goal(value: Any) -> Any:
    if isinstance(value, dict):
        counted_graph(value.get("graph"))
    return value


def _bounded_goal(goal: Goal) -> Goal:
    if goal.graph is not None:
        bounded_graph(goal.graph)
    return goal


# A goal argument: its graph within BoundedGraph's bounds, refused by its counts first.
BoundedGoal = Annotated[Goal, BeforeValidator(_counted_goal), AfterValidator(_bounded_goal)]
GoalText = Annotated[str, Field(min_length=1, max_length=MAX_GOAL_EDGES_CHARS)]
# A stateless tool's goal: a goal object, or its edges as text (partial, nodes from the
# scene) or a predicate's name.
GoalArgument = BoundedGoal | GoalText
GOAL_ARGUMENT_HELP = "edges text 'cup on table; spoon in pot' (partial), a formula " \
                     "'(forall ...)' or {graph, partial}, nodes from the scene"


def resolve_goal(goal: Goal | str, state: WorldState, *, field: str = "goal") -> Goal:
    """A stateless tool's goal, checked against the scene it is checked on.

    Text is goal edges (as set_goal's `edges`), a formula (text starting with `(`) or a
    predicate's name. A goal graph may
    leave out its nodes: every id its edges name is taken from the scene, so the node
    list is never repeated. Edges naming ids the scene lacks are all reported at once,
    sources and targets alike, with the closest ids.
    """
    if isinstance(goal, str):
        name = goal.strip()
        if name in PREDICATES:
            return Goal(predicate=name)  # type: ignore[arg-type]
        if looks_like_formula(name):
            return goal_from_formula(name, state, field=field)
        if (negated := negated_edges_formula(name)) is not None:
            return goal_from_formula(negated, state, field=field)
        return goal_from_edges(goal, state, field=field)
    if goal.graph is not None:
        goal = goal.model_copy(update={"graph": _with_scene_nodes(goal.graph, state, field)})
    check_goal_against(goal, state, field=field)
    return goal


def stateless_source(ctx: ToolContext, *, episode_id: str | None, scene_id: str | None,
                     graph: SceneGraph | None, goal: Goal | str | None = None
                     ) -> tuple[WorldState, Goal | None]:
    """What a stateless tool checks: the state named by its source arguments (a copy,
    the caller's own) and the goal, each read once.

    Exactly one of episode_id, scene_id and graph is set (the input models check it).
    The tool's own `goal` is read against that state (`resolve_goal`); without one, the
    episode's goal or the built-in scene's applies (a built-in goal is built only then).
    """
    if episode_id is not None:
        with ctx.store.use(episode_id) as episode:
            state, other = episode.require_state().copy(), episode.goal
    elif scene_id is not None:
        state = builtin_state(scene_id).copy()
        other = builtin_goal(scene_id) if goal is None else None
    else:
        assert graph is not None
        state, other = state_from_graph(graph), None
    return state, other if goal is None else resolve_goal(goal, state)


def _with_scene_nodes(graph: SceneGraph, state: WorldState, field: str) -> SceneGraph:
    """The goal graph plus, for each id its edges name but its nodes do not, the scene's
    node (label and attributes as the scene has them)."""
    listed = set(graph.node_ids())
    problems: list[str] = []
    wanted: set[str] = set()
    for i, edge in enumerate(graph.edges):
        unknown = [n for n in dict.fromkeys((edge.source, edge.target))
                   if n not in listed and n not in state.objects]
        if unknown:
            near = [m for n in unknown for m in difflib.get_close_matches(
                n, list(state.objects)[:MAX_NEAR_CANDIDATES], n=1, cutoff=0.6)]
            problems.append(f"{field}.graph.edges[{i}] '{edge.sentence()}': no object "
                            f"{' or '.join(unknown)} in the scene"
                            + (f" (did you mean {', '.join(near)}?)" if near else ""))
        wanted.update(n for n in (edge.source, edge.target)
                      if n not in listed and n in state.objects)
    if problems:
        raise ToolArgumentError(
            f"the goal's edges name {len(problems)} object(s) the scene does not have:\n- "
            + "\n- ".join(problems[:10]), field=f"{field}.graph.edges", value=None,
            fix="use ids from the scene: " + ", ".join(sorted(state.objects)[:20]))
    if not wanted:
        return graph
    added = [n for n in state.to_graph().stateless_nodes() if n.id in wanted]
    return graph.model_copy(update={"nodes": [*graph.nodes, *added]})


def _match_perceived(seen: Perceived, state: WorldState | None) -> _Reading:
    """The perceived goal with its objects matched to the episode's ids, and the notes.

    A photo object takes the episode id it shares, else the one episode object of the
    same label and colour. Two or more look-alikes make the match a guess: the goal is
    then only proposed. Each match carries perception's confidence.
    """
    graph = seen.graph
    if state is None:
        return _Reading(Goal(graph=graph), notes=["objects not matched: the episode has no "
                                                   "scene graph yet"])
    rename: dict[str, str] = {}
    shown: dict[str, str] = {}
    ambiguous: list[str] = []

    def alike(node: Node) -> list[str]:
        colour = node.attrs.get("color")
        return sorted(o for o, info in state.objects.items()
                      if info.label == node.label and info.attrs.get("color") == colour)

    for node in graph.nodes:  # first the unmistakable ones: same id, no look-alike
        if node.id in state.objects and len(alike(node)) <= 1:
            rename[node.id] = node.id
            shown[node.id] = f"{node.id} -> {node.id} {seen.confidence.get(node.id, 1.0):.2f}"
    for node in graph.nodes:
        if node.id in rename:
            continue
        same = alike(node)
        free = [o for o in same if o not in rename.values()]
        conf = seen.confidence.get(node.id, 1.0)
        if not free:
            colour = node.attrs.get("color")
            shown[node.id] = (f"{node.id} -> no episode object ({node.label}"
                              f"{', ' + str(colour) if colour else ''})")
            continue
        match = node.id if node.id in free else free[0]
        how = " (by label and colour)"
        if len(same) > 1:
            how = f" (AMBIGUOUS: could be any of {', '.join(same)})"
            conf /= len(same)
            ambiguous.append(node.id)
        rename[node.id] = match
        shown[node.id] = f"{node.id} -> {match} {conf:.2f}{how}"
    # A photo object the scene lacks is left out with its edges, named, and the rest is
    # proposed as a partial goal (never a refusal of the whole photo).
    unmatched = [n.id for n in graph.nodes if n.id not in rename]
    nodes = [n.model_copy(update={"id": rename[n.id]}) for n in graph.nodes if n.id in rename]
    edges = [e.model_copy(update={"source": rename[e.source], "target": rename[e.target]})
             for e in graph.edges if e.source in rename and e.target in rename]
    dropped = [e.sentence() for e in graph.edges
               if e.source not in rename or e.target not in rename]
    matched = graph.model_copy(update={"nodes": nodes, "edges": edges})
    listed = [shown[n.id] for n in graph.nodes if n.id in shown]
    more = f"; ... and {len(listed) - MAX_LISTED_MATCHES} more" \
        if len(listed) > MAX_LISTED_MATCHES else ""
    notes = ["photo objects -> episode ids, confidence: "
             + "; ".join(listed[:MAX_LISTED_MATCHES]) + more]
    for edge in graph.edges:
        sentence = edge.sentence()
        edge_conf = seen.confidence.get(sentence)
        if edge_conf is not None and edge_conf < NOTED_CONFIDENCE:
            notes.append(f"uncertain reading: {sentence} (confidence {edge_conf:.2f})")
        info = state.objects.get(rename.get(edge.source, edge.source))
        if edge.relation == "in" and info is not None and info.props.surface:
            notes.append(f"check: {sentence} was read as `in` because the {edge.source} lies "
                         f"inside the {edge.target}'s outline; if it rests across the rim, "
                         "the photo means `on`, and set_goal with edges is the way to say so")
    if ambiguous:
        notes.append("look-alike objects make the match a guess, so this goal is only "
                     "proposed: confirm or correct it with edges")
    if unmatched:
        notes.append(f"not in the scene, left out: {', '.join(unmatched)} (with "
                     f"{'; '.join(dropped) or 'no edges'}); the rest is only proposed, as a "
                     "partial goal: confirm it with edges, and tell the user what was left out")
    return _Reading(Goal(graph=matched, partial=bool(unmatched)),
                    accepted=not ambiguous and not unmatched, notes=notes)


def _from_words(instruction: str, state: WorldState | None) -> _Reading:
    """The rule-based translation of words alone: always a proposal, never stored."""
    if state is None:
        return _Reading(None, accepted=False,
                        notes=["not translated: the episode has no scene graph yet"])
    reading = read_instruction(instruction, state.to_graph())
    notes = [f"understood: '{c}'" for c in reading.understood]
    notes += [f"not understood: '{c}' ({why})" for c, why in reading.not_understood]
    notes += [f"cannot place: '{e}' ({why}); the proposal leaves it out, so accepting it "
              "narrows the request: tell the user" for e, why in reading.unplaced]
    return _Reading(reading.goal(state.to_graph(), instruction), accepted=False, notes=notes)


def set_goal(ctx: ToolContext, params: SetGoalInput) -> GoalOutput:
    """Replace the goal (or record an instruction); an invalid goal changes nothing.

    Words alone are translated into a proposal (accepted: false) that is not stored: the
    client confirms it by sending its edges back, so a misread word never becomes the
    goal unseen. A goal the scene cannot hold is refused but kept as the user's request
    (`tools.request`): the call ends normally, so a durable store saves that, and then
    the refusal is raised.
    """
    out = _set_goal(ctx, params)
    if isinstance(out, ToolArgumentError):
        raise out
    return out


def _set_goal(ctx: ToolContext, params: SetGoalInput) -> GoalOutput | ToolArgumentError:
    graph = params.graph
    image = decode_base64_image(params.image) if params.image is not None else None
    with ctx.store.use(params.episode_id) as episode:
        reading = _Reading(None)
        if image is not None:
            dictionary = (episode.state.dictionary if episode.state
                          else dictionary_for(episode.dictionary_name))
            seen = perceive_photo(image, dictionary)
            if not seen.confident:
                raise ToolArgumentError(
                    "built-in perception is unsure of the goal image: "
                    + "; ".join(d.message for d in seen.doubts[:5]),
                    field="image", value=None,
                    fix="give the goal as edges or a graph (generate_scene_graph returns "
                        "the perceived proposal to check and correct)")
            reading = _match_perceived(seen, episode.state)
            assert reading.goal is not None
            graph = reading.goal.graph
        goal: Goal | None = None
        partial = bool(params.partial) or (reading.goal is not None and reading.goal.partial)
        formula, formula_field = params.formula, "formula"
        if params.edges is not None and looks_like_formula(params.edges):
            formula, formula_field = params.edges, "edges"
        elif params.edges is not None and \
                (negated := negated_edges_formula(params.edges)) is not None:
            formula, formula_field = negated, "edges"
            reading.notes.append("edges with 'not' read as the formula they mean (a goal "
                                 "graph cannot say not); for every cup and plate at once: "
                                 f"formula='{FORMULA_EXAMPLE}'")
        elif params.edges is not None:
            edges_goal = goal_from_edges(params.edges, episode.state,
                                         partial=params.partial is not False)
            graph, partial = edges_goal.graph, edges_goal.partial
        if formula is not None:
            formula = goal_from_formula(formula, episode.state, field=formula_field).formula
        readings: list[str] = []
        if graph is not None or params.predicate is not None or formula is not None:
            goal = Goal(graph=graph, partial=partial, predicate=params.predicate,
                        formula=formula, instruction=params.instruction)
            refused = _beyond_the_scene(goal, episode, "goal" if graph is None else "graph")
            if refused is not None:
                return refused
            if formula is not None and episode.state is None:
                reading.notes.append("no scene graph yet, so the formula's ids and kinds "
                                     "are not checked: an id the submitted scene lacks "
                                     "never holds")
            if params.graph is not None:  # a graph the client wrote (not edges or a photo)
                readings = label_readings(params.graph, episode.state.dictionary
                                          if episode.state is not None else
                                          dictionary_for(params.graph.dictionary
                                                         or episode.dictionary_name))
        elif params.instruction is not None:
            reading = _from_words(params.instruction, episode.state)
            keep_asked_words(episode, params.instruction)
        if not reading.accepted:
            if params.instruction is not None:  # the words are kept; the proposal is not
                episode.instruction = params.instruction
            proposal = goal or reading.goal
            current = episode.goal
            diff = (check_goal(episode.state, current)
                    if current and episode.state is not None else None)
            return GoalOutput(episode_id=episode.id, goal=current,
                              instruction=episode.instruction, checkable=current is not None,
                              goal_satisfied=diff.satisfied if diff else None, goal_diff=diff,
                              accepted=False, proposal=proposal, notes=reading.notes,
                              label_readings=readings)
        if goal is not None:
            _note_narrowing(episode, goal, reading.notes)
            episode.goal = goal
        if params.instruction is not None:
            episode.instruction = params.instruction
        goal = episode.goal
        diff = check_goal(episode.state, goal) if goal and episode.state is not None else None
        return GoalOutput(episode_id=episode.id, goal=goal,
                          instruction=episode.instruction, checkable=goal is not None,
                          goal_satisfied=diff.satisfied if diff else None, goal_diff=diff,
                          notes=reading.notes, label_readings=readings)


def _beyond_the_scene(goal: Goal, episode: LiveEpisode, field: str
                      ) -> ToolArgumentError | None:
    """check_goal_against; a goal refused because the scene cannot hold it (a rule of
    WORLD_LIMITS, e.g. a capacity) is kept as the request and its refusal returned, to
    be raised once the call's changes are saved. Any other refusal is raised here."""
    state = episode.state
    try:
        check_goal_against(goal, state, field=field)
    except ToolArgumentError as exc:
        if goal.graph is None or state is None:
            raise
        limits = [p.message for p in check_well_formed(goal.graph, state.dictionary,
                                                       partial=goal.partial)
                  if p.rule in WORLD_LIMITS]
        if not limits:
            raise
        keep_asked_goal(episode, goal, "refused by set_goal: " + "; ".join(limits[:3]))
        return ToolArgumentError(
            f"{exc.message}\nthe scene cannot hold this goal, so it is kept as the user's "
            "request: a narrower goal set and reached ends PARTIAL, naming what is left out",
            field=exc.field, value=exc.value, fix=exc.fix)
    return None


def _note_narrowing(episode: LiveEpisode, goal: Goal, notes: list[str]) -> None:
    """A goal replacing one it asks a strict subset of keeps the old one as the request;
    a goal leaving part of the request out says so (end_episode will say PARTIAL)."""
    if episode.goal is not None and is_narrower(goal, episode.goal):
        keep_asked_goal(episode, episode.goal, "narrowed by a later set_goal")
    asked, missing, unsaid = left_out(episode, goal)
    if missing:
        notes.append(f"narrower than {asked}: it leaves out {'; '.join(missing[:10])}; "
                     "end_episode will say PARTIAL, not SUCCESS: tell the user")
    if unsaid:
        notes.append(f"the request also asks {' and '.join(unsaid[:3])}, which a goal graph "
                     "cannot say: end_episode checks it on the final scene (PARTIAL if it "
                     "fails); set_goal with a formula makes it part of the goal")
