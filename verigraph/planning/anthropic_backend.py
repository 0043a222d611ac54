"""The `anthropic` planner: the Messages API with a forced tool whose input is the plan.

Claude answers by calling the tool `propose_actions` (tool_choice forces it), so the
input arrives as a JSON object matching the action schema instead of free text.
An answer without the tool call, or cut off at `max_tokens`, becomes feedback.
"""

from __future__ import annotations

import os
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.errors import VeriGraphError
from verigraph.llm.clients import anthropic_client
from verigraph.llm.http import JsonHttpClient
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.parsing import ParseFailure, parse_answer, parse_tool_input
from verigraph.planning.schema import action_schema

TOOL_NAME = "propose_actions"


class AnthropicConfig(BaseModel):
    """Endpoint and sampling settings; flags override ANTHROPIC_BASE_URL/_MODEL/_API_KEY."""

    model_config = ConfigDict(extra="forbid")

    base_url: str = "https://api.anthropic.com"
    model: str = Field(min_length=1)
    api_key: str | None = Field(default=None, repr=False)
    constrain_ids: bool = True
    temperature: float = Field(default=0.0, ge=0.0, le=1.0)
    max_tokens: int = Field(default=1024, ge=16)
    timeout_s: float = Field(default=120.0, gt=0)
    retries: int = Field(default=4, ge=0, le=20)

    @classmethod
    def from_env(cls, **overrides: Any) -> AnthropicConfig:
        given = {k: v for k, v in overrides.items() if v is not None}
        given.setdefault("base_url", os.environ.get("ANTHROPIC_BASE_URL",
                                                    "https://api.anthropic.com"))
        given.setdefault("api_key", os.environ.get("ANTHROPIC_API_KEY"))
        model = given.get("model") or os.environ.get("ANTHROPIC_MODEL")
        if not model:
            raise VeriGraphError("no model name given for the anthropic planner",
                                 field="--model", fix="pass --model NAME or set ANTHROPIC_MODEL")
        given["model"] = model
        return cls.model_validate(given)


class AnthropicPlanner:
    """Messages-API planner with a forced `propose_actions` tool call."""

    def __init__(self, config: AnthropicConfig, *, client: JsonHttpClient | None = None
                 ) -> None:
        self.config = config
        self.name = f"anthropic:{config.model}"
        self.client = client or anthropic_client(config.base_url, config.api_key,
                                                 timeout=config.timeout_s,
                                                 retries=config.retries)

    def build_payload(self, request: PlannerRequest) -> dict[str, Any]:
        """The Messages API request body for one proposal."""
        limit = f"at most {request.k} actions" if request.k is not None else "the whole plan"
        tool = {
            "name": TOOL_NAME,
            "description": f"Propose {limit} in order; end with {{\"action\": \"done\"}} when "
                           "the goal will hold after them (or alone when it already holds).",
            "input_schema": action_schema(request.graph,
                                          constrain_ids=self.config.constrain_ids),
        }
        return {
            "model": self.config.model,
            "max_tokens": self.config.max_tokens,
            "temperature": self.config.temperature,
            "messages": [{"role": "user", "content": request.prompt +
                          f"\nAnswer by calling the {TOOL_NAME} tool."}],
            "tools": [tool],
            "tool_choice": {"type": "tool", "name": TOOL_NAME},
        }

    def propose(self, request: PlannerRequest) -> PlannerReply:
        data = self.client.post("v1/messages", self.build_payload(request))
        usage = data.get("usage") if isinstance(data.get("usage"), dict) else None
        blocks = data.get("content")
        if not isinstance(blocks, list):
            return PlannerReply(error="the endpoint's answer had no content list",
                                raw=str(data)[:2000], usage=usage)
        truncated = data.get("stop_reason") == "max_tokens"
        texts: list[str] = []
        for block in blocks:
            if not isinstance(block, dict):
                continue
            if block.get("type") == "tool_use" and block.get("name") == TOOL_NAME:
                raw = str(block.get("input"))
                try:
                    actions = parse_tool_input(block.get("input"))
                except ParseFailure as exc:
                    message = str(exc)
                    if truncated:
                        message = ("the answer was cut off by the token limit; propose fewer "
                                   f"actions ({message})")
                    return PlannerReply(error=message, raw=raw, usage=usage)
                return PlannerReply(actions=actions, raw=raw, usage=usage)
            if block.get("type") == "text" and isinstance(block.get("text"), str):
                texts.append(block["text"])
        text = "\n".join(texts)
        try:  # a model that ignored the tool may still have written a readable plan
            actions = parse_answer(text, truncated=truncated)
        except ParseFailure as exc:
            return PlannerReply(error=f"no {TOOL_NAME} tool call in the answer; {exc}",
                                raw=text, usage=usage)
        return PlannerReply(actions=actions, raw=text, usage=usage)

    def close(self) -> None:
        self.client.close()
