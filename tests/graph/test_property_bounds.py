"""Every size the simulator builds from is bounded, whichever way it comes in.

A node's `attrs` get the bounds of the inline dictionary's properties (width and height
from 1 to 500, finite; capacity to 1000; tangram sides and symmetry): a value out of
them is a structured error naming the field and the bound, never a crash, a hang or a
gigabyte of memory in the simulator.
"""

from __future__ import annotations

import math
import time
import tracemalloc
from typing import Any

import pytest

from verigraph.errors import DictionaryError, VeriGraphError
from verigraph.graph.dictionary import (
    MAX_SIZE,
    MIN_SIZE,
    ObjectProperties,
    load_dictionary,
    open_label_properties,
    parse_inline,
)
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import check_well_formed
from verigraph.sim2d import generate_scene
from verigraph.sim2d.placement import MAX_GRID_POINTS, _grid
from verigraph.tools import Toolbox

pytestmark = pytest.mark.fast

OUT_OF_BOUNDS = [1e8, 1e-300, 0.5, 0.0, -3.0, math.nan, math.inf, -math.inf, 501.0]


def _open_scene(key: str, value: Any, role: str = "surface") -> dict[str, Any]:
    return {"nodes": [{"id": "bench", "label": "bench",
                       "attrs": {"movable": False, "surface": True}},
                      {"id": "slab", "label": "slab", "attrs": {role: True, key: value}}],
            "edges": [{"source": "slab", "relation": "on", "target": "bench"}]}


@pytest.mark.parametrize("value", OUT_OF_BOUNDS)
@pytest.mark.parametrize("key", ["width", "height"])
def test_attrs_sizes_get_the_inline_dictionarys_bounds(key: str, value: float) -> None:
    with pytest.raises(DictionaryError) as caught:
        ObjectProperties().overridden({key: value})
    assert caught.value.field == f"attrs.{key}"
    assert f"from {MIN_SIZE:g} to {MAX_SIZE:g}" in caught.value.message
    assert caught.value.fix and "finite" in caught.value.fix
    with pytest.raises(DictionaryError) as inline:
        parse_inline({"objects": {"slab": {key: value}}})
    assert inline.value.field == f"dictionary.objects.slab.{key}"


@pytest.mark.parametrize("value", [MIN_SIZE, 6.0, MAX_SIZE])
def test_sizes_inside_the_bounds_are_kept(value: float) -> None:
    props = open_label_properties({"surface": True, "width": value, "height": value})
    assert props is not None and props.width == value and props.height == value


def test_a_bad_size_is_one_problem_naming_the_node_field_and_bound() -> None:
    graph = SceneGraph.model_validate(_open_scene("width", 1e8))
    problems = check_well_formed(graph, load_dictionary(None))
    assert [p.rule for p in problems] == ["bad_attribute"]
    problem = problems[0]
    assert problem.field == "nodes[1].attrs.width" and problem.node == "slab"
    assert "1e+08" in problem.message or "100000000" in problem.message
    assert "from 1 to 500" in problem.message and "from 1 to 500" in problem.fix


@pytest.mark.parametrize("value", [1e8, 1e-300, math.nan])
@pytest.mark.parametrize("role", ["surface", "container"])
def test_load_scene_with_simulate_refuses_in_bounded_memory(value: float, role: str) -> None:
    """The 521-byte call that took the server from 127 MB to 1.28 GB, and the widths that
    ended in ZeroDivisionError or a pymunk assertion: a structured error, little memory."""
    box = Toolbox()
    tracemalloc.start()
    try:
        with pytest.raises(VeriGraphError) as caught:
            box.call("load_scene", {"graph": _open_scene("width", value, role),
                                    "simulate": True})
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 50 * 2**20, f"refusing took {peak / 2**20:.0f} MB"
    assert "nodes[1].attrs.width" in caught.value.message
    assert "from 1 to 500" in caught.value.message
    assert len(box.context.store) == 0


def test_the_smallest_and_largest_sizes_simulate() -> None:
    for value in (MIN_SIZE, MAX_SIZE):
        for role in ("surface", "container"):
            state = Toolbox().call("load_scene", {"graph": _open_scene("width", value, role),
                                                  "simulate": True})
            assert "slab on bench" in state.summary()


def test_placement_candidates_are_bounded_by_count_not_width() -> None:
    xs = _grid(0.0, 3_000_000.0)
    assert len(xs) <= MAX_GRID_POINTS + 2 and xs[0] == 0.0 and xs[-1] == 3_000_000.0
    assert _grid(0.0, 10.0) == [i * 0.5 for i in range(21)]  # small targets: every 0.5


@pytest.mark.parametrize("attrs,field", [
    ({"capacity": 10**9}, "attrs.capacity"), ({"sides": 10**6}, "attrs.sides"),
    ({"symmetry": 50}, "attrs.symmetry"), ({"symmetry": 4}, "attrs.symmetry"),
])
def test_counts_from_attrs_are_bounded(attrs: dict[str, Any], field: str) -> None:
    triangle = load_dictionary("tangram").objects["small_triangle_1"]  # 3 sides
    with pytest.raises(DictionaryError) as caught:
        triangle.overridden(attrs)
    assert caught.value.field == field and caught.value.fix


def test_a_tangram_goal_check_with_symmetry_in_attrs_ends_quickly() -> None:
    """symmetry 50 on each of seven pieces was 50**7 rotations to try in the goal check."""
    scene = generate_scene("tangram", 1)
    graph = scene.graph.model_dump()
    for node in graph["nodes"]:
        node["attrs"] = {"symmetry": 50}
    started = time.perf_counter()
    with pytest.raises(VeriGraphError) as caught:
        Toolbox().call("validate_plan", {"graph": graph, "plan": "done",
                                         "goal": scene.goal.model_dump()})
    assert time.perf_counter() - started < 5.0
    assert "attrs.symmetry" in caught.value.message and "from 1 to 4" in caught.value.message
