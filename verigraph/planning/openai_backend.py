"""The `openai` planner: any OpenAI-compatible chat-completions endpoint.

Works with OpenAI, Gemini's compatible endpoint, Ollama, vLLM and llama.cpp's server.
The answer is constrained to the action schema; servers disagree on how to ask for
that, so the request format is configurable (`verigraph.llm.formats`: `json_schema`,
`json_object_schema`, `json_object`, or `none`: free text, parsed as JSON or as the text
plan form).

The whole prompt goes into one user message (some chat templates, such as Gemma's,
drop system messages). Malformed or truncated answers become feedback, not errors.
"""

from __future__ import annotations

import os
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from verigraph.errors import VeriGraphError
from verigraph.llm.clients import openai_client
from verigraph.llm.formats import ResponseFormat, response_format_field
from verigraph.llm.http import JsonHttpClient
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.parsing import ParseFailure, parse_answer
from verigraph.planning.schema import SCHEMA_NAME, action_schema, format_instruction


class OpenAIConfig(BaseModel):
    """Endpoint and sampling settings; flags override `OPENAI_BASE_URL`/`_MODEL`/`_API_KEY`."""

    model_config = ConfigDict(extra="forbid")

    base_url: str = Field(description="e.g. https://api.openai.com/v1 or http://127.0.0.1:8080/v1")
    model: str = Field(min_length=1)
    api_key: str | None = Field(default=None, repr=False)
    response_format: ResponseFormat = "json_schema"
    constrain_ids: bool = Field(default=True, description="enumerate object ids in the schema")
    temperature: float = Field(default=0.0, ge=0.0, le=2.0)
    max_tokens: int = Field(default=512, ge=16)
    timeout_s: float = Field(default=120.0, gt=0)
    retries: int = Field(default=4, ge=0, le=20)
    seed: int | None = None

    @classmethod
    def from_env(cls, **overrides: Any) -> OpenAIConfig:
        """Fill missing settings from OPENAI_BASE_URL, OPENAI_MODEL and OPENAI_API_KEY."""
        given = {k: v for k, v in overrides.items() if v is not None}
        given.setdefault("base_url", os.environ.get("OPENAI_BASE_URL",
                                                    "https://api.openai.com/v1"))
        given.setdefault("api_key", os.environ.get("OPENAI_API_KEY"))
        model = given.get("model") or os.environ.get("OPENAI_MODEL")
        if not model:
            raise VeriGraphError("no model name given for the openai planner", field="--model",
                                 fix="pass --model NAME or set OPENAI_MODEL")
        given["model"] = model
        return cls.model_validate(given)


class OpenAIPlanner:
    """Chat-completions planner; one HTTP call (plus transient retries) per proposal."""

    def __init__(self, config: OpenAIConfig, *, name: str | None = None,
                 client: JsonHttpClient | None = None) -> None:
        self.config = config
        self.name = name or f"openai:{config.model}"
        self.client = client or openai_client(config.base_url, config.api_key,
                                              timeout=config.timeout_s, retries=config.retries)

    def build_payload(self, request: PlannerRequest) -> dict[str, Any]:
        """The chat-completions request body for one proposal."""
        schema = action_schema(request.graph, constrain_ids=self.config.constrain_ids)
        payload: dict[str, Any] = {
            "model": self.config.model,
            "messages": [{"role": "user",
                          "content": request.prompt + format_instruction(request.k)}],
            "temperature": self.config.temperature,
            "max_tokens": self.config.max_tokens,
        }
        if self.config.seed is not None:
            payload["seed"] = self.config.seed
        field = response_format_field(self.config.response_format, schema, SCHEMA_NAME)
        if field is not None:
            payload["response_format"] = field
        return payload

    def propose(self, request: PlannerRequest) -> PlannerReply:
        data = self.client.post("chat/completions", self.build_payload(request))
        usage = data.get("usage") if isinstance(data.get("usage"), dict) else None
        try:
            choice = data["choices"][0]
            message = choice.get("message") or {}
            text = message.get("content")
            refusal = message.get("refusal")
            finish = choice.get("finish_reason")
        except (KeyError, IndexError, TypeError, AttributeError):
            return PlannerReply(error="the endpoint's answer had no choices[0].message; "
                                      "answer again with the JSON object",
                                raw=str(data)[:2000], usage=usage)
        if refusal:
            return PlannerReply(error=f"the model refused: {refusal}", raw=str(refusal),
                                usage=usage)
        text = text if isinstance(text, str) else ""
        try:
            actions = parse_answer(text, truncated=finish == "length")
        except ParseFailure as exc:
            return PlannerReply(error=str(exc), raw=text, usage=usage)
        return PlannerReply(actions=actions, raw=text, usage=usage)

    def close(self) -> None:
        self.client.close()
