"""The MCP server in-process, through the SDK client: every tool, resources, prompts."""

from __future__ import annotations

import json
import threading
import time
from typing import Any

import anyio
import pytest
from mcp import Client, MCPError
from mcp_helpers import (  # noqa: F401 - in_process_client: the client fixture
    decode_png,
    in_process_client,
    png_b64,
    structured,
    text,
)

from verigraph.server import INSTRUCTIONS, build_server
from verigraph.tools import TOOL_SPECS, TOOLS, Toolbox

pytestmark = [pytest.mark.fast, pytest.mark.anyio]
STATEFUL = [s.name for s in TOOL_SPECS if "episode_id" in s.input_model.model_fields
            and s.input_model.model_fields["episode_id"].is_required()]


async def load(client: Client, **args: Any) -> str:
    return str(structured(await client.call_tool("load_scene", args or {
        "scene_id": "cup_on_book"}))["episode_id"])


async def test_server_identity_and_instructions(client: Client) -> None:
    assert client.server_info is not None and client.server_info.name == "verigraph"
    assert client.instructions.startswith(INSTRUCTIONS) and "episode_id" in INSTRUCTIONS


async def test_tools_list_matches_the_tool_table(client: Client) -> None:
    tools = (await client.list_tools()).tools
    assert [t.name for t in tools] == [s.name for s in TOOL_SPECS]
    for tool in tools:
        spec = TOOLS[tool.name]
        assert tool.title == spec.title and tool.description == spec.description
        assert tool.annotations is not None
        hints = tool.annotations  # an absent hint means the specification's default
        assert (hints.read_only_hint or False) is spec.read_only
        if not spec.read_only:
            assert hints.destructive_hint in ((None, True) if spec.destructive else (False,))
        assert (hints.idempotent_hint or False) is spec.idempotent
        assert hints.open_world_hint in ((None, True) if spec.open_world else (False,))
        assert set(tool.input_schema["properties"]) == set(spec.input_model.model_fields)
        required = {n for n, f in spec.input_model.model_fields.items() if f.is_required()}
        assert set(tool.input_schema.get("required", [])) == required
        if spec.output_model is None:
            assert tool.output_schema is None
        else:
            assert tool.output_schema is not None
            assert set(tool.output_schema["properties"]) == set(spec.output_model.model_fields)


async def test_cup_on_book_episode_end_to_end(client: Client) -> None:
    eid = await load(client)
    bad = await client.call_tool("execute_actions", {"episode_id": eid,
                                                     "actions": ["move(book, on, shelf)"]})
    out = structured(bad)
    assert out["violation"]["constraint"] == "object_not_clear" and out["tau"] == 1
    assert text(bad).startswith("executed none; stopped: step 1: [object_not_clear]")
    good = structured(await client.call_tool("execute_actions", {"episode_id": eid, "actions": [
        {"action": "move", "object": "cup", "relation": "on", "target": "desk"},
        "move(book, on, shelf)", "done"]}))
    assert good["ok"] and good["goal_satisfied"] and good["done"] and good["tau"] == 0
    verdict = await client.call_tool("end_episode", {"episode_id": eid})
    assert structured(verdict)["verdict"] == "goal_reached"
    assert text(verdict).startswith("SUCCESS: goal reached")


async def test_every_read_only_tool_leaves_the_episode_unchanged(client: Client) -> None:
    eid = await load(client)
    before = structured(await client.call_tool("get_state", {"episode_id": eid}))
    calls = {
        "get_state": {},
        "validate_action": {"action": "move(cup, desk)"},
        "validate_plan": {"plan": "move(cup, desk)\nmove(book, shelf)"},
        "check_goal": {},
        "render_scene": {},
        "solve": {},
        "get_scene_image": {},
    }
    for name, args in calls.items():
        result = await client.call_tool(name, {"episode_id": eid, **args})
        assert not result.is_error, (name, text(result))
        assert TOOLS[name].read_only
    assert structured(await client.call_tool("get_state", {"episode_id": eid})) == before


async def test_structured_results_and_summaries(client: Client) -> None:
    eid = await load(client)
    check = await client.call_tool("validate_action", {"episode_id": eid,
                                                       "action": "move(cup, on, desk)"})
    assert structured(check)["would_change"]["added"][0]["target"] == "desk"
    assert text(check).startswith("valid: move(cup, on, desk) (-cup on book, +cup on desk)\n")
    report = await client.call_tool("validate_plan", {"scene_id": "cup_on_book",
                                                      "plan": "move(book, shelf)"})
    assert structured(report)["violations"][0]["constraint"] == "object_not_clear"
    assert text(report).startswith("INVALID: 1 step(s) checked")
    goal = await client.call_tool("check_goal", {"episode_id": eid})
    assert structured(goal)["satisfied"] is False and text(goal).startswith("goal not reached")
    solved = structured(await client.call_tool("solve", {"episode_id": eid}))
    assert solved["plan"] == ["move(cup, on, desk)", "move(book, on, shelf)"]
    state = structured(await client.call_tool("set_goal", {"episode_id": eid,
                                                           "predicate": "single_stack"}))
    assert state["goal"]["predicate"] == "single_stack"


async def test_image_tools_return_image_content_only(client: Client) -> None:
    eid = await load(client)
    render = await client.call_tool("render_scene", {"episode_id": eid, "width": 200,
                                                     "height": 100})
    assert not render.is_error and render.structured_content is None
    assert [c.type for c in render.content] == ["image", "text"]  # the image, its caption
    assert render.content[0].mime_type == "image/png"
    assert decode_png(render.content[0].data).shape == (100, 200, 3)
    scene = await client.call_tool("get_scene_image", {"episode_id": eid, "task": "tidy"})
    assert scene.structured_content is None and [c.type for c in scene.content] == [
        "image", "text"]
    assert "Dictionary: tableware" in scene.content[1].text and "tidy" in scene.content[1].text


async def test_agent_vlm_route_through_the_server(client: Client) -> None:
    eid = await load(client, image=png_b64(), dictionary="tableware")
    submitted = structured(await client.call_tool("submit_scene_graph", {
        "episode_id": eid, "graph": {
            "nodes": [{"id": "desk", "label": "desk"}, {"id": "Cup", "label": "teacup"}],
            "edges": [{"source": "Cup", "relation": "on", "target": "desk"}]}}))
    assert submitted["accepted"] and submitted["adopted"]
    assert {"field": "nodes[1].label", "before": "teacup", "after": "cup",
            "reading": "teacup read as cup (synonym, tableware dictionary)"} in submitted[
        "normalised"]
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["graph"]["edges"] == [{"source": "cup", "relation": "on", "target": "desk",
                                        "source_side": None, "target_side": None}]


async def test_simulated_episode_renders_the_simulator(client: Client) -> None:
    eid = await load(client, generator={"family": "tangram", "seed": 1}, simulate=True)
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert state["simulated"] and state["relations"] == ["touches"]
    render = await client.call_tool("render_scene", {"episode_id": eid, "view": "goal"})
    assert [c.type for c in render.content] == ["image", "text"]
    assert "simulator's picture" in text(render)
    assert decode_png(render.content[0].data).std() > 5


async def test_generate_scene_graph_returns_the_perceived_graph(client: Client) -> None:
    eid = await load(client, generator={"family": "tableware", "seed": 2}, simulate=True)
    result = await client.call_tool("generate_scene_graph", {"episode_id": eid})
    assert not result.is_error, text(result)
    perceived = structured(result)
    state = structured(await client.call_tool("get_state", {"episode_id": eid}))
    assert perceived["accepted"]
    assert sorted(e["source"] for e in perceived["graph"]["edges"]) == sorted(
        e["source"] for e in state["graph"]["edges"])


@pytest.mark.parametrize("tool", STATEFUL)
async def test_unknown_episode_is_a_tool_error_naming_the_field(client: Client,
                                                                 tool: str) -> None:
    args = {"episode_id": "ep_doesnotexist"}
    extra = {"validate_action": {"action": "done"}, "execute_actions": {"actions": ["done"]},
             "set_goal": {"predicate": "single_stack"}}
    result = await client.call_tool(tool, {**args, **extra.get(tool, {})})
    assert result.is_error
    assert "episode_id: no open episode with id 'ep_doesnotexist'" in text(result)
    assert "fix: pass the episode_id returned by load_scene" in text(result)


@pytest.mark.parametrize("tool, args, needles", [
    ("load_scene", {"scene_id": "cup_on_book", "k": 0}, ["k: Input should be greater than"]),
    ("load_scene", {"scenario": "cup_on_book"}, ["scenario: unknown argument",
                                                 "did you mean 'scene_id'"]),
    ("validate_action", {"episode_id": "e"}, ["action: missing required argument"]),
    ("execute_actions", {"episode_id": "e", "actions": []},
     ["actions: List should have at least 1 item"]),
    ("validate_plan", {"scene_id": "cup_on_book", "plan": 42},
     ["plan: Input should be a valid string"]),
    ("render_scene", {"episode_id": "e", "width": 10**6}, ["width: Input should be less than"]),
    ("submit_scene_graph", {"graph": {"nodes": [{"id": "a"}]}},
     ["graph.nodes[0].label: Field required"]),
    ("solve", {}, ["exactly one of episode_id, scene_id, graph"]),
    ("load_scene", {"image": "%%%"}, ["image: image is not valid base64"]),
])
async def test_bad_arguments_are_tool_errors(client: Client, tool: str, args: dict[str, Any],
                                             needles: list[str]) -> None:
    result = await client.call_tool(tool, args)
    assert result.is_error and result.structured_content is None
    for needle in needles:
        assert needle in text(result)
    assert "https://errors.pydantic.dev" not in text(result)
    still = await client.call_tool("load_scene", {"scene_id": "three_blocks"})
    assert not still.is_error


async def test_a_busy_episode_does_not_stall_other_episodes() -> None:
    toolbox = Toolbox()
    async with Client(build_server(toolbox)) as c:
        busy, free = await load(c), await load(c)
        release = threading.Event()
        held = threading.Event()

        def hold() -> None:
            with toolbox.context.store.use(busy):
                held.set()
                release.wait(5)

        holder = threading.Thread(target=hold)
        holder.start()
        held.wait(5)
        waiting: list[Any] = []

        async def call_busy() -> None:
            waiting.append(await c.call_tool("validate_action", {
                "episode_id": busy, "action": "move(cup, desk)"}))

        async with anyio.create_task_group() as tg:
            tg.start_soon(call_busy)
            start = time.perf_counter()
            other = await c.call_tool("validate_action", {"episode_id": free,
                                                          "action": "move(cup, desk)"})
            assert not other.is_error and time.perf_counter() - start < 2
            assert not waiting  # the busy episode's call is still waiting, off the loop
            release.set()
        holder.join()
        assert structured(waiting[0])["ok"] is True


async def test_json_looking_strings_keep_their_meaning(client: Client) -> None:
    graph = {"nodes": [{"id": "desk", "label": "desk"}], "edges": []}
    result = await client.call_tool("submit_scene_graph", {"episode_id": "null",
                                                           "graph": graph})
    assert result.is_error and "no open episode with id 'null'" in text(result)
    eid = await load(client)
    as_json = await client.call_tool("validate_action", {
        "episode_id": eid, "action": '{"action": "move", "object": "cup", "target": "desk"}'})
    assert structured(as_json)["action"] == "move(cup, on, desk)"


async def test_unknown_tool_is_an_error_result(client: Client) -> None:
    result = await client.call_tool("teleport", {})
    assert result.is_error and "Unknown tool: teleport" in text(result)


async def test_resources_static_and_per_episode(client: Client) -> None:
    uris = [str(r.uri) for r in (await client.list_resources()).resources]
    assert uris == ["verigraph://dictionaries/blocks", "verigraph://dictionaries/kitchen",
                    "verigraph://dictionaries/tableware", "verigraph://dictionaries/tangram",
                    "verigraph://dictionaries/household", "verigraph://dictionaries/all",
                    "verigraph://relations",
                    "verigraph://schema/action", "verigraph://constraints",
                    "verigraph://scenes"]
    templates = [t.uri_template for t in (await client.list_resource_templates())
                 .resource_templates]
    assert templates == ["verigraph://episodes/{episode_id}/graph",
                         "verigraph://episodes/{episode_id}/goal"]

    async def read(uri: str) -> Any:
        contents = (await client.read_resource(uri)).contents
        assert contents[0].mime_type == "application/json"
        return json.loads(contents[0].text)

    blocks = await read("verigraph://dictionaries/blocks")
    assert blocks["objects"]["block"]["capacity"] == 1 and blocks["relations"] == ["on"]
    relations = await read("verigraph://relations")
    assert relations["by_dictionary"]["tangram"] == ["touches"]
    assert relations["by_dictionary"]["kitchen"] == ["on", "in"]
    assert relations["all"] == ["on", "in", "touches"]
    household = await read("verigraph://dictionaries/household")
    assert household["objects"]["fridge"]["openable"] and "inroom" in household["relations"]
    schema = await read("verigraph://schema/action")
    assert {m["$ref"].rsplit("/", 1)[-1] for m in schema["oneOf"]} == {
        "MoveAction", "StateAction", "AlignAction", "DoneAction"}
    assert "object_not_clear" in await read("verigraph://constraints")
    assert set(await read("verigraph://scenes")) == {"cup_on_book", "three_blocks",
                                                      "kitchen_pan", "kitchen_household"}
    eid = await load(client)
    graph = await read(f"verigraph://episodes/{eid}/graph")
    assert {(e["source"], e["target"]) for e in graph["edges"]} == {("book", "desk"),
                                                                    ("cup", "book")}
    goal = await read(f"verigraph://episodes/{eid}/goal")
    assert goal["instruction"] == "Put the book on the shelf."
    with pytest.raises(MCPError) as err:
        await client.read_resource("verigraph://episodes/ep_missing/graph")
    assert err.value.code == -32602 and "no open episode" in err.value.message


async def test_prompts_from_an_episode_and_standalone(client: Client) -> None:
    prompts = (await client.list_prompts()).prompts
    assert [p.name for p in prompts] == ["iterative_planner", "direct_planner",
                                         "scene_graph_generation"]
    eid = await load(client, scene_id="cup_on_book", k=2)
    await client.call_tool("execute_actions", {"episode_id": eid,
                                               "actions": ["move(book, shelf)"]})
    got = await client.get_prompt("iterative_planner", {"episode_id": eid})
    body = got.messages[0].content.text
    assert got.messages[0].role == "user"
    assert "Propose at most 2 actions" in body and "[object_not_clear]" in body
    assert f'episode_id="{eid}"' in body
    standalone = (await client.get_prompt("direct_planner", {})).messages[0].content.text
    assert 'load_scene(scene_id="cup_on_book")' in standalone and "- cup on book" in standalone
    sg = (await client.get_prompt("scene_graph_generation", {"dictionary": "kitchen",
                                                             "task": "cook"}))
    assert "Dictionary: kitchen" in sg.messages[0].content.text


async def test_prompt_errors_are_invalid_params_with_the_reason(client: Client) -> None:
    with pytest.raises(MCPError) as err:
        await client.get_prompt("iterative_planer", {})
    assert err.value.code == -32602
    assert "did you mean iterative_planner" in err.value.message
    assert "scene_graph_generation" in err.value.message
    with pytest.raises(MCPError) as err:
        await client.get_prompt("iterative_planner", {"episode_id": "ep_gone"})
    assert err.value.code == -32602 and "no open episode" in err.value.message
    with pytest.raises(MCPError) as err:
        await client.get_prompt("direct_planner", {"scene": "cup_on_book"})
    assert err.value.code == -32602 and "it takes episode_id, scene_id" in err.value.message
    with pytest.raises(MCPError) as err:
        await client.get_prompt("scene_graph_generation", {"dictionary": "garden"})
    assert err.value.code == -32602 and "not a built-in dictionary" in err.value.message


async def test_prompt_arguments_and_descriptions_read_well(client: Client) -> None:
    for prompt in (await client.list_prompts()).prompts:
        assert prompt.description and "\n" not in prompt.description
        assert "  " not in prompt.description
        assert prompt.arguments
        for argument in prompt.arguments:
            assert argument.description, f"{prompt.name}.{argument.name}"


async def test_generate_scene_graph_without_photo_or_simulator_says_so(client: Client) -> None:
    eid = await load(client, scene_id="cup_on_book")
    result = await client.call_tool("generate_scene_graph", {"episode_id": eid})
    assert result.is_error and result.structured_content is None
    message = text(result)
    assert "no photo and no simulator" in message and "episode_id" in message
    assert "fix: pass image" in message and "get_state" in message
