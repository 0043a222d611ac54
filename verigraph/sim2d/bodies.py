"""Side-view shapes of tabletop objects, built from the dictionary's width and height.

One `BodySpec` per object: convex parts in the object's own frame (origin at the
bottom centre, y up), the cavity of a container, and the height of the face that
carries things. Containers are real hollow bodies (a floor and two walls), so an
object `in` a bowl sits between its walls; fixed furniture stands on the floor with
its carrying top at `FURNITURE_TOP`. Shapes differ by class (a tapered kettle, a dish
that widens upwards, a bowl with slanted walls) so renders stay readable.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from verigraph.graph.dictionary import ObjectProperties

Point = tuple[float, float]
Polygon = tuple[Point, ...]
Cavity = tuple[float, float, float, float]  # x_min, x_max, floor top, rim top (local)

FURNITURE_TOP = 14.0
DEFAULT_SIZE = (6.0, 4.0)
DEFAULT_FURNITURE_SIZE = (40.0, 4.0)
Kind = Literal["box", "container", "furniture"]


@dataclass(frozen=True, slots=True)
class BodySpec:
    """Geometry of one object class (or one piece of furniture) in its local frame."""

    label: str
    kind: Kind
    width: float
    height: float
    parts: tuple[Polygon, ...]
    top: float
    cavity: Cavity | None = None
    wall: float = 0.0
    floor: float = 0.0  # a container's inner width at its floor (a bowl's is under its mouth's)

    @property
    def mass_centre(self) -> tuple[float, float, float]:
        """(mass, x, y) of the parts at unit density, in the local frame.

        Kept here because pymunk only reports a body's mass while it is in a space, and
        a lifted object must still be weighed when its placement is chosen."""
        total = mx = my = 0.0
        for part in self.parts:
            a, cx, cy = _area_centroid(part)
            total += a
            mx += a * cx
            my += a * cy
        return total, mx / total, my / total

    @property
    def thin(self) -> bool:
        """Long and flat (cutlery): may stand upright in a narrow container."""
        return self.kind == "box" and self.width >= 4 * self.height


def _area_centroid(poly: Polygon) -> tuple[float, float, float]:
    area = cx = cy = 0.0
    for i in range(len(poly)):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % len(poly)]
        cross = x0 * y1 - x1 * y0
        area += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    area /= 2
    return abs(area), cx / (6 * area), cy / (6 * area)


def _box(x0: float, y0: float, x1: float, y1: float) -> Polygon:
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


def _tapered(w: float, h: float, top_ratio: float) -> Polygon:
    """Trapezoid standing on its long side (kettle, lid) or on its short side (dish)."""
    b, t = (w / 2, w * top_ratio / 2) if top_ratio <= 1 else (w / (2 * top_ratio), w / 2)
    return ((-b, 0.0), (b, 0.0), (t, h), (-t, h))


def wall_thickness(width: float) -> float:
    return min(1.0, max(0.5, 0.07 * width))


def _container(label: str, w: float, h: float) -> BodySpec:
    t = wall_thickness(w)
    half = w / 2
    parts: tuple[Polygon, ...]
    if label == "bowl":
        # Slanted walls: the floor is narrower than the mouth.
        foot = 0.45 * w
        parts = (_box(-foot, 0.0, foot, t),
                 ((-foot, 0.0), (-foot + t, 0.0), (-half + t, h), (-half, h)),
                 ((foot - t, 0.0), (foot, 0.0), (half, h), (half - t, h)))
        cavity = (-(half - t), half - t, t, h)
        floor = 2 * (foot - t)
    else:
        parts = (_box(-half, 0.0, half, t), _box(-half, t, -half + t, h),
                 _box(half - t, t, half, h))
        cavity = (-(half - t), half - t, t, h)
        floor = 2 * (half - t)
    return BodySpec(label=label, kind="container", width=w, height=h, parts=parts, top=h,
                    cavity=cavity, wall=t, floor=floor)


def movable_spec(label: str, props: ObjectProperties) -> BodySpec:
    """Shape of a movable object from its dictionary size and properties."""
    w = float(props.width or DEFAULT_SIZE[0])
    h = float(props.height or DEFAULT_SIZE[1])
    if props.container:
        return _container(label, w, h)
    if label in ("kettle",):
        part = _tapered(w, h, 0.6)
    elif label in ("lid",):
        part = _tapered(w, h, 0.45)
    elif label in ("plate",):
        part = _tapered(w, h, 1.2)
    else:
        part = _box(-w / 2, 0.0, w / 2, h)
    return BodySpec(label=label, kind="box", width=w, height=h, parts=(part,), top=h)


def furniture_spec(label: str, props: ObjectProperties, width: float, *,
                   legs: bool = False, depth: float | None = None) -> BodySpec:
    """Fixed furniture standing on the floor, carrying things at `FURNITURE_TOP`.

    Tables and desks stand on legs, counters and stoves on a cabinet, a shelf on a
    post; a fixed container is a bin on legs and a fixed non-surface is a plain block.
    In a household every surface stands on two legs (`legs`), so that things fit
    `under` it, and a bin is at least `depth` deep (so a door closes over what it holds).
    """
    h = float(props.height or DEFAULT_FURNITURE_SIZE[1])
    top = FURNITURE_TOP
    half = width / 2
    if not props.surface and not props.container:
        return BodySpec(label=label, kind="furniture", width=width, height=h,
                        parts=(_box(-half, 0.0, half, h),), top=h)
    slab = _box(-half, top - h, half, top)
    parts: tuple[Polygon, ...]
    if props.container:
        t = wall_thickness(width)
        bin_h = max(h, 6.0, depth or 0.0)
        parts = (_box(-half, top - t, half, top), _box(-half, top, -half + t, top + bin_h),
                 _box(half - t, top, half, top + bin_h), _box(-half + 1, 0, -half + 3, top - t),
                 _box(half - 3, 0, half - 1, top - t))
        return BodySpec(label=label, kind="furniture", width=width, height=top + bin_h,
                        parts=parts, top=top + bin_h,
                        cavity=(-(half - t), half - t, top, top + bin_h), wall=t)
    if legs:
        parts = (slab, _box(-half + 1.0, 0.0, -half + 3.0, top - h),
                 _box(half - 3.0, 0.0, half - 1.0, top - h))
    elif label in ("counter", "stove"):
        parts = (slab, _box(-half + 1.0, 0.0, half - 1.0, top - h))
    elif label == "shelf":
        parts = (slab, _box(-1.5, 0.0, 1.5, top - h), _box(-5.0, 0.0, 5.0, 1.0))
    elif label == "desk":
        panel = max(6.0, 0.25 * width)
        parts = (slab, _box(-half, 0.0, -half + panel, top - h),
                 _box(half - 2.0, 0.0, half, top - h))
    else:
        parts = (slab, _box(-half + 1.0, 0.0, -half + 3.0, top - h),
                 _box(half - 3.0, 0.0, half - 1.0, top - h))
    return BodySpec(label=label, kind="furniture", width=width, height=top, parts=parts,
                    top=top)


def under_span(spec: BodySpec, props: ObjectProperties) -> tuple[float, float, float] | None:
    """(x0, x1, ceiling) in the local frame: the free floor between a surface's legs and
    the underside of its top, or None if nothing fits under it (a cabinet base)."""
    if spec.kind != "furniture" or not props.surface or props.container:
        return None
    legs = [p for p in spec.parts[1:] if p[0][1] == 0.0]
    if len(legs) != 2:
        return None
    x0 = max(x for x, _ in legs[0])
    x1 = min(x for x, _ in legs[1])
    ceiling = spec.top - float(props.height or DEFAULT_FURNITURE_SIZE[1])
    return (x0, x1, ceiling) if x1 - x0 > 1.0 else None
