"""The user's request: what an episode's verdict is read against besides its goal.

The goal an episode ends on may be narrower than what was asked: part of the request
was refused (a goal beyond a capacity) or left out (words the translator could not
place, a goal replaced by one with fewer edges). The episode keeps the first request
it was given, once, in `extras`, and `end_episode` reports what of it does not hold, so
a narrowed goal never ends as plain SUCCESS. The request is, first come:

- `load_scene`'s instruction, or the first instruction `set_goal` gets as words alone
  (`ASKED`, read by the translator on the scene as loaded);
- the goal a `set_goal` call was refused for because the scene cannot hold it (a rule
  in `WORLD_LIMITS`: the model wrote it right, the world is too small), or a goal that a
  later `set_goal` replaced by a strict subset of its edges and states (`ASKED_GOAL`).

A goal refused for how it was written (an unknown id, a surface used as a container) is
a mistake to correct, not a request: it is not kept.
"""

from __future__ import annotations

from typing import Any

from verigraph.graph.goal import Goal, check_goal
from verigraph.graph.state import WorldState
from verigraph.graph.translator import read_instruction
from verigraph.tools.store import LiveEpisode

# The episode's first instruction (load_scene's, or set_goal's words alone), kept in
# `extras` since later set_goal instructions replace `instruction`.
ASKED = "asked"
# Where the kept words came from, when not load_scene: "set_goal".
ASKED_IN = "asked_in"
# The first goal asked for and then refused or narrowed: {"goal": ..., "why": ...}.
ASKED_GOAL = "asked_goal"
# Well-formedness rules a goal breaks because the scene cannot hold it, not because it
# was written wrong.
WORLD_LIMITS = frozenset({"over_capacity"})


def has_request(episode: LiveEpisode) -> bool:
    """Whether the episode already keeps its request (the first one stays)."""
    return ASKED in episode.extras or ASKED_GOAL in episode.extras


def keep_asked_words(episode: LiveEpisode, instruction: str) -> None:
    """The words set_goal got alone (a request to translate), when they are the
    episode's first request."""
    if not has_request(episode):
        episode.extras[ASKED] = instruction
        episode.extras[ASKED_IN] = "set_goal"
        episode.mark_changed()


def keep_asked_goal(episode: LiveEpisode, goal: Goal, why: str) -> None:
    """A goal asked for and then refused or narrowed (`why` says which), when it is the
    episode's first request."""
    if not has_request(episode):
        episode.extras[ASKED_GOAL] = {"goal": goal.model_dump(mode="json"), "why": why}
        episode.mark_changed()


def goal_items(goal: Goal) -> set[str] | None:
    """A goal graph's required items (edges and node states) as sentences; None when the
    goal also has a predicate or a formula (no item-wise comparison)."""
    if goal.graph is None or goal.predicate is not None or goal.formula is not None:
        return None
    return {*goal.graph.sentences(), *goal.graph.state_sentences()}


def is_narrower(new: Goal, old: Goal) -> bool:
    """`new` asks for a strict subset of what `old` asks (edges and states; a full
    goal's extra nodes aside)."""
    mine, theirs = goal_items(new), goal_items(old)
    return mine is not None and theirs is not None and mine < theirs


def left_out(episode: LiveEpisode, goal: Goal) -> tuple[str, list[str], list[str]]:
    """The request in a few words, what of it `goal` does not ask for (its edges and
    states compared with the request's; none when either is not a list of edges: a
    formula, a predicate), and the formula clauses of a request in words ("no cup on any
    plate") that a goal without a formula leaves unsaid: it may still bring them about,
    so they are not "left out"; end_episode checks them on the final scene
    (`asked_against`). ("", [], []) when the goal asks for all of it."""
    mine = goal_items(goal)
    asked_goal: Any = episode.extras.get(ASKED_GOAL)
    if isinstance(asked_goal, dict):
        if mine is None:
            return "", [], []
        theirs = goal_items(Goal.model_validate(asked_goal["goal"])) or set()
        return f"the goal first asked for ({asked_goal['why']})", sorted(theirs - mine), []
    asked = episode.extras.get(ASKED)
    if goal.formula is not None or not isinstance(asked, str) or \
            episode.initial_graph is None:
        return "", [], []
    reading = read_instruction(asked, episode.initial_graph)
    if mine is None:
        return "", [], reading.formulas
    wanted = [e.sentence() for e in reading.edges] + [s for s, _ in reading.unplaced] + \
        reading.state_sentences()
    return _words_source(episode), [s for s in wanted if s not in mine], reading.formulas


def _words_source(episode: LiveEpisode) -> str:
    return ("the request set_goal was first given in words"
            if episode.extras.get(ASKED_IN) == "set_goal" else
            "the request the episode was loaded with")


def asked_against(episode: LiveEpisode) -> tuple[str, list[str]]:
    """What the episode was asked, said in a few words, and what of it does not hold on
    the episode's graph now (each with why, when it could not be placed). Nothing
    missing, or no request kept: ("", [])."""
    state = episode.state
    if state is None:
        return "", []
    asked_goal: Any = episode.extras.get(ASKED_GOAL)
    if isinstance(asked_goal, dict):
        missing = _not_done(state, Goal.model_validate(asked_goal["goal"]))
        return f"the goal first asked for ({asked_goal['why']})", missing
    asked = episode.extras.get(ASKED)
    if not isinstance(asked, str) or episode.initial_graph is None:
        return "", []
    reading = read_instruction(asked, episode.initial_graph)
    missing = _not_done(state, reading.goal(episode.initial_graph, asked))
    support = state.support
    for sentence, why in reading.unplaced:
        obj, relation, target = sentence.split(" ", 2)
        if support.get(obj) != (relation, target):
            missing.append(f"{sentence} (asked, but {why})")
    return _words_source(episode), missing


def _not_done(state: WorldState, goal: Goal | None) -> list[str]:
    """What of `goal` does not hold on `state`: its edges and states, and a formula's
    counterexamples."""
    diff = check_goal(state, goal) if goal is not None else None
    if diff is None or diff.satisfied:
        return []
    return [*diff.missing_edges, *diff.missing_states, *diff.formula_detail]
