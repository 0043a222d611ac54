"""Household parts of a tabletop world: doors, switches and rooms.

- **Doors.** An openable fixed container (fridge, cabinet, oven, ...) is a bin with a
  door: a static pymunk body as wide as the bin and `DOOR_THICKNESS` thick, hinged at
  the right rim. Closed, it lies across the opening, so nothing can be lowered in or
  taken out (the placement search rests on the door, which is no object, and finds no
  place); open, it stands upright beside the right wall. `open`/`close` turn it about
  the hinge. Whether a container is open is read from the door's pose, never stored.
- **Switches.** A toggleable object that is on shows a lit element (a round lamp in
  `palette.LIT` on its left leg, or at a movable lamp's top); off, it looks as it
  always did. The switch position is the world's state, like a pose.
- **Rooms.** Furniture stands grouped by room, left to right; a room is the stretch of
  floor its furniture stands on, and `x inroom r` is read from where x stands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pymunk

from verigraph.graph.model import Edge, SceneGraph
from verigraph.sim2d import physics
from verigraph.sim2d.bodies import FURNITURE_TOP
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.scene import TabletopScene, Thing

HOUSEHOLD_RELATIONS = ("under", "nextto", "inroom")
LAMP_HEIGHT = FURNITURE_TOP - 4.5  # above the foot of furniture: on its left leg
OPEN_ANGLE = -math.pi / 2  # turned clockwise about the hinge: upright, outside the bin
LAMP_RADIUS = 2.0  # world units: 6 px across even in a wide household render
DOOR_THICKNESS = 2.0  # thick enough to show its colour inside the outline at 3 px/unit


def lays_out_household(graph: SceneGraph, props: dict[str, object]) -> bool:
    """A graph with rooms, doors, switches' states or the household placements."""
    if any(e.relation in HOUSEHOLD_RELATIONS for e in graph.edges):
        return True
    if any(n.state for n in graph.nodes):
        return True
    return any(getattr(p, "room", False) or getattr(p, "openable", False)
               for p in props.values())


@dataclass(slots=True)
class Door:
    """The door of one openable container: a static body hinged at its right rim."""

    owner: str
    body: pymunk.Body
    hinge: tuple[float, float]  # world point of the hinge (the right rim's top corner)

    def pose(self, open_: bool) -> BodyPose:
        return BodyPose(self.hinge[0], self.hinge[1], OPEN_ANGLE if open_ else 0.0)

    def is_open(self) -> bool:
        """Read from the pose: a door that stands up is open."""
        return math.cos(self.body.angle) < 0.5


def make_door(thing: Thing, open_: bool) -> Door:
    """A door over `thing`'s cavity (local frame: hinge at the origin, extending left)."""
    cavity = thing.spec.cavity
    assert cavity is not None
    left, _, right, _ = thing.bounds()
    width = right - left
    thick = DOOR_THICKNESS
    body = pymunk.Body(body_type=pymunk.Body.STATIC)
    shape = pymunk.Poly(body, [(-width, 0.0), (0.0, 0.0), (0.0, thick), (-width, thick)])
    shape.friction = physics.FRICTION
    rim = float(thing.body.local_to_world((0.0, cavity[3])).y)
    door = Door(thing.id, body, (right, rim))
    physics.set_pose(body, door.pose(open_))
    return door


@dataclass(slots=True)
class Household:
    """Doors by container, switch positions by object, rooms by id (x extent)."""

    doors: dict[str, Door] = field(default_factory=dict)
    switches: dict[str, bool] = field(default_factory=dict)
    rooms: dict[str, tuple[float, float]] = field(default_factory=dict)
    # State keys each node was given, so the observed graph writes them back.
    given: dict[str, set[str]] = field(default_factory=dict)

    def add_door(self, scene: TabletopScene, thing: Thing, open_: bool) -> None:
        door = make_door(thing, open_)
        self.doors[thing.id] = door
        physics.add_body(scene.space, door.body)
        scene.fixtures.append(door.body)

    def set_open(self, obj: str, open_: bool) -> None:
        door = self.doors[obj]
        physics.set_pose(door.body, door.pose(open_))

    def copy_into(self, scene: TabletopScene) -> Household:
        other = Household(switches=dict(self.switches), rooms=dict(self.rooms),
                          given={k: set(v) for k, v in self.given.items()})
        for obj, door in self.doors.items():
            other.add_door(scene, scene.things[obj], door.is_open())
        return other

    def states(self, scene: TabletopScene) -> dict[str, dict[str, bool]]:
        """Every node's state as the world shows it: a key is written when the node was
        given it or it differs from the default (closed, off)."""
        out: dict[str, dict[str, bool]] = {}
        for obj, door in self.doors.items():
            value = door.is_open()
            if value or "open" in self.given.get(obj, set()):
                out.setdefault(obj, {})["open"] = value
        for obj, on in self.switches.items():
            if on or "toggled_on" in self.given.get(obj, set()):
                out.setdefault(obj, {})["toggled_on"] = on
        return out

    def room_edges(self, scene: TabletopScene) -> list[Edge]:
        """`furniture inroom room` for every piece standing on a room's stretch of floor."""
        edges = []
        for t in scene.things.values():
            if not t.fixed or t.body.space is None or t.body.position.y > 0.01:
                continue  # stacked furniture's room is not stated
            x = float(t.body.position.x)
            for room, (x0, x1) in self.rooms.items():
                if x0 <= x <= x1:
                    edges.append(Edge(source=t.id, relation="inroom", target=room))
                    break
        return edges

    def blocking_door(self, scene: TabletopScene, obj: str) -> list[str]:
        """Movable objects a closing door would hit (sticking out over the rim)."""
        door = self.doors[obj]
        probe = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        pose = door.pose(False)
        probe.position = (pose.x, pose.y)
        hits: list[str] = []
        for shape in door.body.shapes:
            assert isinstance(shape, pymunk.Poly)
            ghost = pymunk.Poly(probe, shape.get_vertices())
            ghost.cache_bb()
            for hit in scene.space.shape_query(ghost):
                name = scene.by_body.get(hit.shape.body) if hit.shape.body else None
                if name is not None and not scene.things[name].fixed and name not in hits \
                        and any(p.distance < -0.01 for p in hit.contact_point_set.points):
                    hits.append(name)
        return sorted(hits)


def lamp_centre(thing: Thing) -> tuple[float, float]:
    """Where a toggleable object's lit element is drawn (world coordinates): on the
    left leg of furniture, at the top of a movable object."""
    left, bottom, right, top = thing.bounds()
    if thing.fixed:
        return left + 2.0, bottom + LAMP_HEIGHT
    return (left + right) / 2, top - LAMP_RADIUS - 0.4
