"""Cycles in the support relation (`a on b` points from a to b), found in linear time."""

from __future__ import annotations


def find_single_support_cycle(below: dict[str, str]) -> list[str] | None:
    """find_support_cycle when every object has one support: the same cycle, found by
    walking down from each object in order and stopping at anything already walked."""
    walked: dict[str, str] = {}  # object -> the object its walk started from
    for root in below:
        if root in walked:
            continue
        path: list[str] = []
        node: str | None = root
        while node is not None and node not in walked:
            walked[node] = root
            path.append(node)
            node = below.get(node)
        if node is not None and walked[node] == root:
            return path[path.index(node):]
    return None


def find_support_cycle(below: dict[str, list[str]]) -> list[str] | None:
    """One cycle of the support relation (its nodes in order), or None.

    An iterative three-colour depth-first search: every node and edge is visited once,
    so a 100,000-block tower costs O(nodes + edges) with no recursion limit.
    (`networkx.find_cycle` restarts an edge search per node and grows quadratically
    on a single tall stack.)
    """
    done: set[str] = set()
    for root in below:
        if root in done:
            continue
        path: list[str] = [root]
        on_path: dict[str, int] = {root: 0}
        iterators = [iter(below.get(root, ()))]
        while iterators:
            nxt = next(iterators[-1], None)
            if nxt is None:
                node = path.pop()
                del on_path[node]
                done.add(node)
                iterators.pop()
                continue
            if nxt in on_path:
                return path[on_path[nxt]:]
            if nxt in done:
                continue
            on_path[nxt] = len(path)
            path.append(nxt)
            iterators.append(iter(below.get(nxt, ())))
    return None
