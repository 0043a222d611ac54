"""Putting a lifted object `under` or `nextto` a target (household worlds).

The arm slides the object in sideways rather than lowering it from above (a table's
top is in the way of `under`):
- `under y`: on the floor between y's legs, packed from the left with a gap to what
  already stands there, below y's top;
- `nextto y`: on what y rests on (the floor for furniture), its left side against
  y's right side. On fixed furniture whatever stands right of y is slid right to make
  room; elsewhere the place must be free.
A placement counts only if, once settled, the graph read back is the expected one and
nothing slid or tipped (the same test as `putdown`); otherwise the scene is restored.
"""

from __future__ import annotations

from verigraph.sim2d import physics
from verigraph.sim2d.bodies import under_span
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.placement import DROP_GAP, FIXED_GAP, subtree_of
from verigraph.sim2d.putdown import disturbed
from verigraph.sim2d.readback import read_supports
from verigraph.sim2d.scene import TabletopScene

BESIDE = ("under", "nextto")
TOUCH = 0.03  # how far right of its neighbour a `nextto` object is put


def _local_x(scene: TabletopScene, obj: str) -> tuple[float, float]:
    """The object's leftmost and rightmost local x when upright."""
    xs = [x for part in scene.things[obj].spec.parts for x, _ in part]
    return min(xs), max(xs)


def _under_pose(scene: TabletopScene, obj: str, target: str) -> BodyPose | None:
    thing, tgt = scene.things[obj], scene.things[target]
    span = under_span(tgt.spec, tgt.props)
    if span is None:
        return None
    lo, hi = _local_x(scene, obj)
    if thing.spec.height > span[2] - 0.3:
        return None
    x0 = float(tgt.body.position.x) + span[0] + FIXED_GAP / 2
    x1 = float(tgt.body.position.x) + span[1] - FIXED_GAP / 2
    taken = sorted((t.bounds()[0], t.bounds()[2]) for t in scene.things.values()
                   if t.id != obj and not t.fixed and t.body.space is not None
                   and t.bounds()[1] < span[2] and t.bounds()[2] > x0 and t.bounds()[0] < x1)
    left = x0
    for a, b in taken:
        if left + (hi - lo) + FIXED_GAP / 2 <= a:
            break
        left = max(left, b + FIXED_GAP / 2 + 0.3)
    if left + (hi - lo) > x1:
        return None
    return BodyPose(left - lo, DROP_GAP)


def _nextto_pose(scene: TabletopScene, obj: str, target: str
                 ) -> tuple[BodyPose, tuple[tuple[str, ...], float]] | None:
    """The pose right of the target, and the group slid right to make room (if any)."""
    _, direct = read_supports(scene)
    tgt = scene.things[target]
    base = direct.get(target)
    if base is None or (base.supporter is None and not base.on_floor):
        return None
    lo, hi = _local_x(scene, obj)
    _, bottom, right, _ = tgt.bounds()
    pose = BodyPose(right + TOUCH - lo, bottom + DROP_GAP)
    new_right = right + TOUCH + (hi - lo)
    same = [o for o, d in direct.items() if o != obj and o != target and
            (d.supporter, d.on_floor) == (base.supporter, base.on_floor)]
    ahead = [o for o in same if scene.things[o].bounds()[0] >= right - 0.05]
    nearest = min((scene.things[o].bounds()[0] for o in ahead), default=None)
    if nearest is None or nearest >= new_right + FIXED_GAP:
        return pose, ((), 0.0)
    sup = base.supporter
    if sup is None or not scene.things[sup].fixed:
        return None  # only furniture's load is slid aside
    group = tuple(dict.fromkeys(x for o in ahead for x in subtree_of(direct, o)))
    return pose, (group, new_right + FIXED_GAP - nearest)


def place_beside(scene: TabletopScene, obj: str, relation: str, target: str, *,
                 verify: bool = True) -> str:
    """`placed`, or `no_room` (scene as it was, `obj` still lifted); unverified: the
    placement whatever physics makes of it, or `no_room` when there is none."""
    supports = read_supports(scene)[0]
    slide: tuple[tuple[str, ...], float] = ((), 0.0)
    if relation == "under":
        pose = _under_pose(scene, obj, target)
    else:
        found = _nextto_pose(scene, obj, target)
        pose, slide = (found[0], found[1]) if found is not None else (None, slide)
    if pose is None:
        return "no_room"
    lifted = scene.snapshot()
    ids, dx = slide
    for moved in ids:
        p = physics.pose_of(scene.things[moved].body)
        scene.put(moved, BodyPose(p.x + dx, p.y, p.angle))
    scene.put(obj, pose)
    if physics.overlaps(scene.space, scene.things[obj].body):
        scene.restore(lifted)
        return "no_room"
    intended = scene.snapshot()
    scene.settle()
    if not verify:
        return "placed"
    expected = dict(supports)
    expected[obj] = (relation, target)
    if read_supports(scene)[0] == expected and not disturbed(scene, intended):
        return "placed"
    scene.restore(lifted)
    return "no_room"
