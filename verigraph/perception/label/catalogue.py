"""What each dictionary object looks like in a render: its colour and expected shape.

The detectors ask two questions of the dictionary D: which labels can a region of this
colour be, and how large and how hollow should it look. Sizes come from the same body
specs the simulator builds (so a wider pan in the dictionary is a wider pan here);
objects without a class colour (blocks) can be any block colour.
"""

from __future__ import annotations

from dataclasses import dataclass

from verigraph.graph.dictionary import Dictionary
from verigraph.sim2d import palette
from verigraph.sim2d.bodies import FURNITURE_TOP, movable_spec


@dataclass(frozen=True, slots=True)
class ObjectModel:
    """One label in one colour: what the labeller compares a region against."""

    label: str
    colour: str
    fixed: bool
    width: float
    height: float
    area: float
    perimeter: float
    container: bool
    surface: bool
    own_colour: bool  # False: the colour is per instance (blocks), so it goes in attrs

    def pixel_area(self, scale: float) -> float:
        """Most pixels the object's fill can cover at a scale (thin parts rasterise wide)."""
        return self.area * scale * scale + self.perimeter * scale

    @property
    def long_side(self) -> float:
        return max(self.width, self.height)

    @property
    def short_side(self) -> float:
        return min(self.width, self.height)


def _colour_key(name: str) -> str:
    return name.strip().lower().replace(" ", "")


_MODELS: dict[int, tuple[Dictionary, tuple[ObjectModel, ...]]] = {}
CACHE_SIZE = 32


def object_models(dictionary: Dictionary) -> tuple[ObjectModel, ...]:
    """Every (label, colour) a tabletop render of this dictionary can show (cached per
    dictionary object: dictionaries hold dicts, so they cannot be hashed)."""
    hit = _MODELS.get(id(dictionary))
    if hit is not None and hit[0] is dictionary:
        return hit[1]
    models = _build_models(dictionary)
    if len(_MODELS) >= CACHE_SIZE:
        _MODELS.clear()
    _MODELS[id(dictionary)] = (dictionary, models)
    return models


def _build_models(dictionary: Dictionary) -> tuple[ObjectModel, ...]:
    out: list[ObjectModel] = []
    for label, props in sorted(dictionary.objects.items()):
        if props.sides is not None or props.room:
            continue  # tangram pieces live in the top view; a room is never drawn
        colours = [props.color] if props.color else list(palette.BLOCK_COLORS)
        if props.movable:
            spec = movable_spec(label, props)
            area = sum(_area(p) for p in spec.parts)
            perimeter = sum(_perimeter(p) for p in spec.parts)
            width, height = spec.width, spec.height
        else:
            width = float(props.width or 40.0)
            height = FURNITURE_TOP  # what sim2d draws a carrying surface as
            area = width * height
            perimeter = 2 * (width + height)
        for colour in colours:
            key = _colour_key(colour)
            if key not in palette.COLORS:
                continue
            out.append(ObjectModel(label=label, colour=key, fixed=not props.movable,
                                   width=width, height=height, area=area,
                                   perimeter=perimeter,
                                   container=props.container, surface=props.surface,
                                   own_colour=props.color is not None))
    return tuple(out)


def models_by_colour(dictionary: Dictionary) -> dict[str, list[ObjectModel]]:
    """Object models grouped by the colour they are drawn in."""
    grouped: dict[str, list[ObjectModel]] = {}
    for model in object_models(dictionary):
        grouped.setdefault(model.colour, []).append(model)
    return grouped


def _perimeter(poly: tuple[tuple[float, float], ...]) -> float:
    n = len(poly)
    return sum(((poly[i][0] - poly[(i + 1) % n][0]) ** 2
                + (poly[i][1] - poly[(i + 1) % n][1]) ** 2) ** 0.5 for i in range(n))


def _area(poly: tuple[tuple[float, float], ...]) -> float:
    n = len(poly)
    return abs(sum(poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1]
                   for i in range(n))) / 2
