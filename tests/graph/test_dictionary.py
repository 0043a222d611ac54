"""Dictionary D: built-ins, synonyms, unknown names with the nearest suggestions."""

import pytest

from verigraph.errors import DictionaryError
from verigraph.graph import BUILTIN_DICTIONARIES, builtin_dictionary, load_dictionary
from verigraph.graph.dictionary import union_dictionary

pytestmark = pytest.mark.fast


@pytest.mark.parametrize("name", BUILTIN_DICTIONARIES)
def test_builtins_load(name):
    d = builtin_dictionary(name)
    assert d.name == name and d.objects


@pytest.mark.parametrize("dictionary,word,canonical", [
    ("tableware", "tabletop", "table"), ("kitchen", "countertop", "counter"),
    ("tableware", "Dish", "plate"), ("kitchen", "Frying Pan", "pan"),
    ("kitchen", "cutting-board", "cutting_board"), ("tableware", "plate_2", "plate"),
    ("blocks", "cube", "block"), ("kitchen", "stovetop", "stove"),
])
def test_synonyms_normalise(dictionary, word, canonical):
    assert builtin_dictionary(dictionary).normalise(word) == canonical


def test_unknown_name_is_rejected_with_nearest_names():
    with pytest.raises(DictionaryError) as err:
        builtin_dictionary("tableware").normalise("plat")
    assert "plate" in err.value.fix and err.value.field == "label"


def test_union_covers_the_papers_objects():
    d = union_dictionary()
    for name in ("book", "shelf", "desk", "cup", "plate", "pan", "pot", "stove", "block",
                 "square", "counter"):
        assert d.resolve(name) == name


def test_shared_names_agree_across_dictionaries():
    """The validator must not change its mind about a table depending on the dictionary."""
    seen = {}
    for name in BUILTIN_DICTIONARIES:
        for label, props in builtin_dictionary(name).objects.items():
            key = (props.movable, props.surface, props.container, props.capacity)
            assert seen.setdefault(label, key) == key, label


def test_unknown_dictionary_name_lists_builtins(tmp_path):
    with pytest.raises(DictionaryError, match="blocks, kitchen, tableware, tangram"):
        load_dictionary("galley")
    custom = tmp_path / "d.yaml"
    custom.write_text("name: mine\nobjects:\n  crate: {movable: true, surface: true}\n")
    assert load_dictionary(str(custom)).resolve("crate") == "crate"


def test_attrs_override_properties():
    props = builtin_dictionary("tableware").objects["plate"]
    assert props.overridden({"capacity": 5, "color": "red"}).capacity == 5
    with pytest.raises(DictionaryError) as err:
        props.overridden({"capacity": "lots"})
    assert err.value.field == "attrs.capacity"
