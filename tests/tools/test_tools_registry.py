"""The tool table, argument errors, solve, and the prompt templates."""

from __future__ import annotations

import json
import re

import pytest

from verigraph import prompts
from verigraph.errors import VeriGraphError
from verigraph.graph.builtin_scenes import cup_on_book, cup_on_book_goal
from verigraph.graph.state import WorldState
from verigraph.prompts.filling import fill_planner_prompt, scene_graph_prompt
from verigraph.tools import TOOL_SPECS, TOOLS, Toolbox, ToolConfig, ToolSpec
from verigraph.tools.registry import parse_arguments

pytestmark = pytest.mark.fast

DESIGN_TOOLS = ["load_scene", "set_goal", "get_state", "validate_action", "execute_actions",
                "validate_plan", "check_goal", "generate_scene_graph", "render_scene", "solve",
                "get_scene_image", "submit_scene_graph", "end_episode", "arm_status", "arm_stop",
                "arm_reset"]


def test_tools_follow_design_order_and_naming() -> None:
    assert [s.name for s in TOOL_SPECS] == DESIGN_TOOLS
    assert all(re.fullmatch(r"[a-z_]+", s.name) for s in TOOL_SPECS)


@pytest.mark.parametrize("spec", TOOL_SPECS, ids=lambda s: s.name)
def test_annotations_are_honest(spec: ToolSpec) -> None:
    changes = {"load_scene", "set_goal", "execute_actions", "submit_scene_graph", "end_episode",
               "arm_stop", "arm_reset"}
    assert spec.read_only == (spec.name not in changes)
    # arm_reset re-enables a stopped arm
    assert spec.destructive == (spec.name in {"execute_actions", "end_episode", "arm_reset"})
    # may connect to or move a robot arm
    assert spec.open_world == (spec.name in {"load_scene", "execute_actions",
                                             "submit_scene_graph", "arm_status", "arm_stop",
                                             "arm_reset"})
    assert (spec.output_model is None) == (spec.name in {"render_scene", "get_scene_image"})


def test_unknown_argument_suggests_the_right_name() -> None:
    box = Toolbox()
    with pytest.raises(VeriGraphError) as err:
        box.call("get_state", {"episode": "x"})
    message = str(err.value)
    assert "episode: unknown argument" in message and "did you mean 'episode_id'" in message
    assert "episode_id: missing required argument" in message


def test_union_errors_name_only_the_relevant_member() -> None:
    box = Toolbox()
    with pytest.raises(VeriGraphError) as err:
        box.call("validate_action", {"episode_id": "e", "action": {"action": "move",
                                                                   "object": "cup"}})
    lines = str(err.value).splitlines()
    assert lines[1].startswith("action.target: Field required")
    assert not any("valid string" in line for line in lines)


def test_json_strings_are_decoded_for_object_arguments() -> None:
    box = Toolbox()
    graph = {"nodes": [{"id": "desk", "label": "desk"}], "edges": []}
    state = box.call("load_scene", {"graph": json.dumps(graph)})
    assert state.graph.node_ids() == ["desk"]


def test_unknown_tool_suggests_a_name() -> None:
    with pytest.raises(VeriGraphError) as err:
        Toolbox().call("validate_actions", {})
    assert "did you mean validate_action" in (err.value.fix or "")


def test_solve_finds_and_verifies_the_cup_on_book_plan() -> None:
    box = Toolbox()
    out = box.call("solve", {"scene_id": "cup_on_book"})
    assert out.reachable and out.verified and out.optimal
    assert out.plan == ["move(cup, on, desk)", "move(book, on, shelf)"]
    eid = box.call("load_scene", {"scene_id": "three_blocks"}).episode_id
    out = box.call("solve", {"episode_id": eid})
    assert out.verified and out.length == 1


def test_solve_reports_unreachable_goals() -> None:
    graph = {"nodes": [{"id": "table", "label": "table"}, {"id": "a", "label": "block"},
                       {"id": "b", "label": "block"}],
             "edges": [{"source": "a", "relation": "on", "target": "table"},
                       {"source": "b", "relation": "on", "target": "table"}],
             "dictionary": "blocks"}
    goal = {"graph": {"nodes": graph["nodes"], "edges": [
        {"source": "a", "relation": "on", "target": "b"},
        {"source": "b", "relation": "on", "target": "a"}]}}
    with pytest.raises(VeriGraphError):  # a cyclic goal is rejected before searching
        Toolbox().call("solve", {"graph": graph, "goal": goal})


def test_solve_can_be_disabled_and_needs_a_goal() -> None:
    with pytest.raises(VeriGraphError) as err:
        Toolbox(config=ToolConfig(enable_solve=False)).call("solve", {"scene_id": "cup_on_book"})
    assert "disabled" in str(err.value)
    with pytest.raises(VeriGraphError) as err:
        Toolbox().call("solve", {"scene_id": "kitchen_pan"})
    assert err.value.field == "goal"


def test_prompt_render_api() -> None:
    assert prompts.PROMPT_NAMES == ("iterative_planner", "direct_planner",
                                    "scene_graph_generation")
    assert "k" in prompts.variables("iterative_planner")
    with pytest.raises(VeriGraphError) as err:
        prompts.render("direct_planner", relations="on")
    assert "current_graph" in str(err.value)
    with pytest.raises(VeriGraphError):
        prompts.render("nope")


def test_planner_prompts_carry_the_method() -> None:
    state = WorldState.from_graph(cup_on_book())
    text = fill_planner_prompt("iterative_planner", state, cup_on_book_goal(), k=2)
    for needle in ("at most 2 actions", "`done`", "- book on desk", "- cup on book",
                   "- book on shelf", "object_not_clear", "move(object, relation, target)",
                   "cup (cup): movable, container"):
        assert needle in text
    assert "$" not in text
    direct = fill_planner_prompt("direct_planner", state, cup_on_book_goal())
    assert "whole plan" in direct and "Propose at most" not in direct


def test_scene_graph_prompt_lists_d_and_r() -> None:
    text = scene_graph_prompt(WorldState.from_graph(cup_on_book()).dictionary, "tidy the desk")
    assert "on, in" in text and "- shelf: fixed, surface" in text and "tidy the desk" in text
    assert '{"nodes": [' in text


def test_which_inputs_make_a_call_heavy_is_each_tool_s_own_field() -> None:
    plan = TOOLS["validate_plan"]
    pddl = {"pddl": {"domain": "(define (domain d))", "problem": "(define (problem p))"},
            "plan": ""}
    small = {"scene_id": "cup_on_book", "plan": ["move(cup, on, desk)"]}
    big = {"scene_id": "cup_on_book", "plan": "\n".join(["move(cup, on, desk)"] * 120)}
    assert plan.heavy_when(pddl) and not plan.heavy_when.large(pddl)  # heavy, cheap to check
    assert not plan.heavy_when(small) and plan.heavy_when(big) and plan.heavy_when.large(big)
    # the raw JSON arguments and the validated input give the same answer
    for arguments in (pddl, small, big):
        assert plan.heavy_when(parse_arguments(plan, arguments)) == plan.heavy_when(arguments)
    load = TOOLS["load_scene"]
    assert not load.heavy_when({"scene_id": "cup_on_book"})
    assert load.heavy_when({"scene_id": "cup_on_book", "simulate": True})
    assert not TOOLS["validate_action"].heavy_when({"episode_id": "e", "action": "done"})
