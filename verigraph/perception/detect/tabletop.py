"""Tabletop detector (side view): objects from colour regions, named by a labeller.

Steps: find the floor band; collect colour fragments (plus solid black furniture and
background-coloured objects such as a white plate, which need their own rules); read
the image scale off the furniture, whose carrying top stands `FURNITURE_TOP` world
units above the floor; join fragments of one object that its contents cut apart (a
pot's walls around a knife) using the object's expected size; name each object.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import cv2
import numpy as np

from verigraph.perception.config import PerceptionConfig
from verigraph.perception.detect.colors import BACKGROUND, FLOOR, UNKNOWN, ColourTable
from verigraph.perception.detect.occlusion import (
    Occluder,
    hidden_mask,
    join_across,
    join_occluded,
)
from verigraph.perception.detect.regions import (
    Region,
    colour_fragments,
    core_area,
    dark_blobs,
    enclosed_bright,
)
from verigraph.perception.label.catalogue import ObjectModel
from verigraph.perception.label.labelling import Labeller
from verigraph.sim2d.bodies import FURNITURE_TOP

FLOOR_ROW_FRACTION = 0.3
MERGE_SLACK = 1.2
MERGE_PIXELS = 4.0
CLIPPED_MEAN = 248.0
ACTIVITY_PAD = 4
RIM = 4  # px: widest ring of blurred edge that is taken for a rim, not an object


@dataclass(slots=True)
class Detection:
    """One object found in the image."""

    region: Region
    colour: str
    model: ObjectModel
    score: float = 1.0
    id: str = ""

    @property
    def label(self) -> str:
        return self.model.label

    @property
    def fixed(self) -> bool:
        return self.model.fixed


@dataclass(slots=True)
class PerceivedTabletop:
    """What the tabletop detector saw: objects, the floor line and the scale."""

    detections: list[Detection]
    floor_row: int | None
    scale: float
    warnings: list[str] = field(default_factory=list)


def floor_row(classes: np.ndarray) -> int | None:
    """Top row of the floor band at the bottom of the image, or None."""
    share = (classes == FLOOR).mean(axis=1)
    rows = np.nonzero(share < FLOOR_ROW_FRACTION)[0]
    if len(rows) == len(share):
        return None
    last_clear = int(rows.max()) if len(rows) else -1
    if last_clear >= len(share) - 1:
        return None
    return last_clear + 1


def estimate_scale(fragments: Sequence[Region], table: ColourTable,
                   models: dict[str, list[ObjectModel]], floor: int | None) -> float:
    """Pixels per world unit from furniture standing on the floor (0 if none is seen)."""
    if floor is None:
        return 0.0
    best = 0.0
    best_area = 0
    for r in fragments:
        colour = table.names[r.cls]
        if not any(m.fixed for m in models.get(colour, [])):
            continue
        if r.y1 < floor - 4 or r.area <= best_area:
            continue
        top = r.y0 - 1.5  # the fill starts half an outline below the true edge
        best, best_area = (floor - top) / FURNITURE_TOP, r.area
    return best


def _expected_pixels(models: Sequence[ObjectModel], scale: float) -> tuple[float, float]:
    """Longest side and largest area (px) any movable model of a colour can show."""
    movable = [m for m in models if not m.fixed]
    if not movable or scale <= 0:
        return float("inf"), float("inf")
    return (max(m.long_side for m in movable) * scale,
            max(m.pixel_area(scale) for m in movable))


def assemble(fragments: list[Region], table: ColourTable,
             models: dict[str, list[ObjectModel]], scale: float, classes: np.ndarray,
             notes: list[str], occluders: Sequence[Occluder] = ()) -> list[Region]:
    """Join fragments of one colour that together still fit one object (furniture:
    parts an occluder split; notes say where), and parts on both sides of a band in
    front of them."""
    out: list[Region] = []
    by_class: dict[int, list[Region]] = {}
    for r in fragments:
        by_class.setdefault(r.cls, []).append(r)
    for cls, parts in by_class.items():
        colour_models = models.get(table.names[cls], [])
        parts, across = join_across(parts, occluders, classes.shape)
        notes.extend(dict.fromkeys(across))
        if all(m.fixed for m in colour_models):
            joined, found = join_occluded(parts, classes)  # drawn in one piece
            out.extend(joined)
            notes.extend(found)
            continue
        longest, largest = _expected_pixels(colour_models, scale)
        objects: list[Region] = []
        for part in sorted(parts, key=lambda r: -r.area):
            target = None
            for i, obj in enumerate(objects):
                w, h = obj.union_box(part)
                if max(w, h) <= MERGE_SLACK * longest + MERGE_PIXELS and \
                        obj.area + part.area <= MERGE_SLACK * largest:
                    target = i
                    break
            if target is None:
                objects.append(part)
            else:
                objects[target] = objects[target].merged(part)
        out.extend(objects)
    return out


def bright_objects(candidates: list[Region], image: np.ndarray, table: ColourTable,
                   models: dict[str, list[ObjectModel]], scale: float, *,
                   restored: bool = False) -> list[Region]:
    """Enclosed background-coloured areas that are white/silver objects: closer to the
    object's colour than to the background's, and no larger than the object. A pocket
    whose pixels are all clipped says nothing about its colour; it must at least be
    half as long as the object.

    A pocket's colour is the mean of its brightest quarter, because blur darkens a thin
    white plate towards its outline; in a picture whose motion blur was undone
    (`restored`) the deconvolution's ringing brightens faint echoes of every edge, so
    the brightest quarter of a silver pot reads as wall: there a pocket the brightest
    quarter takes for wall is judged again by its median pixel, which ringing does not
    move (a restored thin white plate still needs the brightest quarter)."""
    options = [c for c in table.bright if table.names[c] in models]
    if not options:
        return []
    expected = {c: _expected_pixels(models[table.names[c]], scale) for c in options}

    def too_large(region: Region, c: int) -> bool:
        longest, largest = expected[c]
        size = max(region.width, region.height)
        return size > MERGE_SLACK * longest + MERGE_PIXELS or region.area > MERGE_SLACK * largest

    out = []
    for region in candidates:
        if all(too_large(region, c) for c in options):
            continue  # larger than any bright object, whatever its colour (the wall)
        pixels = image[region.y0:region.y1, region.x0:region.x1][region.mask].reshape(-1, 3)
        bright = pixels.astype(np.float32)
        level = bright.sum(axis=1)
        mean = bright[level >= np.percentile(level, 75)].mean(axis=0)
        best = _nearest(mean, [BACKGROUND, *options], table)
        if best == BACKGROUND and restored:
            mean = np.median(bright, axis=0)
            best = _nearest(mean, [BACKGROUND, *options], table)
        if best == BACKGROUND:
            continue
        if too_large(region, best):
            continue
        longest = expected[best][0]
        if float(mean.max()) >= CLIPPED_MEAN and max(region.width, region.height) < 0.5 * longest:
            continue
        out.append(Region(best, region.x0, region.y0, region.mask))
    return out


def without_rims(regions: list[Region]) -> list[Region]:
    """The regions less any that is only a rim around another: a region whose box
    holds another's and reaches at most `RIM` px beyond it on every side, with fewer
    pixels than half of that other one. A strong blur, or the ringing of its
    restoration, leaves such a ring of a darker shade around a flat object (a maroon
    ring around a red block); no object of the dictionaries fits around another that
    closely with less than half its pixels (a cup holding a spoon is far larger than
    the spoon)."""
    def rim_of(r: Region, o: Region) -> bool:
        return (r is not o and r.area < 0.5 * o.area
                and r.x0 <= o.x0 and r.y0 <= o.y0 and o.x1 <= r.x1 and o.y1 <= r.y1
                and o.x0 - r.x0 <= RIM and o.y0 - r.y0 <= RIM
                and r.x1 - o.x1 <= RIM and r.y1 - o.y1 <= RIM)
    return [r for r in regions if not any(rim_of(r, o) for o in regions)]


def _nearest(colour: np.ndarray, classes: Sequence[int], table: ColourTable) -> int:
    return min(classes, key=lambda c: float(np.linalg.norm(colour - np.array(table.bgr[c]))))


def detect_tabletop(image: np.ndarray, classes: np.ndarray, table: ColourTable,
                    models: dict[str, list[ObjectModel]], labeller: Labeller,
                    config: PerceptionConfig, occluders: Sequence[Occluder] = (),
                    *, restored: bool = False) -> PerceivedTabletop:
    """Objects in a side-view image whose pixels are already classified (an occluder's
    pixels as UNKNOWN); `restored`: its motion blur was undone (see `bright_objects`)."""
    warnings: list[str] = []
    floor = floor_row(classes)
    # Work inside the box around everything that is neither wall nor floor: a tabletop
    # render is mostly empty wall, and connected components cost per pixel.
    x0, y0, x1, y1 = activity_box(classes)
    crop_image, crop_classes = image[y0:y1, x0:x1], classes[y0:y1, x0:x1]
    found = colour_fragments(crop_image, crop_classes, table, min_core=config.min_core_pixels)
    black = table.index("black")
    if black is not None and "black" in models:
        found += dark_blobs(crop_classes, black, min_area=20 * config.min_core_pixels)
    fragments = [r.shifted(x0, y0) for r in found]
    scale = estimate_scale(fragments, table, models, floor)
    if scale <= 0:
        warnings.append("no furniture standing on a floor was found, so object sizes are "
                        "not checked; labels rest on colour alone")
    if table.bright and any(table.names[c] in models for c in table.bright):
        pockets = [r.shifted(x0, y0) for r in enclosed_bright(
            crop_image, crop_classes, table, min_core=config.min_core_pixels)]
        fragments += bright_objects(pockets, image, table, models, scale,
                                    restored=restored)
    objects = assemble(fragments, table, models, scale, classes, warnings, occluders)
    objects = without_rims(objects)
    all_models = [m for ms in models.values() for m in ms]
    objects = [r for r in objects if table.names[r.cls] in models]
    labels = labeller.label(image, objects, [table.names[r.cls] for r in objects],
                            all_models, scale)
    detections = []
    for region, (model, score) in zip(objects, labels, strict=True):
        if not model.fixed and scale > 0 and \
                region.area < config.min_visible_fraction * model.area * scale * scale:
            continue  # specks of an object colour (noise, blurred edges of others)
        if model.fixed and not _solid_furniture(region, scale):
            continue  # a sliver in a furniture colour (JPEG bleeding, blurred edges)
        detections.append(Detection(region=region, colour=model.colour, model=model,
                                    score=score))
    unknown = _unknown_regions(classes, config, hidden_mask(occluders, classes.shape))
    if unknown:
        warnings.append(f"{unknown} region(s) have colours no dictionary object is drawn "
                        "in; they were left out")
    return PerceivedTabletop(detections=detections, floor_row=floor, scale=scale,
                             warnings=list(dict.fromkeys(warnings)))


def activity_box(classes: np.ndarray, pad: int = ACTIVITY_PAD) -> tuple[int, int, int, int]:
    """(x0, y0, x1, y1) around every pixel that is not wall or floor, padded with wall."""
    busy = (classes != BACKGROUND) & (classes != FLOOR)
    rows = np.flatnonzero(busy.any(axis=1))
    cols = np.flatnonzero(busy.any(axis=0))
    h, w = classes.shape
    if len(rows) == 0:
        return 0, 0, w, h
    return (max(0, int(cols[0]) - pad), max(0, int(rows[0]) - pad),
            min(w, int(cols[-1]) + 1 + pad), min(h, int(rows[-1]) + 1 + pad))


def _solid_furniture(region: Region, scale: float) -> bool:
    """Furniture is thick: it has a core of at least a 2x2 world-unit square (or 8x8 px
    when the scale is unknown)."""
    side = max(5, int(round(2 * scale))) if scale > 0 else 8
    side = min(side, 15)
    padded = np.pad(region.mask.view(np.uint8), 1)
    core = cv2.erode(padded, np.ones((side, side), np.uint8))
    return bool(np.count_nonzero(core))


def _unknown_regions(classes: np.ndarray, config: PerceptionConfig,
                     hidden: np.ndarray | None) -> int:
    """Large areas in colours no object of the dictionary has (an unknown object), not
    counting what an occluder covers."""
    unknown = classes == UNKNOWN
    if hidden is not None:
        unknown &= ~hidden
    if np.count_nonzero(unknown) < 50 * config.min_core_pixels:
        return 0
    n, labels, stats, _ = cv2.connectedComponentsWithStats(unknown.view(np.uint8),
                                                           connectivity=4)
    count = 0
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if area >= 50 * config.min_core_pixels and \
                core_area(labels[y:y + h, x:x + w] == i) >= 25 * config.min_core_pixels:
            count += 1
    return count

