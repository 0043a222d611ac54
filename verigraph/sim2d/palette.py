"""Colour names -> BGR, shared by the renderer and (later) perception.

Each object class draws in its dictionary colour; a node's `attrs.color` overrides it
(blocks carry their colour there, or in their id). Unknown names fall back to a fixed
grey so that a render never depends on anything but the world state.
"""

from __future__ import annotations

import zlib

BGR = tuple[int, int, int]

COLORS: dict[str, BGR] = {
    # furniture
    "brown": (30, 75, 140),
    "walnut": (40, 50, 95),
    "tan": (140, 180, 210),
    "gray": (150, 150, 150),
    "black": (35, 35, 35),
    "wood": (95, 160, 205),
    # tableware and kitchen objects
    "white": (245, 245, 245),
    "blue": (200, 90, 30),
    "red": (40, 40, 210),
    "green": (60, 160, 50),
    "yellow": (40, 210, 240),
    "orange": (30, 140, 250),
    "purple": (160, 50, 130),
    "cyan": (210, 200, 40),
    "pink": (180, 130, 250),
    "navy": (110, 40, 20),
    "silver": (200, 195, 190),
    "steel": (140, 120, 100),
    "slate": (120, 100, 70),
    "teal": (128, 128, 0),
    "darkgray": (80, 80, 80),
    "lime": (50, 220, 150),
    "magenta": (200, 40, 200),
    "olive": (30, 130, 130),
    "maroon": (30, 30, 120),
    "beige": (190, 220, 235),
}
# Household kinds (docs/worlds.md, Household worlds) draw in colours of their own, kept
# out of COLORS: perception's tabletop catalogue is built from COLORS, so a kitchen,
# blocks or tableware render reads exactly as before; `perception.relate.household`
# reads these separately.
HOUSEHOLD_COLORS: dict[str, BGR] = {
    "ivory": (195, 255, 135),
    "oak": (0, 60, 45),
    "charcoal": (75, 15, 105),
    "chrome": (255, 180, 45),
    "cardboard": (120, 135, 255),
    "amber": (15, 90, 255),
    "cream": (120, 180, 135),
    "wheat": (120, 225, 150),
    "gold": (0, 255, 240),
}
# A door of an openable container, and the lit element of a toggleable object that is
# on (an object that is off shows no element: it looks as it always did). These and
# the household colours were picked greedily, each as far (CIELAB) from the palette,
# the wall, the floor, the outline and each other as a shade near its name allows
# (door and lit at least 36 units from everything, the fixed kinds' 35).
DOOR: BGR = (120, 0, 255)
LIT: BGR = (150, 255, 240)
FALLBACK: BGR = (120, 120, 120)
BLOCK_COLORS = ("red", "blue", "green", "yellow", "purple", "orange", "cyan", "pink", "lime",
                "magenta", "olive", "maroon")

BACKGROUND: BGR = (235, 228, 222)
FLOOR: BGR = (105, 115, 125)
OUTLINE: BGR = (25, 25, 25)
TANGRAM_BACKGROUND: BGR = (250, 250, 250)


def object_color(node_id: str, attrs_color: object, class_color: str | None) -> BGR:
    """An object's colour: `attrs.color`, else its class colour, else a colour named in
    its id (`red_block`), else one picked from the id (stable across runs), so equal
    blocks without colours still look distinct."""
    if isinstance(attrs_color, str) and attrs_color.strip().lower().replace(" ", "") in COLORS:
        return bgr(attrs_color)
    if class_color:
        return bgr(class_color)
    for token in node_id.lower().split("_"):
        if token in COLORS:
            return COLORS[token]
    return COLORS[BLOCK_COLORS[zlib.crc32(node_id.encode()) % len(BLOCK_COLORS)]]


def bgr(name: str | None) -> BGR:
    """BGR triple for a colour name (case and spaces ignored), or the fallback grey."""
    if not name:
        return FALLBACK
    key = name.strip().lower().replace(" ", "")
    return COLORS.get(key) or HOUSEHOLD_COLORS.get(key, FALLBACK)
