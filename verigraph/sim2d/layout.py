"""Lay out a tabletop scene graph physically, so that reading it back gives the graph.

Furniture stands side by side on the floor, each piece at least its dictionary width
and wide enough for everything it may ever have to carry (all movable objects for an
unlimited surface, its `capacity` widest ones otherwise), so later moves always find
room. Movable objects are then put down support-first with the same placement search
moves use, settling after each; the seed only shuffles the order in which objects
sharing a support are put down.
"""

from __future__ import annotations

import random
from collections import deque

from verigraph.graph.dictionary import ObjectProperties
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d import physics
from verigraph.sim2d.bodies import furniture_spec, movable_spec
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.placement import FIXED_GAP
from verigraph.sim2d.putdown import put_down
from verigraph.sim2d.readback import read_supports
from verigraph.sim2d.scene import TabletopScene, Thing
from verigraph.sim2d.tabletop import TabletopWorld

FURNITURE_GAP = 8.0
ROOM_SLACK = 1.15


def _room_needed(props: ObjectProperties, movable_widths: list[float]) -> float:
    k = len(movable_widths) if props.capacity is None else min(props.capacity,
                                                                len(movable_widths))
    widest = sorted(movable_widths, reverse=True)[:k]
    return ROOM_SLACK * (sum(widest) + (k + 1) * FIXED_GAP)


def build_tabletop(graph: SceneGraph, seed: int = 0) -> TabletopWorld:
    """A TabletopWorld whose observed graph equals `graph` (raises SimError otherwise)."""
    state = WorldState.from_graph(graph)
    scene = TabletopScene()
    widths = {o.id: float(o.props.width or 6.0) for o in state.objects.values()
              if o.props.movable}
    fixed = [o for o in state.objects.values() if not o.props.movable]
    for obj in fixed:
        if obj.id in state.support and state.objects[state.support[obj.id][1]].props.movable:
            raise SimError(f"fixed object '{obj.id}' cannot stand on movable "
                           f"'{state.support[obj.id][1]}'", field="edges", value=obj.id,
                           fix=f"remove the support edge of '{obj.id}' or make the support "
                               "fixed")
    # Furniture: roots in a row, fixed-on-fixed put on top of their support.
    cursor = 0.0
    for obj in fixed:
        if obj.id in state.support:
            continue
        carried_fixed = sum(float(state.objects[c].props.width or 10.0) + FIXED_GAP
                            for c in state.carried[obj.id] if not state.objects[c].props.movable)
        width = max(float(obj.props.width or 40.0),
                    _room_needed(obj.props, list(widths.values())) + carried_fixed)
        spec = furniture_spec(obj.label, obj.props, width)
        body = physics.make_body(spec, BodyPose(cursor + width / 2, 0.0), fixed=True)
        scene.add(Thing(obj.id, obj.label, obj.props, spec, body, fixed=True))
        cursor += width + FURNITURE_GAP
    for obj in fixed:
        if obj.id not in state.support:
            continue
        base = scene.things.get(state.support[obj.id][1])
        if base is None:
            raise SimError(f"fixed object '{obj.id}' stands on another fixed object that "
                           "is not on the floor", field="edges", value=obj.id,
                           fix="keep furniture at most two levels deep")
        left = base.bounds()[0] + FIXED_GAP + sum(
            t.spec.width + FIXED_GAP for t in scene.things.values()
            if t.fixed and t.id != base.id and t.body.position.y > 0.0
            and base.bounds()[0] <= t.body.position.x <= base.bounds()[2])
        w = float(obj.props.width or 10.0)
        spec = furniture_spec(obj.label, obj.props, w)
        # Furniture specs stand on the floor; lift this one onto its support's top.
        body = physics.make_body(spec, BodyPose(left + w / 2, base.spec.top), fixed=True)
        scene.add(Thing(obj.id, obj.label, obj.props, spec, body, fixed=True))
    _place_movables(scene, state, random.Random(seed))
    supports, _ = read_supports(scene)
    want = {o: st for o, st in state.support.items()}
    if supports != want:
        wrong = sorted(set(want.items()) ^ set(supports.items()))
        name = wrong[0][0]
        raise SimError(f"the simulator could not realise '{name}' as given: physics reads "
                       f"{_fmt(name, supports)} instead of {_fmt(name, want)}", field="edges",
                       value=name, fix="give the object a larger support or fewer neighbours")
    return TabletopWorld(scene, list(graph.nodes), state.dictionary, graph.dictionary)


def _fmt(obj: str, supports: dict[str, tuple[str, str]]) -> str:
    if obj not in supports:
        return f"'{obj}' on nothing"
    rel, target = supports[obj]
    return f"'{obj} {rel} {target}'"


def _place_movables(scene: TabletopScene, state: WorldState, rng: random.Random) -> None:
    """Put movable objects down support-first, each checked against the graph so far."""
    queue: deque[str] = deque(o for o in state.objects if o in scene.things)
    order: list[str] = []
    while queue:
        base = queue.popleft()
        children = [c for c in state.carried[base] if state.objects[c].props.movable]
        rng.shuffle(children)
        order.extend(children)
        queue.extend(children)
    for obj in order:
        info = state.objects[obj]
        relation, target = state.support[obj]
        spec = movable_spec(info.label, info.props)
        body = physics.make_body(spec, BodyPose(0.0, -100.0), fixed=False)
        scene.add(Thing(obj, info.label, info.props, spec, body, fixed=False), in_space=False)
        outcome = put_down(scene, obj, relation, target)
        if outcome == "no_room":
            raise SimError(f"no_room: no free, stable place for '{obj} {relation} {target}' "
                           "in the simulator", field="edges", value=f"{obj} {relation} {target}",
                           fix=f"give {target} fewer or smaller objects, or put {obj} "
                               "somewhere larger")
        if outcome == "unstable":
            raise SimError(f"'{obj} {relation} {target}' does not stay put in the simulator "
                           "(it slides or topples)", field="edges",
                           value=f"{obj} {relation} {target}",
                           fix=f"put {obj} on a wider support")
