"""Scene images and scene graphs: render_scene, get_scene_image, generate_scene_graph,
submit_scene_graph.

Images come from the simulator when the episode has one, else from the photo the
episode was loaded from, else from a drawing of the graph. Scene-graph generation
works with any client: the agent's own vision model reads get_scene_image and answers
through submit_scene_graph; built-in perception plugs in when verigraph.perception
exists.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Literal

import numpy as np
from pydantic import AfterValidator, BaseModel, ConfigDict, Field, ValidationError, model_validator

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.goal import GraphDiff, check_goal, diff
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.submission import Rename, SubmittedGraph, check_submission
from verigraph.graph.wellformed import GraphProblem
from verigraph.prompts.filling import scene_graph_prompt
from verigraph.sim2d import TabletopWorld
from verigraph.sim2d.render import encode_png
from verigraph.tools.context import ToolContext
from verigraph.tools.drawing import draw_graph, render_caption
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.executors import SceneCheck, arm_setup_for, check_tangram_start
from verigraph.tools.fields import (
    DictionaryName,
    EpisodeId,
    ImageData,
    check_attrs_size,
    dictionary_for,
    with_dictionary_advice,
)
from verigraph.tools.images import KeptImage, decode_base64_image
from verigraph.tools.perceived import USER_LABELS, perceive_photo
from verigraph.tools.store import LiveEpisode
from verigraph.tools.texts import graph_lines

Width = Field(default=None, ge=64, le=2048,
              description="pixels; default: the scene's (drawings 640x480)")
Height = Field(default=None, ge=64, le=2048,
               description="pixels; omit to keep the scene's shape")


@dataclass(frozen=True)
class ImageResult:
    """An image tool's answer: PNG bytes and, for get_scene_image, the prompt to use."""

    png: bytes
    text: str | None = None
    mime_type: str = "image/png"


def _colors(state: WorldState) -> dict[str, str]:
    return {o.id: o.props.color for o in state.objects.values() if o.props.color}


def _picture(episode: LiveEpisode, width: int | None = None, height: int | None = None
             ) -> np.ndarray:
    """What a camera would show: simulator render, the loaded photo, or a drawing."""
    render = getattr(episode.world, "render", None)
    if callable(render):
        if isinstance(episode.world, TabletopWorld) and episode.state is not None and \
                episode.state.dictionary.user_labels:
            # Generic bodies (slab, open box, block) say little alone: name each object.
            # Built-in scenes stay unlabelled, as the perception tests see them.
            image = render(width=width, height=height, labels=True)
        else:
            image = render(width=width, height=height)
        return np.asarray(image, dtype=np.uint8)
    if isinstance(episode.image, KeptImage):
        return episode.image.array()
    state = episode.require_state()
    return draw_graph(state.to_graph(), width, height, title="scene graph (drawing)",
                      colors=_colors(state))


# -- render_scene ---------------------------------------------------------------------------
class RenderSceneInput(BaseModel):
    """Which episode to picture, and how large."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    view: Literal["current", "goal"] = Field(
        default="current", description="the current scene or the goal")
    width: int | None = Width
    height: int | None = Height


def render_scene(ctx: ToolContext, params: RenderSceneInput) -> ImageResult:
    """PNG of the current scene (simulator render when simulated) or of the goal graph."""
    with ctx.store.use(params.episode_id) as episode:
        goal_render = getattr(episode.goal_world, "render", None)
        if params.view == "goal" and callable(goal_render):
            image = np.asarray(goal_render(width=params.width, height=params.height),
                               dtype=np.uint8)
        elif params.view == "goal":
            goal = episode.goal
            if goal is None or goal.graph is None:
                what = " (a formula says what must hold, not one graph)" \
                    if goal is not None and goal.formula is not None else ""
                raise ToolArgumentError(f"this episode has no goal graph to draw{what}",
                                        field="view", value="goal",
                                        fix="call set_goal with a graph first, or use "
                                            "view=current")
            colors = _colors(episode.state) if episode.state is not None else {}
            image = draw_graph(goal.graph, params.width, params.height,
                               title="goal graph (drawing)", colors=colors)
        else:
            image = _picture(episode, params.width, params.height)
        world = episode.goal_world if params.view == "goal" else episode.world
        caption = render_caption(params.view, simulated=callable(getattr(world, "render", None)),
                                 photo=params.view == "current"
                                 and isinstance(episode.image, KeptImage))
    return ImageResult(png=encode_png(image), text=caption)


# -- get_scene_image ------------------------------------------------------------------------
class GetSceneImageInput(BaseModel):
    """The episode whose scene the agent should describe, and the task it serves."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    task: str | None = Field(default=None, max_length=4000,
                             description="what the graph is for")
    width: int | None = Width
    height: int | None = Height


def episode_dictionary(ctx: ToolContext, episode_id: str) -> Dictionary:
    """The dictionary an episode's scene is labelled with (the client's labels included)."""
    with ctx.store.use(episode_id) as episode:
        return (episode.state.dictionary if episode.state is not None
                else dictionary_for(episode.dictionary_name))


def get_scene_image(ctx: ToolContext, params: GetSceneImageInput) -> ImageResult:
    """The scene image plus the scene-graph generation prompt (D, R, task)."""
    with ctx.store.use(params.episode_id) as episode:
        image = _picture(episode, params.width, params.height)
        dictionary = (episode.state.dictionary if episode.state is not None
                      else dictionary_for(episode.dictionary_name))
        task = params.task or episode.instruction
        prompt = scene_graph_prompt(dictionary, task, episode_id=episode.id)
    return ImageResult(png=encode_png(image), text=prompt)


# -- submit_scene_graph ---------------------------------------------------------------------
def _small_attrs(graph: SubmittedGraph) -> SubmittedGraph:
    check_attrs_size(graph.nodes)
    return graph


class SubmitSceneGraphInput(BaseModel):
    """The agent's scene graph for an image, checked against D and R."""

    model_config = ConfigDict(extra="forbid")

    graph: Annotated[SubmittedGraph, AfterValidator(_small_attrs)] = Field(
        description="the graph you wrote")
    episode_id: EpisodeId | None = Field(
        default=None, description="image episodes adopt an accepted graph; "
                                  "others compare")
    dictionary: DictionaryName | None = Field(default=None, description="dictionary D to "
                                                                        "check against")


class SceneGraphSubmission(BaseModel):
    """Accepted or not, the normalised graph, every problem and every rename."""

    accepted: bool
    graph: SceneGraph = Field(description="the graph after normalisation")
    problems: list[GraphProblem]
    normalised: list[Rename] = Field(description="spellings that were mapped to canonical "
                                                 "ids, labels and relations")
    dictionary: str
    episode_id: str | None = None
    adopted: bool = Field(default=False, description="the episode now starts from this graph")
    diff_to_episode: GraphDiff | None = Field(
        default=None, description="how it differs from the episode's current graph")
    goal_diff: GraphDiff | None = None
    scene_check: SceneCheck | None = Field(
        default=None, description="arm episodes: whether the arm observes the scene as the "
                                  "adopted graph says")
    # When built-in perception cannot read the client's labels: the scene-graph prompt
    # for the client's own vision model.
    prompt: str | None = None

    def summary(self) -> str:
        if not self.accepted:
            lines = [f"REJECTED: {len(self.problems)} problem(s)"]
            lines += [f"- {p.field}: {p.message} (fix: {p.fix})" for p in self.problems[:20]]
            if len(self.problems) > 20:
                lines.append(f"- ... and {len(self.problems) - 20} more")
            if self.prompt is not None:
                lines.append(f"prompt for your vision model:\n{self.prompt}")
            return "\n".join(lines)
        text = f"accepted: {len(self.graph.nodes)} objects, {len(self.graph.edges)} edges"
        if not self.graph.nodes:
            text += (" (nothing recognised; the scene need not be empty: describe it with "
                     "get_scene_image and submit_scene_graph)")
        if self.normalised:
            text += f", {len(self.normalised)} name(s) normalised"
            read = [r.reading for r in self.normalised if r.reading][:20]
            if read:
                text += " (" + "; ".join(read) + ")"
        if self.adopted:
            text += f"; episode {self.episode_id} now starts from this graph"
            if self.scene_check is not None:
                text += f"; {self.scene_check.summary()}"
        elif self.diff_to_episode is not None:
            text += ("; matches the episode's graph" if self.diff_to_episode.satisfied else
                     "; differs from the episode's graph: "
                     + self.diff_to_episode.summary().removeprefix("goal not reached: "))
        return text + "\n" + graph_lines(self.graph) if self.graph.nodes else text


def submit_scene_graph(ctx: ToolContext, params: SubmitSceneGraphInput) -> SceneGraphSubmission:
    """Normalise and check the graph; an accepted graph starts an image episode."""
    if params.episode_id is None:
        dictionary = dictionary_for(params.dictionary or params.graph.dictionary)
        return _checked(params.graph, dictionary)
    with ctx.store.use(params.episode_id) as episode:
        name = params.dictionary or params.graph.dictionary or episode.dictionary_name
        dictionary = (episode.state.dictionary if episode.state is not None and name is None
                      else dictionary_for(name))
        result = _checked(params.graph, dictionary)
        result.episode_id = episode.id
        if not result.accepted:
            return result
        if episode.state is None:
            state = WorldState.from_graph(result.graph, dictionary)
            check_tangram_start(state)  # the start rule every executor shares
            if episode.executor.startswith("arm:"):  # the arm waited for this graph
                setup = arm_setup_for(episode.executor, ctx.config.arm)
                episode.world, episode.scene_check = ctx.arms.open(setup, state,
                                                                   ctx.store.evict_idle)
                result.scene_check = episode.scene_check
            episode.state = state
            episode.initial_graph = state.to_graph()
            result.adopted = True
            if episode.goal is not None:
                result.goal_diff = check_goal(state, episode.goal)
        else:
            submitted = WorldState.from_graph(result.graph, dictionary)
            result.diff_to_episode = diff(submitted, episode.state.to_graph())
        return result


def _checked(graph: SubmittedGraph, dictionary: Dictionary) -> SceneGraphSubmission:
    scene, renames, problems = check_submission(graph, dictionary)
    problems = with_dictionary_advice(scene, problems, dictionary.name)
    accepted = not problems
    if accepted:
        try:
            scene = SceneGraph.model_validate(scene.model_dump())
        except ValidationError as exc:  # limits such as label length
            err = exc.errors()[0]
            problems.append(GraphProblem(
                rule="invalid_value", node=None, field=".".join(map(str, err["loc"])),
                message=err["msg"], fix="shorten or correct the value"))
            accepted = False
    return SceneGraphSubmission(accepted=accepted, graph=scene, problems=problems,
                                normalised=renames, dictionary=dictionary.name)


# -- generate_scene_graph -------------------------------------------------------------------
class GenerateSceneGraphInput(BaseModel):
    """An image (or an episode's scene) to turn into a scene graph with built-in perception."""

    model_config = ConfigDict(extra="forbid")

    image: ImageData | None = None
    episode_id: EpisodeId | None = Field(default=None, description="use this episode's image")
    dictionary: DictionaryName | None = Field(default=None,
                                              description="dictionary D; default: the "
                                                          "episode's, else all")
    task: str | None = Field(default=None, max_length=4000, description="what the graph is for")

    @model_validator(mode="after")
    def _one_image(self) -> GenerateSceneGraphInput:
        if (self.image is None) == (self.episode_id is None):
            raise ValueError("give exactly one of image or episode_id")
        return self


def generate_scene_graph(ctx: ToolContext, params: GenerateSceneGraphInput
                         ) -> SceneGraphSubmission:
    """Built-in perception of an image, or of the episode's own picture at its default
    size (for a simulated tabletop, the size that keeps thin parts visible)."""
    dictionary = dictionary_for(params.dictionary)
    if params.image is not None:
        image = decode_base64_image(params.image)
    else:
        assert params.episode_id is not None
        with ctx.store.use(params.episode_id) as episode:
            if params.dictionary is None:  # the episode's own, with the client's labels
                dictionary = (episode.state.dictionary if episode.state is not None
                              else dictionary_for(episode.dictionary_name))
            if not callable(getattr(episode.world, "render", None)) and episode.image is None:
                raise ToolArgumentError(
                    f"episode {episode.id} has no photo and no simulator, so there is "
                    f"nothing to perceive (its graph came from {episode.source}); perceiving "
                    "a drawing of that graph would find no objects", field="episode_id",
                    value=episode.id, fix="pass image (a base64 photo of the scene), or "
                    "read the graph the episode already has with get_state")
            image = _picture(episode)
    perceived = perceive_photo(image, dictionary)
    submitted = SubmittedGraph.model_validate(perceived.graph.model_dump())
    out = _checked(submitted, dictionary)
    if not perceived.confident:  # a proposal for the agent to confirm, not a fact
        out.problems += perceived.doubts
        out.accepted = False
    if any(d.rule == USER_LABELS for d in perceived.doubts):
        out.prompt = scene_graph_prompt(dictionary, params.task, episode_id=params.episode_id)
    return out
