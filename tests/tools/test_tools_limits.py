"""Per-request memory bounds at the tool boundary: node attributes and kept photos."""

from __future__ import annotations

import base64

import cv2
import numpy as np
import pytest

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox
from verigraph.tools.images import MAX_PHOTO_SIDE, KeptImage

pytestmark = pytest.mark.fast


def jpeg_b64(width: int, height: int) -> str:
    image = np.full((height, width, 3), 200, dtype=np.uint8)  # a bare wall: nothing to see
    ok, buf = cv2.imencode(".jpg", image)
    assert ok
    return base64.b64encode(buf.tobytes()).decode()


def test_an_image_episode_keeps_its_photo_encoded_and_at_served_size() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"image": jpeg_b64(3200, 2400),
                                  "dictionary": "kitchen"}).episode_id  # type: ignore[union-attr]
    kept = box.context.store.peek(eid).image
    assert isinstance(kept, KeptImage)
    assert max(kept.width, kept.height) == MAX_PHOTO_SIDE
    assert len(kept.png) < 3200 * 2400 * 3 // 20  # far below the decoded 23 MB
    served = box.call("get_scene_image", {"episode_id": eid})
    photo = cv2.imdecode(np.frombuffer(served.png, np.uint8), cv2.IMREAD_COLOR)  # type: ignore[union-attr]
    assert photo.shape == (1200, 1600, 3)


@pytest.mark.parametrize("tool,arguments", [
    ("load_scene", {}),
    ("validate_plan", {"plan": "done"}),
    ("submit_scene_graph", {}),
])
def test_large_node_attributes_are_refused_naming_the_node(tool: str, arguments: dict) -> None:
    graph = {"nodes": [{"id": "table", "label": "table"},
                       {"id": "cup", "label": "cup", "attrs": {"note": "x" * 100_000}}],
             "edges": [{"source": "cup", "relation": "on", "target": "table"}]}
    with pytest.raises(VeriGraphError) as info:
        Toolbox().call(tool, {**arguments, "graph": graph})
    assert "nodes[1].attrs of 'cup'" in str(info.value)
    assert info.value.field == "graph"


@pytest.mark.parametrize("where", ["graph", "goal"])
def test_an_oversized_graph_is_refused_before_its_items_are_checked(where: str) -> None:
    """Its nodes are not even valid: the count alone refuses it, and the error shows only
    the start of the value."""
    nodes = [{"id": i} for i in range(100_000)]  # no labels: item checks would complain
    graph = {"nodes": nodes, "edges": []}
    arguments = {"graph": graph} if where == "graph" else {
        "graph": {"nodes": [], "edges": []}, "goal": {"graph": graph}}
    with pytest.raises(VeriGraphError) as info:
        Toolbox().call("validate_plan", {**arguments, "plan": "done"})
    text = str(info.value)
    assert "the graph has 100000 nodes" in text and "at most 5000 nodes" in text
    assert "label" not in text and len(text) < 1000


def test_a_text_plan_longer_than_its_limit_is_refused() -> None:
    graph = {"nodes": [{"id": "table", "label": "table"}], "edges": []}
    with pytest.raises(VeriGraphError) as info:
        Toolbox().call("validate_plan", {"graph": graph, "plan": "done\n" * 100_000})
    assert info.value.field == "plan" and "at most 400000 characters" in str(info.value)
