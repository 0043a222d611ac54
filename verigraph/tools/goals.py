"""Goals: the set_goal tool and the check every goal passes before it is stored.

A goal graph must be well formed and name only objects of the scene; an image goal is
read by built-in perception. An invalid goal changes nothing.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from verigraph.graph.goal import PREDICATES, Goal, GraphDiff, check_goal
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import check_well_formed
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.fields import (
    BoundedGraph,
    EpisodeId,
    ImageData,
    dictionary_for,
    problems_text,
)
from verigraph.tools.images import decode_image
from verigraph.tools.perceived import perceive

Instruction = Field(default=None, max_length=4000,
                    description="the task in words (shown, not checked)")


def check_goal_against(goal: Goal, state: WorldState | None, *, field: str) -> None:
    """A goal graph must be well formed and name only objects of the scene."""
    if goal.graph is None:
        return
    dictionary = state.dictionary if state is not None else dictionary_for(goal.graph.dictionary)
    problems = check_well_formed(goal.graph, dictionary, partial=goal.partial)
    if problems:
        raise ToolArgumentError(
            f"the goal graph breaks {len(problems)} rule(s):\n"
            + problems_text(problems, f"{field}.graph"), field=f"{field}.graph", value=None,
            fix="correct every listed problem and send the goal again")
    if state is None:
        return
    goal_ids = set(goal.graph.node_ids())
    unknown = sorted(goal_ids - set(state.objects))
    if unknown:
        raise ToolArgumentError(
            f"the goal names objects that are not in the scene: {', '.join(unknown)}",
            field=f"{field}.graph.nodes", value=unknown[0],
            fix=f"use ids from the scene: {', '.join(sorted(state.objects))}")
    absent = sorted(set(state.objects) - goal_ids)
    if absent and not goal.partial:
        raise ToolArgumentError(
            f"a full goal must list every object of the scene; missing: {', '.join(absent)}",
            field=f"{field}.graph.nodes", value=absent[0],
            fix="add the missing objects with their goal supports, or set partial=true to "
                "require only the listed edges")


class SetGoalInput(BaseModel):
    """A goal graph, a predicate, a reference image, or just an instruction."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    graph: BoundedGraph | None = Field(default=None, description="goal scene graph")
    partial: bool = Field(default=False, description="only the listed edges must hold")
    predicate: Literal["single_stack"] | None = Field(
        default=None, description="single_stack: every movable object in one tower")
    image: ImageData | None = Field(default=None, description="reference image of the goal "
                                                              "(needs built-in perception)")
    instruction: str | None = Instruction

    @model_validator(mode="after")
    def _something(self) -> SetGoalInput:
        if not any(v is not None for v in (self.graph, self.predicate, self.image,
                                           self.instruction)):
            raise ValueError("give a goal: graph, predicate, image or instruction")
        if self.image is not None and self.graph is not None:
            raise ValueError("give either graph or image, not both")
        return self


class GoalOutput(BaseModel):
    """The episode's goal after set_goal and how far the current graph is from it."""

    episode_id: str
    goal: Goal | None
    instruction: str | None
    checkable: bool = Field(description="false when only an instruction was given")
    goal_satisfied: bool | None
    goal_diff: GraphDiff | None

    def summary(self) -> str:
        if not self.checkable:
            return ("instruction recorded; it is not checkable by itself: give a goal graph "
                    "or a predicate (" + ", ".join(PREDICATES) + ") to verify it")
        if self.goal_diff is None:
            return "goal set; it will be checked once the scene graph is submitted"
        return f"goal set; {self.goal_diff.summary()}"


def set_goal(ctx: ToolContext, params: SetGoalInput) -> GoalOutput:
    """Replace the goal (or record an instruction); an invalid goal changes nothing."""
    graph = params.graph
    image = decode_image(params.image) if params.image is not None else None
    with ctx.store.use(params.episode_id) as episode:
        if image is not None:
            dictionary = (episode.state.dictionary if episode.state
                          else dictionary_for(episode.dictionary_name))
            seen = perceive(image, dictionary)
            if not seen.confident:
                raise ToolArgumentError(
                    "built-in perception is unsure of the goal image: "
                    + "; ".join(d.message for d in seen.doubts[:5]),
                    field="image", value=None,
                    fix="give the goal as a graph (generate_scene_graph returns the "
                        "perceived proposal to check and correct)")
            graph = seen.graph
        goal: Goal | None = None
        if graph is not None or params.predicate is not None:
            goal = Goal(graph=graph, partial=params.partial, predicate=params.predicate,
                        instruction=params.instruction)
            check_goal_against(goal, episode.state, field="goal" if graph is None else "graph")
        if goal is not None:
            episode.goal = goal
        if params.instruction is not None:
            episode.instruction = params.instruction
        goal = episode.goal
        diff = check_goal(episode.state, goal) if goal and episode.state is not None else None
        return GoalOutput(episode_id=episode.id, goal=goal,
                          instruction=episode.instruction, checkable=goal is not None,
                          goal_satisfied=diff.satisfied if diff else None, goal_diff=diff)
