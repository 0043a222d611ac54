"""Per-step views: for each step of a plan (or of an episode's trace) the graph after it,
the edges it changed, its verdict with the violated constraint, blocking objects and
suggestion, and a drawing of the graph with the change highlighted and the blockers
outlined.

A plan is checked by the `validate_plan` tool function; an episode's trace is re-checked
the same way from its initial graph (the executed prefix plus the refused action), and
the violation the episode recorded wins for the refused step, because a simulator or
an arm can refuse what the graph allows. Simulated episodes add the simulator's picture
of every step (replayed on a copy of the world as loaded, see `frames`) and of the
current scene (the `render_scene` tool function).
"""

from __future__ import annotations

import base64
from typing import Annotated, Literal

import cv2
import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from verigraph.actions.feedback import Violation
from verigraph.actions.report import StepReport, ValidationReport
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d.render import encode_png
from verigraph.tools.acting import MAX_PLAN_ACTIONS, PlanText, ValidatePlanInput, validate_plan_tool
from verigraph.tools.context import ToolContext
from verigraph.tools.drawing import draw_graph
from verigraph.tools.fields import BoundedGraph, EpisodeId, SceneId
from verigraph.tools.goals import BoundedGoal, stateless_source
from verigraph.tools.registry import ToolSpec, argument_error
from verigraph.tools.scenes import RenderSceneInput, render_scene
from verigraph.viewer.frames import boxes, outline, step_frames

Role = Literal["fixed", "container", "surface", "object"]
RENDER_SIZE = (480, 360)
MAX_RENDERED_STEPS = 200  # later steps carry their graph but no picture (size of the answer)


class NodeRole(BaseModel):
    """How the viewer colours a node: fixed furniture, container, movable surface, object."""

    id: str
    label: str
    role: Role


class StepView(BaseModel):
    """One step: verdict, change, graph after it, and its picture (PNG data URL)."""

    step: int
    text: str
    ok: bool
    violation: Violation | None = None
    added: list[Edge] = Field(default_factory=list)
    removed: list[Edge] = Field(default_factory=list)
    outlined: list[str] = Field(default_factory=list, description="objects outlined in red: "
                                "the blocking ones, else those the refused action names")
    graph: SceneGraph = Field(description="the graph after this step (unchanged if refused)")
    render: str | None = Field(default=None, description="data:image/png;base64 drawing")
    scene_render: str | None = Field(default=None, description="the simulator's picture "
                                     "after this step (simulated episodes), blockers framed")


class EpisodeView(BaseModel):
    """Everything the viewer page shows for one plan or episode."""

    title: str
    source: Literal["plan", "episode"]
    episode_id: str | None = None
    roles: list[NodeRole]
    initial_graph: SceneGraph
    initial_render: str
    steps: list[StepView]
    not_checked: int = Field(description="actions after the first violation, not checked")
    valid: bool
    goal_reached: bool | None
    goal_summary: str | None = None
    scene_render: str | None = Field(default=None, description="the simulator's render of "
                                                               "the current scene, if any")
    initial_scene_render: str | None = Field(default=None, description="the simulator's "
                                             "picture of the scene as loaded, if replayed")

    def summary(self) -> str:
        refused = [s for s in self.steps if not s.ok]
        text = f"{'VALID' if self.valid else 'INVALID'}: {len(self.steps)} step(s)"
        if refused and refused[0].violation is not None:
            text += f"; step {refused[0].step} refused: {refused[0].violation.constraint}"
        return text


class ViewInput(BaseModel):
    """An episode (its trace), or a plan on a scene (like validate_plan)."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId | None = Field(default=None, description="show this episode's "
                                         "trace; with plan: check the plan from its graph")
    plan: PlanText | Annotated[list[str | dict[str, object]], Field(
        max_length=MAX_PLAN_ACTIONS)] | None = Field(
        default=None, description="plan text (one action per line) or a list of actions")
    scene_id: SceneId | None = Field(default=None, description="with plan: a built-in "
                                     "scene to check it on (see list_scenes)")
    graph: BoundedGraph | None = Field(default=None, description="with plan: your scene "
                                       "graph to check it on, as load_scene takes it")
    goal: BoundedGoal | None = Field(default=None, description="with plan: check the final "
                                     "graph against this goal")

    @model_validator(mode="after")
    def _something_to_show(self) -> ViewInput:
        if self.plan is None and self.episode_id is None:
            raise ValueError("give an episode_id, or a plan with scene_id or graph")
        return self


def view(ctx: ToolContext, params: ViewInput) -> EpisodeView:
    """The view for an episode's trace, or for a plan on a scene."""
    if params.plan is None:
        assert params.episode_id is not None
        return episode_view(ctx, params.episode_id)
    try:  # the plan's actions are checked here, in full (ViewInput keeps them loose)
        checked = ValidatePlanInput.model_validate(params.model_dump(exclude_none=True))
    except ValidationError as exc:
        raise argument_error(VIEW_SPEC, exc) from None
    return plan_view(ctx, checked)


def plan_view(ctx: ToolContext, params: ValidatePlanInput, title: str = "plan check"
              ) -> EpisodeView:
    """Check the plan with the validate_plan tool function and lay it out per step."""
    report = validate_plan_tool(ctx, params)
    state, _ = stateless_source(ctx, episode_id=params.episode_id, scene_id=params.scene_id,
                                graph=params.graph)
    return _assemble(title, "plan", state, report)


def episode_view(ctx: ToolContext, episode_id: str) -> EpisodeView:
    """The episode's trace from its initial graph: executed steps, then the refused one."""
    with ctx.store.use(episode_id) as episode:
        state = episode.require_state()
        initial = episode.initial_graph or state.to_graph()
        executed = [a.text() for a in episode.executed]
        last = episode.trace[-1] if episode.trace else None
        refused, failed = None, False
        if last is not None and last.violation is not None:
            if last.violation.constraint == "execution_failed" or \
                    len(last.executed) >= len(last.proposed):
                failed = bool(last.executed)  # executed, but the world ended otherwise
            else:
                refused = last.proposed[len(last.executed)]
        recorded = episode.last_violation if refused is not None or failed else None
        goal = episode.goal
        simulated = callable(getattr(episode.world, "render", None))
        initial_world = episode.initial_world if simulated else None
        executed_actions = list(episode.executed)
        source = episode.source
    start = WorldState.from_graph(initial, state.dictionary)
    # Only the executed prefix is checked again (it was applied, so it parses and passes);
    # the refused action is shown from what the episode recorded, whatever it named.
    report = validate_plan_tool(ctx, ValidatePlanInput(plan="\n".join(executed) or "done",
                                                  graph=initial, goal=goal))
    if refused is not None:
        stored = recorded or (last.violation if last is not None else None)
        assert stored is not None  # a refused step is one with a recorded violation
        violation = stored.model_copy(update={"step": len(executed) + 1})
        report.steps.append(StepReport(step=len(executed) + 1, ok=False, text=refused,
                                       violation=violation, action=violation.action))
        report.violations = [violation]
        report.valid = report.plan_valid = False
    elif recorded is not None and report.steps and report.steps[-1].ok:
        last_step = report.steps[-1]  # executed, but the simulator or arm ended otherwise
        report.steps[-1] = last_step.model_copy(update={"ok": False, "violation": recorded})
        report.valid = report.plan_valid = False
    result = _assemble(f"episode ({source})", "episode", start, report)
    result.episode_id = episode_id
    if simulated:
        png = render_scene(ctx, RenderSceneInput(episode_id=episode_id)).png
        outlined = result.steps[-1].outlined if result.steps and not result.steps[-1].ok \
            else []
        result.scene_render = _data_url(_outline_simulated(ctx, episode_id, png, outlined))
    if initial_world is not None:
        first, frames = step_frames(initial_world, executed_actions,
                                    [s.outlined for s in result.steps])
        result.initial_scene_render = _data_url(first)
        for step, frame in zip(result.steps, frames, strict=False):
            step.scene_render = _data_url(frame)
    return result


def _outline_simulated(ctx: ToolContext, episode_id: str, png: bytes, ids: list[str]
                       ) -> bytes:
    """The simulator's render with the objects that block the refused step framed in red."""
    with ctx.store.use(episode_id) as episode:
        framed = boxes(episode.world)
    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)
    if not ids or not framed or image is None:
        return png
    return encode_png(outline(image, framed, ids))


def _data_url(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def _picture(graph: SceneGraph, colors: dict[str, str], title: str,
             added: list[Edge] | None = None, outline: list[str] | None = None) -> str:
    image = draw_graph(graph, *RENDER_SIZE, title=title, colors=colors,
                       highlight=added or (), outline=outline or ())
    return _data_url(encode_png(image))


def _outlined(violation: Violation, action: dict[str, object]) -> list[str]:
    """Who to outline for a refused step: the blocking objects, else the objects the
    action names (a fixed object, a target that is not a surface)."""
    if violation.blocking:
        return list(violation.blocking)
    return [str(action[k]) for k in ("object", "target") if isinstance(action.get(k), str)]


def _role(state: WorldState, node_id: str) -> Role:
    props = state.objects[node_id].props
    if not props.movable:
        return "fixed"
    if props.container:
        return "container"
    return "surface" if props.surface else "object"


def _assemble(title: str, source: Literal["plan", "episode"], state: WorldState,
              report: ValidationReport) -> EpisodeView:
    colors = {o.id: o.props.color for o in state.objects.values() if o.props.color}
    roles = [NodeRole(id=o.id, label=o.label, role=_role(state, o.id))
             for o in state.objects.values()]
    graph = state.to_graph()
    initial = graph
    steps: list[StepView] = []
    for index, step in enumerate(report.steps):
        added = list(step.edit.added) if step.edit else []
        removed = list(step.edit.removed) if step.edit else []
        if step.ok:
            gone = {(e.source, e.relation, e.target) for e in removed}
            kept = [e for e in graph.edges if (e.source, e.relation, e.target) not in gone]
            graph = graph.model_copy(update={"edges": kept + added})
            if step.edit is not None and step.edit.states:  # open, close, toggle_on/off
                after: dict[str, dict[str, bool]] = {}
                for change in step.edit.states:
                    after.setdefault(change.object, {})[change.key] = change.after
                graph = graph.model_copy(update={"nodes": [
                    n.model_copy(update={"state": {**n.state, **after[n.id]}})
                    if n.id in after else n for n in graph.nodes]})
        blocking = _outlined(step.violation, step.action) if step.violation else []
        verdict = f"refused: {step.violation.constraint}" if step.violation else "ok"
        render = (_picture(graph, colors, f"step {step.step}: {step.text} ({verdict})"[:90],
                           added, blocking) if index < MAX_RENDERED_STEPS else None)
        steps.append(StepView(step=step.step, text=step.text, ok=step.ok,
                              violation=step.violation, added=added, removed=removed,
                              outlined=blocking, graph=graph, render=render))
    return EpisodeView(
        title=title, source=source, roles=roles, initial_graph=initial,
        initial_render=_picture(initial, colors, "initial scene"), steps=steps,
        not_checked=report.not_checked, valid=report.valid, goal_reached=report.goal_reached,
        goal_summary=report.goal_diff.summary() if report.goal_diff else None)


VIEW_SPEC = ToolSpec(
    "view_episode", "Episode view (viewer only)",
    "For the episode viewer: per-step graphs, drawings and verdicts of an episode's trace "
    "(episode_id) or of a plan on a scene (plan with scene_id, graph or episode_id).",
    ViewInput, EpisodeView, lambda ctx, params: view(ctx, params), read_only=True,
    idempotent=True)
