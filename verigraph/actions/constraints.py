"""The constraints C: what each refusal says, and its fix.

Whether a precondition holds is the `test` of its row in the action table
(`verigraph.actions.schemas`); the `explain_*` functions here build the refusal when
it does not: what failed, why, and a concrete fix that covers every blocker (a fix
names a real action the verifier accepts). They look only at the object, the target
and their neighbours in the `WorldState` indexes. The tangram `align` check lives here
whole (`check_align`; see the table's docstring for why it is not a row).
"""

from __future__ import annotations

import difflib
from collections.abc import Callable

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, MoveAction, StateAction
from verigraph.graph.dictionary import STATE_WORDS
from verigraph.graph.formula_eval import facts_of
from verigraph.graph.state import WorldState

# The (object, relation, place) edges a known goal asks for (`graph.goal.wanted_placements`),
# with its states (`(fridge, open, "false")`) and sided tangram contacts in the same shape.
# With them every fix keeps the goal edges, states and contacts that hold (it moves an
# object the goal does not keep where it is, says to put back what it must move, to
# close again what the goal wants closed) and moves toward the goal when that move is
# valid; empty (no goal), every fix is the goal-blind one.
Wanted = frozenset[tuple[str, str, str]]
NO_GOAL: Wanted = frozenset()


def wanted_state(wanted: Wanted, obj: str, key: str) -> bool | None:
    """The value the goal wants for `obj`'s state `key`, or None (the goal is silent)."""
    if (obj, key, "true") in wanted:
        return True
    if (obj, key, "false") in wanted:
        return False
    return None


def pinned(state: WorldState, obj: str, wanted: Wanted) -> bool:
    """Whether the goal keeps `obj` where it is (its placement is a goal edge)."""
    where = state.support.get(obj)
    return where is not None and (obj, *where) in wanted


def put_back(state: WorldState, objs: list[str], wanted: Wanted, after: str | None = None
             ) -> str:
    """`; after move(book, on, shelf), put cup back on book (the goal keeps it there)`: said
    once, after a fix's moves, for the objects of `objs` it takes off a goal edge that
    holds; empty when there are none.

    The clause follows every move of the fix, never one of them: putting an object back
    at once would block the very move it was cleared for. An object whose carrier the fix
    moves too goes back once that carrier is where the goal wants it (screws back in the
    tin once the tin is in the cabinet), which also saves moving them twice.
    """
    kept = [o for o in objs if pinned(state, o, wanted)]
    if not kept:
        return ""
    goal_of = {o: (r, p) for o, r, p in sorted(wanted) if r in state.move_relations}
    now: list[str] = []
    waiting: dict[str, list[str]] = {}
    for obj in kept:
        relation, place = state.support[obj]
        if place in objs and place in goal_of and not pinned(state, place, wanted):
            waiting.setdefault(place, []).append(obj)
        else:
            now.append(f"{obj} back {relation} {place}")
    parts = [f"{'after ' + after if after else 'later'}, put {_names(now)}"] if now else []
    for place, objects in waiting.items():
        relation = state.support[objects[0]][0]
        parts.append(f"{'and ' if parts else ''}put {_names(objects)} back {relation} "
                     f"{place} once {place} is {' '.join(goal_of[place])}")
    them = "it" if len(kept) == 1 else "them"
    return f"; {', '.join(parts)} (the goal keeps {them} there)"


def _violation(action: MoveAction | AlignAction | StateAction, constraint: str, message: str,
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


# Where no fixed surface has room, a place for an object is looked for among at most this
# many other objects (in scene order), so a failure in a huge scene costs bounded work.
MAX_PLACE_CANDIDATES = 2000


def _room(state: WorldState, place: str, planned: dict[str, int]) -> float:
    cap = state.objects[place].props.capacity
    used = state.load(place) + planned.get(place, 0)
    return float("inf") if cap is None else cap - used


def _load(state: WorldState, place: str, planned: dict[str, int]) -> str:
    """`2 of 3` (what the place carries of its capacity), or `2, no limit`."""
    cap = state.objects[place].props.capacity
    used = state.load(place) + planned.get(place, 0)
    return f"{used} of {cap}" if cap is not None else f"{used}, no limit"


def _takes(state: WorldState, obj: str, place: str, exclude: set[str],
           planned: dict[str, int], relations: tuple[str, ...] = ("on", "in")) -> str | None:
    """The relation of `relations` by which `obj` can go to `place` now (`on` first), or
    None: the move must pass every check (not itself, not where it is, no cycle, room,
    kind, R)."""
    if place == obj or place in exclude or _room(state, place, planned) <= 0:
        return None
    props = state.objects[place].props
    if not (props.surface or props.container):
        return None
    if state.carried[obj] and obj in state.supports_chain(place):
        return None  # place rests on obj
    for relation, kind in (("on", props.surface), ("in", props.container)):
        if kind and relation in relations and relation in state.move_relations and \
                state.support.get(obj) != (relation, place) and \
                not (relation == "in" and _closed(state, place)):
            return relation
    return None


def _goal_place(state: WorldState, obj: str, exclude: set[str], planned: dict[str, int],
                wanted: Wanted) -> tuple[str, str, str] | None:
    """(relation, place, why) for a valid move of `obj` to where the goal wants it."""
    for source, relation, place in sorted(wanted):
        if source == obj and place in state.objects and relation in ("on", "in") and \
                _takes(state, obj, place, exclude, planned, (relation,)) == relation:
            return relation, place, "where the goal wants it"
    return None


def _forbidden_places(state: WorldState, obj: str, wanted: Wanted) -> set[str]:
    """The places the goal forbids `obj`: named (`(not (on cup_1 plate_a))`) or by kind
    (`("?cup", "not on", "?plate")`, from "no cup on any plate"), read through the
    formula evaluator's kinds; a container forbidden with `not in` forbids what is
    within it too (a formula's `inside` reads down the placements: a cup on a plate in
    the cabinet is in the cabinet)."""
    forbidden: set[tuple[str, str]] = set()  # (relation, place)
    facts = None
    for o, relation, place in wanted:
        if not relation.startswith("not "):
            continue
        if o.startswith("?") or place.startswith("?"):
            facts = facts or facts_of(state)
            if o == obj or (o.startswith("?") and obj in facts.objects_of(o[1:])):
                forbidden.update((relation, p) for p in (
                    facts.objects_of(place[1:]) if place.startswith("?") else (place,)))
        elif o == obj:
            forbidden.add((relation, place))
    places = {place for _, place in forbidden}
    boxes = {place for relation, place in forbidden if relation == "not in"}
    if boxes:
        facts = facts or facts_of(state)
        places.update(o for o in state.objects if any(facts.within(o, b) for b in boxes))
    return places


def _free_place(state: WorldState, obj: str, exclude: set[str],
                planned: dict[str, int] | None = None, *,
                wanted: Wanted = NO_GOAL) -> tuple[str, str, str] | None:
    """(relation, place, why) for a move of `obj` the verifier accepts now, or None.

    Where the goal wants `obj` comes first, when that move is valid. Then a fixed surface
    with room (it never moves and takes anything; `why` is then empty); else a fixed
    container, else a movable surface or container, the one with the most room first, and
    `why` says what it carries and that no fixed surface has room. `planned` counts
    objects earlier hints already put on a place.
    """
    planned = planned or {}
    if wanted and (toward := _goal_place(state, obj, exclude, planned, wanted)):
        return toward
    forbidden = _forbidden_places(state, obj, wanted) if wanted else set()
    exclude = exclude | forbidden  # never a place the goal forbids (`(not (on cup plate))`)
    for surface in state.fixed_surfaces:
        if _takes(state, obj, surface, exclude, planned) == "on":
            return "on", surface, ""
    best: tuple[int, float, int, str, str] | None = None
    for order, (other, info) in enumerate(state.objects.items()):
        if order >= MAX_PLACE_CANDIDATES:
            break
        relation = _takes(state, obj, other, exclude, planned)
        if relation is None:
            continue
        rank = (int(info.props.movable), -_room(state, other, planned), order, relation, other)
        if best is None or rank < best:
            best = rank
    if best is None:
        return None
    relation, place = best[3], best[4]
    info = state.objects[place]
    kind = "surface" if relation == "on" else "container"
    what = f"chosen because {place}, a {'movable' if info.props.movable else 'fixed'} " \
           f"{kind}, carries {_load(state, place, planned)}"
    return relation, place, \
        f"{what} and {_no_fixed_room(state, obj, exclude, planned, forbidden)}"


def _no_fixed_room(state: WorldState, obj: str, exclude: set[str],
                   planned: dict[str, int], forbidden: set[str] | None = None) -> str:
    """Why no fixed surface was chosen: `shelf is full at 3 of 3`, `the goal keeps cup off
    desk`, or there is none."""
    surfaces = state.fixed_surfaces
    if not surfaces:
        return "the scene has no fixed surface"
    reasons = []
    for s in surfaces[:3]:
        if _room(state, s, planned) <= 0:
            reasons.append(f"{s} is full at {_load(state, s, planned)}")
        elif state.support.get(obj) == ("on", s):
            reasons.append(f"{obj} is on {s} already")
        elif forbidden and s in forbidden:
            reasons.append(f"the goal keeps {obj} off {s}")
        else:
            reasons.append(f"{s} is {'the target' if s in exclude else 'ruled out'}")
    more = f" and {len(surfaces) - 3} more fixed surface(s) too" if len(surfaces) > 3 else ""
    return ", ".join(reasons) + more


def _no_place(state: WorldState, obj: str, exclude: set[str], wanted: Wanted = NO_GOAL
              ) -> str:
    """`no place in the scene takes jam_jar now (shelf is full at 3 of 3)`: said instead of
    a placeholder when no surface or container has room for the object (or none the goal
    allows it)."""
    forbidden = _forbidden_places(state, obj, wanted) if wanted else set()
    return f"no place in the scene takes {obj} now " \
           f"({_no_fixed_room(state, obj, exclude | forbidden, {}, forbidden)}); free one first"


def _move_text(obj: str, found: tuple[str, str, str]) -> str:
    relation, place, why = found
    return f"move({obj}, {relation}, {place})" + (f" ({why})" if why else "")


def _place_hint(state: WorldState, obj: str, exclude: set[str], *,
                wanted: Wanted = NO_GOAL) -> str:
    """`move(cup, on, desk)`, or a place with the reason it was chosen (with a goal:
    where the goal wants it first)."""
    found = _free_place(state, obj, exclude, wanted=wanted)
    return _move_text(obj, found) if found else _no_place(state, obj, exclude, wanted)


# A suggestion names at most this many blockers one by one, then how many more there are.
MAX_NAMED_BLOCKERS = 5


def _names(items: list[str]) -> str:
    """`knife`, `knife and spoon`, `knife, spoon and lid`."""
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


def _unstack_order(state: WorldState, blockers: list[str]) -> list[str]:
    """The blockers and everything resting on them, each after what rests on it (the top
    of a stack first), so every object is clear when its turn comes. Iterative, and
    bounded by MAX_PLACE_CANDIDATES objects."""
    order: list[str] = []
    for blocker in blockers:
        todo: list[tuple[str, bool]] = [(blocker, False)]
        while todo and len(order) < MAX_PLACE_CANDIDATES:
            obj, ready = todo.pop()
            if ready:
                order.append(obj)
                continue
            todo.append((obj, True))
            todo.extend((above, False) for above in reversed(list(state.carried[obj])))
    return order


def _unstack_moves(state: WorldState, order: list[str], exclude: set[str],
                   wanted: Wanted) -> list[str]:
    """A move for each of the first MAX_NAMED_BLOCKERS objects of `order` (an unstack
    order), the places accounting for each other (see _clear_hint); what the goal keeps
    where it is goes back after them all (`put_back`)."""
    moving = exclude | set(order)
    planned: dict[str, int] = {}
    hints = []
    for obj in order[:MAX_NAMED_BLOCKERS]:
        found = _free_place(state, obj, moving, planned, wanted=wanted)
        if found is None:
            hints.append(_no_place(state, obj, moving, wanted))
            continue
        hints.append(_move_text(obj, found))
        planned[found[1]] = planned.get(found[1], 0) + 1
    return hints


def _clear_hint(state: WorldState, blockers: list[str], exclude: set[str], after: str, *,
                wanted: Wanted = NO_GOAL) -> str:
    """`move knife, spoon and lid somewhere else first, e.g. move(knife, on, counter), ...`

    Every blocker gets its own move, after the moves of what rests on it, and the places
    account for each other: a place that the earlier hints fill up is not offered again,
    and nothing goes onto an object that is being cleared away, so the suggested moves are
    valid in sequence. Only runs on failure, O(moves x MAX_PLACE_CANDIDATES) at most.
    """
    order = _unstack_order(state, blockers)
    hints = _unstack_moves(state, order, exclude, wanted)
    shown = order[:MAX_NAMED_BLOCKERS]
    named = blockers[:MAX_NAMED_BLOCKERS]
    more = len(blockers) - len(named)
    who = _names(named) if not more else f"{', '.join(named)} and {more} more"
    direct = set(blockers)
    above = [o for o in order if o not in direct]
    tail = " and more" if len(above) > MAX_NAMED_BLOCKERS else ""
    first = (f" (what rests on {'it' if len(blockers) == 1 else 'them'} before: "
             f"{_names(above[:MAX_NAMED_BLOCKERS])}{tail})" if above else "")
    rest = len(order) - len(shown)
    later = f", then {rest} more move(s)" if rest else ""
    return f"move {who} somewhere else first{first}, e.g. {', '.join(hints)}{later}" \
        f"{put_back(state, order, wanted, after)}"


# -- move: the refusals of the move row's preconditions (verigraph.actions.schemas) ----------
# Each is called only when its precondition's test failed, and says why and how to fix it.
def explain_unknown_object(state: WorldState, a: MoveAction | StateAction, *,
                           wanted: Wanted = NO_GOAL) -> Violation:
    """An id the scene lacks: the ids that look like it; with a goal and an unknown
    target, the move the goal wants for the object first."""
    names = (("object", a.object), ("target", a.target)) if isinstance(a, MoveAction) \
        else (("object", a.object),)
    role, name = next((r, n) for r, n in names if n not in state.objects)
    near = _nearest_ids(state, name)
    hint = f"did you mean {' or '.join(near)}?" if near else \
        f"use an id from the scene: {', '.join(list(state.objects)[:8])}"
    if role == "target" and a.object in state.objects and wanted and \
            state.is_clear(a.object) and \
            (toward := _goal_place(state, a.object, set(), {}, wanted)):
        hint = f"e.g. {_move_text(a.object, toward)}; or {hint}"
    return _violation(a, "unknown_object",
                      f"there is no object '{name}' in the scene ({role})", hint)


def explain_relation(state: WorldState, a: MoveAction) -> Violation:
    allowed = state.move_relations
    fix = ("tangram pieces are placed with align(piece, side, target, target_side)"
           if a.relation == "touches" else f"use one of: {', '.join(allowed)}")
    return _violation(a, "unknown_relation",
                      f"'{a.relation}' is not a relation move can create "
                      f"(R = {', '.join(allowed) or 'none'})", fix)


def explain_same_object(state: WorldState, a: MoveAction, *,
                        wanted: Wanted = NO_GOAL) -> Violation:
    return _violation(a, "same_object", f"cannot put {a.object} {a.relation} itself",
                      "choose a different target, e.g. "
                      f"{_place_hint(state, a.object, set(), wanted=wanted)}")


def explain_movable(state: WorldState, a: MoveAction) -> Violation:
    info = state.objects[a.object]
    return _violation(a, "not_movable", f"{a.object} ({info.label}) is fixed and cannot be "
                      "moved", f"move objects onto {a.object} instead of moving it")


def explain_already_there(state: WorldState, a: MoveAction) -> Violation:
    return _violation(a, "already_there", f"{a.object} is already {a.relation} {a.target}",
                      "drop this action; it changes nothing")


def explain_cycle(state: WorldState, a: MoveAction, *, wanted: Wanted = NO_GOAL
                  ) -> Violation:
    chain = state.supports_chain(a.target)
    above = chain[: chain.index(a.object)]
    path = " on ".join([a.target, *above, a.object])
    return _violation(
        a, "would_create_cycle",
        f"cannot put {a.object} {a.relation} {a.target}: {path}, so it would rest on itself",
        f"first move {a.target} off {a.object}, e.g. "
        f"{_place_hint(state, a.target, {a.object, *above}, wanted=wanted)}"
        f"{put_back(state, [a.target], wanted)}", [a.target, *above])


def explain_clear(state: WorldState, a: MoveAction, *, wanted: Wanted = NO_GOAL) -> Violation:
    on_top = state.carried[a.object]
    blockers = list(on_top)
    what = ", ".join(f"{b} is {on_top[b]} {a.object}" for b in blockers)
    return _violation(a, "object_not_clear", f"cannot move {a.object}: {what}",
                      _clear_hint(state, blockers, {a.object}, a.text(), wanted=wanted),
                      blockers)


def _kind_fix(state: WorldState, a: MoveAction, other: str, takes_other: bool,
              wanted: Wanted) -> str:
    """The fix for a target of the wrong kind: the other relation when the target takes
    it now, else a place that does (never a move the verifier would refuse)."""
    kinds = "a surface or a container" if a.relation == "on" else "a container or a surface"
    if takes_other and other in state.move_relations:
        if state.support.get(a.object) == (other, a.target):
            return f"{a.object} is already {other} {a.target}; drop this action"
        cycle = bool(state.carried[a.object]) and a.object in state.supports_chain(a.target)
        closed = other == "in" and _closed(state, a.target)
        if state.has_room(a.target) and not cycle and not closed:
            return f"use move({a.object}, {other}, {a.target})"
    return f"choose {kinds}, e.g. {_place_hint(state, a.object, {a.target}, wanted=wanted)}"


def explain_target_kind(state: WorldState, a: MoveAction, *,
                        wanted: Wanted = NO_GOAL) -> Violation:
    t = state.objects[a.target]
    if a.relation == "on":
        return _violation(a, "target_not_surface",
                          f"{a.target} ({t.label}) is not a surface, nothing can go on it",
                          _kind_fix(state, a, "in", t.props.container, wanted))
    if a.relation == "in":
        return _violation(a, "target_not_container",
                          f"{a.target} ({t.label}) is not a container, nothing can go in it",
                          _kind_fix(state, a, "on", t.props.surface, wanted))
    if a.relation == "under":
        furniture = [o for o in state.fixed_surfaces if o != a.object][:3]
        return _violation(
            a, "target_not_furniture",
            f"{a.target} ({t.label}) is not furniture (a fixed surface), nothing stands "
            "under it", f"use move({a.object}, under, {furniture[0]})" if furniture
            else f"choose a place, e.g. {_place_hint(state, a.object, {a.target}, wanted=wanted)}")
    room = a.target
    near = next((f for f, r in state.rooms.items() if r == room and f != a.object), None)
    return _violation(
        a, "target_is_room",
        f"{room} is a room; an object is placed by furniture and is in the room its "
        "furniture is in", f"use move({a.object}, nextto, {near})" if near else
        f"choose furniture, e.g. {_place_hint(state, a.object, {room}, wanted=wanted)}")


def _closed(state: WorldState, obj: str) -> bool:
    """An openable object that is closed now (no state: closed)."""
    return obj in state.openable and not state.state_value(obj, "open")


def closed_passage(state: WorldState, obj: str, relation: str, target: str) -> str | None:
    """The closed openable container `obj` would have to leave or enter, or None: one
    that holds the object, or the target, directly or through what carries them (bacon
    on a tray in a closed fridge stays there until the fridge is opened), or the target
    itself when the object goes `in` it."""
    if relation == "in" and _closed(state, target):
        return target
    for start in (obj, target):
        held = start
        for carrier in state.supports_chain(start):
            if state.support[held][0] == "in" and _closed(state, carrier):
                return carrier
            held = carrier
    return None


def explain_container_closed(state: WorldState, a: MoveAction, *,
                             wanted: Wanted = NO_GOAL) -> Violation:
    """Open it first; with a goal, close it again after when the goal wants it closed,
    and say so when the move takes the object off a goal edge that holds."""
    box = closed_passage(state, a.object, a.relation, a.target)
    assert box is not None  # the precondition failed on it
    label = state.objects[box].label
    if a.relation == "in" and box == a.target:
        message = f"cannot put {a.object} in {box} ({label}): {box} is closed"
    elif box in state.supports_chain(a.object):
        message = f"cannot take {a.object} out of {box} ({label}): {box} is closed"
    else:
        message = f"cannot reach {a.target} in {box} ({label}): {box} is closed"
    fix = f"open({box}) first, then {a.text()}"
    if wanted_state(wanted, box, "open") is False:
        fix += f", then close({box}) (the goal wants it closed)"
    if pinned(state, a.object, wanted):
        relation, place = state.support[a.object]
        fix += (f"; but the goal keeps {a.object} {relation} {place}: this move undoes "
                "it, so drop it unless it clears the way")
    return _violation(a, "container_closed", message, fix, [box])


def explain_capacity(state: WorldState, a: MoveAction, *,
                     wanted: Wanted = NO_GOAL) -> Violation:
    """With a goal, the fix moves only what the goal does not keep on the target, where
    the goal wants it first; when the goal keeps every one there, another target."""
    held = state.carried[a.target]
    carried = [o for o in held if held[o] in ("on", "in")]
    cap = state.objects[a.target].props.capacity
    message = f"{a.target} already carries {len(carried)} object(s) " \
              f"({', '.join(carried)}), its capacity is {cap}"
    exclude = {a.target, a.object}
    kept = [o for o in carried if pinned(state, o, wanted)]
    free = [o for o in carried if o not in kept]
    if not free:
        return _violation(
            a, "target_full", message,
            f"the goal keeps {_names(kept[:MAX_NAMED_BLOCKERS])}"
            f"{' and more' if len(kept) > MAX_NAMED_BLOCKERS else ''} there: choose another "
            f"target, e.g. {_place_hint(state, a.object, exclude, wanted=wanted)}", carried)
    # The example moves a carried object that is clear and has somewhere to go (with a
    # goal: toward where the goal wants it, if any such move is valid).
    movers = [o for o in free[:MAX_PLACE_CANDIDATES] if state.is_clear(o)]
    hint = next((_move_text(o, found) for o in movers
                 if (found := _goal_place(state, o, exclude, {}, wanted))), None) \
        if wanted else None
    hint = hint or next((_move_text(o, found) for o in movers
                         if (found := _free_place(state, o, exclude))), None)
    if hint is None and not movers:  # none is clear: the first with what rests on it
        order = _unstack_order(state, free[:1])
        hint = ", ".join(_unstack_moves(state, order, exclude, wanted)) + \
            put_back(state, order, wanted, a.text())
    hint = hint or _no_place(state, free[0], exclude)
    keeps = f"; the goal keeps {_names(kept[:MAX_NAMED_BLOCKERS])} there" if kept else ""
    return _violation(
        a, "target_full", message,
        f"make room on {a.target} first ({'any one of ' if len(free) > 1 or not kept else ''}"
        f"{_names(free[:MAX_NAMED_BLOCKERS])}"
        f"{' or more' if len(free) > MAX_NAMED_BLOCKERS else ''} elsewhere{keeps}), e.g. "
        f"{hint}, or choose another target",
        carried)


# -- open, close, toggle_on, toggle_off -----------------------------------------------------
def role_explainer(name: str, role: str) -> Callable[[WorldState, StateAction], Violation]:
    """The refusal of `open(plate)`: the object lacks the role, the fix names objects of
    the scene that have it."""
    def explain(state: WorldState, a: StateAction) -> Violation:
        info = state.objects[a.object]
        having = [o.id for o in state.objects.values() if getattr(o.props, role)][:3]
        fix = (f"{name} only what is {role}, e.g. {name}({having[0]})"
               + (f" ({', '.join(having)} are {role} here)" if len(having) > 1 else "")
               if having else f"nothing in the scene is {role}; drop this action")
        return _violation(a, f"not_{role}",
                          f"{a.object} ({info.label}) is not {role}", fix)
    return explain


_OPPOSITE = {"open": "close", "close": "open", "toggle_on": "toggle_off",
             "toggle_off": "toggle_on"}


def already_explainer(name: str, key: str, value: bool
                      ) -> Callable[[WorldState, StateAction], Violation]:
    """The refusal of `open(fridge)` on an open fridge (`already_open`)."""
    word = STATE_WORDS[key][value]

    def explain(state: WorldState, a: StateAction, *, wanted: Wanted = NO_GOAL) -> Violation:
        default = "" if key in state.states.get(a.object, {}) else \
            f" (no state given: {STATE_WORDS[key][False]})"
        fix = (f"drop this action (the goal wants {a.object} {word})"
               if wanted_state(wanted, a.object, key) is value else
               f"drop this action; {_OPPOSITE[name]}({a.object}) would make it "
               f"{STATE_WORDS[key][not value]}")
        return _violation(a, f"already_{word}", f"{a.object} is already {word}{default}", fix)
    return explain


# -- the goal in a world's refusal (the simulator knows no goal) ---------------------------
def goal_keeps(state: WorldState, obj: str, wanted: Wanted) -> bool:
    """Whether the goal keeps `obj` where it is now: its placement, or one of its
    tangram contacts, is wanted and holds."""
    if pinned(state, obj, wanted):
        return True
    return any((f"{obj}[{side}]", "touches", f"{other}[{other_side}]") in wanted
               or (f"{other}[{other_side}]", "touches", f"{obj}[{side}]") in wanted
               for (piece, side), partners in state.contacts.items() if piece == obj
               for other, other_side in partners)


def with_goal_note(state: WorldState, violation: Violation, wanted: Wanted) -> Violation:
    """A world's refusal (the simulator's room check or overlap, which know no goal)
    with a note when its fix would move a blocker the goal keeps where it is."""
    kept = [b for b in violation.blocking if b in state.objects and goal_keeps(state, b,
                                                                                wanted)]
    if kept:
        them = "it" if len(kept) == 1 else "them"
        violation.suggestion += (f"; the goal keeps {_names(kept[:MAX_NAMED_BLOCKERS])} "
                                 f"where {them} {'is' if len(kept) == 1 else 'are'}: prefer "
                                 f"another target, or put {them} back after")
    return violation


# -- align (tangram, symbolic part; geometry is checked by sim2d) ---------------------------
def _goal_contacts(wanted: Wanted, piece: str) -> list[tuple[int, str, int]]:
    """(side, other, other_side) of each contact the goal wants for `piece`."""
    found = []
    for source, relation, target in wanted:
        if relation != "touches" or "[" not in source:
            continue
        ends = [(name, int(side[:-1])) for name, side in
                (x.rsplit("[", 1) for x in (source, target))]
        for (mine, side), (other, other_side) in (ends, ends[::-1]):
            if mine == piece:
                found.append((side, other, other_side))
    return sorted(found)


def _toward_goal_contact(state: WorldState, a: AlignAction, wanted: Wanted) -> str:
    """`, e.g. align(square, 1, medium_triangle, 1) (a contact the goal wants)` for the
    first contact the goal wants for the moved piece that align could make now."""
    for side, other, other_side in _goal_contacts(wanted, a.object):
        if other in state.objects and (other, other_side) not in \
                state.partners((a.object, side)) and not any(
                s[0] != a.object for s in state.partners((other, other_side))):
            return (f", e.g. align({a.object}, {side}, {other}, {other_side}) (a contact "
                    "the goal wants)")
    return ""


def check_align(state: WorldState, a: AlignAction, *, wanted: Wanted = NO_GOAL
                ) -> Violation | None:
    """The symbolic refusal of an align (sides, occupied sides); with a goal, its fix
    never breaks a contact the goal wants and moves toward one it wants."""
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
        message = (f"side {a.target_side} of {a.target} already touches side {taken[1]} of "
                   f"{taken[0]}")
        toward = _toward_goal_contact(state, a, wanted)
        if {(f"{a.target}[{a.target_side}]", "touches", f"{taken[0]}[{taken[1]}]"),
                (f"{taken[0]}[{taken[1]}]", "touches", f"{a.target}[{a.target_side}]")} \
                & wanted:
            return _violation(a, "side_occupied", message,
                              f"the goal keeps that contact: align {a.object} with another "
                              f"free side{toward or ' of ' + a.target}", [taken[0]])
        return _violation(a, "side_occupied", message,
                          f"align with a free side of {a.target}, or move {taken[0]} away "
                          f"first{toward}", [taken[0]])
    return None
