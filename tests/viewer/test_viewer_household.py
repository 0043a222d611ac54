"""The viewer on a household plan: each step's graph carries the states it changed."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.fast

def test_the_viewer_shows_each_steps_states() -> None:
    from verigraph.tools import Toolbox
    from verigraph.tools.acting import ValidatePlanInput
    from verigraph.viewer.views import plan_view

    box = Toolbox()
    view = plan_view(box.context, ValidatePlanInput(
        scene_id="kitchen_household", plan="open(fridge)\nmove(milk, in, fridge)"))
    fridge = [next(n for n in s.graph.nodes if n.id == "fridge") for s in view.steps]
    assert [f.state for f in fridge] == [{"open": True}, {"open": True}]
    assert view.initial_graph.node("fridge").state == {"open": False}  # type: ignore[union-attr]
