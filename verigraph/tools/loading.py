"""Where an episode's scene comes from: the load_scene tool.

A scene is a built-in scene id, a graph, a photo (read by built-in perception, or
waiting for submit_scene_graph) or a generated sim2d scene. Nothing is stored unless
the whole input is valid.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, model_validator

from verigraph.graph.bddl_problem import MAX_TEXT as MAX_BDDL_CHARS
from verigraph.graph.bddl_problem import import_problem
from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, InlineDictionary
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import label_readings
from verigraph.sim2d import SimWorld, generate_scene, world_for_graph
from verigraph.sim2d.persist import world_state
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.executors import (
    EXECUTOR_HELP,
    SceneCheck,
    arm_setup_for,
    check_executor,
    check_tangram_start,
    enabled_executors,
    executors_text,
)
from verigraph.tools.fields import (
    BoundedGraph,
    DictionaryName,
    ImageData,
    SceneId,
    builtin_scene,
    dictionary_for,
    state_from_graph,
)
from verigraph.tools.goals import BoundedGoal, Instruction, check_goal_against
from verigraph.tools.images import decode_base64_image
from verigraph.tools.perceived import perceive_photo
from verigraph.tools.request import ASKED
from verigraph.tools.store import DEFAULT_K, DEFAULT_THRESHOLD, LiveEpisode
from verigraph.tools.summaries import EpisodeState, describe_episode


class GeneratorSpec(BaseModel):
    """Parameters of the sim2d scene generator."""

    model_config = ConfigDict(extra="forbid")

    family: str = Field(min_length=1, max_length=32,
                        description="blocks, kitchen, tableware or tangram")
    seed: int = Field(default=0, ge=0, le=2**31 - 1)
    n_objects: int | None = Field(default=None, ge=1, le=12,
                                  description="movable objects (default: from seed)")


class LoadSceneInput(BaseModel):
    """Start an episode from exactly one of: scene_id, graph, image, generator, bddl."""

    model_config = ConfigDict(extra="forbid")

    scene_id: SceneId | None = Field(default=None, description="built-in scene id")
    graph: BoundedGraph | None = Field(default=None, description="a scene graph to start from")
    image: ImageData | None = Field(
        default=None, description="photo (no object found: call "
                                   "submit_scene_graph)")
    generator: GeneratorSpec | None = Field(default=None,
                                            description="generate a scene with sim2d")
    bddl: str | None = Field(
        default=None, min_length=1, max_length=MAX_BDDL_CHARS,
        description="BEHAVIOR-1K problem text (BDDL): its scene and goal formula")
    dictionary: DictionaryName | None = Field(
        default=None, description=f"for image/graph: {', '.join(BUILTIN_DICTIONARIES)}, "
                                  "all or yours {extends, objects: {label: {surface, "
                                  "container, capacity}}}")
    goal: BoundedGoal | None = Field(default=None, description="else the built-in one, or set_goal "
                                                        "later")
    instruction: str | None = Instruction
    simulate: bool = Field(default=False, description="same as executor=sim2d")
    executor: str | None = Field(
        default=None, min_length=1, max_length=32,
        description=f"{EXECUTOR_HELP}; default: the server's")
    seed: int = Field(default=0, ge=0, le=2**31 - 1, description="simulator seed")
    k: int = Field(default=DEFAULT_K, ge=1, le=50, description="max actions per "
                                                               "execute_actions call")
    t: int = Field(default=DEFAULT_THRESHOLD, ge=1, le=100,
                   description="stop after t failed calls in a row")

    @model_validator(mode="after")
    def _one_source(self) -> LoadSceneInput:
        given = [n for n in ("scene_id", "graph", "image", "generator", "bddl")
                 if getattr(self, n) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of scene_id, graph, image, generator, bddl "
                             f"(got {', '.join(given) or 'none'})")
        return self


@dataclass
class _Source:
    """What a load_scene source yields before it is checked and stored."""

    name: str
    graph: SceneGraph | None = None
    goal: Goal | None = None
    world: Any = None
    goal_world: Any = None
    image: Any = None


def choose_executor(ctx: ToolContext, params: LoadSceneInput) -> str:
    """The call's executor, else simulate=true (sim2d), else the server's default."""
    if params.executor is None:
        return "sim2d" if params.simulate else ctx.config.executor
    name = check_executor(params.executor,
                          enabled=enabled_executors(ctx.config.executor, ctx.config.arm))
    if params.simulate and name != "sim2d":
        raise ToolArgumentError(f"simulate=true runs the 2D simulator, but executor={name}",
                                field="simulate", value=True,
                                fix="give only executor, or only simulate=true")
    return name


def _read_source(params: LoadSceneInput, executor: str) -> _Source:
    if params.scene_id is not None:
        graph, goal = builtin_scene(params.scene_id)
        return _Source(f"scene_id:{params.scene_id}", graph, goal)
    if params.graph is not None:
        return _Source("graph", params.graph)
    if params.bddl is not None:  # refused whole (naming the predicate) or loaded whole
        imported = import_problem(params.bddl)
        return _Source(f"bddl:{imported.activity}", imported.scene_graph(),
                       Goal(formula=imported.formula))
    if params.generator is not None:
        spec = params.generator
        generated = generate_scene(spec.family, spec.seed, spec.n_objects)
        keep = executor == "sim2d"  # the generator always builds worlds; keep them for sim2d
        return _Source(f"generator:{spec.family}/seed={spec.seed}", generated.graph,
                       getattr(generated, "goal", None), generated.world if keep else None,
                       getattr(generated, "goal_world", None) if keep else None)
    assert params.image is not None
    image = decode_base64_image(params.image)
    seen = perceive_photo(image, dictionary_for(params.dictionary))
    # Built-in perception found nothing it knows, or is unsure: the agent's own vision
    # model may do better, so the episode waits for submit_scene_graph instead of
    # starting from an empty or doubtful scene.
    confident = seen.graph.nodes and seen.confident
    return _Source("image", seen.graph if confident else None, image=image)


def load_scene_tool(ctx: ToolContext, params: LoadSceneInput) -> EpisodeState:
    """Create an episode; nothing is stored unless the whole input is valid.

    An arm episode opens (and, unless dry-run, connects) its arm last, after every other
    check, and compares what the arm observes with the graph. An image episode gets its
    arm when its scene graph is submitted.
    """
    executor = choose_executor(ctx, params)
    source = _read_source(params, executor)
    goal = params.goal or source.goal
    state: WorldState | None = None
    world = source.world
    if source.graph is not None:
        state = state_from_graph(_with_dictionary(source.graph, params.dictionary))
        if executor == "sim2d" and world is None:
            world = world_for_graph(state.to_graph(), seed=params.seed)
        elif world is None:
            check_tangram_start(state)  # the rule sim2d's layout applies, for every executor
        if goal is not None:
            check_goal_against(goal, state, field="goal")
    elif executor == "sim2d":
        field = "simulate" if params.simulate else "executor"
        raise ToolArgumentError("the 2D simulator needs a scene graph, but an image has none "
                                "yet", field=field, value=True if params.simulate else executor,
                                fix="load with executor graph, or pass the graph instead")
    scene_check: SceneCheck | None = None
    if executor.startswith("arm:"):
        setup = arm_setup_for(executor, ctx.config.arm)
        if state is not None:
            world, scene_check = ctx.arms.open(setup, state, ctx.store.evict_idle)

    def make(episode_id: str) -> LiveEpisode:
        return LiveEpisode(id=episode_id, state=state, source=source.name, k=params.k, t=params.t,
                       goal=goal, instruction=params.instruction, world=world,
                       goal_world=source.goal_world, image=source.image,
                       dictionary_name=params.dictionary, executor=executor,
                       scene_check=scene_check,
                       initial_graph=state.to_graph() if state is not None else None,
                       initial_world=world_state(world) if isinstance(world, SimWorld)
                       else None,
                       extras={ASKED: params.instruction} if params.instruction else {})

    try:
        out = describe_episode(ctx.store.add(make))
    except BaseException:
        ctx.arms.close(world)  # e.g. the episode limit: do not keep the arm connected
        raise
    if state is not None and source.graph is not None:
        out.label_readings = label_readings(source.graph, state.dictionary)
    out.executors = executors_text(ctx.config.executor, ctx.config.arm)
    return out


def _with_dictionary(graph: SceneGraph, name: str | InlineDictionary | None) -> SceneGraph:
    if name is None:
        return graph
    if graph.dictionary is not None and graph.dictionary != name:
        raise ToolArgumentError(
            "the graph names a dictionary and another one was given in `dictionary`",
            field="dictionary", value=None, fix="give only one of them")
    return graph.model_copy(update={"dictionary": name})
