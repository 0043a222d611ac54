"""load_scene, set_goal, get_state, end_episode through the transport-free Toolbox."""

from __future__ import annotations

from typing import Any

import pytest
from mcp_helpers import png_b64

from verigraph.errors import VeriGraphError
from verigraph.sim2d.render import encode_png
from verigraph.tools import Toolbox, ToolConfig, UnknownEpisodeError
from verigraph.tools.errors import EpisodeLimitError

pytestmark = pytest.mark.fast

CUP_PLAN = ["move(cup, on, desk)", "move(book, on, shelf)"]


def load(box: Toolbox, **args: Any) -> Any:
    return box.call("load_scene", args)


def test_load_builtin_scene_with_its_goal() -> None:
    box = Toolbox()
    state = load(box, scene_id="cup_on_book")
    assert state.graph.sentences() == ["book on desk", "cup on book"]
    assert state.goal is not None and state.goal_satisfied is False
    assert state.goal_diff.missing_edges == ["book on shelf", "cup on desk"]
    assert (state.k, state.t, state.tau) == (3, 5, 0)
    assert state.dictionary == "tableware" and "in" in state.relations
    assert state.episode_id in state.summary()


def test_load_graph_normalises_synonym_labels() -> None:
    box = Toolbox()
    graph = {"nodes": [{"id": "table", "label": "table"}, {"id": "b1", "label": "Cube"}],
             "edges": [{"source": "b1", "relation": "on", "target": "table"}],
             "dictionary": "blocks"}
    state = load(box, graph=graph, k=2, t=3)
    assert [n.label for n in state.graph.nodes] == ["block", "table"]
    assert (state.k, state.t) == (2, 3)


def test_load_rejects_a_malformed_graph_listing_every_problem() -> None:
    box = Toolbox()
    graph = {"nodes": [{"id": "cup", "label": "cup"}, {"id": "x", "label": "unicorn"},
                       {"id": "desk", "label": "desk"}],
             "edges": [{"source": "desk", "relation": "on", "target": "cup"}]}
    with pytest.raises(VeriGraphError) as err:
        load(box, graph=graph)
    message = str(err.value)
    assert "unicorn" in message and "missing support" not in message
    assert "'cup' (cup) has no support edge" in message
    assert "is not a surface" in message
    assert len(box.context.store) == 0


def test_dictionary_files_cannot_be_read_through_tools(tmp_path: Any) -> None:
    secret = tmp_path / "d.yaml"
    secret.write_text("name: x\nobjects: {}\n")
    box = Toolbox()
    graph = {"nodes": [{"id": "desk", "label": "desk"}], "edges": [], "dictionary": str(secret)}
    with pytest.raises(VeriGraphError) as err:
        load(box, graph=graph)
    assert err.value.field == "graph.dictionary"
    assert "cannot be read" in (err.value.fix or "")


def test_exactly_one_source_is_required() -> None:
    box = Toolbox()
    for args in ({}, {"scene_id": "cup_on_book", "graph": {"nodes": [], "edges": []}}):
        with pytest.raises(VeriGraphError) as err:
            box.call("load_scene", args)
        assert "exactly one of scene_id, graph, image, generator" in str(err.value)


def test_unknown_scene_id_lists_the_known_ones() -> None:
    with pytest.raises(VeriGraphError) as err:
        load(Toolbox(), scene_id="cup_on_boo")
    assert err.value.field == "scene_id" and "cup_on_book" in (err.value.fix or "")


def test_image_episode_waits_for_a_submitted_graph() -> None:
    """A blank photo: built-in perception finds nothing, so the agent's graph is awaited."""
    box = Toolbox()
    state = load(box, image=png_b64(), dictionary="tableware")
    assert state.awaiting_scene_graph and state.graph is None
    assert "submit_scene_graph" in state.summary()
    with pytest.raises(VeriGraphError) as err:
        box.call("execute_actions", {"episode_id": state.episode_id, "actions": ["done"]})
    assert "submit_scene_graph" in (err.value.fix or "")


def test_set_goal_graph_predicate_and_instruction() -> None:
    box = Toolbox()
    eid = load(box, scene_id="three_blocks").episode_id
    out = box.call("set_goal", {"episode_id": eid, "graph": {
        "nodes": [{"id": "red_block", "label": "block"}, {"id": "green_block", "label": "block"}],
        "edges": [{"source": "red_block", "relation": "on", "target": "green_block"}]},
        "partial": True})
    assert out.checkable and out.goal_diff.missing_edges == ["red_block on green_block"]
    out = box.call("set_goal", {"episode_id": eid, "predicate": "single_stack"})
    assert out.goal.predicate == "single_stack" and out.goal_satisfied is False
    out = box.call("set_goal", {"episode_id": eid, "instruction": "stack them all"})
    assert out.instruction == "stack them all" and out.goal.predicate == "single_stack"
    state = box.call("get_state", {"episode_id": eid})
    assert state.instruction == "stack them all"


def test_instruction_alone_is_recorded_but_not_checkable() -> None:
    box = Toolbox()
    eid = load(box, graph={"nodes": [{"id": "desk", "label": "desk"}], "edges": []}).episode_id
    out = box.call("set_goal", {"episode_id": eid, "instruction": "tidy up"})
    assert not out.checkable and "not checkable" in out.summary()


@pytest.mark.parametrize("goal, expected", [
    ({"nodes": [{"id": "cup", "label": "cup"}, {"id": "ghost", "label": "cup"}],
      "edges": [{"source": "cup", "relation": "in", "target": "ghost"}], "partial": True},
     "not in the scene: ghost"),
    ({"nodes": [{"id": "cup", "label": "cup"}, {"id": "desk", "label": "desk"}],
      "edges": [{"source": "cup", "relation": "on", "target": "desk"}]},
     "must list every object"),
    ({"nodes": [{"id": "cup", "label": "cup"}, {"id": "desk", "label": "desk"}],
      "edges": [{"source": "desk", "relation": "on", "target": "cup"}], "partial": True},
     "is not a surface"),
])
def test_invalid_goals_change_nothing(goal: dict[str, Any], expected: str) -> None:
    box = Toolbox()
    eid = load(box, scene_id="cup_on_book").episode_id
    before = box.call("get_state", {"episode_id": eid})
    partial = goal.pop("partial", False)
    with pytest.raises(VeriGraphError) as err:
        box.call("set_goal", {"episode_id": eid, "graph": goal, "partial": partial})
    assert expected in str(err.value)
    assert box.call("get_state", {"episode_id": eid}) == before


def test_goal_image_is_perceived_into_the_goal_graph() -> None:
    """The paper's reference-image goal: a render of the goal state becomes the goal."""
    import base64

    from verigraph.sim2d import generate_scene

    scene = generate_scene("blocks", 11)
    assert scene.goal is not None and scene.goal_world is not None
    box = Toolbox()
    eid = load(box, graph=scene.graph.model_dump()).episode_id
    photo = base64.b64encode(encode_png(scene.goal_world.render(640, 480))).decode()
    out = box.call("set_goal", {"episode_id": eid, "image": photo})
    assert out.goal is not None and out.goal.graph is not None
    assert out.goal.graph.edge_keys() == scene.goal.graph.edge_keys()


def test_end_episode_success_and_the_id_stops_working() -> None:
    box = Toolbox()
    eid = load(box, scene_id="cup_on_book").episode_id
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(book, on, shelf)"]})
    box.call("execute_actions", {"episode_id": eid, "actions": [*CUP_PLAN, "done"]})
    verdict = box.call("end_episode", {"episode_id": eid})
    assert verdict.success and verdict.verdict == "goal_reached"
    assert verdict.executed == ["move(cup, on, desk)", "move(book, on, shelf)"]
    assert [t.tau for t in verdict.trace] == [1, 0] and verdict.calls == 2
    assert verdict.trace[0].violation.constraint == "object_not_clear"
    with pytest.raises(UnknownEpisodeError):
        box.call("get_state", {"episode_id": eid})
    assert len(box.context.store) == 0


def test_end_episode_verdicts_without_success() -> None:
    box = Toolbox()
    eid = load(box, scene_id="cup_on_book", t=2).episode_id
    for _ in range(2):
        box.call("execute_actions", {"episode_id": eid, "actions": ["move(book, on, shelf)"]})
    verdict = box.call("end_episode", {"episode_id": eid})
    assert not verdict.success and verdict.verdict == "threshold_reached"
    eid = load(box, scene_id="kitchen_pan").episode_id
    assert box.call("end_episode", {"episode_id": eid}).verdict == "no_goal"
    eid = load(box, scene_id="cup_on_book").episode_id
    assert box.call("end_episode", {"episode_id": eid}).verdict == "goal_not_reached"


def test_max_episodes_from_config() -> None:
    box = Toolbox(config=ToolConfig(max_episodes=1))
    load(box, scene_id="cup_on_book")
    with pytest.raises(EpisodeLimitError):
        load(box, scene_id="cup_on_book")


def test_oversized_graphs_are_refused_before_indexing() -> None:
    nodes = [{"id": "table", "label": "table"}] + [
        {"id": f"b{i}", "label": "block"} for i in range(5001)]
    edges = [{"source": f"b{i}", "relation": "on", "target": "table"} for i in range(5001)]
    box = Toolbox()
    with pytest.raises(VeriGraphError) as err:
        box.call("load_scene", {"graph": {"nodes": nodes, "edges": edges}})
    assert "at most 5000 nodes" in str(err.value) and err.value.field == "graph"
    assert len(box.context.store) == 0
