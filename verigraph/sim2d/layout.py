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
from verigraph.graph.state import ObjectInfo, WorldState
from verigraph.sim2d import physics
from verigraph.sim2d.beside import BESIDE, place_beside
from verigraph.sim2d.bodies import furniture_spec, movable_spec
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.household import Household, lays_out_household
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


def furniture_width(state: WorldState, obj: ObjectInfo) -> float:
    """Width of a piece of furniture standing on the floor: its own, or wide enough for
    what it may have to carry (the furniture standing on it included)."""
    widths = [float(o.props.width or 6.0) for o in state.objects.values() if o.props.movable]
    carried_fixed = sum(float(state.objects[c].props.width or 10.0) + FIXED_GAP
                        for c in state.carried[obj.id] if not state.objects[c].props.movable)
    return max(float(obj.props.width or 40.0),
               _room_needed(obj.props, widths) + carried_fixed)


def furniture_gap(state: WorldState) -> float:
    """The floor between two pieces of household furniture: room for the widest
    movable object next to the left one."""
    widest = max((float(o.props.width or 6.0) for o in state.objects.values()
                  if o.props.movable), default=0.0)
    return max(FURNITURE_GAP, widest + 2 * FIXED_GAP)


def build_tabletop(graph: SceneGraph, seed: int = 0) -> TabletopWorld:
    """A TabletopWorld whose observed graph equals `graph` (raises SimError otherwise)."""
    state = WorldState.from_graph(graph)
    scene = TabletopScene()
    scene.household = lays_out_household(graph, {o.id: o.props for o in state.objects.values()})
    fixed = [o for o in state.objects.values() if not o.props.movable and not o.props.room]
    household = Household() if scene.household else None
    depth = 0.0
    if household is not None:
        _check_drawable(state)
        fixed = _by_room(fixed, state)
        heights = [float(o.props.height or 4.0) for o in state.objects.values()
                   if o.props.movable]
        depth = sum(heights) + 1.0  # a closed door never meets what a bin holds
    gap = FURNITURE_GAP if household is None else furniture_gap(state)
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
        width = furniture_width(state, obj)
        spec = furniture_spec(obj.label, obj.props, width, legs=scene.household,
                              depth=depth if obj.props.openable else None)
        body = physics.make_body(spec, BodyPose(cursor + width / 2, 0.0), fixed=True)
        scene.add(Thing(obj.id, obj.label, obj.props, spec, body, fixed=True))
        if household is not None and obj.id in state.rooms:
            room = state.rooms[obj.id]
            start = household.rooms.get(room, (cursor - gap / 2, 0.0))[0]
            household.rooms[room] = (start, cursor + width + gap / 2)
        cursor += width + gap
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
        spec = furniture_spec(obj.label, obj.props, w, legs=scene.household,
                              depth=depth if obj.props.openable else None)
        # Furniture specs stand on the floor; lift this one onto its support's top.
        body = physics.make_body(spec, BodyPose(left + w / 2, base.spec.top), fixed=True)
        scene.add(Thing(obj.id, obj.label, obj.props, spec, body, fixed=True))
    if household is not None:
        _fit_out(scene, state, household, graph)
    _place_movables(scene, state, random.Random(seed))
    if household is not None:  # doors stood open while things were put in
        for owner in household.doors:
            household.set_open(owner, state.state_value(owner, "open"))
    supports, _ = read_supports(scene)
    want = {o: st for o, st in state.support.items()}
    if supports != want:
        wrong = sorted(set(want.items()) ^ set(supports.items()))
        name = wrong[0][0]
        raise SimError(f"the simulator could not realise '{name}' as given: physics reads "
                       f"{_fmt(name, supports)} instead of {_fmt(name, want)}", field="edges",
                       value=name, fix="give the object a larger support or fewer neighbours")
    world = TabletopWorld(scene, list(graph.nodes), state.dictionary, graph.dictionary,
                          household)
    if household is not None:
        seen = world.observe()
        missing = sorted(set(graph.canonical().edge_keys()) ^ set(seen.edge_keys()))
        if missing:
            raise SimError(f"the simulator could not realise the household scene as given: "
                           f"{missing[0]}", field="edges", value=str(missing[0]),
                           fix="give the furniture a room, and each room its furniture")
    return world


def _check_drawable(state: WorldState) -> None:
    """Doors are drawn on fixed containers only (a box's lid is not drawn yet)."""
    for obj in state.objects.values():
        if obj.props.openable and (obj.props.movable or not obj.props.container):
            raise SimError(f"the 2D simulator draws doors on fixed containers only; "
                           f"'{obj.id}' ({obj.label}) is an openable "
                           f"{'movable object' if obj.props.movable else 'non-container'}",
                           field="nodes", value=obj.id,
                           fix="load the scene with executor graph (simulate=false), or "
                               f"leave {obj.id} out of the simulated scene")


def _by_room(fixed: list[ObjectInfo], state: WorldState) -> list[ObjectInfo]:
    """Furniture grouped by room (rooms in node order), furniture without one last."""
    order = {room: i for i, room in enumerate(o.id for o in state.objects.values()
                                               if o.props.room)}
    return sorted(fixed, key=lambda o: order.get(state.rooms.get(o.id, ""), len(order)))


def _fit_out(scene: TabletopScene, state: WorldState, household: Household,
             graph: SceneGraph) -> None:
    """Doors on openable containers (open until the objects are in) and switches on
    toggleable objects as the graph's states say; which state keys each node was given."""
    for obj in state.objects.values():
        thing = scene.things.get(obj.id)
        if obj.props.openable and thing is not None:
            household.add_door(scene, thing, True)
        if obj.props.toggleable:
            household.switches[obj.id] = state.state_value(obj.id, "toggled_on")
    household.given = {n.id: set(n.state) for n in graph.nodes if n.state}


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
        outcome = (place_beside(scene, obj, relation, target) if relation in BESIDE
                   else put_down(scene, obj, relation, target))
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
