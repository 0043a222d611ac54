"""Ground truth from physics: which object rests on or in which, read from contacts.

For every object the direct supporter is the body below it that it touches (contact
normal pointing up, preferring the contact under its centre of mass). The relation
then follows from geometry and the dictionary:
- resting on a surface: `on` (unless it sits inside that object's cavity: `in`);
- resting on a container, on its floor or across its rim: `in`;
- resting on something that is neither (a spoon, a kettle), or wedged between walls
  without resting on anything: `in` the innermost container whose cavity holds its
  centre of mass, else whatever its supporter is on (a cup standing on a spoon on the
  desk is on the desk).
Objects on the floor, or touching nothing below, have no support edge.
"""

from __future__ import annotations

from dataclasses import dataclass

from verigraph.sim2d.physics import Contact, probe_contacts
from verigraph.sim2d.scene import TabletopScene, Thing

SUPPORT_NORMAL = 0.5
CAVITY_FLOOR_TOLERANCE = 0.5


@dataclass(frozen=True, slots=True)
class DirectSupport:
    """The body an object physically rests on (None: the floor or nothing)."""

    supporter: str | None
    span: tuple[float, float] | None
    on_floor: bool = False


def direct_support(scene: TabletopScene, thing: Thing,
                   contacts: list[Contact] | None = None, *,
                   same_as: str | None = None) -> DirectSupport:
    """Pick the supporting contact: below the object, under its centre of mass if possible
    (`same_as`: only contacts with that object)."""
    if contacts is None:
        contacts = probe_contacts(scene.space, thing.body)
    com_x = thing.com()[0]
    best: tuple[tuple[bool, float, int], DirectSupport] | None = None
    for index, c in enumerate(contacts):
        if c.ny > -SUPPORT_NORMAL:
            continue
        xs = [p[0] for p in c.points]
        span = (min(xs), max(xs))
        under = span[0] - 0.05 <= com_x <= span[1] + 0.05
        other = scene.by_body.get(c.other)
        if (other is None and c.other is not scene.floor) or (
                same_as is not None and other != same_as):
            continue
        candidate = DirectSupport(other, span, on_floor=other is None)
        score = (under, span[1] - span[0], -index)
        if best is None or score > best[0]:
            best = (score, candidate)
    return best[1] if best is not None else DirectSupport(None, None)


def in_cavity(container: Thing, point: tuple[float, float]) -> bool:
    """Whether a world point lies inside a container's cavity (between walls, below rim)."""
    cavity = container.spec.cavity
    if cavity is None:
        return False
    local = container.body.world_to_local(point)
    x0, x1, y0, y1 = cavity
    return x0 <= local.x <= x1 and y0 - CAVITY_FLOOR_TOLERANCE <= local.y <= y1


def innermost_container(scene: TabletopScene, thing: Thing,
                        exclude: set[str]) -> Thing | None:
    com = thing.com()
    best: Thing | None = None
    for other in scene.things.values():
        if other.id == thing.id or other.id in exclude or not scene.present(other.id):
            continue
        if other.spec.cavity is None or not other.props.container:
            continue
        if in_cavity(other, com) and (best is None or _cavity_area(other) < _cavity_area(best)):
            best = other
    return best


def _cavity_area(thing: Thing) -> float:
    assert thing.spec.cavity is not None
    x0, x1, y0, y1 = thing.spec.cavity
    return (x1 - x0) * (y1 - y0)


def relation_to(scene: TabletopScene, thing: Thing, supporter: Thing) -> str | None:
    """`on`/`in` for an object resting directly on `supporter`, or None if neither fits."""
    props = supporter.props
    if props.container and in_cavity(supporter, thing.com()):
        return "in"
    if props.surface:
        return "on"
    if props.container:
        return "in"
    return None


def read_supports(scene: TabletopScene) -> tuple[dict[str, tuple[str, str]],
                                                 dict[str, DirectSupport]]:
    """Every present object's (relation, target) as physics shows it, and the raw contacts."""
    direct = {t.id: direct_support(scene, t) for t in scene.things.values()
              if scene.present(t.id)}
    resolved: dict[str, tuple[str, str] | None] = {}

    def resolve(obj: str, visiting: set[str]) -> tuple[str, str] | None:
        if obj in resolved:
            return resolved[obj]
        if obj in visiting:
            return None
        visiting.add(obj)
        result: tuple[str, str] | None = None
        sup = direct[obj].supporter
        thing = scene.things[obj]
        if sup is not None:
            rel = relation_to(scene, thing, scene.things[sup])
            if rel is not None:
                result = (rel, sup)
            else:
                holder = innermost_container(scene, thing, exclude={obj})
                result = ("in", holder.id) if holder is not None else resolve(sup, visiting)
        elif not direct[obj].on_floor:
            # Held between a container's walls without resting on anything (wedged).
            holder = innermost_container(scene, thing, exclude={obj})
            result = ("in", holder.id) if holder is not None else None
        visiting.discard(obj)
        resolved[obj] = result
        return result

    for obj in direct:
        resolve(obj, set())
    supports = {obj: rel for obj, rel in resolved.items() if rel is not None}
    return supports, direct
