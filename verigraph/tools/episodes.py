"""Episode lifecycle tools: load_scene, set_goal, get_state, end_episode.

An episode is one run of Algorithm 1: a current graph, an optional goal, the actions
executed so far and the count tau of consecutive failed execute_actions calls.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from verigraph.actions.feedback import Violation
from verigraph.arm import ArmWorld
from verigraph.arm.models import RunMode
from verigraph.graph.goal import PREDICATES, Goal, GraphDiff, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.graph.wellformed import check_well_formed
from verigraph.tools import optional
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.executors import EXECUTOR_HELP, SceneCheck, arm_setup_for, check_executor
from verigraph.tools.fields import (
    BoundedGoal,
    BoundedGraph,
    DictionaryName,
    EpisodeId,
    ImageData,
    SceneId,
    builtin_scene,
    dictionary_for,
    problems_text,
    state_from_graph,
)
from verigraph.tools.images import decode_image
from verigraph.tools.perceived import perceive
from verigraph.tools.store import DEFAULT_K, DEFAULT_T, Episode, TraceEntry

Instruction = Field(default=None, max_length=4000,
                    description="the task in words, shown to planners (not checked by itself)")


# -- shared view ----------------------------------------------------------------------------
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
    relations: list[str]
    last_violation: Violation | None = Field(default=None,
                                             description="feedback of the last failed call")

    def summary(self) -> str:
        if self.graph is None:
            return (f"episode {self.episode_id}: waiting for a scene graph of its image "
                    "(get_scene_image, then submit_scene_graph)")
        edges = "; ".join(self.graph.sentences()) or "no edges"
        goal = "no goal" if self.goal_diff is None else self.goal_diff.summary()
        text = (f"episode {self.episode_id}: {len(self.graph.nodes)} objects ({edges}); {goal}; "
                f"{len(self.executed)} executed, tau={self.tau}/{self.t}, k={self.k}")
        if self.arm_mode is not None:
            text += f"; runs on {self.executor} ({self.arm_mode})"
        if self.scene_check is not None and not self.scene_check.matches:
            text += f"; {self.scene_check.summary()}"
        return text


def describe(episode: Episode) -> EpisodeState:
    state = episode.state
    diff = check_goal(state, episode.goal) if state is not None and episode.goal else None
    dictionary = state.dictionary if state is not None else None
    pending = episode.dictionary_name or "all"
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
        dictionary=dictionary.name if dictionary else pending,
        relations=list((dictionary or dictionary_for(pending)).relations),
        last_violation=episode.last_violation)


# -- load_scene -----------------------------------------------------------------------------
class GeneratorSpec(BaseModel):
    """Parameters of the sim2d scene generator."""

    model_config = ConfigDict(extra="forbid")

    family: str = Field(min_length=1, max_length=32,
                        description="scene family: blocks, kitchen, tableware or tangram")
    seed: int = Field(default=0, ge=0, le=2**31 - 1)
    n_objects: int | None = Field(default=None, ge=1, le=12,
                                  description="movable objects (default: drawn from the seed)")


class LoadSceneInput(BaseModel):
    """Start an episode from exactly one of: scene_id, graph, image, generator."""

    model_config = ConfigDict(extra="forbid")

    scene_id: SceneId | None = None
    graph: BoundedGraph | None = Field(default=None, description="a scene graph to start from")
    image: ImageData | None = Field(
        default=None, description="photo of the scene; without built-in perception the "
                                   "episode waits for submit_scene_graph")
    generator: GeneratorSpec | None = Field(default=None,
                                            description="generate a scene with sim2d")
    dictionary: DictionaryName | None = Field(
        default=None, description="dictionary D for an image or a graph that names none")
    goal: BoundedGoal | None = Field(default=None, description="goal now (else the built-in one, "
                                                        "or set_goal later)")
    instruction: str | None = Instruction
    simulate: bool = Field(default=False, description="also execute actions in the 2D "
                                                      "simulator (needs verigraph.sim2d); "
                                                      "the same as executor=sim2d")
    executor: str | None = Field(
        default=None, min_length=1, max_length=32,
        description=f"where actions run: {EXECUTOR_HELP}; default: the server's. An arm "
                    "episode uses the server's arm configuration (mode dry-run unless the "
                    "operator configured sim or real)")
    seed: int = Field(default=0, ge=0, le=2**31 - 1, description="simulator seed")
    k: int = Field(default=DEFAULT_K, ge=1, le=50, description="max actions per "
                                                               "execute_actions call")
    t: int = Field(default=DEFAULT_T, ge=1, le=100,
                   description="stop after t consecutive failed execute_actions calls")

    @model_validator(mode="after")
    def _one_source(self) -> LoadSceneInput:
        given = [n for n in ("scene_id", "graph", "image", "generator")
                 if getattr(self, n) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of scene_id, graph, image, generator "
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
    name = check_executor(params.executor)
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
    if params.generator is not None:
        spec = params.generator
        generated = optional.generate_scene()(spec.family, spec.seed, spec.n_objects)
        keep = executor == "sim2d"  # the generator always builds worlds; keep them for sim2d
        return _Source(f"generator:{spec.family}/seed={spec.seed}", generated.graph,
                       getattr(generated, "goal", None), generated.world if keep else None,
                       getattr(generated, "goal_world", None) if keep else None)
    assert params.image is not None
    image = decode_image(params.image)
    perceived: SceneGraph | None = None
    if optional.has("verigraph.perception", "perceive"):
        seen = perceive(image, dictionary_for(params.dictionary))
        perceived = seen.graph
        if not perceived.nodes or not seen.confident:
            # Built-in perception found nothing it knows, or is unsure: the agent's own
            # vision model may do better, so the episode waits for submit_scene_graph
            # instead of starting from an empty or doubtful scene.
            perceived = None
    return _Source("image", perceived, image=image)


def load_scene(ctx: ToolContext, params: LoadSceneInput) -> EpisodeState:
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
            world = optional.world_for_graph()(state.to_graph(), seed=params.seed)
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

    def make(episode_id: str) -> Episode:
        return Episode(id=episode_id, state=state, source=source.name, k=params.k, t=params.t,
                       goal=goal, instruction=params.instruction, world=world,
                       goal_world=source.goal_world, image=source.image,
                       dictionary_name=params.dictionary, executor=executor,
                       scene_check=scene_check,
                       initial_graph=state.to_graph() if state is not None else None)

    try:
        return describe(ctx.store.add(make))
    except BaseException:
        ctx.arms.close(world)  # e.g. the episode limit: do not keep the arm connected
        raise


def _with_dictionary(graph: SceneGraph, name: str | None) -> SceneGraph:
    if name is None:
        return graph
    if graph.dictionary is not None and graph.dictionary != name:
        raise ToolArgumentError(
            f"the graph names dictionary '{graph.dictionary}' but dictionary='{name}' was "
            "given", field="dictionary", value=name, fix="give only one of them")
    return graph.model_copy(update={"dictionary": name})


def stateless_source(ctx: ToolContext, *, episode_id: str | None, scene_id: str | None,
                     graph: SceneGraph | None, goal: Goal | None
                     ) -> tuple[WorldState, Goal | None]:
    """The state (a copy) and goal named by a stateless tool's source arguments.

    Exactly one of episode_id, scene_id and graph is set (the input models check it);
    an explicit goal wins over the episode's or the built-in scene's.
    """
    if episode_id is not None:
        with ctx.store.use(episode_id) as episode:
            return episode.require_state().copy(), goal or episode.goal
    if scene_id is not None:
        scene, builtin_goal = builtin_scene(scene_id)
        return state_from_graph(scene), goal or builtin_goal
    assert graph is not None
    return state_from_graph(graph), goal


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


# -- set_goal -------------------------------------------------------------------------------
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


# -- get_state ------------------------------------------------------------------------------
class EpisodeRef(BaseModel):
    """Just the episode."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId


def get_state(ctx: ToolContext, params: EpisodeRef) -> EpisodeState:
    with ctx.store.use(params.episode_id) as episode:
        return describe(episode)


# -- end_episode ----------------------------------------------------------------------------
Verdict = Literal["goal_reached", "goal_not_reached", "threshold_reached", "no_goal",
                  "no_scene"]


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

    def summary(self) -> str:
        text = {"goal_reached": "SUCCESS: goal reached",
                "goal_not_reached": "FAILURE: goal not reached",
                "threshold_reached": f"FAILURE: stopped after tau={self.tau} failed calls",
                "no_goal": "ended (no checkable goal was set)",
                "no_scene": "ended before a scene graph was submitted"}[self.verdict]
        detail = f" ({self.goal_diff.summary()})" if self.goal_diff and not self.success else ""
        return (f"{text}{detail}; {self.steps} action(s) in {self.calls} call(s); "
                f"episode {self.episode_id} closed")


def end_episode(ctx: ToolContext, params: EpisodeRef) -> EpisodeVerdict:
    """Give the final verdict and close the episode (its id stops working)."""
    with ctx.store.use(params.episode_id) as episode:
        state = episode.state
        diff = check_goal(state, episode.goal) if state is not None and episode.goal else None
        verdict: Verdict
        if state is None:
            verdict = "no_scene"
        elif diff is None:
            verdict = "no_goal"
        elif diff.satisfied:
            verdict = "goal_reached"
        elif episode.threshold_reached:
            verdict = "threshold_reached"
        else:
            verdict = "goal_not_reached"
        result = EpisodeVerdict(
            episode_id=episode.id, success=verdict == "goal_reached", verdict=verdict,
            final_graph=state.to_graph() if state is not None else None, goal=episode.goal,
            goal_diff=diff, executed=[a.text() for a in episode.executed],
            steps=len(episode.executed), calls=episode.calls, tau=episode.tau, t=episode.t,
            threshold_reached=episode.threshold_reached, trace=list(episode.trace))
        ctx.store.remove(episode.id)
        return result
