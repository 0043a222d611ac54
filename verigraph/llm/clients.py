"""Authenticated JSON clients for the two model APIs VeriGraph speaks.

One place knows the headers: OpenAI-compatible chat completions (bearer token; OpenAI,
Gemini's compatible endpoint, Ollama, vLLM, llama.cpp's server) and Anthropic's
Messages API (`x-api-key` and a pinned `anthropic-version`).
"""

from __future__ import annotations

from verigraph.llm.http import JsonHttpClient

ANTHROPIC_API_VERSION = "2023-06-01"


def openai_client(base_url: str, api_key: str | None, *, timeout: float, retries: int
                  ) -> JsonHttpClient:
    """A client for an OpenAI-compatible endpoint (no key: no Authorization header)."""
    headers = {"Authorization": f"Bearer {api_key}"} if api_key else {}
    return JsonHttpClient(base_url, headers=headers, timeout=timeout, retries=retries)


def anthropic_client(base_url: str, api_key: str | None, *, timeout: float, retries: int
                     ) -> JsonHttpClient:
    """A client for Anthropic's Messages API."""
    headers = {"anthropic-version": ANTHROPIC_API_VERSION, "content-type": "application/json"}
    if api_key:
        headers["x-api-key"] = api_key
    return JsonHttpClient(base_url, headers=headers, timeout=timeout, retries=retries)
