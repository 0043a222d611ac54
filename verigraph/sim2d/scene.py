"""The physical state of a tabletop world: a pymunk space and the objects in it by id.

`TabletopScene` owns the space and knows which body is which object; it can save and
restore every pose, which is how the placement search tries a placement and takes it
back when the physics does not end where it should.
"""

from __future__ import annotations

from dataclasses import dataclass

import pymunk

from verigraph.graph.dictionary import ObjectProperties
from verigraph.sim2d import physics
from verigraph.sim2d.bodies import BodySpec
from verigraph.sim2d.physics import BodyPose


@dataclass(slots=True)
class Thing:
    """One object of the scene graph and its body."""

    id: str
    label: str
    props: ObjectProperties
    spec: BodySpec
    body: pymunk.Body
    fixed: bool

    def com(self) -> tuple[float, float]:
        """Centre of mass in world coordinates (furniture: centre of its outline)."""
        if self.fixed:
            local = (0.0, self.spec.top / 2)
        else:
            _, cx, cy = self.spec.mass_centre
            local = (cx, cy)
        p = self.body.local_to_world(local)
        return float(p.x), float(p.y)

    @property
    def mass(self) -> float:
        """Mass at the physics density, also while lifted (pymunk says 0 then)."""
        return 0.0 if self.fixed else self.spec.mass_centre[0] * physics.DENSITY

    def bounds(self) -> tuple[float, float, float, float]:
        """Axis-aligned bounds (left, bottom, right, top) of the body's shapes."""
        bbs = [s.cache_bb() for s in self.body.shapes]
        return (min(b.left for b in bbs), min(b.bottom for b in bbs),
                max(b.right for b in bbs), max(b.top for b in bbs))


Snapshot = dict[str, tuple[BodyPose, bool]]


class TabletopScene:
    """A space with a floor, fixed furniture (static) and movable objects (dynamic)."""

    def __init__(self) -> None:
        self.space = physics.new_space()
        self.floor = physics.add_floor(self.space)
        self.things: dict[str, Thing] = {}
        self.by_body: dict[pymunk.Body, str] = {}
        # A household scene also reads `under` and `nextto` from where things stand.
        self.household = False
        # Bodies that are no objects of the graph but stop things (household doors).
        self.fixtures: list[pymunk.Body] = []

    def add(self, thing: Thing, *, in_space: bool = True) -> None:
        self.things[thing.id] = thing
        self.by_body[thing.body] = thing.id
        if in_space:
            physics.add_body(self.space, thing.body)

    def present(self, obj: str) -> bool:
        return self.things[obj].body.space is not None

    def lift(self, obj: str) -> None:
        """Take an object out of the world (it is in the gripper)."""
        body = self.things[obj].body
        if body.space is not None:
            physics.remove_body(self.space, body)

    def put(self, obj: str, pose: BodyPose) -> None:
        """Put an object back into the world at `pose`, at rest."""
        body = self.things[obj].body
        physics.set_pose(body, pose)
        if body.space is None:
            physics.add_body(self.space, body)
            self.space.reindex_shapes_for_body(body)

    def settle(self, max_steps: int = physics.MAX_SETTLE_STEPS) -> int:
        return physics.settle(self.space, max_steps)

    def movable(self) -> list[Thing]:
        return [t for t in self.things.values() if not t.fixed]

    def snapshot(self) -> Snapshot:
        return {t.id: (physics.pose_of(t.body), t.body.space is not None)
                for t in self.things.values() if not t.fixed}

    def restore(self, snap: Snapshot) -> None:
        for obj, (pose, present) in snap.items():
            if present:
                self.put(obj, pose)
            else:
                self.lift(obj)
