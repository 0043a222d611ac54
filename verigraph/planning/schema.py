"""The JSON schema an LLM's answer must match: `{"actions": [action, ...]}`.

Kept inside the subset every structured-output implementation accepts (OpenAI strict
mode, llama.cpp grammars, Anthropic tool input): every property required,
`additionalProperties: false`, `enum` instead of `const`, no numeric or length bounds.
Object ids are enumerated from the scene, so a constrained decoder cannot invent an
object (the verifier would catch it anyway; this just spends the model's effort better).
"""

from __future__ import annotations

from typing import Any

from verigraph.actions.schemas import SCHEMAS
from verigraph.graph.dictionary import PLACEMENT_RELATIONS, SUPPORT_RELATIONS
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.prompts.filling import speaks_household

SCHEMA_NAME = "verigraph_actions"


def _object(properties: dict[str, Any]) -> dict[str, Any]:
    return {"type": "object", "properties": properties, "required": list(properties),
            "additionalProperties": False}


def _names(ids: list[str]) -> dict[str, Any]:
    return {"type": "string", "enum": ids} if ids else {"type": "string"}


def action_schema(graph: SceneGraph | None = None, *, constrain_ids: bool = True
                  ) -> dict[str, Any]:
    """Schema of one answer; tangram scenes get `align`, tabletop scenes `move`, household
    scenes also `under`/`nextto` and the state actions of the action table.

    Without a graph both action kinds are allowed and names are free strings.
    """
    ids: list[str] = []
    tangram = tabletop = True
    household = False
    relations = ["on", "in"]
    if graph is not None:
        state = WorldState.from_graph(graph)
        ids = sorted(state.objects) if constrain_ids else []
        tangram = any(o.props.sides for o in state.objects.values())
        tabletop = not tangram
        household = tabletop and speaks_household(state)
        kinds = PLACEMENT_RELATIONS if household else SUPPORT_RELATIONS
        relations = [r for r in state.dictionary.relations if r in kinds] or relations
    variants: list[dict[str, Any]] = []
    if tabletop:
        variants.append(_object({
            "action": {"type": "string", "enum": ["move"]},
            "object": _names(ids),
            "relation": {"type": "string", "enum": relations},
            "target": _names(ids)}))
    if household:
        variants.append(_object({
            "action": {"type": "string",
                       "enum": [name for name, row in SCHEMAS.items() if row.household]},
            "object": _names(ids)}))
    if tangram:
        variants.append(_object({
            "action": {"type": "string", "enum": ["align"]},
            "object": _names(ids),
            "side": {"type": "integer"},
            "target": _names(ids),
            "target_side": {"type": "integer"}}))
    variants.append(_object({"action": {"type": "string", "enum": ["done"]}}))
    return _object({"actions": {"type": "array", "items": {"anyOf": variants}}})


def format_instruction(k: int | None) -> str:
    """Appended to the prompt: the answer format that replaces one-action-per-line."""
    limit = f"at most {k} actions" if k is not None else "the whole plan"
    return (
        "\n## Answer format\nAnswer with one JSON object and nothing else (this replaces the "
        f"one-action-per-line form): {{\"actions\": [...]}} holding {limit} in order, each "
        'written as {"action": "move", "object": ID, "relation": "on" or "in", "target": ID}'
        ' or {"action": "align", "object": PIECE, "side": N, "target": PIECE, '
        '"target_side": M}, and {"action": "done"} as the last item when the goal will hold '
        'after them (or alone when it already holds).\n')
