"""Where to put an object: free placements on or in a target, found by lowering it.

A placement is chosen like a careful arm would: pick a horizontal position over the
target, lower the object until it touches whatever is highest under it, and keep the
position only if (a) it comes to rest on the intended target in the intended relation
(read with the same rules as the ground truth), (b) it stands on a real footing (not on
an edge) with its centre of mass over the contact with a margin, and (c) every object
under it keeps its centre of mass over its own support. Positions are tried in order of
preference: packed from the left on fixed furniture, centred on small supports and in
containers. Thin cutlery going into a narrow container stands upright.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from verigraph.sim2d import physics
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.readback import (
    DirectSupport,
    direct_support,
    innermost_container,
    relation_to,
)
from verigraph.sim2d.scene import TabletopScene, Thing

DROP_GAP = 0.02
FIXED_GAP = 1.5
GRID = 0.5
MAX_TRIES = 160
MAX_GRID_POINTS = 4096
SIDE_NORMAL = 0.5
FOOTING_PROBE = 0.25
MIN_FOOTING = 2.0
HOUSEHOLD_SIDE_GAP = 0.4  # wider than readback.NEXT_GAP


@dataclass(frozen=True, slots=True)
class PoseChoice:
    """A pose for the moved object, and how it was found."""

    pose: BodyPose
    mode: str


def margin(width: float) -> float:
    """How far inside a contact a centre of mass must stay to count as stable."""
    return min(1.0, 0.15 * max(width, 0.0))


def subtree_of(direct: dict[str, DirectSupport], root: str) -> list[str]:
    """`root` and everything resting on it, directly or indirectly."""
    children: dict[str, list[str]] = {}
    for obj, sup in direct.items():
        if sup.supporter is not None:
            children.setdefault(sup.supporter, []).append(obj)
    out, stack = [], [root]
    while stack:
        node = stack.pop()
        if node in out:
            continue
        out.append(node)
        stack.extend(children.get(node, []))
    return out


def mass_centre(scene: TabletopScene, ids: Iterable[str]) -> tuple[float, float]:
    total, moment = 0.0, 0.0
    for obj in ids:
        thing = scene.things[obj]
        m = thing.mass
        total += m
        moment += m * thing.com()[0]
    return total, (moment / total if total > 0 else 0.0)


def balance_interval(scene: TabletopScene, direct: dict[str, DirectSupport], target: str,
                     mass: float) -> tuple[float, float]:
    """Range of x for the new object's centre of mass that keeps every support under
    `target` balanced (the object's own footing is checked separately)."""
    lo, hi = -math.inf, math.inf
    current: str | None = target
    seen: set[str] = set()
    while current is not None and current not in seen:
        seen.add(current)
        thing = scene.things[current]
        sup = direct.get(current)
        if thing.fixed or sup is None or sup.span is None:
            break
        total, x_com = mass_centre(scene, subtree_of(direct, current))
        left, right = sup.span
        mg = margin(right - left)
        # Something already near or past an edge (held up by friction or a wall) may
        # only get more balanced, never less.
        left, right = min(left + mg, x_com), max(right - mg, x_com)
        if mass > 0:
            lo = max(lo, ((total + mass) * left - total * x_com) / mass)
            hi = min(hi, ((total + mass) * right - total * x_com) / mass)
        current = sup.supporter
    return lo, hi


@dataclass(frozen=True, slots=True)
class _Footprint:
    x0: float
    x1: float
    y0: float
    com_dx: float


def _footprint(thing: Thing, angle: float) -> _Footprint:
    """Local bounds of the object turned by `angle`, and its centre of mass offset."""
    c, s = math.cos(angle), math.sin(angle)
    xs, ys = [], []
    for part in thing.spec.parts:
        for x, y in part:
            xs.append(c * x - s * y)
            ys.append(s * x + c * y)
    _, gx, gy = thing.spec.mass_centre
    return _Footprint(min(xs), max(xs), min(ys), c * gx - s * gy)


class _Terrain:
    """World polygons of everything present, for lowering an object onto them."""

    def __init__(self, scene: TabletopScene, skip: str) -> None:
        self.polys: list[tuple[float, float, list[tuple[float, float]]]] = []
        bodies = [scene.floor, *scene.fixtures] + [
            t.body for t in scene.things.values() if t.id != skip and t.body.space is not None]
        for body in bodies:
            for poly in physics.world_polygons(body):
                xs = [p[0] for p in poly]
                self.polys.append((min(xs), max(xs), poly))

    def rest_height(self, x0: float, x1: float) -> float:
        best = -math.inf
        for left, right, poly in self.polys:
            if right < x0 or left > x1:
                continue
            top = physics.clip_top(poly, x0, x1)
            if top is not None and top > best:
                best = top
        return best


def _upright(obj: Thing, target: Thing, relation: str) -> bool:
    cavity = target.spec.cavity
    if relation != "in" or cavity is None or not obj.spec.thin:
        return False
    inner = cavity[1] - cavity[0]
    depth = cavity[3] - cavity[2]
    return obj.spec.width > inner - 0.2 and obj.spec.height < inner - 0.4 \
        and obj.spec.width <= 1.6 * depth


def _target_range(obj: Thing, target: Thing, relation: str,
                  half_width: float) -> tuple[float, float]:
    left, _, right, _ = target.bounds()
    if target.fixed and relation == "on":
        return left + half_width + FIXED_GAP / 2, right - half_width - FIXED_GAP / 2
    if relation == "on":
        mg = margin(right - left)
        return left + mg, right - mg
    return left, right


def _grid(lo: float, hi: float) -> list[float]:
    """Positions from lo to hi every GRID units; over a very wide target (furniture
    widened for thousands of objects) at most MAX_GRID_POINTS, evenly spaced, so the
    candidates cost memory by the count of objects, never by a width."""
    if hi < lo:
        return []
    step = max(GRID, (hi - lo) / MAX_GRID_POINTS)
    n = min(int((hi - lo) / step), MAX_GRID_POINTS)
    xs = [lo + i * step for i in range(n + 1)]
    if hi - xs[-1] > 1e-6:
        xs.append(hi)
    return xs


def _ordered(lo: float, hi: float, obj: Thing, target: Thing, relation: str,
             half: float) -> list[float]:
    """Candidate centre-of-mass positions, most preferred first.

    Fixed furniture: packed from the left. Movable surfaces: packed from the left where
    the object does not overhang, then the smallest overhangs (balance constraints
    already keep small supports centred). Containers: from the centre outwards.
    """
    xs = _grid(lo, hi)
    if not xs:
        return []
    if target.fixed and relation == "on":
        return xs
    left, _, right, _ = target.bounds()
    if relation == "on":
        a, b = left + half, right - half
        inside = [x for x in xs if a - 1e-6 <= x <= b + 1e-6]
        outside = sorted((x for x in xs if not a - 1e-6 <= x <= b + 1e-6),
                         key=lambda x: (max(a - x, x - b), x))
        if a <= b and lo <= a <= hi and a not in inside:
            inside.insert(0, a)
        return inside + outside
    p = min(max(target.com()[0], lo), hi)
    return sorted(set(xs + [p]), key=lambda x: (abs(x - p), x))


def find_placements(scene: TabletopScene, obj: str, relation: str, target: str,
                    supports: dict[str, tuple[str, str]], direct: dict[str, DirectSupport],
                    *, limit: int = 3) -> list[PoseChoice]:
    """Up to `limit` stable placements of `obj` (currently lifted) `relation` `target`.

    `supports` and `direct` describe the scene without `obj` (see readback).
    """
    thing = scene.things[obj]
    tgt = scene.things[target]
    # Cutlery stands upright only where it cannot lie flat (a narrow cup or mug).
    angles = [math.pi / 2, 0.0] if _upright(thing, tgt, relation) else [0.0]
    terrain = _Terrain(scene, skip=obj)
    bal_lo, bal_hi = balance_interval(scene, direct, target, thing.mass)
    out: list[PoseChoice] = []
    tries = 0
    for angle in angles:
        fp = _footprint(thing, angle)
        half = (fp.x1 - fp.x0) / 2
        lo, hi = _target_range(thing, tgt, relation, half)
        lo, hi = max(lo, bal_lo), min(hi, bal_hi)
        pad = FIXED_GAP / 2 if tgt.fixed and relation == "on" else 0.0
        top = tgt.bounds()[3]
        for cx in _ordered(lo, hi, thing, tgt, relation, half):
            ox = cx - fp.com_dx
            rest = terrain.rest_height(ox + fp.x0 - pad, ox + fp.x1 + pad)
            if not math.isfinite(rest) or (relation == "on" and rest > top + 0.1):
                continue  # something else is in the way: not worth a contact probe
            tries += 1
            if tries > MAX_TRIES:
                return out
            pose = BodyPose(ox, rest - fp.y0 + DROP_GAP, angle)
            if _accept(scene, thing, pose, relation, target, supports):
                out.append(PoseChoice(pose, "upright" if angle else "flat"))
                if len(out) >= limit:
                    return out
    return out


def _accept(scene: TabletopScene, thing: Thing, pose: BodyPose, relation: str, target: str,
            supports: dict[str, tuple[str, str]]) -> bool:
    """Would the object, put down at `pose`, rest stably `relation` `target`?"""
    scene.put(thing.id, pose)
    try:
        contacts = physics.probe_contacts(scene.space, thing.body)
        if any(abs(c.ny) < SIDE_NORMAL for c in contacts):
            return False  # jammed against a wall or a neighbour
        sup = direct_support(scene, thing, contacts)
        if sup.supporter is None or sup.span is None:
            return False
        if scene.household and sup.supporter != target:
            return False  # resting on a neighbour inside a bin would pin it down
        if scene.household:
            own = scene.things[sup.supporter].body
            if any(abs(c.ny) < SIDE_NORMAL and c.other is not own for c in
                   physics.probe_contacts(scene.space, thing.body, HOUSEHOLD_SIDE_GAP)):
                return False  # so close to a neighbour that it would read as next to it
        # The footing: everything within a small drop under the object, since it will
        # tilt that little onto a second rim or edge before coming to rest.
        footing = direct_support(scene, thing, physics.probe_contacts(
            scene.space, thing.body, FOOTING_PROBE), same_as=sup.supporter)
        span = footing.span or sup.span
        left, _, right, _ = thing.bounds()
        if span[1] - span[0] < min(MIN_FOOTING, 0.25 * (right - left)):
            return False  # balanced on an edge (a knife across one wall of a pot)
        com_x = thing.com()[0]
        mg = margin(span[1] - span[0])
        if not span[0] + mg - 1e-6 <= com_x <= span[1] - mg + 1e-6:
            return False
        if physics.overlaps(scene.space, thing.body):
            return False
        return _resulting_support(scene, thing, sup.supporter, supports) == (relation, target)
    finally:
        scene.lift(thing.id)


def _resulting_support(scene: TabletopScene, thing: Thing, supporter: str,
                       supports: dict[str, tuple[str, str]]) -> tuple[str, str] | None:
    rel = relation_to(scene, thing, scene.things[supporter])
    if rel is not None:
        return rel, supporter
    holder = innermost_container(scene, thing, exclude={thing.id})
    if holder is not None:
        return "in", holder.id
    return supports.get(supporter)


def drop_placement(scene: TabletopScene, obj: str, target: str) -> PoseChoice:
    """Unverified fallback: lower the object over the target's centre, whatever is there."""
    thing = scene.things[obj]
    fp = _footprint(thing, 0.0)
    cx = scene.things[target].com()[0]
    ox = cx - fp.com_dx
    rest = _Terrain(scene, skip=obj).rest_height(ox + fp.x0, ox + fp.x1)
    return PoseChoice(BodyPose(ox, rest - fp.y0 + DROP_GAP, 0.0), "drop")
