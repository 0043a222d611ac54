"""Oracle and noisy planners: optimal chunks, the end token, each injected mistake kind."""

from __future__ import annotations

import random

import pytest

from verigraph.actions import DoneAction, MoveAction, validate_action
from verigraph.actions.model import AlignAction
from verigraph.agent import PlannerRequest, make_planner
from verigraph.agent.factory import PlannerOptions
from verigraph.agent.noisy import MISTAKE_KINDS, MistakeKind, NoisyPlanner, make_mistake
from verigraph.agent.oracle import OraclePlanner
from verigraph.graph import Edge, Goal, Node, SceneGraph, WorldState
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal, three_blocks


def request(graph: SceneGraph, goal: Goal | None, k: int | None = 3) -> PlannerRequest:
    return PlannerRequest(mode="iterative" if k else "direct", iteration=1, graph=graph,
                          goal=goal, k=k, prompt="")


def tall_stack() -> SceneGraph:
    """Four blocks: b1 on b0 on table, b3 on b2 on table (two towers)."""
    nodes = [Node(id="table", label="table")] + [Node(id=f"b{i}", label="block")
                                                  for i in range(4)]
    edges = [Edge(source="b0", relation="on", target="table"),
             Edge(source="b1", relation="on", target="b0"),
             Edge(source="b2", relation="on", target="table"),
             Edge(source="b3", relation="on", target="b2")]
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def test_oracle_gives_the_first_k_actions_then_the_end_token() -> None:
    oracle = OraclePlanner()
    first = oracle.propose(request(cup_on_book(), cup_on_book_goal(), k=1))
    assert [a.text() for a in first.actions] == ["move(cup, on, desk)"]
    whole = oracle.propose(request(cup_on_book(), cup_on_book_goal(), k=5))
    assert [a.text() for a in whole.actions] == [
        "move(cup, on, desk)", "move(book, on, shelf)", "done"]
    direct = oracle.propose(request(cup_on_book(), cup_on_book_goal(), k=None))
    assert isinstance(direct.actions[-1], DoneAction)


def test_oracle_answers_done_when_the_goal_already_holds_or_is_missing() -> None:
    stacked = SceneGraph.model_validate({
        "nodes": [{"id": "table", "label": "table"}, {"id": "a", "label": "block"}],
        "edges": [{"source": "a", "relation": "on", "target": "table"}],
        "dictionary": "blocks"})
    reply = OraclePlanner().propose(request(stacked, Goal(predicate="single_stack")))
    assert reply.actions == [DoneAction()]
    reply = OraclePlanner().propose(request(three_blocks(), None))
    assert reply.actions == [DoneAction()] and reply.note and "no checkable goal" in reply.note


def test_noisy_with_rate_zero_is_the_oracle_and_rate_one_always_errs() -> None:
    req = request(tall_stack(), Goal(predicate="single_stack"))
    oracle = OraclePlanner().propose(req).actions
    clean = NoisyPlanner(0.0, seed=1)
    assert all(clean.propose(req).actions == oracle for _ in range(20))
    noisy = NoisyPlanner(1.0, seed=1)
    replies = [noisy.propose(req) for _ in range(50)]
    assert all(r.note and r.note.startswith("injected mistake") for r in replies)
    assert len(noisy.injected) == 50
    assert set(noisy.injected) == set(MISTAKE_KINDS)


def test_noisy_is_reproducible_for_a_seed() -> None:
    req = request(tall_stack(), Goal(predicate="single_stack"))
    a = [NoisyPlanner(0.5, seed=7).propose(req).actions for _ in range(3)]
    b = [NoisyPlanner(0.5, seed=7).propose(req).actions for _ in range(3)]
    assert a == b


def test_injected_mistakes_stay_within_k() -> None:
    req = request(tall_stack(), Goal(predicate="single_stack"), k=2)
    noisy = NoisyPlanner(1.0, seed=3)
    for _ in range(40):
        moves = [a for a in noisy.propose(req).actions if not isinstance(a, DoneAction)]
        assert len(moves) <= 2


EXPECTED = {"non_clear": "object_not_clear", "full_target": "target_full",
            "hallucinated": "unknown_object"}


@pytest.mark.parametrize("kind", ["non_clear", "full_target", "hallucinated", "wrong_relation"])
def test_each_mistake_kind_is_refused_by_the_verifier_for_its_reason(kind: str) -> None:
    state = WorldState.from_graph(tall_stack())
    upcoming = MoveAction(object="b1", relation="on", target="b3")
    mistake = make_mistake(kind, state, upcoming, random.Random(0))  # type: ignore[arg-type]
    assert mistake is not None
    violation = validate_action(state, mistake)
    assert violation is not None
    if kind in EXPECTED:
        assert violation.constraint == EXPECTED[kind]
    else:
        assert isinstance(mistake, MoveAction) and mistake.relation == "in"
        # blocks allow only `on`, so R itself refuses it before the container check
        assert violation.constraint in ("unknown_relation", "target_not_container")


def test_impossible_kinds_return_none() -> None:
    flat = SceneGraph.model_validate({
        "nodes": [{"id": "table", "label": "table"}, {"id": "a", "label": "block"}],
        "edges": [{"source": "a", "relation": "on", "target": "table"}],
        "dictionary": "blocks"})
    state = WorldState.from_graph(flat)
    assert make_mistake("non_clear", state, None, random.Random(0)) is None


def test_tangram_mistakes_are_align_actions_the_verifier_refuses() -> None:
    pieces = [("square", "square"), ("small_triangle_1", "small_triangle_1"),
              ("medium_triangle", "medium_triangle")]
    graph = SceneGraph.model_validate({
        "nodes": [{"id": i, "label": lab} for i, lab in pieces],
        "edges": [{"source": "small_triangle_1", "relation": "touches", "target": "square",
                   "source_side": 0, "target_side": 1}],
        "dictionary": "tangram"})
    state = WorldState.from_graph(graph)
    kinds: tuple[MistakeKind, ...] = ("full_target", "hallucinated", "wrong_relation")
    for kind in kinds:
        mistake = make_mistake(kind, state, None, random.Random(1))
        assert isinstance(mistake, AlignAction), kind
        assert validate_action(state, mistake) is not None


def test_factory_builds_the_offline_planners_and_rejects_unknown_names() -> None:
    assert make_planner("oracle").name == "oracle"
    assert make_planner("noisy", PlannerOptions(noise=0.2)).name == "noisy(20%)"
    with pytest.raises(ValueError, match="unknown planner"):
        make_planner("gpt-17")
    with pytest.raises(ValueError, match="mistake kinds"):
        NoisyPlanner(kinds=())
