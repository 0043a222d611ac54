"""The VLM path: SGG(I, R, D, T) by a vision-language model behind an OpenAI-compatible API.

For users who run such a model (OpenAI, Gemini's compatible endpoint, Ollama, vLLM,
llama.cpp's server): the image goes out with the scene-graph generation prompt (the
relations R, the dictionary D, the task T; the same prompt agents get from
`get_scene_image`), the answer is constrained to a JSON schema of the graph, and it
comes back through the same normalisation and checks as `submit_scene_graph`, so a
model that writes "Red Block" or "on top of" still yields canonical names and every
remaining problem is listed. Chat assistants keep using the agent-side path.

Servers disagree on how to ask for a schema, so `response_format` is configurable, as
for the `openai` planner (`verigraph.llm.formats`): `json_schema` (OpenAI, vLLM, Ollama,
Gemini), `json_object_schema` (llama-cpp-python's server), `json_object` or `none`.
"""

from __future__ import annotations

import base64
import json
import os
import re
from typing import Any, Literal

import cv2
import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError

from verigraph.errors import VeriGraphError
from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, Dictionary, load_dictionary
from verigraph.graph.model import ID_PATTERN
from verigraph.graph.submission import SubmittedGraph, check_submission
from verigraph.llm.clients import openai_client
from verigraph.llm.formats import ResponseFormat, response_format_field
from verigraph.perception.config import ImageLimits
from verigraph.perception.imageio import as_bgr
from verigraph.perception.result import PerceptionResult
from verigraph.prompts.filling import scene_graph_prompt

SCHEMA_NAME = "scene_graph"
# A closing fence's spaces are matched from where their run starts (`(?<!\s)`), read once
# (`*+`): tried at every space of a long run, the pattern was quadratic. The last branch is
# a closing fence right after an opening one (which took the spaces between).
_FENCE = re.compile(r"^```(?:json)?\s*+|(?<!\s)\s*+```$|```$", re.MULTILINE)


class VlmError(VeriGraphError):
    """The model's answer could not be turned into a scene graph."""


class VlmConfig(BaseModel):
    """Endpoint settings; missing ones come from VERIGRAPH_VLM_* or OPENAI_* variables."""

    model_config = ConfigDict(extra="forbid")

    base_url: str = Field(description="e.g. https://api.openai.com/v1, "
                                      "http://127.0.0.1:11434/v1 (Ollama)")
    model: str = Field(min_length=1)
    api_key: str | None = Field(default=None, repr=False)
    response_format: ResponseFormat = "json_schema"
    temperature: float = Field(default=0.0, ge=0.0, le=2.0)
    max_tokens: int = Field(default=2048, ge=64)
    timeout_s: float = Field(default=120.0, gt=0)
    retries: int = Field(default=2, ge=0, le=20)
    image_format: Literal["png", "jpeg"] = "png"
    max_nodes: int = Field(default=40, ge=1, le=500, description="schema limit on objects")
    max_edges: int = Field(default=80, ge=0, le=2000, description="schema limit on edges")

    @classmethod
    def from_env(cls, **overrides: Any) -> VlmConfig:
        """Settings from arguments, else VERIGRAPH_VLM_{BASE_URL,MODEL,API_KEY}, else
        OPENAI_{BASE_URL,MODEL,API_KEY}."""
        given = {k: v for k, v in overrides.items() if v is not None}
        for key in ("base_url", "model", "api_key"):
            env = os.environ.get(f"VERIGRAPH_VLM_{key.upper()}") or \
                os.environ.get(f"OPENAI_{key.upper()}")
            if key not in given and env:
                given[key] = env
        given.setdefault("base_url", "https://api.openai.com/v1")
        if not given.get("model"):
            raise VlmError("no vision model named", field="model",
                           fix="pass model=... or set VERIGRAPH_VLM_MODEL")
        return cls.model_validate(given)


def graph_schema(dictionary: Dictionary, *, max_nodes: int = 40,
                 max_edges: int = 80) -> dict[str, Any]:
    """JSON schema of a scene graph over D and R, in the strict subset OpenAI accepts
    (every property required, optional values nullable, no extra properties). The
    length limits stop small models that repeat themselves until the token limit."""
    names = sorted(set(dictionary.names) | {s for p in dictionary.objects.values()
                                            for s in p.synonyms})
    node = {"type": "object", "additionalProperties": False,
            "required": ["id", "label", "attrs"],
            "properties": {
                "id": {"type": "string", "pattern": ID_PATTERN},
                "label": {"type": "string", "enum": names},
                "attrs": {"type": "object", "additionalProperties": False,
                          "required": ["color"],
                          "properties": {"color": {"type": ["string", "null"]}}}}}
    edge = {"type": "object", "additionalProperties": False,
            "required": ["source", "relation", "target", "source_side", "target_side"],
            "properties": {
                "source": {"type": "string"},
                "relation": {"type": "string", "enum": list(dictionary.relations)},
                "target": {"type": "string"},
                "source_side": {"type": ["integer", "null"]},
                "target_side": {"type": ["integer", "null"]}}}
    return {"type": "object", "additionalProperties": False, "required": ["nodes", "edges"],
            "properties": {"nodes": {"type": "array", "items": node, "maxItems": max_nodes},
                           "edges": {"type": "array", "items": edge,
                                     "maxItems": max_edges}}}


def image_data_url(image: np.ndarray, fmt: str = "png") -> str:
    """A BGR image as a data: URL."""
    ok, buf = cv2.imencode(".png" if fmt == "png" else ".jpg", image)
    if not ok:
        raise VlmError("the image could not be encoded", field="image",
                       fix="pass a BGR uint8 image")
    mime = "image/png" if fmt == "png" else "image/jpeg"
    return f"data:{mime};base64,{base64.b64encode(buf.tobytes()).decode('ascii')}"


def build_payload(config: VlmConfig, image: np.ndarray, dictionary: Dictionary,
                  task: str | None = None) -> dict[str, Any]:
    """The chat-completions body: prompt text and image in one user message (some chat
    templates drop system messages)."""
    prompt = scene_graph_prompt(dictionary, task)
    payload: dict[str, Any] = {
        "model": config.model,
        "messages": [{"role": "user", "content": [
            {"type": "text", "text": prompt},
            {"type": "image_url", "image_url": {"url": image_data_url(image,
                                                                      config.image_format)}},
        ]}],
        "temperature": config.temperature,
        "max_tokens": config.max_tokens,
    }
    schema = graph_schema(dictionary, max_nodes=config.max_nodes, max_edges=config.max_edges)
    field = response_format_field(config.response_format, schema, SCHEMA_NAME)
    if field is not None:
        payload["response_format"] = field
    return payload


def answer_text(data: dict[str, Any]) -> tuple[str, bool]:
    """The message content of a chat-completions answer and whether the token limit cut
    it off; VlmError if there is none."""
    try:
        choice = data["choices"][0]
        message = choice["message"]
    except (KeyError, IndexError, TypeError):
        raise VlmError("the endpoint's answer has no choices[0].message", field="response",
                       value=str(data)[:200], fix="check that the endpoint speaks the "
                       "OpenAI chat-completions API") from None
    if message.get("refusal"):
        raise VlmError(f"the model refused: {message['refusal']}", field="response",
                       value=str(message["refusal"])[:200], fix="try another model or image")
    content = message.get("content")
    if isinstance(content, list):  # some servers return content parts
        content = "".join(p.get("text", "") for p in content if isinstance(p, dict))
    if not isinstance(content, str) or not content.strip():
        raise VlmError("the model answered with no text", field="response", value=None,
                       fix="raise max_tokens or use a model that supports images")
    return content, choice.get("finish_reason") == "length"


def parse_graph(text: str, dictionary: Dictionary, *, truncated: bool = False
                ) -> PerceptionResult:
    """A model's JSON answer -> normalised scene graph; problems become warnings."""
    try:
        data = json.loads(_FENCE.sub("", text.strip()))
    except json.JSONDecodeError as exc:
        if truncated:
            raise VlmError("the answer was cut off at the token limit before the JSON "
                           "ended", field="response", value=text[-200:],
                           fix="raise max_tokens, or lower max_nodes so the schema stops a "
                               "model that repeats itself") from None
        raise VlmError(f"the answer is not JSON ({exc.msg} at character {exc.pos})",
                       field="response", value=text[:200],
                       fix="use response_format json_schema or json_object_schema so the "
                           "server constrains the answer") from None
    notes: list[str] = []
    if isinstance(data, dict):
        for node in data.get("nodes", []) if isinstance(data.get("nodes"), list) else []:
            if isinstance(node, dict) and isinstance(node.get("attrs"), dict):
                node["attrs"] = {k: v for k, v in node["attrs"].items() if v is not None}
        for edge in data.get("edges", []) if isinstance(data.get("edges"), list) else []:
            if isinstance(edge, dict) and edge.get("relation") != "touches" and (
                    edge.get("source_side") is not None or edge.get("target_side") is not None):
                notes.append(f"dropped the side numbers of '{edge.get('source')} "
                             f"{edge.get('relation')} {edge.get('target')}' (only tangram "
                             "contacts have sides)")
                edge["source_side"] = edge["target_side"] = None
        data.pop("dictionary", None)
    try:
        submitted = SubmittedGraph.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        raise VlmError(f"the answer is not a scene graph: {err['msg']}",
                       field=".".join(str(p) for p in err["loc"]), value=str(data)[:200],
                       fix="constrain the answer with the graph schema") from None
    graph, renames, problems = check_submission(submitted, dictionary)
    warnings = notes + [f"renamed {r.field}: {r.before} -> {r.after}" for r in renames]
    warnings += [f"[{p.rule}] {p.message} (fix: {p.fix})" for p in problems]
    name = dictionary.name if dictionary.name in BUILTIN_DICTIONARIES else None
    graph = graph.model_copy(update={"dictionary": name})
    return PerceptionResult(graph=graph, view="vlm", family=name, labeller="vlm",
                            warnings=warnings)


class VlmClient:
    """Scene graphs from an OpenAI-compatible vision endpoint."""

    def __init__(self, config: VlmConfig, *, client: Any = None) -> None:
        self.config = config
        if client is None:
            client = openai_client(config.base_url, config.api_key,
                                   timeout=config.timeout_s, retries=config.retries)
        self.client = client

    def perceive(self, image: object, dictionary: Dictionary | str | None = None,
                 task: str | None = None, limits: ImageLimits | None = None
                 ) -> PerceptionResult:
        """Send the image (array, bytes or path) with the SGG prompt and parse the
        constrained answer."""
        bgr = as_bgr(image, limits)
        d = dictionary if isinstance(dictionary, Dictionary) else load_dictionary(dictionary)
        data = self.client.post("chat/completions", build_payload(self.config, bgr, d, task))
        text, truncated = answer_text(data)
        return parse_graph(text, d, truncated=truncated)

    def close(self) -> None:
        self.client.close()
