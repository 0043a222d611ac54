"""The tool table: names, models, annotations and summaries, in one fixed order.

The MCP server, the CLI and the library all read this table, so a tool is defined
once. `Toolbox.call(name, arguments)` is the transport-free entry point: it validates
raw arguments with the tool's input model (reporting every problem with its field and
fix) and runs the tool.
"""

from __future__ import annotations

import difflib
import json
import logging
import random
import reprlib
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal, Protocol

from pydantic import BaseModel, ValidationError

from verigraph.actions.report import ValidationReport
from verigraph.graph.bulk import collector_paused, graph_items
from verigraph.tools import acting, arm, episodes, goals, loading, scenes, solving, summaries
from verigraph.tools.context import ToolConfig, ToolContext
from verigraph.tools.errors import InvalidArgumentsError, StaleEpisodeError, ToolArgumentError
from verigraph.tools.scenes import ImageResult

# Where a server runs a tool's call (see verigraph.server.tools):
#   inline:     on the event loop, unless its input (`heavy_when`) or episode are large;
#   heavy:      always a heavy call (worker thread, budget, the client's share);
#   thread:     a worker thread outside the heavy queue (the arm's controls answer mid-motion);
#   own_thread: a thread of its own for each call, waiting on nothing (arm_stop).
Lane = Literal["inline", "heavy", "thread", "own_thread"]
# Where an MCP host shows a tool (the MCP Apps `visibility`): to the model, to apps.
Visibility = Literal["model", "app"]

BIG_GRAPH_ITEMS = 300  # nodes or edges of a graph (or a goal's graph)
BIG_PLAN_ITEMS = 100
BIG_PLAN_CHARS = 2000
BIG_IMAGE_CHARS = 100_000


def _field(obj: Any, name: str) -> Any:
    return obj.get(name) if isinstance(obj, dict) else getattr(obj, name, None)


def _big_graph(value: Any) -> bool:
    """A graph, or a goal holding one, of more than BIG_GRAPH_ITEMS nodes or edges."""
    for graph in (value, _field(value, "graph")):
        if any(isinstance(items := _field(graph, key), list) and len(items) > BIG_GRAPH_ITEMS
               for key in ("nodes", "edges")):
            return True
    return False


def _big_plan(value: Any) -> bool:
    return (isinstance(value, str) and len(value) > BIG_PLAN_CHARS) or (
        isinstance(value, list) and len(value) > BIG_PLAN_ITEMS)


@dataclass(frozen=True)
class HeavyWhen:
    """Which of a tool's own inputs make one of its calls heavy (a worker thread within
    the call's budget, never the event loop): any value at all in `given` (an image to
    decode, a scene to generate, the simulator, a PDDL text to explain), or a large
    value in `graphs` (more than 300 nodes or edges), `plans` (more than 100 actions or
    2,000 characters) or `images` (more than 100,000 characters). Reads raw JSON
    arguments and validated input alike."""

    given: tuple[str, ...] = ()
    graphs: tuple[str, ...] = ()
    plans: tuple[str, ...] = ()
    images: tuple[str, ...] = ()

    def large(self, arguments: Any) -> bool:
        """Whether checking the arguments alone would hold an event loop (their size)."""
        return any(_big_graph(_field(arguments, name)) for name in self.graphs) or any(
            _big_plan(_field(arguments, name)) for name in self.plans) or any(
            isinstance(image := _field(arguments, name), str) and len(image) > BIG_IMAGE_CHARS
            for name in self.images)

    def __call__(self, arguments: Any) -> bool:
        """Whether running the call could hold an event loop for long."""
        return any(_field(arguments, name) for name in self.given) or self.large(arguments)


@dataclass(frozen=True)
class Confirmation:
    """A tool that can make a real arm act asks the user first: what it would ask
    (None: nothing to ask for this call) and what stays true when the answer is no."""

    preview: Callable[[ToolContext, Any], arm.ArmQuestion | None]
    unchanged: str


class Summary(Protocol):
    """A tool's text from its result. `data`, where the server has it, is the result as
    the structured content sends it (JSON-ready, dumped once for both), so a text
    rendered from the result's data reads that dict rather than dumping the model again;
    None when the structured content goes as bytes (a large HTTP body) or the caller
    has only the result."""

    def __call__(self, result: Any, data: dict[str, Any] | None = None, /) -> str: ...


@dataclass(frozen=True)
class ToolSpec:
    """One tool: what it takes, what it returns, how it behaves, how to summarise it,
    and how a server runs it (lane, confirmation, viewer), so a tool is one entry."""

    name: str
    title: str
    description: str
    input_model: type[BaseModel]
    output_model: type[BaseModel] | None  # None: an image tool (MCP image content only)
    run: Callable[[ToolContext, Any], Any]
    read_only: bool
    destructive: bool = False
    idempotent: bool = False
    open_world: bool = False  # may reach outside the server: a robot arm and its controller
    summary: Summary = lambda result, data=None: str(result.summary())
    lane: Lane = "inline"
    opens_world: bool = False  # heavy when the server's default executor is not the graph
    episode_sized: bool = True  # its work grows with the episode's graph (heavy if large)
    confirmation: Confirmation | None = None  # asks the user before a real arm acts
    moves_arm: bool = False  # the arm stops when the call is cancelled (deadman)
    viewer: bool = False  # links the MCP Apps episode viewer (`_meta.ui`)
    heavy_when: HeavyWhen = HeavyWhen()  # inputs that make an inline tool's call heavy
    visibility: tuple[Visibility, ...] = ("model", "app")  # ("app",): only apps may call it


TOOL_SPECS: tuple[ToolSpec, ...] = (
    ToolSpec("load_scene", "Start an episode",
             "Start an episode (scene_id, graph, image, sim2d generator or BDDL problem): "
             "episode_id, executors, robot or none. Node attrs (movable, surface, container, "
             'capacity, width), e.g. {"container":true}, beat built-in defaults, give your '
             "label a role.",
             loading.LoadSceneInput, summaries.EpisodeState, loading.load_scene_tool,
             read_only=False, open_world=True, opens_world=True,
             heavy_when=HeavyWhen(given=("image", "generator", "bddl", "simulate", "executor"),
                                  graphs=("graph", "goal"), images=("image",))),
    ToolSpec("set_goal", "Set the goal",
             "Set the goal: edges ('cup on table; spoon in pot'), a BDDL formula, a graph (a "
             "node's state, e.g. {\"open\": false}, is a goal too), a predicate or an image. "
             "Words alone: a proposal to confirm.",
             goals.SetGoalInput, goals.GoalOutput, goals.set_goal,
             read_only=False, idempotent=True,
             heavy_when=HeavyWhen(given=("image",), graphs=("graph",), images=("image",))),
    ToolSpec("get_state", "Episode state",
             "Current graph, goal and its difference, executed actions, tau (consecutive "
             "failed calls), k and t.",
             episodes.EpisodeRef, summaries.EpisodeState, episodes.get_state,
             read_only=True, idempotent=True, viewer=True),
    ToolSpec("validate_action", "Check one action",
             "Check one action without executing it: every violated constraint with a fix, or "
             "the edges it would change. A moved object must be clear (nothing on, in, under "
             "or next to it) and not in a closed container; `in` needs an open container with "
             "room, `on` a surface with room; open/close need an openable object (no state: "
             "closed), toggle_on/off a toggleable one (no state: off).",
             acting.ValidateActionInput, acting.ActionCheck, acting.validate_action_tool,
             read_only=True, idempotent=True, episode_sized=False),
    ToolSpec("execute_actions", "Execute actions",
             "Execute up to k actions (done not counted) until the first violation; the valid "
             "prefix stays. move(x, on|in, y): x movable, clear (nothing on/in it); y a "
             "surface/container with room. Returns graph, feedback with a fix, "
             "tau, goal check, executor (graph, sim2d: nothing physical moves; a real arm "
             "asks first). End with done.",
             acting.ExecuteActionsInput, acting.ExecutionOutput, acting.execute_actions,
             read_only=False, destructive=True, open_world=True, viewer=True, moves_arm=True,
             confirmation=Confirmation(arm.preview_execute,
                                       "nothing moved and the episode is unchanged")),
    ToolSpec("validate_plan", "Validate a whole plan",
             "Stateless: check a whole plan from a scene_id, graph or episode, optionally "
             "against a goal. Per-step report.",
             acting.ValidatePlanInput, ValidationReport, acting.validate_plan_tool,
             read_only=True, idempotent=True, summary=acting.report_summary, viewer=True,
             heavy_when=HeavyWhen(given=("pddl",), graphs=("graph", "goal"), plans=("plan",))),
    ToolSpec("check_goal", "Check the goal",
             "Missing and extra edges and objects between the episode's graph and its goal (or"
             " one given here).",
             acting.CheckGoalInput, acting.GoalCheck, acting.check_goal_tool,
             read_only=True, idempotent=True, heavy_when=HeavyWhen(graphs=("goal",))),
    ToolSpec("generate_scene_graph", "Perceive a scene graph",
             "Built-in perception: image (given or the episode's) -> scene graph. Else: "
             "get_scene_image, then submit_scene_graph.",
             scenes.GenerateSceneGraphInput, scenes.SceneGraphSubmission,
             scenes.generate_scene_graph, read_only=True, idempotent=True,
             lane="heavy", heavy_when=HeavyWhen(images=("image",))),
    ToolSpec("render_scene", "Render the scene",
             "PNG: the simulator's render, else a diagram of the graph (pictures need "
             "simulate=true); view=goal: the goal.",
             scenes.RenderSceneInput, None, scenes.render_scene,
             read_only=True, idempotent=True, lane="heavy", viewer=True),
    ToolSpec("solve", "Reference plan",
             "A reference plan by search, re-checked by the validator: optimal, else its "
             "proven lower bound; pddl: cost-optimal if proven.",
             solving.SolveInput, solving.SolveOutput, solving.solve_tool,
             read_only=True, idempotent=True, lane="heavy",
             heavy_when=HeavyWhen(graphs=("graph", "goal"))),
    ToolSpec("get_scene_image", "Scene image and prompt",
             "The episode's image and the scene-graph prompt (relations R, dictionary D) for "
             "your vision model; answer with submit_scene_graph.",
             scenes.GetSceneImageInput, None, scenes.get_scene_image,
             read_only=True, idempotent=True, lane="heavy"),
    ToolSpec("submit_scene_graph", "Submit a scene graph",
             "Check a scene graph you wrote against D and R (synonyms normalised, every "
             "problem at once).",
             scenes.SubmitSceneGraphInput, scenes.SceneGraphSubmission,
             scenes.submit_scene_graph, read_only=False, idempotent=True, open_world=True,
             heavy_when=HeavyWhen(graphs=("graph",))),
    ToolSpec("end_episode", "End the episode",
             "The end token: verdict, final graph and trace. The episode_id stops working.",
             episodes.EpisodeRef, episodes.EpisodeVerdict, episodes.end_episode,
             read_only=False, destructive=True),
    ToolSpec("arm_status", "Arm status",
             "The arm: driver, mode, connection, latched stop and why, busy, pose, last "
             "outcome. Answers mid-motion.",
             arm.ArmRef, arm.ArmStatusOutput, arm.arm_status,
             read_only=True, idempotent=True, open_world=True, lane="thread"),
    ToolSpec("arm_stop", "Stop the arm",
             "Stop the arm now, even mid-motion, and latch the stop: later motions are refused"
             " until arm_reset.",
             arm.ArmStopInput, arm.ArmStatusOutput, arm.arm_stop,
             read_only=False, idempotent=True, open_world=True, lane="own_thread"),
    ToolSpec("arm_reset", "Reset the arm's stop",
             "Clear the latched stop once the motion ended; nothing moves. A real arm asks "
             "the user; sim/dry-run only if the operator allows it.",
             arm.ArmRef, arm.ArmStatusOutput, arm.arm_reset,
             read_only=False, destructive=True, open_world=True, lane="thread",
             confirmation=Confirmation(arm.preview_reset, "the stop stays latched")),
)
TOOLS: dict[str, ToolSpec] = {spec.name: spec for spec in TOOL_SPECS}


def _pre_parse(model: type[BaseModel], arguments: Mapping[str, Any]) -> dict[str, Any]:
    """Decode JSON given as a string for a non-string field (some clients do that)."""
    fields = model.model_fields
    parsed = dict(arguments)
    for key, value in arguments.items():
        field = fields.get(key)
        if field is None or field.annotation is str or not isinstance(value, str):
            continue
        if not value.lstrip().startswith(("{", "[")):
            continue
        try:
            decoded = json.loads(value)
        except (ValueError, RecursionError):
            continue
        if isinstance(decoded, dict | list):
            parsed[key] = decoded
    return parsed


def _short_repr() -> reprlib.Repr:
    short = reprlib.Repr()
    short.maxlevel, short.maxdict, short.maxlist, short.maxtuple = 2, 3, 3, 3
    short.maxstring = short.maxother = short.maxlong = 60
    return short


_SHORT = _short_repr()


def _shown(value: Any) -> str:
    """The start of a value's repr (never the repr of all of a large input)."""
    text = _SHORT.repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


# Path parts pydantic adds for union members and validators; not argument names.
_UNION_TAGS = ("tagged-union[", "function-", "constrained-", "json-or-python[", "str", "int",
               "list[", "dict[", "nullable[", "union[", "literal[", "model[")


def _clean_path(loc: tuple[int | str, ...]) -> tuple[str, bool]:
    """`actions.0.tagged-union[...].move.target` -> (`actions[0].target`, True if a union)."""
    path = ""
    in_union = False
    skip_tag = False
    for part in loc:
        if isinstance(part, int):
            path += f"[{part}]"
            continue
        if part.startswith(_UNION_TAGS) or part in {"str", "int", "bool"}:
            in_union = True
            skip_tag = part.startswith("tagged-union[")
            continue
        if skip_tag:  # the discriminator value (move / align / done)
            skip_tag = False
            continue
        path += f".{part}" if path else part
    return path, in_union


def _wrong_union_member(err: Any) -> bool:
    """For `JSON action | text` unions, drop the member that does not match the input kind."""
    if err["type"] in ("string_type", "str_type") and isinstance(err.get("input"), dict):
        return True
    return err["type"] in ("model_type", "dict_type", "model_attributes_type") and \
        isinstance(err.get("input"), str)


def argument_error(spec: ToolSpec, exc: ValidationError) -> InvalidArgumentsError:
    """Every problem of the arguments, one per line, each with its field and a fix."""
    fields = spec.input_model.model_fields
    lines: list[str] = []
    first_field: str | None = None
    for err in exc.errors():
        path, in_union = _clean_path(err["loc"])
        top = str(err["loc"][0]) if err["loc"] else ""
        if in_union and _wrong_union_member(err):
            continue
        desc = fields[top].description if top in fields else None
        if err["type"] == "extra_forbidden" and len(err["loc"]) == 1:
            near = difflib.get_close_matches(top, list(fields), n=1)
            hint = f"did you mean '{near[0]}'? " if near else ""
            line = f"{top}: unknown argument (fix: {hint}this tool takes {', '.join(fields)})"
        elif err["type"] == "missing" and len(err["loc"]) == 1:
            line = f"{top}: missing required argument (fix: {desc or 'give it'})"
        elif not err["loc"]:
            line = f"arguments: {err['msg'].removeprefix('Value error, ')}"
        else:
            fix = f" (fix: {desc})" if desc else ""
            line = f"{path}: {err['msg']}, got {_shown(err.get('input'))}{fix}"
        first_field = first_field or top or None
        if line not in lines:
            lines.append(line)
    if not lines:  # every problem was on a union member: never an error with no reason
        for err in exc.errors()[:8]:
            path = _clean_path(err["loc"])[0] or "arguments"
            first_field = first_field or path.split(".")[0].split("[")[0]
            lines.append(f"{path}: {err['msg']}, got {_shown(err.get('input'))}")
    shown = lines[:8] + ([f"... and {len(lines) - 8} more"] if len(lines) > 8 else [])
    return InvalidArgumentsError(f"invalid arguments for {spec.name}:\n" + "\n".join(shown),
                                 field=first_field, value=None)


def parse_arguments(spec: ToolSpec, arguments: Mapping[str, Any] | None, *,
                    large: bool | None = None) -> BaseModel:
    """The tool's input model from raw JSON arguments, or a ToolArgumentError.

    `large`: whether `spec.heavy_when` finds the arguments large, if the caller has read
    it already (the server, to place the call); only large arguments are counted, to
    pause the cyclic collector while their many objects are built (`graph.bulk`)."""
    if arguments is not None and not isinstance(arguments, Mapping):
        raise ToolArgumentError("arguments must be a JSON object", field="arguments",
                                value=type(arguments).__name__,
                                fix="send the arguments as an object of name: value")
    parsed = _pre_parse(spec.input_model, arguments or {})
    try:
        if not (spec.heavy_when.large(parsed) if large is None else large):
            return spec.input_model.model_validate(parsed)
        items = 0  # the objects validation builds, about
        for value in parsed.values():
            items += graph_items(value) + (len(value) if isinstance(value, list) else 0)
        with collector_paused(items):
            return spec.input_model.model_validate(parsed)
    except ValidationError as exc:
        raise argument_error(spec, exc) from None


MAX_STALE_RETRIES = 50
_log = logging.getLogger("verigraph.tools")


class Toolbox:
    """Transport-free tool host: `Toolbox().call("load_scene", {"scene_id": ...})`."""

    def __init__(self, context: ToolContext | None = None, config: ToolConfig | None = None
                 ) -> None:
        self.context = context or ToolContext(config or ToolConfig())

    def spec(self, name: str) -> ToolSpec:
        spec = TOOLS.get(name)
        if spec is None:
            near = difflib.get_close_matches(name, list(TOOLS), n=1)
            raise ToolArgumentError(f"no tool named '{name[:64]}'", field="name",
                                    value=name[:64],
                                    fix=(f"did you mean {near[0]}? " if near else "")
                                    + f"tools: {', '.join(TOOLS)}")
        return spec

    def call(self, name: str, arguments: Mapping[str, Any] | None = None
             ) -> BaseModel | ImageResult:
        """Validate the arguments and run the tool; VeriGraphError on bad input."""
        spec = self.spec(name)
        params = parse_arguments(spec, arguments)
        return self.run(spec, params)

    def run(self, spec: ToolSpec, params: BaseModel) -> BaseModel | ImageResult:
        """Run a tool on already validated input.

        A call that lost a compare-and-set to another process (a durable store shared by
        replicas) stored nothing, so it runs again on the newer state.
        """
        for attempt in range(MAX_STALE_RETRIES):
            try:
                result: BaseModel | ImageResult = spec.run(self.context, params)
                return result
            except StaleEpisodeError as exc:
                if attempt == MAX_STALE_RETRIES - 1:
                    raise
                _log.info("%s: %s changed in another process; running the call again",
                          spec.name, exc.value)
                time.sleep(random.uniform(0, 0.002 * (attempt + 1)))
        raise AssertionError("unreachable")
