"""Generated bad input for every tool: always a tool error, the server keeps serving, and no
episode changes.

Each example takes a valid call and breaks it in one way that must be refused: an
unknown argument, a missing required one, a value of the wrong JSON type, an unknown
episode id, an unparseable action, an invalid image, an over-long string.
"""

from __future__ import annotations

import base64
import os
import string
from collections.abc import Iterator
from typing import Any

import pytest
from anyio.from_thread import BlockingPortal, start_blocking_portal
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from mcp import Client
from mcp.types import CallToolResult
from mcp_helpers import structured, text

from verigraph.actions.parser import parse_text_plan
from verigraph.errors import VeriGraphError
from verigraph.server import build_server
from verigraph.tools import TOOL_SPECS, Toolbox

CUP_GRAPH = {"nodes": [{"id": n, "label": n} for n in ("desk", "shelf", "book", "cup")],
             "edges": [{"source": "book", "relation": "on", "target": "desk"},
                       {"source": "cup", "relation": "on", "target": "book"}]}


def valid_call(name: str, eid: str) -> dict[str, Any]:
    return {
        "load_scene": {"scene_id": "cup_on_book"},
        "set_goal": {"episode_id": eid, "predicate": "single_stack"},
        "validate_action": {"episode_id": eid, "action": "move(cup, desk)"},
        "execute_actions": {"episode_id": eid, "actions": ["move(cup, desk)"]},
        "validate_plan": {"episode_id": eid, "plan": "move(cup, desk)"},
        "generate_scene_graph": {"image": PNG},
        "submit_scene_graph": {"episode_id": eid, "graph": CUP_GRAPH},
    }.get(name, {"episode_id": eid})


PNG = ("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4z8AAAAMBAQDJ/pLvAAAAAElFTkSu"
       "QmCC")


class Harness:
    """One in-process server and client shared by all examples (via a blocking portal)."""

    def __init__(self, portal: BlockingPortal, client: Client, toolbox: Toolbox) -> None:
        self.portal = portal
        self.client = client
        self.toolbox = toolbox
        self.eid = str(structured(self.call("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"])
        self.call("execute_actions", {"episode_id": self.eid, "actions": ["move(book, shelf)"]})
        self.baseline = self.fingerprint()

    def call(self, name: str, args: dict[str, Any]) -> CallToolResult:
        async def run() -> CallToolResult:
            return await self.client.call_tool(name, args)
        return self.portal.call(run)

    def fingerprint(self) -> tuple[dict[str, Any], int]:
        return (structured(self.call("get_state", {"episode_id": self.eid})),
                len(self.toolbox.context.store))


@pytest.fixture(scope="module")
def harness() -> Iterator[Harness]:
    toolbox = Toolbox()
    with start_blocking_portal() as portal:
        client = portal.wrap_async_context_manager(Client(build_server(toolbox)))
        with client as entered:
            yield Harness(portal, entered, toolbox)


def wrong_type(kind: str) -> st.SearchStrategy[Any]:
    """JSON values that can never validate for a field of this kind."""
    if kind == "str":
        return st.one_of(st.integers(), st.booleans(), st.lists(st.integers(), max_size=3),
                         st.dictionaries(st.text(max_size=3), st.integers(), max_size=2))
    if kind in ("int", "bool"):
        return st.one_of(st.lists(st.integers(), min_size=1, max_size=3),
                         st.dictionaries(st.text(max_size=3), st.integers(), min_size=1,
                                         max_size=2))
    if kind == "list":
        return st.one_of(st.integers(), st.booleans(), st.dictionaries(
            st.sampled_from(["a", "b"]), st.integers(), min_size=1, max_size=2))
    return st.one_of(st.integers(), st.booleans(), st.lists(st.integers(), max_size=3))


FIELD_KINDS = {
    "episode_id": "str", "scene_id": "str", "image": "str", "task": "str",
    "dictionary": "object",  # a built-in name or an inline dictionary: never a number or list
    "instruction": "str", "action": "object", "actions": "list", "plan": "object",
    "graph": "object", "goal": "object", "generator": "object", "predicate": "str",
    "view": "str", "k": "int", "t": "int", "seed": "int", "width": "int", "height": "int",
    "max_expansions": "int", "partial": "bool", "simulate": "bool", "all_errors": "bool",
    "executor": "str", "reason": "str", "request_id": "str", "expected_calls": "int",
    "edges": "str", "pddl": "object", "formula": "str", "bddl": "str", "whole_plan": "bool",
    "time_limit": "int", "memory_limit_mb": "int", "anytime": "bool",
}


def not_an_action(s: str) -> bool:
    if s.lstrip().startswith(("{", "[")):
        return False  # JSON text is decoded as a JSON action, which may be valid
    try:
        return not parse_text_plan(s)
    except VeriGraphError:
        return True


def breakages(name: str) -> st.SearchStrategy[tuple[str, Any, Any]]:
    spec = next(s for s in TOOL_SPECS if s.name == name)
    fields = spec.input_model.model_fields
    options: list[st.SearchStrategy[tuple[str, Any, Any]]] = [
        st.tuples(st.just("extra"), st.text(string.ascii_letters + "_", min_size=1,
                                             max_size=12).filter(lambda k: k not in fields),
                  st.integers())]
    required = [f for f, info in fields.items() if info.is_required()]
    if required:
        options.append(st.tuples(st.just("missing"), st.sampled_from(required), st.none()))
    typed = [f for f in fields if f != "plan"]
    options.append(st.sampled_from(typed).flatmap(
        lambda f: st.tuples(st.just("wrong_type"), st.just(f), wrong_type(FIELD_KINDS[f]))))
    if "episode_id" in fields:
        options.append(st.tuples(st.just("unknown_episode"), st.just("episode_id"), st.text(
            string.ascii_letters + string.digits + "_-", min_size=1, max_size=40)))
    if name in ("validate_action", "execute_actions"):
        options.append(st.tuples(st.just("bad_action"), st.just(name),
                                 st.text(max_size=40).filter(not_an_action)))
    if "image" in fields:
        options.append(st.tuples(st.just("bad_image"), st.just("image"),
                                 st.binary(min_size=1, max_size=64)))
    long_str = [f for f in ("episode_id", "scene_id", "dictionary") if f in fields]
    if long_str:
        options.append(st.tuples(st.just("too_long"), st.sampled_from(long_str),
                                 st.integers(65, 400)))
    return st.one_of(options)


def broken(name: str, eid: str, how: str, key: Any, value: Any) -> dict[str, Any]:
    args = dict(valid_call(name, eid))
    if how == "extra":
        args[key] = value
    elif how == "missing":
        args.pop(key, None)
    elif how in ("wrong_type", "unknown_episode"):
        args[key] = value
    elif how == "bad_action":
        args["action" if name == "validate_action" else "actions"] = (
            value if name == "validate_action" else [value])
    elif how == "bad_image":
        args = {"image": base64.b64encode(value).decode()}
        if name == "set_goal":
            args["episode_id"] = eid
    elif how == "too_long":
        args[key] = "x" * value
    return args


@pytest.mark.parametrize("name", [s.name for s in TOOL_SPECS])
def test_bad_input_is_refused_and_changes_nothing(harness: Harness, name: str) -> None:
    @settings(max_examples=int(os.environ.get("FUZZ_EXAMPLES", "25")), deadline=None,
              suppress_health_check=[HealthCheck.function_scoped_fixture,
                                     HealthCheck.filter_too_much])
    @given(breakages(name))
    def check(breakage: tuple[str, Any, Any]) -> None:
        how, key, value = breakage
        if how == "missing" and name == "load_scene":
            assume(False)
        args = broken(name, harness.eid, how, key, value)
        result = harness.call(name, args)
        assert result.is_error, (name, how, args, text(result))
        assert result.structured_content is None
        message = text(result)
        assert message.startswith(f"Error executing tool {name}: "), message
        assert "Traceback" not in message and "errors.pydantic.dev" not in message
        assert harness.fingerprint() == harness.baseline

    check()
    # Still serving after everything above.
    assert not harness.call("get_state", {"episode_id": harness.eid}).is_error


def test_unknown_objects_in_actions_are_violations_that_change_no_graph(
        harness: Harness) -> None:
    toolbox = harness.toolbox
    eid = toolbox.call("load_scene", {"scene_id": "cup_on_book"}).episode_id
    before = toolbox.call("get_state", {"episode_id": eid})
    checked = structured(harness.call("validate_action", {"episode_id": eid,
                                                          "action": "move(mug, on, desk)"}))
    assert checked["violation"]["constraint"] == "unknown_object"
    ran = structured(harness.call("execute_actions", {"episode_id": eid,
                                                      "actions": ["move(cup, on, bookshelf)"]}))
    assert ran["violation"]["constraint"] == "unknown_object"
    assert "shelf" in ran["violation"]["suggestion"]
    after = toolbox.call("get_state", {"episode_id": eid})
    assert after.graph == before.graph and after.executed == []
    assert after.tau == 1  # Algorithm 1 counts the failed iteration
