"""`VeriGraphEnv`: Algorithm 1 as a Gymnasium environment with text in and text out.

One episode is one benchmark task. The observation is the iterative planner prompt the
project's planners read (verigraph.planning.prompting: scene, goal, executed actions, the
feedback on the previous answer); an action is the model's text reply holding up to k
actions or `done`, read by the planners' parser (verigraph.planning.parsing), so JSON, a
fenced block or `move(cup, on, table)` lines all work and anything else is a
malformed answer whose parse error is the next feedback.

Every step goes through the VeriGraph tools (`load_scene`, `set_goal`,
`execute_actions`, `end_episode`) on a `ToolEnvironment`: in process by default
(`InProcessTools`, the functions the MCP server wraps) or over a real MCP transport
(the agent's `McpTools.stdio()` / `McpTools.http(url)`), with the same results either
way.

- `terminated`: the goal holds after the step, or `done` was accepted.
- `truncated`: `threshold` consecutive failed steps (refused, malformed, premature
  `done`: tau of Algorithm 1), or `max_steps` steps.
- `reward`: the rubric (verigraph.env.rubric), success 1/0 by default.
- `info`: the structured state (graph, verdict, violation, executed actions, tau, goal
  distance, state hash, reward terms). The ground-truth goal is not in `info` nor, for
  language tasks, in the prompt; reference policies read `privileged_goal`.

`reset(seed=..., options={"task": ...})` picks the task: a task id, a `Task` (or
its dict) or an index into the task list; without one the seeded generator picks, so
`reset(seed=s)` is reproducible.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Literal, get_args

import gymnasium as gym
from gymnasium import spaces
from pydantic import ValidationError

from verigraph.actions.model import AnyAction
from verigraph.env.dataset import (
    DEFAULT_TEST_FRACTION,
    Split,
    build_tasks,
    load_tasks,
    split_tasks,
    suite_tasks,
)
from verigraph.env.rubric import Rubric, StepOutcome, score
from verigraph.errors import VeriGraphError
from verigraph.graph.goal import Goal, GraphDiff
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.planning.iteration import (
    DEFAULT_K,
    DEFAULT_THRESHOLD,
    MAX_ACTIONS_PER_CALL,
    Iteration,
    call_execute_actions,
    prompt_goal,
    read_state,
)
from verigraph.planning.models import (
    Feedback,
    FeedbackMode,
    IterationVerdict,
    PlannerReply,
    PlannerRequest,
)
from verigraph.planning.parsing import EXPECTED, ParseFailure, parse_answer
from verigraph.planning.progress import goal_distance, shape_feedback
from verigraph.planning.prompting import planner_prompt
from verigraph.planning.tool_calls import InProcessTools, ToolEnvironment
from verigraph.tasks.task import Task

# Observations and actions are text over this alphabet: printable ASCII, the whitespace
# a prompt uses, Latin-1 letters and the common punctuation, arrow and math blocks.
# Characters outside it (only ever quoted from a model's own reply) are shown as '?'.
CHARSET = "".join(chr(c) for c in (9, 10, *range(32, 127), *range(0xA0, 0x180),
                                   *range(0x2010, 0x2070), *range(0x2190, 0x2300)))
_ALLOWED = frozenset(CHARSET)
MAX_OBSERVATION = 32_768
MAX_ACTION = 4_096
RESET_OPTIONS = frozenset({"task"})
CUT = "\n[... cut to the observation limit]\n"


def _within_action_space(text: str) -> str:
    """`text` if the action space holds it; else ParseFailure naming the limit, before a
    character of it is read (a longer reply is outside the space, so it is a malformed
    step, and no parser spends time on it)."""
    if len(text) > MAX_ACTION:
        raise ParseFailure(f"the answer is {len(text):,} characters, more than the {MAX_ACTION:,} "
                           f"an action may hold; write it as {EXPECTED}")
    return text


def fit_text(text: str, limit: int = MAX_OBSERVATION) -> str:
    """`text` inside the observation space: known characters, at most `limit` long."""
    if not _ALLOWED.issuperset(text):
        text = "".join(c if c in _ALLOWED else "?" for c in text)
    if len(text) > limit:
        text = text[: limit - len(CUT)] + CUT
    return text or " "


def state_hash(graph: SceneGraph) -> str:
    """A short, order-independent digest of a scene graph (nodes, edges, dictionary)."""
    dump = graph.canonical().model_dump(mode="json", exclude_none=True)
    blob = json.dumps(dump, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()[:16]


class VeriGraphEnv(gym.Env[str, str]):
    """Text-in, text-out planning episodes on VeriGraph tasks (module docstring)."""

    metadata = {"render_modes": ["ansi"], "render_fps": 4}

    def __init__(self, family: str = "blocks", *, split: Split = "train",
                 tasks: str | Path | Sequence[Task | dict[str, Any]] | None = None,
                 per_group: int | None = None, suite_seed: int = 0,
                 test_fraction: float = DEFAULT_TEST_FRACTION, k: int = DEFAULT_K,
                 threshold: int = DEFAULT_THRESHOLD, max_steps: int = 40,
                 feedback: FeedbackMode = "full",
                 rubric: Rubric | dict[str, float] | None = None,
                 tools: ToolEnvironment | None = None,
                 render_mode: Literal["ansi"] | None = None) -> None:
        for name, value, low, high in (("k", k, 1, MAX_ACTIONS_PER_CALL),
                                       ("threshold", threshold, 1, 100),
                                       ("max_steps", max_steps, 1, 10_000)):
            if not low <= value <= high:
                raise VeriGraphError(f"{name} must be between {low} and {high}", field=name,
                                     value=value, fix=f"use e.g. {name}=3")
        if render_mode not in (None, "ansi"):
            raise VeriGraphError(f"unsupported render_mode {render_mode!r}",
                                 field="render_mode", value=render_mode,
                                 fix="use render_mode='ansi' (the observation text) or None")
        if feedback not in get_args(FeedbackMode):
            raise VeriGraphError(f"unknown feedback mode {feedback!r}", field="feedback",
                                 value=feedback, fix="use full, constraint or none")
        try:
            self.rubric = rubric if isinstance(rubric, Rubric) else Rubric(**(rubric or {}))
        except ValidationError as exc:
            err = exc.errors()[0]
            raise VeriGraphError(f"rubric: {'.'.join(map(str, err['loc']))}: {err['msg']}",
                                 field="rubric", value=rubric,
                                 fix="give weights >= 0 for success, progress, refusal, "
                                     "efficiency (docs/env.md, Reward)") from None
        if tasks is not None:
            pool = load_tasks(tasks)
        else:
            suite = suite_tasks(family) if per_group is None \
                else build_tasks(family, per_group, suite_seed)
            pool = split_tasks(suite, split, test_fraction)
        if not pool:
            raise VeriGraphError("the environment has no tasks", field="tasks",
                                 value=family, fix="raise per_group, or pass tasks")
        self.tasks: list[Task] = pool
        self._by_id = {t.task_id: t for t in pool}
        self.family = family if tasks is None else ",".join(sorted({t.family for t in pool}))
        self.k = k
        self.threshold = threshold
        self.max_steps = max_steps
        self.feedback_mode: FeedbackMode = feedback
        self.render_mode = render_mode
        self.observation_space = spaces.Text(max_length=MAX_OBSERVATION, charset=CHARSET)
        self.action_space = spaces.Text(max_length=MAX_ACTION, charset=CHARSET)
        self._owns_tools = tools is None
        self.tools: ToolEnvironment | None = tools or InProcessTools()
        self.task: Task | None = None
        self.episode_id = ""
        self._reset_state()

    # -- episode state ---------------------------------------------------------------------
    def _reset_state(self) -> None:
        self.graph: SceneGraph | None = None
        self.privileged_goal: Goal | None = None
        self.shown_goal: Goal | None = None
        self.instruction: str | None = None
        self.history: list[str] = []
        self.feedback: Feedback | None = None
        self.goal_satisfied: bool | None = None
        self.goal_diff: GraphDiff | None = None
        self.steps = 0
        self.iteration = Iteration(self.k, self.threshold)
        self.moves = 0
        self.distance_start: int | None = None
        self._distance: int | None = None
        self.episode_return = 0.0
        self.over = True
        self.stop_reason: str | None = None
        self.observation = " "

    def _tools(self) -> ToolEnvironment:
        if self.tools is None:
            raise VeriGraphError("the environment is closed", field="env",
                                 fix="create a new environment")
        return self.tools

    def _end_server_episode(self) -> dict[str, Any] | None:
        if not self.episode_id or self.tools is None:
            return None
        episode, self.episode_id = self.episode_id, ""
        return self.tools.call("end_episode", {"episode_id": episode})

    def _pick(self, options: dict[str, Any] | None) -> Task:
        # Gymnasium's reset takes `options` as a dict or None; anything else, or a key
        # this environment does not read (a misspelt "task" would silently pick a
        # seeded task), is refused before any state changes.
        if options is not None and not isinstance(options, dict):
            raise VeriGraphError(f"reset options must be a dict or None, got "
                                 f"{type(options).__name__}", field="options",
                                 value=repr(options)[:80],
                                 fix='pass options={"task": TASK_ID_OR_INDEX} or none')
        unknown = sorted(map(str, set(options or {}) - RESET_OPTIONS))
        if unknown:
            raise VeriGraphError(f"unknown reset option(s): {', '.join(unknown)[:80]}",
                                 field="options", value=unknown[0][:80],
                                 fix=f"the options are {', '.join(sorted(RESET_OPTIONS))}")
        choice = (options or {}).get("task")
        if choice is None:
            return self.tasks[int(self.np_random.integers(len(self.tasks)))]
        if isinstance(choice, Task | dict):
            return load_tasks([choice])[0]  # hash-checked, as a task file's lines are
        if isinstance(choice, int) and not isinstance(choice, bool):
            if 0 <= choice < len(self.tasks):
                return self.tasks[choice]
            raise VeriGraphError(f"task index {choice} is out of range", field="options.task",
                                 value=choice, fix=f"use 0..{len(self.tasks) - 1}")
        if isinstance(choice, str) and choice in self._by_id:
            return self._by_id[choice]
        known = ", ".join(list(self._by_id)[:5])
        raise VeriGraphError(f"no task {choice!r} in this environment", field="options.task",
                             value=str(choice)[:80],
                             fix=f"pass a task id of env.tasks (e.g. {known}), an index, or "
                                 "a Task")

    def _absorb(self, state: dict[str, Any]) -> None:
        self.graph, self.goal_satisfied, self.goal_diff = read_state(state)
        self._distance = goal_distance(self.graph, self.privileged_goal)

    def _execute(self, tools: ToolEnvironment, actions: list[AnyAction]) -> dict[str, Any]:
        out = call_execute_actions(tools, self.episode_id, actions)
        self._absorb(out)
        self.history.extend(out["executed"])
        self.moves += len(out["executed"])
        return out

    @property
    def tau(self) -> int:
        """Consecutive failed steps (tau of Algorithm 1, verigraph.planning.iteration)."""
        return self.iteration.tau

    # -- Gymnasium API ---------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None
              ) -> tuple[str, dict[str, Any]]:
        super().reset(seed=seed)
        task = self._pick(options)
        tools = self._tools()
        self._end_server_episode()
        self._reset_state()
        self.task = task
        state = tools.call("load_scene", {**task.load, "k": self.k, "t": self.threshold})
        self.episode_id = str(state["episode_id"])
        if task.set_goal:
            tools.call("set_goal", {"episode_id": self.episode_id, **task.set_goal})
            state = tools.call("get_state", {"episode_id": self.episode_id})
        self.privileged_goal = Goal.model_validate(state["goal"]) if state.get("goal") else None
        self._absorb(state)
        self.shown_goal = prompt_goal(self.privileged_goal, task.show_goal_graph)
        self.instruction = state.get("instruction")
        self.history = list(state.get("executed", []))
        self.distance_start = self.distance()
        self.over = False
        self.observation = self._render_prompt()
        return self.observation, self._info(verdict=None, reward_terms={})

    def step(self, action: str) -> tuple[str, float, bool, bool, dict[str, Any]]:
        if self.over or self.task is None:
            raise VeriGraphError("the episode is over (or was never started)", field="action",
                                 fix="call reset() to start the next episode")
        tools = self._tools()
        # The counter moves once the step has an outcome: a tool error on the way (a lost
        # MCP connection) leaves the episode at the step it was on.
        step_number = self.steps + 1
        distance_before = self.distance()
        parsed: list[AnyAction] = []
        text = action if isinstance(action, str) else str(action)
        try:
            parsed = parse_answer(_within_action_space(text))
            error = None
        except ParseFailure as exc:
            error = str(exc)
        outcome = self.iteration.step(PlannerReply(actions=parsed, error=error),
                                      lambda actions: self._execute(tools, actions),
                                      lambda: (self.goal_satisfied, self.goal_diff))
        verdict, out, dropped = outcome.verdict, outcome.out, outcome.dropped
        self.steps = step_number
        self.feedback = outcome.feedback
        terminated = outcome.stop in ("end_token", "goal_reached")
        truncated = outcome.stop == "threshold" or (not terminated
                                                    and self.steps >= self.max_steps)
        if terminated or truncated:
            self.stop_reason = outcome.stop or "step_limit"
        success = terminated and self.goal_satisfied is not False
        distance_after = self.distance()
        reward, terms = score(self.rubric, StepOutcome(
            verdict=verdict, distance_before=distance_before, distance_after=distance_after,
            distance_start=self.distance_start, success=success, moves=self.moves,
            optimal_length=self.task.optimal_length))
        self.episode_return += reward
        if terminated or truncated:
            self.over = True
            self._end_server_episode()
        self.observation = self._render_prompt()
        info = self._info(verdict=verdict, reward_terms=terms, out=out, parsed=parsed,
                          dropped=dropped, success=success if (terminated or truncated)
                          else None)
        return self.observation, reward, terminated, truncated, info

    def render(self) -> str | None:
        return self.observation if self.render_mode == "ansi" else None

    def close(self) -> None:
        if self.tools is None:
            return
        try:
            self._end_server_episode()
        finally:
            if self._owns_tools:
                self.tools.close()
            self.tools = None
            self.over = True

    # -- helpers ---------------------------------------------------------------------------
    def settings(self) -> dict[str, Any]:
        """Every setting besides the task and the actions that changes an episode's
        outcome (k, threshold, max_steps, feedback, the rubric's weights), as JSON.

        Trajectory files record it on each reset line, so a resumed run can tell that
        its episodes were played under other settings (verigraph.env.rollout). The
        tool transport is not among them: in process and over MCP give the same episode.
        """
        return {"k": self.k, "threshold": self.threshold, "max_steps": self.max_steps,
                "feedback": self.feedback_mode, "rubric": self.rubric.model_dump(mode="json")}

    def distance(self) -> int | None:
        """Goal distance of the current graph against the ground-truth goal."""
        return self._distance

    def _render_prompt(self) -> str:
        assert self.graph is not None
        shown = shape_feedback(self.feedback, self.feedback_mode)
        text = planner_prompt("iterative", WorldState.from_graph(self.graph), self.shown_goal,
                              k=self.k, instruction=self.instruction, history=self.history,
                              feedback=shown, iteration=self.steps + 1)
        return fit_text(text)

    def planner_request(self) -> PlannerRequest:
        """What a project planner (verigraph.planning) would be asked at this point.

        The reference policies in verigraph.env.rollout turn any `Planner` into a policy
        with it; `privileged_goal` is filled in, which only the oracle reads.
        """
        if self.graph is None or self.over:
            raise VeriGraphError("no episode is running", field="env",
                                 fix="call reset() first")
        return PlannerRequest(mode="iterative", iteration=self.steps + 1, graph=self.graph,
                              goal=self.shown_goal, privileged_goal=self.privileged_goal,
                              instruction=self.instruction,
                              feedback=shape_feedback(self.feedback, self.feedback_mode),
                              history=list(self.history), k=self.k, prompt=self.observation)

    def _info(self, *, verdict: IterationVerdict | None, reward_terms: dict[str, float],
              out: Mapping[str, Any] | None = None, parsed: list[AnyAction] | None = None,
              dropped: list[AnyAction] | None = None, success: bool | None = None
              ) -> dict[str, Any]:
        assert self.task is not None and self.graph is not None
        out = out or {}
        return {
            "task_id": self.task.task_id, "family": self.task.family,
            "group": self.task.group, "kind": self.task.kind,
            "optimal_length": self.task.optimal_length, "objects": self.task.objects,
            "step": self.steps, "verdict": verdict,
            "parsed": [a.text() for a in parsed or []],
            "dropped": [a.text() for a in dropped or []],
            "executed": list(out.get("executed", [])),
            "not_executed": list(out.get("not_executed", [])),
            "violation": dict(out["violation"]) if out.get("violation") else None,
            "feedback": self.feedback.text if self.feedback else None,
            "tau": self.tau, "moves": self.moves,
            "goal_satisfied": self.goal_satisfied, "goal_distance": self.distance(),
            "goal_diff": self.goal_diff.summary() if self.goal_diff else None,
            "graph": self.graph.model_dump(mode="json", exclude_none=True),
            "state_hash": state_hash(self.graph),
            "reward_terms": dict(reward_terms), "episode_return": self.episode_return,
            "stop_reason": self.stop_reason, "success": success,
        }
