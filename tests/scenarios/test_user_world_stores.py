"""A user's dictionary is stored with the episode in every store: memory://, sqlite:///
and redis:// (a real server); another tool host on the same durable store continues the
episode with the same dictionary and constraints."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest
from store_helpers import redis_url  # noqa: F401 - the session fixture
from user_worlds import inline_scene, open_label_scene

from verigraph.tools import Toolbox, ToolConfig


def call(box: Toolbox, name: str, **arguments: Any) -> Any:
    return box.call(name, arguments)


@pytest.mark.parametrize("scene", [inline_scene, open_label_scene])
def test_the_dictionary_travels_with_the_episode(
        store_url: str, scene: Callable[[], dict[str, Any]]) -> None:
    first = Toolbox(config=ToolConfig(store=store_url))
    loaded = call(first, "load_scene", graph=scene())
    ep = loaded.episode_id
    # Memory stores live in one process: the same host continues; durable ones: another.
    other = first if store_url == "memory://" else Toolbox(config=ToolConfig(store=store_url))
    state = call(other, "get_state", episode_id=ep)
    assert state.dictionary == loaded.dictionary
    assert state.user_labels == loaded.user_labels
    assert "laptop: movable surface, capacity 1" in state.user_labels
    assert state.graph == loaded.graph
    check = call(other, "validate_action", episode_id=ep, action="move(mug, in, desk)")
    assert check.violation.constraint == "target_not_container"
    out = call(other, "execute_actions", episode_id=ep, actions=[
        "move(book_2, in, drawers)", "move(pens, in, drawers)", "move(mug, in, drawers)"])
    assert out.violation.constraint == "target_full"
    assert call(first, "get_state", episode_id=ep).executed == [
        "move(book_2, in, drawers)", "move(pens, in, drawers)"]
