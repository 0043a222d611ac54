"""The state summary every episode tool answers with: what a planner needs to know now.

`describe` turns a stored episode into an `EpisodeState`; its `summary()` is the
one-line text form the tools and the episode resources show.
"""

from __future__ import annotations

from pydantic import BaseModel, Field

from verigraph.actions.feedback import Violation
from verigraph.arm import ArmWorld
from verigraph.arm.models import RunMode
from verigraph.graph.goal import Goal, GraphDiff, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.tools.executors import SceneCheck, executor_line
from verigraph.tools.fields import dictionary_for
from verigraph.tools.store import LiveEpisode
from verigraph.tools.texts import (
    defaults_line,
    dictionary_line,
    goal_line,
    graph_lines,
    sides_line,
)


class EpisodeState(BaseModel):
    """Everything a planner needs to know about an episode right now."""

    episode_id: str
    source: str = Field(description="where the scene came from")
    graph: SceneGraph | None = Field(description="current scene graph; null while waiting "
                                                 "for submit_scene_graph")
    goal: Goal | None
    instruction: str | None
    goal_satisfied: bool | None = Field(description="null when there is no checkable goal")
    goal_diff: GraphDiff | None
    executed: list[str] = Field(description="actions executed so far, in order")
    calls: int = Field(description="execute_actions calls so far")
    tau: int = Field(description="consecutive failed execute_actions calls")
    t: int = Field(description="threshold: the episode stops when tau reaches t")
    k: int = Field(description="at most k actions per execute_actions call")
    threshold_reached: bool
    simulated: bool = Field(description="actions also run in the 2D simulator")
    executor: str = Field(description="where actions run: graph (verification only), sim2d, "
                                      "or arm:<driver>")
    arm_mode: RunMode | None = Field(default=None, description="arm episodes: dry-run (records, "
                                 "moves nothing), sim, or real (the user confirms motions)")
    scene_check: SceneCheck | None = Field(
        default=None, description="arm episodes: whether the arm observed the scene as the "
                                  "graph says when the episode started")
    awaiting_scene_graph: bool
    dictionary: str
    # The client's own labels with their roles; every synonym or case normalisation of
    # a label the client wrote (`box read as block (synonym, blocks dictionary)`).
    user_labels: list[str] = Field(default_factory=list)
    label_readings: list[str] = Field(default_factory=list)
    relations: list[str]
    last_violation: Violation | None = Field(default=None,
                                             description="feedback of the last failed call")
    executors: str | None = Field(default=None, description="load_scene: the executors this "
                                  "server runs, and whether any reaches a robot")

    def summary(self) -> str:
        executor = executor_line(self.executor, self.arm_mode)
        if self.graph is None:
            return (f"episode {self.episode_id}: waiting for a scene graph of its image "
                    f"(get_scene_image, then submit_scene_graph)\n{executor}")
        goal = "no goal" if self.goal_diff is None else self.goal_diff.summary()
        text = (f"episode {self.episode_id}: {len(self.graph.nodes)} objects; {goal}; "
                f"{len(self.executed)} executed, tau={self.tau}/{self.t}, k={self.k} "
                "actions per execute_actions call (done not counted)")
        if self.scene_check is not None and not self.scene_check.matches:
            text += f"; {self.scene_check.summary()}"
        lines = [text, executor, self.executors, graph_lines(self.graph, self.dictionary),
                 defaults_line(self.graph, self.dictionary),
                 sides_line(self.graph, self.dictionary),
                 dictionary_line(self.dictionary, self.user_labels, self.label_readings),
                 goal_line(self.goal)]
        if self.last_violation is not None:
            lines.append(f"last refusal: {self.last_violation.text()}")
        return "\n".join(line for line in lines if line)


def describe_episode(episode: LiveEpisode) -> EpisodeState:
    state = episode.state
    diff = check_goal(state, episode.goal) if state is not None and episode.goal else None
    dictionary = state.dictionary if state is not None else None
    pending = dictionary_for(episode.dictionary_name)
    return EpisodeState(
        episode_id=episode.id, source=episode.source,
        graph=state.to_graph() if state is not None else None, goal=episode.goal,
        instruction=episode.instruction or (episode.goal.instruction if episode.goal else None),
        goal_satisfied=diff.satisfied if diff else None, goal_diff=diff,
        executed=[a.text() for a in episode.executed], calls=episode.calls, tau=episode.tau,
        t=episode.t, k=episode.k, threshold_reached=episode.threshold_reached,
        simulated=episode.executor == "sim2d", executor=episode.executor,
        arm_mode=episode.world.config.mode if isinstance(episode.world, ArmWorld) else None,
        scene_check=episode.scene_check, awaiting_scene_graph=state is None,
        dictionary=(dictionary or pending).name,
        user_labels=(dictionary or pending).user_lines(),
        relations=list((dictionary or pending).relations),
        last_violation=episode.last_violation)
