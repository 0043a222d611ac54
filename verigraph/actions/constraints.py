"""The constraints C: one small function per constraint id, checked in a fixed order.

Each check looks only at the object, the target and their neighbours in the
`WorldState` indexes, so validating an action costs O(degree + stack height).
Execution stops at the first failing check; `validator.all_violations` runs them all,
so a reader sees every reason at once. A Violation says what failed, why, and a concrete
fix that covers every blocker.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, MoveAction
from verigraph.graph.state import WorldState


def _violation(action: MoveAction | AlignAction, constraint: str, message: str,
               suggestion: str, blocking: list[str] | None = None) -> Violation:
    return Violation(action=action.model_dump(), constraint=constraint,  # type: ignore[arg-type]
                     message=message, blocking=blocking or [], suggestion=suggestion)


# Fuzzy matching compares against at most this many ids of a similar length, so an
# unknown name in a huge scene costs a bounded amount of work.
MAX_FUZZY_CANDIDATES = 400


def _nearest_ids(state: WorldState, name: str) -> list[str]:
    """Ids that look like `name`, or whose label is `name` (only runs on failure)."""
    label = state.dictionary.resolve(name)
    by_label = [o.id for o in state.objects.values() if o.label == label][:3]
    candidates = [i for i in state.objects if abs(len(i) - len(name)) <= 3]
    close = difflib.get_close_matches(name, candidates[:MAX_FUZZY_CANDIDATES], n=3, cutoff=0.5)
    return list(dict.fromkeys(by_label + close))[:3]


def _place_hint(state: WorldState, obj: str, exclude: set[str]) -> str:
    place = state.free_place_for(obj, exclude)
    return f"move({obj}, on, {place})" if place else f"move({obj}, on, <a free surface>)"


# A suggestion names at most this many blockers one by one, then how many more there are.
MAX_NAMED_BLOCKERS = 5


def _names(items: list[str]) -> str:
    """`knife`, `knife and spoon`, `knife, spoon and lid`."""
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


def _clear_hint(state: WorldState, blockers: list[str], exclude: set[str]) -> str:
    """`move knife, spoon and lid somewhere else first, e.g. move(knife, on, counter), ...`

    Every blocker gets its own move, and the places account for each other: a surface
    that the earlier hints fill up is not offered again, so the suggested moves are valid
    in sequence. Only runs on failure, O(blockers x fixed surfaces).
    """
    named = blockers[:MAX_NAMED_BLOCKERS]
    full = set(exclude)
    planned: dict[str, int] = {}
    hints = []
    for obj in named:
        place = state.free_place_for(obj, full | set(blockers))
        if place is None:
            hints.append(f"move({obj}, on, <a free surface>)")
            continue
        planned[place] = planned.get(place, 0) + 1
        cap = state.objects[place].props.capacity
        if cap is not None and len(state.carried[place]) + planned[place] >= cap:
            full.add(place)
        hints.append(f"move({obj}, on, {place})")
    more = len(blockers) - len(named)
    who = _names(named) if not more else f"{', '.join(named)} and {more} more"
    return f"move {who} somewhere else first, e.g. {', '.join(hints)}"


# -- move ------------------------------------------------------------------------------------
def check_known_objects(state: WorldState, a: MoveAction) -> Violation | None:
    for role, name in (("object", a.object), ("target", a.target)):
        if name not in state.objects:
            near = _nearest_ids(state, name)
            hint = f"did you mean {' or '.join(near)}?" if near else \
                f"use an id from the scene: {', '.join(list(state.objects)[:8])}"
            return _violation(a, "unknown_object",
                              f"there is no object '{name}' in the scene ({role})", hint)
    return None


def check_relation(state: WorldState, a: MoveAction) -> Violation | None:
    if a.relation not in state.move_relations:
        allowed = state.move_relations
        fix = ("tangram pieces are placed with align(piece, side, target, target_side)"
               if a.relation == "touches" else f"use one of: {', '.join(allowed)}")
        return _violation(a, "unknown_relation",
                          f"'{a.relation}' is not a relation move can create "
                          f"(R = {', '.join(allowed) or 'none'})", fix)
    return None


def check_same_object(state: WorldState, a: MoveAction) -> Violation | None:
    if a.object == a.target:
        return _violation(a, "same_object", f"cannot put {a.object} {a.relation} itself",
                          f"choose a different target, e.g. {_place_hint(state, a.object, set())}")
    return None


def check_movable(state: WorldState, a: MoveAction) -> Violation | None:
    info = state.objects[a.object]
    if not info.props.movable:
        return _violation(a, "not_movable", f"{a.object} ({info.label}) is fixed and cannot be "
                          "moved", f"move objects onto {a.object} instead of moving it")
    return None


def check_already_there(state: WorldState, a: MoveAction) -> Violation | None:
    if state.support.get(a.object) == (a.relation, a.target):
        return _violation(a, "already_there", f"{a.object} is already {a.relation} {a.target}",
                          "drop this action; it changes nothing")
    return None


def check_cycle(state: WorldState, a: MoveAction) -> Violation | None:
    if not state.carried[a.object]:
        return None  # nothing rests on the object, so nothing below the target can be it
    chain = state.supports_chain(a.target)
    if a.object in chain:
        above = chain[: chain.index(a.object)]
        path = " on ".join([a.target, *above, a.object])
        return _violation(
            a, "would_create_cycle",
            f"cannot put {a.object} {a.relation} {a.target}: {path}, so it would rest on itself",
            f"first move {a.target} off {a.object}, e.g. "
            f"{_place_hint(state, a.target, {a.object, *above})}", [a.target, *above])
    return None


def check_clear(state: WorldState, a: MoveAction) -> Violation | None:
    on_top = state.carried[a.object]
    if on_top:
        blockers = list(on_top)
        what = ", ".join(f"{b} is {on_top[b]} {a.object}" for b in blockers)
        return _violation(a, "object_not_clear", f"cannot move {a.object}: {what}",
                          _clear_hint(state, blockers, {a.object}), blockers)
    return None


def check_target_kind(state: WorldState, a: MoveAction) -> Violation | None:
    t = state.objects[a.target]
    if a.relation == "on" and not t.props.surface:
        fix = (f"use move({a.object}, in, {a.target})" if t.props.container else
               f"choose a surface, e.g. {_place_hint(state, a.object, {a.target})}")
        return _violation(a, "target_not_surface",
                          f"{a.target} ({t.label}) is not a surface, nothing can go on it", fix)
    if a.relation == "in" and not t.props.container:
        fix = (f"use move({a.object}, on, {a.target})" if t.props.surface else
               f"choose a container or a surface, e.g. {_place_hint(state, a.object, {a.target})}")
        return _violation(a, "target_not_container",
                          f"{a.target} ({t.label}) is not a container, nothing can go in it", fix)
    return None


def check_capacity(state: WorldState, a: MoveAction) -> Violation | None:
    if state.has_room(a.target):
        return None
    carried = list(state.carried[a.target])
    cap = state.objects[a.target].props.capacity
    first = carried[0]
    return _violation(
        a, "target_full",
        f"{a.target} already carries {len(carried)} object(s) ({', '.join(carried)}), "
        f"its capacity is {cap}",
        f"make room on {a.target} first (any one of {_names(carried[:MAX_NAMED_BLOCKERS])}"
        f"{' or more' if len(carried) > MAX_NAMED_BLOCKERS else ''} elsewhere), e.g. "
        f"{_place_hint(state, first, {a.target, a.object})}, or choose another target",
        carried)


MOVE_CHECKS: tuple[Callable[[WorldState, MoveAction], Violation | None], ...] = (
    check_known_objects, check_relation, check_same_object, check_movable, check_already_there,
    check_cycle, check_clear, check_target_kind, check_capacity,
)
# Checks whose failure makes the later ones meaningless (or unsafe to run: they index the
# object and the target); all_violations stops at them.
GATE_CHECKS = frozenset({check_known_objects, check_relation, check_same_object})


# -- align (tangram, symbolic part; geometry is checked by sim2d) ---------------------------
def check_align(state: WorldState, a: AlignAction) -> Violation | None:
    for role, name in (("object", a.object), ("target", a.target)):
        if name not in state.objects:
            near = _nearest_ids(state, name)
            return _violation(a, "unknown_object", f"there is no piece '{name}' ({role})",
                              f"did you mean {' or '.join(near)}?" if near else
                              f"use a piece from the scene: {', '.join(state.objects)}")
    if a.object == a.target:
        return _violation(a, "same_object", f"cannot align {a.object} with itself",
                          "choose another piece as the target")
    for name, side in ((a.object, a.side), (a.target, a.target_side)):
        n_sides = state.side_count(name)
        if n_sides is None:
            return _violation(a, "unknown_side", f"{name} is not a tangram piece and has no "
                              "sides", "use move(object, relation, target) for tabletop objects")
        if not 0 <= side < n_sides:
            return _violation(a, "unknown_side", f"{name} has sides 0..{n_sides - 1}, not {side}",
                              f"use a side index between 0 and {n_sides - 1}")
    if not state.objects[a.object].props.movable:
        return _violation(a, "not_movable", f"{a.object} is fixed", "move another piece")
    if (a.target, a.target_side) in state.partners((a.object, a.side)):
        return _violation(a, "already_there",
                          f"side {a.side} of {a.object} already touches side {a.target_side} "
                          f"of {a.target}", "drop this action; it changes nothing")
    taken = next((s for s in state.partners((a.target, a.target_side)) if s[0] != a.object),
                 None)
    if taken is not None:
        return _violation(a, "side_occupied",
                          f"side {a.target_side} of {a.target} already touches side {taken[1]} "
                          f"of {taken[0]}", f"align with a free side of {a.target}, or move "
                          f"{taken[0]} away first", [taken[0]])
    return None
