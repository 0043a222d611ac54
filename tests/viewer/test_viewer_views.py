"""The viewer's per-step views, the highlighted/outlined drawings they carry, and the
self-contained report file."""

from __future__ import annotations

import base64
import json
import re

import cv2
import numpy as np
import pytest

from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.graph.model import Edge
from verigraph.tools import Toolbox
from verigraph.tools.drawing import HIGHLIGHT_COLOR, OUTLINE_COLOR, draw_graph
from verigraph.viewer import ViewInput, report_html, view

pytestmark = pytest.mark.fast

REFUSED_PLAN = "move(cup, on, desk)\nmove(desk, on, shelf)\nmove(book, on, shelf)"


def picture(data_url: str) -> np.ndarray:
    prefix = "data:image/png;base64,"
    assert data_url.startswith(prefix)
    image = cv2.imdecode(np.frombuffer(base64.b64decode(data_url[len(prefix):]), np.uint8),
                         cv2.IMREAD_COLOR)
    assert image is not None
    return image


def count(image: np.ndarray, bgr: tuple[int, int, int]) -> int:
    return int((image == np.array(bgr, dtype=np.uint8)).all(axis=2).sum())


def test_outline_and_highlight_are_drawn_only_when_asked() -> None:
    plain = draw_graph(cup_on_book(), 480, 360)
    marked = draw_graph(cup_on_book(), 480, 360, outline=["cup"],
                        highlight=[Edge(source="cup", relation="on", target="book")])
    assert count(plain, OUTLINE_COLOR) == 0 and count(plain, HIGHLIGHT_COLOR) == 0
    assert count(marked, OUTLINE_COLOR) > 200  # a 3 px frame around one box
    assert count(marked, HIGHLIGHT_COLOR) > 50


def test_plan_view_has_one_entry_per_checked_step_with_the_refusal_explained() -> None:
    box = Toolbox()
    result = view(box.context, ViewInput(plan="move(book, on, shelf)\nmove(cup, on, desk)",
                                         scene_id="cup_on_book"))
    assert not result.valid and result.not_checked == 1
    assert [s.ok for s in result.steps] == [False]
    refused = result.steps[0]
    assert refused.violation is not None and refused.violation.constraint == "object_not_clear"
    assert refused.violation.blocking == ["cup"]
    assert count(picture(refused.render or ""), OUTLINE_COLOR) > 200
    assert count(picture(result.initial_render), OUTLINE_COLOR) == 0
    roles = {r.id: r.role for r in result.roles}
    assert roles["desk"] == "fixed" and roles["cup"] in ("object", "container")


def test_ok_steps_carry_the_graph_after_them_and_highlight_the_new_edge() -> None:
    box = Toolbox()
    result = view(box.context, ViewInput(plan="move(cup, on, desk)\nmove(book, on, shelf)",
                                         scene_id="cup_on_book"))
    assert result.valid and result.goal_reached is True
    first, second = result.steps
    assert first.added == [Edge(source="cup", relation="on", target="desk")]
    assert Edge(source="cup", relation="on", target="book") in first.removed
    assert Edge(source="cup", relation="on", target="desk") in first.graph.edges
    assert Edge(source="book", relation="on", target="shelf") in second.graph.edges
    assert count(picture(first.render or ""), HIGHLIGHT_COLOR) > 50


def test_episode_view_replays_the_trace_and_ends_with_the_refused_action() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book"}).episode_id  # type: ignore[union-attr]
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(cup, on, desk)"]})
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(desk, on, shelf)"]})
    result = view(box.context, ViewInput(episode_id=eid))
    assert result.episode_id == eid and result.source == "episode"
    assert [(s.text, s.ok) for s in result.steps] == [("move(cup, on, desk)", True),
                                                     ("move(desk, on, shelf)", False)]
    assert result.steps[1].violation is not None
    assert result.steps[1].violation.constraint == "not_movable"


def test_report_file_embeds_the_view_safely_and_allows_no_network() -> None:
    box = Toolbox()
    result = view(box.context, ViewInput(plan=REFUSED_PLAN, scene_id="cup_on_book"))
    result.title = "</script><script>alert(1)</script>"
    html = report_html(result)
    data = re.search(r'<script id="verigraph-data" type="application/json">(.*?)</script>',
                     html, re.S)
    assert data is not None
    assert json.loads(data.group(1))["title"] == result.title  # escaped, still the same text
    assert "connect-src 'none'" in html and "default-src 'none'" in html
    assert html.count("<script") == 2  # the data and the viewer, nothing injected


def test_simulated_episode_frames_the_blocker_in_the_simulator_render() -> None:
    box = Toolbox()
    eid = box.call("load_scene", {"scene_id": "cup_on_book",  # type: ignore[union-attr]
                                  "simulate": True}).episode_id
    fine = view(box.context, ViewInput(episode_id=eid))
    assert fine.scene_render is not None
    assert count(picture(fine.scene_render), OUTLINE_COLOR) == 0
    box.call("execute_actions", {"episode_id": eid, "actions": ["move(book, on, shelf)"]})
    refused = view(box.context, ViewInput(episode_id=eid))
    assert refused.steps[-1].outlined == ["cup"]
    assert refused.scene_render is not None
    assert count(picture(refused.scene_render), OUTLINE_COLOR) > 200
