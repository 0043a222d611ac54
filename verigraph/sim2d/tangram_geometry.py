"""Tangram pieces (top view): canonical shapes, side numbering, align motions, contacts.

Sizes follow the standard set with the small triangle's leg `UNIT`: small triangles
(legs 1), medium (legs sqrt 2), large (legs 2), square (side 1), parallelogram (sides
sqrt 2 and 1, acute angle 45 degrees). Vertices are listed clockwise as seen from
above, starting at the canonical vertex of docs/design.md section 2, and side i runs from
vertex i to vertex i+1: a triangle's right-angle vertex (sides 0 and 2 are the legs,
side 1 the hypotenuse), the parallelogram's acute vertex that starts a long side, the
square's vertex 0. Local coordinates put the centroid at the origin; pieces are never
mirrored, so a side index names the same edge in every pose.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

UNIT = 4.0
R2 = math.sqrt(2.0)
COLLINEAR_TOLERANCE = 0.05
ANGLE_TOLERANCE = math.radians(2.0)
MIN_OVERLAP_FRACTION = 0.25
OVERLAP_DEPTH = 0.05
SEPARATION = 6.0

Vec = tuple[float, float]

PIECE_NAMES = ("large_triangle_1", "large_triangle_2", "medium_triangle", "small_triangle_1",
               "small_triangle_2", "square", "parallelogram")


@dataclass(frozen=True, slots=True)
class TPose:
    """Rigid motion of a piece: rotation about its centroid, then translation."""

    x: float
    y: float
    theta: float


def _triangle(leg: float) -> list[Vec]:
    # Right angle at v0; clockwise in a y-up frame: up the first leg, across, back.
    return [(0.0, 0.0), (0.0, leg), (leg, 0.0)]


def _raw_model(label: str) -> list[Vec]:
    a = UNIT
    if label.startswith("large_triangle"):
        return _triangle(2 * a)
    if label == "medium_triangle":
        return _triangle(R2 * a)
    if label.startswith("small_triangle"):
        return _triangle(a)
    if label == "square":
        return [(0.0, 0.0), (0.0, a), (a, a), (a, 0.0)]
    if label == "parallelogram":
        # Acute vertex v0, long side 0 at 45 degrees, short side 3 along the x axis.
        return [(0.0, 0.0), (a, a), (2 * a, a), (a, 0.0)]
    raise KeyError(label)


@cache
def piece_model(label: str) -> tuple[Vec, ...]:
    """Canonical vertices of a piece (clockwise from the canonical vertex), centred."""
    pts = _raw_model(label)
    cx, cy = _centroid(pts)
    return tuple((x - cx, y - cy) for x, y in pts)


def _centroid(pts: list[Vec]) -> Vec:
    area = cx = cy = 0.0
    n = len(pts)
    for i in range(n):
        x0, y0 = pts[i]
        x1, y1 = pts[(i + 1) % n]
        cross = x0 * y1 - x1 * y0
        area += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    area /= 2
    return cx / (6 * area), cy / (6 * area)


def signed_area(pts: list[Vec] | tuple[Vec, ...]) -> float:
    n = len(pts)
    return sum(pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1]
               for i in range(n)) / 2


def placed(label: str, pose: TPose) -> list[Vec]:
    """World vertices of a piece in a pose."""
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    return [(pose.x + c * x - s * y, pose.y + s * x + c * y) for x, y in piece_model(label)]


def side(vertices: list[Vec], index: int) -> tuple[Vec, Vec]:
    return vertices[index], vertices[(index + 1) % len(vertices)]


def side_length(label: str, index: int) -> float:
    a, b = side(list(piece_model(label)), index)
    return math.dist(a, b)


def align_pose(label: str, side_index: int, target_vertices: list[Vec],
               target_side: int) -> TPose:
    """Pose putting side `side_index` of a piece against a target side.

    Outward normals opposite (the side directions are antiparallel, as both outlines run
    clockwise) and midpoints coincide.
    """
    model = list(piece_model(label))
    a, b = side(model, side_index)
    c, d = side(target_vertices, target_side)
    own = math.atan2(b[1] - a[1], b[0] - a[0])
    want = math.atan2(c[1] - d[1], c[0] - d[0])
    theta = _wrap(want - own)
    cos, sin = math.cos(theta), math.sin(theta)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    rx, ry = cos * mx - sin * my, sin * mx + cos * my
    tx, ty = (c[0] + d[0]) / 2, (c[1] + d[1]) / 2
    return TPose(tx - rx, ty - ry, theta)


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def sides_touch(p: tuple[Vec, Vec], q: tuple[Vec, Vec], *,
                max_angle: float = ANGLE_TOLERANCE, max_distance: float = COLLINEAR_TOLERANCE,
                min_overlap: float = MIN_OVERLAP_FRACTION) -> bool:
    """Two sides touch: facing (antiparallel within `max_angle` radians), collinear
    within `max_distance`, and sharing more than `min_overlap` of the shorter side.

    Perception calls this with looser tolerances for measured (pixel) geometry.
    """
    (ax, ay), (bx, by) = p
    (cx, cy), (dx, dy) = q
    lp, lq = math.dist(p[0], p[1]), math.dist(q[0], q[1])
    if lp < 1e-9 or lq < 1e-9:
        return False
    ux, uy = (bx - ax) / lp, (by - ay) / lp
    vx, vy = (dx - cx) / lq, (dy - cy) / lq
    if ux * vx + uy * vy > -math.cos(max_angle):
        return False  # not facing: outward normals are not opposite
    for px, py in (q[0], q[1]):
        if abs((px - ax) * uy - (py - ay) * ux) > max_distance:
            return False
    t0 = (cx - ax) * ux + (cy - ay) * uy
    t1 = (dx - ax) * ux + (dy - ay) * uy
    overlap = min(lp, max(t0, t1)) - max(0.0, min(t0, t1))
    return overlap > min_overlap * min(lp, lq)


def touching_sides(p_vertices: list[Vec], q_vertices: list[Vec]) -> list[tuple[int, int]]:
    """Every (side of p, side of q) pair that touches."""
    out = []
    for i in range(len(p_vertices)):
        for j in range(len(q_vertices)):
            if sides_touch(side(p_vertices, i), side(q_vertices, j)):
                out.append((i, j))
    return out


def overlap_depth(p: list[Vec], q: list[Vec]) -> float:
    """How deep two convex polygons overlap (0 when they only touch or are apart).

    Separating axes over both polygons' edge normals. Used on the pairs the physics
    engine reports as in contact, because its penetration depth is unreliable for
    congruent pieces lying exactly on top of each other (it reports 0).
    """
    depth = math.inf
    for poly in (p, q):
        n = len(poly)
        for i in range(n):
            (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % n]
            length = math.hypot(x1 - x0, y1 - y0)
            nx, ny = (y1 - y0) / length, (x0 - x1) / length
            a = [x * nx + y * ny for x, y in p]
            b = [x * nx + y * ny for x, y in q]
            overlap = min(max(a), max(b)) - max(min(a), min(b))
            if overlap <= 0:
                return 0.0
            depth = min(depth, overlap)
    return depth
