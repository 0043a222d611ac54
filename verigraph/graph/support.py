"""What stands on or in what: the support index both world models keep.

`support` maps an object to its one support edge, `(relation, target)`; `carried` maps
every object to what it carries (`{obj: relation}`). `graph.state.WorldState` (the scene
graph's world) and `pddl.blocksworld.problem.BlocksState` (the blocks-world engine's
plain-data world) both extend it, so an edit moves an object the same way in each. This
module imports nothing, so the blocks-world engine can use it without the scene-graph
models (docs/validator.md, Start-up).
"""

from __future__ import annotations


class SupportIndex:
    """Support edges and their inverse, kept in step by `set_support`."""

    __slots__ = ("support", "carried")

    def __init__(self) -> None:
        self.support: dict[str, tuple[str, str]] = {}
        self.carried: dict[str, dict[str, str]] = {}

    def set_support(self, obj: str, relation: str, target: str) -> None:
        """Replace obj's support edge (O(1))."""
        old = self.support.get(obj)
        if old is not None:
            del self.carried[old[1]][obj]
        self.support[obj] = (relation, target)
        self.carried[target][obj] = relation
