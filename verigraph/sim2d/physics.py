"""Thin helpers over pymunk: the space, bodies from specs, settling, and contact probes.

Everything that touches pymunk's API directly lives here, so the rest of sim2d deals in
ids, poses and polygons. Contacts are read geometrically (a slightly inflated copy of a
body's shapes queried against the space), which makes the ground truth a function of
the bodies' poses alone rather than of the solver's contact cache.
"""

from __future__ import annotations

from dataclasses import dataclass

import pymunk

from verigraph.sim2d.bodies import BodySpec

GRAVITY = -981.0
DT = 1.0 / 240.0
FRICTION = 0.9
DENSITY = 1.0
ITERATIONS = 30
COLLISION_SLOP = 0.02
PROBE_RADIUS = 0.06
CALM_SPEED = 0.5
CALM_SPIN = 0.02
CALM_STEPS = 12
MIN_STEPS = 4
MAX_SETTLE_STEPS = 1500
FLOOR_HALF_WIDTH = 5000.0


@dataclass(frozen=True, slots=True)
class BodyPose:
    """Position of a body's origin (bottom centre for tabletop objects) and its angle."""

    x: float
    y: float
    angle: float = 0.0


@dataclass(frozen=True, slots=True)
class Contact:
    """One touching neighbour of a body: the normal points from the body to `other`."""

    other: pymunk.Body
    nx: float
    ny: float
    points: tuple[tuple[float, float], ...]


def new_space() -> pymunk.Space:
    space = pymunk.Space()
    space.gravity = (0.0, GRAVITY)
    space.iterations = ITERATIONS
    space.collision_slop = COLLISION_SLOP
    return space


def add_floor(space: pymunk.Space) -> pymunk.Body:
    """An unnamed static floor: whatever lands on it has no support edge."""
    body = pymunk.Body(body_type=pymunk.Body.STATIC)
    shape = pymunk.Poly(body, [(-FLOOR_HALF_WIDTH, -2.0), (FLOOR_HALF_WIDTH, -2.0),
                               (FLOOR_HALF_WIDTH, 0.0), (-FLOOR_HALF_WIDTH, 0.0)])
    shape.friction = FRICTION
    space.add(body, shape)
    return body


def make_body(spec: BodySpec, pose: BodyPose, *, fixed: bool) -> pymunk.Body:
    """A pymunk body with one convex Poly per part (not yet added to a space)."""
    body = pymunk.Body(body_type=pymunk.Body.STATIC if fixed else pymunk.Body.DYNAMIC)
    for part in spec.parts:
        shape = pymunk.Poly(body, list(part))
        shape.friction = FRICTION
        shape.elasticity = 0.0
        if not fixed:
            shape.density = DENSITY
    set_pose(body, pose)
    return body


def add_body(space: pymunk.Space, body: pymunk.Body) -> None:
    space.add(body, *body.shapes)


def remove_body(space: pymunk.Space, body: pymunk.Body) -> None:
    space.remove(body, *body.shapes)


def set_pose(body: pymunk.Body, pose: BodyPose) -> None:
    # Angle first: Chipmunk turns a body about its centre of gravity, so setting the
    # angle after the position would move the origin away from (x, y).
    body.angle = pose.angle
    body.position = (pose.x, pose.y)
    if body.body_type == pymunk.Body.DYNAMIC:
        body.velocity = (0.0, 0.0)
        body.angular_velocity = 0.0
    if body.space is not None:
        body.space.reindex_shapes_for_body(body)
    else:
        for shape in body.shapes:
            shape.cache_bb()


def pose_of(body: pymunk.Body) -> BodyPose:
    return BodyPose(float(body.position.x), float(body.position.y), float(body.angle))


def settle(space: pymunk.Space, max_steps: int = MAX_SETTLE_STEPS) -> int:
    """Step until every dynamic body is calm for a while (or the step budget runs out).

    Velocities are zeroed at the end so that the next action starts from rest: the
    world state is then fully described by the poses. Returns the steps taken.
    """
    dynamic = [b for b in space.bodies if b.body_type == pymunk.Body.DYNAMIC]
    calm = 0
    steps = 0
    while steps < max_steps:
        space.step(DT)
        steps += 1
        moving = any(b.velocity.length > CALM_SPEED or abs(b.angular_velocity) > CALM_SPIN
                     for b in dynamic)
        calm = 0 if moving else calm + 1
        if calm >= CALM_STEPS and steps >= MIN_STEPS:
            break
    for b in dynamic:
        b.velocity = (0.0, 0.0)
        b.angular_velocity = 0.0
    return steps


def world_polygons(body: pymunk.Body) -> list[list[tuple[float, float]]]:
    """The body's convex parts in world coordinates."""
    out = []
    for shape in body.shapes:
        if isinstance(shape, pymunk.Poly):
            pts = [body.local_to_world(v) for v in shape.get_vertices()]
            out.append([(float(p.x), float(p.y)) for p in pts])
    return out


def probe_contacts(space: pymunk.Space, body: pymunk.Body,
                   radius: float = PROBE_RADIUS) -> list[Contact]:
    """Bodies within `radius` of `body`, with the contact normal and points on them."""
    probe = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    probe.position = body.position
    probe.angle = body.angle
    found: dict[pymunk.Body, Contact] = {}
    for shape in body.shapes:
        if not isinstance(shape, pymunk.Poly):
            continue
        ghost = pymunk.Poly(probe, shape.get_vertices(), radius=radius)
        ghost.cache_bb()
        for hit in space.shape_query(ghost):
            other = hit.shape.body
            if other is body or other is None:
                continue
            cps = hit.contact_point_set
            pts = tuple((float(p.point_b.x), float(p.point_b.y)) for p in cps.points)
            if not pts:
                continue
            prev = found.get(other)
            if prev is None:
                found[other] = Contact(other, float(cps.normal.x), float(cps.normal.y), pts)
            elif cps.normal.y < prev.ny:
                # Keep the most supporting normal, but pool the contact points.
                found[other] = Contact(other, float(cps.normal.x), float(cps.normal.y),
                                       prev.points + pts)
            else:
                found[other] = Contact(other, prev.nx, prev.ny, prev.points + pts)
    return list(found.values())


def overlaps(space: pymunk.Space, body: pymunk.Body, depth: float = 0.02) -> list[pymunk.Body]:
    """Bodies that `body` (already in the space) penetrates deeper than `depth`."""
    hits: list[pymunk.Body] = []
    for shape in body.shapes:
        for hit in space.shape_query(shape):
            other = hit.shape.body
            if other is body or other is None or other in hits:
                continue
            if any(p.distance < -depth for p in hit.contact_point_set.points):
                hits.append(other)
    return hits


def clip_top(poly: list[tuple[float, float]], x0: float, x1: float) -> float | None:
    """Highest y of a convex polygon within the vertical band x0 <= x <= x1 (or None)."""
    best: float | None = None
    n = len(poly)
    for i in range(n):
        ax, ay = poly[i]
        bx, by = poly[(i + 1) % n]
        if x0 <= ax <= x1:
            best = ay if best is None else max(best, ay)
        lo, hi = (ax, bx) if ax <= bx else (bx, ax)
        for x in (x0, x1):
            if lo < x < hi:
                y = ay + (by - ay) * (x - ax) / (bx - ax)
                best = y if best is None else max(best, y)
    return best
