"""One episode's bookkeeping for the loop: its settings, how it starts, and the tool calls.

`LoopConfig` and the task's `EpisodeSpec` (verigraph.tasks.groups) are the loop's
inputs; `EpisodeRun` keeps the mutable state of one run (graph, goal, history, the
trace) and wraps the tools (`load_scene`, `set_goal`, `execute_actions`, `end_episode`)
and the planner call, so `loop.py` holds only Algorithm 1's control flow.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.actions.model import AnyAction
from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.planning.iteration import (
    DEFAULT_K,
    DEFAULT_THRESHOLD,
    MAX_ACTIONS_PER_CALL,
    call_execute_actions,
    prompt_goal,
    read_state,
)
from verigraph.planning.models import (
    DonePolicy,
    EpisodeTrace,
    Feedback,
    FeedbackMode,
    IterationRecord,
    IterationVerdict,
    Mode,
    PlannerReply,
    PlannerRequest,
)
from verigraph.planning.planner import Planner, is_privileged
from verigraph.planning.progress import goal_distance, shape_feedback
from verigraph.planning.prompting import planner_prompt
from verigraph.planning.tool_calls import ToolEnvironment
from verigraph.tasks.task import EpisodeSpec


class LoopConfig(BaseModel):
    """Algorithm 1's knobs: k actions per iteration, the error threshold t (`threshold`),
    the end-token policy; k and t default to the server's (verigraph.planning.iteration)."""

    model_config = ConfigDict(extra="forbid")

    mode: Mode = "iterative"
    k: int = Field(default=DEFAULT_K, ge=1, le=MAX_ACTIONS_PER_CALL,
                   description="at most k actions per iteration")
    threshold: int = Field(default=DEFAULT_THRESHOLD, ge=1, le=100,
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


IterationHook = Callable[[IterationRecord], None]
StartHook = Callable[[EpisodeTrace], None]


class EpisodeRun:
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
        self.graph, self.goal_satisfied, self.goal_diff = read_state(state)
        self.goal = Goal.model_validate(state["goal"]) if state.get("goal") else None
        self.instruction = state.get("instruction")
        self.history = list(state.get("executed", []))

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
        out = call_execute_actions(self.env, self.episode_id, actions)
        self.graph, self.goal_satisfied, self.goal_diff = read_state(out)
        self.history.extend(out["executed"])
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
        shown_goal = prompt_goal(self.goal, self.spec.show_goal_graph)
        shown_feedback = shape_feedback(feedback, self.config.feedback)
        privileged = is_privileged(self.planner)
        prompt = planner_prompt(
            self.config.mode, WorldState.from_graph(self.graph), shown_goal, k=k,
            instruction=self.instruction, history=self.history, feedback=shown_feedback,
            iteration=iteration)
        request = PlannerRequest(mode=self.config.mode, iteration=iteration, graph=self.graph,
                                 goal=shown_goal,
                                 privileged_goal=self.goal if privileged else None,
                                 instruction=self.instruction, feedback=shown_feedback,
                                 history=list(self.history), k=k, prompt=prompt)
        reply = self.planner.propose(request)
        self.trace.llm_calls += reply.llm_calls
        return reply, prompt

    def count(self, verdict: IterationVerdict) -> None:
        """Add an iteration's failure, if it was one, to the trace's counters."""
        if verdict == "malformed":
            self.trace.malformed_outputs += 1
        elif verdict == "violation":
            self.trace.violations_caught += 1
        elif verdict == "premature_done":
            self.trace.premature_done += 1

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
