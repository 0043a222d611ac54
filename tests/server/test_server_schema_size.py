"""tools/list stays small and plain: measured sizes, descriptions, strict-schema keywords.

Every chat turn sends tools/list to the model. The test prints both figures (run with
`-s` to see them) and fails above the limits.
"""

from __future__ import annotations

import json
from typing import Any

import pytest
from jsonschema import Draft202012Validator
from mcp import Client

from verigraph.server import build_server

pytestmark = pytest.mark.fast

# Raised from 40,000 and 15,000 with the household world (object states in every graph,
# four more actions and the rules they follow, the state changes of an edit, a goal's
# missing states), the descriptions that state the rules of a move, the attrs keys, the
# executors and the PDDL planner (a model meets them otherwise only by failing), goal
# formulas (a goal's `formula`, set_goal's with its one example, a goal diff's
# `formula_detail`), BEHAVIOR-1K (load_scene's `bddl`, the five process actions' names)
# and a submitted node's `state` (submit_scene_graph).
MAX_TOTAL_BYTES = 43_700
MAX_CORE_BYTES = 16_700  # names + descriptions + input schemas


def compact(data: Any) -> int:
    return len(json.dumps(data, separators=(",", ":")))


async def wire_tools() -> list[dict[str, Any]]:
    async with Client(build_server()) as client:
        tools = (await client.list_tools()).tools
    return [t.model_dump(mode="json", by_alias=True, exclude_none=True) for t in tools]


def keys_anywhere(schema: Any) -> set[str]:
    if isinstance(schema, dict):
        found = set(schema)
        for value in schema.values():
            found |= keys_anywhere(value)
        return found
    if isinstance(schema, list):
        return set().union(*(keys_anywhere(v) for v in schema)) if schema else set()
    return set()


@pytest.mark.anyio
async def test_tools_list_fits_the_budget() -> None:
    tools = await wire_tools()
    total = compact({"tools": tools})
    core = sum(len(t["name"]) + len(t["description"]) + compact(t["inputSchema"])
               for t in tools)
    print(f"\ntools/list: {total} bytes in all, {core} bytes for names + descriptions + "
          f"input schemas ({len(tools)} tools)")
    assert total <= MAX_TOTAL_BYTES, f"tools/list is {total} bytes (limit {MAX_TOTAL_BYTES})"
    assert core <= MAX_CORE_BYTES, f"names+descriptions+inputs: {core} (limit {MAX_CORE_BYTES})"


@pytest.mark.anyio
async def test_every_top_level_input_has_its_own_description() -> None:
    for tool in await wire_tools():
        for name, prop in tool["inputSchema"].get("properties", {}).items():
            assert prop.get("description"), f"{tool['name']}.{name} has no description"


@pytest.mark.anyio
async def test_no_openapi_keywords_and_every_schema_is_valid_2020_12() -> None:
    for tool in await wire_tools():
        for kind in ("inputSchema", "outputSchema"):
            schema = tool.get(kind)
            if schema is None:
                continue
            Draft202012Validator.check_schema(schema)
            assert not keys_anywhere(schema) & {"discriminator", "nullable", "example"}, \
                f"{tool['name']}.{kind}"


@pytest.mark.anyio
async def test_published_inputs_accept_what_the_server_accepts() -> None:
    """The compact inputs still describe real calls (JSON and text actions, graphs)."""
    schemas = {t["name"]: t["inputSchema"] for t in await wire_tools()}
    graph = {"nodes": [{"id": "cup", "label": "cup"}, {"id": "table", "label": "table"}],
             "edges": [{"source": "cup", "relation": "on", "target": "table"}]}
    calls = [
        ("load_scene", {"scene_id": "cup_on_book", "k": 2}),
        ("load_scene", {"graph": graph, "goal": {"graph": graph, "partial": True}}),
        ("validate_action", {"episode_id": "ep_x", "action": "move(cup, on, table)"}),
        ("validate_action", {"episode_id": "ep_x",
                             "action": {"action": "move", "object": "cup", "target": "table"}}),
        ("execute_actions", {"episode_id": "ep_x", "actions": [
            {"action": "align", "object": "a", "side": 0, "target": "b", "target_side": 1},
            {"action": "done"}, "done"]}),
        ("validate_plan", {"graph": graph, "plan": "move(cup, table)\ndone"}),
    ]
    for name, arguments in calls:
        errors = list(Draft202012Validator(schemas[name]).iter_errors(arguments))
        assert not errors, (name, [e.message for e in errors])
    bad = Draft202012Validator(schemas["load_scene"]).iter_errors({"k": "three"})
    assert list(bad), "a wrongly typed argument must not validate"


@pytest.mark.anyio
async def test_every_structured_result_matches_its_published_output_schema() -> None:
    """Successes, refusals and rejections alike, across the tools that return structure."""
    validators: dict[str, Draft202012Validator] = {}
    checked: set[str] = set()
    async with Client(build_server()) as client:
        for tool in (await client.list_tools()).tools:
            if tool.output_schema is not None:
                validators[tool.name] = Draft202012Validator(tool.output_schema)

        async def call(name: str, arguments: dict[str, Any]) -> dict[str, Any]:
            result = await client.call_tool(name, arguments)
            assert not result.is_error, (name, result.content)
            data = result.structured_content or {}
            errors = [e.message for e in validators[name].iter_errors(data)]
            assert not errors, (name, errors[:3])
            checked.add(name)
            return data

        eid = (await call("load_scene", {"scene_id": "cup_on_book", "k": 2}))["episode_id"]
        await call("validate_action", {"episode_id": eid, "action": "move(book, shelf)"})
        await call("validate_action", {"episode_id": eid, "action": "move(cup, desk)"})
        await call("execute_actions", {"episode_id": eid, "actions": ["move(book, shelf)"]})
        await call("get_state", {"episode_id": eid})
        await call("execute_actions", {"episode_id": eid,
                                       "actions": ["move(cup, desk)", "move(book, shelf)"]})
        await call("check_goal", {"episode_id": eid})
        await call("set_goal", {"episode_id": eid, "predicate": "single_stack"})
        await call("set_goal", {"episode_id": eid, "instruction": "tidy up"})
        await call("validate_plan", {"scene_id": "three_blocks", "plan": "move(a, b)\ndone",
                                     "all_errors": True})
        await call("solve", {"scene_id": "cup_on_book"})
        await call("submit_scene_graph", {"graph": {"nodes": [{"id": "x", "label": "dragon"}]}})
        await call("submit_scene_graph", {"graph": {
            "nodes": [{"id": "cup", "label": "mug"}, {"id": "table", "label": "table"}],
            "edges": [{"source": "cup", "relation": "on", "target": "table"}]}})
        await call("end_episode", {"episode_id": eid})
        sim = (await call("load_scene", {"generator": {"family": "blocks", "seed": 1},
                                         "simulate": True}))["episode_id"]
        await call("generate_scene_graph", {"episode_id": sim})
        await call("end_episode", {"episode_id": sim})
    assert checked >= set(validators) - {"arm_status", "arm_stop", "arm_reset"}


@pytest.mark.anyio
async def test_the_action_schema_resource_is_strict_2020_12() -> None:
    async with Client(build_server()) as client:
        read = await client.read_resource("verigraph://schema/action")
    schema = json.loads(read.contents[0].text)  # type: ignore[union-attr]
    Draft202012Validator.check_schema(schema)
    assert "discriminator" not in keys_anywhere(schema)
    validator = Draft202012Validator(schema)
    assert validator.is_valid({"action": "move", "object": "cup", "target": "table"})
    assert not validator.is_valid({"action": "fly"})
