"""Putting a lifted object down: candidate placements are tried in simulation, one is kept.

A candidate counts only if, once settled, the graph read back is the expected one and
nothing slid or tipped; otherwise the scene is restored and the next one is tried (the
arm checks in simulation before committing, so a verified placement that would topple
is never carried out). When nothing fits, room is made without changing any support:
furniture's load is pushed to the left (closing gaps left by earlier moves), a
movable surface's load is packed aside or slid as a block, and the target's neighbours
on furniture are nudged away. Unverified mode takes the first candidate, or a plain
drop over the target, and lets physics decide.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

from verigraph.sim2d import physics
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.placement import (
    FIXED_GAP,
    PoseChoice,
    drop_placement,
    find_placements,
    margin,
    mass_centre,
    subtree_of,
)
from verigraph.sim2d.readback import NEXT_GAP, DirectSupport, read_supports
from verigraph.sim2d.scene import Snapshot, TabletopScene

CANDIDATES = 3
SETTLE_SHIFT = 0.5
SETTLE_TURN = 0.05
SLIDE_STEP = 1.0
SLIDE_DEPTH = 0.05

Outcome = Literal["placed", "no_room", "unstable", "dropped"]


Slide = tuple[tuple[str, ...], float]


@dataclass(frozen=True, slots=True)
class Plan:
    """A placement, possibly after sliding groups of objects sideways on their support."""

    placement: PoseChoice
    slides: tuple[Slide, ...] = field(default=())


def _shift(scene: TabletopScene, ids: tuple[str, ...], dx: float) -> None:
    for obj in ids:
        pose = physics.pose_of(scene.things[obj].body)
        scene.put(obj, BodyPose(pose.x + dx, pose.y, pose.angle))


def _slide(scene: TabletopScene, slides: tuple[Slide, ...], sign: float = 1.0) -> None:
    for ids, dx in slides:
        _shift(scene, ids, sign * dx)


def _apply(scene: TabletopScene, obj: str, plan: Plan) -> None:
    _slide(scene, plan.slides)
    scene.put(obj, plan.placement.pose)


def _try_slides(scene: TabletopScene, obj: str, relation: str, target: str,
                supports: dict[str, tuple[str, str]], slides: tuple[Slide, ...],
                supports_of: tuple[str, ...] = ()) -> Plan | None:
    """Slide, look for a placement, slide back; the plan if one was found.

    `supports_of`: what the slid groups rest on (they may touch it, nothing else)."""
    _slide(scene, slides)
    try:
        group = {scene.things[o].body for ids, _ in slides for o in ids}
        allowed = group | {scene.things[target].body} | {
            scene.things[s].body for s in supports_of}
        for body in group:
            if any(b not in allowed for b in physics.overlaps(scene.space, body, SLIDE_DEPTH)):
                return None
        moved, moved_direct = read_supports(scene)
        if moved != supports:
            return None
        for ids, _ in slides:
            # A household row slid as one group: each of its stacks must stay balanced.
            parts = [tuple(subtree_of(moved_direct, o)) for o in ids
                     if moved_direct[o].supporter not in ids] if scene.household else [ids]
            if not all(_balanced(scene, moved_direct, part) for part in parts):
                return None
        found = find_placements(scene, obj, relation, target, moved, moved_direct, limit=1)
        return Plan(found[0], slides) if found else None
    finally:
        _slide(scene, tuple(reversed(slides)), -1.0)


def disturbed(scene: TabletopScene, intended: Snapshot) -> list[str]:
    """Objects that slid or tipped noticeably away from their intended poses."""
    out = []
    for obj, (pose, present) in intended.items():
        if not present or not scene.present(obj):
            continue
        now = physics.pose_of(scene.things[obj].body)
        turn = abs(math.remainder(now.angle - pose.angle, 2 * math.pi))
        if math.hypot(now.x - pose.x, now.y - pose.y) > SETTLE_SHIFT or turn > SETTLE_TURN:
            out.append(obj)
    return out


def turned(scene: TabletopScene, before: Snapshot, limit: float) -> list[str]:
    """Objects whose angle changed by more than `limit` (they tipped)."""
    out = []
    for obj, (pose, present) in before.items():
        if present and scene.present(obj):
            now = scene.things[obj].body.angle
            if abs(math.remainder(now - pose.angle, 2 * math.pi)) > limit:
                out.append(obj)
    return out


def _stayed(scene: TabletopScene, intended: Snapshot) -> bool:
    """Nothing slid or tipped while settling (a tilted stack is not a success even if
    it still reads as the right graph)."""
    return not disturbed(scene, intended)


def _loads(direct: dict[str, DirectSupport], target: str, obj: str) -> list[tuple[str, ...]]:
    """What rests on `target`: one group (an object and all it carries) per object."""
    children = [o for o, sup in direct.items() if sup.supporter == target and o != obj]
    return [tuple(subtree_of(direct, c)) for c in children]


def _rows(scene: TabletopScene, groups: list[tuple[str, ...]]) -> list[tuple[str, ...]]:
    """Groups standing next to each other (a household `nextto` row) as one group, so
    that sliding keeps them together."""
    out: list[tuple[str, ...]] = []
    for ids in sorted(groups, key=lambda g: _extent(scene, g)[0]):
        if out and _extent(scene, ids)[0] - _extent(scene, out[-1])[1] <= NEXT_GAP:
            out[-1] = out[-1] + ids
        else:
            out.append(ids)
    return out


def _extent(scene: TabletopScene, ids: tuple[str, ...]) -> tuple[float, float]:
    bounds = [scene.things[o].bounds() for o in ids]
    return min(b[0] for b in bounds), max(b[2] for b in bounds)


def _balanced(scene: TabletopScene, direct: dict[str, DirectSupport],
              group: tuple[str, ...]) -> bool:
    """The group's centre of mass is over the contact of its bottom object."""
    root = group[0]
    span = direct[root].span
    if span is None:
        return False
    _, x_com = mass_centre(scene, group)
    mg = margin(span[1] - span[0])
    return span[0] + mg <= x_com <= span[1] - mg


def _packed(scene: TabletopScene, loads: list[tuple[str, ...]], edge: float, gap: float,
            direction: float) -> tuple[Slide, ...]:
    """Push every group towards one edge (direction -1: left, +1: right), keeping order."""
    slides = []
    cursor = edge
    groups = sorted(loads, key=lambda g: -direction * _extent(scene, g)[0])
    for ids in groups:
        lo, hi = _extent(scene, ids)
        near, far = (lo, hi) if direction < 0 else (hi, lo)
        dx = cursor - near
        dx = min(0.0, dx) if direction < 0 else max(0.0, dx)
        if dx:
            slides.append((ids, dx))
        cursor = far + dx - direction * gap
    return tuple(slides)


def _slide_plans(scene: TabletopScene, obj: str, relation: str, target: str,
                 supports: dict[str, tuple[str, str]], direct: dict[str, DirectSupport]
                 ) -> list[Plan]:
    """Make room: push the target's load to one side (furniture: to the left), or slide
    a movable surface's whole load sideways as one block; if the target stands on
    furniture, also push its neighbours there aside so that the object may overhang."""
    tgt = scene.things[target]
    loads = _loads(direct, target, obj)
    if scene.household:
        loads = _rows(scene, loads)
    left, _, right, _ = tgt.bounds()
    own: list[tuple[Slide, ...]] = []
    if relation == "on" and loads:
        if tgt.fixed:
            own.append(_packed(scene, loads, left + FIXED_GAP / 2, FIXED_GAP, -1.0))
        else:
            own.append(_packed(scene, loads, left, 0.2, -1.0))
            own.append(_packed(scene, loads, right, 0.2, 1.0))
            block = tuple(dict.fromkeys(o for ids in loads for o in ids))
            reach = (right - left) / 2 + scene.things[obj].spec.width / 2
            for k in range(1, int(reach / SLIDE_STEP) + 1):
                own.append(((block, -k * SLIDE_STEP),))
                own.append(((block, k * SLIDE_STEP),))
    options: list[tuple[tuple[Slide, ...], tuple[str, ...]]] = [(o, (target,)) for o in own]
    base = direct.get(target)
    floor = base.supporter if base is not None else None
    if floor is not None and not tgt.fixed and scene.things[floor].fixed:
        for aside in _nudges(scene, direct, floor, target, obj):
            options.append((aside, (floor,)))
            options.extend((aside + o, (floor, target)) for o in own[:2])
    for slides, rests_on in options:
        if not slides:
            continue
        plan = _try_slides(scene, obj, relation, target, supports, slides, rests_on)
        if plan is not None:
            return [plan]
    return []


def _nudges(scene: TabletopScene, direct: dict[str, DirectSupport], furniture: str,
            target: str, obj: str) -> list[tuple[Slide, ...]]:
    """Ways to make room around `target` on a piece of furniture: push the neighbours on
    one side or both away by the moved object's width, move the target itself away
    from them, or push everything else to the furniture's edges."""
    left, _, right, _ = scene.things[furniture].bounds()
    groups = [g for g in _loads(direct, furniture, obj) if target not in g]
    if scene.household:
        groups = _rows(scene, groups)
    centre = sum(_extent(scene, tuple(subtree_of(direct, target)))) / 2
    before = [g for g in groups if sum(_extent(scene, g)) / 2 < centre]
    after = [g for g in groups if sum(_extent(scene, g)) / 2 >= centre]
    width = scene.things[obj].spec.width
    right_block = (tuple(dict.fromkeys(o for g in after for o in g)), width)
    left_block = (tuple(dict.fromkeys(o for g in before for o in g)), -width)
    own = tuple(subtree_of(direct, target))
    options: list[tuple[Slide, ...]] = [
        (right_block,), (left_block,), (left_block, right_block),
        ((own, width / 2),), ((own, -width / 2),), ((own, width),), ((own, -width),),
        _packed(scene, before, left + FIXED_GAP / 2, FIXED_GAP, -1.0)
        + _packed(scene, after, right - FIXED_GAP / 2, FIXED_GAP, 1.0)]
    return [tuple(sl for sl in o if sl[0]) for o in options if any(sl[0] for sl in o)]


def put_down(scene: TabletopScene, obj: str, relation: str, target: str, *,
             verify: bool = True) -> Outcome:
    """Put the lifted `obj` `relation` `target` and settle.

    verify=True: a placement counts only if physics ends with `obj relation target`,
    everything else unchanged and nothing slid or tipped; otherwise the scene is left
    as it was (with `obj` still lifted) and the result says why: `no_room` (no
    candidate at all) or `unstable` (every candidate slid or toppled in simulation).
    verify=False: the first candidate, or a plain drop over the target, and whatever
    physics makes of it.
    """
    supports, direct = read_supports(scene)
    plans = [Plan(p) for p in find_placements(scene, obj, relation, target, supports, direct,
                                              limit=CANDIDATES)]
    if not plans:
        plans = _slide_plans(scene, obj, relation, target, supports, direct)
    if not plans:
        if verify:
            return "no_room"
        scene.put(obj, drop_placement(scene, obj, target).pose)
        scene.settle()
        return "dropped"
    if not verify:
        _apply(scene, obj, plans[0])
        scene.settle()
        return "placed"
    expected = dict(supports)
    expected[obj] = (relation, target)
    lifted = scene.snapshot()
    for plan in plans:
        _apply(scene, obj, plan)
        intended = scene.snapshot()
        scene.settle()
        if read_supports(scene)[0] == expected and _stayed(scene, intended):
            return "placed"
        scene.restore(lifted)
    return "unstable"
