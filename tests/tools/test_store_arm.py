"""An arm episode in a durable store: the graph and the latched stop are stored; the
driver connection is opened again by the process that loads the episode."""

from __future__ import annotations

from pathlib import Path

from arm_deps import require

from verigraph.arm import ArmWorld
from verigraph.arm.config import parse_arm_config
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

require("pybullet")


def arm_toolbox(url: str) -> Toolbox:
    """A server process with a dry-run Panda whose operator lets the agent reset it."""
    arm = ArmSetup(parse_arm_config({"driver": "pybullet", "agent_may_reset": True}))
    return Toolbox(config=ToolConfig(store=url, arm=arm))


def test_a_reloaded_arm_episode_reconnects_and_stays_latched(tmp_path: Path) -> None:
    url = f"sqlite:///{tmp_path / 'episodes.db'}"
    first = arm_toolbox(url)
    ep = first.call("load_scene", {"scene_id": "cup_on_book",
                                   "executor": "arm:pybullet"}).episode_id
    first.call("execute_actions", {"episode_id": ep, "actions": ["move(book, shelf)"]})
    assert first.call("arm_stop", {"episode_id": ep}).stop_latched
    before = first.call("get_state", {"episode_id": ep})  # the next call stores the latch

    second = arm_toolbox(url)
    status = second.call("arm_status", {"episode_id": ep})
    assert status.stop_latched and status.executor == "arm:pybullet"
    world = second.context.store.peek(ep).world
    assert isinstance(world, ArmWorld) and world is not first.context.store.peek(ep).world
    assert second.call("get_state", {"episode_id": ep}) == before
    assert not second.call("arm_reset", {"episode_id": ep}).stop_latched
    # The cleared latch is stored too: a third process starts unlatched.
    third = arm_toolbox(url)
    assert not third.call("arm_status", {"episode_id": ep}).stop_latched
