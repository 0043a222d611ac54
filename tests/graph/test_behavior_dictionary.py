"""The `behavior` dictionary: BEHAVIOR-1K's kinds with roles from their abilities, read
on first use only."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from verigraph.errors import DictionaryError
from verigraph.graph.behavior import label_of_synset, synset
from verigraph.graph.dictionary import load_dictionary, parse_inline

pytestmark = pytest.mark.fast

ROOT = Path(__file__).parents[2]


def test_common_names_roles_and_synsets() -> None:
    d = load_dictionary("behavior")
    assert len(d.objects) > 3000
    fridge = d.properties("fridge")
    assert (fridge.movable, fridge.container, fridge.openable, fridge.cold_source) == \
        (False, True, True, True)
    assert synset("fridge") == "electric_refrigerator.n.01"
    assert label_of_synset()["electric_refrigerator.n.01"] == "fridge"
    # the lemma and the synset read as the kind; a BEHAVIOR object name too
    assert d.resolve("electric_refrigerator") == "fridge"
    assert d.resolve("electric_refrigerator.n.01_1") == "fridge"
    stove = d.properties("stove")
    assert stove.toggleable and stove.heat_source and not stove.movable and stove.surface
    dishwasher = d.properties("dishwasher")
    assert dishwasher.openable and dishwasher.toggleable
    apple = d.properties("apple")
    assert apple.movable and apple.cookable and apple.freezable
    assert d.properties("kitchen").room


def test_a_movable_support_has_the_documented_default_capacity() -> None:
    d = load_dictionary("behavior")
    assert d.properties("plate").capacity == 4  # fillable: a movable container
    assert d.properties("countertop").capacity is None  # furniture: unlimited


def test_every_label_is_one_kind_and_none_ends_in_a_number() -> None:
    data = json.loads((ROOT / "verigraph/graph/data/behavior.json").read_text())
    labels = list(data["objects"])
    assert len(labels) == len(set(labels))
    assert not [label for label in labels if label.rsplit("_", 1)[-1].isdigit()]
    # every synset maps back to its label
    assert all(data["synsets"][label] for label in data["synsets"])


def test_a_user_dictionary_extends_behavior() -> None:
    mine = parse_inline({"extends": "behavior",
                         "objects": {"widget": {"surface": True, "capacity": 2}}}).build()
    assert mine.resolve("dishwasher") == "dishwasher"
    assert mine.properties("widget").surface
    assert mine.home("widget") == "your label"


def test_an_unknown_word_is_refused_with_near_names() -> None:
    with pytest.raises(DictionaryError) as err:
        load_dictionary("behavior").normalise("electric_refrigeratr")
    assert "fridge" in (err.value.fix or "")


def test_the_dictionary_is_not_read_when_unused() -> None:
    code = ("from verigraph.cli import main\n"
            "import contextlib, io\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    main(['solve', '--scene', 'cup_on_book', '--goal', 'single_stack', '--json'])\n"
            "from verigraph.graph import behavior\n"
            "print(behavior._data.cache_info().currsize)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=120, check=False)
    assert out.stdout.strip().splitlines()[-1] == "0", out.stderr
