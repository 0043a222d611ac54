"""Oracle and noisy planners: optimal chunks, the end token, each injected mistake kind."""

from __future__ import annotations

import random

import pytest

from verigraph.actions import DoneAction, MoveAction, validate_action
from verigraph.actions.model import AlignAction
from verigraph.graph import Edge, Goal, Node, SceneGraph, WorldState
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal, three_blocks
from verigraph.planning import PlannerRequest, make_planner
from verigraph.planning.factory import PlannerOptions
from verigraph.planning.models import Feedback
from verigraph.planning.noisy import MISTAKE_KINDS, NoiseProfile, NoisyPlanner, make_mistake
from verigraph.planning.oracle import OraclePlanner

pytestmark = pytest.mark.fast


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
    replies = [noisy.propose(req) for _ in range(60)]
    assert all(r.note and r.note.startswith("injected mistake") for r in replies)
    assert set(noisy.injected) >= set(MISTAKE_KINDS)


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


def test_mistakes_are_not_vetted_some_are_valid_but_useless_some_refused() -> None:
    state = WorldState.from_graph(tall_stack())
    planned = MoveAction(object="b1", relation="on", target="b3")
    rng = random.Random(0)
    verdicts = [validate_action(state, make_mistake("random_move", state, planned, rng))
                for _ in range(60)]
    assert any(v is None for v in verdicts) and any(v is not None for v in verdicts)
    ghost = make_mistake("hallucinated", state, planned, rng)
    violation = validate_action(state, ghost)
    assert violation is not None and violation.constraint == "unknown_object"
    loaded = make_mistake("non_clear", state, planned, rng)
    violation = validate_action(state, loaded)
    assert violation is not None and violation.constraint == "object_not_clear"


def test_per_call_errors_malformed_premature_done_and_repeats() -> None:
    req = request(tall_stack(), Goal(predicate="single_stack"))
    broken = NoisyPlanner(seed=0, profile=NoiseProfile(action_error=0.0, malformed=1.0))
    reply = broken.propose(req)
    assert reply.error and reply.raw and not reply.actions
    quitter = NoisyPlanner(seed=0, profile=NoiseProfile(action_error=0.0, premature_done=1.0))
    assert quitter.propose(req).actions == [DoneAction()]
    refused = MoveAction(object="b0", relation="on", target="b3")
    violation = validate_action(WorldState.from_graph(tall_stack()), refused)
    assert violation is not None
    stubborn = NoisyPlanner(seed=0, profile=NoiseProfile(action_error=0.0, repeat=1.0))
    again = stubborn.propose(request(tall_stack(), Goal(predicate="single_stack")).model_copy(
        update={"feedback": Feedback(kind="violation", text=violation.text(),
                                     violation=violation)}))
    assert again.actions[0] == refused


def test_noisy_never_reads_the_privileged_goal() -> None:
    req = PlannerRequest(mode="iterative", iteration=1, graph=cup_on_book(), goal=None,
                         privileged_goal=cup_on_book_goal(), k=3, prompt="",
                         instruction="Tidy up, please.")
    reply = NoisyPlanner(0.0, seed=0).propose(req)
    assert reply.actions == [DoneAction()]
    assert reply.note is not None and "not understood" in reply.note
    assert OraclePlanner().propose(req).actions[0].text() == "move(cup, on, desk)"


def test_tangram_mistakes_are_align_actions() -> None:
    pieces = [("square", "square"), ("small_triangle_1", "small_triangle_1"),
              ("medium_triangle", "medium_triangle")]
    graph = SceneGraph.model_validate({
        "nodes": [{"id": i, "label": lab} for i, lab in pieces],
        "edges": [{"source": "small_triangle_1", "relation": "touches", "target": "square",
                   "source_side": 0, "target_side": 1}],
        "dictionary": "tangram"})
    state = WorldState.from_graph(graph)
    planned = AlignAction(object="medium_triangle", side=0, target="square", target_side=0)
    for kind in ("random_move", "hallucinated", "wrong_relation"):
        mistake = make_mistake(kind, state, planned, random.Random(1))  # type: ignore[arg-type]
        assert isinstance(mistake, AlignAction), kind
    wrong = make_mistake("wrong_relation", state, planned, random.Random(1))
    assert validate_action(state, wrong) is not None


def test_factory_builds_the_offline_planners_and_rejects_unknown_names() -> None:
    assert make_planner("oracle").name == "oracle"
    assert make_planner("noisy", PlannerOptions(noise=0.2)).name == "noisy(20%)"
    with pytest.raises(ValueError, match="unknown planner"):
        make_planner("gpt-17")
    with pytest.raises(ValueError, match="mistake kinds"):
        NoisyPlanner(kinds=())
