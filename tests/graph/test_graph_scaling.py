"""Graph checks scale linearly: tall towers, deep cycles and many misspelt labels."""

from __future__ import annotations

import random

import pytest

from verigraph.graph import Edge, Node, SceneGraph, WorldState, builtin_dictionary, wellformed
from verigraph.graph.dictionary import Dictionary
from verigraph.graph.wellformed import (
    check_well_formed,
    find_single_support_cycle,
    find_support_cycle,
)

pytestmark = pytest.mark.fast

BLOCKS = builtin_dictionary("blocks")


def tower(n: int) -> SceneGraph:
    nodes = [Node(id="table", label="table")] + [Node(id=f"b{i}", label="block")
                                                 for i in range(n)]
    edges = [Edge(source=f"b{i}", relation="on", target=f"b{i - 1}" if i else "table")
             for i in range(n)]
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


class CountingSupports(dict[str, list[str]]):
    """A support map that counts the lookups the cycle search makes."""

    lookups = 0

    def get(self, key, default=None):  # type: ignore[no-untyped-def, override]
        CountingSupports.lookups += 1
        return super().get(key, default)


def test_cycle_search_touches_each_support_once():
    n = 20_000
    below = CountingSupports({f"b{i}": [f"b{i - 1}" if i else "table"] for i in range(n)})
    CountingSupports.lookups = 0
    assert find_support_cycle(below) is None
    assert CountingSupports.lookups <= n + 1


def test_cycle_at_the_top_of_a_tall_tower_is_found_and_named():
    g = tower(30_000)
    # b29999 -> b29998 -> ... is a chain; close a loop between the two top blocks
    g.edges[-2] = Edge(source="b29998", relation="on", target="b29999")
    problems = [p for p in check_well_formed(g, BLOCKS) if p.rule == "cycle"]
    assert len(problems) == 1
    assert "b29998" in problems[0].message and "b29999" in problems[0].message


def test_well_formed_tall_tower_indexes_every_block():
    state = WorldState.from_graph(tower(50_000))
    assert state.supports_chain("b49999")[-1] == "table"
    assert len(state.supports_chain("b49999")) == 50_000


def test_spelling_suggestions_are_capped(monkeypatch: pytest.MonkeyPatch):
    calls = []
    real = Dictionary.nearest

    def counted(self: Dictionary, name: str, n: int = 3) -> list[str]:
        calls.append(name)
        return real(self, name, n)

    monkeypatch.setattr(Dictionary, "nearest", counted)
    g = tower(5000)
    g = g.model_copy(update={"nodes": [g.nodes[0]] + [Node(id=n.id, label="blok")
                                                      for n in g.nodes[1:]]})
    problems = [p for p in check_well_formed(g, BLOCKS) if p.rule == "unknown_label"]
    assert len(problems) == 5000  # every problem is still reported
    assert len(calls) == wellformed.MAX_SPELLING_SUGGESTIONS
    assert "block" in problems[0].fix  # the first ones carry the real suggestion
    assert "close in spelling" not in problems[-1].fix  # later ones: role and declaration
    assert problems[-1].fix.startswith("declare it:")


def random_supports(rng: random.Random, n: int) -> dict[str, str]:
    """Each object on a random other object or on the table: cycles appear often."""
    names = [f"o{i}" for i in range(n)]
    below = {name: rng.choice(names + ["table"]) for name in names}
    return {k: below[k] for k in rng.sample(names, n)}  # any insertion order


def test_single_support_cycle_walk_finds_the_cycle_the_general_search_finds():
    rng = random.Random(7)
    found = 0
    for _ in range(2000):
        below = random_supports(rng, rng.randint(1, 12))
        expected = find_support_cycle({k: [v] for k, v in below.items()})
        assert find_single_support_cycle(below) == expected
        found += expected is not None
    assert found > 100  # the cases exercised both answers


def test_problems_keep_their_order_and_words_on_a_large_broken_graph():
    g = tower(20_000)
    nodes = [*g.nodes, Node(id="b4", label="block"), Node(id="extra", label="block")]
    edges = list(g.edges)
    edges[9999] = Edge(source="b9999", relation="on", target="b10000")  # a cycle
    edges += [Edge(source="b4", relation="on", target="table"),  # b4 on two supports
              Edge(source="extra", relation="on", target="b3")]  # b3 now carries two
    problems = check_well_formed(g.model_copy(update={"nodes": nodes, "edges": edges}), BLOCKS)
    assert [(p.rule, p.node) for p in problems] == [
        ("duplicate_id", "b4"), ("over_capacity", "b3"), ("multiple_supports", "b4"),
        ("over_capacity", "b10000"), ("cycle", "b9999")]
    assert problems[2].message == ("'b4' rests on or in 2 objects; an object has exactly "
                                   "one support")
    assert problems[3].message == "'b10000' carries 2 objects but its capacity is 1"
    assert problems[-1].message == "support edges form a cycle: b9999 -> b10000 -> b9999"
