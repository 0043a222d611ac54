"""Household states from a side view: doors open or closed, switches on or off.

sim2d draws household furniture (fridge, cabinet, sink, ...) in colours of their own
(`palette.HOUSEHOLD_COLORS`, far from the tabletop palette), a door of an openable
container in `palette.DOOR` hinged at its right rim (closed: lying across the
opening; open: standing upright beside it) and the lit element of a toggleable object
that is on in `palette.LIT` (on its left leg, `LAMP_HEIGHT` units above its
foot). This reads them back:

- furniture: connected areas of a household colour (a colour two kinds share is read
  as the first kind and marked unsure);
- a door: the `DOOR` area at the furniture's hinge corner; lying flat (at least twice
  as wide as tall) is closed, upright open; shorter than 80% of the furniture's width
  means partly hidden, shorter than half or neither flat nor upright is unsure;
- a switch: lit pixels over the object's box against the lamp's area; at least half
  is on; none, with the object's own colour showing in the lamp's disc and nothing
  but it, its outline, the wall or the floor, is off; anything else (a partly hidden,
  washed-out or recoloured lamp) is unsure.

Every reading has a confidence, written under `object.key` (`fridge.open`,
`stove.toggled_on`); below `CONFIDENT` it is listed as uncertain with the reason, so
the graph is a proposal, never silently wrong. Renders without household colours,
doors or a lit element are left exactly as they were read.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import cv2
import numpy as np

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.model import Node
from verigraph.perception.result import CONFIDENT, DetectedObject, Uncertain
from verigraph.sim2d import palette
from verigraph.sim2d.household import DOOR_THICKNESS, LAMP_HEIGHT, LAMP_RADIUS

COLOUR_TOLERANCE = 14.0  # CIELAB distance for a pixel to count as a household colour
FLOOR_UNITS = 3.0  # the floor band under a side view is 3 world units high
MIN_FURNITURE_UNITS = 6.0  # a piece of furniture covers at least 6 square units
DOOR_SHOWN = 0.8
DOOR_HALF = 0.5
LIT_ON = 0.5
OWN_SHOWN = 0.3
OTHER_SHOWN = 0.15
SURE, PARTLY, UNSURE, UNSEEN = 0.95, 0.7, 0.35, 0.2
SCALE_AGREEMENT = 0.15

Box = tuple[int, int, int, int]


@dataclass(slots=True)
class HouseholdReading:
    """What was read: new furniture nodes with their boxes, states of objects already
    detected, confidences and doubts, and notes for the warnings."""

    nodes: list[Node] = field(default_factory=list)
    objects: list[DetectedObject] = field(default_factory=list)
    states: dict[str, dict[str, bool]] = field(default_factory=dict)
    confidence: dict[str, float] = field(default_factory=dict)
    uncertain: list[Uncertain] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def sure(self) -> int:
        """How many readings are sure (what a second reading must beat)."""
        return sum(c >= CONFIDENT for c in self.confidence.values())

    @property
    def found(self) -> bool:
        return bool(self.nodes or self.states or self.uncertain)

    def note(self, obj: str, key: str, value: bool | None, confidence: float,
             reason: str) -> None:
        item = f"{obj}.{key}"
        self.confidence[item] = confidence
        if value is not None:
            self.states.setdefault(obj, {})[key] = value
        if confidence < CONFIDENT:
            self.uncertain.append(Uncertain(item=item, confidence=confidence, reason=reason))


def _lab(image: np.ndarray) -> np.ndarray:
    lab = cv2.cvtColor(image, cv2.COLOR_BGR2LAB).astype(np.float32)
    lab[..., 0] *= 100.0 / 255.0
    lab[..., 1:] -= 128.0
    return lab


def _mask(lab: np.ndarray, colour: palette.BGR) -> np.ndarray:
    ref = _lab(np.array([[colour]], dtype=np.uint8))[0, 0]
    return np.asarray(np.linalg.norm(lab - ref, axis=2) < COLOUR_TOLERANCE)


def _areas(mask: np.ndarray, min_area: int) -> list[tuple[Box, int]]:
    """Boxes (x0, y0, x1, y1; x1, y1 exclusive) and pixel counts of connected areas."""
    n, _, stats, _ = cv2.connectedComponentsWithStats(mask.astype(np.uint8), connectivity=8)
    out = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if area >= min_area:
            out.append(((x, y, x + w, y + h), area))
    return out


def floor_scale(image: np.ndarray) -> float:
    """Pixels per world unit from the floor band (3 units high in a sim2d side view)."""
    lab = _lab(image)
    floor = _mask(lab, palette.FLOOR).mean(axis=1)
    rows = 0
    for share in floor[::-1]:
        if share < 0.5:
            break
        rows += 1
    return rows / FLOOR_UNITS


def household_kinds(dictionary: Dictionary) -> dict[str, list[str]]:
    """Household colour -> the fixed kinds drawn in it (dictionary order)."""
    out: dict[str, list[str]] = {}
    for label, props in dictionary.objects.items():
        key = (props.color or "").strip().lower().replace(" ", "")
        if not props.movable and not props.room and key in palette.HOUSEHOLD_COLORS:
            out.setdefault(key, []).append(label)
    return out


def read_household(image: np.ndarray, dictionary: Dictionary,
                   objects: list[DetectedObject], scale: float = 0.0) -> HouseholdReading:
    """Household furniture, doors and switches in a side view (see the module doc)."""
    reading = HouseholdReading()
    kinds = household_kinds(dictionary)
    toggleable = [o for o in objects if (p := dictionary.objects.get(o.label)) is not None
                  and p.toggleable]
    if not kinds and not toggleable:
        return reading
    lab = _lab(image)
    floor = floor_scale(image)
    # The floor band gives the scale unless the picture is cropped or turned (then the
    # detected objects' sizes disagree, and they win).
    if floor > 0 and (scale <= 0 or abs(floor / scale - 1.0) <= SCALE_AGREEMENT):
        scale = floor
    if scale <= 0:
        return reading
    lit = _mask(lab, palette.LIT)
    lamps = _areas(lit, max(4, int((LAMP_RADIUS * scale) ** 2 / 4)))
    doors = _areas(_mask(lab, palette.DOOR), max(4, int((DOOR_THICKNESS * scale) ** 2)))
    taken = {o.id for o in objects}
    pieces: list[tuple[str, Box, palette.BGR]] = []
    for colour, labels in kinds.items():
        bgr = palette.HOUSEHOLD_COLORS[colour]
        for box, _ in sorted(_areas(_mask(lab, bgr), int(MIN_FURNITURE_UNITS * scale ** 2))):
            label = labels[0]
            node_id = _unique(label, taken)
            reading.nodes.append(Node(id=node_id, label=label))
            reading.objects.append(DetectedObject(id=node_id, label=label, colour=colour,
                                                  box=box, score=1.0 / len(labels)))
            if len(labels) > 1:
                reading.confidence[node_id] = UNSURE
                reading.uncertain.append(Uncertain(
                    item=node_id, confidence=UNSURE,
                    reason=f"{colour} is the colour of {' and '.join(labels)}: read as "
                           f"{label}"))
            pieces.append((node_id, box, bgr))
    if not pieces and not doors and not lamps:
        return reading  # nothing household in view: the reading stays as it was
    for node_id, box, bgr in pieces:
        props = dictionary.objects[reading.objects[[o.id for o in reading.objects]
                                                   .index(node_id)].label]
        if props.openable:
            _read_door(reading, node_id, box, doors, scale)
        if props.toggleable:
            _read_switch(reading, node_id, box, lab, lit, bgr, scale)
    for obj in toggleable:
        _read_switch(reading, obj.id, obj.box, lab, lit, palette.bgr(obj.colour), scale,
                     off_too=bool(pieces or doors))
    if pieces:
        reading.warnings.append(
            f"household furniture seen ({', '.join(sorted(n.id for n in reading.nodes))}): "
            "its doors and switches are read, what stands in, on, under or next to it and "
            "the rooms are not; confirm them or send the graph")
    return reading


def _unique(label: str, taken: set[str]) -> str:
    node_id, k = label, 2
    while node_id in taken:
        node_id, k = f"{label}_{k}", k + 1
    taken.add(node_id)
    return node_id


def _read_door(reading: HouseholdReading, obj: str, box: Box,
               doors: list[tuple[Box, int]], scale: float) -> None:
    """The door at the furniture's hinge (top-right corner): flat closed, upright open."""
    x0, y0, x1, _ = box
    reach = max(4.0, 0.03 * (x1 - x0))
    # Closed or open, a door ends at the hinge: its bottom on the rim, its right end at
    # the furniture's right side (or one door's thickness past it).
    near = [d for d, _ in doors if abs(d[3] - y0) <= reach
            and -reach <= d[2] - x1 <= reach + min(d[2] - d[0], d[3] - d[1])]
    if not near:
        reading.note(obj, "open", None, UNSEEN,
                     "no door is seen at its hinge (hidden, or out of the picture): open or "
                     "closed cannot be read")
        return
    dx0, dy0, dx1, dy1 = max(near, key=lambda d: (d[2] - d[0]) * (d[3] - d[1]))
    w, h = dx1 - dx0, dy1 - dy0
    length = x1 - x0
    if w >= 2 * h:
        value, shown = False, w / length
    elif h >= 2 * w:
        value, shown = True, h / length
    else:
        reading.note(obj, "open", None, UNSURE,
                     f"its door shows {w}x{h} px, neither lying flat nor upright")
        return
    word = "open" if value else "closed"
    if shown >= DOOR_SHOWN:
        reading.note(obj, "open", value, SURE, f"door {word}")
    elif shown >= DOOR_HALF:
        reading.note(obj, "open", value, PARTLY,
                     f"door {word}, {shown:.0%} of it seen (part hidden)")
    else:
        reading.note(obj, "open", value, UNSURE,
                     f"only {shown:.0%} of its door is seen: it looks {word}")


def _read_switch(reading: HouseholdReading, obj: str, box: Box, lab: np.ndarray,
                 lit: np.ndarray, own: palette.BGR, scale: float, *,
                 off_too: bool = True) -> None:
    """The share of lit pixels around the lamp (on the left leg, see sim2d.household).
    Without `off_too` (a tabletop with no household furniture, where off is the
    default) only a lamp that is lit, or partly lit, is reported."""
    x0, _, _, y1 = box
    cx = x0 + 2.0 * scale
    cy = y1 - LAMP_HEIGHT * scale
    r = max(2.0, LAMP_RADIUS * scale)
    h, w = lit.shape
    ys, xs = np.ogrid[:h, :w]
    disc = (xs - cx) ** 2 + (ys - cy) ** 2 <= r * r
    area = max(1.0, math.pi * r * r)
    # Lit pixels are counted over the object's box (a box read off pixels, or a scale,
    # may be a little off), its own colour in the lamp's disc.
    bx0, by0, bx1, by1 = box
    near = (xs >= bx0 - r) & (xs < bx1 + r) & (ys >= by0 - r) & (ys < by1 + r)
    share = float(np.count_nonzero(lit & near)) / area
    mine = float(np.count_nonzero(_mask(lab, own) & disc)) / area
    # Off needs the disc to show only the object, its outline, the wall or the floor:
    # a lit lamp whose colour is off (a hue shift) shows as something else there.
    scenery = _mask(lab, own) | _mask(lab, palette.OUTLINE) | _mask(lab, palette.BACKGROUND) \
        | _mask(lab, palette.FLOOR)
    other = float(np.count_nonzero(disc & ~scenery)) / area
    if share == 0.0 and not off_too:
        return
    if share >= LIT_ON:
        reading.note(obj, "toggled_on", True, SURE, "lit")
    elif share == 0.0 and mine >= OWN_SHOWN and other <= OTHER_SHOWN:
        reading.note(obj, "toggled_on", False, SURE, "not lit")
    elif share > 0.0:
        reading.note(obj, "toggled_on", True, UNSURE,
                     f"its lamp is only {share:.0%} lit (part hidden, or washed out)")
    elif other > OTHER_SHOWN:
        reading.note(obj, "toggled_on", None, UNSEEN,
                     f"{other:.0%} of where its lamp is shows a colour of neither the object "
                     "nor the scenery: on or off cannot be read")
    else:
        reading.note(obj, "toggled_on", None, UNSEEN,
                     "its lamp is not seen (hidden): on or off cannot be read")
