"""Symbolic clearance over a raised target: may a neighbour be in the way of lowering?

The simulator puts an object down by lowering it over the target until it touches the
highest thing under it (`placement`), and the placement counts only if that thing is
the target. So a neighbour standing higher than where the object would come to rest
blocks every position its footprint reaches: a tray lowered onto a cup in a mug meets
a bowl on the book next door, a bowl lowered onto a mug meets a plate resting across
a cup on the neighbouring book and hanging over the mug, and a bowl lowered onto a cup
on a tray meets a book lying across a mug beside it on the same tray. Only when the
target stands directly on furniture does the simulator push neighbours aside; higher
up it cannot.

The state holds no positions, so this check assumes the worst: anything on the same
furniture (other than what carries the target or lies on or in it) may stand right
next to the target, and anything above the bottom of a stack may hang over its edge.
An object that stays within the target's outline (through a container's opening, or
alone on a wide enough surface) can only meet something hanging over the target, so
then only things whose underside may be as high as the target's top count.
The heights are nominal (dictionary sizes, contents on a container's floor when they
fit through its opening, on its rim otherwise), with a margin for tilts.
"""

from __future__ import annotations

from verigraph.graph.state import WorldState
from verigraph.sim2d.bodies import movable_spec

HEIGHT_MARGIN = 1.0
FIT_CLEARANCE = 0.4


def _height(state: WorldState, obj: str) -> float:
    info = state.objects[obj]
    return movable_spec(info.label, info.props).height


def _rests_inside(state: WorldState, obj: str, container: str) -> tuple[bool, float]:
    """(goes through the opening, floor height above the container's bottom)."""
    info = state.objects[container]
    cavity = movable_spec(info.label, info.props).cavity
    if cavity is None:
        return False, 0.0
    width = float(state.objects[obj].props.width or 6.0)
    return width <= cavity[1] - cavity[0] - FIT_CLEARANCE, cavity[2]


def bottom(state: WorldState, obj: str, relation: str | None = None,
           holder: str | None = None) -> float:
    """Nominal height of the object's underside above the furniture carrying its stack
    (`relation`, `holder`: where it would be put; by default where it is)."""
    if holder is None:
        current = state.support.get(obj)
        if current is None:
            return 0.0
        relation, holder = current
    if not state.objects[holder].props.movable:
        return 0.0
    if relation == "in":
        inside, floor = _rests_inside(state, obj, holder)
        if inside:
            return bottom(state, holder) + floor
    return top(state, holder)


def top(state: WorldState, obj: str) -> float:
    """Nominal height of the object's top above the furniture carrying its stack."""
    if not state.objects[obj].props.movable:
        return 0.0
    return bottom(state, obj) + _height(state, obj)


def _stack_root(state: WorldState, obj: str) -> tuple[str, str | None]:
    """(the object of the stack standing on furniture, that furniture)."""
    current, seen = obj, {obj}
    while True:
        below = state.support.get(current)
        if below is None:
            return current, None
        if not state.objects[below[1]].props.movable:
            return current, below[1]
        if below[1] in seen:
            return current, None
        current = below[1]
        seen.add(current)


def _highest_bottom(state: WorldState, obj: str) -> float:
    """The highest the object's underside can be: things in a container taken as
    resting on its rim (on whatever else is inside), never as low as its floor."""
    below = state.support.get(obj)
    if below is None or not state.objects[below[1]].props.movable:
        return 0.0
    holder = below[1]
    return _highest_bottom(state, holder) + _height(state, holder)


def _within(state: WorldState, obj: str, relation: str, target: str) -> bool:
    """`obj` would stay within the target's outline: through a container's opening, or
    alone on a surface at least as wide. Then only something hanging over the target
    can be in its way, and that lies higher than the target's top."""
    if relation == "in":
        return _rests_inside(state, obj, target)[0]
    width = float(state.objects[obj].props.width or 6.0)
    return not state.carried[target] and width <= float(state.objects[target].props.width
                                                        or 6.0)


def lowering_blockers(state: WorldState, obj: str, relation: str, target: str) -> list[str]:
    """Neighbours that may stand in the way of lowering `obj` `relation` `target`: for a
    target raised on another movable object, or standing on furniture with `obj` wider
    than it (a pot lowered over a cup), every object on the same furniture, other than
    what carries the target or lies on or in it, that reaches above where `obj` would
    come to rest (a neighbour on the same tray, in another stack, or a lamp beside the
    cup that cannot be pushed off the counter's end)."""
    below = state.support.get(target)
    if below is None:
        return []  # furniture itself
    if not state.objects[below[1]].props.movable:
        if _within(state, obj, relation, target):
            return []  # on furniture, neighbours are pushed aside
        furniture: str | None = below[1]  # but what overhangs it may meet a taller one
    else:
        _, furniture = _stack_root(state, target)
    if furniture is None:
        return []
    rest = bottom(state, obj, relation, target)
    within = _within(state, obj, relation, target)
    skip = {obj, target} | set(state.carried[target]) | set(state.supports_chain(target))
    target_top = top(state, target)
    blockers = []
    for other in state.objects:
        if other in skip or not state.objects[other].props.movable:
            continue
        if within and _highest_bottom(state, other) < target_top - HEIGHT_MARGIN:
            continue  # lower than the target's top, it cannot hang over the target
        if _stack_root(state, other)[1] != furniture:
            continue
        if top(state, other) > rest - HEIGHT_MARGIN:
            blockers.append(other)
    return sorted(blockers)
