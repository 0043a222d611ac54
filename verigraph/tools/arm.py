"""Arm tools: arm_status, arm_stop, arm_reset, and the previews a human approves.

The stop must work while a motion runs, so arm_stop and arm_status do not wait for
the episode's lock (the arm controller is thread-safe for them); arm_reset does wait,
so a stop cannot be cleared in the middle of a call that is still ending.

`preview_execute` and `preview_reset` say what a call would do to a *real* arm, so a
transport that can ask its user (MCP elicitation) asks before the call runs; see
verigraph.server.confirmation.
"""

from __future__ import annotations

from dataclasses import dataclass

from pydantic import BaseModel, ConfigDict, Field

from verigraph.actions.execution import World
from verigraph.actions.model import MoveAction
from verigraph.actions.validator import apply_action, validate_action
from verigraph.arm import ArmStatus, ArmWorld, ConfirmationRequest
from verigraph.arm.models import AuditOutcome
from verigraph.errors import VeriGraphError
from verigraph.tools.context import ToolContext
from verigraph.tools.errors import EpisodeStateError
from verigraph.tools.executors import enabled_executors, runs_on
from verigraph.tools.fields import EpisodeId, count_moves, parse_actions
from verigraph.tools.store import LiveEpisode


class ArmRef(BaseModel):
    """The episode whose arm to ask about or act on."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId


class ArmStopInput(BaseModel):
    """The episode whose arm to stop, and why (kept in the audit log)."""

    model_config = ConfigDict(extra="forbid")

    episode_id: EpisodeId
    reason: str = Field(default="stop requested through arm_stop", min_length=1,
                        max_length=200, description="why (audit log, arm_status)")


class ArmStatusOutput(ArmStatus):
    """The arm adapter's state for one episode, and what this call did."""

    episode_id: str
    executor: str
    note: str | None = Field(default=None, description="what this call did")

    def summary(self) -> str:
        return (f"{self.note}; " if self.note else "") + super().summary()


def _arm(ctx: ToolContext, episode: LiveEpisode) -> ArmWorld:
    """The episode's arm, or an error saying how to get one: the executor string that
    reaches this server's arm, or that it has none (so no episode here moves a robot)."""
    if isinstance(episode.world, ArmWorld):
        return episode.world
    if episode.executor.startswith("arm:"):
        raise EpisodeStateError(
            f"episode {episode.id} has no arm yet: it waits for its scene graph",
            field="episode_id", value=episode.id,
            fix="submit the scene graph with submit_scene_graph; the arm attaches then")
    config = ctx.config
    executors = enabled_executors(config.executor, config.arm)
    where = runs_on(episode.executor).removeprefix(f"{episode.executor} (").removesuffix(")")
    if config.arm is None:
        raise EpisodeStateError(
            f"episode {episode.id} runs on {episode.executor}, not on an arm ({where}), and "
            "this server has no arm configured: no executor here reaches a robot",
            field="episode_id", value=episode.id,
            fix="load the scene with executor arm:<driver> on a server started with "
                f"--executor arm:<driver> or --arm-config; this server runs {executors}")
    arm = config.arm.executor
    raise EpisodeStateError(
        f"episode {episode.id} runs on {episode.executor}, not on an arm ({where}); this "
        f"server's arm is reached with executor {arm}",
        field="episode_id", value=episode.id,
        fix=f"load the scene with executor arm:<driver>, here executor={arm}, to use arm "
            f"tools (this server runs {executors})")


def _output(episode: LiveEpisode, status: ArmStatus, note: str | None = None) -> ArmStatusOutput:
    return ArmStatusOutput(**status.model_dump(), episode_id=episode.id,
                           executor=episode.executor, note=note)


def arm_status(ctx: ToolContext, params: ArmRef) -> ArmStatusOutput:
    """The arm's state; answers at once, even during a motion."""
    episode = ctx.store.peek(params.episode_id)
    world = _arm(ctx, episode)
    return _output(episode, world.status())


def arm_stop(ctx: ToolContext, params: ArmStopInput) -> ArmStatusOutput:
    """Latch the stop and halt any motion now; only arm_reset clears the latch."""
    episode = ctx.store.peek(params.episode_id)
    world = _arm(ctx, episode)
    already = world.stop_latched  # never the driver's status: it might hang
    status = world.stop(params.reason)
    note = ("the stop was already latched; it stays latched" if already else
            "stop latched: the arm halted and refuses every motion until arm_reset")
    return _output(episode, status, note)


def arm_reset(ctx: ToolContext, params: ArmRef) -> ArmStatusOutput:
    """Clear the arm's latched stop or error once the stopped motion has ended: a real
    arm asks the user; sim and dry-run only if the operator allowed it. Nothing moves."""
    with ctx.store.use(params.episode_id) as episode:
        world = _arm(ctx, episode)
        was = world.status()
        status = world.reset()
        note = (f"stop cleared (it was latched: {was.stop_reason}); nothing moved"
                if was.stop_latched else "reset done; no stop was latched")
        return _output(episode, status, note)


# -- what a human approves before a real arm acts ------------------------------------------
@dataclass(frozen=True)
class ArmQuestion:
    """The real-arm requests a call would make, the text to show the user, and the arm
    (whose audit log records the answer and whose config sets the deadline)."""

    requests: tuple[ConfirmationRequest, ...]
    text: str
    world: ArmWorld

    @property
    def timeout_s(self) -> float:
        return self.world.config.confirm_timeout_s

    def record(self, shown: str | None, outcome: AuditOutcome, detail: str) -> None:
        """Write the user's answer (or why there was none) to the arm's audit log, with
        the text `shown` to the user (this question's text if it was not asked)."""
        self.world.log_confirmation(shown or self.text, outcome, detail)


def _real_arm(world: World | None) -> ArmWorld | None:
    return world if isinstance(world, ArmWorld) and world.config.mode == "real" else None


def _question(world: ArmWorld, what: str, requests: list[ConfirmationRequest]) -> ArmQuestion:
    config = world.config
    where = f" at {config.host}" if config.host else ""
    lines = [f"VeriGraph asks before the REAL arm ({config.driver}{where}) acts: {what}."]
    lines += [f"{i}. {r.motion}" for i, r in enumerate(requests, start=1)]
    if any(r.waypoints for r in requests):
        r = requests[0]
        grip = f", grip {r.force_n:.0f} N" if r.force_n is not None else ""
        lines.append(f"Tool speed {r.speed_m_s:.2f} m/s{grip}; the path of the tool and of "
                     "the whole arm (every link, the hand, the fingers, the held object) was "
                     "checked against the workspace, the table and the keep-out zones. "
                     "Nothing moves unless you approve.")
    lines.append("Approve?")
    return ArmQuestion(tuple(requests), "\n".join(lines), world)


def preview_execute(ctx: ToolContext, params: BaseModel) -> ArmQuestion | None:
    """The motions an execute_actions call would make on a real arm (None: none).

    Walks the actions as execute_in_world will: each must pass the validator on the
    episode's graph (whose predicted result the next one sees) and then the arm's own
    checks on the scene it observes; the walk ends at the first action that would not
    reach the arm. Bad input gives None: the call itself reports it.
    """
    try:
        with ctx.store.use(getattr(params, "episode_id", "")) as episode:
            world = _real_arm(episode.world)
            if world is None or episode.state is None or episode.threshold_reached:
                return None
            actions = parse_actions(getattr(params, "actions", []))
            if count_moves(actions) > episode.k:
                return None  # the call refuses this before anything runs
            state = episode.state.copy()
            moves: list[MoveAction] = []
            for action in actions:
                if not isinstance(action, MoveAction) or validate_action(state, action):
                    break  # done, align, or a violation: execution stops there too
                apply_action(state, action)
                moves.append(action)
            requests = world.preview(moves)
    except VeriGraphError:
        return None
    if not requests:
        return None
    count = f"{len(requests)} motion{'s' if len(requests) > 1 else ''}"
    return _question(world, f"execute_actions on episode {episode.id}, {count}", requests)


def preview_reset(ctx: ToolContext, params: BaseModel) -> ArmQuestion | None:
    """What arm_reset would ask on a real arm with a latched stop (None: nothing)."""
    try:
        episode = ctx.store.peek(getattr(params, "episode_id", ""))
    except VeriGraphError:
        return None
    world = _real_arm(episode.world)
    request = world.reset_request() if world is not None else None
    if world is None or request is None:
        return None
    return _question(world, f"arm_reset on episode {episode.id}", [request])
