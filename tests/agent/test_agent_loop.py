"""Algorithm 1 semantics: k, tau counting and reset, threshold t, the end token, direct mode.

The loop runs against the real tool layer (InProcessTools); planners are scripted test
doubles so every iteration's proposal is known in advance.
"""

from __future__ import annotations

import json

import pytest
from planning_doubles import ScriptedPlannerForTests as Scripted

from verigraph.actions import DoneAction, MoveAction
from verigraph.agent import LoopConfig, run_episode
from verigraph.agent.console import verdict_line
from verigraph.planning import InProcessTools, PlannerReply
from verigraph.planning.models import EpisodeTrace
from verigraph.planning.noisy import NoisyPlanner
from verigraph.planning.oracle import OraclePlanner
from verigraph.planning.parsing import split_proposal
from verigraph.tasks import EpisodeSpec

pytestmark = pytest.mark.fast

CUP = EpisodeSpec(load={"scene_id": "cup_on_book"})  # book on desk, cup on book
STACK = EpisodeSpec(load={"scene_id": "three_blocks"})  # goal: single_stack
SOLVE_CUP = ["move(cup, on, desk)", "move(book, on, shelf)", "done"]
NOT_CLEAR = ["move(book, on, shelf)"]  # refused at the start: cup is on book
SAME = ["move(cup, on, cup)"]  # refused always
GHOST = ["move(ghost, on, desk)"]  # refused always


def run(planner: object, spec: EpisodeSpec = CUP, env: InProcessTools | None = None,
        **config: object) -> EpisodeTrace:
    return run_episode(env or InProcessTools(), planner, spec,  # type: ignore[arg-type]
                       LoopConfig.model_validate(config))


def test_loop_sends_at_most_k_actions_and_records_the_rest_as_dropped() -> None:
    planner = Scripted([SOLVE_CUP, ["move(book, on, shelf)", "done"]])
    trace = run(planner, k=1)
    first, second = trace.iterations
    assert planner.requests[0].k == 1
    assert "at most 1 actions" in planner.requests[0].prompt
    assert first.executed == ["move(cup, on, desk)"]
    assert first.dropped == ["move(book, on, shelf)", "done"]
    assert first.verdict == "clean"
    assert second.executed == ["move(book, on, shelf)"]
    assert second.verdict == "end_token"
    assert trace.success and trace.actions_executed == 2


def test_split_proposal_ignores_everything_after_done() -> None:
    cup = MoveAction(object="cup", target="desk")
    book = MoveAction(object="book", target="shelf")
    moves, done, dropped = split_proposal([cup, DoneAction(), book], k=3)
    assert moves == [cup] and done and dropped == [book]
    moves, done, dropped = split_proposal([cup, book, DoneAction()], k=1)
    assert moves == [cup] and not done and dropped == [book, DoneAction()]


def test_tau_counts_consecutive_failures_and_resets_on_a_clean_iteration() -> None:
    planner = Scripted([NOT_CLEAR, NOT_CLEAR, ["move(cup, on, desk)"], SAME,
                        ["move(book, on, shelf)", "done"]])
    trace = run(planner, threshold=5)
    assert [r.tau for r in trace.iterations] == [1, 2, 0, 1, 0]
    assert [r.server_tau for r in trace.iterations] == [1, 2, 0, 1, 0]
    assert [r.verdict for r in trace.iterations] == [
        "violation", "violation", "clean", "violation", "end_token"]
    assert trace.success and trace.violations_caught == 3


@pytest.mark.parametrize("t", [1, 2, 3, 5])
def test_always_invalid_planner_ends_at_threshold_with_a_clear_verdict(t: int) -> None:
    trace = run(Scripted([GHOST]), threshold=t)
    assert len(trace.iterations) == t
    assert [r.tau for r in trace.iterations] == list(range(1, t + 1))
    assert trace.stop_reason == "threshold"
    assert trace.verdict == "threshold_reached" and not trace.success
    assert trace.actions_executed == 0 and trace.violations_caught == t
    last = trace.iterations[-1].feedback
    assert last is not None and last.violation is not None
    assert last.violation.constraint == "unknown_object"
    line = verdict_line(trace)
    assert line.startswith("FAILURE (threshold_reached, stopped: threshold)")


def test_feedback_of_a_violation_reaches_the_next_prompt() -> None:
    planner = Scripted([NOT_CLEAR, SOLVE_CUP])
    trace = run(planner)
    second = planner.requests[1]
    assert second.feedback is not None and second.feedback.violation is not None
    assert second.feedback.violation.constraint == "object_not_clear"
    assert second.feedback.violation.blocking == ["cup"]
    assert "object_not_clear" in second.prompt and "move(cup, on" in second.prompt
    assert trace.success


def test_end_token_stops_the_loop_under_the_trust_policy_even_if_the_goal_is_missed() -> None:
    planner = Scripted([["done"], SOLVE_CUP])
    trace = run(planner, done_policy="trust")
    assert len(trace.iterations) == 1 and len(planner.requests) == 1
    assert trace.stop_reason == "end_token"
    assert trace.verdict == "goal_not_reached" and not trace.success


def test_verify_policy_refuses_a_premature_done_and_counts_it_as_a_failure() -> None:
    planner = Scripted([["done"], SOLVE_CUP])
    trace = run(planner, done_policy="verify")
    first, second = trace.iterations
    assert first.verdict == "premature_done" and first.tau == 1
    assert first.feedback is not None and "book on shelf" in first.feedback.text
    assert second.verdict == "end_token" and second.tau == 0
    assert trace.success and trace.premature_done == 1


def test_done_when_the_goal_holds_ends_the_episode_successfully() -> None:
    trace = run(Scripted([["move(cup, on, desk)", "move(book, on, shelf)"], ["done"]]),
                stop_on_goal=False)
    assert [r.verdict for r in trace.iterations] == ["clean", "end_token"]
    assert trace.stop_reason == "end_token" and trace.success


def test_stop_on_goal_ends_the_episode_before_the_planner_can_undo_the_goal() -> None:
    undo = ["move(cup, on, book)"]
    reach = ["move(cup, on, desk)", "move(book, on, shelf)"]
    stopped = run(Scripted([reach, undo, ["done"]]))
    assert stopped.stop_reason == "goal_reached" and stopped.success
    assert len(stopped.iterations) == 1 and stopped.iterations[0].goal_distance == 0
    literal = run(Scripted([reach, undo, ["done"]]), stop_on_goal=False,
                  done_policy="trust")
    assert [r.verdict for r in literal.iterations] == ["clean", "clean", "end_token"]
    assert not literal.success and literal.stop_reason == "end_token"


def test_malformed_answers_count_towards_tau_and_become_feedback() -> None:
    bad = PlannerReply(error="the answer is not valid JSON", raw="{oops")
    planner = Scripted([bad, PlannerReply(actions=[]), SOLVE_CUP])
    trace = run(planner, threshold=5)
    assert [r.verdict for r in trace.iterations] == ["malformed", "malformed", "end_token"]
    assert [r.tau for r in trace.iterations] == [1, 2, 0]
    fb = planner.requests[1].feedback
    assert fb is not None and fb.kind == "malformed" and "not valid JSON" in fb.text
    assert "not valid JSON" in planner.requests[1].prompt
    assert trace.malformed_outputs == 2 and trace.success


def test_malformed_answers_alone_reach_the_threshold() -> None:
    trace = run(Scripted([PlannerReply(error="garbage")]), threshold=2)
    assert trace.stop_reason == "threshold" and len(trace.iterations) == 2
    assert trace.verdict == "goal_not_reached" and not trace.success


def test_a_planner_that_never_finishes_stops_at_the_iteration_limit() -> None:
    shuffle = Scripted([["move(cup, on, desk)"], ["move(cup, on, book)"]] * 10)
    trace = run(shuffle, max_iterations=6, no_progress=0)
    assert trace.stop_reason == "iteration_limit" and len(trace.iterations) == 6
    assert all(r.tau == 0 for r in trace.iterations)


def test_valid_moves_back_and_forth_stop_at_the_no_progress_rule() -> None:
    shuffle = Scripted([["move(cup, on, desk)"], ["move(cup, on, book)"]] * 20)
    trace = run(shuffle, no_progress=4, threshold=3)
    assert trace.stop_reason == "no_progress" and not trace.success
    # desk brings the cup one edge closer (a new low), then 4 iterations without a new low
    assert [r.goal_distance for r in trace.iterations] == [2, 4, 2, 4, 2]
    assert all(r.tau == 0 for r in trace.iterations)


def test_direct_mode_makes_one_call_and_gives_no_feedback() -> None:
    planner = Scripted([["move(cup, on, shelf)", "move(book, on, desk)", "move(cup, on, desk)"]])
    bad = run(planner, mode="direct")
    assert len(planner.requests) == 1 and planner.requests[0].k is None
    assert "Write the whole plan" in planner.requests[0].prompt
    assert bad.stop_reason == "single_shot" and not bad.success
    assert bad.iterations[0].executed == ["move(cup, on, shelf)"]
    assert bad.iterations[0].verdict == "violation"
    assert bad.iterations[0].feedback is not None
    assert bad.iterations[0].feedback.violation is not None
    assert bad.iterations[0].feedback.violation.constraint == "already_there"
    good = run(OraclePlanner(), mode="direct")
    assert good.success and good.llm_calls == 1 and good.actions_executed == 2


def test_goal_graph_can_be_hidden_from_the_prompt_but_is_still_checked() -> None:
    spec = EpisodeSpec(load={"scene_id": "cup_on_book"}, show_goal_graph=False,
                       set_goal={"instruction": "Put the book on the shelf, cup on the desk."})
    planner = Scripted([SOLVE_CUP])
    trace = run(planner, spec)
    prompt = planner.requests[0].prompt
    assert "Put the book on the shelf, cup on the desk." in prompt
    assert "Goal graph" not in prompt
    assert planner.requests[0].goal is None  # only the words are shown
    assert planner.requests[0].privileged_goal is None  # only a privileged planner gets it
    assert trace.success


@pytest.mark.parametrize("mode", ["iterative", "direct"])
def test_a_planner_exception_ends_the_episode_with_planner_error(mode: str) -> None:
    env = InProcessTools()
    script = [["move(cup, on, desk)"], RuntimeError("endpoint down")]
    trace = run(Scripted(script[1:] if mode == "direct" else script), env=env, mode=mode)
    assert trace.stop_reason == "planner_error" and not trace.success
    assert trace.planner_error == "RuntimeError: endpoint down"
    assert trace.iterations[-1].verdict == "planner_error"
    assert trace.verdict == "goal_not_reached" and trace.final_graph is not None
    assert len(env.toolbox.context.store) == 0  # the episode was closed


def test_constraint_and_none_feedback_modes_show_the_planner_less() -> None:
    for mode, expect in (("constraint", "[object_not_clear] an action was refused"),
                         ("none", None)):
        planner = Scripted([NOT_CLEAR, SOLVE_CUP])
        trace = run(planner, feedback=mode)
        shown = planner.requests[1].feedback
        assert (shown.text if shown else None) == expect
        assert shown is None or shown.violation is None
        assert "move(cup, on" not in planner.requests[1].prompt
        full = trace.iterations[0].feedback  # the trace keeps the verifier's whole report
        assert full is not None and full.violation is not None
        assert trace.feedback_mode == mode and trace.success


def test_the_trace_is_json_and_round_trips() -> None:
    trace = run(Scripted([NOT_CLEAR, SOLVE_CUP]), record_prompts=True)
    data = json.loads(json.dumps(trace.model_dump(mode="json")))
    again = EpisodeTrace.model_validate(data)
    assert again == trace
    assert again.iterations[0].prompt is not None
    assert again.final_graph is not None and "book on shelf" in again.final_graph.sentences()


@pytest.mark.parametrize("k", [1, 2, 3, 5])
def test_oracle_reaches_builtin_goals_for_every_k(k: int) -> None:
    for spec in (CUP, STACK):
        trace = run(OraclePlanner(), spec, k=k)
        assert trace.success and trace.violations_caught == 0
        assert all(len(r.executed) <= k for r in trace.iterations)


def test_noisy_planner_recovers_with_feedback_and_beats_direct_mode() -> None:
    env = InProcessTools()
    iterative = direct = 0
    episodes = 40
    for seed in range(episodes):
        for spec in (CUP, STACK):
            t_iter = run(NoisyPlanner(0.3, seed=seed), spec, env=env)
            t_direct = run(NoisyPlanner(0.3, seed=seed), spec, env=env, mode="direct")
            iterative += t_iter.success
            direct += t_direct.success
    assert iterative / (2 * episodes) >= 0.95
    assert direct / (2 * episodes) <= 0.85
