"""Asking the user before a real arm acts: MCP elicitation through resolvers.

On protocol 2026-07-28 a server cannot push `elicitation/create` in the middle of a
tool call (`ctx.elicit` raises NoBackChannelError), so the question is asked by a
resolver before the tool body runs: it previews what the call would do to a real arm
(`verigraph.tools.arm.preview_*`) and asks once; the SDK carries the question and the
answer (InputRequiredResult and the client's retry on 2026-07-28, a pushed request on
older versions). The body then installs a `PreApproved` hook for the call, covering
exactly the approved motions, and the arm controller consults it before each one.

A client that declared no elicitation capability, a decline or a cancel: the call
fails with a tool error before anything runs, so nothing moves and the episode is
unchanged. The answer is only as trustworthy as the client that shows the question.

This module deliberately has no `from __future__ import annotations`: the SDK reads
the resolvers' annotations with `typing.get_type_hints`, which cannot see the
closures they refer to once annotations are strings.
"""

import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated, Any, Literal

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

from verigraph.arm import PreApproved
from verigraph.tools.arm import ArmQuestion, preview_execute, preview_reset
from verigraph.tools.context import ToolContext
from verigraph.tools.registry import Toolbox


class ArmApproval(BaseModel):
    """The form the user answers: one yes or no."""

    approve: bool = Field(description="true lets the real arm do exactly what is listed")


@dataclass(frozen=True)
class Preview:
    """The resolver's look ahead: the question for this call, if it has one."""

    question: ArmQuestion | None


@dataclass(frozen=True)
class NotAsked:
    """Why no question went to the client."""

    reason: Literal["nothing_to_ask", "client_cannot_ask"]


Previewer = Callable[[ToolContext, BaseModel], ArmQuestion | None]

# Tools that can make a real arm act, and what each would ask.
PREVIEWS: dict[str, Previewer] = {"execute_actions": preview_execute,
                                  "arm_reset": preview_reset}
PREVIEW_PARAM = "arm_preview"
ANSWER_PARAM = "arm_confirmation"

# What stays true after a refusal, per tool.
UNCHANGED = {"execute_actions": "nothing moved and the episode is unchanged",
             "arm_reset": "the stop stays latched"}


def can_elicit(ctx: Context) -> bool:
    """Whether the client declared form elicitation (the SDK's own test, without raising)."""
    caps = ctx.client_capabilities
    elicitation = caps.elicitation if caps is not None else None
    return elicitation is not None and (elicitation.form is not None or elicitation.url is None)


def resolver_parameters(name: str, toolbox: Toolbox,
                        params_of_call: Callable[[], BaseModel | None]
                        ) -> list[inspect.Parameter]:
    """Two keyword parameters the SDK fills by running resolvers before `name` runs.

    `params_of_call` returns the input the argument gate validated for this call (None
    if there is none: then nothing is previewed, so nothing real may move).
    """
    previewer = PREVIEWS[name]

    async def arm_preview(ctx: Context) -> Preview:
        params = params_of_call()
        if params is None:
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
        return Elicit(preview.question.text, ArmApproval)

    keyword = inspect.Parameter.KEYWORD_ONLY
    return [
        inspect.Parameter(PREVIEW_PARAM, keyword, default=None,
                          annotation=Annotated[Preview, Resolve(arm_preview)]),
        inspect.Parameter(ANSWER_PARAM, keyword, default=None,
                          annotation=Annotated[ElicitationResult[ArmApproval],
                                               Resolve(arm_confirmation)]),
    ]


def approval_hook(name: str, arguments: dict[str, Any]) -> PreApproved:
    """The hook for this call, from the resolved preview and answer (taken out of
    `arguments`); a ToolError when the user declined or could not be asked."""
    preview = arguments.pop(PREVIEW_PARAM, None)
    answer = arguments.pop(ANSWER_PARAM, None)
    question = preview.question if isinstance(preview, Preview) else None
    if question is None:
        return PreApproved([])  # nothing was shown, so no real action is approved
    data = answer.data if isinstance(answer, AcceptedElicitation) else None
    if isinstance(data, ArmApproval) and data.approve:
        return PreApproved(question.requests)
    what = "; ".join(r.motion for r in question.requests)
    if isinstance(data, NotAsked):
        raise ToolError(
            f"{name} would make the real arm act ({what}), and this client cannot ask the "
            f"user to confirm (it declared no elicitation support), so {UNCHANGED[name]} "
            "(fix: use an MCP client that supports elicitation, or have the operator run "
            "the arm in mode sim or dry-run)")
    said = "did not approve" if isinstance(data, ArmApproval) else \
        f"answered {getattr(answer, 'action', 'nothing')}"
    raise ToolError(f"the user {said} the real arm's action ({what}), so {UNCHANGED[name]} "
                    "(fix: change the plan, or send it again and approve)")
