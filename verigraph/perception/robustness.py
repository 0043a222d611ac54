"""The robustness suite: what a real camera does to a render, at a mild and a strong
level, and how perception copes (exact accuracy and the silent-wrong rate).

A wrong graph that comes with a warning (or uncertain items) is forgivable: the agent
is told to check it. A wrong graph that comes with neither is the failure this suite
counts as **silent-wrong**. Mild levels are what a decent camera in a lit room gives;
strong ones are well past that (and perception is expected to say so, not to be right).

`SHAKE_AND_OCCLUDERS` adds what a camera on a moving arm sees: motion blur of several
lengths and directions, bars of several widths, tilts and positions in front of the
scene (the arm itself), and a blob (a hand). Under an occluder a wrong graph must also
name the objects the occluder hides (`CellResult.unnamed` counts those that do not).

`pole_sweep` puts a plain bar hanging from the top edge (a pole, a cable, an arm link)
in front of every scene, in every colour of the palette (so it often looks like a
known object) and at several widths and lengths, one combination per scene.

`bar_sweep` generalises it: a plain bar reaching in from the top, the left or the right
edge, square to it or tilted, in every palette colour and in the wall's own colour,
at several widths and lengths (`draw_bar`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.perception.metrics import score_graph
from verigraph.perception.pipeline import perceive_image
from verigraph.perception.result import DetectedObject
from verigraph.sim2d import palette
from verigraph.sim2d.degrade import Degradation, degrade
from verigraph.sim2d.degrade_ops import content_box
from verigraph.sim2d.generator import generate_scene
from verigraph.sim2d.palette import COLORS

SUITE: dict[str, dict[str, Degradation]] = {
    "hue": {"mild": Degradation(hue=6.0), "strong": Degradation(hue=25.0)},
    "gamma": {"mild": Degradation(gamma=1.25), "strong": Degradation(gamma=1.8)},
    "white balance": {"mild": Degradation(white_balance=(0.9, 1.0, 1.1)),
                      "strong": Degradation(white_balance=(0.7, 1.0, 1.3))},
    "wall colour": {"mild": Degradation(wall=(212, 208, 205)),
                    "strong": Degradation(wall=(170, 215, 175))},
    "rotation": {"mild": Degradation(rotation=2.0), "strong": Degradation(rotation=8.0)},
    "scale": {"mild": Degradation(scale=0.75), "strong": Degradation(scale=0.5)},
    "crop": {"mild": Degradation(crop=0.1), "strong": Degradation(crop=0.3)},
    "perspective": {"mild": Degradation(perspective=0.015),
                    "strong": Degradation(perspective=0.05)},
    "noise": {"mild": Degradation(noise=8.0), "strong": Degradation(noise=20.0)},
    "blur": {"mild": Degradation(blur=1.0), "strong": Degradation(motion_blur=9)},
    "occlusion": {"mild": Degradation(occlusion=0.01), "strong": Degradation(occlusion=0.04)},
}
DESCRIPTIONS = {
    "hue": "hue turned 6 / 25 degrees",
    "gamma": "tone curve exponent 1.25 / 1.8",
    "white balance": "B, R gains 0.9, 1.1 / 0.7, 1.3",
    "wall colour": "wall repainted darker grey / pale green",
    "rotation": "camera roll 2 / 8 degrees",
    "scale": "image scaled 0.75 / 0.5",
    "crop": "up to 10% / 30% of each side cut (never into objects)",
    "perspective": "corners moved up to 1.5% / 5% (tilt)",
    "noise": "Gaussian noise sigma 8 / 20",
    "blur": "Gaussian sigma 1 px / 9-px motion blur",
    "occlusion": "grey bar 1% / 4% of the width in front of the scene",
}
SHAKE_AND_OCCLUDERS: dict[str, dict[str, Degradation]] = {
    "motion blur": {
        "5 px": Degradation(motion_blur=5),
        "9 px": Degradation(motion_blur=9),
        "9 px horizontal": Degradation(motion_blur=9, motion_angle=0.0),
        "9 px vertical": Degradation(motion_blur=9, motion_angle=90.0),
        "13 px": Degradation(motion_blur=13),
    },
    "bar": {
        "2% vertical": Degradation(occlusion=0.02),
        "6% vertical": Degradation(occlusion=0.06),
        "4% through the middle": Degradation(occlusion=0.04, occlusion_at=0.5),
        "3% horizontal": Degradation(occlusion=0.03, occlusion_angle=90.0),
        "3% tilted 30 deg": Degradation(occlusion=0.03, occlusion_angle=30.0),
    },
    "blob": {
        "radius 15%": Degradation(blob=0.15),
        "radius 30%": Degradation(blob=0.3),
    },
}
OCCLUDERS = ("occlusion", "bar", "blob")  # degradations that put something in front
FAMILIES = ("blocks", "kitchen", "tableware", "tangram")
FIRST_SEED = 20_000
SHAKE_SEED = 40_000  # SHAKE_AND_OCCLUDERS runs on scenes of its own
POLE_SEED = 70_000  # the pole sweep (the pole finder was tuned on 60000-60311)
POLE_COLOURS = tuple(COLORS)  # every colour of the palette
POLE_WIDTHS = (0.01, 0.02, 0.04)  # shares of the image width
POLE_LENGTHS = (0.35, 0.6, 0.85, 1.0)  # shares of the image height, from the top edge


@dataclass(frozen=True, slots=True)
class CellResult:
    """Outcome counts of one (family, degradation, level) cell."""

    family: str
    degradation: str
    level: str
    images: int
    exact: int
    flagged: int  # results that carried warnings or uncertain items
    silent_wrong: int
    unnamed: int = 0  # wrong graphs that name no occluded object

    @property
    def exact_rate(self) -> float:
        return self.exact / self.images if self.images else 0.0

    @property
    def silent_wrong_rate(self) -> float:
        return self.silent_wrong / self.images if self.images else 0.0


def run_suite(families: Iterable[str] = FAMILIES, n: int = 20,
              degradations: Iterable[str] | None = None,
              levels: Iterable[str] | None = ("mild", "strong"),
              first_seed: int = FIRST_SEED,
              suite: dict[str, dict[str, Degradation]] | None = None) -> list[CellResult]:
    """Perceive n generated scenes per family under every degradation and level of
    `suite` (default `SUITE`; `levels` None: every level the suite has)."""
    suite = SUITE if suite is None else suite
    names = list(degradations) if degradations is not None else list(suite)
    out = []
    for family in families:
        scenes = [generate_scene(family, first_seed + i) for i in range(n)]
        renders = [scene.world.render() for scene in scenes]
        for name in names:
            for level in (list(suite[name]) if levels is None else levels):
                exact = flagged = silent = unnamed = 0
                for scene, image in zip(scenes, renders, strict=True):
                    spoilt = degrade(image, suite[name][level], seed=scene.seed)
                    result = perceive_image(spoilt, dictionary=family)
                    right = score_graph(result.graph, scene.graph, family).exact
                    exact += right
                    flagged += not result.confident
                    silent += (not right) and result.confident
                    unnamed += (not right) and not result.occluded
                out.append(CellResult(family, name, level, n, exact, flagged, silent,
                                      unnamed))
    return out


def pole_spec(i: int) -> tuple[str, Degradation]:
    """The i-th pole of the sweep: colours cycle fastest, then widths, then lengths,
    so any 26 consecutive scenes see every colour of the palette."""
    colour = POLE_COLOURS[i % len(POLE_COLOURS)]
    rest = i // len(POLE_COLOURS)
    width = POLE_WIDTHS[rest % len(POLE_WIDTHS)]
    length = POLE_LENGTHS[(rest // len(POLE_WIDTHS)) % len(POLE_LENGTHS)]
    return (f"{colour} {width:.0%} wide, {length:.0%} down",
            Degradation(pole=width, pole_length=length, pole_colour=COLORS[colour]))


@dataclass(frozen=True, slots=True)
class PoleOutcome:
    """One scene of the pole sweep: what was put in front, and how perception did."""

    family: str
    seed: int
    pole: str
    exact: bool
    flagged: bool
    posing: bool = False  # the pole was read as an object (see `BarOutcome`)

    @property
    def silent_wrong(self) -> bool:
        return not self.exact and not self.flagged


def pole_sweep(families: Iterable[str] = FAMILIES, n: int = 104,
               first_seed: int = POLE_SEED) -> list[PoleOutcome]:
    """n scenes per family (seeds from `first_seed`), the i-th with `pole_spec(i)`
    in front of it; n = 312 covers every colour, width and length once."""
    out = []
    for family in families:
        for i in range(n):
            scene = generate_scene(family, first_seed + i)
            name, spec = pole_spec(i)
            clean = scene.world.render()
            spoilt = degrade(clean, spec, seed=scene.seed)
            result = perceive_image(spoilt, dictionary=family)
            right = score_graph(result.graph, scene.graph, family).exact
            out.append(PoleOutcome(family, scene.seed, name, right, not result.confident,
                                   _posing(right, result.objects, clean, spoilt)))
    return out


BAR_SEED = 80_000  # the bar sweep
BAR_EDGES = ("top", "left", "right")  # the edge a bar reaches in from
BAR_TILTS = (0.0, 20.0, -20.0)  # degrees from square to that edge
WALL = "wall"  # a bar in the picture's background colour (the wall, the tangram table)
BAR_COLOURS = (*POLE_COLOURS, WALL)
BAR_WIDTHS = POLE_WIDTHS  # shares of the image's extent along the edge
BAR_LENGTHS = POLE_LENGTHS  # shares of the image's extent across that edge


@dataclass(frozen=True, slots=True)
class Bar:
    """A plain bar in front of the scene: the edge it reaches in from, its tilt from
    square to that edge (degrees), colour name (a palette colour or `WALL`), width (a
    share of the image's extent along that edge), how far in it reaches (a share of
    the image's height for the top edge, of its width for a side, measured square to
    the edge) and where it enters (0-1 along the content box)."""

    edge: str
    tilt: float
    colour: str
    width: float
    length: float
    at: float

    def describe(self) -> str:
        tilt = f" tilted {self.tilt:+.0f} deg" if self.tilt else ""
        return (f"{self.colour} {self.width:.0%} wide from the {self.edge}{tilt}, "
                f"{self.length:.0%} in")


def bar_spec(i: int, seed: int) -> Bar:
    """The i-th bar of the sweep: colours cycle fastest, then widths, then lengths (so
    any 27 consecutive scenes see every colour, and 324 every combination); the edge,
    tilt and entry point are drawn from the scene's seed."""
    colour = BAR_COLOURS[i % len(BAR_COLOURS)]
    rest = i // len(BAR_COLOURS)
    width = BAR_WIDTHS[rest % len(BAR_WIDTHS)]
    length = BAR_LENGTHS[(rest // len(BAR_WIDTHS)) % len(BAR_LENGTHS)]
    rng = np.random.default_rng(seed + 1)
    return Bar(edge=BAR_EDGES[int(rng.integers(len(BAR_EDGES)))],
               tilt=BAR_TILTS[int(rng.integers(len(BAR_TILTS)))], colour=colour,
               width=width, length=length, at=float(rng.uniform(0, 1)))


def draw_bar(image: np.ndarray, bar: Bar, *, tangram: bool = False) -> np.ndarray:
    """A copy of a render with `bar` drawn plain in front of it (no outline,
    anti-aliased sides, sub-pixel corners), entering across the content box."""
    h, w = image.shape[:2]
    wall = palette.TANGRAM_BACKGROUND if tangram else palette.BACKGROUND
    x0, y0, x1, y1 = content_box(image, [wall, palette.FLOOR])
    colour = wall if bar.colour == WALL else COLORS[bar.colour]
    width = max(2.0, bar.width * (w if bar.edge == "top" else h))
    t = math.radians(bar.tilt)
    if bar.edge == "top":
        start = np.array([x0 + width / 2 + bar.at * max(1.0, x1 - x0 - width), -2.0])
        inward, depth = np.array([math.sin(t), math.cos(t)]), bar.length * h
    else:
        y = y0 + bar.at * max(1.0, y1 - y0)
        sign = 1.0 if bar.edge == "left" else -1.0
        start = np.array([-2.0 if sign > 0 else w + 1.0, y])
        inward, depth = np.array([sign * math.cos(t), math.sin(t)]), bar.length * w
    end = start + inward * (depth + 2.0) / max(math.cos(t), 1e-6)
    start = start - inward * width  # from beyond the frame: the edge cuts it square
    across = np.array([inward[1], -inward[0]]) * width / 2
    corners = np.array([start - across, end - across, end + across, start + across])
    out = image.copy()
    shift = 4
    cv2.fillConvexPoly(out, np.round(corners * (1 << shift)).astype(np.int32), colour,
                       cv2.LINE_AA, shift)
    return out


@dataclass(frozen=True, slots=True)
class BarOutcome:
    """One scene of the bar sweep: the bar, how perception did, and whether a region
    read as an object lies mostly on the bar (an occluder reported as an object)."""

    family: str
    seed: int
    bar: Bar
    exact: bool
    flagged: bool
    posing: bool = False

    @property
    def silent_wrong(self) -> bool:
        return not self.exact and not self.flagged


POSING_SHARE = 0.6  # share of a detected object's box on the bar that makes it the bar


def bar_sweep(families: Iterable[str] = FAMILIES, n: int = 324,
              first_seed: int = BAR_SEED) -> list[BarOutcome]:
    """n scenes per family (seeds from `first_seed`), the i-th with `bar_spec(i)` in
    front of it."""
    out = []
    for family in families:
        for i in range(n):
            scene = generate_scene(family, first_seed + i)
            bar = bar_spec(i, scene.seed)
            clean = scene.world.render()
            spoilt = draw_bar(clean, bar, tangram=family == "tangram")
            result = perceive_image(spoilt, dictionary=family)
            right = score_graph(result.graph, scene.graph, family).exact
            out.append(BarOutcome(family, scene.seed, bar, right, not result.confident,
                                  _posing(right, result.objects, clean, spoilt)))
    return out


def _posing(right: bool, objects: Iterable[DetectedObject], clean: np.ndarray,
            spoilt: np.ndarray) -> bool:
    """A wrong graph with an object whose box lies mostly (`POSING_SHARE`) on what was
    drawn in front: that occluder itself was read as the object."""
    if right:
        return False
    on_bar = np.any(spoilt != clean, axis=2)
    for o in objects:
        x0, y0, x1, y1 = o.box
        part = on_bar[y0:y1, x0:x1]
        if part.size and float(part.mean()) >= POSING_SHARE:
            return True
    return False
