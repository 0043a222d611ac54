"""Episode lifecycle tools after loading: get_state and end_episode (the end token).

An episode is one run of Algorithm 1: a current graph, an optional goal, the actions
executed so far and the count tau of consecutive failed execute_actions calls. It starts
with load_scene (`tools.loading`), gets its goal with set_goal (`tools.goals`) and is
summarised by `tools.summaries`; `tools.store` keeps it.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from verigraph.graph.goal import Goal, GraphDiff, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.tools.context import ToolContext
from verigraph.tools.executors import arm_mode_of, executors_text, runs_on
from verigraph.tools.fields import EpisodeId
from verigraph.tools.request import asked_against
from verigraph.tools.store import TraceEntry
from verigraph.tools.summaries import EpisodeState, describe_episode
from verigraph.tools.texts import edges_line


# -- get_state ------------------------------------------------------------------------------
class EpisodeRef(BaseModel):
    """Just the episode."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId


def get_state(ctx: ToolContext, params: EpisodeRef) -> EpisodeState:
    with ctx.store.use(params.episode_id) as episode:
        out = describe_episode(episode)
    out.executors = executors_text(ctx.config.executor, ctx.config.arm)
    return out


# -- end_episode ----------------------------------------------------------------------------
# end_episode's text names at most this many items of the request not done (all are in
# `asked_missing`).
MAX_ASKED_SHOWN = 20
Verdict = Literal["goal_reached", "partial", "goal_not_reached", "threshold_reached",
                  "no_goal", "no_scene"]


class EpisodeVerdict(BaseModel):
    """The end token's answer: did the episode reach its goal, and how it got there."""

    episode_id: str
    success: bool = Field(description="a checkable goal holds on the final graph")
    verdict: Verdict
    final_graph: SceneGraph | None
    goal: Goal | None
    goal_diff: GraphDiff | None
    executed: list[str]
    steps: int = Field(description="actions executed")
    calls: int = Field(description="execute_actions calls")
    tau: int
    t: int
    threshold_reached: bool
    trace: list[TraceEntry]
    runs_on: str | None = Field(default=None, description="the episode's executor")
    asked_missing: list[str] = Field(
        default_factory=list, description="what the user's request (load_scene's "
        "instruction, or the first goal set_goal refused or narrowed) asked for that does "
        "not hold at the end (with why, when it could not be placed)")
    asked: str | None = Field(default=None, description="which request asked_missing "
                              "is read against")

    def observed(self) -> str | None:
        """A simulator or arm episode: whether every action ended as predicted."""
        if self.runs_on is None or self.runs_on.startswith("graph"):
            return None
        differed = [t.call for t in self.trace
                    if t.violation is not None and t.violation.constraint == "execution_failed"]
        if differed:
            return ("observed != predicted in call(s) " + ", ".join(map(str, differed))
                    + " (execution_failed): the final graph is what the world observed")
        return (f"observed = predicted: each of the {self.steps} action(s) ended where the "
                "plan said")

    def summary(self) -> str:
        text = self._verdict_text()
        observed = self.observed()
        if observed is None:
            return text
        lines = text.split("\n")
        return "\n".join([*lines[:2], observed, *lines[2:]])

    def _asked_text(self) -> str:
        shown = self.asked_missing[:MAX_ASKED_SHOWN]
        more = len(self.asked_missing) - len(shown)
        return "; ".join(shown) + (f"; ... and {more} more" if more else "")

    def _verdict_text(self) -> str:
        if self.verdict == "partial":
            text = ("PARTIAL: the goal set was reached, but it is narrower than "
                    f"{self.asked}; not done: " + self._asked_text()
                    + f"; {self.steps} action(s) in {self.calls} call(s); episode "
                    f"{self.episode_id} closed")
            if self.runs_on is not None:
                text += f"\nexecutor: {self.runs_on}"
            if self.final_graph is not None:
                text += "\n" + edges_line(self.final_graph, "final graph")
            return text
        text = {"goal_reached": "SUCCESS: goal reached",
                "goal_not_reached": "FAILURE: goal not reached",
                "threshold_reached": f"FAILURE: stopped after tau={self.tau} failed calls",
                "no_goal": "ended (no checkable goal was set)",
                "no_scene": "ended before a scene graph was submitted"}[self.verdict]
        detail = f" ({self.goal_diff.summary()})" if self.goal_diff and not self.success else ""
        if self.asked_missing:  # no goal was set, but the user asked for something
            detail += f"; not done of {self.asked}: " + self._asked_text()
        text = (f"{text}{detail}; {self.steps} action(s) in {self.calls} call(s); "
                f"episode {self.episode_id} closed")
        if self.runs_on is not None:
            text += f"\nexecutor: {self.runs_on}"
        if self.final_graph is not None:
            text += "\n" + edges_line(self.final_graph, "final graph")
        return text


def end_episode(ctx: ToolContext, params: EpisodeRef) -> EpisodeVerdict:
    """Give the final verdict and close the episode (its id stops working)."""
    with ctx.store.use(params.episode_id) as episode:
        state = episode.state
        diff = check_goal(state, episode.goal) if state is not None and episode.goal else None
        verdict: Verdict
        asked_missing: list[str] = []
        asked: str | None = None
        if state is None:
            verdict = "no_scene"
        elif diff is None:
            verdict = "no_goal"
            asked, asked_missing = asked_against(episode)
        elif diff.satisfied:
            asked, asked_missing = asked_against(episode)
            verdict = "partial" if asked_missing else "goal_reached"
        elif episode.threshold_reached:
            verdict = "threshold_reached"
        else:
            verdict = "goal_not_reached"
        result = EpisodeVerdict(
            episode_id=episode.id, success=verdict == "goal_reached", verdict=verdict,
            final_graph=state.to_graph() if state is not None else None, goal=episode.goal,
            goal_diff=diff, executed=[a.text() for a in episode.executed],
            steps=len(episode.executed), calls=episode.calls, tau=episode.tau, t=episode.t,
            threshold_reached=episode.threshold_reached, trace=list(episode.trace),
            runs_on=runs_on(episode.executor, arm_mode_of(episode.world)),
            asked_missing=asked_missing, asked=asked if asked_missing else None)
        ctx.store.remove(episode.id)
        return result

