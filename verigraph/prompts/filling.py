"""Fill the prompt templates from an episode or a scene: the words a planner reads.

Shared by the MCP prompts, get_scene_image, the agent loop and VLM perception, so every
planner sees the same description of actions A, constraints C, the graphs and the end
token. It sits just above `actions` because the planner prompt lists the constraints C.
"""

from __future__ import annotations

from collections.abc import Sequence

from verigraph import prompts
from verigraph.actions.feedback import CONSTRAINT_DESCRIPTIONS, Violation
from verigraph.actions.model import AnyAction
from verigraph.actions.schemas import HOUSEHOLD_CONSTRAINTS, SCHEMAS
from verigraph.graph.dictionary import (
    HOUSEHOLD_RELATIONS,
    PLACEMENT_RELATIONS,
    SUPPORT_RELATIONS,
    Dictionary,
    state_text,
)
from verigraph.graph.formula_eval import meanings_in
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState

TANGRAM_ONLY = {"unknown_side", "side_occupied", "overlap"}
TABLETOP_ONLY = {"object_not_clear", "target_full", "target_not_surface", "target_not_container",
                 "would_create_cycle"}
NOT_FOR_PLANNERS = {"execution_failed", "malformed_action"}


def _is_tangram(relations: Sequence[str]) -> bool:
    return "touches" in relations and "on" not in relations


def speaks_household(state: WorldState) -> bool:
    """Whether the scene has what only household worlds have: openable objects, rooms,
    object states given, or an object under or next to another. Prompts speak of the
    household actions and rules only then, so a tabletop in the household dictionary
    (whose stove could be switched) reads as a kitchen one; the actions are accepted
    everywhere all the same."""
    return bool(state.openable or state.rooms or state.states) or any(
        o.props.room for o in state.objects.values()) or any(
        r not in SUPPORT_RELATIONS for r, _ in state.support.values())


def prompt_relations(state: WorldState) -> tuple[str, ...]:
    """The relations a prompt names: the dictionary's R, without the household ones
    (`under`, `nextto`, `inroom`) unless the scene is a household (`speaks_household`)."""
    relations = state.dictionary.relations
    if speaks_household(state):
        return relations
    return tuple(r for r in relations if r in SUPPORT_RELATIONS or r not in HOUSEHOLD_RELATIONS)


def objects_text(state: WorldState) -> str:
    """One line per object with its role; in a household, its states too (`openable,
    now closed (default)`)."""
    household = speaks_household(state)
    lines = []
    for obj in state.objects.values():
        p = obj.props
        kinds = ["room" if p.room else "movable" if p.movable else "fixed"]
        if p.surface:
            kinds.append("surface")
        if p.container:
            kinds.append("container")
        if p.sides:
            kinds.append(f"{p.sides} sides")
        if (p.surface or p.container) and p.capacity is not None:
            kinds.append(f"holds at most {p.capacity}")
        states = state_text(p, state.states.get(obj.id, {})) if household else ""
        if states:
            roles = [r for r, on in (("openable", p.openable), ("toggleable", p.toggleable))
                     if on]
            kinds.append(f"{' and '.join(roles)}, now {states}")
        lines.append(f"- {obj.id} ({obj.label}): {', '.join(kinds)}")
    return "\n".join(lines)


def graph_text(state: WorldState) -> str:
    lines = [f"- {e.sentence()}" for e in state.to_graph().edges] or ["- (no edges)"]
    if not _is_tangram(state.dictionary.relations):
        free = [o.id for o in state.objects.values()
                if o.props.movable and o.id not in state.support]
        if free:
            lines.append(f"- not resting on anything: {', '.join(free)}")
    rooms = rooms_text(state)
    if rooms:
        lines.append(f"- {rooms}")
    return "\n".join(lines)


def rooms_text(state: WorldState) -> str:
    """`rooms: kitchen: cabinet, counter, fridge; dining_room: table`: the furniture of
    each room (and what stands on, in, under or next to it goes with it); empty without
    rooms."""
    if not state.rooms:
        return ""
    by_room: dict[str, list[str]] = {}
    for furniture, room in sorted(state.rooms.items()):
        by_room.setdefault(room, []).append(furniture)
    return "rooms: " + "; ".join(f"{room}: {', '.join(items)}"
                                 for room, items in by_room.items())


def goal_section(goal: Goal | None, instruction: str | None = None) -> str:
    lines = []
    if instruction or (goal and goal.instruction):
        lines.append(f"Instruction: {instruction or (goal.instruction if goal else '')}")
    if goal is not None and goal.graph is not None:
        kind = "these edges must hold (others may too)" if goal.partial else \
            "the final graph must have exactly these edges"
        lines.append(f"Goal graph ({kind}):")
        lines.extend(f"- {s}" for s in goal.graph.sentences())
        lines.extend(f"- {s}" for s in goal.graph.state_sentences())
    if goal is not None and goal.predicate == "single_stack":
        lines.append("All movable objects must end up in one single tower on a fixed object.")
    if goal is not None and goal.formula is not None:
        lines.append("Goal formula (BDDL; kinds are labels, ?x variables, other names ids; "
                     "it must hold at the end):")
        text = goal.formula_text() or ""
        lines.append(text)
        lines.extend(meanings_in(text))
    return "\n".join(lines) or "No goal was given; ask the user what the robot should achieve."


def actions_text(relations: Sequence[str], household: bool = False) -> str:
    """The actions a planner may use; with `household`, every row of the action table
    (move with under and nextto, open, close, toggle_on, toggle_off)."""
    if _is_tangram(relations):
        return ("- align(piece, side, target_piece, target_side): slide a piece so that one "
                "of its sides touches a side of another piece (sides are numbered clockwise "
                "from 0)\n- done: the end token, when the goal holds")
    if not household:
        moves = [r for r in relations if r in SUPPORT_RELATIONS]
        return (f"- move(object, relation, target) with relation in {{{', '.join(moves)}}}: "
                "pick up the object (with nothing on or in it) and put it on or in the "
                "target\n- move(object, target): short for move(object, on, target)\n"
                "- done: the end token, when the goal holds")
    moves = [r for r in relations if r in PLACEMENT_RELATIONS]
    lines = [f"- move(object, relation, target) with relation in {{{', '.join(moves)}}}: "
             "pick up the object (with nothing on, in, under or next to it, and not inside a "
             "closed container) and put it on or in the target, under it (furniture) or "
             "next to it", "- move(object, target): short for move(object, on, target)"]
    for row in SCHEMAS.values():
        if row.household:
            lines.append(f"- {row.form()}: {row.effect.text()} (object: "
                         f"{row.parameters[0].needs})")
    lines.append("- done: the end token, when the goal holds")
    return "\n".join(lines)


def constraints_text(relations: Sequence[str], household: bool = False) -> str:
    """The constraints C a planner must respect; the action table's household ones
    only with `household`."""
    tangram = _is_tangram(relations)
    lines = []
    for cid, text in CONSTRAINT_DESCRIPTIONS.items():
        if cid in NOT_FOR_PLANNERS or cid in (TABLETOP_ONLY if tangram else TANGRAM_ONLY):
            continue
        if cid in HOUSEHOLD_CONSTRAINTS and not household:
            continue
        lines.append(f"- {cid}: {text}")
    return "\n".join(lines)


def history_text(executed: Sequence[AnyAction]) -> str:
    if not executed:
        return "Nothing has been executed yet."
    return "Executed so far, in order:\n" + "\n".join(f"- {a.text()}" for a in executed)


def feedback_text(violation: Violation | None, calls: int) -> str:
    if violation is not None:
        return violation.text()
    return "None: this is the first answer." if calls == 0 else \
        "None: every action of your previous answer was executed."


def tool_hint(episode_id: str | None) -> str:
    if not episode_id:
        return ""
    return (f"\n(With the VeriGraph tools: check a single action with validate_action("
            f"episode_id=\"{episode_id}\", action=...), run your answer with execute_actions("
            f"episode_id=\"{episode_id}\", actions=[...]), read the violation and the new graph "
            "it returns, repeat, and call end_episode when you answer done.)")


def fill_planner_prompt(name: str, state: WorldState, goal: Goal | None, *, k: int = 3,
                   executed: Sequence[AnyAction] = (), violation: Violation | None = None,
                   calls: int = 0, instruction: str | None = None,
                   episode_id: str | None = None) -> str:
    """The iterative or direct planner prompt for a state and goal."""
    relations = prompt_relations(state)
    household = speaks_household(state)
    return prompts.render(
        name, relations=", ".join(relations), objects=objects_text(state),
        current_graph=graph_text(state), goal=goal_section(goal, instruction),
        actions=actions_text(relations, household),
        constraints=constraints_text(relations, household),
        history=history_text(executed), feedback=feedback_text(violation, calls), k=k,
        tool_hint=tool_hint(episode_id))


def dictionary_text(dictionary: Dictionary) -> str:
    """One line per label with its role; the client's own labels are marked, so that a
    vision model labels with them rather than with the nearest built-in word."""
    lines = []
    for name in dictionary.names:
        p = dictionary.objects[name]
        kinds = ["movable" if p.movable else "fixed"]
        if p.surface:
            kinds.append("surface")
        if p.container:
            kinds.append("container")
        if (p.surface or p.container) and p.capacity is not None:
            kinds.append(f"capacity {p.capacity}")
        mine = " (your label)" if name in dictionary.user_labels else ""
        synonyms = f"; also called {', '.join(p.synonyms)}" if p.synonyms else ""
        lines.append(f"- {name}{mine}: {', '.join(kinds)}{synonyms}")
    return "\n".join(lines)


def scene_graph_prompt(dictionary: Dictionary, task: str | None = None,
                       episode_id: str | None = None) -> str:
    """The scene-graph generation prompt for a dictionary D and relations R."""
    hint = ""
    if episode_id:
        hint = (f"\n(With the VeriGraph tools: send the JSON with submit_scene_graph("
                f"episode_id=\"{episode_id}\", graph=...); it lists every problem at once.)")
    return prompts.render(
        "scene_graph_generation", relations=", ".join(dictionary.relations),
        dictionary_name=dictionary.name, dictionary=dictionary_text(dictionary),
        task=task or "No specific task: describe every object and what supports it.",
        tool_hint=hint)
