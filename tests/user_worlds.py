"""A home office as a user would describe it: desk, shelf, laptop, mug, pen holder, books
and a drawer unit, given with an inline dictionary or with labels declared in attrs."""

from __future__ import annotations

import copy
from typing import Any

# The user's own kinds of object, extending the tableware dictionary (desk, shelf, mug,
# book come from there).
HOME_OFFICE: dict[str, Any] = {
    "name": "home_office", "extends": "tableware", "objects": {
        "laptop": {"surface": True, "capacity": 1, "width": 14, "height": 2,
                   "color": "silver"},
        "pen holder": {"container": True, "capacity": 3, "width": 5, "height": 6,
                       "color": "black", "synonyms": ["pencil cup"]},
        "drawer unit": {"movable": False, "container": True, "capacity": 2, "width": 24,
                        "height": 14, "color": "gray"}}}

_NODES: list[dict[str, Any]] = [
    {"id": "desk", "label": "desk"}, {"id": "shelf", "label": "shelf"},
    {"id": "drawers", "label": "drawer unit"}, {"id": "laptop", "label": "laptop"},
    {"id": "mug", "label": "Mug"}, {"id": "pens", "label": "Pen Holder"},
    {"id": "book_1", "label": "book"}, {"id": "book_2", "label": "notebook"}]
_EDGES: list[dict[str, str]] = [
    {"source": "laptop", "relation": "on", "target": "desk"},
    {"source": "mug", "relation": "on", "target": "laptop"},
    {"source": "pens", "relation": "on", "target": "desk"},
    {"source": "book_1", "relation": "on", "target": "shelf"},
    {"source": "book_2", "relation": "on", "target": "book_1"}]

# The same roles declared on each node instead (open labels over the tableware dictionary).
_DECLARED = {"laptop": HOME_OFFICE["objects"]["laptop"],
             "pens": {k: v for k, v in HOME_OFFICE["objects"]["pen holder"].items()
                      if k != "synonyms"},
             "drawers": HOME_OFFICE["objects"]["drawer unit"]}


def inline_scene() -> dict[str, Any]:
    """The home office with its inline dictionary."""
    return {"nodes": copy.deepcopy(_NODES), "edges": copy.deepcopy(_EDGES),
            "dictionary": copy.deepcopy(HOME_OFFICE)}


def open_label_scene() -> dict[str, Any]:
    """The home office on the tableware dictionary, user labels declared in attrs."""
    nodes = copy.deepcopy(_NODES)
    for node in nodes:
        if node["id"] in _DECLARED:
            node["attrs"] = dict(_DECLARED[node["id"]])
    return {"nodes": nodes, "edges": copy.deepcopy(_EDGES), "dictionary": "tableware"}


# Only the edges that must hold at the end: laptop on the shelf, mug back on the desk.
GOAL: dict[str, Any] = {"partial": True, "graph": {
    "nodes": [{"id": "laptop", "label": "laptop"}, {"id": "mug", "label": "mug"},
              {"id": "shelf", "label": "shelf"}, {"id": "desk", "label": "desk"}],
    "edges": [{"source": "laptop", "relation": "on", "target": "shelf"},
              {"source": "mug", "relation": "on", "target": "desk"}]}}
