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
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from verigraph.perception.metrics import score_graph
from verigraph.perception.pipeline import perceive_image
from verigraph.sim2d.degrade import Degradation, degrade
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
            spoilt = degrade(scene.world.render(), spec, seed=scene.seed)
            result = perceive_image(spoilt, dictionary=family)
            right = score_graph(result.graph, scene.graph, family).exact
            out.append(PoleOutcome(family, scene.seed, name, right, not result.confident))
    return out
