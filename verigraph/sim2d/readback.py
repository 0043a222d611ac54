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

from collections.abc import Callable, Mapping
from dataclasses import dataclass

from verigraph.sim2d.bodies import under_span
from verigraph.sim2d.physics import Contact, probe_contacts
from verigraph.sim2d.scene import TabletopScene, Thing

SUPPORT_NORMAL = 0.5
CAVITY_FLOOR_TOLERANCE = 0.5
NEXT_GAP = 0.2  # an object at most this far right of another on the same base is next to it


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
    return support_relation(surface=props.surface, container=props.container,
                            centre_in_cavity=props.container and in_cavity(supporter,
                                                                          thing.com()))


def support_relation(*, surface: bool, container: bool, centre_in_cavity: bool
                     ) -> str | None:
    """The rule for an object resting directly on a supporter, shared with perception
    (which reads the same facts off pixels): inside a container's cavity `in`, on a
    surface `on`, on a container's rim `in`, on anything else (a spoon) None."""
    if container and centre_in_cavity:
        return "in"
    if surface:
        return "on"
    if container:
        return "in"
    return None


def resolve_supports(direct: Mapping[str, DirectSupport],
                     relation: Callable[[str, str], str | None],
                     holder: Callable[[str], str | None]) -> dict[str, tuple[str, str]]:
    """(relation, target) of every object from what it directly rests on.

    `relation(obj, supporter)` applies `support_relation`; `holder(obj)` is the
    innermost container whose cavity holds the object's centre. An object resting on
    something that is neither surface nor container is `in` its holder, else whatever
    its supporter is on; one resting on nothing (wedged between walls) is `in` its
    holder; one on the floor has no edge. Shared with perception, whose direct supports
    and cavities come from pixels instead of contacts.
    """
    resolved: dict[str, tuple[str, str] | None] = {}

    def resolve(obj: str, visiting: set[str]) -> tuple[str, str] | None:
        if obj in resolved:
            return resolved[obj]
        if obj in visiting:
            return None
        visiting.add(obj)
        result: tuple[str, str] | None = None
        sup = direct[obj].supporter
        if sup is not None:
            rel = relation(obj, sup)
            if rel is not None:
                result = (rel, sup)
            else:
                inside = holder(obj)
                result = ("in", inside) if inside is not None else resolve(sup, visiting)
        elif not direct[obj].on_floor:
            # Held between a container's walls without resting on anything (wedged).
            inside = holder(obj)
            result = ("in", inside) if inside is not None else None
        visiting.discard(obj)
        resolved[obj] = result
        return result

    for obj in direct:
        resolve(obj, set())
    return {obj: rel for obj, rel in resolved.items() if rel is not None}


def read_supports(scene: TabletopScene) -> tuple[dict[str, tuple[str, str]],
                                                 dict[str, DirectSupport]]:
    """Every present object's (relation, target) as physics shows it, and the raw contacts."""
    direct = {t.id: direct_support(scene, t) for t in scene.things.values()
              if scene.present(t.id)}

    def holder(obj: str) -> str | None:
        inside = innermost_container(scene, scene.things[obj], exclude={obj})
        return inside.id if inside is not None else None

    supports = resolve_supports(
        direct, lambda obj, sup: relation_to(scene, scene.things[obj], scene.things[sup]),
        holder)
    if scene.household:
        supports.update(beside(scene, direct))
    return supports, direct


def beside(scene: TabletopScene, direct: Mapping[str, DirectSupport]
           ) -> dict[str, tuple[str, str]]:
    """Household placements read from where things stand: a movable object whose left
    side is within `NEXT_GAP` of the right side of another thing resting on the same
    base (the same supporter, or both the floor) is `nextto` it; one standing on the
    floor between a surface's legs, below its top, is `under` it."""
    out: dict[str, tuple[str, str]] = {}
    things = [scene.things[obj] for obj in direct]
    for t in things:
        base = direct[t.id]
        if t.fixed or (base.supporter is None and not base.on_floor):
            continue
        left, bottom, right, top = t.bounds()
        best: tuple[float, str] | None = None
        for other in things:
            o_base = direct[other.id]
            if other is t or (o_base.supporter, o_base.on_floor) != (base.supporter,
                                                                     base.on_floor):
                continue
            _, o_bottom, o_right, o_top = other.bounds()
            gap = left - o_right
            if -0.05 <= gap <= NEXT_GAP and min(top, o_top) > max(bottom, o_bottom) and (
                    best is None or gap < best[0]):
                best = (gap, other.id)
        if best is not None:
            out[t.id] = ("nextto", best[1])
            continue
        if not base.on_floor:
            continue
        centre = (left + right) / 2
        for f in things:
            span = under_span(f.spec, f.props) if f.fixed else None
            if span is None:
                continue
            x, y = float(f.body.position.x), float(f.body.position.y)
            if x + span[0] <= centre <= x + span[1] and top <= y + span[2] + 0.05:
                out[t.id] = ("under", f.id)
                break
    return out
