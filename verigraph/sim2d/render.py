"""OpenCV renderer: a world's current state drawn as a BGR image, nothing else.

Every object is drawn with its own physics outline, filled in its class colour (a
node's `attrs.color` wins, as for blocks) with a thin dark border; furniture is drawn
first, the floor is a grey band. Drawing reads poses only and never changes the world,
so the same state always gives the same pixels. The tabletop camera frames the
furniture (plus headroom for stacks) so frames of one episode line up.

Image size: a caller may fix width and height; a side view of a kitchen is five times
wider than tall, so squeezing it into 640x480 leaves most of the frame empty sky and a
cup wall two pixels wide. Without a size, a tabletop is drawn at `PIXELS_PER_UNIT` (the
image takes the scene's own shape, at least `MIN_WIDTH` wide, at most `MAX_SIDE` on
either side); with only one side given, the other follows the scene's shape. The
tangram's top view is compact and keeps 640x480 by default.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Protocol

import cv2
import numpy as np
import pymunk

from verigraph.graph.dictionary import builtin_dictionary
from verigraph.graph.model import Node
from verigraph.sim2d import palette, physics
from verigraph.sim2d.bodies import FURNITURE_TOP
from verigraph.sim2d.household import LAMP_RADIUS, Door, Household, lamp_centre
from verigraph.sim2d.scene import TabletopScene

SHIFT = 4
SCALE = 1 << SHIFT
HEADROOM = 24.0
MARGIN = 3.0
PIXELS_PER_UNIT = 8.0  # a 0.5-unit cup wall is 4 px: still visible under blur and JPEG
MIN_WIDTH = 640
MAX_SIDE = 2048
DEFAULT_SIZE = (640, 480)

View = tuple[float, float, float, float]  # x0, y0, x1, y1 in world units


class TabletopPicture(Protocol):
    """What a side view is drawn from: the bodies of a scene and the nodes' colours.

    A plain description, so the renderer needs no world class (the worlds call it)."""

    @property
    def scene(self) -> TabletopScene: ...

    @property
    def nodes(self) -> Sequence[Node]: ...

    @property
    def household(self) -> Household: ...


class TangramPicture(Protocol):
    """What a top view is drawn from: the pieces, their labels and placed outlines."""

    @property
    def nodes(self) -> Sequence[Node]: ...

    @property
    def labels(self) -> Mapping[str, str]: ...

    def vertices(self, piece: str) -> list[tuple[float, float]]: ...


def frame_size(view: View, width: int | None = None, height: int | None = None, *,
               default: tuple[int, int] | None = None) -> tuple[int, int]:
    """(width, height) of the image for a view: the caller's size where given, the other
    side from the view's shape (at most MAX_SIDE: past that the scene is centred in a
    frame of another shape); with neither, `default` or the view at PIXELS_PER_UNIT."""
    x0, y0, x1, y1 = view
    view_w, view_h = max(x1 - x0, 1e-6), max(y1 - y0, 1e-6)
    if width is not None and height is not None:
        return width, height
    if width is not None:
        return width, min(MAX_SIDE, max(1, round(width * view_h / view_w)))
    if height is not None:
        return min(MAX_SIDE, max(1, round(height * view_w / view_h))), height
    if default is not None:
        return default
    scale = max(PIXELS_PER_UNIT, MIN_WIDTH / view_w)
    scale = min(scale, MAX_SIDE / view_w, MAX_SIDE / view_h)
    return max(1, round(view_w * scale)), max(1, round(view_h * scale))


class _Camera:
    """World rectangle -> pixels, uniform scale, centred, y up in the world."""

    def __init__(self, view: View, width: int, height: int, *, bottom: bool = False) -> None:
        x0, y0, x1, y1 = view
        self.s = min(width / (x1 - x0), height / (y1 - y0))
        self.ox = (width - (x1 - x0) * self.s) / 2 - x0 * self.s
        # Side views keep the floor at the bottom edge; spare height goes to the sky.
        self.oy = height + y0 * self.s if bottom else \
            (height - (y1 - y0) * self.s) / 2 + y1 * self.s

    def points(self, poly: Sequence[tuple[float, float]]) -> np.ndarray:
        arr = np.asarray(poly, dtype=np.float64)
        px = (self.ox + arr[:, 0] * self.s) * SCALE
        py = (self.oy - arr[:, 1] * self.s) * SCALE
        return np.round(np.stack([px, py], axis=1)).astype(np.int32)

    def pixel(self, x: float, y: float) -> tuple[int, int]:
        return int(round(self.ox + x * self.s)), int(round(self.oy - y * self.s))


def _draw_polys(img: np.ndarray, cam: _Camera, polys: list[list[tuple[float, float]]],
                color: palette.BGR) -> None:
    pts = [cam.points(p) for p in polys]
    cv2.polylines(img, pts, True, palette.OUTLINE, 3, cv2.LINE_8, SHIFT)
    for p in pts:  # one call per convex part: fillPoly would XOR overlapping parts
        cv2.fillConvexPoly(img, p, color, cv2.LINE_8, SHIFT)


def _label(img: np.ndarray, text: str, at: tuple[int, int]) -> None:
    """Dark text, or light text where it lands on something dark (a black stove)."""
    (w, h), _ = cv2.getTextSize(text, cv2.FONT_HERSHEY_SIMPLEX, 0.4, 1)
    x, y = at
    under = img[max(0, y - h):max(0, y + 1), max(0, x):max(0, x + w)]
    dark = under.size > 0 and float(under.mean()) < 90
    colour = (235, 235, 235) if dark else (20, 20, 20)
    cv2.putText(img, text, at, cv2.FONT_HERSHEY_SIMPLEX, 0.4, colour, 1, cv2.LINE_AA)


def _door_points(door: Door) -> list[tuple[float, float]]:
    return [(float(v.x), float(v.y)) for shape in door.body.shapes
            if isinstance(shape, pymunk.Poly) for v in shape.get_vertices()]


def tabletop_view(world: TabletopPicture) -> View:
    """Furniture extent with headroom for stacks; grows if something stands higher."""
    things = [t for t in world.scene.things.values() if t.body.space is not None]
    fixed = [t.bounds() for t in things if t.fixed] or [t.bounds() for t in things] \
        or [(0.0, 0.0, 40.0, FURNITURE_TOP)]
    doors = [max(door.body.local_to_world(p).y for p in _door_points(door))
             for door in world.household.doors.values()]  # an open door stands up
    top = max([b[3] for b in (t.bounds() for t in things)] + [FURNITURE_TOP] + doors)
    x0 = min(b[0] for b in fixed) - MARGIN
    x1 = max(b[2] for b in fixed) + MARGIN
    y1 = max(top + MARGIN, FURNITURE_TOP + HEADROOM)
    return x0, -3.0, x1, y1


def _tabletop_frame(world: TabletopPicture, width: int | None, height: int | None,
                    view: View | None = None) -> tuple[_Camera, int, int]:
    """The side-view camera and frame size a tabletop is drawn (and boxed) with."""
    view = view or tabletop_view(world)
    width, height = frame_size(view, width, height)
    return _Camera(view, width, height, bottom=True), width, height


def render_tabletop(world: TabletopPicture, width: int | None = None, height: int | None = None,
                    *, labels: bool = False, view: View | None = None) -> np.ndarray:
    cam, width, height = _tabletop_frame(world, width, height, view)
    img = np.empty((height, width, 3), dtype=np.uint8)
    img[:] = palette.BACKGROUND
    floor_y = cam.pixel(0.0, 0.0)[1]
    img[max(floor_y, 0):, :] = palette.FLOOR
    colors = {n.id: n.attrs.get("color") for n in world.nodes}
    things = sorted(world.scene.things.values(), key=lambda t: not t.fixed)
    for t in things:
        if t.body.space is None:
            continue
        color = palette.object_color(t.id, colors.get(t.id), t.props.color)
        _draw_polys(img, cam, physics.world_polygons(t.body), color)
    _draw_household(img, cam, world)
    if labels:
        for t in things:
            if t.body.space is None:
                continue
            left, _, right, top = t.bounds()
            x, y = cam.pixel((left + right) / 2, top)
            if t.fixed:
                y = cam.pixel(0.0, t.spec.top - 1.5)[1] + 12
                x = cam.pixel(left + 1.0, 0.0)[0]
            else:
                x -= 3 * len(t.id)
                y -= 4
            _label(img, t.id, (x, y))
    return img


def _draw_household(img: np.ndarray, cam: _Camera, world: TabletopPicture) -> None:
    """Doors (closed across the opening, open upright beside it) and the lit element of
    everything that is switched on; nothing for what is off."""
    house = world.household
    for door in house.doors.values():
        _draw_polys(img, cam, physics.world_polygons(door.body), palette.DOOR)
    for obj, on in house.switches.items():
        thing = world.scene.things.get(obj)
        if not on or thing is None or thing.body.space is None:
            continue
        x, y = lamp_centre(thing)
        centre = cam.points([(x, y)])[0]
        radius = int(round(LAMP_RADIUS * cam.s * SCALE))
        cv2.circle(img, (int(centre[0]), int(centre[1])), radius, palette.OUTLINE, 3,
                   cv2.LINE_8, SHIFT)
        cv2.circle(img, (int(centre[0]), int(centre[1])), radius, palette.LIT, -1,
                   cv2.LINE_8, SHIFT)


def tabletop_boxes(world: TabletopPicture, width: int | None = None, height: int | None = None
                   ) -> dict[str, tuple[int, int, int, int]]:
    """Pixel boxes (x0, y0, x1, y1) of the objects in `render_tabletop`'s picture of the
    same size, so a caller can mark objects (e.g. the ones blocking an action)."""
    cam, _, _ = _tabletop_frame(world, width, height)
    boxes = {}
    for t in world.scene.things.values():
        if t.body.space is None:
            continue
        left, bottom, right, top = t.bounds()
        (x0, y0), (x1, y1) = cam.pixel(left, top), cam.pixel(right, bottom)
        boxes[t.id] = (x0, y0, x1, y1)
    return boxes


def _tangram_frame(world: TangramPicture, width: int | None, height: int | None
                   ) -> tuple[dict[str, list[tuple[float, float]]], _Camera, int, int]:
    """The pieces' outlines and the top-view camera framing all of them."""
    polys = {n.id: world.vertices(n.id) for n in world.nodes}
    xs = [x for poly in polys.values() for x, _ in poly] or [0.0, 1.0]
    ys = [y for poly in polys.values() for _, y in poly] or [0.0, 1.0]
    m = 2 * MARGIN
    view = (min(xs) - m, min(ys) - m, max(xs) + m, max(ys) + m)
    width, height = frame_size(view, width, height, default=DEFAULT_SIZE)
    return polys, _Camera(view, width, height), width, height


def tangram_boxes(world: TangramPicture, width: int | None = None, height: int | None = None
                  ) -> dict[str, tuple[int, int, int, int]]:
    """Pixel boxes (x0, y0, x1, y1) of the pieces (their polygons' bounds) in
    `render_tangram`'s picture of the same size, as `tabletop_boxes` for a side view."""
    polys, cam, _, _ = _tangram_frame(world, width, height)
    boxes = {}
    for piece, poly in polys.items():
        corners = [cam.pixel(x, y) for x, y in poly]
        boxes[piece] = (min(x for x, _ in corners), min(y for _, y in corners),
                        max(x for x, _ in corners), max(y for _, y in corners))
    return boxes


def render_tangram(world: TangramPicture, width: int | None = None, height: int | None = None,
                   *, labels: bool = False) -> np.ndarray:
    polys, cam, width, height = _tangram_frame(world, width, height)
    img = np.empty((height, width, 3), dtype=np.uint8)
    img[:] = palette.TANGRAM_BACKGROUND
    tangram = builtin_dictionary("tangram")
    for node in world.nodes:
        color = palette.object_color(node.id, node.attrs.get("color"),
                                     tangram.properties(world.labels[node.id]).color)
        _draw_polys(img, cam, [polys[node.id]], color)
    if labels:
        for node in world.nodes:
            poly = polys[node.id]
            cx = sum(x for x, _ in poly) / len(poly)
            cy = sum(y for _, y in poly) / len(poly)
            for i in range(len(poly)):
                (ax, ay), (bx, by) = poly[i], poly[(i + 1) % len(poly)]
                mx, my = (ax + bx) / 2 * 0.8 + cx * 0.2, (ay + by) / 2 * 0.8 + cy * 0.2
                px, py = cam.pixel(mx, my)
                _label(img, str(i), (px - 4, py + 4))
    return img


def side_by_side(images: Sequence[np.ndarray], titles: Sequence[str] | None = None,
                 gap: int = 8) -> np.ndarray:
    """Images of equal height next to each other, with optional titles on top."""
    h = max(i.shape[0] for i in images)
    band = 28 if titles else 0
    total = sum(i.shape[1] for i in images) + gap * (len(images) - 1)
    out = np.full((h + band, total, 3), 255, dtype=np.uint8)
    x = 0
    for k, image in enumerate(images):
        out[band:band + image.shape[0], x:x + image.shape[1]] = image
        if titles:
            cv2.putText(out, titles[k], (x + 8, 20), cv2.FONT_HERSHEY_SIMPLEX, 0.6,
                        (20, 20, 20), 1, cv2.LINE_AA)
        x += image.shape[1] + gap
    return out


def encode_png(image: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", image)
    if not ok:  # pragma: no cover - OpenCV only fails on invalid arrays
        raise ValueError("PNG encoding failed")
    return bytes(buf.tobytes())
