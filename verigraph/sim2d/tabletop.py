"""The tabletop world (side view, gravity): moves are lifted, placed, settled and read back.

`move(o, rel, t)` lifts `o` out of the world (what rested on it is left behind and
falls), settles, searches free placements on or in `t` (see placement and putdown),
puts `o` down, settles and reads the graph back from contacts. Candidates are tried in
simulation first: one that slides, tips or ends in another graph is taken back and the
next tried. When nothing fits, or everything would topple, the world refuses with
`no_room` before anything moves. In unverified mode there are no such checks:
the arm carries the object up and over the target (whatever rests on it rides along or
falls, see carry), puts it down where it can and physics decides what the graph becomes.
"""

from __future__ import annotations

import math

import numpy as np

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, MoveAction, StateAction
from verigraph.graph.dictionary import Dictionary, InlineDictionary
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.sim2d import physics
from verigraph.sim2d.beside import BESIDE, place_beside
from verigraph.sim2d.carry import carry_over
from verigraph.sim2d.errors import SimError
from verigraph.sim2d.household import Household
from verigraph.sim2d.putdown import put_down, turned
from verigraph.sim2d.readback import read_supports
from verigraph.sim2d.render import render_tabletop
from verigraph.sim2d.scene import TabletopScene, Thing
from verigraph.sim2d.world import SimWorld, WorldKind

LIFT_TURN = 0.5


class TabletopWorld(SimWorld):
    """Blocks, kitchen and tableware scenes: furniture is static, objects are dynamic."""

    kind: WorldKind = "tabletop"

    def __init__(self, scene: TabletopScene, nodes: list[Node], dictionary: Dictionary,
                 dictionary_name: str | InlineDictionary | None,
                 household: Household | None = None) -> None:
        self.scene = scene
        self.nodes = [n.model_copy(deep=True) for n in nodes]
        self.dictionary = dictionary
        self.dictionary_name = dictionary_name
        # Doors, switches and rooms; a plain tabletop has switches only (a stove).
        self.household = household if household is not None else Household(switches={
            t.id: False for t in scene.things.values() if t.props.toggleable})

    # -- World protocol --------------------------------------------------------------------
    def observe(self) -> SceneGraph:
        supports, _ = read_supports(self.scene)
        edges = [Edge(source=obj, relation=rel, target=target)
                 for obj, (rel, target) in supports.items()]
        edges += self.household.room_edges(self.scene)
        states = self.household.states(self.scene)
        nodes = [n.model_copy(deep=True) for n in self.nodes]
        for node in nodes:
            node.state = states.get(node.id, {})
        return SceneGraph(nodes=nodes, edges=edges,
                          dictionary=self.dictionary_name).canonical()

    def perform_state(self, action: StateAction) -> Violation | None:
        """Open or close a door, or flip a switch (the validator has checked the roles
        and the current state). A door that would close on something sticking out of
        its container is refused before anything moves."""
        obj = action.object
        if obj not in self.scene.things:
            raise SimError(f"there is no object '{obj}' in the simulated scene",
                           field="object", value=obj,
                           fix=f"use one of {', '.join(self.scene.things)}")
        house = self.household
        if action.action in ("open", "close"):
            if obj not in house.doors:
                return Violation(action=action.model_dump(), constraint="not_openable",
                                 message=f"{obj} has no door in the simulator",
                                 suggestion=f"do not {action.action} {obj}")
            if action.action == "close":
                blocking = house.blocking_door(self.scene, obj)
                if blocking:
                    return Violation(
                        action=action.model_dump(), constraint="no_room",
                        message=f"the door of {obj} would hit {', '.join(blocking)}, which "
                                "sticks out over its rim; nothing was moved",
                        blocking=blocking, suggestion=f"take {blocking[0]} out of {obj} first")
            house.set_open(obj, action.action == "open")
            house.given.setdefault(obj, set()).add("open")
            return None
        if obj not in house.switches:
            return Violation(action=action.model_dump(), constraint="not_toggleable",
                             message=f"{obj} has no switch in the simulator",
                             suggestion=f"do not {action.action} {obj}")
        house.switches[obj] = action.action == "toggle_on"
        house.given.setdefault(obj, set()).add("toggled_on")
        return None

    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        if not isinstance(action, MoveAction):
            return Violation(action=action.model_dump(), constraint="unknown_side",
                             message="align needs tangram pieces; this is a tabletop world",
                             suggestion="use move(object, relation, target)")
        self._check_ids(action)
        return self._move(action, verified=True)

    def perform_unverified(self, action: MoveAction | AlignAction) -> SceneGraph:
        if not isinstance(action, MoveAction):
            raise SimError("align needs tangram pieces; this is a tabletop world",
                           field="action", value=action.text(),
                           fix="use move(object, relation, target)")
        self._check_ids(action)
        thing = self.scene.things[action.object]
        if thing.fixed:
            raise SimError(f"the arm cannot lift {action.object}: it is fixed furniture",
                           field="object", value=action.object, fix="move a movable object")
        if action.object == action.target:
            raise SimError(f"cannot put {action.object} {action.relation} itself",
                           field="target", value=action.target, fix="choose another target")
        self._move(action, verified=False)
        return self.observe()

    def tipped(self, limit: float = 0.35) -> list[str]:
        """Movable objects that fell over: tilted, or a container on its side or upside
        down (cutlery standing upright and flat things lying flipped do not count)."""
        out = []
        for t in self.scene.movable():
            if t.body.space is None:
                continue
            angle = math.remainder(t.body.angle, 2 * math.pi)
            if abs(angle) <= limit:
                continue
            upright = t.spec.thin and abs(abs(angle) - math.pi / 2) <= limit
            flipped = t.spec.kind == "box" and abs(abs(angle) - math.pi) <= limit
            if not (upright or flipped):
                out.append(t.id)
        return out

    # -- SimWorld ----------------------------------------------------------------------------
    def render(self, width: int | None = None, height: int | None = None, *,
               labels: bool = False) -> np.ndarray:
        return render_tabletop(self, width, height, labels=labels)

    def copy(self) -> TabletopWorld:
        scene = TabletopScene()
        for t in self.scene.things.values():
            body = physics.make_body(t.spec, physics.pose_of(t.body), fixed=t.fixed)
            scene.add(Thing(t.id, t.label, t.props, t.spec, body, t.fixed),
                      in_space=t.body.space is not None)
        scene.household = self.scene.household
        return TabletopWorld(scene, self.nodes, self.dictionary, self.dictionary_name,
                             self.household.copy_into(scene))

    # -- internals ---------------------------------------------------------------------------
    def _check_ids(self, action: MoveAction) -> None:
        for role, name in (("object", action.object), ("target", action.target)):
            if name not in self.scene.things:
                raise SimError(f"there is no object '{name}' in the simulated scene",
                               field=role, value=name,
                               fix=f"use one of {', '.join(self.scene.things)}")

    def _move(self, action: MoveAction, *, verified: bool) -> Violation | None:
        scene = self.scene
        before = scene.snapshot()
        held = read_supports(scene)[0] if verified else {}
        if not verified:
            carry_over(scene, action.object, action.target)
        scene.lift(action.object)
        scene.settle()
        if verified:
            after = read_supports(scene)[0]
            moved = sorted({o for o in set(held) | set(after)
                            if o != action.object and held.get(o) != after.get(o)}
                           | set(turned(scene, before, LIFT_TURN)))
            if moved:  # something leant on the object: lifting it would upset that
                scene.restore(before)
                return self._refusal(action, held, "disturbs", moved)
        if action.relation in BESIDE:
            outcome = place_beside(scene, action.object, action.relation, action.target,
                                   verify=verified)
        else:
            outcome = put_down(scene, action.object, action.relation, action.target,
                               verify=verified)
        if outcome in ("no_room", "unstable"):
            scene.restore(before)
            return self._refusal(action, read_supports(scene)[0], outcome)
        return None

    def _refusal(self, action: MoveAction, supports: dict[str, tuple[str, str]],
                 outcome: str, moved: list[str] | None = None) -> Violation:
        target = action.target
        if moved:
            return Violation(
                action=action.model_dump(), constraint="no_room",
                message=f"lifting {action.object} would make {', '.join(moved)} slide or "
                        f"fall (it leans on {action.object}); nothing was moved",
                blocking=moved, suggestion=f"move {moved[0]} away from {action.object} first")
        carried = sorted(o for o, (_, t) in supports.items() if t == target)
        what = f" ({target} carries {', '.join(carried)})" if carried else ""
        why = ("found no free place for" if outcome == "no_room" else
               "found only places that slide or topple for")
        return Violation(
            action=action.model_dump(), constraint="no_room",
            message=f"the simulator {why} {action.object} {action.relation} {target}{what}; "
                    "nothing was moved", blocking=carried,
            suggestion=(f"move {carried[0]} off {target} first, or choose another target"
                        if carried else "choose another target"))
