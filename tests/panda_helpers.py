"""Helpers shared by the PyBullet Panda tests (in-process world and through the server)."""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # importing the scene needs pybullet; the tests check for it first
    from verigraph.arm.sim.panda_scene import PandaScene


def arm_moving(scene: PandaScene) -> threading.Event:
    """An event set when the scene's arm first follows a joint trajectory."""
    moving = threading.Event()
    follow = scene.follow

    def follow_and_signal(*args: Any, **kwargs: Any) -> Any:
        moving.set()
        return follow(*args, **kwargs)

    scene.follow = follow_and_signal  # type: ignore[method-assign]
    return moving
