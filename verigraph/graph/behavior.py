"""The `behavior` dictionary: BEHAVIOR-1K's object kinds with roles from their abilities.

Built from the `bddl` package's knowledge base by `scripts/build_behavior_dictionary.py`
into `data/behavior.json` (package data; nothing downloads at run time) and read the
first time something names it, so a command that never does pays nothing for its 3,299
kinds. The label of a kind is its common name (`fridge`); the BEHAVIOR synset
(`electric_refrigerator.n.01`) and lemma are synonyms, and `synset` gives it back.
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Any

BEHAVIOR = "behavior"


@cache
def _data() -> dict[str, Any]:
    text = resources.files("verigraph.graph").joinpath("data", f"{BEHAVIOR}.json").read_text()
    data: dict[str, Any] = json.loads(text)
    return data


@cache
def behavior_dictionary() -> Any:
    """The `behavior` Dictionary (typed Any here: dictionary.py imports this module)."""
    from verigraph.graph.dictionary import Dictionary

    data = _data()
    return Dictionary.model_validate({"name": data["name"], "relations": data["relations"],
                                      "objects": data["objects"]})


def synset(label: str) -> str | None:
    """The BEHAVIOR synset of a kind of the `behavior` dictionary (`fridge` ->
    `electric_refrigerator.n.01`), None for a label it does not have."""
    found: str | None = _data()["synsets"].get(label)
    return found


@cache
def label_of_synset() -> dict[str, str]:
    """Synset -> the label of its kind (`electric_refrigerator.n.01` -> `fridge`)."""
    return {s: label for label, s in _data()["synsets"].items()}
