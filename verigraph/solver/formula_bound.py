"""An admissible lower bound on the actions a goal formula still needs.

Every action changes one thing about one object: a move changes where its object rests,
`open`/`close` one object's `open` state, `toggle_on`/`toggle_off` its `toggled_on`
state. So if, in every way of making the formula true, the object `a` must change where
it rests (an `on`/`in` atom about `a` has the wrong truth), one action is spent on `a`;
distinct such requirements cost distinct actions. The bound walks the formula and
returns, for the truth value wanted, the requirements every solution shares (`needed`)
and a count no solution beats (`least`):

- an atom with the wrong truth: one requirement (`on`/`in`: the source's place; `open`,
  `toggled_on`: that state of the object) and at least one action; an atom of another
  relation (`under`, `nextto`, `inroom`) counts one action and no requirement, since
  moving either object may change it;
- all parts wanted (and, forall, or wanted false, ...): the union of the parts'
  requirements, at least as many actions as the union holds and as any part needs;
- one part wanted (or, exists, ...): the requirements all parts share, the fewest
  actions of any part;
- `forn` and the pair quantifiers: one action when their truth is wrong.

A part whose truth is already the wanted one needs nothing, so the bound is 0 exactly
at the goal. Admissible, so A* over it stays optimal.
"""

from __future__ import annotations

from verigraph.graph.formula import Atom, Formula, Imply, Junction, Not, Pairs, Quantified
from verigraph.graph.formula_eval import Facts, holds_in

Need = tuple[frozenset[tuple[str, str]], int]
_NOTHING: Need = (frozenset(), 0)
PLACE_RELATIONS = ("on", "in")


def formula_bound(formula: Formula, facts: Facts) -> int:
    """Actions the formula needs at least, from the state `facts` describe."""
    return _Bound(facts).need(formula, {}, True)[1]


def _all(needs: list[Need]) -> Need:
    union: frozenset[tuple[str, str]] = frozenset().union(*(n[0] for n in needs))
    return union, max([len(union), *(n[1] for n in needs)])


def _any(needs: list[Need]) -> Need:
    if not needs:
        return frozenset(), 1
    shared = frozenset.intersection(*(n[0] for n in needs))
    return shared, max(len(shared), min(n[1] for n in needs))


class _Bound:
    def __init__(self, facts: Facts) -> None:
        self.facts = facts

    def need(self, node: Formula, env: dict[str, str], want: bool) -> Need:
        if holds_in(node, self.facts, env) == want:
            return _NOTHING
        if isinstance(node, Atom):
            terms = [env.get(t, t) for t in node.terms]
            if len(terms) == 1:
                return frozenset({(node.relation, terms[0])}), 1
            if node.relation in PLACE_RELATIONS:
                return frozenset({("place", terms[0])}), 1
            return frozenset(), 1
        if isinstance(node, Not):
            return self.need(node.body, env, not want)
        if isinstance(node, Junction):
            parts = [self.need(p, env, want) for p in node.parts]
            return _all(parts) if (node.op == "and") == want else _any(parts)
        if isinstance(node, Imply):  # (or (not condition) then)
            parts = [self.need(node.condition, env, not want), self.need(node.then, env, want)]
            return _any(parts) if want else _all(parts)
        if isinstance(node, Quantified) and node.op in ("forall", "exists"):
            name = node.param.name
            parts = [self.need(node.body, {**env, name: o}, want)
                     for o in self.facts.objects_of(node.param.kind)]
            return _all(parts) if (node.op == "forall") == want else _any(parts)
        assert isinstance(node, Quantified | Pairs)
        return frozenset(), 1
