"""Symbolic room check: does a valid move also fit physically? Sizes only, no physics.

The validator's constraints know capacities but not sizes, so some valid moves cannot
be carried out: a book on a plate that a tray already covers, a kettle into a pot with
a pan lying across its rim. `room_violation` predicts those from the dictionary widths
and the simulator's container geometry, conservatively: when it returns None, sim2d
finds a stable placement (the test suite checks this over many random scenes). It
explains the failure the way the other constraints do, so a planner can fix the plan.

Rules, with extent(x) = max(width(x), what x carries side by side on it, or the widest
thing in or across it for a container):
- on fixed furniture: always room (furniture is sized for every movable object);
- on a movable surface: alone, anything (centred); beside a load, the load's extents
  plus half the object fit within the width (the object may overhang the far edge),
  and a surface resting on something narrower than itself carries a single object;
- on or in a target lying in a movable container: only what passes its opening;
- a surface that balances several objects (it rests on something narrower, stands on
  a narrower foot like a plate, or its load hangs over its edges) takes no more load
  anywhere above it and gives none up: the rest could tip;
- on or in a target raised on another movable object: no other stack on the same
  furniture reaches above where the object would rest (see `clearance`: it may stand
  right beside the target, or hang over it); the same for a target on furniture with
  an object wider than it (a pot over a cup beside a lamp);
- in a container: nothing lies across its rim; an object narrower than the opening
  goes inside if the contents side by side leave room (one that only just fits, only
  into an empty container; cutlery may stand upright in an empty narrow one); a wider
  one rests on the rim if nothing sticks out.
"""

from __future__ import annotations

from verigraph.actions.feedback import Violation
from verigraph.actions.model import MoveAction
from verigraph.graph.state import WorldState
from verigraph.sim2d.bodies import movable_spec
from verigraph.sim2d.clearance import lowering_blockers

CLEARANCE = 0.4
GAP = 0.3
OVERHANG_MARGIN = 1.0
CROWD_SLACK = 2.0


def _width(state: WorldState, obj: str) -> float:
    return float(state.objects[obj].props.width or 6.0)


def extent(state: WorldState, obj: str) -> float:
    """Horizontal space an object takes with everything it carries: a surface's load
    stands side by side, a container's is inside or across its rim."""
    widths = [extent(state, c) for c in state.carried[obj]]
    load = sum(widths) if state.objects[obj].props.surface else max(widths, default=0.0)
    return max(_width(state, obj), load)


def _crowded(state: WorldState, support: str) -> bool:
    """The support's load is clearly wider than it, so things on it overhang."""
    load = state.carried[support]
    if state.objects[support].props.surface and len(load) > 1:
        used = sum(extent(state, c) for c in load) + GAP * (len(load) - 1)
        return used > _width(state, support) + CROWD_SLACK
    return False


def base_width(state: WorldState, obj: str) -> float:
    """Width of what the object stands on (a plate's foot is narrower than its top)."""
    info = state.objects[obj]
    spec = movable_spec(info.label, info.props)
    feet = [x for part in spec.parts for x, y in part if abs(y) < 1e-9]
    return max(feet) - min(feet) if feet else _width(state, obj)


def _balances(state: WorldState, obj: str) -> bool:
    """A movable surface whose load may rely on balance: it rests on something narrower
    (or across a rim), it stands on a foot narrower than its top (a plate), or its load
    hangs well over its edges."""
    info = state.objects[obj]
    if not info.props.movable or not info.props.surface:
        return False
    below = state.support.get(obj)
    if below is not None and state.objects[below[1]].props.movable and (
            below[0] == "in" or _width(state, below[1]) < _width(state, obj)):
        return True
    return base_width(state, obj) < 0.9 * _width(state, obj) or _crowded(state, obj)


def _above(state: WorldState, obj: str) -> set[str]:
    """`obj` and everything on or in it, directly or not."""
    out, stack = set(), [obj]
    while stack:
        x = stack.pop()
        out.add(x)
        stack.extend(state.carried[x])
    return out


def _balancing_below(state: WorldState, start: str, adding: int = 0) -> str | None:
    """The first support from `start` downwards that balances more than one object
    (counting `adding` objects about to be put somewhere above it)."""
    current: str | None = start
    seen: set[str] = set()
    while current is not None and current not in seen:
        seen.add(current)
        if _balances(state, current) and len(_above(state, current)) + adding > 2:
            return current  # it balances more than one object (side by side or a tower)
        below = state.support.get(current)
        current = below[1] if below is not None else None
    return None


def _inner(state: WorldState, obj: str) -> tuple[float, float]:
    """Opening width and depth of a movable container in the simulator."""
    info = state.objects[obj]
    cavity = movable_spec(info.label, info.props).cavity
    if cavity is None:
        return 0.0, 0.0
    return cavity[1] - cavity[0], cavity[3] - cavity[2]


def _fail(action: MoveAction, message: str, blocking: list[str], suggestion: str) -> Violation:
    return Violation(action=action.model_dump(), constraint="no_room",
                     message=message, blocking=blocking, suggestion=suggestion)


def room_violation(state: WorldState, action: MoveAction) -> Violation | None:
    """Why a (validator-valid) move has no room in the simulator, or None."""
    obj, rel, target = action.object, action.relation, action.target
    source = state.support.get(obj)
    balancing = _balancing_below(state, source[1]) if source is not None else None
    if balancing is not None:
        others = sorted(c for c in state.carried[balancing] if obj not in _above(state, c))
        return _fail(action, f"{balancing} balances several objects, {obj} among them; "
                     f"taking {obj} away could tip it", others,
                     f"move {others[0]} off {balancing} first" if others else
                     f"move the objects on {balancing} off it first")
    t = state.objects[target]
    if not t.props.movable:
        return None
    load = sorted(state.carried[target])
    need = _width(state, obj)
    below = state.support.get(target)
    balancing = _balancing_below(state, below[1], adding=1) if below is not None else None
    if balancing is not None:
        return _fail(action, f"{target} stands on {balancing}, which would balance several "
                     "objects; more load could tip it", [balancing],
                     f"put {obj} somewhere steadier, or clear {balancing} first")
    blockers = lowering_blockers(state, obj, rel, target)
    if blockers and below is not None and not state.objects[below[1]].props.movable:
        return _fail(action, f"{obj} is wider than {target} and {blockers[0]} beside it "
                     f"stands higher: {obj} could not be lowered {rel} {target} past it",
                     blockers, f"move {blockers[0]} away first, or choose a wider target")
    if blockers:
        return _fail(action, f"{target} is raised on {below[1] if below else target} and "
                     f"{blockers[0]} may stand as high right beside it or over it: {obj} could "
                     f"not be lowered {rel} {target} past it", blockers,
                     f"move {blockers[0]} off its stack first, or put {obj} somewhere lower")
    if below is not None and below[0] == "in" and state.objects[below[1]].props.movable:
        opening = _inner(state, below[1])[0]
        if need > opening - CLEARANCE:  # it would have to pass the outer rim
            return _fail(action, f"{target} lies in {below[1]}, whose opening is "
                         f"{opening:.1f} wide: {obj} ({need:g} wide) cannot be lowered "
                         f"{rel} it", [below[1]],
                         f"take {target} out of {below[1]} first, or choose a larger target")
    if rel == "on":
        width = _width(state, target)
        used = sum(extent(state, c) for c in load) + GAP * len(load)
        # With a load, the object goes beside it and may overhang the far edge by up to
        # half its width (minus a margin); alone, it is centred whatever its size.
        if load and used + need / 2 + OVERHANG_MARGIN > width:
            return _fail(action, f"{obj} does not fit on {target}: {target} is {width:g} wide, "
                         f"{'its load takes ' + f'{used:g}' + ' and ' if load else ''}"
                         f"{obj} needs {need:g}", load,
                         f"move {load[0]} off {target} first, or choose a larger target"
                         if load else "choose a larger target")
        if load and below is not None and state.objects[below[1]].props.movable and (
                below[0] == "in" or _width(state, below[1]) < width):
            return _fail(action, f"{target} rests on the narrower {below[1]}: it can balance "
                         f"only one object, and it carries {', '.join(load)}", load,
                         f"put {obj} somewhere steadier, or move {target} onto a wider "
                         "support first")
        return None
    opening, depth = _inner(state, target)
    rim = [c for c in load if _width(state, c) > opening - CLEARANCE]
    if rim:
        return _fail(action, f"{target} is blocked: {rim[0]} lies across its rim or stands "
                     "in it", rim, f"take {rim[0]} off {target} first")
    if need <= opening - CLEARANCE:
        used = sum(_width(state, c) for c in load) + CLEARANCE * (len(load) + 1)
        if used + need > opening:
            return _fail(action, f"{obj} does not fit in {target} next to "
                         f"{', '.join(load)}: the opening is {opening:.1f} wide", load,
                         f"take {load[0]} out of {target} first")
        return None
    if need <= opening:
        if load:  # a snug fit: it would land on what is already inside
            return _fail(action, f"{obj} only just fits in {target}, which already holds "
                         f"{', '.join(load)}", load, f"take {load[0]} out of {target} first")
        return None
    info = state.objects[obj]
    spec = movable_spec(info.label, info.props)
    if not load and spec.thin and spec.height < opening - CLEARANCE \
            and spec.width <= 1.6 * depth:
        return None  # stands upright inside
    tall = [c for c in load if float(state.objects[c].props.height or 4.0) > depth - 0.2
            or state.carried[c]]
    if tall:
        return _fail(action, f"{obj} is wider than the opening of {target} and would rest "
                     f"on its rim, but {tall[0]} sticks out of {target}", tall,
                     f"take {tall[0]} out of {target} first")
    return None
