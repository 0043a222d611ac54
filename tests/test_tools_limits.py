"""Per-request memory bounds at the tool boundary: node attributes and kept photos."""

from __future__ import annotations

import base64

import cv2
import numpy as np
import pytest

from verigraph.errors import VeriGraphError
from verigraph.tools import Toolbox
from verigraph.tools.images import MAX_PHOTO_SIDE, KeptImage


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
