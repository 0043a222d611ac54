"""load_scene(bddl=...): a BEHAVIOR problem's text starts an episode with its scene and goal
formula, or is refused whole naming the predicate; nothing is stored on a refusal."""

from __future__ import annotations

import pytest
from bddl_problems import DISHES, FILLED

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox

pytestmark = pytest.mark.fast


def test_a_problem_starts_an_episode_with_its_goal_formula() -> None:
    tools = Toolbox()
    state = tools.call("load_scene", {"bddl": DISHES})
    assert state.source == "bddl:putting_dishes_away"
    assert {n.id for n in state.graph.nodes} >= {"fridge_1", "cabinet_1", "kitchen"}
    assert state.graph.dictionary == "behavior"
    assert state.goal is not None and "(inside ?plate cabinet_1)" in str(state.goal)
    assert state.goal_satisfied is False
    checked = tools.call("check_goal", {"episode_id": state.episode_id})
    assert checked.satisfied is False


def test_an_unsupported_predicate_is_refused_and_nothing_stored() -> None:
    tools = Toolbox()
    tools.call("load_scene", {"bddl": DISHES})
    with pytest.raises(VeriGraphError) as err:
        tools.call("load_scene", {"bddl": FILLED})
    assert err.value.field == "bddl" and "'filled'" in err.value.message
    assert len(tools.context.store) == 1


def test_bddl_is_one_source_among_the_others() -> None:
    with pytest.raises(VeriGraphError) as err:
        Toolbox().call("load_scene", {"bddl": DISHES, "scene_id": "cup_on_book"})
    assert "exactly one of scene_id, graph, image, generator, bddl" in str(err.value)
