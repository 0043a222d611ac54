"""The `response_format` dialects of OpenAI-compatible servers, shared by every client.

Servers disagree on how to ask for an answer constrained to a JSON schema:

- `json_schema`: `{"type": "json_schema", "json_schema": {"name", "strict", "schema"}}`
  (OpenAI, vLLM, Ollama, Gemini);
- `json_object_schema`: `{"type": "json_object", "schema": S}` (llama-cpp-python's
  server, which rejects `json_schema` with HTTP 500);
- `json_object`: plain JSON mode, the schema only described in the prompt;
- `none`: free text.
"""

from __future__ import annotations

from typing import Any, Literal

ResponseFormat = Literal["json_schema", "json_object_schema", "json_object", "none"]
RESPONSE_FORMATS: tuple[str, ...] = ("json_schema", "json_object_schema", "json_object", "none")
DEFAULT_SCHEMA_NAME = "answer"


def response_format_field(kind: ResponseFormat, schema: dict[str, Any],
                          name: str = DEFAULT_SCHEMA_NAME) -> dict[str, Any] | None:
    """The `response_format` request field for a server dialect (None: leave it out)."""
    if kind == "json_schema":
        return {"type": "json_schema",
                "json_schema": {"name": name, "strict": True, "schema": schema}}
    if kind == "json_object_schema":
        return {"type": "json_object", "schema": schema}
    if kind == "json_object":
        return {"type": "json_object"}
    return None
