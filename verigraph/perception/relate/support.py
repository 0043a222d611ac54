"""Relations `on` and `in` from pixels, by the simulator's own readback rules.

For every object the direct supporter is what lies right under its bottom edge (within
two outline widths), preferring the one under its centre, as physics prefers the
contact under the centre of mass. The relation then follows `sim2d.readback` itself
(`support_relation`, `resolve_supports`, the same `DirectSupport` and cavity floor
tolerance), with a container's cavity taken as its convex hull: resting on a surface is
`on` unless the centre sits inside that object's cavity; resting on a container is
`in`; resting on something that is neither (a spoon) is `in` the smallest container
around the centre, else whatever that thing rests on. Only what pixels show differently
from contacts lives here: the downward scan and the cavities as hulls.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from verigraph.perception.detect.tabletop import Detection
from verigraph.sim2d.readback import (
    CAVITY_FLOOR_TOLERANCE,
    DirectSupport,
    resolve_supports,
    support_relation,
)

NOTHING, FLOOR_ID = 0, -1
UNDER_TOLERANCE = 2.0
WIDE_GAP_FACTOR = 2


def label_map(shape: tuple[int, int], detections: Sequence[Detection],
              floor_row: int | None) -> np.ndarray:
    """int32 map: detection index + 1 per pixel, FLOOR_ID below the floor line, else 0."""
    out = np.zeros(shape, dtype=np.int32)
    if floor_row is not None:
        out[floor_row:, :] = FLOOR_ID
    for i, d in enumerate(detections):
        r = d.region
        view = out[r.y0:r.y1, r.x0:r.x1]
        view[r.mask] = i + 1
    return out


def support_in_image(index: int, detections: Sequence[Detection], labels: np.ndarray,
                   gap: int) -> DirectSupport:
    """Scan down from every bottom pixel of the object for the first other thing.

    The supporter is named by its detection id (ids are assigned before supports are
    read); the span is the contact's first and last image column."""
    r = detections[index].region
    rows = r.mask.shape[0]
    # Lowest pixel of the object in each column (columns without pixels are skipped).
    has = r.mask.any(axis=0)
    lowest = rows - 1 - np.argmax(r.mask[::-1, :], axis=0)
    cols = np.nonzero(has)[0]
    if len(cols) == 0:
        return DirectSupport(None, None)
    h = labels.shape[0]
    hit_values: list[np.ndarray] = []  # what each column meets, in the order met
    hit_columns: list[np.ndarray] = []
    for step in range(1, gap + 1):
        ys = r.y0 + lowest[cols] + step
        ok = ys < h
        if not ok.any():
            break
        xs = r.x0 + cols
        hits = np.zeros(len(cols), dtype=np.int32)
        hits[ok] = labels[ys[ok], xs[ok]]
        new = (hits != NOTHING) & (hits != index + 1)
        hit_values.append(hits[new])
        hit_columns.append(cols[new])
        cols = cols[~new]
        if len(cols) == 0:
            break
    found: dict[int, np.ndarray] = {}  # thing -> its columns, things in order first met
    if hit_values:
        values, columns = np.concatenate(hit_values), np.concatenate(hit_columns)
        distinct, first = np.unique(values, return_index=True)
        for value in distinct[np.argsort(first)]:
            found[int(value)] = columns[values == value]
    if not found:
        return DirectSupport(None, None)
    com_x = detections[index].region.centroid()[0] - r.x0
    near = max(UNDER_TOLERANCE, 0.1 * r.width)
    best: tuple[tuple[bool, int], int] | None = None
    for value, cs in found.items():
        # Columns, not their span: blur can leave a sliver of the table's colour on
        # both sides of a block, which spans everything but touches little.
        score = (bool(np.any(np.abs(cs - com_x) <= near)), len(cs))
        if best is None or score > best[0]:
            best = (score, value)
    assert best is not None
    value = best[1]
    span = (float(r.x0 + found[value].min()), float(r.x0 + found[value].max()))
    if value == FLOOR_ID:
        return DirectSupport(None, span, on_floor=True)
    return DirectSupport(detections[value - 1].id, span)


class Cavities:
    """Convex hulls of containers: a point inside one is inside its cavity."""

    def __init__(self, detections: Sequence[Detection], tolerance: float) -> None:
        self.tolerance = tolerance
        self.bottoms = [d.region.y1 for d in detections]
        self.hulls: dict[int, tuple[np.ndarray, float]] = {}
        for i, d in enumerate(detections):
            if d.model.container:
                hull = d.region.hull()
                self.hulls[i] = (hull, float(cv2.contourArea(hull)))

    def holds(self, container: int, point: tuple[float, float]) -> bool:
        entry = self.hulls.get(container)
        if entry is None:
            return False
        dist = cv2.pointPolygonTest(entry[0], (float(point[0]), float(point[1])), True)
        return bool(dist >= -self.tolerance)

    def nested(self, inner: int, outer: int, centres: Sequence[tuple[float, float]]) -> bool:
        """Whether object `inner` stands inside container `outer`."""
        return self.bottoms[inner] < self.bottoms[outer] and self.holds(outer, centres[inner])

    def innermost(self, point: tuple[float, float], exclude: int) -> int | None:
        """The innermost container around a point of object `exclude` (the one standing
        highest: a pot in a pan is inside the pan), among those whose bottom is below the
        object's (what a container stands in cannot be inside it)."""
        inside = [(self.bottoms[i], area, i) for i, (_, area) in self.hulls.items()
                  if i != exclude and self.bottoms[exclude] < self.bottoms[i]
                  and self.holds(i, point)]
        return min(inside)[2] if inside else None


def infer_supports(detections: Sequence[Detection], labels: np.ndarray, *, gap: int,
                   scale: float) -> dict[str, tuple[str, str]]:
    """(relation, supporter id) for every detection that rests on or in another
    (detection ids must be assigned; `scale` is pixels per world unit)."""
    index = {d.id: i for i, d in enumerate(detections)}
    direct = [support_in_image(i, detections, labels, gap) for i in range(len(detections))]
    for i, d in enumerate(direct):
        # Everything in a settled scene rests on something: when blur or JPEG widen
        # the dark band under an object beyond the gap, look a little further.
        if d.supporter is None and not d.on_floor:
            direct[i] = support_in_image(i, detections, labels, WIDE_GAP_FACTOR * gap)
    # The simulator's cavity floor tolerance in pixels, plus one for the outline.
    cavities = Cavities(detections, CAVITY_FLOOR_TOLERANCE * scale + 1.0)
    centres = [d.region.centroid() for d in detections]
    for i, d in enumerate(direct):
        # A container's floor can hide under outlines in a small render: an object whose
        # centre is in a cavity rests in that container, unless what it was found
        # resting on stands inside the container too (a cup on a plate in a bowl).
        holder = cavities.innermost(centres[i], exclude=i)
        sup = index[d.supporter] if d.supporter is not None else None
        if holder is None or sup == holder or detections[i].model.fixed:
            continue
        if sup is not None and cavities.nested(sup, holder, centres):
            continue
        direct[i] = DirectSupport(detections[holder].id, None)

    def relation(obj: str, sup: str) -> str | None:
        model = detections[index[sup]].model
        return support_relation(
            surface=model.surface, container=model.container,
            centre_in_cavity=model.container and cavities.holds(index[sup],
                                                                centres[index[obj]]))

    def holder_of(obj: str) -> str | None:
        inside = cavities.innermost(centres[index[obj]], exclude=index[obj])
        return detections[inside].id if inside is not None else None

    return resolve_supports({d.id: s for d, s in zip(detections, direct, strict=True)},
                            relation, holder_of)
