"""Algorithm 1 (docs/design.md section 6) as an agent that works only through the tools.

Iterative mode, per iteration: render the planner prompt for the current graph, ask the
planner for at most k actions (or the end token), send them to `execute_actions`
(execute-until-violation), and read back the new graph and the violation. tau counts
consecutive failed iterations and is reset by a clean one; the episode stops when the
planner's end token is accepted or when tau reaches the threshold t. `end_episode`
gives the verdict. One iteration (the verdict, tau, the end-token rule and the stops
they call for) is verigraph.planning.iteration's `Iteration`, which the environment's
`step` drives too; this module adds the planner call, the trace and the stops below.

Stops besides t, each recorded as the trace's `stop_reason`:

- `goal_reached` (`stop_on_goal`, default on): the goal holds after an iteration, so
  the episode ends there instead of asking for `done` (a planner cannot undo a reached
  goal). Off, only the end token stops a successful run: the paper's literal rule.
- `no_progress` (`no_progress=N`, default 15, 0 = off): N consecutive iterations
  without a new lowest distance to the goal (see progress.py). Valid moves back and
  forth reset tau, so without it only `max_iterations` would end them.
- `iteration_limit` (`max_iterations`, default 60): the last safety stop.
- `planner_error`: the planner raised (an endpoint still down after its retries, a
  bug); the episode is closed, the error is in the trace, and the caller carries on.

Refinements of the loop itself, recorded in the trace:

- A malformed answer (not JSON, not actions, truncated) is a failed iteration: it
  counts towards tau and its parse error is the next feedback.
- `done_policy="verify"` (default): an end token while a checkable goal does not hold
  is refused like any invalid action (feedback shows the goal difference, tau + 1).
  `done_policy="trust"` is the paper's literal reading: the end token always stops.

Direct mode ("Ours (Direct)"): one planner call for the whole plan, executed until
the first violation, no feedback, no second call.
"""

from __future__ import annotations

import contextlib
import time

from verigraph.actions.model import DoneAction
from verigraph.agent.episode import EpisodeRun, IterationHook, LoopConfig, StartHook
from verigraph.planning.iteration import MAX_ACTIONS_PER_CALL, Iteration
from verigraph.planning.models import EpisodeTrace, Feedback, IterationRecord
from verigraph.planning.parsing import split_proposal
from verigraph.planning.planner import Planner
from verigraph.planning.progress import ProgressMeter, malformed_feedback, violation_feedback
from verigraph.planning.tool_calls import ToolEnvironment
from verigraph.tasks.task import EpisodeSpec

__all__ = ["MAX_ACTIONS_PER_CALL", "LoopConfig", "run_episode"]


def _iterate(ep: EpisodeRun) -> None:
    config = ep.config
    step = Iteration(config.k, config.threshold, verify_done=config.done_policy == "verify",
                     stop_on_goal=config.stop_on_goal)
    feedback: Feedback | None = None
    meter = ProgressMeter(config.no_progress)
    meter.update(ep.distance())
    for iteration in range(1, config.max_iterations + 1):
        started = time.perf_counter()
        try:
            reply, prompt = ep.ask(iteration, feedback)
        except Exception as exc:  # noqa: BLE001 (any planner failure ends only this episode)
            ep.planner_failed(iteration, exc, started)
            return
        outcome = step.step(reply, ep.execute, lambda: (ep.goal_satisfied, ep.goal_diff))
        feedback = outcome.feedback
        ep.count(outcome.verdict)
        record = IterationRecord(
            iteration=iteration, proposed=[a.text() for a in reply.actions],
            verdict=outcome.verdict, tau=outcome.tau, llm_calls=reply.llm_calls,
            raw_output=reply.raw, note=reply.note,
            prompt=prompt if config.record_prompts else None,
            dropped=[a.text() for a in outcome.dropped], feedback=feedback,
            goal_satisfied=ep.goal_satisfied, goal_distance=ep.distance())
        if outcome.out:
            record.executed = list(outcome.out["executed"])
            record.server_tau = outcome.out.get("tau")
        record.seconds = time.perf_counter() - started
        ep.record(record)
        if outcome.stop is not None:
            ep.trace.stop_reason = outcome.stop
            return
        if meter.update(record.goal_distance):
            ep.trace.stop_reason = "no_progress"
            return
    ep.trace.stop_reason = "iteration_limit"


def _direct(ep: EpisodeRun) -> None:
    started = time.perf_counter()
    try:
        reply, prompt = ep.ask(1, None)
    except Exception as exc:  # noqa: BLE001 (any planner failure ends only this episode)
        ep.planner_failed(1, exc, started)
        return
    record = IterationRecord(
        iteration=1, proposed=[a.text() for a in reply.actions], verdict="clean", tau=0,
        llm_calls=reply.llm_calls, raw_output=reply.raw, note=reply.note,
        prompt=prompt if ep.config.record_prompts else None)
    moves, done, dropped = split_proposal(reply.actions, None)
    record.dropped = [a.text() for a in dropped]
    if reply.error is not None or not (moves or done):
        record.feedback = malformed_feedback(reply)
        record.verdict = "malformed"
        record.tau = 1
        ep.trace.malformed_outputs += 1
    else:
        record.verdict = "end_token" if done else "clean"
        for start in range(0, len(moves), MAX_ACTIONS_PER_CALL):
            batch = moves[start:start + MAX_ACTIONS_PER_CALL]
            last = start + MAX_ACTIONS_PER_CALL >= len(moves)
            out = ep.execute([*batch, *([DoneAction()] if done and last else [])])
            record.executed.extend(out["executed"])
            record.server_tau = out.get("tau")
            if out.get("violation"):
                record.feedback = violation_feedback(out)
                record.verdict = "violation"
                record.tau = 1
                ep.trace.violations_caught += 1
                break
    record.goal_satisfied = ep.goal_satisfied
    record.goal_distance = ep.distance()
    record.seconds = time.perf_counter() - started
    ep.record(record)
    ep.trace.stop_reason = "single_shot"


def run_episode(env: ToolEnvironment, planner: Planner, spec: EpisodeSpec,
                config: LoopConfig | None = None, *, on_iteration: IterationHook | None = None,
                on_start: StartHook | None = None) -> EpisodeTrace:
    """Run one episode through the tools and return its trace (verdict included).

    A planner exception ends the episode with `stop_reason="planner_error"` and the
    error in `trace.planner_error`; the verdict is still taken, so the trace is whole.
    Anything else that escapes (a tool error, Ctrl-C) closes the server-side episode
    with `end_episode` and propagates.
    """
    config = config or LoopConfig()
    ep = EpisodeRun(env, planner, spec, config, on_iteration)
    started = time.perf_counter()
    try:
        ep.start()
        if on_start is not None:
            on_start(ep.trace)
        if config.mode == "iterative":
            _iterate(ep)
        else:
            _direct(ep)
    except BaseException:
        if ep.episode_id:
            with contextlib.suppress(Exception):
                env.call("end_episode", {"episode_id": ep.episode_id})
        raise
    ep.finish()
    ep.trace.wall_time_s = time.perf_counter() - started
    return ep.trace
