"""The episode's goal ranks the fixes of validate_action and execute_actions: a blocker
goes where the goal wants it (edge goals and formula goals); without a goal, as before."""

from __future__ import annotations

import pytest

from llm_trials import THIRD_SET, with_attachments
from verigraph.tools import Toolbox
from verigraph.tools.registry import TOOLS

pytestmark = pytest.mark.fast
LIFT = "move(ice_bucket, on, shelf)"  # the ice bucket holds tube_d, tube_e and the pipette


def lab(box: Toolbox) -> str:
    graph = with_attachments(THIRD_SET / "t05_lab", "@json:./start.json")
    return str(box.call("load_scene", {"graph": graph}).episode_id)


def fixes(box: Toolbox, episode: str) -> tuple[str, str]:
    checked = box.call("validate_action", {"episode_id": episode, "action": LIFT})
    ran = box.call("execute_actions", {"episode_id": episode, "actions": [LIFT]})
    assert checked.violation is not None and ran.violation is not None
    assert TOOLS["execute_actions"].summary(ran)  # the text builds
    return checked.violation.suggestion, ran.violation.suggestion


@pytest.mark.parametrize("goal", [{"edges": "tube_d in centrifuge; pipette on shelf"},
                                  {"formula": "(and (inside tube_d centrifuge) "
                                              "(ontop pipette shelf))"}])
def test_the_episode_goal_sends_the_blockers_where_it_wants_them(goal: dict[str, str]) -> None:
    box = Toolbox()
    episode = lab(box)
    blind = fixes(box, episode)
    assert all("where the goal wants it" not in fix for fix in blind)
    box.call("set_goal", {"episode_id": episode, **goal})
    for fix in fixes(box, episode):
        assert "move(tube_d, in, centrifuge) (where the goal wants it)" in fix
        assert "move(pipette, on, shelf) (where the goal wants it)" in fix
