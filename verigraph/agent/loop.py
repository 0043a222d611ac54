"""Algorithm 1 (DESIGN section 6) as an agent that works only through the tools.

Iterative mode, per iteration: render the planner prompt for the current graph, ask the
planner for at most k actions (or the end token), send them to `execute_actions`
(execute-until-violation), and read back the new graph and the violation. tau counts
consecutive failed iterations and is reset by a clean one; the episode stops when the
planner's end token is accepted or when tau reaches the threshold t. `end_episode`
gives the verdict.

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
from collections.abc import Callable, Mapping
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, DoneAction
from verigraph.agent.environment import ToolEnvironment
from verigraph.agent.models import (
    DonePolicy,
    EpisodeTrace,
    Feedback,
    FeedbackMode,
    IterationRecord,
    Mode,
    PlannerReply,
    PlannerRequest,
)
from verigraph.agent.planner import Planner
from verigraph.agent.progress import ProgressMeter, goal_distance, shape_feedback
from verigraph.agent.prompting import planner_prompt
from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState

MAX_ACTIONS_PER_CALL = 50  # execute_actions' limit; direct plans are sent in such chunks


class LoopConfig(BaseModel):
    """Algorithm 1's knobs: k actions per iteration, threshold t, the end-token policy."""

    model_config = ConfigDict(extra="forbid")

    mode: Mode = "iterative"
    k: int = Field(default=3, ge=1, le=MAX_ACTIONS_PER_CALL,
                   description="at most k actions per iteration")
    threshold: int = Field(default=5, ge=1, le=100,
                           description="stop after t consecutive failed iterations")
    done_policy: DonePolicy = "verify"
    stop_on_goal: bool = Field(default=True,
                               description="stop as soon as the goal holds (off: only the "
                                           "end token stops, the paper's literal rule)")
    no_progress: int = Field(default=15, ge=0, le=10_000,
                             description="stop after this many iterations without a new "
                                         "lowest distance to the goal (0 = never)")
    feedback: FeedbackMode = Field(default="full",
                                   description="what the planner is shown of a failure: "
                                               "full, constraint (id only) or none")
    max_iterations: int = Field(default=60, ge=1, le=10_000,
                                description="safety stop for planners that never finish")
    record_prompts: bool = Field(default=False, description="keep each prompt in the trace")


class EpisodeSpec(BaseModel):
    """How to start one episode: raw `load_scene` and optional `set_goal` arguments.

    `show_goal_graph=False` hides the goal graph from LLM prompts (instruction tasks:
    the planner reads the words, the verifier checks the ground-truth graph).
    """

    model_config = ConfigDict(extra="forbid")

    task_id: str | None = None
    load: dict[str, Any] = Field(description="load_scene arguments (without k and t)")
    set_goal: dict[str, Any] | None = Field(default=None,
                                            description="set_goal arguments (no episode_id)")
    show_goal_graph: bool = True


IterationHook = Callable[[IterationRecord], None]
StartHook = Callable[[EpisodeTrace], None]


def split_proposal(actions: list[AnyAction], k: int | None
                   ) -> tuple[list[AnyAction], bool, list[AnyAction]]:
    """(moves to send, end token reached, dropped): obey k; nothing after `done` counts."""
    moves: list[AnyAction] = []
    done = False
    rest: list[AnyAction] = []
    for index, action in enumerate(actions):
        if isinstance(action, DoneAction):
            done = True
            rest = actions[index + 1:]
            break
        moves.append(action)
    if k is not None and len(moves) > k:
        return moves[:k], False, [*moves[k:], *([DoneAction()] if done else []), *rest]
    return moves, done, rest


def _prompt_goal(goal: Goal | None, show_graph: bool) -> Goal | None:
    if goal is None or show_graph or goal.graph is None:
        return goal
    if goal.predicate is None:
        return None
    return goal.model_copy(update={"graph": None})


class _Episode:
    """Mutable bookkeeping of one run; the public result is the EpisodeTrace."""

    def __init__(self, env: ToolEnvironment, planner: Planner, spec: EpisodeSpec,
                 config: LoopConfig, hook: IterationHook | None) -> None:
        self.env = env
        self.planner = planner
        self.spec = spec
        self.config = config
        self.hook = hook
        self.episode_id = ""
        self.graph: SceneGraph | None = None
        self.goal: Goal | None = None
        self.instruction: str | None = None
        self.history: list[str] = []
        self.goal_satisfied: bool | None = None
        self.goal_diff: GraphDiff | None = None
        self.trace = EpisodeTrace(planner=planner.name, mode=config.mode, k=config.k,
                                  threshold=config.threshold, done_policy=config.done_policy,
                                  transport=env.transport, task=spec.task_id,
                                  stop_on_goal=config.stop_on_goal,
                                  feedback_mode=config.feedback)

    # -- tools ---------------------------------------------------------------------------
    def _absorb_state(self, state: Mapping[str, Any]) -> None:
        graph = state.get("graph")
        if graph is None:
            raise VeriGraphError(
                "the episode has no scene graph yet (it was loaded from an image and no "
                "perception is installed)", field="scene", value=self.episode_id,
                fix="load a scene graph, a scene id or a generated scene, or describe the "
                    "image with get_scene_image + submit_scene_graph first")
        self.graph = SceneGraph.model_validate(graph)
        self.goal = Goal.model_validate(state["goal"]) if state.get("goal") else None
        self.instruction = state.get("instruction")
        self.history = list(state.get("executed", []))
        self.goal_satisfied = state.get("goal_satisfied")
        diff = state.get("goal_diff")
        self.goal_diff = GraphDiff.model_validate(diff) if diff else None

    def start(self) -> None:
        iterative = self.config.mode == "iterative"
        load = {**self.spec.load, "k": self.config.k if iterative else MAX_ACTIONS_PER_CALL,
                "t": self.config.threshold if iterative else 1}
        state = self.env.call("load_scene", load)
        self.episode_id = str(state["episode_id"])
        self.trace.episode_id = self.episode_id
        if self.spec.set_goal:
            self.env.call("set_goal", {"episode_id": self.episode_id, **self.spec.set_goal})
            state = self.env.call("get_state", {"episode_id": self.episode_id})
        self._absorb_state(state)
        self.trace.initial_graph = self.graph
        self.trace.goal = self.goal
        self.trace.instruction = self.instruction

    def execute(self, actions: list[AnyAction]) -> dict[str, Any]:
        out = self.env.call("execute_actions", {
            "episode_id": self.episode_id,
            "actions": [a.model_dump(mode="json") for a in actions]})
        self.graph = SceneGraph.model_validate(out["graph"])
        self.history.extend(out["executed"])
        self.goal_satisfied = out.get("goal_satisfied")
        diff = out.get("goal_diff")
        self.goal_diff = GraphDiff.model_validate(diff) if diff else None
        self.trace.actions_executed += len(out["executed"])
        return out

    def finish(self) -> None:
        verdict = self.env.call("end_episode", {"episode_id": self.episode_id})
        self.trace.success = bool(verdict.get("success"))
        self.trace.verdict = verdict.get("verdict")
        final = verdict.get("final_graph")
        self.trace.final_graph = SceneGraph.model_validate(final) if final else None
        diff = verdict.get("goal_diff")
        self.trace.goal_diff = GraphDiff.model_validate(diff) if diff else None
        self.trace.verdict_summary = self.trace.goal_diff.summary() if self.trace.goal_diff \
            else verdict.get("verdict")

    # -- planner -------------------------------------------------------------------------
    def ask(self, iteration: int, feedback: Feedback | None) -> tuple[PlannerReply, str]:
        assert self.graph is not None
        k = self.config.k if self.config.mode == "iterative" else None
        shown_goal = _prompt_goal(self.goal, self.spec.show_goal_graph)
        shown_feedback = shape_feedback(feedback, self.config.feedback)
        prompt = planner_prompt(
            self.config.mode, WorldState.from_graph(self.graph), shown_goal, k=k,
            instruction=self.instruction, history=self.history, feedback=shown_feedback,
            iteration=iteration)
        request = PlannerRequest(mode=self.config.mode, iteration=iteration, graph=self.graph,
                                 goal=shown_goal, privileged_goal=self.goal,
                                 instruction=self.instruction, feedback=shown_feedback,
                                 history=list(self.history), k=k, prompt=prompt)
        reply = self.planner.propose(request)
        self.trace.llm_calls += reply.llm_calls
        return reply, prompt

    def planner_failed(self, iteration: int, exc: Exception, started: float) -> None:
        """End the episode on a planner exception: one record, the error in the trace."""
        message = f"{type(exc).__name__}: {exc}"[:500]
        self.trace.planner_error = message
        self.trace.stop_reason = "planner_error"
        self.record(IterationRecord(iteration=iteration, proposed=[], verdict="planner_error",
                                    tau=0, llm_calls=0, note=f"planner raised {message}",
                                    goal_satisfied=self.goal_satisfied,
                                    seconds=time.perf_counter() - started))

    def distance(self) -> int | None:
        return goal_distance(self.graph, self.goal) if self.graph is not None else None

    def record(self, record: IterationRecord) -> None:
        self.trace.iterations.append(record)
        if self.hook is not None:
            self.hook(record)


def _malformed(reply: PlannerReply) -> Feedback:
    reason = reply.error or "it contained no action (not even done)"
    return Feedback(kind="malformed",
                    text=f"[malformed_action] your previous answer could not be used: {reason}")


def _violation_feedback(out: Mapping[str, Any]) -> Feedback:
    violation = Violation.model_validate(out["violation"])
    executed = ", ".join(out.get("executed") or []) or "none"
    skipped = ", ".join(out.get("not_executed") or []) or "none"
    return Feedback(kind="violation", violation=violation,
                    text=f"{violation.text()} (executed from your answer: {executed}; not "
                         f"executed: {skipped})")


def _iterate(ep: _Episode) -> None:
    config = ep.config
    tau = 0
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
        record = IterationRecord(
            iteration=iteration, proposed=[a.text() for a in reply.actions], verdict="clean",
            tau=tau, llm_calls=reply.llm_calls, raw_output=reply.raw, note=reply.note,
            prompt=prompt if config.record_prompts else None)
        moves, done, dropped = split_proposal(reply.actions, config.k)
        record.dropped = [a.text() for a in dropped]
        server_threshold = False
        ended = False
        if reply.error is not None or not (moves or done):
            feedback = _malformed(reply)
            record.verdict = "malformed"
            ep.trace.malformed_outputs += 1
        else:
            feedback = None
            if moves:
                out = ep.execute([*moves, *([DoneAction()] if done else [])])
                record.executed = list(out["executed"])
                record.server_tau = out.get("tau")
                server_threshold = bool(out.get("threshold_reached"))
                if out.get("violation"):
                    feedback = _violation_feedback(out)
                    record.verdict = "violation"
                    ep.trace.violations_caught += 1
                ended = done and feedback is None
            else:
                ended = True
            if ended:
                if ep.goal_satisfied is False and config.done_policy == "verify":
                    diff = ep.goal_diff.summary() if ep.goal_diff else "goal not reached"
                    feedback = Feedback(
                        kind="premature_done",
                        text=f"[premature_done] you answered done, but {diff}. Keep planning "
                             "towards the goal and answer done only once it holds.")
                    record.verdict = "premature_done"
                    ep.trace.premature_done += 1
                    ended = False
                else:
                    record.verdict = "end_token"
        tau = 0 if record.verdict in ("clean", "end_token") else tau + 1
        record.tau = tau
        record.feedback = feedback
        record.goal_satisfied = ep.goal_satisfied
        record.goal_distance = ep.distance()
        record.seconds = time.perf_counter() - started
        ep.record(record)
        if ended:
            ep.trace.stop_reason = "end_token"
            return
        if config.stop_on_goal and ep.goal_satisfied:
            ep.trace.stop_reason = "goal_reached"
            return
        if tau >= config.threshold or server_threshold:
            ep.trace.stop_reason = "threshold"
            return
        if meter.update(record.goal_distance):
            ep.trace.stop_reason = "no_progress"
            return
    ep.trace.stop_reason = "iteration_limit"


def _direct(ep: _Episode) -> None:
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
        record.feedback = _malformed(reply)
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
                record.feedback = _violation_feedback(out)
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
    ep = _Episode(env, planner, spec, config, on_iteration)
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
