"""Asking the user before a real arm acts: MCP elicitation through resolvers.

On protocol 2026-07-28 a server cannot push `elicitation/create` in the middle of a
tool call (`ctx.elicit` raises NoBackChannelError), so the question is asked by a
resolver before the tool body runs: it previews what the call would do to a real arm
(`verigraph.tools.arm.preview_*`) and asks once; the SDK carries the question and the
answer (InputRequiredResult and the client's retry on 2026-07-28, a pushed request on
older versions). The body then installs a `PreApproved` hook for the call, covering
exactly the approved motions, and the arm controller consults it before each one.

A client that declared no elicitation capability, a decline, a cancel or an answer
after `confirm_timeout_s`: the call fails with a tool error before anything runs, so
nothing moves and the episode is unchanged; each is written to the arm's audit log
with the question. The deadline is stated in the question; on 2026-07-28 the client's
retry must answer the question as first rendered (the SDK checks its digest), so the
time it was first asked is kept per question text until the deadline has passed. The
answer is only as trustworthy as the client that shows the question.

`arm_call` wraps every tool call that may touch an arm (verigraph.server.tools imports
this module only for those): it tags the arm's audit records with the episode and
the client, counts the call as the deadman's heartbeat, and, while execute_actions
runs, stops and latches the arm as soon as the call is cancelled (the client
disconnected or cancelled it), so nothing more is sent.

This module deliberately has no `from __future__ import annotations`: the SDK reads
the resolvers' annotations with `typing.get_type_hints`, which cannot see the
closures they refer to once annotations are strings.
"""

import inspect
import threading
import time
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from typing import Annotated, Any, Literal

import anyio
import anyio.to_thread
from mcp.server.mcpserver import (
    AcceptedElicitation,
    Context,
    Elicit,
    ElicitationResult,
    Resolve,
)
from mcp.server.mcpserver.exceptions import ToolError
from pydantic import BaseModel, Field

from verigraph.arm import ArmWorld, PreApproved, confirm_scope
from verigraph.arm.audit import audit_scope
from verigraph.errors import VeriGraphError
from verigraph.tools.arm import ArmQuestion
from verigraph.tools.registry import Confirmation, Toolbox, ToolSpec


class ArmApproval(BaseModel):
    """The form the user answers: one yes or no."""

    approve: bool = Field(description="true lets the real arm do exactly what is listed")


@dataclass
class Preview:
    """The resolver's look ahead: the question for this call, if it has one, and the
    time by which the user must answer it (set when it is asked)."""

    question: ArmQuestion | None
    deadline: float | None = field(default=None)
    shown: str | None = field(default=None)  # the text put to the user


@dataclass(frozen=True)
class NotAsked:
    """Why no question went to the client."""

    reason: Literal["nothing_to_ask", "client_cannot_ask"]


PREVIEW_PARAM = "arm_preview"
ANSWER_PARAM = "arm_confirmation"


def can_elicit(ctx: Context) -> bool:
    """Whether the client declared form elicitation (the SDK's own test, without raising)."""
    caps = ctx.client_capabilities
    elicitation = caps.elicitation if caps is not None else None
    return elicitation is not None and (elicitation.form is not None or elicitation.url is None)


def _confirmation(spec: ToolSpec) -> Confirmation:
    if spec.confirmation is None:
        raise ValueError(f"{spec.name} asks the user nothing")
    return spec.confirmation


def resolver_parameters(spec: ToolSpec, toolbox: Toolbox,
                        request_arguments: Callable[[ToolSpec, Context], BaseModel]
                        ) -> list[inspect.Parameter]:
    """Two keyword parameters the SDK fills by running resolvers before the tool runs.

    The preview reads the call's input as the server checked it (verigraph.server.tools
    step 1) from the request with `request_arguments` (the caller's, so that this module
    needs nothing of the tool-call path that enters it); input that does not check
    previews nothing, so nothing real may move.
    """
    previewer = _confirmation(spec).preview

    async def arm_preview(ctx: Context) -> Preview:
        try:
            params = request_arguments(spec, ctx)
        except VeriGraphError:
            return Preview(None)
        question = await anyio.to_thread.run_sync(previewer, toolbox.context, params)
        return Preview(question)

    async def arm_confirmation(
            ctx: Context, preview: Annotated[Preview, Resolve(arm_preview)]
    ) -> Elicit[ArmApproval] | NotAsked:
        if preview.question is None:
            return NotAsked("nothing_to_ask")
        if not can_elicit(ctx):
            return NotAsked("client_cannot_ask")
        question = preview.question
        asked_at = _ASKED.first_asked(question.text, retry=bool(ctx.input_responses),
                                      timeout_s=question.timeout_s)
        preview.deadline = asked_at + question.timeout_s
        when = time.strftime("%H:%M:%S UTC", time.gmtime(preview.deadline))
        preview.shown = (f"{question.text}\n(Answer within {question.timeout_s:g} s, by "
                         f"{when}; a later answer counts as no.)")
        return Elicit(preview.shown, ArmApproval)

    keyword = inspect.Parameter.KEYWORD_ONLY
    return [
        inspect.Parameter(PREVIEW_PARAM, keyword, default=None,
                          annotation=Annotated[Preview, Resolve(arm_preview)]),
        inspect.Parameter(ANSWER_PARAM, keyword, default=None,
                          annotation=Annotated[ElicitationResult[ArmApproval],
                                               Resolve(arm_confirmation)]),
    ]


def approval_hook(spec: ToolSpec, arguments: dict[str, Any]) -> PreApproved:
    """The hook for this call, from the resolved preview and answer (taken out of
    `arguments`); a ToolError (logged in the arm's audit) when the user declined, could
    not be asked, or answered after the deadline."""
    name, unchanged = spec.name, _confirmation(spec).unchanged
    preview = arguments.pop(PREVIEW_PARAM, None)
    answer = arguments.pop(ANSWER_PARAM, None)
    question = preview.question if isinstance(preview, Preview) else None
    if question is None:
        return PreApproved([])  # nothing was shown, so no real action is approved
    assert isinstance(preview, Preview)
    data = answer.data if isinstance(answer, AcceptedElicitation) else None
    what = "; ".join(r.motion for r in question.requests)
    late = preview.deadline is not None and time.time() > preview.deadline
    if isinstance(data, ArmApproval) and data.approve and not late:
        question.record(preview.shown, "done", "approved by the user")
        return PreApproved(question.requests)
    if isinstance(data, NotAsked):
        question.record(preview.shown, "refused",
                        "the client cannot ask the user (no elicitation)")
        raise ToolError(
            f"{name} would make the real arm act ({what}), and this client cannot ask the "
            f"user to confirm (it declared no elicitation support), so {unchanged} "
            "(fix: use an MCP client that supports elicitation, or have the operator run "
            "the arm in mode sim or dry-run)")
    if late:
        question.record(preview.shown, "timeout",
                        f"answered after the {question.timeout_s:g} s deadline: counted as no")
        raise ToolError(f"the user answered after the {question.timeout_s:g} s deadline, "
                        f"which counts as no, so {unchanged} (fix: send the action "
                        "again and answer within the time shown)")
    said = "did not approve" if isinstance(data, ArmApproval) else \
        f"answered {getattr(answer, 'action', 'nothing')}"
    question.record(preview.shown, "declined", f"the user {said}")
    raise ToolError(f"the user {said} the real arm's action ({what}), so {unchanged} "
                    "(fix: change the plan, or send it again and approve)")


class AskedQuestions:
    """When each question text was first asked, so a retry sees the same deadline.

    Entries expire once their deadline is well past; a retry after that is asked again
    (with a new deadline) rather than accepted.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._asked: dict[str, tuple[float, float]] = {}  # text -> (asked at, expires)

    def first_asked(self, text: str, *, retry: bool, timeout_s: float) -> float:
        now = time.time()
        with self._lock:
            self._asked = {k: v for k, v in self._asked.items() if v[1] > now}
            if retry and text in self._asked:
                return self._asked[text][0]
            self._asked[text] = (now, now + 2 * timeout_s + 60)
            return now


_ASKED = AskedQuestions()


def _arm_of(toolbox: Toolbox, params: BaseModel) -> tuple[str | None, ArmWorld | None]:
    episode_id = getattr(params, "episode_id", None)
    if not isinstance(episode_id, str):
        return None, None
    try:
        world = toolbox.context.store.peek(episode_id).world
    except Exception:
        return episode_id, None
    return episode_id, world if isinstance(world, ArmWorld) else None


def take_answers(arguments: dict[str, Any]) -> dict[str, Any]:
    """Take the resolved preview and answer out of a confirmed tool's arguments."""
    return {key: arguments.pop(key, None) for key in (PREVIEW_PARAM, ANSWER_PARAM)}


@asynccontextmanager
async def arm_call(spec: ToolSpec, toolbox: Toolbox, params: BaseModel,
                   answers: dict[str, Any] | None, client_name: str) -> AsyncIterator[None]:
    """The scope of one tool call for the arm: audit identity (the episode, and the MCP
    client name), the confirmation hook from `answers` (see `take_answers`; None for
    tools that ask nothing), heartbeat and, for a motion, the deadman on the call."""
    episode_id, world = _arm_of(toolbox, params)
    if world is not None:
        world.touch()
    with audit_scope(episode_id=episode_id, client=client_name):
        hook = approval_hook(spec, answers) if answers is not None else None
        with confirm_scope(hook):
            async with _deadman(spec, world):
                yield


@asynccontextmanager
async def _deadman(spec: ToolSpec, world: ArmWorld | None) -> AsyncIterator[None]:
    """While a motion tool runs: stop and latch the arm if the call is cancelled."""
    if world is None or not spec.moves_arm or world.config.mode == "dry-run":
        yield  # a dry run moves nothing: there is nothing to stop
        return
    finished = False

    async def watch() -> None:
        try:
            await anyio.sleep_forever()
        except anyio.get_cancelled_exc_class():
            if not finished:  # the call was cancelled: its client is gone
                world.stop("the client that asked for this motion is gone "
                           "(disconnected or cancelled the call)")
            raise

    async with anyio.create_task_group() as tg:
        tg.start_soon(watch)
        try:
            yield
        finally:
            finished = True
            tg.cancel_scope.cancel()
