"""render_scene, get_scene_image, submit_scene_graph, generate_scene_graph, image decoding."""

from __future__ import annotations

import base64

import cv2
import numpy as np
import pytest
from mcp_helpers import png_b64

from verigraph.graph.builtin_scenes import cup_on_book, three_blocks
from verigraph.sim2d.render import encode_png
from verigraph.tools import ToolArgumentError, Toolbox
from verigraph.tools.drawing import draw_graph, layout
from verigraph.tools.images import decode_base64_image

pytestmark = pytest.mark.fast


def decode(png: bytes) -> np.ndarray:
    image = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR)
    assert image is not None
    return image


def test_layout_puts_each_object_above_its_support() -> None:
    pos = layout(cup_on_book())
    assert pos["cup"][1] > pos["book"][1] > pos["desk"][1]
    assert pos["cup"][0] == pytest.approx(pos["book"][0])
    assert pos["shelf"][1] == pos["desk"][1]
    towers = layout(three_blocks())
    assert towers["red_block"][1] > towers["blue_block"][1] > towers["table"][1]


def test_drawing_is_deterministic_and_coloured() -> None:
    a = draw_graph(cup_on_book(), 320, 240, colors={"desk": "walnut"})
    b = draw_graph(cup_on_book(), 320, 240, colors={"desk": "walnut"})
    assert a.shape == (240, 320, 3) and np.array_equal(a, b)
    assert (a != 255).any()  # something was drawn
    walnut = np.array([45, 75, 110], dtype=np.uint8)
    assert (a == walnut).all(axis=2).sum() > 100


def test_render_scene_is_a_png_of_the_requested_size() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id
    image = box.call("render_scene", {"episode_id": eid, "width": 300, "height": 200})
    assert image.mime_type == "image/png" and "DIAGRAM" in (image.text or "")
    assert decode(image.png).shape == (200, 300, 3)
    goal = box.call("render_scene", {"episode_id": eid, "view": "goal"})
    assert not np.array_equal(decode(goal.png), decode(box.call(
        "render_scene", {"episode_id": eid}).png))


def test_render_scene_default_frame_follows_the_scene() -> None:
    """A simulated kitchen comes back in its own wide shape (thin walls stay visible);
    one side given keeps that shape; a graph-only episode is drawn at 640x480."""
    box = Toolbox()
    eid = box.call("load_scene", {"generator": {"family": "kitchen", "seed": 7},
                                  "simulate": True}).episode_id
    wide = decode(box.call("render_scene", {"episode_id": eid}).png)
    height, width = wide.shape[:2]
    assert width >= 640 and width > 2 * height
    narrow = decode(box.call("render_scene", {"episode_id": eid, "width": 640}).png)
    assert narrow.shape[1] == 640 and abs(narrow.shape[0] / 640 - height / width) < 0.01
    graph_only = box.call("load_scene", {"scene_id": "three_blocks", "simulate": False})
    drawing = decode(box.call("render_scene", {"episode_id": graph_only.episode_id}).png)
    assert drawing.shape == (480, 640, 3)


def test_render_goal_needs_a_goal_graph() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "three_blocks"}).episode_id  # predicate goal
    with pytest.raises(ToolArgumentError) as err:
        box.call("render_scene", {"episode_id": eid, "view": "goal"})
    assert err.value.field == "view"


def test_get_scene_image_returns_the_loaded_photo_and_the_prompt() -> None:
    box = Toolbox()
    photo = png_b64(40, 30, (0, 255, 0))
    eid = box.call("load_scene", {"image": photo, "dictionary": "kitchen",
                                  "instruction": "put the lid on the pot"}).episode_id
    out = box.call("get_scene_image", {"episode_id": eid})
    image = decode(out.png)
    assert image.shape == (30, 40, 3) and (image[..., 1] == 255).all()
    assert "Dictionary: kitchen" in out.text and "stove" in out.text
    assert "put the lid on the pot" in out.text and f'episode_id="{eid}"' in out.text


def test_large_photos_are_sent_back_scaled_down() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"image": png_b64(2400, 1200)}).episode_id
    image = decode(box.call("get_scene_image", {"episode_id": eid}).png)
    assert image.shape == (800, 1600, 3)


def test_submit_normalises_and_reports_every_problem_at_once() -> None:
    box = Toolbox()
    graph = {"nodes": [{"id": "Red Block", "label": "cube"}, {"id": "tbl", "label": "Table Top"},
                       {"id": "x", "label": "unicorn"}, {"id": "b2", "label": "block"},
                       {"id": "b3", "label": "block"}],
             "edges": [{"source": "Red Block", "relation": "on top of", "target": "table"},
                       {"source": "b2", "relation": "beside", "target": "tbl"},
                       {"source": "b3", "relation": "on", "target": "nowhere"}]}
    out = box.call("submit_scene_graph", {"graph": graph, "dictionary": "blocks"})
    assert not out.accepted
    rules = sorted(p.rule for p in out.problems)
    assert rules == ["dangling_edge", "missing_support", "missing_support", "unknown_label",
                     "unknown_relation"]
    renames = {(r.before, r.after) for r in out.normalised}
    assert {("Red Block", "red_block"), ("cube", "block"), ("Table Top", "table"),
            ("on top of", "on"), ("table", "tbl")} <= renames
    assert "REJECTED: 5 problem(s)" in out.summary()


def test_accepted_submission_starts_an_image_episode() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"image": png_b64()}).episode_id
    graph = {"nodes": [{"id": "desk", "label": "writing desk"}, {"id": "mug", "label": "mug"}],
             "edges": [{"source": "mug", "relation": "on", "target": "desk"}]}
    out = box.call("submit_scene_graph", {"episode_id": eid, "graph": graph})
    assert out.accepted and out.adopted and out.problems == []
    state = box.call("get_state", {"episode_id": eid})
    assert not state.awaiting_scene_graph and state.graph.sentences() == ["mug on desk"]
    ran = box.call("execute_actions", {"episode_id": eid, "actions": ["move(mug, desk)"]})
    assert ran.violation.constraint == "already_there"


def test_rejected_submission_leaves_the_episode_waiting() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"image": png_b64()}).episode_id
    out = box.call("submit_scene_graph", {"episode_id": eid, "graph": {
        "nodes": [{"id": "mug", "label": "mug"}], "edges": []}})
    assert not out.accepted and not out.adopted
    assert box.call("get_state", {"episode_id": eid}).awaiting_scene_graph


def test_submission_for_a_loaded_scene_is_compared_not_adopted() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id
    graph = {"nodes": [{"id": n, "label": n} for n in ("desk", "shelf", "book", "cup")],
             "edges": [{"source": "book", "relation": "on", "target": "desk"},
                       {"source": "cup", "relation": "on", "target": "desk"}]}
    out = box.call("submit_scene_graph", {"episode_id": eid, "graph": graph})
    assert out.accepted and not out.adopted
    assert out.diff_to_episode.missing_edges == ["cup on book"]
    assert box.call("get_state", {"episode_id": eid}).graph.sentences() == [
        "book on desk", "cup on book"]


@pytest.mark.parametrize("family,seed", [("kitchen", 3), ("tableware", 4), ("blocks", 5)])
def test_generate_scene_graph_perceives_a_simulated_render(family: str, seed: int) -> None:
    """Built-in perception through the tool: a sim2d render back to its scene graph."""
    from verigraph.sim2d import generate_scene

    scene = generate_scene(family, seed)
    photo = base64.b64encode(encode_png(scene.world.render(640, 480))).decode()
    out = Toolbox().call("generate_scene_graph", {"image": photo, "dictionary": family})
    assert out.accepted, out
    assert sorted(n.label for n in out.graph.nodes) == sorted(n.label for n in scene.graph.nodes)
    assert len(out.graph.edges) == len(scene.graph.edges)


def test_an_image_perception_cannot_read_waits_for_the_agents_graph() -> None:
    box = Toolbox()
    blank = png_b64(40, 30, (0, 255, 0))
    state = box.call("load_scene", {"image": blank, "dictionary": "kitchen"})
    assert state.awaiting_scene_graph and state.graph is None


def test_unsure_perception_is_a_proposal_to_confirm_not_a_fact() -> None:
    """A picture with a grey bar in front: perception joins the table and says so, and
    the tools return its graph as a proposal (not accepted) with the reason, start an
    image episode without it, and refuse it as a goal."""
    from verigraph.sim2d import Degradation, degrade, generate_scene

    scene = generate_scene("blocks", 20_000)
    barred = degrade(scene.world.render(), Degradation(occlusion=0.02), seed=1)
    photo = base64.b64encode(encode_png(barred)).decode()
    box = Toolbox()
    out = box.call("generate_scene_graph", {"image": photo, "dictionary": "blocks"})
    assert not out.accepted and out.graph.nodes
    doubts = [p for p in out.problems if p.rule == "perception_uncertain"]
    assert doubts and all(p.field == "image" and "submit_scene_graph" in p.fix
                          for p in doubts)
    state = box.call("load_scene", {"image": photo, "dictionary": "blocks"})
    assert state.awaiting_scene_graph and state.graph is None
    eid = box.call("load_scene", {"graph": scene.graph.model_dump(),
                                  "simulate": False}).episode_id
    with pytest.raises(ToolArgumentError) as err:
        box.call("set_goal", {"episode_id": eid, "image": photo})
    assert err.value.field == "image" and "unsure" in str(err.value)
    clean = base64.b64encode(encode_png(scene.world.render())).decode()
    assert box.call("generate_scene_graph", {"image": clean, "dictionary": "blocks"}).accepted


@pytest.mark.parametrize("payload, message", [
    ("not base64 at all!", "not valid base64"),
    (base64.b64encode(b"GIF89a....").decode(), "not a PNG or JPEG"),
    ("", "empty"),
])
def test_bad_images_name_the_field(payload: str, message: str) -> None:
    with pytest.raises(ToolArgumentError) as err:
        decode_base64_image(payload, field="image")
    assert err.value.field == "image" and message in str(err.value)


def test_image_decompression_bombs_are_refused() -> None:
    png = bytearray(encode_png(np.zeros((4, 4, 3), np.uint8)))
    png[16:24] = (100_000).to_bytes(4, "big") + (100_000).to_bytes(4, "big")
    with pytest.raises(ToolArgumentError) as err:
        decode_base64_image(base64.b64encode(bytes(png)).decode())
    assert "100000x100000 pixels, too large" in str(err.value)
    ok, buf = cv2.imencode(".jpg", np.zeros((4, 6, 3), np.uint8))
    jpeg = bytearray(buf.tobytes())
    sof = next(i for i in range(2, len(jpeg) - 1) if jpeg[i] == 0xFF and jpeg[i + 1] == 0xC0)
    jpeg[sof + 5:sof + 9] = (60_000).to_bytes(2, "big") + (60_000).to_bytes(2, "big")
    with pytest.raises(ToolArgumentError) as err:
        decode_base64_image(base64.b64encode(bytes(jpeg)).decode())
    assert "60000x60000 pixels, too large" in str(err.value)


def test_jpeg_images_decode() -> None:
    image = np.zeros((30, 40, 3), np.uint8)
    image[:, :20] = (255, 255, 255)
    ok, buf = cv2.imencode(".jpg", image)
    decoded = decode_base64_image(base64.b64encode(buf.tobytes()).decode())
    assert decoded.shape == (30, 40, 3) and decoded[:, :10].mean() > 200


def test_data_url_prefix_is_accepted() -> None:
    image = decode_base64_image("data:image/png;base64," + png_b64(8, 6))
    assert image.shape == (6, 8, 3)
