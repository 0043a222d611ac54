"""Physical processes: cook, heat, freeze, cool and thaw as rows of the action table.

BEHAVIOR's thermal states (`cooked`, `hot`, `frozen`) change by where an object is:
on or in a heat source that is on, on or in a cold source. Here each change is one
action with preconditions, a row of `verigraph.actions.schemas` like `open`:

- `cook(x)`: x is cookable, not cooked, and stands on or in a heat source (directly or
  through what carries it: a pan on the stove) that is on (a heat source that cannot be
  toggled is always on); x becomes cooked;
- `heat(x)`: the same for heatable x; x becomes hot;
- `freeze(x)`: x is freezable, not frozen, on or in a cold source (a fridge, a freezer;
  on when it can be toggled); x becomes frozen;
- `cool(x)`: x is hot and not on an active heat source; x is no longer hot;
- `thaw(x)`: x is frozen and not in an active cold source; x is no longer frozen.

Each action sets one state, so a goal `(and (cooked x) (hot x))` takes two steps; every
other process of BEHAVIOR (slicing, soaking, cleaning, filling, ...) is refused by
name at import (verigraph.graph.bddl_problem). This module holds the helpers the rows'
tests call and their refusals; the rows themselves are in the table.
"""

from __future__ import annotations

from collections.abc import Callable

from verigraph.actions.constraints import NO_GOAL, Wanted, pinned, put_back, wanted_state
from verigraph.actions.feedback import Violation
from verigraph.actions.model import StateAction
from verigraph.graph.dictionary import STATE_WORDS
from verigraph.graph.state import WorldState

# action -> (state key, value it sets, role the object needs, source role it needs or
# must not be on when active, whether the source is needed (True) or in the way (False))
PROCESSES: dict[str, tuple[str, bool, str, str, bool]] = {
    "cook": ("cooked", True, "cookable", "heat_source", True),
    "heat": ("hot", True, "heatable", "heat_source", True),
    "freeze": ("frozen", True, "freezable", "cold_source", True),
    "cool": ("hot", False, "heatable", "heat_source", False),
    "thaw": ("frozen", False, "freezable", "cold_source", False),
}
SOURCE_WORDS = {"heat_source": "heat source", "cold_source": "cold source"}
# Refusal ids of the process rows (beside not_<role>; described in actions.feedback).
ALREADY = {"cook": "already_cooked", "heat": "already_hot", "freeze": "already_frozen",
           "cool": "already_cool", "thaw": "already_thawed"}
NO_SOURCE = {"heat_source": "no_heat_source", "cold_source": "no_cold_source"}
SOURCE_OFF = {"heat_source": "heat_source_off", "cold_source": "cold_source_off"}
STILL_AT_SOURCE = {"heat_source": "still_heated", "cold_source": "still_cold"}


def source_below(state: WorldState, obj: str, role: str) -> str | None:
    """The nearest object with `role` (heat_source, cold_source) that `obj` rests on or
    in, directly or through what carries it (a pan on the stove); None if there is none.
    `under` and `nextto` are no contact."""
    current = state.support.get(obj)
    while current is not None and current[0] in ("on", "in"):
        below = current[1]
        if getattr(state.objects[below].props, role):
            return below
        current = state.support.get(below)
    return None


def source_on(state: WorldState, source: str | None) -> bool:
    """A source works when it is on, or when it cannot be toggled at all."""
    if source is None:
        return False
    return not state.objects[source].props.toggleable or \
        state.state_value(source, "toggled_on")


def active_source_below(state: WorldState, obj: str, role: str) -> bool:
    """Whether `obj` rests on or in a working source of `role`."""
    return source_on(state, source_below(state, obj, role))


def process_needs(state: WorldState, obj: str, key: str, want: bool
                  ) -> list[frozenset[tuple[str, str]]]:
    """What else a search must do before a process changes `obj`'s state `key` to
    `want`, as requirements ("one of these things must change": `("place", x)`,
    `("toggled_on", source)`), for an admissible bound: to cook, heat or freeze, the
    object (or what carries it) must come to rest on a working source, or the source
    under it be turned on; to cool or thaw, the reverse."""
    for k, value, _, role, needed in PROCESSES.values():
        if k != key or value != want:
            continue
        if active_source_below(state, obj, role) != needed:
            chain = [obj, *state.supports_chain(obj)]
            source = source_below(state, obj, role)
            things = {("place", o) for o in chain[: chain.index(source) if source else None]
                      if state.objects[o].props.movable}
            if source is not None and state.objects[source].props.toggleable:
                things.add(("toggled_on", source))
            return [frozenset(things)] if things else []
        return []
    return []


HELPERS = {"source_below": source_below, "source_on": source_on,
           "active_source_below": active_source_below}


def _violation(a: StateAction, constraint: str, message: str, fix: str) -> Violation:
    return Violation(action=a.model_dump(), constraint=constraint,  # type: ignore[arg-type]
                     message=message, suggestion=fix)


def _sources(state: WorldState, role: str) -> list[str]:
    return [o for o, info in state.objects.items() if getattr(info.props, role)][:3]


def already_processed_explainer(name: str) -> Callable[[WorldState, StateAction], Violation]:
    key, value, _, _, _ = PROCESSES[name]
    word = STATE_WORDS[key][value]

    def explain(state: WorldState, a: StateAction) -> Violation:
        default = "" if key in state.states.get(a.object, {}) else \
            f" (no state given: {STATE_WORDS[key][False]})"
        return _violation(a, ALREADY[name], f"{a.object} is already {word}{default}",
                          "drop this action")
    return explain


def no_source_explainer(name: str) -> Callable[[WorldState, StateAction], Violation]:
    role = PROCESSES[name][3]
    word = SOURCE_WORDS[role]

    def explain(state: WorldState, a: StateAction, *, wanted: Wanted = NO_GOAL) -> Violation:
        there = _sources(state, role)
        # With a goal: the source the goal wants the object on or in first.
        goal_sources = [place for obj, relation, place in sorted(wanted)
                        if obj == a.object and relation in ("on", "in")
                        and place in state.objects
                        and getattr(state.objects[place].props, role)]
        there = list(dict.fromkeys([*goal_sources, *there]))
        relation = "in" if there and state.objects[there[0]].props.container and \
            not state.objects[there[0]].props.surface else "on"
        fix = (f"put it on or in a {word} first, e.g. move({a.object}, {relation}, "
               f"{there[0]}){put_back(state, [a.object], wanted, a.text())}" if there else
               f"nothing in the scene is a {word}; drop this action")
        return _violation(a, NO_SOURCE[role], f"{a.object} is not on or in a {word}", fix)
    return explain


def source_off_explainer(name: str) -> Callable[[WorldState, StateAction], Violation]:
    role = PROCESSES[name][3]

    def explain(state: WorldState, a: StateAction, *, wanted: Wanted = NO_GOAL) -> Violation:
        source = source_below(state, a.object, role)
        after = (f", then toggle_off({source}) (the goal wants it off)"
                 if wanted_state(wanted, str(source), "toggled_on") is False else "")
        return _violation(a, SOURCE_OFF[role],
                          f"{a.object} rests on or in {source}, a {SOURCE_WORDS[role]} that is off"
                          + ("" if "toggled_on" in state.states.get(str(source), {}) else
                             " (no state given: off)"),
                          f"toggle_on({source}) first{after}")
    return explain


def still_at_source_explainer(name: str) -> Callable[[WorldState, StateAction], Violation]:
    role = PROCESSES[name][3]

    def explain(state: WorldState, a: StateAction, *, wanted: Wanted = NO_GOAL) -> Violation:
        source = str(source_below(state, a.object, role))
        move = f"move {a.object} off {source}"
        toward = next((f"move({a.object}, {relation}, {place}) (where the goal wants it)"
                       for obj, relation, place in sorted(wanted)
                       if obj == a.object and relation in ("on", "in") and place != source
                       and (a.object, relation, place) != (a.object, *state.support[a.object])),
                      None)
        move = toward or move
        switch = f"toggle_off({source})" if state.objects[source].props.toggleable else ""
        # With a goal: what keeps a goal edge or state first (the goal keeps the object
        # where it is: switch the source off; the goal wants the source on: move).
        kept = pinned(state, a.object, wanted)
        if switch and wanted_state(wanted, source, "toggled_on") is not True and kept:
            fix = f"{switch} (the goal keeps {a.object} where it is), or {move}"
        elif switch and wanted_state(wanted, source, "toggled_on") is True:
            fix = f"{move} (the goal wants {source} on)"
        else:
            fix = move + (f", or {switch}" if switch else "")
        return _violation(a, STILL_AT_SOURCE[role],
                          f"{a.object} rests on {source}, a {SOURCE_WORDS[role]} that is on",
                          fix)
    return explain
