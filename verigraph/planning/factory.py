"""Build a planner backend by name from one options model (CLI flags, benchmark settings)."""

from __future__ import annotations

from typing import Literal, get_args

from pydantic import BaseModel, ConfigDict, Field

from verigraph.llm.formats import ResponseFormat
from verigraph.planning.greedy import GreedyPlanner
from verigraph.planning.noisy import MISTAKE_KINDS, MistakeKind, NoisyPlanner
from verigraph.planning.oracle import OraclePlanner
from verigraph.planning.planner import Planner
from verigraph.planning.rule_based import RuleBasedPlanner

PlannerName = Literal["oracle", "rule-based", "greedy", "noisy", "openai", "anthropic",
                      "llm-local"]
PLANNER_NAMES: tuple[str, ...] = get_args(PlannerName)


class PlannerOptions(BaseModel):
    """Settings of every backend; each backend reads the ones it needs."""

    model_config = ConfigDict(extra="forbid")

    noise: float = Field(default=0.3, ge=0.0, le=1.0, description="noisy: mistakes per call")
    seed: int = Field(default=0, description="noisy, greedy: RNG seed")
    mistakes: tuple[MistakeKind, ...] = MISTAKE_KINDS
    base_url: str | None = None
    model: str | None = None
    api_key: str | None = Field(default=None, repr=False)
    response_format: ResponseFormat | None = None
    constrain_ids: bool = True
    temperature: float | None = None
    max_tokens: int | None = None
    timeout_s: float | None = None
    retries: int | None = None


def make_planner(name: str, options: PlannerOptions | None = None) -> Planner:
    """A fresh planner; LLM backends read missing settings from the environment."""
    options = options or PlannerOptions()
    if name == "oracle":
        return OraclePlanner()
    if name == "rule-based":
        return RuleBasedPlanner()
    if name == "greedy":
        return GreedyPlanner(seed=options.seed)
    if name == "noisy":
        return NoisyPlanner(rate=options.noise, seed=options.seed, kinds=options.mistakes)
    common = {"temperature": options.temperature, "max_tokens": options.max_tokens,
              "timeout_s": options.timeout_s, "retries": options.retries,
              "constrain_ids": options.constrain_ids}
    if name == "openai":
        from verigraph.planning.openai_backend import OpenAIConfig, OpenAIPlanner

        return OpenAIPlanner(OpenAIConfig.from_env(
            base_url=options.base_url, model=options.model, api_key=options.api_key,
            response_format=options.response_format, **common))
    if name == "anthropic":
        from verigraph.planning.anthropic_backend import AnthropicConfig, AnthropicPlanner

        return AnthropicPlanner(AnthropicConfig.from_env(
            base_url=options.base_url, model=options.model, api_key=options.api_key,
            **common))
    if name == "llm-local":
        from verigraph.planning.local import LocalLLMPlanner

        return LocalLLMPlanner(max_tokens=options.max_tokens or 256,
                               temperature=options.temperature or 0.0,
                               constrain_ids=options.constrain_ids)
    raise ValueError(f"unknown planner '{name}'; use one of {', '.join(PLANNER_NAMES)}")
