"""Symbolic room check for household actions: does a valid action also fit in sim2d?

`room.room_violation` covers `on` and `in`; this adds what the household simulator
(sim2d.household, sim2d.beside) cannot do, conservatively, from sizes alone:
- `open`, `close`, `toggle_on`, `toggle_off`: always room (a bin is deeper than
  everything in the scene stacked, so a door never closes on what it holds);
- nothing goes `in` a movable container about as wide as its opening, or wider with
  a foot narrower than it (a plate over a pan): it wedges;
- nothing is lowered `on` or `in` something that stands under furniture, or next to
  something that does (the furniture's top is in the way);
- `under f`: the object is lower than f's underside and fits between f's legs beside
  what already stands there (each with a gap);
- nothing is lowered `on` or `in` something that stands next to something (it could
  lean on the neighbour);
- `nextto y`: nothing is next to y yet (the place at y's right side is free), y carries
  nothing (its load may reach over its side), and y's base, down its `nextto` chain,
  is furniture standing on the floor (the row beside it fits in the gap to the next
  piece) or a fixed surface (its load fits in half its width); not under furniture
  (things there stand apart), not in a container, not on a movable object.
"""

from __future__ import annotations

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction, MoveAction
from verigraph.graph.state import WorldState
from verigraph.sim2d.bodies import furniture_spec, movable_spec, under_span
from verigraph.sim2d.layout import furniture_gap, furniture_width
from verigraph.sim2d.placement import DROP_GAP, FIXED_GAP
from verigraph.sim2d.room import base_width, room_violation

UNDER_GAP = FIXED_GAP + 0.3
HEADROOM = 0.3
SNUG = 0.1  # an object this close to a container's opening width drops in unevenly


def _width(state: WorldState, obj: str) -> float:
    return float(state.objects[obj].props.width or 6.0)


def _fail(action: MoveAction, message: str, blocking: list[str], suggestion: str) -> Violation:
    return Violation(action=action.model_dump(), constraint="no_room", message=message,
                     blocking=blocking, suggestion=suggestion)


def _base(state: WorldState, obj: str) -> tuple[str, str]:
    """Down `obj`'s nextto chain: (relation, target) of the first other placement, or
    ("floor", furniture) for a chain that starts at furniture."""
    current = obj
    while True:
        below = state.support.get(current)
        if below is None:
            return "floor", current
        if below[0] != "nextto":
            return below
        current = below[1]


def _row(state: WorldState, start: str) -> list[str]:
    """The objects in `start`'s nextto chain to its right (`start` excluded)."""
    out: list[str] = []
    current = start
    while True:
        nxt = [o for o, rel in state.carried[current].items() if rel == "nextto"]
        if not nxt:
            return out
        current = nxt[0]
        out.append(current)


def _under_load(state: WorldState, furniture: str, moving: str) -> list[str]:
    """What stands on the floor under `furniture`: its `under` objects and their rows."""
    out = []
    for o, rel in state.carried[furniture].items():
        if rel == "under" and o != moving:
            out += [o] + [x for x in _row(state, o) if x != moving]
    return out


def _span(state: WorldState, furniture: str) -> tuple[float, float] | None:
    """(free width between the legs, clearance under the top) in the simulator."""
    info = state.objects[furniture]
    spec = furniture_spec(info.label, info.props, furniture_width(state, info), legs=True)
    span = under_span(spec, info.props)
    return (span[1] - span[0], span[2]) if span is not None else None


def _under_room(state: WorldState, action: MoveAction, furniture: str, width: float
                ) -> Violation | None:
    span = _span(state, furniture)
    if span is None:
        return _fail(action, f"nothing fits under {furniture} in the simulator", [],
                     "choose another place")
    if float(state.objects[action.object].props.height or 4.0) > \
            span[1] - HEADROOM - DROP_GAP:
        return _fail(action, f"{action.object} is too tall to stand under {furniture} (its "
                     f"underside is {span[1]:.0f} high)", [], "choose another place")
    load = _under_load(state, furniture, action.object)
    used = sum(_width(state, o) for o in load) + UNDER_GAP * (len(load) + 2) + width
    if used > span[0]:
        return _fail(action, f"there is no room left under {furniture} ({span[0]:.0f} "
                     f"wide; {', '.join(sorted(load))} stand there)", sorted(load),
                     f"move {sorted(load)[0]} away first, or choose another place")
    return None


def household_room_violation(state: WorldState, action: AnyAction) -> Violation | None:
    """Why a validator-valid action has no room in the household simulator, or None."""
    if not isinstance(action, MoveAction):
        return None
    obj, rel, target = action.object, action.relation, action.target
    if rel in ("on", "in"):
        chain = _base(state, target)
        if chain[0] == "under":
            return _fail(action, f"{target} stands under {chain[1]}: nothing can be lowered "
                         f"{rel} it", [target], f"move {target} out from under {chain[1]} "
                         "first")
        below = state.support.get(target)
        if below is not None and below[0] == "nextto":
            return _fail(action, f"{target} stands right next to {below[1]}: what goes {rel} "
                         f"it could lean on {below[1]}", [below[1]],
                         f"move {target} away from {below[1]} first")
        info = state.objects[target]
        if rel == "in" and info.props.movable:
            spec = movable_spec(info.label, info.props)
            opening = spec.cavity[1] - spec.cavity[0] if spec.cavity is not None else 0.0
            width, foot = _width(state, obj), base_width(state, obj)
            if spec.cavity is not None and (abs(opening - width) < SNUG or (
                    width > opening > foot)):
                return _fail(action, f"{obj} is about as wide as the opening of {target}: it "
                             "would wedge or drop in unevenly", [target],
                             "choose another container")
            if spec.cavity is not None and opening > foot > spec.floor:
                return _fail(action, f"{obj} stands on a base {foot:g} wide and the floor of "
                             f"{target} is {spec.floor:.1f} wide under slanted walls: it would "
                             "wedge between them", [target], "choose another container")
        capacity = state.objects[target].props.capacity
        if rel == "on" and not state.objects[target].props.movable and capacity is not None:
            crowded = _surface_violation(state, action, target)
            if crowded is not None:
                return crowded
        return room_violation(state, action)
    width = _width(state, obj)
    if rel == "under":
        return _under_room(state, action, target, width)
    taken = [o for o, r in state.carried[target].items() if r == "nextto"]
    if taken:
        return _fail(action, f"{taken[0]} already stands next to {target} (on its right "
                     "side, the side the simulator uses)", taken,
                     f"move {taken[0]} away first, or put {obj} next to {taken[0]}")
    load = [o for o, r in state.carried[target].items() if r in ("on", "in")]
    if load:
        return _fail(action, f"{target} carries {', '.join(sorted(load))}, which may reach "
                     "over its side", sorted(load), f"move {sorted(load)[0]} off {target} "
                     "first")
    kind, base = _base(state, target)
    if kind == "floor":
        if state.objects[base].props.movable:
            return _fail(action, f"{base} stands on nothing", [base], "choose another place")
        row = [o for o in _row(state, base) if o != obj]
        used = sum(_width(state, o) for o in row) + width + FIXED_GAP
        if used > furniture_gap(state):
            return _fail(action, f"the row beside {base} would not fit before the next "
                         "piece of furniture", row, "choose another place")
        return None
    if kind == "under":
        return _fail(action, f"{target} stands under {base}: things under furniture stand "
                     "apart, not next to each other", [target], f"put {obj} under {base} "
                     "instead")
    if kind == "on" and not state.objects[base].props.movable:
        return _surface_violation(state, action, base)
    return _fail(action, f"{target} is {kind} {base}: the simulator puts things next to "
                 "objects standing on furniture or the floor only", [base],
                 "choose another place")


def _surface_violation(state: WorldState, action: MoveAction, surface: str
                       ) -> Violation | None:
    """Everything standing on fixed `surface` (its load and their rows) must fit in
    half its width, so sliding a row aside never pushes anything off its edge."""
    info = state.objects[surface]
    load = [o for o, r in state.carried[surface].items() if r == "on" and o != action.object]
    load += [x for o in list(load) for x in _row(state, o) if x != action.object]
    used = sum(_width(state, o) for o in load) + _width(state, action.object) + \
        FIXED_GAP * (len(load) + 2)
    if used > furniture_width(state, info) / 2:
        return _fail(action, f"{surface} is too crowded in the simulator for "
                     f"{action.object} as well", sorted(load),
                     f"move {sorted(load)[0]} off {surface} first" if load
                     else "choose another place")
    return None

