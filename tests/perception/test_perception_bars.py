"""Plain bars reaching in from the top or a side, square or tilted, in every colour
(the wall's own included): found by their geometry, never read as an object, never a
wrong graph without a warning; objects cut by the frame are no bars. And tangram sides
that meet along part of their length only (a gap the outlines hide) are doubted."""

from __future__ import annotations

import numpy as np
import pytest

from verigraph.perception import perceive_image, score_graph
from verigraph.perception.detect.occlusion import find_poles
from verigraph.perception.result import DetectedObject
from verigraph.perception.robustness import (
    BAR_COLOURS,
    BAR_SEED,
    POLE_SEED,
    POSING_SHARE,
    SUITE,
    Bar,
    bar_spec,
    draw_bar,
    pole_spec,
)
from verigraph.sim2d import palette
from verigraph.sim2d.degrade import degrade
from verigraph.sim2d.generator import generate_scene

pytestmark = pytest.mark.fast

SAMPLE_SEED = 38_200  # scenes no sweep and no tuning used
SCENERY = [palette.BACKGROUND, palette.FLOOR]


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware", "tangram"])
def test_a_bar_of_every_colour_from_any_side_never_gives_a_silent_wrong_graph(
        family: str) -> None:
    """One scene per colour (the palette and the wall's), edges, tilts, widths and
    lengths as the sweep draws them: no wrong graph comes without a warning."""
    silent = []
    for k in range(len(BAR_COLOURS)):
        scene = generate_scene(family, SAMPLE_SEED + k)
        bar = bar_spec(k + len(BAR_COLOURS) * (k % 12), scene.seed)
        image = draw_bar(scene.world.render(), bar, tangram=family == "tangram")
        result = perceive_image(image, dictionary=family)
        if not score_graph(result.graph, scene.graph, family).exact and result.confident:
            silent.append((scene.seed, bar.describe()))
    assert not silent, silent


@pytest.mark.parametrize(("edge", "tilt"), [("left", 0.0), ("right", 0.0), ("left", 20.0),
                                            ("right", -20.0), ("top", 20.0),
                                            ("top", -20.0)])
def test_a_bar_from_a_side_or_tilted_is_found_and_hides_what_it_covers(
        edge: str, tilt: float) -> None:
    """A red bar reaching 60% across a blocks scene from `edge`: found as a bar from
    that edge (in `blocked`), and the graph is exact or flagged."""
    scene = generate_scene("blocks", SAMPLE_SEED + 50)
    bar = Bar(edge=edge, tilt=tilt, colour="red", width=0.02, length=0.6, at=0.4)
    image = draw_bar(scene.world.render(), bar)
    poles = find_poles(image, scenery=SCENERY)
    assert [p.edge for p in poles] == [edge], (bar.describe(), [p.box for p in poles])
    result = perceive_image(image, dictionary="blocks")
    assert any(b.kind == "pole" for b in result.blocked)
    word = "hanging from the top edge" if edge == "top" else f"in from the {edge} edge"
    assert any(word in w for w in result.warnings)
    assert score_graph(result.graph, scene.graph, "blocks").exact or not result.confident


def test_a_tilted_bar_is_followed_to_its_end() -> None:
    """The mask of a bar tilted 20 degrees follows it: its far end lies where the bar
    ends, not below where it entered."""
    scene = generate_scene("blocks", SAMPLE_SEED + 51)
    clean = scene.world.render()
    bar = Bar(edge="top", tilt=20.0, colour="blue", width=0.02, length=0.6, at=0.3)
    image = draw_bar(clean, bar)
    (pole,) = find_poles(image, scenery=SCENERY)
    drawn = np.any(image != clean, axis=2)
    mask = pole.full_mask(drawn.shape)
    assert float(np.mean(mask[drawn])) > 0.95  # the bar is covered ...
    assert np.count_nonzero(mask) < 2.5 * np.count_nonzero(drawn)  # ... and little else
    rows = np.nonzero(drawn.any(axis=1))[0]
    assert pole.box[3] >= rows.max() - 2


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_furniture_cut_by_a_tilted_camera_is_no_bar(family: str) -> None:
    """A roll or a tilt cuts furniture (and what stands on it) off at the sides: the
    frame shows the scene there, outlined, and no bar is reported; under the strong
    tilt (where a cut outline can still pass for a thin dark bar) the graph stays
    right."""
    for k in range(6):
        scene = generate_scene(family, SAMPLE_SEED + 60 + k)
        for name, level in (("rotation", "strong"), ("perspective", "mild")):
            image = degrade(scene.world.render(), SUITE[name][level], seed=scene.seed)
            assert find_poles(image, scenery=SCENERY) == [], (family, scene.seed, name)
        image = degrade(scene.world.render(), SUITE["perspective"]["strong"],
                        seed=scene.seed)
        result = perceive_image(image, dictionary=family)
        assert score_graph(result.graph, scene.graph, family).exact, scene.seed


def test_a_wall_coloured_bar_is_not_read_as_anything() -> None:
    """A bar in the wall's colour does not show at the edge; where it crosses objects
    the result is exact or flagged, never an object made of it."""
    for k in range(6):
        scene = generate_scene("kitchen", SAMPLE_SEED + 70 + k)
        bar = Bar(edge=("top", "left", "right")[k % 3], tilt=0.0, colour="wall",
                  width=0.04, length=1.0, at=0.5)
        result = perceive_image(draw_bar(scene.world.render(), bar), dictionary="kitchen")
        assert score_graph(result.graph, scene.graph, "kitchen").exact or \
            not result.confident, scene.seed


@pytest.mark.parametrize(("seed", "pair"), [(31163, ("small_triangle_1", "small_triangle_2")),
                                            (32803, ("small_triangle_1", "square"))])
def test_a_tangram_contact_along_part_of_a_side_is_doubted(seed: str | int,
                                                           pair: tuple[str, str]) -> None:
    """Two sides running side by side across a gap the outlines fill (a small triangle
    or the square beside a neighbour) meet along part of the shorter side only: the
    contact is listed as uncertain with that reason, so the wrong graph is flagged."""
    scene = generate_scene("tangram", int(seed))
    result = perceive_image(scene.world.render(), dictionary="tangram")
    assert not score_graph(result.graph, scene.graph, "tangram").exact
    assert not result.confident
    doubted = [u for u in result.uncertain if u.item.startswith(f"{pair[0]} touches "
                                                                 f"{pair[1]}")]
    assert doubted and "of the shorter one only" in doubted[0].reason
    assert result.confidence[doubted[0].item] < 0.5


def test_tangram_contacts_along_whole_sides_stay_sure() -> None:
    """Clean figures read right stay unflagged by the partial-contact check (measured:
    none of 596 right figures of seeds 34000-34599 newly flagged)."""
    for seed in range(34_000, 34_040):
        scene = generate_scene("tangram", seed)
        result = perceive_image(scene.world.render(), dictionary="tangram")
        assert not any("of the shorter one only" in u.reason for u in result.uncertain), \
            seed


def _objects_on_the_bar(objects: list[DetectedObject], clean: np.ndarray,
                        barred: np.ndarray) -> list[str]:
    """Detected objects whose box lies mostly on what was drawn in front (the sweep's
    measure of a bar read as an object)."""
    drawn = np.any(barred != clean, axis=2)
    return [o.id for o in objects
            if drawn[o.box[1]:o.box[3], o.box[0]:o.box[2]].mean() >= POSING_SHARE]


# Bars the sweep found read as objects: one entering a side right above the floor's edge
# (wall on one side of it, floor on the other), the anti-aliased end of a bar tilted 20
# degrees, a bar leaving the picture through another edge, a short wide pole hanging
# into a wide kitchen (seeds of `bar_sweep` and `pole_sweep`).
BAR_CASES = [
    ("kitchen", 80_069, "left"),  # navy 4% from the left, 35% in, above the floor
    ("blocks", 80_059, "right"),  # wood 4% from the right, 35% in, above the floor
    ("blocks", 80_169, "right"),  # blue 1% from the right, 85% in, on the floor's edge
    ("kitchen", 80_228, "top"),  # purple 4% tilted +20 deg: its end a spoon
    ("tableware", 80_068, "top"),  # pink 4% tilted -20 deg: its end a fork
    ("kitchen", 80_316, "right"),  # teal 4% tilted -20 deg, out through the top edge
    ("tableware", 80_224, "left"),  # red 4% tilted -20 deg, out through the top edge
]


@pytest.mark.parametrize(("family", "seed", "edge"), BAR_CASES)
def test_a_bar_is_never_read_as_an_object(family: str, seed: int, edge: str) -> None:
    """The bar is found from its edge, its whole length and end are read as no object
    (no detection lies on it) and the graph is exact, flagged for the bar in front."""
    scene = generate_scene(family, seed)
    bar = bar_spec(seed - BAR_SEED, seed)
    assert bar.edge == edge
    clean = scene.world.render()
    barred = draw_bar(clean, bar)
    result = perceive_image(barred, dictionary=family)
    assert [b.kind for b in result.blocked if b.kind == "pole"] == ["pole"], result.blocked
    word = "hanging from the top edge" if edge == "top" else f"in from the {edge} edge"
    assert any(word in w for w in result.warnings), result.warnings
    assert _objects_on_the_bar(result.objects, clean, barred) == []
    assert score_graph(result.graph, scene.graph, family).exact, bar.describe()
    assert not result.confident


@pytest.mark.parametrize(("family", "seed"), [("kitchen", 70_054), ("kitchen", 70_060),
                                              ("tableware", 70_059)])
def test_a_short_wide_pole_in_a_wide_picture_is_no_object(family: str, seed: int) -> None:
    """A pole 4% of a wide kitchen's width wide reaching 35% down is hardly longer than
    wide (77 by 115 px at 1929 px): still a pole from the top edge, where the scene never
    shows, not a shelf, a kettle or a bowl hanging there."""
    name, spec = pole_spec(seed - POLE_SEED)
    scene = generate_scene(family, seed)
    clean = scene.world.render()
    barred = degrade(clean, spec, seed=seed)
    result = perceive_image(barred, dictionary=family)
    assert any(b.kind == "pole" for b in result.blocked), name
    assert _objects_on_the_bar(result.objects, clean, barred) == [], name
    assert score_graph(result.graph, scene.graph, family).exact, name


def test_a_tilted_bar_is_masked_to_its_end_and_to_the_frame() -> None:
    """The mask of a bar tilted 20 degrees covers its square-cut end, and that of a
    bar leaving through the top edge covers it up to the frame."""
    for family, seed in (("kitchen", 80_228), ("kitchen", 80_316)):
        scene = generate_scene(family, seed)
        clean = scene.world.render()
        barred = draw_bar(clean, bar_spec(seed - BAR_SEED, seed))
        (pole,) = find_poles(barred, scenery=SCENERY)
        drawn = np.any(barred != clean, axis=2)
        covered = pole.full_mask(drawn.shape)[drawn]
        assert float(np.mean(covered)) > 0.99, (seed, float(np.mean(covered)))
