"""The native hand model: grasps and releases checked on the scene, one step at a time.

The gripper is an object of the scene (a fixed holder of capacity one), so holding a
block is the edge `block in hand`. A grasp (pick-up, unstack) names where the block is
taken from and fails when the hand is full, the block is covered or the source is wrong;
a release (put-down, stack) fails when the block is not the one held or the target is
covered. Each failure has its own constraint id and a concrete fix. Nothing here builds
a pydantic model: steps are compact tuples, turned into JSON-ready dicts at the end.
"""

from __future__ import annotations

import difflib

from verigraph.pddl.blocksworld.domain import BlocksDomain, UnsupportedDomainError
from verigraph.pddl.blocksworld.plans import PlanStep
from verigraph.pddl.blocksworld.problem import BlocksProblem, BlocksState

# (constraint, message, blocking, suggestion)
Failure = tuple[str, str, list[str], str]
EdgeTuple = tuple[str, str, str]


class HandModel:
    """Checks and applies plan steps on a blocks-world scene with an optional hand."""

    __slots__ = ("state", "table", "hand", "declared", "domain")

    def __init__(self, state: BlocksState, problem: BlocksProblem, domain: BlocksDomain) -> None:
        self.state = state
        self.table = problem.table
        self.hand = problem.hand
        self.declared = set(problem.blocks)
        self.domain = domain

    def _where(self, x: str) -> str:
        rel, target = self.state.support[x]
        if rel == "in":
            return "in the hand"
        return "on the table" if target == self.table else f"on {target}"

    def _unknown(self, step: PlanStep) -> Failure | None:
        for a in step.args:
            if a not in self.declared:
                near = difflib.get_close_matches(a, list(self.declared), n=3, cutoff=0.5)
                hint = (f"did you mean {' or '.join(near)}?" if near
                        else f"use a declared object: {', '.join(sorted(self.declared)[:8])}")
                return ("unknown_object", f"the problem declares no object '{a}'", [], hint)
        return None

    def _covered(self, x: str) -> Failure | None:
        on_top = list(self.state.carried[x])
        if not on_top:
            return None
        top = on_top[0]
        d = self.domain
        fix = (f"{d.call('unstack', top, x)} and {d.call('put-down', top)} first" if self.hand
               else f"{d.call('move-b-to-t', top, x)} first")
        return ("object_not_clear",
                f"{top} is on {x}: {d.atom('on', top, x)} holds, so {d.atom('clear', x)} is "
                "false", on_top, fix)

    def _hand_full(self) -> Failure | None:
        assert self.hand is not None
        held = list(self.state.carried[self.hand])
        if not held:
            return None
        d = self.domain
        return ("hand_full", f"the hand already holds {held[0]}: {d.atom('holding', held[0])} "
                f"holds, so {d.atom('handempty')} is false", held,
                f"release it first, e.g. {d.call('put-down', held[0])}")

    def _source(self, x: str, source: str | None) -> Failure | None:
        """`source` None means the table."""
        want = ("on", self.table if source is None else source)
        if self.state.support[x] == want:
            return None
        rel, below = self.state.support[x]
        d = self.domain
        named = "the table" if source is None else source
        needed = d.atom("ontable", x) if source is None else d.atom("on", x, source)
        if rel == "in":
            fix = "it is already held; release it instead"
        elif below == self.table:
            fix = (d.call("pick-up", x) if self.hand else
                   f"move it with {d.call('move-t-to-b', x, '<block>')}")
        else:
            fix = (d.call("unstack", x, below) if self.hand else
                   f"name its real source: {d.call('move-b-to-t', x, below)}")
        return ("wrong_source", f"{x} is {self._where(x)}, not on {named}: {needed} is false",
                [], fix)

    def _target(self, x: str, y: str, forbid_self: bool) -> Failure | None:
        if x == y:
            if not forbid_self:
                raise UnsupportedDomainError(
                    f"this domain lets {x} be moved onto itself, a state no scene graph (and "
                    "no real blocks world) has; add (not (= ?bm ?bt)) to the move action")
            return ("same_object", f"cannot put {x} on itself", [],
                    "choose another block or the table")
        on_top = list(self.state.carried[y])
        if on_top:
            return ("target_full", f"{y} already carries {on_top[0]} (capacity 1)", on_top,
                    f"clear {y} first or choose another target")
        if self.hand is not None and self.state.support[y][0] == "in":
            return ("target_full", f"{y} is held by the hand", [y], "put it down first")
        return None

    def _not_held(self, x: str) -> Failure | None:
        assert self.hand is not None
        if self.state.support[x] == ("in", self.hand):
            return None
        held = list(self.state.carried[self.hand])
        holds = f"the hand holds {held[0]}" if held else "the hand is empty"
        d = self.domain
        fix = (f"release {held[0]} instead" if held else
               f"grasp {x} first with {d.call('pick-up', x)} or {d.call('unstack', x, '...')}")
        return ("not_held", f"cannot release {x}: {holds}, so {d.atom('holding', x)} is false",
                held, fix)

    def check(self, step: PlanStep, forbid_self: bool = True) -> Failure | None:
        """The first reason `step` cannot run now, or None (changes nothing)."""
        failure = self._unknown(step)
        if failure:
            return failure
        role, args = step.role, step.args
        x = args[0]
        if role in ("pick-up", "unstack"):
            return (self._hand_full() or self._covered(x)
                    or self._source(x, args[1] if role == "unstack" else None))
        if role in ("put-down", "stack"):
            return self._not_held(x) or (self._target(x, args[1], True) if role == "stack"
                                         else None)
        if role == "move-b-to-b":
            return (self._covered(x) or self._source(x, args[1])
                    or self._target(x, args[2], forbid_self))
        if role == "move-b-to-t":
            return self._covered(x) or self._source(x, args[1])
        return self._covered(x) or self._source(x, None) or self._target(x, args[1], forbid_self)

    def apply(self, step: PlanStep) -> tuple[EdgeTuple, EdgeTuple]:
        """Apply a checked step; returns (removed edge, added edge)."""
        role, args = step.role, step.args
        x = args[0]
        if role in ("pick-up", "unstack"):
            assert self.hand is not None
            rel, target = "in", self.hand
        elif role == "stack":
            rel, target = "on", args[1]
        elif role == "move-b-to-b":
            rel, target = "on", args[2]
        elif role == "move-t-to-b":
            rel, target = "on", args[1]
        else:
            rel, target = "on", self.table
        old = self.state.support[x]
        self.state.set_support(x, rel, target)
        return (x, old[0], old[1]), (x, rel, target)

    def holds(self, role: str, args: tuple[str, ...]) -> bool:
        """A goal atom in the current state (facts about a held block are false)."""
        s = self.state
        if role == "on":
            return s.support.get(args[0]) == ("on", args[1])
        if role == "ontable":
            return s.support.get(args[0]) == ("on", self.table)
        if role == "clear":
            return not s.carried[args[0]] and s.support[args[0]][0] != "in"
        if role == "holding":
            return self.hand is not None and s.support.get(args[0]) == ("in", self.hand)
        return self.hand is None or not s.carried[self.hand]
