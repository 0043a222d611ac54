"""One iteration of Algorithm 1 (verigraph.planning.iteration) against the real tools:
the verdicts, tau counting malformed answers beside the server's count of refusals, the
premature end token and the stops."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pytest

from verigraph.actions import AnyAction, DoneAction, MoveAction
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.planning import InProcessTools, PlannerReply
from verigraph.planning.iteration import Iteration, prompt_goal

pytestmark = pytest.mark.fast


class Episode:
    """A cup_on_book episode on the in-process tools, with its goal read back."""

    def __init__(self, t: int = 5) -> None:
        self.tools = InProcessTools()
        state = self.tools.call("load_scene", {"scene_id": "cup_on_book", "k": 3, "t": t})
        self.episode_id = str(state["episode_id"])
        self.satisfied: bool | None = state.get("goal_satisfied")
        self.diff: GraphDiff | None = None

    def execute(self, actions: list[AnyAction]) -> Mapping[str, Any]:
        out = self.tools.call("execute_actions", {
            "episode_id": self.episode_id,
            "actions": [a.model_dump(mode="json") for a in actions]})
        self.satisfied = out.get("goal_satisfied")
        diff = out.get("goal_diff")
        self.diff = GraphDiff.model_validate(diff) if diff else None
        return out

    def goal(self) -> tuple[bool | None, GraphDiff | None]:
        return self.satisfied, self.diff


def move(obj: str, target: str) -> MoveAction:
    return MoveAction(object=obj, relation="on", target=target)


def test_tau_counts_malformed_answers_and_refusals_and_a_clean_iteration_resets_it() -> None:
    ep = Episode()
    it = Iteration(3, 5)
    malformed = it.step(PlannerReply(actions=[], error="not JSON"), ep.execute, ep.goal)
    assert (malformed.verdict, malformed.tau, malformed.out) == ("malformed", 1, {})
    assert malformed.feedback is not None and "not JSON" in malformed.feedback.text
    refused = it.step(PlannerReply(actions=[move("book", "shelf")]), ep.execute, ep.goal)
    assert (refused.verdict, refused.tau) == ("violation", 2)
    assert refused.out["tau"] == 1  # the server saw only the refusal
    clean = it.step(PlannerReply(actions=[move("cup", "desk")]), ep.execute, ep.goal)
    assert (clean.verdict, clean.tau, clean.stop, clean.feedback) == ("clean", 0, None, None)


def test_k_drops_the_surplus_and_the_end_token_is_refused_while_the_goal_fails() -> None:
    ep = Episode()
    it = Iteration(1, 5)
    first = it.step(PlannerReply(actions=[move("cup", "desk"), move("book", "shelf"),
                                          DoneAction()]), ep.execute, ep.goal)
    assert [a.text() for a in first.moves] == ["move(cup, on, desk)"]
    assert [a.text() for a in first.dropped] == ["move(book, on, shelf)", "done"]
    done = it.step(PlannerReply(actions=[DoneAction()]), lambda _: {}, lambda: (False, None))
    assert (done.verdict, done.tau, done.ended, done.stop) == ("premature_done", 1, False, None)
    assert done.feedback is not None and "goal not reached" in done.feedback.text
    trusted = Iteration(1, 5, verify_done=False).step(
        PlannerReply(actions=[DoneAction()]), lambda _: {}, lambda: (False, None))
    assert (trusted.verdict, trusted.ended, trusted.stop) == ("end_token", True, "end_token")


def test_tau_reaching_t_stops_the_episode() -> None:
    ep = Episode(t=2)
    it = Iteration(3, 2)
    outcomes = [it.step(PlannerReply(actions=[move("cup", "cup")]), ep.execute, ep.goal)
                for _ in range(2)]
    assert [(o.tau, o.stop) for o in outcomes] == [(1, None), (2, "threshold")]
    assert outcomes[-1].server_threshold


def test_prompt_goal_hides_the_goal_graph_and_formula_unless_the_task_shows_them() -> None:
    stack = Goal(predicate="single_stack", formula="(and)")
    assert prompt_goal(stack, True) is stack
    hidden = prompt_goal(stack, False)
    assert hidden is not None and (hidden.predicate, hidden.formula) == ("single_stack", None)
    assert prompt_goal(Goal(formula="(and)"), False) is None
    plain = Goal(predicate="single_stack")
    assert prompt_goal(plain, False) is plain
